//! The 9 directions of the tribox and its 18 planes, defined once: every other spelling (the
//! floating-point directions, the plane normals, the diagonal sums, the projections of a
//! point, the local axes of a corner) is derived from [`DIRS`].
//!
//! The directions, in the paper's order, are x, y, z, x+y, x+z, y+z, x−z, y−x, z−y,
//! *unnormalised*. Plane `2d` is the lower bound of direction `d` (outward normal −d) and
//! plane `2d+1` its upper bound (outward normal +d).

use crate::geometry::Point3;

/// The 9 directions, in the paper's order, as integer vectors: the one definition.
pub(super) const DIRS: [[i8; 3]; 9] = [
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 1, 0],
    [1, 0, 1],
    [0, 1, 1],
    [1, 0, -1],
    [-1, 1, 0],
    [0, -1, 1],
];

/// The 9 directions as doubles (the value of
/// [`TriboxBounds::DIRECTIONS`](super::TriboxBounds::DIRECTIONS)).
pub(super) const DIRECTIONS: [[f64; 3]; 9] = {
    let mut t = [[0.0; 3]; 9];
    let mut d = 0;
    while d < 9 {
        t[d] = [DIRS[d][0] as f64, DIRS[d][1] as f64, DIRS[d][2] as f64];
        d += 1;
    }
    t
};

/// The outward normals of the 18 planes as doubles (the value of
/// [`Tribox::PLANE_NORMALS`](super::Tribox::PLANE_NORMALS)).
pub(super) const PLANE_NORMALS: [[f64; 3]; 18] = {
    let mut t = [[0.0; 3]; 18];
    let mut j = 0;
    while j < 18 {
        let n = normal(j);
        t[j] = [n[0] as f64, n[1] as f64, n[2] as f64];
        j += 1;
    }
    t
};

/// The two coordinates (with the sign of the second) whose sum is each diagonal direction
/// `3 + k`: the coordinate with coefficient +1 first (the first of two such), then the other,
/// `true` when its coefficient is −1. So x+y is `(0, 1, false)` and y−x is `(1, 0, true)`.
pub(super) const DIAGONAL_AXES: [(usize, usize, bool); 6] = {
    let mut t = [(0, 0, false); 6];
    let mut k = 0;
    while k < 6 {
        let d = DIRS[3 + k];
        let mut first = 3;
        let mut second = 3;
        let mut i = 0;
        while i < 3 {
            if d[i] == 1 && first == 3 {
                first = i;
            } else if d[i] != 0 {
                second = i;
            }
            i += 1;
        }
        t[k] = (first, second, d[second] < 0);
        k += 1;
    }
    t
};

/// The 9 projections of a point, diagonal ones rounded: x, y, z, then the sums of
/// [`DIAGONAL_AXES`] (x+y, x+z, y+z, x−z, y−x, z−y; `a + (−b)` is `a − b` in floating point).
#[inline(always)]
pub(super) fn projections(p: &Point3) -> [f64; 9] {
    let c = [p.x, p.y, p.z];
    let diagonal = |k: usize| {
        let (i, j, minus) = DIAGONAL_AXES[k];
        if minus { c[i] - c[j] } else { c[i] + c[j] }
    };
    [
        c[0],
        c[1],
        c[2],
        diagonal(0),
        diagonal(1),
        diagonal(2),
        diagonal(3),
        diagonal(4),
        diagonal(5),
    ]
}

/// The outward normal of plane `j` as an integer vector.
pub(super) const fn normal(j: usize) -> [i8; 3] {
    let d = DIRS[j / 2];
    if j % 2 == 1 { d } else { [-d[0], -d[1], -d[2]] }
}

/// The plane whose outward normal is `w` (evaluated at compile time only).
pub(super) const fn plane_of(w: [i8; 3]) -> u8 {
    let mut j = 0;
    while j < 18 {
        let n = normal(j);
        if n[0] == w[0] && n[1] == w[1] && n[2] == w[2] {
            return j as u8;
        }
        j += 1;
    }
    panic!("not a tribox normal")
}

/// `CHAMFER_PARENTS[j]`: for a chamfer plane j (6..18), the two principal planes whose normals
/// add up to its normal (its bound is redundant when at least the sum of theirs).
pub(super) const CHAMFER_PARENTS: [[u8; 2]; 18] = {
    let mut t = [[0u8; 2]; 18];
    let mut j = 6;
    while j < 18 {
        let n = normal(j);
        let mut found = 0;
        let mut i = 0;
        while i < 3 {
            if n[i] != 0 {
                let mut e = [0i8; 3];
                e[i] = n[i];
                t[j][found] = plane_of(e);
                found += 1;
            }
            i += 1;
        }
        j += 1;
    }
    t
};

/// The Euclidean length of plane j's normal: 1 for principal planes, √2 for chamfers.
pub(super) fn normal_norm(j: usize) -> f64 {
    if j < 6 { 1.0 } else { std::f64::consts::SQRT_2 }
}

/// Checks of the derived tables.
#[cfg(test)]
mod tests {
    use super::*;

    /// The derived table is the one once written out.
    #[test]
    fn diagonal_axes_are_the_diagonal_directions() {
        assert_eq!(
            DIAGONAL_AXES,
            [
                (0, 1, false),
                (0, 2, false),
                (1, 2, false),
                (0, 2, true),
                (1, 0, true),
                (2, 1, true),
            ]
        );
    }
}
