//! Geometric decisions of the kernel, all exact, with symbolic perturbation for ties.
//!
//! Sign convention inside the kernel: a tetrahedron (a,b,c,d) is *positive* when its volume
//! (b-a)·((c-a)×(d-a)) is positive, which is `robust::orient3d(a,b,c,d) < 0`.
//! The perturbation follows Devillers & Teillaud (2011), as in CGAL's `Delaunay_triangulation_3`:
//! points are ordered lexicographically; an exactly cospherical 5-tuple is decided by the
//! orientation of the tetrahedron in which the largest point is replaced by the query (twice at most);
//! an exactly coplanar point on a hull facet is decided by the perturbed in-circle test of that facet.
//!
//! One file on purpose (it is long, a third of it tests): the static and semi-static filters, the
//! double-double stage and the exact fallback of each predicate share their error bounds and are
//! checked against each other, so they are read together.
use crate::geom::predicates as gp;

pub type P = [f64; 3];

/// Static error bounds of the orient and insphere filters, valid for points whose coordinates differ
/// by at most `ext` on every axis (the largest side of their bounding box): a determinant beyond them
/// has its exact sign without computing the per-call (semi-static) bound. `NONE` never decides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub orient: f64,
    pub insphere: f64,
}

impl Bounds {
    pub const NONE: Bounds = Bounds {
        orient: f64::INFINITY,
        insphere: f64::INFINITY,
    };

    /// Bounds for points whose coordinate differences are at most `ext`. The semi-static bounds are
    /// at most O3D_BOUND·mx·my·mz and ISP_BOUND·M²·mx·my·mz with every factor ≤ ext (computed
    /// differences may exceed ext by a rounding, covered by the 1.001 in the constants). Outside
    /// [1e-30, 1e30] (underflow could then matter, or overflow) it is `NONE`.
    pub fn for_extent(ext: f64) -> Bounds {
        if !(1e-30..=1e30).contains(&ext) {
            return Bounds::NONE;
        }
        let e3 = ext * ext * ext * (1.0 + 1e-12);
        Bounds {
            orient: O3D_BOUND * e3,
            insphere: ISP_BOUND * e3 * ext * ext * (1.0 + 1e-12),
        }
    }

    /// Largest side of the bounding box [lo, hi].
    pub fn extent(lo: P, hi: P) -> f64 {
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    }
}

/// Positive when (a,b,c,d) has positive volume, negative when negative, 0 when coplanar. Exact sign
/// (the magnitude approximates 6 × volume).
#[inline(always)]
pub fn orient(a: P, b: P, c: P, d: P) -> f64 {
    orient_within(a, b, c, d, f64::INFINITY)
}

/// [`orient`] for points within the extent of static bound `sb` (`Bounds::orient`).
#[inline(always)]
pub fn orient_within(a: P, b: P, c: P, d: P, sb: f64) -> f64 {
    let (det, bound) = orient3d_filter(a, b, c, d, sb);
    if det > bound || -det > bound {
        return -det;
    }
    if bound == 0.0 {
        // the points share one coordinate exactly (a section on an axis plane): coplanar
        return 0.0;
    }
    if let Some(det) = orient3d_dd(a, b, c, d) {
        return -det;
    }
    -gp::orient3d(a, b, c, d)
}

/// Positive when e is strictly inside the circumsphere of the positive tetrahedron (a,b,c,d),
/// negative outside, 0 on it. Exact sign.
#[inline(always)]
pub fn insphere(a: P, b: P, c: P, d: P, e: P) -> f64 {
    insphere_within(a, b, c, d, e, f64::INFINITY)
}

/// [`insphere`] for points within the extent of static bound `sb` (`Bounds::insphere`).
#[inline(always)]
pub fn insphere_within(a: P, b: P, c: P, d: P, e: P, sb: f64) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        let det = insphere_det_packed(a, b, c, d, e);
        if det > sb || -det > sb {
            return -det;
        }
    }
    let (det, bound) = insphere_filter(a, b, c, d, e, sb);
    if det > bound || -det > bound {
        return -det;
    }
    if bound == 0.0 {
        // the points share one coordinate exactly: every 3×3 minor, hence the determinant, is 0
        return 0.0;
    }
    if let Some(det) = insphere_dd(a, b, c, d, e) {
        return -det;
    }
    -gp::insphere(a, b, c, d, e)
}

// Double-double stage between the filter and `robust`'s adaptive insphere, for the nearly coplanar
// 5-tuples that sections on tilted planes produce in bulk: there the determinant is about
// ε·permanent, below Shewchuk's stage-B bound, and `robust` went on to its tail and exact stages
// (zero-filling 30 KB of expansion buffers per call; most of the Elephant's run time). Here the
// coordinate differences are formed exactly (as double-doubles) and the determinant is evaluated in
// double-double, within ~2^-100 × permanent of the exact value; when it clears a bound far above that
// error its sign is the exact sign, otherwise (exact zeros, extreme exponents) `robust` decides.
type Dd = (f64, f64);

#[inline(always)]
fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline(always)]
fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    (s, b - (s - a))
}

#[inline(always)]
fn split(a: f64) -> Dd {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// a·b = p + e exactly (Dekker's splitting, or one fused multiply-add when `FMA`: the same exact
/// pair either way, so the stages below give bit-identical results with or without FMA).
#[inline(always)]
fn two_prod<const FMA: bool>(a: f64, b: f64) -> Dd {
    let p = a * b;
    if FMA {
        return (p, a.mul_add(b, -p));
    }
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
}

#[inline(always)]
fn dd_add(x: Dd, y: Dd) -> Dd {
    let (sh, sl) = two_sum(x.0, y.0);
    let (th, tl) = two_sum(x.1, y.1);
    let (sh, sl) = fast_two_sum(sh, sl + th);
    fast_two_sum(sh, sl + tl)
}

#[inline(always)]
fn dd_sub(x: Dd, y: Dd) -> Dd {
    dd_add(x, (-y.0, -y.1))
}

/// The cross terms are plain products (not fused even with `FMA`, to stay bit-identical).
#[inline(always)]
fn dd_mul<const FMA: bool>(x: Dd, y: Dd) -> Dd {
    let (p, e) = two_prod::<FMA>(x.0, y.0);
    fast_two_sum(p, e + (x.0 * y.1 + x.1 * y.0))
}

/// Whether the CPU has fused multiply-add (detected once; the double-double stages then take their
/// FMA build, about a third fewer operations per product).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn has_fma() -> bool {
    use std::sync::atomic::{AtomicU8, Ordering};
    static FMA: AtomicU8 = AtomicU8::new(0);
    match FMA.load(Ordering::Relaxed) {
        1 => false,
        2 => true,
        _ => {
            let yes = std::arch::is_x86_feature_detected!("fma");
            FMA.store(1 + yes as u8, Ordering::Relaxed);
            yes
        }
    }
}

/// `robust::insphere`'s determinant (its sign convention) when double-double arithmetic certifies
/// its sign, else `None`.
fn insphere_dd(a: P, b: P, c: P, d: P, e: P) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    if has_fma() {
        // SAFETY: the CPU has FMA (checked above).
        return unsafe { insphere_dd_fma(a, b, c, d, e) };
    }
    insphere_dd_with::<false>(a, b, c, d, e)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn insphere_dd_fma(a: P, b: P, c: P, d: P, e: P) -> Option<f64> {
    insphere_dd_with::<true>(a, b, c, d, e)
}

#[inline(always)]
fn insphere_dd_with<const FMA: bool>(a: P, b: P, c: P, d: P, e: P) -> Option<f64> {
    let diff = |p: P| [0, 1, 2].map(|k| two_sum(p[k], -e[k]));
    let (pa, pb, pc, pd) = (diff(a), diff(b), diff(c), diff(d));
    let m = [pa, pb, pc, pd]
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.0.abs()));
    // keep products far from overflow and underflow (else `robust`)
    if !(m > 1e-30 && m < 1e30) {
        return None;
    }
    let [aex, aey, aez] = pa;
    let [bex, bey, bez] = pb;
    let [cex, cey, cez] = pc;
    let [dex, dey, dez] = pd;
    // an upper bound of the permanent (absolute values of every product of the expansion)
    let h = |x: Dd| x.0.abs() * (1.0 + 1e-10);
    let m2 = |p: Dd, q: Dd, r: Dd, s: Dd| h(p) * h(q) + h(r) * h(s);
    let (ab, bc, cd) = (
        m2(aex, bey, bex, aey),
        m2(bex, cey, cex, bey),
        m2(cex, dey, dex, cey),
    );
    let (da, ac, bd) = (
        m2(dex, aey, aex, dey),
        m2(aex, cey, cex, aey),
        m2(bex, dey, dex, bey),
    );
    let lift = |x: Dd, y: Dd, z: Dd| h(x) * h(x) + h(y) * h(y) + h(z) * h(z);
    let permanent = (cd * h(bez) + bd * h(cez) + bc * h(dez)) * lift(aex, aey, aez)
        + (da * h(cez) + ac * h(dez) + cd * h(aez)) * lift(bex, bey, bez)
        + (ab * h(dez) + bd * h(aez) + da * h(bez)) * lift(cex, cey, cez)
        + (bc * h(aez) + ac * h(bez) + ab * h(cez)) * lift(dex, dey, dez);
    let minor = |p: Dd, q: Dd, r: Dd, s: Dd| dd_sub(dd_mul::<FMA>(p, q), dd_mul::<FMA>(r, s));
    let ab = minor(aex, bey, bex, aey);
    let bc = minor(bex, cey, cex, bey);
    let cd = minor(cex, dey, dex, cey);
    let da = minor(dex, aey, aex, dey);
    let ac = minor(aex, cey, cex, aey);
    let bd = minor(bex, dey, dex, bey);
    let abc = dd_add(
        dd_sub(dd_mul::<FMA>(bc, aez), dd_mul::<FMA>(ac, bez)),
        dd_mul::<FMA>(ab, cez),
    );
    let bcd = dd_add(
        dd_sub(dd_mul::<FMA>(cd, bez), dd_mul::<FMA>(bd, cez)),
        dd_mul::<FMA>(bc, dez),
    );
    let cda = dd_add(
        dd_add(dd_mul::<FMA>(da, cez), dd_mul::<FMA>(ac, dez)),
        dd_mul::<FMA>(cd, aez),
    );
    let dab = dd_add(
        dd_add(dd_mul::<FMA>(ab, dez), dd_mul::<FMA>(bd, aez)),
        dd_mul::<FMA>(da, bez),
    );
    let lift = |x: Dd, y: Dd, z: Dd| {
        dd_add(
            dd_add(dd_mul::<FMA>(x, x), dd_mul::<FMA>(y, y)),
            dd_mul::<FMA>(z, z),
        )
    };
    let (al, bl, cl, dl) = (
        lift(aex, aey, aez),
        lift(bex, bey, bez),
        lift(cex, cey, cez),
        lift(dex, dey, dez),
    );
    let det = dd_add(
        dd_sub(dd_mul::<FMA>(dl, abc), dd_mul::<FMA>(cl, dab)),
        dd_sub(dd_mul::<FMA>(bl, cda), dd_mul::<FMA>(al, bcd)),
    );
    let det = det.0 + det.1;
    // ~40 double-double operations deep, each within 2^-100 of its operands' magnitudes: the
    // error is far below 1e-24 × permanent. The absolute term covers underflow of the low parts when
    // some differences are tiny: each costs at most ~1e-308 times a cofactor below 1e120 (m < 1e30).
    let bound = 1e-24 * permanent + 1e-150;
    (det > bound || -det > bound).then_some(det)
}

/// `robust::orient3d`'s determinant (its sign convention) when double-double arithmetic certifies
/// its sign, else `None` (exact zeros among them). For four nearly coplanar points on a tilted
/// plane (every point of a cell lies on one of its faces) the filter fails and `robust` would go
/// to its tail and exact stages.
fn orient3d_dd(a: P, b: P, c: P, d: P) -> Option<f64> {
    #[cfg(target_arch = "x86_64")]
    if has_fma() {
        // SAFETY: the CPU has FMA (checked above).
        return unsafe { orient3d_dd_fma(a, b, c, d) };
    }
    orient3d_dd_with::<false>(a, b, c, d)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn orient3d_dd_fma(a: P, b: P, c: P, d: P) -> Option<f64> {
    orient3d_dd_with::<true>(a, b, c, d)
}

#[inline(always)]
fn orient3d_dd_with<const FMA: bool>(a: P, b: P, c: P, d: P) -> Option<f64> {
    let diff = |p: P| [0, 1, 2].map(|k| two_sum(p[k], -d[k]));
    let (pa, pb, pc) = (diff(a), diff(b), diff(c));
    let m = [pa, pb, pc]
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.0.abs()));
    // keep products far from overflow and underflow (else `robust`)
    if !(m > 1e-30 && m < 1e30) {
        return None;
    }
    let [adx, ady, adz] = pa;
    let [bdx, bdy, bdz] = pb;
    let [cdx, cdy, cdz] = pc;
    // an upper bound of the permanent
    let h = |x: Dd| x.0.abs() * (1.0 + 1e-10);
    let permanent = h(adz) * (h(bdx) * h(cdy) + h(cdx) * h(bdy))
        + h(bdz) * (h(cdx) * h(ady) + h(adx) * h(cdy))
        + h(cdz) * (h(adx) * h(bdy) + h(bdx) * h(ady));
    let mul = dd_mul::<FMA>;
    let det = dd_add(
        dd_add(
            mul(adz, dd_sub(mul(bdx, cdy), mul(cdx, bdy))),
            mul(bdz, dd_sub(mul(cdx, ady), mul(adx, cdy))),
        ),
        mul(cdz, dd_sub(mul(adx, bdy), mul(bdx, ady))),
    );
    let det = det.0 + det.1;
    // ~10 double-double operations deep, each within 2^-100 of its operands' magnitudes; the
    // absolute term covers underflow of the low parts (cofactors below 1e60 as m < 1e30).
    let bound = 1e-24 * permanent + 1e-200;
    (det > bound || -det > bound).then_some(det)
}

// Semi-static filters. They evaluate Shewchuk's determinants (same expressions as his orient3d and
// insphere, hence the same signs as `robust`) and bound the rounding error from the largest
// coordinate differences instead of the permanent: Shewchuk's bounds are (7+56ε)ε·permanent and
// (16+224ε)ε·permanent, and the permanents are at most 6·mx·my·mz and 72·M²·mx·my·mz (mx = largest
// |x difference|, M = max(mx,my,mz)). Outside a safe exponent range the bound is +∞, so the caller
// falls back to the adaptive exact predicate. A bound of +∞ is also returned for NaN.
const EPS: f64 = f64::EPSILON / 2.0;
const O3D_BOUND: f64 = (7.0 + 56.0 * EPS) * EPS * 6.0 * 1.001;
const ISP_BOUND: f64 = (16.0 + 224.0 * EPS) * EPS * 72.0 * 1.001;

#[inline(always)]
fn in_safe_range(lo: f64, hi: f64) -> bool {
    lo > 1e-55 && hi < 1e55
}

#[inline(always)]
fn orient3d_filter(a: P, b: P, c: P, d: P, sb: f64) -> (f64, f64) {
    let (adx, ady, adz) = (a[0] - d[0], a[1] - d[1], a[2] - d[2]);
    let (bdx, bdy, bdz) = (b[0] - d[0], b[1] - d[1], b[2] - d[2]);
    let (cdx, cdy, cdz) = (c[0] - d[0], c[1] - d[1], c[2] - d[2]);
    let det = adz * (bdx * cdy - cdx * bdy)
        + bdz * (cdx * ady - adx * cdy)
        + cdz * (adx * bdy - bdx * ady);
    if det > sb || -det > sb {
        return (det, sb);
    }
    let mx = adx.abs().max(bdx.abs()).max(cdx.abs());
    let my = ady.abs().max(bdy.abs()).max(cdy.abs());
    let mz = adz.abs().max(bdz.abs()).max(cdz.abs());
    let lo = mx.min(my).min(mz);
    let hi = mx.max(my).max(mz);
    if lo == 0.0 && !det.is_nan() {
        // one coordinate equal in all four points: the determinant is exactly 0 (bound 0 says so)
        return (0.0, 0.0);
    }
    if !in_safe_range(lo, hi) {
        return (det, f64::INFINITY);
    }
    (det, O3D_BOUND * mx * my * mz)
}

/// The determinant of [`insphere_filter`], bit for bit (the same operations on the same operands, in
/// the same order), with two lanes of SSE2 (baseline on x86_64) doing pairs of them: (x, y) of a
/// point difference, pairs of 2×2 minors, of 3×3 minors and of lifts.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn insphere_det_packed(a: P, b: P, c: P, d: P, e: P) -> f64 {
    use std::arch::x86_64::*;
    // SAFETY: SSE2 is part of the x86_64 baseline; the loads read two f64 of a [f64; 3].
    unsafe {
        let exy = _mm_loadu_pd(e.as_ptr());
        let ez = _mm_set1_pd(e[2]);
        let ad = _mm_sub_pd(_mm_loadu_pd(a.as_ptr()), exy); // [aex, aey]
        let bd = _mm_sub_pd(_mm_loadu_pd(b.as_ptr()), exy);
        let cd = _mm_sub_pd(_mm_loadu_pd(c.as_ptr()), exy);
        let dd = _mm_sub_pd(_mm_loadu_pd(d.as_ptr()), exy);
        let z_ab = _mm_sub_pd(_mm_set_pd(b[2], a[2]), ez); // [aez, bez]
        let z_cd = _mm_sub_pd(_mm_set_pd(d[2], c[2]), ez); // [cez, dez]
        let z_bc = _mm_shuffle_pd(z_ab, z_cd, 0b01); // [bez, cez]
        let z_da = _mm_shuffle_pd(z_cd, z_ab, 0b01); // [dez, aez]
        let x_ab = _mm_unpacklo_pd(ad, bd); // [aex, bex]
        let y_ab = _mm_unpackhi_pd(ad, bd); // [aey, bey]
        let x_bc = _mm_unpacklo_pd(bd, cd);
        let y_bc = _mm_unpackhi_pd(bd, cd);
        let x_cd = _mm_unpacklo_pd(cd, dd);
        let y_cd = _mm_unpackhi_pd(cd, dd);
        let x_da = _mm_unpacklo_pd(dd, ad);
        let y_da = _mm_unpackhi_pd(dd, ad);
        // [ab, bc], [cd, da], [ac, bd]
        let m_abbc = _mm_sub_pd(_mm_mul_pd(x_ab, y_bc), _mm_mul_pd(x_bc, y_ab));
        let m_cdda = _mm_sub_pd(_mm_mul_pd(x_cd, y_da), _mm_mul_pd(x_da, y_cd));
        let m_acbd = _mm_sub_pd(_mm_mul_pd(x_ab, y_cd), _mm_mul_pd(x_cd, y_ab));
        let m_bccd = _mm_shuffle_pd(m_abbc, m_cdda, 0b01); // [bc, cd]
        let m_daab = _mm_shuffle_pd(m_cdda, m_abbc, 0b01); // [da, ab]
                                                           // [abc, bcd] = [aez, bez]·[bc, cd] - [bez, cez]·[ac, bd] + [cez, dez]·[ab, bc]
        let t1 = _mm_add_pd(
            _mm_sub_pd(_mm_mul_pd(z_ab, m_bccd), _mm_mul_pd(z_bc, m_acbd)),
            _mm_mul_pd(z_cd, m_abbc),
        );
        // [cda, dab] = [cez, dez]·[da, ab] + [dez, aez]·[ac, bd] + [aez, bez]·[cd, da]
        let t2 = _mm_add_pd(
            _mm_add_pd(_mm_mul_pd(z_cd, m_daab), _mm_mul_pd(z_da, m_acbd)),
            _mm_mul_pd(z_ab, m_cdda),
        );
        // [alift, blift], [clift, dlift]
        let l_ab = _mm_add_pd(
            _mm_add_pd(_mm_mul_pd(x_ab, x_ab), _mm_mul_pd(y_ab, y_ab)),
            _mm_mul_pd(z_ab, z_ab),
        );
        let l_cd = _mm_add_pd(
            _mm_add_pd(_mm_mul_pd(x_cd, x_cd), _mm_mul_pd(y_cd, y_cd)),
            _mm_mul_pd(z_cd, z_cd),
        );
        let l_db = _mm_shuffle_pd(l_cd, l_ab, 0b11); // [dlift, blift]
        let l_ca = _mm_shuffle_pd(l_cd, l_ab, 0b00); // [clift, alift]
        let t_abc_cda = _mm_shuffle_pd(t1, t2, 0b00); // [abc, cda]
        let t_dab_bcd = _mm_shuffle_pd(t2, t1, 0b11); // [dab, bcd]
                                                      // [dlift·abc - clift·dab, blift·cda - alift·bcd], then the sum of the two lanes
        let h = _mm_sub_pd(_mm_mul_pd(l_db, t_abc_cda), _mm_mul_pd(l_ca, t_dab_bcd));
        _mm_cvtsd_f64(h) + _mm_cvtsd_f64(_mm_unpackhi_pd(h, h))
    }
}

#[inline(always)]
fn insphere_filter(a: P, b: P, c: P, d: P, e: P, sb: f64) -> (f64, f64) {
    let (aex, aey, aez) = (a[0] - e[0], a[1] - e[1], a[2] - e[2]);
    let (bex, bey, bez) = (b[0] - e[0], b[1] - e[1], b[2] - e[2]);
    let (cex, cey, cez) = (c[0] - e[0], c[1] - e[1], c[2] - e[2]);
    let (dex, dey, dez) = (d[0] - e[0], d[1] - e[1], d[2] - e[2]);
    let ab = aex * bey - bex * aey;
    let bc = bex * cey - cex * bey;
    let cd = cex * dey - dex * cey;
    let da = dex * aey - aex * dey;
    let ac = aex * cey - cex * aey;
    let bd = bex * dey - dex * bey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    if det > sb || -det > sb {
        return (det, sb);
    }
    let mx = aex.abs().max(bex.abs()).max(cex.abs()).max(dex.abs());
    let my = aey.abs().max(bey.abs()).max(cey.abs()).max(dey.abs());
    let mz = aez.abs().max(bez.abs()).max(cez.abs()).max(dez.abs());
    let lo = mx.min(my).min(mz);
    let hi = mx.max(my).max(mz);
    if lo == 0.0 && !det.is_nan() {
        // one coordinate equal in all five points: the determinant is exactly 0 (bound 0 says so)
        return (0.0, 0.0);
    }
    if !in_safe_range(lo, hi) {
        return (det, f64::INFINITY);
    }
    (det, ISP_BOUND * hi * hi * mx * my * mz)
}

/// Lexicographic order on coordinates (the perturbation order).
#[inline]
pub fn lex_less(a: &P, b: &P) -> bool {
    a[0] < b[0] || (a[0] == b[0] && (a[1] < b[1] || (a[1] == b[1] && a[2] < b[2])))
}

/// Orientation of three exactly coplanar points inside their plane, read in the first of the
/// xy, yz, zx projections that is not degenerate. The same projection is chosen for every
/// non-collinear triple of one plane, so signs are consistent within a plane. 0 iff collinear.
#[inline]
pub fn coplanar_orient(a: P, b: P, c: P) -> f64 {
    let o = gp::orient2d([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]);
    if o != 0.0 {
        return o;
    }
    let o = gp::orient2d([a[1], a[2]], [b[1], b[2]], [c[1], c[2]]);
    if o != 0.0 {
        return o;
    }
    gp::orient2d([a[2], a[0]], [b[2], b[0]], [c[2], c[0]])
}

/// True when the three points are collinear (or not distinct). Exact.
#[inline]
pub fn collinear(a: P, b: P, c: P) -> bool {
    coplanar_orient(a, b, c) == 0.0
}

/// Perturbed conflict test of a positive finite tetrahedron `t` with `q`: true when `q` is inside the
/// perturbed circumsphere. Never ties.
#[inline(always)]
pub fn conflict_finite(t: [P; 4], q: P, sb: &Bounds) -> bool {
    let s = insphere_within(t[0], t[1], t[2], t[3], q, sb.insphere);
    if s != 0.0 {
        return s > 0.0;
    }
    perturbed_insphere_tie(t, q)
}

#[cold]
fn perturbed_insphere_tie(t: [P; 4], q: P) -> bool {
    let pts = [t[0], t[1], t[2], t[3], q];
    let mut idx = [0usize, 1, 2, 3, 4];
    idx.sort_by(|&i, &j| cmp_lex(&pts[i], &pts[j]));
    for k in (0..5).rev() {
        let j = idx[k];
        if j == 4 {
            return false;
        }
        let mut r = t;
        r[j] = q;
        let o = orient(r[0], r[1], r[2], r[3]);
        if o != 0.0 {
            return o > 0.0;
        }
    }
    debug_assert!(false, "perturbed insphere undecided");
    false
}

fn cmp_lex(a: &P, b: &P) -> std::cmp::Ordering {
    a[0].partial_cmp(&b[0])
        .unwrap()
        .then(a[1].partial_cmp(&b[1]).unwrap())
        .then(a[2].partial_cmp(&b[2]).unwrap())
}

/// Perturbed conflict test of an infinite tetrahedron: `t` has the infinite vertex at position `k`
/// (its coordinates in `t[k]` are ignored), `d` is the apex of the finite tetrahedron on the other side
/// of the hull facet. True when `q` lies strictly outside the hull facet, or on its plane and inside its
/// perturbed circumcircle.
#[inline]
pub fn conflict_infinite(t: [P; 4], k: usize, d: P, q: P, sb: &Bounds) -> bool {
    let mut r = t;
    r[k] = q;
    let o = orient_within(r[0], r[1], r[2], r[3], sb.orient);
    if o != 0.0 {
        return o > 0.0;
    }
    coplanar_conflict(t, k, d, q)
}

#[cold]
fn coplanar_conflict(t: [P; 4], k: usize, d: P, q: P) -> bool {
    // Every sphere through the facet's three vertices cuts the facet's plane in their circumcircle, so
    // the sphere through the facet and `d` decides the circle. (t with ∞→d) is negative: flip the sign.
    let mut r = t;
    r[k] = d;
    let s = -insphere(r[0], r[1], r[2], r[3], q);
    if s != 0.0 {
        return s > 0.0;
    }
    let f: Vec<P> = (0..4).filter(|&i| i != k).map(|i| t[i]).collect();
    perturbed_tie(
        [f[0], f[1], f[2]],
        q,
        |p| *p,
        |g| coplanar_orient(g[0], g[1], g[2]),
    )
}

/// The planar symbolic perturbation's answer to an exact tie: is `q` inside the circle of the
/// triangle `f` of one plane? The lexicographically largest of the four points (by `key`, a 3D
/// position: a function of the points alone, never of the cell or the insertion order) decides:
/// if it is `q`, `q` is outside; else `q` is inside iff the triangle with that point replaced by
/// `q` has `f`'s orientation (by `orient`, exact); on a collinear substitution the next point
/// decides.
#[cold]
fn perturbed_tie<T: Copy>(
    f: [T; 3],
    q: T,
    key: impl Fn(&T) -> P,
    orient: impl Fn([T; 3]) -> f64,
) -> bool {
    let own = orient(f) > 0.0;
    let pts = [f[0], f[1], f[2], q];
    let mut idx = [0usize, 1, 2, 3];
    idx.sort_by(|&i, &j| cmp_lex(&key(&pts[i]), &key(&pts[j])));
    for m in (0..4).rev() {
        let j = idx[m];
        if j == 3 {
            return false;
        }
        let mut g = f;
        g[j] = q;
        let o = orient(g);
        if o != 0.0 {
            return (o > 0.0) == own;
        }
    }
    debug_assert!(false, "perturbed tie undecided");
    false
}

/// A point of a plane for [`plane_incircle`]: its uv in the plane's frame and its 3D position (the
/// key of the symbolic perturbation).
pub type UvPoint = ([f64; 2], P);

/// Whether `q` is inside the circumcircle of `a, b, c` in one plane's uv (any orientation of the
/// three: the exact `incircle` is oriented by the exact `orient2d`). An exact tie is broken by a 2D
/// symbolic perturbation, the planar analogue of [`conflict_finite`]'s 3D one with the same order
/// (lexicographic on the 3D positions, a function of the points alone, never of the cell or the
/// insertion order): the lexicographically largest point decides; if it is `q`, `q` is outside;
/// else the answer is the orientation of the triangle with that point replaced by `q`, and on a
/// collinear substitution the next point decides. Being the same order matters: for exactly
/// coplanar points the 3D perturbation restricted to their plane is this 2D one (an off-plane
/// apex's term is an orientation of four coplanar points, zero), so a plane-rule decision never
/// contradicts a 3D decision on a tuple spanning two parallel planes. `None` when `a, b, c` are collinear in uv (no
/// circle: the caller falls back to the 3D predicates).
pub fn plane_incircle(a: UvPoint, b: UvPoint, c: UvPoint, q: UvPoint) -> Option<bool> {
    let o = gp::orient2d(a.0, b.0, c.0);
    if o == 0.0 {
        return None;
    }
    // counter-clockwise order
    let f = if o > 0.0 { [a, b, c] } else { [a, c, b] };
    let s = gp::incircle(f[0].0, f[1].0, f[2].0, q.0);
    if s != 0.0 {
        return Some(s > 0.0);
    }
    Some(perturbed_tie(
        f,
        q,
        |p| p.1,
        |g| gp::orient2d(g[0].0, g[1].0, g[2].0),
    ))
}

/// Whether `q` is inside the circumcircle of `a, b, c`, four points of one plane, decided on their
/// 3D positions through the plane's `apex` (a fixed point off the plane): every sphere through
/// three points of a plane meets it in their circle, so the sphere through `a, b, c` and the apex
/// decides for any `q` on the plane, whatever tetrahedron `a, b, c` belong to. Unlike
/// [`plane_incircle`] it reads the same floats as the 3D predicates that decide the mixed tuples,
/// so the two cannot see two different roundings of one configuration (the uv are another
/// rounding of the ideal points: on a nearly collinear triple the two circles differ
/// macroscopically). For points exactly on an axis plane it is [`plane_incircle`]. An exact tie is
/// broken as there (the lexicographically largest point replaced by `q`, oriented against the
/// apex). `None` when `a, b, c` are collinear (no circle: the caller falls back).
pub fn plane_insphere(a: P, b: P, c: P, q: P, apex: P) -> Option<bool> {
    let o = orient(a, b, c, apex);
    if o == 0.0 {
        return None;
    }
    let f = if o > 0.0 { [a, b, c] } else { [a, c, b] };
    let s = insphere(f[0], f[1], f[2], apex, q);
    if s != 0.0 {
        return Some(s > 0.0);
    }
    Some(perturbed_tie(
        f,
        q,
        |p| *p,
        |g| orient(g[0], g[1], g[2], apex),
    ))
}

/// Whether `q` is strictly between `a` and `b`, three points known to lie on one line (they share
/// two planes): compared on the uv axis along which `a` and `b` differ most, by exact float
/// comparisons (the axis choice only has to be one along which the line is not constant).
pub fn line_between(a: [f64; 2], b: [f64; 2], q: [f64; 2]) -> bool {
    let k = if (b[0] - a[0]).abs() >= (b[1] - a[1]).abs() {
        0
    } else {
        1
    };
    let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
    lo < q[k] && q[k] < hi
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn double_double_stage_agrees_with_robust() {
        // nearly coplanar 5-tuples on tilted planes (rounded), nearly cospherical ones, random ones
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut answered, mut nonzero) = (0, 0);
        for k in 0..40000 {
            let n: P = [
                r.gen::<f64>() - 0.5,
                r.gen::<f64>() - 0.5,
                r.gen::<f64>() - 0.5,
            ];
            let u: P = [n[1], -n[0], 0.0];
            let v: P = [
                n[1] * u[2] - n[2] * u[1],
                n[2] * u[0] - n[0] * u[2],
                n[0] * u[1] - n[1] * u[0],
            ];
            let o: P = [r.gen(), r.gen(), r.gen()];
            let mut p: [P; 5] = [[0.0; 3]; 5];
            for (i, q) in p.iter_mut().enumerate() {
                let (s, t): (f64, f64) = (r.gen::<f64>() - 0.5, r.gen::<f64>() - 0.5);
                let h = match k % 4 {
                    0 => 0.0,
                    1 if i == 4 => 1e-12 * (r.gen::<f64>() - 0.5),
                    2 => r.gen::<f64>() - 0.5,
                    _ => 0.0,
                };
                *q = std::array::from_fn(|c| o[c] + s * u[c] + t * v[c] + h * n[c]);
            }
            if k % 4 == 3 {
                // on a sphere, rounded
                for q in p.iter_mut() {
                    let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
                    *q = q.map(|c| c / l);
                }
            }
            let exact = gp::insphere(p[0], p[1], p[2], p[3], p[4]);
            if exact != 0.0 {
                nonzero += 1;
            }
            if let Some(dd) = insphere_dd(p[0], p[1], p[2], p[3], p[4]) {
                answered += 1;
                assert_eq!(dd > 0.0, exact > 0.0, "case {k}: {p:?}");
                assert!(exact != 0.0, "case {k}");
            }
        }
        assert!(answered > nonzero / 2, "{answered} of {nonzero}");
    }

    #[test]
    fn double_double_orient_agrees_with_robust() {
        // nearly coplanar 4-tuples on tilted planes (rounded), exactly coplanar ones, random ones
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let (mut answered, mut nonzero) = (0, 0);
        for k in 0..40000 {
            let n: P = [
                r.gen::<f64>() - 0.5,
                r.gen::<f64>() - 0.5,
                r.gen::<f64>() - 0.5,
            ];
            let u: P = [n[1], -n[0], 0.0];
            let v: P = [
                n[1] * u[2] - n[2] * u[1],
                n[2] * u[0] - n[0] * u[2],
                n[0] * u[1] - n[1] * u[0],
            ];
            let o: P = [r.gen(), r.gen(), r.gen()];
            let mut p: [P; 4] = [[0.0; 3]; 4];
            for (i, q) in p.iter_mut().enumerate() {
                let (s, t): (f64, f64) = (r.gen::<f64>() - 0.5, r.gen::<f64>() - 0.5);
                let h = match k % 4 {
                    1 if i == 3 => 1e-13 * (r.gen::<f64>() - 0.5),
                    2 => r.gen::<f64>() - 0.5,
                    _ => 0.0,
                };
                *q = std::array::from_fn(|c| o[c] + s * u[c] + t * v[c] + h * n[c]);
            }
            if k % 4 == 3 {
                // exactly coplanar: the fourth point is the midpoint of a dyadic pair
                p[3] = [0.5 * (p[0][0] + p[1][0]), p[0][1], p[0][2]];
                p[1] = [p[1][0], p[0][1], p[0][2]];
            }
            let exact = gp::orient3d(p[0], p[1], p[2], p[3]);
            if exact != 0.0 {
                nonzero += 1;
            }
            for fma in [false, true] {
                let dd = if fma {
                    #[cfg(target_arch = "x86_64")]
                    {
                        if !has_fma() {
                            continue;
                        }
                        // SAFETY: checked just above.
                        unsafe { orient3d_dd_fma(p[0], p[1], p[2], p[3]) }
                    }
                    #[cfg(not(target_arch = "x86_64"))]
                    continue;
                } else {
                    orient3d_dd_with::<false>(p[0], p[1], p[2], p[3])
                };
                if let Some(dd) = dd {
                    answered += !fma as usize;
                    assert_eq!(dd > 0.0, exact > 0.0, "case {k}: {p:?}");
                    assert!(exact != 0.0, "case {k}");
                }
            }
        }
        assert!(answered > nonzero * 9 / 10, "{answered} of {nonzero}");
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn fma_double_double_stages_are_bit_identical() {
        if !has_fma() {
            return;
        }
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        for k in 0..20000 {
            let mut p: [P; 5] = [[0.0; 3]; 5];
            for q in p.iter_mut() {
                *q = [r.gen(), r.gen(), 0.3 * r.gen::<f64>()];
            }
            if k % 2 == 0 {
                for q in p.iter_mut() {
                    q[2] = 0.3 * q[0] - 0.7 * q[1];
                }
            }
            let [a, b, c, d, e] = p;
            // SAFETY: the CPU has FMA.
            let (x, y) = unsafe { (insphere_dd_fma(a, b, c, d, e), orient3d_dd_fma(a, b, c, d)) };
            assert_eq!(
                x.map(f64::to_bits),
                insphere_dd_with::<false>(a, b, c, d, e).map(f64::to_bits)
            );
            assert_eq!(
                y.map(f64::to_bits),
                orient3d_dd_with::<false>(a, b, c, d).map(f64::to_bits)
            );
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn packed_insphere_determinant_is_bit_identical() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for k in 0..20000 {
            let mut p: [P; 5] = [[0.0; 3]; 5];
            for q in p.iter_mut() {
                let s = if k % 2 == 0 { 1.0 } else { 1e-3 };
                *q = [
                    r.gen::<f64>() * s,
                    r.gen::<f64>(),
                    r.gen::<f64>() * 7.0 - 3.0,
                ];
            }
            let (det, _) = insphere_filter(p[0], p[1], p[2], p[3], p[4], 0.0);
            let packed = insphere_det_packed(p[0], p[1], p[2], p[3], p[4]);
            assert_eq!(det.to_bits(), packed.to_bits(), "case {k}");
        }
    }

    #[test]
    fn filters_agree_with_exact_predicates() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let mut decided = 0;
        let sb = Bounds::for_extent(2.0);
        let mut static_decided = 0;
        for k in 0..20000 {
            // mix of random and nearly degenerate inputs (points on a plane / sphere, rounded)
            let mut p: [P; 5] = [[0.0; 3]; 5];
            for q in p.iter_mut() {
                *q = [r.gen(), r.gen(), r.gen()];
            }
            if k % 3 == 1 {
                for q in p.iter_mut() {
                    q[2] = 0.3 * q[0] + 0.7 * q[1];
                }
            }
            if k % 3 == 2 {
                for q in p.iter_mut() {
                    let (t, u): (f64, f64) = (r.gen::<f64>() * 6.3, r.gen::<f64>() * 3.1);
                    *q = [u.sin() * t.cos(), u.sin() * t.sin(), u.cos()];
                }
            }
            let o = orient(p[0], p[1], p[2], p[3]);
            let ro = -gp::orient3d(p[0], p[1], p[2], p[3]);
            assert_eq!(o.partial_cmp(&0.0), ro.partial_cmp(&0.0));
            let s = insphere(p[0], p[1], p[2], p[3], p[4]);
            let rs = -gp::insphere(p[0], p[1], p[2], p[3], p[4]);
            assert_eq!(s.partial_cmp(&0.0), rs.partial_cmp(&0.0));
            // static bounds: every coordinate here is in [-1, 1]
            let o = orient_within(p[0], p[1], p[2], p[3], sb.orient);
            assert_eq!(o.partial_cmp(&0.0), ro.partial_cmp(&0.0));
            let s = insphere_within(p[0], p[1], p[2], p[3], p[4], sb.insphere);
            assert_eq!(s.partial_cmp(&0.0), rs.partial_cmp(&0.0));
            let (det, _) = orient3d_filter(p[0], p[1], p[2], p[3], 0.0);
            if det.abs() > sb.orient {
                static_decided += 1;
            }
            let (det, bound) = insphere_filter(p[0], p[1], p[2], p[3], p[4], f64::INFINITY);
            if det.abs() > bound {
                decided += 1;
                assert_eq!((-det).partial_cmp(&0.0), rs.partial_cmp(&0.0));
            }
        }
        assert!(
            decided > 6000,
            "the filter decides the random cases: {decided}"
        );
        assert!(static_decided > 5000, "{static_decided}");
        assert_eq!(Bounds::for_extent(0.0), Bounds::NONE);
        assert_eq!(Bounds::for_extent(f64::INFINITY), Bounds::NONE);
    }
    #[test]
    fn plane_incircle_ties_by_position() {
        // the unit square's corners are cocircular: the two diagonals are decided by the order of
        // the 3D keys alone
        let sq = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
        let ids = [[0u64, 1, 2, 3], [3, 2, 1, 0], [5, 9, 2, 7], [1, 3, 0, 2]];
        for g in ids {
            let p: Vec<UvPoint> = (0..4).map(|i| (sq[i], [g[i] as f64, 0.0, 0.0])).collect();
            // exactly one diagonal: triangles (0,1,2)+(0,2,3) or (0,1,3)+(1,2,3), both orientations
            let d02 = !plane_incircle(p[0], p[1], p[2], p[3]).unwrap()
                && !plane_incircle(p[0], p[2], p[3], p[1]).unwrap();
            let d13 = !plane_incircle(p[0], p[1], p[3], p[2]).unwrap()
                && !plane_incircle(p[1], p[2], p[3], p[0]).unwrap();
            assert!(d02 != d13, "{g:?}");
            assert_eq!(
                plane_incircle(p[0], p[1], p[2], p[3]),
                plane_incircle(p[2], p[1], p[0], p[3])
            );
        }
        assert_eq!(
            plane_incircle(
                ([0.0, 0.0], [0.0; 3]),
                ([1.0, 0.0], [1.0; 3]),
                ([2.0, 0.0], [2.0; 3]),
                ([0.5, 0.5], [3.0; 3])
            ),
            None
        );
        assert!(line_between([0.0, 1.0], [0.0, 3.0], [1e-17, 2.0]));
        assert!(!line_between([0.0, 1.0], [0.0, 3.0], [0.0, 3.0]));
    }

    /// On an axis plane the points are exactly coplanar, so the circle through three of them seen
    /// through any apex off the plane is their circle in (u,v): [`plane_insphere`] answers as
    /// [`plane_incircle`] does, ties (a small integer grid is massively cocircular) included, from
    /// either side of the plane.
    #[test]
    fn plane_insphere_is_plane_incircle_on_an_axis_plane() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let (mut ties, mut n) = (0, 0);
        for _ in 0..20000 {
            let z = 0.375;
            let q: Vec<[f64; 2]> = (0..4)
                .map(|_| [r.gen_range(-3..=3) as f64, r.gen_range(-3..=3) as f64])
                .collect();
            let p: Vec<P> = q.iter().map(|u| [u[0], u[1], z]).collect();
            let uvp = |i: usize| (q[i], p[i]);
            let want = plane_incircle(uvp(0), uvp(1), uvp(2), uvp(3));
            for apex in [[0.3, -0.2, z + 7.0], [-1.1, 0.4, z - 2.5]] {
                assert_eq!(plane_insphere(p[0], p[1], p[2], p[3], apex), want, "{q:?}");
            }
            if want.is_some() {
                n += 1;
                ties += (gp::incircle(q[0], q[1], q[2], q[3]) == 0.0) as usize;
            }
        }
        assert!(n > 15000 && ties > 1000, "{n} {ties}");
    }

    #[test]
    fn signs() {
        let a = [0.0, 0.0, 0.0];
        let b = [1.0, 0.0, 0.0];
        let c = [0.0, 1.0, 0.0];
        let d = [0.0, 0.0, 1.0];
        assert!(orient(a, b, c, d) > 0.0);
        assert!(insphere(a, b, c, d, [0.2, 0.2, 0.2]) > 0.0);
        assert!(insphere(a, b, c, d, [2.0, 2.0, 2.0]) < 0.0);
        assert!(coplanar_orient(a, b, c) > 0.0);
        assert!(collinear(a, b, [3.0, 0.0, 0.0]));
        // Cospherical: the perturbed answers of the two tetrahedra sharing a facet must disagree
        // about each other's apex in a consistent way (exactly one of them is Delaunay).
        let e = [1.0, 1.0, 1.0];
        assert_eq!(insphere(a, b, c, d, e), 0.0);
        let _ = conflict_finite([a, b, c, d], e, &Bounds::NONE);
    }
}
