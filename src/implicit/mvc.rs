//! Closed-form mean-value integral of a constant over a planar polygon, as seen from a point
//! (Bermano, Vaxman & Gotsman 2011, Appendix A, "a polyhedron with piecewise-constant boundary values").
//!
//! For a point x at signed height γ ≠ 0 above the plane of a polygon P, the mean-value weight of P is
//!
//! ```text
//!   I_P(x) = ∫_P dσ(y) / |y − x| = ∫_P |γ| / |y − x|⁴ dA(y)
//! ```
//!
//! (dσ is the area of P's projection onto the unit sphere around x). By Stokes' theorem it is a sum over
//! the directed boundary edges of P (outer loops counter-clockwise, holes clockwise). Our derivation
//! (checked against quadrature in the tests) uses the triangle fan from x', the foot of x on the plane:
//! for an edge p1→p2 (coordinates relative to x'), with `len = |p2 − p1|`, `h` the signed distance of x'
//! to the left of the edge, `s1, s2 = s1 + len` the positions of p1, p2 along the edge measured from the
//! foot of x' on the edge's line, and `c = sqrt(h² + γ²)`, polar integration of the triangle (x', p1, p2)
//! gives
//!
//! ```text
//!   I_e = h / (2 |γ| c) · (atan(s2 / c) − atan(s1 / c))
//!       = h / (2 |γ| c) · atan2(c · len, c² + s1 s2)
//! ```
//!
//! which is the paper's `L_e(y2 − x) − L_e(y1 − x)` up to the choice of the antiderivative; the paper's
//! corner weights `w_y = L_e2(y − x) − L_e1(y − x)` are the same sum regrouped by vertices. The single
//! `atan2` form is exact for the angle difference (it lies in (0, π)) and needs one transcendental per
//! edge. `I_P = Σ_e I_e`; the common factor `1 / (2|γ|)` is applied once per polygon.

/// One directed polygon edge in a plane's (u,v) frame, prepared for repeated evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    pub p1: [f64; 2],
    pub d: [f64; 2],
    pub len: f64,
    pub inv_len: f64,
}

impl Edge {
    /// `None` for a zero-length edge (it contributes nothing).
    pub fn new(p1: [f64; 2], p2: [f64; 2]) -> Option<Edge> {
        let d = [p2[0] - p1[0], p2[1] - p1[1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        if len > 0.0 && len.is_finite() {
            Some(Edge {
                p1,
                d,
                len,
                inv_len: 1.0 / len,
            })
        } else {
            None
        }
    }
}

/// Edges of closed loops (each loop's closing edge last → first included), zero-length edges dropped.
pub fn loop_edges<'a>(loops: impl IntoIterator<Item = &'a [[f64; 2]]>) -> Vec<Edge> {
    let mut out = Vec::new();
    for l in loops {
        let n = l.len();
        for i in 0..n {
            if let Some(e) = Edge::new(l[i], l[(i + 1) % n]) {
                out.push(e);
            }
        }
    }
    out
}

/// `2|γ| · I_e` for one edge, seen from the point with foot `q` and squared height `g2 > 0`.
#[inline(always)]
pub fn edge_term(e: &Edge, q: [f64; 2], g2: f64) -> f64 {
    let ax = e.p1[0] - q[0];
    let ay = e.p1[1] - q[1];
    // h = (a × d) / len: signed distance of q to the left of the edge; s1 = (d · a) / len.
    let h = (ax * e.d[1] - ay * e.d[0]) * e.inv_len;
    let s1 = (ax * e.d[0] + ay * e.d[1]) * e.inv_len;
    let s2 = s1 + e.len;
    let c2 = h * h + g2;
    let c = c2.sqrt();
    h / c * (c * e.len).atan2(c2 + s1 * s2)
}

/// `I_P(x)` for the region bounded by `edges`, x having foot `q` in the plane frame and height `gamma`
/// (must be non-zero: the integral diverges like 1/|γ| over the region).
pub fn region_integral(edges: &[Edge], q: [f64; 2], gamma: f64) -> f64 {
    let g2 = gamma * gamma;
    let mut s = 0.0;
    for e in edges {
        s += edge_term(e, q, g2);
    }
    s / (2.0 * gamma.abs())
}

/// Even-odd point-in-region test over closed loops (used only for points lying on a face's plane).
pub fn point_in_loops<'a>(q: [f64; 2], loops: impl IntoIterator<Item = &'a [[f64; 2]]>) -> bool {
    let mut inside = false;
    for l in loops {
        let n = l.len();
        for i in 0..n {
            let a = l[i];
            let b = l[(i + 1) % n];
            if (a[1] > q[1]) != (b[1] > q[1]) {
                let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                if q[0] < x {
                    inside = !inside;
                }
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss–Legendre nodes and weights on [0,1], 8 points.
    fn gauss8() -> ([f64; 8], [f64; 8]) {
        let x = [
            -0.960_289_856_497_536_2,
            -0.796_666_477_413_626_7,
            -0.525_532_409_916_329,
            -0.183_434_642_495_649_8,
            0.183_434_642_495_649_8,
            0.525_532_409_916_329,
            0.796_666_477_413_626_7,
            0.960_289_856_497_536_2,
        ];
        let w = [
            0.101_228_536_290_376_3,
            0.222_381_034_453_374_5,
            0.313_706_645_877_887_3,
            0.362_683_783_378_362,
            0.362_683_783_378_362,
            0.313_706_645_877_887_3,
            0.222_381_034_453_374_5,
            0.101_228_536_290_376_3,
        ];
        let mut xs = [0.0; 8];
        let mut ws = [0.0; 8];
        for i in 0..8 {
            xs[i] = 0.5 * (x[i] + 1.0);
            ws[i] = 0.5 * w[i];
        }
        (xs, ws)
    }

    /// ∫ over the rectangle [x0,x1]×[y0,y1] of |γ| / (|y − q|² + γ²)², composite Gauss rule.
    fn quad_rect(r: [f64; 4], q: [f64; 2], gamma: f64, n: usize) -> f64 {
        let (gx, gw) = gauss8();
        let (hx, hy) = ((r[1] - r[0]) / n as f64, (r[3] - r[2]) / n as f64);
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                for a in 0..8 {
                    for b in 0..8 {
                        let x = r[0] + (i as f64 + gx[a]) * hx - q[0];
                        let y = r[2] + (j as f64 + gx[b]) * hy - q[1];
                        let d = x * x + y * y + gamma * gamma;
                        s += gw[a] * gw[b] * hx * hy * gamma.abs() / (d * d);
                    }
                }
            }
        }
        s
    }

    /// Same integrand over a triangle, by the collapsed-square (Duffy) map.
    fn quad_tri(t: [[f64; 2]; 3], q: [f64; 2], gamma: f64, n: usize) -> f64 {
        let (gx, gw) = gauss8();
        let h = 1.0 / n as f64;
        let e1 = [t[1][0] - t[0][0], t[1][1] - t[0][1]];
        let e2 = [t[2][0] - t[0][0], t[2][1] - t[0][1]];
        let jac = (e1[0] * e2[1] - e1[1] * e2[0]).abs();
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                for a in 0..8 {
                    for b in 0..8 {
                        let u = (i as f64 + gx[a]) * h;
                        let v = (j as f64 + gx[b]) * h;
                        // (u, v) in the unit square → (u, u v) weight u on the triangle (0,0),(1,0),(1,1)
                        let (bu, bv) = (u - u * v, u * v);
                        let x = t[0][0] + bu * e1[0] + bv * e2[0] - q[0];
                        let y = t[0][1] + bu * e1[1] + bv * e2[1] - q[1];
                        let d = x * x + y * y + gamma * gamma;
                        s += gw[a] * gw[b] * h * h * u * jac * gamma.abs() / (d * d);
                    }
                }
            }
        }
        s
    }

    fn rect_loop(r: [f64; 4]) -> Vec<[f64; 2]> {
        vec![[r[0], r[2]], [r[1], r[2]], [r[1], r[3]], [r[0], r[3]]]
    }

    #[test]
    fn closed_form_matches_quadrature_on_rectangles() {
        let r = [-0.3, 0.5, -0.2, 0.4];
        let edges = loop_edges([rect_loop(r).as_slice()]);
        for (q, g) in [
            ([0.1, 0.1], 0.3),
            ([0.1, 0.1], -0.3),
            ([0.9, -0.7], 0.2),
            ([0.45, 0.35], 0.15),
            ([-0.3, 0.4], 0.5),
        ] {
            let closed = region_integral(&edges, q, g);
            let numeric = quad_rect(r, q, g, 24);
            assert!(
                (closed - numeric).abs() < 1e-6 * numeric.max(1.0),
                "q={q:?} γ={g}: closed {closed} vs quadrature {numeric}"
            );
        }
    }

    #[test]
    fn closed_form_matches_quadrature_on_triangles_and_holes() {
        let t = [[0.0, 0.0], [0.7, 0.1], [0.2, 0.6]];
        let edges = loop_edges([t.as_slice()]);
        for (q, g) in [([0.3, 0.2], 0.25), ([-0.5, 0.9], 0.4), ([0.7, 0.1], 0.3)] {
            let closed = region_integral(&edges, q, g);
            let numeric = quad_tri(t, q, g, 24);
            assert!(
                (closed - numeric).abs() < 1e-6 * numeric.max(1.0),
                "triangle q={q:?}: {closed} vs {numeric}"
            );
        }
        // A square with a clockwise square hole: the closed form over both loops equals the outer
        // integral minus the hole's.
        let outer = [-0.5, 0.5, -0.5, 0.5];
        let hole = [-0.2, 0.1, -0.1, 0.3];
        let mut hole_cw = rect_loop(hole);
        hole_cw.reverse();
        let outer_ccw = rect_loop(outer);
        let edges = loop_edges([outer_ccw.as_slice(), hole_cw.as_slice()]);
        let q = [0.05, 0.0];
        let g = 0.2;
        let closed = region_integral(&edges, q, g);
        let numeric = quad_rect(outer, q, g, 24) - quad_rect(hole, q, g, 24);
        assert!((closed - numeric).abs() < 1e-6 * numeric.max(1.0));
    }

    #[test]
    fn whole_plane_limit_is_the_half_sphere() {
        // A huge square seen from close by covers the half sphere: ∫ dσ / |y − x| → 2π/|γ|·(1/2)…
        // exactly: ∫_plane |γ|/(ρ²+γ²)² dA = π/|γ|.
        let r = [-1e6, 1e6, -1e6, 1e6];
        let edges = loop_edges([rect_loop(r).as_slice()]);
        for g in [0.5, 1.0, 2.0] {
            let v = region_integral(&edges, [0.3, -0.2], g);
            assert!((v - std::f64::consts::PI / g).abs() < 1e-9, "{v}");
        }
    }

    #[test]
    fn point_in_loops_even_odd() {
        let outer = rect_loop([0.0, 1.0, 0.0, 1.0]);
        let hole = rect_loop([0.4, 0.6, 0.4, 0.6]);
        let loops = [outer.as_slice(), hole.as_slice()];
        assert!(point_in_loops([0.2, 0.2], loops));
        assert!(!point_in_loops([0.5, 0.5], loops));
        assert!(!point_in_loops([1.5, 0.5], loops));
    }
}
