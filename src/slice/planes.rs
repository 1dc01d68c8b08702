//! Where the slicer cuts: the plane sets of [`SliceMode`] placed in a mesh's bounding box, each plane
//! kept clear of the mesh's vertices ([`PLANE_CLEARANCE`]).
use super::bounding_box;
use crate::mesh::TriMesh;
use crate::sections::Plane;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// How [`make_planes`] places the cutting planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SliceMode {
    /// Random unit normals through random points of the central 80% of the bounding box.
    Random,
    /// Planes perpendicular to the longest bounding-box axis, evenly spaced strictly inside.
    Parallel,
    /// Planes cycling over x, y, z; on each axis evenly spaced strictly inside the bounding box.
    Axes,
    /// A rotational probe or radial MRI: planes through one common line, the line through the
    /// bounding-box centre along its longest axis. Normals are evenly spaced over a half-turn about
    /// that axis (a plane turned by 180° is the same plane) from a seeded random starting angle.
    /// The line is moved off the centre by a few 10⁻⁵ of the diagonal only when a mesh vertex lies
    /// (almost) on it, since such a vertex would lie on every plane.
    Fan,
    /// A freehand ultrasound probe moved along the body: one frame per position evenly spaced
    /// strictly inside the box along its longest axis, each through the point of the central axis
    /// at that position, its normal tilted from the axis by a seeded random angle of at most
    /// [`SWEEP_MAX_TILT_DEG`] in a seeded random direction.
    Sweep,
    /// A probe rocked on the skin: a fan about a line outside the object, parallel to the
    /// second-longest axis and a tenth of the shortest extent beyond the box face on the `+` side of
    /// the shortest axis. The planes' angles are spread strictly between the angles at which, seen
    /// from the line, the box's first and last corners appear, so every plane crosses the box.
    Tilt,
}

/// Largest angle between a [`SliceMode::Sweep`] plane's normal and the longest axis, in degrees.
pub const SWEEP_MAX_TILT_DEG: f64 = 15.0;

/// Generated planes keep at least this distance (relative to the bounding-box diagonal) from every
/// mesh vertex, so the sections they make are generic: no contour touches another or itself at a
/// vertex lying on the plane (which `slice_mesh` handles, but which makes touching contours).
pub const PLANE_CLEARANCE: f64 = 1e-7;

/// `n` cutting planes for `mesh` (deterministic for a given `seed`, which `Random`, `Fan` and `Sweep`
/// use). Empty when the mesh has no vertices. Planes closer than [`PLANE_CLEARANCE`] to a vertex are
/// moved: axis-aligned and sweep planes shifted along their axis by a few millionths of the extent,
/// fan and tilt planes turned about their line by a few microradians (more only when vertices crowd
/// the line); such random planes are drawn again.
pub fn make_planes(mesh: &TriMesh, n: usize, seed: u64, mode: SliceMode) -> Vec<Plane> {
    let Some(b) = Bounds::of(mesh) else {
        return Vec::new();
    };
    match mode {
        SliceMode::Random => random_planes(&b, n, seed),
        SliceMode::Parallel => {
            let k = b.longest();
            (0..n)
                .map(|i| b.axis_plane(k, (i + 1) as f64 / (n + 1) as f64))
                .collect()
        }
        SliceMode::Axes => (0..n)
            .map(|i| {
                let k = i % 3;
                let per_axis = (n - k).div_ceil(3);
                b.axis_plane(k, (i / 3 + 1) as f64 / (per_axis + 1) as f64)
            })
            .collect(),
        SliceMode::Fan => fan_planes(&b, n, seed),
        SliceMode::Sweep => sweep_planes(&b, n, seed),
        SliceMode::Tilt => tilt_planes(&b, n),
    }
}

/// The mesh's bounding box and the clearance every generated plane keeps from its vertices.
struct Bounds<'a> {
    mesh: &'a TriMesh,
    lo: [f64; 3],
    hi: [f64; 3],
    ext: [f64; 3],
    diag: f64,
    /// [`PLANE_CLEARANCE`] times the bounding-box diagonal.
    eps: f64,
}

impl<'a> Bounds<'a> {
    fn of(mesh: &'a TriMesh) -> Option<Bounds<'a>> {
        let (lo, hi) = bounding_box(&mesh.vertices)?;
        let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let diag = (ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]).sqrt();
        Some(Bounds {
            mesh,
            lo,
            hi,
            ext,
            diag,
            eps: PLANE_CLEARANCE * diag,
        })
    }

    /// No mesh vertex within `eps` of `p`: the section is generic (see [`PLANE_CLEARANCE`]).
    fn clear(&self, p: &Plane) -> bool {
        self.mesh
            .vertices
            .iter()
            .all(|&v| p.signed_distance(v).abs() > self.eps)
    }

    /// The longest bounding-box axis (the last one on ties).
    fn longest(&self) -> usize {
        (0..3)
            .max_by(|&a, &b| self.ext[a].total_cmp(&self.ext[b]))
            .unwrap_or(2)
    }

    /// The axes by decreasing extent: the [`longest`](Self::longest), then the other two (the lower
    /// index first on a tie).
    fn axes_by_extent(&self) -> [usize; 3] {
        let k0 = self.longest();
        let (a, c) = ((k0 + 1) % 3, (k0 + 2) % 3);
        let (a, c) = (a.min(c), a.max(c));
        if self.ext[c] > self.ext[a] {
            [k0, c, a]
        } else {
            [k0, a, c]
        }
    }

    fn centre(&self) -> [f64; 3] {
        std::array::from_fn(|k| self.lo[k] + 0.5 * self.ext[k])
    }

    /// The plane perpendicular to axis `k` at fraction `f` of the box, or the nearest clear one at
    /// f, f+δ, f−δ, f+2δ, ... (δ = 10⁻⁶); `f` itself when none of 41 is clear.
    fn axis_plane(&self, k: usize, f: f64) -> Plane {
        let mut normal = [0.0; 3];
        normal[k] = 1.0;
        self.plane_along(k, self.lo, normal, f)
    }

    /// The plane with `normal` through `base` moved to fraction `f` of the box along axis `k`, or
    /// the nearest clear one at f, f+δ, f−δ, ... (δ = 10⁻⁶); `f` itself when none of 41 is clear.
    /// `normal` must not be perpendicular to axis `k`.
    fn plane_along(&self, k: usize, base: [f64; 3], normal: [f64; 3], f: f64) -> Plane {
        let plane_at = |f: f64| {
            let mut p = base;
            p[k] = self.lo[k] + self.ext[k] * f;
            Plane::from_point_normal(p, normal).expect("non-zero normal")
        };
        (0..41i32)
            .map(|j| plane_at(f + 1e-6 * f64::from(alternate(j))))
            .find(|p| self.clear(p))
            .unwrap_or_else(|| plane_at(f))
    }
}

/// 0, 1, −1, 2, −2, ...: the j-th retry offset, nearest first.
fn alternate(j: i32) -> i32 {
    if j % 2 == 1 {
        (j + 1) / 2
    } else {
        -j / 2
    }
}

/// A line `point + t·e[axis]` (the world axis not in `across`) about which planes turn: the plane at angle θ has the
/// normal cos θ e[across[0]] + sin θ e[across[1]]. That normal's component along the line is an
/// exact zero, so every point of the line has, in floating point, the same signed distance as
/// `point` (a rounding of the offset, ~10⁻¹⁶ of |point|): the planes share the line as exactly as
/// a plane equation can hold it.
struct Pivot {
    point: [f64; 3],
    across: [usize; 2],
}

impl Pivot {
    fn plane(&self, theta: f64) -> Plane {
        let mut n = [0.0; 3];
        n[self.across[0]] = theta.cos();
        n[self.across[1]] = theta.sin();
        let d = -(n[0] * self.point[0] + n[1] * self.point[1] + n[2] * self.point[2]);
        Plane::from_equation(n, d).expect("unit normal")
    }

    /// The plane at `theta`, or the nearest clear one turned by ±1, ±2, ±4, ... microradians (the
    /// steps grow because a vertex at distance r from the line blocks an angle of about 2·eps/r),
    /// keeping to the open interval `range`; `theta` itself when none of 41 is clear.
    fn clear_plane(&self, b: &Bounds, theta: f64, range: (f64, f64)) -> Plane {
        (0..41i32)
            .map(|j| theta + turn(j))
            .filter(|&t| range.0 < t && t < range.1)
            .map(|t| self.plane(t))
            .find(|p| b.clear(p))
            .unwrap_or_else(|| self.plane(theta))
    }
}

/// 0, 1, −1, 2, −2, 4, −4, ... microradians: the j-th retry turn, smallest first.
fn turn(j: i32) -> f64 {
    let m = alternate(j);
    if m == 0 {
        0.0
    } else {
        f64::from(m.signum()) * 1e-6 * 2f64.powi(m.abs() - 1)
    }
}

/// Distance of `v` from the line through `p` along world axis `axis`.
fn distance_to_axis_line(v: [f64; 3], p: [f64; 3], axis: usize) -> f64 {
    let (a, c) = ((axis + 1) % 3, (axis + 2) % 3);
    (v[a] - p[a]).hypot(v[c] - p[c])
}

/// The fan's common line: along the longest axis through the box centre, moved diagonally across
/// the other two axes by multiples of 10⁻⁵ of the diagonal (nearest first) until no vertex is
/// within 100 eps of it. A vertex on the line lies on every plane, and one close to it blocks a
/// wide range of angles; 100 eps keeps that range below ±0.01 rad.
fn fan_pivot(b: &Bounds) -> Pivot {
    let [k0, k1, k2] = b.axes_by_extent();
    let centre = b.centre();
    let at = |j: i32| {
        let mut p = centre;
        let s = 1e-5 * b.diag * f64::from(alternate(j));
        p[k1] += s;
        p[k2] += s;
        p
    };
    let far = |p: [f64; 3]| {
        b.mesh
            .vertices
            .iter()
            .all(|&v| distance_to_axis_line(v, p, k0) > 100.0 * b.eps)
    };
    let point = (0..41).map(at).find(|&p| far(p)).unwrap_or(centre);
    Pivot {
        point,
        across: [k1, k2],
    }
}

/// [`SliceMode::Fan`]: `n` planes through [`fan_pivot`]'s line at θ₀ + π i / n, θ₀ uniform in
/// [0, π/n) from `seed`.
fn fan_planes(b: &Bounds, n: usize, seed: u64) -> Vec<Plane> {
    let pivot = fan_pivot(b);
    let step = std::f64::consts::PI / n.max(1) as f64;
    let theta0 = ChaCha8Rng::seed_from_u64(seed).gen_range(0.0..step);
    let free = (f64::NEG_INFINITY, f64::INFINITY);
    (0..n)
        .map(|i| pivot.clear_plane(b, theta0 + step * i as f64, free))
        .collect()
}

/// [`SliceMode::Sweep`]: at fraction (i + 1)/(n + 1) of the longest axis, through the central axis,
/// the normal tilted from it by an angle uniform in [0, [`SWEEP_MAX_TILT_DEG`]] towards a direction
/// uniform on the circle (both drawn from `seed` before any retry, so retries change no later plane).
fn sweep_planes(b: &Bounds, n: usize, seed: u64) -> Vec<Plane> {
    let [k0, k1, k2] = b.axes_by_extent();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let max_tilt = SWEEP_MAX_TILT_DEG.to_radians();
    let mut planes = Vec::with_capacity(n);
    for i in 0..n {
        let tilt = rng.gen_range(0.0..=max_tilt);
        let towards = rng.gen_range(0.0..std::f64::consts::TAU);
        let mut normal = [0.0; 3];
        normal[k0] = tilt.cos();
        normal[k1] = tilt.sin() * towards.cos();
        normal[k2] = tilt.sin() * towards.sin();
        let f = (i + 1) as f64 / (n + 1) as f64;
        planes.push(b.plane_along(k0, b.centre(), normal, f));
    }
    planes
}

/// [`SliceMode::Tilt`]: the line runs along the second-longest axis, at the centre along the
/// longest and max(0.1 × shortest extent, 10⁻³ × diagonal) beyond the `+` face of the shortest (the
/// floor keeps it outside a flat box). Seen from the line, in the plane of the other two axes, the
/// box spans the directions between its extreme corners (less than a half-turn, the box lying on
/// one side); the planes take the directions (i + 1)/(n + 1) of the way across.
fn tilt_planes(b: &Bounds, n: usize) -> Vec<Plane> {
    let [k0, _, k2] = b.axes_by_extent();
    let mut point = b.centre();
    point[k2] = b.hi[k2] + (0.1 * b.ext[k2]).max(1e-3 * b.diag);
    let pivot = Pivot {
        point,
        across: [k0, k2],
    };
    let corner_directions = [b.lo[k0], b.hi[k0]]
        .into_iter()
        .flat_map(|x| [b.lo[k2], b.hi[k2]].map(|z| (z - point[k2]).atan2(x - point[k0])));
    let (lo, hi) = corner_directions.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
        (lo.min(a), hi.max(a))
    });
    // A plane containing direction ψ (in the k0-k2 plane) has its normal at ψ + π/2.
    let quarter = std::f64::consts::FRAC_PI_2;
    (0..n)
        .map(|i| {
            let psi = lo + (hi - lo) * (i + 1) as f64 / (n + 1) as f64;
            pivot.clear_plane(b, psi + quarter, (lo + quarter, hi + quarter))
        })
        .collect()
}

/// Random unit normals (rejection sampling of the ball) through random points of the central 80%
/// of the box; a plane too close to a vertex is drawn again (kept after 100 (n + 10) attempts).
fn random_planes(b: &Bounds, n: usize, seed: u64) -> Vec<Plane> {
    let (lo, ext) = (b.lo, b.ext);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut planes = Vec::with_capacity(n);
    let mut attempts = 0usize;
    while planes.len() < n {
        attempts += 1;
        let d: [f64; 3] = [
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        ];
        let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(1e-4..=1.0).contains(&len2) {
            continue; // rejection sampling of the ball gives uniform directions
        }
        let p: [f64; 3] = std::array::from_fn(|k| lo[k] + ext[k] * rng.gen_range(0.1..0.9));
        if let Some(pl) = Plane::from_point_normal(p, d) {
            if b.clear(&pl) || attempts > 100 * (n + 10) {
                planes.push(pl);
            }
        }
    }
    planes
}
