//! Which label each tetrahedron of K takes (the rule is the module doc of `partition`).
use super::interfaces::Mesh;
use super::{Complex, NONE};
use crate::arrangement::Arrangement;
use crate::bm::complex::outward_face;
use crate::fxhash::FxHashMap;
use crate::sections::{Plane, Sections};

/// A label's (by index) value at a point, larger: more that label's; what decides the tetrahedra
/// the planes leave open.
pub type Prefer<'a> = dyn Fn(u32, [f64; 3]) -> f64 + Sync + 'a;

/// Rounds of majority vote after the growth.
const SMOOTHING_ROUNDS: usize = 4;

/// A labelled region of a section in its plane's (u,v) frame.
struct Region {
    label: u32,
    outer: Vec<[f64; 2]>,
    holes: Vec<Vec<[f64; 2]>>,
    lo: [f64; 2],
    hi: [f64; 2],
}

/// The labelled regions of every section, found by arrangement plane.
pub(super) struct Regions<'a> {
    pub sections: &'a Sections,
    /// Per arrangement plane, its section (`None`: a wall of the box).
    section_of_plane: Vec<Option<usize>>,
    /// Per section, its arrangement plane.
    plane_of_section: Vec<Option<u32>>,
    /// Per section, its regions (label as an index into the partition's labels).
    regions: Vec<Vec<Region>>,
    pub n_labels: usize,
}

/// Crossing-number test of `q` against the closed polygon `p` (float: a section triangle's centre
/// is far from the outline; `validate::winding_number`, exact, decides otherwise on a few
/// slivers, which changes outputs).
fn inside(p: &[[f64; 2]], q: [f64; 2]) -> bool {
    let mut odd = false;
    let mut j = p.len() - 1;
    for i in 0..p.len() {
        let (a, b) = (p[i], p[j]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if q[0] < x {
                odd = !odd;
            }
        }
        j = i;
    }
    odd
}

/// Per section (of `n`), the arrangement plane it lies on (`None`: not a plane of the arrangement).
pub(super) fn plane_of_section(arrangement: &Arrangement, n: usize) -> Vec<Option<u32>> {
    let mut out = vec![None; n];
    for (p, ap) in arrangement.planes.iter().enumerate() {
        if let Some(s) = ap.section.filter(|&s| s < n) {
            out[s] = Some(p as u32);
        }
    }
    out
}

impl<'a> Regions<'a> {
    pub fn new(sections: &'a Sections, arrangement: &Arrangement, labels: &[i32]) -> Regions<'a> {
        let index = |l: i32| labels.binary_search(&l).map_or(NONE, |i| i as u32);
        let regions = (sections.sections.iter())
            .map(|s| {
                (s.regions.iter())
                    .map(|r| {
                        let (mut lo, mut hi) = (r.outer.points2[0], r.outer.points2[0]);
                        for q in &r.outer.points2 {
                            for k in 0..2 {
                                lo[k] = lo[k].min(q[k]);
                                hi[k] = hi[k].max(q[k]);
                            }
                        }
                        Region {
                            label: index(r.label),
                            outer: r.outer.points2.clone(),
                            holes: r.holes.iter().map(|h| h.points2.clone()).collect(),
                            lo,
                            hi,
                        }
                    })
                    .collect()
            })
            .collect();
        Regions {
            sections,
            section_of_plane: arrangement.planes.iter().map(|p| p.section).collect(),
            plane_of_section: plane_of_section(arrangement, sections.sections.len()),
            regions,
            n_labels: labels.len(),
        }
    }

    /// The section on arrangement plane `p`, if any.
    pub fn section(&self, p: u32) -> Option<usize> {
        self.section_of_plane.get(p as usize).copied().flatten()
    }

    /// The arrangement plane of section `s`, if any.
    pub fn plane_id(&self, s: usize) -> Option<u32> {
        self.plane_of_section[s]
    }

    pub fn plane(&self, s: usize) -> &Plane {
        &self.sections.sections[s].plane
    }

    /// The label (index) of the region of section `s` holding `x` (3D, on the plane), if any.
    pub fn locate(&self, s: usize, x: [f64; 3]) -> Option<u32> {
        let q = self.plane(s).to_2d(x);
        self.regions[s]
            .iter()
            .find(|r| {
                (0..2).all(|k| r.lo[k] <= q[k] && q[k] <= r.hi[k])
                    && inside(&r.outer, q)
                    && !r.holes.iter().any(|h| inside(h, q))
            })
            .map(|r| r.label)
    }
}

/// The section plane that the vertices `f` all lie on (the smallest such plane), if any.
pub(super) fn common_section_plane(mesh: &Mesh, regions: &Regions, f: &[u32]) -> Option<u32> {
    let first = &mesh.planes[f[0] as usize];
    first.iter().copied().find(|&p| {
        regions.section(p).is_some() && f[1..].iter().all(|&v| mesh.planes[v as usize].contains(&p))
    })
}

/// The labels of K's tetrahedra, and how they were decided.
pub(super) struct Assigned {
    /// Per tetrahedron, its label (an index into the partition's labels).
    pub label: Vec<u32>,
    /// Tetrahedra standing on a section: their label is the section's, never changed.
    pub pinned: Vec<bool>,
    /// Per tetrahedron, the labels compatible with the sections (a bit per label below 64; all
    /// bits with more labels, and for pinned tetrahedra).
    pub compatible: Vec<u64>,
    pub on_sections: u64,
    pub one_compatible: u64,
    pub grown: u64,
    /// Tetrahedra standing on section triangles of two labels.
    pub conflicts: u64,
    /// Section triangles of K whose centre lies in no labelled region.
    pub unlocated: u64,
}

/// A set of labels (indices below 64; with more labels every set is "all").
type Mask = u64;
const ALL: Mask = !0;

fn bit(l: u32) -> Mask {
    if l < 64 {
        1 << l
    } else {
        ALL
    }
}

/// Per tetrahedron the label of its section faces (`NONE` where it has none), and per vertex and
/// edge on a section plane the labels of the section triangles around it.
struct SectionFaces {
    forced: Vec<u32>,
    conflicts: u64,
    unlocated: u64,
    vertex_labels: FxHashMap<(u32, u32), Mask>,
    edge_labels: FxHashMap<(u32, u32, u32), Mask>,
}

fn section_faces(complex: &Complex, mesh: &Mesh, regions: &Regions) -> SectionFaces {
    let mut out = SectionFaces {
        forced: vec![NONE; complex.tets.len()],
        conflicts: 0,
        unlocated: 0,
        vertex_labels: FxHashMap::default(),
        edge_labels: FxHashMap::default(),
    };
    for (t, tet) in complex.tets.iter().enumerate() {
        for i in 0..4 {
            let f = outward_face(tet, i);
            let Some(p) = common_section_plane(mesh, regions, &f) else {
                continue;
            };
            let s = regions.section(p).expect("a section plane");
            let x = f.map(|v| mesh.positions[v as usize]);
            let centre = [0, 1, 2].map(|k| (x[0][k] + x[1][k] + x[2][k]) / 3.0);
            let Some(l) = regions.locate(s, centre) else {
                out.unlocated += 1;
                continue;
            };
            match out.forced[t] {
                NONE => out.forced[t] = l,
                m if m != l => {
                    out.conflicts += 1;
                    out.forced[t] = m.min(l);
                }
                _ => {}
            }
            for k in 0..3 {
                *out.vertex_labels.entry((f[k], p)).or_default() |= bit(l);
                let (a, b) = (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3]));
                *out.edge_labels.entry((a, b, p)).or_default() |= bit(l);
            }
        }
    }
    out
}

/// The labels compatible with tetrahedron `tet`: on every section plane its vertices lie on, the
/// labels around its simplex there (`ALL` where nothing constrains it, 0 where nothing fits).
fn compatible(tet: &[u32; 4], mesh: &Mesh, regions: &Regions, sf: &SectionFaces) -> Mask {
    let mut mask = ALL;
    let mut seen: smallvec::SmallVec<[u32; 8]> = smallvec::SmallVec::new();
    // a collar image stands for its base (the prism's edge joins them)
    let mut tet: smallvec::SmallVec<[u32; 4]> = tet.iter().map(|&v| mesh.origin(v)).collect();
    tet.sort_unstable();
    tet.dedup();
    for &v in &tet {
        for &p in &mesh.planes[v as usize] {
            if seen.contains(&p) || regions.section(p).is_none() {
                continue;
            }
            seen.push(p);
            let on: smallvec::SmallVec<[u32; 4]> = (tet.iter().copied())
                .filter(|&w| mesh.planes[w as usize].contains(&p))
                .collect();
            let m = match on.len() {
                1 => sf.vertex_labels.get(&(on[0], p)),
                2 => sf.edge_labels.get(&(on[0].min(on[1]), on[0].max(on[1]), p)),
                _ => None,
            };
            if let Some(m) = m {
                mask &= m;
            }
        }
    }
    mask
}

/// The label most of `t`'s labelled neighbours have, among `mask` where some of them fit it
/// (ties: the smaller); `current` wins ties with it.
fn vote(complex: &Complex, label: &[u32], t: usize, mask: Mask, current: u32) -> Option<u32> {
    let mut votes: smallvec::SmallVec<[(u32, u32); 4]> = smallvec::SmallVec::new();
    for &n in &complex.nbr[t] {
        if n == NONE || label[n as usize] == NONE {
            continue;
        }
        let l = label[n as usize];
        match votes.iter_mut().find(|(m, _)| *m == l) {
            Some(v) => v.1 += 1,
            None => votes.push((l, 1)),
        }
    }
    if votes.iter().any(|(l, _)| bit(*l) & mask != 0) {
        votes.retain(|(l, _)| bit(*l) & mask != 0);
    }
    let score = |&(l, n): &(u32, u32)| (2 * n + u32::from(l == current), std::cmp::Reverse(l));
    votes.iter().max_by_key(|v| score(v)).map(|v| v.0)
}

/// The smallest label in `mask`, if it names one.
fn smallest(mask: Mask, n_labels: usize) -> Option<u32> {
    (mask != 0 && mask != ALL)
        .then(|| mask.trailing_zeros())
        .filter(|&l| (l as usize) < n_labels)
}

pub(super) fn assign(
    complex: &Complex,
    mesh: &Mesh,
    regions: &Regions,
    prefer: Option<&Prefer<'_>>,
) -> Assigned {
    let n = complex.tets.len();
    let sf = section_faces(complex, mesh, regions);
    let mut out = Assigned {
        label: vec![NONE; n],
        pinned: vec![false; n],
        compatible: Vec::new(),
        on_sections: 0,
        one_compatible: 0,
        grown: 0,
        conflicts: sf.conflicts,
        unlocated: sf.unlocated,
    };
    let mut masks = vec![ALL; n];
    for (t, mask) in masks.iter_mut().enumerate() {
        if sf.forced[t] != NONE {
            out.label[t] = sf.forced[t];
            out.pinned[t] = true;
            out.on_sections += 1;
            continue;
        }
        let m = compatible(&complex.tets[t], mesh, regions, &sf);
        let m = if regions.n_labels <= 64 { m } else { ALL };
        *mask = m;
        if m.count_ones() == 1 && (m.trailing_zeros() as usize) < regions.n_labels {
            out.label[t] = m.trailing_zeros();
            out.one_compatible += 1;
        }
    }
    out.grown = match prefer {
        Some(prefer) => preferred(
            complex,
            mesh,
            &mut out.label,
            &masks,
            regions.n_labels as u32,
            prefer,
        ),
        None => grow(complex, &mut out.label, &masks, regions.n_labels),
    };
    let free: Vec<usize> = (0..n)
        .filter(|&t| !out.pinned[t] && masks[t].count_ones() != 1)
        .collect();
    for _ in 0..SMOOTHING_ROUNDS {
        let changes: Vec<(usize, u32)> = (free.iter())
            .filter_map(|&t| {
                let l = vote(complex, &out.label, t, masks[t], out.label[t])?;
                (l != out.label[t]).then_some((t, l))
            })
            .collect();
        if changes.is_empty() {
            break;
        }
        for (t, l) in changes {
            out.label[t] = l;
        }
    }
    out.compatible = masks;
    out
}

/// Label the unlabelled tetrahedra by `prefer` at their centroids: the best of their compatible
/// labels (of all where none fits); the number labelled.
fn preferred(
    complex: &Complex,
    mesh: &Mesh,
    label: &mut [u32],
    masks: &[Mask],
    n_labels: u32,
    prefer: &Prefer<'_>,
) -> u64 {
    use rayon::prelude::*;
    let chosen: Vec<(usize, u32)> = (0..label.len())
        .into_par_iter()
        .filter(|&t| label[t] == NONE)
        .map(|t| {
            let p = complex.tets[t].map(|v| mesh.positions[v as usize]);
            let c = [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k] + p[3][k]) / 4.0);
            let fits = |l: u32| bit(l) & masks[t] != 0;
            let any = (0..n_labels).any(fits);
            let best = (0..n_labels)
                .filter(|&l| !any || fits(l))
                .map(|l| (prefer(l, c), l))
                .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)))
                .map_or(0, |b| b.1);
            (t, best)
        })
        .collect();
    for &(t, l) in &chosen {
        label[t] = l;
    }
    chosen.len() as u64
}

/// Label the unlabelled tetrahedra in layers of face neighbours from the labelled ones (module
/// doc); the number labelled.
fn grow(complex: &Complex, label: &mut [u32], masks: &[Mask], n_labels: usize) -> u64 {
    let n = label.len();
    let mut queued = vec![false; n];
    let mut layer: Vec<usize> = Vec::new();
    let push_nbrs = |t: usize, label: &[u32], queued: &mut [bool], next: &mut Vec<usize>| {
        for &m in &complex.nbr[t] {
            if m != NONE && label[m as usize] == NONE && !queued[m as usize] {
                queued[m as usize] = true;
                next.push(m as usize);
            }
        }
    };
    for t in 0..n {
        if label[t] != NONE {
            push_nbrs(t, label, &mut queued, &mut layer);
        }
    }
    let mut grown = 0;
    while !layer.is_empty() {
        let chosen: Vec<u32> = (layer.iter())
            .map(|&t| {
                vote(complex, label, t, masks[t], NONE)
                    .map(|l| match smallest(masks[t], n_labels) {
                        Some(s) if bit(l) & masks[t] == 0 => s,
                        _ => l,
                    })
                    .unwrap_or(0)
            })
            .collect();
        for (&t, &l) in layer.iter().zip(&chosen) {
            label[t] = l;
        }
        grown += layer.len() as u64;
        let mut next = Vec::new();
        for &t in &layer {
            push_nbrs(t, label, &mut queued, &mut next);
        }
        layer = next;
    }
    // what no labelled tetrahedron reaches (a component of K with no section: none in practice)
    for t in 0..n {
        if label[t] == NONE {
            label[t] = smallest(masks[t], n_labels).unwrap_or(0);
            grown += 1;
        }
    }
    grown
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_number_inside_a_square_with_a_notch() {
        let p = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 1.0], [0.0, 2.0]];
        assert!(inside(&p, [0.5, 0.5]));
        assert!(!inside(&p, [1.0, 1.5]));
        assert!(!inside(&p, [3.0, 0.5]));
    }

    #[test]
    fn a_vote_prefers_compatible_labels_then_the_majority_then_the_smaller() {
        // tetrahedron 0 with neighbours 1, 2, 3 labelled 1, 2, 2
        let c = Complex::new(
            8,
            vec![[0, 1, 2, 3], [0, 2, 1, 4], [0, 3, 2, 5], [0, 1, 3, 6]],
        );
        let label = [NONE, 1, 2, 2];
        assert_eq!(vote(&c, &label, 0, ALL, NONE), Some(2));
        assert_eq!(vote(&c, &label, 0, bit(1), NONE), Some(1));
        assert_eq!(vote(&c, &[NONE, 1, 2, NONE], 0, ALL, NONE), Some(1));
        assert_eq!(smallest(bit(3) | bit(5), 8), Some(3));
        assert_eq!(smallest(ALL, 8), None);
    }
}
