//! The visible and hidden runs of one line, gathered piece by piece as its pieces are decided
//! (see `pieces.rs`).

use super::EdgeClass;
use super::line::Line;
use super::marks::Mark;
use super::piece::Piece;

/// The visible and hidden runs of a line, piece by piece; the pieces a view that clips leaves
/// out are not runs.
pub(super) struct Runs {
    class: EdgeClass,
    /// The line's index in the pass.
    line: usize,
    /// Whether the line is clipped (see [`Line::clipped`]).
    clipped: bool,
    /// The picture of the line's first end.
    first: [f64; 2],
    out: Vec<Piece>,
    /// The current run.
    run: Option<Run>,
}

/// A run of pieces of one state along a line, from its start.
#[derive(Debug, Clone, Copy)]
pub(super) struct Run {
    /// `None` where the view clips the line away, else the run's visibility.
    state: Option<bool>,
    /// The picture of its start.
    start: [f64; 2],
    /// Its start's rough parameter and mark.
    from: (f64, Mark),
    /// Whether a tile's plane passes through its start.
    border: bool,
}

impl Runs {
    /// Runs of line `l` (index `line`), from its first end.
    pub(super) fn new(l: &Line, line: usize) -> Runs {
        Runs {
            class: l.class,
            line,
            clipped: l.clipped,
            first: l.ends[0],
            out: Vec::new(),
            run: None,
        }
    }

    /// The piece of the current run, ending at the picture `end` of the point `to`, where a
    /// tile's plane passes if `border`.
    pub(super) fn piece(
        &self,
        run: &Run,
        end: [f64; 2],
        to: (f64, Mark),
        border: bool,
    ) -> Option<Piece> {
        let visible = run.state?;
        Some(Piece {
            class: self.class,
            visible,
            ends: [run.start, end],
            line: self.line,
            t: [run.from.0, to.0],
            border: [run.border, border],
            marks: [run.from.1, to.1],
        })
    }

    /// The next piece's state, from the point `at` (where a tile's plane passes if `border`);
    /// where it changes, the run ends at the picture `picture` of the piece's start.
    pub(super) fn step(
        &mut self,
        state: Option<bool>,
        at: (f64, Mark),
        border: bool,
        picture: impl FnOnce() -> [f64; 2],
    ) {
        match self.run {
            Some(run) if run.state != state => {
                let start = picture();
                if let Some(p) = self.piece(&run, start, at, border) {
                    self.out.push(p);
                }
                self.run = Some(Run {
                    state,
                    start,
                    from: at,
                    border,
                });
            }
            None => {
                self.run = Some(Run {
                    state,
                    start: self.first,
                    from: (0.0, Mark::First),
                    border: false,
                })
            }
            _ => {}
        }
    }

    /// The runs, the last ending at `end`.
    pub(super) fn finish(mut self, end: [f64; 2]) -> Vec<Piece> {
        if let Some(run) = self.run
            && let Some(p) = self.piece(&run, end, (1.0, Mark::Last), false)
        {
            self.out.push(p);
        }
        if self.clipped {
            // A drawn end is inside the frustum, in front of the eye, so its picture is finite
            // but for a cut rounded onto an end: such a piece has no length to draw.
            self.out
                .retain(|p| p.ends.iter().flatten().all(|c| c.is_finite()));
        }
        self.out
    }
}
