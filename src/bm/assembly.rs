//! The solid as one tetrahedral complex K: the kept tetrahedra of every cell in global vertex ids,
//! and its surface ∂K, the triangles with exactly one kept side, oriented outward.
//!
//! When the two cells of every face triangulate it alike (tagged kernel + shared diagram samples:
//! `nonconforming_faces == 0`), K is a conforming tetrahedralization and ∂K is closed and embedded
//! by construction: a section triangle kept from both sides is interior, from one side is surface,
//! from neither is a flat zone (not in ∂K, counted with its area). What ∂K can still have are
//! singularities (an edge with four surface triangles, a vertex whose surface link is several
//! cycles, paper Fig. 12a): they are resolved inside K (`fill`, `singular`, `manifold`), and
//! what is left is counted (`docs/design/conforming-complex.md`).
//!
//! Over 800 lines only with its unit tests (the test modules at the end); the code is shorter.
use super::cell::CellResult;
use super::manifold::ToggleStats;
use super::refine::{Planes, Triangulation};
use super::singular::{EdgeGaps, Reach, SingularStats, Snapshot};
use super::slab::{FaceTri, Side};
use crate::arrangement::Arrangement;
use crate::arrangement::VertexPool;
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::mesh::{TetMesh, TriMesh};

/// K and what its boundary looks like.
#[derive(Clone, Debug, Default)]
pub struct Assembled {
    pub surface: TriMesh,
    pub tets: TetMesh,
    /// Per vertex of `tets`, the arrangement planes it lies on (by tags): what a later stage that
    /// splits the complex on the planes (`partition`) reads.
    pub planes: Vec<super::refine::Planes>,
    /// Per vertex of `tets`, the point on a plane whose image in the collar it is (`u32::MAX`:
    /// none): such a point stands for its base where labels are read off the planes.
    pub lifted_from: Vec<u32>,
    /// Faces with two cells whose section triangulations differ (K is then not conforming there).
    pub nonconforming_faces: u64,
    /// Section triangles that no kept tetrahedron stands on, on faces with a cell on each side or
    /// on a cap (the paper's flat zones): left out of ∂K.
    pub flat_triangles: u64,
    pub flat_area: f64,
    /// Edges of ∂K with more than two surface triangles.
    pub singular_edges: u64,
    /// Vertices of ∂K whose surface triangles form more than one fan (pinched), counted once each.
    pub singular_vertices: u64,
    /// Singular edges and vertices before filling, and the tetrahedra filling added.
    pub singular_edges_found: u64,
    pub singular_vertices_found: u64,
    pub tets_filled: u64,
    /// Flat zones given slabs of tetrahedra (`slab`).
    pub slabs: super::slab::SlabStats,
    /// Gaps at singularities grown into (`singular`).
    pub grown: super::singular::SingularStats,
    /// Whether that growth split edges at a fraction of their length (`NEEDLE_FRACTION`): growth
    /// near the simplices left double sheets, this fewer.
    pub growth_by_fraction: bool,
    /// Whole tetrahedra toggled to lower the number of singularities (`manifold`).
    pub toggled: super::manifold::ToggleStats,
    /// Flat tetrahedra toggled so that ∂K does not fold flat there.
    pub folds_closed: super::manifold::ToggleStats,
    /// Enclosed voids that no section witnesses, taken into K (`voids`).
    pub voids: super::voids::VoidStats,
    /// Pinched vertices left by growth and toggles whose smaller cones lost their tips (`carve`).
    pub carved: super::carve::CarveStats,
    /// Slivers on the outer boundary of the cells' triangulations, taken out (`refine`).
    pub hull_slivers: u64,
    /// Handles no section witnesses, closed by membranes of step-1 survivors (`tunnels`).
    pub tunnels: super::tunnels::TunnelStats,
    /// Handles no section witnesses, cut by layers of kept tetrahedra (`cuts`).
    pub cuts: super::tunnels::TunnelStats,
    /// The prisms over the sections near every plane (`collar`).
    pub collar: super::collar::CollarStats,
    /// What `--smooth` did (all zero without it).
    pub smooth: super::smooth::SmoothStats,
    /// Singular simplices on no plane that the collar left (or that were there where it was
    /// refused), carved after it (`carve::carve_off_planes`).
    pub carved_off_planes: super::carve::CarveStats,
    /// Wall-clock seconds of each stage of the assembly, in order.
    pub stage_seconds: Vec<(&'static str, f64)>,
    /// The process's peak resident memory (MiB) when each stage ended, where the platform
    /// tells: which stage raised it.
    pub stage_peak_memory_mib: Vec<(&'static str, f64)>,
}

/// Wall-clock time of consecutive stages: `lap(name)` ends the stage running since the last lap.
struct Laps {
    last: std::time::Instant,
    laps: Vec<(&'static str, f64)>,
    peaks: Vec<(&'static str, f64)>,
}

impl Laps {
    fn start() -> Self {
        Laps {
            last: std::time::Instant::now(),
            laps: Vec::new(),
            peaks: Vec::new(),
        }
    }

    /// Ends stage `name`; its seconds.
    fn lap(&mut self, name: &'static str) -> f64 {
        let now = std::time::Instant::now();
        let seconds = (now - self.last).as_secs_f64();
        self.laps.push((name, seconds));
        if let Some(peak) = crate::memory::peak_resident() {
            self.peaks.push((name, peak.mib()));
        }
        self.last = now;
        seconds
    }
}

/// Thickness of a flat zone's slab, relative to the bounding-box diagonal (less where the apex
/// of its tetrahedron is nearer: half its height).
pub const SLAB_THICKNESS: f64 = 1e-3;

/// How far from a pinched vertex a carved cone ends, relative to the bounding-box diagonal (at
/// most a quarter of each edge): the growth's distance, far below the sampling of real sections.
pub const CARVE_DISTANCE: f64 = 1e-3;

/// Global ids per cell: pool ids, and fresh ids (appended to `positions`) for cell-local vertices.
pub(super) fn global_maps(
    results: &[Option<CellResult>],
    positions: &mut Vec<[f64; 3]>,
) -> Vec<Vec<u32>> {
    results
        .iter()
        .map(|r| match r.as_ref().and_then(|r| r.input.as_ref()) {
            Some(inp) => inp
                .global
                .iter()
                .enumerate()
                .map(|(l, &g)| {
                    if g == u32::MAX {
                        positions.push(inp.points[l]);
                        (positions.len() - 1) as u32
                    } else {
                        g
                    }
                })
                .collect(),
            None => Vec::new(),
        })
        .collect()
}

/// Most rounds of growing into gaps at singularities, and how far from them (relative to the
/// bounding-box diagonal; at most halfway along an edge).
const GROW_ROUNDS: usize = 8;
pub const SINGULAR_GROWTH: f64 = 1e-3;

/// Points that settling a tunnel's membrane adds keep at least this distance (relative to the
/// diagonal) from the other vertices of their tetrahedra: twice what the shared files' tests
/// demand of any constructed point, above the closest input contour vertices' 7.6e-8.
const TUNNEL_MIN_GAP: f64 = 1e-7;

/// Tetrahedra flatter than this (relative to the diagonal) fold ∂K flat where three or four of
/// their faces are on it (`manifold::close_flat_folds`): 10× the tolerance at which `check`
/// calls two triangles a double sheet.
pub const FLAT_FOLD: f64 = 1e-8;

/// Most rounds of filling (each may expose new singularities at the filled tets).
const FILL_ROUNDS: usize = 8;

fn sorted3(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

/// Assemble K from the cells' kept tetrahedra (positively oriented, `robust::orient3d > 0`); with
/// `slabs`, flat zones get slabs of tetrahedra; with `fill_voids`, enclosed voids that no section
/// witnesses are filled (before singularities are resolved, and again after growth); with
/// `collar` > 0 (relative to the diagonal), the solid near every plane is the prism over its
/// section (`collar`); with `smooth`, ∂K is refined and faired between the planes first
/// (`smooth`).
pub fn assemble(
    arr: &Arrangement,
    pool: &VertexPool,
    results: &[Option<CellResult>],
    slabs: bool,
    fill_voids: bool,
    collar: f64,
    smooth: Option<super::smooth::Smoothing>,
) -> Assembled {
    let mut laps = Laps::start();
    let mut positions = pool.positions.clone();
    let maps = global_maps(results, &mut positions);
    let mut out = Assembled::default();
    // sized once: grown cell by cell, the lists were copied over and over
    let total = |f: fn(&CellResult) -> usize| results.iter().flatten().map(f).sum::<usize>();
    let mut tets: Vec<[u32; 4]> = Vec::with_capacity(total(|r| r.kept.len()));
    let mut fillable: Vec<[u32; 4]> = Vec::with_capacity(total(|r| r.fillable.len()));
    let mut external: Vec<[u32; 4]> = Vec::with_capacity(total(|r| r.external.len()));
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r else { continue };
        let m = &maps[c];
        let global = |t: &[u32; 4]| t.map(|v| m[v as usize]);
        tets.extend(r.kept.iter().map(global));
        fillable.extend(r.fillable.iter().map(global));
        external.extend(r.external.iter().map(global));
    }
    let faces = face_sides(arr, results, &maps, &mut positions);
    count_faces(&faces, &positions, &mut out);
    let mut internal: FxHashSet<[u32; 3]> = faces
        .iter()
        .flatten()
        .flat_map(|s| &s.tris)
        .map(|t| sorted3(t.tri))
        .collect();
    let mut planes = global_planes(pool, results, &maps, positions.len());
    let mut k = Triangulation {
        positions: &mut positions,
        planes: &mut planes,
        kept: &mut tets,
        fillable: &mut fillable,
        external: &mut external,
        internal: &mut internal,
    };
    let diag = diagonal(&pool.positions);
    laps.lap("join");
    out.hull_slivers = super::refine::drop_hull_slivers(&mut k);
    laps.lap("hull_slivers");
    if slabs && out.flat_triangles > 0 {
        out.slabs = super::slab::thicken(&mut k, &faces, SLAB_THICKNESS * diag);
    }
    laps.lap("slabs");
    if fill_voids {
        out.voids = super::voids::fill(&mut k);
    }
    laps.lap("voids");
    let nonconforming = nonconforming_vertices(&faces);
    resolve_singularities(&mut k, &nonconforming, diag, fill_voids, &mut out);
    laps.lap("singularities");
    if fill_voids {
        let on_hole = hole_vertices(results, &maps, k.positions.len());
        let settle = super::tunnels::Settle {
            growth_rounds: GROW_ROUNDS,
            growth_distance: SINGULAR_GROWTH * diag,
            min_gap: TUNNEL_MIN_GAP * diag,
            near_coplanar: crate::eval::near_coplanar::NEAR_COPLANAR_RELATIVE_TOLERANCE * diag,
        };
        let found;
        (out.tunnels, found) = super::tunnels::close(&mut k, &on_hole, settle);
        out.cuts = super::cuts::cut(&mut k, settle, found);
    }
    laps.lap("tunnels");
    if let Some(how) = smooth {
        out.smooth = super::smooth::smooth(&mut k, &arr.planes, how, diag);
        out.smooth.max_shift /= diag;
        laps.lap("smooth");
    }
    let mut collared = None;
    let n_before_collar = k.positions.len();
    let mut lifted = Vec::new();
    if collar > 0.0 {
        let max_shift = super::collar::MAX_SHIFT_PER_HEIGHT * collar * diag;
        let (stats, b) = super::collar::build(&mut k, &arr.planes, collar * diag, max_shift);
        out.collar = stats;
        if let Some(c) = b {
            collared = Some((c.boundary, c.singular));
            lifted = c.lifted_from;
        }
        out.collar.min_height /= diag;
        out.collar.max_shift /= diag;
    }
    // ∂K and its singular simplices, each found once (the collar found them for its result)
    let (mut boundary, mut singular) = collared.unwrap_or_else(|| {
        let b = boundary_of(k.kept);
        let s = super::fill::singular_simplices(&b);
        (b, s)
    });
    if collar > 0.0 {
        let distance = CARVE_DISTANCE * diag;
        out.carved_off_planes =
            super::carve::carve_off_planes(&mut k, singular.clone(), &nonconforming, distance);
        if out.carved_off_planes.vertices > 0 {
            boundary = boundary_of(k.kept);
            singular = super::fill::singular_simplices(&boundary);
        }
    }
    let seconds = laps.lap("collar");
    if collar > 0.0 {
        out.collar.seconds = seconds;
    }
    out.singular_edges = singular.0.len() as u64;
    out.singular_vertices = singular.1.len() as u64;
    out.surface = TriMesh::with_used_vertices(&positions, &boundary);
    // TetMesh wants positive volume (orient3d < 0): swap two vertices
    out.tets = TetMesh {
        vertices: positions,
        tets: tets.iter().map(|t| [t[0], t[1], t[3], t[2]]).collect(),
    };
    planes.resize(out.tets.vertices.len(), super::refine::Planes::new());
    out.planes = planes;
    out.lifted_from = vec![u32::MAX; n_before_collar];
    out.lifted_from.extend(lifted);
    out.lifted_from.resize(out.tets.vertices.len(), u32::MAX);
    laps.lap("surface");
    out.stage_seconds = laps.laps;
    out.stage_peak_memory_mib = laps.peaks;
    out
}

/// Per global vertex: whether it lies on a hole of a section (a loop of a face's section whose
/// orientation is opposite to the face's largest loop, which is an outer boundary).
fn hole_vertices(results: &[Option<CellResult>], maps: &[Vec<u32>], n: usize) -> Vec<bool> {
    let mut on_hole = vec![false; n];
    for (c, r) in results.iter().enumerate() {
        let Some(input) = r.as_ref().and_then(|r| r.input.as_ref()) else {
            continue;
        };
        for slot in &input.slots {
            // the loops' areas in (u,v), computed when the run's input was slimmed
            let areas = &slot.loop_areas;
            let Some(outer) = areas
                .iter()
                .copied()
                .max_by(|a, b| a.abs().total_cmp(&b.abs()))
            else {
                continue;
            };
            for (l, a) in slot.loops.iter().zip(areas) {
                if a * outer < 0.0 {
                    for &v in l {
                        on_hole[maps[c][v as usize] as usize] = true;
                    }
                }
            }
        }
    }
    on_hole
}

/// Singular edges and pinched vertices of ∂K: filled with whole step-1 survivors where a gap of
/// them closes one (`fill`), then grown into near them (`singular`), then the pinches left carved
/// (`carve`), the voids that opened filled and the flat folds closed (`settle`).
fn resolve_singularities(
    k: &mut Triangulation,
    nonconforming: &FxHashSet<u32>,
    diag: f64,
    fill_voids: bool,
    out: &mut Assembled,
) {
    let filled = super::fill::fill_and_drop(k.kept, k.fillable, FILL_ROUNDS);
    out.tets_filled = filled.added;
    out.singular_edges_found = filled.found.0.len() as u64;
    out.singular_vertices_found = filled.found.1.len() as u64;
    let max_toggles = 4 * k.kept.len() + 1000;
    let (toggled, sets) =
        super::manifold::resolve(k, nonconforming, max_toggles, Some(filled.left));
    out.toggled = toggled;
    let start = Snapshot::of(k);
    let first_grown = k.positions.len();
    let near = Reach::near(SINGULAR_GROWTH * diag);
    let limits = Limits {
        max_toggles,
        carve_distance: CARVE_DISTANCE * diag,
        flat_fold: FLAT_FOLD * diag,
        fill_voids,
    };
    let mut kept = settle(k, &start, sets.clone(), nonconforming, near, limits);
    // growth near the simplices only, repeated round after round along long edges, can leave
    // needles whose faces lie on each other; grown again from the same K with the edges split
    // at a fraction of their length, the one that leaves fewer singular simplices after carving
    // and the flat folds' toggles, then fewer double sheets, stays
    let sheets = double_sheets(k, first_grown);
    if sheets > 0 {
        let left = singular_count(k);
        let after_near = Snapshot::of_since(k, &start);
        start.clone().restore(k);
        let spread = Reach {
            fraction: NEEDLE_FRACTION,
            ..near
        };
        let by_fraction = settle(k, &start, sets, nonconforming, spread, limits);
        if (singular_count(k), double_sheets(k, first_grown)) < (left, sheets) {
            kept = by_fraction;
            out.growth_by_fraction = true;
        } else {
            after_near.restore(k);
        }
    }
    out.grown = kept.resolved.grown;
    out.toggled.add(&kept.resolved.toggled);
    out.carved = kept.carved;
    out.voids.voids_filled += kept.voids.voids_filled;
    out.voids.tets_filled += kept.voids.tets_filled;
    out.folds_closed = kept.folds;
}

/// How far `settle` may go: toggles of the singular simplices, how far carving reaches, how flat a
/// fold's tetrahedra are, and whether enclosed voids are filled.
#[derive(Clone, Copy)]
struct Limits {
    max_toggles: usize,
    carve_distance: f64,
    flat_fold: f64,
    fill_voids: bool,
}

/// What `settle` did.
struct Settled {
    resolved: Resolved,
    carved: super::carve::CarveStats,
    voids: super::voids::VoidStats,
    folds: super::manifold::ToggleStats,
}

/// [`grow_all_ways`] from `start` (the state K is in), then the pinches left carved (`carve`),
/// the voids that opened filled, and the flat folds closed (`manifold::close_flat_folds`).
fn settle(
    k: &mut Triangulation,
    start: &Snapshot,
    sets: Sets,
    nonconforming: &FxHashSet<u32>,
    reach: Reach,
    limits: Limits,
) -> Settled {
    let resolved = grow_all_ways(k, start, sets, nonconforming, reach, limits.max_toggles);
    let carved = super::carve::carve_pinches(
        k,
        resolved.left.clone(),
        nonconforming,
        limits.carve_distance,
    );
    let voids = if limits.fill_voids {
        super::voids::fill(k)
    } else {
        Default::default()
    };
    let folds = super::manifold::close_flat_folds(k, nonconforming, limits.flat_fold);
    Settled {
        resolved,
        carved,
        voids,
        folds,
    }
}

/// Singular edges and pinched vertices of ∂K.
fn singular_count(k: &Triangulation) -> usize {
    let (edges, vertices) = singular_sets(k.kept);
    edges.len() + vertices.len()
}

/// Fraction of an edge at which growth splits it when growing near the simplices left double
/// sheets (`singular::Reach`). Measured always on (not as a second try) on the generated odd
/// inputs (seeds 0..120 and the shared odd files), clean of 118: 0.1 → 102, 0.2 → 106, 0.3 → 106
/// (0: 101); as the second try, 0.2 gives 104.
const NEEDLE_FRACTION: f64 = 0.2;

/// Overlapping near-coplanar pairs and crossings among the triangles of ∂K at a point from
/// `first` on (growth's points: where its needles are), as `check` counts them on those
/// triangles alone (its tolerance relative to their box, not the model's: stricter; the handle
/// stage asks the same search for its pairs at the model's tolerance,
/// `eval::check::overlapping_near_coplanar_pairs`).
fn double_sheets(k: &Triangulation, first: usize) -> usize {
    let tris = boundary_near(k.kept, |v| v as usize >= first);
    if tris.is_empty() {
        return 0;
    }
    let mesh = crate::mesh::TriMesh::with_used_vertices(k.positions, &tris);
    let found = crate::eval::check::self_intersections(&mesh);
    found.overlapping_coplanar + found.count
}

/// Growth at the singular simplices `sets`, split at `reach`, then the toggles: near the edges
/// first and by whole tetrahedra first, the better of the two, then where some are left the
/// saddle bridges. `start` is the state K is in (the caller's copy: K is copied once, not once
/// per level).
fn grow_all_ways(
    k: &mut Triangulation,
    start: &Snapshot,
    sets: Sets,
    nonconforming: &FxHashSet<u32>,
    reach: Reach,
    max_toggles: usize,
) -> Resolved {
    // Growth at edges near them only (nothing far from them changes, but it can be refused
    // where a whole gap would fit) or by whole gap tetrahedra (which can pinch K far from the
    // edge): neither is better on every input, so both orders run from the same K, each followed
    // by the toggles, and the one leaving fewer singular simplices (ties: fewer points) stays.
    let near_first = grow_then_toggle(
        k,
        [EdgeGaps::NearEdge, EdgeGaps::Whole],
        sets.clone(),
        nonconforming,
        reach,
        max_toggles,
    );
    let kept = if near_first.is_clean() {
        near_first
    } else {
        let after_near = Snapshot::of_since(k, start);
        start.clone().restore(k);
        let whole_first = grow_then_toggle(
            k,
            [EdgeGaps::Whole, EdgeGaps::NearEdge],
            sets,
            nonconforming,
            reach,
            max_toggles,
        );
        if near_first.rank() < whole_first.rank() {
            after_near.restore(k);
            near_first
        } else {
            whole_first
        }
    };
    // where some are left, the saddle bridges (growth that keeps off the planes) from there
    if kept.is_clean() {
        return kept;
    }
    let before = Snapshot::of(k);
    let off_plane = grow_then_toggle(
        k,
        [EdgeGaps::OffPlane, EdgeGaps::NearEdge],
        kept.left.clone(),
        nonconforming,
        reach,
        max_toggles,
    );
    if off_plane.count() < kept.count() {
        kept.then(off_plane)
    } else {
        before.restore(k);
        kept
    }
}

/// What a pass of growth and toggles did, and the singular simplices it left.
struct Resolved {
    grown: SingularStats,
    toggled: ToggleStats,
    left: Sets,
}

impl Resolved {
    fn count(&self) -> u64 {
        (self.left.0.len() + self.left.1.len()) as u64
    }

    fn is_clean(&self) -> bool {
        self.count() == 0
    }

    /// Better is lower: fewer singular simplices left, then fewer points added.
    fn rank(&self) -> (u64, u64) {
        (self.count(), self.grown.points)
    }

    /// This pass followed by `later` (which started where this one ended).
    fn then(mut self, later: Resolved) -> Resolved {
        self.grown.add(&later.grown);
        self.toggled.add(&later.toggled);
        self.left = later.left;
        self
    }
}

/// Growth at the singular simplices in the two ways of `order`, then the toggles. `sets`: the
/// singular simplices of ∂K now.
fn grow_then_toggle(
    k: &mut Triangulation,
    order: [EdgeGaps; 2],
    sets: Sets,
    nonconforming: &FxHashSet<u32>,
    reach: Reach,
    max_toggles: usize,
) -> Resolved {
    let mut grown = SingularStats::default();
    let mut known = Some(sets);
    for how in order {
        let (stats, now) = super::singular::resolve(k, GROW_ROUNDS, reach, how, known);
        grown.add(&stats);
        known = now;
    }
    let (toggled, left) = super::manifold::resolve(k, nonconforming, max_toggles, known);
    Resolved {
        grown,
        toggled,
        left,
    }
}

/// Singular edges and pinched vertices of ∂K (`fill::singular_simplices`).
pub(super) type Sets = (Vec<(u32, u32)>, Vec<u32>);

/// Per face with a section, per cell on it: its section triangles in global ids. A cell without
/// volume gets one more vertex (appended to `positions`), inside it, as the apex of its triangles.
fn face_sides(
    arr: &Arrangement,
    results: &[Option<CellResult>],
    maps: &[Vec<u32>],
    positions: &mut Vec<[f64; 3]>,
) -> Vec<Vec<Side>> {
    let mut sides: FxHashMap<u32, Vec<Side>> = FxHashMap::default();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r else { continue };
        let m = &maps[c];
        let virtual_apex = match (r.flat_only, r.input.as_ref()) {
            (true, Some(inp)) => {
                positions.push(cell_interior_point(arr, inp.cell));
                Some((positions.len() - 1) as u32)
            }
            _ => None,
        };
        let g = |v: u32| match (v, virtual_apex) {
            (u32::MAX, Some(a)) => a,
            (u32::MAX, None) => v,
            _ => m[v as usize],
        };
        for fs in &r.faces {
            let tris = fs
                .triangles
                .iter()
                .zip(&fs.apexes)
                .map(|(&(t, attached), &apex)| FaceTri {
                    tri: t.map(g),
                    attached,
                    apex: g(apex),
                })
                .collect();
            sides.entry(fs.face).or_default().push(Side {
                tris,
                has_volume: !r.flat_only,
            });
        }
    }
    let mut faces: Vec<(u32, Vec<Side>)> = sides.into_iter().collect();
    faces.sort_unstable_by_key(|f| f.0);
    faces.into_iter().map(|f| f.1).collect()
}

/// The mean of a cell's polygon vertices: strictly inside the convex cell.
fn cell_interior_point(arr: &Arrangement, cell: u32) -> [f64; 3] {
    let (mut sum, mut n) = ([0.0; 3], 0.0);
    for cf in &arr.cells[cell as usize].faces {
        for &v in &arr.faces[cf.face as usize].polygon {
            let p = arr.pool.positions[v as usize];
            for i in 0..3 {
                sum[i] += p[i];
            }
            n += 1.0;
        }
    }
    sum.map(|x| x / n)
}

/// The planes of every global vertex: a pool vertex's tags, a cell-local one's planes in its cell.
fn global_planes(
    pool: &VertexPool,
    results: &[Option<CellResult>],
    maps: &[Vec<u32>],
    n: usize,
) -> Vec<Planes> {
    let mut planes: Vec<Planes> = vec![Planes::new(); n];
    for (g, t) in pool.tags.iter().enumerate() {
        planes[g] = t.iter().copied().collect();
    }
    for (c, r) in results.iter().enumerate() {
        let Some(inp) = r.as_ref().and_then(|r| r.input.as_ref()) else {
            continue;
        };
        // slimmed inputs: the cell-local vertices' planes (a vertex that adopted a shared
        // sample's id since has the pool's)
        for (l, p) in &inp.local_planes {
            if inp.global[*l as usize] == u32::MAX {
                planes[maps[c][*l as usize] as usize] = p.iter().copied().collect();
            }
        }
    }
    planes
}

pub(crate) fn diagonal(points: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let d: f64 = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum();
    d.sqrt()
}

/// The triangles of `tets` with exactly one tetrahedron, oriented outward from it, sorted.
pub fn boundary_of(tets: &[[u32; 4]]) -> Vec<[u32; 3]> {
    let mut out = super::faces::boundary(tets);
    out.sort_unstable();
    out
}

/// The triangles of ∂K with a vertex that is `marked` (∂K of the kept tetrahedra at such
/// vertices, restricted to those triangles: the same triangles as on the whole of ∂K).
pub(super) fn boundary_near(kept: &[[u32; 4]], marked: impl Fn(u32) -> bool) -> Vec<[u32; 3]> {
    let near: Vec<[u32; 4]> = (kept.iter())
        .filter(|t| t.iter().any(|&v| marked(v)))
        .copied()
        .collect();
    super::faces::boundary(&near)
        .into_iter()
        .filter(|f| f.iter().any(|&v| marked(v)))
        .collect()
}

/// The vertices of the faces whose two cells triangulate them differently.
fn nonconforming_vertices(faces: &[Vec<Side>]) -> FxHashSet<u32> {
    let mut out = FxHashSet::default();
    for sides in faces {
        let with_volume: Vec<&Side> = sides.iter().filter(|s| s.has_volume).collect();
        if with_volume.len() == 2 && sorted_keys(with_volume[0]) != sorted_keys(with_volume[1]) {
            out.extend(with_volume.iter().flat_map(|s| &s.tris).flat_map(|t| t.tri));
        }
    }
    out
}

fn sorted_keys(side: &Side) -> Vec<[u32; 3]> {
    let mut keys: Vec<[u32; 3]> = side.tris.iter().map(|t| sorted3(t.tri)).collect();
    keys.sort_unstable();
    keys
}

/// Non-conforming faces and flat-zone triangles, from the cells' own face triangles (cells
/// without volume triangulate their faces in 2D and are not compared).
fn count_faces(faces: &[Vec<Side>], positions: &[[f64; 3]], out: &mut Assembled) {
    for sides in faces {
        let with_volume: Vec<Vec<[u32; 3]>> = sides
            .iter()
            .filter(|s| s.has_volume)
            .map(sorted_keys)
            .collect();
        if with_volume.len() == 2 && with_volume[0] != with_volume[1] {
            out.nonconforming_faces += 1;
        }
        let sides = super::slab::considered(sides);
        let attached: FxHashSet<[u32; 3]> = sides
            .iter()
            .flat_map(|s| &s.tris)
            .filter(|t| t.attached)
            .map(|t| sorted3(t.tri))
            .collect();
        // a triangle of any side that no side attaches to (by key, once), as `slab` takes them:
        // on a non-conforming face the sides' triangles differ, and the first side's alone
        // undercounted them (a warning of "8 of 7" left out)
        let mut flat: Vec<[u32; 3]> = (sides.iter().flat_map(|s| &s.tris))
            .map(|t| sorted3(t.tri))
            .filter(|k| !attached.contains(k))
            .collect();
        flat.sort_unstable();
        flat.dedup();
        for k in flat {
            out.flat_triangles += 1;
            out.flat_area += crate::geom::triangle_area(k.map(|v| positions[v as usize]));
        }
    }
}

/// The singular edges and pinched vertices of the boundary of `tets` (their order does not depend
/// on the triangles' order, so the boundary is not sorted).
pub(super) fn singular_sets(tets: &[[u32; 4]]) -> Sets {
    super::fill::singular_simplices(&super::faces::boundary(tets))
}

/// [`singular_sets`] of `tets` after a change that touched only the stars of the sorted vertices
/// `touched`, from `before` (the sets of the tetrahedra before the change): simplices through no
/// touched vertex kept their stars, so only the tetrahedra through a touched vertex are looked at.
/// Equal to `singular_sets(tets)`, in the same order.
pub(super) fn singular_sets_after(tets: &[[u32; 4]], before: Sets, touched: &[u32]) -> Sets {
    // a touched vertex may have left every tetrahedron: marks cover it too
    let n = tets
        .iter()
        .flatten()
        .chain(touched)
        .max()
        .map_or(0, |&v| v as usize + 1);
    let mut mark = vec![false; n];
    for &v in touched {
        mark[v as usize] = true;
    }
    // a vertex of `before` beyond the marks is in no tetrahedron and was not touched
    let is_touched = |v: u32| mark.get(v as usize).copied().unwrap_or(false);
    // every tetrahedron with a face through a touched vertex: the faces' kept owners all are
    let near: Vec<[u32; 4]> = tets
        .iter()
        .copied()
        .filter(|t| t.iter().any(|&v| mark[v as usize]))
        .collect();
    let tris: Vec<[u32; 3]> = super::faces::boundary(&near)
        .into_iter()
        .filter(|f| f.iter().any(|&v| mark[v as usize]))
        .collect();
    let (near_edges, near_vertices) = super::fill::singular_simplices(&tris);
    let (mut edges, mut vertices) = before;
    edges.retain(|&(a, b)| !is_touched(a) && !is_touched(b));
    edges.extend(
        near_edges
            .into_iter()
            .filter(|&(a, b)| is_touched(a) || is_touched(b)),
    );
    edges.sort_unstable();
    vertices.retain(|&v| !is_touched(v));
    vertices.extend(near_vertices.into_iter().filter(|&v| is_touched(v)));
    vertices.sort_unstable();
    (edges, vertices)
}

/// (edges with more than two triangles, vertices whose triangles form more than one fan).
pub fn singularities(tris: &[[u32; 3]]) -> (u64, u64) {
    let (edges, vertices) = super::fill::singular_simplices(tris);
    (edges.len() as u64, vertices.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_triangles_of_a_non_conforming_face_are_counted_from_both_sides() {
        // the unit square (0,1,2,3) split along one diagonal by one cell, the other by the other,
        // no kept tetrahedron on it: four flat-zone triangles for the slabs, area 2
        let side = |tris: [[u32; 3]; 2]| Side {
            tris: tris
                .iter()
                .map(|&tri| FaceTri {
                    tri,
                    attached: false,
                    apex: 4,
                })
                .collect(),
            has_volume: true,
        };
        let faces = vec![vec![
            side([[0, 1, 2], [0, 2, 3]]),
            side([[0, 3, 1], [1, 3, 2]]),
        ]];
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let mut out = Assembled::default();
        count_faces(&faces, &positions, &mut out);
        assert_eq!((out.nonconforming_faces, out.flat_triangles), (1, 4));
        assert!((out.flat_area - 2.0).abs() < 1e-12);
    }

    #[test]
    fn two_tets_share_an_interior_face() {
        // two positive tets on either side of the triangle (0,1,2): 6 boundary triangles
        let tets = vec![[0, 1, 2, 3], [0, 2, 1, 4]];
        let b = boundary_of(&tets);
        assert_eq!(b.len(), 6);
        assert!(!b.iter().any(|t| sorted3(*t) == [0, 1, 2]));
        assert_eq!(singularities(&b), (0, 0));
    }

    #[test]
    fn tets_meeting_at_an_edge_or_a_vertex_are_singular() {
        // two tets sharing only the edge (0,1): that edge has four surface triangles
        let edge = boundary_of(&[[0, 1, 2, 3], [0, 1, 4, 5]]);
        assert_eq!(singularities(&edge).0, 1);
        // sharing only vertex 0: one pinched vertex, no singular edge
        let vertex = boundary_of(&[[0, 1, 2, 3], [0, 4, 5, 6]]);
        assert_eq!(singularities(&vertex), (0, 1));
    }

    /// The Kuhn triangulation of an n×n×n grid of cubes (six tetrahedra per cube, conforming).
    fn kuhn_grid(n: u32) -> Vec<[u32; 4]> {
        let id = |x: u32, y: u32, z: u32| (x * (n + 1) + y) * (n + 1) + z;
        let mut out = Vec::new();
        for (x, y, z) in
            (0..n).flat_map(|x| (0..n).flat_map(move |y| (0..n).map(move |z| (x, y, z))))
        {
            for axes in [
                [0, 1, 2],
                [0, 2, 1],
                [1, 0, 2],
                [1, 2, 0],
                [2, 0, 1],
                [2, 1, 0],
            ] {
                // the path from the cube's low corner to its high one, one axis at a time
                let mut c = [x, y, z];
                let mut t = [id(x, y, z); 4];
                for (i, &a) in axes.iter().enumerate() {
                    c[a] += 1;
                    t[i + 1] = id(c[0], c[1], c[2]);
                }
                out.push(t);
            }
        }
        out
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// The sets updated from the touched vertices are the sets computed from scratch: random
        /// subsets of a grid's tetrahedra (singular everywhere), then random tetrahedra toggled.
        #[test]
        fn singular_sets_after_a_change_equal_the_sets_from_scratch(
            kept in proptest::collection::vec(proptest::bool::weighted(0.6), 6 * 27),
            toggles in proptest::collection::vec(0usize..6 * 27, 1..12),
        ) {
            let grid = kuhn_grid(3);
            let mut flags = kept;
            let list = |flags: &[bool]| -> Vec<[u32; 4]> {
                grid.iter().zip(flags).filter(|(_, &k)| k).map(|(t, _)| *t).collect()
            };
            let before = singular_sets(&list(&flags));
            let mut touched = Vec::new();
            for &t in &toggles {
                flags[t] ^= true;
                touched.extend(grid[t]);
            }
            touched.sort_unstable();
            touched.dedup();
            let after = list(&flags);
            proptest::prop_assert_eq!(singular_sets_after(&after, before, &touched), singular_sets(&after));
        }
    }
}
