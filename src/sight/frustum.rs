//! Clipping to the frustum: a perspective eye inside the scene.
//!
//! When some vertex of the scene is not strictly in front of a perspective eye (the eye in a
//! room, walking down a street), both drawing layers keep only what lies inside the view's
//! frustum ([`View::frustum`]: beyond the near plane, within the field of view at the aspect
//! of [`View::with_clipping`]); everything in front of the eye still hides what lies behind
//! it, as in the world. The hidden-line pass (`hidden`) draws the parts of lines inside it:
//!
//! - a line wholly behind the eye (no point strictly in front of it) is left out; a line that
//!   crosses the plane of the eye is *wide*: its picture is unbounded. Only crossings of
//!   pictures inside the picture's window can cut a drawn piece (drawn pieces lie in the
//!   frustum) or be made by a contour in front of the eye, so each line's picture is clipped to
//!   the window, grown a little ([`Clip::framed`]), before the grid: for a wide edge, the
//!   picture of its part in front of the eye, a ray. A picture too far out to clip reliably
//!   (and a wide intersection line) is tested against every other line instead. A triangle
//!   that crosses the plane of the eye is listed in every picture cell;
//! - a line not wholly inside the frustum is cut where it crosses each of its planes, and its
//!   pieces outside are not drawn;
//! - where a line's picture crosses a wide contour's, the point of the contour behind the
//!   crossing must be in front of the eye for the contour to cut the line: decided exactly
//!   ([`contour_in_front`]).
//!
//! The visible-surface pass (`surfaces`) cuts each face's visible polygons by the same five
//! planes ([`Clip::planes`]) and keeps the parts inside.
//!
//! Each plane is a form `n·(x − eye) − d` ([`Form::Frustum`]) with a normal `n` in doubles (a
//! sum of the view's frame vectors) and `d` the near distance or 0: given relative to the
//! eye, so that moving scene and eye together leaves every plane as it is and the clipped
//! drawing moves bit for bit. Each clipped end is the intersection of an input edge (or an
//! intersection line, or a face's trace) with such a plane, constructed once like every other
//! cut ([`cut_point`](crate::sight::along::cut_point)). The normals' rounding turns the
//! planes by about 2⁻⁵³ radians from the exact frustum: immaterial for drawing, and every
//! decision is made against the same planes.

use crate::geometry::kernel::{Difference, Polynomial, Product, rounded};
use crate::geometry::predicates::Side;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};
use crate::sight::along::{Form, PictureAt};
use crate::views::{Eye, Picture, View, ViewError, Window};
use std::cmp::Ordering;

/// The frustum of a perspective view that clips: its near plane and the four planes through
/// the eye and the picture's edges, and the plane of its eye.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Clip {
    /// The planes as forms relative to the eye (near, left, right, bottom, top), each with its
    /// sign inside.
    planes: [(Form, Ordering); 5],
    /// The eye.
    eye: Point3,
    /// The view's forward direction: the depth of `x` is `forward·(x − eye)`.
    forward: Vector3,
    /// Half the width and height of the picture's window, grown by 2⁻¹⁶ (the side planes'
    /// pictures are within a few units in the last place of `±aspect` and `±1`).
    window: [f64; 2],
}

/// The part of a line's picture inside the window of a view that clips (see [`Clip::framed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Framed {
    /// The part inside the grown window: a segment.
    Inside([[f64; 2]; 2]),
    /// No part is inside the window.
    Outside,
    /// The part could not be bounded reliably (a picture far outside the window).
    Unbounded,
}

impl Clip {
    /// The frustum of a perspective view; `None` for an orthographic view.
    pub(crate) fn of(view: &View) -> Option<Clip> {
        let Eye::Point(eye) = *view.eye() else {
            return None;
        };
        let frustum = view.frustum()?;
        // Each normal points inside: every plane's form is positive there.
        let planes = frustum
            .planes
            .map(|(_, normal, offset)| (Form::Frustum(normal, offset), Ordering::Greater));
        let [h, v] = view.window()?;
        // A point on the view's axis beyond the near plane is inside every plane: a plane
        // whose form is not positive there has no inside (a degenerate view).
        let inside = eye + view.forward() * (2.0 * view.near());
        let eye_point = Eye::Point(eye);
        if planes
            .iter()
            .any(|(form, sign)| form.sign_at(&eye_point, &inside) != *sign)
        {
            return None;
        }
        let grown = 1.0 + 1.0 / (1u64 << 16) as f64;
        Some(Clip {
            planes,
            eye,
            forward: view.forward(),
            window: [h / v * grown, grown],
        })
    }

    /// The part inside the (grown) window of the picture of a line of the scene: the segment
    /// between the pictures `ends` of its ends (both in front of the eye), or, for a line
    /// crossing the plane of the eye from `front` (in front, with picture `from`) to `other`,
    /// the picture of its part in front of the eye: the ray from `from` along
    /// `L(other)·D(front) − L(front)·D(other)` (picture forms `L`, depth `D`; each component
    /// exact, rounded once). Clipped in floating point, which the grown window covers unless a
    /// point is more than 2³⁰ times the window away: then `Unbounded`.
    pub(crate) fn framed(&self, picture: &Picture, line: FramedLine) -> Framed {
        let (start, direction, limit) = match line {
            FramedLine::Segment([p, q]) => (p, [q[0] - p[0], q[1] - p[1]], 1.0),
            FramedLine::Ray { front, from, other } => {
                (from, ray_direction(picture, front, other), f64::INFINITY)
            }
        };
        let far = 2f64.powi(30) * self.window[0].max(self.window[1]);
        let beyond = |p: [f64; 2]| !(p[0].abs() <= far && p[1].abs() <= far);
        if beyond(start) || direction.iter().any(|d| !d.is_finite()) {
            return Framed::Unbounded;
        }
        // Liang and Barsky: the parameters where the line is inside each slab.
        let (mut enter, mut exit) = (0.0f64, limit);
        for k in 0..2 {
            let w = self.window[k];
            if direction[k] == 0.0 {
                if start[k].abs() > w {
                    return Framed::Outside;
                }
                continue;
            }
            let (s0, s1) = (
                (-w - start[k]) / direction[k],
                (w - start[k]) / direction[k],
            );
            enter = enter.max(s0.min(s1));
            exit = exit.min(s0.max(s1));
        }
        if enter
            .partial_cmp(&exit)
            .is_none_or(|o| o == Ordering::Greater)
        {
            return Framed::Outside;
        }
        let at = |s: f64| {
            [0, 1].map(|k| (start[k] + s * direction[k]).clamp(-self.window[k], self.window[k]))
        };
        Framed::Inside([at(enter), at(exit)])
    }

    /// Half the width and height of the picture's window, grown a little: every point inside
    /// the frustum has its picture inside.
    pub(crate) fn window(&self) -> [f64; 2] {
        self.window
    }

    /// The planes as forms along lines.
    pub(crate) fn forms(&self) -> impl Iterator<Item = Form> + '_ {
        self.planes.iter().map(|p| p.0)
    }

    /// The planes as forms (near, left, right, bottom, top), each with its sign strictly
    /// inside the frustum.
    pub(crate) fn planes(&self) -> impl Iterator<Item = (Form, Ordering)> + '_ {
        self.planes.iter().copied()
    }

    /// Whether `x` lies strictly inside the frustum, decided exactly.
    pub(crate) fn contains(&self, eye: &Eye, x: &Point3) -> bool {
        self.planes
            .iter()
            .all(|(form, inside)| form.sign_at(eye, x) == *inside)
    }

    /// Whether a point lies strictly inside the frustum, given the exact sign of each plane's
    /// form at it.
    pub(crate) fn contains_by(&self, sign: impl Fn(&Form) -> Ordering) -> bool {
        self.planes
            .iter()
            .all(|(form, inside)| sign(form) == *inside)
    }

    /// The depth as a form, relative to the eye: positive in front of it (the polynomial of
    /// [`Clip::in_front`]).
    pub(crate) fn depth(&self) -> Form {
        Form::Frustum(self.forward, 0.0)
    }

    /// The depth of `x` as a polynomial: positive in front of the eye (the same form as the
    /// picture's depth, so the same decisions).
    fn depth_at(&self, x: &Point3) -> Side {
        Side {
            origin: self.eye,
            normal: self.forward,
            offset: 0.0,
            x: *x,
        }
    }

    /// Whether `x` lies strictly in front of the eye, exactly.
    pub(crate) fn in_front(&self, x: &Point3) -> bool {
        self.depth_at(x).sign() == Ordering::Greater
    }
}

/// The direction of the picture of the segment from `front`, in front of a perspective eye,
/// towards `other`, not in front (up to where it crosses the plane of the eye): the ray from
/// `front`'s picture along `L(other)·D(front) − L(front)·D(other)`, for the picture forms `L`
/// and the depth `D` (its picture is `L/D`, and `P(x) − P(front)` is that vector times
/// `t / (D(x)·D(front))` at `x = front + t·(other − front)`). Each component exact, rounded
/// once (so its sign is exact).
pub(crate) fn ray_direction(picture: &Picture, front: &Point3, other: &Point3) -> [f64; 2] {
    let at = |k, x| PictureAt { picture, k, x };
    [0, 1].map(|k| {
        rounded(&Difference(
            Product(at(k, other), at(2, front)),
            Product(at(k, front), at(2, other)),
        ))
    })
}

/// A line's picture for [`Clip::framed`].
#[derive(Debug, Clone, Copy)]
pub(crate) enum FramedLine<'a> {
    /// A segment between the pictures of two points in front of the eye.
    Segment([[f64; 2]; 2]),
    /// A line from `front`, in front of the eye with picture `from`, to `other`, not.
    Ray {
        /// The end in front of the eye.
        front: &'a Point3,
        /// Its picture.
        from: [f64; 2],
        /// The other end.
        other: &'a Point3,
    },
}

/// The scene's mesh objects, and the frustum when the view clips (see [`pictured`]).
pub(crate) type Pictured<'s> = (Vec<(ObjectId, &'s Mesh)>, Option<Clip>);

/// The scene's mesh objects, and the view's frustum when the view clips: a perspective eye
/// with some vertex not strictly in front of it (an error naming it for a view without a
/// frustum). The one rule by which the hidden-line and visible-surface passes and `verify`
/// decide whether to clip.
pub(crate) fn pictured<'s>(scene: &'s Scene, view: &View) -> Result<Pictured<'s>, ViewError> {
    match Picture::of(view).mesh_objects_in_front(scene) {
        Ok(meshes) => Ok((meshes, None)),
        Err(e @ ViewError::NotInFront { .. }) => match Clip::of(view) {
            Some(clip) => Ok((scene.mesh_objects(scene.roots()), Some(clip))),
            None => Err(e),
        },
        Err(e) => Err(e),
    }
}

/// Whether the point where the segment `cd` crosses the plane through the eye and the line
/// `ab` lies strictly in front of the eye, given the sides `sc`, `sd` of `c` and `d` of that
/// plane (opposite, or one of them zero). With `O(x) = orient3d(a, b, x, eye)` and depth `S`,
/// the crossing is `X = (O(d)·c − O(c)·d) / (O(d) − O(c))`, so the sign of `S(X)` is that of
/// `S(c)·O(d) − S(d)·O(c)` times that of `O(d) − O(c)`, which is `sd` (or `−sc`).
pub(crate) fn contour_in_front(
    near: &Clip,
    eye: &Eye,
    [a, b]: [&Point3; 2],
    [c, d]: [&Point3; 2],
    [sc, sd]: [Ordering; 2],
) -> bool {
    match (sc, sd) {
        (Ordering::Equal, _) => near.in_front(c),
        (_, Ordering::Equal) => near.in_front(d),
        _ => {
            let numerator = Difference(
                Product(near.depth_at(c), eye.determinant(a, b, d)),
                Product(near.depth_at(d), eye.determinant(a, b, c)),
            );
            let s = numerator.sign();
            s != Ordering::Equal && s == sd
        }
    }
}

/// The planes of a window of the picture ([`Window`]): each bound of the window as the plane of
/// the points whose picture lies on it, `rows[k]·x = c` for an orthographic view and
/// `(rows[k] − c·rows[2])·(x − eye) = 0` for a perspective one (the picture forms of
/// [`Picture::rows`]; the second normal rounded, like the frustum's side planes). Each plane
/// is the same double-valued form wherever the window is used, so the tiles of a grid cut an
/// edge at their common border at the same point, built once from the input like every other
/// cut; and the half-open windows split space: every point of a line lies in exactly one tile
/// (on a lower bound's plane it is inside, on an upper bound's outside).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TilePlanes {
    /// Each bound's form, and whether it is a lower bound (inside where the form is positive
    /// or zero; an upper bound is inside where it is negative).
    planes: Vec<(Form, bool)>,
    /// The point the forms are taken from (the eye, or the origin).
    origin: Point3,
}

impl TilePlanes {
    /// The planes of `window` in `view`; `None` when the window is the whole picture, and an
    /// error when a bound's plane does not fit in doubles.
    pub(crate) fn of(view: &View, window: &Window) -> Result<Option<TilePlanes>, ViewError> {
        let picture = Picture::of(view);
        let (rows, origin) = picture.rows();
        let mut planes = Vec::new();
        for (k, bounds) in [window.x, window.y].into_iter().enumerate() {
            for (lower, c) in [(true, bounds[0]), (false, bounds[1])] {
                if c.is_infinite() {
                    continue;
                }
                let form = if picture.is_perspective() {
                    let normal = rows[k] - rows[2] * c;
                    if !normal.iter().all(|x| x.is_finite()) {
                        return Err(ViewError::Options(
                            "a window's bound is too far out for this view",
                        ));
                    }
                    Form::Frustum(normal, 0.0)
                } else {
                    Form::Frustum(rows[k], c)
                };
                planes.push((form, lower));
            }
        }
        Ok((!planes.is_empty()).then_some(TilePlanes { planes, origin }))
    }

    /// Whether a sign of a bound's form is inside.
    fn inside(sign: Ordering, lower: bool) -> bool {
        if lower {
            sign != Ordering::Less
        } else {
            sign == Ordering::Less
        }
    }

    /// Whether a point is in the tile, given the exact sign of each bound's form at it.
    pub(crate) fn contains_by(&self, sign: impl Fn(&Form) -> Ordering) -> bool {
        self.planes
            .iter()
            .all(|(form, lower)| TilePlanes::inside(sign(form), *lower))
    }

    /// Whether `x` is in the tile, exactly.
    pub(crate) fn contains(&self, eye: &Eye, x: &Point3) -> bool {
        self.contains_by(|form| form.sign_at(eye, x))
    }

    /// The bounds' forms.
    pub(crate) fn forms(&self) -> impl Iterator<Item = Form> + '_ {
        self.planes.iter().map(|p| p.0)
    }

    /// Whether every one of `points` lies outside one bound's plane by more than the rounding
    /// of its form in floating point could account for, with room to spare: then nothing of
    /// their convex hull (an object's CBOX, an edge) is in the tile, nor (for an orthographic
    /// view, whose planes are parallel to the lines of sight only to within rounding) anything
    /// on a line of sight through the tile. A filter for leaving work out, never a decision:
    /// `false` when unsure.
    pub(crate) fn surely_outside(&self, points: &[Point3]) -> bool {
        self.planes.iter().any(|(form, lower)| {
            let Form::Frustum(normal, offset) = form else {
                return false;
            };
            points.iter().all(|x| {
                let d = x - self.origin;
                let value = normal.dot(&d) - offset;
                let size = normal.amax() * (x.coords.amax() + self.origin.coords.amax());
                let margin = (3.0 * size + offset.abs()) / (1u64 << 30) as f64;
                if *lower {
                    value < -margin
                } else {
                    value > margin
                }
            })
        })
    }
}
