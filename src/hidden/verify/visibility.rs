//! Check 1: VISP through the object hierarchy at sample points inside every piece, against the
//! piece's visibility (see the module documentation of [`verify`](super)).

use super::report::{Check, Disagreement, Verification};
use super::trace::{Source, Traced, TracedPiece};
use super::{NEAR_END_ULPS, SAMPLES};
use crate::geometry::Point3;
use crate::mesh::Mesh;
use crate::queries::visp::{Visibility, VisibilityIndex};
use crate::scene::{ObjectId, Scene};
use crate::sight::along::{Form, Sample};
use crate::sight::meet::{Meet, OnLine};
use crate::views::{Eye, View};
use rayon::prelude::*;
use std::cell::Cell;
use std::cmp::Ordering;

/// What one sample found.
enum Sampled {
    Agrees { grazing: bool },
    NearEnd,
    Disagrees { t: f64, visibility: Visibility },
}

/// Check 1: VISP at the samples of every edge piece.
pub(super) fn visibility(scene: &Scene, view: &View, traced: &Traced, report: &mut Verification) {
    let index = VisibilityIndex::whole_scene(scene, view.clone());
    let eye = view.eye();
    let found: Vec<(usize, Vec<Sampled>)> = traced
        .pieces
        .par_iter()
        .enumerate()
        .map(|(i, p)| match (p.source, &p.meet) {
            (Source::Intersection { faces }, Some(meet)) => {
                (i, line_samples(scene, &index, eye, p, meet, faces))
            }
            _ => (i, samples(&index, eye, p)),
        })
        .collect();
    report.unchecked_intersections = traced
        .pieces
        .iter()
        .filter(|p| matches!(p.source, Source::Intersection { .. }) && p.meet.is_none())
        .count();
    for (i, sampled) in found {
        let p = &traced.pieces[i];
        for s in sampled {
            match s {
                Sampled::Agrees { grazing } => {
                    report.samples += 1;
                    report.grazing += usize::from(grazing);
                }
                Sampled::NearEnd => report.near_ends += 1,
                Sampled::Disagrees { t, visibility } => {
                    report.samples += 1;
                    report.disagree(Disagreement {
                        check: Check::Visibility,
                        object: object_of(scene, &p.source),
                        line: describe(scene, p),
                        at: format!("t = {t:e} (piece t = [{:e}, {:e}])", p.t[0], p.t[1]),
                        expected: visibility.to_string().to_lowercase(),
                        found: if p.visible { "visible" } else { "hidden" }.to_string(),
                    });
                }
            }
        }
    }
}

/// VISP at the samples of one edge piece.
fn samples(index: &VisibilityIndex, eye: &Eye, p: &TracedPiece) -> Vec<Sampled> {
    let [lo, hi] = p.t;
    SAMPLES
        .iter()
        .map(|&f| {
            let at = |f: f64| lo + (hi - lo) * f;
            let inside = |t: f64| {
                let margin = NEAR_END_ULPS * f64::EPSILON * t.abs();
                t - lo > margin && hi - t > margin && t > 0.0 && t < 1.0
            };
            // A sample whose line of sight passes exactly through the edge of the only faces
            // that hide it (a vertex's picture on the piece, say) stands for no piece around
            // it: the sample moves (a sixteenth of the piece either way), unless every try
            // grazes (a piece right behind a contour): then the closed faces hide it.
            if !inside(at(f)) {
                return Sampled::NearEnd;
            }
            let tries = [at(f), at(f + 1.0 / 16.0), at(f - 1.0 / 16.0)];
            let mut first = None;
            for t in tries.into_iter().filter(|&t| inside(t)) {
                let (visibility, grazing) = visp_at(index, eye, &p.line, t);
                first.get_or_insert((t, visibility));
                if !grazing {
                    return sampled(p, t, visibility, false);
                }
            }
            match first {
                Some((t, visibility)) => sampled(p, t, visibility, true),
                None => Sampled::NearEnd,
            }
        })
        .collect()
}

/// VISP at the samples of one piece of an intersection line (on the exact line `meet`, of the
/// faces `faces`): each sample is where a plane `x_k = c` across the line (a double `c` of the
/// coordinate along which the piece runs furthest, at the fractions [`SAMPLES`] of the piece's
/// rounded span) cuts it, a point of the line defined from the input and never rounded; every
/// face test is the exact sign of a plane's form there ([`Meet::sign_at`]). The faces the line
/// lies on do not hide it. Samples within 2⁻³⁰ of the piece's span of its ends are not taken
/// (the piece's ends are known here only as rounded points).
fn line_samples(
    scene: &Scene,
    index: &VisibilityIndex,
    eye: &Eye,
    p: &TracedPiece,
    meet: &Meet,
    faces: [(ObjectId, usize); 2],
) -> Vec<Sampled> {
    let [a, b] = &p.line;
    let k = (0..3)
        .max_by(|&i, &j| (b[i] - a[i]).abs().total_cmp(&(b[j] - a[j]).abs()))
        .unwrap_or(0);
    let [lo, hi] = p.t.map(|t| a[k] + t * (b[k] - a[k]));
    let margin = (hi - lo).abs() / (1u64 << 30) as f64;
    // The triangles of the faces the line lies on, which do not hide it.
    let own: Vec<[Point3; 3]> = faces
        .iter()
        .filter_map(|&(o, f)| {
            let mesh = scene[o].mesh()?;
            let face = mesh.faces().get(f)?;
            Some(
                face.triangle_range()
                    .map(|t| mesh.triangle(t))
                    .collect::<Vec<_>>(),
            )
        })
        .flatten()
        .collect();
    SAMPLES
        .iter()
        .map(|&f| {
            let c = lo + (hi - lo) * f;
            // The sample's parameter along the rounded line, for the report.
            let t = p.t[0] + (p.t[1] - p.t[0]) * f;
            if !((c - lo).abs() > margin && (hi - c).abs() > margin) {
                return Sampled::NearEnd;
            }
            let mut corner = [0.0; 3];
            corner[k] = c;
            let (p0, mut p1, mut p2) = (
                Point3::from(corner),
                Point3::from(corner),
                Point3::from(corner),
            );
            p1[(k + 1) % 3] = 1.0;
            p2[(k + 2) % 3] = 1.0;
            let across = Form::Plane([p0, p1, p2]);
            if meet.slope_sign(eye, &across) == Ordering::Equal {
                return Sampled::NearEnd;
            }
            let at = OnLine::Cut(meet.increasing(eye, across));
            let sign = |form: &Form| meet.sign_at(eye, &at, form);
            let near = meet.approximate(eye, &at);
            let radius = meet.magnitude(&at).max(near.coords.amax()) / (1u64 << 39) as f64;
            let grazed = Cell::new(false);
            let hides = |tri: &[Point3; 3], strict: bool| {
                if own.contains(tri) {
                    return false;
                }
                let (hides, grazes) = hides_by(eye, tri, &sign);
                grazed.set(grazed.get() || grazes);
                hides && !(strict && grazes)
            };
            let (closed, _) = index.visp_by((&near, radius), |tri| hides(tri, false));
            let visibility = if closed == Visibility::Visible || !grazed.get() {
                closed
            } else {
                let (open, _) = index.visp_by((&near, radius), |tri| hides(tri, true));
                if open == Visibility::Visible {
                    // The answer rests on lines of sight through faces' edges only.
                    return sampled(p, t, closed, true);
                }
                closed
            };
            sampled(p, t, visibility, false)
        })
        .collect()
}

/// Whether the triangle `tri` hides a point given by the exact sign of any form there, and
/// whether its line of sight passes exactly through an edge of the triangle (see [`hides_at`]).
fn hides_by(eye: &Eye, tri: &[Point3; 3], sign: &impl Fn(&Form) -> Ordering) -> (bool, bool) {
    let facing = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if facing == Ordering::Equal || sign(&Form::Plane(*tri)) != facing.reverse() {
        return (false, false);
    }
    let sides = [0, 1, 2].map(|i| sign(&Form::Sight(tri[i], tri[(i + 1) % 3])));
    let inside = !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less));
    (inside, inside && sides.contains(&Ordering::Equal))
}

/// A sample's outcome: VISP found `visibility` at `t`.
fn sampled(p: &TracedPiece, t: f64, visibility: Visibility, grazing: bool) -> Sampled {
    if (visibility == Visibility::Visible) == p.visible {
        Sampled::Agrees { grazing }
    } else {
        Sampled::Disagrees { t, visibility }
    }
}

/// VISP at `X(t)` on `line`, with the closed faces, and whether the answer rests on lines of
/// sight through faces' edges only (HIDDEN with the closed faces, VISIBLE with the open ones).
fn visp_at(index: &VisibilityIndex, eye: &Eye, [a, b]: &[Point3; 2], t: f64) -> (Visibility, bool) {
    let (near, radius) = Sample::At(t).point(a, b);
    let near = (&near, radius);
    let grazed = Cell::new(false);
    let (closed, _) = index.visp_by(near, |tri| {
        let (hides, grazes) = hides_at(eye, tri, a, b, t);
        grazed.set(grazed.get() || grazes);
        hides
    });
    if closed == Visibility::Visible || !grazed.get() {
        return (closed, false);
    }
    let (open, _) = index.visp_by(near, |tri| hides_at(eye, tri, a, b, t) == (true, false));
    (closed, open == Visibility::Visible)
}

/// Whether the triangle `tri` hides `X(t) = a + t·(b − a)` (strictly behind its plane, the
/// line of sight through the closed triangle), and whether that line of sight passes exactly
/// through an edge of the triangle.
fn hides_at(eye: &Eye, tri: &[Point3; 3], a: &Point3, b: &Point3, t: f64) -> (bool, bool) {
    let facing = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if facing == Ordering::Equal || Form::Plane(*tri).sign_along(eye, a, b, t) != facing.reverse() {
        return (false, false);
    }
    let sides = [0, 1, 2].map(|i| Form::Sight(tri[i], tri[(i + 1) % 3]).sign_along(eye, a, b, t));
    let inside = !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less));
    (inside, inside && sides.contains(&Ordering::Equal))
}

/// The path of a piece's object (of its first face's, for an intersection line).
fn object_of(scene: &Scene, source: &Source) -> String {
    match source {
        Source::Edge { object } => scene.path(*object),
        Source::Intersection { faces } => faces
            .first()
            .map(|&(o, _)| scene.path(o))
            .unwrap_or_default(),
    }
}

/// A piece's line, for a person: an edge by its vertex indices, else by its ends.
fn describe(scene: &Scene, p: &TracedPiece) -> String {
    let [a, b] = p.line;
    let class = p.class.name();
    let vertex = |mesh: &Mesh, x: &Point3| mesh.vertices().iter().position(|v| v == x);
    if let Source::Edge { object } = p.source
        && let Some(mesh) = scene[object].mesh()
        && let (Some(i), Some(j)) = (vertex(mesh, &a), vertex(mesh, &b))
    {
        return format!("{class} edge v{i}–v{j}");
    }
    format!(
        "{class} line ({}, {}, {})–({}, {}, {})",
        a.x, a.y, a.z, b.x, b.y, b.z
    )
}
