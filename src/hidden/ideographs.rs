//! Franklin's ideographs: an object whose picture is too small to matter is drawn as its
//! CBOX, or left out, before the hidden-line pass. Franklin: "It is possible for a subobject
//! to have an ideograph, or a simpler representation that replaces it when the object after
//! scaling is too small." Smallness is the exact projected area of the CBOX
//! ([`crate::views::projected_area`]), in picture units.
//!
//! ```
//! use kepler::{hidden::ideographs::{Ideograph, ideographs}, views::View};
//! let mut scene = kepler::scene::Scene::new();
//! scene.add_mesh(None, "speck", kepler::solids::icosahedron(0.01).unwrap()).unwrap();
//! assert_eq!(ideographs(&scene, &View::standard(), 1.0, Ideograph::Omit).unwrap().culled, 1);
//! ```

use super::Result;
use crate::scene::Scene;
use crate::views::projected_area::projected_area_aabb;
use crate::views::{Picture, View};

/// What to do with an object whose picture is too small to draw: Franklin's ideographs.
///
/// ```
/// assert_ne!(kepler::hidden::ideographs::Ideograph::Bound, kepler::hidden::ideographs::Ideograph::Omit);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
// The command line's --ideograph: its `--help` lists the values by name only.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Ideograph {
    /// Draw its CBOX instead (a box, with its hidden lines removed like any object).
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Bound,
    /// Leave it out.
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Omit,
}

/// The scene to draw once the small objects are replaced by their ideographs, and how many.
///
/// ```
/// let i = kepler::hidden::ideographs::Ideographs {
///     scene: kepler::scene::Scene::new(), culled: 0, triangles_culled: 0, triangles_added: 0,
/// };
/// assert_eq!(i.culled, 0);
/// ```
#[derive(Debug)]
pub struct Ideographs {
    /// Every mesh object of the input as a top-level object named by its path, the small
    /// ones replaced by their CBOX or left out.
    pub scene: Scene,
    /// How many objects were replaced or left out.
    pub culled: u64,
    /// Their triangles.
    pub triangles_culled: u64,
    /// The triangles of the boxes drawn instead.
    pub triangles_added: u64,
}

/// Replaces every mesh object whose CBOX's picture has an area below `min_area` (in picture
/// units squared: scene units for an orthographic view; see [`Picture`]) by its ideograph.
/// The areas are Schmalstieg and Tobler's exact projected areas
/// ([`crate::views::projected_area`]); a box the eye is inside is never small. An error if a
/// perspective view has geometry not in front of the eye.
///
/// ```
/// use kepler::{hidden::ideographs::{Ideograph, ideographs}, scene::Scene, views::View};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "big", kepler::solids::cube(10.0).unwrap()).unwrap();
/// scene.add_mesh(None, "speck", kepler::solids::icosahedron(0.01).unwrap()).unwrap();
/// let small = ideographs(&scene, &View::standard(), 1.0, Ideograph::Bound).unwrap();
/// assert_eq!((small.culled, small.triangles_culled, small.triangles_added), (1, 20, 12));
/// let gone = ideographs(&scene, &View::standard(), 1.0, Ideograph::Omit).unwrap();
/// assert_eq!(gone.scene.roots().len(), 1);
/// ```
pub fn ideographs(
    scene: &Scene,
    view: &View,
    min_area: f64,
    mode: Ideograph,
) -> Result<Ideographs> {
    let picture = Picture::of(view);
    let meshes = picture.mesh_objects_in_front(scene)?;
    let mut out = Ideographs {
        scene: Scene::new(),
        culled: 0,
        triangles_culled: 0,
        triangles_added: 0,
    };
    for (id, mesh) in meshes {
        let cbox = scene.cbox(id);
        let name = scene.path(id);
        if projected_area_aabb(&cbox, view) >= min_area {
            out.scene.add_mesh(None, name, mesh.clone())?;
            continue;
        }
        out.culled += 1;
        out.triangles_culled += mesh.triangles().len() as u64;
        if mode == Ideograph::Bound {
            // A flat or degenerate box has no solid to draw: its picture is below the
            // threshold anyway, so it is left out.
            if let Ok(b) = crate::solids::box_between(cbox.min, cbox.max) {
                out.triangles_added += b.triangles().len() as u64;
                out.scene.add_mesh(None, name, b)?;
            }
        }
    }
    Ok(out)
}
