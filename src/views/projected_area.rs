//! The area of a box's picture, after Schmalstieg and Tobler (1999), "Fast projected area
//! computation for three-dimensional bounding boxes".
//!
//! The paper classifies the eye against the six planes of the box's faces: "These six planes
//! subdivide Euclidean space into 3³ = 27 regions. The case where the viewpoint is inside the
//! box does not allow meaningful area computation, so 26 valid cases remain." A 6-bit code
//! ([`classify`]) indexes a table of the silhouette ("hull polygon") of the box seen from that
//! region ([`HULL`]), and the area is a contour integral over the projected silhouette
//! vertices. Only four or six corners are projected, against eight for the usual estimate, the
//! 2-D bounding box of the projected corners (the lab's `bounding_rect_area`): "The total number of
//! operations is 159 for Case 2 and 3 (six vertices), and 115 for case 1 (four vertices). The
//! number of operations required to compute a simple two-dimensional box area is 163." The
//! benchmark `benches/projected_area.rs` measures both on the same boxes.
//!
//! This is the engine's part, used for Franklin's ideographs (`kepler::hidden::ideographs`): the
//! table and the area of an axis-aligned box. The lab (`kepler::lab::projected_area`) adds
//! oriented boxes and triboxes.
//!
//! Here the classification is exact (comparisons), and the corners are projected by the drawing's own map,
//! [`Picture::point`], each coordinate rounded once from its exact value (dearer than the
//! paper's 18-operation projection, so projecting fewer corners saves more). An area is in
//! the picture coordinates of [`Picture::of`]: for a perspective view the area on the
//! picture plane where the field of view spans `y` in `[-1, 1]`, for an orthographic view
//! the area of the orthographic projection in scene units. An orthographic eye is at
//! infinity, so it is classified by the signs of its direction ([`Eye::Infinity`]), which
//! are exact.
//!
//! A perspective picture needs the box in front of the eye. The results are:
//! - the eye in the closed box (code 0): `f64::INFINITY`, the box covers the whole view;
//! - the box strictly in front of the eye: its area;
//! - the box wholly at or behind the plane through the eye across the view direction: 0, as
//!   nothing of it is in front;
//! - the box reaching across that plane: `f64::INFINITY`, its picture is unbounded.
//!
//! Corners are numbered as the paper's table implies (its rows for single faces: "0 4 7 3
//! left", "1 2 6 5 right", "0 1 5 4 bottom", "2 3 7 6 top", "0 3 2 1 front", "4 5 6 7
//! back"): left/right is `x` min/max, bottom/top `y`, front/back `z`, and [`CORNERS`] gives
//! each corner's sides. Drawn with `x` to the right, `y` up and `z` into the page:
//!
//! ```text
//!      7 +---------+ 6
//!       /|        /|
//!      / |       / |
//!   3 +---------+ 2|
//!     |  |      |  |
//!     |4 +------|--+ 5
//!     | /       | /
//!     |/        |/
//!   0 +---------+ 1
//! ```
//!
//! Errors in the paper, found by deriving the table ([`HULL`]) and comparing:
//! - row 5 (left, bottom) is printed as a copy of row 6 (right, bottom), "0 1 2 6 5 4", with
//!   row 6's description; the silhouette from the left-bottom region is `0 1 5 4 7 3`. Every
//!   other row agrees with ours up to the starting vertex (same cyclic order, same
//!   counter-clockwise orientation);
//! - the code classifies with `eye.x > bbox[7].x` and so on, taking corner 7 as the maximum,
//!   but in the table's numbering the maximum is corner 6 (corner 7 is left-top-back);
//! - the code does not compile as printed (`int pos` declared twice, `!num = …` for
//!   `!(num = …)`, and the Pascal `:=`).
//!
//! ```
//! use kepler::views::projected_area::projected_area_aabb;
//! use kepler::geometry::{Aabb, Vector3};
//! use kepler::views::View;
//! // The unit cube seen along its diagonal: a regular hexagon of area √3.
//! let cube = Aabb { min: [0.0; 3], max: [1.0; 3] };
//! let view = View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap();
//! assert!((projected_area_aabb(&cube, &view) - 3f64.sqrt()).abs() < 1e-15);
//! ```

use crate::geometry::{Aabb, Point3};
use crate::views::{Eye, Picture, View};
use std::cmp::Ordering;

/// The corners in the paper's numbering: corner `k` is on the maximum side along axis `i`
/// when `CORNERS[k][i]` is 1, on the minimum side when it is 0.
///
/// ```
/// use kepler::views::projected_area::CORNERS;
/// assert_eq!(CORNERS[0], [0, 0, 0]); // left, bottom, front
/// assert_eq!(CORNERS[6], [1, 1, 1]); // right, top, back
/// ```
pub const CORNERS: [[u8; 3]; 8] = [
    [0, 0, 0],
    [1, 0, 0],
    [1, 1, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 0, 1],
    [1, 1, 1],
    [0, 1, 1],
];

/// The hull vertex table: row `code` ([`classify`]) holds the number of silhouette corners
/// (4 when the eye faces one face, 6 when it sees two or three; 0 for the eye inside, code
/// 0, and for the invalid codes, which have both bits of an axis set), then the corners
/// ([`CORNERS`]) in order around the silhouette, counter-clockwise in the picture, starting
/// from the lowest index; unused entries are 0.
///
/// Derived here, not copied: the paper's printed table has a wrong row (see the module
/// documentation). For each code the eye is put in its region around the cube `[0, 2]³`, at
/// coordinate −1, 1 or 3 along each axis, and `p → q` is a silhouette edge when every other
/// corner `r` has `det(p − e, q − e, r − e) < 0`: seen from the eye, all of the box lies to
/// the left of the edge. The signs are exact in integers, and no other corner lies in the
/// plane of a silhouette edge and the eye, because the eye is on no face plane. The test
/// `tests/projected_area.rs` checks the table against the hulls of projected corners.
///
/// ```
/// use kepler::views::projected_area::HULL;
/// assert_eq!(HULL[1], [4, 0, 4, 7, 3, 0, 0]); // left: the face x = min
/// assert_eq!(HULL[5], [6, 0, 1, 5, 4, 7, 3]); // left, bottom (misprinted in the paper)
/// assert_eq!(HULL[3], [0; 7]); // left and right at once: invalid
/// ```
pub const HULL: [[u8; 7]; 43] = {
    let mut table = [[0; 7]; 43];
    let mut code = 0;
    while code < 43 {
        table[code] = silhouette(code as u8);
        code += 1;
    }
    table
};

/// The [`HULL`] row of `code`, from the geometry of the cube `[0, 2]³` seen from its region.
const fn silhouette(code: u8) -> [u8; 7] {
    let mut eye = [0i64; 3];
    let mut axis = 0;
    while axis < 3 {
        let low = (code >> (2 * axis)) & 1 == 1;
        let high = (code >> (2 * axis + 1)) & 1 == 1;
        eye[axis] = match (low, high) {
            (true, true) => return [0; 7],
            (true, false) => -1,
            (false, true) => 3,
            (false, false) => 1,
        };
        axis += 1;
    }
    // Corners relative to the eye.
    let mut c = [[0i64; 3]; 8];
    let mut k = 0;
    while k < 8 {
        let mut i = 0;
        while i < 3 {
            c[k][i] = 2 * CORNERS[k][i] as i64 - eye[i];
            i += 1;
        }
        k += 1;
    }
    // next[p] = q for each silhouette edge p → q; 8 for none. An eye inside sees no edge
    // with the whole box on one side.
    let mut next = [8u8; 8];
    let mut p = 0;
    while p < 8 {
        let mut q = 0;
        while q < 8 {
            let mut edge = q != p;
            let mut r = 0;
            while edge && r < 8 {
                edge = r == p || r == q || det(c[p], c[q], c[r]) < 0;
                r += 1;
            }
            if edge {
                next[p] = q as u8;
            }
            q += 1;
        }
        p += 1;
    }
    let mut row = [0u8; 7];
    let mut start = 0;
    while start < 8 && next[start] == 8 {
        start += 1;
    }
    if start == 8 {
        return row;
    }
    let mut n = 0;
    let mut v = start as u8;
    loop {
        row[1 + n] = v;
        n += 1;
        v = next[v as usize];
        if v as usize == start {
            break;
        }
    }
    row[0] = n as u8;
    row
}

/// `det(a, b, c)`: negative when `a`, `b`, `c` (seen from the origin) are counter-clockwise in
/// a picture with `x` right and `y` up, whose third axis (`x × y`) points to the viewer.
const fn det(a: [i64; 3], b: [i64; 3], c: [i64; 3]) -> i64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// The paper's 6-bit code of `eye` against the six face planes of `b`: bit 0 left (`x <
/// min.x`), 1 right (`x > max.x`), 2 bottom (`y < min.y`), 3 top (`y > max.y`), 4 front (`z <
/// min.z`), 5 back (`z > max.z`). Exact: a point on a plane is not outside it, and code 0 is the eye in the closed box. An eye at
/// infinity ([`Eye::Infinity`], an orthographic view) is outside on the side its direction
/// points to along each axis where that component is not zero. An empty box gives a code
/// with both bits of an axis set.
///
/// ```
/// use kepler::views::projected_area::classify;
/// use kepler::geometry::{Aabb, Point3, Vector3};
/// use kepler::views::Eye;
/// let b = Aabb { min: [0.0; 3], max: [1.0; 3] };
/// assert_eq!(classify(&b, &Eye::Point(Point3::new(-1.0, 0.5, 2.0))), 1 | 32); // left, back
/// assert_eq!(classify(&b, &Eye::Point(Point3::new(1.0, 0.5, 0.0))), 0); // on the boundary
/// assert_eq!(classify(&b, &Eye::Infinity(Vector3::new(0.0, 1.0, -1.0))), 8 | 16); // top, front
/// ```
pub fn classify(b: &Aabb, eye: &Eye) -> u8 {
    match eye {
        Eye::Point(e) => (0..3).fold(0, |code, i| {
            code | u8::from(e[i] < b.min[i]) << (2 * i) | u8::from(e[i] > b.max[i]) << (2 * i + 1)
        }),
        Eye::Infinity(u) => direction_code(|i| u[i].partial_cmp(&0.0)),
    }
}

/// The code of an eye at infinity whose direction has the sign `sign(i)` along axis `i`.
pub fn direction_code(sign: impl Fn(usize) -> Option<Ordering>) -> u8 {
    (0..3).fold(0, |code, i| match sign(i) {
        Some(Ordering::Less) => code | 1 << (2 * i),
        Some(Ordering::Greater) => code | 1 << (2 * i + 1),
        _ => code,
    })
}

/// The area of the picture of an axis-aligned box in `view` (units and the values for an eye
/// inside or a box not in front of the eye: see the [module documentation](self)); 0 for an
/// empty box.
///
/// ```
/// use kepler::views::projected_area::projected_area_aabb;
/// use kepler::geometry::{Aabb, Point3, Vector3};
/// use kepler::views::View;
/// let b = Aabb { min: [-1.0; 3], max: [1.0; 3] };
/// // Face-on from 3 units with a 90° field of view: the near face, at depth 2, spans
/// // [-1/2, 1/2]² in the picture (up to the rounding of tan 45°).
/// let v = View::perspective(Point3::new(0.0, 0.0, 3.0), Point3::origin(), Vector3::y(), 90.0).unwrap();
/// assert!((projected_area_aabb(&b, &v) - 1.0).abs() < 1e-15);
/// let inside = View::perspective(Point3::origin(), Point3::new(0.0, 0.0, 1.0), Vector3::y(), 90.0).unwrap();
/// assert_eq!(projected_area_aabb(&b, &inside), f64::INFINITY);
/// ```
pub fn projected_area_aabb(b: &Aabb, view: &View) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let code = classify(b, view.eye());
    let corner = |k: u8| {
        let [x, y, z] = CORNERS[usize::from(k)].map(usize::from);
        Point3::new(
            [b.min[0], b.max[0]][x],
            [b.min[1], b.max[1]][y],
            [b.min[2], b.max[2]][z],
        )
    };
    silhouette_area(code, corner, view)
}

/// The area of the silhouette of [`HULL`]`[code]` with the given corners: the paper's contour
/// integral, `Σ (x_i − x_(i+1)) (y_i + y_(i+1)) / 2` over the projected silhouette.
pub fn silhouette_area(code: u8, corner: impl Fn(u8) -> Point3, view: &View) -> f64 {
    let Some(row) = HULL.get(usize::from(code)) else {
        return 0.0;
    };
    let n = usize::from(row[0]);
    if n == 0 {
        return f64::INFINITY;
    }
    let silhouette = &row[1..=n];
    let picture = Picture::of(view);
    let mut points = [Point3::origin(); 6];
    for (p, &k) in points.iter_mut().zip(silhouette) {
        *p = corner(k);
    }
    let points = &points[..n];
    // The eye is outside, so every point of the box is on a ray from the eye through a face
    // turned to it, at or beyond that face; those faces' corners are the silhouette and, seen
    // from a corner region, the nearest corner, which is in front whenever its three
    // silhouette neighbours are. So the silhouette decides where the box is.
    if let Some(area) = area_not_in_front(&picture, points) {
        return area;
    }
    let mut projected = [[0.0; 2]; 6];
    for (q, p) in projected.iter_mut().zip(points) {
        *q = picture.point(p);
    }
    let projected = &projected[..n];
    // Measuring `y` from the first vertex leaves the sum unchanged (the differences of `x`
    // sum to zero) and keeps it from cancelling when the picture is far from the origin.
    let y0 = projected[0][1];
    let mut sum = 0.0;
    for (i, a) in projected.iter().enumerate() {
        let b = projected[(i + 1) % n];
        sum += (a[0] - b[0]) * ((a[1] - y0) + (b[1] - y0));
    }
    // Counter-clockwise, so positive but for rounding on a box seen edge-on.
    (0.5 * sum).max(0.0)
}

/// The area of the picture of a convex body whose points `points` are not all strictly in
/// front of a perspective eye (see [`Picture::in_front`]), when they decide it: 0 when none is
/// (nothing of the body is in front), `f64::INFINITY` when some are and some are not (the
/// picture is unbounded); `None` when all are, or the view is orthographic, and the picture
/// has a finite area to compute.
///
/// ```
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::views::{Picture, View, projected_area::area_not_in_front};
/// let v = View::perspective(Point3::new(0.0, 0.0, 10.0), Point3::origin(), Vector3::y(), 60.0).unwrap();
/// let p = Picture::of(&v);
/// let (near, far) = (Point3::new(0.0, 0.0, 11.0), Point3::new(0.0, 0.0, 1.0));
/// assert_eq!(area_not_in_front(&p, &[near]), Some(0.0));
/// assert_eq!(area_not_in_front(&p, &[near, far]), Some(f64::INFINITY));
/// assert_eq!(area_not_in_front(&p, &[far]), None);
/// ```
pub fn area_not_in_front(picture: &Picture, points: &[Point3]) -> Option<f64> {
    if !picture.is_perspective() {
        return None;
    }
    let in_front = points.iter().filter(|p| picture.in_front(p)).count();
    if in_front == 0 {
        Some(0.0)
    } else if in_front < points.len() {
        Some(f64::INFINITY)
    } else {
        None
    }
}
