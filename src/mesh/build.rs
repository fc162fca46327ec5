//! Building a mesh's faces from input polygons: each polygon is decided exactly (repeated
//! vertices, zero area, planarity, simplicity) and becomes a face, several faces (a polygon
//! that is not exactly planar, split into triangles), or none (a degenerate one).
//!
//! Every sign is an exact predicate on the input coordinates. The rounded quantities of a face
//! (its plane, texture frame and area) are computed on its points scaled by a power of two
//! (exact) when they are very large or very small, then scaled back, so they neither overflow
//! nor underflow into nonsense at any scale.

use super::face::{Face, Loop, Plane};
use super::{MeshError, Validation};
use crate::geometry::polygon::{dominant_axis, newell_normal, triangulate_along};
use crate::geometry::predicates::{collinear, orient2d, orient3d, project};
use crate::geometry::{Point3, Vector3};
use smallvec::SmallVec;
use std::cmp::Ordering;

/// Points whose largest coordinate magnitude lies in `[2^-SAFE, 2^SAFE]` (or is 0) are used
/// as they are: products of up to four of their coordinates neither overflow nor underflow,
/// and the results are the same bits as with any power-of-two scaling. Others are scaled.
const SAFE: i32 = 200;

/// `x · 2^e`, exact unless the result overflows or falls below the normal range, for any `e`
/// (in steps, since `2^e` itself is representable only for `e` in −1074..=1023).
pub(crate) fn times_power_of_two(mut x: f64, mut e: i32) -> f64 {
    while e != 0 {
        let step = e.clamp(-1000, 1000);
        x *= 2f64.powi(step);
        e -= step;
    }
    x
}

/// The power of two `e` by which to scale coordinates whose largest magnitude is `largest`
/// so that it comes near 1: 0 when it is 0, not finite, or within `2^±safe` already.
pub(crate) fn normalising_exponent(largest: f64, safe: i32) -> i32 {
    if largest == 0.0 || !largest.is_finite() {
        return 0;
    }
    // log2 of a positive finite f64 is finite and within about 1 of its exponent.
    let k = largest.log2().floor() as i32;
    if k.abs() <= safe { 0 } else { -k }
}

/// The largest coordinate magnitude of the points.
pub(crate) fn largest_coordinate<'a>(points: impl IntoIterator<Item = &'a Point3>) -> f64 {
    points
        .into_iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0.0, f64::max)
}

/// A polygon's points, inline for triangles and quads.
pub(crate) type Points = SmallVec<[Point3; 4]>;

/// Triangles of a polygon (indices into its loop), inline for triangles and quads.
pub(crate) type Local = SmallVec<[[usize; 3]; 2]>;

/// Triangles of a face (indices into the mesh's vertices), inline for triangles and quads.
pub(crate) type Triangles = SmallVec<[[u32; 3]; 2]>;

/// The points scaled by `2^e`.
fn scaled(points: &[Point3], e: i32) -> Points {
    if e == 0 {
        return SmallVec::from_slice(points);
    }
    points
        .iter()
        .map(|p| p.map(|c| times_power_of_two(c, e)))
        .collect()
}

/// What an input polygon becomes.
pub(crate) enum Shape {
    /// Nothing: a degenerate face (repeated vertices, or zero area), left out.
    Degenerate,
    /// One planar face: its vertex loop and its triangles (indices into the loop).
    Planar(Loop, Local),
    /// A polygon that is not exactly planar, split into these triangles (indices into the
    /// loop), each a face.
    Split(Loop, Local),
}

/// Decides what the input polygon `idx` (face `fi`, vertex indices already merged) becomes,
/// or the error that refuses it (`Strict` refuses degenerate and non-planar polygons, both
/// modes refuse polygons that cross themselves).
pub(crate) fn shape(
    vertices: &[Point3],
    mut idx: Loop,
    fi: usize,
    validation: Validation,
) -> Result<Shape, MeshError> {
    match validation {
        Validation::Strict => {
            if let Some(v) = repeated(&idx) {
                let p = vertices[v as usize];
                return Err(MeshError::RepeatedVertex {
                    face: fi,
                    x: p.x,
                    y: p.y,
                    z: p.z,
                });
            }
        }
        Validation::Repair => {
            // A vertex repeated in a row is a zero-length side: the loop without it is the
            // same polygon. A vertex repeated elsewhere makes the loop touch itself.
            idx.dedup();
            while idx.len() > 1 && idx.first() == idx.last() {
                idx.pop();
            }
            if idx.len() < 3 || repeated(&idx).is_some() {
                return Ok(Shape::Degenerate);
            }
        }
    }
    let pts: Points = idx.iter().map(|&i| vertices[i as usize]).collect();
    let (a, b) = (&pts[0], &pts[1]);
    let Some(k) = (2..pts.len()).find(|&k| !collinear(a, b, &pts[k])) else {
        return match validation {
            Validation::Strict => Err(MeshError::ZeroArea { face: fi }),
            Validation::Repair => Ok(Shape::Degenerate),
        };
    };
    if pts.len() == 3 {
        return Ok(Shape::Planar(
            idx,
            SmallVec::from_buf_and_len([[0, 1, 2]; 2], 1),
        ));
    }
    let c = &pts[k];
    let off_plane =
        (2..pts.len()).find(|&j| j != k && orient3d(a, b, c, &pts[j]) != Ordering::Equal);
    if let (Some(corner), Validation::Strict) = (off_plane, validation) {
        return Err(MeshError::NonPlanar { face: fi, corner });
    }
    // Projections in the order of the normal's components, largest first: for a planar
    // polygon the first is simple exactly when the polygon is; a polygon that is not planar
    // is split in the first projection where it is simple.
    let axes = projection_axes(&pts);
    let tris = axes
        .iter()
        .find_map(|&axis| match off_plane {
            None => triangulate_along(&pts, axis).ok().map(SmallVec::from_vec),
            Some(_) => canonical_split(&idx, &pts, axis).map(SmallVec::from_vec),
        })
        .ok_or(MeshError::NotSimple { face: fi })?;
    Ok(match off_plane {
        None => Shape::Planar(idx, tris),
        Some(_) => Shape::Split(idx, tris),
    })
}

/// A vertex index the loop visits twice, if any.
fn repeated(idx: &[u32]) -> Option<u32> {
    if idx.len() <= 8 {
        // Few vertices: every pair, without sorting a copy.
        return (1..idx.len()).find_map(|j| idx[..j].contains(&idx[j]).then_some(idx[j]));
    }
    let mut sorted = idx.to_vec();
    sorted.sort_unstable();
    sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
}

/// The coordinate axes to project the polygon `pts` along, in the order of its (Newell)
/// normal's components, largest first.
fn projection_axes(pts: &[Point3]) -> [usize; 3] {
    let n = newell_normal(&scaled(
        pts,
        normalising_exponent(largest_coordinate(pts), SAFE),
    ));
    let first = dominant_axis(&n);
    let mut axes = [first, (first + 1) % 3, (first + 2) % 3];
    axes[1..].sort_by(|&i, &j| n[j].abs().total_cmp(&n[i].abs()));
    axes
}

/// The triangles (indices into the loop `idx`, turning as it does) that split a polygon that
/// is not exactly planar, in the projection along `axis`, or `None` if it is not simple there.
/// The split is part of the surface, so it must not depend on how the polygon is given: it is
/// made on the loop started at its smallest vertex index and run towards the smaller of that
/// vertex's neighbours, so that the polygon given from another vertex, reversed, or mirrored
/// (which reverses it) is split along the same diagonals.
fn canonical_split(idx: &[u32], pts: &[Point3], axis: usize) -> Option<Vec<[usize; 3]>> {
    let n = idx.len();
    let start = (0..n).min_by_key(|&i| idx[i])?;
    let forward = idx[(start + 1) % n] < idx[(start + n - 1) % n];
    let order: Vec<usize> = (0..n)
        .map(|k| if forward { start + k } else { start + n - k } % n)
        .collect();
    let canonical: Vec<Point3> = order.iter().map(|&i| pts[i]).collect();
    let tris = triangulate_along(&canonical, axis).ok()?;
    Some(
        tris.into_iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| order[k]);
                if forward { [a, b, c] } else { [a, c, b] }
            })
            .collect(),
    )
}

/// The face with vertex loop `idx` (planar, not degenerate) and triangles `local` (indices
/// into the loop), whose triangles start at `first_triangle` in the mesh's list; `diagonals`
/// marks the sides that are diagonals of a split polygon (bit `i`: the side from vertex `i`),
/// and `polygon` is the input polygon it comes from.
pub(crate) fn face(
    vertices: &[Point3],
    (idx, diagonals, polygon): (Loop, u8, u32),
    local: &[[usize; 3]],
    first_triangle: usize,
) -> (Face, Triangles) {
    let pts: Points = idx.iter().map(|&i| vertices[i as usize]).collect();
    let e = normalising_exponent(largest_coordinate(&pts), SAFE);
    let q = scaled(&pts, e);
    let n2 = newell_normal(&q);
    let len = n2.norm();
    let normal: Vector3 = if len > 0.0 && len.is_finite() {
        n2 / len
    } else {
        // The rounded normal vanished (a face extremely thin for its distance from the
        // origin): the axis of the exact projection its triangulation was made in, signed
        // by the exact orientation there.
        exact_axis_normal(&pts, local)
    };
    let centroid = q.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / q.len() as f64;
    let d = times_power_of_two(-normal.dot(&centroid), -e);
    let area = times_power_of_two(len / 2.0, -2 * e);
    let tris: Triangles = local.iter().map(|t| t.map(|k| idx[k])).collect();
    let face = Face {
        horizontal: pts.iter().all(|p| p.z == pts[0].z),
        plane: Plane::new(normal, d),
        area,
        triangles: first_triangle..first_triangle + tris.len(),
        vertices: idx,
        diagonals,
        polygon,
    };
    (face, tris)
}

/// A unit normal along a coordinate axis in which the first triangle of `local` is not
/// degenerate, pointing the way its vertices turn (exact).
fn exact_axis_normal(pts: &[Point3], local: &[[usize; 3]]) -> Vector3 {
    let Some(&[i, j, k]) = local.first() else {
        return Vector3::z();
    };
    (0..3)
        .find_map(|axis| {
            let o = orient2d(
                project(&pts[i], axis),
                project(&pts[j], axis),
                project(&pts[k], axis),
            );
            let sign = match o {
                Ordering::Greater => 1.0,
                Ordering::Less => -1.0,
                Ordering::Equal => return None,
            };
            let mut n = Vector3::zeros();
            n[axis] = sign;
            Some(n)
        })
        .unwrap_or_else(Vector3::z)
}

/// The sides of triangle `t` (indices into a polygon of `n` vertices) that are not sides of
/// the polygon: bit `i` for the side from `t[i]` to `t[(i + 1) % 3]`.
pub(crate) fn diagonals_of(t: &[usize; 3], n: usize) -> u8 {
    (0..3).fold(0, |bits, i| {
        let (u, v) = (t[i], t[(i + 1) % 3]);
        let side = (u + 1) % n == v || (v + 1) % n == u;
        if side { bits } else { bits | 1 << i }
    })
}

/// Merges vertices with exactly equal coordinates (`-0.0` equals `0.0`) after checking that
/// they are finite; returns the distinct vertices in first-seen order, the map from input
/// index to output index, and how many were merged.
///
/// Each vertex is the first one (lowest index) with its coordinates, or a copy of it. Found
/// by sorting the coordinates' bits with the indices (equal doubles have equal bits once -0.0
/// is gone) in parallel, rather than with a hash table filled in input order: on a scan of
/// half a million vertices the table's inserts, one cache miss each on one thread, took 0.16
/// s of a 0.55 s build, the sort a fraction of it. The result depends on neither.
pub(crate) fn merge_duplicates(
    mut vertices: Vec<Point3>,
) -> Result<(Vec<Point3>, Vec<u32>, usize), MeshError> {
    use rayon::prelude::*;
    let parallel = vertices.len() >= PARALLEL_VERTICES;
    let not_finite = |p: &Point3| p.iter().any(|c| !c.is_finite());
    let bad = if parallel {
        vertices.par_iter().position_first(not_finite)
    } else {
        vertices.iter().position(not_finite)
    };
    if let Some(vertex) = bad {
        return Err(MeshError::NonFinite { vertex });
    }
    // Adding +0.0 turns -0.0 into +0.0, so both sort and compare as one value.
    let key = |(i, p): (usize, &mut Point3)| {
        p.apply(|c| *c += 0.0);
        ([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()], i as u32)
    };
    let mut keyed: Vec<([u64; 3], u32)> = if parallel {
        vertices.par_iter_mut().enumerate().map(key).collect()
    } else {
        vertices.iter_mut().enumerate().map(key).collect()
    };
    if parallel {
        keyed.par_sort_unstable();
    } else {
        keyed.sort_unstable();
    }
    // first[i]: the lowest index with vertex i's coordinates (the first of its run, since
    // the indices are unique and sorted within a run); then, in input order, each first
    // vertex takes the next output index and each copy its first's.
    let mut first = vec![0u32; vertices.len()];
    for run in keyed.chunk_by(|a, b| a.0 == b.0) {
        for &(_, i) in run {
            first[i as usize] = run[0].1;
        }
    }
    drop(keyed);
    let mut out = Vec::with_capacity(vertices.len());
    for i in 0..first.len() {
        let f = first[i] as usize;
        first[i] = if f == i {
            out.push(vertices[i]);
            (out.len() - 1) as u32
        } else {
            first[f]
        };
    }
    let merged = vertices.len() - out.len();
    Ok((out, first, merged))
}

/// Meshes of at least this many vertices are checked and sorted in parallel.
const PARALLEL_VERTICES: usize = 1 << 14;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// The merge against a first-seen hash table: on vertex lists below and above the
    /// parallel size, drawn from few distinct points (many copies, -0.0 among them) in any
    /// order, the same distinct vertices in the same order and the same map.
    #[test]
    fn merging_keeps_the_first_of_equal_vertices_in_input_order() {
        let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
        let mut below = |n: u64| rng.next_u64() % n;
        let coordinate = [0.0, -0.0, 1.0, -1.0, 0.1, 1e-300, f64::MIN_POSITIVE, 1e300];
        for (len, distinct) in [
            (0, 1),
            (1, 1),
            (7, 3),
            (1000, 40),
            (50_000, 300),
            (40_000, 512),
        ] {
            let vertices: Vec<Point3> = (0..len)
                .map(|_| {
                    let k = below(distinct);
                    let c = |s: u64| coordinate[((k >> s) % 8) as usize];
                    Point3::new(c(0), c(3), c(6))
                })
                .collect();
            let mut seen = std::collections::HashMap::new();
            let mut expected = Vec::new();
            let expected_map: Vec<u32> = vertices
                .iter()
                .map(|p| {
                    let key = p.map(|c| (c + 0.0).to_bits());
                    *seen.entry((key.x, key.y, key.z)).or_insert_with(|| {
                        expected.push(p.map(|c| c + 0.0));
                        (expected.len() - 1) as u32
                    })
                })
                .collect();
            let (out, map, merged) = merge_duplicates(vertices.clone()).unwrap();
            assert_eq!(map, expected_map, "{len} vertices of {distinct}");
            assert_eq!(merged, len - expected.len());
            let bits = |v: &[Point3]| v.iter().map(|p| p.map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&out), bits(&expected));
        }
    }

    /// A vertex that is not finite is refused by its index, the first such one.
    #[test]
    fn merging_names_the_first_vertex_that_is_not_finite() {
        for len in [10, 40_000] {
            let mut vertices = vec![Point3::new(1.0, 2.0, 3.0); len];
            vertices[len / 2].y = f64::NAN;
            vertices[len - 1].z = f64::INFINITY;
            assert_eq!(
                merge_duplicates(vertices),
                Err(MeshError::NonFinite { vertex: len / 2 })
            );
        }
    }
}
