//! Diagram samples shared by both cells of a face.
//!
//! Each cell samples the branching and cutting diagrams of its faces from its own Delaunay
//! triangulation (the Moebius diagram seen from its side). Inserted into that cell only, they made
//! the two cells of a face triangulate it differently on 544 of Elephant's 1129 shared faces (all
//! but one measured difference; `docs/design/conforming-complex.md`), which the first pipeline
//! then had to overlay. Here every cell's samples on a face become one global pool vertex each (tagged with the
//! face's plane), and both cells of the face insert all of them: with the same points on a face,
//! both restrictions of the cells' triangulations to the face are the same 2D Delaunay triangulation
//! (exactly so on axis-aligned planes; on oblique ones up to ties that rounding decides).
//!
//! Termination: the samples come from each cell's first run, whose triangulation holds only its
//! own samples; the second run recomputes them identically (same input, deterministic) and adds
//! the other side's, which are never sampled from again.
use super::cell::CellResult;
use crate::arrangement::{Arrangement, FaceId, VertexPool};
use smallvec::smallvec;
use std::collections::HashMap;

/// One sample on a face, as a global pool vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SharedSample {
    pub gid: u32,
    pub uv: [f64; 2],
    pub p3: [f64; 3],
}

/// Per face id, the samples both of its cells insert (in the order their ids were assigned).
#[derive(Clone, Debug, Default)]
pub struct SharedSamples {
    pub by_face: Vec<Vec<SharedSample>>,
    /// Two samples of one face closer than this (in every coordinate) are one sample
    /// ([`SAME_SAMPLE_RELATIVE`] of the arrangement's box diagonal; 0 before `extend`).
    pub same: f64,
}

/// Relative to the arrangement's box diagonal: samples of one face closer than this are one. The
/// two cells of a face can compute the same diagram point (a cutting sample of the face's own
/// section, a branching sample both sides see) in another float order, a few ulps apart; kept as
/// two vertices, both cells insert both, and a cavity through the pair is not star-shaped (the
/// cell falls back to the untagged kernel: generated odd files g041, g098).
pub const SAME_SAMPLE_RELATIVE: f64 = 1e-11;

/// The exact position of a sample, as a lookup key.
pub fn key(p3: [f64; 3]) -> [u64; 3] {
    p3.map(f64::to_bits)
}

/// A face's samples by position, found exactly or within a tolerance: a hash grid of cells as
/// wide as the tolerance, a query probing the 27 cells around it.
#[derive(Clone, Debug, Default)]
pub struct NearSamples {
    tol: f64,
    samples: Vec<SharedSample>,
    grid: HashMap<[i64; 3], Vec<usize>>,
}

impl NearSamples {
    pub fn new(tol: f64, samples: impl IntoIterator<Item = SharedSample>) -> NearSamples {
        let mut out = NearSamples {
            tol,
            ..Default::default()
        };
        for x in samples {
            out.insert(x);
        }
        out
    }

    fn cell(&self, p: [f64; 3]) -> [i64; 3] {
        if self.tol > 0.0 {
            p.map(|c| (c / self.tol).floor() as i64)
        } else {
            [0; 3]
        }
    }

    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    pub fn insert(&mut self, x: SharedSample) {
        let c = self.cell(x.p3);
        self.grid.entry(c).or_default().push(self.samples.len());
        self.samples.push(x);
    }

    /// The sample at `p` exactly, else the nearest within the tolerance (the first inserted of
    /// equally near ones).
    pub fn find(&self, p: [f64; 3]) -> Option<SharedSample> {
        let c = self.cell(p);
        let mut best: Option<(f64, usize)> = None;
        let reach = if self.tol > 0.0 { 1 } else { 0 };
        for dx in -reach..=reach {
            for dy in -reach..=reach {
                for dz in -reach..=reach {
                    let Some(list) = self.grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &i in list {
                        let q = self.samples[i].p3;
                        let d = (0..3).map(|k| (q[k] - p[k]).abs()).fold(0.0, f64::max);
                        if d <= self.tol && best.is_none_or(|b| (d, i) < b) {
                            best = Some((d, i));
                        }
                    }
                }
            }
        }
        best.map(|(_, i)| self.samples[i])
    }
}

impl SharedSamples {
    /// Make pool vertices of the cell-local vertices of `results` (diagram samples and their
    /// Steiner points) that are not shared yet, face by face in increasing face id, the negative
    /// cell's before the positive cell's, each in local id order: deterministic whatever the
    /// threads did. A position already shared on the face, or sampled by both cells, is one vertex.
    /// Returns the faces that got new samples.
    pub fn extend(
        &mut self,
        arr: &Arrangement,
        pool: &mut VertexPool,
        results: &[Option<CellResult>],
    ) -> Vec<FaceId> {
        self.by_face.resize(arr.faces.len(), Vec::new());
        self.same = same_tolerance(arr);
        let mut changed = Vec::new();
        for (f, face) in arr.faces.iter().enumerate() {
            let mut seen = NearSamples::new(self.same, self.by_face[f].iter().copied());
            let before = self.by_face[f].len();
            for (input, s) in face_sides(f, face, results) {
                // slimmed inputs: the slot's cell-local vertices with their (u,v)
                for &(l, uv) in &input.slots[s].local_uv {
                    let l = l as usize;
                    if input.global[l] != u32::MAX {
                        continue;
                    }
                    let p3 = input.points[l];
                    if seen.find(p3).is_none() {
                        pool.positions.push(p3);
                        pool.tags.push(smallvec![face.plane]);
                        pool.uv.push(smallvec![uv]);
                        let gid = (pool.positions.len() - 1) as u32;
                        let x = SharedSample { gid, uv, p3 };
                        self.by_face[f].push(x);
                        seen.insert(x);
                    }
                }
            }
            if self.by_face[f].len() > before {
                changed.push(f as FaceId);
            }
        }
        changed
    }

    /// Give every cell-local vertex of `result` at the position of a shared sample of its face
    /// that sample's global id (a cell that kept a run without the other side's samples, or a
    /// Steiner point that landed on a shared one): one position, one vertex.
    pub fn adopt_ids(&self, result: &mut CellResult) {
        let Some(input) = result.input.as_mut() else {
            return;
        };
        let lookup: Vec<NearSamples> = input.slots.iter().map(|sl| self.near(sl.face)).collect();
        for l in 0..input.points.len() {
            if input.global[l] != u32::MAX {
                continue;
            }
            let m = input.mask[l];
            if let Some(x) = (0..input.slots.len())
                .filter(|&s| m >> s & 1 == 1)
                .find_map(|s| lookup[s].find(input.points[l]))
            {
                input.global[l] = x.gid;
            }
        }
    }

    /// Cell-local vertices of `results` that no shared sample stands for (points only one cell of
    /// a face inserted).
    pub fn one_sided(&self, results: &[Option<CellResult>]) -> u64 {
        results
            .iter()
            .flatten()
            .filter_map(|r| r.input.as_ref())
            .map(|i| i.global.iter().filter(|&&g| g == u32::MAX).count() as u64)
            .sum()
    }

    /// The samples of face `f` (none for a face without).
    /// Shared points given before any cell runs (`seeds`: a plane and a point on it, such as the
    /// outline two labels share inside the section of all labels): each becomes a pool vertex on
    /// the face of its plane holding it, inserted by both cells of that face from their first run
    /// on, so that conformity splits what it takes away. A point within `margin` of its face's
    /// polygon or section boundary, or in no face's section, is left out; the number placed.
    pub fn seeded(
        arr: &Arrangement,
        pool: &mut VertexPool,
        seeds: &[(u32, [f64; 3])],
        margin: f64,
    ) -> (SharedSamples, u64) {
        use super::cell_input::{SectionLocator, Where};
        use crate::geom::predicates::orient2d;
        let mut out = SharedSamples {
            by_face: vec![Vec::new(); arr.faces.len()],
            same: same_tolerance(arr),
        };
        let mut faces_of: HashMap<u32, Vec<usize>> = HashMap::new();
        for (f, face) in arr.faces.iter().enumerate() {
            if !face.pieces.is_empty() {
                faces_of.entry(face.plane).or_default().push(f);
            }
        }
        let uv = |v: u32, p: u32| arr.uv(v, p).unwrap_or([f64::NAN; 2]);
        let mut locators: HashMap<usize, SectionLocator> = HashMap::new();
        let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
        let mut placed = 0;
        for &(p, x) in seeds {
            let q = arr.planes[p as usize].plane.to_2d(x);
            let clear_of = |a: [f64; 2], b: [f64; 2]| {
                let len = (b[0] - a[0]).hypot(b[1] - a[1]);
                orient2d(a, b, q) > 0.0 && orient2d(a, b, q) / len > margin
            };
            let Some(&f) = faces_of.get(&p).into_iter().flatten().find(|&&f| {
                let poly = &arr.faces[f].polygon;
                (0..poly.len()).all(|i| clear_of(uv(poly[i], p), uv(poly[(i + 1) % poly.len()], p)))
            }) else {
                continue;
            };
            let loc = locators.entry(f).or_insert_with(|| {
                let loops: Vec<Vec<[f64; 2]>> = (arr.faces[f].pieces.iter())
                    .flat_map(|pc| std::iter::once(&pc.outer).chain(&pc.holes))
                    .map(|l| l.iter().map(|&v| uv(v, p)).collect())
                    .collect();
                SectionLocator::new(&loops)
            });
            if loc.locate_clear(q, margin) != Where::Inside || seen.contains_key(&key(x)) {
                continue;
            }
            pool.positions.push(x);
            pool.tags.push(smallvec![p]);
            pool.uv.push(smallvec![q]);
            let gid = (pool.positions.len() - 1) as u32;
            seen.insert(key(x), gid);
            out.by_face[f].push(SharedSample { gid, uv: q, p3: x });
            placed += 1;
        }
        (out, placed)
    }

    /// The samples of face `f` by position, within [`SharedSamples::same`].
    pub fn near(&self, f: FaceId) -> NearSamples {
        NearSamples::new(self.same, self.on_face(f).iter().copied())
    }

    pub fn on_face(&self, f: FaceId) -> &[SharedSample] {
        self.by_face.get(f as usize).map_or(&[], Vec::as_slice)
    }

    pub fn len(&self) -> usize {
        self.by_face.iter().map(Vec::len).sum()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether one of `faces` has shared samples.
    pub fn touches(&self, faces: impl IntoIterator<Item = FaceId>) -> bool {
        faces.into_iter().any(|f| !self.on_face(f).is_empty())
    }
}

/// [`SAME_SAMPLE_RELATIVE`] of the arrangement's box diagonal.
fn same_tolerance(arr: &Arrangement) -> f64 {
    let (lo, hi) = arr.bbox;
    SAME_SAMPLE_RELATIVE * (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

/// The cells of face `f` that ran, with the slot of the face in each.
fn face_sides<'a>(
    f: usize,
    face: &crate::arrangement::Face,
    results: &'a [Option<CellResult>],
) -> impl Iterator<Item = (&'a super::cell_input::CellInput, usize)> + 'a {
    [face.negative_cell, face.positive_cell]
        .into_iter()
        .flatten()
        .filter_map(move |c| {
            let input = results[c as usize].as_ref()?.input.as_ref()?;
            let s = input.slots.iter().position(|sl| sl.face as usize == f)?;
            Some((input, s))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(gid: u32, p3: [f64; 3]) -> SharedSample {
        SharedSample {
            gid,
            uv: [p3[0], p3[1]],
            p3,
        }
    }

    #[test]
    fn a_sample_a_few_ulps_off_is_found_and_a_distinct_one_is_not() {
        let x = 0.009518436077619128;
        let near = NearSamples::new(
            1e-11,
            [sample(1, [x, -0.3085, 0.1182]), sample(2, [0.5, 0.5, 0.5])],
        );
        // the two roundings of one diagram point of g098 (a generated odd file)
        let off = [x, -0.3085 + 5.6e-17, 0.1182 + 1.4e-17];
        assert_eq!(near.find(off).map(|s| s.gid), Some(1));
        assert_eq!(near.find([x, -0.3085, 0.1182]).map(|s| s.gid), Some(1));
        assert_eq!(near.find([x + 2e-11, -0.3085, 0.1182]), None);
        assert_eq!(near.find([0.5, 0.5 + 9e-12, 0.5]).map(|s| s.gid), Some(2));
        // across a grid cell's border, the nearest of two
        let t = 1e-11;
        let near = NearSamples::new(
            t,
            [
                sample(7, [3.0 * t, 0.0, 0.0]),
                sample(8, [3.9 * t, 0.0, 0.0]),
            ],
        );
        assert_eq!(near.find([3.6 * t, 0.0, 0.0]).map(|s| s.gid), Some(8));
        assert_eq!(near.find([2.05 * t, 0.0, 0.0]).map(|s| s.gid), Some(7));
        // without a tolerance, only the exact position
        let exact = NearSamples::new(0.0, [sample(3, [0.1, 0.2, 0.3])]);
        assert_eq!(exact.find([0.1, 0.2, 0.3]).map(|s| s.gid), Some(3));
        assert_eq!(exact.find([0.1, 0.2, 0.3 + 1e-16]), None);
    }
}
