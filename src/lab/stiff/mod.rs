//! Stiff and extreme scenes, parametrised and seeded (issue 15): see [`generate`].
//!
//! A hidden-line drawing is a long chain of decisions: which side of a plane a vertex lies on,
//! where two edges cross in the picture, whether a face hides a point. Each is the sign of a
//! small determinant, and a scene is *stiff* when those determinants are tiny beside the
//! coordinates they come from, so that floating-point arithmetic decides them by its rounding
//! error. Franklin (1981) already asked for output "exact to the arithmetic precision of the
//! computer, not just to the accuracy of a pixel"; these families are the scenes where only an
//! exact engine gets there. Each is a small scene of a few objects, tens to a few hundred
//! triangles (the fan excepted), with an integer stiffness `k`: small `k` is mild, and the end
//! of the range is as extreme as doubles allow. The seed moves and sizes the objects and picks
//! the view, so that many different scenes of one stiffness can be drawn and checked.
//!
//! - **tilt**: faces coplanar up to a tilt of `10^-k` (`k = 16`: exactly coplanar), a plate
//!   sunk into a block with its top crossing the block's top, and a block against the front
//!   face. The planes' determinants vanish to `10^-k`; the intersection line of two nearly
//!   coplanar faces is where z-buffers fight and where a rounded intersection point lands
//!   anywhere along the face.
//! - **sliver**: a needle (a triangular prism) and a blade (a flat tetrahedron) whose faces
//!   have an aspect of `10^k`, piercing a box. Their planes are determined by a short side, so
//!   a plane computed from rounded data tilts by `10^k` ulps; their pictures are lines.
//! - **offset**: features of size about 1 on a block, the whole scene `10^k` from the origin.
//!   The coordinates keep the scene's shape exactly (they are dyadic, see below), but every
//!   difference cancels `k` digits, and a picture point rounded near `10^16` is off by 1.
//! - **scale**: intersecting solids scaled by `2^k`, `k` to ±300: products of coordinates
//!   overflow or underflow unless the engine moves the scene into its working range.
//! - **edge-on**: faces that contain the view direction exactly (seen as lines), edges seen
//!   end-on (as points), and faces tilted `10^-k` away from edge-on, whose pictures are
//!   slivers: the orientation tests with the eye are zero or nearly.
//! - **fan**: `2^k` triangles around a cone's apex (the cone closed by a polygon of `2^k`
//!   sides, or open), a bar piercing the cone near the apex, and on some seeds a post whose
//!   edge passes exactly through the apex; the view looks near the apex. Many edges meet in
//!   one point, so crossings there are ties, and every line of sight near it passes close to
//!   all of them.
//! - **nested**: boxes nested 3 to 5 deep with gaps of `10^-k` (or none: faces in their
//!   parents' planes), a rod through them all, boxes resting on the outside: hidden outlines
//!   `10^-k` from visible ones, and hidden faces exactly in visible faces' planes.
//! - **touching**: boxes on a grid sharing faces, edges and vertices exactly, or apart by gaps
//!   of `10^-k`, a tetrahedron standing on one: contact with no volume, where a visibility
//!   test sees a point exactly on a face.
//! - **tangent**: a box sunk `10^-k` into a block's top, one pressed `10^-k` into its front,
//!   and tetrahedra whose edge grazes the top `10^-k` below and above it: intersection lines
//!   that are thin slivers, or nearly exist.
//! - **inside-out**: meshes whose faces all point inward (as some files give them) among
//!   outward ones, with a face `10^-k` from another's plane: the tests that take a face's
//!   orientation for its side of the solid must not be fooled.
//!
//! The coordinates are built exactly: multiples of 1/8, with the small lengths the power of
//! two nearest `10^-k` (so `10^-15` is `2^-50`), within a few units of the origin so that each
//! sum of them is a double. So a plane meant to be tilted by `10^-k` is, faces meant to touch
//! do, and every quad is exactly planar. Generic views look along directions like
//! `(-0.3, 1, -0.45)`, not dyadic, so that no edge of these scenes is seen end-on and no
//! vertex exactly behind another by chance; the edge-on family looks along an exact direction
//! on purpose; nested, touching and the fan are seen in perspective, and the scale family on
//! odd seeds.
//!
//! [`write()`] saves a scene as OBJ files and a scene file with its camera, which
//! [`crate::scene::file::load`] reads back to the same meshes: `kepler gen` on the command
//! line.
//!
//! ```
//! use kepler::lab::stiff::{Family, generate};
//! use kepler::hidden::{Options, draw};
//! let stiff = generate(Family::Tilt, 12, 3).unwrap();
//! assert_eq!(stiff.name(), "tilt k=12 seed=3");
//! let drawing = draw(&stiff.scene, &stiff.view, &Options::default()).unwrap();
//! assert!(drawing.polylines.iter().any(|l| l.visible));
//! assert!(drawing.polylines.iter().any(|l| !l.visible));
//! ```

mod cameras;
mod choices;
mod families;
mod save;
mod shapes;

pub use save::write;

use self::choices::Choices;
use crate::mesh::Mesh;
use crate::random::SplitMix64;
use crate::scene::{Camera, Scene};
use crate::views::View;
use std::fmt;
use std::ops::RangeInclusive;

/// A family of stiff scenes, each with an integer stiffness parameter `k` (see the
/// [module](self) for what each stresses).
///
/// ```
/// use kepler::lab::stiff::Family;
/// assert_eq!(Family::EdgeOn.name(), "edge-on");
/// assert_eq!(Family::from_name("inside-out"), Some(Family::InsideOut));
/// assert_eq!(Family::Scale.parameters(true), [-280, 0, 280]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// Faces coplanar up to a tilt of `10^-k`; `k = 16` exactly coplanar.
    Tilt,
    /// Needles and blades with faces of aspect `10^k` piercing a box.
    Sliver,
    /// Features of size about 1 on a block, the scene `10^k` from the origin.
    Offset,
    /// Intersecting solids scaled by `2^k`.
    Scale,
    /// Faces seen exactly edge-on, and faces tilted `10^-k` from edge-on.
    EdgeOn,
    /// `2^k` triangles around a cone's apex, seen near the apex.
    Fan,
    /// Boxes nested inside each other with gaps of `10^-k`.
    Nested,
    /// Boxes sharing faces, edges and vertices, or apart by `10^-k`.
    Touching,
    /// Boxes and edges `10^-k` into, or above, another's face.
    Tangent,
    /// Meshes turned inside out among outward ones, a face `10^-k` from another's plane.
    InsideOut,
}

impl Family {
    /// Every family, in the order of the report.
    ///
    /// ```
    /// use kepler::lab::stiff::Family;
    /// assert_eq!(Family::ALL.len(), 10);
    /// assert!(Family::ALL.iter().all(|f| Family::from_name(f.name()) == Some(*f)));
    /// ```
    pub const ALL: [Family; 10] = [
        Family::Tilt,
        Family::Sliver,
        Family::Offset,
        Family::Scale,
        Family::EdgeOn,
        Family::Fan,
        Family::Nested,
        Family::Touching,
        Family::Tangent,
        Family::InsideOut,
    ];

    /// The family's name: `tilt`, `sliver`, `offset`, `scale`, `edge-on`, `fan`, `nested`,
    /// `touching`, `tangent` or `inside-out`.
    ///
    /// ```
    /// assert_eq!(kepler::lab::stiff::Family::InsideOut.name(), "inside-out");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Family::Tilt => "tilt",
            Family::Sliver => "sliver",
            Family::Offset => "offset",
            Family::Scale => "scale",
            Family::EdgeOn => "edge-on",
            Family::Fan => "fan",
            Family::Nested => "nested",
            Family::Touching => "touching",
            Family::Tangent => "tangent",
            Family::InsideOut => "inside-out",
        }
    }

    /// The family with this [name](Family::name).
    ///
    /// ```
    /// use kepler::lab::stiff::Family;
    /// assert_eq!(Family::from_name("fan"), Some(Family::Fan));
    /// assert_eq!(Family::from_name("Fan"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.name() == name)
    }

    /// What `k` means.
    ///
    /// ```
    /// assert_eq!(kepler::lab::stiff::Family::Sliver.parameter(), "aspect 10^k");
    /// ```
    pub fn parameter(self) -> &'static str {
        match self {
            Family::Tilt => "tilt 10^-k (k = 16: coplanar)",
            Family::Sliver => "aspect 10^k",
            Family::Offset => "offset 10^k",
            Family::Scale => "scale 2^k",
            Family::EdgeOn => "tilt 10^-k from edge-on",
            Family::Fan => "2^k triangles at the apex",
            Family::Nested => "gap 10^-k",
            Family::Touching => "gap 10^-k",
            Family::Tangent => "depth 10^-k",
            Family::InsideOut => "offset 10^-k from coplanar",
        }
    }

    /// The values of `k` [`generate`] accepts.
    ///
    /// ```
    /// use kepler::lab::stiff::Family;
    /// assert_eq!(Family::Offset.range(), 0..=16);
    /// assert!(Family::ALL.iter().all(|f| f.parameters(false).iter().all(|k| f.range().contains(k))));
    /// ```
    pub fn range(self) -> RangeInclusive<i32> {
        match self {
            Family::Tilt => 1..=16,
            Family::Sliver => 1..=12,
            Family::Offset => 0..=16,
            Family::Scale => -300..=300,
            Family::Fan => 2..=12,
            Family::EdgeOn
            | Family::Nested
            | Family::Touching
            | Family::Tangent
            | Family::InsideOut => 1..=15,
        }
    }

    /// The values of `k` to run, from mild to extreme: three when `quick` (both ends of the
    /// range and one between; for the scale ±280 and 0, for the fan 2, 6 and 9: at `k = 12`
    /// one fan takes minutes to draw and verify), else seven to ten.
    ///
    /// ```
    /// use kepler::lab::stiff::Family;
    /// assert_eq!(Family::Tilt.parameters(true), [1, 8, 16]);
    /// assert_eq!(Family::Fan.parameters(false).last(), Some(&11));
    /// ```
    pub fn parameters(self, quick: bool) -> Vec<i32> {
        let (quick_values, full): (&[i32], &[i32]) = match self {
            Family::Tilt => (&[1, 8, 16], &[1, 2, 4, 6, 8, 10, 12, 14, 15, 16]),
            Family::Sliver => (&[1, 6, 12], &[1, 2, 4, 6, 8, 10, 12]),
            Family::Offset => (&[0, 8, 16], &[0, 2, 4, 6, 8, 10, 12, 14, 15, 16]),
            Family::Scale => (
                &[-280, 0, 280],
                &[-300, -200, -100, -30, 0, 30, 100, 200, 300],
            ),
            // At 2^12 triangles a scene takes 13 s to draw and 25 s to verify (the fan's
            // triangles all meet at the apex: the intersection pass is quadratic there), so
            // the report stops at 2^11; `kepler gen` makes k = 12.
            Family::Fan => (&[2, 6, 9], &[2, 4, 6, 8, 10, 11]),
            Family::EdgeOn
            | Family::Nested
            | Family::Touching
            | Family::Tangent
            | Family::InsideOut => (&[1, 8, 15], &[1, 3, 5, 7, 9, 11, 13, 15]),
        };
        if quick { quick_values } else { full }.to_vec()
    }
}

impl fmt::Display for Family {
    /// The family's [name](Family::name).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A generated scene: its family, stiffness and seed, the scene (its camera set to the view)
/// and the view to draw it in.
///
/// ```
/// use kepler::lab::stiff::{Family, generate};
/// let s = generate(Family::Nested, 5, 1).unwrap();
/// assert!(s.view.is_perspective());
/// assert!(s.scene.camera().is_some());
/// assert_eq!((s.family, s.parameter, s.seed), (Family::Nested, 5, 1));
/// ```
#[derive(Debug)]
pub struct StiffScene {
    /// The family.
    pub family: Family,
    /// The stiffness `k`.
    pub parameter: i32,
    /// The seed of the placement.
    pub seed: u64,
    /// The scene: one top-level mesh object per solid, and the camera of `view`.
    pub scene: Scene,
    /// The view, [`View::from_camera`] of the scene's camera.
    pub view: View,
}

impl StiffScene {
    /// The scene's name: family, stiffness and seed.
    ///
    /// ```
    /// let s = kepler::lab::stiff::generate(kepler::lab::stiff::Family::Scale, -280, 0).unwrap();
    /// assert_eq!(s.name(), "scale k=-280 seed=0");
    /// ```
    pub fn name(&self) -> String {
        format!("{} k={} seed={}", self.family, self.parameter, self.seed)
    }

    /// The stem of the files [`write`] makes: `tilt-k12-seed3`.
    fn stem(&self) -> String {
        format!("{}-k{}-seed{}", self.family, self.parameter, self.seed)
    }
}

/// What can go wrong generating a stiff scene.
///
/// ```
/// use kepler::lab::stiff::{Family, StiffError, generate};
/// let e = generate(Family::Sliver, 13, 0).unwrap_err();
/// assert!(matches!(e, StiffError::Parameter { parameter: 13, .. }));
/// assert_eq!(e.to_string(), "sliver: k = 13 is outside 1..=12 (aspect 10^k)");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum StiffError {
    /// `k` is outside the family's [range](Family::range).
    #[error("{family}: k = {parameter} is outside {}..={} ({})",
        family.range().start(), family.range().end(), family.parameter())]
    Parameter {
        /// The family.
        family: Family,
        /// The stiffness asked for.
        parameter: i32,
    },
    /// The engine refused what the generator built (a bug of the generator).
    #[error(transparent)]
    Engine(#[from] crate::Error),
}

/// The scene of `family` at stiffness `parameter` (within [`Family::range`]), placed by
/// `seed`: the same arguments give the same scene, bit for bit.
///
/// ```
/// use kepler::lab::stiff::{Family, generate};
/// let a = generate(Family::Touching, 9, 1).unwrap();
/// let b = generate(Family::Touching, 9, 2).unwrap();
/// let meshes = |s: &kepler::scene::Scene| -> Vec<kepler::mesh::Mesh> {
///     s.mesh_objects(s.roots()).into_iter().map(|(_, m)| m.clone()).collect()
/// };
/// assert_eq!(meshes(&a.scene), meshes(&generate(Family::Touching, 9, 1).unwrap().scene));
/// assert_ne!(meshes(&a.scene), meshes(&b.scene));
/// ```
pub fn generate(family: Family, parameter: i32, seed: u64) -> Result<StiffScene, StiffError> {
    if !family.range().contains(&parameter) {
        return Err(StiffError::Parameter { family, parameter });
    }
    let (scene, view) = build(family, parameter, seed)?;
    Ok(StiffScene {
        family,
        parameter,
        seed,
        scene,
        view,
    })
}

// ---------------------------------------------------------------------------------------------
// The families.

/// The solids of a scene, by name, and the camera to see them with.
pub(super) type Layout = (Vec<(String, Mesh)>, Camera);

/// The scene and view of a family at stiffness `k`, placed by `seed`.
fn build(family: Family, k: i32, seed: u64) -> crate::Result<(Scene, View)> {
    let rng = &mut Choices(SplitMix64(seed));
    let (objects, camera) = match family {
        Family::Tilt => families::tilt(k, rng),
        Family::Sliver => families::sliver(k, rng),
        Family::Offset => families::offset(k, rng),
        Family::Scale => families::scale(k, rng, seed % 2 == 1),
        Family::EdgeOn => families::edge_on(k, rng),
        Family::Fan => families::fan(k, rng),
        Family::Nested => families::nested(k, rng),
        Family::Touching => families::touching(k, rng),
        Family::Tangent => families::tangent(k, rng),
        Family::InsideOut => families::inside_out(k, rng),
    }?;
    let mut scene = Scene::new();
    for (name, mesh) in objects {
        scene.add_mesh(None, name, mesh)?;
    }
    scene.set_camera(camera);
    let view = View::from_camera(&camera)?;
    Ok((scene, view))
}
