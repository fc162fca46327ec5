//! One cell `S ∩ C` of the subdivision and its split by a plane (Crosnier and Rossignac 1999,
//! §4). A cell is kept implicitly, as the paper does: its region `C` (a tribox: at most 18
//! half-spaces along the 9 directions), the object's triangles that may meet `C`, and the
//! cell's vertices, from which its tribox follows.
//!
//! # The vertices of a cell, incrementally
//!
//! Splitting a cell by the plane `h: d · x = h` keeps, on each side, the parent's vertices on
//! that side (closed), and adds the vertices the cut creates, all on `h` and shared by both
//! children:
//! - edges of `S` crossing `h` inside `C` (the paper's "edges of S with faces of C");
//! - vertices of the polygon `C ∩ h` inside `S` ("vertices of C in S");
//! - edges of that polygon crossing faces of `S` ("edges of C with faces of S").
//!
//! Vertices of `S` in `C` are the root cell's vertices, passed down. Every vertex of `S ∩ C'`
//! is one of these, so the children's vertex sets are complete.
//!
//! # Exactness
//!
//! Every decision (side of `h`, inside a half-space of `C`, crossing or not) is an exact sign
//! of an expansion in the input coordinates and the regions' offsets. A built point is each
//! coordinate's exact rational value, numerator and denominator each correctly rounded, then
//! divided: within 2 ulps of the coordinate, and known exact when both were exact and the
//! division leaves no remainder (a region corner is exact when it lies exactly on its three
//! planes). Each inexact coordinate carries an error of 4 ulps that surely holds the exact
//! one; a tribox is taken over the corners of these error boxes, so it contains the exact
//! cell. Only the region's corners are classified against `S` as rounded points: one that may
//! lie within its error of the surface is kept whatever the answer, since an extra point can
//! only loosen a bound.

use crate::bounds::tribox::{Tribox, TriboxBounds};
use crate::geometry::exact::{
    add_round_down, add_round_up, estimate, expansion, expansion_product, expansion_sum, negated,
    scale_expansion, sum_sign,
};
use crate::geometry::{Aabb, Point3, Vector3};
use crate::mesh::{Containment, Mesh, TriangleTree, classify_point};
use std::cmp::Ordering;

/// A vertex of a cell: a point, and how far (in each coordinate) the exact vertex may be from
/// it: 0 for the object's own vertices and for built coordinates found exact. `sure` tells
/// that the exact vertex is known to lie in the cell; the others are kept only because they
/// may (a built point whose error box meets a splitting plane goes to both sides).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CellVertex {
    p: Point3,
    err: [f64; 3],
    sure: bool,
}

impl CellVertex {
    /// An exact point of the cell.
    fn exact(p: Point3) -> CellVertex {
        CellVertex {
            p,
            err: [0.0; 3],
            sure: true,
        }
    }

    /// A built point of the cell: coordinates marked exact are, the others are within 2 ulps.
    fn built(p: Point3, exact: [bool; 3]) -> CellVertex {
        CellVertex {
            p,
            sure: true,
            err: [0, 1, 2].map(|k| {
                if exact[k] {
                    0.0
                } else {
                    4.0 * f64::EPSILON * p[k].abs() + 4.0 * f64::MIN_POSITIVE
                }
            }),
        }
    }

    /// The largest error of a coordinate.
    fn max_err(&self) -> f64 {
        self.err[0].max(self.err[1]).max(self.err[2])
    }
}

/// A cell `S ∩ C`.
#[derive(Clone, Debug)]
pub(crate) struct Cell {
    /// The region `C`.
    pub region: TriboxBounds,
    /// The tribox of the cell (contains the exact cell; inside `region`).
    pub tribox: TriboxBounds,
    /// The object's triangles that meet `C` (closed).
    triangles: Vec<u32>,
    /// The cell's vertices (a superset only by points within rounding of the cell).
    vertices: Vec<CellVertex>,
}

/// Which children a parent's vertex goes to.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Children {
    Below,
    Above,
    Both,
}

/// The terms of `n_j · p − β_j` for plane `j` of a region (all products exact: the normals'
/// entries are 0 and ±1).
fn plane_terms(j: usize, beta: f64, p: &Point3) -> ([f64; 4], usize) {
    let n = Tribox::PLANE_NORMALS[j];
    let mut t = [0.0; 4];
    let mut len = 0;
    for k in 0..3 {
        if n[k] != 0.0 {
            t[len] = n[k] * p[k];
            len += 1;
        }
    }
    t[len] = -beta;
    (t, len + 1)
}

/// The exact value of `n_j · p − β_j` as an expansion.
fn plane_value(j: usize, beta: f64, p: &Point3) -> Vec<f64> {
    let (t, len) = plane_terms(j, beta, p);
    expansion(&t[..len])
}

/// The exact sign of `n_j · p − β_j`.
fn plane_sign(j: usize, beta: f64, p: &Point3) -> Ordering {
    let (t, len) = plane_terms(j, beta, p);
    sum_sign(&t[..len])
}

/// The offsets `β_j` of the 18 half-spaces `n_j · x ≤ β_j` of a region.
fn offsets(region: &TriboxBounds) -> [f64; 18] {
    std::array::from_fn(|j| {
        if j % 2 == 0 {
            -region.min()[j / 2]
        } else {
            region.max()[j / 2]
        }
    })
}

/// The point `Σ wᵢ pᵢ / Σ wᵢ` for exact weights, each coordinate from a correctly rounded
/// numerator and denominator; a coordinate is exact when both are and the division leaves no
/// remainder.
fn weighted_point(weights: &[Vec<f64>], points: &[Point3], total: &[f64]) -> CellVertex {
    let den = estimate(total);
    let den_exact = sum_sign(&[total, &[-den]].concat()) == Ordering::Equal;
    let coordinate = |k: usize| {
        let mut num: Vec<f64> = Vec::new();
        for (w, p) in weights.iter().zip(points) {
            num = expansion_sum(&num, &scale_expansion(w, p[k]));
        }
        let n = estimate(&num);
        let q = n / den;
        let exact = den_exact
            && sum_sign(&[&num[..], &[-n]].concat()) == Ordering::Equal
            && (-q).mul_add(den, n) == 0.0
            && (q == 0.0 || q.abs() >= f64::MIN_POSITIVE);
        (q, exact)
    };
    let c = [0, 1, 2].map(coordinate);
    CellVertex::built(Point3::new(c[0].0, c[1].0, c[2].0), c.map(|(_, e)| e))
}

/// Whether the point `Σ wᵢ pᵢ / W` (weights all of one sign with `W`, so a convex combination)
/// satisfies the half-spaces of `region` other than `skip`, decided exactly.
fn combination_inside(
    beta: &[f64; 18],
    skip: impl Fn(usize) -> bool,
    weights: &[Vec<f64>],
    points: &[Point3],
    total_sign: Ordering,
) -> bool {
    (0..18).filter(|&j| !skip(j)).all(|j| {
        let signs: Vec<Ordering> = points.iter().map(|p| plane_sign(j, beta[j], p)).collect();
        if signs.iter().all(|&s| s != Ordering::Greater) {
            return true; // a convex combination of points inside
        }
        if signs.iter().all(|&s| s == Ordering::Greater) {
            return false;
        }
        let mut value: Vec<f64> = Vec::new();
        for (w, p) in weights.iter().zip(points) {
            value = expansion_sum(&value, &expansion_product(w, &plane_value(j, beta[j], p)));
        }
        let s = sum_sign(&value);
        let s = if total_sign == Ordering::Less {
            s.reverse()
        } else {
            s
        };
        s != Ordering::Greater
    })
}

impl Cell {
    /// The whole object: its tribox is its region.
    pub fn root(mesh: &Mesh) -> Cell {
        let mut used = vec![false; mesh.vertices().len()];
        for t in mesh.triangles() {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let vertices: Vec<CellVertex> = mesh
            .vertices()
            .iter()
            .zip(&used)
            .filter(|&(_, &u)| u)
            .map(|(&p, _)| CellVertex::exact(p))
            .collect();
        let points: Vec<Point3> = vertices.iter().map(|v| v.p).collect();
        let tribox = TriboxBounds::from_points(&points);
        Cell {
            region: tribox,
            tribox,
            triangles: (0..mesh.triangles().len() as u32).collect(),
            vertices,
        }
    }

    /// The number of vertices kept for the cell.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// The number of the object's triangles that may meet the cell's region.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The plane `d · x = h` bisecting the cell's tribox slab along direction `d`, if that slab
    /// has room for a plane strictly inside.
    pub fn bisector(&self, d: usize) -> Option<f64> {
        let (lo, hi) = (self.tribox.min()[d], self.tribox.max()[d]);
        let h = 0.5 * lo + 0.5 * hi;
        (lo < h && h < hi).then_some(h)
    }

    /// Up to `count` planes across direction `d` through the object's vertices in the cell
    /// (at their values along `d`, rounded for the diagonal directions),
    /// strictly inside its tribox's slab (evenly spread in rank when there are more): where a
    /// concave corner can be cut off, which no bisector reaches.
    pub fn feature_planes(&self, d: usize, count: usize) -> Vec<f64> {
        let n = TriboxBounds::DIRECTIONS[d];
        let (lo, hi) = (self.tribox.min()[d], self.tribox.max()[d]);
        let mut values: Vec<f64> = self
            .vertices
            .iter()
            .filter(|v| v.err == [0.0; 3])
            .map(|v| n[0] * v.p.x + n[1] * v.p.y + n[2] * v.p.z)
            .filter(|&h| lo < h && h < hi)
            .collect();
        values.sort_unstable_by(f64::total_cmp);
        values.dedup();
        if values.len() <= count {
            return values;
        }
        (0..count)
            .map(|i| values[(2 * i + 1) * values.len() / (2 * count)])
            .collect()
    }

    /// The width of the cell's tribox along direction `d` (in length units).
    pub fn thickness(&self, d: usize) -> f64 {
        let norm = Vector3::from(TriboxBounds::DIRECTIONS[d]).norm();
        (self.tribox.max()[d] - self.tribox.min()[d]) / norm
    }

    /// The side of the plane `d · x = h` that a vertex is on, decided exactly for its whole
    /// error box: `Both` when the box meets the plane.
    fn side(v: &CellVertex, d: usize, h: f64) -> Children {
        let n = TriboxBounds::DIRECTIONS[d];
        // reach is a sum of at most two errors, each with slack enough for its rounding.
        let reach: f64 = (0..3).map(|k| n[k].abs() * v.err[k]).sum();
        if reach == 0.0 {
            return match plane_sign(2 * d + 1, h, &v.p) {
                Ordering::Less => Children::Below,
                Ordering::Greater => Children::Above,
                Ordering::Equal => Children::Both,
            };
        }
        let (t, len) = plane_terms(2 * d + 1, h, &v.p);
        let mut terms = [0.0; 5];
        terms[..len].copy_from_slice(&t[..len]);
        terms[len] = reach;
        let upper = sum_sign(&terms[..=len]);
        terms[len] = -reach;
        let lower = sum_sign(&terms[..=len]);
        if upper == Ordering::Less {
            Children::Below
        } else if lower == Ordering::Greater {
            Children::Above
        } else {
            Children::Both
        }
    }

    /// Splits the cell by the plane `d · x = h`: `[below, above]`, or None unless some vertex
    /// surely of the cell lies strictly on each side. Then both exact children have volume and both
    /// regions are solid; a plane at the cell's extreme (inside the tribox only by its
    /// outward rounding) or just beyond it would leave a flat region or an empty cell.
    pub fn split(&self, mesh: &Mesh, tree: &TriangleTree, d: usize, h: f64) -> Option<[Cell; 2]> {
        let sides: Vec<Children> = self.vertices.iter().map(|v| Cell::side(v, d, h)).collect();
        let strictly = |want: Children| {
            self.vertices
                .iter()
                .zip(&sides)
                .any(|(v, &side)| v.sure && side == want)
        };
        if !(strictly(Children::Below) && strictly(Children::Above)) {
            return None;
        }
        let [below_region, above_region] = self.region.split(d, h);
        let beta = offsets(&self.region);

        // Triangles, and the edges of S crossing h.
        let sorted = self.triangles_by_side(mesh, d, h);

        let mut new_vertices = edge_crossings(mesh, &sorted.crossing_edges, &beta, d, h);

        // The polygon C ∩ h: a face of the upper region's boundary.
        let boundary = Tribox::new(&above_region).cleaned();
        let above_beta = offsets(&above_region);
        new_vertices.extend(polygon_corners(tree, &boundary, &above_beta, d));
        new_vertices.extend(polygon_edge_crossings(
            mesh,
            &boundary,
            &above_beta,
            &sorted.on_h,
            d,
            h,
        ));

        let (below_vertices, above_vertices) = self.vertices_by_side(&sides, &new_vertices);

        let child = |region: TriboxBounds, triangles: Vec<u32>, vertices: Vec<CellVertex>| {
            let tribox = bounds_of(&vertices)
                .intersection(&region)
                .intersection(&self.tribox);
            Cell {
                region,
                tribox,
                triangles,
                vertices,
            }
        };
        Some([
            child(below_region, sorted.below, below_vertices),
            child(above_region, sorted.above, above_vertices),
        ])
    }

    /// The cell's triangles on each side of the plane `d · x = h` (those meeting it on both),
    /// the triangles meeting it, and the edges of `S` crossing it strictly (each once, sorted).
    fn triangles_by_side(&self, mesh: &Mesh, d: usize, h: f64) -> TrianglesBySide {
        let hi_plane = 2 * d + 1;
        // The side of h as the sign of n · p − h with n = direction d: plane 2d + 1 with
        // offset h.
        let side_of = |p: &Point3| plane_sign(hi_plane, h, p);
        let mut below_triangles = Vec::new();
        let mut above_triangles = Vec::new();
        let mut on_h = Vec::new();
        let mut crossing_edges: Vec<(u32, u32)> = Vec::new();
        for &t in &self.triangles {
            let tri = mesh.triangles()[t as usize];
            let s = tri.map(|v| side_of(&mesh.vertices()[v as usize]));
            let below = s.iter().any(|&x| x != Ordering::Greater);
            let above = s.iter().any(|&x| x != Ordering::Less);
            if below {
                below_triangles.push(t);
            }
            if above {
                above_triangles.push(t);
            }
            if below && above {
                on_h.push(t);
                for k in 0..3 {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    if (s[k] == Ordering::Less && s[(k + 1) % 3] == Ordering::Greater)
                        || (s[k] == Ordering::Greater && s[(k + 1) % 3] == Ordering::Less)
                    {
                        crossing_edges.push((a.min(b), a.max(b)));
                    }
                }
            }
        }
        crossing_edges.sort_unstable();
        crossing_edges.dedup();
        TrianglesBySide {
            below: below_triangles,
            above: above_triangles,
            on_h,
            crossing_edges,
        }
    }

    /// The parent's vertices on each side of the cut, `(below, above)` (both when a built
    /// point is within its err of h), each followed by the vertices the cut made.
    fn vertices_by_side(
        &self,
        sides: &[Children],
        new_vertices: &[CellVertex],
    ) -> (Vec<CellVertex>, Vec<CellVertex>) {
        let mut below_vertices = Vec::with_capacity(self.vertices.len() + new_vertices.len());
        let mut above_vertices = Vec::with_capacity(self.vertices.len() + new_vertices.len());
        for (v, side) in self.vertices.iter().zip(sides) {
            // A built point on both sides by its error box may be in either cell only.
            let kept = CellVertex {
                sure: v.sure && (*side != Children::Both || v.err == [0.0; 3]),
                ..*v
            };
            if *side != Children::Above {
                below_vertices.push(kept);
            }
            if *side != Children::Below {
                above_vertices.push(kept);
            }
        }
        below_vertices.extend_from_slice(new_vertices);
        above_vertices.extend_from_slice(new_vertices);
        (below_vertices, above_vertices)
    }
}

/// A cell's triangles sorted by a splitting plane (see [`Cell::triangles_by_side`]).
struct TrianglesBySide {
    /// The triangles with a corner on or below the plane.
    below: Vec<u32>,
    /// The triangles with a corner on or above the plane.
    above: Vec<u32>,
    /// The triangles in both lists: those that meet the plane.
    on_h: Vec<u32>,
    /// The edges with one end strictly on each side, as `(lower index, higher index)`.
    crossing_edges: Vec<(u32, u32)>,
}

/// The vertices where the edges of `S` crossing the plane `d · x = h` cross it inside the
/// region of offsets `beta`: the point (A b − B a) / (A − B) with A, B the values of the plane
/// at a and b, inside C when each other half-space holds there.
fn edge_crossings(
    mesh: &Mesh,
    crossing_edges: &[(u32, u32)],
    beta: &[f64; 18],
    d: usize,
    h: f64,
) -> Vec<CellVertex> {
    let (lo_plane, hi_plane) = (2 * d, 2 * d + 1);
    let mut new_vertices = Vec::new();
    let skip_d = |j: usize| j == lo_plane || j == hi_plane;
    for &(a, b) in crossing_edges {
        let points = [mesh.vertices()[a as usize], mesh.vertices()[b as usize]];
        let (va, vb) = (
            plane_value(hi_plane, h, &points[0]),
            plane_value(hi_plane, h, &points[1]),
        );
        let weights = [negated(&vb), va.clone()];
        let total = expansion_sum(&va, &negated(&vb));
        let total_sign = sum_sign(&total);
        if combination_inside(beta, skip_d, &weights, &points, total_sign) {
            new_vertices.push(weighted_point(&weights, &points, &total));
        }
    }
    new_vertices
}

/// Corner `v` of `boundary` (the upper region's, of offsets `beta`) as a cell vertex: exact
/// when it lies exactly on its three (independent) planes.
fn region_corner(boundary: &Tribox, beta: &[f64; 18], v: u8) -> CellVertex {
    let p = boundary.vertices()[v as usize];
    let on_planes = boundary.vertex_planes()[v as usize]
        .iter()
        .all(|&j| plane_sign(j as usize, beta[j as usize], &p) == Ordering::Equal);
    CellVertex::built(p, [on_planes; 3])
}

/// The corners of the polygon C ∩ h (the face of plane `2d` of `boundary`, the upper region's,
/// of offsets `beta`) inside `S`, or that may lie within their error of its surface (a
/// rounded corner that may is kept, not sure).
fn polygon_corners(
    tree: &TriangleTree,
    boundary: &Tribox,
    beta: &[f64; 18],
    d: usize,
) -> Vec<CellVertex> {
    let mut new_vertices = Vec::new();
    for &v in boundary.face(2 * d) {
        let mut vertex = region_corner(boundary, beta, v);
        // A rounded corner that may lie within err of the surface is kept, not sure.
        let inside = classify_point(tree, &vertex.p) != Containment::Outside;
        if inside || tree.distance(&vertex.p) <= 4.0 * vertex.max_err() {
            vertex.sure = inside && vertex.err == [0.0; 3];
            new_vertices.push(vertex);
        }
    }
    new_vertices
}

/// The points where the edges of the polygon C ∩ h (the face of plane `2d` of `boundary`, the
/// upper region's, of offsets `beta`) cross the triangles `on_h` of `S`: the line
/// {n_lo · x = β_lo, n_j · x = β_j} meets triangle t where its barycentric weights, the 2 × 2
/// determinants of the two plane values at the other two corners, agree in sign.
fn polygon_edge_crossings(
    mesh: &Mesh,
    boundary: &Tribox,
    beta: &[f64; 18],
    on_h: &[u32],
    d: usize,
    h: f64,
) -> Vec<CellVertex> {
    let (lo_plane, hi_plane) = (2 * d, 2 * d + 1);
    let skip_d = |j: usize| j == lo_plane || j == hi_plane;
    let polygon = boundary.face(lo_plane);
    let mut new_vertices = Vec::new();
    for (k, &u) in polygon.iter().enumerate() {
        let v = polygon[(k + 1) % polygon.len()];
        let Some(j) = (0..18).find(|&j| {
            j != lo_plane && {
                let f = boundary.face(j);
                (0..f.len()).any(|i| {
                    let (x, y) = (f[i], f[(i + 1) % f.len()]);
                    (x, y) == (u, v) || (x, y) == (v, u)
                })
            }
        }) else {
            continue;
        };
        let (pu, pv) = (
            region_corner(boundary, beta, u),
            region_corner(boundary, beta, v),
        );
        let pad = pu.max_err().max(pv.max_err());
        let lo = [0, 1, 2].map(|i| pu.p[i].min(pv.p[i]) - pad);
        let hi = [0, 1, 2].map(|i| pu.p[i].max(pv.p[i]) + pad);
        for &t in on_h {
            let tri = mesh.triangle(t as usize);
            let outside_box = (0..3)
                .any(|i| tri.iter().all(|p| p[i] < lo[i]) || tri.iter().all(|p| p[i] > hi[i]));
            if outside_box {
                continue;
            }
            let values = tri.map(|p| (plane_value(lo_plane, -h, &p), plane_value(j, beta[j], &p)));
            let weights: Vec<Vec<f64>> = (0..3)
                .map(|i| {
                    let (b, c) = (&values[(i + 1) % 3], &values[(i + 2) % 3]);
                    expansion_sum(
                        &expansion_product(&b.0, &c.1),
                        &negated(&expansion_product(&c.0, &b.1)),
                    )
                })
                .collect();
            let total = expansion_sum(&expansion_sum(&weights[0], &weights[1]), &weights[2]);
            let total_sign = sum_sign(&total);
            if total_sign == Ordering::Equal
                || weights.iter().any(|w| sum_sign(w) == total_sign.reverse())
            {
                continue;
            }
            let skip = |m: usize| skip_d(m) || m == j;
            if combination_inside(beta, skip, &weights, &tri, total_sign) {
                new_vertices.push(weighted_point(&weights, &tri, &total));
            }
        }
    }
    new_vertices
}

/// The tribox of the vertices' boxes: the exact bounds of the object's vertices, and of the
/// eight corners (rounded outward) of each built vertex's box.
fn bounds_of(vertices: &[CellVertex]) -> TriboxBounds {
    let mut points = Vec::with_capacity(vertices.len() * 2);
    for v in vertices {
        if v.err == [0.0; 3] {
            points.push(v.p);
        } else {
            let error_box = Aabb {
                min: [0, 1, 2].map(|k| add_round_down(v.p[k], -v.err[k])),
                max: [0, 1, 2].map(|k| add_round_up(v.p[k], v.err[k])),
            };
            points.extend_from_slice(&error_box.corners());
        }
    }
    TriboxBounds::from_points(&points)
}
