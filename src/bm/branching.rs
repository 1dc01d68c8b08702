//! Samples of the branching diagram on the cell's faces, the pragmatic iterative route of DESIGN.md.
//!
//! For a point a on face f (plane P, unit normal n into the cell) the maximal empty sphere tangent to
//! P at a touches first the site b minimising r_b(a) = |a − b|² / (2 h_b), h_b = n·(b − a) (a Moebius
//! diagram of the sites). The Delaunay triangulation carries it: the apex of the `Vf` tet standing on
//! a grounded triangle is that triangle's minimiser. Two neighbouring internal grounded triangles
//! whose apexes b1, b2 are *discontinuous* sites (no common plane, or a common plane on which the edge
//! b1b2 is external: different contours or far-apart parts of one) straddle the branching diagram;
//! we place a sample on their shared edge where r_b1 = r_b2 (a quadratic in the edge parameter).
//! The caller inserts the samples and re-triangulates, a few rounds, until none is found.
//! Samples are thinned: none closer than half the face's median contour edge to another sample or to
//! a contour vertex. Samples are linked into chains along the diagram (marching squares on the
//! sampling grid, see `grid_samples`), which the cell makes Delaunay edges (`chains`).
use super::cell_input::{CellInput, IdMap};
use super::chains::{same_branch, thin_chains, Chains, DiagramSample, Kind, SlotDiagram};
use super::classify::{Classifier, TetType};
use super::complex::{outward_face, Complex};
use super::cutting::Thinning;
use crate::sections::{dot, sub};

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d)
}

/// Per slot, the internal grounded triangles on it standing under a `Vf` tet, each (outward from
/// its tet) with that tet's apex, the vertex off the slot: the Delaunay picture of the Moebius
/// diagram. One pass over the tets, in tet order.
pub fn apex_triangles(
    input: &CellInput,
    cx: &Complex,
    ty: &[TetType],
    cl: &Classifier,
) -> Vec<Vec<([u32; 3], u32)>> {
    let mut out = vec![Vec::new(); input.slots.len()];
    for (t, tv) in cx.tets.iter().enumerate() {
        if ty[t] != TetType::Vf {
            continue;
        }
        for i in 0..4 {
            let f = outward_face(tv, i);
            let on = input.mask[f[0] as usize]
                & input.mask[f[1] as usize]
                & input.mask[f[2] as usize]
                & !input.mask[tv[i] as usize];
            if on == 0 || cl.triangle_external(f[0], f[1], f[2]) {
                continue;
            }
            for (s, list) in out.iter_mut().enumerate() {
                if on >> s & 1 == 1 {
                    list.push((f, tv[i]));
                }
            }
        }
    }
    out
}

/// The median length of slot `s`'s contour edges (0 without contour): the sampling density the
/// diagram samples are thinned to.
pub(super) fn contour_spacing(input: &CellInput, s: usize) -> f64 {
    let mut lens: Vec<f64> = input.slots[s]
        .contour_edges()
        .iter()
        .map(|&(a, b)| dist2(input.points[a as usize], input.points[b as usize]).sqrt())
        .collect();
    lens.sort_by(f64::total_cmp);
    if lens.is_empty() {
        0.0
    } else {
        lens[lens.len() / 2]
    }
}

/// Unit normal of slot `s`'s plane pointing into the cell (sites have positive height along it).
pub(super) fn into_cell_normal(input: &CellInput, s: usize) -> [f64; 3] {
    let slot = &input.slots[s];
    let n = slot.geom().normal;
    if slot.outward_is_plane_normal {
        [-n[0], -n[1], -n[2]]
    } else {
        n
    }
}

/// Branching samples of every slot of the cell, with their diagram identity (slot, site pair)
/// and chain links (see [`grid_samples`]). `apex` is [`apex_triangles`] of the same triangulation.
pub fn sample_chains(
    input: &CellInput,
    cl: &mut Classifier,
    apex: &[Vec<([u32; 3], u32)>],
) -> Chains {
    let mut out = Chains::default();
    for (s, slot) in input.slots.iter().enumerate() {
        let tri_apex = &apex[s];
        if tri_apex.is_empty() {
            continue;
        }
        let h = contour_spacing(input, s);
        let n = into_cell_normal(input, s);
        // edges → (triangle apexes)
        let mut by_edge: IdMap<(u32, u32), Vec<u32>> = IdMap::default();
        for &(f, apex) in tri_apex {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                by_edge.entry((a.min(b), a.max(b))).or_default().push(apex);
            }
        }
        // Does the Delaunay triangulation show a discontinuity of the apex map on this face?
        let mut discontinuous = false;
        for (&(p, q), apexes) in &by_edge {
            if apexes.len() != 2 || slot.contour_edges().contains(&(p, q)) {
                continue;
            }
            let (b1, b2) = (apexes[0], apexes[1]);
            if b1 == b2 {
                continue;
            }
            let common = input.mask[b1 as usize] & input.mask[b2 as usize];
            if common == 0 || cl.edge_external(b1, b2) {
                discontinuous = true;
                break;
            }
        }
        if !discontinuous || h <= 0.0 {
            continue;
        }
        out.extend(grid_samples(input, cl, s, n, h));
    }
    out
}

/// A site of slot `s`'s Moebius diagram: (local vertex, position, height h_b above the plane).
pub(super) type Site = (u32, [f64; 3], f64);

/// The sites of slot `s`'s Moebius diagram: the cell's section vertices off the slot (not the
/// cell-local samples) strictly on the cell's side of its plane (`n` into the cell).
pub(super) fn moebius_sites(input: &CellInput, s: usize, n: [f64; 3]) -> Vec<Site> {
    let bit = 1u128 << s;
    let origin = input.slots[s].geom().origin;
    (0..input.points.len() as u32)
        .filter(|&v| input.mask[v as usize] & bit == 0 && input.global[v as usize] != u32::MAX)
        .filter_map(|v| {
            let x = input.points[v as usize];
            let hb = dot(n, sub(x, origin));
            (hb > 0.0).then_some((v, x, hb))
        })
        .collect()
}

/// Sample the section on a grid of spacing `h`, find each grid point's minimiser of r_b, and on every
/// grid edge whose two minimisers are discontinuous place a point where r_b1 = r_b2 (bisection on the
/// segment). Two samples on edges of one grid square are consecutive when they are on the same
/// branch: their site pairs match up continuously (`chains::same_branch`; the sites are section
/// vertices and change from vertex to neighbouring vertex along a branch). Marching squares: a square
/// with two samples of a branch links them; a square with four, a saddle, links them so that the
/// corners whose minimiser is discontinuous with the centre's are cut off; a square with three (a
/// missing crossing) links none. The samples are thinned along these chains
/// (`chains::thin_chains`): points closer than h/2 to a contour vertex or to another sample are
/// dropped, their chain neighbours linked.
fn grid_samples(input: &CellInput, cl: &mut Classifier, s: usize, n: [f64; 3], h: f64) -> Chains {
    let slot = &input.slots[s];
    let bit = 1u128 << s;
    let diagram = SlotDiagram::new(input, s);
    let sites = &diagram.sites;
    if sites.len() < 2 {
        return Chains::default();
    }
    let on_face: Vec<u32> = (0..input.points.len() as u32)
        .filter(|&v| input.mask[v as usize] & bit != 0)
        .collect();
    let grid = SampleGrid::over(on_face.iter().map(|&v| slot.uv[v as usize]), h);
    let search = NearestSite {
        plane: *slot.geom(),
        n,
        sites,
        index: &diagram.index,
    };
    let minimiser = grid_minimisers(input, s, &grid, &search);
    let guard = super::guard::ContourGuard::of_slot(input, s, 0.5 * h);
    let mut thin = Thinning::guarded(0.5 * h, guard);
    for &v in &on_face {
        thin.occupy(slot.uv[v as usize]);
    }
    let (cands, on_edge) = edge_samples(input, cl, s, h, &grid, &search, &minimiser);
    // continuity of two sites (cached point location of the segment's midpoint)
    let mut cont = |a: u32, b: u32| {
        a == b || (input.mask[a as usize] & input.mask[b as usize] != 0 && !cl.edge_external(a, b))
    };
    let squares = squares_with_samples(&grid, &on_edge);
    let mut links: Vec<(u32, u32)> = Vec::new();
    for &(j, i) in &squares {
        link_square(
            (i, j),
            &grid,
            &search,
            &minimiser,
            &on_edge,
            &mut cont,
            &mut links,
        );
    }
    links.sort_unstable();
    links.dedup();
    thin_chains(cands, &links, &mut thin, |x, y| {
        diagram
            .between(input, x.uv, y.uv, x.sites, y.sites, &mut cont)
            .is_some()
    })
}

/// The sampling grid of a face: (nx + 1) × (ny + 1) points from `lo`, spacing (sx, sy).
struct SampleGrid {
    lo: [f64; 2],
    sx: f64,
    sy: f64,
    nx: usize,
    ny: usize,
}

impl SampleGrid {
    /// Over the bounding box of `uvs`, spacing about `h` (at most 400 steps a side).
    fn over(uvs: impl Iterator<Item = [f64; 2]>, h: f64) -> Self {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in uvs {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let nx = (((hi[0] - lo[0]) / h).ceil() as usize).clamp(1, 400);
        let ny = (((hi[1] - lo[1]) / h).ceil() as usize).clamp(1, 400);
        let (sx, sy) = ((hi[0] - lo[0]) / nx as f64, (hi[1] - lo[1]) / ny as f64);
        SampleGrid { lo, sx, sy, nx, ny }
    }

    fn at(&self, i: f64, j: f64) -> [f64; 2] {
        [self.lo[0] + self.sx * i, self.lo[1] + self.sy * j]
    }

    /// Points per grid row.
    fn width(&self) -> usize {
        self.nx + 1
    }
}

/// The minimiser of r_b over a face's sites.
struct NearestSite<'a> {
    plane: crate::sections::Plane,
    /// Unit normal into the cell.
    n: [f64; 3],
    sites: &'a [Site],
    index: &'a SiteIndex,
}

impl NearestSite<'_> {
    fn r(&self, a3: [f64; 3], site: &Site) -> f64 {
        // h_b measured from a (a is on the plane up to rounding)
        let hb = dot(self.n, sub(site.1, a3));
        if hb <= 0.0 {
            f64::INFINITY
        } else {
            dist2(a3, site.1) / (2.0 * hb)
        }
    }

    /// Same answer as a scan of all sites in order (smallest r, first site on ties), visiting only
    /// the sites whose in-plane distance can still beat the best r found (r_b(a) >= that distance).
    fn argmin(&self, q: [f64; 2]) -> usize {
        self.argmin_near(q, None)
    }

    /// [`NearestSite::argmin`] starting from `hint`'s r (the minimiser of a neighbouring grid
    /// point, usually this one's too): buckets whose bound exceeds it are skipped from the start.
    /// The same answer: every site with r up to the hint's is still visited.
    fn argmin_near(&self, q: [f64; 2], hint: Option<usize>) -> usize {
        let a3 = self.plane.to_3d(q);
        // a hint below the plane (r infinite) bounds nothing: the search starts as without one
        let mut best = (hint.map(|k| (self.r(a3, &self.sites[k]), k)))
            .filter(|b| b.0 < f64::INFINITY)
            .unwrap_or((f64::INFINITY, 0));
        self.index.visit_below(q, best.0, |k| {
            let v = self.r(a3, &self.sites[k]);
            if v < best.0 || (v == best.0 && v < f64::INFINITY && k < best.1) {
                best = (v, k);
            }
            best.0
        });
        best.1
    }
}

/// The minimiser of every grid point inside the section (row-major), `None` outside.
fn grid_minimisers(
    input: &CellInput,
    s: usize,
    grid: &SampleGrid,
    search: &NearestSite,
) -> Vec<Option<usize>> {
    let slot = &input.slots[s];
    let w = grid.width();
    let mut minimiser: Vec<Option<usize>> = vec![None; w * (grid.ny + 1)];
    for j in 0..=grid.ny {
        let row = slot.locator().row(grid.at(0.0, j as f64)[1]);
        for i in 0..=grid.nx {
            let q = grid.at(i as f64, j as f64);
            if row.locate(q[0]) == super::cell_input::Where::Inside {
                // the left or lower neighbour's minimiser bounds the search
                let hint = (i > 0)
                    .then(|| minimiser[j * w + i - 1])
                    .flatten()
                    .or_else(|| (j > 0).then(|| minimiser[(j - 1) * w + i]).flatten());
                minimiser[j * w + i] = Some(search.argmin_near(q, hint));
            }
        }
    }
    minimiser
}

/// Per grid edge (2 (j w + i) + {0: along x, 1: along y}) its candidate and the candidate's sites
/// (smaller first).
type EdgeSamples = IdMap<usize, (u32, (u32, u32))>;

/// The candidates in grid order, one on every grid edge whose minimisers are discontinuous and
/// change sign of r_b1 − r_b2 along it (`None` when too close to the section's boundary).
fn edge_samples(
    input: &CellInput,
    cl: &mut Classifier,
    s: usize,
    h: f64,
    grid: &SampleGrid,
    search: &NearestSite,
    minimiser: &[Option<usize>],
) -> (Vec<Option<DiagramSample>>, EdgeSamples) {
    let slot = &input.slots[s];
    let sites = search.sites;
    let (nx, ny, w) = (grid.nx, grid.ny, grid.width());
    let mut cands: Vec<Option<DiagramSample>> = Vec::new();
    let mut on_edge: EdgeSamples = IdMap::default();
    let mut pairs_checked: IdMap<(usize, usize), bool> = IdMap::default();
    for j in 0..=ny {
        for i in 0..=nx {
            let Some(m0) = minimiser[j * w + i] else {
                continue;
            };
            for (dir, (di, dj)) in [(1usize, 0usize), (0, 1)].into_iter().enumerate() {
                let (i1, j1) = (i + di, j + dj);
                if i1 > nx || j1 > ny {
                    continue;
                }
                let Some(m1) = minimiser[j1 * w + i1] else {
                    continue;
                };
                if m0 == m1 {
                    continue;
                }
                let key_pair = (m0.min(m1), m0.max(m1));
                let disc = *pairs_checked.entry(key_pair).or_insert_with(|| {
                    let (b1, b2) = (sites[m0].0, sites[m1].0);
                    let common = input.mask[b1 as usize] & input.mask[b2 as usize];
                    common == 0 || cl.edge_external(b1, b2)
                });
                if !disc {
                    continue;
                }
                let (q0, q1) = (grid.at(i as f64, j as f64), grid.at(i1 as f64, j1 as f64));
                let Some(q) = equal_r_point(search, q0, q1, m0, m1) else {
                    continue;
                };
                let inside = slot
                    .locator()
                    .locate_clear(q, super::chains::SAMPLE_CLEARANCE * h)
                    == super::cell_input::Where::Inside;
                let (b0, b1) = (sites[m0].0, sites[m1].0);
                on_edge.insert(
                    2 * (j * w + i) + dir,
                    (cands.len() as u32, (b0.min(b1), b0.max(b1))),
                );
                cands.push(inside.then(|| DiagramSample {
                    slot: s,
                    uv: q,
                    p3: search.plane.to_3d(q),
                    kind: Kind::Branching,
                    sites: (b0.min(b1), b0.max(b1)),
                }));
            }
        }
    }
    (cands, on_edge)
}

/// The point of segment q0q1 where r of site m0 equals r of site m1 (bisection), if r_m0 − r_m1
/// goes from ≤ 0 to ≥ 0 along it.
fn equal_r_point(
    search: &NearestSite,
    q0: [f64; 2],
    q1: [f64; 2],
    m0: usize,
    m1: usize,
) -> Option<[f64; 2]> {
    let f = |t: f64| {
        let q = [q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1])];
        let a3 = search.plane.to_3d(q);
        search.r(a3, &search.sites[m0]) - search.r(a3, &search.sites[m1])
    };
    let (mut a, mut b) = (0.0, 1.0);
    let fa = f(a);
    if !(fa <= 0.0 && f(b) >= 0.0) {
        return None;
    }
    for _ in 0..50 {
        let mid = 0.5 * (a + b);
        if f(mid) <= 0.0 {
            a = mid;
        } else {
            b = mid;
        }
    }
    let t = 0.5 * (a + b);
    Some([q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1])])
}

/// The grid squares (j, i) with a candidate on one of their edges, sorted.
fn squares_with_samples(grid: &SampleGrid, on_edge: &EdgeSamples) -> Vec<(usize, usize)> {
    let (nx, ny, w) = (grid.nx, grid.ny, grid.width());
    let mut squares: Vec<(usize, usize)> = Vec::new();
    for &e in on_edge.keys() {
        let (g, dir) = (e / 2, e % 2);
        let (i, j) = (g % w, g / w);
        if dir == 0 {
            if j < ny {
                squares.push((j, i));
            }
            if j > 0 {
                squares.push((j - 1, i));
            }
        } else {
            if i < nx {
                squares.push((j, i));
            }
            if i > 0 {
                squares.push((j, i - 1));
            }
        }
    }
    squares.sort_unstable();
    squares.dedup();
    squares
}

/// Marching squares on square (i, j): its candidates grouped by branch, two of a branch linked, a
/// saddle's four linked in two pairs (see `grid_samples`).
fn link_square(
    (i, j): (usize, usize),
    grid: &SampleGrid,
    search: &NearestSite,
    minimiser: &[Option<usize>],
    on_edge: &EdgeSamples,
    cont: &mut impl FnMut(u32, u32) -> bool,
    links: &mut Vec<(u32, u32)>,
) {
    let w = grid.width();
    let sites = search.sites;
    // bottom, right, top, left (counter-clockwise from the corner (i, j))
    let sides = [
        2 * (j * w + i),
        2 * (j * w + i + 1) + 1,
        2 * ((j + 1) * w + i),
        2 * (j * w + i) + 1,
    ];
    let found: Vec<(usize, u32, (u32, u32))> = sides
        .iter()
        .enumerate()
        .filter_map(|(k, e)| on_edge.get(e).map(|&(c, m)| (k, c, m)))
        .collect();
    if found.len() < 2 {
        return;
    }
    // group the square's samples by branch (site pairs that match up continuously)
    let mut group: Vec<usize> = (0..found.len()).collect();
    for a in 0..found.len() {
        for b in a + 1..found.len() {
            if group[b] == b && same_branch(found[a].2, found[b].2, cont) {
                group[b] = group[a];
            }
        }
    }
    for g0 in 0..found.len() {
        let g: Vec<(usize, u32)> = (0..found.len())
            .filter(|&k| group[k] == g0)
            .map(|k| (found[k].0, found[k].1))
            .collect();
        match g.len() {
            2 => links.push((g[0].1.min(g[1].1), g[0].1.max(g[1].1))),
            4 => {
                // saddle: the corners' minimisers alternate between the two sides; the
                // segments cut off the two corners not on the centre's side
                let (Some(mc), Some(m00)) = (
                    Some(search.argmin(grid.at(i as f64 + 0.5, j as f64 + 0.5))),
                    minimiser[j * w + i],
                ) else {
                    continue;
                };
                let corner_with_centre = cont(sites[mc].0, sites[m00].0);
                let by_side = |k: usize| g.iter().find(|x| x.0 == k).map(|x| x.1);
                let (Some(b), Some(rt), Some(t), Some(l)) =
                    (by_side(0), by_side(1), by_side(2), by_side(3))
                else {
                    continue;
                };
                let pairs = if !corner_with_centre {
                    // cut off corner (i, j) (bottom + left) and corner (i+1, j+1)
                    [(b, l), (rt, t)]
                } else {
                    // cut off corners (i+1, j) (bottom + right) and (i, j+1)
                    [(b, rt), (t, l)]
                };
                links.extend(pairs.iter().map(|&(x, y)| (x.min(y), x.max(y))));
            }
            _ => {}
        }
    }
}

/// The sites bucketed by their projection on the face's plane, for the minimiser search of r_b:
/// since |a − b|² = h_b² + d² (d the in-plane distance), r_b(a) = h_b / 2 + d² / (2 h_b), at least
/// `lower_bound(D, h range)` for a bucket at distance D whose sites' heights lie in that range; a
/// bucket whose bound exceeds the best r found so far cannot hold a better site.
pub(super) struct SiteIndex {
    lo: [f64; 2],
    cell: f64,
    nx: i64,
    ny: i64,
    /// Site indices per bucket (row-major), ascending.
    buckets: Vec<Vec<u32>>,
    /// Per bucket the range of the sites' heights above the plane, widened by `slack`.
    heights: Vec<(f64, f64)>,
    /// Range of all heights, widened by `slack`.
    all_heights: (f64, f64),
    /// Absolute slack on distances for rounding (coordinates' magnitude × 1e-9).
    slack: f64,
}

impl SiteIndex {
    pub(super) fn new(plane: &crate::sections::Plane, sites: &[Site]) -> SiteIndex {
        let uv: Vec<[f64; 2]> = sites.iter().map(|s| plane.to_2d(s.1)).collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut scale: f64 = 1.0;
        for (q, s) in uv.iter().zip(sites) {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
            scale =
                s.1.iter()
                    .chain(plane.origin.iter())
                    .fold(scale, |m, c| m.max(c.abs()));
        }
        let ext = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let per_axis = ((sites.len() as f64 / 2.0).sqrt().ceil() as i64).clamp(1, 256);
        let cell = if ext > 0.0 && ext.is_finite() {
            ext / per_axis as f64
        } else {
            1.0
        };
        let nx = (((hi[0] - lo[0]) / cell) as i64 + 1).clamp(1, 257);
        let ny = (((hi[1] - lo[1]) / cell) as i64 + 1).clamp(1, 257);
        let slack = 1e-9 * scale;
        let mut buckets = vec![Vec::new(); (nx * ny) as usize];
        let mut heights = vec![(f64::INFINITY, f64::NEG_INFINITY); (nx * ny) as usize];
        let mut all_heights = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, q) in uv.iter().enumerate() {
            let ix = (((q[0] - lo[0]) / cell) as i64).clamp(0, nx - 1);
            let iy = (((q[1] - lo[1]) / cell) as i64).clamp(0, ny - 1);
            let b = (iy * nx + ix) as usize;
            buckets[b].push(k as u32);
            let h = sites[k].2;
            heights[b] = (heights[b].0.min(h - slack), heights[b].1.max(h + slack));
            all_heights = (all_heights.0.min(h - slack), all_heights.1.max(h + slack));
        }
        SiteIndex {
            lo,
            cell,
            nx,
            ny,
            buckets,
            heights,
            all_heights,
            slack,
        }
    }

    /// Least value of h / 2 + d² / (2 h) over h in `hr` (h > 0), d ≥ `d` (shrunk by the slack),
    /// scaled down by 1e-9 for rounding.
    fn lower_bound(&self, d: f64, hr: (f64, f64)) -> f64 {
        let d = (d - self.slack).max(0.0);
        let h = d.clamp(hr.0, hr.1.max(hr.0));
        // h is never NaN here (finite slack and heights); h <= 0 only when d is 0
        if h <= 0.0 {
            return 0.0;
        }
        (0.5 * h + d * d / (2.0 * h)) * (1.0 - 1e-9)
    }

    /// Call `f(site)` for every site that may have r below the current best, ring by ring of buckets
    /// around `q`; `f` returns the best r so far.
    pub(super) fn visit(&self, q: [f64; 2], f: impl FnMut(usize) -> f64) {
        self.visit_below(q, f64::INFINITY, f)
    }

    /// [`SiteIndex::visit`] when a site with r = `start` is known: the buckets whose bound
    /// exceeds it are not visited.
    pub(super) fn visit_below(&self, q: [f64; 2], start: f64, mut f: impl FnMut(usize) -> f64) {
        let fx = ((q[0] - self.lo[0]) / self.cell).floor();
        let fy = ((q[1] - self.lo[1]) / self.cell).floor();
        // far outside the buckets (or not finite): plain scan
        if !(fx.abs() < 1e6 && fy.abs() < 1e6) {
            for k in self.buckets.iter().flatten() {
                f(*k as usize);
            }
            return;
        }
        let (cx, cy) = (fx as i64, fy as i64);
        // the farthest bucket is this many rings away
        let last = [cx, cx - (self.nx - 1), cy, cy - (self.ny - 1)]
            .iter()
            .map(|d| d.abs())
            .max()
            .unwrap_or(0);
        // rings nearer than this hold no bucket (q outside the grid): start there, or a query far
        // from tiny sites walks up to 10⁶ empty rings
        let first = [-cx, cx - (self.nx - 1), -cy, cy - (self.ny - 1)]
            .into_iter()
            .fold(0, i64::max);
        let mut best = start;
        let mut bucket = |x: i64, y: i64, best: &mut f64| {
            if x >= 0 && x < self.nx && y >= 0 && y < self.ny {
                let b = (y * self.nx + x) as usize;
                if self.buckets[b].is_empty() {
                    return;
                }
                // distance from q to the bucket's square
                let (bx, by) = (
                    self.lo[0] + x as f64 * self.cell,
                    self.lo[1] + y as f64 * self.cell,
                );
                let dx = (bx - q[0]).max(q[0] - bx - self.cell).max(0.0);
                let dy = (by - q[1]).max(q[1] - by - self.cell).max(0.0);
                if self.lower_bound((dx * dx + dy * dy).sqrt(), self.heights[b]) > *best {
                    return;
                }
                for &k in &self.buckets[b] {
                    *best = f(k as usize);
                }
            }
        };
        for ring in first..=last {
            // every point of a bucket in this ring is at least (ring - 1) buckets away from q
            let reach = (ring - 1).max(0) as f64 * self.cell;
            if self.lower_bound(reach, self.all_heights) > best {
                break;
            }
            if ring == 0 {
                bucket(cx, cy, &mut best);
                continue;
            }
            let (x0, x1) = ((cx - ring).max(0), (cx + ring).min(self.nx - 1));
            for y in [cy - ring, cy + ring] {
                for x in x0..=x1 {
                    bucket(x, y, &mut best);
                }
            }
            let (y0, y1) = ((cy - ring + 1).max(0), (cy + ring - 1).min(self.ny - 1));
            for y in y0..=y1 {
                bucket(cx - ring, y, &mut best);
                bucket(cx + ring, y, &mut best);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// r_b(a) of a site over the plane z = 0 at the in-plane point `q`.
    fn r(site: &Site, q: [f64; 2]) -> f64 {
        let a = [q[0], q[1], 0.0];
        dist2(a, site.1) / (2.0 * site.2)
    }

    /// A search started from any site's r (a neighbour's minimiser, which may even be a site
    /// below the plane, r infinite) finds what the search from nothing finds, and what a scan of
    /// all sites finds (smallest r, first site on ties): sites on a coarse lattice, so that
    /// equal r are common.
    #[test]
    fn a_search_started_from_a_hint_finds_the_same_minimiser() {
        let plane = crate::sections::Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let mut x = 7u64;
        let mut next = |m: u64| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 33) % m
        };
        let sites: Vec<Site> = (0..300u32)
            .map(|k| {
                let (px, py) = (next(20) as f64 * 0.05, next(20) as f64 * 0.05);
                // a few below the plane (r infinite from above)
                let h = if k % 37 == 0 {
                    -0.1
                } else {
                    0.05 * (1 + next(4)) as f64
                };
                (k, [px, py, h], h)
            })
            .collect();
        let index = SiteIndex::new(&plane, &sites);
        let search = NearestSite {
            plane,
            n: [0.0, 0.0, 1.0],
            sites: &sites,
            index: &index,
        };
        for _ in 0..2000 {
            let q3 = [next(41) as f64 * 0.025, next(41) as f64 * 0.025, 0.0];
            let q = plane.to_2d(q3);
            let scan = (0..sites.len())
                .map(|k| (search.r(q3, &sites[k]), k))
                .fold((f64::INFINITY, 0), |m, x| if x.0 < m.0 { x } else { m });
            let plain = search.argmin(q);
            assert_eq!(plain, scan.1, "at {q:?}");
            let hint = next(sites.len() as u64) as usize;
            assert_eq!(
                search.argmin_near(q, Some(hint)),
                plain,
                "at {q:?} from {hint}"
            );
            assert_eq!(search.argmin_near(q, Some(plain)), plain, "at {q:?}");
        }
    }

    /// Sites in a 2e-5 square, queries up to 1 away (odd076: a tiny contour beside a large section;
    /// every query walked up to 10⁶ empty rings of buckets before reaching the sites, 2 minutes
    /// in one cell): the index finds the scan's minimiser, and 40,000 far queries take well under
    /// a second.
    #[test]
    fn far_queries_find_the_nearest_site_without_walking_empty_rings() {
        let plane = crate::sections::Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let sites: Vec<Site> = (0..64u32)
            .map(|k| {
                let (x, y) = ((k % 8) as f64 * 2.5e-6, (k / 8) as f64 * 2.5e-6);
                let h = 1e-6 * (1.0 + (k % 5) as f64);
                (k, [0.3 + x, 0.2 + y, h], h)
            })
            .collect();
        let index = SiteIndex::new(&plane, &sites);
        let start = std::time::Instant::now();
        for i in 0..200 {
            for j in 0..200 {
                let q2 = [-0.5 + i as f64 / 199.0, -0.5 + j as f64 / 199.0];
                let q = plane.to_2d([q2[0], q2[1], 0.0]);
                let mut best = (f64::INFINITY, usize::MAX);
                index.visit(q, |k| {
                    let v = r(&sites[k], q2);
                    if v < best.0 || (v == best.0 && k < best.1) {
                        best = (v, k);
                    }
                    best.0
                });
                let scan = (0..sites.len()).map(|k| (r(&sites[k], q2), k)).fold(
                    (f64::INFINITY, usize::MAX),
                    |m, x| if x.0 < m.0 { x } else { m },
                );
                assert_eq!(best.1, scan.1, "at {q2:?}");
            }
        }
        let secs = start.elapsed().as_secs_f64();
        assert!(secs < 2.0, "40,000 far queries took {secs} s");
    }
}
