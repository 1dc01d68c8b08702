//! Insertion order: BRIO (biased randomized insertion order, Amenta–Choi–Rote) with every round
//! sorted along a 3D Hilbert curve, so that consecutive points are close (short walks, warm caches)
//! while the rounds keep the randomised expected bounds.
use rand::seq::SliceRandom;
use rand::SeedableRng;

const BITS: u32 = 21;

/// Hilbert index of a point of the 2^BITS grid (Skilling's transpose algorithm).
pub fn hilbert_index(mut x: [u32; 3], bits: u32) -> u64 {
    let m = 1u32 << (bits - 1);
    let mut q = m;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= p;
            } else {
                let t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
        q >>= 1;
    }
    for i in 1..3 {
        x[i] ^= x[i - 1];
    }
    let mut t = 0;
    q = m;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for xi in x.iter_mut() {
        *xi ^= t;
    }
    let mut h = 0u64;
    for b in (0..bits).rev() {
        for xi in x {
            h = (h << 1) | ((xi >> b) & 1) as u64;
        }
    }
    h
}

/// Hilbert keys of points quantised to a 2^bits grid over the bounding box.
pub fn hilbert_keys(pts: &[[f64; 3]], bits: u32) -> Vec<u64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    let top = (1u32 << bits) - 1;
    let scale = if ext > 0.0 { top as f64 / ext } else { 0.0 };
    pts.iter()
        .map(|p| {
            let q = |k: usize| (((p[k] - lo[k]) * scale) as u32).min(top);
            hilbert_index([q(0), q(1), q(2)], bits)
        })
        .collect()
}

/// Boundaries of the BRIO rounds of `n` points: 0, …, n/64, n/8, n (from the end: n/8, n/64, ...
/// until a first round of at most 1000 points).
pub fn brio_rounds(n: usize) -> Vec<usize> {
    let mut cuts = vec![n];
    let mut m = n;
    while m > 1000 {
        m /= 8;
        cuts.push(m);
    }
    cuts.push(0);
    cuts.reverse();
    cuts
}

/// BRIO order of all point indices: a random permutation cut into rounds growing by a factor 8 (the
/// last round holds 7/8 of the points, as CGAL's multiscale sort does), each round sorted along the
/// Hilbert curve. Deterministic.
///
/// Each round sorts plain u64 words (Hilbert key above the point index) rather than indices by a
/// looked-up key: no indirection in the comparisons. The grid resolution leaves room for the index
/// (at least 2^10 cells per axis, 2^14 for up to 2^20 points), much finer than the point spacing
/// that matters for locality; ties are ordered by index.
pub fn brio_order(pts: &[[f64; 3]]) -> Vec<u32> {
    let n = pts.len();
    let idx_bits = (usize::BITS - n.leading_zeros()).max(1);
    let bits = ((64 - idx_bits) / 3).clamp(1, BITS);
    let keys = hilbert_keys(pts, bits);
    let mut idx: Vec<u32> = (0..n as u32).collect();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5EED);
    idx.shuffle(&mut rng);
    let cuts = brio_rounds(n);
    let mut words: Vec<u64> = Vec::with_capacity(n);
    let low = (1u64 << idx_bits) - 1;
    for w in cuts.windows(2) {
        words.clear();
        words.extend(
            idx[w[0]..w[1]]
                .iter()
                .map(|&i| (keys[i as usize] << idx_bits) | i as u64),
        );
        words.sort_unstable();
        for (d, &x) in idx[w[0]..w[1]].iter_mut().zip(&words) {
            *d = (x & low) as u32;
        }
    }
    idx
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn hilbert_is_a_bijection_on_a_small_grid() {
        let mut seen = std::collections::HashSet::new();
        for x in 0..8 {
            for y in 0..8 {
                for z in 0..8 {
                    assert!(seen.insert(hilbert_index([x, y, z], 3)));
                }
            }
        }
        // consecutive indices are grid neighbours
        let mut by_index = vec![[0u32; 3]; 512];
        for x in 0..8 {
            for y in 0..8 {
                for z in 0..8 {
                    by_index[hilbert_index([x, y, z], 3) as usize] = [x, y, z];
                }
            }
        }
        for w in by_index.windows(2) {
            let d: i64 = (0..3)
                .map(|k| (w[0][k] as i64 - w[1][k] as i64).abs())
                .sum();
            assert_eq!(d, 1);
        }
    }

    #[test]
    fn brio_is_a_permutation() {
        let pts: Vec<[f64; 3]> = (0..5000)
            .map(|i| [i as f64, (i * 7 % 13) as f64, 0.5])
            .collect();
        let mut o = brio_order(&pts);
        o.sort();
        assert!(o.iter().enumerate().all(|(i, &v)| i as u32 == v));
    }
}
