//! Kepler's integration tests, in one test crate (one binary to compile and link instead of
//! one per file): one module per area, named as the file it lives in, and the helpers they
//! share in [`common`].
//!
//! `cargo test --release` runs the default suite (a few minutes on two cores). Cases that
//! take more than about 20 s in release are marked `#[ignore = "slow: …"]`; run them with
//!
//! ```text
//! cargo test --release -- --ignored
//! ```
//!
//! (or everything with `cargo test --release -- --include-ignored`). One module's tests:
//! `cargo test --release --test it <module>::`.
//!
//! Proptest keeps its regressions beside each module's source, as
//! `tests/it/<module>.proptest-regressions`.

mod common;

mod arithmetic;
#[cfg(feature = "lab")]
mod boxtree;
// The command line: needs the `kepler` binary, built only with the `cli` feature (a
// default feature, so plain `cargo test --release` runs these).
#[cfg(feature = "cli")]
mod cli;
#[cfg(feature = "cli")]
mod cli_index;
#[cfg(feature = "cli")]
mod cli_tiles;
#[cfg(feature = "lab")]
mod clip;
mod collinear_cuts;
mod crowds;
#[cfg(feature = "lab")]
mod culling;
mod cut_order;
mod dxf;
mod exact_values;
mod geometry;
mod grid;
mod hatch;
mod hidden_exact;
mod hidden_oracle;
mod inbox;
mod include;
mod intersection_lines;
mod io;
mod layering;
mod mesh;
mod near;
mod output;
mod plotter;
mod predicates;
#[cfg(feature = "lab")]
mod projected_area;
mod query_range;
mod range;
#[cfg(feature = "lab")]
mod report;
#[cfg(feature = "lab")]
mod report_reference;
mod scan;
mod scene;
mod scene_file;
mod scene_index;
mod solids;
#[cfg(feature = "lab")]
mod stiff;
mod surfaces;
mod surfaces_exact;
mod surfaces_near;
mod tiles;
mod tribox;
#[cfg(feature = "lab")]
mod triboxes;
#[cfg(feature = "lab")]
mod triboxes_exact;
mod verify;
mod visp;
