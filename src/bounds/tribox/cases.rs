//! The block's corners and the paper's four cases (section 3): the numbering of the 8
//! corners by their coordinate signs, the six local planes of the canonical corner, and per
//! case the planes defining the corner's four vertex slots and each local face's sub-list.
//! Cases 3 and 4 are case 2 in a rotated frame. Everything here is computed at compile time.

use super::directions::{DIRS, plane_of};

/// The signs (sx, sy, sz) of corner `c`: bit i set means the minimum along axis i.
pub(super) const fn corner_signs(c: usize) -> [i8; 3] {
    [
        if c & 1 == 0 { 1 } else { -1 },
        if c & 2 == 0 { 1 } else { -1 },
        if c & 4 == 0 { 1 } else { -1 },
    ]
}

/// The corner with signs `s`.
pub(super) const fn corner_of(s: [i8; 3]) -> usize {
    (s[0] < 0) as usize | ((s[1] < 0) as usize) << 1 | ((s[2] < 0) as usize) << 2
}

/// Local plane A of the canonical corner, X ≤ α_A. The local planes A, B, C, AB, AC, BC are,
/// as vectors in the reflected frame, the first six directions ([`DIRS`] 0..6: x, y, z, x+y,
/// x+z, y+z).
pub(super) const A: usize = 0;
/// Local plane B, Y ≤ α_B.
pub(super) const B: usize = 1;
/// Local plane C, Z ≤ α_C.
pub(super) const C: usize = 2;
/// Local chamfer plane AB, X + Y ≤ α_AB.
pub(super) const AB: usize = 3;
/// Local chamfer plane AC, X + Z ≤ α_AC.
pub(super) const AC: usize = 4;
/// Local chamfer plane BC, Y + Z ≤ α_BC.
pub(super) const BC: usize = 5;

/// `CORNER_PLANES[c][k]`: the global plane of local plane k (A, B, C, AB, AC, BC) at corner c.
pub(super) const CORNER_PLANES: [[u8; 6]; 8] = {
    let mut t = [[0u8; 6]; 8];
    let mut c = 0;
    while c < 8 {
        let s = corner_signs(c);
        let mut k = 0;
        while k < 6 {
            let l = DIRS[k];
            t[c][k] = plane_of([l[0] * s[0], l[1] * s[1], l[2] * s[2]]);
            k += 1;
        }
        c += 1;
    }
    t
};

/// A sub-list: up to 4 vertex indices (unused entries 0) and its length.
pub(super) type SubList = ([u8; 4], u8);

/// Per case (1..4, index case − 1): the local planes defining each of the corner's 4 vertex
/// slots, and each local face's sub-list of slots (counter-clockwise seen from outside in the
/// canonical frame). Case 1 slots: v1, v2, v3, p; case 2 slots: v1, v3, q2 = A∩AC∩BC and
/// q3 = A∩AB∩BC (the paper's v'_2 and v''_3).
pub(super) struct CaseTable {
    pub(super) slot_planes: [[usize; 3]; 4],
    pub(super) sub_lists: [SubList; 6],
}

/// Case 1: p inside the block; slots v1, v2, v3, p.
pub(super) const CASE1: CaseTable = CaseTable {
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

/// Case 2: p beyond h_A; slots v1, v3, q2, q3.
pub(super) const CASE2: CaseTable = CaseTable {
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
pub(super) const ROTATION: [usize; 6] = [B, C, A, BC, AB, AC];
/// The rotation applied twice (x→z→y→x): A' = C, B' = A, C' = B.
pub(super) const ROTATION2: [usize; 6] = [C, A, B, AC, BC, AB];

/// Case table `t` seen in the frame rotated by `sigma`: slot planes renamed, sub-lists moved
/// to the renamed faces.
pub(super) const fn rotate_case(t: &CaseTable, sigma: [usize; 6]) -> CaseTable {
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

/// The four cases, index case − 1: cases 3 and 4 are case 2 rotated once and twice.
pub(super) const CASES: [CaseTable; 4] = [
    CASE1,
    CASE2,
    rotate_case(&CASE2, ROTATION),
    rotate_case(&CASE2, ROTATION2),
];

/// The coordinate signs of each corner, as doubles.
pub(super) const CORNER_SIGNS: [[f64; 3]; 8] = {
    let mut t = [[0.0; 3]; 8];
    let mut c = 0;
    while c < 8 {
        let s = corner_signs(c);
        t[c] = [s[0] as f64, s[1] as f64, s[2] as f64];
        c += 1;
    }
    t
};
