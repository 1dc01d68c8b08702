//! Chains of diagram samples and their Delaunay conformity (paper §3, "Delaunay conformity
//! condition": two branching (cutting) vertices consecutive along B_C (M_C) are joined by an edge).
//!
//! Every branching or cutting sample carries its diagram identity: the slot it lies on, its kind and
//! the unordered pair of sites (b1, b2) whose tangent-sphere radii are equal there. The samplers
//! (`branching`, `cutting`) produce *candidates* linked where the diagram runs from one to the next
//! (marching-squares adjacency on the branching grid, shared endpoints of the cutting source edges);
//! [`thin_chains`] thins them along the chains, closing each chain over a dropped candidate, and keeps
//! a link only when the diagram between its two samples stays inside the section and in the two
//! sites' cells ([`SlotDiagram::between`]). After the samples are inserted, [`conform_pairs`] splits
//! every linked pair that is not an edge of the slot's grounded triangles with a Steiner point on the
//! diagram between them, a few rounds, and reports what is left.
use super::branching::{into_cell_normal, moebius_sites, Site, SiteIndex};
use super::cell_input::{slots_of, CellInput, IdMap, Mask, Where};
use super::cutting::{diagram_point_across, Thinning};
use super::guard::ContourGuard;
use crate::delaunay::Delaunay;
use crate::sections::{dot, sub};

/// Diagram samples closer than this fraction of the sampling step (grid spacing, or the edge a
/// sample was found across) to the section boundary are not taken: such a point is on the boundary
/// up to rounding, where the kernel would see it on one plane only.
pub(super) const SAMPLE_CLEARANCE: f64 = 1e-6;

/// Which diagram a sample lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    Branching,
    Cutting,
}

/// A sample of the branching or cutting diagram of one slot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiagramSample {
    pub slot: usize,
    /// (u,v) in the slot's plane.
    pub uv: [f64; 2],
    pub p3: [f64; 3],
    pub kind: Kind,
    /// The two sites (local vertex ids, smaller first) with equal radii here.
    pub sites: (u32, u32),
}

/// Samples with their chain links.
#[derive(Clone, Debug, Default)]
pub struct Chains {
    pub samples: Vec<DiagramSample>,
    /// Samples consecutive along the diagram (indices into `samples`, smaller first), sorted.
    pub pairs: Vec<(u32, u32)>,
}

impl Chains {
    /// Append `other`, its indices shifted.
    pub fn extend(&mut self, other: Chains) {
        let k = self.samples.len() as u32;
        self.samples.extend(other.samples);
        self.pairs
            .extend(other.pairs.into_iter().map(|(a, b)| (a + k, b + k)));
    }
}

/// Thin linked candidates along their chains. In candidate order, a candidate is dropped when it
/// has no position (`None`) or lies closer than the thinning radius to an occupied point (contour
/// vertices, earlier samples); its neighbours are then linked to each other, so a chain closes over
/// it. Kept samples occupy their position. A link between two kept samples survives when
/// `valid(a, b)` (the diagram between them stays in the section and in the sites' cells).
pub(super) fn thin_chains(
    cands: Vec<Option<DiagramSample>>,
    links: &[(u32, u32)],
    thin: &mut Thinning,
    mut valid: impl FnMut(&DiagramSample, &DiagramSample) -> bool,
) -> Chains {
    let n = cands.len();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    let link = |adj: &mut Vec<Vec<u32>>, a: u32, b: u32| {
        if a != b && !adj[a as usize].contains(&b) {
            adj[a as usize].push(b);
            adj[b as usize].push(a);
        }
    };
    for &(a, b) in links {
        if (a as usize) < n && (b as usize) < n {
            link(&mut adj, a, b);
        }
    }
    let mut new_id = vec![u32::MAX; n];
    let mut samples = Vec::new();
    for i in 0..n {
        let keep = cands[i].filter(|c| !thin.near(c.uv));
        if let Some(c) = keep {
            thin.occupy(c.uv);
            new_id[i] = samples.len() as u32;
            samples.push(c);
            continue;
        }
        // close the chain over candidate i
        let nb = std::mem::take(&mut adj[i]);
        for &x in &nb {
            adj[x as usize].retain(|&y| y as usize != i);
        }
        for (k, &x) in nb.iter().enumerate() {
            for &y in &nb[k + 1..] {
                link(&mut adj, x, y);
            }
        }
    }
    let mut pairs = Vec::new();
    for (i, nb) in adj.iter().enumerate() {
        for &j in nb {
            let (a, b) = (new_id[i], new_id[j as usize]);
            if (i as u32) < j && a != u32::MAX && b != u32::MAX {
                let (sa, sb) = (&samples[a as usize], &samples[b as usize]);
                if valid(sa, sb) {
                    pairs.push((a.min(b), a.max(b)));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    Chains { samples, pairs }
}

/// The Moebius diagram of one slot: its sites and their index, for placing and checking points
/// between two samples of a chain.
pub struct SlotDiagram {
    pub(super) s: usize,
    /// Unit normal into the cell.
    pub(super) n: [f64; 3],
    pub(super) sites: Vec<Site>,
    pub(super) index: SiteIndex,
}

impl SlotDiagram {
    pub fn new(input: &CellInput, s: usize) -> SlotDiagram {
        let n = into_cell_normal(input, s);
        let sites = moebius_sites(input, s, n);
        let index = SiteIndex::new(input.slots[s].geom(), &sites);
        SlotDiagram { s, n, sites, index }
    }

    /// The point where r_b1 = r_b2 (`sa`, else `sb`) on the perpendicular bisector of the chord
    /// pa pb nearest the chord's midpoint (within the chord's length of it), else the midpoint.
    /// `None` when that point or the chord's midpoint is not strictly inside the section (the edge
    /// would be external, e.g. across a notch), or the site with the smallest
    /// radius there is none of the four sites, continuous with none of them (see [`continuous`]),
    /// and smaller than theirs beyond rounding: the diagram between the two samples leaves the
    /// section or runs into a third site's cell. (The sites are section vertices: along one branch
    /// of the diagram they change from vertex to neighbouring vertex of the same contours.)
    pub fn between(
        &self,
        input: &CellInput,
        pa: [f64; 2],
        pb: [f64; 2],
        sa: (u32, u32),
        sb: (u32, u32),
        cont: &mut impl FnMut(u32, u32) -> bool,
    ) -> Option<[f64; 2]> {
        let slot = &input.slots[self.s];
        let plane = *slot.geom();
        let site = |x: u32| {
            let x3 = input.points[x as usize];
            (plane.to_2d(x3), dot(self.n, sub(x3, plane.origin)))
        };
        let x = diagram_point_across(pa, pb, site(sa.0), site(sa.1))
            .or_else(|| diagram_point_across(pa, pb, site(sb.0), site(sb.1)))
            .unwrap_or([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
        let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
        if !x.iter().all(|c| c.is_finite())
            || slot.locator().locate(x) != Where::Inside
            || slot.locator().locate(mid) != Where::Inside
        {
            return None;
        }
        let x3 = plane.to_3d(x);
        let r = |p: [f64; 3]| {
            let h = dot(self.n, sub(p, x3));
            if h > 0.0 {
                dot(sub(p, x3), sub(p, x3)) / (2.0 * h)
            } else {
                f64::INFINITY
            }
        };
        let four = [sa.0, sa.1, sb.0, sb.1];
        let own = four
            .iter()
            .map(|&b| r(input.points[b as usize]))
            .fold(f64::INFINITY, f64::min);
        let mut best = (f64::INFINITY, usize::MAX);
        self.index.visit(x, |k| {
            let v = r(self.sites[k].1);
            if v < best.0 {
                best = (v, k);
            }
            best.0
        });
        if own <= best.0 * (1.0 + 1e-9) || best.1 == usize::MAX {
            return Some(x);
        }
        let m = self.sites[best.1].0;
        four.iter().any(|&b| cont(m, b)).then_some(x)
    }
}

/// Sites a and b (section vertices) are continuous: the same vertex, or on a common slot with the
/// segment ab not outside its section (a contour edge, or midpoint inside or on the boundary); the
/// negation of the samplers' "discontinuous" (`Classifier::edge_external`, uncached).
pub fn continuous(input: &CellInput, a: u32, b: u32) -> bool {
    if a == b {
        return true;
    }
    let m = input.mask[a as usize] & input.mask[b as usize];
    if m == 0 {
        return false;
    }
    let k = super::cell_input::edge_key(a, b);
    (0..input.slots.len())
        .filter(|&s| m >> s & 1 == 1)
        .all(|s| {
            let slot = &input.slots[s];
            if slot.contour_edges().contains(&k) {
                return true;
            }
            let (p, q) = (slot.uv[a as usize], slot.uv[b as usize]);
            let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            slot.locator().locate(mid) != Where::Outside
        })
}

/// Two site pairs are the same branch of a diagram: their sites match up continuously (`cont`,
/// [`continuous`] or a cached equivalent).
pub fn same_branch(a: (u32, u32), b: (u32, u32), cont: &mut impl FnMut(u32, u32) -> bool) -> bool {
    (cont(a.0, b.0) && cont(a.1, b.1)) || (cont(a.0, b.1) && cont(a.1, b.0))
}

/// Two inserted samples consecutive along a diagram (local vertex ids).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SamplePair {
    pub slot: usize,
    pub kind: Kind,
    pub sites: (u32, u32),
    pub ends: (u32, u32),
}

/// What [`conform_pairs`] did.
#[derive(Clone, Debug, Default)]
pub struct PairConformity {
    /// Steiner points inserted (local ids, with their kind), ascending.
    pub steiner: Vec<(u32, Kind)>,
    /// The pairs after splitting.
    pub pairs: Vec<SamplePair>,
    /// Of `pairs`, those that are not edges of their slot's grounded triangles at the end.
    pub not_edges: Vec<SamplePair>,
}

/// Is (u, v) an edge of a grounded triangle on slot `s` of a non-flat tet of `dt`?
pub fn is_grounded_edge(dt: &Delaunay, mask: &[Mask], s: usize, u: u32, v: u32) -> bool {
    dt.vertex_tets(u).into_iter().any(|t| {
        let tv = dt.tet_vertices(t);
        tv.contains(&v)
            && tv.iter().fold(!0 as Mask, |m, &w| m & mask[w as usize]) == 0
            && grounded_on(&tv, u, v, mask, s)
    })
}

/// Calls `f(tet, u, v)` for every edge uv of a non-flat tet of `dt` whose two ends are diagram
/// points (ids `>= min_id`), once per tet holding it.
fn for_each_diagram_edge(
    dt: &Delaunay,
    min_id: u32,
    mask: &[Mask],
    mut f: impl FnMut(&[u32; 4], u32, u32),
) {
    for t in dt.tets() {
        let tv = dt.tet_vertices(t);
        if tv.iter().filter(|&&v| v >= min_id).count() < 2
            || tv.iter().fold(!0 as Mask, |m, &w| m & mask[w as usize]) != 0
        {
            continue;
        }
        for (a, b) in super::complex::TET_EDGES {
            let (u, v) = (tv[a], tv[b]);
            if u >= min_id && v >= min_id {
                f(&tv, u, v);
            }
        }
    }
}

/// Whether edge uv of tet `tv` is an edge of a grounded triangle on slot `s` of that tet (another
/// of its vertices lies on the slot).
fn grounded_on(tv: &[u32; 4], u: u32, v: u32, mask: &[Mask], s: usize) -> bool {
    let bit: Mask = 1 << s;
    tv.iter()
        .any(|&w| w != u && w != v && mask[w as usize] & bit != 0)
}

/// Per pair, whether its ends are an edge of a grounded triangle on its slot of a non-flat tet of
/// `dt` (one pass over the tets; every pair end is at least `min_id`, so tets with fewer than two
/// such vertices are skipped at once).
pub fn grounded_pair_edges(
    dt: &Delaunay,
    mask: &[Mask],
    pairs: &[SamplePair],
    min_id: u32,
) -> Vec<bool> {
    let mut found = vec![false; pairs.len()];
    let mut wanted: IdMap<(u32, u32), Vec<u32>> = IdMap::default();
    for (i, p) in pairs.iter().enumerate() {
        wanted
            .entry(super::cell_input::edge_key(p.ends.0, p.ends.1))
            .or_default()
            .push(i as u32);
    }
    for_each_diagram_edge(dt, min_id, mask, |tv, u, v| {
        for &i in wanted
            .get(&super::cell_input::edge_key(u, v))
            .into_iter()
            .flatten()
        {
            if grounded_on(tv, u, v, mask, pairs[i as usize].slot) {
                found[i as usize] = true;
            }
        }
    });
    found
}

/// Split every pair that is not an edge of its slot's grounded triangles in `dt` with a Steiner
/// point on the diagram between its ends ([`SlotDiagram::between`]; a pair whose point falls
/// outside the section is left as it is), inserted as a cell-local vertex, up to `max_rounds`
/// rounds; every round re-checks all pairs (an insertion can take an earlier edge away), and so
/// does a last check.
pub fn conform_pairs(
    input: &mut CellInput,
    dt: &mut Delaunay,
    pairs: Vec<SamplePair>,
    max_rounds: usize,
) -> crate::error::Result<PairConformity> {
    let mut out = PairConformity::default();
    let mut pairs = pairs;
    let min_id = pairs
        .iter()
        .map(|p| p.ends.0.min(p.ends.1))
        .min()
        .unwrap_or(0);
    let mut diagrams: IdMap<usize, SlotDiagram> = IdMap::default();
    let mut guards: IdMap<usize, ContourGuard> = IdMap::default();
    // whether each pair is an edge, for the current triangulation and pairs
    let mut edge = grounded_pair_edges(dt, &input.mask, &pairs, min_id);
    for _ in 0..max_rounds {
        let missing: Vec<usize> = (0..pairs.len()).filter(|&i| !edge[i]).collect();
        if missing.is_empty() {
            break;
        }
        let mut split = false;
        let mut added = Vec::new();
        for i in missing {
            let p = pairs[i];
            let (u, v) = p.ends;
            let d = diagrams
                .entry(p.slot)
                .or_insert_with(|| SlotDiagram::new(input, p.slot));
            let uv = &input.slots[p.slot].uv;
            let Some(x) = d.between(
                input,
                uv[u as usize],
                uv[v as usize],
                p.sites,
                p.sites,
                &mut |a, b| continuous(input, a, b),
            ) else {
                continue;
            };
            // a Steiner point must not take a contour edge away either (the pair stays no edge)
            let guard = guards.entry(p.slot).or_insert_with(|| {
                let h = super::branching::contour_spacing(input, p.slot);
                ContourGuard::of_slot(input, p.slot, 0.5 * h)
            });
            if guard.encroaches(x) {
                continue;
            }
            let p3 = input.slots[p.slot].geom().to_3d(x);
            if !p3.iter().all(|c| c.is_finite()) {
                return Err(crate::Error::input(
                    format!("cell {} diagram Steiner point", input.cell),
                    "non-finite coordinate",
                ));
            }
            let l = input.add_local_vertex(p.slot, x, p3);
            // an exact duplicate answers with the existing vertex
            let w = dt.insert_tagged(p3, &input.tags[l as usize]);
            if w == u || w == v {
                continue;
            }
            out.steiner.push((l, p.kind));
            split = true;
            pairs[i].ends = (u, w);
            added.push(SamplePair { ends: (w, v), ..p });
        }
        pairs.extend(added);
        if !split {
            // nothing changed: `edge` still holds
            break;
        }
        edge = grounded_pair_edges(dt, &input.mask, &pairs, min_id);
    }
    out.not_edges = (0..pairs.len())
        .filter(|&i| !edge[i])
        .map(|i| pairs[i])
        .collect();
    out.pairs = pairs;
    Ok(out)
}

/// Longest detour [`route_pairs`] takes through other diagram points.
const ROUTE_MAX_EDGES: usize = 4;

/// Per slot, the grounded edges of `dt` between vertices `>= min_id` (diagram points: own
/// samples, Steiner points, the other side's samples), as adjacency lists.
fn diagram_edges(dt: &Delaunay, mask: &[Mask], min_id: u32) -> IdMap<(usize, u32), Vec<u32>> {
    let mut adj: IdMap<(usize, u32), Vec<u32>> = IdMap::default();
    for_each_diagram_edge(dt, min_id, mask, |tv, u, v| {
        let on = mask[u as usize] & mask[v as usize];
        // the set bits only: a scan of all 128 was most of the pairs' routing time
        for s in slots_of(on) {
            if grounded_on(tv, u, v, mask, s) {
                adj.entry((s, u)).or_default().push(v);
                adj.entry((s, v)).or_default().push(u);
            }
        }
    });
    for l in adj.values_mut() {
        l.sort_unstable();
        l.dedup();
    }
    adj
}

/// A path of grounded edges from `u` to `v` on slot `s` through at most `ROUTE_MAX_EDGES - 1`
/// other diagram points, each strictly closer to `v` than the one before and within half the
/// pair's length of the segment uv (so the path follows the diagram between the two samples).
fn route(
    adj: &IdMap<(usize, u32), Vec<u32>>,
    uv: &[[f64; 2]],
    s: usize,
    u: u32,
    v: u32,
) -> Option<Vec<u32>> {
    let (a, b) = (uv[u as usize], uv[v as usize]);
    let d2 = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    let len2 = d2(a, b);
    let near_segment = |p: [f64; 2]| {
        let t = (((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2)
            .clamp(0.0, 1.0);
        d2(p, [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]) <= 0.25 * len2
    };
    let mut path = vec![u];
    fn go(
        adj: &IdMap<(usize, u32), Vec<u32>>,
        uv: &[[f64; 2]],
        s: usize,
        v: u32,
        path: &mut Vec<u32>,
        ok: &dyn Fn([f64; 2]) -> bool,
    ) -> bool {
        let cur = *path.last().unwrap();
        let Some(next) = adj.get(&(s, cur)) else {
            return false;
        };
        if next.contains(&v) {
            path.push(v);
            return true;
        }
        if path.len() >= ROUTE_MAX_EDGES {
            return false;
        }
        let dist = |w: u32| {
            let (p, q) = (uv[w as usize], uv[v as usize]);
            (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)
        };
        for &w in next {
            if dist(w) < dist(cur) && !path.contains(&w) && ok(uv[w as usize]) {
                path.push(w);
                if go(adj, uv, s, v, path, ok) {
                    return true;
                }
                path.pop();
            }
        }
        false
    }
    go(adj, uv, s, v, &mut path, &near_segment).then_some(path)
}

/// Where the other side's diagram points stand between two consecutive samples (the two cells'
/// diagrams cross there, paper Fig. 12a), the pair is an edge path through them: each pair of
/// `not_edges` that such a path joins is replaced in `pairs` by the path's edges. Returns the
/// pairs still not joined.
pub fn route_pairs(
    input: &CellInput,
    dt: &Delaunay,
    pairs: &mut Vec<SamplePair>,
    not_edges: Vec<SamplePair>,
    min_id: u32,
) -> Vec<SamplePair> {
    if not_edges.is_empty() {
        return not_edges;
    }
    let adj = diagram_edges(dt, &input.mask, min_id);
    let mut left = Vec::new();
    for p in not_edges {
        let uv = &input.slots[p.slot].uv;
        let Some(path) = route(&adj, uv, p.slot, p.ends.0, p.ends.1) else {
            left.push(p);
            continue;
        };
        if let Some(i) = pairs
            .iter()
            .position(|q| q.slot == p.slot && q.ends == p.ends)
        {
            pairs.swap_remove(i);
        }
        pairs.extend(path.windows(2).map(|w| SamplePair {
            ends: (w[0], w[1]),
            ..p
        }));
    }
    left
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(x: f64) -> DiagramSample {
        DiagramSample {
            slot: 0,
            uv: [x, 0.0],
            p3: [x, 0.0, 0.0],
            kind: Kind::Branching,
            sites: (0, 1),
        }
    }

    /// A chain of candidates 0.1 apart thinned to radius 0.25 keeps every third one and stays one
    /// chain (each kept sample linked to the next kept one); a candidate without position and one
    /// near an occupied point are bridged over; a link the validity test refuses is cut.
    #[test]
    fn thinning_keeps_chains_connected() {
        let mut cands: Vec<Option<DiagramSample>> =
            (0..10).map(|i| Some(sample(0.1 * i as f64))).collect();
        let links: Vec<(u32, u32)> = (0..9).map(|i| (i, i + 1)).collect();
        let mut thin = Thinning::new(0.25);
        let c = thin_chains(cands.clone(), &links, &mut thin, |_, _| true);
        let xs: Vec<f64> = c.samples.iter().map(|s| s.uv[0]).collect();
        assert_eq!(xs.len(), 4, "{xs:?}");
        assert!((xs[3] - 0.9).abs() < 1e-12, "{xs:?}");
        assert_eq!(c.pairs, vec![(0, 1), (1, 2), (2, 3)]);
        // the first sample has no position, the fourth is near an occupied point
        cands[0] = None;
        let mut thin = Thinning::new(0.25);
        thin.occupy([0.3, 0.2]);
        let c = thin_chains(cands.clone(), &links, &mut thin, |_, _| true);
        let xs: Vec<f64> = c.samples.iter().map(|s| s.uv[0]).collect();
        assert_eq!(xs.len(), 3, "{xs:?}");
        assert!(
            (xs[0] - 0.1).abs() < 1e-12 && (xs[1] - 0.5).abs() < 1e-12,
            "{xs:?}"
        );
        assert_eq!(c.pairs, vec![(0, 1), (1, 2)]);
        // two chains (y = 0 and y = 1): no link between them appears; refused links are cut
        let two: Vec<Option<DiagramSample>> = (0..8)
            .map(|i| {
                let mut c = sample(0.3 * (i % 4) as f64);
                c.uv[1] = (i / 4) as f64;
                Some(c)
            })
            .collect();
        let links2: Vec<(u32, u32)> = vec![(0, 1), (1, 2), (2, 3), (4, 5), (5, 6), (6, 7)];
        let mut thin = Thinning::new(0.25);
        let c = thin_chains(two, &links2, &mut thin, |a, b| {
            !(a.uv[1] == 1.0 && a.uv[0].max(b.uv[0]) > 0.65)
        });
        assert_eq!(c.samples.len(), 8);
        assert_eq!(c.pairs, vec![(0, 1), (1, 2), (2, 3), (4, 5), (5, 6)]);
    }

    /// Local id of the vertex at (x, y) on slot `s` of `input`.
    fn vertex_at(input: &CellInput, s: usize, x: f64, y: f64) -> u32 {
        (0..input.points.len() as u32)
            .find(|&v| {
                let p = input.points[v as usize];
                input.mask[v as usize] >> s & 1 == 1
                    && (p[0] - x).abs() < 1e-9
                    && (p[1] - y).abs() < 1e-9
            })
            .unwrap()
    }

    /// One circle on z = 0 under four circles on z = 1 (paper Fig. 4d). Two samples far apart on
    /// the branch x = 0 (between the left and the right circles), with two samples of the branch
    /// y = 0 just beside the chord's midpoint: the pair is not a Delaunay edge. The loop splits it at
    /// (0, 0), where the two branches cross, and every piece is then an edge of a grounded triangle;
    /// with no rounds the pair stays a non-edge.
    #[test]
    fn a_pair_blocked_by_another_branch_is_split_on_the_diagram() {
        let base = crate::bm::cutting::tests::one_facing_four();
        // sites: (-0.2, -0.6) on the lower left circle, (0.2, -0.6) on the lower right one
        let sites = {
            let (a, b) = (
                vertex_at(&base, 1, -0.2, -0.6),
                vertex_at(&base, 1, 0.2, -0.6),
            );
            (a.min(b), a.max(b))
        };
        let run = |rounds: usize| {
            let mut input = base.clone();
            let mut dt = Delaunay::try_new(&input.points).unwrap();
            let mut ids = Vec::new();
            for q in [[0.0, -0.9], [0.0, 0.9], [0.05, 0.0], [-0.05, 0.0]] {
                let p3 = input.slots[0].geom().to_3d(q);
                let l = input.add_local_vertex(0, q, p3);
                assert_eq!(dt.insert(p3), l);
                ids.push(l);
            }
            let pair = SamplePair {
                slot: 0,
                kind: Kind::Branching,
                sites,
                ends: (ids[0], ids[1]),
            };
            assert!(!is_grounded_edge(&dt, &input.mask, 0, ids[0], ids[1]));
            let pc = conform_pairs(&mut input, &mut dt, vec![pair], rounds).unwrap();
            (input, dt, pc)
        };
        let (_, _, pc) = run(0);
        assert!(pc.steiner.is_empty());
        assert_eq!(pc.not_edges.len(), 1);
        let (input, dt, pc) = run(8);
        assert!(!pc.steiner.is_empty());
        assert!(pc.not_edges.is_empty(), "{:?}", pc.not_edges);
        assert_eq!(pc.pairs.len(), 1 + pc.steiner.len());
        let first = pc.steiner[0].0;
        let p = input.points[first as usize];
        assert!(p[0].abs() < 1e-9 && p[1].abs() < 1e-9, "{p:?}");
        // the pieces chain the two ends, and each is an edge of a grounded triangle on slot 0 of
        // a finite tet (checked here on the tets themselves)
        let tets: Vec<[u32; 4]> = dt.tets().map(|t| dt.tet_vertices(t)).collect();
        for q in &pc.pairs {
            let (u, v) = q.ends;
            assert!(
                tets.iter().any(|t| t.contains(&u)
                    && t.contains(&v)
                    && t.iter()
                        .filter(|&&w| input.mask[w as usize] & 1 != 0)
                        .count()
                        >= 3),
                "{:?} is not a grounded edge",
                q.ends
            );
        }
    }
}
