//! Boissonnat–Memari reconstruction: per arrangement cell, Delaunay of contour vertices and branching
//! samples, pruned in three steps; the kept tetrahedra of all cells are one conforming complex whose
//! boundary is the solid's surface.
//!
//! Flow: face boundary loops (global pool ids) → rounds of { every dirty cell in parallel (rayon):
//! Delaunay (our kernel, tagged construction: `cell::cell_delaunay`), branching samples
//! (`branching`), conformity check } with global Steiner splits (`conform`) until every contour edge
//! is an edge of every cell's section triangulation → the cells' diagram samples become pool
//! vertices and every cell runs once more with the samples of both sides of its faces
//! (`shared_samples`), so both triangulate each face alike (a pair the other side's points took
//! away is joined through them, `chains::route_pairs`) → per cell classify (`classify`, by plane
//! tags) + prune (`prune`, steps 1–3) → `assembly`: the kept tetrahedra as one complex; flat zones
//! get slabs of tetrahedra (`slab`), singular edges and pinched vertices are filled (`fill`), grown
//! into (`refine`, `singular`) or toggled away (`manifold`), enclosed voids no section witnesses
//! are filled (`voids`) and handles none witnesses closed by membranes of tetrahedra (`tunnels`)
//! or cut where no section is (`cuts`), never by moving a vertex.
//!
//! Decisions (see each module's doc): flat tets (four vertices on one plane by tags) are left out in
//! the cells; tet types by the tag rule in `classify`; step 3 uses the paper's face-count rule plus
//! filling of enclosed voids; branching samples are placed on the Moebius diagram where the Delaunay
//! apex map is discontinuous. Cutting-diagram samples (`cutting`) are added beside the branching
//! samples where a site's Moebius cell on a face is disconnected next to a connected one (the
//! borders of flat zones). Consecutive branching or cutting samples (chains along the diagram,
//! `chains`) are made Delaunay edges of the cell by Steiner points on the diagram (counts
//! `sample_pairs`, `sample_steiner_points`, `sample_pairs_not_edges`, the last warned per cell and
//! face).
//!
//! Known limits: what the resolution inside the complex leaves (singular simplices, flat-zone
//! triangles without a slab, faces two cells triangulate differently where a cell fell back to the
//! untagged kernel) is counted and warned. `Options::delaunay` switches branching and cutting
//! samples, flat-zone slabs and sample sharing off, to study what each contributes. No part of the
//! engine reads environment variables: every switch is a typed option.
pub mod assembly;
pub mod branching;
pub mod carve;
pub mod cell;
pub mod cell_input;
pub mod chains;
pub mod classify;
pub mod collar;
pub mod complex;
pub mod conform;
pub mod cuts;
pub mod cutting;
pub mod edges;
pub(crate) mod faces;
pub mod fill;
pub mod guard;
pub mod manifold;
pub mod partition;
pub mod prune;
pub mod refine;
pub mod shared_samples;
pub mod singular;
pub mod slab;
pub mod smooth;
pub mod spacing;
pub mod tunnels;
pub mod voids;

use crate::arrangement::Arrangement;
use crate::error::Result;
use crate::sections::Sections;
use crate::solid::{Options, Report, Solid};
use cell::{CellResult, CellTiming, Sampling};
use cell_input::CellInput;
use rayon::prelude::*;

/// Seeds closer than this to their face's polygon or section boundary (relative to the
/// bounding-box diagonal) are left out (`SharedSamples::seeded`).
const SEED_MARGIN: f64 = 1e-7;

/// Most global conformity rounds before giving up (warned).
const MAX_ROUNDS: usize = 12;

/// `cells` ordered by decreasing number of section vertices on their faces, so that the threads,
/// taking cells in this order (`par_bridge`), start the longest ones first and finish together.
fn biggest_first(
    arr: &Arrangement,
    loops: &[Vec<Vec<u32>>],
    cells: impl Iterator<Item = usize>,
) -> Vec<usize> {
    let mut w: Vec<(usize, usize)> = cells
        .map(|c| {
            let n = arr.cells[c]
                .faces
                .iter()
                .map(|cf| loops[cf.face as usize].iter().map(Vec::len).sum::<usize>())
                .sum();
            (n, c)
        })
        .collect();
    w.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    w.into_iter().map(|(_, c)| c).collect()
}

/// Gather cell `c`'s input and run it, the input gathering timed into the result.
#[allow(clippy::too_many_arguments)]
fn run_timed(
    arr: &Arrangement,
    pool: &crate::arrangement::VertexPool,
    loops: &[Vec<Vec<u32>>],
    c: u32,
    sampling: Sampling,
    check_only: bool,
    samples_only: bool,
    seeds: Option<&shared_samples::SharedSamples>,
) -> Result<Option<CellResult>> {
    let t = std::time::Instant::now();
    let Some(input) = CellInput::build(arr, pool, loops, c) else {
        return Ok(None);
    };
    let build = t.elapsed().as_secs_f64();
    let mut r = if samples_only {
        cell::run_cell_samples_seeded(input, sampling, seeds)?
    } else {
        cell::run_cell_seeded(input, sampling, check_only, seeds)?
    };
    r.timing.input += build;
    // what only the run itself reads goes (a rerun with shared samples builds its input anew)
    if let Some(input) = r.input.as_mut() {
        input.slim();
    }
    Ok(Some(r))
}

/// The cells after global conformity splitting: what `assembly` joins into one complex.
pub struct CellRuns {
    /// The arrangement's vertex pool with the conformity Steiner points added.
    pub pool: crate::arrangement::VertexPool,
    /// Per cell, its result (`None`: a cell with no section on its faces).
    pub results: Vec<Option<CellResult>>,
    pub rounds: usize,
    /// Every contour edge became an edge of every cell's section triangulation.
    pub conforming: bool,
    pub steiner_points: usize,
    pub cell_runs: u64,
    pub timing: CellTiming,
    pub seconds: f64,
    pub shared: SharingCounts,
}

/// Run every cell (in parallel), splitting contour edges globally until every cell's section
/// triangulations have them as edges (or `MAX_ROUNDS` ran out: `conforming` is false).
pub fn run_cells(arrangement: &Arrangement, options: &Options) -> Result<CellRuns> {
    run_cells_seeded(arrangement, options, &[]).map(|(runs, _)| runs)
}

/// [`run_cells`] with shared points given on the planes (`SharedSamples::seeded`: a plane and a
/// point on it); with the runs, how many of them were placed on a face. Seeds need shared samples
/// (`DelaunayOptions::shared_samples` with some sampling on); without, none is placed.
pub fn run_cells_seeded(
    arrangement: &Arrangement,
    options: &Options,
    seed_points: &[(u32, [f64; 3])],
) -> Result<(CellRuns, u64)> {
    let arr = arrangement;
    let mut pool = arr.pool.clone();
    let mut splits = conform::Splits::default();
    let n_cells = arr.cells.len();
    let mut results: Vec<Option<CellResult>> = vec![None; n_cells];
    let mut dirty: Vec<bool> = vec![true; n_cells];
    let mut prev_loops: Vec<usize> = vec![usize::MAX; arr.faces.len()];
    let sampling = Sampling {
        branching: options.delaunay.branching,
        cutting: options.delaunay.cutting,
    };
    // with shared samples the cells run again with both sides' samples: the first runs need only
    // their samples and contour conformity, not classification and pruning
    let sharing = options.delaunay.shared_samples && (sampling.branching || sampling.cutting);
    let (seeds, placed) = if sharing && !seed_points.is_empty() {
        let margin = SEED_MARGIN * assembly::diagonal(&pool.positions);
        shared_samples::SharedSamples::seeded(arr, &mut pool, seed_points, margin)
    } else {
        (shared_samples::SharedSamples::default(), 0)
    };
    let seeded = (placed > 0).then_some(&seeds);
    let progress = options.progress.then(|| cell_progress(n_cells));
    let t0 = std::time::Instant::now();
    let mut rounds = 0;
    let mut conforming = false;
    let mut timing = CellTiming::default();
    let mut cell_runs = 0u64;
    while rounds < MAX_ROUNDS {
        rounds += 1;
        let loops = conform::face_loops(arr, &splits);
        mark_dirty(arr, &loops, &mut prev_loops, &mut dirty);
        let todo = biggest_first(arr, &loops, (0..n_cells).filter(|&c| dirty[c]));
        if let Some(pb) = &progress {
            pb.set_message(format!("round {rounds}"));
            pb.set_length(todo.len() as u64);
            pb.set_position(0);
        }
        let mut out: Vec<(usize, Result<Option<CellResult>>)> = todo
            .iter()
            .par_bridge()
            .map(|&c| {
                let r = run_timed(
                    arr, &pool, &loops, c as u32, sampling, true, sharing, seeded,
                );
                if let Some(pb) = &progress {
                    pb.inc(1);
                }
                (c, r)
            })
            .collect();
        out.sort_unstable_by_key(|o| o.0);
        let mut missing = Vec::new();
        for (c, r) in out {
            let r = r?;
            dirty[c] = false;
            cell_runs += 1;
            if let Some(r) = &r {
                timing.add(&r.timing);
                missing.extend(r.missing.iter().copied());
            }
            results[c] = r;
        }
        if missing.is_empty() {
            conforming = true;
            break;
        }
        missing.sort_unstable();
        missing.dedup();
        for (a, b) in missing {
            splits.split(&mut pool, a, b);
        }
    }
    // Cells stopped at the conformity check (only possible when rounds ran out) are finished now.
    if !conforming {
        let loops = conform::face_loops(arr, &splits);
        let redo = biggest_first(
            arr,
            &loops,
            (0..n_cells).filter(|&c| results[c].as_ref().is_some_and(|r| !r.missing.is_empty())),
        );
        let mut out: Vec<(usize, Result<Option<CellResult>>)> = redo
            .iter()
            .par_bridge()
            .map(|&c| {
                let r = run_timed(
                    arr, &pool, &loops, c as u32, sampling, false, sharing, seeded,
                );
                (c, r)
            })
            .collect();
        out.sort_unstable_by_key(|o| o.0);
        for (c, r) in out {
            let r = r?;
            cell_runs += 1;
            if let Some(r) = &r {
                timing.add(&r.timing);
            }
            results[c] = r;
        }
    }
    let shared = if options.delaunay.shared_samples && (sampling.branching || sampling.cutting) {
        share_samples(
            arr,
            &mut pool,
            &mut splits,
            sampling,
            &mut results,
            &mut timing,
            seeds,
        )?
    } else {
        SharingCounts::default()
    };
    if let Some(pb) = &progress {
        pb.finish_and_clear();
    }
    Ok((
        CellRuns {
            pool,
            results,
            rounds,
            conforming,
            steiner_points: splits.mid.len(),
            cell_runs,
            timing,
            seconds: t0.elapsed().as_secs_f64(),
            shared,
        },
        placed,
    ))
}

/// The progress bar of the cell runs.
fn cell_progress(n_cells: usize) -> indicatif::ProgressBar {
    let pb = indicatif::ProgressBar::new(n_cells as u64);
    pb.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} cells")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    pb
}

/// A cell is dirty when one of its faces' loops changed since the last round (`prev_loops`: the
/// number of loop vertices per face then, updated here).
fn mark_dirty(
    arr: &Arrangement,
    loops: &[Vec<Vec<u32>>],
    prev_loops: &mut [usize],
    dirty: &mut [bool],
) {
    for (f, l) in loops.iter().enumerate() {
        let len: usize = l.iter().map(Vec::len).sum();
        if len != prev_loops[f] {
            prev_loops[f] = len;
            let face = &arr.faces[f];
            for c in [face.positive_cell, face.negative_cell]
                .into_iter()
                .flatten()
            {
                dirty[c as usize] = true;
            }
        }
    }
}

/// What sharing the diagram samples did.
#[derive(Clone, Copy, Debug, Default)]
pub struct SharingCounts {
    /// Samples and diagram Steiner points made pool vertices (one per position and face).
    pub samples: u64,
    /// Rounds of re-running cells with the points of both sides of their faces.
    pub rounds: u64,
    /// Cell runs with shared points.
    pub cells_rerun: u64,
    /// Cells whose run with shared points lost a contour edge to the other side's samples: they
    /// keep their run without them (their faces then differ from the other side's).
    pub cells_kept_unshared: u64,
    /// Points only one cell of their face inserted when the rounds ended.
    pub one_sided: u64,
    /// Cells whose only finished run misses contour edges the other side's samples took away.
    pub cells_missing_contour_edges: u64,
}

/// What a rerun with shared samples did to its cell's result.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rerun {
    /// The rerun's result replaced the cell's.
    Shared,
    /// The other side's samples took a contour edge away; the cell keeps its finished run.
    KeptUnshared,
    /// As `KeptUnshared`, but with no finished run to keep: the rerun's result stays, missing it.
    MissingEdges,
}

/// A rerun: what it did, its times, and the contour edges it lost to the other side's samples
/// (edges its cell's previous run had).
struct RerunOutcome {
    what: Rerun,
    timing: CellTiming,
    lost: Vec<(u32, u32)>,
}

/// Run cell `c` again with the shared samples, its result `slot` replaced in place; what it did
/// and the rerun's times (`None`: the cell has no input any more, its result stays).
#[allow(clippy::too_many_arguments)]
fn rerun_cell(
    arr: &Arrangement,
    pool: &crate::arrangement::VertexPool,
    loops: &[Vec<Vec<u32>>],
    sampling: Sampling,
    shared: &shared_samples::SharedSamples,
    split: bool,
    c: usize,
    slot: &mut Option<CellResult>,
) -> Result<Option<RerunOutcome>> {
    let start = slot.as_mut().and_then(|r| r.start.take());
    let Some(input) = CellInput::build(arr, pool, loops, c as u32) else {
        return Ok(None);
    };
    // a finished run on other contour points (before a contour edge was split) is not kept
    let current = slot
        .as_ref()
        .and_then(|p| p.input.as_ref())
        .is_some_and(|old| old.points == input.points);
    let mut r = cell::run_cell_sharing(input, sampling, shared, split, start)?;
    let timing = r.timing;
    // the contour edges the other side's samples took away (not those the cell's own run missed)
    let before: &[(u32, u32)] = slot.as_ref().map_or(&[], |p| &p.missing);
    let lost: Vec<(u32, u32)> = (r.missing.iter())
        .filter(|e| !before.contains(e))
        .copied()
        .collect();
    let what = if r.missing.is_empty() {
        Rerun::Shared
    } else if let Some(p) = slot.as_mut().filter(|p| p.pruned && current) {
        // the other side's samples took a contour edge away: keep a finished run without them
        // if there is one, else this one (its section then misses that edge)
        p.start = r.start.take();
        return Ok(Some(RerunOutcome {
            what: Rerun::KeptUnshared,
            timing,
            lost,
        }));
    } else {
        Rerun::MissingEdges
    };
    shared.adopt_ids(&mut r);
    if let Some(input) = r.input.as_mut() {
        input.slim();
    }
    *slot = Some(r);
    Ok(Some(RerunOutcome { what, timing, lost }))
}

/// Most rounds of sharing: each round's cells may add diagram samples and split contour edges that
/// the other side's samples took away (new points, inserted by both sides in the next round). A
/// round ending with points one side has not inserted leaves that face non-conforming; the
/// generated odd inputs need up to 12 (one on sweeps).
const MAX_SHARING_ROUNDS: usize = 16;

/// Make every cell's diagram samples (and their Steiner points) pool vertices and run again every
/// cell with such points on a face, inserting those of both sides (`shared_samples`), until no
/// cell adds a point of its own. A contour edge that a rerun misses (the other side's samples took
/// it away) is split in `splits`, for every cell that has it, and those cells run again: keeping
/// the run without the other side's samples, as before, left the two cells of a face with
/// different points on it, a non-conforming face and exact crossings (generated odd seed 45). The
/// reruns' times are added to `timing`.
fn share_samples(
    arr: &Arrangement,
    pool: &mut crate::arrangement::VertexPool,
    splits: &mut conform::Splits,
    sampling: Sampling,
    results: &mut [Option<CellResult>],
    timing: &mut CellTiming,
    seeds: shared_samples::SharedSamples,
) -> Result<SharingCounts> {
    let mut shared = seeds;
    let mut counts = SharingCounts::default();
    let mut dirty_faces = shared.extend(arr, pool, results);
    let mut loops = conform::face_loops(arr, splits);
    // per cell, what its last rerun did (the counts are of the final state)
    let mut last: Vec<Option<Rerun>> = vec![None; results.len()];
    let mut lost_first: Option<usize> = None;
    // at least one round: the cells stopped at conformity
    while (counts.rounds == 0 || !dirty_faces.is_empty())
        && (counts.rounds as usize) < MAX_SHARING_ROUNDS
    {
        counts.rounds += 1;
        // no more splitting of pairs: where the two sides' diagrams cross (paper Fig. 12a) each
        // side's splits would take the other's pair edges away forever; a pair the other side's
        // points took away is joined through them instead (`chains::route_pairs`)
        let split = false;
        let dirty: std::collections::HashSet<u32> = dirty_faces.iter().copied().collect();
        // the first round runs every cell to the end (the earlier runs stopped at conformity)
        let first = counts.rounds == 1;
        let run: Vec<bool> = (0..results.len())
            .map(|c| {
                results[c].is_some()
                    && (first || arr.cells[c].faces.iter().any(|cf| dirty.contains(&cf.face)))
            })
            .collect();
        // each rerun replaces its cell's result in place, so that the old and the new results of
        // every cell are never held at once (on a 1000-frame sweep they were gigabytes)
        let (pool_now, shared_now) = (&*pool, &shared);
        let loops_now = &loops;
        let outcomes: Vec<(usize, Result<Option<RerunOutcome>>)> = results
            .par_iter_mut()
            .enumerate()
            .filter(|(c, _)| run[*c])
            .map(|(c, slot)| {
                let r = rerun_cell(
                    arr, pool_now, loops_now, sampling, shared_now, split, c, slot,
                );
                (c, r)
            })
            .collect();
        let mut missing = Vec::new();
        for (c, outcome) in outcomes {
            let Some(o) = outcome? else {
                continue;
            };
            counts.cells_rerun += 1;
            timing.add(&o.timing);
            last[c] = Some(o.what);
            missing.extend(o.lost);
        }
        dirty_faces = shared.extend(arr, pool, results);
        // a contour edge the other side's samples took away is split, for both sides (the two
        // cells of a face then insert the same points again, and the Steiner point restores the
        // edge's halves), and the cells of the faces whose loops changed run again
        // only while that converges: never more edges than the first round lost (where splits
        // do not restore an edge, its halves would be lost again, twice as many every round)
        let first_lost = *lost_first.get_or_insert(missing.len());
        if !missing.is_empty()
            && missing.len() <= first_lost
            && (counts.rounds as usize) < MAX_SHARING_ROUNDS
        {
            missing.sort_unstable();
            missing.dedup();
            for (a, b) in missing {
                splits.split(pool, a, b);
            }
            let now = conform::face_loops(arr, splits);
            let changed = (0..now.len())
                .filter(|&f| now[f] != loops[f])
                .map(|f| f as u32);
            dirty_faces.extend(changed);
            dirty_faces.sort_unstable();
            dirty_faces.dedup();
            loops = now;
        }
    }
    counts.cells_kept_unshared = last
        .iter()
        .filter(|w| **w == Some(Rerun::KeptUnshared))
        .count() as u64;
    counts.cells_missing_contour_edges = last
        .iter()
        .filter(|w| **w == Some(Rerun::MissingEdges))
        .count() as u64;
    // the starts' triangulations are dropped in parallel too (tens of MB on big inputs)
    results.par_iter_mut().flatten().for_each(|r| {
        shared.adopt_ids(r);
        r.start = None;
    });
    counts.samples = shared.len() as u64;
    counts.one_sided = shared.one_sided(results);
    Ok(counts)
}

/// Reconstruct with the Delaunay pruning method. Fills `report` (phases, counts, warnings).
pub fn reconstruct(
    sections: &Sections,
    arrangement: &Arrangement,
    options: &Options,
    report: &mut Report,
) -> Result<Solid> {
    let k = reconstruct_complex(sections, arrangement, options, report, &[])?;
    Ok(Solid {
        surface: k.surface,
        tets: Some(k.tets),
        report: Report::default(),
    })
}

/// The solid as one complex, with its vertices' planes ([`reconstruct`] without dropping them).
pub fn reconstruct_complex(
    _sections: &Sections,
    arrangement: &Arrangement,
    options: &Options,
    report: &mut Report,
    seeds: &[(u32, [f64; 3])],
) -> Result<assembly::Assembled> {
    let arr = arrangement;
    let CellRuns {
        pool,
        results,
        rounds,
        conforming,
        steiner_points,
        cell_runs,
        timing,
        seconds,
        shared,
    } = {
        let (runs, placed) = run_cells_seeded(arr, options, seeds)?;
        if !seeds.is_empty() {
            report.count("seed_points", seeds.len() as u64);
            report.count("seed_points_placed", placed);
        }
        runs
    };
    report.count("shared_samples", shared.samples);
    report.count("cells_rerun_sharing_samples", shared.cells_rerun);
    report.count("sharing_rounds", shared.rounds);
    report.count("cells_kept_unshared", shared.cells_kept_unshared);
    report.count("one_sided_points", shared.one_sided);
    report.count(
        "cells_missing_contour_edges",
        shared.cells_missing_contour_edges,
    );
    if shared.cells_missing_contour_edges > 0 {
        report.warnings.push(format!(
            "{} cells miss contour edges that the other side's diagram samples took away",
            shared.cells_missing_contour_edges
        ));
    }
    if shared.cells_kept_unshared > 0 {
        report.warnings.push(format!(
            "{} cells lost a contour edge to the other side's diagram samples and keep their own samples only",
            shared.cells_kept_unshared
        ));
    }
    if !conforming {
        report.warnings.push(format!(
            "conformity splitting stopped after {MAX_ROUNDS} rounds: some contour edges are not Delaunay edges"
        ));
    }
    report.phases.push(crate::solid::Phase {
        name: "cells (delaunay, conformity, pruning)".into(),
        seconds,
    });
    report.note_peak_memory("cells");
    report.count("conformity_rounds", rounds as u64);
    report.count("cell_runs", cell_runs);
    for (name, secs) in timing.entries() {
        report
            .values
            .insert(format!("cell_cpu_seconds.{name}"), secs);
    }
    report.count("steiner_points", steiner_points as u64);
    report.count("points", (pool.positions.len()) as u64);
    for r in results.iter().flatten() {
        report.count("tets_delaunay", r.tets);
        report.count("tets_flat", r.flat_tets);
        report.count("cells_untagged", r.untagged as u64);
        report.count("step1_removed", r.counts.step1_removed);
        report.count("step2_removed", r.counts.step2_removed);
        report.count("step2_vf_groups_removed", r.counts.step2_vf_groups_removed);
        report.count("step3_added", r.counts.step3_added);
        report.count("step3_cavities_filled", r.counts.step3_cavities_filled);
        report.count("tets_kept", r.kept.len() as u64);
        report.count("branching_samples", r.branching_samples);
        report.count("cutting_samples", r.cutting_samples);
        report.count("sample_pairs", r.sample_pairs);
        report.count("sample_steiner_points", r.sample_steiner_points);
        let not_edges: u64 = r.sample_pairs_not_edges.iter().map(|x| x.1).sum();
        report.count("sample_pairs_not_edges", not_edges);
        for &(face, k) in &r.sample_pairs_not_edges {
            let cell = r.input.as_ref().map_or(u32::MAX, |i| i.cell);
            report.warnings.push(format!(
                "cell {cell}, face {face}: {k} pairs of consecutive diagram samples are not Delaunay edges after {} rounds of Steiner splits",
                cell::SAMPLE_PAIR_ROUNDS
            ));
        }
        report.count("cutting_samples_on_flat_border", r.cutting_on_flat_border);
        *report.values.entry("cell_flat_area".into()).or_insert(0.0) += r.flat_area;
    }
    Ok(assemble_cells(arr, &pool, &results, options, report))
}

/// The solid as one complex (`assembly`): the surface is the boundary of the kept tetrahedra.
fn assemble_cells(
    arr: &Arrangement,
    pool: &crate::arrangement::VertexPool,
    results: &[Option<CellResult>],
    options: &Options,
    report: &mut Report,
) -> assembly::Assembled {
    let slabs = options.delaunay.thicken_flat_zones;
    let fill_voids = !options.delaunay.keep_topology;
    let k = report.time("assembly", || {
        assembly::assemble(
            arr,
            pool,
            results,
            slabs,
            fill_voids,
            options.delaunay.collar,
            options.delaunay.smooth,
        )
    });
    report_assembly_counts(&k, report);
    report_assembly_warnings(&k, slabs, report);
    k
}

/// What `--smooth` did, in the report (nothing without it).
fn report_smoothing(s: &smooth::SmoothStats, report: &mut Report) {
    if s.sweeps == 0 && s.points == 0 {
        return;
    }
    report.count("smooth_points", s.points);
    report.count("smooth_edges_not_split", s.edges_not_split);
    report.count("smooth_sweeps", s.sweeps);
    report.count("smooth_points_moved", s.moved);
    report.count("smooth_steps_shortened", s.steps_shortened);
    report.count("smooth_steps_refused", s.steps_refused);
    report.count("smooth_points_put_back", s.put_back);
    report.values.insert("smooth_max_shift".into(), s.max_shift);
}

/// The assembly's counts and values in the report.
fn report_assembly_counts(k: &assembly::Assembled, report: &mut Report) {
    report.count("nonconforming_faces", k.nonconforming_faces);
    report.count("flat_zone_triangles", k.flat_triangles);
    report.values.insert("flat_zone_area".into(), k.flat_area);
    report.count("flat_zone_triangles_thickened", k.slabs.thickened);
    report.count("flat_zone_triangles_left", k.slabs.left);
    report.count("slab_tets", k.slabs.tets);
    report.count("slab_gaps_closed", k.slabs.gaps_closed);
    report.count("slab_gaps_open", k.slabs.gaps_open);
    report.count("slab_points", k.slabs.points);
    report
        .values
        .insert("slab_min_thickness".into(), k.slabs.min_thickness);
    report.count("singular_edges_found", k.singular_edges_found);
    report.count("singular_vertices_found", k.singular_vertices_found);
    report.count("tets_filled", k.tets_filled);
    report.count("hull_slivers_dropped", k.hull_slivers);
    report.count("singular_edge_gaps_grown", k.grown.edge_gaps);
    report.count("singular_vertex_gaps_grown", k.grown.vertex_gaps);
    report.count("singular_growth_tets", k.grown.tets);
    report.count("singular_growth_by_fraction", k.growth_by_fraction as u64);
    for (round, &(e, v)) in k.grown.per_round.iter().enumerate() {
        report.count(&format!("singular_round.{round}.edges"), e);
        report.count(&format!("singular_round.{round}.vertices"), v);
    }
    report.count("singular_toggles_added", k.toggled.added);
    report.count("singular_toggles_removed", k.toggled.removed);
    report.count("flat_fold_toggles_added", k.folds_closed.added);
    report.count("flat_fold_toggles_removed", k.folds_closed.removed);
    report.count("pinches_carved", k.carved.vertices);
    report.count("pinch_tips_removed", k.carved.tips);
    report.count("pinches_not_carved", k.carved.refused);
    report.count("pinches_carved_after_collar", k.carved_off_planes.vertices);
    report.count(
        "pinches_not_carved_after_collar",
        k.carved_off_planes.refused,
    );
    report.count("voids_filled", k.voids.voids_filled);
    report.count("void_tets_filled", k.voids.tets_filled);
    report.count("tunnel_candidates", k.tunnels.candidates);
    report.count("tunnel_membranes", k.tunnels.membranes);
    report.count("tunnels_closed", k.tunnels.tunnels_closed);
    report.count("tunnel_membranes_refused", k.tunnels.membranes_refused);
    report.count("tunnel_batches_undone", k.tunnels.batches_undone);
    report.count("tunnel_membranes_untested", k.tunnels.membranes_untested);
    report.count("tunnel_tets_added", k.tunnels.tets_added);
    report.count("cut_candidates", k.cuts.candidates);
    report.count("cuts", k.cuts.membranes);
    report.count("handles_cut", k.cuts.tunnels_closed);
    report.count("cuts_refused", k.cuts.membranes_refused);
    report.count("cut_batches_undone", k.cuts.batches_undone);
    report.count("cuts_untested", k.cuts.membranes_untested);
    report.count("cut_tets", k.cuts.tets_added);
    report.count("collar_cells", k.collar.cells);
    report.count("collar_cells_refused", k.collar.cells_refused);
    report.count("collar_cells_too_sharp", k.collar.cells_too_sharp);
    report.count("collar_prisms", k.collar.prisms);
    report.count("collar_cells_left_singular", k.collar.cells_left_singular);
    report
        .values
        .insert("collar_min_height".into(), k.collar.min_height);
    report
        .values
        .insert("collar_max_shift".into(), k.collar.max_shift);
    report
        .values
        .insert("collar_seconds".into(), k.collar.seconds);
    for (stage, mib) in &k.stage_peak_memory_mib {
        report
            .values
            .insert(format!("assembly_peak_memory_mib.{stage}"), *mib);
    }
    for (stage, secs) in &k.stage_seconds {
        report
            .values
            .insert(format!("assembly_seconds.{stage}"), *secs);
    }
    report.count("singular_edges", k.singular_edges);
    report.count("singular_vertices", k.singular_vertices);
    report_smoothing(&k.smooth, report);
}

/// The assembly's warnings: what it could not resolve or protect, and the flat zones; `slabs`:
/// whether flat zones were to be thickened.
fn report_assembly_warnings(k: &assembly::Assembled, slabs: bool, report: &mut Report) {
    if k.smooth.put_back > 0 {
        report.warnings.push(format!(
            "smooth: {} points put back where their fairing found them (the faired surface crossed itself there): the surface is less smooth there",
            k.smooth.put_back
        ));
    }
    if k.tunnels.skipped_singular {
        report.warnings.push(
            "tunnels: handles that no section witnesses are left open (the boundary of the complex is not a manifold)".into(),
        );
    }
    if k.tunnels.membranes_untested > 0 {
        report.warnings.push(format!(
            "tunnels: {} membranes closing handles no section witnesses were not tried (the budget of batches ran out): those handles stay",
            k.tunnels.membranes_untested
        ));
    }
    if k.cuts.membranes_untested > 0 {
        report.warnings.push(format!(
            "cuts: {} layers cutting handles no section witnesses were not tried (the budget of tries ran out): those handles stay",
            k.cuts.membranes_untested
        ));
    }
    if k.collar.cells_left_singular > 0 {
        report.warnings.push(format!(
            "collar: {} cells keep their solid as it was (their collar would make the surface singular): sections just off their planes are not protected there",
            k.collar.cells_left_singular
        ));
    }
    let flipped = k.collar.cells_refused - k.collar.cells_too_sharp;
    if flipped > 0 {
        report.warnings.push(format!(
            "collar: {flipped} cells keep their solid as it was (a mapped tetrahedron would flip or leave the cell): sections just off their planes are not protected there",
        ));
    }
    if k.collar.cells_too_sharp > 0 {
        report.warnings.push(format!(
            "collar: {} cells keep their solid as it was (two of their section planes meet at a section vertex at an angle too sharp for a collar of the full height): sections just off their planes are not protected there",
            k.collar.cells_too_sharp
        ));
    }
    if k.nonconforming_faces > 0 {
        report.warnings.push(format!(
            "{} faces are triangulated differently by their two cells: the complex is not conforming there and its boundary may cross itself",
            k.nonconforming_faces
        ));
    }
    if k.slabs.thickened > 0 {
        report.warnings.push(format!(
            "flat zones: {} section triangles (area {:.6e}) that no cell attaches to on either side (the paper's Fig. 13) thickened into slabs of tetrahedra, at least {:.3e} thick",
            k.slabs.thickened, k.flat_area, k.slabs.min_thickness
        ));
    }
    let left = if slabs {
        k.slabs.left
    } else {
        k.flat_triangles
    };
    if left > 0 {
        report.warnings.push(format!(
            "{left} of {} flat-zone section triangles (area {:.6e} in all) have no kept tetrahedron on either side and no slab: left out of the solid",
            k.flat_triangles, k.flat_area
        ));
    }
    if k.singular_edges + k.singular_vertices > 0 {
        report.warnings.push(format!(
            "the boundary of the complex has {} singular edges and {} pinched vertices that its resolution leaves: the surface is not a manifold there",
            k.singular_edges, k.singular_vertices
        ));
    }
}
