//! Which triangles the pair search still lists: those a certified patch does not cover.

use super::{NONE, Patches};
use crate::geometry::Aabb;
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// Which triangles a pair search must list, given their certified `patches`
/// ([`super::certified`]) and `boxes`: those in no certified patch, and those whose box
/// meets the box of a piece of another patch or of a triangle in none. Any other triangle
/// can meet only triangles of its own patch, which the certificate proves apart.
pub(in crate::sight::intersections) fn listed(patches: &Patches, boxes: &[Aabb]) -> Vec<bool> {
    let (piece, pieces) = (&patches.piece, patches.piece_patch.len());
    let patch_of = |p: u32| {
        if p == NONE {
            NONE
        } else {
            patches.piece_patch[p as usize]
        }
    };
    let uncertified = piece.iter().filter(|&&p| p == NONE).count();
    if pieces == 0 || uncertified > piece.len() / 4 {
        // Most triangles are listed anyway: not worth a tree of their boxes.
        return vec![true; piece.len()];
    }
    let mut piece_boxes = vec![Aabb::EMPTY; pieces];
    for (t, &p) in piece.iter().enumerate() {
        if p != NONE {
            piece_boxes[p as usize] = piece_boxes[p as usize].union(&boxes[t]);
        }
    }
    // Every box that may block: each piece's, and each triangle's in no patch.
    let rectangle = |b: &Aabb| Rectangle::from_corners(b.min, b.max);
    let blockers: Vec<GeomWithData<Rectangle<[f64; 3]>, u32>> = piece_boxes
        .iter()
        .enumerate()
        .filter(|(_, b)| !b.is_empty())
        .map(|(p, b)| GeomWithData::new(rectangle(b), p as u32))
        .chain(
            (0..piece.len())
                .filter(|&t| piece[t] == NONE)
                .map(|t| GeomWithData::new(rectangle(&boxes[t]), NONE)),
        )
        .collect();
    let tree = RTree::bulk_load(blockers);
    // Per piece, the boxes of other patches that meet its own (`None`: too many, all its
    // triangles listed).
    let near: Vec<Option<Vec<Aabb>>> = piece_boxes
        .par_iter()
        .enumerate()
        .map(|(p, b)| {
            let mut found = Vec::new();
            if b.is_empty() {
                return Some(found);
            }
            let envelope = AABB::from_corners(b.min, b.max);
            for x in tree.locate_in_envelope_intersecting(&envelope) {
                if patch_of(x.data) != patch_of(p as u32) {
                    if found.len() == NEAR {
                        return None;
                    }
                    let r = x.geom();
                    found.push(Aabb::new(r.lower().into(), r.upper().into()));
                }
            }
            Some(found)
        })
        .collect();
    piece
        .par_iter()
        .zip(boxes)
        .map(|(&p, b)| {
            p == NONE
                || near[p as usize]
                    .as_ref()
                    .is_none_or(|near| near.iter().any(|n| n.intersects(b)))
        })
        .collect()
}

/// A piece whose box meets more than this many boxes of other patches has all its
/// triangles listed.
const NEAR: usize = 64;
