//! Saving a stiff scene: one OBJ file per object and a scene file naming them, with the
//! camera of the view, which [`crate::scene::file::load`] reads back.

use super::StiffScene;
use crate::mesh::Mesh;
use crate::scene::{Camera, Content, Projection};
use std::path::{Path, PathBuf};

/// Writes the scene into `dir` (created if missing): one OBJ file per object, its vertices
/// and polygons with every coordinate written to round trip, and a scene file naming them
/// with a `[camera]` section for the view. Returns the scene file's path
/// (`DIR/tilt-k12-seed3.toml`); [`crate::scene::file::load`] reads it back to the same
/// meshes.
///
/// ```
/// use kepler::lab::stiff::{Family, generate, write};
/// let stiff = generate(Family::Offset, 16, 0).unwrap();
/// let dir = std::env::temp_dir().join(format!("kepler-stiff-doc-{}", std::process::id()));
/// let path = write(&stiff, &dir).unwrap();
/// assert!(path.ends_with("offset-k16-seed0.toml"));
/// let scene = kepler::scene::file::load(&path).unwrap();
/// assert_eq!(scene.roots().len(), stiff.scene.roots().len());
/// assert_eq!(scene.camera(), stiff.scene.camera());
/// # std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn write(stiff: &StiffScene, dir: &Path) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let stem = stiff.stem();
    let mut toml = format!(
        "# kepler gen: {} ({})\n",
        stiff.name(),
        stiff.family.parameter()
    );
    if let Some(camera) = stiff.scene.camera() {
        toml += &camera_toml(camera);
    }
    for &id in stiff.scene.roots() {
        let object = &stiff.scene[id];
        let Content::Mesh(mesh) = object.content() else {
            continue;
        };
        let file = format!("{stem}-{}.obj", object.name());
        std::fs::write(dir.join(&file), obj(mesh, &stiff.name(), object.name()))?;
        // Object names are the generator's own: plain words, nothing to escape.
        toml += &format!(
            "\n[[object]]\nname = \"{}\"\nmesh = \"{file}\"\n",
            object.name()
        );
    }
    let path = dir.join(format!("{stem}.toml"));
    std::fs::write(&path, toml)?;
    Ok(path)
}

/// The `[camera]` section of a scene file for `camera`, its numbers written to round trip.
///
/// Written by hand rather than through serde and `toml`: `toml` (1.x, by `toml_writer`) writes
/// a double with `Display`, positionally (`2^280` as 85 digits and `.0`), where these files
/// have the shortest form of `{:?}` (`1.942668892225729e84`), as the scale family's cameras
/// need.
pub(super) fn camera_toml(camera: &Camera) -> String {
    let v = |p: [f64; 3]| format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2]);
    let projection = match camera.projection {
        Projection::Orthographic { direction } => {
            format!(
                "projection = \"orthographic\"\nview-dir = {}\n",
                v(direction)
            )
        }
        Projection::Perspective { eye, target, fov } => format!(
            "projection = \"perspective\"\neye = {}\ntarget = {}\nfov = {fov:?}\n",
            v(eye),
            v(target)
        ),
    };
    format!("\n[camera]\n{projection}up = {}\n", v(camera.up))
}

/// The OBJ text of a mesh: its vertices (`{:?}` prints the shortest decimal that reads back
/// to the same double) and its input polygons.
pub(super) fn obj(mesh: &Mesh, scene: &str, object: &str) -> String {
    let vertices = mesh
        .vertices()
        .iter()
        .map(|p| format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z));
    let faces = mesh.polygons().into_iter().map(|polygon| {
        let corners: String = polygon.iter().map(|i| format!(" {}", i + 1)).collect();
        format!("f{corners}\n")
    });
    let header = format!("# kepler gen: {scene}, object {object}\n");
    std::iter::once(header)
        .chain(vertices)
        .chain(faces)
        .collect()
}
