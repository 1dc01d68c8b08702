//! Classification of a cell's Delaunay simplices by plane tags (never by coordinates).
//!
//! * A simplex is *grounded* on slot `s` when all its vertices carry the slot's bit.
//! * Grounded edge on `s`: *contour* when it is a boundary edge of the face's section (Steiner splits
//!   applied), else *internal* / *external* by the exact point-in-section test of its midpoint in the
//!   plane's (u,v) frame (a midpoint on the boundary counts as inside). Grounded triangle: by centroid.
//!   A simplex grounded on several slots (vertices on an arrangement edge) is external if it is external
//!   on any of them.
//! * Tetrahedron types, for vertices with one to three tags (rule, in this order):
//!   - `Flat`: one slot holds all four vertices (a near-flat sliver of the face created by rounding;
//!     it has no volume and is always removed in step 1);
//!   - `Vf`: some slot holds three vertices (a grounded face);
//!   - `Ee`: some pair of *opposite* edges are both grounded (necessarily on different slots); these
//!     edges are the tet's pivot edges in step 2;
//!   - `Evv`: some edge is grounded;
//!   - `Vvvv`: no edge is grounded.
use super::cell_input::{slots_of, CellInput, IdMap, Mask, Where};
use super::complex::{Complex, TET_EDGES};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TetType {
    Flat,
    Vf,
    Ee,
    Evv,
    Vvvv,
}

#[derive(Clone, Debug, Default)]
pub struct Classified {
    pub ty: Vec<TetType>,
    /// Has an external grounded edge or triangle, or is flat: removed in step 1.
    pub external: Vec<bool>,
    /// Bit `k` set when `TET_EDGES[k]` is grounded.
    pub grounded_edges: Vec<u8>,
    /// Bit `k` set when `TET_EDGES[k]` is a pivot edge of a `Ee` tet.
    pub pivot_edges: Vec<u8>,
    /// Bit `i` set when the face opposite local vertex `i` is grounded (lies on a section plane).
    pub grounded_faces: Vec<u8>,
    /// Bit `i` set when the face opposite vertex `i` is grounded and inside the section (an internal
    /// section triangle).
    pub section_faces: Vec<u8>,
    /// Bit `i` set when the face opposite vertex `i` lies on a cap: a face whose other side holds
    /// no cell that could attach (see `Slot::beyond_may_attach`).
    pub cap_faces: Vec<u8>,
}

/// Bit `i` set when the face opposite vertex `i` has its three vertices on a common slot.
pub fn grounded_faces(m: [Mask; 4]) -> u8 {
    let faces = [
        m[1] & m[2] & m[3],
        m[0] & m[2] & m[3],
        m[0] & m[1] & m[3],
        m[0] & m[1] & m[2],
    ];
    (0..4).filter(|&i| faces[i] != 0).fold(0, |b, i| b | 1 << i)
}

pub struct Classifier<'a> {
    pub input: &'a CellInput,
    edge_cache: IdMap<(u32, u32), bool>,
}

impl<'a> Classifier<'a> {
    pub fn new(input: &'a CellInput) -> Self {
        Classifier {
            input,
            edge_cache: IdMap::default(),
        }
    }

    pub fn edge_external(&mut self, a: u32, b: u32) -> bool {
        let k = super::cell_input::edge_key(a, b);
        if let Some(&x) = self.edge_cache.get(&k) {
            return x;
        }
        let inp = self.input;
        let m = inp.mask[a as usize] & inp.mask[b as usize];
        let mut ext = false;
        for s in slots_of(m) {
            let slot = &inp.slots[s];
            if slot.contour_edges().contains(&k) {
                continue;
            }
            let (p, q) = (slot.uv[a as usize], slot.uv[b as usize]);
            let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            if slot.locator().locate(mid) == Where::Outside {
                ext = true;
                break;
            }
        }
        self.edge_cache.insert(k, ext);
        ext
    }

    /// Step 1 removes tet `t` (of type `ty`, grounded edge bits `g` from [`tet_type`]): it is flat,
    /// or has an external grounded edge, or (a `Vf`) an external grounded face.
    pub fn tet_external(&mut self, t: &[u32; 4], ty: TetType, g: u8) -> bool {
        if ty == TetType::Flat {
            return true;
        }
        for (k, &(i, j)) in TET_EDGES.iter().enumerate() {
            if g >> k & 1 == 1 && self.edge_external(t[i], t[j]) {
                return true;
            }
        }
        if ty == TetType::Vf {
            let mask = &self.input.mask;
            for i in 0..4 {
                let f = super::complex::outward_face(t, i);
                let mf = mask[f[0] as usize] & mask[f[1] as usize] & mask[f[2] as usize];
                if mf != 0 && self.triangle_external(f[0], f[1], f[2]) {
                    return true;
                }
            }
        }
        false
    }

    pub fn triangle_external(&self, a: u32, b: u32, c: u32) -> bool {
        let inp = self.input;
        let m = inp.mask[a as usize] & inp.mask[b as usize] & inp.mask[c as usize];
        slots_of(m).any(|s| {
            let slot = &inp.slots[s];
            let (p, q, r) = (
                slot.uv[a as usize],
                slot.uv[b as usize],
                slot.uv[c as usize],
            );
            let g = [(p[0] + q[0] + r[0]) / 3.0, (p[1] + q[1] + r[1]) / 3.0];
            slot.locator().locate(g) == Where::Outside
        })
    }
}

/// Type of a tetrahedron from its vertices' slot masks; also its grounded and pivot edge bits.
pub fn tet_type(m: [Mask; 4]) -> (TetType, u8, u8) {
    let mut grounded = 0u8;
    for (k, &(i, j)) in TET_EDGES.iter().enumerate() {
        if m[i] & m[j] != 0 {
            grounded |= 1 << k;
        }
    }
    if m[0] & m[1] & m[2] & m[3] != 0 {
        return (TetType::Flat, grounded, 0);
    }
    let faces = [
        m[1] & m[2] & m[3],
        m[0] & m[2] & m[3],
        m[0] & m[1] & m[3],
        m[0] & m[1] & m[2],
    ];
    if faces.iter().any(|&f| f != 0) {
        return (TetType::Vf, grounded, 0);
    }
    let mut pivots = 0u8;
    for k in 0..3 {
        if grounded >> k & 1 == 1 && grounded >> (5 - k) & 1 == 1 {
            pivots |= 1 << k | 1 << (5 - k);
        }
    }
    if pivots != 0 {
        (TetType::Ee, grounded, pivots)
    } else if grounded != 0 {
        (TetType::Evv, grounded, 0)
    } else {
        (TetType::Vvvv, grounded, 0)
    }
}

/// The type of every tetrahedron of `cx` (`tet_type` on its vertices' slot masks).
pub fn tet_types(input: &CellInput, cx: &Complex) -> Vec<TetType> {
    cx.tets
        .iter()
        .map(|t| tet_type(t.map(|v| input.mask[v as usize])).0)
        .collect()
}

pub fn classify(input: &CellInput, cx: &Complex) -> Classified {
    let mut cl = Classifier::new(input);
    let n = cx.len();
    let mut out = Classified {
        ty: Vec::with_capacity(n),
        external: Vec::with_capacity(n),
        grounded_edges: Vec::with_capacity(n),
        pivot_edges: Vec::with_capacity(n),
        grounded_faces: Vec::with_capacity(n),
        section_faces: Vec::with_capacity(n),
        cap_faces: Vec::with_capacity(n),
    };
    let caps: Mask = input
        .slots
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.beyond_may_attach)
        .fold(0, |m, (i, _)| m | 1 << i);
    for t in &cx.tets {
        let m = [
            input.mask[t[0] as usize],
            input.mask[t[1] as usize],
            input.mask[t[2] as usize],
            input.mask[t[3] as usize],
        ];
        let (ty, g, p) = tet_type(m);
        let ext = cl.tet_external(t, ty, g);
        out.ty.push(ty);
        out.external.push(ext);
        out.grounded_edges.push(g);
        out.pivot_edges.push(p);
        let gf = grounded_faces(m);
        let mut sf = gf;
        if ext && ty != TetType::Flat {
            for i in 0..4 {
                let f = super::complex::outward_face(t, i);
                if gf >> i & 1 == 1 && cl.triangle_external(f[0], f[1], f[2]) {
                    sf &= !(1 << i);
                }
            }
        }
        out.grounded_faces.push(gf);
        out.section_faces.push(sf);
        let fm = [
            m[1] & m[2] & m[3],
            m[0] & m[2] & m[3],
            m[0] & m[1] & m[3],
            m[0] & m[1] & m[2],
        ];
        out.cap_faces.push(
            (0..4)
                .filter(|&i| fm[i] & caps != 0)
                .fold(0, |b, i| b | 1 << i),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn typing_rule() {
        let (p, q, r, s) = (1u128, 2u128, 4u128, 8u128);
        assert_eq!(tet_type([p, p, p, p]).0, TetType::Flat);
        assert_eq!(tet_type([p, p, p, q]).0, TetType::Vf);
        let (ty, g, piv) = tet_type([p, p, q, q]);
        assert_eq!(ty, TetType::Ee);
        assert_eq!(g, 1 | 1 << 5);
        assert_eq!(piv, 1 | 1 << 5);
        assert_eq!(tet_type([p, p, q, r]).0, TetType::Evv);
        assert_eq!(tet_type([p, q, r, s]).0, TetType::Vvvv);
        // a vertex on the line P∩Q: edges (0,1) on P and (0,2) on Q share a vertex → Evv
        assert_eq!(tet_type([p | q, p, q, r]).0, TetType::Evv);
        // P∩Q vertex with P and Q partners on opposite edges → Vf on P (3 vertices carry P)
        assert_eq!(tet_type([p | q, p, q, p]).0, TetType::Vf);
    }
}
