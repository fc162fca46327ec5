//! The result of the hidden-line pass: classified polylines in view coordinates.

use crate::geometry::exact::ldexp;
use serde::Serialize;

/// What an edge of a drawing is (see the module documentation of [`crate::hidden`]).
///
/// ```
/// use kepler::hidden::EdgeClass;
/// assert_eq!(EdgeClass::Silhouette.name(), "silhouette");
/// assert_eq!(EdgeClass::ALL.len(), 5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum EdgeClass {
    /// Between a face turned towards the eye and one turned away (both faces on the same side
    /// of the edge in the picture), or an edge of a face seen edge-on.
    Silhouette,
    /// An edge of only one face (an open mesh's rim).
    Boundary,
    /// Between two faces meeting at a dihedral angle sharper than the crease angle.
    Crease,
    /// Where two faces pierce each other.
    Intersection,
    /// Any other edge between two faces that are not coplanar.
    Smooth,
}

impl EdgeClass {
    /// Every class, in drawing order (smooth first, so that feature lines are drawn on top).
    pub const ALL: [EdgeClass; 5] = [
        EdgeClass::Smooth,
        EdgeClass::Crease,
        EdgeClass::Intersection,
        EdgeClass::Boundary,
        EdgeClass::Silhouette,
    ];

    /// The class's name in SVG layer ids and JSON: `silhouette`, `boundary`, `crease`,
    /// `intersection` or `smooth`.
    ///
    /// ```
    /// assert_eq!(kepler::hidden::EdgeClass::Intersection.name(), "intersection");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            EdgeClass::Silhouette => "silhouette",
            EdgeClass::Boundary => "boundary",
            EdgeClass::Crease => "crease",
            EdgeClass::Intersection => "intersection",
            EdgeClass::Smooth => "smooth",
        }
    }
}

/// A maximal chain of visible (or of hidden) pieces of edges of one class, in view
/// coordinates: `x` to the right and `y` up in the picture, in scene units for an
/// orthographic view (see [`crate::hidden`] for perspective).
///
/// ```
/// use kepler::hidden::{EdgeClass, Polyline};
/// let p = Polyline { class: EdgeClass::Crease, visible: true, points: vec![[0.0, 0.0], [3.0, 4.0]] };
/// assert_eq!(p.length(), 5.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Polyline {
    /// The class of the edges.
    pub class: EdgeClass,
    /// Whether the pieces are visible (else hidden).
    pub visible: bool,
    /// The vertices, at least two; a closed chain repeats its first vertex at the end.
    pub points: Vec<[f64; 2]>,
}

impl Polyline {
    /// The length of the polyline in view coordinates.
    ///
    /// ```
    /// use kepler::hidden::{EdgeClass, Polyline};
    /// let p = Polyline { class: EdgeClass::Boundary, visible: false, points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]] };
    /// assert_eq!(p.length(), 2.0);
    /// ```
    pub fn length(&self) -> f64 {
        self.points
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum()
    }
}

/// A hidden-line drawing: its polylines, and a record of the work done.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// let d = Drawing {
///     polylines: vec![Polyline { class: EdgeClass::Silhouette, visible: true, points: vec![[0.0, 0.0], [2.0, 0.0]] }],
///     stages: Vec::new(),
/// };
/// assert_eq!(d.length(EdgeClass::Silhouette, true), 2.0);
/// assert_eq!(d.length(EdgeClass::Silhouette, false), 0.0);
/// assert_eq!(d.bounds(), Some(([0.0, 0.0], [2.0, 0.0])));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drawing {
    /// The polylines, grouped by class (in [`EdgeClass::ALL`] order) and visibility.
    pub polylines: Vec<Polyline>,
    /// What each stage of the pass computed or skipped, and its time.
    #[serde(skip)]
    pub stages: Vec<StageReport>,
}

impl Drawing {
    /// The drawing with every point multiplied by `2^exponent` (exactly, unless a coordinate
    /// overflows or leaves the normal range). A segment whose ends become equal (its picture
    /// below the smallest subnormal, say) is left out, as the pass leaves out pieces of zero
    /// length: consecutive equal points are taken once, and a polyline left with a single point
    /// is dropped. So the drawing never holds a segment of zero length.
    ///
    /// ```
    /// use kepler::hidden::{Drawing, EdgeClass, Polyline};
    /// let p = Polyline { class: EdgeClass::Boundary, visible: true, points: vec![[0.0, 0.0], [1.0, 3.0]] };
    /// let d = Drawing { polylines: vec![p], stages: Vec::new() }.scaled(-1);
    /// assert_eq!(d.polylines[0].points[1], [0.5, 1.5]);
    /// // 2^-1074 is the smallest subnormal: half of it rounds to 0.
    /// let tiny = f64::from_bits(1);
    /// let p = |points| Polyline { class: EdgeClass::Silhouette, visible: true, points };
    /// let d = Drawing {
    ///     polylines: vec![p(vec![[0.0, 0.0], [tiny, 0.0]]), p(vec![[0.0, 0.0], [tiny, 0.0], [4.0, 0.0]])],
    ///     stages: Vec::new(),
    /// };
    /// assert_eq!(d.scaled(-1).polylines, vec![p(vec![[0.0, 0.0], [2.0, 0.0]])]);
    /// ```
    pub fn scaled(mut self, exponent: i32) -> Drawing {
        for p in &mut self.polylines {
            for q in &mut p.points {
                *q = q.map(|x| ldexp(x, exponent));
            }
            // Equal as numbers (`-0.0 == 0.0`), as the pass compares a piece's ends.
            p.points.dedup_by(|q, r| q == r);
        }
        self.polylines.retain(|p| p.points.len() >= 2);
        self
    }

    /// The total length of the polylines of one class and visibility, in view coordinates.
    ///
    /// ```
    /// let d = kepler::hidden::Drawing { polylines: Vec::new(), stages: Vec::new() };
    /// assert_eq!(d.length(kepler::hidden::EdgeClass::Crease, true), 0.0);
    /// ```
    pub fn length(&self, class: EdgeClass, visible: bool) -> f64 {
        self.polylines
            .iter()
            .filter(|p| p.class == class && p.visible == visible)
            .map(Polyline::length)
            .fold(0.0, |total, l| total + l)
    }

    /// Every segment of the drawing (consecutive vertices of a polyline) with its polyline's
    /// class and visibility, in order.
    ///
    /// ```
    /// use kepler::hidden::{Drawing, EdgeClass, Polyline};
    /// let d = Drawing {
    ///     polylines: vec![Polyline { class: EdgeClass::Crease, visible: false, points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 2.0]] }],
    ///     stages: Vec::new(),
    /// };
    /// let s: Vec<_> = d.segments().collect();
    /// assert_eq!(s[1], (EdgeClass::Crease, false, [[1.0, 0.0], [1.0, 2.0]]));
    /// ```
    pub fn segments(&self) -> impl Iterator<Item = (EdgeClass, bool, [[f64; 2]; 2])> + '_ {
        self.polylines.iter().flat_map(|p| {
            p.points
                .windows(2)
                .map(move |w| (p.class, p.visible, [w[0], w[1]]))
        })
    }

    /// The smallest box `(min, max)` holding every polyline vertex, or `None` for an empty
    /// drawing.
    ///
    /// ```
    /// let d = kepler::hidden::Drawing { polylines: Vec::new(), stages: Vec::new() };
    /// assert_eq!(d.bounds(), None);
    /// ```
    pub fn bounds(&self) -> Option<([f64; 2], [f64; 2])> {
        let mut points = self.polylines.iter().flat_map(|p| p.points.iter());
        let first = *points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        }))
    }
}

/// One stage of the hidden-line pass as `--stats` reports it.
///
/// ```
/// let s = kepler::hidden::StageReport { name: "grid", done: "1,204 crossings".into(), skipped: None, seconds: 0.002 };
/// assert_eq!(s.name, "grid");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StageReport {
    /// The stage.
    pub name: &'static str,
    /// What it computed.
    pub done: String,
    /// What it left out and why, if anything.
    pub skipped: Option<String>,
    /// Its wall-clock time.
    pub seconds: f64,
}
