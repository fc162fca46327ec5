//! FNV-1a over 64-bit words: a hash that is the same in every build and run (unlike `std`'s
//! hasher, whose algorithm may change), for the fingerprints kepler writes into files (a tile
//! file's, a DXF file's GUIDs). Written by hand because it is two lines.

/// An FNV-1a hash being computed.
pub(crate) struct Fnv(u64);

impl Fnv {
    /// A hash started from FNV's offset basis mixed with `seed` (two seeds give two hashes
    /// of the same words).
    pub(crate) fn new(seed: u64) -> Fnv {
        let mut h = Fnv(0xcbf2_9ce4_8422_2325);
        h.word(seed);
        h
    }

    /// Mixes in one word.
    pub(crate) fn word(&mut self, w: u64) {
        self.0 = (self.0 ^ w).wrapping_mul(0x0000_0100_0000_01b3);
    }

    /// The hash of the words so far.
    pub(crate) fn finish(&self) -> u64 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use crate::fnv::Fnv;

    #[test]
    fn words_in_another_order_or_seed_hash_differently() {
        let hash = |seed: u64, words: &[u64]| {
            let mut h = Fnv::new(seed);
            words.iter().for_each(|&w| h.word(w));
            h.finish()
        };
        // Fixed values: the hash must never change between builds.
        assert_eq!(hash(0, &[]), 0xaf63_bd4c_8601_b7df);
        assert_ne!(hash(0, &[1, 2]), hash(0, &[2, 1]));
        assert_ne!(hash(0, &[1, 2]), hash(1, &[1, 2]));
    }
}
