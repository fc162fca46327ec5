//! The INBOX: an axis-aligned box entirely inside a solid, as large as is practical
//! (Franklin 1981: "It should be as large as is easy to determine").
//!
//! Two constructions, both ending with an exact check, so an inbox never pokes out:
//!
//! - **Kernel box** (convex solids). The largest box inside the intersection of the faces'
//!   half-spaces, a small convex program: the box with centre `c` and half-sizes `h` lies in
//!   `n·x ≤ d` exactly when `n·c + |n|·h ≤ d`; maximise `Σ log h` by a barrier method with
//!   Newton steps (a 6×6 system per step, nalgebra). Any point on the inner side of every
//!   face plane of a closed, outward-oriented mesh is inside it (the first face a ray from
//!   it meets is met from inside), so the box is accepted when its eight corners pass exact
//!   `orient3d` tests against every triangle. For a convex solid the kernel is the solid and
//!   the box is the largest inscribed box.
//! - **Grown box** (any closed solid). From the deepest of a grid of interior seeds (inside
//!   by exact classification, depth from the R-tree's nearest triangle), a cube that fits the
//!   free ball grows one side at a time, doubling its step while it stays clear and halving
//!   it when blocked. A box is clear when no triangle meets its open interior, decided
//!   exactly ([`triangle_meets_open_box`]); a clear box whose centre is inside lies inside.
//!
//! Both finish by snapping each side outward onto a vertex coordinate when that stays valid,
//! so a box-shaped solid's inbox is exactly itself.

use crate::geometry::predicates::{orient2d, orient3d, project, triangle_meets_open_box};
use crate::geometry::{Aabb, Point3, Vector3};
use crate::mesh::{
    Containment, Mesh, TriangleTree, classify_point, largest_coordinate, normalising_exponent,
    times_power_of_two,
};
use nalgebra::{Matrix6, Vector6};
use serde::Serialize;
use std::cmp::Ordering;

/// How an inbox was found.
///
/// ```
/// use kepler::bounds::{InboxMethod, inbox};
/// let i = inbox(&kepler::solids::cube(1.0).unwrap()).unwrap();
/// assert_eq!(i.method, InboxMethod::Kernel);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum InboxMethod {
    /// The largest box in the intersection of the face half-spaces (optimal for convex solids).
    Kernel,
    /// Grown from a deep interior point.
    Grown,
    /// The largest inbox of the subobjects.
    Subobject,
}

/// An inbox and how it was found.
///
/// ```
/// let i = kepler::bounds::inbox(&kepler::solids::cube(2.0).unwrap()).unwrap();
/// assert_eq!((i.aabb.min, i.aabb.max), ([-1.0; 3], [1.0; 3]));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Inbox {
    /// The box.
    pub aabb: Aabb,
    /// How it was found.
    pub method: InboxMethod,
}

/// The inbox of a mesh, or `None` when the mesh has no interior: it is open, inconsistently
/// oriented, flat, or no interior box could be certified.
///
/// ```
/// use kepler::bounds::inbox;
/// let sphere = kepler::solids::uv_sphere(1.0, 32, 16).unwrap();
/// let b = inbox(&sphere).unwrap().aabb;
/// // At least 95% of the sphere's inscribed cube (edge 2/√3).
/// assert!(b.volume() >= 0.95 * (2.0 / 3f64.sqrt()).powi(3));
/// ```
pub fn inbox(mesh: &Mesh) -> Option<Inbox> {
    if !mesh.is_solid() {
        return None;
    }
    // Very large or very small coordinates: the box of the mesh scaled by a power of two
    // (exactly) towards unit size, scaled back and checked again.
    match normalising_exponent(largest_coordinate(mesh.vertices()), SAFE) {
        0 => unscaled_inbox(mesh),
        e => scaled_inbox(mesh, e),
    }
}

/// Meshes whose largest coordinate magnitude lies in `[2^-SAFE, 2^SAFE]` are boxed as they
/// are: the volumes, squared distances and Newton steps of the constructions stay finite and
/// normal.
const SAFE: i32 = 150;

/// The inbox of `mesh` computed on the mesh scaled by `2^e`, scaled back: each side moved
/// inward where scaling back is not exact, and the box checked again exactly against the
/// mesh (a box inside the inbox of the scaled mesh is inside the mesh when scaling was exact).
fn scaled_inbox(mesh: &Mesh, e: i32) -> Option<Inbox> {
    // Scaled vertex by vertex: a scaling matrix's determinant (`2^3e`) would overflow or
    // underflow.
    let vertices = mesh
        .vertices()
        .iter()
        .map(|p| p.map(|c| times_power_of_two(c, e)))
        .collect();
    let faces = mesh.faces().iter().map(|f| f.vertices().to_vec()).collect();
    let scaled = Mesh::from_polygons(vertices, faces).ok()?;
    // A scaling that lost bits (a mesh spanning more than the range of f64's exponents) can
    // change the mesh: no inbox then.
    if scaled.vertices().len() != mesh.vertices().len() || !scaled.is_solid() {
        return None;
    }
    let found = unscaled_inbox(&scaled)?;
    let back = |x: f64, up: bool| {
        let y = times_power_of_two(x, -e);
        let again = times_power_of_two(y, e);
        match (again == x, up) {
            (true, _) => y,
            (false, true) if again > x => y.next_down(),
            (false, false) if again < x => y.next_up(),
            _ => y,
        }
    };
    let aabb = Aabb {
        min: found.aabb.min.map(|x| back(x, false)),
        max: found.aabb.max.map(|x| back(x, true)),
    };
    let tree = TriangleTree::new(mesh);
    let inside = (0..3).all(|k| aabb.min[k] < aabb.max[k])
        && classify_point(
            &tree,
            &Point3::from([0, 1, 2].map(|k| aabb.min[k] / 2.0 + aabb.max[k] / 2.0)),
        ) == Containment::Inside
        && clear(&tree, &aabb);
    inside.then_some(Inbox {
        aabb,
        method: found.method,
    })
}

/// [`inbox`] of a mesh of moderate coordinates.
fn unscaled_inbox(mesh: &Mesh) -> Option<Inbox> {
    let cbox = Aabb::from_points(mesh.vertices());
    if cbox.volume() <= 0.0 {
        return None;
    }
    let outward = if mesh.orientation() == Ordering::Less {
        Ordering::Greater
    } else {
        Ordering::Less
    };
    if in_kernel(mesh, &cbox, outward) {
        return Some(Inbox {
            aabb: cbox,
            method: InboxMethod::Kernel,
        });
    }
    let kernel = kernel_box(mesh, &cbox, outward);
    let flip = if outward == Ordering::Less { 1.0 } else { -1.0 };
    if kernel.is_some() && looks_convex(mesh, flip) {
        return kernel.map(|aabb| Inbox {
            aabb,
            method: InboxMethod::Kernel,
        });
    }
    let grown = grown_box(mesh, &cbox).map(|aabb| Inbox {
        aabb,
        method: InboxMethod::Grown,
    });
    let kernel = kernel.map(|aabb| Inbox {
        aabb,
        method: InboxMethod::Kernel,
    });
    match (kernel, grown) {
        (Some(k), Some(g)) => Some(if k.aabb.volume() >= g.aabb.volume() {
            k
        } else {
            g
        }),
        (k, g) => k.or(g),
    }
}

/// Whether every corner of `b` lies on the inner side of (or on) every triangle's plane;
/// `outward` is the `orient3d` sign of a point outside (it depends on the mesh's orientation).
fn in_kernel(mesh: &Mesh, b: &Aabb, outward: Ordering) -> bool {
    use rayon::prelude::*;
    let inside = |t: usize| box_inside_plane(&mesh.triangle(t), b, outward);
    let n = mesh.triangles().len();
    if n >= crate::mesh::PARALLEL_POLYGONS {
        (0..n).into_par_iter().all(inside)
    } else {
        (0..n).all(inside)
    }
}

/// Whether no corner of `b` lies strictly on the `outward` side of the plane of `t`, exactly.
///
/// Only the corners that can be extreme along the triangle's normal are tested: a normal
/// component whose sign the rounded cross product cannot be trusted with (far below its
/// rounding bound) makes both of its corners candidates. A triangle with one constant
/// coordinate lies in an axis plane and is decided by comparisons alone.
fn box_inside_plane(t: &[Point3; 3], b: &Aabb, outward: Ordering) -> bool {
    let [p, q, r] = t;
    for k in 0..3 {
        if p[k] == q[k] && q[k] == r[k] {
            // n = (0.., n_k, ..0), n_k with the sign of the projection's orientation, and
            // orient3d(p, q, r, x) has the sign of -n_k·(x_k - p_k): a corner is outside when
            // x_k - p_k has the sign `beyond`.
            let nk = orient2d(project(p, k), project(q, k), project(r, k));
            let beyond = if outward == Ordering::Less {
                nk
            } else {
                nk.reverse()
            };
            let out = |x: f64| x != p[k] && x.total_cmp(&p[k]) == beyond;
            return !(out(b.min[k]) || out(b.max[k]));
        }
    }
    let (u, v) = (q - p, r - p);
    let n = u.cross(&v);
    let bound = |i: usize, j: usize| 1e-10 * ((u[i] * v[j]).abs() + (u[j] * v[i]).abs());
    let certain = [
        n.x.abs() > bound(1, 2),
        n.y.abs() > bound(2, 0),
        n.z.abs() > bound(0, 1),
    ];
    // Outside means orient3d == outward, i.e. n·(x - p) has sign -outward; the corner most
    // likely outside maximises -outward·n·x.
    let towards = if outward == Ordering::Less { 1.0 } else { -1.0 };
    b.corners().iter().enumerate().all(|(i, c)| {
        let extreme = (0..3).all(|k| {
            let high = i & (1 << k) != 0;
            !certain[k] || high == (n[k] * towards > 0.0)
        });
        !extreme || orient3d(p, q, r, c) != outward
    })
}

/// Whether the surface looks convex: across every edge, no vertex of a neighbouring face
/// lies outside the face's plane by more than a rounding margin. This only chooses which
/// construction to run (the kernel box alone for convex solids); whatever it says, the box
/// returned has passed an exact test, so a rounding margin here costs nothing in exactness.
///
/// The faces' sides are bucketed by their lower vertex (a counting pass): the faces across
/// side `(u, v)` are those with side `(v, u)`, in the same bucket.
fn looks_convex(mesh: &Mesh, flip: f64) -> bool {
    use rayon::prelude::*;
    let margin = 1e-9
        * Aabb::from_points(mesh.vertices())
            .size()
            .into_iter()
            .fold(0.0, f64::max);
    fn sides(f: &crate::mesh::Face) -> impl Iterator<Item = (u32, u32)> + '_ {
        let v = f.vertices();
        (0..v.len()).map(move |e| (v[e], v[(e + 1) % v.len()]))
    }
    let mut start = vec![0usize; mesh.vertices().len() + 1];
    for f in mesh.faces() {
        for (u, v) in sides(f) {
            start[u.min(v) as usize + 1] += 1;
        }
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut next = start.clone();
    let mut bucketed = vec![(0u32, 0u32, 0u32); start[start.len() - 1]];
    for (i, f) in mesh.faces().iter().enumerate() {
        for (u, v) in sides(f) {
            let slot = &mut next[u.min(v) as usize];
            bucketed[*slot] = (u, v, i as u32);
            *slot += 1;
        }
    }
    drop(next);
    let convex_across = |bucket: &[(u32, u32, u32)], &(u, v, f): &(u32, u32, u32)| {
        let plane = mesh.faces()[f as usize].plane();
        let mut across = bucket.iter().filter(|s| (s.0, s.1) == (v, u)).peekable();
        across.peek().is_some()
            && across.all(|&(_, _, g)| {
                mesh.face_points(g as usize)
                    .all(|p| flip * plane.evaluate(&p) <= margin)
            })
    };
    (0..mesh.vertices().len()).into_par_iter().all(|b| {
        let bucket = &bucketed[start[b]..start[b + 1]];
        bucket.iter().all(|s| convex_across(bucket, s))
    })
}

/// The kernel box, if the vertex centroid is strictly inside every face plane.
fn kernel_box(mesh: &Mesh, cbox: &Aabb, outward: Ordering) -> Option<Aabb> {
    let flip = if outward == Ordering::Less { 1.0 } else { -1.0 };
    // Work in coordinates centred on the CBOX and scaled to unit size, for conditioning.
    let centre = nalgebra::center(&cbox.min_point(), &cbox.max_point());
    let scale = cbox.size().into_iter().fold(0.0, f64::max);
    let planes: Vec<(Vector3, f64)> = mesh
        .faces()
        .iter()
        .map(|f| {
            let n = f.plane().normal * flip;
            (n, -(f.plane().d * flip + n.dot(&centre.coords)) / scale)
        })
        .collect();
    let c0 = mesh
        .vertices()
        .iter()
        .fold(Vector3::zeros(), |s, p| s + (p - centre) / scale)
        / mesh.vertices().len() as f64;
    let slack0 = planes
        .iter()
        .map(|(n, d)| d - n.dot(&c0))
        .fold(f64::INFINITY, f64::min);
    if slack0.is_nan() || slack0 <= 1e-9 {
        return None;
    }
    let (c, h) = maximise_box_on_active(&planes, c0, slack0 / 4.0);
    let to_world = |v: Vector3| Point3::from(centre.coords + v * scale);
    let mut b = Aabb::new(to_world(c - h), to_world(c + h));
    // Shrink towards the centre until the exact test accepts (rounding only).
    let mut shrink = 1e-12;
    while !in_kernel(mesh, &b, outward) {
        if shrink > 1e-3 {
            return None;
        }
        b = Aabb::new(
            to_world(c - h * (1.0 - shrink)),
            to_world(c + h * (1.0 - shrink)),
        );
        shrink *= 16.0;
    }
    Some(snap_to_vertices(mesh, b, |b| in_kernel(mesh, b, outward)))
}

/// [`maximise_box`] over a few of the planes at a time (cutting planes): solved over a sample,
/// the box is checked against every plane, the most violated are added, and it is solved
/// again, until no plane is violated. A million-face convex mesh then costs a few passes over
/// its planes instead of a Newton iteration over all of them at every step. The answer is an
/// approximation either way: the box is certified exactly afterwards.
fn maximise_box_on_active(planes: &[(Vector3, f64)], c0: Vector3, h0: f64) -> (Vector3, Vector3) {
    const START: usize = 256;
    const ADDED: usize = 256;
    if planes.len() <= 2 * START {
        return maximise_box(planes, c0, h0);
    }
    let stride = planes.len().div_ceil(START);
    let mut active: Vec<(Vector3, f64)> = planes.iter().step_by(stride).copied().collect();
    for _ in 0..32 {
        let (c, h) = maximise_box(&active, c0, h0);
        let mut violated: Vec<(f64, usize)> = planes
            .iter()
            .enumerate()
            .map(|(i, (n, d))| (n.dot(&c) + n.abs().dot(&h) - d, i))
            .filter(|&(excess, _)| excess > 0.0)
            .collect();
        if violated.is_empty() {
            return (c, h);
        }
        violated.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        active.extend(violated.iter().take(ADDED).map(|&(_, i)| planes[i]));
    }
    maximise_box(planes, c0, h0)
}

/// Maximises `Σ log h` subject to `n·c + |n|·h ≤ d` for every plane, from the strictly
/// feasible start `(c0, h0·(1,1,1))`, by the barrier method with damped Newton steps. Every
/// iterate is strictly feasible.
fn maximise_box(planes: &[(Vector3, f64)], c0: Vector3, h0: f64) -> (Vector3, Vector3) {
    let rows: Vec<(Vector6<f64>, f64)> = planes
        .iter()
        .map(|(n, d)| {
            let a = n.abs();
            (Vector6::new(n.x, n.y, n.z, a.x, a.y, a.z), *d)
        })
        .collect();
    let mut z = Vector6::new(c0.x, c0.y, c0.z, h0, h0, h0);
    let slacks = |z: Vector6<f64>| rows.iter().map(move |(a, d)| d - a.dot(&z));
    let feasible =
        |z: &Vector6<f64>| z[3] > 0.0 && z[4] > 0.0 && z[5] > 0.0 && slacks(*z).all(|s| s > 0.0);
    let barrier = |z: &Vector6<f64>, t: f64| -> f64 {
        -t * (z[3].ln() + z[4].ln() + z[5].ln()) - slacks(*z).map(f64::ln).sum::<f64>()
    };
    let mut t = 1.0;
    let m = rows.len() as f64 + 3.0;
    while m / t > 1e-10 {
        for _ in 0..50 {
            let mut g = Vector6::zeros();
            let mut hess = Matrix6::zeros();
            for k in 3..6 {
                g[k] -= t / z[k];
                hess[(k, k)] += t / (z[k] * z[k]);
            }
            for (a, d) in &rows {
                let s = d - a.dot(&z);
                g += a / s;
                hess += a * a.transpose() / (s * s);
            }
            // Near the optimum the Hessian can become too ill-conditioned to factor; every
            // iterate is strictly feasible, so stopping there still gives a valid box.
            let Some(step) = hess.cholesky().map(|c| -c.solve(&g)) else {
                return split(z);
            };
            let decrement = -g.dot(&step);
            if decrement.is_nan() || decrement <= 1e-11 {
                break;
            }
            let f0 = barrier(&z, t);
            let mut alpha = 1.0;
            loop {
                let cand = z + step * alpha;
                if feasible(&cand) && barrier(&cand, t) <= f0 - 0.25 * alpha * decrement {
                    z = cand;
                    break;
                }
                alpha *= 0.5;
                if alpha < 1e-12 {
                    break;
                }
            }
            if alpha < 1e-12 {
                break;
            }
        }
        t *= 20.0;
    }
    split(z)
}

/// The centre and half-sizes of the box variable `z = (c, h)`.
fn split(z: Vector6<f64>) -> (Vector3, Vector3) {
    (z.fixed_rows::<3>(0).into(), z.fixed_rows::<3>(3).into())
}

/// Whether the open box `b` meets no triangle of the tree (exact).
fn clear(tree: &TriangleTree, b: &Aabb) -> bool {
    tree.in_box(b).all(|(_, t)| !triangle_meets_open_box(&t, b))
}

/// Grows boxes from the deepest interior seeds and returns the largest.
fn grown_box(mesh: &Mesh, cbox: &Aabb) -> Option<Aabb> {
    const GRID: usize = 7;
    const SEEDS: usize = 3;
    let tree = TriangleTree::new(mesh);
    let size = cbox.size();
    let mut seeds: Vec<(f64, Point3)> = Vec::new();
    for i in 0..GRID * GRID * GRID {
        let cell = [i % GRID, (i / GRID) % GRID, i / (GRID * GRID)];
        let p = Point3::from(std::array::from_fn::<f64, 3, _>(|k| {
            cbox.min[k] + size[k] * (cell[k] as f64 + 0.5) / GRID as f64
        }));
        if classify_point(&tree, &p) == Containment::Inside {
            seeds.push((tree.distance(&p), p));
        }
    }
    seeds.sort_by(|a, b| b.0.total_cmp(&a.0));
    seeds
        .iter()
        .take(SEEDS)
        .filter_map(|&(depth, p)| grow_from(&tree, mesh, cbox, p, depth))
        .max_by(|a, b| a.volume().total_cmp(&b.volume()))
}

/// Grows one box from an interior point `p` at distance about `depth` from the surface.
fn grow_from(tree: &TriangleTree, mesh: &Mesh, cbox: &Aabb, p: Point3, depth: f64) -> Option<Aabb> {
    let mut half = depth / 3f64.sqrt();
    let mut b = Aabb::new(p - Vector3::repeat(half), p + Vector3::repeat(half));
    while !clear(tree, &b) {
        half *= 0.5;
        if half <= 0.0 || half < depth * 1e-9 {
            return None;
        }
        b = Aabb::new(p - Vector3::repeat(half), p + Vector3::repeat(half));
    }
    let extent = cbox.size().into_iter().fold(0.0, f64::max);
    let min_step = extent * 1e-10;
    // Side s: axis s % 3, upper side when s >= 3.
    let mut steps = [extent / 8.0; 6];
    while steps.iter().any(|&s| s >= min_step) {
        for (side, step) in steps.iter_mut().enumerate() {
            if *step < min_step {
                continue;
            }
            let (k, up) = (side % 3, side >= 3);
            let mut cand = b;
            if up {
                cand.max[k] = (b.max[k] + *step).min(cbox.max[k]);
            } else {
                cand.min[k] = (b.min[k] - *step).max(cbox.min[k]);
            }
            if cand == b {
                *step = 0.0;
                continue;
            }
            if clear(tree, &cand) {
                b = cand;
                *step *= 2.0;
            } else {
                *step *= 0.5;
            }
        }
    }
    Some(snap_to_vertices(mesh, b, |c| clear(tree, c)))
}

/// Moves each side of `b` outward onto the nearest vertex coordinate within a small relative
/// distance, keeping each move only if `valid` still accepts the box.
fn snap_to_vertices(mesh: &Mesh, mut b: Aabb, valid: impl Fn(&Aabb) -> bool) -> Aabb {
    let extent = b.size().into_iter().fold(0.0, f64::max);
    let reach = extent * 1e-6;
    for side in 0..6 {
        let (k, up) = (side % 3, side >= 3);
        let current = if up { b.max[k] } else { b.min[k] };
        let target = mesh
            .vertices()
            .iter()
            .map(|v| v[k])
            .filter(|&x| if up { x > current } else { x < current })
            .filter(|&x| (x - current).abs() <= reach)
            .min_by(|x, y| (x - current).abs().total_cmp(&(y - current).abs()));
        if let Some(x) = target {
            let mut cand = b;
            if up {
                cand.max[k] = x;
            } else {
                cand.min[k] = x;
            }
            if valid(&cand) {
                b = cand;
            }
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`looks_convex`] by brute force: every side against every side of every face.
    fn looks_convex_brute_force(mesh: &Mesh, flip: f64) -> bool {
        let margin = 1e-9
            * Aabb::from_points(mesh.vertices())
                .size()
                .into_iter()
                .fold(0.0, f64::max);
        let sides = |f: usize| {
            let v = mesh.faces()[f].vertices().to_vec();
            (0..v.len()).map(move |e| (v[e], v[(e + 1) % v.len()]))
        };
        (0..mesh.faces().len()).all(|f| {
            let plane = mesh.faces()[f].plane();
            sides(f).all(|(u, v)| {
                let across: Vec<usize> = (0..mesh.faces().len())
                    .filter(|&g| sides(g).any(|s| s == (v, u)))
                    .collect();
                !across.is_empty()
                    && across.iter().all(|&g| {
                        mesh.face_points(g)
                            .all(|p| flip * plane.evaluate(&p) <= margin)
                    })
            })
        })
    }

    #[test]
    fn looks_convex_agrees_with_brute_force() {
        let two_boxes = |b: [f64; 3]| {
            let a = crate::solids::box_between([0.0; 3], [1.0; 3]).unwrap();
            let c = crate::solids::box_between(b, [b[0] + 1.0, b[1] + 1.0, b[2] + 1.0]);
            Mesh::concatenate([&a, &c.unwrap()]).unwrap()
        };
        let open = Mesh::from_polygons(
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
            ],
            vec![vec![0, 1, 2]],
        )
        .unwrap();
        let meshes = [
            (crate::solids::cube(2.0).unwrap(), Some(true)),
            (crate::solids::uv_sphere(1.0, 12, 7).unwrap(), Some(true)),
            (crate::solids::dodecahedron(1.0).unwrap(), Some(true)),
            (crate::solids::torus(2.0, 0.5, 12, 6).unwrap(), Some(false)),
            // Touching along a face (a merged L), along an edge (four faces on it) and at a
            // corner; and an open triangle (a side with nothing across).
            (two_boxes([1.0, 0.0, 0.0]), None),
            (two_boxes([1.0, 1.0, 0.0]), Some(false)),
            (two_boxes([1.0, 1.0, 1.0]), None),
            (open, Some(false)),
        ];
        for (i, (mesh, convex)) in meshes.iter().enumerate() {
            for flip in [1.0, -1.0] {
                let fast = looks_convex(mesh, flip);
                assert_eq!(
                    fast,
                    looks_convex_brute_force(mesh, flip),
                    "mesh {i}, flip {flip}"
                );
                if flip == 1.0
                    && let Some(c) = convex
                {
                    assert_eq!(fast, *c, "mesh {i}");
                }
            }
        }
    }
}
