//! Plane tags of points and the combinatorial rules they imply (the "tagged" kernel).
//!
//! A point on an input plane carries the plane's global id and its exact coordinates `uv` in the
//! plane's own frame, and a global id `gid`. In floats, points of an oblique plane are ~1 ulp off
//! the plane, so 3D predicates on them decide ties by rounding noise; the two cells on either side
//! of a face then triangulate it differently. With tags, every decision that is degenerate for the
//! *ideal* points (the points exactly on their planes) is taken combinatorially or in uv:
//!
//! * **Line rule.** When two vertices `a, b` of the tested tetrahedron and the query `q` are on one
//!   line for the ideal points — they share two planes (the line where the planes meet), or they
//!   share a plane and are exactly collinear in its uv (a row of a grid) or on one known segment
//!   (a contour edge and its conformity midpoints, whose rounded uv are collinear only nearly) —
//!   `q` conflicts iff it is
//!   strictly between `a` and `b` on that line: a line through two points of a sphere is inside
//!   the sphere exactly between them (and for an infinite tetrahedron, whose hull facet's plane
//!   then contains `q`, inside its circumcircle exactly between them). Every tetrahedron around the
//!   edge `ab` gets the same answer, so no facet of three collinear ideal points is ever created;
//!   without the rule, the float side of a facet `(a, b, y)` would decide, which is rounding noise.
//! * **Plane rule.** Otherwise, when the three vertices of a facet `F` and `q` share a plane, `q`
//!   conflicts iff it is inside `F`'s circumcircle: the circumsphere of *any* tetrahedron on `F`
//!   meets the plane in `F`'s circumcircle, so the answer is independent of the tetrahedron's
//!   fourth vertex, hence of the cell; and the tetrahedron on the other side of `F` (finite or infinite) gets the same answer,
//!   so `F` is never a cavity boundary facet for `q`: no flat tetrahedron (four co-tagged vertices)
//!   can be created. The circle is read on the points' 3D positions through a fixed point off the
//!   plane, the plane's apex ([`PlaneApexes`], [`pred::plane_insphere`]): the same floats the 3D
//!   predicates of the mixed tetrahedra read. (Read in the plane's uv instead, as it still is for a
//!   plane without an apex, [`pred::plane_incircle`], it sees another rounding of the same ideal
//!   points; where three of them are nearly collinear their circle is so large that the two
//!   roundings disagree on which side of it a query is, the rule contradicts the neighbouring
//!   tetrahedra's 3D decisions and the cavity is not star-shaped: two cells of the shared odd033.)
//!   With one apex per plane the rule is the orientation test of the points inverted about the
//!   apex, a consistent 2D triangulation of the plane's points; ties by the 2D symbolic
//!   perturbation in the lexicographic order of the positions.
//! * Else the float 3D predicates (with their lexicographic perturbation) decide.
//!
//! The choice of rule is unique: a tetrahedron cannot have co-tagged facets on two different planes
//! with `q` unless their common edge lies on the planes' line with `q`, where the line rule takes
//! precedence (and two co-tagged facets on one plane would be a flat tetrahedron, never created).
//!
//! Requirements and limits. The uv frame of a plane must be a similarity of the plane (orthonormal
//! axes): the line rule orders points in uv, and without an apex the plane rule reads circles in
//! uv as the plane's circles. An apex must be the same point in every triangulation sharing points
//! of its plane (a function of the plane alone). The rules are exact for the
//! ideal points; every other decision is the float 3D predicate, equal to the ideal one except
//! near an ideal degeneracy. Where ideal points are exactly cospherical across *different* planes
//! (mirror-image grids on two planes through one line; a sphere centred on a fan's common line, as
//! in the shipped `nested_fan.csl`; the corners of a lattice cell on orthogonal faces), a mixed
//! 5-tuple and a co-tagged one are both decided by rounding noise, of different tetrahedra, and
//! the two can disagree: the conflict region is then not star-shaped (some new tetrahedron would
//! not be positive). The insertion is then refused, the triangulation stays valid without the
//! point and takes no more points, and `Delaunay::consistent` fails; the engine triangulates such
//! a cell untagged instead (counted), and the pipeline then moves the contour vertices to generic
//! position in their planes, 1e-10 of the diagonal, and runs again
//! (`validate::move_to_generic_position`). Removing the tie itself needs every predicate on the
//! ideal points (exact plane-frame coordinates, one position per point on two planes); open.
//! (The untagged cells once seen on axis-plane grids were not this: the star test's inner point,
//! the centroid of a tetrahedron flat up to rounding, had rounded out of the hull; it is now
//! checked to be strictly inside. No cell of the generated axis grids up to 200 planes is
//! refused, nor of the 12 shared files, nor of the shared odd files: `tests/odd_inputs.rs`.)
use super::pred::{self, P};
use smallvec::SmallVec;

/// The planes a point lies on (up to [`MAX_PLANES`]: a contour vertex, a crossing of two planes,
/// an arrangement corner, a corner where more faces of a cell meet), with the point's exact
/// coordinates in each plane's frame, and the point's global id (a segment's ends are named by it).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointTags {
    /// (global plane id, uv in that plane); sorted by plane id by the kernel.
    pub planes: SmallVec<[(u32, [f64; 2]); 3]>,
    pub gid: u64,
    /// The gids of the ends of a segment the point is known to lie on (a contour edge it splits):
    /// it is collinear with them and with every other point of that segment, whatever its rounded
    /// coordinates say.
    pub segment: Option<[u64; 2]>,
}

impl PointTags {
    /// Tags for a point with global id `gid` on `planes` (any order).
    pub fn new(gid: u64, planes: &[(u32, [f64; 2])]) -> PointTags {
        let mut t = PointTags {
            planes: planes.iter().copied().collect(),
            gid,
            segment: None,
        };
        t.planes.sort_by_key(|p| p.0);
        t
    }

    /// A point on no plane (its gid is irrelevant: it never meets a plane or line rule).
    pub fn none() -> PointTags {
        PointTags::default()
    }

    /// uv of the point in `plane`, if it lies on it.
    pub fn uv(&self, plane: u32) -> Option<[f64; 2]> {
        self.planes.iter().find(|p| p.0 == plane).map(|p| p.1)
    }

    pub fn on(&self, plane: u32) -> bool {
        self.planes.iter().any(|p| p.0 == plane)
    }

    /// Sorts the planes and checks them: at most [`MAX_PLANES`], distinct ids, finite uv.
    pub(super) fn normalized(&self) -> Result<PointTags, String> {
        let mut t = PointTags::new(self.gid, &self.planes);
        t.segment = self.segment;
        if t.planes.len() > MAX_PLANES {
            return Err(format!("{} planes (at most {MAX_PLANES})", t.planes.len()));
        }
        if t.planes.windows(2).any(|w| w[0].0 == w[1].0) {
            return Err("a plane repeated".into());
        }
        if !t.planes.iter().all(|p| p.1.iter().all(|c| c.is_finite())) {
            return Err("non-finite uv".into());
        }
        Ok(t)
    }
}

/// Per plane id, a fixed point off the plane (its "apex") through which the plane rule decides
/// circles on the points' 3D positions ([`pred::plane_insphere`]). It must be the same point in
/// every triangulation that shares points of the plane (both cells of a face), so it is a function
/// of the plane alone. A plane without an apex is decided in its uv ([`pred::plane_incircle`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlaneApexes(Vec<(u32, P)>);

impl PlaneApexes {
    /// From (plane id, apex) pairs; a repeated id keeps its first apex.
    pub fn new(mut apexes: Vec<(u32, P)>) -> PlaneApexes {
        apexes.sort_by_key(|a| a.0);
        apexes.dedup_by_key(|a| a.0);
        PlaneApexes(apexes)
    }

    /// The apex of the plane through `point` with unit `normal`: `height` along the normal.
    pub fn above(point: P, normal: P, height: f64) -> P {
        std::array::from_fn(|k| point[k] + height * normal[k])
    }

    #[inline]
    pub fn get(&self, plane: u32) -> Option<P> {
        self.0
            .binary_search_by_key(&plane, |a| a.0)
            .ok()
            .map(|i| self.0[i].1)
    }
}

/// The most planes a point's tags may name: one bit each in the masks of the rules. A corner of a
/// cell where four or more of its faces meet (the apex of a pyramid cut by four planes through one
/// point) has that many; a point on three generic planes is already determined.
pub const MAX_PLANES: usize = 8;

/// A point's tags with its 3D position (the key of the symbolic perturbation, in-plane as in 3D).
pub type TaggedPoint<'a> = (&'a PointTags, P);

/// Bit i set when `p` lies on `q`'s i-th plane.
#[inline]
fn mask(p: &PointTags, q: &PointTags) -> u8 {
    if let ([(a, _)], [(b, _)]) = (&p.planes[..], &q.planes[..]) {
        // one plane each, the usual contour vertex
        return (a == b) as u8;
    }
    let mut m = 0;
    for (i, &(pl, _)) in q.planes.iter().enumerate() {
        if p.planes.iter().any(|x| x.0 == pl) {
            m |= 1 << i;
        }
    }
    m
}

const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// The tagged decision of whether `q` conflicts with the tetrahedron of vertices `v` (`None` for the
/// infinite vertex), or `None` when no tag rule applies (the 3D predicates decide). See the module
/// doc for the rules and why they make the cavity consistent.
#[inline]
pub(super) fn conflict(
    v: [Option<TaggedPoint>; 4],
    q: TaggedPoint,
    apexes: &PlaneApexes,
) -> Option<bool> {
    let (q, qp) = q;
    if q.planes.is_empty() {
        return None;
    }
    let m: [u8; 4] = std::array::from_fn(|i| v[i].map_or(0, |t| mask(t.0, q)));
    // a rule needs two vertices on a plane of q's (most tests of a cavity have none)
    if m.iter().filter(|&&x| x != 0).count() < 2 {
        return None;
    }
    for (i, j) in PAIRS {
        let c = m[i] & m[j];
        if c == 0 {
            continue;
        }
        let (a, b) = (v[i].unwrap().0, v[j].unwrap().0);
        if let Some(pl) = line_plane_of(a, b, q, c) {
            return Some(pred::line_between(
                a.uv(pl).unwrap(),
                b.uv(pl).unwrap(),
                q.uv(pl).unwrap(),
            ));
        }
    }
    for [x, y, z] in FACETS {
        let c = m[x] & m[y] & m[z];
        if c != 0 {
            let pl = q.planes[c.trailing_zeros() as usize].0;
            let f = [v[x].unwrap(), v[y].unwrap(), v[z].unwrap()];
            return plane_conflict(pl, f, (q, qp), apexes);
        }
    }
    None
}

/// The vertices of the facet opposite each vertex of a tetrahedron, in increasing order.
const FACETS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];

/// Whether `q` is inside the circumcircle of facet `f`, all four on plane `pl`: through the
/// plane's apex when it has one, else in its uv. `None` when `f` is collinear (no circle).
#[inline]
pub(super) fn plane_conflict(
    pl: u32,
    f: [TaggedPoint; 3],
    q: TaggedPoint,
    apexes: &PlaneApexes,
) -> Option<bool> {
    match apexes.get(pl) {
        Some(apex) => pred::plane_insphere(f[0].1, f[1].1, f[2].1, q.1, apex),
        None => {
            let uvp = |(t, p): TaggedPoint| (t.uv(pl).unwrap(), p);
            pred::plane_incircle(uvp(f[0]), uvp(f[1]), uvp(f[2]), uvp(q))
        }
    }
}

/// The plane in whose uv `a, b, q` are on one line for the ideal points: the lowest plane they
/// share when they share two (the planes' line), else the plane they share if they are exactly
/// collinear in its uv. `common` = the bits of `q`'s planes shared by `a` and `b`.
#[inline]
fn line_plane_of(a: &PointTags, b: &PointTags, q: &PointTags, common: u8) -> Option<u32> {
    if common == 0 {
        return None;
    }
    let pl = q.planes[common.trailing_zeros() as usize].0;
    match common.count_ones() {
        1 => {
            let o = crate::geom::predicates::orient2d(a.uv(pl)?, b.uv(pl)?, q.uv(pl)?);
            (o == 0.0 || on_one_segment(a, b, q)).then_some(pl)
        }
        _ => Some(pl),
    }
}

/// Whether the three points lie on one known segment (`PointTags::segment`): each is one of its
/// ends or is tagged with it.
#[inline]
fn on_one_segment(a: &PointTags, b: &PointTags, q: &PointTags) -> bool {
    [a.segment, b.segment, q.segment]
        .into_iter()
        .flatten()
        .any(|s| {
            [a, b, q]
                .iter()
                .all(|p| p.segment == Some(s) || s.contains(&p.gid))
        })
}

/// See [`line_plane_of`]: `Some(plane)` when the three points are collinear for the ideal points
/// (whatever their float coordinates say), the plane whose uv orders them.
#[inline]
pub fn line_plane(a: &PointTags, b: &PointTags, q: &PointTags) -> Option<u32> {
    line_plane_of(a, b, q, mask(a, q) & mask(b, q))
}

/// True when the three points are collinear for the ideal points ([`line_plane`]).
#[inline]
pub fn on_one_line(a: &PointTags, b: &PointTags, c: &PointTags) -> bool {
    line_plane(a, b, c).is_some()
}

/// True when the four points are degenerate for the ideal points by their tags alone: all four on
/// one plane, or three of them on one line. Such a tetrahedron is never built (its orientation is
/// 0 by definition, whatever the floats say).
#[inline]
pub fn degenerate(p: [&PointTags; 4]) -> bool {
    let m = [mask(p[0], p[3]), mask(p[1], p[3]), mask(p[2], p[3])];
    if m[0] & m[1] & m[2] != 0 {
        return true;
    }
    on_one_line(p[0], p[1], p[2])
        || on_one_line(p[0], p[1], p[3])
        || on_one_line(p[0], p[2], p[3])
        || on_one_line(p[1], p[2], p[3])
}

/// Whether the facet opposite vertex `i` of `v` (with `q` in place of `v[i]`) is degenerate by tags:
/// the walk must not cross it (the orientation is 0 for the ideal points).
#[inline]
pub(super) fn walk_degenerate(v: [Option<&PointTags>; 4], i: usize, q: &PointTags) -> bool {
    if q.planes.is_empty() {
        return false;
    }
    let m = v.map(|t| t.map_or(0, |t| mask(t, q)));
    let f: SmallVec<[usize; 3]> = (0..4).filter(|&k| k != i).collect();
    if m[f[0]] & m[f[1]] & m[f[2]] != 0 {
        return true;
    }
    [(0, 1), (0, 2), (1, 2)].into_iter().any(|(x, y)| {
        let c = m[f[x]] & m[f[y]];
        c != 0 && line_plane_of(v[f[x]].unwrap(), v[f[y]].unwrap(), q, c).is_some()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(gid: u64, planes: &[(u32, [f64; 2])]) -> PointTags {
        PointTags::new(gid, planes)
    }

    /// [`conflict`] with each point's 3D key made from its gid (the rules only need an order).
    fn rule(v: [Option<&PointTags>; 4], q: &PointTags) -> Option<bool> {
        let key = |t: &PointTags| [t.gid as f64, 0.0, 0.0];
        conflict(
            v.map(|t| t.map(|t| (t, key(t)))),
            (q, key(q)),
            &PlaneApexes::default(),
        )
    }

    /// Issue 14, a known failure (the untagged cell of the shipped `data/nested_fan.csl`, reduced
    /// to six of its 88 points): two poles on the fan's common line, mirrored in z, whose float
    /// positions are 600 ulps off each other's mirror, and two mirrored pairs on planes 2 and 3.
    /// The six are cospherical; the plane rule in (u,v) decides the cavity tetrahedron by its facet
    /// on plane 3 (in-circle +6.5e-25) and its neighbour across a facet mixing both planes by its
    /// facet on plane 2 (−2.4e-23): each plane's (u,v) come from projecting the rounded points, so
    /// the two planes see the ideal configuration lean different ways and the cavity is not
    /// star-shaped. With the second pole's (u,v) consistent with the first's in both planes (the
    /// exact mirror), the ties are exact and the symbolic perturbation decides them alike. The
    /// engine now reads the plane rule on the 3D positions (one position per point, through each
    /// plane's apex), which removes the two planes' disagreement but not the tie itself: the 3D
    /// floats decide exactly cospherical points of two planes by rounding, differently for a mixed
    /// tetrahedron and a co-tagged one. Needed: every predicate on the ideal points (exact
    /// plane-frame coordinates). Until then the pipeline moves such inputs' contour vertices to
    /// generic position and runs again (`bm_fan`'s symmetric solids; the shipped file is clean).
    #[test]
    fn fan_poles_rounded_differently_in_two_planes_refuse_the_tagged_kernel() {
        use crate::delaunay::Delaunay;
        let pts = [
            [
                3.464101615137755e-5,
                3.464101615137755e-5,
                0.9999958780710745,
            ],
            [
                0.00016054253614770003,
                -9.922085411959126e-5,
                0.99998514726758,
            ],
            [
                0.00016054253614770003,
                -9.922085411959126e-5,
                -0.99998514726758,
            ],
            [
                3.464101615138132e-5,
                3.464101615138188e-5,
                -0.9999958780710745,
            ],
            [
                4.598072006328534e-5,
                2.841848761658606e-5,
                0.9999957457184792,
            ],
            [
                4.598072006328534e-5,
                2.841848761658606e-5,
                -0.9999957457184792,
            ],
        ];
        let pole = |gid, z: f64, u2, u3| t(gid, &[(2, [u2, z]), (3, [u3, z])]);
        let mut tags = vec![
            pole(
                147,
                0.9999958780710745,
                1.5005692050237754e-6,
                -1.370444973174858e-5,
            ),
            t(313, &[(2, [-0.0001822661118060509, 0.99998514726758])]),
            t(266, &[(2, [-0.0001822661118060509, -0.99998514726758])]),
            pole(
                146,
                -0.9999958780710745,
                1.5005692050243438e-6,
                -1.3704449731749804e-5,
            ),
            t(397, &[(3, [-2.663923794710144e-5, 0.9999957457184792])]),
            t(354, &[(3, [-2.663923794710144e-5, -0.9999957457184792])]),
        ];
        assert!(Delaunay::try_new(&pts).is_ok());
        // today: refused (the caller falls back to the untagged kernel, its faces may differ)
        assert!(Delaunay::try_new_tagged(&pts, &tags).is_err());
        tags[3] = pole(
            146,
            -0.9999958780710745,
            1.5005692050237754e-6,
            -1.370444973174858e-5,
        );
        assert!(Delaunay::try_new_tagged(&pts, &tags).is_ok());
    }

    #[test]
    fn plane_rule_ignores_the_apex() {
        // F on plane 7, q inside its circumcircle; apex untagged or on another plane
        let a = t(0, &[(7, [0.0, 0.0])]);
        let b = t(1, &[(7, [1.0, 0.0])]);
        let c = t(2, &[(7, [0.0, 1.0])]);
        let qin = t(3, &[(7, [0.6, 0.6])]);
        let qout = t(4, &[(7, [2.0, 2.0])]);
        let d = t(5, &[(3, [0.0, 0.0])]);
        for apex in [Some(&d), None] {
            assert_eq!(rule([Some(&a), Some(&b), Some(&c), apex], &qin), Some(true));
            assert_eq!(
                rule([apex, Some(&b), Some(&c), Some(&a)], &qout),
                Some(false)
            );
        }
        // q on another plane: no rule
        assert_eq!(rule([Some(&a), Some(&b), Some(&c), Some(&d)], &d), None);
        assert!(degenerate([&a, &b, &c, &qin]));
        assert!(!degenerate([&a, &b, &c, &d]));
    }

    #[test]
    fn a_split_point_is_on_its_segment_whatever_its_rounding() {
        // a contour edge of plane 4 and its midpoint, rounded a little off the line in uv
        let a = t(10, &[(4, [0.1, 0.3])]);
        let b = t(11, &[(4, [0.7, 0.5])]);
        let mut m = t(20, &[(4, [0.4, 0.4 + 1e-17])]);
        assert_ne!(
            crate::geom::predicates::orient2d([0.1, 0.3], [0.7, 0.5], [0.4, 0.4 + 1e-17]),
            0.0
        );
        assert!(!on_one_line(&a, &b, &m));
        m.segment = Some([10, 11]);
        assert!(on_one_line(&a, &b, &m));
        // a second split point of the same edge, and the first one's ends
        let mut m2 = t(21, &[(4, [0.25, 0.35])]);
        m2.segment = Some([10, 11]);
        assert!(on_one_line(&a, &m, &m2) && on_one_line(&m2, &b, &m));
        // another edge's end is not on it
        let c = t(12, &[(4, [0.4, 0.9])]);
        assert!(!on_one_line(&a, &m, &c));
        let apex = t(5, &[(3, [0.0, 0.0])]);
        assert_eq!(
            rule([Some(&a), Some(&b), Some(&c), Some(&apex)], &m),
            Some(true)
        );
    }

    #[test]
    fn line_rule_between_the_edge_endpoints() {
        // points on the line of planes 1 and 2 (v = 0 in plane 1, u = 0 in plane 2)
        let on = |g: u64, s: f64| t(g, &[(2, [0.0, s]), (1, [s, 0.0])]);
        let (a, b) = (on(0, 0.0), on(1, 2.0));
        let c = t(2, &[(1, [1.0, 5.0])]);
        let d = t(3, &[(2, [4.0, 1.0])]);
        let v = [Some(&a), Some(&b), Some(&c), Some(&d)];
        assert_eq!(rule(v, &on(4, 1.0)), Some(true));
        assert_eq!(rule(v, &on(5, 3.0)), Some(false));
        assert!(on_one_line(&a, &b, &on(4, 1.0)));
        assert!(degenerate([&a, &c, &b, &on(4, 1.0)]));
        assert!(walk_degenerate(v, 2, &on(4, 1.0)));
        assert!(!walk_degenerate(v, 0, &on(4, 1.0)));
    }

    /// Six points of the shipped `odd033.json` (a cell of 91 points reduced): a row of five on
    /// oblique plane 5 that a common-line trim left nearly collinear (one of them on plane 7 too)
    /// and one on plane 7. Their (u,v) are another rounding of the ideal points than their 3D
    /// positions, and the circle through a nearly collinear triple is so large that the two
    /// roundings put the query on different sides of it: decided in (u,v), the plane rule
    /// contradicts the 3D predicates of the neighbouring mixed tetrahedra and the cavity is not
    /// star-shaped (the cell fell back to the untagged kernel). Decided through the plane's apex on
    /// the same floats as the 3D predicates, the triangulation is valid.
    #[test]
    fn a_nearly_collinear_row_on_an_oblique_plane_is_decided_on_the_3d_positions() {
        let pts = [
            [
                -0.03685385079472842,
                0.11043625904737553,
                -0.05036481637403165,
            ],
            [
                -0.07092104040270758,
                0.1476424478774026,
                -0.05608358522734733,
            ],
            [
                -0.07530388459264077,
                0.15242913417925225,
                -0.05681932206197219,
            ],
            [
                -0.07760104970692842,
                0.15493796367652335,
                -0.05720494128924898,
            ],
            [
                -0.09875865578302015,
                0.17773970213013973,
                -0.060564407180365404,
            ],
            [
                -0.22563535417657923,
                0.32059777587877186,
                -0.06854894904760728,
            ],
        ];
        let tags = vec![
            t(473, &[(5, [0.12029203715126621, -0.04025933627331001])]),
            t(498, &[(5, [0.15482620996737786, -0.0774745095249049])]),
            t(503, &[(5, [0.1592691336598282, -0.08226235107391563])]),
            t(504, &[(5, [0.16159778803800143, -0.08477178606692462])]),
            t(
                518,
                &[
                    (5, [0.18268460166788036, -0.10788446383023297]),
                    (7, [-0.19885815598959905, -0.0504555217639993]),
                ],
            ),
            t(1336, &[(7, [-0.3899164302840689, -0.058617296256634255])]),
        ];
        let apexes = PlaneApexes::new(vec![
            (
                5,
                [-1.519391115153065, -1.3734596676492947, -2.935190576642579],
            ),
            (
                7,
                [-2.777968901140287, -1.905886320907536, 1.0983045935636517],
            ),
        ]);
        use crate::delaunay::Delaunay;
        assert!(Delaunay::try_new_tagged(&pts, &tags).is_err());
        let dt = Delaunay::try_new_tagged_with(&pts, &tags, &apexes).unwrap();
        dt.is_valid().unwrap();
        assert!(dt.num_finite_tets() > 0);
    }

    /// A pyramid on a quadrilateral cut by its five planes: its top is on the four side planes (a corner of the
    /// cell where four faces meet, as in the shared Horsers, whose six such cells fell back to the
    /// untagged kernel when tags took at most three planes).
    #[test]
    fn a_corner_on_four_planes_is_tagged() {
        use crate::delaunay::Delaunay;
        let sub = |a: P, b: P| -> P { std::array::from_fn(|k| a[k] - b[k]) };
        let dot = |a: P, b: P| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: P, b: P| -> P {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let unit = |a: P| -> P {
            let l = dot(a, a).sqrt();
            a.map(|c| c / l)
        };
        // not a regular pyramid: its five corners would be cospherical across planes
        let top: P = [0.13, -0.07, 1.1];
        let base: [P; 4] = [
            [1.1, 0.9, 0.0],
            [-0.8, 1.2, 0.0],
            [-1.3, -0.7, 0.0],
            [0.9, -1.05, 0.0],
        ];
        // plane k (0..4) through the top and base edge k; plane 4 the base; frames (origin, u, v)
        let mut frames: Vec<(P, P, P)> = (0..4)
            .map(|k| {
                let (a, b) = (base[k], base[(k + 1) % 4]);
                let u = unit(sub(b, a));
                let n = unit(cross(sub(b, a), sub(top, a)));
                (top, u, cross(n, u))
            })
            .collect();
        frames.push(([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        let on = |p: P| -> Vec<u32> {
            (0..5u32)
                .filter(|&k| {
                    let (o, u, v) = frames[k as usize];
                    dot(sub(p, o), unit(cross(u, v))).abs() < 1e-12
                })
                .collect()
        };
        let mut pts = vec![top];
        pts.extend(base);
        for k in 0..4 {
            let (a, b) = (base[k], base[(k + 1) % 4]);
            // (weights that put no three of a face's points on one line)
            pts.push(std::array::from_fn(|i| {
                0.3 * a[i] + 0.45 * b[i] + 0.25 * top[i]
            }));
            pts.push(std::array::from_fn(|i| 0.6 * a[i] + 0.4 * top[i]));
        }
        pts.push([0.1, -0.2, 0.0]);
        let tags: Vec<PointTags> = pts
            .iter()
            .enumerate()
            .map(|(g, &p)| {
                let planes: Vec<(u32, [f64; 2])> = on(p)
                    .into_iter()
                    .map(|k| {
                        let (o, u, v) = frames[k as usize];
                        (k, [dot(sub(p, o), u), dot(sub(p, o), v)])
                    })
                    .collect();
                t(g as u64, &planes)
            })
            .collect();
        assert_eq!(tags[0].planes.len(), 4);
        let apexes = PlaneApexes::new(
            (0..5u32)
                .map(|k| {
                    let (o, u, v) = frames[k as usize];
                    (k, PlaneApexes::above(o, unit(cross(u, v)), 3.0))
                })
                .collect(),
        );
        for a in [PlaneApexes::default(), apexes] {
            let dt = Delaunay::try_new_tagged_with(&pts, &tags, &a).unwrap();
            dt.is_valid().unwrap();
            // the pyramid's volume, in tetrahedra none of which is flat
            let vol: f64 = dt
                .all_tets()
                .filter(|&t| !dt.is_infinite(t))
                .map(|t| {
                    let p = dt.tet_vertices(t).map(|w| pts[w as usize]);
                    dot(sub(p[1], p[0]), cross(sub(p[2], p[0]), sub(p[3], p[0]))).abs() / 6.0
                })
                .sum();
            let b = |k: usize| sub(base[k], base[0]);
            let area = 0.5 * (cross(b(1), b(2))[2] + cross(b(2), b(3))[2]);
            assert!((vol - area * top[2] / 3.0).abs() < 1e-12, "{vol}");
        }
    }
}
