//! The polytope: [`Tribox`], the boundary of a tribox (at most 32 vertices, one face per
//! bounding plane), evaluated from its bounds by the paper's corner classification, with its
//! vertices, faces, volume and area.

use super::cases::{A, AB, AC, B, BC, C, CORNER_PLANES};
use super::corners::{clamped_chamfers, generic_vertices, masked_corner, reflected};
use super::directions;
use super::faces::{
    CHAMFER_LOOPS, FACE_CORNER_INDICES, GENERIC, MAX_FACE, MAX_VERTICES, PRINCIPAL_LOOPS,
    VERTEX_PLANES,
};
use super::slabs::TriboxBounds;
use crate::geometry::{Point3, Vector3};

/// The boundary of a tribox: at most 32 vertices and one face per bounding plane.
///
/// Face `j` lies on plane `j` (see [`TriboxBounds::to_array18`]); its loop is counter-clockwise
/// seen from outside. As the paper's algorithm produces it ([`TriboxBounds::boundary`]), every
/// corner contributes four vertices and every face its corners' sub-lists, so singular inputs
/// leave repeated vertices and degenerate faces; [`cleaned`](Self::cleaned) is the exact
/// intersection with exactly equal vertices merged, zero-length edges and faces left with
/// fewer than 3 vertices dropped.
///
/// Each vertex remembers three planes with independent normals through it.
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let cube: Vec<Point3> = (0..8)
///     .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
///     .collect();
/// let raw = TriboxBounds::from_points(&cube).boundary();
/// assert_eq!(raw.vertices().len(), 32);
/// let clean = raw.cleaned();
/// assert_eq!((clean.vertices().len(), clean.face_count()), (8, 6));
/// assert_eq!(clean.volume(), 1.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Tribox {
    pub(super) bounds: TriboxBounds,
    /// Four vertices per corner (a cleaned boundary keeps its vertices first, in order).
    pub(super) vertices: [[Point3; 4]; 8],
    pub(super) vertex_planes: [[[u8; 3]; 4]; 8],
    pub(super) vertex_count: u8,
    pub(super) faces: [[u8; MAX_FACE]; 18],
    pub(super) face_len: [u8; 18],
    pub(super) cases: [u8; 8],
}

impl Tribox {
    /// The outward normals of the 18 planes (unnormalised, in the order of
    /// [`TriboxBounds::to_array18`]).
    ///
    /// ```
    /// use kepler::bounds::tribox::Tribox;
    /// assert_eq!(Tribox::PLANE_NORMALS[0], [-1.0, 0.0, 0.0]); // min x
    /// assert_eq!(Tribox::PLANE_NORMALS[15], [-1.0, 1.0, 0.0]); // max (y - x)
    /// ```
    pub const PLANE_NORMALS: [[f64; 3]; 18] = directions::PLANE_NORMALS;

    /// Evaluates the boundary of the tribox of `bounds` by the paper's corner classification.
    /// Empty bounds give an empty boundary.
    ///
    /// ```
    /// use kepler::bounds::tribox::{Tribox, TriboxBounds};
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// assert_eq!(Tribox::new(&b), b.boundary());
    /// assert!(Tribox::new(&TriboxBounds::empty()).is_empty());
    /// ```
    #[inline(never)]
    pub fn new(bounds: &TriboxBounds) -> Tribox {
        if bounds.is_empty() {
            return Tribox::blank(bounds);
        }
        let beta = bounds.offsets();
        let clamped = clamped_chamfers(&beta);
        if !clamped.contains(&true)
            && let Some(vertices) = generic_vertices(&beta)
        {
            return Tribox::generic(bounds, vertices);
        }
        Tribox::from_corners(bounds, |c| {
            let planes = CORNER_PLANES[c];
            let b = |k: usize| beta[usize::from(planes[k])];
            let al = [b(A), b(B), b(C), b(AB), b(AC), b(BC)];
            let mask = usize::from(clamped[usize::from(planes[AB])])
                | usize::from(clamped[usize::from(planes[AC])]) << 1
                | usize::from(clamped[usize::from(planes[BC])]) << 2;
            let (case, v) = match mask {
                0 => masked_corner::<0>(al),
                1 => masked_corner::<1>(al),
                2 => masked_corner::<2>(al),
                3 => masked_corner::<3>(al),
                4 => masked_corner::<4>(al),
                5 => masked_corner::<5>(al),
                6 => masked_corner::<6>(al),
                _ => masked_corner::<7>(al),
            };
            (case, reflected(c, &v))
        })
    }

    /// A boundary with no vertex and no face.
    #[inline(always)]
    pub(super) fn blank(bounds: &TriboxBounds) -> Tribox {
        Tribox {
            bounds: *bounds,
            vertices: [[const { Point3::new(0.0, 0.0, 0.0) }; 4]; 8],
            vertex_planes: [[[0; 3]; 4]; 8],
            vertex_count: 0,
            faces: [[0; MAX_FACE]; 18],
            face_len: [0; 18],
            cases: [0; 8],
        }
    }

    /// The generic boundary (every corner in case 1) with the given vertices: its planes and
    /// face loops are the compile-time [`GENERIC`] table's.
    fn generic(bounds: &TriboxBounds, vertices: [[Point3; 4]; 8]) -> Tribox {
        Tribox {
            bounds: *bounds,
            vertices,
            vertex_planes: GENERIC.vertex_planes,
            vertex_count: MAX_VERTICES as u8,
            faces: GENERIC.faces,
            face_len: GENERIC.face_len,
            cases: [1; 8],
        }
    }

    /// The boundary from each corner's case and four vertices in world coordinates (`corner`
    /// returns them, by [`reflected`]), and each face's loop, its corners' sub-lists
    /// concatenated counter-clockwise around it (tabulated for every combination of cases).
    /// Every field is computed before the boundary is built, so that nothing is written twice.
    #[inline(always)]
    pub(super) fn from_corners(
        bounds: &TriboxBounds,
        mut corner: impl FnMut(usize) -> (usize, [Point3; 4]),
    ) -> Tribox {
        let mut cases = [0u8; 8];
        let vertices = std::array::from_fn(|c| {
            let (case, v) = corner(c);
            cases[c] = case as u8;
            v
        });
        if cases == [1; 8] {
            // The generic boundary (every corner in case 1), at once.
            return Tribox::generic(bounds, vertices);
        }
        let vertex_planes = std::array::from_fn(|c| VERTEX_PLANES[c][usize::from(cases[c]) - 1]);
        // Two bits per corner: its case − 1.
        let two_bits = cases.map(|k| usize::from(k - 1));
        let combo = |j: usize| {
            let [c0, c1, c2, c3] = FACE_CORNER_INDICES[j];
            if j < 6 {
                two_bits[c0] | two_bits[c1] << 2 | two_bits[c2] << 4 | two_bits[c3] << 6
            } else {
                two_bits[c0] | two_bits[c1] << 2
            }
        };
        let faces = std::array::from_fn(|j| {
            if j < 6 {
                PRINCIPAL_LOOPS.loops[combo(j)][j]
            } else {
                CHAMFER_LOOPS.loops[combo(j)][j - 6]
            }
            .to_le_bytes()
        });
        let face_len = std::array::from_fn(|j| {
            if j < 6 {
                PRINCIPAL_LOOPS.lens[combo(j)][j]
            } else {
                CHAMFER_LOOPS.lens[combo(j)][j - 6]
            }
        });
        Tribox {
            bounds: *bounds,
            vertices,
            vertex_planes,
            vertex_count: MAX_VERTICES as u8,
            faces,
            face_len,
            cases,
        }
    }

    /// The bounds this boundary was evaluated from.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().bounds(), &b);
    /// ```
    pub fn bounds(&self) -> &TriboxBounds {
        &self.bounds
    }

    /// Whether the boundary has no vertex (the tribox of no point).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert!(TriboxBounds::empty().boundary().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.vertex_count == 0
    }

    /// The vertices.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let t = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]).boundary().cleaned();
    /// assert_eq!(t.vertices(), &[Point3::new(1.0, 2.0, 3.0)]);
    /// ```
    pub fn vertices(&self) -> &[Point3] {
        &self.vertices.as_flattened()[..self.vertex_count as usize]
    }

    /// For each vertex, three planes (ascending indices 0..18, independent normals) through
    /// it. In a raw boundary a clamped chamfer may stand for its two principal planes; in a
    /// cleaned one each listed plane passes exactly through the vertex.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let t = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]).boundary().cleaned();
    /// assert_eq!(t.vertex_planes(), &[[1, 3, 5]]); // max x, max y, max z
    /// ```
    pub fn vertex_planes(&self) -> &[[u8; 3]] {
        &self.vertex_planes.as_flattened()[..self.vertex_count as usize]
    }

    /// The loop of face `plane` (indices into [`vertices`](Self::vertices), counter-clockwise
    /// seen from outside); empty for a plane index beyond 17 or a face removed by clean-up.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// let t = b.boundary();
    /// assert!(!t.face(1).is_empty());
    /// assert!(t.cleaned().face(1).is_empty()); // a needle has no face of positive area
    /// assert!(t.face(18).is_empty());
    /// ```
    pub fn face(&self, plane: usize) -> &[u8] {
        match (self.faces.get(plane), self.face_len.get(plane)) {
            (Some(f), Some(&n)) => &f[..n as usize],
            _ => &[],
        }
    }

    /// The faces that have vertices, as (plane index, loop).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// assert_eq!(b.boundary().faces().count(), 18);
    /// ```
    pub fn faces(&self) -> impl Iterator<Item = (usize, &[u8])> + '_ {
        (0..18)
            .map(|j| (j, self.face(j)))
            .filter(|(_, f)| !f.is_empty())
    }

    /// The number of faces that have vertices: on a cleaned boundary, the number of faces of
    /// positive area (at most 18).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().face_count(), 18); // raw: every plane has its (degenerate) face
    /// assert_eq!(TriboxBounds::from_points(&[Point3::origin()]).boundary().cleaned().face_count(), 0);
    /// ```
    pub fn face_count(&self) -> usize {
        self.face_len.iter().filter(|&&n| n > 0).count()
    }

    /// The paper's case (1 to 4) of each corner of the block; corner `c` is the maximum along
    /// axis i when bit i of `c` is clear, the minimum when it is set. All 0 when empty.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().corner_cases(), [1; 8]);
    /// ```
    pub fn corner_cases(&self) -> [u8; 8] {
        self.cases
    }

    /// The enclosed volume (divergence theorem over the face loops; degenerate faces add
    /// nothing).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // The corner tetrahedron of the unit cube: its tribox is {x, y, z ≥ 0, x+y, x+z, y+z ≤ 1},
    /// // the tetrahedron (1/6) plus the pyramid from (½, ½, ½) over its slanted face (1/12).
    /// let tet = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    /// assert_eq!(TriboxBounds::from_points(&tet).boundary().volume(), 0.25);
    /// ```
    pub fn volume(&self) -> f64 {
        let o = self.reference();
        let six_v: f64 = self
            .faces()
            .map(|(_, f)| {
                let p = |i: usize| self.vertices()[f[i] as usize] - o;
                let p0 = p(0);
                (1..f.len().saturating_sub(1))
                    .map(|i| p0.dot(&p(i).cross(&p(i + 1))))
                    .sum::<f64>()
            })
            .sum();
        six_v / 6.0
    }

    /// The total area of the faces.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // The tribox of the corner tetrahedron (see `volume`): three right triangles of area ½
    /// // and three chamfer triangles of area √2/4.
    /// let tet = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    /// let area = TriboxBounds::from_points(&tet).boundary().surface_area();
    /// assert!((area - (1.5 + 0.75 * 2f64.sqrt())).abs() < 1e-15);
    /// ```
    pub fn surface_area(&self) -> f64 {
        self.faces()
            .map(|(_, f)| {
                let p = |i: usize| self.vertices()[f[i] as usize];
                let p0 = p(0);
                let twice: Vector3 = (1..f.len().saturating_sub(1))
                    .map(|i| (p(i) - p0).cross(&(p(i + 1) - p0)))
                    .sum();
                twice.norm() / 2.0
            })
            .sum()
    }

    /// A reference point for the volume: the centre of the block (or the origin when empty).
    fn reference(&self) -> Point3 {
        let (lo, hi) = (self.bounds.min, self.bounds.max);
        if self.bounds.is_empty() {
            Point3::origin()
        } else {
            Point3::new(
                0.5 * lo[0] + 0.5 * hi[0],
                0.5 * lo[1] + 0.5 * hi[1],
                0.5 * lo[2] + 0.5 * hi[2],
            )
        }
    }
}

impl TriboxBounds {
    /// The boundary of the tribox, by the paper's corner classification. See [`Tribox`].
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// assert_eq!(b.boundary().cleaned().vertices().len(), 2); // a needle along (1, 1, 1)
    /// ```
    #[inline]
    pub fn boundary(&self) -> Tribox {
        Tribox::new(self)
    }
}
