//! Path order for pen plotters: the polylines of each layer ordered, and turned, to shorten
//! the pen's travel between them (`kepler render --order`).
//!
//! A plotter draws a layer's paths in the order of the file and lifts the pen between them,
//! so its travel is the distance from each path's end to the next path's start. The drawing
//! pass emits paths in the order it chained them, which leaves the pen crossing the page
//! back and forth. [`ordered`] reorders each layer (one class and visibility, as the SVG
//! groups them) greedily, as vpype's `linesort` does: from the end of the path drawn last,
//! the nearest free path end (from an R-tree of ends, rstar, rebuilt whenever half its ends
//! belong to paths already drawn), that path drawn from there, reversed if it was its far
//! end. Only the order and direction of paths change: every
//! point stays the same double, so the drawing is the same set of segments.
//!
//! [`pen_travel`] is the travel the pen makes between paths in the file's order, summed over
//! the layers (each layer starts where its first path starts), in view coordinates.
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline};
//! use kepler::output::{ordered, pen_travel};
//! let line = |a: [f64; 2], b: [f64; 2]| Polyline {
//!     class: EdgeClass::Silhouette, visible: true, points: vec![a, b],
//! };
//! let drawing = Drawing {
//!     polylines: vec![line([0.0, 0.0], [1.0, 0.0]), line([5.0, 0.0], [6.0, 0.0]), line([2.0, 0.0], [1.0, 0.0])],
//!     stages: Vec::new(),
//! };
//! assert_eq!(pen_travel(&drawing), 4.0 + 4.0);
//! let better = ordered(&drawing);
//! assert_eq!(pen_travel(&better), 3.0);
//! assert_eq!(better.polylines[1].points, vec![[1.0, 0.0], [2.0, 0.0]]);
//! ```

use crate::hidden::{Drawing, EdgeClass, Polyline};
use rstar::RTree;
use rstar::primitives::GeomWithData;

/// A path end in the R-tree: the point, its path and whether it is the path's last point.
type End = GeomWithData<[f64; 2], (usize, bool)>;

/// The layers of a drawing as the SVG writes them: hidden ones first, each in
/// [`EdgeClass::ALL`] order, then the visible ones.
fn layers() -> impl Iterator<Item = (EdgeClass, bool)> {
    [false, true]
        .into_iter()
        .flat_map(|visible| EdgeClass::ALL.into_iter().map(move |c| (c, visible)))
}

/// The drawing with each layer's paths reordered and turned to shorten the pen's travel
/// (see the module documentation). Layers come in the SVG's order.
pub fn ordered(drawing: &Drawing) -> Drawing {
    let mut polylines = Vec::with_capacity(drawing.polylines.len());
    for (class, visible) in layers() {
        let layer: Vec<&Polyline> = drawing
            .polylines
            .iter()
            .filter(|p| p.class == class && p.visible == visible && !p.points.is_empty())
            .collect();
        polylines.extend(order_layer(&layer));
    }
    Drawing {
        polylines,
        stages: drawing.stages.clone(),
    }
}

/// One layer's paths in greedy nearest-end order, from its first path as given.
fn order_layer(layer: &[&Polyline]) -> Vec<Polyline> {
    let points: Vec<&[[f64; 2]]> = layer.iter().map(|p| p.points.as_slice()).collect();
    pen_order(&points)
        .into_iter()
        .map(|(i, reversed)| {
            let mut path = layer[i].clone();
            if reversed {
                path.points.reverse();
            }
            path
        })
        .collect()
}

/// The order in which a plotter should draw `paths` (each at least one point) to shorten its
/// travel between them, greedily from the first as given: each path's index and whether to
/// draw it reversed.
///
/// ```
/// let paths: [&[[f64; 2]]; 3] = [&[[0.0, 0.0], [1.0, 0.0]], &[[9.0, 0.0], [8.0, 0.0]], &[[3.0, 0.0], [2.0, 0.0]]];
/// assert_eq!(kepler::output::pen_order(&paths), vec![(0, false), (2, true), (1, true)]);
/// ```
pub fn pen_order(paths: &[&[[f64; 2]]]) -> Vec<(usize, bool)> {
    let Some(first) = paths.first().filter(|p| !p.is_empty()) else {
        return Vec::new();
    };
    let end = |i: usize, last: bool| {
        let p = paths[i];
        End::new(if last { p[p.len() - 1] } else { p[0] }, (i, last))
    };
    // Ends of drawn paths stay in the tree until they are as many as the live ones; then the
    // tree is built again from the live ends (bulk loading is cheaper than removing).
    let live = |used: &[bool]| -> Vec<End> {
        (1..paths.len())
            .filter(|&i| !used[i] && !paths[i].is_empty())
            .flat_map(|i| [end(i, false), end(i, true)])
            .collect()
    };
    let mut used = vec![false; paths.len()];
    used[0] = true;
    let mut tree = RTree::bulk_load(live(&used));
    let mut stale = 0;
    let mut out = Vec::with_capacity(paths.len());
    out.push((0, false));
    let mut at = first[first.len() - 1];
    for _ in 1..paths.len() {
        let Some(&(i, last)) = tree
            .nearest_neighbor_iter(&at)
            .map(|e| &e.data)
            .find(|(i, _)| !used[*i])
        else {
            break;
        };
        used[i] = true;
        stale += 2;
        at = if last {
            paths[i][0]
        } else {
            paths[i][paths[i].len() - 1]
        };
        out.push((i, last));
        if 2 * stale > tree.size() {
            tree = RTree::bulk_load(live(&used));
            stale = 0;
        }
    }
    out
}

/// `paths` (each at least one point) in the order, and the direction, [`pen_order`] draws
/// them. The hatch layer of `kepler render --hatch --order` is ordered with it.
pub fn ordered_paths(paths: Vec<Vec<[f64; 2]>>) -> Vec<Vec<[f64; 2]>> {
    let order = {
        let slices: Vec<&[[f64; 2]]> = paths.iter().map(Vec::as_slice).collect();
        pen_order(&slices)
    };
    let mut paths: Vec<Option<Vec<[f64; 2]>>> = paths.into_iter().map(Some).collect();
    order
        .into_iter()
        .filter_map(|(i, reversed)| {
            let mut path = paths[i].take()?;
            if reversed {
                path.reverse();
            }
            Some(path)
        })
        .collect()
}

/// The pen's travel between paths, layer by layer, in the drawing's order (view units).
pub fn pen_travel(drawing: &Drawing) -> f64 {
    layers()
        .map(|(class, visible)| {
            let ends: Vec<([f64; 2], [f64; 2])> = drawing
                .polylines
                .iter()
                .filter(|p| p.class == class && p.visible == visible && !p.points.is_empty())
                .map(|p| (p.points[0], p.points[p.points.len() - 1]))
                .collect();
            ends.windows(2)
                .map(|w| (w[1].0[0] - w[0].1[0]).hypot(w[1].0[1] - w[0].1[1]))
                .sum::<f64>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Random layers: the reordered drawing has the same segments (as unordered pairs, bit
    /// for bit) in each layer, never more travel than a path-by-path greedy written out
    /// plainly, and less than the given order on scattered paths.
    #[test]
    fn ordering_keeps_every_segment_and_shortens_travel() {
        let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
        let mut unit = || rng.unit();
        for round in 0..20 {
            let polylines: Vec<Polyline> = (0..200)
                .map(|k| {
                    let n = 2 + (unit() * 3.0) as usize;
                    let mut p = [unit() * 100.0, unit() * 100.0];
                    let points = (0..n)
                        .map(|_| {
                            p = [p[0] + unit(), p[1] + unit()];
                            p
                        })
                        .collect();
                    Polyline {
                        class: EdgeClass::ALL[(k + round) % 5],
                        visible: k % 3 != 0,
                        points,
                    }
                })
                .collect();
            let drawing = Drawing {
                polylines,
                stages: Vec::new(),
            };
            let better = ordered(&drawing);
            let segments = |d: &Drawing, class, visible| {
                let mut s: Vec<[[u64; 2]; 2]> = d
                    .polylines
                    .iter()
                    .filter(|p| p.class == class && p.visible == visible)
                    .flat_map(|p| p.points.windows(2).map(|w| [w[0], w[1]]))
                    .map(|[a, b]| {
                        let (a, b) = (a.map(f64::to_bits), b.map(f64::to_bits));
                        if a <= b { [a, b] } else { [b, a] }
                    })
                    .collect();
                s.sort_unstable();
                s
            };
            for (class, visible) in layers() {
                assert_eq!(
                    segments(&drawing, class, visible),
                    segments(&better, class, visible)
                );
            }
            assert!(pen_travel(&better) < 0.5 * pen_travel(&drawing));
            let expected = greedy_travel(&drawing);
            let travel = pen_travel(&better);
            assert!(
                (travel - expected).abs() <= 1e-9 * expected,
                "{travel} against {expected}"
            );
        }
    }

    /// The pen travel of the same greedy choice as [`ordered`]'s, by scanning every free end.
    fn greedy_travel(drawing: &Drawing) -> f64 {
        let mut expected = 0.0;
        for (class, visible) in layers() {
            let layer: Vec<&Polyline> = drawing
                .polylines
                .iter()
                .filter(|p| p.class == class && p.visible == visible)
                .collect();
            let Some(first) = layer.first() else { continue };
            let mut free: Vec<bool> = vec![true; layer.len()];
            free[0] = false;
            let mut at = *first.points.last().unwrap();
            while let Some((d, i, last)) = (0..layer.len())
                .filter(|&i| free[i])
                .flat_map(|i| {
                    let p = &layer[i].points;
                    [(p[0], i, false), (p[p.len() - 1], i, true)]
                })
                .map(|(q, i, last)| ((q[0] - at[0]).hypot(q[1] - at[1]), i, last))
                .min_by(|x, y| x.0.total_cmp(&y.0))
            {
                expected += d;
                free[i] = false;
                let p = &layer[i].points;
                at = if last { p[0] } else { p[p.len() - 1] };
            }
        }
        expected
    }
}
