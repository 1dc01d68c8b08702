//! Validation and repair of cross-sections, shared by the CSL and JSON readers and by anyone who
//! builds a [`Sections`] in memory (the mesh slicer, tests).
//!
//! Repairs (reported in `Sections::warnings`): duplicate consecutive vertices are removed, contours
//! are re-oriented (outer counter-clockwise, holes clockwise seen from the normal), and unless
//! `ReadOptions::strict`, a region with a self-intersecting or self-touching contour is replaced by
//! the simple regions it encloses (nonzero winding, see `repair`), touching or overlapping
//! regions of one label (or a hole touching its outer contour) are merged into the union of their
//! material, regions of different labels that touch are kept and ones that overlap in area are
//! resolved by the lower label keeping the overlap (`labels`); the CSL and JSON readers also repair
//! plane equations (`planes`). In strict mode these are the errors below.
//! Errors (`Error::Input`, located by a [`Locator`]): non-finite or out-of-range numbers, zero normal,
//! a vertex off its plane beyond `OFF_PLANE_RELATIVE_TOLERANCE` × the model's bounding-box diagonal,
//! fewer than 3 distinct vertices, a self-intersecting (or self-touching) contour, two contours of
//! one plane crossing or touching (of one label; of different labels, overlapping in area), a hole
//! not inside its parent, a region inside another region's material, and the same plane given twice.
//!
//! Every intersection and containment decision uses the exact `orient2d` predicate on the
//! authoritative 2D coordinates (`points2`); floats are only used for bucketing and distances.
//!
//! Over 800 lines only with its unit tests (the test modules at the end); the code is shorter.
use crate::error::{Error, Result};
use crate::geom::predicates::orient2d;
use crate::sections::{cross, dot, sub, Contour, Plane, Section, Sections};

mod common_lines;
mod contours;
mod generic_position;
mod labels;
pub mod planes;
mod repair;
pub use common_lines::{reconcile_common_lines, LineTrims, LINE_STRIP_RELATIVE};
pub use contours::segments_intersect;
use contours::{check_intersections, check_nesting, section_contours};
pub use generic_position::{move_to_generic_position, GenericMoves, GENERIC_MOVE_RELATIVE};
pub use labels::{one_material, one_material_with_junctions, LABEL_OVERLAP_RELATIVE_AREA};
use planes::check_duplicate_planes;
pub use repair::NUDGE_RELATIVE;
pub(crate) use repair::{material_of, pieces_of};

/// A vertex may lie this far from its plane, relative to the diagonal of the model's bounding box.
/// Measured on the shared CSL files: at most 4.9e-5 (Horsers, coordinates printed with 2 decimals,
/// 1.2e-2 absolute); every other file is below 3e-10. 1e-3 is 20x above the worst real file and far
/// below any real misplacement.
pub const OFF_PLANE_RELATIVE_TOLERANCE: f64 = 1e-3;

/// Two planes are the same plane when they are this close over the model's bounding box,
/// relative to its diagonal.
pub const DUPLICATE_PLANE_RELATIVE_TOLERANCE: f64 = 1e-9;

/// Largest accepted coordinate magnitude: keeps products in the exact predicates (up to degree 4 in
/// insphere) far from overflow.
pub const MAX_COORDINATE: f64 = 1e30;

/// Nonzero magnitudes below this are flushed to zero (they would underflow in the predicates).
pub const TINY_COORDINATE: f64 = 1e-100;

/// How input is read. By default the readers repair what real segmentations contain (see the
/// module docs and README, "Input formats") and say so in `Sections::warnings`; with `strict`
/// every such repair is instead the located `Error::Input` it was before repairs existed.
/// (Duplicate consecutive vertices and orientation are always repaired.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReadOptions {
    pub strict: bool,
}

/// Which contour of a region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Outer,
    Hole(usize),
}

/// A contour of a `Sections`: section index (position in `sections.sections`), region, role.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContourId {
    pub section: usize,
    pub region: usize,
    pub role: Role,
}

/// Turns indices into the text of `Error::Input::location` (file, line or JSON path, plane, component).
pub trait Locator {
    fn plane(&self, section: usize) -> String;
    fn contour(&self, id: ContourId) -> String;
}

/// No locations: for checks whose outcome decides a repair, where the message is not used (and the
/// regions may already differ from the input's, which the readers' locators index).
pub(super) struct NoLocation;

impl Locator for NoLocation {
    fn plane(&self, _: usize) -> String {
        String::new()
    }
    fn contour(&self, _: ContourId) -> String {
        String::new()
    }
}

/// Locations for a `Sections` built in memory: `SOURCE: section S (plane P), region R, hole H`.
struct MemoryLocator<'a> {
    source: &'a str,
    source_index: Vec<usize>,
}

impl Locator for MemoryLocator<'_> {
    fn plane(&self, s: usize) -> String {
        format!(
            "{}: section {s} (plane {})",
            self.source,
            self.source_index.get(s).copied().unwrap_or(s)
        )
    }
    fn contour(&self, id: ContourId) -> String {
        let role = match id.role {
            Role::Outer => "outer contour".to_string(),
            Role::Hole(h) => format!("hole {h}"),
        };
        format!("{}, region {}, {role}", self.plane(id.section), id.region)
    }
}

/// Validate and repair sections built in memory. `source` names them in messages.
pub fn validate(sections: Sections, source: &str) -> Result<Sections> {
    let loc = MemoryLocator {
        source,
        source_index: sections.sections.iter().map(|s| s.source_index).collect(),
    };
    validate_with(sections, &loc)
}

/// Collects repairs of one kind; reported as one warning with a count and the first locations.
#[derive(Default)]
struct RepairLog {
    count: usize,
    first: Vec<String>,
}

impl RepairLog {
    fn add(&mut self, location: impl FnOnce() -> String) {
        self.count += 1;
        if self.first.len() < 3 {
            self.first.push(location());
        }
    }
    fn report(self, what: &str, out: &mut Vec<String>) {
        if self.count == 0 {
            return;
        }
        let more = if self.count > self.first.len() {
            format!(" and {} more", self.count - self.first.len())
        } else {
            String::new()
        };
        out.push(format!(
            "{what} on {} contour(s): {}{more}",
            self.count,
            self.first.join("; ")
        ));
    }
}

/// Validate and repair, naming places with `loc`, with the default (repairing) options.
pub fn validate_with(sections: Sections, loc: &dyn Locator) -> Result<Sections> {
    validate_with_options(sections, loc, &ReadOptions::default())
}

/// Validate and repair, naming places with `loc`. Readers call this after building the sections.
pub fn validate_with_options(
    mut sections: Sections,
    loc: &dyn Locator,
    options: &ReadOptions,
) -> Result<Sections> {
    for (s, sec) in sections.sections.iter().enumerate() {
        check_plane(&sec.plane).map_err(|r| Error::input(loc.plane(s), r))?;
    }
    let mut reoriented = RepairLog::default();

    check_coordinates(&mut sections, loc)?;
    snap_to_planes(&mut sections, loc)?;
    let (duplicates, collinear, collinear_count) = remove_redundant_vertices(&mut sections, loc)?;

    // Self-intersecting and self-touching contours, then same-label and different-label
    // conflicts (unless strict): see `repair` and `labels`.
    let area_tol = labels::area_tolerance(&sections);
    let remap;
    let loc: &dyn Locator = if options.strict {
        loc
    } else {
        remap = repair_regions(&mut sections, loc, area_tol);
        &remap
    };

    check_duplicate_planes(&sections, loc)?;
    for (s, sec) in sections.sections.iter().enumerate() {
        check_section_contours(sec, s, loc, options.strict, area_tol)?;
    }

    // Orientation: outer counter-clockwise, holes clockwise (the contours are simple by now).
    orient_contours(&mut sections, loc, &mut reoriented);

    let max_label = sections
        .sections
        .iter()
        .flat_map(|s| &s.regions)
        .map(|r| r.label)
        .max()
        .unwrap_or(0);
    sections.n_labels = sections.n_labels.max(max_label.max(0) as usize);
    duplicates.report(
        "removed duplicate consecutive vertices",
        &mut sections.warnings,
    );
    collinear.report(
        &format!(
            "removed {collinear_count} vertices lying on the segment between their neighbours within rounding ({COLLINEAR_RELATIVE_TOLERANCE:e} of the model diagonal: the contour's shape is unchanged; kept, they make sliver triangles whose side of the contour is rounding noise)"
        ),
        &mut sections.warnings,
    );
    reoriented.report(
        "reversed orientation (outer contours must be counter-clockwise and holes clockwise seen from the plane normal)",
        &mut sections.warnings,
    );
    Ok(sections)
}

/// Coordinates: consistent lengths, finite, in range; points3 filled in when missing.
fn check_coordinates(sections: &mut Sections, loc: &dyn Locator) -> Result<()> {
    for (s, sec) in sections.sections.iter_mut().enumerate() {
        let plane = sec.plane;
        for (r, region) in sec.regions.iter_mut().enumerate() {
            for (role, c) in contours_mut(region) {
                let id = ContourId {
                    section: s,
                    region: r,
                    role,
                };
                if c.points3.is_empty() {
                    c.points3 = c.points2.iter().map(|&q| plane.to_3d(q)).collect();
                }
                if c.points3.len() != c.points2.len() {
                    return Err(Error::input(
                        loc.contour(id),
                        format!(
                            "{} 2D points but {} 3D points",
                            c.points2.len(),
                            c.points3.len()
                        ),
                    ));
                }
                for (i, q) in c.points2.iter_mut().enumerate() {
                    for x in q.iter_mut() {
                        *x = check_coordinate(*x).map_err(|e| {
                            Error::input(loc.contour(id), format!("vertex {i}: {e}"))
                        })?;
                    }
                }
                for (i, p) in c.points3.iter().enumerate() {
                    for &x in p {
                        check_coordinate(x).map_err(|e| {
                            Error::input(loc.contour(id), format!("vertex {i}: {e}"))
                        })?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// Off-plane distances and snapping (points3 := the plane point of points2).
fn snap_to_planes(sections: &mut Sections, loc: &dyn Locator) -> Result<()> {
    let tol = off_plane_tolerance(sections);
    for (s, sec) in sections.sections.iter_mut().enumerate() {
        let plane = sec.plane;
        let mut max_off = sec.max_off_plane.max(0.0);
        for (r, region) in sec.regions.iter_mut().enumerate() {
            for (role, c) in contours_mut(region) {
                let id = ContourId {
                    section: s,
                    region: r,
                    role,
                };
                for (i, (p, q)) in c.points3.iter().zip(&c.points2).enumerate() {
                    let off = plane.signed_distance(*p).abs();
                    let on = plane.to_3d(*q);
                    let gap = dot(sub(*p, on), sub(*p, on)).sqrt();
                    if !(off <= tol && gap <= tol) {
                        return Err(Error::input(
                            loc.contour(id),
                            format!(
                                "vertex {i} is {:.3e} off its plane (3D point {:.3e} from its 2D point); tolerance {tol:.3e} ({OFF_PLANE_RELATIVE_TOLERANCE} x model diagonal)",
                                off, gap
                            ),
                        ));
                    }
                    max_off = max_off.max(off);
                }
                c.points3 = c.points2.iter().map(|&q| plane.to_3d(q)).collect();
            }
        }
        sec.max_off_plane = max_off;
    }
    Ok(())
}

/// Duplicate consecutive vertices (closing edge included), vertices on their neighbours' chord
/// within rounding, then the vertex count: the logs of both repairs and the collinear vertices
/// removed.
fn remove_redundant_vertices(
    sections: &mut Sections,
    loc: &dyn Locator,
) -> Result<(RepairLog, RepairLog, usize)> {
    let flat_tolerance = COLLINEAR_RELATIVE_TOLERANCE * model_diagonal(sections);
    let (mut duplicates, mut collinear) = (RepairLog::default(), RepairLog::default());
    let mut collinear_count = 0;
    for (s, sec) in sections.sections.iter_mut().enumerate() {
        let shared = positions_in_several_places(sec);
        for (r, region) in sec.regions.iter_mut().enumerate() {
            for (role, c) in contours_mut(region) {
                let id = ContourId {
                    section: s,
                    region: r,
                    role,
                };
                if remove_consecutive_duplicates(c) {
                    duplicates.add(|| loc.contour(id));
                }
                let removed = remove_collinear_within_rounding(c, flat_tolerance, &|q| {
                    shared.contains(&point_key(q))
                });
                if removed > 0 {
                    collinear_count += removed;
                    collinear.add(|| loc.contour(id));
                }
                if c.points2.len() < 3 {
                    return Err(Error::input(
                        loc.contour(id),
                        format!(
                            "contour has {} distinct vertices, at least 3 are needed",
                            c.points2.len()
                        ),
                    ));
                }
            }
        }
    }
    Ok((duplicates, collinear, collinear_count))
}

/// The region repairs of every section (not strict): self-intersections, same-label conflicts,
/// different labels touching or overlapping. Their warnings go to `sections.warnings`; the
/// locator names repaired regions by the input component they came from.
fn repair_regions<'a>(
    sections: &mut Sections,
    loc: &'a dyn Locator,
    area_tol: f64,
) -> repair::RemapLocator<'a> {
    let nudge = NUDGE_RELATIVE * model_diagonal(sections);
    let mut repairs = Vec::new();
    let map = sections
        .sections
        .iter_mut()
        .enumerate()
        .map(|(s, sec)| {
            let mut map = repair::repair_self_intersections(sec, s, loc, nudge, &mut repairs);
            repair::repair_label_conflicts(sec, s, loc, nudge, &mut map, &mut repairs);
            labels::repair_label_overlaps(sec, s, loc, area_tol, nudge, &mut map, &mut repairs);
            map
        })
        .collect();
    sections.warnings.extend(repairs);
    repair::RemapLocator { inner: loc, map }
}

/// The contours of section `s` are simple, disjoint and properly nested. Strict: all of them.
/// Otherwise regions of different labels may touch: each label must pass on its own, and no two
/// labels may overlap in area (`labels`).
fn check_section_contours(
    sec: &crate::sections::Section,
    s: usize,
    loc: &dyn Locator,
    strict: bool,
    area_tol: f64,
) -> Result<()> {
    let contours = section_contours(s, sec, 0..sec.regions.len());
    let all = check_intersections(&contours, loc).and_then(|_| check_nesting(&contours, loc));
    if all.is_ok() || strict {
        return all;
    }
    let mut labels: Vec<i32> = sec.regions.iter().map(|r| r.label).collect();
    labels.sort_unstable();
    labels.dedup();
    for label in labels {
        let members = (0..sec.regions.len()).filter(|&r| sec.regions[r].label == label);
        let contours = section_contours(s, sec, members);
        check_intersections(&contours, loc)?;
        check_nesting(&contours, loc)?;
    }
    labels::check_labels_disjoint(sec, s, loc, area_tol)
}

/// Reverse the contours that run the wrong way (outer counter-clockwise, holes clockwise).
fn orient_contours(sections: &mut Sections, loc: &dyn Locator, reoriented: &mut RepairLog) {
    for (s, sec) in sections.sections.iter_mut().enumerate() {
        for (r, region) in sec.regions.iter_mut().enumerate() {
            for (role, c) in contours_mut(region) {
                let ccw = orientation(&c.points2) > 0.0;
                if ccw != (role == Role::Outer) {
                    c.points2.reverse();
                    c.points3.reverse();
                    reoriented.add(|| {
                        loc.contour(ContourId {
                            section: s,
                            region: r,
                            role,
                        })
                    });
                }
            }
        }
    }
}

fn contours_mut(
    region: &mut crate::sections::Region,
) -> impl Iterator<Item = (Role, &mut Contour)> {
    std::iter::once((Role::Outer, &mut region.outer)).chain(
        region
            .holes
            .iter_mut()
            .enumerate()
            .map(|(h, c)| (Role::Hole(h), c)),
    )
}

/// A coordinate as the predicates can take it: finite, at most `MAX_COORDINATE`, tiny values flushed.
pub fn check_coordinate(x: f64) -> std::result::Result<f64, String> {
    if !x.is_finite() {
        return Err(format!("coordinate {x} is not a finite number"));
    }
    if x.abs() > MAX_COORDINATE {
        return Err(format!(
            "coordinate {x:e} exceeds the supported magnitude {MAX_COORDINATE:e}"
        ));
    }
    Ok(if x.abs() < TINY_COORDINATE { 0.0 } else { x })
}

fn check_plane(p: &Plane) -> std::result::Result<(), String> {
    let all = p
        .normal
        .iter()
        .chain(&p.origin)
        .chain(&p.u)
        .chain(&p.v)
        .chain(std::iter::once(&p.offset));
    if all.clone().any(|x| !x.is_finite()) {
        return Err("plane has a coordinate that is not a finite number".into());
    }
    if p.normal == [0.0; 3] {
        return Err("plane normal is zero".into());
    }
    let eps = 1e-9;
    let uxv = cross(p.u, p.v);
    let frame_ok = (dot(p.normal, p.normal) - 1.0).abs() < eps
        && (dot(p.u, p.u) - 1.0).abs() < eps
        && (dot(p.v, p.v) - 1.0).abs() < eps
        && dot(p.u, p.v).abs() < eps
        && (0..3).all(|k| (uxv[k] - p.normal[k]).abs() < eps)
        && p.signed_distance(p.origin).abs() <= eps * (1.0 + p.offset.abs());
    if !frame_ok {
        return Err(
            "plane frame is not orthonormal with u x v = normal (build planes with Plane::from_equation or Plane::from_point_normal)"
                .into(),
        );
    }
    Ok(())
}

/// Diagonal of the bounding box of every 3D vertex (0 when there are none).
pub fn model_diagonal(sections: &Sections) -> f64 {
    match sections.bounding_box() {
        Some((lo, hi)) => dot(sub(hi, lo), sub(hi, lo)).sqrt(),
        None => 0.0,
    }
}

/// Absolute off-plane tolerance for these sections.
pub fn off_plane_tolerance(sections: &Sections) -> f64 {
    OFF_PLANE_RELATIVE_TOLERANCE * model_diagonal(sections)
}

/// A contour vertex this close (relative to the model diagonal) to the segment between its
/// neighbours is on it: far above the rounding of coordinates, far below any sampled feature.
pub const COLLINEAR_RELATIVE_TOLERANCE: f64 = 1e-12;

fn point_key(q: [f64; 2]) -> [u64; 2] {
    q.map(f64::to_bits)
}

/// The 2D positions that occur more than once among the section's contour vertices: where
/// regions touch (labels sharing an outline) or a contour touches itself. They are never
/// removed, so touching regions keep their common vertices.
fn positions_in_several_places(sec: &Section) -> std::collections::HashSet<[u64; 2]> {
    let mut seen = std::collections::HashSet::new();
    let mut several = std::collections::HashSet::new();
    for r in &sec.regions {
        for c in std::iter::once(&r.outer).chain(&r.holes) {
            for &q in &c.points2 {
                if !seen.insert(point_key(q)) {
                    several.insert(point_key(q));
                }
            }
        }
    }
    several
}

/// Remove the vertices of `c` that lie strictly between their neighbours and within `tolerance`
/// of the segment joining them (a straight contour stretch whose rounded vertices zig-zag by
/// ulps), except those `protected` says to keep; every vertex of a removed run stays within
/// `tolerance` of the segment that replaces it, and at least three vertices are left. How many
/// were removed.
fn remove_collinear_within_rounding(
    c: &mut Contour,
    tolerance: f64,
    protected: &dyn Fn([f64; 2]) -> bool,
) -> usize {
    let n = c.points2.len();
    if n <= 3 || tolerance <= 0.0 {
        return 0;
    }
    let p = &c.points2;
    let on_segment = |v: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        let (ab, av, bv) = (sub2(b, a), sub2(v, a), sub2(v, b));
        let len2 = dot2(ab, ab);
        let cross = ab[0] * av[1] - ab[1] * av[0];
        len2 > 0.0
            && cross * cross <= tolerance * tolerance * len2
            && dot2(av, ab) > 0.0
            && dot2(bv, ab) < 0.0
    };
    // Start from a vertex that stays (none removed when every vertex is on a line: degenerate,
    // left to the checks that follow).
    let stays = |i: usize| protected(p[i]) || !on_segment(p[i], p[(i + n - 1) % n], p[(i + 1) % n]);
    let Some(start) = (0..n).find(|&i| stays(i)) else {
        return 0;
    };
    let mut keep = vec![true; n];
    let mut last = start;
    let mut run: Vec<usize> = Vec::new();
    for step in 1..n {
        let v = (start + step) % n;
        let next = (v + 1) % n;
        let removable = !protected(p[v])
            && on_segment(p[v], p[last], p[next])
            && run.iter().all(|&r| on_segment(p[r], p[last], p[next]));
        if removable {
            run.push(v);
            keep[v] = false;
        } else {
            last = v;
            run.clear();
        }
    }
    let removed = keep.iter().filter(|&&k| !k).count();
    if removed == 0 || n - removed < 3 {
        return 0;
    }
    let mut k = keep.iter();
    c.points2.retain(|_| *k.next().unwrap());
    let mut k = keep.iter();
    c.points3.retain(|_| *k.next().unwrap());
    removed
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Remove consecutive equal vertices (in 2D, closing edge included). True if any were removed.
#[allow(clippy::needless_range_loop)]
fn remove_consecutive_duplicates(c: &mut Contour) -> bool {
    let n = c.points2.len();
    let mut keep = vec![true; n];
    let mut any = false;
    for i in 1..n {
        if c.points2[i] == c.points2[i - 1] {
            keep[i] = false;
            any = true;
        }
    }
    // Closing edge: drop trailing vertices equal to the first kept one.
    let mut last = n;
    while last > 1 && c.points2[last - 1] == c.points2[0] {
        if keep[last - 1] {
            keep[last - 1] = false;
            any = true;
        }
        last -= 1;
    }
    if any {
        let mut k = keep.iter();
        c.points2.retain(|_| *k.next().unwrap());
        let mut k = keep.iter();
        c.points3.retain(|_| *k.next().unwrap());
    }
    any
}

/// Sign of the orientation of a simple polygon, exactly: the turn at its lexicographically smallest
/// vertex (positive for counter-clockwise).
pub fn orientation(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    if n < 3 {
        return 0.0;
    }
    let mut m = 0;
    for i in 1..n {
        if (p[i][0], p[i][1]) < (p[m][0], p[m][1]) {
            m = i;
        }
    }
    orient2d(p[(m + n - 1) % n], p[m], p[(m + 1) % n])
}

/// Winding number of `poly` around `q`, exact (`q` must not be on the boundary for a meaningful answer).
pub fn winding_number(q: [f64; 2], poly: &[[f64; 2]]) -> i32 {
    let n = poly.len();
    let mut w = 0;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        if a[1] <= q[1] {
            if b[1] > q[1] && orient2d(a, b, q) > 0.0 {
                w += 1;
            }
        } else if b[1] <= q[1] && orient2d(a, b, q) < 0.0 {
            w -= 1;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sections::{Region, Section};

    fn square(plane: &Plane, x0: f64, y0: f64, s: f64) -> Contour {
        Contour::from_2d(
            plane,
            vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]],
        )
    }

    fn one_plane(regions: Vec<Region>) -> Sections {
        let plane = Plane::from_equation([0.0, 0.0, 1.0], -1.0).unwrap();
        Sections {
            sections: vec![Section {
                plane,
                regions,
                source_index: 0,
                max_off_plane: 0.0,
            }],
            n_labels: 1,
            warnings: vec![],
            label_names: Default::default(),
        }
    }

    fn z1() -> Plane {
        Plane::from_equation([0.0, 0.0, 1.0], -1.0).unwrap()
    }

    #[test]
    fn square_with_hole_is_valid_and_reoriented() {
        let p = z1();
        let mut hole = square(&p, 1.0, 1.0, 1.0);
        hole.points2.reverse();
        hole.points3.reverse();
        let mut outer = square(&p, 0.0, 0.0, 3.0);
        outer.points2.reverse(); // clockwise outer: must be fixed
        outer.points3.reverse();
        let s = one_plane(vec![Region {
            label: 1,
            outer,
            holes: vec![hole],
        }]);
        let v = validate(s, "mem").unwrap();
        let r = &v.sections[0].regions[0];
        assert!(r.outer.signed_area() > 0.0);
        assert!(r.holes[0].signed_area() < 0.0);
        assert_eq!(v.warnings.len(), 1, "{:?}", v.warnings);
        assert!((r.area() - 8.0).abs() < 1e-12);
    }

    /// A square whose bottom side carries vertices off the side by `dev` (alternately up and down).
    fn square_with_row(dev: f64) -> Contour {
        let mut pts = vec![[0.0, 0.0]];
        for k in 1..10 {
            let up = if k % 2 == 0 { dev } else { -dev };
            pts.push([k as f64 * 0.3, up]);
        }
        pts.extend([[3.0, 0.0], [3.0, 3.0], [0.0, 3.0]]);
        Contour::from_2d(&z1(), pts)
    }

    #[test]
    fn vertices_on_a_side_within_rounding_are_removed_with_a_warning() {
        // diagonal of the model ~4.24: tolerance ~4.2e-12; ulp-level zig-zag (1e-16) goes
        let s = one_plane(vec![Region {
            label: 1,
            outer: square_with_row(1e-16),
            holes: vec![],
        }]);
        let v = validate(s, "mem").unwrap();
        let outer = &v.sections[0].regions[0].outer;
        assert_eq!(outer.points2.len(), 4, "{:?}", outer.points2);
        assert_eq!(outer.points3.len(), 4);
        assert!((v.sections[0].regions[0].area() - 9.0).abs() < 1e-12);
        let w = v
            .warnings
            .iter()
            .find(|w| w.contains("removed 9 vertices"))
            .expect("warned");
        assert!(w.contains("plane"), "{w}");
    }

    #[test]
    fn a_real_bend_and_a_spike_are_kept() {
        // a bend of 1e-9 (far above rounding) is shape: kept
        let s = one_plane(vec![Region {
            label: 1,
            outer: square_with_row(1e-9),
            holes: vec![],
        }]);
        let v = validate(s, "mem").unwrap();
        assert_eq!(v.sections[0].regions[0].outer.points2.len(), 13);
        assert!(!v.warnings.iter().any(|w| w.contains("within rounding")));
        // a vertex on the line of its neighbours but not between them is not removed here
        let mut c = Contour::from_2d(&z1(), vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        assert_eq!(
            remove_collinear_within_rounding(&mut c, 1e-12, &|_| false),
            0
        );
    }

    #[test]
    fn vertices_where_regions_touch_are_kept() {
        // two squares of different labels sharing the zig-zag side y = 0 (one above, one below)
        let above = square_with_row(1e-16);
        let mut below_pts: Vec<[f64; 2]> = above.points2[..11].to_vec();
        below_pts.reverse();
        below_pts.extend([[0.0, -3.0], [3.0, -3.0]]);
        below_pts.rotate_left(1);
        let below = Contour::from_2d(&z1(), below_pts);
        let mut s = one_plane(vec![
            Region {
                label: 1,
                outer: above,
                holes: vec![],
            },
            Region {
                label: 2,
                outer: below,
                holes: vec![],
            },
        ]);
        s.n_labels = 2;
        let v = validate(s, "mem").unwrap();
        for r in &v.sections[0].regions {
            assert_eq!(r.outer.points2.len(), 13, "label {}", r.label);
        }
        assert!(!v.warnings.iter().any(|w| w.contains("within rounding")));
    }

    #[test]
    fn a_long_gentle_arc_is_not_flattened_beyond_the_tolerance() {
        // every triple of this arc (radius 1e9, spacing 0.01) is within 5e-14 of its chord, the
        // whole arc is not (sagitta 5e-8): runs are checked against the segment that replaces them
        let n = 2000;
        let r = 1e9;
        let mut pts: Vec<[f64; 2]> = (0..=n)
            .map(|k| {
                let t = (k as f64 - 0.5 * n as f64) * 0.01 / r; // radians
                [r * t.sin(), -2.0 * r * (0.5 * t).sin().powi(2)]
            })
            .collect();
        pts.push([10.0, -100.0]);
        pts.push([-10.0, -100.0]);
        let mut c = Contour::from_2d(&z1(), pts.clone());
        let removed = remove_collinear_within_rounding(&mut c, 1e-12, &|_| false);
        for (k, p) in pts.iter().enumerate().take(n + 1) {
            // the distance of every input vertex from the output polygon's arc part stays small
            let near = c.points2.windows(2).any(|w| {
                let (a, b) = (w[0], w[1]);
                let ab = sub2(b, a);
                let ap = sub2(*p, a);
                let t = (dot2(ap, ab) / dot2(ab, ab)).clamp(0.0, 1.0);
                let d = sub2(ap, [t * ab[0], t * ab[1]]);
                dot2(d, d).sqrt() <= 1e-12 * 1.000001
            });
            assert!(
                near,
                "vertex {k} left farther than the tolerance ({removed} removed)"
            );
        }
        assert!(removed > 0 && removed < n - 10, "{removed} removed");
    }

    fn validate_strict(sections: Sections, source: &str) -> Result<Sections> {
        let loc = MemoryLocator {
            source,
            source_index: sections.sections.iter().map(|s| s.source_index).collect(),
        };
        validate_with_options(sections, &loc, &ReadOptions { strict: true })
    }

    #[test]
    fn bow_tie_is_rejected_when_strict_and_repaired_otherwise() {
        let p = z1();
        let c = Contour::from_2d(&p, vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]);
        let s = one_plane(vec![Region {
            label: 1,
            outer: c,
            holes: vec![],
        }]);
        let v = validate(s.clone(), "mem").unwrap();
        assert_eq!(v.sections[0].regions.len(), 2);
        assert!(
            v.warnings[0]
                .starts_with("mem: section 0 (plane 0), region 0, outer contour: repaired"),
            "{:?}",
            v.warnings
        );
        let e = validate_strict(s, "mem").unwrap_err().to_string();
        assert!(
            e.contains("self-intersecting") && e.contains("mem: section 0"),
            "{e}"
        );
    }

    #[test]
    fn spike_and_touching_vertex_are_rejected() {
        let p = z1();
        // Goes to (2,0) and back along the same line to (1,0).
        let spike = Contour::from_2d(&p, vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        let e = validate_strict(
            one_plane(vec![Region {
                label: 1,
                outer: spike,
                holes: vec![],
            }]),
            "m",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("self-intersecting"), "{e}");
        // Repaired: the spike has no area, the triangle (0,0) (1,0) (1,1) is left.
        let v = validate(
            one_plane(vec![Region {
                label: 1,
                outer: Contour::from_2d(&p, vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
                holes: vec![],
            }]),
            "m",
        )
        .unwrap();
        assert_eq!(v.sections[0].regions.len(), 1);
        assert!((v.sections[0].regions[0].area() - 0.5).abs() < 1e-12);
        // Two squares sharing one corner: refused when strict, moved apart otherwise.
        let corner = one_plane(vec![
            Region {
                label: 1,
                outer: square(&p, 0.0, 0.0, 1.0),
                holes: vec![],
            },
            Region {
                label: 1,
                outer: square(&p, 1.0, 1.0, 1.0),
                holes: vec![],
            },
        ]);
        let v = validate(corner.clone(), "m").unwrap();
        assert_eq!(v.sections[0].regions.len(), 2);
        assert!((v.sections[0].area() - 2.0).abs() < 1e-4);
        let e = validate_strict(corner, "m").unwrap_err().to_string();
        assert!(e.contains("cross"), "{e}");
    }

    #[test]
    fn nesting_rules() {
        let p = z1();
        let hole_outside = one_plane(vec![Region {
            label: 1,
            outer: square(&p, 0.0, 0.0, 1.0),
            holes: vec![square(&p, 5.0, 5.0, 1.0)],
        }]);
        let e = validate(hole_outside, "m").unwrap_err().to_string();
        assert!(e.contains("hole is not inside its parent"), "{e}");
        let overlapping = one_plane(vec![
            Region {
                label: 1,
                outer: square(&p, 0.0, 0.0, 10.0),
                holes: vec![],
            },
            Region {
                label: 1,
                outer: square(&p, 1.0, 1.0, 1.0),
                holes: vec![],
            },
        ]);
        let e = validate_strict(overlapping.clone(), "m")
            .unwrap_err()
            .to_string();
        assert!(e.contains("regions overlap"), "{e}");
        let v = validate(overlapping, "m").unwrap();
        assert_eq!(v.sections[0].regions.len(), 1);
        assert!((v.sections[0].area() - 100.0).abs() < 1e-9);
        // An island inside a hole is fine.
        let island = one_plane(vec![
            Region {
                label: 1,
                outer: square(&p, 0.0, 0.0, 10.0),
                holes: vec![square(&p, 1.0, 1.0, 8.0)],
            },
            Region {
                label: 2,
                outer: square(&p, 2.0, 2.0, 1.0),
                holes: vec![],
            },
        ]);
        let v = validate(island, "m").unwrap();
        assert_eq!(v.n_labels, 2);
    }

    #[test]
    fn duplicates_removed_and_degenerate_rejected() {
        let p = z1();
        let c = Contour::from_2d(
            &p,
            vec![[0.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]],
        );
        let v = validate(
            one_plane(vec![Region {
                label: 1,
                outer: c,
                holes: vec![],
            }]),
            "m",
        )
        .unwrap();
        assert_eq!(v.sections[0].regions[0].outer.points2.len(), 3);
        assert!(v.warnings[0].contains("duplicate"));
        let c = Contour::from_2d(&p, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]);
        let e = validate(
            one_plane(vec![Region {
                label: 1,
                outer: c,
                holes: vec![],
            }]),
            "m",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("at least 3"), "{e}");
    }

    #[test]
    fn duplicate_planes_and_off_plane() {
        let p = z1();
        let mut s = one_plane(vec![Region {
            label: 1,
            outer: square(&p, 0.0, 0.0, 1.0),
            holes: vec![],
        }]);
        let mut second = s.sections[0].clone();
        second.plane = Plane::from_equation([0.0, 0.0, -2.0], 2.0).unwrap(); // same plane, flipped
        second.regions[0].outer = square(&second.plane, 0.0, 0.0, 1.0);
        second.source_index = 7;
        s.sections.push(second);
        let e = validate(s.clone(), "m").unwrap_err().to_string();
        assert!(
            e.contains("duplicate plane") && e.contains("plane 7") && e.contains("plane 0"),
            "{e}"
        );
        s.sections.pop();
        s.sections[0].regions[0].outer.points3[2][2] += 0.5;
        let e = validate(s, "m").unwrap_err().to_string();
        assert!(e.contains("vertex 2") && e.contains("off its plane"), "{e}");
    }

    #[test]
    fn large_contour_crossing_found_by_the_grid() {
        let p = z1();
        let n = 20_000;
        let circle: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        let region = |pts: Vec<[f64; 2]>| Region {
            label: 1,
            outer: Contour::from_2d(&p, pts),
            holes: vec![],
        };
        let t = std::time::Instant::now();
        validate(one_plane(vec![region(circle.clone())]), "m").unwrap();
        assert!(t.elapsed().as_secs_f64() < 1.0);
        let mut crossed = circle;
        crossed.swap(777, 778);
        let e = validate_strict(one_plane(vec![region(crossed.clone())]), "m")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("edges 776 and 778") || e.contains("self-intersecting"),
            "{e}"
        );
        let v = validate(one_plane(vec![region(crossed)]), "m").unwrap();
        assert_eq!(v.sections[0].regions.len(), 2, "{:?}", v.warnings);
    }
}
