//! Repair of plane equations that disagree with their vertices, shared by the CSL and JSON readers
//! (not in strict mode, where the off-plane vertex is the error). The readers call it before they
//! project the vertices onto their planes.
//!
//! 1. Sign convention: when the stated planes do not all fit their vertices, but every plane stated
//!    by an equation with an offset fits a x + b y + c z - d = 0 within the tolerance (planes stated
//!    otherwise fitting as stated), those planes are read with that convention (one warning naming
//!    the file).
//! 2. Otherwise, per plane whose vertices do not fit its equation: when the vertices are coplanar
//!    within the tolerance (plane fitted as the Newell normal of its loops, each turned to the stated
//!    normal's side, through the mean of its vertices), that plane replaces the stated one, with a
//!    warning giving the distance, the angle and the offset change. Not when most vertices agree
//!    with the stated plane: then the others are misplaced, and the reader rejects them. Not for a
//!    plane that has contours given in its own frame (JSON `points2d`): those define points of the
//!    stated plane.
//!
//! Also the check, for every reader, that no plane is given twice (`check_duplicate_planes`).
use super::{model_diagonal, Locator, DUPLICATE_PLANE_RELATIVE_TOLERANCE};
use crate::error::{Error, Result};
use crate::sections::{dot, sub, Plane, Sections};

/// A plane as a reader found it, with the vertices given in 3D.
pub struct StatedPlane<'a> {
    pub plane: Plane,
    /// The vertices given in 3D.
    pub vertices: &'a [[f64; 3]],
    /// The contours, as indices into `vertices` (for the Newell normal).
    pub loops: Vec<&'a [usize]>,
    /// Stated as an equation with an offset (whose sign convention may be the other one).
    pub offset_form: bool,
    /// May be replaced by the plane through its vertices.
    pub refittable: bool,
    /// Where the plane is stated (file, line or JSON path, plane), for warnings.
    pub location: String,
}

/// Largest distance of `vertices` from `plane` (0 when there are none).
fn max_off(plane: &Plane, vertices: &[[f64; 3]]) -> f64 {
    vertices
        .iter()
        .map(|v| plane.signed_distance(*v).abs())
        .fold(0.0, f64::max)
}

/// The same equation with the opposite sign of the offset: a x + b y + c z - d = 0.
fn flipped(plane: &Plane) -> Plane {
    Plane::from_equation(plane.normal, -plane.offset).expect("a valid plane stays valid")
}

/// Repair the planes in place (see the module docs); `tol` is the absolute off-plane tolerance.
pub fn repair_plane_equations(
    planes: &mut [StatedPlane],
    tol: f64,
    file_name: &str,
    warnings: &mut Vec<String>,
) {
    let fails = |r: &StatedPlane| max_off(&r.plane, r.vertices) > tol;
    let n_failing = planes.iter().filter(|r| fails(r)).count();
    if n_failing == 0 {
        return;
    }
    let convention = |r: &StatedPlane| {
        if r.offset_form {
            flipped(&r.plane)
        } else {
            r.plane
        }
    };
    if planes
        .iter()
        .all(|r| max_off(&convention(r), r.vertices) <= tol)
    {
        let others = planes.iter().filter(|r| !r.offset_form).count();
        for r in planes.iter_mut() {
            r.plane = convention(r);
        }
        let which = if others > 0 {
            " (the planes stated with an offset)"
        } else {
            ""
        };
        warnings.push(format!(
            "{file_name}: repaired plane equations: the vertices of {n_failing} of {} plane(s) are off their plane a x + b y + c z + d = 0, but every plane fits a x + b y + c z - d = 0; read the file{which} with that convention",
            planes.len()
        ));
        return;
    }
    for r in planes.iter_mut() {
        let stated_off = max_off(&r.plane, r.vertices);
        if stated_off <= tol || !r.refittable {
            continue;
        }
        let agree = r
            .vertices
            .iter()
            .filter(|v| r.plane.signed_distance(**v).abs() <= tol)
            .count();
        if 2 * agree > r.vertices.len() {
            continue;
        }
        let Some(fit) = fit_plane(r) else { continue };
        let fit_off = max_off(&fit, r.vertices);
        if fit_off > tol {
            continue;
        }
        let angle = dot(fit.normal, r.plane.normal)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        warnings.push(format!(
            "{}: repaired plane equation: its vertices are up to {stated_off:.3e} off the stated plane (tolerance {tol:.3e}) but coplanar within {fit_off:.3e}; took the plane through them: normal turned by {angle:.3} degrees, offset {:.6e} -> {:.6e} (unit normal)",
            r.location,
            r.plane.offset,
            fit.offset
        ));
        r.plane = fit;
    }
}

/// The plane through a plane's vertices: Newell normal of its loops (each on the stated normal's
/// side, so holes add instead of cancelling), through the vertices' mean.
fn fit_plane(r: &StatedPlane) -> Option<Plane> {
    if r.vertices.is_empty() {
        return None;
    }
    let nv = r.vertices.len() as f64;
    let mut mean = [0.0; 3];
    for v in r.vertices {
        for k in 0..3 {
            mean[k] += v[k] / nv;
        }
    }
    let mut normal = [0.0; 3];
    for l in &r.loops {
        let m = l.len();
        let mut n = [0.0; 3];
        for i in 0..m {
            let p = sub(r.vertices[l[i]], mean);
            let q = sub(r.vertices[l[(i + 1) % m]], mean);
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        let s = if dot(n, r.plane.normal) < 0.0 {
            -1.0
        } else {
            1.0
        };
        for k in 0..3 {
            normal[k] += s * n[k];
        }
    }
    let plane = Plane::from_equation(normal, 0.0)?;
    Plane::from_equation(plane.normal, -dot(plane.normal, mean))
}

/// No two sections lie on the same plane (within `DUPLICATE_PLANE_RELATIVE_TOLERANCE` of the
/// model's diagonal over its bounding box).
pub(super) fn check_duplicate_planes(sections: &Sections, loc: &dyn Locator) -> Result<()> {
    let corners: Vec<[f64; 3]> = match sections.bounding_box() {
        Some((lo, hi)) => (0..8)
            .map(|k| {
                [
                    if k & 1 == 0 { lo[0] } else { hi[0] },
                    if k & 2 == 0 { lo[1] } else { hi[1] },
                    if k & 4 == 0 { lo[2] } else { hi[2] },
                ]
            })
            .collect(),
        None => vec![[0.0; 3]],
    };
    let diag = model_diagonal(sections);
    let eps = DUPLICATE_PLANE_RELATIVE_TOLERANCE * if diag > 0.0 { diag } else { 1.0 };
    let planes: Vec<Plane> = sections.sections.iter().map(|s| s.plane).collect();
    for j in 0..planes.len() {
        for i in 0..j {
            let (a, b) = (&planes[i], &planes[j]);
            let c = dot(a.normal, b.normal);
            if c.abs() < 1.0 - 1e-6 {
                continue;
            }
            let s = c.signum();
            let normals_equal = (0..3).all(|k| (a.normal[k] - s * b.normal[k]).abs() <= 1e-12);
            let same = corners
                .iter()
                .all(|&x| (a.signed_distance(x) - s * b.signed_distance(x)).abs() <= eps)
                && (normals_equal || sections.bounding_box().is_some());
            if same {
                return Err(Error::input(
                    loc.plane(j),
                    format!("duplicate plane: same plane as {}", loc.plane(i)),
                ));
            }
        }
    }
    Ok(())
}
