//! Moving contour vertices off an exact cosphericity across planes, where the tagged Delaunay
//! kernel cannot decide it.
//!
//! The kernel decides ties among points of one plane by the plane's own rules (`delaunay::tags`)
//! and every other decision by the float 3D predicates. Where points of two planes are exactly
//! cospherical for the input as given (a sphere or a cylinder centred on a fan's common line: its
//! sections are symmetric about the line), the two kinds of decision meet an ideal tie that each
//! settles by rounding, differently, and a cell's cavity is not star-shaped; the cell is then
//! triangulated untagged and the two cells of a face may triangulate it differently (a
//! non-conforming face, an open or crossing surface).
//!
//! The repair: every contour vertex that lies on its own plane only moves in that plane by a
//! distance far above the rounding of the predicates (1e-10 of the model's diagonal, and at most
//! 1e-4 of the shortest contour edge at its position, so that no contour can cross itself or
//! another), in a direction that is a hash of its coordinates (vertices at one position move
//! alike, so contours that touch still share their vertices). Vertices on a common line of two
//! planes stay where they are: the two sections agree there. The ideal ties are gone, and the
//! moves are 1e-10 of the diagonal: every section agrees with the input's to that order.
use crate::sections::{dot, Contour, Region, Sections};

/// How far a vertex moves, relative to the model's diagonal.
pub const GENERIC_MOVE_RELATIVE: f64 = 1e-10;

/// At most this fraction of the shortest contour edge at the vertex's position.
const MOVE_PER_EDGE: f64 = 1e-4;

/// A vertex within this many moves of another plane is on a common line: it stays.
const ON_LINE_MOVES: f64 = 1e3;

/// What [`move_to_generic_position`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GenericMoves {
    /// Contour vertices moved.
    pub moved: u64,
    /// Contour vertices left in place on a common line of two planes.
    pub kept_on_lines: u64,
    /// The longest move (absolute).
    pub max_move: f64,
}

/// `sections` with every contour vertex on its own plane only moved in the plane (module docs).
pub fn move_to_generic_position(sections: &Sections) -> (Sections, GenericMoves) {
    let diag = super::model_diagonal(sections);
    let step = GENERIC_MOVE_RELATIVE * diag;
    let on_line = ON_LINE_MOVES * step;
    let planes: Vec<_> = sections.sections.iter().map(|s| s.plane).collect();
    let mut out = sections.clone();
    let mut moves = GenericMoves::default();
    for (i, section) in out.sections.iter_mut().enumerate() {
        let plane = section.plane;
        let others: Vec<_> = (planes.iter().enumerate())
            .filter(|&(j, p)| j != i && dot(p.normal, plane.normal).abs() < 1.0 - 1e-12)
            .map(|(_, p)| *p)
            .collect();
        let on_a_line =
            |p: [f64; 3]| (others.iter()).any(|o| o.signed_distance(p).abs() <= on_line);
        let shortest = shortest_edges(section);
        let contours = (section.regions.iter_mut()).flat_map(|r| {
            let Region { outer, holes, .. } = r;
            std::iter::once(outer).chain(holes.iter_mut())
        });
        for c in contours {
            move_contour(c, step, &shortest, &on_a_line, &mut moves);
            c.points3 = c.points2.iter().map(|&q| plane.to_3d(q)).collect();
        }
    }
    (out, moves)
}

/// The bits of a 2D point: vertices of different contours at one position are one key.
type Key = [u64; 2];

fn key(q: [f64; 2]) -> Key {
    q.map(f64::to_bits)
}

/// Per vertex position of the section, its shortest contour edge over every contour through it
/// (so that a vertex two contours share moves alike in both).
fn shortest_edges(section: &crate::sections::Section) -> crate::fxhash::FxHashMap<Key, f64> {
    let mut out: crate::fxhash::FxHashMap<Key, f64> = Default::default();
    let contours = (section.regions.iter()).flat_map(|r| std::iter::once(&r.outer).chain(&r.holes));
    for c in contours {
        let n = c.points2.len();
        for k in 0..n {
            let (a, b) = (c.points2[k], c.points2[(k + 1) % n]);
            let len = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
            for q in [a, b] {
                let e = out.entry(key(q)).or_insert(f64::INFINITY);
                *e = e.min(len);
            }
        }
    }
    out
}

/// Move the vertices of `c` (its 2D coordinates) that are not `on_a_line`.
fn move_contour(
    c: &mut Contour,
    step: f64,
    shortest: &crate::fxhash::FxHashMap<Key, f64>,
    on_a_line: &impl Fn([f64; 3]) -> bool,
    moves: &mut GenericMoves,
) {
    for k in 0..c.points2.len() {
        if on_a_line(c.points3[k]) {
            moves.kept_on_lines += 1;
            continue;
        }
        let q = c.points2[k];
        let d = step.min(MOVE_PER_EDGE * shortest[&key(q)]);
        if d.is_nan() || d <= 0.0 {
            continue;
        }
        let angle = direction(q);
        c.points2[k] = [q[0] + d * angle.cos(), q[1] + d * angle.sin()];
        moves.moved += 1;
        moves.max_move = moves.max_move.max(d);
    }
}

/// An angle that depends only on the bits of `q` (a splitmix64 of them).
fn direction(q: [f64; 2]) -> f64 {
    let mut x = q[0].to_bits() ^ q[1].to_bits().rotate_left(29) ^ 0x9E37_79B9_7F4A_7C15;
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 31;
    (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sections::{Plane, Section};

    fn section(plane: Plane, loops: Vec<Vec<[f64; 3]>>) -> Section {
        let regions = loops
            .into_iter()
            .map(|l| Region {
                label: 1,
                outer: Contour::from_2d(&plane, l.iter().map(|&p| plane.to_2d(p)).collect()),
                holes: Vec::new(),
            })
            .collect();
        Section {
            plane,
            regions,
            source_index: 0,
            max_off_plane: 0.0,
        }
    }

    /// Plane z = 0 with two squares touching at (1, 1, 0) and a corner (0, 0, 0) on the plane
    /// x = 0 too; plane x = 0 with one square. The corners on the common line (the y axis) stay,
    /// every other vertex moves in its plane by the step, and the touching corner moves alike in
    /// both squares.
    #[test]
    fn vertices_move_in_their_planes_except_on_common_lines() {
        let z0 = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let x0 = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let square = |o: [f64; 3], a: [f64; 3], b: [f64; 3]| {
            let at = |s: f64, t: f64| [0, 1, 2].map(|k| o[k] + s * a[k] + t * b[k]);
            vec![at(0.0, 0.0), at(1.0, 0.0), at(1.0, 1.0), at(0.0, 1.0)]
        };
        let (ex, ey, ez) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        let sections = Sections {
            sections: vec![
                section(
                    z0,
                    vec![square([0.0; 3], ex, ey), square([1.0, 1.0, 0.0], ex, ey)],
                ),
                section(x0, vec![square([0.0, 0.0, 1.0], ey, ez)]),
            ],
            ..Default::default()
        };
        let (moved, stats) = move_to_generic_position(&sections);
        let step = GENERIC_MOVE_RELATIVE * crate::validate::model_diagonal(&sections);
        // on plane z = 0: (0,0,0) and (0,1,0) are on x = 0; nothing of x = 0's square is on z = 0
        assert_eq!((stats.moved, stats.kept_on_lines), (10, 2));
        assert!((stats.max_move - step).abs() <= 1e-9 * step);
        for (s, m) in sections.sections.iter().zip(&moved.sections) {
            for (r, n) in s.regions.iter().zip(&m.regions) {
                for (p, q) in r.outer.points3.iter().zip(&n.outer.points3) {
                    let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
                    let on_line = p[0] == 0.0 && p[2] == 0.0;
                    assert!(if on_line {
                        d == 0.0
                    } else {
                        d > 0.5 * step && d <= 1.01 * step
                    });
                    assert!(
                        m.plane.signed_distance(*q).abs() < 1e-15,
                        "{q:?} left its plane"
                    );
                }
            }
        }
        let corner = |r: usize, k: usize| moved.sections[0].regions[r].outer.points2[k];
        // (1, 1, 0): corner 2 of the first square, corner 0 of the second
        assert_eq!(corner(0, 2), corner(1, 0));
    }

    /// A vertex between two edges 1e-9 long moves at most 1e-4 of them: no contour crosses itself.
    #[test]
    fn short_edges_bound_the_move() {
        let z0 = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let tri = vec![[0.0, 0.0, 0.0], [1e-9, 0.0, 0.0], [0.0, 1e-9, 0.0]];
        let far = vec![[10.0, 10.0, 0.0], [11.0, 10.0, 0.0], [10.0, 11.0, 0.0]];
        let sections = Sections {
            sections: vec![section(z0, vec![tri, far])],
            ..Default::default()
        };
        let (moved, stats) = move_to_generic_position(&sections);
        assert_eq!(stats.moved, 6);
        let small = &moved.sections[0].regions[0].outer.points2;
        let orig = &sections.sections[0].regions[0].outer.points2;
        for (p, q) in orig.iter().zip(small) {
            let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
            assert!(d > 0.0 && d <= 1e-4 * 1e-9 * 1.0001, "{d:e}");
        }
        assert!(crate::validate::orientation(small) > 0.0);
    }

    /// Two triangles touching at (5, 5), one with edges of 1 there and one with an edge of 1e-8:
    /// the shared vertex moves alike in both, by the bound of the shorter edge.
    #[test]
    fn a_shared_vertex_moves_alike_in_every_contour() {
        let z0 = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let big = vec![[5.0, 5.0, 0.0], [6.0, 5.0, 0.0], [5.0, 6.0, 0.0]];
        let small = vec![[5.0, 5.0, 0.0], [5.0, 4.0, 0.0], [5.0 - 1e-8, 5.0, 0.0]];
        let sections = Sections {
            sections: vec![section(z0, vec![big, small])],
            ..Default::default()
        };
        let (moved, _) = move_to_generic_position(&sections);
        let at = |r: usize| moved.sections[0].regions[r].outer.points2[0];
        assert_eq!(at(0), at(1));
        let p = sections.sections[0].regions[0].outer.points2[0];
        let d = ((p[0] - at(0)[0]).powi(2) + (p[1] - at(0)[1]).powi(2)).sqrt();
        assert!(d > 0.0 && d <= 1e-4 * 1e-8 * 1.01, "{d:e}"); // the coordinates round it
    }
}
