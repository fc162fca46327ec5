//! The scene layer's error: what went wrong building or reading a scene, and what is wrong
//! with one of its objects.

use crate::io::FileError;
use crate::mesh::MeshError;
use crate::solids::SolidError;

/// What went wrong building or reading a scene: the scene layer's error.
///
/// ```
/// use kepler::scene::{ObjectProblem, Scene, SceneError};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// let e = scene.add_group(Some(cube), "inner").unwrap_err();
/// assert!(matches!(e, SceneError::Object { problem: ObjectProblem::HasFaces, .. }));
/// assert_eq!(e.to_string(), "object 'cube': it has faces, so it cannot also have subobjects");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file, or a mesh file, could not be read or holds bad input.
    #[error(transparent)]
    File(#[from] FileError),
    /// An error caused at a line of a scene file: by a mesh file or a solid it names, or by an
    /// object it places.
    #[error("{path}:{line}: {source}")]
    AtLine {
        /// The scene file.
        path: String,
        /// The 1-based line.
        line: usize,
        /// What went wrong there.
        #[source]
        source: Box<SceneError>,
    },
    /// A built-in solid with bad parameters.
    #[error(transparent)]
    Solid(#[from] SolidError),
    /// A problem with a named object.
    #[error("object '{object}': {problem}")]
    Object {
        /// The object's name (or path).
        object: String,
        /// What is wrong with it.
        problem: ObjectProblem,
    },
}

/// What is wrong with an object of a scene (see [`SceneError::Object`]).
///
/// ```
/// assert_eq!(
///     kepler::scene::ObjectProblem::SingularTransform.to_string(),
///     "the transform is singular or not finite"
/// );
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObjectProblem {
    /// Its parent is not in the scene.
    #[error("its parent is not in this scene")]
    ParentMissing,
    /// It is a mesh object, which cannot have subobjects.
    #[error("it has faces, so it cannot also have subobjects")]
    HasFaces,
    /// Its transform is singular or not finite.
    #[error("the transform is singular or not finite")]
    SingularTransform,
    /// The object to instance is not in the scene.
    #[error("the object to instance is not in this scene")]
    SourceMissing,
    /// Its mesh, transformed, is not a valid mesh.
    #[error(transparent)]
    Mesh(MeshError),
    /// Its meshes, joined into one, are not a valid mesh.
    #[error("flattening: {0}")]
    Flatten(MeshError),
}

/// `Result` with the scene layer's [`SceneError`].
pub type Result<T, E = SceneError> = std::result::Result<T, E>;
