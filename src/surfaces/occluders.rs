//! VISFAC2: the walk of an object's hierarchy that gathers the faces hiding some area of F (the
//! occluders), with the paper's early exits.

use super::index::Index;
use super::overlap;
use super::target::{Target, canonical_loop, spanning_triangle};
use super::{Exits, Result};
use crate::geometry::Point3;
use crate::mesh::Mesh;
use crate::scene::{Content, ObjectId, Scene};
use crate::sight::line::Sight;
use crate::views::Eye;

/// A face of an occluder that hides some area of F: its vertex loop, a triangle spanning its
/// plane (see [`spanning_triangle`]) and its triangles.
pub(super) struct Occluder {
    pub(super) corners: Vec<Point3>,
    pub(super) plane: [Point3; 3],
    /// Whether every corner lies exactly in `plane`.
    pub(super) planar: bool,
    pub(super) triangles: Vec<[Point3; 3]>,
}

impl Occluder {
    /// Face `g` of `mesh` as an occluder, its spanning triangle as seen from `eye`.
    fn of(mesh: &Mesh, g: usize, eye: &Eye) -> Occluder {
        let triangles = mesh.faces()[g]
            .triangle_range()
            .map(|t| mesh.triangle(t))
            .collect();
        let (plane, planar) = spanning_triangle(mesh, g, eye);
        Occluder {
            corners: canonical_loop(mesh, g),
            plane,
            planar,
            triangles,
        }
    }
}

/// VISFAC2(A, F): gathers in `occluders` the faces of `a` that hide some area of F (what they
/// hide of F, together, is what `a` hides of it), with the hierarchy's early exits; `true`
/// when an INBOX or a single face hides all of F.
pub(super) fn visfac2(
    scene: &Scene,
    a: ObjectId,
    target: &Target,
    own: (ObjectId, usize),
    index: Option<&Index>,
    occluders: &mut Vec<Occluder>,
    exits: &mut Exits,
) -> Result<bool> {
    let cbox = scene.cbox(a);
    let pictured = index.map(|i| i.cbox_pictures.get(a).copied().flatten());
    if target.cannot_be_hidden_by(&cbox, pictured) {
        exits.cbox_skipped += 1;
        return Ok(false);
    }
    if let Some(inbox) = scene.inbox(a) {
        let hides_all = target.vertices.iter().all(|v| {
            let sight = Sight::to_eye(v, &target.eye);
            sight.eye_outside(&cbox) && sight.surely_meets_open(&inbox.aabb)
        });
        if hides_all {
            exits.inbox_hid += 1;
            return Ok(true);
        }
    }
    match scene[a].content() {
        Content::Mesh(mesh) => {
            let near = match index.and_then(|i| i.grids.get(a)) {
                Some(grid) => grid.near(target.extent),
                None => (0..mesh.faces().len()).collect(),
            };
            for g in near {
                if (a, g) == own {
                    continue;
                }
                exits.faces_tested += 1;
                let corners: Vec<Point3> = mesh.face_points(g).collect();
                let plane = mesh.triangle(mesh.faces()[g].triangle_range().start);
                if !target.may_be_hidden_by(&corners, &plane) {
                    continue;
                }
                // Only a face that hides some area of F counts (exactly): one touching F
                // along a line would add nothing but rounding.
                if !hides_some_area(target, mesh, g, &plane) {
                    continue;
                }
                exits.faces_in_front += 1;
                if overlap::hides_all(&target.eye, &target.vertices, &corners, &plane) {
                    exits.face_hid += 1;
                    return Ok(true);
                }
                occluders.push(Occluder::of(mesh, g, &target.eye));
            }
        }
        Content::Subobjects(children) => {
            for &c in children {
                if visfac2(scene, c, target, own, index, occluders, exits)? {
                    return Ok(true);
                }
            }
        }
    }
    Ok(false)
}

/// Whether face `g` of `mesh` (whose first triangle is `plane`) hides some area of the
/// target's face, decided exactly: some triangle of it against some triangle of F.
fn hides_some_area(target: &Target, mesh: &Mesh, g: usize, plane: &[Point3; 3]) -> bool {
    mesh.faces()[g].triangle_range().any(|s| {
        let s = mesh.triangle(s);
        target
            .triangles
            .iter()
            .any(|t| overlap::hides_area(&target.eye, &target.plane, target.eye_side, t, &s, plane))
    })
}
