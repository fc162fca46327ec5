//! Point queries through the object hierarchy (Franklin 1981, algorithms A and B): INCLUDE,
//! whether a point is in an object, and VISP, whether an object hides a point; and ray
//! shooting, the first face a ray meets.
//!
//! Each query walks the scene graph as the paper does: the bounds decide first (a point
//! inside an INBOX is in; a point outside a CBOX or tribox is out; a line of sight that misses
//! a CBOX passes; one through an INBOX is blocked), then a mesh's faces decide exactly, then
//! subobjects in turn. Every answer says which [`Stage`] decided it, and [`Counters`] add them
//! up over a batch.
//!
//! The geometry of lines of sight that these queries and the two drawing layers share (exact
//! forms along an edge, meet lines, intersection lines, the frustum) is the layer before this
//! one, `sight` (internal to the crate).
//!
//! ```
//! use kepler::{geometry::Point3, scene::Scene, queries::{Stage, include::{Inclusion, include}}};
//! let mut scene = Scene::new();
//! let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! assert_eq!(include(&scene, cube, &Point3::new(0.5, 0.5, 0.5)).unwrap(), (Inclusion::In, Stage::Inbox));
//! assert_eq!(include(&scene, cube, &Point3::new(1.0, 0.5, 0.5)).unwrap(), (Inclusion::On, Stage::Faces));
//! ```

pub mod include;
pub mod projection_grid;
pub mod visp;

use crate::geometry::Point3;
use rayon::prelude::*;
use serde::Serialize;

/// Why a query cannot be answered: the queries layer's error.
///
/// ```
/// use kepler::{geometry::Point3, queries::{QueryError, include::include}, scene::Scene};
/// let mut s = Scene::new();
/// let tent = kepler::io::read_mesh(std::path::Path::new("scenes/meshes/tent.stl")).unwrap();
/// let t = s.add_mesh(None, "tent", tent).unwrap();
/// assert!(matches!(include(&s, t, &Point3::origin()), Err(QueryError::NotClosed { .. })));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QueryError {
    /// INCLUDE asked of an object with an open mesh, which has no inside.
    #[error(
        "object '{object}': is an open mesh ({boundary_edges} boundary edges, {odd_edges} edges \
         on an odd number of faces) and has no inside: INCLUDE needs closed meshes"
    )]
    NotClosed {
        /// The path of the open mesh's object.
        object: String,
        /// Its edges on one face.
        boundary_edges: usize,
        /// Its edges on an odd number of faces.
        odd_edges: usize,
    },
}

/// What decided a query's answer, from the cheapest to the dearest.
///
/// ```
/// use kepler::queries::Stage;
/// assert!(Stage::Inbox < Stage::Faces);
/// assert_eq!(Stage::Tribox.name(), "TRIBOX");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Stage {
    /// An inscribing box: the point is inside one, or a line of sight passes through one.
    Inbox,
    /// A circumscribing box: the point is outside one, or a line of sight misses one.
    Cbox,
    /// A tribox: the point is outside one.
    Tribox,
    /// The faces of a mesh, tested exactly.
    Faces,
}

impl Stage {
    /// The name the paper (and the command line's summary) uses.
    ///
    /// ```
    /// assert_eq!(kepler::queries::Stage::Inbox.name(), "INBOX");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Stage::Inbox => "INBOX",
            Stage::Cbox => "CBOX",
            Stage::Tribox => "TRIBOX",
            Stage::Faces => "faces",
        }
    }
}

/// How many answers of a batch each [`Stage`] decided.
///
/// ```
/// use kepler::queries::{Counters, Stage};
/// let mut c = Counters::default();
/// c.record(Stage::Cbox);
/// c.record(Stage::Faces);
/// assert_eq!((c.cbox, c.faces, c.total()), (1, 1, 2));
/// ```
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Counters {
    /// Answers decided by an INBOX.
    pub inbox: u64,
    /// Answers decided by a CBOX.
    pub cbox: u64,
    /// Answers decided by a tribox.
    pub tribox: u64,
    /// Answers decided by faces.
    pub faces: u64,
}

impl Counters {
    /// Counts one answer decided by `stage`.
    ///
    /// ```
    /// let mut c = kepler::queries::Counters::default();
    /// c.record(kepler::queries::Stage::Tribox);
    /// assert_eq!(c.tribox, 1);
    /// ```
    pub fn record(&mut self, stage: Stage) {
        match stage {
            Stage::Inbox => self.inbox += 1,
            Stage::Cbox => self.cbox += 1,
            Stage::Tribox => self.tribox += 1,
            Stage::Faces => self.faces += 1,
        }
    }

    /// The counts of both.
    ///
    /// ```
    /// use kepler::queries::Counters;
    /// let a = Counters { inbox: 1, cbox: 2, tribox: 0, faces: 3 };
    /// assert_eq!(a.merged(&a).total(), 12);
    /// ```
    pub fn merged(&self, other: &Counters) -> Counters {
        Counters {
            inbox: self.inbox + other.inbox,
            cbox: self.cbox + other.cbox,
            tribox: self.tribox + other.tribox,
            faces: self.faces + other.faces,
        }
    }

    /// The number of answers counted.
    ///
    /// ```
    /// assert_eq!(kepler::queries::Counters::default().total(), 0);
    /// ```
    pub fn total(&self) -> u64 {
        self.inbox + self.cbox + self.tribox + self.faces
    }

    /// The counts with the stage names, for reports.
    ///
    /// ```
    /// let c = kepler::queries::Counters { inbox: 4, cbox: 0, tribox: 0, faces: 1 };
    /// assert_eq!(c.by_stage()[0], ("INBOX", 4));
    /// ```
    pub fn by_stage(&self) -> [(&'static str, u64); 4] {
        [
            (Stage::Inbox.name(), self.inbox),
            (Stage::Cbox.name(), self.cbox),
            (Stage::Tribox.name(), self.tribox),
            (Stage::Faces.name(), self.faces),
        ]
    }
}

/// Answers every point with `query`, in parallel, in the order given, and counts the stages.
fn in_parallel<T: Send>(
    points: &[Point3],
    query: impl Fn(&Point3) -> (T, Stage) + Sync,
) -> (Vec<T>, Counters) {
    let decided: Vec<(T, Stage)> = points.par_iter().map(&query).collect();
    let mut counters = Counters::default();
    let answers = decided
        .into_iter()
        .map(|(answer, stage)| {
            counters.record(stage);
            answer
        })
        .collect();
    (answers, counters)
}
