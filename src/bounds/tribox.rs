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

use std::cmp::Ordering;
use std::sync::OnceLock;

use rayon::prelude::*;
use serde::{Serialize, Serializer};

use crate::geometry::exact::{
    accurate_sum, accurate_sum_array, accurate_sum3_lanes, sum_sign, sum_sign_array, two_sum,
};
use crate::geometry::{Point3, Vector3};

/// The 9 directions, in the paper's order, as integer vectors.
const DIRS: [[i8; 3]; 9] = [
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

/// The two coordinates (with the sign of the second) whose sum is each diagonal direction.
const DIAGONAL_AXES: [(usize, usize, bool); 6] = [
    (0, 1, false),
    (0, 2, false),
    (1, 2, false),
    (0, 2, true),
    (1, 0, true),
    (2, 1, true),
];

/// The 9 projections of a point, diagonal ones rounded.
#[inline(always)]
fn projections(p: &Point3) -> [f64; 9] {
    let (x, y, z) = (p.x, p.y, p.z);
    [x, y, z, x + y, x + z, y + z, x - z, y - x, z - y]
}

/// The most vertices a raw boundary has: four per corner.
const MAX_VERTICES: usize = 32;
/// The longest face loop: 4 corners × 2 vertices (principal) or 2 corners × 4 (chamfer).
const MAX_FACE: usize = 8;

/// The outward normal of plane `j` as an integer vector.
const fn normal(j: usize) -> [i8; 3] {
    let d = DIRS[j / 2];
    if j % 2 == 1 { d } else { [-d[0], -d[1], -d[2]] }
}

/// The plane whose outward normal is `w` (evaluated at compile time only).
const fn plane_of(w: [i8; 3]) -> u8 {
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

/// The signs (sx, sy, sz) of corner `c`: bit i set means the minimum along axis i.
const fn corner_signs(c: usize) -> [i8; 3] {
    [
        if c & 1 == 0 { 1 } else { -1 },
        if c & 2 == 0 { 1 } else { -1 },
        if c & 4 == 0 { 1 } else { -1 },
    ]
}

/// The corner with signs `s`.
const fn corner_of(s: [i8; 3]) -> usize {
    (s[0] < 0) as usize | ((s[1] < 0) as usize) << 1 | ((s[2] < 0) as usize) << 2
}

/// Local planes of the canonical corner: A, B, C, AB, AC, BC, as vectors in the reflected frame.
const LOCAL_AXES: [[i8; 3]; 6] = [
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 1, 0],
    [1, 0, 1],
    [0, 1, 1],
];
const A: usize = 0;
const B: usize = 1;
const C: usize = 2;
const AB: usize = 3;
const AC: usize = 4;
const BC: usize = 5;

/// `CORNER_PLANES[c][k]`: the global plane of local plane k (A, B, C, AB, AC, BC) at corner c.
const CORNER_PLANES: [[u8; 6]; 8] = {
    let mut t = [[0u8; 6]; 8];
    let mut c = 0;
    while c < 8 {
        let s = corner_signs(c);
        let mut k = 0;
        while k < 6 {
            let l = LOCAL_AXES[k];
            t[c][k] = plane_of([l[0] * s[0], l[1] * s[1], l[2] * s[2]]);
            k += 1;
        }
        c += 1;
    }
    t
};

/// `CHAMFER_PARENTS[j]`: for a chamfer plane j (6..18), the two principal planes whose normals
/// add up to its normal (its bound is redundant when at least the sum of theirs).
const CHAMFER_PARENTS: [[u8; 2]; 18] = {
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

/// `FACE_CORNERS[j]`: the (corner, local plane) pairs incident to plane j, counter-clockwise
/// seen from outside; principal planes have 4, chamfer planes 2 (their order is then immaterial).
const FACE_CORNERS: [([(u8, u8); 4], u8); 18] = {
    let mut t = [([(0u8, 0u8); 4], 0u8); 18];
    let mut j = 0;
    while j < 18 {
        let n = normal(j);
        if j < 6 {
            let i = j / 2;
            // Offset of a corner from the face centre, rotated by +90° about n each step.
            let mut r = [1i8; 3];
            r[i] = 0;
            let mut step = 0;
            while step < 4 {
                let s = [n[0] + r[0], n[1] + r[1], n[2] + r[2]];
                t[j].0[step] = (corner_of(s) as u8, i as u8);
                r = [
                    n[1] * r[2] - n[2] * r[1],
                    n[2] * r[0] - n[0] * r[2],
                    n[0] * r[1] - n[1] * r[0],
                ];
                step += 1;
            }
            t[j].1 = 4;
        } else {
            let free = if n[0] == 0 {
                0
            } else if n[1] == 0 {
                1
            } else {
                2
            };
            let local = [BC, AC, AB][free];
            let mut s = n;
            s[free] = 1;
            t[j].0[0] = (corner_of(s) as u8, local as u8);
            s[free] = -1;
            t[j].0[1] = (corner_of(s) as u8, local as u8);
            t[j].1 = 2;
        }
        j += 1;
    }
    t
};

/// Per case (1..4, index case − 1): the local planes defining each of the corner's 4 vertex
/// slots, and each local face's sub-list of slots (counter-clockwise seen from outside in the
/// canonical frame). Case 1 slots: v1, v2, v3, p; case 2 slots: v1, v3, q2 = A∩AC∩BC and
/// q3 = A∩AB∩BC (the paper's v'_2 and v''_3).
struct CaseTable {
    slot_planes: [[usize; 3]; 4],
    sub_lists: [SubList; 6],
}

const CASE1: CaseTable = CaseTable {
    slot_planes: [[C, AC, BC], [A, AB, AC], [B, AB, BC], [AB, AC, BC]],
    // A: [v2]; B: [v3]; C: [v1]; AB: [v3, p, v2]; AC: [v2, p, v1]; BC: [v1, p, v3].
    sub_lists: [
        ([1, 0, 0, 0], 1),
        ([2, 0, 0, 0], 1),
        ([0, 0, 0, 0], 1),
        ([2, 3, 1, 0], 3),
        ([1, 3, 0, 0], 3),
        ([0, 3, 2, 0], 3),
    ],
};

const CASE2: CaseTable = CaseTable {
    slot_planes: [[C, AC, BC], [B, AB, BC], [A, AC, BC], [A, AB, BC]],
    // A: [q3, q2]; B: [v3]; C: [v1]; AB: [v3, q3]; AC: [q2, v1]; BC: [v1, q2, q3, v3].
    sub_lists: [
        ([3, 2, 0, 0], 2),
        ([1, 0, 0, 0], 1),
        ([0, 0, 0, 0], 1),
        ([1, 3, 0, 0], 2),
        ([2, 0, 0, 0], 2),
        ([0, 2, 3, 1], 4),
    ],
};

/// The cyclic rotation x→y→z→x of the local planes: in the rotated frame, local plane k is the
/// original local plane `ROTATION[k]` (A' = B, B' = C, C' = A, A'B' = BC, A'C' = AB, B'C' = AC).
/// It preserves orientation, so cases 3 and 4 are case 2 seen in the once- and twice-rotated
/// frames.
const ROTATION: [usize; 6] = [B, C, A, BC, AB, AC];
const ROTATION2: [usize; 6] = [C, A, B, AC, BC, AB];

const fn rotate_case(t: &CaseTable, sigma: [usize; 6]) -> CaseTable {
    let mut slot_planes = [[0; 3]; 4];
    let mut s = 0;
    while s < 4 {
        let mut k = 0;
        while k < 3 {
            slot_planes[s][k] = sigma[t.slot_planes[s][k]];
            k += 1;
        }
        s += 1;
    }
    let mut sub_lists = [([0; 4], 0); 6];
    let mut f = 0;
    while f < 6 {
        sub_lists[sigma[f]] = t.sub_lists[f];
        f += 1;
    }
    CaseTable {
        slot_planes,
        sub_lists,
    }
}

const CASES: [CaseTable; 4] = [
    CASE1,
    CASE2,
    rotate_case(&CASE2, ROTATION),
    rotate_case(&CASE2, ROTATION2),
];

/// `VERTEX_PLANES[c][case][slot]`: the global planes (ascending) defining a corner's vertex.
const VERTEX_PLANES: [[[[u8; 3]; 4]; 4]; 8] = {
    let mut t = [[[[0u8; 3]; 4]; 4]; 8];
    let mut c = 0;
    while c < 8 {
        let mut k = 0;
        while k < 4 {
            let mut s = 0;
            while s < 4 {
                let l = CASES[k].slot_planes[s];
                let mut p = [
                    CORNER_PLANES[c][l[0]],
                    CORNER_PLANES[c][l[1]],
                    CORNER_PLANES[c][l[2]],
                ];
                // Sort three.
                if p[0] > p[1] {
                    p = [p[1], p[0], p[2]];
                }
                if p[1] > p[2] {
                    p = [p[0], p[2], p[1]];
                }
                if p[0] > p[1] {
                    p = [p[1], p[0], p[2]];
                }
                t[c][k][s] = p;
                s += 1;
            }
            k += 1;
        }
        c += 1;
    }
    t
};

/// A sub-list: up to 4 vertex indices (unused entries 0) and its length.
type SubList = ([u8; 4], u8);

/// `SUB_LISTS[c][case][local]`: a corner's sub-list for a local face as global vertex indices
/// (4c + slot), reversed at corners whose reflection reverses orientation (sx·sy·sz = −1).
const SUB_LISTS: [[[SubList; 6]; 4]; 8] = {
    let mut t = [[[([0u8; 4], 0u8); 6]; 4]; 8];
    let mut c = 0;
    while c < 8 {
        let s = corner_signs(c);
        let reverse = s[0] * s[1] * s[2] < 0;
        let mut k = 0;
        while k < 4 {
            let mut f = 0;
            while f < 6 {
                let (list, len) = CASES[k].sub_lists[f];
                let mut out = [0u8; 4];
                let mut i = 0;
                while i < len as usize {
                    let slot = if reverse {
                        list[len as usize - 1 - i]
                    } else {
                        list[i]
                    };
                    out[i] = 4 * c as u8 + slot;
                    i += 1;
                }
                t[c][k][f] = (out, len);
                f += 1;
            }
            k += 1;
        }
        c += 1;
    }
    t
};

/// The loop of face j for the cases of its corners (in [`FACE_CORNERS`] order) encoded as
/// `combo = Σ (case_i − 1) << 2i`: 8 packed vertex indices (byte i the i-th) and its length
/// (evaluated at compile time only).
const fn face_loop(j: usize, combo: usize) -> (u64, u8) {
    let (list, n) = FACE_CORNERS[j];
    let mut packed = 0u64;
    let mut len = 0;
    let mut i = 0;
    while i < n as usize {
        let (c, local) = list[i];
        let case = (combo >> (2 * i)) & 3;
        let (sub, m) = SUB_LISTS[c as usize][case][local as usize];
        let mut k = 0;
        while k < m as usize {
            packed |= (sub[k] as u64) << (8 * len);
            len += 1;
            k += 1;
        }
        i += 1;
    }
    (packed, len)
}

/// Face loops ([`face_loop`]) tabulated for every combination of cases, combination first so
/// that the loops of one combination share cache lines (a table per face, 4 KiB apart, put
/// every face's usual loop in the same cache set): `loops[combo][j]` and `lens[combo][j]` for
/// the `F` faces from plane `first` on, whose `n` corners give `4^n` combinations.
struct FaceLoops<const F: usize, const COMBOS: usize> {
    loops: [[u64; F]; COMBOS],
    lens: [[u8; F]; COMBOS],
}

impl<const F: usize, const COMBOS: usize> FaceLoops<F, COMBOS> {
    const fn new(first: usize) -> Self {
        let mut t = FaceLoops {
            loops: [[0; F]; COMBOS],
            lens: [[0; F]; COMBOS],
        };
        let mut combo = 0;
        while combo < COMBOS {
            let mut j = 0;
            while j < F {
                assert!(1 << (2 * FACE_CORNERS[first + j].1 as usize) == COMBOS);
                let (packed, len) = face_loop(first + j, combo);
                t.loops[combo][j] = packed;
                t.lens[combo][j] = len;
                j += 1;
            }
            combo += 1;
        }
        t
    }
}

/// The loops of the 6 principal faces (4 corners each).
static PRINCIPAL_LOOPS: FaceLoops<6, 256> = FaceLoops::new(0);
/// The loops of the 12 chamfer faces (2 corners each).
static CHAMFER_LOOPS: FaceLoops<12, 16> = FaceLoops::new(6);

/// The vertex planes and face loops of a boundary, as [`Tribox`] stores them.
struct Topology {
    vertex_planes: [[[u8; 3]; 4]; 8],
    faces: [[u8; MAX_FACE]; 18],
    face_len: [u8; 18],
}

/// The topology of the generic boundary, every corner in case 1 (combination 0 of every face).
static GENERIC: Topology = {
    let mut t = Topology {
        vertex_planes: [[[0; 3]; 4]; 8],
        faces: [[0; MAX_FACE]; 18],
        face_len: [0; 18],
    };
    let mut c = 0;
    while c < 8 {
        t.vertex_planes[c] = VERTEX_PLANES[c][0];
        c += 1;
    }
    let mut j = 0;
    while j < 18 {
        let (packed, len) = face_loop(j, 0);
        t.faces[j] = packed.to_le_bytes();
        t.face_len[j] = len;
        j += 1;
    }
    t
};

/// The corners of each face (as in [`FACE_CORNERS`]; unused entries 0).
const FACE_CORNER_INDICES: [[usize; 4]; 18] = {
    let mut t = [[0usize; 4]; 18];
    let mut j = 0;
    while j < 18 {
        let (list, n) = FACE_CORNERS[j];
        let mut i = 0;
        while i < n as usize {
            t[j][i] = list[i].0 as usize;
            i += 1;
        }
        j += 1;
    }
    t
};

/// The coordinate signs of each corner, as doubles.
const CORNER_SIGNS: [[f64; 3]; 8] = {
    let mut t = [[0.0; 3]; 8];
    let mut c = 0;
    while c < 8 {
        let s = corner_signs(c);
        t[c] = [s[0] as f64, s[1] as f64, s[2] as f64];
        c += 1;
    }
    t
};

/// Bounds of a point set along the tribox's 9 directions: the 18 parameters of its tribox.
///
/// Serialises (serde) as the 18 numbers of [`to_array18`](Self::to_array18).
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0), Point3::new(0.0, 0.0, 0.0)]);
/// assert_eq!(b.max()[3], 3.0); // max of x + y
/// assert_eq!(b.min()[8], 0.0); // min of z - y
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriboxBounds {
    min: [f64; 9],
    max: [f64; 9],
}

impl Serialize for TriboxBounds {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.to_array18().serialize(serializer)
    }
}

impl TriboxBounds {
    /// The 9 directions in the paper's order: x, y, z, x+y, x+z, y+z, x−z, y−x, z−y.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert_eq!(TriboxBounds::DIRECTIONS[7], [-1.0, 1.0, 0.0]); // y - x
    /// ```
    pub const DIRECTIONS: [[f64; 3]; 9] = {
        let mut t = [[0.0; 3]; 9];
        let mut d = 0;
        while d < 9 {
            t[d] = [DIRS[d][0] as f64, DIRS[d][1] as f64, DIRS[d][2] as f64];
            d += 1;
        }
        t
    };

    /// The bounds of no point: every minimum +∞, every maximum −∞.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert!(TriboxBounds::empty().is_empty());
    /// ```
    pub fn empty() -> Self {
        Self {
            min: [f64::INFINITY; 9],
            max: [f64::NEG_INFINITY; 9],
        }
    }

    /// The bounds of a point set, in one pass. Points with a NaN coordinate are skipped for the
    /// directions it touches (and are then never contained).
    ///
    /// Each diagonal sum is rounded in `f64`; its exact error is looked at only when the rounded
    /// sum reaches the current extreme, and the final bound is moved one ulp outward when a point
    /// attaining it has an exact sum beyond it. The result is the exact extreme rounded outward.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.1, 0.7, 0.0)]);
    /// assert_eq!(b.max()[3], (0.1f64 + 0.7).next_up()); // 0.1 + 0.7 rounds down in f64
    /// assert_eq!(b.min()[3], 0.1 + 0.7);
    /// ```
    pub fn from_points(points: &[Point3]) -> Self {
        let mut acc = Accumulator::new();
        acc.add(points);
        acc.finish()
    }

    /// [`from_points`](Self::from_points) in parallel (rayon): chunks are folded on separate
    /// threads and their accumulators merged. Same result.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let pts: Vec<Point3> = (0..1000).map(|i| Point3::new(i as f64 * 0.1, 1.0, -0.3)).collect();
    /// assert_eq!(TriboxBounds::par_from_points(&pts), TriboxBounds::from_points(&pts));
    /// ```
    pub fn par_from_points(points: &[Point3]) -> Self {
        const CHUNK: usize = 1 << 15;
        points
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut acc = Accumulator::new();
                acc.add(chunk);
                acc
            })
            .reduce(Accumulator::new, Accumulator::merge)
            .finish()
    }

    /// Whether these bounds contain no point.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// assert!(!TriboxBounds::from_points(&[Point3::origin()]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.min[0] > self.max[0]
    }

    /// The lower bounds, one per direction, in the order of [`DIRECTIONS`](Self::DIRECTIONS).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 4.0)]);
    /// assert_eq!(b.min(), &[1.0, 2.0, 4.0, 3.0, 5.0, 6.0, -3.0, 1.0, 2.0]);
    /// ```
    pub fn min(&self) -> &[f64; 9] {
        &self.min
    }

    /// The upper bounds, one per direction, in the order of [`DIRECTIONS`](Self::DIRECTIONS).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 4.0)]);
    /// assert_eq!(b.max(), b.min());
    /// ```
    pub fn max(&self) -> &[f64; 9] {
        &self.max
    }

    /// The 18 bounds as `[min_x, max_x, min_y, max_y, min_z, max_z, min_(x+y), max_(x+y), …,
    /// min_(z−y), max_(z−y)]`: element `2d` / `2d+1` is the lower / upper bound of direction `d`,
    /// which is also the index of the corresponding plane and face. This is the JSON layout.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(&b.to_array18()[..8], &[0.0, 1.0, 0.0, 2.0, 0.0, 3.0, 0.0, 3.0]);
    /// assert_eq!(serde_json::to_string(&b).unwrap(),
    ///     "[0.0,1.0,0.0,2.0,0.0,3.0,0.0,3.0,0.0,4.0,0.0,5.0,-2.0,0.0,0.0,1.0,0.0,1.0]");
    /// ```
    pub fn to_array18(&self) -> [f64; 18] {
        std::array::from_fn(|j| {
            if j % 2 == 0 {
                self.min[j / 2]
            } else {
                self.max[j / 2]
            }
        })
    }

    /// Whether `p` satisfies all 18 inequalities, decided exactly (a point on a bounding plane
    /// is inside). Diagonal projections are not rounded: their comparison with the bound is the
    /// exact sign of a three-term sum.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0)]);
    /// assert!(b.contains_point(&Point3::new(0.5, 0.5, 0.0)));
    /// assert!(!b.contains_point(&Point3::new(1.0, 0.0, 0.0))); // y - x below its minimum 0
    /// ```
    pub fn contains_point(&self, p: &Point3) -> bool {
        let c = [p.x, p.y, p.z];
        let axes_inside = c
            .iter()
            .zip(self.min.iter().zip(&self.max))
            .all(|(&v, (&lo, &hi))| lo <= v && v <= hi);
        axes_inside
            && DIAGONAL_AXES.iter().enumerate().all(|(k, &(i, j, minus))| {
                let (a, b) = (c[i], if minus { -c[j] } else { c[j] });
                let (lo, hi) = (self.min[3 + k], self.max[3 + k]);
                (lo == f64::NEG_INFINITY || sum_sign(&[a, b, -lo]) != Ordering::Less)
                    && (hi == f64::INFINITY || sum_sign(&[a, b, -hi]) != Ordering::Greater)
            })
    }

    /// Whether the slabs of `self` and `other` overlap along all 9 directions (touching counts).
    /// Disjoint slabs along one direction prove the triboxes disjoint; overlapping slabs along
    /// all nine are the paper's interference filter (not an exact polytope test).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let a = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0)]);
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)]);
    /// let c = TriboxBounds::from_points(&[Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 2.0, 0.0)]);
    /// assert!(a.intersects(&b));
    /// assert!(!a.intersects(&c));
    /// ```
    pub fn intersects(&self, other: &TriboxBounds) -> bool {
        (0..9).all(|d| self.min[d] <= other.max[d] && other.min[d] <= self.max[d])
    }

    /// The bounds of the union of both point sets.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let p = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)];
    /// let a = TriboxBounds::from_points(&p[..1]);
    /// let b = TriboxBounds::from_points(&p[1..]);
    /// assert_eq!(a.union(&b), TriboxBounds::from_points(&p));
    /// assert_eq!(a.union(&TriboxBounds::empty()), a);
    /// ```
    pub fn union(&self, other: &TriboxBounds) -> TriboxBounds {
        TriboxBounds {
            min: std::array::from_fn(|d| self.min[d].min(other.min[d])),
            max: std::array::from_fn(|d| self.max[d].max(other.max[d])),
        }
    }

    /// The points in both: the intersection of the two sets of 18 half-spaces (empty bounds
    /// when some slab pair does not overlap).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let a = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 1.0, 1.0), Point3::new(3.0, 3.0, 3.0)]);
    /// let both = a.intersection(&b);
    /// assert_eq!((both.min()[0], both.max()[0], both.max()[3]), (1.0, 2.0, 4.0));
    /// assert!(a.intersection(&TriboxBounds::empty()).is_empty());
    /// ```
    pub fn intersection(&self, other: &TriboxBounds) -> TriboxBounds {
        let b = TriboxBounds {
            min: std::array::from_fn(|d| self.min[d].max(other.min[d])),
            max: std::array::from_fn(|d| self.max[d].min(other.max[d])),
        };
        if (0..9).any(|d| b.min[d] > b.max[d]) {
            TriboxBounds::empty()
        } else {
            b
        }
    }

    /// The two halves cut by the plane `d · x = h` across direction `d` (an index into
    /// [`DIRECTIONS`](Self::DIRECTIONS)): `[below, above]`, the first with its maximum along `d`
    /// lowered to `h`, the second with its minimum raised to `h` (either empty when `h` lies
    /// outside the slab). Hierarchical triboxes split their regions this way.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// let [below, above] = b.split(3, 1.0); // the plane x + y = 1
    /// assert_eq!((below.min()[3], below.max()[3]), (0.0, 1.0));
    /// assert_eq!((above.min()[3], above.max()[3]), (1.0, 4.0));
    /// assert!(b.split(0, 5.0)[1].is_empty());
    /// ```
    pub fn split(&self, d: usize, h: f64) -> [TriboxBounds; 2] {
        let (mut below, mut above) = (*self, *self);
        below.max[d] = below.max[d].min(h);
        above.min[d] = above.min[d].max(h);
        [below, above].map(|b| b.intersection(&b))
    }

    /// The boundary of the tribox, by the paper's corner classification. See [`Tribox`].
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// assert_eq!(b.boundary().cleaned().vertices().len(), 2); // a needle along (1, 1, 1)
    /// ```
    #[inline]
    pub fn boundary(&self) -> Tribox {
        Tribox::new(self)
    }

    /// The bounds as offsets of the 18 half-spaces n_j · x ≤ β_j: β_(2d) = −min_d,
    /// β_(2d+1) = max_d (negation is exact).
    fn offsets(&self) -> [f64; 18] {
        std::array::from_fn(|j| {
            if j % 2 == 0 {
                -self.min[j / 2]
            } else {
                self.max[j / 2]
            }
        })
    }

    /// The bounds with half-space offsets `beta` (see [`offsets`](Self::offsets)).
    fn from_offsets(beta: &[f64; 18]) -> Self {
        TriboxBounds {
            min: std::array::from_fn(|d| -beta[2 * d]),
            max: std::array::from_fn(|d| beta[2 * d + 1]),
        }
    }
}

/// Running extremes of a point set. For the 6 diagonal directions the extremes are of the
/// rounded sums, with a flag telling whether a point attaining the extreme has an exact sum
/// beyond it.
#[derive(Clone, Copy)]
struct Accumulator {
    min: [f64; 9],
    max: [f64; 9],
    below_min: [bool; 6],
    above_max: [bool; 6],
}

impl Accumulator {
    fn new() -> Self {
        Accumulator {
            min: [f64::INFINITY; 9],
            max: [f64::NEG_INFINITY; 9],
            below_min: [false; 6],
            above_max: [false; 6],
        }
    }

    /// Adds points, block by block. A branch-free pass takes the extremes of the 9 rounded
    /// projections of a block (cache resident); only when a block reaches a running diagonal
    /// extreme is it scanned again, for the exact errors of the sums attaining it.
    fn add(&mut self, points: &[Point3]) {
        const BLOCK: usize = 2048;
        for block in points.chunks(BLOCK) {
            let mut lo = [f64::INFINITY; 9];
            let mut hi = [f64::NEG_INFINITY; 9];
            for p in block {
                let v = projections(p);
                for d in 0..9 {
                    lo[d] = if v[d] < lo[d] { v[d] } else { lo[d] };
                    hi[d] = if v[d] > hi[d] { v[d] } else { hi[d] };
                }
            }
            for d in 0..3 {
                self.min[d] = self.min[d].min(lo[d]);
                self.max[d] = self.max[d].max(hi[d]);
            }
            for (k, &(i, j, minus)) in DIAGONAL_AXES.iter().enumerate() {
                let d = 3 + k;
                // The exact error of the sums of the block's points that round to `m`: whether
                // one is positive (`sign` 1) or negative (-1).
                let error_beyond = |m: f64, sign: f64| {
                    block.iter().any(|p| {
                        let (a, b) = (p[i], if minus { -p[j] } else { p[j] });
                        a + b == m && two_sum(a, b).1 * sign > 0.0
                    })
                };
                if hi[d] >= self.max[d] {
                    let above = error_beyond(hi[d], 1.0);
                    if hi[d] > self.max[d] {
                        self.max[d] = hi[d];
                        self.above_max[k] = above;
                    } else {
                        self.above_max[k] |= above;
                    }
                }
                if lo[d] <= self.min[d] {
                    let below = error_beyond(lo[d], -1.0);
                    if lo[d] < self.min[d] {
                        self.min[d] = lo[d];
                        self.below_min[k] = below;
                    } else {
                        self.below_min[k] |= below;
                    }
                }
            }
        }
    }

    fn merge(self, other: Self) -> Self {
        let mut out = self;
        for d in 0..9 {
            out.min[d] = self.min[d].min(other.min[d]);
            out.max[d] = self.max[d].max(other.max[d]);
        }
        for k in 0..6 {
            let d = 3 + k;
            out.below_min[k] = (self.min[d] == out.min[d] && self.below_min[k])
                || (other.min[d] == out.min[d] && other.below_min[k]);
            out.above_max[k] = (self.max[d] == out.max[d] && self.above_max[k])
                || (other.max[d] == out.max[d] && other.above_max[k]);
        }
        out
    }

    fn finish(self) -> TriboxBounds {
        let mut b = TriboxBounds {
            min: self.min,
            max: self.max,
        };
        for k in 0..6 {
            if self.below_min[k] {
                b.min[3 + k] = b.min[3 + k].next_down();
            }
            if self.above_max[k] {
                b.max[3 + k] = b.max[3 + k].next_up();
            }
        }
        b
    }
}

/// A local bound of a corner, as the generic corner formulas ([`corner`]) need it: the
/// tightened bounds of [`Tribox::cleaned`] ([`OffsetForm`]). [`Tribox::new`] evaluates the same
/// formulas from tables of simplified forms instead ([`masked_corner`]).
trait LocalBound: Copy {
    fn neg(self) -> Self;
    /// The value, for a principal bound (a single double).
    fn value(self) -> f64;
    /// a + b, correctly rounded.
    fn sum2(a: Self, b: Self) -> f64;
    /// a + b + c, correctly rounded.
    fn sum3(a: Self, b: Self, c: Self) -> f64;
    /// Whether a + b + c + d + e > 0, exactly.
    fn positive5(a: Self, b: Self, c: Self, d: Self, e: Self) -> bool;
    /// The case (1..4) of the canonical corner with local bounds `[α_A, α_B, α_C, α_AB, α_AC,
    /// α_BC]`: x_p > α_A ⇔ α_AB + α_AC − α_BC − 2α_A > 0, and cyclically; at most one holds once
    /// the chamfers are clamped, so the paper's order of the tests is immaterial.
    #[inline]
    fn case_of(al: [Self; 6]) -> usize {
        let [a, b, c, ab, ac, bc] = al;
        if Self::positive5(ab, ac, bc.neg(), a.neg(), a.neg()) {
            2
        } else if Self::positive5(ab, ac.neg(), bc, b.neg(), b.neg()) {
            3
        } else if Self::positive5(ab.neg(), ac, bc, c.neg(), c.neg()) {
            4
        } else {
            1
        }
    }
}

/// A linear form in the six local bounds `[α_A, α_B, α_C, α_AB, α_AC, α_BC]` of a corner, with
/// integer coefficients in −2..=2 (so that every term `coef · α` is an exact double).
type Form = [i8; 6];

/// A signed combination of local bounds: up to four (local plane, coefficient) pairs, unused
/// pairs with coefficient 0.
type Combination = [(usize, i8); 4];

/// A combination of one local bound.
const fn one(k: usize) -> Combination {
    [(k, 1), (0, 0), (0, 0), (0, 0)]
}

/// The combination `α_k − α_l`.
const fn minus(k: usize, l: usize) -> Combination {
    [(k, 1), (l, -1), (0, 0), (0, 0)]
}

/// The combination `α_k + α_l + α_m` with the given signs.
const fn three(k: (usize, i8), l: (usize, i8), m: (usize, i8)) -> Combination {
    [k, l, m, (0, 0)]
}

/// The effective local bound k of a corner whose clamped chamfers are the set bits of `mask`
/// (bit 0: AB, bit 1: AC, bit 2: BC) as a form: a clamped chamfer is the exact sum of its two
/// principal bounds.
const fn local_form(k: usize, mask: usize) -> Form {
    let mut f = [0; 6];
    if k >= AB && mask & (1 << (k - AB)) != 0 {
        let [p, q] = [[A, B], [A, C], [B, C]][k - AB];
        f[p] = 1;
        f[q] = 1;
    } else {
        f[k] = 1;
    }
    f
}

/// A combination of effective local bounds as a form, the symbolic cancellations of clamped
/// chamfers done (evaluated at compile time only).
const fn form_of(combination: Combination, mask: usize) -> Form {
    let mut f = [0i8; 6];
    let mut i = 0;
    while i < 4 {
        let (k, c) = combination[i];
        let l = local_form(k, mask);
        let mut m = 0;
        while m < 6 {
            f[m] += c * l[m];
            m += 1;
        }
        i += 1;
    }
    let mut m = 0;
    while m < 6 {
        assert!(
            f[m] >= -2 && f[m] <= 2,
            "a term would not be an exact double"
        );
        m += 1;
    }
    f
}

/// The three case tests of the canonical corner (x_p > α_A, y_p > α_B, z_p > α_C), each a
/// combination whose positivity is the test: α_AB + α_AC − α_BC − 2α_A > 0, and cyclically.
const CASE_TESTS: [Combination; 3] = [
    [(AB, 1), (AC, 1), (BC, -1), (A, -2)],
    [(AB, 1), (AC, -1), (BC, 1), (B, -2)],
    [(AB, -1), (AC, 1), (BC, 1), (C, -2)],
];

/// Case 1 vertex slots (v1, v2, v3, p; paper eqs 2–7), each coordinate a combination; the
/// coordinates of p are half their combination.
const CASE1_COORDS: [[Combination; 3]; 4] = [
    [minus(AC, C), minus(BC, C), one(C)],
    [one(A), minus(AB, A), minus(AC, A)],
    [minus(AB, B), one(B), minus(BC, B)],
    [
        three((AB, 1), (AC, 1), (BC, -1)),
        three((AB, 1), (AC, -1), (BC, 1)),
        three((AB, -1), (AC, 1), (BC, 1)),
    ],
];

/// Case 2 vertex slots (v1, v3, q2 = A∩AC∩BC, q3 = A∩AB∩BC; paper eqs 5, 7, 8, 9).
const CASE2_COORDS: [[Combination; 3]; 4] = [
    [minus(AC, C), minus(BC, C), one(C)],
    [minus(AB, B), one(B), minus(BC, B)],
    [one(A), three((BC, 1), (AC, -1), (A, 1)), minus(AC, A)],
    [one(A), minus(AB, A), three((BC, 1), (AB, -1), (A, 1))],
];

/// Case 2's slots in the frame rotated by `sigma` ([`ROTATION`] or [`ROTATION2`]), with the
/// coordinates `w` put back as `[w[perm[0]], w[perm[1]], w[perm[2]]]`: cases 3 and 4.
const fn rotated_coords(sigma: [usize; 6], perm: [usize; 3]) -> [[Combination; 3]; 4] {
    let mut t = CASE2_COORDS;
    let mut s = 0;
    while s < 4 {
        let mut i = 0;
        while i < 3 {
            let mut combination = CASE2_COORDS[s][perm[i]];
            let mut k = 0;
            while k < 4 {
                combination[k].0 = sigma[combination[k].0];
                k += 1;
            }
            t[s][i] = combination;
            i += 1;
        }
        s += 1;
    }
    t
}

/// The formulas of a corner with a given clamp mask: its case tests, and per case its four
/// vertices (slot order of [`CASES`]) in the canonical frame, as forms.
struct CornerForms {
    tests: [Form; 3],
    /// The sign of each test when the clamping alone decides it (see [`known_sign`]).
    known: [Option<Ordering>; 3],
    /// For each test, an earlier test of which it is the negation (its sign is then known).
    negates: [Option<usize>; 3],
    coords: [[[Form; 3]; 4]; 4],
}

/// The sign of a test form when the clamp mask decides it: the zero form is zero, and
/// `±(α_P + α_Q − α_PQ)` for an unclamped chamfer PQ is positive (negative) since an unclamped
/// chamfer bound is strictly below the sum of its principal bounds (see [`clamped_chamfers`]).
const fn known_sign(f: Form, mask: usize) -> Option<Ordering> {
    if forms_equal(f, [0; 6], 1) {
        return Some(Ordering::Equal);
    }
    let mut k = AB;
    while k <= BC {
        if mask & (1 << (k - AB)) == 0 {
            // α_P + α_Q − α_PQ, as the clamped form of PQ minus its own bound.
            let mut g = local_form(k, 1 << (k - AB));
            g[k] = -1;
            if forms_equal(f, g, 1) {
                return Some(Ordering::Greater);
            }
            if forms_equal(f, g, -1) {
                return Some(Ordering::Less);
            }
        }
        k += 1;
    }
    None
}

/// Whether `f = sign · g`.
const fn forms_equal(f: Form, g: Form, sign: i8) -> bool {
    let mut m = 0;
    while m < 6 {
        if f[m] != sign * g[m] {
            return false;
        }
        m += 1;
    }
    true
}

/// `CORNER_FORMS[mask]`: the formulas of a corner whose clamped chamfers are the set bits of
/// `mask` (see [`local_form`]).
const CORNER_FORMS: [CornerForms; 8] = {
    let cases = [
        CASE1_COORDS,
        CASE2_COORDS,
        rotated_coords(ROTATION, [2, 0, 1]),
        rotated_coords(ROTATION2, [1, 2, 0]),
    ];
    let mut t = [const {
        CornerForms {
            tests: [[0; 6]; 3],
            known: [None; 3],
            negates: [None; 3],
            coords: [[[[0; 6]; 3]; 4]; 4],
        }
    }; 8];
    let mut mask = 0;
    while mask < 8 {
        let mut i = 0;
        while i < 3 {
            t[mask].tests[i] = form_of(CASE_TESTS[i], mask);
            // The test is case 1's doubled p coordinate minus twice the principal bound (see
            // `masked_corner`).
            let mut m = 0;
            while m < 6 {
                let twice = if m == i { 2 } else { 0 };
                assert!(t[mask].tests[i][m] == form_of(CASE1_COORDS[3][i], mask)[m] - twice);
                m += 1;
            }
            t[mask].known[i] = known_sign(t[mask].tests[i], mask);
            let mut j = 0;
            while j < i {
                if forms_equal(t[mask].tests[i], t[mask].tests[j], -1) {
                    t[mask].negates[i] = Some(j);
                }
                j += 1;
            }
            i += 1;
        }
        let mut k = 0;
        while k < 4 {
            let mut s = 0;
            while s < 4 {
                let mut i = 0;
                while i < 3 {
                    t[mask].coords[k][s][i] = form_of(cases[k][s][i], mask);
                    i += 1;
                }
                s += 1;
            }
            k += 1;
        }
        mask += 1;
    }
    t
};

/// The nonzero terms `coef_k · α_k` of a form (exact doubles) and their number.
#[inline(always)]
fn form_terms(f: &Form, al: &[f64; 6]) -> ([f64; 6], usize) {
    let mut terms = [0.0; 6];
    let mut n = 0;
    for (&c, &x) in f.iter().zip(al) {
        if c != 0 {
            terms[n] = f64::from(c) * x;
            n += 1;
        }
    }
    (terms, n)
}

/// The exact sign of a form. The sum of at most two exact terms is rounded once, which keeps
/// its sign; longer sums go through the filtered exact sign. The number of terms of a constant
/// form is a constant, so one arm remains, on a fixed-length array (kept in registers).
#[inline(always)]
fn form_sign(f: &Form, al: &[f64; 6]) -> Ordering {
    let (t, n) = form_terms(f, al);
    match n {
        0..=2 => (t[0] + t[1]).partial_cmp(&0.0).unwrap_or(Ordering::Equal),
        3 => sum_sign_array([t[0], t[1], t[2]]),
        4 => sum_sign_array([t[0], t[1], t[2], t[3]]),
        5 => sum_sign_array([t[0], t[1], t[2], t[3], t[4]]),
        _ => sum_sign_array(t),
    }
}

/// The exact value of a form, correctly rounded (one addition for at most two terms; see
/// [`form_sign`] for the arms).
#[inline(always)]
fn form_value(f: &Form, al: &[f64; 6]) -> f64 {
    let (t, n) = form_terms(f, al);
    match n {
        0..=2 => t[0] + t[1],
        3 => accurate_sum_array([t[0], t[1], t[2]]),
        4 => accurate_sum_array([t[0], t[1], t[2], t[3]]),
        5 => accurate_sum_array([t[0], t[1], t[2], t[3], t[4]]),
        _ => accurate_sum_array(t),
    }
}

/// The number of nonzero coefficients of a form.
const fn form_len(f: &Form) -> usize {
    let mut n = 0;
    let mut m = 0;
    while m < 6 {
        if f[m] != 0 {
            n += 1;
        }
        m += 1;
    }
    n
}

/// A vertex from the forms of its coordinates. Written out so that, the forms being
/// constants, every coefficient test folds away.
#[inline(always)]
fn slot(coords: &[Form; 3], al: &[f64; 6]) -> [f64; 3] {
    [
        form_value(&coords[0], al),
        form_value(&coords[1], al),
        form_value(&coords[2], al),
    ]
}

/// The four vertices of case 2, 3 or 4 from their forms.
#[inline(always)]
fn slots(coords: &[[Form; 3]; 4], al: &[f64; 6]) -> [[f64; 3]; 4] {
    [
        slot(&coords[0], al),
        slot(&coords[1], al),
        slot(&coords[2], al),
        slot(&coords[3], al),
    ]
}

/// The canonical corner with local bounds `al = [α_A, α_B, α_C, α_AB, α_AC, α_BC]` whose
/// clamped chamfers are the set bits of `MASK`: its case (1..4) and its four vertices in the
/// slot order of [`CASES`], each coordinate the correctly rounded exact value of its formula
/// (halved for p). The formulas are the symbolically simplified forms of [`CORNER_FORMS`], so
/// that exact cancellations of clamped chamfers cost no arithmetic, and tests whose sign the
/// clamping decides ([`CornerForms::known`]) none either. The tests are taken in the paper's
/// order, as [`LocalBound::case_of`] does.
///
/// Test i (x_p > α_A, y_p > α_B, z_p > α_C) is the sign of `2p_i − 2α_i`, and `2p_i` is the
/// form case 1 rounds for its last slot anyway (halving it): since rounding to nearest is
/// monotone and `2α_i` is a double, the rounded `2p_i` above (below) `2α_i` proves the exact one
/// above (below) it, so one comparison decides the test, and the exact sign of the test's form
/// is needed only when they are equal.
#[inline(always)]
fn masked_corner<const MASK: usize>(al: [f64; 6]) -> (usize, [[f64; 3]; 4]) {
    let forms = const { &CORNER_FORMS[MASK] };
    let p2 = &forms.coords[0][3];
    // The doubled p, correctly rounded (computed where a test or case 1 needs it).
    let twice_p = [
        form_value(&p2[0], &al),
        form_value(&p2[1], &al),
        form_value(&p2[2], &al),
    ];
    // Written out (no loop, no closure) so that the constant tables fold.
    #[inline(always)]
    fn sign(
        forms: &CornerForms,
        i: usize,
        earlier: &[Ordering],
        twice_p: f64,
        al: &[f64; 6],
    ) -> Ordering {
        match (forms.known[i], forms.negates[i]) {
            (Some(known), _) => known,
            (None, Some(j)) => earlier[j].reverse(),
            // One rounded addition keeps the sign of a sum of two exact terms.
            (None, None) if form_len(&forms.tests[i]) <= 2 => form_sign(&forms.tests[i], al),
            (None, None) => {
                let bound = 2.0 * al[i];
                if twice_p > bound {
                    Ordering::Greater
                } else if twice_p < bound {
                    Ordering::Less
                } else {
                    form_sign(&forms.tests[i], al)
                }
            }
        }
    }
    let s0 = sign(forms, 0, &[], twice_p[0], &al);
    if s0 == Ordering::Greater {
        return (2, slots(&forms.coords[1], &al));
    }
    let s1 = sign(forms, 1, &[s0], twice_p[1], &al);
    if s1 == Ordering::Greater {
        return (3, slots(&forms.coords[2], &al));
    }
    if sign(forms, 2, &[s0, s1], twice_p[2], &al) == Ordering::Greater {
        return (4, slots(&forms.coords[3], &al));
    }
    // Halving is exact but for subnormal results.
    let c = &forms.coords[0];
    (
        1,
        [
            slot(&c[0], &al),
            slot(&c[1], &al),
            slot(&c[2], &al),
            twice_p.map(|x| 0.5 * x),
        ],
    )
}

/// A tight bound as a linear form in the 18 offsets, in half-units: `Σ_k coef_k β_k / 2`.
#[derive(Clone, Copy)]
struct OffsetForm<'a> {
    coef: [i32; 18],
    beta: &'a [f64; 18],
}

impl OffsetForm<'_> {
    fn combine(forms: &[Self]) -> [i32; 18] {
        std::array::from_fn(|k| forms.iter().map(|f| f.coef[k]).sum())
    }
}

impl LocalBound for OffsetForm<'_> {
    fn neg(self) -> Self {
        OffsetForm {
            coef: self.coef.map(|c| -c),
            beta: self.beta,
        }
    }
    fn value(self) -> f64 {
        eval_form(&self.coef, self.beta) * 0.5
    }
    fn sum2(a: Self, b: Self) -> f64 {
        eval_form(&OffsetForm::combine(&[a, b]), a.beta) * 0.5
    }
    fn sum3(a: Self, b: Self, c: Self) -> f64 {
        eval_form(&OffsetForm::combine(&[a, b, c]), a.beta) * 0.5
    }
    fn positive5(a: Self, b: Self, c: Self, d: Self, e: Self) -> bool {
        sign_of_form(&OffsetForm::combine(&[a, b, c, d, e]), a.beta) == Ordering::Greater
    }
}

/// Classifies the canonical corner with local bounds `[α_A, α_B, α_C, α_AB, α_AC, α_BC]`
/// (chamfers already clamped) and computes its four vertices in the canonical frame.
/// Returns the case (1..4) and the vertices in the slot order of [`CASES`].
#[inline]
fn corner<T: LocalBound>(al: [T; 6]) -> (usize, [[f64; 3]; 4]) {
    let [a, b, c, ab, ac, bc] = al;
    match T::case_of(al) {
        2 => return (2, case2(al)),
        3 => {
            let v = case2([b, c, a, bc, ab, ac]);
            return (3, v.map(|w| [w[2], w[0], w[1]]));
        }
        4 => {
            let v = case2([c, a, b, ac, bc, ab]);
            return (4, v.map(|w| [w[1], w[2], w[0]]));
        }
        _ => {}
    }
    // Case 1: p inside the block. Paper eqs (2)-(7); halving is exact.
    let v1 = [T::sum2(ac, c.neg()), T::sum2(bc, c.neg()), c.value()];
    let v2 = [a.value(), T::sum2(ab, a.neg()), T::sum2(ac, a.neg())];
    let v3 = [T::sum2(ab, b.neg()), b.value(), T::sum2(bc, b.neg())];
    let p = [
        0.5 * T::sum3(ab, ac, bc.neg()),
        0.5 * T::sum3(ab, ac.neg(), bc),
        0.5 * T::sum3(ab.neg(), ac, bc),
    ];
    (1, [v1, v2, v3, p])
}

/// Case 2 (p beyond h_A): vertices v1, v3 (eqs 5, 7), q2 = A∩AC∩BC and q3 = A∩AB∩BC
/// (eqs 8, 9), in the canonical frame.
#[inline]
fn case2<T: LocalBound>(al: [T; 6]) -> [[f64; 3]; 4] {
    let [a, b, c, ab, ac, bc] = al;
    let v1 = [T::sum2(ac, c.neg()), T::sum2(bc, c.neg()), c.value()];
    let v3 = [T::sum2(ab, b.neg()), b.value(), T::sum2(bc, b.neg())];
    let q2 = [a.value(), T::sum3(bc, ac.neg(), a), T::sum2(ac, a.neg())];
    let q3 = [a.value(), T::sum2(ab, a.neg()), T::sum3(bc, ab.neg(), a)];
    [v1, v3, q2, q3]
}

/// The vertices `v` of corner `c`, computed in its canonical frame, in world coordinates (each
/// coordinate times the corner's sign; adding +0 turns the −0 of a reflected zero into +0).
#[inline(always)]
fn reflected(c: usize, v: &[[f64; 3]; 4]) -> [Point3; 4] {
    let s = CORNER_SIGNS[c];
    let r = |v: &[f64; 3]| Point3::new(s[0] * v[0] + 0.0, s[1] * v[1] + 0.0, s[2] * v[2] + 0.0);
    [r(&v[0]), r(&v[1]), r(&v[2]), r(&v[3])]
}

/// The vertices of the generic boundary, no chamfer clamped and every corner in case 1,
/// evaluated for the 8 corners at once (lane c is corner c, so that the arithmetic
/// vectorises); `None` when some corner is in another case or needs exact arithmetic (a
/// doubled p coordinate equal to twice its principal bound, or a sum [`accurate_sum3_lanes`]
/// does not certify), left to [`masked_corner`]. The same operations as
/// [`masked_corner::<0>`](masked_corner) in case 1, hence the same doubles.
#[inline(always)]
fn generic_vertices(beta: &[f64; 18]) -> Option<[[Point3; 4]; 8]> {
    // Plain loops over fixed arrays (array::from_fn and map were left as calls).
    let mut al = [[0.0; 8]; 6];
    for (k, lanes) in al.iter_mut().enumerate() {
        for (c, x) in lanes.iter_mut().enumerate() {
            *x = beta[usize::from(CORNER_PLANES[c][k])];
        }
    }
    let [a, b, c, ab, ac, bc] = al;
    let neg = |mut x: [f64; 8]| {
        for v in &mut x {
            *v = -*v;
        }
        x
    };
    // The doubled p (CASE1_COORDS's last slot), terms in the order of the local planes.
    let (px, cx) = accurate_sum3_lanes(ab, ac, neg(bc));
    let (py, cy) = accurate_sum3_lanes(ab, neg(ac), bc);
    let (pz, cz) = accurate_sum3_lanes(neg(ab), ac, bc);
    // Case 1 everywhere: every test x_p > α_A (and cyclically) decided negative.
    let mut below = cx && cy && cz;
    for k in 0..8 {
        below &= (px[k] < 2.0 * a[k]) & (py[k] < 2.0 * b[k]) & (pz[k] < 2.0 * c[k]);
    }
    if !below {
        return None;
    }
    let mut out = [[const { Point3::new(0.0, 0.0, 0.0) }; 4]; 8];
    for (k, o) in out.iter_mut().enumerate() {
        let (aa, bb, cc, ab, ac, bc) = (a[k], b[k], c[k], ab[k], ac[k], bc[k]);
        *o = reflected(
            k,
            &[
                [ac - cc, bc - cc, cc + 0.0],
                [aa + 0.0, ab - aa, ac - aa],
                [ab - bb, bb + 0.0, bc - bb],
                [0.5 * px[k], 0.5 * py[k], 0.5 * pz[k]],
            ],
        );
    }
    Some(out)
}

/// Which chamfer bounds are clamped: β_j ≥ β_p1 + β_p2 for its parent principal planes.
#[inline]
fn clamped_chamfers(beta: &[f64; 18]) -> [bool; 18] {
    let mut clamped = [false; 18];
    for j in 6..18 {
        let [p1, p2] = CHAMFER_PARENTS[j];
        // β_p1 + β_p2 = s + e exactly, and rounding to nearest puts s + e strictly between
        // the neighbours of s: so β_j ≥ s + e ⇔ β_j > s, or β_j = s and e ≤ 0.
        // The error e is needed only in a tie.
        let (x, y) = (beta[usize::from(p1)], beta[usize::from(p2)]);
        let s = x + y;
        clamped[j] = beta[j] > s || (beta[j] == s && two_sum(x, y).1 <= 0.0);
    }
    clamped
}

/// The boundary of a tribox: at most 32 vertices and one face per bounding plane.
///
/// Face `j` lies on plane `j` (see [`TriboxBounds::to_array18`]); its loop is counter-clockwise
/// seen from outside. As the paper's algorithm produces it ([`TriboxBounds::boundary`]), every
/// corner contributes four vertices and every face its corners' sub-lists, so singular inputs
/// leave repeated vertices and degenerate faces; [`cleaned`](Self::cleaned) is the exact
/// intersection with exactly equal vertices merged, zero-length edges and faces left with
/// fewer than 3 vertices dropped.
///
/// Each vertex remembers three planes with independent normals through it.
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let cube: Vec<Point3> = (0..8)
///     .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
///     .collect();
/// let raw = TriboxBounds::from_points(&cube).boundary();
/// assert_eq!(raw.vertices().len(), 32);
/// let clean = raw.cleaned();
/// assert_eq!((clean.vertices().len(), clean.face_count()), (8, 6));
/// assert_eq!(clean.volume(), 1.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Tribox {
    bounds: TriboxBounds,
    /// Four vertices per corner (a cleaned boundary keeps its vertices first, in order).
    vertices: [[Point3; 4]; 8],
    vertex_planes: [[[u8; 3]; 4]; 8],
    vertex_count: u8,
    faces: [[u8; MAX_FACE]; 18],
    face_len: [u8; 18],
    cases: [u8; 8],
}

impl Tribox {
    /// The outward normals of the 18 planes (unnormalised, in the order of
    /// [`TriboxBounds::to_array18`]).
    ///
    /// ```
    /// use kepler::bounds::tribox::Tribox;
    /// assert_eq!(Tribox::PLANE_NORMALS[0], [-1.0, 0.0, 0.0]); // min x
    /// assert_eq!(Tribox::PLANE_NORMALS[15], [-1.0, 1.0, 0.0]); // max (y - x)
    /// ```
    pub const PLANE_NORMALS: [[f64; 3]; 18] = {
        let mut t = [[0.0; 3]; 18];
        let mut j = 0;
        while j < 18 {
            let n = normal(j);
            t[j] = [n[0] as f64, n[1] as f64, n[2] as f64];
            j += 1;
        }
        t
    };

    /// Evaluates the boundary of the tribox of `bounds` by the paper's corner classification.
    /// Empty bounds give an empty boundary.
    ///
    /// ```
    /// use kepler::bounds::tribox::{Tribox, TriboxBounds};
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// assert_eq!(Tribox::new(&b), b.boundary());
    /// assert!(Tribox::new(&TriboxBounds::empty()).is_empty());
    /// ```
    #[inline(never)]
    pub fn new(bounds: &TriboxBounds) -> Tribox {
        if bounds.is_empty() {
            return Tribox::blank(bounds);
        }
        let beta = bounds.offsets();
        let clamped = clamped_chamfers(&beta);
        if !clamped.contains(&true)
            && let Some(vertices) = generic_vertices(&beta)
        {
            return Tribox::generic(bounds, vertices);
        }
        Tribox::from_corners(bounds, |c| {
            let planes = CORNER_PLANES[c];
            let b = |k: usize| beta[usize::from(planes[k])];
            let al = [b(A), b(B), b(C), b(AB), b(AC), b(BC)];
            let mask = usize::from(clamped[usize::from(planes[AB])])
                | usize::from(clamped[usize::from(planes[AC])]) << 1
                | usize::from(clamped[usize::from(planes[BC])]) << 2;
            let (case, v) = match mask {
                0 => masked_corner::<0>(al),
                1 => masked_corner::<1>(al),
                2 => masked_corner::<2>(al),
                3 => masked_corner::<3>(al),
                4 => masked_corner::<4>(al),
                5 => masked_corner::<5>(al),
                6 => masked_corner::<6>(al),
                _ => masked_corner::<7>(al),
            };
            (case, reflected(c, &v))
        })
    }

    /// A boundary with no vertex and no face.
    #[inline(always)]
    fn blank(bounds: &TriboxBounds) -> Tribox {
        Tribox {
            bounds: *bounds,
            vertices: [[const { Point3::new(0.0, 0.0, 0.0) }; 4]; 8],
            vertex_planes: [[[0; 3]; 4]; 8],
            vertex_count: 0,
            faces: [[0; MAX_FACE]; 18],
            face_len: [0; 18],
            cases: [0; 8],
        }
    }

    /// The generic boundary (every corner in case 1) with the given vertices: its planes and
    /// face loops are the compile-time [`GENERIC`] table's.
    fn generic(bounds: &TriboxBounds, vertices: [[Point3; 4]; 8]) -> Tribox {
        Tribox {
            bounds: *bounds,
            vertices,
            vertex_planes: GENERIC.vertex_planes,
            vertex_count: MAX_VERTICES as u8,
            faces: GENERIC.faces,
            face_len: GENERIC.face_len,
            cases: [1; 8],
        }
    }

    /// The boundary from each corner's case and four vertices in world coordinates (`corner`
    /// returns them, by [`reflected`]), and each face's loop, its corners' sub-lists
    /// concatenated counter-clockwise around it (tabulated for every combination of cases).
    /// Every field is computed before the boundary is built, so that nothing is written twice.
    #[inline(always)]
    fn from_corners(
        bounds: &TriboxBounds,
        mut corner: impl FnMut(usize) -> (usize, [Point3; 4]),
    ) -> Tribox {
        let mut cases = [0u8; 8];
        let vertices = std::array::from_fn(|c| {
            let (case, v) = corner(c);
            cases[c] = case as u8;
            v
        });
        if cases == [1; 8] {
            // The generic boundary (every corner in case 1), at once.
            return Tribox::generic(bounds, vertices);
        }
        let vertex_planes = std::array::from_fn(|c| VERTEX_PLANES[c][usize::from(cases[c]) - 1]);
        // Two bits per corner: its case − 1.
        let two_bits = cases.map(|k| usize::from(k - 1));
        let combo = |j: usize| {
            let [c0, c1, c2, c3] = FACE_CORNER_INDICES[j];
            if j < 6 {
                two_bits[c0] | two_bits[c1] << 2 | two_bits[c2] << 4 | two_bits[c3] << 6
            } else {
                two_bits[c0] | two_bits[c1] << 2
            }
        };
        let faces = std::array::from_fn(|j| {
            if j < 6 {
                PRINCIPAL_LOOPS.loops[combo(j)][j]
            } else {
                CHAMFER_LOOPS.loops[combo(j)][j - 6]
            }
            .to_le_bytes()
        });
        let face_len = std::array::from_fn(|j| {
            if j < 6 {
                PRINCIPAL_LOOPS.lens[combo(j)][j]
            } else {
                CHAMFER_LOOPS.lens[combo(j)][j - 6]
            }
        });
        Tribox {
            bounds: *bounds,
            vertices,
            vertex_planes,
            vertex_count: MAX_VERTICES as u8,
            faces,
            face_len,
            cases,
        }
    }

    /// The bounds this boundary was evaluated from.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().bounds(), &b);
    /// ```
    pub fn bounds(&self) -> &TriboxBounds {
        &self.bounds
    }

    /// Whether the boundary has no vertex (the tribox of no point).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert!(TriboxBounds::empty().boundary().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.vertex_count == 0
    }

    /// The vertices.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let t = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]).boundary().cleaned();
    /// assert_eq!(t.vertices(), &[Point3::new(1.0, 2.0, 3.0)]);
    /// ```
    pub fn vertices(&self) -> &[Point3] {
        &self.vertices.as_flattened()[..self.vertex_count as usize]
    }

    /// For each vertex, three planes (ascending indices 0..18, independent normals) through
    /// it. In a raw boundary a clamped chamfer may stand for its two principal planes; in a
    /// cleaned one each listed plane passes exactly through the vertex.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let t = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]).boundary().cleaned();
    /// assert_eq!(t.vertex_planes(), &[[1, 3, 5]]); // max x, max y, max z
    /// ```
    pub fn vertex_planes(&self) -> &[[u8; 3]] {
        &self.vertex_planes.as_flattened()[..self.vertex_count as usize]
    }

    /// The loop of face `plane` (indices into [`vertices`](Self::vertices), counter-clockwise
    /// seen from outside); empty for a plane index beyond 17 or a face removed by clean-up.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// let t = b.boundary();
    /// assert!(!t.face(1).is_empty());
    /// assert!(t.cleaned().face(1).is_empty()); // a needle has no face of positive area
    /// assert!(t.face(18).is_empty());
    /// ```
    pub fn face(&self, plane: usize) -> &[u8] {
        match (self.faces.get(plane), self.face_len.get(plane)) {
            (Some(f), Some(&n)) => &f[..n as usize],
            _ => &[],
        }
    }

    /// The faces that have vertices, as (plane index, loop).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)]);
    /// assert_eq!(b.boundary().faces().count(), 18);
    /// ```
    pub fn faces(&self) -> impl Iterator<Item = (usize, &[u8])> + '_ {
        (0..18)
            .map(|j| (j, self.face(j)))
            .filter(|(_, f)| !f.is_empty())
    }

    /// The number of faces that have vertices: on a cleaned boundary, the number of faces of
    /// positive area (at most 18).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().face_count(), 18); // raw: every plane has its (degenerate) face
    /// assert_eq!(TriboxBounds::from_points(&[Point3::origin()]).boundary().cleaned().face_count(), 0);
    /// ```
    pub fn face_count(&self) -> usize {
        self.face_len.iter().filter(|&&n| n > 0).count()
    }

    /// The paper's case (1 to 4) of each corner of the block; corner `c` is the maximum along
    /// axis i when bit i of `c` is clear, the minimum when it is set. All 0 when empty.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(b.boundary().corner_cases(), [1; 8]);
    /// ```
    pub fn corner_cases(&self) -> [u8; 8] {
        self.cases
    }

    /// The enclosed volume (divergence theorem over the face loops; degenerate faces add
    /// nothing).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // The corner tetrahedron of the unit cube: its tribox is {x, y, z ≥ 0, x+y, x+z, y+z ≤ 1},
    /// // the tetrahedron (1/6) plus the pyramid from (½, ½, ½) over its slanted face (1/12).
    /// let tet = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    /// assert_eq!(TriboxBounds::from_points(&tet).boundary().volume(), 0.25);
    /// ```
    pub fn volume(&self) -> f64 {
        let o = self.reference();
        let six_v: f64 = self
            .faces()
            .map(|(_, f)| {
                let p = |i: usize| self.vertices()[f[i] as usize] - o;
                let p0 = p(0);
                (1..f.len().saturating_sub(1))
                    .map(|i| p0.dot(&p(i).cross(&p(i + 1))))
                    .sum::<f64>()
            })
            .sum();
        six_v / 6.0
    }

    /// The total area of the faces.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // The tribox of the corner tetrahedron (see `volume`): three right triangles of area ½
    /// // and three chamfer triangles of area √2/4.
    /// let tet = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
    /// let area = TriboxBounds::from_points(&tet).boundary().surface_area();
    /// assert!((area - (1.5 + 0.75 * 2f64.sqrt())).abs() < 1e-15);
    /// ```
    pub fn surface_area(&self) -> f64 {
        self.faces()
            .map(|(_, f)| {
                let p = |i: usize| self.vertices()[f[i] as usize];
                let p0 = p(0);
                let twice: Vector3 = (1..f.len().saturating_sub(1))
                    .map(|i| (p(i) - p0).cross(&(p(i + 1) - p0)))
                    .sum();
                twice.norm() / 2.0
            })
            .sum()
    }

    /// A reference point for the volume: the centre of the block (or the origin when empty).
    fn reference(&self) -> Point3 {
        let (lo, hi) = (self.bounds.min, self.bounds.max);
        if self.bounds.is_empty() {
            Point3::origin()
        } else {
            Point3::new(
                0.5 * lo[0] + 0.5 * hi[0],
                0.5 * lo[1] + 0.5 * hi[1],
                0.5 * lo[2] + 0.5 * hi[2],
            )
        }
    }

    /// The exact boundary of the intersection of the 18 half-spaces, cleaned up: exactly equal
    /// vertices merged, zero-length edges removed and faces left with fewer than 3 vertices
    /// dropped. An axis-aligned box cleans to its 8 vertices and 6 faces.
    ///
    /// The corner classification presumes that every plane touches the tribox, as exact bounds
    /// of points do; a diagonal bound rounded outward may miss it by less than an ulp and then
    /// leave a sliver face. So each bound is first tightened to the exact maximum of its
    /// direction over the tribox (linear programming duality: the least nonnegative combination
    /// of other bounds, kept symbolic, as clamping does), the corners are classified with these
    /// tight bounds, and two vertices are merged when the exact values of their coordinates, as
    /// sums of bounds, are equal (not when their rounded values are). The result is the exact
    /// polytope with every vertex coordinate correctly rounded.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // A needle along (1, 1, 1): the differences x−z, y−x, z−y are pinned to 0, so the tribox
    /// // is the segment, although 0.1 + 0.1 and 0.7 + 0.7 are rounded.
    /// let b = TriboxBounds::from_points(&[Point3::new(0.1, 0.1, 0.1), Point3::new(0.7, 0.7, 0.7)]);
    /// let t = b.boundary().cleaned();
    /// assert_eq!(t.vertices().len(), 2);
    /// assert_eq!(t.face_count(), 0);
    /// ```
    pub fn cleaned(&self) -> Tribox {
        if self.bounds.is_empty() {
            return Tribox::blank(&self.bounds);
        }
        let beta = self.bounds.offsets();
        let tight = tight_forms(&beta);
        // When tightening only clamped chamfers at their block corners (the common case), the
        // fast evaluation gives the same boundary: same exact values, same correct roundings.
        let clamped = clamped_chamfers(&beta);
        let only_clamps = (0..18).all(|j| {
            let mut own = [0; 18];
            own[j] = 2;
            tight[j] == own
                || (j >= 6 && {
                    let mut corner = [0; 18];
                    for p in CHAMFER_PARENTS[j] {
                        corner[p as usize] = 2;
                    }
                    clamped[j] && tight[j] == corner
                })
        });
        let raw = if only_clamps {
            Tribox::new(&self.bounds)
        } else {
            Tribox::from_corners(&self.bounds, |c| {
                let planes = CORNER_PLANES[c];
                let (case, v) = corner(std::array::from_fn(|k| OffsetForm {
                    coef: tight[planes[k] as usize],
                    beta: &beta,
                }));
                (case, reflected(c, &v))
            })
        };
        let n = raw.vertex_count as usize;
        let forms: Vec<VertexForm> = raw
            .vertex_planes()
            .iter()
            .map(|p| VertexForm::new(p, &tight))
            .collect();
        // Representatives: the first vertex of each class of exactly equal vertices.
        let mut new_index = [0u8; MAX_VERTICES];
        let mut kept: Vec<usize> = Vec::with_capacity(n);
        for i in 0..n {
            let found = kept.iter().position(|&r| {
                close(&raw.vertices()[r], &raw.vertices()[i]) && forms[r].equals(&forms[i], &beta)
            });
            new_index[i] = match found {
                Some(k) => k as u8,
                None => {
                    kept.push(i);
                    (kept.len() - 1) as u8
                }
            };
        }
        let mut t = Tribox::blank(&self.bounds);
        t.cases = raw.cases;
        for (k, &r) in kept.iter().enumerate() {
            t.vertices.as_flattened_mut()[k] = raw.vertices()[r];
            t.vertex_planes.as_flattened_mut()[k] =
                touching_planes(&raw.vertex_planes()[r], &tight, &clamped);
        }
        t.vertex_count = kept.len() as u8;
        for j in 0..18 {
            let mut out = [0u8; MAX_FACE];
            let mut len = 0;
            for &v in raw.face(j) {
                let v = new_index[v as usize];
                if len == 0 || out[len - 1] != v {
                    out[len] = v;
                    len += 1;
                }
            }
            while len > 1 && out[len - 1] == out[0] {
                len -= 1;
            }
            t.faces[j] = out;
            t.face_len[j] = if len >= 3 { len as u8 } else { 0 };
        }
        t
    }

    /// A simplified tribox: planes moved outward by at most `tol` so that small faces vanish,
    /// then cleaned (the paper's "small outward displacement on the bounding planes").
    ///
    /// Planes are taken in order 0..18. For plane j, the bound is compared with the largest
    /// value its direction takes on the polytope of the other 17 constraints (the position at
    /// which plane j stops touching the tribox: for a chamfer at most the block's corner). If
    /// moving plane j there is a displacement of at most `tol`, measured along its unit normal,
    /// and does not increase the number of faces, the bound is moved there (rounded outward).
    /// A plane never moves inward, so the simplified tribox contains the original one and every
    /// point it contained; `tol` is a distance in the units of the coordinates, and each plane
    /// moves at most once. A negative or NaN `tol` moves nothing.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // A unit cube with its edge x = y = 1 shaved by 0.001: the chamfer face x + y = 1.999 is
    /// // a thin strip.
    /// let mut pts: Vec<Point3> = (0..8)
    ///     .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
    ///     .filter(|p| p.x + p.y < 2.0)
    ///     .collect();
    /// for z in [0.0, 1.0] {
    ///     pts.push(Point3::new(1.0, 0.999, z));
    ///     pts.push(Point3::new(0.999, 1.0, z));
    /// }
    /// let t = TriboxBounds::from_points(&pts).boundary();
    /// assert_eq!(t.cleaned().face_count(), 7);
    /// let s = t.simplified(0.01);
    /// assert_eq!(s.face_count(), 6);
    /// assert!(pts.iter().all(|p| s.bounds().contains_point(p)));
    /// ```
    pub fn simplified(&self, tol: f64) -> Tribox {
        let mut current = self.cleaned();
        if current.is_empty() || tol.is_nan() || tol < 0.0 {
            return current;
        }
        let mut beta = self.bounds.offsets();
        for j in 0..18 {
            let Some(support) = support_without(j, &beta) else {
                continue;
            };
            // Displacement d = support − β_j, exactly, in half-units: 2d = Σ halves·β − 2β_j.
            let mut coef = support.dense();
            coef[j] -= 2;
            if sign_of_form(&coef, &beta) != Ordering::Greater {
                continue;
            }
            let distance = eval_form(&coef, &beta) * 0.5 / normal_norm(j);
            if distance.is_nan() || distance > tol {
                continue;
            }
            let mut moved = beta;
            moved[j] = round_up_form(support, &beta);
            let candidate = Tribox::new(&TriboxBounds::from_offsets(&moved)).cleaned();
            if candidate.face_count() <= current.face_count() {
                beta = moved;
                current = candidate;
            }
        }
        current
    }
}

/// Whether two computed points may be the same exact point: each coordinate is the correct
/// rounding of an exact sum, halved at most twice (exact but for subnormal results), so equal
/// exact values give doubles at most two steps apart.
fn close(p: &Point3, q: &Point3) -> bool {
    // Doubles ordered as integers (NaN and overflow aside): consecutive doubles differ by 1.
    let key = |x: f64| {
        let b = x.to_bits() as i64;
        if b < 0 { i64::MIN - b } else { b }
    };
    (0..3).all(|i| key(p[i]).abs_diff(key(q[i])) <= 2)
}

/// The Euclidean length of plane j's normal: 1 for principal planes, √2 for chamfers.
fn normal_norm(j: usize) -> f64 {
    if j < 6 { 1.0 } else { std::f64::consts::SQRT_2 }
}

/// Integer 3×3 determinant.
fn det3(m: [[i32; 3]; 3]) -> i32 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Integer adjugate: `adj(m) · m = det(m) · I`.
fn adjugate(m: [[i32; 3]; 3]) -> [[i32; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            // Cofactor (k, i).
            let r = [(k + 1) % 3, (k + 2) % 3];
            let c = [(i + 1) % 3, (i + 2) % 3];
            m[r[0]][c[0]] * m[r[1]][c[1]] - m[r[0]][c[1]] * m[r[1]][c[0]]
        })
    })
}

/// The normals of planes p as matrix rows.
fn normal_rows(p: [usize; 3]) -> [[i32; 3]; 3] {
    p.map(|j| normal(j).map(i32::from))
}

/// The exact coordinates of a vertex as linear forms in the 18 offsets β: coordinate i is
/// `Σ_k num[i][k] β_k / (2 den)`, solved by the adjugate from its three planes, each at its
/// tight offset (a form in half-units, see [`tight_forms`]).
struct VertexForm {
    num: [[i32; 18]; 3],
    den: i32,
}

impl VertexForm {
    fn new(planes: &[u8; 3], tight: &[[i32; 18]; 18]) -> Self {
        let p = planes.map(usize::from);
        let m = normal_rows(p);
        let adj = adjugate(m);
        let num = std::array::from_fn(|i| {
            std::array::from_fn(|k| (0..3).map(|r| adj[i][r] * tight[p[r]][k]).sum())
        });
        VertexForm { num, den: det3(m) }
    }

    /// Whether both forms have exactly the same value for every coordinate.
    fn equals(&self, other: &VertexForm, beta: &[f64; 18]) -> bool {
        (0..3).all(|i| {
            let coef: [i32; 18] =
                std::array::from_fn(|k| other.den * self.num[i][k] - self.den * other.num[i][k]);
            sign_of_form(&coef, beta) == Ordering::Equal
        })
    }
}

/// Each bound as the exact maximum of its direction over the tribox, as a form in half-units:
/// `tight[j]` has coefficients c with `h_j = Σ_k c_k β_k / 2`. It is `2 β_j` itself when plane j
/// touches the tribox, otherwise the least combination of other bounds (an optimal dual
/// basis, whose planes all touch the tribox by complementary slackness).
fn tight_forms(beta: &[f64; 18]) -> [[i32; 18]; 18] {
    std::array::from_fn(|j| {
        let mut own = [0; 18];
        own[j] = 2;
        match support_without(j, beta) {
            Some(basis) => {
                let halves = basis.dense();
                let coef: [i32; 18] = std::array::from_fn(|k| halves[k] - own[k]);
                if sign_of_form(&coef, beta) == Ordering::Less {
                    halves
                } else {
                    own
                }
            }
            None => own,
        }
    })
}

/// Calls `f` with the terms `c_k β_k` of an integer form, each coefficient split into signed
/// powers of two so that every term is an exact double (on the stack when there are few).
fn with_form_terms<R>(coef: &[i32; 18], beta: &[f64; 18], f: impl FnOnce(&[f64]) -> R) -> R {
    const STACK: usize = 64;
    let fill = |terms: &mut [f64]| {
        let mut n = 0;
        for (k, &c) in coef.iter().enumerate() {
            let mut m = c.unsigned_abs();
            let mut scale = if c < 0 { -beta[k] } else { beta[k] };
            while m != 0 {
                if m & 1 == 1 {
                    terms[n] = scale;
                    n += 1;
                }
                scale *= 2.0;
                m >>= 1;
            }
        }
        n
    };
    let count: u32 = coef.iter().map(|c| c.unsigned_abs().count_ones()).sum();
    if count as usize <= STACK {
        let mut terms = [0.0; STACK];
        let n = fill(&mut terms);
        f(&terms[..n])
    } else {
        let mut terms = vec![0.0; count as usize];
        let n = fill(&mut terms);
        f(&terms[..n])
    }
}

/// The exact sign of `Σ coef_k β_k`.
fn sign_of_form(coef: &[i32; 18], beta: &[f64; 18]) -> Ordering {
    with_form_terms(coef, beta, sum_sign)
}

/// `Σ coef_k β_k`, correctly rounded.
fn eval_form(coef: &[i32; 18], beta: &[f64; 18]) -> f64 {
    with_form_terms(coef, beta, accurate_sum)
}

/// Three planes with independent normals through a vertex of the cleaned boundary, each
/// touching the tribox, principal planes first: a plane whose bound was tightened stands for
/// the planes of its tight form, and a chamfer at its block corner for its two principal
/// planes (the vertex is on all of them, since their combination is an equality there).
fn touching_planes(planes: &[u8; 3], tight: &[[i32; 18]; 18], clamped: &[bool; 18]) -> [u8; 3] {
    let mut cand: Vec<u8> = Vec::with_capacity(9);
    for &j in planes {
        let form = &tight[j as usize];
        if form[j as usize] != 2 {
            cand.extend((0..18u8).filter(|&k| form[k as usize] != 0));
        } else if clamped[j as usize] {
            cand.extend(CHAMFER_PARENTS[j as usize]);
        } else {
            cand.push(j);
        }
    }
    cand.sort_unstable();
    cand.dedup();
    for a in 0..cand.len() {
        for b in a + 1..cand.len() {
            for c in b + 1..cand.len() {
                let p = [cand[a], cand[b], cand[c]];
                if det3(normal_rows(p.map(usize::from))) != 0 {
                    return p;
                }
            }
        }
    }
    *planes
}

/// A nonnegative combination of three plane normals equal to another plane's normal:
/// `Σ_i halves_i n_(planes_i) = 2 n_j` with `halves ≥ 0` (a dual feasible basis of the linear
/// program "maximise n_j · x over the other 17 half-spaces"); its value `Σ halves_i β_i / 2` is
/// an upper bound of n_j · x over the tribox.
#[derive(PartialEq)]
struct DualBasis {
    planes: [usize; 3],
    halves: [i32; 3],
}

impl DualBasis {
    /// The value, rounded (see [`support_without`] for its error).
    fn approx(&self, beta: &[f64; 18]) -> f64 {
        let [a, b, c] = self.planes;
        let [ha, hb, hc] = self.halves.map(f64::from);
        0.5 * (ha * beta[a] + hb * beta[b] + hc * beta[c])
    }

    /// The value as a dense form in half-units.
    fn dense(&self) -> [i32; 18] {
        let mut coef = [0; 18];
        for (&p, &h) in self.planes.iter().zip(&self.halves) {
            coef[p] += h;
        }
        coef
    }
}

/// For each plane j, the distinct dual feasible bases made of three other planes with
/// independent normals (computed once; 36 to 40 per plane).
fn dual_bases() -> &'static [Vec<DualBasis>; 18] {
    static TABLE: OnceLock<[Vec<DualBasis>; 18]> = OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|j| {
            let d = normal(j).map(i32::from);
            let mut out: Vec<DualBasis> = Vec::new();
            for a in 0..18 {
                for b in a + 1..18 {
                    for c in b + 1..18 {
                        if a == j || b == j || c == j {
                            continue;
                        }
                        // Columns are the normals: solve M λ = d with M = rowsᵀ.
                        let rows = normal_rows([a, b, c]);
                        let m: [[i32; 3]; 3] =
                            std::array::from_fn(|r| std::array::from_fn(|k| rows[k][r]));
                        let det = det3(m);
                        if det == 0 {
                            continue;
                        }
                        let adj = adjugate(m);
                        // λ = adj · d / det; in half-units (|det| is 1 or 2 for these normals).
                        let halves: [i32; 3] = std::array::from_fn(|k| {
                            (0..3).map(|r| adj[k][r] * d[r]).sum::<i32>() * 2 / det
                        });
                        if halves.iter().any(|&l| l < 0) {
                            continue;
                        }
                        // Keep the planes with a positive coefficient, padded by a zero term.
                        let mut basis = DualBasis {
                            planes: [a, b, c],
                            halves,
                        };
                        for k in 0..3 {
                            if basis.halves[k] == 0 {
                                basis.planes[k] = j;
                            }
                        }
                        if !out.iter().any(|o| o.dense() == basis.dense()) {
                            out.push(basis);
                        }
                    }
                }
            }
            out
        })
    })
}

/// The exact maximum of n_j · x over the polytope of the 17 half-spaces other than j, as the
/// least value of a dual feasible basis (linear programming duality); `None` when there is
/// none (the maximum is unbounded; never for bounds of points).
///
/// The rounded values pick the least candidate; only candidates within the rounding error of
/// it are compared exactly.
fn support_without(j: usize, beta: &[f64; 18]) -> Option<&'static DualBasis> {
    let candidates = &dual_bases()[j];
    let (mut best, least) = candidates
        .iter()
        .map(|c| c.approx(beta))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    // Each value is half a sum of three rounded products of magnitude at most 4 m (halves
    // ≤ 4), so the kernel's bound of a sum of three terms over 6 m bounds its error; two
    // values within twice that of each other may be in either order.
    let m = beta.iter().fold(0.0f64, |m, b| m.max(b.abs()));
    let slack = 2.0 * (24.0 * f64::EPSILON * m + f64::MIN_POSITIVE);
    for (i, c) in candidates.iter().enumerate() {
        if i != best && c.approx(beta) <= least + slack {
            let (cd, bd) = (c.dense(), candidates[best].dense());
            let diff: [i32; 18] = std::array::from_fn(|k| cd[k] - bd[k]);
            if sign_of_form(&diff, beta) == Ordering::Less {
                best = i;
            }
        }
    }
    candidates.get(best)
}

/// The smallest double at least `Σ halves_i β_i / 2`.
fn round_up_form(f: &DualBasis, beta: &[f64; 18]) -> f64 {
    let coef = f.dense();
    // Correctly rounded and halved: at most a step or two below the exact value.
    let mut r = eval_form(&coef, beta) * 0.5;
    while with_form_terms(&coef, beta, |terms| {
        let mut all = terms.to_vec();
        all.push(-2.0 * r);
        sum_sign(&all) == Ordering::Greater
    }) {
        r = r.next_up();
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift generator.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }

        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }

    /// The boundary by the generic corner formulas on exact forms (every clamped chamfer the
    /// form of its two principal bounds): each sign exact, each coordinate correctly rounded.
    fn reference(bounds: &TriboxBounds) -> Tribox {
        let beta = bounds.offsets();
        let clamped = clamped_chamfers(&beta);
        let forms: [[i32; 18]; 18] = std::array::from_fn(|j| {
            let mut f = [0; 18];
            if clamped[j] {
                for p in CHAMFER_PARENTS[j] {
                    f[usize::from(p)] = 2;
                }
            } else {
                f[j] = 2;
            }
            f
        });
        Tribox::from_corners(bounds, |c| {
            let planes = CORNER_PLANES[c];
            let (case, v) = corner(std::array::from_fn(|k| OffsetForm {
                coef: forms[usize::from(planes[k])],
                beta: &beta,
            }));
            (case, reflected(c, &v))
        })
    }

    /// Bit-for-bit equality of two boundaries (a zero's sign included).
    fn assert_same(t: &Tribox, r: &Tribox, b: &TriboxBounds) {
        assert_eq!(t.corner_cases(), r.corner_cases(), "{b:?}");
        let bits = |t: &Tribox| -> Vec<u64> {
            t.vertices()
                .iter()
                .flat_map(|p| [p.x, p.y, p.z].map(f64::to_bits))
                .collect()
        };
        assert_eq!(bits(t), bits(r), "{b:?}");
        assert_eq!(t.vertex_planes(), r.vertex_planes(), "{b:?}");
        for j in 0..18 {
            assert_eq!(t.face(j), r.face(j), "{b:?}");
        }
    }

    /// A random cloud of a few points: generic, on a coarse grid (many exact ties and clamped
    /// chamfers whose sums cancel exactly), or of wildly different magnitudes; scaled by a
    /// power of ten from 1e-310 to 1e300, mixed signs (and no sum of bounds overflows).
    fn cloud(rng: &mut Rng) -> Vec<Point3> {
        const SCALES: [f64; 8] = [1.0, 1e-300, 1e300, 1e-160, 3e150, 1e-310, 0.1, -7.0];
        let scale = SCALES[rng.below(8) as usize];
        let kind = rng.below(6);
        let n = 1 + rng.below(9) as usize;
        (0..n)
            .map(|_| {
                let mut c = [0.0; 3];
                for x in &mut c {
                    *x = scale
                        * match kind {
                            0 => 2.0 * rng.unit() - 1.0,
                            1 => (rng.below(5) as f64 - 2.0) * 0.5,
                            2 => rng.below(3) as f64,
                            3 => (rng.unit() - 0.5) * 2f64.powi(rng.below(120) as i32 - 100),
                            4 => rng.below(4) as f64 * 0.1 + [0.0, 1e-17][rng.below(2) as usize],
                            _ => rng.unit(),
                        };
                }
                Point3::new(c[0], c[1], c[2])
            })
            .collect()
    }

    #[test]
    fn simplified_forms_match_the_exact_formulas() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut masks = [0usize; 8];
        let mut cases = [0usize; 5];
        for it in 0..100_000 {
            let mut b = TriboxBounds::from_points(&cloud(&mut rng));
            if it % 3 == 2 {
                // Bounds of no point set: random cuts across random directions.
                for _ in 0..1 + rng.below(4) {
                    let d = rng.below(9) as usize;
                    let (lo, hi) = (b.min()[d], b.max()[d]);
                    let pick = b.split(d, lo + (hi - lo) * rng.unit())[rng.below(2) as usize];
                    if !pick.is_empty() {
                        b = pick;
                    }
                }
            }
            let t = Tribox::new(&b);
            assert_same(&t, &reference(&b), &b);
            let clamped = clamped_chamfers(&b.offsets());
            for (c, planes) in CORNER_PLANES.iter().enumerate() {
                let mask = (3..6).fold(0, |m, k| {
                    m | usize::from(clamped[usize::from(planes[k])]) << (k - 3)
                });
                masks[mask] += 1;
                cases[usize::from(t.corner_cases()[c])] += 1;
            }
        }
        // Every clamp mask and every case is exercised.
        assert!(masks.iter().all(|&m| m > 100), "{masks:?}");
        assert!(cases[1..].iter().all(|&m| m > 100), "{cases:?}");
    }

    /// Bounds on the edge of every filter: small integers times a power of two (so that
    /// chamfers equal the sum of their principal bounds, and p lies on a principal plane,
    /// exactly and often), with chamfers set to the rounded sum of their principal bounds and
    /// bounds moved by an ulp either way; from subnormal scales to near overflow.
    fn edge_bounds(rng: &mut Rng) -> TriboxBounds {
        const SCALES: [i32; 8] = [-1074, -1060, -1000, -500, 0, 30, 500, 1000];
        let scale = 2f64.powi(SCALES[rng.below(8) as usize]);
        // An odd factor makes sums inexact (and their errors ties of a half ulp) at times.
        let factor = [1.0, 3.0, 0.1, 1.0 + f64::EPSILON][rng.below(4) as usize];
        let mut beta: [f64; 18] = std::array::from_fn(|j| {
            let range = if j < 6 { 5 } else { 9 };
            (rng.below(range) as f64 - 1.0) * factor * scale
        });
        for j in 6..18 {
            if rng.below(2) == 0 {
                let [p, q] = CHAMFER_PARENTS[j].map(usize::from);
                beta[j] = beta[p] + beta[q];
            }
        }
        for _ in 0..rng.below(4) {
            let j = rng.below(18) as usize;
            beta[j] = if rng.below(2) == 0 {
                beta[j].next_up()
            } else {
                beta[j].next_down()
            };
        }
        TriboxBounds::from_offsets(&beta)
    }

    #[test]
    fn ties_and_near_ties_match_the_exact_formulas() {
        let mut rng = Rng(0x0bad_cafe_f00d_d00d);
        // Corner tests (x_p > α_A and cyclically) that are exactly zero, and that the rounded
        // doubled p cannot decide (equal to 2α but not exactly), on unclamped corners.
        let (mut zero, mut undecided, mut clamp_ties) = (0, 0, 0);
        for _ in 0..200_000 {
            let b = edge_bounds(&mut rng);
            if b.is_empty() {
                continue;
            }
            let t = Tribox::new(&b);
            assert_same(&t, &reference(&b), &b);
            let beta = b.offsets();
            for j in 6..18 {
                let [p, q] = CHAMFER_PARENTS[j].map(usize::from);
                clamp_ties += usize::from(beta[j] == beta[p] + beta[q]);
            }
            let clamped = clamped_chamfers(&beta);
            for planes in CORNER_PLANES {
                let al = planes.map(|j| beta[usize::from(j)]);
                if (3..6).any(|k| clamped[usize::from(planes[k])]) {
                    continue;
                }
                for (i, test) in CASE_TESTS.iter().enumerate() {
                    let terms = test.map(|(k, c)| f64::from(c) * al[k]);
                    let twice_p = accurate_sum(&terms[..3]);
                    if sum_sign(&terms) == Ordering::Equal {
                        zero += 1;
                    } else if twice_p == 2.0 * al[i] {
                        undecided += 1;
                    }
                }
            }
        }
        assert!(zero > 2_000 && undecided > 1_000, "{zero} {undecided}");
        assert!(clamp_ties > 10_000, "{clamp_ties}");
    }
}
