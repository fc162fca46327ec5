//! What the walks of VISFAC2 share in one view, built once: each mesh's faces by picture cells
//! ([`FaceGrid`]) and the picture of every object's CBOX.

use super::face_grid::FaceGrid;
use super::target::cbox_picture;
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};
use crate::sight::frustum::Clip;
use crate::views::{Picture, View};
use rayon::prelude::*;
use slotmap::SecondaryMap;

/// The faces of each mesh by picture cells, and the box of the picture of each object's CBOX
/// (`None` when a corner is not in front of the eye): every face's walk tests the CBOXes of
/// the objects it passes, and building a CBOX's picture (eight correctly rounded points) once
/// instead of once per face is most of what a walk over many objects costs.
pub(super) struct Index {
    pub(super) grids: SecondaryMap<ObjectId, FaceGrid>,
    pub(super) cbox_pictures: SecondaryMap<ObjectId, Option<[[f64; 2]; 2]>>,
}

impl Index {
    /// The index of `meshes` and of every object of `scene` in `view`.
    pub(super) fn new(
        scene: &Scene,
        meshes: &[(ObjectId, &Mesh)],
        view: &View,
        picture: &Picture,
        clip: Option<&Clip>,
    ) -> Index {
        let built: Vec<(ObjectId, FaceGrid)> = meshes
            .par_iter()
            .map(|&(id, mesh)| (id, FaceGrid::new(scene, (id, mesh), view, picture, clip)))
            .collect();
        let mut grids = SecondaryMap::new();
        grids.extend(built);
        let objects: Vec<ObjectId> = scene
            .roots()
            .iter()
            .flat_map(|&r| scene.subtree(r))
            .collect();
        let pictured: Vec<(ObjectId, Option<[[f64; 2]; 2]>)> = objects
            .par_iter()
            .map(|&id| (id, cbox_picture(picture, &scene.cbox(id))))
            .collect();
        let mut cbox_pictures = SecondaryMap::new();
        cbox_pictures.extend(pictured);
        Index {
            grids,
            cbox_pictures,
        }
    }
}
