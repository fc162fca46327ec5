//! Error against run time: the exact engine beside cheaper arithmetic and sampled answers.
//!
//! - [`measure`]: how wrong a drawing is against the exact one: lengths drawn with the wrong
//!   visibility, missing or extra, the Hausdorff distance between vertices, wrong ends of runs.
//! - [`chart`]: SVG charts of those figures, log-log and semi-log, with exact variants on a
//!   floor line.

pub mod chart;
pub mod measure;
pub mod reference;
pub mod variants;
