//! Charts of the report (SVG, with plotters).
