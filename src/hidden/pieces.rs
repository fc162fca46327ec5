//! The pieces of one line between its cuts, each decided by one VISP query at a point strictly
//! inside it: [`pieces`] for an edge, [`line_pieces`] for an intersection line (stage 4, see
//! `visibility.rs`).

use super::cover::Occluders;
use super::cuts::TILE_CUT;
use super::line::{Cut, Line, MeetLine, on_faces};
use super::marks::Mark;
use super::piece::Piece;
use super::runs::Runs;
use crate::geometry::Point3;
use crate::queries::Counters;
use crate::queries::visp::Visibility;
use crate::scene::{ObjectId, Scene};
use crate::sight::along::{Form, Sample, cut_point, hides_at};
use crate::sight::frustum::{Clip, TilePlanes};
use crate::sight::meet::{OnLine, balance};
use crate::views::{Eye, Picture};
use std::cmp::Ordering;

/// The visible and hidden runs of the edge `l` (index `line`) cut at `cuts` (sorted by their
/// approximate parameters), and the stages that decided its pieces. The cuts are put in their
/// exact order along the edge (their parameters' error bounds leave only near ties to decide
/// exactly, and a near tie's parameter is then correctly rounded, so the pieces' ranges follow
/// that order), those at one point taken once (the smallest key); each piece between two
/// consecutive cuts is decided at a point strictly inside it ([`Sample`]).
pub(super) fn pieces(
    occluders: &Occluders,
    scene: &Scene,
    eye: &Eye,
    picture: &Picture,
    (clip, tile): (Option<Clip>, Option<&TilePlanes>),
    (line, l): (usize, &Line),
    cuts: &[(u32, &Cut)],
) -> (Vec<Piece>, Counters) {
    let mut counters = Counters::default();
    if l.back && !l.clipped {
        let piece = Piece {
            class: l.class,
            visible: false,
            ends: l.ends,
            line,
            t: [0.0, 1.0],
            border: [false; 2],
            marks: [Mark::First, Mark::Last],
        };
        return (vec![piece], counters);
    }
    let (a, b) = (&l.a, &l.b);
    let merged = ordered(eye, l, cuts);
    let bounds: Vec<((u32, &Cut), bool)> = merged.iter().map(|((i, c), b)| ((*i, c), *b)).collect();
    let mut runs = Runs::new(l, line);
    for k in 0..=bounds.len() {
        let (lo, border) = match k.checked_sub(1).map(|k| bounds[k]) {
            Some(((index, c), border)) => (Some((index, c)), border),
            None => (None, false),
        };
        let mark = lo.map_or(Mark::First, |(index, _)| Mark::Cut(index));
        let lo = lo.map(|(_, c)| c);
        let sample = Sample::between(
            eye,
            a,
            b,
            [lo.map(|c| &c.zero), bounds.get(k).map(|c| &c.0.1.zero)],
        );
        let sign = |form: &Form| sample.sign(form, eye, a, b);
        let state = if l.clipped && !inside(clip, tile, sign) {
            None
        } else if l.back {
            Some(false)
        } else {
            let (approximate, radius) = sample.point(a, b);
            let hides = |object: ObjectId, tri: usize| {
                scene[object]
                    .mesh()
                    .is_some_and(|m| hides_at(eye, &m.triangle(tri), sign))
            };
            let answer = occluders.visp((&approximate, radius), hides, &mut counters);
            Some(answer == Visibility::Visible)
        };
        runs.step(state, (lo.map_or(0.0, |c| c.zero.t), mark), border, || {
            cut_picture(picture, eye, l, lo)
        });
    }
    (runs.finish(l.ends[1]), counters)
}

/// The cuts of the edge `l` (sorted by their approximate parameters) in their exact order
/// along it, those at one point taken once (the smallest key), each with whether a tile's
/// plane passes through it (see [`pieces`]).
fn ordered(eye: &Eye, l: &Line, cuts: &[(u32, &Cut)]) -> Vec<((u32, Cut), bool)> {
    let (a, b) = (&l.a, &l.b);
    let order = |x: &Cut, y: &Cut| x.zero.compare(&y.zero, eye, a, b);
    // Insertion sort: the cuts come sorted by parameter, so only near ties move.
    let mut sorted = cuts.to_vec();
    for i in 1..sorted.len() {
        let mut j = i;
        while j > 0 && order(sorted[j].1, sorted[j - 1].1) == Ordering::Less {
            sorted.swap(j, j - 1);
            j -= 1;
        }
    }
    // Each point once, with whether a tile's plane passes through it.
    let mut merged: Vec<((u32, Cut), bool)> = Vec::with_capacity(sorted.len());
    for (index, c) in sorted {
        let border = c.key[0] == TILE_CUT;
        match merged.last_mut() {
            Some((last, on_border)) if order(&last.1, c) == Ordering::Equal => {
                *on_border |= border;
                if c.key < last.1.key {
                    *last = (index, *c);
                }
            }
            _ => merged.push(((index, *c), border)),
        }
    }
    // The pieces' parameter ranges in the exact order too (verify checks the pieces by them):
    // a near tie's rough parameters may be out of order, so each point near another takes its
    // parameter correctly rounded, which is monotone.
    let near: Vec<bool> = (0..merged.len())
        .map(|k| {
            let z = &merged[k].0.1.zero;
            let near = |j: usize| merged.get(j).is_some_and(|(c, _)| c.1.zero.near(z));
            (k > 0 && near(k - 1)) || near(k + 1)
        })
        .collect();
    for (((_, cut), _), near) in merged.iter_mut().zip(near) {
        if near {
            cut.zero = cut.zero.correctly_rounded(eye, a, b);
        }
    }
    merged
}

/// The visible and hidden runs of the intersection line `l` (lying on `m`) cut at `cuts`
/// (strictly inside it), and the stages that decided its pieces. The cuts are ordered along
/// the line exactly, those at one point taken once (the smallest key); each piece between two
/// consecutive points is decided at a point strictly inside it defined from the input
/// ([`Meet::sign_between`](crate::sight::meet::Meet::sign_between)).
pub(super) fn line_pieces(
    occluders: &Occluders,
    scene: &Scene,
    eye: &Eye,
    picture: &Picture,
    (clip, tile): (Option<Clip>, Option<&TilePlanes>),
    (line, l, m): (usize, &Line, &MeetLine),
    cuts: &[(u32, &Cut)],
) -> (Vec<Piece>, Counters) {
    let meet = &m.meet;
    let inner = ordered_on_line(eye, m, cuts);
    let points: Vec<OnLine> = std::iter::once(m.ends[0])
        .chain(inner.iter().map(|x| x.0))
        .chain(std::iter::once(m.ends[1]))
        .collect();
    let drawn = |k: usize| -> [f64; 2] {
        if k == 0 {
            return l.ends[0];
        }
        if k == points.len() - 1 {
            return l.ends[1];
        }
        match inner[k - 1].1.1.sighted {
            Some(p) => p,
            None => meet.picture(picture, eye, &points[k]),
        }
    };
    let weights: Vec<f64> = points.iter().map(|p| meet.weight(eye, p)).collect();
    let places: Vec<Point3> = points.iter().map(|p| meet.approximate(eye, p)).collect();
    let magnitudes: Vec<f64> = points.iter().map(|p| meet.magnitude(p)).collect();
    // Each point's rough parameter along the line, for the pieces' provenance.
    let along = |k: usize| {
        if k == 0 {
            (0.0, Mark::First)
        } else {
            (inner[k - 1].1.1.zero.t, Mark::Cut(inner[k - 1].1.0))
        }
    };
    let mut counters = Counters::default();
    let mut runs = Runs::new(l, line);
    for k in 0..points.len() - 1 {
        let scales = [balance(weights[k]), balance(weights[k + 1])];
        let sign = |form: &Form| meet.sign_between(eye, [&points[k], &points[k + 1]], scales, form);
        let state = if l.clipped && !inside(clip, tile, sign) {
            None
        } else {
            let (u, v) = (weights[k] * scales[0], weights[k + 1] * scales[1]);
            let approximate =
                Point3::from((places[k].coords * u + places[k + 1].coords * v) / (u + v));
            // The places are within 2⁻⁴² of their magnitudes, the weights within 2⁻⁴² of
            // theirs: the point between them is within 2⁻³⁹ of those magnitudes.
            let radius = [k, k + 1]
                .iter()
                .map(|&i| magnitudes[i].max(places[i].coords.amax()))
                .fold(0.0f64, f64::max)
                / (1u64 << 39) as f64;
            let hides = |object: ObjectId, tri: usize| {
                !on_faces(m, scene, object, tri)
                    && scene[object]
                        .mesh()
                        .is_some_and(|mesh| hides_at(eye, &mesh.triangle(tri), sign))
            };
            let answer = occluders.visp((&approximate, radius), hides, &mut counters);
            Some(answer == Visibility::Visible)
        };
        let border = k > 0 && inner[k - 1].2;
        runs.step(state, along(k), border, || drawn(k));
    }
    (runs.finish(l.ends[1]), counters)
}

/// The cuts of the intersection line `m` ordered along it exactly, those at one point taken
/// once (the smallest key), each as a point of the line and with whether a tile's plane
/// passes through it (see [`line_pieces`]).
fn ordered_on_line<'c>(
    eye: &Eye,
    m: &MeetLine,
    cuts: &[(u32, &'c Cut)],
) -> Vec<(OnLine, (u32, &'c Cut), bool)> {
    let meet = &m.meet;
    let mut sorted: Vec<(OnLine, (u32, &Cut))> = cuts.iter().map(|&c| (c.1.point(), c)).collect();
    // Stable: the cuts come roughly sorted already.
    sorted.sort_by(|x, y| {
        meet.compare(eye, &x.0, &y.0)
            .then(x.1.1.key.cmp(&y.1.1.key))
    });
    // Each point once (the smallest key), with whether a tile's plane passes through it.
    let mut inner: Vec<(OnLine, (u32, &Cut), bool)> = Vec::with_capacity(sorted.len());
    for (point, cut) in sorted {
        let border = cut.1.key[0] == TILE_CUT;
        match inner.last_mut() {
            Some(last) if meet.compare(eye, &last.0, &point).is_eq() => last.2 |= border,
            _ => inner.push((point, cut, border)),
        }
    }
    inner
}

/// Whether a point of a clipped line is drawn: inside the frustum of a view that clips and
/// inside the tile, given the exact sign of each plane's form at it.
pub(super) fn inside(
    clip: Option<Clip>,
    tile: Option<&TilePlanes>,
    sign: impl Fn(&Form) -> Ordering,
) -> bool {
    clip.is_none_or(|n| n.contains_by(&sign)) && tile.is_none_or(|t| t.contains_by(&sign))
}

/// The picture of a cut of the edge `l` (`None`: its first end).
pub(super) fn cut_picture(picture: &Picture, eye: &Eye, l: &Line, cut: Option<&Cut>) -> [f64; 2] {
    match cut {
        Some(Cut {
            sighted: Some(p), ..
        }) => *p,
        Some(c) => cut_point(picture, eye, &c.zero.form, &l.a, &l.b),
        None => l.ends[0],
    }
}
