//! Stage 4 of the pass: the occluder index over the meshes' pictures, then every line's
//! visible and hidden runs, decided piece by piece (see `pieces.rs`) in parallel.

use super::cover::{Occluders, PicturedMesh};
use super::line::Cut;
use super::pass::{Pass, timed};
use super::piece::Piece;
use super::pieces::{line_pieces, pieces};
use crate::queries::Counters;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering as Atomic};
use std::time::Instant;

/// Meshes with more triangles than this use no INBOX: their picture cells answer directly,
/// and the greedy INBOX of a large non-convex mesh costs more to build than it saves.
pub(super) const INBOX_LIMIT: usize = 4096;

impl Pass<'_> {
    /// Stage 4: the occluder index, then the visible and hidden runs of every line.
    pub(super) fn visibility(&mut self, progress: &(dyn Fn(u64, u64) + Sync)) -> Vec<Piece> {
        let clock = Instant::now();
        let meshes: Vec<PicturedMesh> = self
            .leaves
            .iter()
            .map(|l| {
                (
                    l.id,
                    l.mesh,
                    l.pictures.as_slice(),
                    l.front.as_slice(),
                    l.turned.as_slice(),
                )
            })
            .collect();
        let queries = self.lines.iter().filter(|l| !l.back).count() + self.cuts.len();
        let occluders = Occluders::new(
            self.scene,
            (self.eye, self.picture),
            self.clip.map(|c| c.window()),
            &meshes,
            INBOX_LIMIT,
            queries,
        );
        let large = meshes
            .iter()
            .filter(|(_, m, ..)| m.triangles().len() > INBOX_LIMIT)
            .count();
        let done = format!(
            "{} meshes' triangles listed by picture cells ({} entries)",
            meshes.len(),
            occluders.entries()
        );
        let away = occluders.turned_away();
        let skipped = (large > 0 || away > 0).then(|| {
            let mut parts = Vec::new();
            if away > 0 {
                parts.push(format!(
                    "{away} triangles turned away from the eye (their own solid hides what \
                     they would)"
                ));
            }
            if large > 0 {
                parts.push(format!(
                    "INBOX of {large} meshes of more than {INBOX_LIMIT} triangles (their \
                     picture cells answer directly)"
                ));
            }
            parts.join("; ")
        });
        timed(&mut self.stages, "occluders", clock, done, skipped);

        let clock = Instant::now();
        let cuts = &self.cuts;
        let lines = &self.lines;
        let (first_cut, by_line) = cuts_by_line(cuts, lines.len());
        let done = AtomicU64::new(0);
        let total = lines.len() as u64;
        let (scene, eye, picture, meets) = (self.scene, &self.eye, &self.picture, &self.meets);
        let clip = (self.clip, self.tile.as_ref());
        let decided: Vec<(Vec<Piece>, Counters)> = (0..lines.len())
            .into_par_iter()
            .map(|l| {
                let n = done.fetch_add(1, Atomic::Relaxed) + 1;
                if n.is_multiple_of(1024) || n == total {
                    progress(n, total);
                }
                let mut line_cuts: Vec<(u32, &Cut)> = by_line[first_cut[l]..first_cut[l + 1]]
                    .iter()
                    .map(|&k| (k, &cuts[k as usize].1))
                    .collect();
                line_cuts.sort_unstable_by(|x, y| x.1.zero.t.total_cmp(&y.1.zero.t));
                match lines[l].meet {
                    Some(m) => line_pieces(
                        &occluders,
                        scene,
                        eye,
                        picture,
                        clip,
                        (l, &lines[l], &meets[m]),
                        &line_cuts,
                    ),
                    None => pieces(
                        &occluders,
                        scene,
                        eye,
                        picture,
                        clip,
                        (l, &lines[l]),
                        &line_cuts,
                    ),
                }
            })
            .collect();
        let (all, done) = merged(decided);
        timed(&mut self.stages, "visibility", clock, done, None);
        all
    }
}

/// The cuts grouped by line (a counting sort of their indices: the cuts stay in place): for
/// each of the `lines`, where its cuts begin in the second list (and where the next line's
/// begin), and the cuts' indices line by line.
fn cuts_by_line(cuts: &[(usize, Cut)], lines: usize) -> (Vec<usize>, Vec<u32>) {
    let mut first_cut = vec![0usize; lines + 1];
    for &(l, _) in cuts.iter() {
        first_cut[l + 1] += 1;
    }
    for l in 0..lines {
        first_cut[l + 1] += first_cut[l];
    }
    let mut by_line = vec![0u32; cuts.len()];
    let mut next = first_cut.clone();
    for (k, &(l, _)) in cuts.iter().enumerate() {
        by_line[next[l]] = k as u32;
        next[l] += 1;
    }
    (first_cut, by_line)
}

/// Every line's pieces in line order, and what deciding them took, for `--stats`.
fn merged(decided: Vec<(Vec<Piece>, Counters)>) -> (Vec<Piece>, String) {
    let mut counters = Counters::default();
    let mut all = Vec::new();
    for (p, c) in decided {
        counters = counters.merged(&c);
        all.extend(p);
    }
    let done = format!(
        "{} pieces decided by VISP: {} by CBOX, {} by INBOX, {} by faces",
        counters.total(),
        counters.cbox,
        counters.inbox,
        counters.faces
    );
    (all, done)
}
