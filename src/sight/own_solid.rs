//! A solid seen from outside hides its own faces turned away from the eye: the shortcut that
//! lets the hidden-line pass (edges between two such faces) and VISFAC (whole faces) skip
//! occlusion tests, decided exactly from the mesh's topology and the sign of its volume.

use super::intersections;
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};
use crate::views::Eye;
use std::cmp::Ordering;

/// [`turned_away`] for a mesh that, moreover, does not pierce itself (no two of its triangles
/// without a common vertex cross; found as the hidden-line pass finds intersection lines): the
/// sign of [`Eye::orient3d`] of a face the solid itself hides all of, or `None`.
pub(crate) fn hidden_by_own_solid(
    scene: &Scene,
    id: ObjectId,
    mesh: &Mesh,
    eye: &Eye,
) -> Option<Ordering> {
    let side = turned_away(scene, id, mesh, eye)?;
    intersections::between(mesh, mesh, true, eye)
        .is_empty()
        .then_some(side)
}

/// For a mesh that bounds a solid the eye is outside of (closed, consistently oriented, not
/// flat; the eye outside its CBOX), the sign of [`Eye::orient3d`] of a face turned away from
/// the eye; `None` otherwise. Every point of an edge between two faces turned away is then
/// hidden by the solid itself: its line of sight enters the solid, which it must leave through
/// a face in front of the point before reaching the eye.
pub(crate) fn turned_away(scene: &Scene, id: ObjectId, mesh: &Mesh, eye: &Eye) -> Option<Ordering> {
    let topology = mesh.topology();
    if !(topology.closed && topology.consistently_oriented) {
        return None;
    }
    if let Eye::Point(e) = eye
        && scene.cbox(id).contains_point(e)
    {
        return None;
    }
    // Seen from outside, an outward face is counter-clockwise: orient3d(face, eye) < 0.
    match mesh.orientation() {
        Ordering::Equal => None,
        sign => Some(sign),
    }
}
