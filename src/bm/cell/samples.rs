//! A cell's diagram samples: rounds of branching and cutting samples (paper §2.2), each taken on
//! the triangulation the last round left and inserted into it with the other sides' shared
//! samples, and consecutive samples joined by Delaunay edges (`chains`).
use super::{cell_delaunay, points_delaunay, Clock, RunStart, Sampling, Start, BRANCHING_ROUNDS};
use crate::bm::cell_input::{CellInput, IdSet};
use crate::bm::chains::{conform_pairs, Chains, DiagramSample, Kind, SamplePair};
use crate::bm::classify::{tet_types, Classifier};
use crate::bm::complex::Complex;
use crate::bm::shared_samples::{NearSamples, SharedSamples};
use crate::error::Result;

/// Add to `input` (and `batch`) the shared samples on its faces that it did not sample itself
/// (those already there by global id: `present`, the global ids of `input`'s vertices). Returns
/// how many.
fn add_foreign_samples(
    input: &mut CellInput,
    shared: Option<&SharedSamples>,
    present: &IdSet<u32>,
    batch: &mut Vec<[f64; 3]>,
) -> u64 {
    let Some(shared) = shared else { return 0 };
    let mut n = 0;
    for s in 0..input.slots.len() {
        for x in shared.on_face(input.slots[s].face) {
            if !present.contains(&x.gid) {
                input.add_vertex(s, x.uv, x.p3, x.gid);
                batch.push(x.p3);
                n += 1;
            }
        }
    }
    n
}

/// Per slot of `input`: the shared samples on its face by position (exact, or within the
/// samples' tolerance: the cell's own computation of a shared sample may be a few ulps off).
fn shared_lookup(input: &CellInput, shared: Option<&SharedSamples>) -> Vec<NearSamples> {
    input
        .slots
        .iter()
        .map(|slot| shared.map_or_else(NearSamples::default, |sh| sh.near(slot.face)))
        .collect()
}

/// The cell's Delaunay triangulation, and whether the tagged kernel made it.
pub(super) struct Tri {
    pub(super) dt: crate::delaunay::Delaunay,
    pub(super) tagged: bool,
}

/// How a run takes its diagram samples.
pub(super) struct SampleRun<'a> {
    pub(super) sampling: Sampling,
    pub(super) pair_rounds: usize,
    pub(super) shared: Option<&'a SharedSamples>,
    pub(super) start: Start<'a>,
}

/// What the diagram samples added to a cell: counts for the report, the cutting samples' local
/// ids (ascending) for the flat zones' border, and the run's start if it keeps it.
#[derive(Default)]
pub(super) struct Sampled {
    pub(super) branching: u64,
    pub(super) cutting: u64,
    pub(super) cut_ids: Vec<u32>,
    pub(super) pairs: u64,
    pub(super) pair_steiner: u64,
    pub(super) pairs_not_edges: std::collections::BTreeMap<u32, u64>,
    pub(super) pair_list: Vec<(usize, u32, u32)>,
    pub(super) foreign: u64,
    pub(super) start: Option<Box<RunStart>>,
}

/// Rounds of diagram samples (and, in the first, the shared samples of the other sides), each
/// sampled on the triangulation the last round left and inserted into it; `cx` follows `tri`.
pub(super) fn insert_diagram_samples(
    input: &mut CellInput,
    tri: &mut Tri,
    cx: &mut Complex,
    how: &SampleRun,
    clock: &mut Clock,
) -> Result<Sampled> {
    let mut out = Sampled::default();
    let lookup = shared_lookup(input, how.shared);
    for round in 0..BRANCHING_ROUNDS {
        let reuse = match how.start {
            Start::Reuse(st) if round == 0 => Some(st),
            _ => None,
        };
        let (branch_chains, cut_chains) = match reuse {
            Some(st) => (st.branching.clone(), st.cutting.clone()),
            None => diagram_samples(input, cx, how.sampling, clock),
        };
        // the start's parts before the samples go in (its triangulation is taken after)
        let mut keep = (round == 0 && matches!(how.start, Start::Keep)).then(|| StartParts {
            points: input.points.clone(),
            tagged: tri.tagged,
            branching: branch_chains.clone(),
            cutting: cut_chains.clone(),
        });
        let (n_branch_round, n_cut_round) = (branch_chains.samples.len(), cut_chains.samples.len());
        let has_shared = round == 0 && lookup.iter().any(|m| !m.is_empty());
        if n_branch_round + n_cut_round == 0 && !has_shared {
            if let Some(parts) = keep.take() {
                out.start = Some(Box::new(parts.complete(input, tri)?));
            }
            if reuse.is_some() {
                *cx = Complex::from_delaunay(input.points.len(), &tri.dt);
            }
            break;
        }
        out.branching += n_branch_round as u64;
        out.cutting += n_cut_round as u64;
        // inserted into the triangulation we have, in one batch (same result as re-triangulating
        // everything); a reused start has this round's samples in already
        let mut chains = branch_chains;
        chains.extend(cut_chains);
        let first_sample = input.points.len() as u32;
        let batch = Batch {
            lookup: &lookup,
            first_cut: input.points.len() + n_branch_round,
            has_shared,
            present: match reuse {
                Some(st) if st.with_samples => chains.samples.len(),
                _ => 0,
            },
        };
        insert_samples(input, tri, &chains, &batch, how, &mut out)?;
        if let Some(parts) = keep.take() {
            out.start = Some(Box::new(parts.complete(input, tri)?));
        }
        clock.lap(|t| &mut t.delaunay);
        join_sample_pairs(input, tri, &chains, first_sample, how, &mut out)?;
        clock.lap(|t| &mut t.sample_pairs);
        *cx = Complex::from_delaunay(input.points.len(), &tri.dt);
        clock.lap(|t| &mut t.delaunay);
    }
    Ok(out)
}

/// A run's start (`RunStart`) before its samples are inserted.
struct StartParts {
    points: Vec<[f64; 3]>,
    tagged: bool,
    branching: Chains,
    cutting: Chains,
}

impl StartParts {
    /// The start, with the triangulation `tri` that now holds the samples too; when the tag rules
    /// failed on them (`tri` fell back to the untagged kernel), with the contour points'
    /// triangulation instead, and the reruns insert the samples again as the whole run would.
    fn complete(self, input: &CellInput, tri: &Tri) -> Result<RunStart> {
        let (dt, tagged, with_samples) = if tri.tagged == self.tagged {
            (tri.dt.clone_compact(), tri.tagged, true)
        } else {
            let mut tagged = true;
            let dt = points_delaunay(&self.points, &input.tags, &input.apexes, &mut tagged)?;
            (dt, tagged, false)
        };
        Ok(RunStart {
            points: self.points,
            dt,
            with_samples,
            tagged,
            branching: self.branching,
            cutting: self.cutting,
        })
    }
}

/// What one round's batch of samples inserts.
struct Batch<'a> {
    /// Per slot, the shared samples by position.
    lookup: &'a [NearSamples],
    /// Local id of the round's first cutting sample.
    first_cut: usize,
    /// The other sides' shared samples go in too.
    has_shared: bool,
    /// How many of the round's own samples the triangulation has already (a reused start's).
    present: usize,
}

/// Insert one round's samples (with their global ids where `lookup` knows them) and, with
/// `has_shared`, the other sides' shared samples, in one batch (less those already `present`).
fn insert_samples(
    input: &mut CellInput,
    tri: &mut Tri,
    chains: &Chains,
    b: &Batch,
    how: &SampleRun,
    out: &mut Sampled,
) -> Result<()> {
    let mut batch = Vec::with_capacity(chains.samples.len());
    // the global ids of the cell's vertices: a shared sample stands for one vertex of the cell (a
    // second own sample near it stays local), and the other sides' samples not among them go in
    let mut taken: IdSet<u32> = input
        .global
        .iter()
        .copied()
        .filter(|&g| g != u32::MAX)
        .collect();
    for &DiagramSample {
        slot: s, uv: q, p3, ..
    } in &chains.samples
    {
        if !p3.iter().all(|c| c.is_finite()) {
            return Err(crate::Error::input(
                format!("cell {} diagram sample", input.cell),
                "non-finite coordinate",
            ));
        }
        let gid = b.lookup[s]
            .find(p3)
            .map(|x| x.gid)
            .filter(|&g| taken.insert(g))
            .unwrap_or(u32::MAX);
        let l = input.add_vertex(s, q, p3, gid);
        batch.push(p3);
        if l as usize >= b.first_cut {
            out.cut_ids.push(l);
        }
    }
    if b.has_shared {
        out.foreign += add_foreign_samples(input, how.shared, &taken, &mut batch);
    }
    let batch = &batch[b.present..];
    let first = input.points.len() - batch.len();
    let ids = tri.dt.insert_batch_tagged(batch, &input.tags[first..]);
    if tri.tagged && tri.dt.consistent().is_err() {
        tri.dt = cell_delaunay(input, &mut tri.tagged)?;
    }
    // ids in local order (a duplicate gets the earlier vertex's id)
    debug_assert!(ids
        .iter()
        .enumerate()
        .all(|(i, &id)| id as usize <= first + i));
    Ok(())
}

/// Consecutive samples along a diagram become edges (Steiner points on the diagram); with shared
/// samples, a pair the other side's points took away is routed through them.
fn join_sample_pairs(
    input: &mut CellInput,
    tri: &mut Tri,
    chains: &Chains,
    first_sample: u32,
    how: &SampleRun,
    out: &mut Sampled,
) -> Result<()> {
    let pairs: Vec<SamplePair> = chains
        .pairs
        .iter()
        .map(|&(a, b)| {
            let d = &chains.samples[a as usize];
            SamplePair {
                slot: d.slot,
                kind: d.kind,
                sites: d.sites,
                ends: (first_sample + a, first_sample + b),
            }
        })
        .collect();
    out.pairs += pairs.len() as u64;
    if pairs.is_empty() {
        return Ok(());
    }
    let mut pc = conform_pairs(input, &mut tri.dt, pairs, how.pair_rounds)?;
    if tri.tagged && tri.dt.consistent().is_err() {
        tri.dt = cell_delaunay(input, &mut tri.tagged)?;
    }
    if how.shared.is_some() {
        let not_edges = std::mem::take(&mut pc.not_edges);
        pc.not_edges =
            crate::bm::chains::route_pairs(input, &tri.dt, &mut pc.pairs, not_edges, first_sample);
    }
    for &(l, kind) in &pc.steiner {
        if kind == Kind::Cutting {
            out.cut_ids.push(l);
        }
    }
    out.pair_steiner += pc.steiner.len() as u64;
    for p in &pc.not_edges {
        *out.pairs_not_edges
            .entry(input.slots[p.slot].face)
            .or_default() += 1;
    }
    out.pair_list
        .extend(pc.pairs.iter().map(|p| (p.slot, p.ends.0, p.ends.1)));
    Ok(())
}

/// One round's branching and cutting samples of the triangulation `cx` of `input`.
fn diagram_samples(
    input: &CellInput,
    cx: &Complex,
    sampling: Sampling,
    clock: &mut Clock,
) -> (Chains, Chains) {
    let ty = tet_types(input, cx);
    let mut cl = Classifier::new(input);
    let apex = crate::bm::branching::apex_triangles(input, cx, &ty, &cl);
    let branch_chains = if sampling.branching {
        crate::bm::branching::sample_chains(input, &mut cl, &apex)
    } else {
        Default::default()
    };
    clock.lap(|t| &mut t.branching);
    // from the same triangulation, kept apart from the branching samples
    let cut_chains = if sampling.cutting {
        crate::bm::cutting::sample_chains(input, cx, &ty, &mut cl, &apex, &branch_chains.samples)
    } else {
        Default::default()
    };
    clock.lap(|t| &mut t.cutting);
    (branch_chains, cut_chains)
}
