//! The 3D arrangement: the box cut incrementally by every input plane.
//!
//! Every vertex is the intersection of three planes (its defining triple) and carries the set of all
//! planes through it. Its side with respect to another plane h is decided exactly:
//! `sign(det[p;q;r;h]) · sign(det3(n_p,n_q,n_r))` (the 4×4 determinant of plane equations
//! `[n d]` equals `det3 · (n_h·x + d_h)` at the vertex x). A vertex exactly on h gets the tag h.
//! Vertices created on an edge (a,b) by plane h are keyed by (a,b,h), so the cells around an
//! edge share them; faces are shared because both cells split them identically.
//!
//! Each vertex keeps a bound on the error of its rounded position (`point_error`), each cell the box
//! of its vertices and the largest of their bounds: a cell whose grown box lies strictly on one side
//! of the cutting plane is not split and needs no exact predicate (every vertex of it is strictly on
//! that side); only the vertices of the other cells are decided exactly (once per cut, shared by
//! the cells around them). `cut` also drops the new cells the caller's `keep` rejects (cells no
//! section reaches, `reach`): nothing is built inside them any more.
use super::exact::{sign_det3, sign_det4};
use super::signs::SignVec;
use super::PlaneTags;
use crate::fxhash::FxHashMap as HashMap;
use crate::sections::{cross, dot};

/// A face of a cell during construction: counter-clockwise seen from outside the cell.
#[derive(Clone, Debug)]
pub(crate) struct BFace {
    pub plane: u32,
    pub poly: Vec<u32>,
}

#[derive(Clone, Debug)]
pub(crate) struct BCell {
    pub faces: Vec<BFace>,
    /// Side of the cell with respect to the planes that split it (and the walls): -1, +1; 0 for
    /// the others until `complete_signs` fills them in at the end.
    pub sign: SignVec,
    /// Box of the rounded vertex positions.
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    /// Largest position error bound of its vertices (per coordinate).
    pub err: f64,
}

pub(crate) struct CellBuilder {
    pub eq: Vec<[f64; 4]>,
    pub triple: Vec<[u32; 3]>,
    det3_sign: Vec<i8>,
    pub tags: Vec<PlaneTags>,
    pub pos: Vec<[f64; 3]>,
    /// Per vertex: bound on |exact - rounded| of every coordinate of `pos`.
    pub err: Vec<f64>,
    pub cells: Vec<BCell>,
    edge_vertex: HashMap<(u32, u32, u32), u32>,
    /// Exact sides with respect to the plane being cut, valid where `side_stamp == stamp`.
    side_val: Vec<i8>,
    side_stamp: Vec<u32>,
    stamp: u32,
    /// The planes cut so far are the input planes `0..cut_count` (cut in order).
    cut_count: u32,
    /// The previous cut's cell list, emptied: its allocation is reused (a fresh list per cut
    /// cost a page fault per 4 KiB on long sweeps).
    spare: Vec<BCell>,
}

/// Whether a cut keeps a new cell (`cut` drops it otherwise).
pub(crate) type Keep<'a> = &'a dyn Fn(&CellBuilder, &BCell) -> bool;

pub(crate) fn plane_point(eq: &[[f64; 4]], t: [u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|p| eq[p as usize]);
    crate::geom::three_planes_point(a, b, c)
}

/// Bound on the error of every coordinate of `plane_point(eq, t)` (at `x`), from the rounding of
/// the cross products, the determinant and the quotient (Cramer's rule); infinite when the
/// determinant is too small to bound it.
pub(crate) fn point_error(eq: &[[f64; 4]], t: [u32; 3], x: [f64; 3]) -> f64 {
    let e = t.map(|p| eq[p as usize]);
    let s = e
        .iter()
        .flat_map(|r| r[..3].iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let d: f64 = e.iter().map(|r| r[3].abs()).sum();
    let n = |r: [f64; 4]| [r[0], r[1], r[2]];
    let det = dot(n(e[0]), cross(n(e[1]), n(e[2])));
    let xm = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let eps = f64::EPSILON;
    let ddet = 64.0 * eps * s * s * s;
    let dnum = 32.0 * eps * s * s * d;
    if det.is_nan() || det.abs() <= 2.0 * ddet || !xm.is_finite() {
        return f64::INFINITY;
    }
    2.0 * ((dnum + xm * ddet) / (det.abs() - ddet) + eps * xm)
}

impl CellBuilder {
    /// `eq`: all plane equations; `walls`: the six wall plane ids in the order
    /// x_lo, x_hi, y_lo, y_hi, z_lo, z_hi (x_lo has normal -x, ...).
    pub fn new_box(eq: Vec<[f64; 4]>, walls: [u32; 6]) -> CellBuilder {
        let n = eq.len();
        let mut b = CellBuilder {
            eq,
            triple: Vec::new(),
            det3_sign: Vec::new(),
            tags: Vec::new(),
            pos: Vec::new(),
            err: Vec::new(),
            cells: Vec::new(),
            edge_vertex: HashMap::default(),
            side_val: Vec::new(),
            side_stamp: Vec::new(),
            stamp: 0,
            cut_count: 0,
            spare: Vec::new(),
        };
        // corner index bits: x (0 lo, 1 hi), y, z.
        let mut corner = [0u32; 8];
        for (idx, c) in corner.iter_mut().enumerate() {
            let t = [
                walls[idx & 1],
                walls[2 + ((idx >> 1) & 1)],
                walls[4 + ((idx >> 2) & 1)],
            ];
            *c = b.add_vertex(t, t.iter().copied().collect());
        }
        let v = |x: usize, y: usize, z: usize| corner[x | (y << 1) | (z << 2)];
        // Each face counter-clockwise seen from outside.
        let faces = vec![
            BFace {
                plane: walls[0],
                poly: vec![v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)],
            },
            BFace {
                plane: walls[1],
                poly: vec![v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)],
            },
            BFace {
                plane: walls[2],
                poly: vec![v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)],
            },
            BFace {
                plane: walls[3],
                poly: vec![v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0)],
            },
            BFace {
                plane: walls[4],
                poly: vec![v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)],
            },
            BFace {
                plane: walls[5],
                poly: vec![v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)],
            },
        ];
        let mut sign = SignVec::filled(n, 0);
        for w in walls {
            sign.set(w as usize, -1);
        }
        let mut cell = BCell {
            faces,
            sign,
            lo: [0.0; 3],
            hi: [0.0; 3],
            err: 0.0,
        };
        b.set_bounds(&mut cell);
        b.cells.push(cell);
        b
    }

    /// Box and error bound of a cell from its vertices.
    fn set_bounds(&self, c: &mut BCell) {
        let (mut lo, mut hi, mut err) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3], 0.0f64);
        for f in &c.faces {
            for &v in &f.poly {
                let p = self.pos[v as usize];
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
                err = err.max(self.err[v as usize]);
            }
        }
        (c.lo, c.hi, c.err) = (lo, hi, err);
    }

    /// The side of the whole cell with respect to plane `h` when its grown box decides it
    /// (every vertex strictly on that side), else 0.
    fn box_side(&self, c: &BCell, h: u32) -> i8 {
        let e = self.eq[h as usize];
        let (mut dmin, mut dmax, mut mag) = (e[3], e[3], e[3].abs());
        for (k, &ek) in e[..3].iter().enumerate() {
            let (a, b) = (ek * c.lo[k], ek * c.hi[k]);
            dmin += a.min(b);
            dmax += a.max(b);
            mag += a.abs().max(b.abs());
        }
        let n1 = e[0].abs() + e[1].abs() + e[2].abs();
        let bound = n1 * c.err + 8.0 * f64::EPSILON * mag;
        if !bound.is_finite() {
            0
        } else if dmin > bound {
            1
        } else if dmax < -bound {
            -1
        } else {
            0
        }
    }

    /// Exact side of vertex `v` with respect to `h` during the cut of `h`, computed once per cut
    /// (a vertex found on `h` gets the tag); vertices created by this cut (ids from `nv`) lie on `h`.
    fn cut_side(&mut self, v: u32, h: u32, nv: usize) -> i8 {
        let vi = v as usize;
        if vi >= nv {
            return 0;
        }
        if self.side_stamp[vi] == self.stamp {
            return self.side_val[vi];
        }
        let s = self.side(v, h);
        if s == 0 && !self.tags[vi].contains(&h) {
            let t = &mut self.tags[vi];
            t.push(h);
            t.sort_unstable();
        }
        self.side_stamp[vi] = self.stamp;
        self.side_val[vi] = s;
        s
    }

    fn add_vertex(&mut self, t: [u32; 3], mut tags: PlaneTags) -> u32 {
        tags.sort_unstable();
        tags.dedup();
        let n = |p: u32| {
            let e = self.eq[p as usize];
            [e[0], e[1], e[2]]
        };
        let s = sign_det3(n(t[0]), n(t[1]), n(t[2]));
        debug_assert!(s != 0);
        self.det3_sign.push(s);
        let x = plane_point(&self.eq, t);
        self.err.push(point_error(&self.eq, t, x));
        self.pos.push(x);
        self.triple.push(t);
        self.tags.push(tags);
        (self.pos.len() - 1) as u32
    }

    /// Exact side of vertex `v` with respect to plane `h`.
    pub fn side(&self, v: u32, h: u32) -> i8 {
        if self.tags[v as usize].contains(&h) {
            return 0;
        }
        let t = self.triple[v as usize];
        let m = [
            self.eq[t[0] as usize],
            self.eq[t[1] as usize],
            self.eq[t[2] as usize],
            self.eq[h as usize],
        ];
        sign_det4(m) * self.det3_sign[v as usize]
    }

    fn edge_vertex(&mut self, a: u32, b: u32, h: u32) -> u32 {
        let key = (a.min(b), a.max(b), h);
        if let Some(&v) = self.edge_vertex.get(&key) {
            return v;
        }
        let common: PlaneTags = self.tags[a as usize]
            .iter()
            .copied()
            .filter(|p| self.tags[b as usize].contains(p))
            .collect();
        debug_assert!(common.len() >= 2);
        let t = [common[0], common[1], h];
        let mut tags = common.clone();
        tags.push(h);
        let v = self.add_vertex(t, tags);
        self.edge_vertex.insert(key, v);
        v
    }

    /// Cut every cell by plane `h`; of the two parts of a split cell, those `keep` rejects are
    /// dropped.
    pub fn cut(&mut self, h: u32, keep: Keep) -> Result<(), String> {
        let nv = self.pos.len();
        self.side_val.resize(nv, 0);
        self.side_stamp.resize(nv, 0);
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.side_stamp.iter_mut().for_each(|s| *s = u32::MAX);
            self.stamp = 1;
        }
        let mut old = std::mem::take(&mut self.cells);
        let mut out = std::mem::take(&mut self.spare);
        out.clear();
        out.reserve(old.len() + old.len() / 4);
        for cell in old.drain(..) {
            // A cell wholly on one side keeps sign 0 for h until `complete_signs`: no write here
            // (one per cell and cut was most of the construction's memory traffic).
            if self.box_side(&cell, h) != 0 {
                out.push(cell);
                continue;
            }
            let (mut any_pos, mut any_neg) = (false, false);
            for f in &cell.faces {
                for &v in &f.poly {
                    match self.cut_side(v, h, nv) {
                        1 => any_pos = true,
                        -1 => any_neg = true,
                        _ => {}
                    }
                }
            }
            if !(any_pos && any_neg) {
                out.push(cell);
                continue;
            }
            for part in self.split(cell, h, nv)? {
                if keep(self, &part) {
                    out.push(part);
                }
            }
        }
        self.cells = out;
        self.spare = old;
        self.cut_count = self.cut_count.max(h + 1);
        Ok(())
    }

    /// Whether input plane `i` has been cut (planes are cut in the order of their ids).
    pub fn is_cut(&self, i: u32) -> bool {
        i < self.cut_count
    }

    /// Fill in every cell's side of every plane it was not split by (after the last cut): from
    /// its box where that decides, else exactly from a vertex of the cell off the plane.
    pub fn complete_signs(&mut self) {
        use rayon::prelude::*;
        let mut cells = std::mem::take(&mut self.cells);
        // each cell on its own (reads only the vertices): a 1000-frame sweep has 380k cells
        // times 1000 planes of them
        let this = &*self;
        cells.par_iter_mut().for_each(|c| {
            for h in 0..this.cut_count {
                if c.sign.get(h as usize) != 0 {
                    continue;
                }
                let mut s = this.box_side(c, h);
                if s == 0 {
                    let off = c
                        .faces
                        .iter()
                        .flat_map(|f| f.poly.iter())
                        .find(|&&v| !this.tags[v as usize].contains(&h));
                    s = off.map_or(0, |&v| this.side(v, h));
                }
                debug_assert!(s != 0, "a cell lies on one side of every plane");
                c.sign.set(h as usize, s);
            }
        });
        self.cells = cells;
    }

    /// The two parts of `cell` on the positive and negative side of `h` (the sides of its vertices
    /// are in the cut's cache).
    fn split(&mut self, cell: BCell, h: u32, nv: usize) -> Result<[BCell; 2], String> {
        let side = |b: &CellBuilder, v: u32| {
            if (v as usize) < nv {
                b.side_val[v as usize]
            } else {
                0
            }
        };
        let mut parts = Vec::with_capacity(2);
        let mut pos_faces = Vec::new();
        let mut neg_faces = Vec::new();
        for f in &cell.faces {
            let n = f.poly.len();
            let mut pp = Vec::with_capacity(n + 2);
            let mut np = Vec::with_capacity(n + 2);
            for i in 0..n {
                let a = f.poly[i];
                let b = f.poly[(i + 1) % n];
                let (sa, sb) = (side(self, a), side(self, b));
                if sa >= 0 {
                    pp.push(a);
                }
                if sa <= 0 {
                    np.push(a);
                }
                if sa * sb < 0 {
                    let x = self.edge_vertex(a, b, h);
                    pp.push(x);
                    np.push(x);
                }
            }
            if pp.len() >= 3 {
                pos_faces.push(BFace {
                    plane: f.plane,
                    poly: pp,
                });
            }
            if np.len() >= 3 {
                neg_faces.push(BFace {
                    plane: f.plane,
                    poly: np,
                });
            }
        }
        // Vertices created in this step lie on h.
        let on_h = |v: u32| side(self, v) == 0;
        for (faces, s) in [(&mut pos_faces, 1i8), (&mut neg_faces, -1i8)] {
            let mut next: HashMap<u32, u32> = HashMap::default();
            for f in faces.iter() {
                let n = f.poly.len();
                for i in 0..n {
                    let (u, w) = (f.poly[i], f.poly[(i + 1) % n]);
                    if on_h(u) && on_h(w) {
                        next.insert(w, u);
                    }
                }
            }
            let start = *next
                .keys()
                .min()
                .ok_or_else(|| format!("plane {h}: a split cell has no cap"))?;
            let mut cap = vec![start];
            let mut cur = next[&start];
            while cur != start && cap.len() <= next.len() {
                cap.push(cur);
                cur = *next
                    .get(&cur)
                    .ok_or_else(|| format!("plane {h}: the cap of a split cell is not closed"))?;
            }
            if cur != start || cap.len() != next.len() || cap.len() < 3 {
                return Err(format!(
                    "plane {h}: the cap of a split cell is not one polygon"
                ));
            }
            faces.push(BFace {
                plane: h,
                poly: cap,
            });
            let sign = cell.sign.clone().with(h as usize, s);
            let mut part = BCell {
                faces: std::mem::take(faces),
                sign,
                lo: [0.0; 3],
                hi: [0.0; 3],
                err: 0.0,
            };
            self.set_bounds(&mut part);
            parts.push(part);
        }
        let [p, n]: [BCell; 2] = parts.try_into().map_err(|_| format!("plane {h}: split"))?;
        Ok([p, n])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Unit-normal plane equations: the box [-1, 1]³ (walls 0..6) and `k` random planes through the
    /// box, half of them nearly parallel to the one before (small determinants, large errors).
    fn planes(k: usize, seed: u64) -> Vec<[f64; 4]> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut eq = Vec::new();
        for a in 0..3 {
            for s in [-1.0, 1.0] {
                let mut e = [0.0; 4];
                e[a] = s;
                e[3] = -1.0;
                eq.push(e);
            }
        }
        let mut last = [0.0, 0.0, 1.0];
        for i in 0..k {
            let mut n: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            if i % 2 == 1 {
                let t = 10f64.powf(rng.gen_range(-12.0..-3.0));
                n = std::array::from_fn(|j| last[j] + t * n[j]);
            }
            let l = dot(n, n).sqrt();
            let n = n.map(|x| x / l);
            last = n;
            eq.push([n[0], n[1], n[2], rng.gen_range(-0.5..0.5)]);
        }
        eq
    }

    fn builder(eq: Vec<[f64; 4]>, cut: usize) -> CellBuilder {
        let mut b = CellBuilder::new_box(eq, [0, 1, 2, 3, 4, 5]);
        for h in 6..6 + cut as u32 {
            b.cut(h, &|_, _| true).unwrap();
        }
        b
    }

    #[test]
    fn the_error_bound_holds_the_exact_vertex() {
        // The exact vertex lies strictly between the axis planes at pos ± err (exact 4×4 signs).
        for seed in 0..4 {
            let b = builder(planes(14, seed), 14);
            let mut finite = 0;
            for v in 0..b.pos.len() {
                let (t, x, e) = (b.triple[v], b.pos[v], b.err[v]);
                if !e.is_finite() {
                    continue;
                }
                finite += 1;
                for k in 0..3 {
                    for (off, want) in [(e, -1), (-e, 1)] {
                        let mut h = [0.0; 4];
                        h[k] = 1.0;
                        h[3] = -(x[k] + off);
                        if h[3] == -x[k] {
                            continue; // the offset vanished in rounding: nothing to check
                        }
                        let m = [
                            b.eq[t[0] as usize],
                            b.eq[t[1] as usize],
                            b.eq[t[2] as usize],
                            h,
                        ];
                        let s = super::sign_det4(m) * b.det3_sign[v];
                        assert_eq!(s, want, "vertex {v} axis {k}: err {e}");
                    }
                }
            }
            assert!(finite > 100, "{finite}");
        }
    }

    #[test]
    fn a_cell_decided_by_its_box_has_every_vertex_on_that_side() {
        let mut decided = 0;
        for seed in 0..4 {
            let eq = planes(16, seed);
            let b = builder(eq, 12);
            for h in 18..22u32 {
                for c in &b.cells {
                    let s = b.box_side(c, h);
                    if s == 0 {
                        continue;
                    }
                    decided += 1;
                    for f in &c.faces {
                        for &v in &f.poly {
                            assert_eq!(b.side(v, h), s, "plane {h}, vertex {v}");
                        }
                    }
                }
            }
        }
        assert!(decided > 1000, "{decided}");
    }

    #[test]
    fn dropped_cells_leave_the_others_as_they_were() {
        // Keeping only the cells that touch the ball of radius 0.3 gives exactly those cells of the
        // full construction (same vertices by position and tags, same faces).
        let eq = planes(12, 9);
        let near = |b: &CellBuilder, c: &BCell| {
            let d: f64 = (0..3)
                .map(|k| (c.lo[k].max(0.0) + (-c.hi[k]).max(0.0)).powi(2))
                .sum::<f64>();
            let _ = b;
            d.sqrt() <= 0.3
        };
        let full = builder(eq.clone(), 12);
        let mut part = CellBuilder::new_box(eq, [0, 1, 2, 3, 4, 5]);
        for h in 6..18u32 {
            part.cut(h, &near).unwrap();
        }
        let key = |b: &CellBuilder, c: &BCell| {
            let mut fs: Vec<String> = c
                .faces
                .iter()
                .map(|f| {
                    let mut p: Vec<String> = f
                        .poly
                        .iter()
                        .map(|&v| format!("{:?}{:?}", b.pos[v as usize], b.tags[v as usize]))
                        .collect();
                    p.sort();
                    format!("{} {:?}", f.plane, p)
                })
                .collect();
            fs.sort();
            fs
        };
        let all: std::collections::HashSet<Vec<String>> =
            full.cells.iter().map(|c| key(&full, c)).collect();
        let kept = full.cells.iter().filter(|c| near(&full, c)).count();
        assert!(part.cells.len() >= kept && part.cells.len() < full.cells.len());
        for c in &part.cells {
            assert!(all.contains(&key(&part, c)));
        }
    }
}
