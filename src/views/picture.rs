//! The picture map: from world coordinates to the 2-D coordinates of a drawing, exactly
//! rounded.

use super::{Eye, View, ViewError};
use crate::geometry::exact::{accurate_sum, expansion, two_product, two_sum};
use crate::geometry::kernel::{Polynomial, builds_exactly, plain_dot};
use crate::geometry::predicates::Side;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};

/// The map from world points to picture coordinates (`x` right, `y` up), as three affine
/// forms `row·(p - origin)`: for an orthographic view `x = right·p`, `y = up·p` (scene units);
/// for a perspective view `x = (k·right)·(p - eye) / depth`, `y = (k·up)·(p - eye) / depth`
/// with `depth = forward·(p - eye)` and `k = 1/tan(fov/2)`, so the field of view spans `y` in
/// `[-1, 1]`. The rows are the view's doubles, taken as exact; every picture coordinate is
/// rounded once from the exact value of its forms (see [`Picture::point`]).
///
/// A perspective picture has its centre of projection exactly at the eye, so a plane through
/// the eye maps to a line: the crossing of two edges in the picture is the picture of an exact
/// point of 3-D space, the one the eye's predicates find.
///
/// ```
/// use kepler::{geometry::Point3, views::{Picture, View}};
/// let pic = Picture::of(&View::standard());
/// assert_eq!(pic.point(&Point3::new(0.1, 0.2, 9.0)), [0.1, 0.2]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Picture {
    rows: [Vector3; 3],
    origin: Point3,
    perspective: bool,
}

impl Picture {
    /// The picture map of a view.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 10.0), Point3::origin(), Vector3::y(), 90.0).unwrap();
    /// let p = Picture::of(&v).point(&Point3::new(1.0, 2.0, 0.0));
    /// assert!((p[0] - 0.1).abs() < 1e-15 && (p[1] - 0.2).abs() < 1e-15);
    /// ```
    pub fn of(view: &View) -> Picture {
        let (right, up) = view.right_up();
        match (view.eye(), view.fov) {
            (Eye::Point(e), Some(fov)) => {
                let k = 1.0 / (fov.to_radians() / 2.0).tan();
                Picture {
                    rows: [right * k, up * k, view.forward()],
                    origin: *e,
                    perspective: true,
                }
            }
            _ => Picture {
                rows: [right, up, Vector3::zeros()],
                origin: Point3::origin(),
                perspective: false,
            },
        }
    }

    /// The three rows (`x`, `y`, depth; depth is zero for an orthographic view, whose depth
    /// form is the constant 1) and the origin they are applied from: form `k` at `p` is
    /// `rows[k]·(p - origin)` exactly.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let (rows, origin) = Picture::of(&View::standard()).rows();
    /// assert_eq!((rows[0], rows[1], origin), (Vector3::x(), Vector3::y(), Point3::origin()));
    /// ```
    pub fn rows(&self) -> ([Vector3; 3], Point3) {
        (self.rows, self.origin)
    }

    /// Whether the map divides by depth (a perspective view).
    ///
    /// ```
    /// assert!(!kepler::views::Picture::of(&kepler::views::View::standard()).is_perspective());
    /// ```
    pub fn is_perspective(&self) -> bool {
        self.perspective
    }

    /// The exact value of form `k` (0: `x`, 1: `y`, 2: depth, which is 1 for an orthographic
    /// view) at `p`, as an expansion (see [`crate::geometry::exact`]).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, exact::accurate_sum}, views::{Picture, View}};
    /// let pic = Picture::of(&View::standard());
    /// assert_eq!(accurate_sum(&pic.form(1, &Point3::new(3.0, 4.0, 5.0))), 4.0);
    /// assert_eq!(pic.form(2, &Point3::new(3.0, 4.0, 5.0)), vec![1.0]);
    /// ```
    pub fn form(&self, k: usize, p: &Point3) -> Vec<f64> {
        if k == 2 && !self.perspective {
            return vec![1.0];
        }
        let (terms, n) = self.terms(k, p);
        expansion(&terms[..n])
    }

    /// The exact terms of form `k` at `p` (products of the row with `p - origin`): the first
    /// `n` of the returned array.
    #[inline]
    fn terms(&self, k: usize, p: &Point3) -> ([f64; 12], usize) {
        let row = &self.rows[k];
        let (mut out, mut n) = ([0.0; 12], 0);
        for i in 0..3 {
            let (d, e) = two_sum(p[i], -self.origin[i]);
            for x in [d, e] {
                let (h, l) = two_product(row[i], x);
                for v in [h, l] {
                    if v != 0.0 {
                        out[n] = v;
                        n += 1;
                    }
                }
            }
        }
        (out, n)
    }

    /// Form `k` at `p`, rounded once.
    #[inline]
    fn rounded(&self, k: usize, p: &Point3) -> f64 {
        if !builds_exactly() {
            let row = &self.rows[k];
            return plain_dot(
                &[row.x, row.y, row.z],
                &[p.x, p.y, p.z],
                &[self.origin.x, self.origin.y, self.origin.z],
            );
        }
        let (terms, n) = self.terms(k, p);
        accurate_sum(&terms[..n])
    }

    /// The picture coordinates of `p`: each coordinate of an orthographic view is the exact
    /// value rounded once (within half a unit in the last place); of a perspective view, the
    /// rounded numerator over the rounded depth (within 1.5 units). `p` must lie in front of a
    /// perspective eye.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let v = View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap();
    /// let [x, y] = Picture::of(&v).point(&Point3::new(1.0, 1.0, 1.0));
    /// assert!(x.abs() < 1e-15 && y.abs() < 1e-15);
    /// ```
    pub fn point(&self, p: &Point3) -> [f64; 2] {
        let (x, y) = (self.rounded(0, p), self.rounded(1, p));
        if self.perspective {
            let depth = self.rounded(2, p);
            [x / depth, y / depth]
        } else {
            [x, y]
        }
    }

    /// How far from `picture`, the picture of `p` ([`Picture::point`]), the picture of any point
    /// within `radius` of `p` may lie (infinite when such a point may be at or behind a
    /// perspective eye): `radius` times the rows' lengths for an orthographic view; for a
    /// perspective one, with `L` a picture form and `D` the depth, the picture moves by at most
    /// `(|rows[k]| + |picture|·|rows[2]|)·radius / (D(p) − |rows[2]|·radius)`. For finding
    /// what lies near a point known only approximately, never for a decision.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let pic = Picture::of(&View::standard());
    /// let p = Point3::new(3.0, 4.0, 5.0);
    /// assert_eq!(pic.reach(&p, pic.point(&p), 0.0), 0.0);
    /// assert!(pic.reach(&p, pic.point(&p), 0.5) >= 0.5);
    /// ```
    pub fn reach(&self, p: &Point3, picture: [f64; 2], radius: f64) -> f64 {
        if radius == 0.0 {
            return 0.0;
        }
        let norm = |k: usize| self.rows[k].norm();
        let across = norm(0).max(norm(1));
        let reach = if self.perspective {
            let depth = self.rounded(2, p) - norm(2) * radius;
            if depth.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return f64::INFINITY;
            }
            let spread = picture[0].abs().max(picture[1].abs());
            radius * (across + spread * norm(2)) / depth
        } else {
            radius * across
        };
        // The bound's own roundings, generously.
        let reach = reach * (1.0 + 1.0 / (1u64 << 20) as f64);
        if reach.is_nan() { f64::INFINITY } else { reach }
    }

    /// The point of the plane `normal·x + d = 0` whose picture is `p`, in floating point (for
    /// texture coordinates, not for decisions), or `None` when the plane contains the lines of
    /// sight (seen edge-on) or the point is not in front of a perspective eye.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let pic = Picture::of(&View::standard());
    /// let q = pic.unproject([0.5, 0.25], &Vector3::z(), -2.0).unwrap();
    /// assert_eq!(q, Point3::new(0.5, 0.25, 2.0));
    /// assert!(pic.unproject([0.5, 0.25], &Vector3::x(), 0.0).is_none());
    /// ```
    pub fn unproject(&self, p: [f64; 2], normal: &Vector3, d: f64) -> Option<Point3> {
        let [r, u, w] = &self.rows;
        if self.perspective {
            // x - eye = λ·D with rows·D = (p.x, p.y, 1).
            let m = nalgebra::Matrix3::from_rows(&[r.transpose(), u.transpose(), w.transpose()]);
            let dir = m.lu().solve(&Vector3::new(p[0], p[1], 1.0))?;
            let denominator = normal.dot(&dir);
            let lambda = -(normal.dot(&self.origin.coords) + d) / denominator;
            (lambda.is_finite() && lambda > 0.0).then(|| self.origin + dir * lambda)
        } else {
            let m =
                nalgebra::Matrix3::from_rows(&[r.transpose(), u.transpose(), normal.transpose()]);
            let x = m.lu().solve(&Vector3::new(p[0], p[1], -d))?;
            x.iter().all(|c| c.is_finite()).then(|| Point3::from(x))
        }
    }

    /// Every mesh object of the scene, depth-first, with its mesh; for a perspective view, an
    /// error naming the first object with a vertex not strictly in front of the eye (its
    /// picture would be meaningless).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, scene::Scene, views::{Picture, View}};
    /// let mut scene = Scene::new();
    /// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!(Picture::of(&View::standard()).mesh_objects_in_front(&scene).unwrap().len(), 1);
    /// let inside = View::perspective(Point3::origin(), Point3::new(1.0, 0.0, 0.0), Vector3::z(), 40.0).unwrap();
    /// let e = Picture::of(&inside).mesh_objects_in_front(&scene).unwrap_err();
    /// assert!(e.to_string().starts_with("object 'cube': vertex"));
    /// ```
    pub fn mesh_objects_in_front<'s>(
        &self,
        scene: &'s Scene,
    ) -> Result<Vec<(ObjectId, &'s Mesh)>, ViewError> {
        let meshes = scene.mesh_objects(scene.roots());
        for &(id, mesh) in &meshes {
            if let Some(i) = mesh.vertices().iter().position(|p| !self.in_front(p)) {
                return Err(ViewError::NotInFront {
                    object: scene.path(id),
                    vertex: i,
                    point: mesh.vertices()[i],
                });
            }
        }
        Ok(meshes)
    }

    /// Whether `p` lies strictly in front of a perspective eye (always true for an
    /// orthographic view), decided exactly.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Picture, View}};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 10.0), Point3::origin(), Vector3::y(), 60.0).unwrap();
    /// let pic = Picture::of(&v);
    /// assert!(pic.in_front(&Point3::new(5.0, 5.0, 9.0)));
    /// assert!(!pic.in_front(&Point3::new(5.0, 5.0, 10.0)));
    /// ```
    pub fn in_front(&self, p: &Point3) -> bool {
        if !self.perspective {
            return true;
        }
        // The depth's floating-point estimate decides when its error bound allows (exactly
        // as the expansion would), else the exact expansion.
        let depth = Side {
            origin: self.origin,
            normal: self.rows[2],
            offset: 0.0,
            x: *p,
        }
        .estimate();
        if depth.value.is_finite() && depth.value.abs() > depth.bound {
            return depth.value > 0.0;
        }
        self.form(2, p).last().is_some_and(|&top| top > 0.0)
    }
}
