//! Where to evaluate the indicator: an octree over the box (cubic cells, the longest side split into
//! 2^depth), refined coarse-to-fine (paper §4.5) where a cube holds more than one section contour
//! vertex, or where the function changes sign among its corners — always down to `depth − 2`, and
//! below that only where the trilinear interpolation of the corners misplaces the zero set by more than
//! half a finest step (checked with one evaluation at the cube centre). Inside a coarser leaf the
//! function is the trilinear interpolation of its corners, as in the paper's octree oracle. At the
//! finest level the sign-changing cubes are followed across every face with a sign change, so the set
//! of finest cubes handed to the extraction contains the whole zero set it touches (closed surface).
//! Evaluations are batched per level and run in parallel with rayon; nodes live in a hash map keyed by
//! finest-grid node.
use super::indicator::Indicator;
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A small multiplicative hasher for integer keys (grid nodes and edges).
#[derive(Default, Clone, Copy)]
pub struct IntHasher(u64);

impl Hasher for IntHasher {
    fn finish(&self) -> u64 {
        // fmix64 (MurmurHash3): every input bit reaches the low bits hashbrown indexes with
        // (grid keys differ mostly in their high bits).
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

pub type IntMap<K, V> = HashMap<K, V, BuildHasherDefault<IntHasher>>;
pub type IntSet<K> = HashSet<K, BuildHasherDefault<IntHasher>>;

/// The finest grid: cubes of side `h` from `origin`, `cubes[k]` of them along axis k (≤ 2^depth).
#[derive(Clone, Debug)]
pub struct Grid {
    pub origin: [f64; 3],
    pub h: f64,
    pub depth: u32,
    pub cubes: [u32; 3],
}

const BITS: u32 = 21;
const MASK: u64 = (1 << BITS) - 1;

impl Grid {
    /// Cubic cells: the longest box side is divided into 2^depth.
    pub fn new(lo: [f64; 3], hi: [f64; 3], depth: u32) -> Grid {
        let depth = depth.clamp(1, 20);
        let n = 1u32 << depth;
        let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let h = if ext > 0.0 { ext / n as f64 } else { 1.0 };
        let mut cubes = [1u32; 3];
        for k in 0..3 {
            cubes[k] = (((hi[k] - lo[k]) / h).ceil() as u32).clamp(1, n);
        }
        Grid {
            origin: lo,
            h,
            depth,
            cubes,
        }
    }
    pub fn key(i: [u32; 3]) -> u64 {
        i[0] as u64 | (i[1] as u64) << BITS | (i[2] as u64) << (2 * BITS)
    }
    pub fn unkey(k: u64) -> [u32; 3] {
        [
            (k & MASK) as u32,
            ((k >> BITS) & MASK) as u32,
            ((k >> (2 * BITS)) & MASK) as u32,
        ]
    }
    pub fn node_position(&self, i: [u32; 3]) -> [f64; 3] {
        [
            self.origin[0] + i[0] as f64 * self.h,
            self.origin[1] + i[1] as f64 * self.h,
            self.origin[2] + i[2] as f64 * self.h,
        ]
    }
    /// The finest cube across face (`axis`, `side`: 0 low, 1 high) of finest cube `c`, if inside
    /// the grid.
    pub fn face_neighbour(&self, c: [u32; 3], axis: usize, side: u32) -> Option<[u32; 3]> {
        let mut n = c;
        if side == 0 {
            n[axis] = n[axis].checked_sub(1)?;
        } else {
            n[axis] += 1;
            if n[axis] >= self.cubes[axis] {
                return None;
            }
        }
        Some(n)
    }

    /// The finest cube holding `p` (clamped to the grid).
    pub fn cube_of(&self, p: [f64; 3]) -> [u32; 3] {
        let mut c = [0u32; 3];
        for k in 0..3 {
            let t = ((p[k] - self.origin[k]) / self.h).floor();
            c[k] = if t.is_finite() && t > 0.0 {
                (t as u32).min(self.cubes[k] - 1)
            } else {
                0
            };
        }
        c
    }
}

/// The evaluated nodes and the finest cubes that carry the zero set.
#[derive(Debug)]
pub struct Field {
    pub grid: Grid,
    /// Node values: evaluated ones, and trilinear interpolations inside coarse octree leaves.
    pub values: IntMap<u64, f64>,
    /// Finest cubes (lower corner node) whose corners change sign.
    pub surface_cubes: Vec<[u32; 3]>,
    /// Cubes examined per octree level (coarse to fine).
    pub cubes_per_level: Vec<u64>,
    /// Sign-changing octree leaves coarser than the finest level (their inside is interpolated).
    pub coarse_surface_leaves: u64,
    pub flood_waves: u64,
    /// Number of true evaluations of the indicator.
    pub evaluations: u64,
    /// Number of node values interpolated inside coarse leaves.
    pub interpolated: u64,
    first_level: u32,
    /// Per level from `first_level`: the refined cubes (keys of their lower corners).
    refined: Vec<IntSet<u64>>,
}

/// Corner `c` (bits x=1, y=2, z=4) of the cube with lower corner `i` and side `s` (finest units).
pub fn corner(i: [u32; 3], s: u32, c: usize) -> [u32; 3] {
    [
        i[0] + s * (c as u32 & 1),
        i[1] + s * ((c as u32 >> 1) & 1),
        i[2] + s * ((c as u32 >> 2) & 1),
    ]
}

/// The six faces of a cube: axis, side (0 low, 1 high), the corners on it (bits x=1, y=2, z=4).
pub const CUBE_FACES: [(usize, u32, [usize; 4]); 6] = [
    (0, 0, [0, 2, 4, 6]),
    (0, 1, [1, 3, 5, 7]),
    (1, 0, [0, 1, 4, 5]),
    (1, 1, [2, 3, 6, 7]),
    (2, 0, [0, 1, 2, 3]),
    (2, 1, [4, 5, 6, 7]),
];

pub fn is_inside(v: f64) -> bool {
    v > 0.0
}

/// Octree refinement parameters.
#[derive(Clone, Copy, Debug)]
pub struct Refinement {
    /// First level examined everywhere.
    pub coarse: u32,
    /// Sign-changing cubes are always refined down to `depth − leaf_slack` (so a surface leaf spans at
    /// most 2^leaf_slack finest steps); below, only where the contour is or where the trilinear
    /// interpolation of the corners misplaces the zero set by more than `tolerance` finest steps.
    pub leaf_slack: u32,
    pub tolerance: f64,
    /// A cube holding at least this many contour vertices is refined (the paper: more than one).
    pub contour_vertices: u32,
}

impl Default for Refinement {
    fn default() -> Self {
        Refinement {
            coarse: 5,
            leaf_slack: 2,
            tolerance: 0.5,
            contour_vertices: 2,
        }
    }
}

impl Field {
    fn evaluate(&mut self, ind: &Indicator, keys: impl Iterator<Item = u64>) -> u64 {
        let mut missing: Vec<u64> = Vec::new();
        let mut seen: IntSet<u64> = IntSet::default();
        for k in keys {
            if !self.values.contains_key(&k) && seen.insert(k) {
                missing.push(k);
            }
        }
        let grid = &self.grid;
        let vals: Vec<f64> = missing
            .par_iter()
            .with_min_len(64)
            .map(|&k| ind.eval(grid.node_position(Grid::unkey(k))))
            .collect();
        let n = missing.len() as u64;
        self.values.extend(missing.into_iter().zip(vals));
        self.evaluations += n;
        n
    }

    fn corner_values(&self, i: [u32; 3], s: u32) -> [f64; 8] {
        let mut v = [0.0; 8];
        for (c, vc) in v.iter_mut().enumerate() {
            *vc = self.values[&Grid::key(corner(i, s, c))];
        }
        v
    }

    /// The value at a finest node not evaluated: trilinear in the deepest octree leaf holding it.
    fn leaf_value(&self, n: [u32; 3]) -> f64 {
        let depth = self.grid.depth;
        for (li, refined) in self.refined.iter().enumerate() {
            let l = self.first_level + li as u32;
            let s = 1u32 << (depth - l);
            let mut c = [0u32; 3];
            for k in 0..3 {
                c[k] = n[k].min(self.grid.cubes[k] - 1) / s * s;
            }
            if l < depth && refined.contains(&Grid::key(c)) {
                continue;
            }
            let v = self.corner_values(c, s);
            let t: Vec<f64> = (0..3)
                .map(|k| (n[k] as f64 - c[k] as f64) / s as f64)
                .collect();
            let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
            let x00 = lerp(v[0], v[1], t[0]);
            let x10 = lerp(v[2], v[3], t[0]);
            let x01 = lerp(v[4], v[5], t[0]);
            let x11 = lerp(v[6], v[7], t[0]);
            return lerp(lerp(x00, x10, t[1]), lerp(x01, x11, t[1]), t[2]);
        }
        -1.0
    }

    fn fill(&mut self, keys: impl Iterator<Item = u64>) {
        let mut missing: Vec<u64> = keys.filter(|k| !self.values.contains_key(k)).collect();
        missing.sort_unstable();
        missing.dedup();
        let vals: Vec<f64> = missing
            .iter()
            .map(|&k| self.leaf_value(Grid::unkey(k)))
            .collect();
        self.interpolated += missing.len() as u64;
        self.values.extend(missing.into_iter().zip(vals));
    }

    /// Build the field. `contour_points`: section contour vertices (refinement seeds);
    /// `progress`: called with (stage, evaluations so far).
    pub fn build(
        ind: &Indicator,
        grid: Grid,
        contour_points: &[[f64; 3]],
        refinement: Refinement,
        progress: &dyn Fn(&str, u64),
    ) -> Field {
        let depth = grid.depth;
        let l0 = refinement.coarse.min(depth);
        let mut field = Field {
            grid,
            values: IntMap::default(),
            surface_cubes: Vec::new(),
            cubes_per_level: Vec::new(),
            coarse_surface_leaves: 0,
            flood_waves: 0,
            evaluations: 0,
            interpolated: 0,
            first_level: l0,
            refined: Vec::new(),
        };
        let fine_contour = field.contour_vertices_per_cube(contour_points);
        let mut active = field.cubes_of_level(l0);
        // Seeds for the finest-level closure inside coarse surface leaves.
        let mut seeds: Vec<[u32; 3]> = Vec::new();
        for l in l0..=depth {
            let s = 1u32 << (depth - l);
            field.cubes_per_level.push(active.len() as u64);
            let keys: Vec<u64> = active
                .iter()
                .flat_map(|&i| (0..8).map(move |c| Grid::key(corner(i, s, c))))
                .collect();
            field.evaluate(ind, keys.into_iter());
            progress(&format!("octree level {l}"), field.evaluations);
            if l == depth {
                field.refined.push(IntSet::default());
                break;
            }
            let refine = field.refine_level(ind, &active, l, &fine_contour, refinement, &mut seeds);
            field
                .refined
                .push(refine.iter().map(|&i| Grid::key(i)).collect());
            active = field.children(&refine, s / 2);
        }
        field.close_zero_set(active, seeds, progress);
        field
    }

    /// Contour vertices per finest cube.
    fn contour_vertices_per_cube(&self, contour_points: &[[f64; 3]]) -> IntMap<u64, u32> {
        let mut fine_contour: IntMap<u64, u32> = IntMap::default();
        for &p in contour_points {
            *fine_contour
                .entry(Grid::key(self.grid.cube_of(p)))
                .or_insert(0) += 1;
        }
        fine_contour
    }

    /// Every cube of level `l` (lower corners, x fastest).
    fn cubes_of_level(&self, l: u32) -> Vec<[u32; 3]> {
        let cubes = self.grid.cubes;
        let s = 1u32 << (self.grid.depth - l);
        let n: Vec<u32> = (0..3).map(|k| cubes[k].div_ceil(s)).collect();
        let mut active = Vec::new();
        for z in 0..n[2] {
            for y in 0..n[1] {
                for x in 0..n[0] {
                    active.push([x * s, y * s, z * s]);
                }
            }
        }
        active
    }

    /// The cubes of level `l` (corners evaluated) to refine: those holding contour vertices, those
    /// with a sign change above `depth − leaf_slack`, and below it those whose centre the trilinear
    /// interpolation misses. The sign-changing cubes that stay leaves seed the closure.
    fn refine_level(
        &mut self,
        ind: &Indicator,
        active: &[[u32; 3]],
        l: u32,
        fine_contour: &IntMap<u64, u32>,
        refinement: Refinement,
        seeds: &mut Vec<[u32; 3]>,
    ) -> Vec<[u32; 3]> {
        let depth = self.grid.depth;
        let s = 1u32 << (depth - l);
        let mut contour_count: IntMap<u64, u32> = IntMap::default();
        for (&k, &n) in fine_contour {
            let c = Grid::unkey(k);
            *contour_count
                .entry(Grid::key([c[0] / s * s, c[1] / s * s, c[2] / s * s]))
                .or_insert(0) += n;
        }
        let half = s / 2;
        // Sign-changing cubes that may stay leaves: check their centre against trilinear.
        let must = l + refinement.leaf_slack < depth;
        let mut candidates = Vec::new();
        let mut refine = Vec::new();
        for &i in active {
            let v = self.corner_values(i, s);
            let n_in = v.iter().filter(|&&x| is_inside(x)).count();
            let crossing = n_in != 0 && n_in != 8;
            let contour = contour_count.get(&Grid::key(i)).copied().unwrap_or(0);
            if contour >= refinement.contour_vertices || (crossing && must) {
                refine.push(i);
            } else if crossing {
                candidates.push(i);
            }
        }
        let centres: Vec<u64> = candidates
            .iter()
            .map(|&i| Grid::key([i[0] + half, i[1] + half, i[2] + half]))
            .collect();
        self.evaluate(ind, centres.iter().copied());
        for (&i, ck) in candidates.iter().zip(&centres) {
            let v = self.corner_values(i, s);
            let mean = v.iter().sum::<f64>() / 8.0;
            let (lo, hi) = v
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // Zero misplaced by about |error| / slope, slope ≈ (hi − lo) / s finest steps.
            let err = (self.values[ck] - mean).abs();
            if err * s as f64 > refinement.tolerance * (hi - lo) {
                refine.push(i);
            } else {
                self.coarse_surface_leaves += 1;
                push_crossing_seeds(i, s, &v, self.grid.cubes, seeds);
            }
        }
        refine
    }

    /// The children (side `half`) of the cubes `refine` that lie in the grid.
    fn children(&self, refine: &[[u32; 3]], half: u32) -> Vec<[u32; 3]> {
        let cubes = self.grid.cubes;
        let mut next = Vec::new();
        for &i in refine {
            for c in 0..8 {
                let ch = corner(i, half, c);
                if (0..3).all(|k| ch[k] < cubes[k]) {
                    next.push(ch);
                }
            }
        }
        next
    }

    /// Finest level: follow the zero set across cube faces from `active` and `seeds` until it
    /// closes.
    fn close_zero_set(
        &mut self,
        active: Vec<[u32; 3]>,
        seeds: Vec<[u32; 3]>,
        progress: &dyn Fn(&str, u64),
    ) {
        let mut visited: IntSet<u64> = IntSet::default();
        let mut frontier = Vec::new();
        for i in active.into_iter().chain(seeds) {
            if visited.insert(Grid::key(i)) {
                frontier.push(i);
            }
        }
        while !frontier.is_empty() {
            let keys: Vec<u64> = frontier
                .iter()
                .flat_map(|&i| (0..8).map(move |c| Grid::key(corner(i, 1, c))))
                .collect();
            self.fill(keys.into_iter());
            self.flood_waves += 1;
            #[allow(clippy::manual_is_multiple_of)] // `is_multiple_of` needs Rust 1.87
            if self.flood_waves % 16 == 0 {
                progress("zero-set closure", self.evaluations);
            }
            let mut next = Vec::new();
            for &i in &frontier {
                let v = self.corner_values(i, 1);
                let inside: Vec<bool> = v.iter().map(|&x| is_inside(x)).collect();
                let n_in = inside.iter().filter(|&&b| b).count();
                if n_in == 0 || n_in == 8 {
                    continue;
                }
                self.surface_cubes.push(i);
                for (axis, side, cs) in CUBE_FACES {
                    let fi = cs.iter().filter(|&&c| inside[c]).count();
                    if fi == 0 || fi == 4 {
                        continue;
                    }
                    if let Some(nb) = self.grid.face_neighbour(i, axis, side) {
                        if visited.insert(Grid::key(nb)) {
                            next.push(nb);
                        }
                    }
                }
            }
            frontier = next;
        }
    }
}

/// Seeds of a coarse surface leaf (lower corner `i`, side `s`, corner values `v`): the finest cube
/// at the zero crossing of each sign-changing cube edge.
fn push_crossing_seeds(
    i: [u32; 3],
    s: u32,
    v: &[f64; 8],
    cubes: [u32; 3],
    seeds: &mut Vec<[u32; 3]>,
) {
    for (a, b) in CUBE_EDGES {
        let (fa, fb) = (v[a], v[b]);
        if is_inside(fa) == is_inside(fb) {
            continue;
        }
        let t = fa / (fa - fb);
        let ca = corner(i, s, a);
        let cb = corner(i, s, b);
        let mut cube = [0u32; 3];
        for k in 0..3 {
            cube[k] = if ca[k] == cb[k] {
                if ca[k] == i[k] {
                    i[k]
                } else {
                    ca[k] - 1
                }
            } else {
                let x = (i[k] as f64 + t * s as f64).floor() as u32;
                x.clamp(i[k], i[k] + s - 1)
            };
            cube[k] = cube[k].min(cubes[k] - 1);
        }
        seeds.push(cube);
    }
}

/// The 12 edges of a cube as corner pairs.
const CUBE_EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];
