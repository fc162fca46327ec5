//! Counting placement: items placed by a small integer key (a vertex, a grid cell), stably,
//! in two linear passes instead of a comparison sort. The mesh build sorts its edge uses by
//! their lower vertex this way, and the grids place their (cell, item) entries by cell.
//!
//! Written by hand because it is a few lines and the one shape every caller needs (the
//! bucket starts as well as the placed items); a radix-sort crate would give the order but
//! not the starts.

/// The items placed by bucket (`bucket(item) < buckets`), as `value(item)`, in their input
/// order within a bucket, and where each bucket starts: bucket `b` holds
/// `placed[start[b]..start[b + 1]]`. Writing the values straight into their places needs no
/// copy of the items. (Tested against a stable sort below; crate-private, so no doctest.)
pub(crate) fn by_bucket<T, U: Copy>(
    buckets: usize,
    items: &[T],
    bucket: impl Fn(&T) -> usize,
    value: impl Fn(&T) -> U,
) -> (Vec<usize>, Vec<U>) {
    let mut start = vec![0usize; buckets + 1];
    for item in items {
        start[bucket(item) + 1] += 1;
    }
    for b in 0..buckets {
        start[b + 1] += start[b];
    }
    let Some(first) = items.first() else {
        return (start, Vec::new());
    };
    // Each bucket's start serves as its cursor (no second array of counts): after placing,
    // `start[b]` has moved on to where bucket `b + 1` starts, and one shift puts it back.
    let mut placed = vec![value(first); items.len()];
    for item in items {
        let slot = &mut start[bucket(item)];
        placed[*slot] = value(item);
        *slot += 1;
    }
    start.copy_within(0..buckets, 1);
    start[0] = 0;
    (start, placed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_as_a_stable_sort_by_bucket_does() {
        let mut seed = 5u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for (n, buckets) in [(0, 1), (1, 1), (10, 3), (1000, 7), (5000, 4000)] {
            let items: Vec<(usize, u64)> = (0..n)
                .map(|_| ((next() % buckets as u64) as usize, next()))
                .collect();
            let (start, placed) = by_bucket(buckets, &items, |x| x.0, |x| *x);
            let mut sorted = items.clone();
            sorted.sort_by_key(|x| x.0);
            assert_eq!(placed, sorted);
            assert_eq!(start.len(), buckets + 1);
            for b in 0..buckets {
                assert!(placed[start[b]..start[b + 1]].iter().all(|x| x.0 == b));
            }
            assert_eq!(start[buckets], n);
        }
    }
}
