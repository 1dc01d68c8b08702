//! Exact predicates (Shewchuk's adaptive arithmetic via the `robust` crate). Signs follow `robust`:
//! `orient2d > 0` when a,b,c are counter-clockwise; `orient3d > 0` when d lies below the plane of a,b,c
//! (a,b,c counter-clockwise seen from above); `incircle`/`insphere` > 0 when the point is inside
//! (for positively oriented a,b,c(,d)).
use robust::{Coord, Coord3D};

#[inline]
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    robust::orient2d(c2(a), c2(b), c2(c))
}
#[inline]
pub fn incircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    robust::incircle(c2(a), c2(b), c2(c), c2(d))
}
#[inline]
pub fn orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}
#[inline]
pub fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))
}
#[inline]
fn c2(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}
#[inline]
fn c3(p: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn sign_conventions() {
        assert!(orient2d([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]) > 0.0);
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!(orient3d(a, b, c, [0.0, 0.0, -1.0]) > 0.0);
        assert!(orient3d(a, b, c, [0.0, 0.0, 1.0]) < 0.0);
    }
}
