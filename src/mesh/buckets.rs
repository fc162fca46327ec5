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
/// copy of the items. Many items are placed in parallel ([`in_parallel`]), with the same
/// result. (Tested against a stable sort below; crate-private, so no doctest.)
pub(crate) fn by_bucket<T: Sync, U: Copy + Send>(
    buckets: usize,
    items: &[T],
    bucket: impl Fn(&T) -> usize + Sync,
    value: impl Fn(&T) -> U + Sync,
) -> (Vec<usize>, Vec<U>) {
    let parts = rayon::current_num_threads().min(MAX_PARTS);
    if items.len() >= PARALLEL_ITEMS && parts > 1 && u32::try_from(buckets).is_ok() {
        return in_parallel(buckets, items, bucket, value, parts);
    }
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

/// At least this many items are placed in parallel.
const PARALLEL_ITEMS: usize = 1 << 15;

/// At most this many parts of the buckets are placed at once.
const MAX_PARTS: usize = 8;

/// [`by_bucket`] in `parts` parallel parts: the buckets are cut into ranges of equal width,
/// and each part counts and then places, in its own slice of the output, the items whose
/// bucket is in its range, reading all the items in order (so each bucket keeps their order).
/// Every part reads every item's bucket (computed once, in parallel): a sequential read, far
/// cheaper than the scattered writes that the parts share out.
fn in_parallel<T: Sync, U: Copy + Send>(
    buckets: usize,
    items: &[T],
    bucket: impl Fn(&T) -> usize + Sync,
    value: impl Fn(&T) -> U + Sync,
    parts: usize,
) -> (Vec<usize>, Vec<U>) {
    use rayon::prelude::*;
    let keys: Vec<u32> = items.par_iter().map(|x| bucket(x) as u32).collect();
    let width = buckets.div_ceil(parts).max(1);
    let ranges: Vec<std::ops::Range<usize>> = (0..parts)
        .map(|p| (p * width).min(buckets)..((p + 1) * width).min(buckets))
        .collect();
    // Each range's starts, counted from its own first item.
    let local: Vec<Vec<usize>> = ranges
        .par_iter()
        .map(|range| {
            let mut start = vec![0usize; range.len() + 1];
            for &k in &keys {
                let k = k as usize;
                if range.contains(&k) {
                    start[k - range.start + 1] += 1;
                }
            }
            for b in 0..range.len() {
                start[b + 1] += start[b];
            }
            start
        })
        .collect();
    let mut placed = vec![value(&items[0]); items.len()];
    let mut slices = Vec::with_capacity(parts);
    let mut rest = &mut placed[..];
    for (range, start) in ranges.iter().zip(&local) {
        let (here, after) = rest.split_at_mut(start[range.len()]);
        slices.push((range.clone(), start, here));
        rest = after;
    }
    slices.into_par_iter().for_each(|(range, start, slice)| {
        let mut cursor = start[..range.len()].to_vec();
        for (k, item) in keys.iter().zip(items) {
            let k = *k as usize;
            if range.contains(&k) {
                let slot = &mut cursor[k - range.start];
                slice[*slot] = value(item);
                *slot += 1;
            }
        }
    });
    let mut start = Vec::with_capacity(buckets + 1);
    let mut offset = 0;
    for (range, part) in ranges.iter().zip(&local) {
        start.extend(part[..range.len()].iter().map(|s| s + offset));
        offset += part[range.len()];
    }
    start.push(offset);
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
        for (n, buckets) in [
            (0, 1),
            (1, 1),
            (10, 3),
            (1000, 7),
            (5000, 4000),
            // Placed in parallel: few buckets, many, one, and more parts than buckets.
            (PARALLEL_ITEMS, 5),
            (100_000, 70_001),
            (40_000, 1),
            (50_000, 3),
        ] {
            let items: Vec<(usize, u64)> = (0..n)
                .map(|_| ((next() % buckets as u64) as usize, next()))
                .collect();
            let (start, placed) = by_bucket(buckets, &items, |x| x.0, |x| *x);
            let mut sorted = items.clone();
            sorted.sort_by_key(|x| x.0);
            assert_eq!(placed, sorted);
            // The parallel placement itself, in several numbers of parts, whatever the
            // machine's threads.
            for parts in [2, 3, 8] {
                if n > 0 {
                    let parallel = in_parallel(buckets, &items, |x| x.0, |x| *x, parts);
                    assert_eq!(
                        parallel,
                        (start.clone(), placed.clone()),
                        "{n} {buckets} {parts}"
                    );
                }
            }
            assert_eq!(start.len(), buckets + 1);
            for b in 0..buckets {
                assert!(placed[start[b]..start[b + 1]].iter().all(|x| x.0 == b));
            }
            assert_eq!(start[buckets], n);
        }
    }
}
