//! Sign vectors: the side (−1, 0 on, +1) of a cell, a face or a point with respect to every plane,
//! two bits per plane. A dense sweep has a thousand planes and a million cells and faces: one byte
//! per sign held gigabytes (Elephant, 1000 frames: 2.9 GB after the arrangement).

/// Signs packed 32 to a word: 0 → `00`, +1 → `01`, −1 → `11`; bits past `len` stay 0, so equal
/// vectors have equal words (`Eq`, `Hash`).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct SignVec {
    words: Vec<u64>,
    len: usize,
}

const PER_WORD: usize = 32;

#[inline(always)]
fn code(s: i8) -> u64 {
    match s.signum() {
        0 => 0,
        1 => 1,
        _ => 3,
    }
}

#[inline(always)]
fn decode(b: u64) -> i8 {
    // 0 → 0, 1 → 1, 3 → −1
    (b & 1) as i8 * (1 - (b & 2) as i8)
}

impl SignVec {
    /// `len` signs, all `s`.
    pub fn filled(len: usize, s: i8) -> SignVec {
        SignVec::from_fn(len, |_| s)
    }

    /// `len` signs, the j-th `f(j)` (only its sign counts).
    pub fn from_fn(len: usize, mut f: impl FnMut(usize) -> i8) -> SignVec {
        let mut words = vec![0u64; len.div_ceil(PER_WORD)];
        for (w, word) in words.iter_mut().enumerate() {
            let start = w * PER_WORD;
            for j in start..(start + PER_WORD).min(len) {
                *word |= code(f(j)) << (2 * (j - start));
            }
        }
        SignVec { words, len }
    }

    #[inline(always)]
    pub fn get(&self, j: usize) -> i8 {
        debug_assert!(j < self.len);
        decode(self.words[j / PER_WORD] >> (2 * (j % PER_WORD)))
    }

    #[inline(always)]
    pub fn set(&mut self, j: usize, s: i8) {
        debug_assert!(j < self.len);
        let shift = 2 * (j % PER_WORD);
        let w = &mut self.words[j / PER_WORD];
        *w = (*w & !(3 << shift)) | (code(s) << shift);
    }

    /// This vector with sign `j` set to `s`.
    pub fn with(mut self, j: usize, s: i8) -> SignVec {
        self.set(j, s);
        self
    }

    pub fn iter(&self) -> impl Iterator<Item = i8> + '_ {
        (0..self.len).map(|j| self.get(j))
    }

    /// Marks in `acc` (one word per word of these vectors) the signs where `self` and `other`
    /// differ: a word's pair of bits is nonzero there.
    pub fn mark_differences(&self, other: &SignVec, acc: &mut [u64]) {
        debug_assert_eq!(self.len, other.len);
        for ((a, x), y) in acc.iter_mut().zip(&self.words).zip(&other.words) {
            *a |= x ^ y;
        }
    }

    /// Whether `acc` (from [`SignVec::mark_differences`]) marks sign `j`.
    pub fn marked(acc: &[u64], j: usize) -> bool {
        (acc[j / PER_WORD] >> (2 * (j % PER_WORD))) & 3 != 0
    }

    /// Words of a vector of `len` signs (for [`SignVec::mark_differences`]'s accumulator).
    pub fn words_for(len: usize) -> usize {
        len.div_ceil(PER_WORD)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signs_round_trip_across_word_boundaries() {
        let pattern = |j: usize| [-1i8, 0, 1, 1, 0, -1, -1][j % 7];
        for len in [0, 1, 31, 32, 33, 64, 65, 1006] {
            let v = SignVec::from_fn(len, pattern);
            assert_eq!(v.iter().count(), len);
            assert!(v.iter().eq((0..len).map(pattern)), "{len}");
            let mut w = SignVec::filled(len, 0);
            for j in 0..len {
                w.set(j, pattern(j));
            }
            assert_eq!(v, w, "{len}");
            // values other than −1, 0, 1 count by their sign
            assert_eq!(SignVec::from_fn(len, |j| 5 * pattern(j)), v);
        }
    }

    #[test]
    fn set_overwrites_and_equal_vectors_hash_alike() {
        use std::hash::{BuildHasher, BuildHasherDefault};
        let hash = |v: &SignVec| {
            BuildHasherDefault::<std::collections::hash_map::DefaultHasher>::default().hash_one(v)
        };
        let a = SignVec::filled(40, -1).with(33, 1).with(33, 0);
        let b = SignVec::filled(40, -1).with(33, 0);
        assert_eq!(a, b);
        assert_eq!(hash(&a), hash(&b));
        assert_ne!(a, SignVec::filled(40, -1));
    }

    #[test]
    fn differences_are_marked_where_signs_differ() {
        let a = SignVec::from_fn(70, |j| if j % 3 == 0 { 1 } else { -1 });
        let b = a.clone().with(0, -1).with(35, 0).with(69, -1);
        let mut acc = vec![0u64; SignVec::words_for(70)];
        a.mark_differences(&a.clone(), &mut acc);
        assert!((0..70).all(|j| !SignVec::marked(&acc, j)));
        a.mark_differences(&b, &mut acc);
        let marked: Vec<usize> = (0..70).filter(|&j| SignVec::marked(&acc, j)).collect();
        assert_eq!(marked, vec![0, 35, 69]);
    }
}
