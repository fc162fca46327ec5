//! Prisms: a simple polygon extruded along z.

use super::{MAX_POLYGON_VERTICES, SolidError, positive};
use crate::geometry::Point3;
use crate::geometry::polygon::segments_meet;
use crate::geometry::predicates::{MAX_COORDINATE, orient2d};
use crate::mesh::Mesh;
use std::cmp::Ordering;

/// The solid swept by the polygon `outline` (in the xy-plane) from z = 0 to z = `height`.
///
/// The outline must be a simple polygon (its boundary neither crosses nor touches itself,
/// decided with exact predicates) without holes, with at least 3 distinct vertices and at most
/// [`MAX_POLYGON_VERTICES`]; it may be convex or not and wound either way. Repeated
/// consecutive points (including geo's closing point) are dropped. The bottom and top caps
/// are single polygon faces, the walls one quad per outline edge.
///
/// ```
/// use geo::polygon;
/// // An L-shape of area 3: caps with 6 vertices, 6 wall quads.
/// let l = polygon![(x: 0.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0),
///                  (x: 1.0, y: 1.0), (x: 1.0, y: 2.0), (x: 0.0, y: 2.0)];
/// let p = kepler::solids::prism(&l, 2.0).unwrap();
/// assert_eq!(p.faces().len(), 8);
/// assert!((p.volume() - 6.0).abs() < 1e-12);
/// ```
pub fn prism(outline: &geo::Polygon<f64>, height: f64) -> Result<Mesh, SolidError> {
    let height = positive("prism", "height", height)?;
    let mut ring = outline_points(outline)?;
    if winding(&ring) == Ordering::Less {
        ring.reverse();
    }
    let n = ring.len();
    let vertices: Vec<Point3> = ring
        .iter()
        .map(|p| Point3::new(p[0], p[1], 0.0))
        .chain(ring.iter().map(|p| Point3::new(p[0], p[1], height)))
        .collect();
    let n32 = n as u32;
    let mut faces = Vec::with_capacity(n + 2);
    faces.push((0..n32).rev().collect());
    faces.push((n32..2 * n32).collect());
    faces.extend((0..n32).map(|i| {
        let j = (i + 1) % n32;
        vec![i, j, n32 + j, n32 + i]
    }));
    Ok(Mesh::from_polygons(vertices, faces)?)
}

/// The outline's vertices without repeats, after checking that it has no holes, finite
/// coordinates in range, between 3 and [`MAX_POLYGON_VERTICES`] vertices and no
/// self-intersection (which rules out zero area too: a ring on one line folds back).
fn outline_points(outline: &geo::Polygon<f64>) -> Result<Vec<[f64; 2]>, SolidError> {
    let bad = |problem: String| SolidError::InvalidOutline { problem };
    let holes = outline.interiors().len();
    if holes > 0 {
        return Err(bad(format!(
            "has {holes} hole{}; a prism's outline must have none",
            if holes == 1 { "" } else { "s" }
        )));
    }
    let mut ring: Vec<[f64; 2]> = Vec::new();
    for c in outline.exterior().coords() {
        if !(c.x.is_finite() && c.y.is_finite()) {
            return Err(bad(format!(
                "has a point ({}, {}) that is not finite",
                c.x, c.y
            )));
        }
        if c.x.abs() > MAX_COORDINATE || c.y.abs() > MAX_COORDINATE {
            return Err(bad(format!(
                "has a point ({:e}, {:e}) beyond 1e100 in magnitude",
                c.x, c.y
            )));
        }
        // Adding 0.0 turns -0.0 into 0.0.
        let p = [c.x + 0.0, c.y + 0.0];
        if ring.last() != Some(&p) {
            ring.push(p);
        }
    }
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    if ring.len() < 3 {
        return Err(bad(format!(
            "has {} distinct consecutive point{}; at least 3 are needed",
            ring.len(),
            if ring.len() == 1 { "" } else { "s" }
        )));
    }
    if ring.len() > MAX_POLYGON_VERTICES {
        return Err(bad(format!(
            "has {} points; at most {MAX_POLYGON_VERTICES} are allowed",
            ring.len()
        )));
    }
    if let Some((i, j)) = self_contact(&ring) {
        return Err(bad(format!(
            "is not simple: its edges {i} and {j} (0-based, edge k from point k to k + 1) cross, touch or overlap"
        )));
    }
    Ok(ring)
}

/// Whether the simple polygon `ring` turns counter-clockwise (`Greater`) or clockwise
/// (`Less`), decided exactly at its lowest-leftmost vertex. (Its neighbours cannot be
/// collinear with it: they would lie on the same side of it, folding back, and
/// [`self_contact`] rejects that.)
fn winding(ring: &[[f64; 2]]) -> Ordering {
    let n = ring.len();
    let lowest = (0..n)
        .min_by(|&a, &b| {
            let (p, q) = (ring[a], ring[b]);
            p[1].total_cmp(&q[1]).then(p[0].total_cmp(&q[0]))
        })
        .unwrap_or(0);
    orient2d(
        ring[(lowest + n - 1) % n],
        ring[lowest],
        ring[(lowest + 1) % n],
    )
}

/// The first pair of edges (edge k runs from point k to point k + 1) that meet other than at
/// a shared endpoint of neighbouring edges, or that overlap, decided exactly. Edges are swept
/// in order of their smallest x so that only edges with overlapping x-ranges are compared.
fn self_contact(ring: &[[f64; 2]]) -> Option<(usize, usize)> {
    let n = ring.len();
    let seg = |k: usize| (ring[k], ring[(k + 1) % n]);
    let xmin = |k: usize| ring[k][0].min(ring[(k + 1) % n][0]);
    let xmax = |k: usize| ring[k][0].max(ring[(k + 1) % n][0]);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| xmin(a).total_cmp(&xmin(b)));
    for (pos, &i) in order.iter().enumerate() {
        for &j in &order[pos + 1..] {
            if xmin(j) > xmax(i) {
                break;
            }
            let (lo, hi) = (i.min(j), i.max(j));
            let adjacent = hi == lo + 1 || (lo == 0 && hi == n - 1);
            let (a, b) = seg(lo);
            let (c, d) = seg(hi);
            let meets = if adjacent {
                // Neighbouring edges share one endpoint; they meet elsewhere only when they
                // fold back onto each other.
                let (shared, p, q) = if hi == lo + 1 { (b, a, d) } else { (a, b, c) };
                folds_back(shared, p, q)
            } else {
                segments_meet(a, b, c, d)
            };
            if meets {
                return Some((lo, hi));
            }
        }
    }
    None
}

/// Whether the edges from `shared` to `p` and to `q` overlap: the three points are collinear
/// and `p`, `q` lie on the same side of `shared`.
fn folds_back(shared: [f64; 2], p: [f64; 2], q: [f64; 2]) -> bool {
    if orient2d(shared, p, q) != Ordering::Equal {
        return false;
    }
    // Collinear: same direction iff every coordinate moves the same way (signs of
    // differences of doubles are exact).
    (0..2).all(|k| (p[k] - shared[k]).total_cmp(&0.0) == (q[k] - shared[k]).total_cmp(&0.0))
}
