//! The one seeded generator: SplitMix64 (Steele, Lea and Flood 2014), for everything the
//! crate makes at random and must make again on every machine: Franklin's random segments
//! ([`crate::grid::random_segments`]), the lab's spheres and stiff scenes, and the test and
//! benchmark data.
//!
//! Written by hand because it is a dozen lines where a random-number crate would be a
//! dependency of the library, and because the scenes it makes are part of what the project
//! publishes (the same seed gives the same scene, whatever a crate's next version does).
//!
//! ```
//! use kepler::random::SplitMix64;
//! let mut a = SplitMix64(7);
//! let x = a.unit();
//! assert!((0.0..1.0).contains(&x));
//! assert_eq!(SplitMix64(7).unit(), x);
//! assert!((2.0..3.0).contains(&a.range(2.0, 3.0)));
//! assert!(a.below(10) < 10);
//! ```

/// SplitMix64: its state is the seed, advanced by a constant at each draw and mixed.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform double in `[0, 1)` (a multiple of 2⁻⁵³).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform double in `[lo, hi)` (for `lo < hi`).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// An integer in `0..n` (for `n > 0`; the remainder of the next draw).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// An integer in `lo..=hi`, as a double (for `lo ≤ hi`): exact coordinates.
    pub fn int(&mut self, lo: i32, hi: i32) -> f64 {
        f64::from(lo + self.below((hi - lo + 1) as usize) as i32)
    }

    /// A vector with each coordinate uniform in `[-r, r)`.
    pub fn vector(&mut self, r: f64) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }

    /// One of `items` (not empty).
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }
}
