//! Topology: the ends of visible and hidden runs in one drawing with no such end nearby in
//! the other.

use crate::hidden::Drawing;
use rstar::RTree;
use rstar::primitives::GeomWithData;

/// The ends that differ between the drawings: at each point where segments end (points
/// within the tolerance of each other are one point), the number of visible segment ends and
/// the number of hidden ones are counted in each drawing, and their differences summed. An
/// interior vertex of a polyline is two ends (of its two segments), so a drawing chained
/// into long polylines and one drawn run by run count alike; a visibility change moved, a
/// run split or merged where the other drawing does not, a line ending short, all count.
pub(super) fn wrong_ends(a: &Drawing, b: &Drawing, tolerance: f64) -> usize {
    // Every segment end: (point, drawing, visible).
    let mut ends: Vec<([f64; 2], usize, bool)> = Vec::new();
    for (k, d) in [a, b].into_iter().enumerate() {
        for line in &d.polylines {
            for w in line.points.windows(2) {
                for p in [w[0], w[1]] {
                    if p[0].is_finite() && p[1].is_finite() {
                        ends.push((p, k, line.visible));
                    }
                }
            }
        }
    }
    let tree = RTree::bulk_load(
        ends.iter()
            .enumerate()
            .map(|(i, e)| GeomWithData::new(e.0, i))
            .collect::<Vec<GeomWithData<[f64; 2], usize>>>(),
    );
    // Points within the tolerance of each other, transitively, are one point.
    let mut cluster = vec![usize::MAX; ends.len()];
    let mut wrong = 0usize;
    for start in 0..ends.len() {
        if cluster[start] != usize::MAX {
            continue;
        }
        cluster[start] = start;
        let mut counts = [[0i64; 2]; 2];
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            let (p, k, visible) = ends[i];
            counts[k][usize::from(visible)] += 1;
            for near in tree.locate_within_distance(p, tolerance * tolerance) {
                if cluster[near.data] == usize::MAX {
                    cluster[near.data] = start;
                    stack.push(near.data);
                }
            }
        }
        let [a, b] = counts;
        wrong += (a[0].abs_diff(b[0]) + a[1].abs_diff(b[1])) as usize;
    }
    wrong
}
