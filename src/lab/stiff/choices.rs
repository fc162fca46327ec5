//! The seeded choices of a stiff scene.

use crate::random::SplitMix64;

/// The seeded choices of a scene, drawn from the crate's [`SplitMix64`] (so the same seed
/// gives the same scene on every machine). Integers are drawn by scaling a uniform double, as
/// the scenes published so far were made.
pub(super) struct Choices(pub(super) SplitMix64);

impl Choices {
    /// A uniform integer in `0..n` (for `n > 0`).
    pub(super) fn below(&mut self, n: usize) -> usize {
        ((self.0.unit() * n as f64) as usize).min(n - 1)
    }

    /// A uniform multiple of 1/8 in `[lo, hi]` (the first above `lo` when there is none).
    pub(super) fn eighths(&mut self, lo: f64, hi: f64) -> f64 {
        let (a, b) = ((lo * 8.0).ceil(), (hi * 8.0).floor());
        let steps = if b > a { (b - a) as usize + 1 } else { 1 };
        (a + self.below(steps) as f64) / 8.0
    }

    /// One of `items` (not empty).
    pub(super) fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }

    /// 1 or −1.
    pub(super) fn sign(&mut self) -> f64 {
        if self.below(2) == 0 { 1.0 } else { -1.0 }
    }
}
