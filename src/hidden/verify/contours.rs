//! Check 2: every silhouette and boundary edge that the sign test (`sign_test.rs`) finds is
//! drawn whole, as pieces of its class (see the module documentation of [`verify`](super)).

use super::super::EdgeClass;
use super::report::{Check, Disagreement, Verification};
use super::sign_test::{Contours, EdgeKey, contour_edges, point_key};
use super::trace::{Source, Traced, TracedPiece};
use crate::geometry::kernel::{Between, Polynomial};
use crate::geometry::predicates::Side;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};
use crate::sight::frustum::pictured;
use crate::views::View;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::HashMap;

fn edge_key(a: &Point3, b: &Point3) -> EdgeKey {
    let (x, y) = (point_key(a), point_key(b));
    if x <= y { [x, y] } else { [y, x] }
}

/// Check 2: every silhouette and boundary edge of the sign test drawn whole.
pub(super) fn contours(scene: &Scene, view: &View, traced: &Traced, report: &mut Verification) {
    let eye = view.eye();
    // A view that clips draws contours only inside its frustum: those are checked.
    let clip = pictured(scene, view).ok().and_then(|(_, clip)| clip);
    let (on, lines_of) = edge_pieces(scene, traced);
    let meshes = scene.mesh_objects(scene.roots());
    // An exact copy of an earlier mesh is drawn by that one's pieces.
    let first = crate::hidden::pass::originals(&meshes);
    let drawn_as: HashMap<ObjectId, ObjectId> = meshes
        .iter()
        .zip(&first)
        .map(|(&(id, _), &f)| (id, meshes[f].0))
        .collect();
    let found: Vec<(ObjectId, Contours)> = meshes
        .par_iter()
        .map(|&(id, mesh)| (id, contour_edges(mesh, eye)))
        .collect();
    for (object, found) in found {
        report.unchecked_edges += found.unchecked;
        let Some(mesh) = scene[object].mesh() else {
            continue;
        };
        let source = drawn_as[&object];
        let lines = lines_of.get(&source).map(Vec::as_slice).unwrap_or_default();
        let cover = found.chains.covering(mesh, lines);
        for c in found.contours {
            let (a, b) = (
                mesh.vertices()[c.vertices[0] as usize],
                mesh.vertices()[c.vertices[1] as usize],
            );
            if clip.is_some_and(|n| !(n.contains(eye, &a) && n.contains(eye, &b))) {
                report.unchecked_edges += 1;
                continue;
            }
            let (check, class) = match c.class {
                EdgeClass::Boundary => {
                    report.boundaries += 1;
                    (Check::Boundary, EdgeClass::Boundary)
                }
                _ => {
                    report.silhouettes += 1;
                    (Check::Silhouette, EdgeClass::Silhouette)
                }
            };
            let pieces = |key: &EdgeKey| {
                on.get(&(source, *key))
                    .map(Vec::as_slice)
                    .unwrap_or_default()
            };
            let drawn = match c.chain {
                None => whole(traced, pieces(&edge_key(&a, &b)), class),
                Some(chain) => {
                    let parts = found.chains.between(chain, c.vertices, &cover);
                    drawn_along(traced, mesh, (c.vertices, &parts), class, pieces)
                }
            };
            if let Err((at, found)) = drawn {
                report.disagree(Disagreement {
                    check,
                    object: scene.path(object),
                    line: format!("edge v{}–v{}", c.vertices[0], c.vertices[1]),
                    at,
                    expected: format!("{} pieces covering it", class.name()),
                    found,
                });
            }
        }
    }
}

/// The traced pieces (their indices) of each edge, by its object and the bits of its ends.
type PiecesOn = HashMap<(ObjectId, EdgeKey), Vec<usize>>;

/// The lines of the drawing of each object whose mesh has T-junctions, by the bits of their
/// ends.
type LinesOf = HashMap<ObjectId, Vec<EdgeKey>>;

/// The traced pieces of each edge (by object and the bits of its ends), and the lines of each
/// object whose mesh has T-junctions: one may run along several pieces of a side.
fn edge_pieces(scene: &Scene, traced: &Traced) -> (PiecesOn, LinesOf) {
    let mut on: PiecesOn = HashMap::new();
    let mut lines_of: LinesOf = HashMap::new();
    let has_junctions =
        |object: ObjectId| scene[object].mesh().is_some_and(|m| m.t_junctions() > 0);
    for (i, p) in traced.pieces.iter().enumerate() {
        if let Source::Edge { object } = p.source {
            let key = edge_key(&p.line[0], &p.line[1]);
            let pieces = on.entry((object, key)).or_default();
            if pieces.is_empty() && has_junctions(object) {
                lines_of.entry(object).or_default().push(key);
            }
            pieces.push(i);
        }
    }
    (on, lines_of)
}

/// A part of a contour edge between consecutive vertices of its chain, with the lines of the
/// drawing that run along it.
type Part<'k> = ([u32; 2], &'k [EdgeKey]);

/// Whether the contour edge `vertices`, a piece of a side with T-junctions, is drawn whole as
/// pieces of `class`: each of its `parts` between consecutive vertices of its chain (with the
/// lines of the drawing that run along it, whose traced pieces `pieces` gives) tiled by the
/// pieces of one line; else where it is not and what is there.
fn drawn_along<'k>(
    traced: &Traced,
    mesh: &Mesh,
    (vertices, parts): ([u32; 2], &[Part<'k>]),
    class: EdgeClass,
    pieces: impl Fn(&EdgeKey) -> &'k [usize],
) -> Result<(), (String, String)> {
    for &(w, lines) in parts {
        let ends = w.map(|v| mesh.vertices()[v as usize]);
        let part = match lines {
            [] => Err(("t = [0e0, 1]".to_string(), "nothing".to_string())),
            [line] => tiled_between(traced, pieces(line), class, ends),
            more => Err((
                "its line".to_string(),
                format!("pieces of {} lines covering it", more.len()),
            )),
        };
        if let Err((at, found)) = part {
            let at = if w == vertices {
                at
            } else {
                format!("its piece v{}–v{}, {at}", w[0], w[1])
            };
            return Err((at, found));
        }
    }
    Ok(())
}

/// Whether the pieces `on` an edge, all of `class`, tile its parameter range `[0, 1]`; else
/// where they do not and what is there.
fn whole(traced: &Traced, on: &[usize], class: EdgeClass) -> Result<(), (String, String)> {
    if let Some(&i) = on.iter().find(|&&i| traced.pieces[i].class != class) {
        let p = &traced.pieces[i];
        return Err((
            format!("t = [{:e}, {:e}]", p.t[0], p.t[1]),
            format!("a {} piece", p.class.name()),
        ));
    }
    let mut ranges: Vec<[f64; 2]> = on.iter().map(|&i| traced.pieces[i].t).collect();
    ranges.sort_by(|x, y| x[0].total_cmp(&y[0]));
    let mut reached = 0.0;
    for r in ranges {
        if r[0] != reached {
            let what = if r[0] > reached {
                "nothing"
            } else {
                "overlapping pieces"
            };
            return Err((format!("t = {reached:e}"), what.to_string()));
        }
        reached = r[1];
    }
    if reached != 1.0 {
        return Err((format!("t = [{reached:e}, 1]"), "nothing".to_string()));
    }
    Ok(())
}

/// Whether the pieces `on` a line of the drawing (an edge cut at T-junctions and joined, whose
/// ends are input vertices collinear with `part`), those over the segment `part` all of
/// `class`, tile the line's parameter range over `part`; else where they do not and what is
/// there. The ends of `part` are input vertices on the line, at parameters that are not
/// doubles: each piece's ends are compared with them exactly.
fn tiled_between(
    traced: &Traced,
    on: &[usize],
    class: EdgeClass,
    part: [Point3; 2],
) -> Result<(), (String, String)> {
    let nothing = || ("t = [0e0, 1]".to_string(), "nothing".to_string());
    let Some(first) = on.first().map(|&i| &traced.pieces[i]) else {
        return Err(nothing());
    };
    let [a, b] = first.line;
    let Some(k) = (0..3).find(|&k| a[k] != b[k]) else {
        return Err(nothing());
    };
    let rising = a[k] < b[k];
    // The parameter `t` compared with the parameter of the point `w` of the line, exactly:
    // the sign of `X(t)ₖ − wₖ` along the coordinate `k`, which the line runs along.
    let compare = |t: f64, w: &Point3| -> Ordering {
        if w == &a || w == &b {
            let end = if w == &a { 0.0 } else { 1.0 };
            return t.partial_cmp(&end).unwrap_or(Ordering::Equal);
        }
        let mut normal = Vector3::zeros();
        normal[k] = 1.0;
        let side = |x: Point3| Side {
            origin: *w,
            normal,
            offset: 0.0,
            x,
        };
        let sign = Between(side(a), side(b), t).sign();
        if rising { sign } else { sign.reverse() }
    };
    // The ends of `part` in the order of the line's parameter.
    let [lo, hi] = if (part[0][k] < part[1][k]) == rising {
        part
    } else {
        [part[1], part[0]]
    };
    let mut over: Vec<&TracedPiece> = on
        .iter()
        .map(|&i| &traced.pieces[i])
        .filter(|p| compare(p.t[0], &hi) == Ordering::Less)
        .filter(|p| compare(p.t[1], &lo) == Ordering::Greater)
        .collect();
    if let Some(p) = over.iter().find(|p| p.class != class) {
        return Err((
            format!("t = [{:e}, {:e}] of its line", p.t[0], p.t[1]),
            format!("a {} piece", p.class.name()),
        ));
    }
    over.sort_by(|x, y| x.t[0].total_cmp(&y.t[0]));
    let (Some(start), Some(end)) = (over.first(), over.last()) else {
        return Err(nothing());
    };
    if compare(start.t[0], &lo) == Ordering::Greater {
        return Err((
            format!("t < {:e} of its line", start.t[0]),
            "nothing".to_string(),
        ));
    }
    for w in over.windows(2) {
        let (reached, next) = (w[0].t[1], w[1].t[0]);
        if next != reached {
            let what = if next > reached {
                "nothing"
            } else {
                "overlapping pieces"
            };
            return Err((format!("t = {reached:e} of its line"), what.to_string()));
        }
    }
    if compare(end.t[1], &hi) == Ordering::Less {
        return Err((
            format!("t > {:e} of its line", end.t[1]),
            "nothing".to_string(),
        ));
    }
    Ok(())
}
