//! The collar: near every cutting plane the solid is the prism over its section.
//!
//! The pruned complex K meets a plane in exactly its section, but just off the plane its section is
//! the radial image of the links of K's vertices on the plane. Where such a link folds back (a
//! crease where two branches part at a cutting-diagram chain, the crevice between two slabs, a fan
//! whose edges zig-zag in angle), the section a hair off the plane is a tangle of loops at that scale
//! instead of the contour, and whatever a user computes there (a slice, a voxel, a dose grid) sees it.
//!
//! Per cell C, K's tetrahedra in C are mapped by a homothety φ_C (centre c_C, the volume centroid
//! of C's triangulation, ratio s_C < 1), and the shell between ∂C and φ_C(∂C) is filled over every
//! kept section triangle t by the prism (t, φ_C(t)), split into three tetrahedra by the global order
//! of t's vertices (two prisms sharing an edge then share its wall's diagonal). A homothety keeps
//! orientation and maps the convex C into itself, so K stays a conforming, embedded complex; points
//! on the planes do not move, so the sections stay exact; and every section within the collar's
//! height of a plane is the section itself, shrunk by less than that height about c_C. What touched
//! a plane at an edge or a vertex only (no section triangle) lifts off it by the collar's height.
//!
//! Cells are the classes of K's triangulation T under "shares a face not on a plane, or a vertex on
//! no plane" (within a cell, T is connected through such faces; between cells every face is on one).
//! A cell whose image fails the checks (a rounded tetrahedron flipped, a point on the wrong side of
//! one of its planes) keeps K as it was, and is counted.
use super::complex::outward_face;
use super::refine::{common_plane, key3, Planes, Triangulation};
use crate::arrangement::ArrPlane;
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::geom::predicates::orient3d;
use crate::sections::{dot, sub};
use petgraph::unionfind::UnionFind;
use rayon::prelude::*;
use smallvec::SmallVec;

mod affine;

/// Largest shrink 1 − s_C: a cell whose solid lies within `height / 0.05` of one of its section
/// planes gets a thinner collar rather than a homothety that moves its far side much.
pub const MAX_SHRINK: f64 = 0.05;

/// Least ratio of a collar's height to the farthest move of its cell's map.
pub const MIN_STEEPNESS: f64 = 0.1;

/// Farthest a homothety may move a point, in collar heights: where a cell is much wider than
/// deep (a slab between two oblique planes), its collar gets thinner instead.
pub const MAX_SHIFT_PER_HEIGHT: f64 = 10.0;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CollarStats {
    /// Cells whose tetrahedra were mapped and given prisms.
    pub cells: u64,
    /// Cells whose image failed a check and kept K as it was.
    pub cells_refused: u64,
    /// Of those, the cells no map could lift by the full height (`too_sharp`), not tried.
    pub cells_too_sharp: u64,
    /// Cells whose collar would have made ∂K singular and kept K as it was.
    pub cells_left_singular: u64,
    /// Section triangles given a prism (three tetrahedra each).
    pub prisms: u64,
    /// Thinnest collar (the height of a prism over its base plane).
    pub min_height: f64,
    /// Largest distance a point of K moved.
    pub max_shift: f64,
    /// Time taken.
    pub seconds: f64,
}

/// The cell class of every tetrahedron of `tets` (the roots of a union-find): tetrahedra meet
/// across faces on no common plane and at vertices on no plane. Faces are grouped by the bucketed
/// face table (no hash map of the whole complex's faces); a face of more than two tetrahedra joins
/// them in pairs in index order.
fn cell_classes(tets: &[[u32; 4]], planes: &[Planes]) -> Vec<usize> {
    let mut uf = UnionFind::<usize>::new(tets.len());
    let faces = super::faces::FaceTable::new(tets);
    faces.for_each_face(|codes| {
        let (t, i) = ((codes[0] >> 2) as usize, (codes[0] & 3) as usize);
        if codes.len() < 2 || common_plane(planes, outward_face(&tets[t], i)).is_some() {
            return;
        }
        for pair in codes.chunks_exact(2) {
            uf.union((pair[0] >> 2) as usize, (pair[1] >> 2) as usize);
        }
    });
    let mut inner_vertex = vec![usize::MAX; planes.len()];
    for (i, t) in tets.iter().enumerate() {
        for &v in t {
            if planes[v as usize].is_empty() {
                let o = &mut inner_vertex[v as usize];
                if *o == usize::MAX {
                    *o = i;
                }
                uf.union(i, *o);
            }
        }
    }
    (0..tets.len()).map(|i| uf.find_mut(i)).collect()
}

/// One cell's part of K: its kept tetrahedra (indices into K), the section triangles on its
/// faces (oriented out of it, with their plane), and the volume centroid of its triangulation.
#[derive(Default)]
struct CellPart {
    kept: Vec<usize>,
    bases: Vec<([u32; 3], u32)>,
    moment: [f64; 3],
    volume: f64,
}

impl CellPart {
    /// The volume centroid of the cell's triangulation: strictly inside the convex cell.
    fn centre(&self) -> [f64; 3] {
        self.moment.map(|m| m / self.volume)
    }
}

/// The cells of K's triangulation with a section triangle on a face. Every section triangle
/// gets a prism on each side whose cell has volume, kept from that side or not: the collar is
/// the section thickened, and K's tetrahedra on its faces stand on the prisms' tops.
fn cell_parts(k: &Triangulation) -> Vec<CellPart> {
    let all: Vec<[u32; 4]> = k
        .kept
        .iter()
        .chain(k.fillable.iter())
        .chain(k.external.iter())
        .copied()
        .collect();
    let class = cell_classes(&all, k.planes);
    let mut index: FxHashMap<usize, usize> = FxHashMap::default();
    let mut parts: Vec<CellPart> = Vec::new();
    let mut part_of = |root: usize, parts: &mut Vec<CellPart>| {
        *index.entry(root).or_insert_with(|| {
            parts.push(CellPart::default());
            parts.len() - 1
        })
    };
    // per tetrahedron in parallel, its section faces, volume and moment; summed in order after
    let shares: Vec<TetShare> = (all.par_iter().enumerate())
        .map(|(i, t)| tet_share(k, t, i < k.kept.len()))
        .collect();
    for (i, share) in shares.into_iter().enumerate() {
        let p = part_of(class[i], &mut parts);
        if i < k.kept.len() {
            parts[p].kept.push(i);
        }
        parts[p].bases.extend(share.bases);
        for (m, x) in parts[p].moment.iter_mut().zip(share.moment) {
            *m += x;
        }
        parts[p].volume += share.volume;
    }
    for part in &mut parts {
        part.bases.sort_unstable_by_key(|b| key3(b.0));
        part.bases.dedup_by_key(|b| key3(b.0));
    }
    parts
}

/// One tetrahedron's part in its cell's [`CellPart`].
struct TetShare {
    bases: SmallVec<[([u32; 3], u32); 1]>,
    moment: [f64; 3],
    volume: f64,
}

/// Tetrahedron `t`'s faces on a plane (a kept one's all, another's those on a section) and its
/// volume and moment.
fn tet_share(k: &Triangulation, t: &[u32; 4], kept: bool) -> TetShare {
    let mut bases = SmallVec::new();
    for j in 0..4 {
        let f = outward_face(t, j);
        if let Some(plane) = common_plane(k.planes, f) {
            if kept || k.internal.contains(&key3(f)) {
                bases.push((f, plane));
            }
        }
    }
    let x = t.map(|v| k.positions[v as usize]);
    let volume = orient3d(x[0], x[1], x[2], x[3]).abs();
    let moment = std::array::from_fn(|d| volume * (x[0][d] + x[1][d] + x[2][d] + x[3][d]) / 4.0);
    TetShare {
        bases,
        moment,
        volume,
    }
}

fn signed_distance(plane: &ArrPlane, x: [f64; 3]) -> f64 {
    plane.plane.signed_distance(x)
}

/// A cell's collar, checked but not yet applied: the images of its points, its mapped
/// tetrahedra and prisms in cell-local ids (`fresh_id` for images that are new points).
struct CellCollar {
    /// (vertex of K, its image: a new point where the vertex is `on_plane`, else its new place).
    images: Vec<(u32, [f64; 3])>,
    tets: Vec<[u32; 4]>,
    prisms: Vec<[u32; 4]>,
    height: f64,
    shift: f64,
}

/// An affine map x ↦ x + t + G(x − c) of a cell into itself (G small, so that I + G keeps
/// orientation).
#[derive(Clone, Copy, Debug)]
struct Contraction {
    c: [f64; 3],
    t: [f64; 3],
    g: [[f64; 3]; 3],
}

impl Contraction {
    fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        let d = [0, 1, 2].map(|i| x[i] - self.c[i]);
        [0, 1, 2].map(|i| x[i] + self.t[i] + (0..3).map(|j| self.g[i][j] * d[j]).sum::<f64>())
    }
}

/// The contractions to try for a cell, least distorting first: a squeeze along the mean normal
/// of its section planes (on parallel planes it moves every point by at most the collar height;
/// on oblique ones it may fail the checks), then a homothety (uniform height on every face, but
/// it moves far points more: its shrink is capped so that no point moves more than `max_shift`).
fn contractions(
    k: &Triangulation,
    part: &CellPart,
    arr_planes: &[ArrPlane],
    height: f64,
    max_shift: f64,
) -> Vec<Contraction> {
    let c = part.centre();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    let mut nearest = f64::INFINITY;
    for &(_, p) in &part.bases {
        let plane = &arr_planes[p as usize].plane;
        nearest = nearest.min(plane.signed_distance(c).abs());
        let n = plane.normal;
        let n = match normals.first() {
            Some(&m) if dot(n, m) < 0.0 => n.map(|x| -x),
            _ => n,
        };
        normals.push(n);
    }
    if nearest.is_nan() || nearest <= 0.0 {
        return Vec::new();
    }
    let mut mean = [0.0; 3];
    for n in &normals {
        for i in 0..3 {
            mean[i] += n[i];
        }
    }
    let len = dot(mean, mean).sqrt();
    let mut out = Vec::new();
    let shrink = (height / nearest).min(MAX_SHRINK);
    if len > 0.0 {
        let m = mean.map(|x| x / len);
        let along = normals.iter().map(|&n| dot(n, m).abs()).fold(1.0, f64::min);
        if along > 0.5 {
            let a = shrink / along;
            out.push(Contraction {
                c,
                t: [0.0; 3],
                g: [0, 1, 2].map(|i| [0, 1, 2].map(|j| -a * m[i] * m[j])),
            });
        }
    }
    let reach = part
        .kept
        .iter()
        .flat_map(|&i| k.kept[i])
        .map(|v| dist(k.positions[v as usize], c))
        .fold(0.0, f64::max);
    let shrink = if reach > 0.0 {
        shrink.min(max_shift / reach)
    } else {
        shrink
    };
    out.push(Contraction {
        c,
        t: [0.0; 3],
        g: [0, 1, 2].map(|i| [0, 1, 2].map(|j| if i == j { -shrink } else { 0.0 })),
    });
    out
}

/// The cell's collar: the first cheap candidate that lifts by the full height within
/// `max_shift`, else the best of all (the highest collar up to `height`, then the smallest move).
fn best_collar(
    k: &Triangulation,
    part: &CellPart,
    arr_planes: &[ArrPlane],
    height: f64,
    max_shift: f64,
) -> Option<CellCollar> {
    let key = |cc: &CellCollar| {
        let lift = (cc.height.min(height) / height * 100.0).floor();
        (-lift, cc.shift)
    };
    // the full height within the allowed move: the linear program would only move points less
    let good = |cc: &CellCollar| cc.height >= 0.99 * height && cc.shift <= max_shift;
    let better = |a: Option<CellCollar>, b: CellCollar| match a {
        Some(a) if key(&a) <= key(&b) => Some(a),
        _ => Some(b),
    };
    let mut best: Option<CellCollar> = None;
    for phi in contractions(k, part, arr_planes, height, max_shift) {
        if let Ok(cc) = cell_collar(k, part, arr_planes, phi) {
            if good(&cc) {
                return Some(cc);
            }
            best = better(best, cc);
        }
    }
    if let Some(phi) = affine::best_affine(k, part, arr_planes, height, max_shift) {
        if let Ok(cc) = cell_collar(k, part, arr_planes, phi) {
            best = better(best, cc);
        }
    }
    // a collar whose points move far along the plane and little off it has walls nearly in the
    // plane, folded onto their neighbours (a double sheet): the cell keeps its solid
    best.filter(|cc| cc.height >= MIN_STEEPNESS * cc.shift)
}

/// Whether no map of the cell can pass the steepness check: a vertex of base triangles on two
/// planes whose inward normals make an angle α with cos(α/2) < `MIN_STEEPNESS`. Its image w must
/// lie `height` off both planes, so |w| ≥ height / cos(α/2): the move alone exceeds
/// height / `MIN_STEEPNESS`, whatever the map. On a freehand sweep, frames crossing inside the box
/// at a few degrees make most cells so (Elephant, 300 frames: 7,744 of 9,744), and skipping their
/// linear programs changes no result.
fn too_sharp(part: &CellPart, arr_planes: &[ArrPlane]) -> bool {
    let c = part.centre();
    let inward = |p: u32| {
        let plane = &arr_planes[p as usize].plane;
        let s = plane.signed_distance(c).signum();
        plane.normal.map(|x| s * x)
    };
    // (vertex, plane) of every base corner; a vertex with two planes is on both planes' bases
    let mut corners: Vec<(u32, u32)> = (part.bases.iter())
        .flat_map(|&(f, p)| f.map(|v| (v, p)))
        .collect();
    corners.sort_unstable();
    corners.dedup();
    // cos²(α/2) = (1 + cos α) / 2, with a margin for the rounding of the normals
    let limit = 2.0 * MIN_STEEPNESS * MIN_STEEPNESS * (1.0 - 1e-6) - 1.0;
    corners.chunk_by(|a, b| a.0 == b.0).any(|run| {
        run.iter()
            .enumerate()
            .any(|(i, a)| (run[i + 1..].iter()).any(|b| dot(inward(a.1), inward(b.1)) < limit))
    })
}

/// The collar of one cell under `phi`, or `Err` where a check fails.
fn cell_collar(
    k: &Triangulation,
    part: &CellPart,
    arr_planes: &[ArrPlane],
    phi: Contraction,
) -> Result<CellCollar, ()> {
    let c = phi.c;
    let bases = &part.bases;
    let phi = |x: [f64; 3]| phi.apply(x);
    // images: local ids are K's ids for points on no plane, and `fresh_id`s otherwise, resolved
    // when applied
    let mut image: FxHashMap<u32, u32> = FxHashMap::default();
    let mut images: Vec<(u32, [f64; 3])> = Vec::new();
    let mut local_pos: FxHashMap<u32, [f64; 3]> = FxHashMap::default();
    let mut shift = 0.0f64;
    let mut map_vertex = |v: u32| -> u32 {
        *image.entry(v).or_insert_with(|| {
            let x = k.positions[v as usize];
            let y = phi(x);
            shift = shift.max(dist(x, y));
            let id = if on_plane(k, v) {
                fresh_id(images.len())
            } else {
                v
            };
            images.push((v, y));
            local_pos.insert(id, y);
            id
        })
    };
    let tets: Vec<[u32; 4]> = part
        .kept
        .iter()
        .map(|&i| k.kept[i].map(&mut map_vertex))
        .collect();
    let mut prisms = Vec::with_capacity(3 * bases.len());
    for &(f, _) in bases {
        prisms.extend(prism(f, &mut map_vertex));
    }
    // a point on no plane is only ever seen mapped; a point on a plane keeps its place as a base
    let pos = |v: u32| {
        local_pos
            .get(&v)
            .copied()
            .unwrap_or_else(|| k.positions[v as usize])
    };
    let orient = |t: &[u32; 4]| orient3d(pos(t[0]), pos(t[1]), pos(t[2]), pos(t[3]));
    if tets.iter().any(|t| orient(t) <= 0.0) {
        return Err(());
    }
    if prisms.iter().any(|t| orient(t) <= 0.0) {
        return Err(());
    }
    if !stays_in_cell(k, &images, arr_planes, c, shift) {
        return Err(());
    }
    let height = bases
        .iter()
        .flat_map(|&(f, p)| f.map(|v| (v, p)))
        .map(|(v, p)| {
            let y = pos(image[&v]);
            signed_distance(&arr_planes[p as usize], y).abs()
        })
        .fold(f64::INFINITY, f64::min);
    Ok(CellCollar {
        images,
        tets,
        prisms,
        height,
        shift,
    })
}

/// Whether every image lies strictly on the same side of every plane as its point (as the
/// cell's centre, for a point on the plane): the map keeps each cell's solid inside the cell.
/// Only planes within `shift` of the points' bounding box can be crossed.
fn stays_in_cell(
    k: &Triangulation,
    images: &[(u32, [f64; 3])],
    arr_planes: &[ArrPlane],
    c: [f64; 3],
    shift: f64,
) -> bool {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &(v, _) in images {
        let x = k.positions[v as usize];
        for i in 0..3 {
            lo[i] = lo[i].min(x[i] - shift);
            hi[i] = hi[i].max(x[i] + shift);
        }
    }
    // a plane farther from the box's centre than its half diagonal misses the box (one distance
    // instead of eight: the arrangement of a dense sweep has a thousand planes, most far away)
    let mid = [0, 1, 2].map(|i| 0.5 * (lo[i] + hi[i]));
    let radius = 0.5 * dist(lo, hi);
    arr_planes.iter().enumerate().all(|(p, plane)| {
        if signed_distance(plane, mid).abs() > radius * (1.0 + 1e-9) {
            return true;
        }
        let corner = |m: usize| [0, 1, 2].map(|i| if m >> i & 1 == 0 { lo[i] } else { hi[i] });
        let sides = (0..8).map(|m| signed_distance(plane, corner(m)));
        let (min, max) = sides.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
            (a.min(d), b.max(d))
        });
        if min > 0.0 || max < 0.0 {
            return true;
        }
        let centre = signed_distance(plane, c);
        images.iter().all(|&(v, y)| {
            let side = if k.planes[v as usize].contains(&(p as u32)) {
                centre
            } else {
                signed_distance(plane, k.positions[v as usize])
            };
            signed_distance(plane, y) * side > 0.0
        })
    })
}

/// The three tetrahedra of the prism between the section triangle `f` (oriented out of the cell)
/// and its image, positively oriented where the prism is convex. The wall over an edge (a, b),
/// a < b, gets the diagonal from a to b's image whichever prism it belongs to, so the prisms
/// of two triangles sharing an edge share their wall's triangles.
fn prism(f: [u32; 3], mut top: impl FnMut(u32) -> u32) -> [[u32; 4]; 3] {
    let mut base = f;
    base.sort_unstable();
    // sorting by an odd permutation reverses the base's orientation
    let odd = base != f && base != [f[1], f[2], f[0]] && base != [f[2], f[0], f[1]];
    let [x, y, z] = base;
    let [xt, yt, zt] = base.map(&mut top);
    let mut tets = [[x, y, z, zt], [x, yt, y, zt], [x, xt, yt, zt]];
    if odd {
        for t in &mut tets {
            t.swap(0, 1);
        }
    }
    tets
}

/// A point on a plane keeps its place (as a prism's base) and its image is a new point; a point on
/// no plane lies in one cell only and moves.
fn on_plane(k: &Triangulation, v: u32) -> bool {
    !k.planes[v as usize].is_empty()
}

/// The cell-local id of the `n`-th image while it is not yet a point of K: far above K's ids.
fn fresh_id(n: usize) -> u32 {
    u32::MAX - 1 - n as u32
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// K with some cells' collars applied: positions (old ones moved, new ones appended), tetrahedra,
/// and per tetrahedron the part it came from (`None`: a cell left as it was).
struct Applied {
    positions: Vec<[f64; 3]>,
    /// Per point appended (after K's), the point on a plane whose image it is.
    lifted_from: Vec<u32>,
    kept: Vec<[u32; 4]>,
    part: Vec<Option<usize>>,
}

fn apply(k: &Triangulation, parts: &[CellPart], collars: &[Option<CellCollar>]) -> Applied {
    let mut out = Applied {
        positions: k.positions.clone(),
        lifted_from: Vec::new(),
        kept: Vec::with_capacity(k.kept.len() * 2),
        part: Vec::with_capacity(k.kept.len() * 2),
    };
    let mut mapped = vec![false; k.kept.len()];
    for (p, (part, cc)) in parts.iter().zip(collars).enumerate() {
        let Some(cc) = cc else { continue };
        let mut fresh: FxHashMap<u32, u32> = FxHashMap::default();
        for (n, &(v, y)) in cc.images.iter().enumerate() {
            if on_plane(k, v) {
                out.positions.push(y);
                out.lifted_from.push(v);
                fresh.insert(fresh_id(n), (out.positions.len() - 1) as u32);
            } else {
                out.positions[v as usize] = y;
            }
        }
        let resolve = |t: &[u32; 4]| t.map(|v| *fresh.get(&v).unwrap_or(&v));
        let before = out.kept.len();
        out.kept
            .extend(cc.tets.iter().chain(&cc.prisms).map(resolve));
        out.part
            .resize(out.part.len() + out.kept.len() - before, Some(p));
        for &i in &part.kept {
            mapped[i] = true;
        }
    }
    for (t, _) in k.kept.iter().zip(&mapped).filter(|(_, &m)| !m) {
        out.kept.push(*t);
        out.part.push(None);
    }
    out
}

/// K with its collar: ∂K and its singular simplices, and per point the collar appended (after
/// K's), the point on a plane whose image it is.
pub struct Collared {
    pub boundary: Vec<[u32; 3]>,
    pub singular: super::assembly::Sets,
    pub lifted_from: Vec<u32>,
}

/// What became of a cell's collar.
enum Tried {
    /// No volume or no section triangle on its faces: nothing to try.
    Not,
    /// Two of its section planes meet at a base vertex too sharply (`too_sharp`).
    TooSharp,
    /// Every candidate map failed a check.
    Refused,
    Collar(CellCollar),
}

/// Most rounds of leaving out the collars of cells at singular simplices.
const SINGULAR_ROUNDS: usize = 4;

/// Give K its collar of `height` (absolute), moving no point more than `max_shift` where the
/// cell's planes are not parallel. The last change to K: the unkept lists are emptied.
///
/// A collar over every section triangle can meet the cell's solid where it touched the plane at an
/// edge or a vertex only, and make that edge or vertex singular. So the result is checked: where
/// ∂K has more singular simplices than without the collar, the cells at them keep their solid as it
/// was (their neighbours' collars stay), for a few rounds, and otherwise no cell gets a collar.
/// With the stats, ∂K when the collar was applied (`assembly::boundary_of` of the new K) and, per
/// point it appended (after K's), the point on a plane whose image it is.
pub fn build(
    k: &mut Triangulation,
    arr_planes: &[ArrPlane],
    height: f64,
    max_shift: f64,
) -> (CollarStats, Option<Collared>) {
    let mut stats = CollarStats::default();
    let parts = cell_parts(k);
    // cells are independent: their collars are found in parallel, beside ∂K's singular count
    let (found, (e0, v0)): (Vec<Tried>, _) = rayon::join(
        || {
            parts
                .par_iter()
                .map(|part| {
                    if part.volume <= 0.0 || part.bases.is_empty() {
                        return Tried::Not;
                    }
                    if too_sharp(part, arr_planes) {
                        return Tried::TooSharp;
                    }
                    match best_collar(k, part, arr_planes, height, max_shift) {
                        Some(cc) => Tried::Collar(cc),
                        None => Tried::Refused,
                    }
                })
                .collect()
        },
        || {
            let (e, v) = super::assembly::singular_sets(k.kept);
            (e.len() as u64, v.len() as u64)
        },
    );
    stats.cells_too_sharp = found
        .iter()
        .filter(|f| matches!(f, Tried::TooSharp))
        .count() as u64;
    stats.cells_refused =
        stats.cells_too_sharp + found.iter().filter(|f| matches!(f, Tried::Refused)).count() as u64;
    let mut collars: Vec<Option<CellCollar>> = (found.into_iter())
        .map(|f| match f {
            Tried::Collar(cc) => Some(cc),
            _ => None,
        })
        .collect();
    let allowed = e0 + v0;
    let mut applied = None;
    for _ in 0..SINGULAR_ROUNDS {
        let a = apply(k, &parts, &collars);
        let boundary = super::assembly::boundary_of(&a.kept);
        let (e, v) = super::fill::singular_simplices(&boundary);
        if (e.len() + v.len()) as u64 <= allowed {
            applied = Some((a, boundary, (e, v)));
            break;
        }
        let at: FxHashSet<u32> = e.iter().flat_map(|&(x, y)| [x, y]).chain(v).collect();
        for (t, p) in a.kept.iter().zip(&a.part) {
            if let Some(p) = p {
                if t.iter().any(|v| at.contains(v)) && collars[*p].take().is_some() {
                    stats.cells_left_singular += 1;
                }
            }
        }
    }
    k.fillable.clear();
    k.external.clear();
    let Some((a, boundary, singular)) = applied else {
        stats.cells_left_singular += collars.iter().flatten().count() as u64;
        return (stats, None);
    };
    for cc in collars.iter().flatten() {
        stats.cells += 1;
        stats.prisms += cc.prisms.len() as u64 / 3;
        stats.min_height = if stats.cells == 1 {
            cc.height
        } else {
            stats.min_height.min(cc.height)
        };
        stats.max_shift = stats.max_shift.max(cc.shift);
    }
    k.planes.resize(a.positions.len(), Planes::new());
    *k.positions = a.positions;
    *k.kept = a.kept;
    let collared = Collared {
        boundary,
        singular,
        lifted_from: a.lifted_from,
    };
    (stats, Some(collared))
}

#[cfg(test)]
mod tests {
    use super::super::refine::test_support::orient;
    use super::*;

    /// A base triangle on z = 0 whose cell lies above (outward: facing down), in every vertex
    /// order: the three tetrahedra are positive, fill the prism, and two prisms sharing an edge
    /// split its wall alike.
    /// Two section planes through the x axis at a dihedral angle, a cell between them whose
    /// volume centroid is at `centre`, and base triangles on both planes sharing vertex 0.
    fn wedge(angle_degrees: f64, shared: bool) -> (CellPart, Vec<ArrPlane>) {
        let a = angle_degrees.to_radians();
        let plane = |n: [f64; 3]| ArrPlane {
            plane: crate::sections::Plane::from_equation(n, 0.0).unwrap(),
            section: Some(0),
        };
        // z = 0 and the plane through the x axis turned by `a` from it
        let planes = vec![plane([0.0, 0.0, 1.0]), plane([0.0, -a.sin(), a.cos()])];
        let mid = 0.5 * a;
        let part = CellPart {
            kept: Vec::new(),
            bases: vec![([0, 1, 2], 0), ([if shared { 0 } else { 3 }, 4, 5], 1)],
            moment: [0.0, mid.cos(), mid.sin()],
            volume: 1.0,
        };
        (part, planes)
    }

    /// A vertex on two planes 10° apart cannot be lifted a collar height off both within ten
    /// heights (cos 85° < 0.1); at 12° it can, and so can two planes that share no vertex.
    #[test]
    fn a_vertex_on_two_planes_at_a_sharp_angle_refuses_the_cell() {
        let (part, planes) = wedge(10.0, true);
        assert!(too_sharp(&part, &planes));
        let (part, planes) = wedge(12.0, true);
        assert!(!too_sharp(&part, &planes));
        let (part, planes) = wedge(10.0, false);
        assert!(!too_sharp(&part, &planes));
    }

    #[test]
    fn prisms_are_positive_and_share_walls() {
        // 0..3 base, 3..6 their tops at z = 1, 6 a fourth base point, 7 its top
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
        ];
        let top = |v: u32| if v == 6 { 7 } else { v + 3 };
        // outward (seen from below, clockwise from above): 0, 2, 1 and its rotations
        for f in [[0, 2, 1], [2, 1, 0], [1, 0, 2]] {
            let tets = prism(f, top);
            let volume: f64 = tets.iter().map(|&t| orient(&p, t)).sum();
            assert!(tets.iter().all(|&t| orient(&p, t) > 0.0), "{f:?}: {tets:?}");
            // robust's orient3d is six times the volume: the prism holds 1/2
            assert!((volume - 3.0).abs() < 1e-12, "{f:?}: {volume}");
        }
        let a = prism([0, 2, 1], top);
        let b = prism([1, 2, 6], top);
        let walls = |tets: &[[u32; 4]; 3]| {
            let mut w: Vec<[u32; 3]> = tets
                .iter()
                .flat_map(|t| (0..4).map(move |i| key3(outward_face(t, i))))
                .filter(|f| {
                    f.iter()
                        .filter(|&&v| v == 1 || v == 2 || v == 4 || v == 5)
                        .count()
                        == 3
                })
                .collect();
            w.sort_unstable();
            w
        };
        assert_eq!(walls(&a), walls(&b));
        assert_eq!(walls(&a).len(), 2);
    }
}
