//! Sections from loose closed planar contours in 3D, each with a label and nothing else: no plane
//! equations, no hole flags (what a DICOM RT Structure Set holds, see `io::rtstruct`).
//!
//! * **Planes** come from the points. Each contour's plane is its Newell normal through its centroid
//!   (exact for a planar polygon, and a least-squares-like fit for a nearly planar one); a contour
//!   with a point farther from its own plane than the tolerance is an error. Contours whose points
//!   all lie within the tolerance of a plane already found join that plane's section, so the
//!   contours of several labels on one slice share one section. The tolerance is the CSL and JSON
//!   readers' one: `OFF_PLANE_RELATIVE_TOLERANCE` × the diagonal of the bounding box of all points.
//!   A section's plane is then refitted over all its contours (their Newell normals summed, so
//!   weighted by area, through the mean of their points), its normal signed so that its largest
//!   component is positive (axial slices get +z whatever the contours' winding).
//! * **Holes** come from nesting: within one label on one plane, a contour inside an odd number of
//!   the others is a hole of the innermost one containing it; inside an even number (0, 2, ...) it
//!   is an outer contour (an island in a hole is material again). A contour is inside another when
//!   all its points are (nonzero winding); contours that cross are both outer, and the validator's
//!   repair merges them.
//!
//! The sections are then validated and repaired like any input (`validate::validate_with_options`:
//! orientation, keyholes and self-intersections, touching contours of one label, snapping).
use crate::error::{Error, Result};
use crate::sections::{cross, dot, sub, Contour, Plane, Region, Section, Sections};
use crate::validate::{
    self, winding_number, ContourId, Locator, ReadOptions, Role, OFF_PLANE_RELATIVE_TOLERANCE,
};
use std::collections::BTreeMap;

/// One input contour: its label, its points, and where it is (for messages).
#[derive(Clone, Debug)]
pub struct LooseContour {
    pub label: i32,
    pub points: Vec<[f64; 3]>,
    /// Location text, e.g. `plan.dcm: ROI "Body" (number 1), contour 3`.
    pub location: String,
}

/// Build validated sections from `contours`. `file` names the input in plane locations;
/// `warnings` (the reader's own) and `label_names` are carried into the result.
pub fn sections_from_loose_contours(
    contours: &[LooseContour],
    file: &str,
    label_names: BTreeMap<i32, String>,
    warnings: Vec<String>,
    options: &ReadOptions,
) -> Result<Sections> {
    let tol = OFF_PLANE_RELATIVE_TOLERANCE * diagonal(contours);
    let fits = contours
        .iter()
        .map(|c| contour_plane(c, tol))
        .collect::<Result<Vec<_>>>()?;
    let groups = group_by_plane(contours, &fits, tol);

    let mut sections = Vec::with_capacity(groups.len());
    let mut loc = LooseLocator {
        file,
        contours,
        first: Vec::new(),
        regions: Vec::new(),
    };
    for (g, members) in groups.iter().enumerate() {
        let plane = group_plane(contours, &fits, members).ok_or_else(|| {
            Error::input(
                contours[members[0]].location.clone(),
                "cannot fit a plane through this contour's section (numbers too large or too small)",
            )
        })?;
        let (regions, origin) = nest(contours, members, &plane);
        loc.first.push(members[0]);
        loc.regions.push(origin);
        sections.push(Section {
            plane,
            regions,
            source_index: g,
            max_off_plane: 0.0,
        });
    }
    validate::validate_with_options(
        Sections {
            sections,
            n_labels: 0,
            warnings,
            label_names,
        },
        &loc,
        options,
    )
}

/// Locations: a contour is named by its input location, a plane by its first contour.
struct LooseLocator<'a> {
    file: &'a str,
    contours: &'a [LooseContour],
    /// Per section: its first input contour.
    first: Vec<usize>,
    /// Per section, per region: (outer input contour, hole input contours).
    regions: Vec<Vec<(usize, Vec<usize>)>>,
}

impl Locator for LooseLocator<'_> {
    fn plane(&self, s: usize) -> String {
        format!(
            "{}: plane {s} (the plane of {})",
            self.file, self.contours[self.first[s]].location
        )
    }
    fn contour(&self, id: ContourId) -> String {
        let (outer, holes) = &self.regions[id.section][id.region];
        let c = match id.role {
            Role::Outer => *outer,
            Role::Hole(h) => holes[h],
        };
        self.contours[c].location.clone()
    }
}

fn diagonal(contours: &[LooseContour]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in contours.iter().flat_map(|c| &c.points) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        return 0.0;
    }
    dot(sub(hi, lo), sub(hi, lo)).sqrt()
}

/// A contour's own plane: (Newell normal, length 2 × area; centroid).
struct Fit {
    normal: [f64; 3],
    centroid: [f64; 3],
}

fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for p in points {
        for k in 0..3 {
            c[k] += p[k];
        }
    }
    c.map(|x| x / points.len() as f64)
}

/// Newell normal about the centroid (about the centroid so that an exactly axial contour gets an
/// exactly axial normal), and the check that every point is within `tol` of that plane.
fn contour_plane(c: &LooseContour, tol: f64) -> Result<Fit> {
    if c.points.len() < 3 {
        return Err(Error::input(
            c.location.clone(),
            format!(
                "contour has {} point(s), at least 3 are needed",
                c.points.len()
            ),
        ));
    }
    let m = centroid(&c.points);
    let mut n = [0.0; 3];
    for (i, p) in c.points.iter().enumerate() {
        let q = c.points[(i + 1) % c.points.len()];
        n = add(n, cross(sub(*p, m), sub(q, m)));
    }
    let len = dot(n, n).sqrt();
    if !(len.is_finite() && len > 0.0) {
        return Err(Error::input(
            c.location.clone(),
            "contour encloses no area (its points are collinear or repeated), so it has no plane",
        ));
    }
    let unit = n.map(|x| x / len);
    let (worst, off) = c
        .points
        .iter()
        .map(|p| dot(unit, sub(*p, m)).abs())
        .enumerate()
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    if off > tol {
        return Err(Error::input(
            c.location.clone(),
            format!(
                "contour is not planar: point {worst} is {off:.3e} off the plane of the contour (Newell normal through its centroid); tolerance {tol:.3e} ({OFF_PLANE_RELATIVE_TOLERANCE} x the bounding-box diagonal of all points)"
            ),
        ));
    }
    Ok(Fit {
        normal: n,
        centroid: m,
    })
}

/// Contours grouped by plane, in order of first appearance: a contour joins the first group whose
/// founding contour's plane has all its points within `tol`.
fn group_by_plane(contours: &[LooseContour], fits: &[Fit], tol: f64) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, c) in contours.iter().enumerate() {
        let fits_group = |g: &Vec<usize>| {
            let f = &fits[g[0]];
            let n = f.normal.map(|x| x / dot(f.normal, f.normal).sqrt());
            c.points
                .iter()
                .all(|p| dot(n, sub(*p, f.centroid)).abs() <= tol)
        };
        match groups.iter_mut().find(|g| fits_group(g)) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}

/// The plane of a group: Newell normals summed (each turned to agree with the first, since
/// contours of either winding share a plane), through the mean of all points; the normal's largest
/// component made positive.
fn group_plane(contours: &[LooseContour], fits: &[Fit], members: &[usize]) -> Option<Plane> {
    let first = fits[members[0]].normal;
    let mut n = [0.0; 3];
    let mut sum = [0.0; 3];
    let mut count = 0usize;
    for &i in members {
        let f = fits[i].normal;
        let s = if dot(f, first) < 0.0 { -1.0 } else { 1.0 };
        n = add(n, f.map(|x| s * x));
        for p in &contours[i].points {
            sum = add(sum, *p);
        }
        count += contours[i].points.len();
    }
    let big = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    if n[big] < 0.0 {
        n = n.map(|x| -x);
    }
    Plane::from_point_normal(sum.map(|x| x / count as f64), n)
}

/// The regions of one section: per label, contours nested by containment. Returns the regions and,
/// per region, (outer input contour, hole input contours) for the locator.
#[allow(clippy::type_complexity)]
fn nest(
    contours: &[LooseContour],
    members: &[usize],
    plane: &Plane,
) -> (Vec<Region>, Vec<(usize, Vec<usize>)>) {
    let flat: Vec<Vec<[f64; 2]>> = members
        .iter()
        .map(|&i| contours[i].points.iter().map(|p| plane.to_2d(*p)).collect())
        .collect();
    let boxes: Vec<[f64; 4]> = flat.iter().map(|c| box2(c)).collect();
    let inside = |a: usize, b: usize| {
        a != b
            && contours[members[a]].label == contours[members[b]].label
            && box_within(&boxes[a], &boxes[b])
            && flat[a].iter().all(|&q| winding_number(q, &flat[b]) != 0)
    };
    let containers: Vec<Vec<usize>> = (0..members.len())
        .map(|a| (0..members.len()).filter(|&b| inside(a, b)).collect())
        .collect();
    // A contour inside an odd number of others is a hole of the innermost one (the container with
    // one container fewer); every other contour is outer (also, should nesting not form a chain,
    // one with no such container: the validator then says what is wrong with it).
    let parent: Vec<Option<usize>> = (0..members.len())
        .map(|a| {
            let depth = containers[a].len();
            (depth % 2 == 1)
                .then(|| {
                    containers[a]
                        .iter()
                        .copied()
                        .find(|&b| containers[b].len() + 1 == depth)
                })
                .flatten()
        })
        .collect();
    let contour = |a: usize| Contour {
        points2: flat[a].clone(),
        // The input points: the validator measures their distance from the plane and snaps them.
        points3: contours[members[a]].points.clone(),
    };
    let mut regions = Vec::new();
    let mut origin = Vec::new();
    let mut region_of = vec![0; members.len()];
    for a in (0..members.len()).filter(|&a| parent[a].is_none()) {
        region_of[a] = regions.len();
        regions.push(Region {
            label: contours[members[a]].label,
            outer: contour(a),
            holes: Vec::new(),
        });
        origin.push((members[a], Vec::new()));
    }
    for a in 0..members.len() {
        if let Some(p) = parent[a] {
            let r = region_of[p];
            regions[r].holes.push(contour(a));
            origin[r].1.push(members[a]);
        }
    }
    (regions, origin)
}

fn box2(c: &[[f64; 2]]) -> [f64; 4] {
    c.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, q| {
            [
                b[0].min(q[0]),
                b[1].min(q[1]),
                b[2].max(q[0]),
                b[3].max(q[1]),
            ]
        },
    )
}

fn box_within(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] >= b[0] && a[1] >= b[1] && a[2] <= b[2] && a[3] <= b[3]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
