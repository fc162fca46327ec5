//! Stage 5 of the pass: the pieces finished (hidden ones dropped unless asked for, each
//! stretch of line once unless overlaps are kept) and chained into the drawing.

use super::chain::chain;
use super::marks;
use super::pass::Pass;
use super::piece::Piece;
use super::{Drawing, Options, OverlapReport, Overlaps, overlaps};
use std::time::Instant;

/// Stage 5 of the pass: the drawing chained from the pieces, each stretch of line once when
/// the options ask for it. The pass keeps the stages' reports.
pub(super) fn chained(pass: &mut Pass, pieces: Vec<Piece>, options: &Options) -> Drawing {
    let clock = Instant::now();
    let (pieces, report) = finished(&*pass, pieces, options);
    match report {
        Some(r) => {
            let done = format!(
                "{} groups of {} segments on one line drawn once ({:.6} of line no longer drawn \
                 twice)",
                r.groups, r.segments, r.removed_length
            );
            pass.stage("overlaps", clock, done, None);
        }
        None => {
            let skipped = "each stretch drawn once (asked to keep overlapping pieces)";
            pass.stage("overlaps", clock, String::new(), Some(skipped.to_string()));
        }
    }
    let clock = Instant::now();
    let polylines = chain(&pieces);
    pass.stage(
        "chains",
        clock,
        format!("{} polylines from {} runs", polylines.len(), pieces.len()),
        (!options.hidden).then(|| "hidden pieces (not asked for)".to_string()),
    );
    Drawing {
        polylines,
        stages: pass.stages.clone(),
    }
}

/// The pieces a drawing chains: hidden ones dropped unless the options ask for them, each
/// stretch of a picture line once when they ask for that (with what was removed).
pub(super) fn finished<P: marks::Provenance>(
    provenance: &P,
    mut pieces: Vec<Piece>,
    options: &Options,
) -> (Vec<Piece>, Option<OverlapReport>) {
    if !options.hidden {
        pieces.retain(|p| p.visible);
    }
    match options.overlaps {
        Overlaps::Once => {
            let (pieces, report) = overlaps::drawn_once(provenance, pieces);
            (pieces, Some(report))
        }
        Overlaps::Keep => (pieces, None),
    }
}
