//! The outlines two labels share in a section, put into K as edges of its section triangulation
//! (module doc of `partition`, step 1). Every change is a split of all tetrahedra around a
//! triangle or an edge of the plane, so K stays conforming; a split that would flip a tetrahedron
//! is not made (the segment is counted as missed).
use super::labels::Regions;
use crate::bm::complex::outward_face;
use crate::bm::refine::Planes;
use crate::fxhash::FxHashMap;
use crate::geom::predicates::{orient2d, orient3d};

/// Most steps of one segment's walk (crossings and vertices passed).
const MAX_STEPS: usize = 100_000;

/// Relative position along an edge below which a crossing is taken as passing through the end.
const END_SNAP: f64 = 1e-9;

/// K being split: positions, the planes of every vertex, positively oriented tetrahedra.
pub(super) struct Mesh {
    pub positions: Vec<[f64; 3]>,
    pub planes: Vec<Planes>,
    /// Per point, the point on a plane whose image in the collar it is (`u32::MAX`: none).
    pub lifted_from: Vec<u32>,
    pub tets: Vec<[u32; 4]>,
}

impl Mesh {
    /// The point `v` stands for on the planes: its base where it is a collar image.
    pub fn origin(&self, v: u32) -> u32 {
        match self.lifted_from[v as usize] {
            u32::MAX => v,
            b => b,
        }
    }
}

#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Inserted {
    pub segments: u64,
    pub points: u64,
    pub splits: u64,
    pub missed: u64,
}

type EdgeKey = ([u64; 3], [u64; 3]);

/// Per section, the segments (3D ends) that regions of different labels share.
pub type SharedSegments = Vec<Vec<[[f64; 3]; 2]>>;

/// The segments (3D ends) that regions of different labels share, per section.
pub fn shared_segments(sections: &crate::sections::Sections) -> SharedSegments {
    let key = |p: [f64; 3]| p.map(f64::to_bits);
    (sections.sections.iter())
        .map(|sec| {
            // per undirected edge (exact ends), the first label that has it and the edge
            let mut seen: FxHashMap<EdgeKey, (i32, [[f64; 3]; 2])> = FxHashMap::default();
            let mut out = Vec::new();
            for r in &sec.regions {
                for c in std::iter::once(&r.outer).chain(&r.holes) {
                    let p = &c.points3;
                    for i in 0..p.len() {
                        let (a, b) = (p[i], p[(i + 1) % p.len()]);
                        let k = if key(a) < key(b) {
                            (key(a), key(b))
                        } else {
                            (key(b), key(a))
                        };
                        match seen.get(&k) {
                            Some(&(l, seg)) if l != r.label => {
                                out.push(seg);
                                seen.remove(&k);
                            }
                            Some(_) => {}
                            None => {
                                seen.insert(k, (r.label, [a, b]));
                            }
                        }
                    }
                }
            }
            out
        })
        .collect()
}

/// The mesh with its vertex stars, while splitting.
struct Splitter<'m> {
    mesh: &'m mut Mesh,
    star: Vec<Vec<u32>>,
    /// The section's plane: its arrangement id and its (u,v) frame.
    plane: u32,
    frame: crate::sections::Plane,
    splits: u64,
}

impl Splitter<'_> {
    fn uv(&self, v: u32) -> [f64; 2] {
        self.frame.to_2d(self.mesh.positions[v as usize])
    }

    fn on_plane(&self, v: u32) -> bool {
        self.mesh.planes[v as usize].contains(&self.plane)
    }

    /// The tetrahedra holding every vertex of `s`.
    fn around(&self, s: &[u32]) -> Vec<u32> {
        (self.star[s[0] as usize].iter().copied())
            .filter(|&t| s.iter().all(|v| self.mesh.tets[t as usize].contains(v)))
            .collect()
    }

    /// Replace, in every tetrahedron holding all of `s`, each vertex of `s` in turn by a new vertex
    /// at `x` (an edge split for two, a triangle split for three); `None`, and nothing changed,
    /// when a new tetrahedron would not have its old one's orientation.
    fn split(&mut self, s: &[u32], x: [f64; 3]) -> Option<u32> {
        let around = self.around(s);
        let v = self.mesh.positions.len() as u32;
        let mut new: Vec<(u32, [u32; 4])> = Vec::new();
        for &t in &around {
            let tet = self.mesh.tets[t as usize];
            let p = tet.map(|w| self.mesh.positions[w as usize]);
            let sign = orient3d(p[0], p[1], p[2], p[3]).signum();
            for &w in s {
                let k = tet
                    .iter()
                    .position(|&y| y == w)
                    .expect("in the tetrahedron");
                let mut q = p;
                q[k] = x;
                if orient3d(q[0], q[1], q[2], q[3]).signum() != sign {
                    return None;
                }
                let mut n = tet;
                n[k] = v;
                new.push((t, n));
            }
        }
        let mut planes: Planes = self.mesh.planes[s[0] as usize].clone();
        planes.retain(|p| {
            s[1..]
                .iter()
                .all(|&w| self.mesh.planes[w as usize].contains(p))
        });
        self.mesh.positions.push(x);
        self.mesh.planes.push(planes);
        self.mesh.lifted_from.push(u32::MAX);
        self.star.push(Vec::new());
        // the first piece of each tetrahedron takes its index, the others are appended
        let mut first = crate::fxhash::FxHashSet::default();
        for (t, n) in new {
            let old = self.mesh.tets[t as usize];
            let id = if first.insert(t) {
                for w in old {
                    self.star[w as usize].retain(|&y| y != t);
                }
                self.mesh.tets[t as usize] = n;
                t
            } else {
                self.mesh.tets.push(n);
                (self.mesh.tets.len() - 1) as u32
            };
            for w in n {
                self.star[w as usize].push(id);
            }
        }
        self.splits += 1;
        Some(v)
    }

    /// The section triangles around `c`, each as its two other vertices counter-clockwise.
    fn fan(&self, c: u32) -> Vec<[u32; 2]> {
        let mut out: Vec<[u32; 2]> = Vec::new();
        for &t in &self.star[c as usize] {
            let tet = self.mesh.tets[t as usize];
            for i in 0..4 {
                let f = outward_face(&tet, i);
                if !f.contains(&c) || !f.iter().all(|&w| self.on_plane(w)) {
                    continue;
                }
                let k = f.iter().position(|&w| w == c).expect("holds c");
                let (mut u, mut w) = (f[(k + 1) % 3], f[(k + 2) % 3]);
                if orient2d(self.uv(c), self.uv(u), self.uv(w)) < 0.0 {
                    std::mem::swap(&mut u, &mut w);
                }
                if !out.contains(&[u, w]) {
                    out.push([u, w]);
                }
            }
        }
        out
    }

    /// Walk from vertex `c` to the point `b` along the plane, splitting every edge crossed; the
    /// vertex at `b` (inserted where it is not one), `None` where the walk failed.
    fn walk(&mut self, mut c: u32, b: [f64; 3], b_vertex: Option<u32>) -> Option<u32> {
        let bq = self.frame.to_2d(b);
        for _ in 0..MAX_STEPS {
            if Some(c) == b_vertex || self.mesh.positions[c as usize] == b {
                return Some(c);
            }
            let cq = self.uv(c);
            let mut step = None;
            for [u, w] in self.fan(c) {
                let (uq, wq) = (self.uv(u), self.uv(w));
                let o1 = orient2d(cq, uq, bq);
                let o2 = orient2d(cq, wq, bq);
                if o1 < 0.0 || o2 > 0.0 {
                    continue;
                }
                let ahead = |q: [f64; 2]| {
                    (q[0] - cq[0]) * (bq[0] - cq[0]) + (q[1] - cq[1]) * (bq[1] - cq[1]) > 0.0
                };
                if o1 == 0.0 && !ahead(uq) || o2 == 0.0 && !ahead(wq) {
                    continue;
                }
                step = Some((u, w, o1, o2));
                break;
            }
            let (u, w, o1, o2) = step?;
            let o3 = orient2d(self.uv(u), self.uv(w), bq);
            // along an edge of the fan: b on it, or the walk goes on from its end
            for (e, o) in [(u, o1), (w, o2)] {
                if o == 0.0 {
                    let d = |q: [f64; 2]| (q[0] - cq[0]).hypot(q[1] - cq[1]);
                    if d(bq) < d(self.uv(e)) {
                        return self.split(&[c, e], b);
                    }
                    c = e;
                }
            }
            if o1 == 0.0 || o2 == 0.0 {
                continue;
            }
            if o3 > 0.0 {
                return self.split(&[c, u, w], b);
            }
            if o3 == 0.0 {
                return self.split(&[u, w], b);
            }
            // the segment crosses edge (u, w)
            let (su, sw) = (orient2d(cq, bq, self.uv(u)), orient2d(cq, bq, self.uv(w)));
            let t = su / (su - sw);
            if t < END_SNAP {
                c = u;
                continue;
            }
            if t > 1.0 - END_SNAP {
                c = w;
                continue;
            }
            let (pu, pw) = (
                self.mesh.positions[u as usize],
                self.mesh.positions[w as usize],
            );
            let x = [0, 1, 2].map(|k| pu[k] + t * (pw[k] - pu[k]));
            c = self.split(&[u, w], x)?;
        }
        None
    }

    /// The vertex of K at `x` on the plane, inserted where there is none (a point of a section
    /// triangle found by search), `None` where `x` is in no section triangle of K.
    fn vertex_at(&mut self, x: [f64; 3], at: &FxHashMap<[u64; 3], u32>) -> Option<u32> {
        if let Some(&v) = at.get(&x.map(f64::to_bits)) {
            return Some(v);
        }
        let q = self.frame.to_2d(x);
        let mut found = None;
        'tets: for tet in &self.mesh.tets {
            for i in 0..4 {
                let f = outward_face(tet, i);
                if !f.iter().all(|&w| self.on_plane(w)) {
                    continue;
                }
                let [a, b, c] = f.map(|w| self.uv(w));
                let o = [orient2d(a, b, q), orient2d(b, c, q), orient2d(c, a, q)];
                if o.iter().all(|&s| s >= 0.0) || o.iter().all(|&s| s <= 0.0) {
                    found = Some((f, o));
                    break 'tets;
                }
            }
        }
        let (f, o) = found?;
        if let Some(k) = (0..3).find(|&k| self.mesh.positions[f[k] as usize] == x) {
            return Some(f[k]);
        }
        match o.iter().position(|&s| s == 0.0) {
            Some(k) => self.split(&[f[k], f[(k + 1) % 3]], x),
            None => self.split(&f, x),
        }
    }
}

/// Put every shared outline segment of every section into `mesh` (module doc).
pub(super) fn insert(mesh: &mut Mesh, regions: &Regions, segments: &SharedSegments) -> Inserted {
    let mut out = Inserted::default();
    if segments.iter().all(Vec::is_empty) {
        return out;
    }
    let mut star: Vec<Vec<u32>> = vec![Vec::new(); mesh.positions.len()];
    for (t, tet) in mesh.tets.iter().enumerate() {
        for &v in tet {
            star[v as usize].push(t as u32);
        }
    }
    for (s, segs) in segments.iter().enumerate() {
        let Some(plane) = regions.plane_id(s) else {
            out.missed += segs.len() as u64;
            continue;
        };
        if segs.is_empty() {
            continue;
        }
        let mut at: FxHashMap<[u64; 3], u32> = FxHashMap::default();
        for (v, p) in mesh.positions.iter().enumerate() {
            if mesh.planes[v].contains(&plane) {
                at.insert(p.map(f64::to_bits), v as u32);
            }
        }
        let mut sp = Splitter {
            frame: *regions.plane(s),
            mesh: &mut *mesh,
            star: std::mem::take(&mut star),
            plane,
            splits: 0,
        };
        for &[a, b] in segs {
            out.segments += 1;
            let n0 = sp.mesh.positions.len();
            let Some(va) = sp.vertex_at(a, &at) else {
                out.missed += 1;
                continue;
            };
            at.insert(a.map(f64::to_bits), va);
            let vb = at.get(&b.map(f64::to_bits)).copied();
            match sp.walk(va, b, vb) {
                Some(v) => {
                    at.insert(b.map(f64::to_bits), v);
                }
                None => out.missed += 1,
            }
            out.points += (sp.mesh.positions.len() - n0) as u64;
        }
        out.splits += sp.splits;
        star = sp.star;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sections::Plane;

    /// Triangle (0,1,2) on z = 0 (plane id 0) with apex 3 above and 4 below.
    fn bipyramid() -> Mesh {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.2, 1.0],
            [0.2, 0.2, -1.0],
        ];
        let on: Planes = smallvec::smallvec![0];
        let planes = vec![on.clone(), on.clone(), on, Planes::new(), Planes::new()];
        let mut tets = vec![[0, 1, 2, 3], [0, 2, 1, 4]];
        for t in &mut tets {
            let p = t.map(|v| positions[v as usize]);
            if orient3d(p[0], p[1], p[2], p[3]) < 0.0 {
                t.swap(0, 1);
            }
        }
        Mesh {
            lifted_from: vec![u32::MAX; positions.len()],
            positions,
            planes,
            tets,
        }
    }

    fn splitter(mesh: &mut Mesh) -> Splitter<'_> {
        let mut star = vec![Vec::new(); mesh.positions.len()];
        for (t, tet) in mesh.tets.iter().enumerate() {
            for &v in tet {
                star[v as usize].push(t as u32);
            }
        }
        Splitter {
            frame: Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap(),
            mesh,
            star,
            plane: 0,
            splits: 0,
        }
    }

    fn signs(mesh: &Mesh) -> Vec<f64> {
        (mesh.tets.iter())
            .map(|t| {
                let p = t.map(|v| mesh.positions[v as usize]);
                orient3d(p[0], p[1], p[2], p[3]).signum()
            })
            .collect()
    }

    #[test]
    fn a_walk_to_a_point_inside_splits_the_triangle_and_stops_at_the_hull() {
        let mut mesh = bipyramid();
        let mut sp = splitter(&mut mesh);
        // from vertex 0 to a point inside the triangle: a triangle split (two tets become six)
        let v = sp.walk(0, [0.3, 0.3, 0.0], None).unwrap();
        assert_eq!(v, 5);
        assert_eq!(sp.mesh.tets.len(), 6);
        assert!(!sp.around(&[0, 5]).is_empty(), "the segment is an edge");
        // from the new point across edge (1,2) to beyond it: outside the triangle, the walk fails
        assert!(sp.walk(5, [2.0, 2.0, 0.0], None).is_none());
        assert!(signs(&mesh).iter().all(|&s| s > 0.0));
    }

    #[test]
    fn a_walk_between_two_edges_splits_both() {
        let mut mesh = bipyramid();
        let mut sp = splitter(&mut mesh);
        let a = sp.split(&[0, 1], [0.5, 0.0, 0.0]).unwrap();
        // from the middle of (0,1) to the middle of (0,2): crosses the edge (a, 2)
        let b = sp.walk(a, [0.0, 0.5, 0.0], None).unwrap();
        assert!(!sp.around(&[a, b]).is_empty());
        assert_eq!(sp.mesh.planes[b as usize].as_slice(), &[0]);
        let n = sp.mesh.tets.len();
        assert!(signs(&mesh).iter().all(|&s| s > 0.0));
        // every face shared by at most two tetrahedra: still a complex
        let mut faces = std::collections::HashMap::new();
        for t in &mesh.tets {
            for i in 0..4 {
                let mut f = outward_face(t, i);
                f.sort_unstable();
                *faces.entry(f).or_insert(0) += 1;
            }
        }
        assert!(faces.values().all(|&c| c <= 2), "{n} tets");
    }
}
