//! Projected areas of the lab's bounds: oriented boxes by Schmalstieg and Tobler's table, their
//! bounding rectangles (the paper's comparison), and triboxes by the convex hull of their
//! projected vertices.
//!
//! The engine's part, the hull table and the area of an axis-aligned box, is
//! [`crate::views::projected_area`]; here the eye is classified in an oriented box's own frame
//! ("transform the viewpoint in the local coordinate system of the OBB") with exact signs, and
//! the same table gives the silhouette.
//!
//! ```
//! use kepler::lab::projected_area::{bounding_rect_area, projected_area};
//! use kepler::lab::oriented::OrientedBox;
//! use kepler::geometry::{Aabb, Vector3};
//! use kepler::views::View;
//! // The unit cube seen along its diagonal: a regular hexagon of area √3; its bounding
//! // rectangle is 4/3 of it.
//! let cube = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0; 3] });
//! let view = View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap();
//! assert!((projected_area(&cube, &view) - 3f64.sqrt()).abs() < 1e-15);
//! assert!((bounding_rect_area(&cube, &view) - 4.0 / 3f64.sqrt()).abs() < 1e-15);
//! ```

use crate::bounds::tribox::Tribox;
use crate::geometry::Vector3;
use crate::geometry::exact::{sum_sign, two_product};
use crate::geometry::polygon::bounding_box;
use crate::lab::oriented::OrientedBox;
use crate::views::projected_area::{CORNERS, area_not_in_front, direction_code, silhouette_area};
use crate::views::{Eye, Picture, View};
use geo::{Area, ConvexHull, MultiPoint, Point};
use std::cmp::Ordering;

/// The code of `eye` against an oriented box, in the box's frame as the paper does ("transform
/// the viewpoint in the local coordinate system of the OBB"), but with the exact sign of
/// `axis · eye − bound` (as [`OrientedBox::contains_point`] decides), or of `axis · direction`.
fn classify_oriented(b: &OrientedBox, eye: &Eye) -> u8 {
    match eye {
        Eye::Point(e) => (0..3).fold(0, |code, k| {
            let below = dot_minus_sign(&b.axes[k], &e.coords, b.min[k]) == Ordering::Less;
            let above = dot_minus_sign(&b.axes[k], &e.coords, b.max[k]) == Ordering::Greater;
            code | u8::from(below) << (2 * k) | u8::from(above) << (2 * k + 1)
        }),
        Eye::Infinity(u) => direction_code(|k| Some(dot_minus_sign(&b.axes[k], u, 0.0))),
    }
}

/// The exact sign of `a · v − c`: the six exact products and `−c`, summed exactly.
fn dot_minus_sign(a: &Vector3, v: &Vector3, c: f64) -> Ordering {
    let mut terms = [0.0; 7];
    for i in 0..3 {
        (terms[2 * i], terms[2 * i + 1]) = two_product(a[i], v[i]);
    }
    terms[6] = -c;
    sum_sign(&terms)
}

/// The area of the picture of an oriented box in `view`, its corners as
/// [`OrientedBox::corners`] gives them (units and the values for an eye inside or a box not in
/// front of the eye: see the [module documentation](self)); 0 for an empty box. The eye is
/// classified in the box's frame, exactly.
///
/// ```
/// use kepler::lab::{oriented::OrientedBox, projected_area::projected_area};
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::views::View;
/// // A unit square turned 45° about z, seen from above.
/// let s = 0.5f64.sqrt();
/// let axes = [Vector3::new(s, s, 0.0), Vector3::new(-s, s, 0.0), Vector3::z()];
/// let b = OrientedBox { axes, min: [0.0; 3], max: [1.0; 3] };
/// assert!((projected_area(&b, &View::standard()) - 1.0).abs() < 1e-15);
/// ```
pub fn projected_area(b: &OrientedBox, view: &View) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let code = classify_oriented(b, view.eye());
    let corners = b.corners();
    let corner = |k: u8| {
        let [x, y, z] = CORNERS[usize::from(k)];
        corners[usize::from(x | y << 1 | z << 2)]
    };
    silhouette_area(code, corner, view)
}

/// The paper's comparison: the area of the 2-D bounding box of the pictures of the eight
/// corners (as [`OrientedBox::corners`] gives them), an overestimate of
/// [`projected_area`]. A perspective view needs the corners in front of the eye, and gives 0
/// when none is and `f64::INFINITY` when only some are (the eye in the box included); 0 for an
/// empty box.
///
/// ```
/// use kepler::lab::{oriented::OrientedBox, projected_area::bounding_rect_area};
/// use kepler::geometry::{Aabb, Vector3};
/// use kepler::views::View;
/// // A unit square turned 45° about z, seen from above: its bounding square has area 2.
/// let s = 0.5f64.sqrt();
/// let axes = [Vector3::new(s, s, 0.0), Vector3::new(-s, s, 0.0), Vector3::z()];
/// let b = OrientedBox { axes, min: [0.0; 3], max: [1.0; 3] };
/// assert!((bounding_rect_area(&b, &kepler::views::View::standard()) - 2.0).abs() < 1e-15);
/// ```
pub fn bounding_rect_area(b: &OrientedBox, view: &View) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let picture = Picture::of(view);
    let corners = b.corners();
    if let Some(area) = area_not_in_front(&picture, &corners) {
        return area;
    }
    let [lo, hi] = bounding_box(corners.iter().map(|p| picture.point(p)));
    (hi[0] - lo[0]) * (hi[1] - lo[1])
}

/// The area of the picture of a tribox in `view`: the area of the 2-D convex hull of its
/// projected vertices (geo's `ConvexHull` and `Area`), which is the picture of a convex
/// polytope in front of the eye. No paper gives a table for the tribox's up to 18 faces, so
/// the silhouette is not walked. As for boxes: `f64::INFINITY` for the eye in the closed
/// tribox (decided exactly) or a tribox reaching across the plane through a perspective eye
/// across the view direction, 0 for one wholly at or behind it, and 0 for an empty tribox.
///
/// ```
/// use kepler::lab::projected_area::projected_area_tribox;
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// use kepler::views::View;
/// // The tribox of four corners of the unit cube lies in the cube and holds the corners, so
/// // from above its picture is the unit square.
/// let p = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
/// let t = TriboxBounds::from_points(&p.map(Point3::from)).boundary();
/// assert_eq!(projected_area_tribox(&t, &View::standard()), 1.0);
/// ```
pub fn projected_area_tribox(t: &Tribox, view: &View) -> f64 {
    if t.is_empty() {
        return 0.0;
    }
    if let Eye::Point(e) = view.eye()
        && t.bounds().contains_point(e)
    {
        return f64::INFINITY;
    }
    let picture = Picture::of(view);
    let vertices = t.vertices();
    if let Some(area) = area_not_in_front(&picture, vertices) {
        return area;
    }
    let points: MultiPoint<f64> = vertices
        .iter()
        .map(|p| Point::from(picture.point(p)))
        .collect();
    points.convex_hull().unsigned_area()
}
