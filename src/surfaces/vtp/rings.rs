//! Rings from the boundary pieces: pieces are linked head to tail (at a point where rings
//! touch, the next piece is the first one clockwise from the way back), a ring through a point
//! twice is split there, vertices between two pieces of one line are dropped, and a ring's
//! turning tells an outer ring from a hole.

use super::Vtp;
use std::cmp::Ordering;
use std::collections::HashMap;

impl<'a> Vtp<'a> {
    /// The boundary pieces linked into rings (of piece indices): at a point with several ways
    /// on, the first one clockwise from the way back; pieces along one line merged; rings
    /// through a point twice split there.
    pub(super) fn link(&self, pieces: &[BoundaryPiece]) -> Vec<Vec<usize>> {
        let mut leaving: HashMap<u32, Vec<usize>> = HashMap::new();
        for (i, p) in pieces.iter().enumerate() {
            leaving.entry(p.from).or_default().push(i);
        }
        let mut used = vec![false; pieces.len()];
        let mut rings = Vec::new();
        for start in 0..pieces.len() {
            if used[start] {
                continue;
            }
            let mut ring = Vec::new();
            let mut current = start;
            loop {
                used[current] = true;
                ring.push(current);
                let options = leaving.get(&pieces[current].to).map_or(&[][..], |v| &v[..]);
                let next = match options {
                    [only] => Some(*only),
                    _ => self.next_clockwise(pieces, current, options),
                };
                match next {
                    Some(n) if n == start => break,
                    Some(n) if !used[n] => current = n,
                    // Not closed (cannot happen for a boundary of cells): drop the ring.
                    _ => {
                        ring.clear();
                        break;
                    }
                }
            }
            if !ring.is_empty() {
                rings.extend(split_at_repeats(pieces, ring));
            }
        }
        rings
            .into_iter()
            .map(|r| merge_collinear(pieces, r))
            .filter(|r| r.len() >= 3)
            .collect()
    }

    /// Among `options` leaving the end of piece `incoming`, the first clockwise from the way
    /// back along `incoming` (seen from the side F's plane's gradient points to).
    pub(super) fn next_clockwise(
        &self,
        pieces: &[BoundaryPiece],
        incoming: usize,
        options: &[usize],
    ) -> Option<usize> {
        let back = (pieces[incoming].line, !pieces[incoming].forward);
        let dir = |p: usize| (pieces[p].line, pieces[p].forward);
        let orient = |x: (u32, bool), y: (u32, bool)| -> Ordering {
            let t = self.turn(x.0, y.0);
            if x.1 == y.1 { t } else { t.reverse() }
        };
        let half = |p: usize| match orient(back, dir(p)) {
            Ordering::Less => 0,
            Ordering::Equal => 1,
            Ordering::Greater => 2,
        };
        options.iter().copied().min_by(|&x, &y| {
            half(x)
                .cmp(&half(y))
                .then_with(|| match orient(dir(x), dir(y)) {
                    Ordering::Less => Ordering::Less,
                    Ordering::Greater => Ordering::Greater,
                    Ordering::Equal => x.cmp(&y),
                })
        })
    }

    /// The total turning of a ring of pieces, in radians (±2π): each turn's size from the
    /// rounded directions of the lines, its sign exact.
    pub(super) fn turning(&self, pieces: &[BoundaryPiece], ring: &[usize]) -> f64 {
        let n = ring.len();
        let direction = |p: &BoundaryPiece| {
            let d = self.lines[p.line as usize].direction();
            let s = if p.forward { 1.0 } else { -1.0 };
            let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            d.map(|c| s * c / norm)
        };
        (0..n)
            .map(|i| {
                let (p, q) = (&pieces[ring[i]], &pieces[ring[(i + 1) % n]]);
                let (a, b) = (direction(p), direction(q));
                let cross = [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ];
                let size = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2])
                    .sqrt()
                    .atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
                let t = self.turn(p.line, q.line);
                let sign = if p.forward == q.forward {
                    t
                } else {
                    t.reverse()
                };
                match sign {
                    Ordering::Greater => size,
                    Ordering::Less => -size,
                    Ordering::Equal => 0.0,
                }
            })
            .sum()
    }
}

/// The ring split into rings through distinct points.
pub(super) fn split_at_repeats(pieces: &[BoundaryPiece], ring: Vec<usize>) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut todo = vec![ring];
    while let Some(ring) = todo.pop() {
        let mut seen: HashMap<u32, usize> = HashMap::new();
        let repeat = ring
            .iter()
            .enumerate()
            .find_map(|(j, &p)| seen.insert(pieces[p].from, j).map(|i| (i, j)));
        match repeat {
            Some((i, j)) => {
                todo.push(ring[i..j].to_vec());
                todo.push(ring[j..].iter().chain(&ring[..i]).copied().collect());
            }
            None => out.push(ring),
        }
    }
    out
}

/// The ring with consecutive pieces along one line joined.
pub(super) fn merge_collinear(pieces: &[BoundaryPiece], ring: Vec<usize>) -> Vec<usize> {
    let n = ring.len();
    // Keep a piece when the one before it runs along another line.
    let kept: Vec<usize> = (0..n)
        .filter(|&i| pieces[ring[(i + n - 1) % n]].line != pieces[ring[i]].line)
        .map(|i| ring[i])
        .collect();
    if kept.is_empty() { ring } else { kept }
}

/// A piece of the boundary of the cells' union: from one point to another along a line, the
/// way `q_L` points (`forward`) or against it, with a cell on its left.
#[derive(Debug, Clone, Copy)]
pub(super) struct BoundaryPiece {
    pub(super) from: u32,
    pub(super) to: u32,
    pub(super) line: u32,
    pub(super) forward: bool,
    pub(super) cell: usize,
}
