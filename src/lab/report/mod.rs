//! Error against run time: the exact engine beside cheaper arithmetic and sampled answers.

pub mod chart;
pub mod measure;
pub mod reference;
pub mod variants;
