//! Culling experiments: how well each bounding volume, used as a filter in one view, decides
//! which pairs of objects can be left to each other in the hidden-line pass.
//!
//! Two mesh objects interact in a drawing only where their pictures overlap. A filter decides
//! a pair when it proves they do not interact:
//! - **rstar on projected boxes**: the 2-D bounding boxes of the pictures of their CBOXes'
//!   corners are disjoint (an R-tree self-join lists the others);
//! - **CBOX**: the pictures of their CBOXes (convex: the hulls of the projected corners) are
//!   disjoint;
//! - **TRIBOX**: the pictures of their triboxes are disjoint;
//! - **INBOX**: one object's INBOX hides the other's CBOX entirely (every corner's line of
//!   sight meets the open INBOX, seen from outside the first object's CBOX; the points whose
//!   line of sight meets a box form a convex set, so the corners decide for the whole box), so
//!   the hidden object need not be drawn against it.
//!
//! The work a decided pair saves is counted as the triangle pairs a brute-force pass would test
//! between the two objects. A bound with a corner not in front of a perspective eye has no
//! bounded picture, and decides nothing. Disjointness of two convex pictures is decided with
//! exact `orient2d` signs on the rounded pictures; touching pictures count as overlapping.
//!
//! ```
//! use kepler::{lab::culling::cull, scene::Scene, views::View};
//! use nalgebra::{Matrix4, Vector3};
//! let mut scene = Scene::new();
//! let cube = kepler::solids::cube(1.0).unwrap();
//! scene.add_mesh(None, "a", cube.clone()).unwrap();
//! let moved = cube.transformed(&Matrix4::new_translation(&Vector3::new(5.0, 0.0, 0.0))).unwrap();
//! scene.add_mesh(None, "b", moved).unwrap();
//! let report = cull(&scene, &View::standard()).unwrap();
//! assert_eq!(report.pairs, 1);
//! assert!(report.filters.iter().all(|f| f.name == "inbox" || f.decided == 1));
//! ```

use crate::Result;
use crate::geometry::Point3;
use crate::geometry::polygon::bounding_box;
use crate::geometry::predicates::orient2d;
use crate::scene::{ObjectId, Scene};
use crate::sight::line::Sight;
use crate::views::{Picture, View};
use geo::{ConvexHull, MultiPoint};
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};
use std::cmp::Ordering;

/// What one filter decided.
///
/// ```
/// let f = kepler::lab::culling::FilterRow { name: "cbox", decided: 3, triangle_pairs_saved: 144 };
/// assert_eq!(f.decided, 3);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct FilterRow {
    /// `rstar`, `cbox`, `tribox` or `inbox`.
    pub name: &'static str,
    /// How many pairs of objects it proves not to interact.
    pub decided: u64,
    /// The triangle pairs (`triangles(a) · triangles(b)`) of those pairs.
    pub triangle_pairs_saved: u64,
}

/// The answer of [`cull`] for one view.
///
/// ```
/// use kepler::{lab::culling::cull, scene::Scene, views::View};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "a", kepler::solids::cube(1.0).unwrap()).unwrap();
/// let r = cull(&scene, &View::standard()).unwrap();
/// assert_eq!((r.objects, r.pairs, r.undecided), (1, 0, 0));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct CullReport {
    /// Mesh objects in the scene.
    pub objects: u64,
    /// Pairs of them.
    pub pairs: u64,
    /// Their triangle pairs.
    pub triangle_pairs: u64,
    /// Each filter on its own, in the order rstar, CBOX, TRIBOX, INBOX.
    pub filters: Vec<FilterRow>,
    /// Pairs no filter decides: those the hidden-line pass must compare.
    pub undecided: u64,
    /// Their triangle pairs.
    pub undecided_triangle_pairs: u64,
}

/// Compares the filters on every pair of mesh objects of `scene` seen from `view`. An error if
/// a perspective view has geometry not in front of the eye (as for drawings).
///
/// ```
/// use kepler::{lab::culling::cull, scene::Scene, views::View};
/// let mut scene = Scene::new();
/// let cube = kepler::solids::cube(1.0).unwrap();
/// scene.add_mesh(None, "a", cube.clone()).unwrap();
/// scene.add_mesh(None, "b", cube).unwrap();
/// let r = cull(&scene, &View::standard()).unwrap();
/// assert_eq!(r.undecided, 1); // the same place: nothing separates them
/// ```
pub fn cull(scene: &Scene, view: &View) -> Result<CullReport> {
    let picture = Picture::of(view);
    let meshes = picture.mesh_objects_in_front(scene)?;
    let bounds: Vec<Bounds> = meshes
        .iter()
        .map(|&(id, mesh)| Bounds::of(scene, id, mesh.triangles().len() as u64, &picture))
        .collect();
    let n = bounds.len();
    let triangle_pairs = |i: usize, j: usize| bounds[i].triangles * bounds[j].triangles;
    let meeting = meeting_pairs(&bounds);
    let all_pairs = (n * n.saturating_sub(1) / 2) as u64;
    let all_triangle_pairs: u64 = {
        let total: u64 = bounds.iter().map(|b| b.triangles).sum();
        let squares: u64 = bounds.iter().map(|b| b.triangles * b.triangles).sum();
        (total * total - squares) / 2
    };
    let met_triangle_pairs: u64 = meeting.iter().map(|&(i, j)| triangle_pairs(i, j)).sum();
    let mut rows = vec![FilterRow {
        name: "rstar",
        decided: all_pairs - meeting.len() as u64,
        triangle_pairs_saved: all_triangle_pairs - met_triangle_pairs,
    }];
    let eye = *view.eye();
    let hides = |a: &Bounds, b: &Bounds| -> bool {
        let Some(inbox) = a.inbox else { return false };
        b.corners.iter().all(|c| {
            let sight = Sight::to_eye(c, &eye);
            sight.eye_outside(&a.cbox_box) && sight.surely_meets_open(&inbox)
        })
    };
    // Each filter on its own: the pairs whose boxes do not meet are decided by all of them.
    let tests: [(&'static str, PairTest); 3] = [
        ("cbox", &|i, j| apart(&bounds[i].cbox, &bounds[j].cbox)),
        ("tribox", &|i, j| {
            apart(&bounds[i].tribox, &bounds[j].tribox)
        }),
        ("inbox", &|i, j| {
            hides(&bounds[i], &bounds[j]) || hides(&bounds[j], &bounds[i])
        }),
    ];
    let mut undecided = (0, 0);
    let mut decided_by_any = vec![false; meeting.len()];
    for (name, test) in tests {
        let mut row = FilterRow {
            name,
            decided: 0,
            triangle_pairs_saved: 0,
        };
        if name != "inbox" {
            row.decided = rows[0].decided;
            row.triangle_pairs_saved = rows[0].triangle_pairs_saved;
        }
        for (k, &(i, j)) in meeting.iter().enumerate() {
            if test(i, j) {
                row.decided += 1;
                row.triangle_pairs_saved += triangle_pairs(i, j);
                decided_by_any[k] = true;
            }
        }
        rows.push(row);
    }
    for (k, &(i, j)) in meeting.iter().enumerate() {
        if !decided_by_any[k] {
            undecided.0 += 1;
            undecided.1 += triangle_pairs(i, j);
        }
    }
    Ok(CullReport {
        objects: n as u64,
        pairs: all_pairs,
        triangle_pairs: all_triangle_pairs,
        filters: rows,
        undecided: undecided.0,
        undecided_triangle_pairs: undecided.1,
    })
}

/// The pairs `(i, j)`, `i < j`, of objects whose projected boxes meet (all others are
/// rstar's), sorted; those with an unbounded picture meet everything.
fn meeting_pairs(bounds: &[Bounds]) -> Vec<(usize, usize)> {
    let n = bounds.len();
    let boxes: Vec<GeomWithData<Rectangle<[f64; 2]>, usize>> = bounds
        .iter()
        .enumerate()
        .filter_map(|(i, b)| {
            let [lo, hi] = b.cbox.as_ref()?.extent;
            Some(GeomWithData::new(Rectangle::from_corners(lo, hi), i))
        })
        .collect();
    let tree = RTree::bulk_load(boxes);
    let mut meeting: Vec<(usize, usize)> = tree
        .intersection_candidates_with_other_tree(&tree)
        .filter(|(a, b)| a.data < b.data)
        .map(|(a, b)| (a.data, b.data))
        .collect();
    let unbounded: Vec<usize> = (0..n).filter(|&i| bounds[i].cbox.is_none()).collect();
    for &i in &unbounded {
        meeting.extend((0..n).filter(|&j| j != i).map(|j| (i.min(j), i.max(j))));
    }
    meeting.sort_unstable();
    meeting.dedup();
    meeting
}

/// A filter's test on a pair of objects (by index): `true` when it decides the pair.
type PairTest<'a> = &'a dyn Fn(usize, usize) -> bool;

/// One object's bounds and their pictures.
struct Bounds {
    triangles: u64,
    /// The CBOX's corners.
    corners: Vec<Point3>,
    cbox_box: crate::geometry::Aabb,
    inbox: Option<crate::geometry::Aabb>,
    /// The pictures of the CBOX and of the tribox (`None` when not wholly in front).
    cbox: Option<Convex>,
    tribox: Option<Convex>,
}

impl Bounds {
    fn of(scene: &Scene, id: ObjectId, triangles: u64, picture: &Picture) -> Bounds {
        let cbox_box = scene.cbox(id);
        let corners = cbox_box.corners().to_vec();
        let tribox = crate::bounds::tribox::Tribox::new(&scene.tribox(id));
        Bounds {
            triangles,
            cbox: Convex::of(&corners, picture),
            tribox: Convex::of(tribox.vertices(), picture),
            corners,
            cbox_box,
            inbox: scene.inbox(id).map(|i| i.aabb),
        }
    }
}

/// The picture of a convex polytope: the convex hull of its projected vertices (geo's, with
/// exact predicates), and its bounding box.
struct Convex {
    hull: Vec<[f64; 2]>,
    extent: [[f64; 2]; 2],
}

impl Convex {
    /// `None` when a vertex is not in front of the eye (or there are none).
    fn of(vertices: &[Point3], picture: &Picture) -> Option<Convex> {
        if vertices.is_empty() || !vertices.iter().all(|v| picture.in_front(v)) {
            return None;
        }
        let points: MultiPoint<f64> = vertices
            .iter()
            .map(|v| {
                let [x, y] = picture.point(v);
                geo::Point::new(x, y)
            })
            .collect();
        let mut hull: Vec<[f64; 2]> = points
            .convex_hull()
            .exterior()
            .coords()
            .map(|c| [c.x, c.y])
            .collect();
        // geo closes the ring; the first point again is not a vertex.
        if hull.len() > 1 && hull.first() == hull.last() {
            hull.pop();
        }
        let extent = bounding_box(hull.iter().copied());
        Some(Convex { hull, extent })
    }
}

/// Whether two convex pictures are certainly disjoint: an edge line of one leaves the other
/// strictly outside (exact signs on the rounded points). A degenerate picture (a segment or a
/// point) is compared through its hull's edges both ways.
fn apart(a: &Option<Convex>, b: &Option<Convex>) -> bool {
    let (Some(a), Some(b)) = (a, b) else {
        return false;
    };
    separated_by_an_edge_of(a, b) || separated_by_an_edge_of(b, a)
}

/// Whether an edge of `a` has all of `b` strictly on its outer side (the side away from the
/// rest of `a`).
fn separated_by_an_edge_of(a: &Convex, b: &Convex) -> bool {
    let n = a.hull.len();
    if n < 3 {
        return false;
    }
    (0..n).any(|i| {
        let (p, q) = (a.hull[i], a.hull[(i + 1) % n]);
        let inside = orient2d(p, q, a.hull[(i + 2) % n]);
        inside != Ordering::Equal
            && b.hull
                .iter()
                .all(|&r| orient2d(p, q, r) == inside.reverse())
    })
}
