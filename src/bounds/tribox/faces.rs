//! The topology of a raw boundary, tabulated at compile time from the case tables: which
//! corners each face meets (counter-clockwise), each corner's vertex planes and sub-lists in
//! global indices, and the loop of every face for every combination of its corners' cases.

use super::cases::{AB, AC, BC, CASES, CORNER_PLANES, SubList, corner_of, corner_signs};
use super::directions::normal;

/// The most vertices a raw boundary has: four per corner.
pub(super) const MAX_VERTICES: usize = 32;
/// The longest face loop: 4 corners × 2 vertices (principal) or 2 corners × 4 (chamfer).
pub(super) const MAX_FACE: usize = 8;

/// `FACE_CORNERS[j]`: the (corner, local plane) pairs incident to plane j, counter-clockwise
/// seen from outside; principal planes have 4, chamfer planes 2 (their order is then immaterial).
pub(super) const FACE_CORNERS: [([(u8, u8); 4], u8); 18] = {
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

/// `VERTEX_PLANES[c][case][slot]`: the global planes (ascending) defining a corner's vertex.
pub(super) const VERTEX_PLANES: [[[[u8; 3]; 4]; 4]; 8] = {
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

/// `SUB_LISTS[c][case][local]`: a corner's sub-list for a local face as global vertex indices
/// (4c + slot), reversed at corners whose reflection reverses orientation (sx·sy·sz = −1).
pub(super) const SUB_LISTS: [[[SubList; 6]; 4]; 8] = {
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
pub(super) const fn face_loop(j: usize, combo: usize) -> (u64, u8) {
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
pub(super) struct FaceLoops<const F: usize, const COMBOS: usize> {
    pub(super) loops: [[u64; F]; COMBOS],
    pub(super) lens: [[u8; F]; COMBOS],
}

impl<const F: usize, const COMBOS: usize> FaceLoops<F, COMBOS> {
    /// The table for the `F` faces from plane `first` on.
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
pub(super) static PRINCIPAL_LOOPS: FaceLoops<6, 256> = FaceLoops::new(0);
/// The loops of the 12 chamfer faces (2 corners each).
pub(super) static CHAMFER_LOOPS: FaceLoops<12, 16> = FaceLoops::new(6);

/// The vertex planes and face loops of a boundary, as [`Tribox`] stores them.
pub(super) struct Topology {
    pub(super) vertex_planes: [[[u8; 3]; 4]; 8],
    pub(super) faces: [[u8; MAX_FACE]; 18],
    pub(super) face_len: [u8; 18],
}

/// The topology of the generic boundary, every corner in case 1 (combination 0 of every face).
pub(super) static GENERIC: Topology = {
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
pub(super) const FACE_CORNER_INDICES: [[usize; 4]; 18] = {
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
