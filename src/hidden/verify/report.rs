//! What the checks found: the [`Verification`] report and its [`Disagreement`]s, each naming
//! the [`Check`] it failed.

use super::{DESCRIBED, NEAR_END_ULPS};
use std::fmt;

/// Which check a disagreement failed.
///
/// ```
/// assert_eq!(kepler::hidden::verify::Check::Visibility.to_string(), "visibility");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// VISP at a sample point against the piece's visibility.
    Visibility,
    /// A silhouette edge (found by the sign test) drawn whole as silhouette pieces.
    Silhouette,
    /// A boundary edge drawn whole as boundary pieces.
    Boundary,
    /// The drawing's segments against the pieces.
    Drawing,
}

impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Check::Visibility => "visibility",
            Check::Silhouette => "silhouette",
            Check::Boundary => "boundary",
            Check::Drawing => "drawing",
        })
    }
}

/// One disagreement, described for a person.
///
/// ```
/// use kepler::hidden::verify::{Check, Disagreement};
/// let d = Disagreement {
///     check: Check::Visibility,
///     object: "cube".into(),
///     line: "edge v0–v1".into(),
///     at: "t = 0.25".into(),
///     expected: "hidden".into(),
///     found: "visible".into(),
/// };
/// assert_eq!(d.to_string(), "visibility: object 'cube', edge v0–v1, at t = 0.25: expected hidden, found visible");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Disagreement {
    /// The check.
    pub check: Check,
    /// The object's path (empty for a segment of the drawing).
    pub object: String,
    /// The line: an edge by its vertices, an intersection line by its faces, or a segment.
    pub line: String,
    /// Where on it.
    pub at: String,
    /// What the independent check says.
    pub expected: String,
    /// What the drawing has.
    pub found: String,
}

impl fmt::Display for Disagreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.check)?;
        if !self.object.is_empty() {
            write!(f, "object '{}', ", self.object)?;
        }
        write!(
            f,
            "{}, at {}: expected {}, found {}",
            self.line, self.at, self.expected, self.found
        )
    }
}

/// What [`verify`] checked and found.
///
/// ```
/// let v = kepler::hidden::verify::Verification::default();
/// assert_eq!((v.checks(), v.disagreements), (0, 0));
/// assert!(v.to_string().starts_with("verify: 0 checks, 0 disagreements"));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Verification {
    /// Sample points whose visibility VISP checked.
    pub samples: usize,
    /// Of those, samples whose line of sight passes exactly through an edge of a face that
    /// hides them (there the closed face hides, as the drawing's rule says).
    pub grazing: usize,
    /// Silhouette edges found by the sign test, each checked drawn whole.
    pub silhouettes: usize,
    /// Boundary edges, each checked drawn whole.
    pub boundaries: usize,
    /// Segments of the drawing matched with pieces.
    pub segments: usize,
    /// The number of disagreements.
    pub disagreements: usize,
    /// The first few of them ([`DESCRIBED`]).
    pub described: Vec<Disagreement>,
    /// Pieces of intersection lines, whose visibility is not checked yet.
    pub unchecked_intersections: usize,
    /// Samples not checked for lying within a few units in the last place of a piece's end.
    pub near_ends: usize,
    /// Edges the sign test does not decide: seen end-on, between two faces seen edge-on, or of
    /// more than two triangles; and, in a view that clips, contours not wholly inside its
    /// frustum.
    pub unchecked_edges: usize,
    /// The time the checks took, in seconds.
    pub seconds: f64,
}

impl Verification {
    /// The number of checks made.
    ///
    /// ```
    /// let v = kepler::hidden::verify::Verification { samples: 5, segments: 2, ..Default::default() };
    /// assert_eq!(v.checks(), 7);
    /// ```
    pub fn checks(&self) -> usize {
        self.samples + self.silhouettes + self.boundaries + self.segments
    }

    pub(super) fn disagree(&mut self, d: Disagreement) {
        self.disagreements += 1;
        if self.described.len() < DESCRIBED {
            self.described.push(d);
        }
    }
}

impl fmt::Display for Verification {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "verify: {} checks, {} disagreements ({:.3} s)",
            self.checks(),
            self.disagreements,
            self.seconds
        )?;
        writeln!(
            f,
            "verify: {} visibility samples by VISP ({} grazing a hiding face's edge), {} \
             silhouette and {} boundary edges drawn whole, {} drawing segments matched to pieces",
            self.samples, self.grazing, self.silhouettes, self.boundaries, self.segments
        )?;
        writeln!(
            f,
            "verify: not checked: {} intersection-line pieces (without their exact line), \
             {} samples within {NEAR_END_ULPS} ulps of a piece's end, {} edges end-on, between \
             faces edge-on or of more than two triangles",
            self.unchecked_intersections, self.near_ends, self.unchecked_edges
        )?;
        for d in &self.described {
            writeln!(f, "verify: disagreement: {d}")?;
        }
        if self.disagreements > self.described.len() {
            writeln!(
                f,
                "verify: ... and {} more disagreements",
                self.disagreements - self.described.len()
            )?;
        }
        Ok(())
    }
}
