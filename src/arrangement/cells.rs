//! The 3D arrangement: the box cut incrementally by every input plane.
//!
//! Every vertex is the intersection of three planes (its defining triple) and carries the set of all
//! planes through it. Its side with respect to another plane h is decided exactly:
//! `sign(det[p;q;r;h]) · sign(det3(n_p,n_q,n_r))` (the 4×4 determinant of plane equations
//! `[n d]` equals `det3 · (n_h·x + d_h)` at the vertex x). A vertex exactly on h gets the tag h.
//! Vertices created on an edge (a,b) by plane h are keyed by (a,b,h), so the cells around an
//! edge share them; faces are shared because both cells split them identically.
use super::exact::{sign_det3, sign_det4};
use super::PlaneTags;
use crate::fxhash::FxHashMap as HashMap;

/// A face of a cell during construction: counter-clockwise seen from outside the cell.
#[derive(Clone, Debug)]
pub(crate) struct BFace {
    pub plane: u32,
    pub poly: Vec<u32>,
}

#[derive(Clone, Debug)]
pub(crate) struct BCell {
    pub faces: Vec<BFace>,
    /// Side of the cell with respect to every plane (-1, +1; 0 while the plane is not yet processed).
    pub sign: Vec<i8>,
}

pub(crate) struct CellBuilder {
    pub eq: Vec<[f64; 4]>,
    pub triple: Vec<[u32; 3]>,
    det3_sign: Vec<i8>,
    pub tags: Vec<PlaneTags>,
    pub pos: Vec<[f64; 3]>,
    pub cells: Vec<BCell>,
    edge_vertex: HashMap<(u32, u32, u32), u32>,
}

pub(crate) fn plane_point(eq: &[[f64; 4]], t: [u32; 3]) -> [f64; 3] {
    let (a, b, c) = (eq[t[0] as usize], eq[t[1] as usize], eq[t[2] as usize]);
    let n1 = [a[0], a[1], a[2]];
    let n2 = [b[0], b[1], b[2]];
    let n3 = [c[0], c[1], c[2]];
    let c23 = cross(n2, n3);
    let c31 = cross(n3, n1);
    let c12 = cross(n1, n2);
    let det = dot(n1, c23);
    let mut x = [0.0; 3];
    for k in 0..3 {
        x[k] = -(a[3] * c23[k] + b[3] * c31[k] + c[3] * c12[k]) / det;
    }
    x
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
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
            cells: Vec::new(),
            edge_vertex: HashMap::default(),
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
        let mut sign = vec![0i8; n];
        for w in walls {
            sign[w as usize] = -1;
        }
        b.cells.push(BCell { faces, sign });
        b
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
        self.pos.push(plane_point(&self.eq, t));
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

    /// Cut every cell by plane `h`.
    pub fn cut(&mut self, h: u32) -> Result<(), String> {
        let nv = self.pos.len();
        let mut side = Vec::with_capacity(nv);
        for v in 0..nv as u32 {
            let s = self.side(v, h);
            if s == 0 && !self.tags[v as usize].contains(&h) {
                let t = &mut self.tags[v as usize];
                t.push(h);
                t.sort_unstable();
            }
            side.push(s);
        }
        let old = std::mem::take(&mut self.cells);
        let mut out = Vec::with_capacity(old.len() * 2);
        for cell in old {
            let (mut any_pos, mut any_neg) = (false, false);
            for f in &cell.faces {
                for &v in &f.poly {
                    match side[v as usize] {
                        1 => any_pos = true,
                        -1 => any_neg = true,
                        _ => {}
                    }
                }
            }
            if !(any_pos && any_neg) {
                let mut c = cell;
                c.sign[h as usize] = if any_pos { 1 } else { -1 };
                out.push(c);
                continue;
            }
            let mut pos_faces = Vec::new();
            let mut neg_faces = Vec::new();
            for f in &cell.faces {
                let n = f.poly.len();
                let mut pp = Vec::with_capacity(n + 2);
                let mut np = Vec::with_capacity(n + 2);
                for i in 0..n {
                    let a = f.poly[i];
                    let b = f.poly[(i + 1) % n];
                    let sa = side.get(a as usize).copied().unwrap_or(0);
                    let sb = side.get(b as usize).copied().unwrap_or(0);
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
            let on_h = |v: u32| side.get(v as usize).is_none_or(|&s| s == 0);
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
                    cur = *next.get(&cur).ok_or_else(|| {
                        format!("plane {h}: the cap of a split cell is not closed")
                    })?;
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
                let mut sign = cell.sign.clone();
                sign[h as usize] = s;
                out.push(BCell {
                    faces: std::mem::take(faces),
                    sign,
                });
            }
        }
        self.cells = out;
        Ok(())
    }
}
