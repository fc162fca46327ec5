//! A piece: a visible or hidden stretch of one line of the pass, in picture coordinates, with
//! what its ends are exactly; what the stages hand on to overlap removal, chaining and tiles.

use super::EdgeClass;
use super::marks::Mark;

/// A visible or hidden piece of an edge, in picture coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece {
    /// The class of its edge.
    pub class: EdgeClass,
    /// Whether it is visible.
    pub visible: bool,
    /// Its ends.
    pub ends: [[f64; 2]; 2],
    /// The index of its line in the pass, and its range of the line's parameter `t` (where
    /// `X(t) = a + t·(b - a)`): what [`super::verify`] checks it by.
    pub line: usize,
    /// See `line`.
    pub t: [f64; 2],
    /// Whether a tile's plane passes through each end (see [`super::tiles`]).
    pub border: [bool; 2],
    /// What its ends are, exactly (see [`super::marks`]).
    pub marks: [Mark; 2],
}
