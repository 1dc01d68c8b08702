//! Exact signs of small polynomials in f64 inputs (Shewchuk-style expansion arithmetic).
//!
//! Used for the combinatorial decisions of the arrangement: the side of an arrangement vertex
//! (three planes) with respect to a fourth plane is the sign of a 4×4 determinant of plane
//! equations; the side of a contour vertex with respect to a plane is the sign of `n·p + d`.
//! Every function first tries a floating-point filter and falls back to exact expansions.

/// A nonoverlapping expansion, components in increasing magnitude, no zeros.
#[derive(Clone, Debug, Default)]
pub struct Expansion(pub Vec<f64>);

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    let br = b - bv;
    let ar = a - av;
    (x, ar + br)
}

#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    (x, a.mul_add(b, -x))
}

impl Expansion {
    pub fn product(a: f64, b: f64) -> Expansion {
        let (x, y) = two_product(a, b);
        let mut v = Vec::with_capacity(2);
        if y != 0.0 {
            v.push(y);
        }
        if x != 0.0 {
            v.push(x);
        }
        Expansion(v)
    }
    /// Shewchuk's GROW-EXPANSION with zero elimination.
    pub fn grow(&self, b: f64) -> Expansion {
        let mut h = Vec::with_capacity(self.0.len() + 1);
        let mut q = b;
        for &e in &self.0 {
            let (s, hh) = two_sum(q, e);
            if hh != 0.0 {
                h.push(hh);
            }
            q = s;
        }
        if q != 0.0 {
            h.push(q);
        }
        Expansion(h)
    }
    pub fn add(&self, other: &Expansion) -> Expansion {
        let mut acc = self.clone();
        for &f in &other.0 {
            acc = acc.grow(f);
        }
        acc
    }
    pub fn neg(&self) -> Expansion {
        Expansion(self.0.iter().map(|x| -x).collect())
    }
    pub fn sub(&self, other: &Expansion) -> Expansion {
        self.add(&other.neg())
    }
    /// Shewchuk's SCALE-EXPANSION with zero elimination (two_sum in place of fast_two_sum).
    pub fn scale(&self, b: f64) -> Expansion {
        let e = &self.0;
        let mut h = Vec::with_capacity(2 * e.len());
        if e.is_empty() || b == 0.0 {
            return Expansion(h);
        }
        let (mut q, hh) = two_product(e[0], b);
        if hh != 0.0 {
            h.push(hh);
        }
        for &ei in &e[1..] {
            let (t1, t0) = two_product(ei, b);
            let (sum, hh) = two_sum(q, t0);
            if hh != 0.0 {
                h.push(hh);
            }
            let (q2, hh) = two_sum(t1, sum);
            if hh != 0.0 {
                h.push(hh);
            }
            q = q2;
        }
        if q != 0.0 {
            h.push(q);
        }
        Expansion(h)
    }
    pub fn mul(&self, other: &Expansion) -> Expansion {
        let mut acc = Expansion::default();
        for &f in &other.0 {
            acc = acc.add(&self.scale(f));
        }
        acc
    }
    pub fn sign(&self) -> i8 {
        match self.0.last() {
            None => 0,
            Some(&x) if x > 0.0 => 1,
            Some(_) => -1,
        }
    }
    /// Approximate value (sum of the components).
    #[allow(dead_code)]
    pub fn estimate(&self) -> f64 {
        self.0.iter().sum()
    }
}

#[inline]
fn fsign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// Exact sign of `a·b + c` for 3-vectors a, b (used for `n·p + d`).
pub fn sign_dot_plus(a: [f64; 3], b: [f64; 3], c: f64) -> i8 {
    let v = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + c;
    let mag = (a[0] * b[0]).abs() + (a[1] * b[1]).abs() + (a[2] * b[2]).abs() + c.abs();
    if v.abs() > 8.0 * f64::EPSILON * mag {
        return fsign(v);
    }
    dot_plus(a, b, c).sign()
}

/// `a·b + c` as an exact expansion.
pub fn dot_plus(a: [f64; 3], b: [f64; 3], c: f64) -> Expansion {
    Expansion::product(a[0], b[0])
        .add(&Expansion::product(a[1], b[1]))
        .add(&Expansion::product(a[2], b[2]))
        .grow(c)
}

/// Exact sign of the 3×3 determinant with rows a, b, c.
pub fn sign_det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> i8 {
    let m0 = a[0] * (b[1] * c[2] - b[2] * c[1]);
    let m1 = a[1] * (b[0] * c[2] - b[2] * c[0]);
    let m2 = a[2] * (b[0] * c[1] - b[1] * c[0]);
    let det = m0 - m1 + m2;
    let perm = a[0].abs() * ((b[1] * c[2]).abs() + (b[2] * c[1]).abs())
        + a[1].abs() * ((b[0] * c[2]).abs() + (b[2] * c[0]).abs())
        + a[2].abs() * ((b[0] * c[1]).abs() + (b[1] * c[0]).abs());
    if det.abs() > 16.0 * f64::EPSILON * perm {
        return fsign(det);
    }
    let minor =
        |p: f64, q: f64, r: f64, s: f64| Expansion::product(p, q).sub(&Expansion::product(r, s));
    let e0 = minor(b[1], c[2], b[2], c[1]).scale(a[0]);
    let e1 = minor(b[0], c[2], b[2], c[0]).scale(a[1]);
    let e2 = minor(b[0], c[1], b[1], c[0]).scale(a[2]);
    e0.sub(&e1).add(&e2).sign()
}

/// Exact sign of the 4×4 determinant with rows `m[0..4]`.
pub fn sign_det4(m: [[f64; 4]; 4]) -> i8 {
    // Laplace expansion along the first two rows: sum over column pairs S of
    // (-1)^(1+c1+c2) det(rows01, S) det(rows23, complement S).
    const PAIRS: [(usize, usize, usize, usize, f64); 6] = [
        (0, 1, 2, 3, 1.0),
        (0, 2, 1, 3, -1.0),
        (0, 3, 1, 2, 1.0),
        (1, 2, 0, 3, 1.0),
        (1, 3, 0, 2, -1.0),
        (2, 3, 0, 1, 1.0),
    ];
    let mut det = 0.0;
    let mut perm = 0.0;
    for &(a, b, c, d, s) in &PAIRS {
        let top = m[0][a] * m[1][b] - m[0][b] * m[1][a];
        let bot = m[2][c] * m[3][d] - m[2][d] * m[3][c];
        let ptop = (m[0][a] * m[1][b]).abs() + (m[0][b] * m[1][a]).abs();
        let pbot = (m[2][c] * m[3][d]).abs() + (m[2][d] * m[3][c]).abs();
        det += s * top * bot;
        perm += ptop * pbot;
    }
    if det.abs() > 32.0 * f64::EPSILON * perm {
        return fsign(det);
    }
    det4_exact(m).sign()
}

pub fn det4_exact(m: [[f64; 4]; 4]) -> Expansion {
    const PAIRS: [(usize, usize, usize, usize, bool); 6] = [
        (0, 1, 2, 3, false),
        (0, 2, 1, 3, true),
        (0, 3, 1, 2, false),
        (1, 2, 0, 3, false),
        (1, 3, 0, 2, true),
        (2, 3, 0, 1, false),
    ];
    let mut acc = Expansion::default();
    for &(a, b, c, d, negate) in &PAIRS {
        let top = Expansion::product(m[0][a], m[1][b]).sub(&Expansion::product(m[0][b], m[1][a]));
        let bot = Expansion::product(m[2][c], m[3][d]).sub(&Expansion::product(m[2][d], m[3][c]));
        let term = top.mul(&bot);
        acc = if negate {
            acc.sub(&term)
        } else {
            acc.add(&term)
        };
    }
    acc
}

/// True when the two plane equations are equal up to a nonzero scale (all 2×2 minors vanish).
pub fn same_plane(a: [f64; 4], b: [f64; 4]) -> bool {
    for i in 0..4 {
        for j in i + 1..4 {
            let m = Expansion::product(a[i], b[j]).sub(&Expansion::product(a[j], b[i]));
            if m.sign() != 0 {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn det4_identity_and_permutation() {
        let id = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(sign_det4(id), 1);
        assert_eq!(det4_exact(id).sign(), 1);
        let sw = [id[1], id[0], id[2], id[3]];
        assert_eq!(sign_det4(sw), -1);
        assert_eq!(det4_exact(sw).sign(), -1);
        let sw2 = [id[0], id[1], id[3], id[2]];
        assert_eq!(det4_exact(sw2).sign(), -1);
        let cyc = [id[1], id[2], id[3], id[0]];
        assert_eq!(det4_exact(cyc).sign(), -1);
    }

    #[test]
    fn det4_exact_matches_float_on_random() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for _ in 0..2000 {
            let mut m = [[0.0; 4]; 4];
            for r in &mut m {
                for x in r.iter_mut() {
                    *x = rng.gen_range(-1.0..1.0);
                }
            }
            let e = det4_exact(m).estimate();
            // Reference by cofactor expansion along the first row in f64.
            let d3 = |r: [[f64; 3]; 3]| {
                r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
                    - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
                    + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0])
            };
            let mut f = 0.0;
            for c in 0..4 {
                let mut sub = [[0.0; 3]; 3];
                for r in 1..4 {
                    let mut k = 0;
                    for (cc, &x) in m[r].iter().enumerate() {
                        if cc != c {
                            sub[r - 1][k] = x;
                            k += 1;
                        }
                    }
                }
                let s = if c % 2 == 0 { 1.0 } else { -1.0 };
                f += s * m[0][c] * d3(sub);
            }
            assert!((e - f).abs() < 1e-12, "{e} vs {f}");
            assert_eq!(sign_det4(m), fsign(f));
        }
    }

    #[test]
    fn exact_zero_on_dependent_rows() {
        // Row 3 = row 0 + row 1 in exact arithmetic with awkward values.
        let a = [0.1, 0.7, -0.3, 1e-9];
        let b = [0.3, -0.2, 0.9, 0.123456789];
        let c = [0.5, 0.25, 0.125, 3.0];
        let d = [0.1 + 0.3, 0.7 - 0.2, -0.3 + 0.9, 1e-9 + 0.123456789];
        // Not exactly dependent after rounding in general; use exact multiples instead.
        let _ = d;
        let d2 = [2.0 * a[0], 2.0 * a[1], 2.0 * a[2], 2.0 * a[3]];
        assert_eq!(sign_det4([a, b, c, d2]), 0);
        assert!(same_plane(a, d2));
        assert!(!same_plane(a, b));
        assert_eq!(
            sign_det3([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.3, 0.1, 0.7]),
            0
        );
        assert_eq!(
            sign_det3([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            1
        );
        assert_eq!(
            sign_dot_plus([0.1, 0.2, 0.3], [1.0, 1.0, 1.0], -0.6000000000000001),
            dot_plus([0.1, 0.2, 0.3], [1.0, 1.0, 1.0], -0.6000000000000001).sign()
        );
    }
}
