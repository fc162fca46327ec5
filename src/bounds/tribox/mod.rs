//! The tribox of Crosnier and Rossignac (1999): the intersection of 18 half-spaces, the slabs
//! bounding the projections of a point set on 9 fixed directions, and its boundary.
//!
//! The directions, in the paper's order, are x, y, z, x+y, x+z, y+z, x−z, y−x, z−y. They are
//! *unnormalised*: the projection of (x, y, z) on x+y is x+y. Plane `2d` is the lower bound of
//! direction `d` (outward normal −d) and plane `2d+1` its upper bound (outward normal +d); this
//! is the order of [`TriboxBounds::to_array18`] and of the faces of a [`Tribox`].
//!
//! # Exactness
//! Axis bounds are coordinates, hence exact. A diagonal bound is the smallest double at least
//! (largest at most) the exact extreme projection, so no input point is ever cut off.
//! [`TriboxBounds::contains_point`] decides every inequality exactly. The boundary
//! ([`TriboxBounds::boundary`]) is the paper's corner classification with every sign decided
//! exactly ([`crate::geometry::exact::sum_sign`]) and every vertex coordinate the
//! correctly rounded value of an exact sum of at most a few bounds
//! ([`crate::geometry::exact::accurate_sum`]). It is exactly the intersection of
//! the 18 half-spaces when every bounding plane touches that intersection, as exact bounds of
//! points do; a diagonal bound rounded outward can miss it by less than an ulp and leave an
//! ulp-thin sliver face. [`Tribox::cleaned`] tightens such bounds symbolically first and is
//! always the exact intersection.
//!
//! # Boundary evaluation (paper section 3)
//! Each of the 8 corners of the block B (the axis-aligned box) is reflected to the canonical
//! corner (max x, max y, max z) by coordinate signs. There the six planes are the principal
//! planes h_A: X ≤ α_A, h_B: Y ≤ α_B, h_C: Z ≤ α_C and the chamfer planes h_AB: X+Y ≤ α_AB,
//! h_AC: X+Z ≤ α_AC, h_BC: Y+Z ≤ α_BC, each α the maximum of its signed combination. A chamfer
//! with α_AB ≥ α_A + α_B cannot cut the block and is *clamped*: its effective bound is the
//! two-term sum α_A + α_B, kept symbolic so that later formulas cancel exactly. The point p
//! where the three chamfers meet is then outside at most one principal plane: case 1 (inside
//! all), case 2 (beyond h_A), case 3 (beyond h_B), case 4 (beyond h_C). Each corner yields four
//! vertices and one sub-list per incident face; face loops concatenate their corners' sub-lists.
//!
//! The case tests compare the correctly rounded doubled coordinates of p, which case 1 needs
//! anyway, with twice the principal bounds (rounding is monotone), and take the exact sign of the
//! test only when they are equal. With no chamfer clamped, the 8 corners are first evaluated
//! together for case 1 (vectorisable lanes), and corner by corner only when a corner is in
//! another case or a sum needs exact arithmetic.
//!
//! # What a tribox is
//! An axis-aligned box bounds a set by 6 planes along 3 directions; a tribox adds the 6
//! face diagonals of the cube, so 18 planes along 9 directions (Crosnier and Rossignac, 1999).
//! It cuts off the box's edges and corners with chamfers and hugs a diagonal object far
//! better, yet stays as cheap to compute and to compare as a box: its parameters are the
//! extremes of 9 projections, two triboxes overlap only if their 9 slabs do, and the
//! boundary of every tribox has the same combinatorial shape, read from fixed tables.
//!
//! # Steps
//! 1. [`directions`]: the 9 directions and 18 planes, defined once.
//! 2. [`slabs`]: [`TriboxBounds`], the 18 bounds of a point set (exact, rounded outward), and
//!    the set operations on them.
//! 3. [`cases`] and [`faces`]: the corner numbering, the four cases of a corner and the face
//!    loops of every combination of cases, all tabulated at compile time.
//! 4. [`forms`] and [`corners`]: each corner classified and its four vertices computed from
//!    simplified formulas with exact signs and correctly rounded coordinates.
//! 5. [`polytope`]: [`Tribox`], the raw boundary assembled from the corners, with its
//!    vertices, faces, volume and area.
//! 6. [`cleanup`] (with [`support`]): the exact polytope, bounds tightened symbolically,
//!    equal vertices merged and degenerate faces dropped; and the simplified tribox.
//!
//! # Complexity
//! Bounds take one pass over the points, O(n) (9 projections per point; exact error terms
//! only for points at a diagonal extreme), in parallel with
//! [`TriboxBounds::par_from_points`]. The boundary is O(1): 8 corners, 32 vertices, 18 faces,
//! with no search (tables fixed at compile time). Clean-up is O(1) too, at most 18 supports
//! of 36 to 40 candidate dual bases each and 32² vertex comparisons.
//!
//! ```
//! use kepler::bounds::tribox::TriboxBounds;
//! use kepler::geometry::Point3;
//! let pts = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0), Point3::new(1.0, 0.0, 0.0)];
//! let bounds = TriboxBounds::from_points(&pts);
//! assert!(pts.iter().all(|p| bounds.contains_point(p)));
//! let tribox = bounds.boundary().cleaned();
//! assert_eq!(tribox.vertices().len(), 3);
//! assert_eq!(tribox.face_count(), 2); // a flat triangle: its two sides
//! assert_eq!(tribox.volume(), 0.0);
//! ```

/// Step 3: corner numbering and the four cases.
mod cases;
/// Step 6: the exact, cleaned and simplified polytope.
mod cleanup;
/// Step 4: each corner's case and vertices.
mod corners;
/// Step 1: the 9 directions and 18 planes.
mod directions;
/// Step 3: the face loops of every combination of cases.
mod faces;
/// Step 4: the corner formulas as simplified forms.
mod forms;
/// Step 5: the raw boundary.
mod polytope;
/// Step 2: the bounds of a point set.
mod slabs;
/// Step 6: exact forms in the offsets and supports by duality.
mod support;
/// Randomised checks of the corner formulas.
#[cfg(test)]
mod tests;

pub use polytope::Tribox;
pub use slabs::TriboxBounds;
