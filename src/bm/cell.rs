//! One cell, end to end: Delaunay of its section vertices (plus branching samples), conformity check,
//! classification, pruning, and what the gluing needs (kept tets, non-planar boundary, per face the
//! section triangles seen from this cell and whether the cell attaches to them).
use super::cell_input::{CellInput, IdMap, IdSet, Mask};
use super::classify::{classify, Classifier, TetType};

/// Rounds of branching and cutting sampling (sample, re-triangulate) per cell.
const BRANCHING_ROUNDS: usize = 1;

/// Most rounds of Steiner splits making consecutive diagram samples Delaunay edges.
pub const SAMPLE_PAIR_ROUNDS: usize = 8;

/// Which samples of the Moebius diagram a cell adds to its contour vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    /// Samples of the branching diagram (`branching`).
    pub branching: bool,
    /// Samples of the cutting diagram (`cutting`).
    pub cutting: bool,
}

impl Default for Sampling {
    fn default() -> Self {
        Sampling {
            branching: true,
            cutting: true,
        }
    }
}
use super::chains::Chains;
use super::complex::{outward_face, Complex};
use super::prune::{prune, PruneCounts};
use super::shared_samples::SharedSamples;
use crate::error::Result;
mod samples;
use samples::{insert_diagram_samples, SampleRun, Sampled, Tri};

/// The section triangles of one face as this cell's triangulation has them.
#[derive(Clone, Debug, Default)]
pub struct FaceSide {
    pub face: u32,
    /// Internal grounded triangles on the face that bound a non-flat tet of this cell, oriented
    /// outward from the cell (local ids), with whether a kept tet stands on them.
    pub triangles: Vec<([u32; 3], bool)>,
    /// Per triangle, the fourth vertex of this cell's tet standing on it (`u32::MAX` in a cell
    /// without volume): where a flat zone gets its slab (`slab`).
    pub apexes: Vec<u32>,
}

/// The start of a cell's run that every rerun with shared samples repeats exactly (it depends on
/// the cell's contour points only): the first round's diagram samples and the Delaunay
/// triangulation of the contour points with them. Kept from the first run so that the reruns only
/// insert the other sides' samples (the triangulation is unique for a point set under the
/// perturbation, whatever the insertion order).
#[derive(Clone, Debug)]
pub struct RunStart {
    /// The contour points the start was computed from.
    points: Vec<[f64; 3]>,
    /// Their triangulation, with the first round's samples after them when `with_samples`.
    dt: crate::delaunay::Delaunay,
    with_samples: bool,
    tagged: bool,
    branching: Chains,
    cutting: Chains,
}

#[derive(Clone, Debug, Default)]
pub struct CellResult {
    pub input: Option<CellInput>,
    /// The first run's start, for the reruns with shared samples (`RunStart`).
    pub start: Option<Box<RunStart>>,
    /// Contour edges (global ids) that are not edges of this cell's section triangulation.
    pub missing: Vec<(u32, u32)>,
    pub kept: Vec<[u32; 4]>,
    /// The tets that survived step 1 (no external face) but are not kept: adding one keeps every
    /// section triangle's status outside the section, so singularities can be filled with them.
    pub fillable: Vec<[u32; 4]>,
    /// The other tets (removed in step 1: a face outside its section), flat ones left out. With
    /// `kept` and `fillable`, the cell's whole triangulation, which the complex is refined in
    /// (`refine`).
    pub external: Vec<[u32; 4]>,
    pub faces: Vec<FaceSide>,
    pub counts: PruneCounts,
    pub tets: u64,
    pub flat_tets: u64,
    pub branching_samples: u64,
    pub cutting_samples: u64,
    /// Pairs of diagram samples consecutive along a branching or cutting diagram (`chains`).
    pub sample_pairs: u64,
    /// Steiner points on the diagrams that split pairs which were not Delaunay edges.
    pub sample_steiner_points: u64,
    /// Samples of the other cells of its faces that this cell inserted (`shared_samples`).
    pub foreign_samples: u64,
    /// The run went through classification and pruning (else it stopped at conformity).
    pub pruned: bool,
    /// Per face, pairs (after splitting) still not edges of the face's section triangles.
    pub sample_pairs_not_edges: Vec<(u32, u64)>,
    /// The consecutive pairs after splitting: (slot, local id, local id).
    pub sample_pair_list: Vec<(usize, u32, u32)>,
    /// Cutting samples that end on the border of a flat zone of this cell (a vertex of a section
    /// triangle the cell attaches to and of one it leaves flat).
    pub cutting_on_flat_border: u64,
    /// Area of the internal section triangles this cell leaves unattached (its flat zones, whether
    /// or not the other side attaches there).
    pub flat_area: f64,
    /// CPU seconds spent in this run's sub-phases.
    pub timing: CellTiming,
    /// The cell has no volume (every vertex on one plane): no tets, and its `faces` are each slot's
    /// section triangulated in 2D, none attached.
    pub flat_only: bool,
    /// The tagged kernel met an exact cosphericity across planes it cannot decide, so the cell was
    /// triangulated untagged (its faces may then differ from the other side's).
    pub untagged: bool,
}

/// CPU seconds per sub-phase of one cell run (summed over cells and rounds in the report).
#[derive(Clone, Copy, Debug, Default)]
pub struct CellTiming {
    /// Gathering the cell's points, slots and locators (`CellInput::build`).
    pub input: f64,
    /// Delaunay triangulations (kernel) and their neighbour complexes.
    pub delaunay: f64,
    /// Branching-diagram samples (without the re-triangulation).
    pub branching: f64,
    /// Cutting-diagram samples (without the re-triangulation).
    pub cutting: f64,
    /// Consecutive diagram samples made Delaunay edges (checks and Steiner insertions).
    pub sample_pairs: f64,
    /// Section triangles per face and the contour-edge conformity check.
    pub conformity: f64,
    /// Simplex classification by plane tags.
    pub classify: f64,
    /// Pruning steps 1–3.
    pub prune: f64,
    /// Kept tets, non-planar boundary and per-face section triangles for the gluing.
    pub output: f64,
}

impl CellTiming {
    pub fn add(&mut self, o: &CellTiming) {
        self.input += o.input;
        self.delaunay += o.delaunay;
        self.branching += o.branching;
        self.cutting += o.cutting;
        self.sample_pairs += o.sample_pairs;
        self.conformity += o.conformity;
        self.classify += o.classify;
        self.prune += o.prune;
        self.output += o.output;
    }

    /// (name, seconds) pairs in pipeline order.
    pub fn entries(&self) -> [(&'static str, f64); 9] {
        [
            ("input", self.input),
            ("delaunay", self.delaunay),
            ("branching", self.branching),
            ("cutting", self.cutting),
            ("sample_pairs", self.sample_pairs),
            ("conformity", self.conformity),
            ("classify", self.classify),
            ("prune", self.prune),
            ("output", self.output),
        ]
    }
}

/// Seconds since `t`, restarting `t`.
fn lap(t: &mut std::time::Instant) -> f64 {
    let now = std::time::Instant::now();
    let d = now.duration_since(*t).as_secs_f64();
    *t = now;
    d
}

/// Triangulate `points` with our exact kernel; finite tets in input vertex ids, positively oriented
/// in `robust`'s convention (`orient3d > 0`, the pruning's convention; the kernel hands out the
/// opposite orientation, so two vertices are swapped; `assembly` swaps them back for `TetMesh`), in canonical order (see
/// [`finite_tets`]). Exact duplicates are merged by the kernel into the smallest index.
pub fn delaunay_tets(points: &[[f64; 3]]) -> Result<Vec<[u32; 4]>> {
    Ok(finite_tets(&crate::delaunay::Delaunay::try_new(points)?))
}

/// The finite tets of `dt` as [`delaunay_tets`] gives them. The kernel's perturbation makes the
/// triangulation unique for a point set, but its tet slots depend on the insertion history; so each
/// tet is rotated (by an even permutation, keeping its orientation) to start with its smallest
/// vertex, then its smallest other vertex, and the list is sorted. A triangulation built at once or
/// grown by later insertions then gives the same list.
pub fn finite_tets(dt: &crate::delaunay::Delaunay) -> Vec<[u32; 4]> {
    let mut tets: Vec<[u32; 4]> = dt
        .tets()
        .map(|t| {
            let v = dt.tet_vertices(t);
            super::complex::canonical_tet([v[0], v[1], v[3], v[2]]).0
        })
        .collect();
    tets.sort_unstable();
    tets
}

/// The Delaunay triangulation of the cell's points: tagged (the plane rules of
/// `delaunay::tags`, so both cells of a face triangulate it alike and no tet is flat), or, when
/// `*tagged` is false or the tagged kernel meets an exact cosphericity across planes it cannot
/// decide, untagged (then `*tagged` becomes false: the cell's faces may differ from the other
/// side's, counted by the caller).
fn cell_delaunay(input: &CellInput, tagged: &mut bool) -> Result<crate::delaunay::Delaunay> {
    points_delaunay(&input.points, &input.tags, &input.apexes, tagged)
}

/// [`cell_delaunay`] of the first `points.len()` points of a cell (tags alongside).
fn points_delaunay(
    points: &[[f64; 3]],
    tags: &[crate::delaunay::PointTags],
    apexes: &crate::delaunay::PlaneApexes,
    tagged: &mut bool,
) -> Result<crate::delaunay::Delaunay> {
    if *tagged {
        match crate::delaunay::Delaunay::try_new_tagged_with(points, &tags[..points.len()], apexes)
        {
            Ok(dt) => return Ok(dt),
            Err(crate::Error::Input { .. }) => *tagged = false,
            Err(e) => return Err(e),
        }
    }
    crate::delaunay::Delaunay::try_new(points)
}

/// Per slot: sorted vertex triple → (the triangle oriented outward from its tet, the tet).
type SectionTriangles = IdMap<[u32; 3], ([u32; 3], u32)>;

/// Where a cell run stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stop {
    /// After the contour conformity check, whatever it found (the samples are all the caller wants).
    AtConformity,
    /// After the conformity check when contour edges are missing, else after pruning.
    AtMissingEdges,
    /// After pruning.
    Never,
}

/// Run the cell. With `check_only`, stop after the conformity check when edges are missing.
pub fn run_cell(input: CellInput, sampling: Sampling, check_only: bool) -> Result<CellResult> {
    run_cell_seeded(input, sampling, check_only, None)
}

/// [`run_cell`] inserting the shared points `seeds` on its faces (`SharedSamples::seeded`).
pub fn run_cell_seeded(
    input: CellInput,
    sampling: Sampling,
    check_only: bool,
    seeds: Option<&SharedSamples>,
) -> Result<CellResult> {
    let stop = if check_only {
        Stop::AtMissingEdges
    } else {
        Stop::Never
    };
    run_cell_with(
        input,
        sampling,
        stop,
        SAMPLE_PAIR_ROUNDS,
        seeds,
        Start::Compute,
    )
}

/// Run the cell up to its conformity check: its diagram samples (in `input`, cell-local) and the
/// contour edges missing, no classification or pruning (the cell is run again with shared samples).
pub fn run_cell_samples(input: CellInput, sampling: Sampling) -> Result<CellResult> {
    run_cell_samples_seeded(input, sampling, None)
}

/// [`run_cell_samples`] inserting the shared points `seeds` on its faces.
pub fn run_cell_samples_seeded(
    input: CellInput,
    sampling: Sampling,
    seeds: Option<&SharedSamples>,
) -> Result<CellResult> {
    // a start that holds seeds is not what a rerun repeats (the reruns insert shared points
    // after their own samples): with seeds, the reruns start anew
    let start = if seeds.is_some() {
        Start::Compute
    } else {
        Start::Keep
    };
    run_cell_with(
        input,
        sampling,
        Stop::AtConformity,
        SAMPLE_PAIR_ROUNDS,
        seeds,
        start,
    )
}

/// [`run_cell`] inserting, besides its own diagram samples, every sample of `shared` on its faces
/// (its own get their global ids from there too; see `shared_samples`); without `split_pairs`, its
/// consecutive samples that are not edges stay so (counted), and it adds no point of its own.
/// `start`: the first run's (`RunStart`), used where the contour points are still the same, and
/// handed on in the result.
pub fn run_cell_sharing(
    input: CellInput,
    sampling: Sampling,
    shared: &SharedSamples,
    split_pairs: bool,
    start: Option<Box<RunStart>>,
) -> Result<CellResult> {
    let rounds = if split_pairs { SAMPLE_PAIR_ROUNDS } else { 0 };
    let how = match &start {
        Some(st) if st.points == input.points && (sampling.branching || sampling.cutting) => {
            Start::Reuse(st)
        }
        _ => Start::Compute,
    };
    let mut r = run_cell_with(input, sampling, Stop::Never, rounds, Some(shared), how)?;
    r.start = start;
    Ok(r)
}

/// Where a run's start (`RunStart`) comes from.
#[derive(Clone, Copy)]
enum Start<'a> {
    Compute,
    /// Compute it and keep it in the result.
    Keep,
    Reuse(&'a RunStart),
}

/// [`run_cell`] with at most `pair_rounds` rounds of Steiner splits on the diagram pairs, and the
/// samples of `shared` (if any) on the cell's faces.
fn run_cell_with(
    mut input: CellInput,
    sampling: Sampling,
    stop: Stop,
    pair_rounds: usize,
    shared: Option<&SharedSamples>,
    start: Start,
) -> Result<CellResult> {
    let all = input.mask.iter().fold(!0u128, |a, &m| a & m);
    if all != 0 || input.points.len() < 4 {
        // every vertex on one plane: no volume to reconstruct in this cell, but its sections are
        // there (unattached), so that a section no cell with volume sees is still a flat zone
        return Ok(CellResult {
            faces: flat_cell_faces(&input),
            flat_only: true,
            input: Some(input),
            ..Default::default()
        });
    }
    let mut clock = Clock {
        timing: CellTiming::default(),
        last: std::time::Instant::now(),
    };
    let mut tri = match start {
        Start::Reuse(st) => Tri {
            dt: st.dt.clone_compact(),
            tagged: st.tagged,
        },
        _ => {
            let mut tagged = true;
            let dt = cell_delaunay(&input, &mut tagged)?;
            Tri { dt, tagged }
        }
    };
    // a reused start already holds the samples: its complex is built once they are all in
    let mut cx = match start {
        Start::Reuse(_) => Complex::default(),
        _ => Complex::from_delaunay(input.points.len(), &tri.dt),
    };
    clock.lap(|t| &mut t.delaunay);
    let mut sampled = Sampled::default();
    if sampling.branching || sampling.cutting {
        let how = SampleRun {
            sampling,
            pair_rounds,
            shared,
            start,
        };
        sampled = insert_diagram_samples(&mut input, &mut tri, &mut cx, &how, &mut clock)?;
    }
    let top = section_triangles(&input, &cx);
    let missing = missing_contour_edges(&input, &top);
    clock.lap(|t| &mut t.conformity);
    if stop == Stop::AtConformity || (stop == Stop::AtMissingEdges && !missing.is_empty()) {
        return Ok(CellResult {
            input: Some(input),
            start: sampled.start,
            missing,
            tets: cx.len() as u64,
            timing: clock.timing,
            untagged: !tri.tagged,
            ..Default::default()
        });
    }
    let cl = classify(&input, &cx);
    let flat_tets = cl.ty.iter().filter(|&&t| t == TetType::Flat).count() as u64;
    clock.lap(|t| &mut t.classify);
    let (alive, counts) = prune(&cx, &cl);
    clock.lap(|t| &mut t.prune);
    let (kept, fillable, external) = by_fate(&cx, &alive, &cl);
    let faces = face_sides(&input, &cx, &top, &alive);
    let (flat_area, cutting_on_flat_border) = flat_zones(&input, &faces, &sampled.cut_ids);
    clock.lap(|t| &mut t.output);
    Ok(CellResult {
        input: Some(input),
        start: sampled.start,
        missing,
        kept,
        fillable,
        external,
        faces,
        counts,
        tets: cx.len() as u64,
        flat_tets,
        branching_samples: sampled.branching,
        cutting_samples: sampled.cutting,
        sample_pairs: sampled.pairs,
        sample_steiner_points: sampled.pair_steiner,
        foreign_samples: sampled.foreign,
        pruned: true,
        sample_pairs_not_edges: sampled.pairs_not_edges.into_iter().collect(),
        sample_pair_list: sampled.pair_list,
        cutting_on_flat_border,
        flat_area,
        timing: clock.timing,
        flat_only: false,
        untagged: !tri.tagged,
    })
}

/// A cell run's CPU time per sub-phase, and when the last lap ended.
struct Clock {
    timing: CellTiming,
    last: std::time::Instant,
}

impl Clock {
    /// Add the time since the last lap to the sub-phase `phase` picks.
    fn lap(&mut self, phase: impl FnOnce(&mut CellTiming) -> &mut f64) {
        *phase(&mut self.timing) += lap(&mut self.last);
    }
}

/// Section triangles per slot: the faces of non-flat tets with all three vertices on the slot
/// (sorted key → outward face and its tet).
fn section_triangles(input: &CellInput, cx: &Complex) -> Vec<SectionTriangles> {
    let mut top: Vec<SectionTriangles> = vec![IdMap::default(); input.slots.len()];
    for (t, tv) in cx.tets.iter().enumerate() {
        // flat: one slot holds all four vertices (classify's `TetType::Flat`)
        if tv
            .iter()
            .fold(!0 as Mask, |m, &v| m & input.mask[v as usize])
            != 0
        {
            continue;
        }
        for i in 0..4 {
            let f = outward_face(tv, i);
            let m =
                input.mask[f[0] as usize] & input.mask[f[1] as usize] & input.mask[f[2] as usize];
            if m == 0 {
                continue;
            }
            let mut k = f;
            k.sort_unstable();
            for (s, on_slot) in top.iter_mut().enumerate() {
                if m >> s & 1 == 1 {
                    on_slot.entry(k).or_insert((f, t as u32));
                }
            }
        }
    }
    top
}

/// Conformity: the contour edges (global ids, sorted) that are no edge of a section triangle.
fn missing_contour_edges(input: &CellInput, top: &[SectionTriangles]) -> Vec<(u32, u32)> {
    let mut missing = Vec::new();
    for (s, slot) in input.slots.iter().enumerate() {
        let mut edges: IdSet<(u32, u32)> = IdSet::default();
        for k in top[s].keys() {
            edges.insert((k[0], k[1]));
            edges.insert((k[0], k[2]));
            edges.insert((k[1], k[2]));
        }
        for &(a, b) in slot.contour_edges() {
            if !edges.contains(&(a, b)) {
                missing.push((input.global[a as usize], input.global[b as usize]));
            }
        }
    }
    missing.sort_unstable();
    missing.dedup();
    missing
}

/// The cell's tets as kept, fillable (survived step 1) and external, flat ones left out.
type Fates = (Vec<[u32; 4]>, Vec<[u32; 4]>, Vec<[u32; 4]>);

fn by_fate(cx: &Complex, alive: &[bool], cl: &super::classify::Classified) -> Fates {
    let mut kept = Vec::new();
    let mut fillable = Vec::new();
    let mut external = Vec::new();
    for (t, tv) in cx.tets.iter().enumerate() {
        if !alive[t] {
            // a flat tet (untagged kernel) has no inside; in the triangulation it would be a
            // third and fourth tet on face triangles of its plane, and stars through it would
            // look pinched to the complex's growth and toggles
            if cl.ty[t] == TetType::Flat {
                continue;
            }
            if cl.external[t] {
                external.push(*tv);
            } else {
                fillable.push(*tv);
            }
            continue;
        }
        kept.push(*tv);
    }
    (kept, fillable, external)
}

/// Per slot, its internal section triangles, whether a kept tet stands on each, and that tet's
/// fourth vertex.
fn face_sides(
    input: &CellInput,
    cx: &Complex,
    top: &[SectionTriangles],
    alive: &[bool],
) -> Vec<FaceSide> {
    let classifier = Classifier::new(input);
    (0..input.slots.len())
        .map(|s| {
            let mut with_apex: Vec<([u32; 3], bool, u32)> = top[s]
                .values()
                .filter(|(f, _)| !classifier.triangle_external(f[0], f[1], f[2]))
                .map(|&(f, t)| {
                    let tv = cx.tets[t as usize];
                    let apex = tv.into_iter().find(|v| !f.contains(v)).unwrap_or(u32::MAX);
                    (f, alive[t as usize], apex)
                })
                .collect();
            with_apex.sort_unstable();
            FaceSide {
                face: input.slots[s].face,
                triangles: with_apex.iter().map(|&(f, a, _)| (f, a)).collect(),
                apexes: with_apex.iter().map(|w| w.2).collect(),
            }
        })
        .collect()
}

/// The paper's flat zones of this cell (their area), and how many cutting samples (`cut_ids`,
/// ascending) ended on their border.
fn flat_zones(input: &CellInput, faces: &[FaceSide], cut_ids: &[u32]) -> (f64, u64) {
    let mut flat_area = 0.0;
    let mut sides: IdMap<u32, (bool, bool)> = IdMap::default();
    for side in faces {
        for &(f, attached) in &side.triangles {
            if !attached {
                let p = f.map(|v| input.points[v as usize]);
                let w = crate::sections::cross(
                    crate::sections::sub(p[1], p[0]),
                    crate::sections::sub(p[2], p[0]),
                );
                flat_area += 0.5 * crate::sections::dot(w, w).sqrt();
            }
            for v in f {
                if cut_ids.binary_search(&v).is_ok() {
                    let e = sides.entry(v).or_default();
                    e.0 |= attached;
                    e.1 |= !attached;
                }
            }
        }
    }
    let on_border = sides.values().filter(|&&(a, f)| a && f).count() as u64;
    (flat_area, on_border)
}

/// Per slot, its section (the loops, in the slot's (u,v)) triangulated in 2D by a constrained
/// Delaunay triangulation, every triangle unattached and oriented outward from the cell: the faces
/// of a cell without volume. A slot whose loops cannot all be constraints (crossing, which
/// validated sections do not have) gets no triangles.
fn flat_cell_faces(input: &CellInput) -> Vec<FaceSide> {
    use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
    input
        .slots
        .iter()
        .map(|slot| {
            let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = Default::default();
            let mut local_of = Vec::new();
            let mut handle: IdMap<u32, spade::handles::FixedVertexHandle> = IdMap::default();
            let mut ok = true;
            for l in &slot.loops {
                for &v in l {
                    if handle.contains_key(&v) {
                        continue;
                    }
                    let q = slot.uv[v as usize];
                    match cdt.insert(Point2::new(q[0], q[1])) {
                        Ok(h) => {
                            if h.index() >= local_of.len() {
                                local_of.resize(h.index() + 1, u32::MAX);
                            }
                            // two loop vertices at one (u,v) would be merged: not a valid section
                            ok &= local_of[h.index()] == u32::MAX;
                            local_of[h.index()] = v;
                            handle.insert(v, h);
                        }
                        Err(_) => ok = false,
                    }
                }
            }
            for l in &slot.loops {
                for i in 0..l.len() {
                    let (a, b) = (handle.get(&l[i]), handle.get(&l[(i + 1) % l.len()]));
                    if let (Some(&a), Some(&b)) = (a, b) {
                        if a != b && cdt.try_add_constraint(a, b).is_empty() {
                            ok &= cdt.exists_constraint(a, b);
                        }
                    }
                }
            }
            let mut triangles = Vec::new();
            if ok {
                for f in cdt.inner_faces() {
                    let [a, b, c] = f.vertices().map(|v| v.fix().index());
                    let q = [a, b, c].map(|i| slot.uv[local_of[i] as usize]);
                    let centroid = [
                        (q[0][0] + q[1][0] + q[2][0]) / 3.0,
                        (q[0][1] + q[1][1] + q[2][1]) / 3.0,
                    ];
                    if slot.locator().locate(centroid) != super::cell_input::Where::Inside {
                        continue;
                    }
                    // counter-clockwise in (u,v) faces along the plane normal (u × v = n)
                    let t = [local_of[a], local_of[b], local_of[c]];
                    let t = if slot.outward_is_plane_normal {
                        t
                    } else {
                        [t[0], t[2], t[1]]
                    };
                    triangles.push((t, false));
                }
            }
            triangles.sort_unstable();
            FaceSide {
                face: slot.face,
                apexes: vec![u32::MAX; triangles.len()],
                triangles,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::cutting::tests::one_facing_four;

    /// Pairs of `r` that are not edges of its face's internal section triangles.
    fn pairs_off_triangles(r: &CellResult) -> Vec<(usize, u32, u32)> {
        r.sample_pair_list
            .iter()
            .filter(|&&(s, u, v)| {
                !r.faces[s]
                    .triangles
                    .iter()
                    .any(|(t, _)| t.contains(&u) && t.contains(&v))
            })
            .copied()
            .collect()
    }

    /// A rerun with shared samples that starts from the first run's triangulation and first-round
    /// samples gives what the whole run gives; a start of other points is not used.
    #[test]
    fn a_rerun_from_the_first_runs_start_is_the_whole_run() {
        let first = run_cell_samples(one_facing_four(), Sampling::default()).unwrap();
        let start = first.start.expect("a first run keeps its start");
        assert!(!start.branching.samples.is_empty());
        let shared = SharedSamples::default();
        let whole =
            run_cell_sharing(one_facing_four(), Sampling::default(), &shared, true, None).unwrap();
        let mut other = start.clone();
        other.points[0][0] += 1e-3;
        for given in [Some(start), Some(other)] {
            let r = run_cell_sharing(one_facing_four(), Sampling::default(), &shared, true, given)
                .unwrap();
            assert_eq!(r.kept, whole.kept);
            assert_eq!(r.external, whole.external);
            assert_eq!(r.branching_samples, whole.branching_samples);
            assert_eq!(
                r.input.unwrap().points,
                whole.input.as_ref().unwrap().points
            );
            assert!(r.start.is_some(), "the start is handed on");
        }
    }

    #[test]
    fn consecutive_branching_samples_are_section_edges() {
        let r = run_cell(one_facing_four(), Sampling::default(), false).unwrap();
        eprintln!(
            "branching {} cutting {} pairs {} steiner {} not edges {:?}",
            r.branching_samples,
            r.cutting_samples,
            r.sample_pairs,
            r.sample_steiner_points,
            r.sample_pairs_not_edges
        );
        assert!(r.branching_samples > 0);
        assert!(r.sample_pairs > 0);
        assert!(
            r.sample_pairs_not_edges.is_empty(),
            "{:?}",
            r.sample_pairs_not_edges
        );
        assert_eq!(
            r.sample_pair_list.len() as u64,
            r.sample_pairs + r.sample_steiner_points
        );
        let off = pairs_off_triangles(&r);
        assert!(off.is_empty(), "{off:?}");
        // every pair is on the bottom (the branching diagram of the four circles), and the chains
        // follow the cross x = 0, y = 0 between them
        let input = r.input.as_ref().unwrap();
        for &(s, u, v) in &r.sample_pair_list {
            assert_eq!(s, 0);
            for w in [u, v] {
                let p = input.points[w as usize];
                assert!(p[0].abs().min(p[1].abs()) < 0.02, "{p:?} off the cross");
            }
        }
    }

    /// On these parallel planes consecutive samples along the straight branches are Delaunay edges
    /// without splitting: the pair list is the same with and without Steiner rounds (the splitting
    /// itself is tested in `chains`).
    #[test]
    fn straight_branches_need_no_splitting() {
        let r = run_cell_with(
            one_facing_four(),
            Sampling::default(),
            Stop::Never,
            0,
            None,
            Start::Compute,
        )
        .unwrap();
        assert!(r.sample_pairs > 0);
        assert!(pairs_off_triangles(&r).is_empty());
        assert!(r.sample_pairs_not_edges.is_empty());
    }
}
