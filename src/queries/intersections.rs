//! Intersection lines: where two faces pierce each other, in different objects or in one.
//!
//! Candidate triangle pairs are those whose boxes meet, found with a uniform 3-D grid over the
//! region where the two meshes' boxes overlap; objects whose CBOXes do not overlap are not
//! compared at all. Which vertices lie on which side of the other triangle's plane is
//! decided exactly, and two triangles pierce each other only when each has vertices strictly
//! on both sides of the other's plane: touching faces (a box resting on another, neighbours
//! sharing an edge or a vertex) make no intersection line, and coplanar faces none
//! either. The part of the line inside both triangles runs between two of the points where a
//! triangle's edge crosses the other's plane; those are ordered along the line in floating
//! point (only ends within a few units in the last place of each other can be misordered),
//! and each end is built once from the input coordinates, exactly as an edge's cut.

use super::along::{Form, cut_point};
use crate::geometry::predicates::orient3d;
use crate::geometry::{Aabb, Point3};
use crate::mesh::Mesh;
use crate::views::{Eye, Picture};
use rayon::prelude::*;
use std::cmp::Ordering;

/// An end of an intersection segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum End {
    /// A vertex of one triangle, lying on the other's plane.
    Vertex(Point3),
    /// Where a triangle's edge crosses the plane of the other triangle.
    Crossing {
        /// The edge's ends.
        points: [Point3; 2],
        /// The other triangle.
        plane: [Point3; 3],
    },
}

impl End {
    /// The end as a rounded point (for the boxes and the order along the line).
    fn approximate(&self, eye: &Eye) -> Point3 {
        match self {
            End::Vertex(p) => *p,
            End::Crossing {
                points: [a, b],
                plane,
                ..
            } => {
                let t = Form::Plane(*plane).zero_along(eye, a, b).unwrap_or(0.5);
                a + (b - a) * t
            }
        }
    }

    /// The picture of the end, built once from the input coordinates.
    pub(crate) fn picture(&self, picture: &Picture, eye: &Eye) -> [f64; 2] {
        match self {
            End::Vertex(p) => picture.point(p),
            End::Crossing {
                points: [a, b],
                plane,
                ..
            } => cut_point(picture, eye, &Form::Plane(*plane), a, b),
        }
    }
}

/// A segment along which two triangles (of meshes 0 and 1, faces `faces`) pierce each other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Segment {
    /// Its ends.
    pub ends: [End; 2],
    /// Its ends, rounded.
    pub points: [Point3; 2],
    /// The faces whose triangles meet, in meshes 0 and 1.
    pub faces: [usize; 2],
    /// The triangles that meet, in meshes 0 and 1.
    pub triangles: [usize; 2],
}

/// The intersection segments of the triangles of `m0` with those of `m1` (`same` when they are
/// one mesh: then each pair once, and triangles sharing a vertex or a face are not compared).
pub(crate) fn between(m0: &Mesh, m1: &Mesh, same: bool, eye: &Eye) -> Vec<Segment> {
    candidate_pairs(m0, m1, same)
        .par_iter()
        .filter_map(|&(i, j)| {
            let (i, j) = (i as usize, j as usize);
            segment(&m0.triangle(i), &m1.triangle(j), eye).map(|ends| Segment {
                points: ends.map(|e| e.approximate(eye)),
                ends,
                faces: [m0.face_of(i), m1.face_of(j)],
                triangles: [i, j],
            })
        })
        .collect()
}

/// The pairs of triangles (of `m0`, of `m1`) whose closed boxes meet, each once: a uniform
/// 3-D grid over the region where the meshes' boxes overlap, cells about the size of a
/// triangle's box, each triangle listed in the cells its box meets. A pair is reported only in
/// the cell holding the low corner of the two boxes' overlap, so once. For one mesh (`same`),
/// pairs sharing a vertex or a face are left out.
fn candidate_pairs(m0: &Mesh, m1: &Mesh, same: bool) -> Vec<(u32, u32)> {
    let boxes = |m: &Mesh| -> Vec<Aabb> {
        (0..m.triangles().len())
            .into_par_iter()
            .map(|t| Aabb::from_points(&m.triangle(t)))
            .collect()
    };
    let b0 = boxes(m0);
    let b1 = if same { Vec::new() } else { boxes(m1) };
    if b0.len() * if same { b0.len() } else { b1.len() } <= FEW_PAIRS {
        return few_pairs(m0, &b0, if same { &b0 } else { &b1 }, same);
    }
    let second = if same { &b0 } else { &b1 };
    let whole = |b: &[Aabb]| b.iter().fold(Aabb::EMPTY, |u, x| u.union(x));
    let (w0, w1) = (whole(&b0), whole(second));
    let region = Aabb::new(
        Point3::from([0, 1, 2].map(|k| w0.min[k].max(w1.min[k]))),
        Point3::from([0, 1, 2].map(|k| w0.max[k].min(w1.max[k]))),
    );
    if (0..3).any(|k| region.min[k] > region.max[k]) {
        return Vec::new();
    }
    let mean = b0
        .iter()
        .chain(second.iter())
        .map(|b| b.size().into_iter().fold(0.0, f64::max))
        .sum::<f64>()
        / (b0.len() + second.len()).max(1) as f64;
    let size = region.size();
    // Cells twice the mean box: the total of pairs tested, about N²·(1 + e/s)⁶·s²/area for
    // boxes of size e in cells of size s, is least at s = 2e.
    let side = 2.0 * mean;
    // Only occupied cells are listed (items are sorted by cell), so a surface in a large
    // region costs nothing for the empty cells; the cap keeps cell numbers in 63 bits.
    let shape = size.map(|e| {
        if side > 0.0 {
            ((e / side).ceil() as usize).clamp(1, 1 << 20)
        } else {
            1
        }
    });
    let index = |k: usize, v: f64| -> usize {
        if size[k] <= 0.0 {
            return 0;
        }
        let c = (v - region.min[k]) / size[k] * shape[k] as f64;
        if c >= shape[k] as f64 {
            shape[k] - 1
        } else if c > 0.0 {
            c as usize
        } else {
            0
        }
    };
    let cell_of = |c: [usize; 3]| ((c[2] * shape[1] + c[1]) * shape[0] + c[0]) as u64;
    let list = |b: &[Aabb], mesh: u32| -> Vec<(u64, u32)> {
        b.par_iter()
            .enumerate()
            .fold(Vec::new, |mut out, (t, bx)| {
                if (0..3).any(|k| bx.max[k] < region.min[k] || bx.min[k] > region.max[k]) {
                    return out;
                }
                let r = |k: usize| index(k, bx.min[k])..=index(k, bx.max[k]);
                for z in r(2) {
                    for y in r(1) {
                        for x in r(0) {
                            out.push((cell_of([x, y, z]), (mesh << 31) | t as u32));
                        }
                    }
                }
                out
            })
            .reduce(Vec::new, |mut x, mut y| {
                x.append(&mut y);
                x
            })
    };
    let mut items = list(&b0, 0);
    if !same {
        items.extend(list(&b1, 1));
    }
    items.par_sort_unstable();
    let runs: Vec<&[(u64, u32)]> = items.chunk_by(|x, y| x.0 == y.0).collect();
    runs.par_iter()
        .flat_map_iter(|run| {
            let cell = run[0].0;
            let of = |item: (u64, u32)| (item.1 & 0x7fff_ffff) as usize;
            // Items sort by mesh within a cell (mesh 0 first): split there.
            let split = if same {
                run.len()
            } else {
                run.partition_point(|i| i.1 >> 31 == 0)
            };
            let (firsts, seconds) = if same {
                (*run, *run)
            } else {
                run.split_at(split)
            };
            let mut out = Vec::new();
            for (n, &x) in firsts.iter().enumerate() {
                // For one mesh, each pair once: the items after x (larger triangle indices).
                let others = if same { &seconds[n + 1..] } else { seconds };
                for &y in others {
                    let (i, j) = (of(x), of(y));
                    let (bi, bj) = (&b0[i], &second[j]);
                    if !bi.intersects(bj) {
                        continue;
                    }
                    let low = [0, 1, 2].map(|k| index(k, bi.min[k].max(bj.min[k])));
                    if cell_of(low) != cell || (same && neighbours(m0, i, j)) {
                        continue;
                    }
                    out.push((i as u32, j as u32));
                }
            }
            out
        })
        .collect()
}

/// Up to this many triangle pairs, every pair is tested: no grid.
const FEW_PAIRS: usize = 1 << 14;

/// [`candidate_pairs`] by testing every pair of the triangles' boxes `b0` and `b1`.
fn few_pairs(m0: &Mesh, b0: &[Aabb], b1: &[Aabb], same: bool) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for (i, bi) in b0.iter().enumerate() {
        let start = if same { i + 1 } else { 0 };
        for (j, bj) in b1.iter().enumerate().skip(start) {
            if bi.intersects(bj) && !(same && neighbours(m0, i, j)) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

/// Whether triangles `i` and `j` of one mesh lie on one face or share a vertex: they are
/// not compared for intersection.
fn neighbours(m: &Mesh, i: usize, j: usize) -> bool {
    shares_vertex(&m.triangles()[i], &m.triangles()[j]) || m.face_of(i) == m.face_of(j)
}

/// Whether two triangles share a vertex index.
fn shares_vertex(a: &[u32; 3], b: &[u32; 3]) -> bool {
    a.iter().any(|v| b.contains(v))
}

/// The segment where the triangles `t0` and `t1` pierce each other, if they do along a segment
/// of positive length.
fn segment(t0: &[Point3; 3], t1: &[Point3; 3], eye: &Eye) -> Option<[End; 2]> {
    let s0 = t0.map(|p| orient3d(&t1[0], &t1[1], &t1[2], &p));
    if !straddles(&s0) {
        return None;
    }
    let s1 = t1.map(|p| orient3d(&t0[0], &t0[1], &t0[2], &p));
    if !straddles(&s1) {
        return None;
    }
    let e0 = plane_section(t0, &s0, t1)?;
    let e1 = plane_section(t1, &s1, t0)?;
    // Order the four ends along the line (the direction of the normals' cross product).
    let n0 = (t0[1] - t0[0]).cross(&(t0[2] - t0[0]));
    let n1 = (t1[1] - t1[0]).cross(&(t1[2] - t1[0]));
    let d = n0.cross(&n1);
    let along = |e: &End| e.approximate(eye).coords.dot(&d);
    let sorted = |[x, y]: [End; 2]| {
        if along(&x) <= along(&y) {
            [x, y]
        } else {
            [y, x]
        }
    };
    let ([a0, b0], [a1, b1]) = (sorted(e0), sorted(e1));
    let start = if along(&a0) >= along(&a1) { a0 } else { a1 };
    let end = if along(&b0) <= along(&b1) { b0 } else { b1 };
    (along(&start) < along(&end)).then_some([start, end])
}

/// Whether the triangle has vertices strictly on both sides of the other's plane. Without,
/// the triangles are apart, coplanar, or only touch (a face resting on another meets it along
/// an edge that is drawn already): no intersection line.
fn straddles(s: &[Ordering; 3]) -> bool {
    s.contains(&Ordering::Greater) && s.contains(&Ordering::Less)
}

/// The two ends of the section of triangle `t` by the plane of `other`, given the exact sides
/// `s` of its vertices, or `None` when the plane only touches it at one point.
fn plane_section(t: &[Point3; 3], s: &[Ordering; 3], other: &[Point3; 3]) -> Option<[End; 2]> {
    let mut ends = Vec::with_capacity(3);
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] == Ordering::Equal {
            ends.push(End::Vertex(t[i]));
        } else if s[j] != Ordering::Equal && s[i] != s[j] {
            ends.push(End::Crossing {
                points: [t[i], t[j]],
                plane: *other,
            });
        }
    }
    match ends[..] {
        [a, b] => Some([a, b]),
        _ => None,
    }
}

/// Where the segment `ab` passes through the closed triangle `tri` crossing its plane (its
/// ends strictly on either side of it), the parameter of the crossing along `ab`.
pub(crate) fn pierces(eye: &Eye, a: &Point3, b: &Point3, tri: &[Point3; 3]) -> Option<f64> {
    let (sa, sb) = (
        orient3d(&tri[0], &tri[1], &tri[2], a),
        orient3d(&tri[0], &tri[1], &tri[2], b),
    );
    if sa == Ordering::Equal || sb == Ordering::Equal || sa == sb {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match orient3d(a, b, &tri[i], &tri[(i + 1) % 3]) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    if above && below {
        return None;
    }
    Form::Plane(*tri).zero_along(eye, a, b)
}
