//! The face F being tested: its vertices, plane, picture and framing, what cannot or may hide
//! it, and how a face's vertex loop and spanning triangle are read the same whichever way
//! round it is given.

use super::face_grid::{GRID_MARGIN, window};
use crate::geometry::polygon::bounding_box;
use crate::geometry::predicates::{orient2d, orient3d, project};
use crate::geometry::{Aabb, Point3};
use crate::mesh::Mesh;
use crate::sight::frustum::Clip;
use crate::views::{Eye, Picture, View};
use geo::{Coord, LineString, MultiPolygon, Polygon};
use std::cmp::Ordering;

/// The face being tested: its vertices, plane and picture.
pub(super) struct Target {
    pub(super) vertices: Vec<Point3>,
    /// Its vertex loop from a canonical start and way round (see [`canonical_loop`]).
    pub(super) canonical: Vec<Point3>,
    /// The face's triangles.
    pub(super) triangles: Vec<[Point3; 3]>,
    /// The face's first triangle (its plane).
    pub(super) plane: [Point3; 3],
    pub(super) eye: Eye,
    pub(super) picture: Picture,
    /// The side of the face's plane the eye is on.
    pub(super) eye_side: Ordering,
    /// A box holding the picture of its part inside the frustum: the bounding box of its
    /// picture, or the picture's window for a face not wholly in front of the eye.
    pub(super) extent: [[f64; 2]; 2],
    /// Where it lies against the frustum of a view that clips.
    pub(super) framing: Framing,
    /// The exact signs of the components of the normal `(q − p) × (r − p)` of its plane's
    /// triangle `[p, q, r]`.
    normal: [Ordering; 3],
}

/// Where a face lies against the frustum of a view that clips (decided exactly at its
/// vertices).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Framing {
    /// Every vertex strictly inside (and any face, when the view does not clip).
    Inside,
    /// Every vertex weakly outside one of its planes: no area inside.
    Outside,
    /// Neither: its visible polygons are cut by the planes.
    Across,
}

impl Target {
    pub(super) fn new(mesh: &Mesh, face: usize, view: &View, clip: Option<&Clip>) -> Target {
        let vertices: Vec<Point3> = mesh.face_points(face).collect();
        let triangles: Vec<[Point3; 3]> = mesh.faces()[face]
            .triangle_range()
            .map(|t| mesh.triangle(t))
            .collect();
        let plane = triangles[0];
        let eye = *view.eye();
        let picture = Picture::of(view);
        let framing = match clip {
            None => Framing::Inside,
            Some(c)
                if c.planes().all(|(form, inside)| {
                    vertices.iter().all(|v| form.sign_at(&eye, v) == inside)
                }) =>
            {
                Framing::Inside
            }
            Some(c)
                if c.planes().any(|(form, inside)| {
                    vertices.iter().all(|v| form.sign_at(&eye, v) != inside)
                }) =>
            {
                Framing::Outside
            }
            Some(_) => Framing::Across,
        };
        // No picture of a point not in front of the eye is ever built.
        let extent = match (clip, window(view)) {
            (Some(c), Some(w)) if !vertices.iter().all(|x| c.in_front(x)) => w,
            _ => bounding_box(vertices.iter().map(|v| picture.point(v))),
        };
        let normal = [0, 1, 2].map(|k| {
            orient2d(
                project(&plane[0], k),
                project(&plane[1], k),
                project(&plane[2], k),
            )
        });
        Target {
            normal,
            eye_side: eye.orient3d(&plane[0], &plane[1], &plane[2]),
            canonical: canonical_loop(mesh, face),
            vertices,
            triangles,
            plane,
            eye,
            picture,
            extent,
            framing,
        }
    }

    /// The whole face in the picture.
    pub(super) fn polygon(&self) -> MultiPolygon<f64> {
        ring(
            self.vertices
                .iter()
                .map(|v| self.picture.point(v))
                .collect(),
        )
    }

    /// Whether nothing in the closed box can hide the face: no point of it lies strictly on the
    /// eye's side of the face's plane (decided exactly at its corners), or its picture misses
    /// the face's. `pictured` is the box's [`cbox_picture`] when the caller holds it (computed
    /// here otherwise).
    pub(super) fn cannot_be_hidden_by(
        &self,
        b: &Aabb,
        pictured: Option<Option<[[f64; 2]; 2]>>,
    ) -> bool {
        if !self.has_corner_on_eye_side(b) {
            return true;
        }
        // The picture of the box holds the pictures of all it holds when every corner is in
        // front of the eye; the two pictures must miss by more than a margin far above
        // rounding.
        let Some([low, high]) = pictured.unwrap_or_else(|| cbox_picture(&self.picture, b)) else {
            return false;
        };
        let [f_low, f_high] = self.extent;
        let scale = low.iter().chain(&high).chain(&f_low).chain(&f_high);
        let margin = GRID_MARGIN * scale.fold(0.0f64, |m, v| m.max(v.abs()));
        (0..2).any(|k| low[k] > f_high[k] + margin || high[k] < f_low[k] - margin)
    }

    /// Whether some corner of the box lies strictly on the eye's side of the face's plane.
    /// `orient3d(p, q, r, x)` has the sign of `−n·(x − p)` for the normal `n` of
    /// `[p, q, r]`, so it is greatest, times the eye's side `s`, at the corner taking the low
    /// end of each axis where `s·n_k > 0` and the high end where `s·n_k < 0` (either where
    /// `n_k = 0`: the form does not depend on that coordinate). One exact `orient3d` there
    /// decides for all eight corners.
    pub(super) fn has_corner_on_eye_side(&self, b: &Aabb) -> bool {
        let [p, q, r] = &self.plane;
        let s = self.eye_side;
        if s == Ordering::Equal {
            return b.corners().iter().any(|c| orient3d(p, q, r, c) == s);
        }
        let corner = Point3::from([0, 1, 2].map(|k| {
            if self.normal[k] == s {
                b.min[k]
            } else {
                b.max[k]
            }
        }));
        orient3d(p, q, r, &corner) == s
    }

    /// Whether the polygon `corners` (a face of an occluder, with a triangle `g` spanning its
    /// plane) may hide points of this face: some part of it lies strictly on the eye's side of
    /// this face's plane, it is not seen edge-on, and some vertex of this face lies strictly
    /// behind its plane. Exact.
    pub(super) fn may_be_hidden_by(&self, corners: &[Point3], g: &[Point3; 3]) -> bool {
        let [p, q, r] = &self.plane;
        if !corners
            .iter()
            .any(|c| orient3d(p, q, r, c) == self.eye_side)
        {
            return false;
        }
        let g_side = self.eye.orient3d(&g[0], &g[1], &g[2]);
        g_side != Ordering::Equal
            && self
                .vertices
                .iter()
                .any(|v| orient3d(&g[0], &g[1], &g[2], v) == g_side.reverse())
    }
}

/// The box of the pictures of the corners of `b`, or `None` when a corner is not in front of
/// the eye (the picture of the box is then unbounded).
pub(super) fn cbox_picture(picture: &Picture, b: &Aabb) -> Option<[[f64; 2]; 2]> {
    let corners = b.corners();
    corners
        .iter()
        .all(|c| picture.in_front(c))
        .then(|| bounding_box(corners.iter().map(|c| picture.point(c))))
}

/// The vertex loop of face `face` from its vertex of least index, towards the neighbour of
/// lesser index: the same whichever vertex the face starts at and whichever way round it is
/// given (as mirroring reverses it), so VTP(F) is built in the same order, and each of its
/// points from the same planes.
pub(super) fn canonical_loop(mesh: &Mesh, face: usize) -> Vec<Point3> {
    let indices = mesh.faces()[face].vertices();
    let n = indices.len();
    let start = (0..n).min_by_key(|&i| indices[i]).unwrap_or(0);
    let step = if indices[(start + 1) % n] <= indices[(start + n - 1) % n] {
        1
    } else {
        n - 1
    };
    (0..n)
        .map(|k| mesh.vertices()[indices[(start + k * step) % n] as usize])
        .collect()
}

/// A triangle of vertices of face `face` spanning its plane, the same whatever the face's first
/// vertex and way round, the scene's placement or scale: the first two vertices by index and
/// the next by index not on their line, turned like the face's first triangle as seen from
/// `eye`; and whether the face is exactly planar. Points of the face's plane are built from the
/// gradient of this triangle's form, so this choice keeps them the same bits when the face is
/// reversed (as mirroring does). The face's first triangle when the face is not exactly planar
/// or is seen edge-on.
pub(super) fn spanning_triangle(mesh: &Mesh, face: usize, eye: &Eye) -> ([Point3; 3], bool) {
    let first = mesh.triangle(mesh.faces()[face].triangle_range().start);
    let turn = eye.orient3d(&first[0], &first[1], &first[2]);
    let planar = mesh.face_points(face).all(|c| {
        first.contains(&c) || orient3d(&first[0], &first[1], &first[2], &c) == Ordering::Equal
    });
    if turn == Ordering::Equal || !planar {
        return (first, planar);
    }
    let mut indices = mesh.faces()[face].vertices().to_vec();
    indices.sort_unstable();
    indices.dedup();
    let point = |i: u32| mesh.vertices()[i as usize];
    let [a, b] = [0, 1].map(|k| point(indices[k]));
    let span = indices[2..]
        .iter()
        .find_map(|&k| {
            let c = point(k);
            match eye.orient3d(&a, &b, &c) {
                Ordering::Equal => None,
                t if t == turn => Some([a, b, c]),
                _ => Some([a, c, b]),
            }
        })
        .unwrap_or(first);
    (span, true)
}

/// A closed ring of points as a multipolygon.
pub(super) fn ring(points: Vec<[f64; 2]>) -> MultiPolygon<f64> {
    let coords: Vec<Coord<f64>> = points.into_iter().map(|[x, y]| Coord { x, y }).collect();
    MultiPolygon::new(vec![Polygon::new(LineString::new(coords), Vec::new())])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vector3;
    use crate::random::SplitMix64;

    /// The one corner tested stands for all eight: random faces (general and perpendicular to
    /// an axis, either way round), boxes crossing, touching and missing their planes, flat
    /// boxes, and both kinds of eye.
    #[test]
    fn one_corner_decides_for_the_box() {
        let mut rng = SplitMix64(5);
        let mut answers = [0usize; 2];
        for round in 0..3_000 {
            let point =
                |rng: &mut SplitMix64| Point3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4));
            let mut t = [point(&mut rng), point(&mut rng), point(&mut rng)];
            if round % 3 == 0 {
                let (k, v) = (rng.below(3), rng.int(-2, 2));
                t.iter_mut().for_each(|p| p[k] = v);
            }
            let Ok(mesh) = Mesh::from_polygons(t.to_vec(), vec![vec![0, 1, 2]]) else {
                continue;
            };
            if mesh.faces().is_empty() {
                continue;
            }
            let view = if round % 2 == 0 {
                View::orthographic(rng.vector(1.0) + Vector3::new(0.0, 0.0, 0.1), Vector3::z())
            } else {
                View::perspective(
                    Point3::new(rng.int(-9, 9), rng.int(-9, 9), rng.int(5, 9)),
                    Point3::origin(),
                    Vector3::z(),
                    40.0,
                )
            };
            let Ok(view) = view else { continue };
            let target = Target::new(&mesh, 0, &view, None);
            let [low, high] = [point(&mut rng), point(&mut rng)];
            let mut b = Aabb {
                min: [0, 1, 2].map(|k| low[k].min(high[k])),
                max: [0, 1, 2].map(|k| low[k].max(high[k])),
            };
            if round % 5 == 0 {
                b.max[round % 3] = b.min[round % 3];
            }
            let [p, q, r] = &target.plane;
            let brute = b
                .corners()
                .iter()
                .any(|c| orient3d(p, q, r, c) == target.eye_side);
            assert_eq!(target.has_corner_on_eye_side(&b), brute, "{round}");
            answers[usize::from(brute)] += 1;
        }
        assert!(answers.iter().all(|&n| n > 300), "{answers:?}");
    }
}
