//! A line of the drawing before its visibility is decided ([`Line`], and [`MeetLine`] for an
//! intersection segment) and the cuts on it ([`Cut`]), with the helpers the stages share to
//! place a cut along a line.

use super::EdgeClass;
use super::marks::MarkKey;
use crate::geometry::Point3;
use crate::geometry::kernel::Polynomial;
use crate::scene::{ObjectId, Scene};
use crate::sight::along::{Form, Zero};
use crate::sight::meet::{Meet, OnLine};
use crate::views::Eye;

/// A line's name, the same in every tile: an edge by its mesh object (its index among the
/// scene's mesh objects) and its index among the object's classified edges; an intersection
/// segment by its two objects and its index among their segments. Ordered as the whole pass
/// orders its lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum LineId {
    /// An edge: object, index.
    Edge(u32, u32),
    /// An intersection segment: objects, index.
    Meet(u32, u32, u32),
}

/// A line of the drawing before visibility: an edge or an intersection segment.
#[derive(Debug, Clone, Copy)]
pub(super) struct Line {
    pub(super) a: Point3,
    pub(super) b: Point3,
    /// The pictures of `a` and `b`.
    pub(super) ends: [[f64; 2]; 2],
    pub(super) class: EdgeClass,
    /// For an intersection segment: its index in [`Pass::meets`](super::pass::Pass::meets).
    pub(super) meet: Option<usize>,
    /// Whether the line is an edge between two faces turned away from the eye on a solid that
    /// the eye is outside of: then the solid itself hides all of it.
    pub(super) back: bool,
    /// For an edge: the triangles on its sides (in its mesh).
    pub(super) triangles: Option<[u32; 2]>,
    /// Whether the line crosses the plane of a perspective eye that clips: its picture is
    /// unbounded (see `queries/frustum.rs`).
    pub(super) wide: bool,
    /// Whether the line is not wholly inside the frustum of a view that clips: its pieces
    /// outside it are not drawn.
    pub(super) clipped: bool,
    /// For an edge: the index of its leaf and its ends' vertex indices (which name a cut that
    /// it makes on an intersection line the same way in a transformed scene).
    pub(super) leaf: u32,
    pub(super) vertices: [u32; 2],
    /// The line's name, the same in every tile of a grid (see [`tiles`](super::tiles)).
    pub(super) id: LineId,
}

/// An intersection segment in the pass: where it lies and the faces that do not hide it.
#[derive(Debug, Clone, Copy)]
pub(super) struct MeetLine {
    pub(super) meet: Meet,
    pub(super) ends: [OnLine; 2],
    pub(super) on_faces: [(ObjectId, usize); 2],
    /// The names of its ends (see [`MarkKey`]).
    pub(super) keys: [MarkKey; 2],
}

impl Line {
    /// The index among the scene's mesh objects of the edge's object (of the first object of
    /// an intersection segment): the same in every tile, so cuts are named by it.
    pub(super) fn object(&self) -> u32 {
        match self.id {
            LineId::Edge(o, _) | LineId::Meet(o, _, _) => o,
        }
    }

    /// Whether the line's picture bounds regions where the visible surface changes.
    pub(super) fn is_contour(&self) -> bool {
        matches!(self.class, EdgeClass::Silhouette | EdgeClass::Boundary)
    }
}

/// Where a line is cut: the zero of a form along it, strictly inside it (on an edge, with its
/// approximate parameter and a bound on that parameter's error, ordered exactly; on an
/// intersection line, a form increasing along it with a rough parameter for a first sort,
/// ordered exactly by the line). `sighted` is the picture of an input vertex when the cut is
/// where the line of sight through that vertex meets the line (collinear pictures); the other
/// cuts' pictures are built from their forms. `key` names the cut from the indices of what
/// makes it, the same in a transformed scene (of two cuts at one point, the one with the
/// smaller key is drawn).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Cut {
    pub(super) zero: Zero,
    pub(super) sighted: Option<[f64; 2]>,
    pub(super) key: [u32; 4],
}

impl Cut {
    /// A cut of an edge.
    pub(super) fn on_edge(zero: Zero, sighted: Option<[f64; 2]>, key: [u32; 4]) -> Cut {
        Cut { zero, sighted, key }
    }

    /// A cut of an intersection line where `form`, increasing along it, vanishes; `t` its
    /// rough parameter.
    pub(super) fn on_line(form: Form, t: f64, sighted: Option<[f64; 2]>, key: [u32; 4]) -> Cut {
        let zero = Zero {
            form,
            rising: true,
            t,
            error: f64::INFINITY,
        };
        Cut { zero, sighted, key }
    }

    /// The cut of an intersection line, as a point of it.
    pub(super) fn point(&self) -> OnLine {
        OnLine::Cut(self.zero.form)
    }
}

/// The parameter along `ab` where `form` vanishes, roughly (for a first sort of cuts only).
pub(super) fn rough_parameter(eye: &Eye, form: &Form, a: &Point3, b: &Point3) -> f64 {
    let (fa, fb) = (
        form.at(eye, a).estimate().value,
        form.at(eye, b).estimate().value,
    );
    let t = fa / (fa - fb);
    if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// Whether triangle `tri` of `object` lies on one of the faces an intersection line runs on.
pub(super) fn on_faces(m: &MeetLine, scene: &Scene, object: ObjectId, tri: usize) -> bool {
    m.on_faces
        .iter()
        .any(|&(o, f)| o == object && scene[object].mesh().is_some_and(|m| m.face_of(tri) == f))
}
