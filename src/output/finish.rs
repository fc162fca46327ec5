//! Finishing a drawing for a pen plotter: the one step between the drawing pass and the
//! writers, shared by `kepler render` and the Python package (`kepler.render(order=…)`).
//!
//! Two things make a drawing plotter-ready. Each stretch of line drawn once (touching
//! objects, T-junctions, a line right behind a contour) is decided **inside** the pass
//! ([`crate::hidden::Options::overlaps`]): whether two pieces lie on one line is an exact
//! predicate on the input edges or the meet lines of planes they come from, and that
//! description is gone once pieces are chained into polylines of rounded points; deciding
//! it here, from output points, would be the kind of decision from rounded output that
//! breaks exactness. What is left for after the pass is the order of paths: [`finish`]
//! reorders and turns each layer's paths ([`ordered`]) when asked, which moves no point,
//! and measures the pen's travel before and after ([`pen_travel`]).
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline};
//! use kepler::output::{Finishing, finish};
//! let line = |a: [f64; 2], b: [f64; 2]| Polyline {
//!     class: EdgeClass::Silhouette, visible: true, points: vec![a, b],
//! };
//! let drawing = Drawing {
//!     polylines: vec![line([0.0, 0.0], [1.0, 0.0]), line([5.0, 0.0], [6.0, 0.0]), line([2.0, 0.0], [1.0, 0.0])],
//!     stages: Vec::new(),
//! };
//! let finished = finish(drawing, &Finishing { order: true });
//! assert_eq!((finished.travel_before, finished.travel_after), (8.0, Some(3.0)));
//! assert_eq!(finished.drawing.polylines[1].points, vec![[1.0, 0.0], [2.0, 0.0]]);
//! ```

use super::order::{ordered, pen_travel};
use crate::hidden::Drawing;
use std::time::Instant;

/// How a drawing is finished after the pass (see the [module documentation](self)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Finishing {
    /// Order and turn each layer's paths to shorten the pen's travel (`kepler render --order`).
    pub order: bool,
}

/// A drawing as it is written, and what finishing it did.
#[derive(Clone, Debug)]
pub struct Finished {
    /// The drawing to write.
    pub drawing: Drawing,
    /// The pen's travel between paths in the pass's order (view coordinates).
    pub travel_before: f64,
    /// The travel after ordering, when the paths were ordered.
    pub travel_after: Option<f64>,
    /// The time finishing took, in seconds.
    pub seconds: f64,
}

impl Finished {
    /// The `--stats` line of `kepler render` for this step (ending in a newline).
    pub fn stats(&self) -> String {
        let before = self.travel_before;
        match self.travel_after {
            Some(after) => format!(
                "order          {:>7.4}  pen travel between paths {before:.6} -> {after:.6} \
                 (view coordinates)\n",
                self.seconds
            ),
            None => format!(
                "order          {:>7}  skipped: pen travel between paths {before:.6} (--order \
                 shortens it)\n",
                ""
            ),
        }
    }
}

/// The drawing finished as `finishing` asks: its paths in pen order when asked, every point
/// the same double as drawn.
pub fn finish(drawing: Drawing, finishing: &Finishing) -> Finished {
    let clock = Instant::now();
    let travel_before = pen_travel(&drawing);
    let (drawing, travel_after) = if finishing.order {
        let drawing = ordered(&drawing);
        let after = pen_travel(&drawing);
        (drawing, Some(after))
    } else {
        (drawing, None)
    };
    Finished {
        drawing,
        travel_before,
        travel_after,
        seconds: clock.elapsed().as_secs_f64(),
    }
}
