//! A face: a planar polygon with its plane equation and Franklin's texture coordinate system.

use crate::geometry::{Point3, Vector3};
use nalgebra::{Matrix3, Matrix4};

/// The plane `a·x + b·y + c·z + d = 0` of a face (Franklin's face equation), with
/// `(a, b, c)` the unit outward normal.
///
/// The plane is a fast, rounded description used for texture coordinates and cheap filters;
/// exact decisions use the face's vertices with the exact predicates instead.
///
/// ```
/// use kepler::mesh::Plane;
/// use kepler::geometry::{Point3, Vector3};
/// let p = Plane::new(Vector3::new(0.0, 0.0, 1.0), -2.0);
/// assert_eq!(p.evaluate(&Point3::new(5.0, 5.0, 3.0)), 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Unit outward normal `(a, b, c)`.
    pub normal: Vector3,
    /// The constant `d`.
    pub d: f64,
}

impl Plane {
    /// A plane from its unit normal and constant.
    ///
    /// ```
    /// use kepler::{mesh::Plane, geometry::Vector3};
    /// assert_eq!(Plane::new(Vector3::x(), 1.0).d, 1.0);
    /// ```
    pub fn new(normal: Vector3, d: f64) -> Plane {
        Plane { normal, d }
    }

    /// `a·x + b·y + c·z + d`: the signed distance of `p` from the plane, positive outside.
    ///
    /// ```
    /// use kepler::{mesh::Plane, geometry::{Point3, Vector3}};
    /// assert_eq!(Plane::new(Vector3::x(), -1.0).evaluate(&Point3::new(3.0, 0.0, 0.0)), 2.0);
    /// ```
    pub fn evaluate(&self, p: &Point3) -> f64 {
        self.normal.dot(&p.coords) + self.d
    }
}

/// Franklin's texture coordinate system of a face (1981, "Definitions and data structure").
///
/// - Origin: the point of the face plane closest to the 3-D origin.
/// - Unit x-vector: in the plane, with no z component; `(1, 0, 0)` for a horizontal face.
/// - Unit y-vector: in the plane, with a positive z component; `(0, 1, 0)` for a horizontal
///   face.
///
/// For a non-horizontal face the x-vector is `ẑ × n` normalised, so `x × y = n` and a face
/// whose vertices turn counter-clockwise around its outward normal also turns
/// counter-clockwise in texture coordinates. A horizontal face (all vertices with exactly the
/// same z) uses the paper's fixed axes, so a downward-facing horizontal face turns clockwise
/// in texture coordinates (the paper's parity). The third texture coordinate `w` is the
/// distance along `x × y`, zero on the plane.
///
/// ```
/// use kepler::{mesh::TextureFrame, geometry::{Point3, Vector3}};
/// // The wall y = 2 facing -y: x-vector (1, 0, 0), y-vector (0, 0, 1), origin (0, 2, 0).
/// let f = TextureFrame::new(&Vector3::new(0.0, -1.0, 0.0), 2.0, false);
/// let t = f.to_texture(&Point3::new(3.0, 2.0, 5.0));
/// assert!((t.x - 3.0).abs() < 1e-15 && (t.y - 5.0).abs() < 1e-15 && t.z.abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureFrame {
    origin: Point3,
    x: Vector3,
    y: Vector3,
    w: Vector3,
}

impl TextureFrame {
    /// The frame of the plane `normal·x + d = 0` (`normal` a unit vector); `horizontal` when
    /// the face's vertices all have exactly the same z.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::Vector3};
    /// let f = TextureFrame::new(&Vector3::z(), -1.0, true);
    /// assert_eq!(f.x_axis(), Vector3::x());
    /// assert_eq!(f.origin().z, 1.0);
    /// ```
    pub fn new(normal: &Vector3, d: f64, horizontal: bool) -> TextureFrame {
        let (x, y) = if horizontal || (normal.x == 0.0 && normal.y == 0.0) {
            (Vector3::x(), Vector3::y())
        } else {
            let x = Vector3::new(-normal.y, normal.x, 0.0).normalize();
            (x, normal.cross(&x))
        };
        TextureFrame {
            origin: Point3::from(normal * -d),
            x,
            y,
            w: x.cross(&y),
        }
    }

    /// The origin: the point of the face plane closest to the 3-D origin.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::Vector3};
    /// assert_eq!(TextureFrame::new(&Vector3::x(), -4.0, false).origin().x, 4.0);
    /// ```
    pub fn origin(&self) -> Point3 {
        self.origin
    }

    /// The unit x-vector of the texture system, in global coordinates.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::Vector3};
    /// assert_eq!(TextureFrame::new(&Vector3::z(), 0.0, true).x_axis(), Vector3::x());
    /// ```
    pub fn x_axis(&self) -> Vector3 {
        self.x
    }

    /// The unit y-vector of the texture system, in global coordinates.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::Vector3};
    /// let f = TextureFrame::new(&Vector3::new(1.0, 0.0, 0.0), 0.0, false);
    /// assert_eq!(f.y_axis(), Vector3::z());
    /// ```
    pub fn y_axis(&self) -> Vector3 {
        self.y
    }

    /// Global → texture coordinates `(x, y, w)`; `w` is zero on the face plane.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::{Point3, Vector3}};
    /// let f = TextureFrame::new(&Vector3::z(), -1.0, true);
    /// assert_eq!(f.to_texture(&Point3::new(2.0, 3.0, 1.0)), Point3::new(2.0, 3.0, 0.0));
    /// ```
    pub fn to_texture(&self, p: &Point3) -> Point3 {
        let v = p - self.origin;
        Point3::new(v.dot(&self.x), v.dot(&self.y), v.dot(&self.w))
    }

    /// Texture `(x, y, w)` → global coordinates.
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::{Point3, Vector3}};
    /// let f = TextureFrame::new(&Vector3::z(), -1.0, true);
    /// assert_eq!(f.to_global(&Point3::new(2.0, 3.0, 0.0)), Point3::new(2.0, 3.0, 1.0));
    /// ```
    pub fn to_global(&self, t: &Point3) -> Point3 {
        self.origin + self.x * t.x + self.y * t.y + self.w * t.z
    }

    /// The texture → global transform as an affine 4×4 matrix (columns x, y, w, origin).
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::{Point3, Vector3}};
    /// let f = TextureFrame::new(&Vector3::z(), -2.0, true);
    /// let m = f.texture_to_global();
    /// assert_eq!(m.transform_point(&Point3::new(1.0, 0.0, 0.0)), Point3::new(1.0, 0.0, 2.0));
    /// ```
    pub fn texture_to_global(&self) -> Matrix4<f64> {
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::from_columns(&[self.x, self.y, self.w]));
        m.fixed_view_mut::<3, 1>(0, 3)
            .copy_from(&self.origin.coords);
        m
    }

    /// The global → texture transform as an affine 4×4 matrix (the inverse of
    /// [`texture_to_global`](TextureFrame::texture_to_global): the axes are orthonormal).
    ///
    /// ```
    /// use kepler::{mesh::TextureFrame, geometry::{Point3, Vector3}};
    /// let f = TextureFrame::new(&Vector3::z(), -2.0, true);
    /// let m = f.global_to_texture();
    /// assert_eq!(m.transform_point(&Point3::new(1.0, 0.0, 2.0)), Point3::new(1.0, 0.0, 0.0));
    /// ```
    pub fn global_to_texture(&self) -> Matrix4<f64> {
        let r = Matrix3::from_rows(&[self.x.transpose(), self.y.transpose(), self.w.transpose()]);
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
        m.fixed_view_mut::<3, 1>(0, 3)
            .copy_from(&(-(r * self.origin.coords)));
        m
    }
}

/// A face of a [`Mesh`](super::Mesh): the indices of its vertices in order (counter-clockwise
/// seen from outside), its plane and its texture coordinate system.
///
/// ```
/// use kepler::solids;
/// let cube = solids::cube(1.0).unwrap();
/// let top = cube.faces().iter().find(|f| f.plane().normal.z > 0.5).unwrap();
/// assert_eq!(top.vertices().len(), 4);
/// assert_eq!(top.texture().x_axis(), kepler::geometry::Vector3::x());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    pub(crate) vertices: Loop,
    pub(crate) plane: Plane,
    pub(crate) area: f64,
    pub(crate) triangles: std::ops::Range<usize>,
    /// The sides that are diagonals of a split polygon, not edges of the input polygon (bit
    /// `i`: the side from vertex `i`).
    pub(crate) diagonals: u8,
    /// Whether the face's vertices all have exactly the same z (its texture frame then has
    /// the paper's fixed axes): the frame is computed from this and the plane when asked for,
    /// rather than stored (96 bytes a face).
    pub(crate) horizontal: bool,
    /// The input polygon the face is (part of).
    pub(crate) polygon: u32,
}

/// A face's vertex loop: inline for triangles and quads, so that most faces need no
/// allocation of their own.
pub(crate) type Loop = smallvec::SmallVec<[u32; 4]>;

impl Face {
    /// Indices of the face's vertices in the mesh, in order.
    ///
    /// ```
    /// let t = kepler::solids::tetrahedron(1.0).unwrap();
    /// assert_eq!(t.faces()[0].vertices().len(), 3);
    /// ```
    pub fn vertices(&self) -> &[u32] {
        &self.vertices
    }

    /// The face's plane equation.
    ///
    /// ```
    /// let c = kepler::solids::cube(2.0).unwrap();
    /// assert!(c.faces().iter().all(|f| (f.plane().d + 1.0).abs() < 1e-15));
    /// ```
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The face's texture coordinate system.
    ///
    /// ```
    /// let c = kepler::solids::cube(2.0).unwrap();
    /// assert!(c.faces().iter().all(|f| f.texture().y_axis().z >= 0.0));
    /// ```
    pub fn texture(&self) -> TextureFrame {
        TextureFrame::new(&self.plane.normal, self.plane.d, self.horizontal)
    }

    /// The face's area.
    ///
    /// ```
    /// let c = kepler::solids::cube(2.0).unwrap();
    /// assert!(c.faces().iter().all(|f| f.area() == 4.0));
    /// ```
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The range of this face's triangles in [`Mesh::triangles`](super::Mesh::triangles).
    ///
    /// ```
    /// let c = kepler::solids::cube(2.0).unwrap();
    /// assert_eq!(c.faces()[0].triangle_range().len(), 2);
    /// ```
    pub fn triangle_range(&self) -> std::ops::Range<usize> {
        self.triangles.clone()
    }

    /// Whether side `side` of the face (from vertex `side` to the next) is an edge of the
    /// input polygon: false for the diagonals along which a polygon that is not exactly planar
    /// was split into triangle faces ([`Mesh::split_polygons`](super::Mesh::split_polygons)).
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let quad = vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 1e-9), p(0., 1., 0.)];
    /// let m = Mesh::from_polygons(quad, vec![vec![0, 1, 2, 3]]).unwrap();
    /// // Split along the diagonal from vertex 0 to vertex 2.
    /// let f = &m.faces()[0];
    /// assert_eq!(f.vertices(), &[0, 1, 2]);
    /// assert_eq!((0..3).map(|s| f.is_polygon_edge(s)).collect::<Vec<_>>(), [true, true, false]);
    /// ```
    pub fn is_polygon_edge(&self, side: usize) -> bool {
        side >= 8 || self.diagonals >> side & 1 == 0
    }

    /// The index of the input polygon this face is, or is part of (a polygon that is not
    /// exactly planar becomes several triangle faces): its position among the faces given to
    /// [`Mesh::from_polygons`](super::Mesh::from_polygons), kept by
    /// [`Mesh::transformed`](super::Mesh::transformed).
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let v = vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 1e-9), p(0., 1., 0.), p(2., 0., 0.)];
    /// // The first face has zero area and is dropped; the quad is split in two.
    /// let m = Mesh::from_polygons(v, vec![vec![0, 1, 4], vec![0, 1, 2, 3]]).unwrap();
    /// assert_eq!(m.faces().iter().map(|f| f.polygon()).collect::<Vec<_>>(), [1, 1]);
    /// ```
    pub fn polygon(&self) -> usize {
        self.polygon as usize
    }
}
