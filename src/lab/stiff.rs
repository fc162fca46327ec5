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

use super::boxtree::spheres::SplitMix64;
use crate::geometry::exact::ldexp;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::scene::{Camera, Content, Projection, Scene};
use crate::solids;
use crate::views::View;
use std::cmp::Ordering;
use std::fmt;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

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
fn camera_toml(camera: &Camera) -> String {
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
fn obj(mesh: &Mesh, scene: &str, object: &str) -> String {
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

// ---------------------------------------------------------------------------------------------
// The families.

/// The solids of a scene, by name, and the camera to see them with.
type Layout = (Vec<(String, Mesh)>, Camera);

/// The scene and view of a family at stiffness `k`, placed by `seed`.
fn build(family: Family, k: i32, seed: u64) -> crate::Result<(Scene, View)> {
    let rng = &mut Rng(SplitMix64(seed));
    let (objects, camera) = match family {
        Family::Tilt => tilt(k, rng),
        Family::Sliver => sliver(k, rng),
        Family::Offset => offset(k, rng),
        Family::Scale => scale(k, rng, seed % 2 == 1),
        Family::EdgeOn => edge_on(k, rng),
        Family::Fan => fan(k, rng),
        Family::Nested => nested(k, rng),
        Family::Touching => touching(k, rng),
        Family::Tangent => tangent(k, rng),
        Family::InsideOut => inside_out(k, rng),
    }?;
    let mut scene = Scene::new();
    for (name, mesh) in objects {
        scene.add_mesh(None, name, mesh)?;
    }
    scene.set_camera(camera);
    let view = View::from_camera(&camera)?;
    Ok((scene, view))
}

/// A plate sunk into a block, its top tilted `10^-k` about a line in the block's top (so the
/// two tops cross there), and a block in front whose back face is tilted `10^-k` about a
/// vertical line in the block's front face. `k = 16`: both exactly coplanar.
fn tilt(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let t = if k >= 16 { 0.0 } else { ten_to_the(-k) };
    let (w, y0, h) = (
        rng.eighths(3.0, 4.5),
        rng.eighths(1.0, 1.875),
        rng.eighths(1.0, 1.875),
    );
    let depth = rng.eighths(2.0, 3.0);
    let base = solids::box_between([0.0, y0, 0.0], [w, y0 + depth, h])?;
    // The plate: 2 or 4 wide, its top h ∓ rise at its ends, h at its middle.
    let half = 1.0 + rng.below(2) as f64;
    let xa = rng.eighths(0.25 - half, w - half - 0.25);
    let ya = y0 + rng.eighths(-1.0, 0.5);
    let yb = ya + rng.eighths(1.5, 2.5);
    let bottom = h - rng.eighths(0.5, 0.75);
    let rise = rng.sign() * t * half;
    let plate = hexahedron(std::array::from_fn(|c| {
        let (right, back, top) = (c & 1 != 0, c & 2 != 0, c & 4 != 0);
        let z = match (top, right) {
            (false, _) => bottom,
            (true, false) => h - rise,
            (true, true) => h + rise,
        };
        Point3::new(
            if right { xa + 2.0 * half } else { xa },
            if back { yb } else { ya },
            z,
        )
    }))?;
    // The block in front: 2 wide, its back face y0 ∓ t at its sides.
    let xf = rng.eighths(-0.75, w - 1.25);
    let yf = y0 - rng.eighths(1.0, 2.0);
    let top = rng.eighths(0.75, h + 0.5);
    let lean = rng.sign() * t;
    let front = hexahedron(std::array::from_fn(|c| {
        let (right, back, up) = (c & 1 != 0, c & 2 != 0, c & 4 != 0);
        let y = match (back, right) {
            (false, _) => yf,
            (true, false) => y0 - lean,
            (true, true) => y0 + lean,
        };
        Point3::new(
            if right { xf + 2.0 } else { xf },
            y,
            if up { top } else { 0.0 },
        )
    }))?;
    Ok((
        named([("base", base), ("plate", plate), ("front", front)]),
        generic_view(rng),
    ))
}

/// A needle (a triangular prism about 3.5 long, its cross-section about `4·10^-k`) and a blade
/// (a tetrahedron about 2 across and `2·10^-k` thick), both piercing a box's front face.
fn sliver(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let h = 4.0 * ten_to_the(-k);
    let (w, y0, depth, height) = (
        rng.eighths(3.0, 4.0),
        rng.eighths(0.5, 1.0),
        rng.eighths(2.0, 3.0),
        rng.eighths(1.5, 2.5),
    );
    let block = solids::box_between([0.0, y0, 0.0], [w, y0 + depth, height])?;
    let o = Point3::new(
        rng.eighths(0.5, w - 1.0),
        y0 - rng.eighths(1.0, 1.5),
        rng.eighths(0.5, height - 0.5),
    );
    let along = Vector3::new(
        rng.eighths(-1.0, 1.0),
        rng.eighths(2.5, 3.5),
        rng.eighths(-0.5, 0.5),
    );
    let needle = prism(
        [
            o,
            o + Vector3::new(h, 0.0, 0.0),
            o + Vector3::new(h / 2.0, 0.0, h),
        ],
        along,
    )?;
    // The blade: one corner inside the box, two in front of it, the fourth just above (or
    // below) a point inside the triangle.
    let z = rng.eighths(0.25, height - 0.25);
    let inner = Point3::new(rng.eighths(1.0, w - 1.0), y0 + rng.eighths(0.5, 1.5), z);
    let left = Point3::new(
        inner.x - rng.eighths(0.5, 1.0),
        y0 - rng.eighths(0.5, 1.5),
        z,
    );
    let right = Point3::new(
        inner.x + rng.eighths(0.5, 1.0),
        y0 - rng.eighths(0.5, 1.5),
        z,
    );
    let middle = (inner.coords + left.coords + 2.0 * right.coords) / 4.0;
    let apex = Point3::new(middle.x, middle.y, z + rng.sign() * h / 2.0);
    let blade = tetrahedron([inner, left, right, apex])?;
    Ok((
        named([("block", block), ("needle", needle), ("blade", blade)]),
        generic_view(rng),
    ))
}

/// A block about 7 wide with three features of size 0.5 to 1.5 on its top (one resting, one
/// sunk, one across its front edge), all moved `10^k` along each axis (the signs by the seed).
/// The features are multiples of 1/8, so every coordinate is exact up to `k = 15`; at
/// `k = 16` the doubles are 2 apart, and the scene is 16 times larger to stay exact.
fn offset(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let t = 10f64.powi(k);
    let grow = ((t.next_up() - t) * 8.0).max(1.0);
    let origin = [rng.sign() * t, rng.sign() * t, rng.sign() * t];
    let (w, d, h) = (
        rng.eighths(6.0, 7.5),
        rng.eighths(6.0, 7.5),
        rng.eighths(3.0, 4.0),
    );
    let s1 = rng.eighths(0.5, 1.5);
    let (x1, y1) = (rng.eighths(1.0, w - 4.0), rng.eighths(1.0, d - 3.0));
    let s2 = 2.0 * rng.eighths(0.25, 0.75);
    let (x2, y2) = (
        x1 + s1 + rng.eighths(0.25, 1.0),
        y1 + rng.eighths(-0.5, 0.5),
    );
    let s3 = 2.0 * rng.eighths(0.25, 0.75);
    let x3 = rng.eighths(1.0, w - 2.0);
    let boxes = [
        ("block", [0.0, 0.0, 0.0], [w, d, h]),
        ("resting", [x1, y1, h], [x1 + s1, y1 + s1, h + s1]),
        (
            "sunk",
            [x2, y2, h - s2 / 2.0],
            [x2 + s2, y2 + s2, h + s2 / 2.0],
        ),
        (
            "edge",
            [x3, -s3 / 2.0, h - s3 / 2.0],
            [x3 + s3, s3 / 2.0, h + s3 / 2.0],
        ),
    ];
    let at = |c: [f64; 3]| std::array::from_fn(|i| origin[i] + c[i] * grow);
    let objects = boxes
        .into_iter()
        .map(|(name, lo, hi)| Ok((name.to_string(), solids::box_between(at(lo), at(hi))?)))
        .collect::<crate::Result<_>>()?;
    Ok((objects, generic_view(rng)))
}

/// A block pierced by a rod and a spike, a box in front of it, all scaled by `2^k` (exactly);
/// seen orthographically on even seeds, in perspective (the eye scaled too) on odd ones.
fn scale(k: i32, rng: &mut Rng, seed_is_odd: bool) -> crate::Result<Layout> {
    let (w, d, h) = (
        rng.eighths(3.0, 4.0),
        rng.eighths(3.0, 4.0),
        rng.eighths(2.0, 3.0),
    );
    let (yr, zr) = (rng.eighths(0.5, d - 1.5), rng.eighths(0.5, h - 1.5));
    let rod = (
        [-1.0, yr, zr],
        [
            w + 1.0,
            yr + rng.eighths(0.5, 1.0),
            zr + rng.eighths(0.5, 1.0),
        ],
    );
    // The spike's apex stands above the block; its base, inside, is a triangle around the
    // apex's foot.
    let (xt, yt) = (rng.eighths(1.0, w - 1.0), rng.eighths(1.0, d - 1.0));
    let spike = [
        [xt, yt, h + rng.eighths(0.75, 1.5)],
        [
            xt - rng.eighths(0.5, 1.0),
            yt - rng.eighths(0.25, 0.75),
            h - rng.eighths(0.5, 1.0),
        ],
        [
            xt + rng.eighths(0.5, 1.0),
            yt - rng.eighths(0.25, 0.75),
            h - rng.eighths(0.5, 1.0),
        ],
        [
            xt + rng.eighths(-0.25, 0.25),
            yt + rng.eighths(0.5, 1.0),
            h - rng.eighths(0.5, 1.0),
        ],
    ];
    let xf = rng.eighths(-0.5, w - 2.0);
    let front = (
        [xf, -rng.eighths(2.0, 3.0), 0.0],
        [
            xf + rng.eighths(1.5, 2.5),
            -rng.eighths(0.5, 1.0),
            rng.eighths(1.0, 2.0),
        ],
    );
    let s = |c: [f64; 3]| c.map(|x| ldexp(x, k));
    let p = |c: [f64; 3]| Point3::from(s(c));
    let camera = if seed_is_odd {
        let centre = [w / 2.0, d / 2.0, h / 2.0];
        let eye = [
            centre[0] + rng.sign() * rng.eighths(4.0, 8.0),
            centre[1] - rng.eighths(10.0, 14.0),
            centre[2] + rng.eighths(6.0, 10.0),
        ];
        perspective(s(eye), s(centre))
    } else {
        generic_view(rng)
    };
    Ok((
        named([
            ("block", solids::box_between(s([0.0; 3]), s([w, d, h]))?),
            ("rod", solids::box_between(s(rod.0), s(rod.1))?),
            ("spike", tetrahedron(spike.map(p))?),
            ("front", solids::box_between(s(front.0), s(front.1))?),
        ]),
        camera,
    ))
}

/// Seen along an exact direction `d`: a prism along `d` (faces edge-on, edges end-on), a slab
/// with two faces containing `d` but no edge along it, piercing the prism, a slab behind whose
/// faces are `10^-k` from containing `d`, and a floor.
fn edge_on(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let d = rng.pick(&EXACT_DIRECTIONS);
    let half = Vector3::from(d) / 2.0;
    let eps = ten_to_the(-k);
    let floor = solids::box_between([-3.5, -2.0, -2.0], [3.5, 4.0, -1.5])?;
    let o = Point3::new(
        rng.eighths(-2.5, -1.5),
        rng.eighths(-1.5, -1.0),
        rng.eighths(-1.25, -0.75),
    );
    let across = Vector3::new(rng.eighths(1.0, 1.5), rng.eighths(-0.25, 0.25), 0.0);
    let up = Vector3::new(rng.eighths(-0.25, 0.25), 0.0, rng.eighths(1.25, 1.75));
    let prism = parallelepiped(o, [half, across, up])?;
    // A corner inside the prism, the slab reaching out of it.
    let inside = o + half / 2.0 + across / 2.0 + up / 4.0;
    let g = Vector3::new(rng.eighths(0.5, 1.0), 0.0, rng.eighths(-0.25, 0.25));
    let rise = Vector3::new(
        rng.eighths(-0.25, 0.25),
        rng.eighths(-0.25, 0.25),
        rng.eighths(1.0, 1.5),
    );
    let slab = parallelepiped(inside, [half + g, half - g, rise])?;
    let behind = o + Vector3::new(
        rng.eighths(0.5, 1.5),
        rng.eighths(1.5, 2.5),
        rng.eighths(-0.25, 0.5),
    );
    let g2 = Vector3::new(rng.eighths(0.5, 1.0), 0.0, 0.0);
    let tilted = parallelepiped(
        behind,
        [half + g2 + Vector3::new(0.0, 0.0, eps), half - g2, rise],
    )?;
    let camera = Camera {
        projection: Projection::Orthographic { direction: d },
        up: [0.0, 0.0, 1.0],
    };
    Ok((
        named([
            ("floor", floor),
            ("prism", prism),
            ("slab", slab),
            ("tilted", tilted),
        ]),
        camera,
    ))
}

/// A cone of `2^k` triangles standing on a floor (closed by its base, a polygon of `2^k`
/// sides, on half the seeds; open, its rim on the floor, on the others), a bar through it
/// below the apex and, on half the seeds, a post whose vertical edge passes exactly through the
/// apex; the eye above looks at a point 1/8 from the apex.
fn fan(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let (ax, ay, height) = (
        rng.eighths(-0.5, 0.5),
        rng.eighths(-0.5, 0.5),
        rng.eighths(2.5, 3.5),
    );
    let radius = rng.eighths(1.5, 2.5);
    // The base: 2^k points of the circle, from exact rational points of its first quarter
    // (t = j/m, the point ((1 − t²)/(1 + t²), 2t/(1 + t²)), rounded the same way everywhere,
    // unlike sines) turned by quarter turns, which are exact.
    let m = 1u32 << (k - 2);
    let quarter: Vec<(f64, f64)> = (0..m)
        .map(|j| {
            let t = f64::from(j) / f64::from(m);
            let n = 1.0 + t * t;
            (radius * ((1.0 - t * t) / n), radius * (2.0 * t / n))
        })
        .collect();
    let mut vertices = vec![Point3::new(ax, ay, height)];
    for turn in 0..4 {
        vertices.extend(quarter.iter().map(|&(x, y)| {
            let (x, y) = match turn {
                0 => (x, y),
                1 => (-y, x),
                2 => (-x, -y),
                _ => (y, -x),
            };
            Point3::new(x, y, 0.0)
        }));
    }
    let n = 4 * m;
    let mut faces: Vec<Vec<u32>> = (0..n).map(|i| vec![1 + i, 1 + (i + 1) % n, 0]).collect();
    let cone = if rng.below(2) == 0 {
        faces.push((1..=n).rev().collect());
        outward(Mesh::from_polygons(vertices, faces)?)?
    } else {
        Mesh::from_polygons(vertices, faces)?
    };
    let floor = solids::box_between([-3.0, -3.0, -0.5], [3.0, 3.0, 0.0])?;
    let zb = rng.eighths(height / 2.0, height - 0.75);
    let yb = ay - rng.eighths(0.125, 0.375);
    let bar = solids::box_between(
        [-3.0, yb, zb],
        [
            3.0,
            yb + rng.eighths(0.25, 0.5),
            zb + rng.eighths(0.25, 0.5),
        ],
    )?;
    let mut objects = named([("floor", floor), ("cone", cone), ("bar", bar)]);
    if rng.below(2) == 0 {
        let post = solids::box_between(
            [ax, ay, height - 0.75],
            [ax + 0.375, ay + 0.375, height + 0.5],
        )?;
        objects.push(("post".to_string(), post));
    }
    let eye = [
        ax + rng.eighths(-1.5, 1.5),
        ay - rng.eighths(2.0, 3.0),
        height + rng.eighths(3.5, 5.0),
    ];
    Ok((
        objects,
        perspective(eye, [ax + rng.sign() / 8.0, ay, height]),
    ))
}

/// An outer box with 2 to 4 boxes nested in it, each face of each inset by 0, 1, 2 or 3 times
/// `10^-k` or by 1/8 to 1/4; a rod through them all, a lid resting on the outer box and a box
/// against its side; seen in perspective.
fn nested(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let mut lo = [
        rng.eighths(-2.0, -1.5),
        rng.eighths(-1.5, -1.0),
        rng.eighths(-1.5, -1.0),
    ];
    let mut hi = lo.map(|c| c + rng.eighths(2.5, 3.25));
    let (outer_lo, outer_hi) = (lo, hi);
    let mut objects = vec![("outer".to_string(), solids::box_between(lo, hi)?)];
    let levels = 2 + rng.below(3);
    let mut inset = || match rng.below(5) {
        4 => rng.eighths(0.125, 0.25),
        m => m as f64 * g,
    };
    for level in 1..=levels {
        for i in 0..3 {
            lo[i] += inset();
            hi[i] -= inset();
        }
        objects.push((format!("inner{level}"), solids::box_between(lo, hi)?));
    }
    // Through the middle, which every nested box contains.
    let mid = |i: usize| ((outer_lo[i] + outer_hi[i]) * 4.0).floor() / 8.0;
    let rod = solids::box_between(
        [outer_lo[0] - 1.0, mid(1) - 0.125, mid(2) - 0.125],
        [outer_hi[0] + 1.0, mid(1) + 0.125, mid(2) + 0.125],
    )?;
    let s = rng.eighths(0.5, 1.0);
    let (xl, yl) = (
        rng.eighths(outer_lo[0], outer_hi[0] - 0.5),
        rng.eighths(outer_lo[1], outer_hi[1] - 0.5),
    );
    let lid = solids::box_between([xl, yl, outer_hi[2]], [xl + s, yl + s, outer_hi[2] + s])?;
    let zs = rng.eighths(outer_lo[2], outer_hi[2] - 0.75);
    let side = solids::box_between(
        [outer_lo[0] - 0.75, outer_lo[1] + 0.5, zs],
        [outer_lo[0], outer_lo[1] + 1.25, zs + 0.75],
    )?;
    objects.extend(named([("rod", rod), ("lid", lid), ("side", side)]));
    let centre = [0, 1, 2].map(mid);
    let eye = [
        centre[0] + rng.sign() * rng.eighths(4.0, 6.0),
        centre[1] - rng.eighths(7.0, 9.0),
        centre[2] + rng.eighths(4.0, 6.0),
    ];
    Ok((objects, perspective(eye, centre)))
}

/// Boxes in the cells of a 3 × 2 × 2 grid (each cell taken with probability 2/3), neighbours
/// touching or apart by `10^-k` or `2·10^-k` along each axis, and a tetrahedron standing on
/// the top of one with a corner at the box's corner; seen in perspective.
fn touching(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let cells = [3, 2, 2];
    let start = [-2.25, -1.5, -1.25];
    // Along each axis, where each cell starts and how long it is.
    let axes: Vec<Vec<(f64, f64)>> = (0..3)
        .map(|i| {
            let mut at = start[i];
            (0..cells[i])
                .map(|_| {
                    let cell = (at, rng.eighths(1.0, 1.5));
                    at += cell.1 + g * rng.below(3) as f64;
                    cell
                })
                .collect()
        })
        .collect();
    let mut chosen: Vec<[usize; 3]> = Vec::new();
    for x in 0..cells[0] {
        for y in 0..cells[1] {
            for z in 0..cells[2] {
                if rng.below(3) != 0 || chosen.len() + (12 - 4 * x - 2 * y - z) <= 3 {
                    chosen.push([x, y, z]);
                }
            }
        }
    }
    let mut objects = Vec::new();
    for c in &chosen {
        let lo: [f64; 3] = std::array::from_fn(|i| axes[i][c[i]].0);
        let hi: [f64; 3] = std::array::from_fn(|i| axes[i][c[i]].0 + axes[i][c[i]].1);
        objects.push((
            format!("box{}{}{}", c[0], c[1], c[2]),
            solids::box_between(lo, hi)?,
        ));
    }
    // On the highest chosen box, at its corner of smallest x and y.
    let top = chosen
        .iter()
        .max_by_key(|c| c[2])
        .copied()
        .unwrap_or([0; 3]);
    let (x, y) = (axes[0][top[0]].0, axes[1][top[1]].0);
    let z = axes[2][top[2]].0 + axes[2][top[2]].1;
    let (a, b) = (rng.eighths(0.5, 1.0), rng.eighths(0.5, 1.0));
    let tetra = tetrahedron([
        Point3::new(x, y, z),
        Point3::new(x + a, y, z),
        Point3::new(x, y + b, z),
        Point3::new(x + a / 4.0, y + b / 4.0, z + rng.eighths(0.5, 1.0)),
    ])?;
    objects.push(("tetra".to_string(), tetra));
    let eye = [
        rng.sign() * rng.eighths(4.0, 6.0),
        -rng.eighths(7.0, 9.0),
        rng.eighths(5.0, 7.0),
    ];
    Ok((objects, perspective(eye, [0.0; 3])))
}

/// The block of the tangent and inside-out families and its width, front, depth and height:
/// `[0, w] × [y0, y0 + d] × [0, h]`.
fn block(rng: &mut Rng) -> crate::Result<(Mesh, [f64; 4])> {
    let (w, y0, d, h) = (
        rng.eighths(3.0, 3.75),
        rng.eighths(0.0, 0.5),
        rng.eighths(2.5, 3.0),
        rng.eighths(1.5, 2.0),
    );
    Ok((
        solids::box_between([0.0, y0, 0.0], [w, y0 + d, h])?,
        [w, y0, d, h],
    ))
}

/// A block with a box sunk `10^-k` into its top, one pressed `10^-k` into its front face, and
/// two tetrahedra whose lowest edge runs `10^-k` below and `10^-k` above its top.
fn tangent(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let (block, [w, y0, d, h]) = block(rng)?;
    let (xs, ys) = (
        rng.eighths(w - 1.25, w - 0.5),
        rng.eighths(y0 + 0.5, y0 + 1.25),
    );
    let sunk = solids::box_between(
        [xs, ys, h - g],
        [
            xs + rng.eighths(1.0, 1.5),
            ys + rng.eighths(1.0, 1.5),
            h - g + rng.eighths(0.5, 1.0),
        ],
    )?;
    let (xp, zp) = (rng.eighths(0.25, 1.25), rng.eighths(0.25, h - 1.0));
    let pressed = solids::box_between(
        [xp, y0 - rng.eighths(0.5, 1.0), zp],
        [
            xp + rng.eighths(0.75, 1.25),
            y0 + g,
            zp + rng.eighths(0.5, 0.75),
        ],
    )?;
    let at = Point3::new(
        rng.eighths(0.25, 1.0),
        rng.eighths(y0 + 1.5, y0 + d - 0.5),
        h - g,
    );
    let below = wedge(rng, at)?;
    let at = Point3::new(rng.eighths(0.25, 1.0), y0 + 0.75, h + g);
    let above = wedge(rng, at)?;
    Ok((
        named([
            ("block", block),
            ("sunk", sunk),
            ("pressed", pressed),
            ("grazing-in", below),
            ("grazing-out", above),
        ]),
        generic_view(rng),
    ))
}

/// A block; a box turned inside out, through the block's side, its top `10^-k` above or below
/// the block's; a tetrahedron turned inside out through the block's front face; an outward box
/// in front, `10^-k` from the front face.
fn inside_out(k: i32, rng: &mut Rng) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let (block, [w, y0, _, h]) = block(rng)?;
    let (xb, yb, zb) = (
        rng.eighths(w - 1.0, w - 0.5),
        rng.eighths(y0 + 0.25, y0 + 1.0),
        rng.eighths(0.25, h - 0.75),
    );
    let inverted_box = reversed(&solids::box_between(
        [xb, yb, zb],
        [
            xb + rng.eighths(1.5, 2.0),
            yb + rng.eighths(1.0, 1.5),
            h + rng.sign() * g,
        ],
    )?)?;
    let (xc, zc) = (rng.eighths(0.75, w - 1.5), rng.eighths(0.5, h - 0.75));
    let inverted_tetra = reversed(&tetrahedron([
        Point3::new(xc, y0 + rng.eighths(0.5, 1.0), zc),
        Point3::new(xc - 0.5, y0 - 1.0, zc - rng.eighths(0.25, 0.5)),
        Point3::new(xc + 0.5, y0 - 1.0, zc - rng.eighths(0.25, 0.5)),
        Point3::new(xc, y0 - 0.75, zc + 0.5),
    ])?)?;
    let xf = rng.eighths(-0.5, w - 1.5);
    let front = solids::box_between(
        [xf, y0 - rng.eighths(0.75, 1.25), 0.0],
        [xf + rng.eighths(1.0, 1.5), y0 - g, rng.eighths(0.5, 1.0)],
    )?;
    Ok((
        named([
            ("block", block),
            ("inverted-box", inverted_box),
            ("inverted-tetra", inverted_tetra),
            ("front", front),
        ]),
        generic_view(rng),
    ))
}

// ---------------------------------------------------------------------------------------------
// Solids and views.

/// A wedge: a tetrahedron whose lowest edge runs from `a` along `x` (1 to 1.5 long), its other
/// two corners above the edge's middle, one on each side.
fn wedge(rng: &mut Rng, a: Point3) -> crate::Result<Mesh> {
    let length = rng.eighths(1.0, 1.5);
    let b = Point3::new(a.x + length, a.y + rng.eighths(-0.25, 0.25), a.z);
    let up = a.z + rng.eighths(0.5, 0.75);
    let xm = a.x + length / 2.0;
    let c = Point3::new(xm, a.y - rng.eighths(0.25, 0.5), up);
    let e = Point3::new(xm, a.y + rng.eighths(0.25, 0.5), up);
    tetrahedron([a, b, c, e])
}

/// View directions for the generic orthographic views: from the front (`+y`), above and to a
/// side; not dyadic, so that no difference of two of the scenes' (dyadic) vertices is
/// parallel to one, and no edge is seen end-on by chance.
const GENERIC_DIRECTIONS: [[f64; 3]; 5] = [
    [-0.3, 1.0, -0.45],
    [0.35, 1.0, -0.55],
    [-0.6, 1.0, -0.35],
    [0.55, 1.0, -0.7],
    [-0.15, 1.0, -0.8],
];

/// Exact (dyadic) view directions for the edge-on family.
const EXACT_DIRECTIONS: [[f64; 3]; 4] = [
    [-1.0, 2.0, -0.5],
    [0.5, 2.0, -0.75],
    [-0.75, 2.0, -1.0],
    [1.0, 2.0, -0.5],
];

/// An orthographic camera along one of [`GENERIC_DIRECTIONS`], `z` up.
fn generic_view(rng: &mut Rng) -> Camera {
    Camera {
        projection: Projection::Orthographic {
            direction: rng.pick(&GENERIC_DIRECTIONS),
        },
        up: [0.0, 0.0, 1.0],
    }
}

/// A perspective camera from `eye` at `target`, `z` up, with a field of view of 40 degrees.
fn perspective(eye: [f64; 3], target: [f64; 3]) -> Camera {
    Camera {
        projection: Projection::Perspective {
            eye,
            target,
            fov: 40.0,
        },
        up: [0.0, 0.0, 1.0],
    }
}

/// `10^e` rounded to the nearest power of two (`10^-15` is `2^-50`): a length that keeps sums
/// with multiples of 1/8 below 4 exact.
fn ten_to_the(e: i32) -> f64 {
    ldexp(
        1.0,
        (f64::from(e) * std::f64::consts::LOG2_10).round() as i32,
    )
}

/// The objects with their names as strings.
fn named<const N: usize>(objects: [(&str, Mesh); N]) -> Vec<(String, Mesh)> {
    objects
        .into_iter()
        .map(|(name, mesh)| (name.to_string(), mesh))
        .collect()
}

/// The faces of a hexahedron whose corner `c` is on the high side of axis `i` when bit `i` of
/// `c` is set (as [`solids::box_between`] numbers them).
const BOX_FACES: [[u32; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

/// The hexahedron with these corners (numbered as in [`BOX_FACES`]), turned outward.
fn hexahedron(corners: [Point3; 8]) -> crate::Result<Mesh> {
    let faces = BOX_FACES.iter().map(|f| f.to_vec()).collect();
    outward(Mesh::from_polygons(corners.to_vec(), faces)?)
}

/// The parallelepiped at `o` with edges `u`, `v`, `w`, turned outward.
fn parallelepiped(o: Point3, [u, v, w]: [Vector3; 3]) -> crate::Result<Mesh> {
    hexahedron(std::array::from_fn(|c| {
        let mut p = o;
        for (bit, e) in [u, v, w].iter().enumerate() {
            if c & (1 << bit) != 0 {
                p += *e;
            }
        }
        p
    }))
}

/// The tetrahedron with these corners, turned outward.
fn tetrahedron(p: [Point3; 4]) -> crate::Result<Mesh> {
    let faces = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
    outward(Mesh::from_polygons(p.to_vec(), faces)?)
}

/// The prism swept by the triangle `t` along `a`, turned outward.
fn prism(t: [Point3; 3], a: Vector3) -> crate::Result<Mesh> {
    let vertices = vec![t[0], t[1], t[2], t[0] + a, t[1] + a, t[2] + a];
    let faces = vec![
        vec![0, 2, 1],
        vec![3, 4, 5],
        vec![0, 1, 4, 3],
        vec![1, 2, 5, 4],
        vec![2, 0, 3, 5],
    ];
    outward(Mesh::from_polygons(vertices, faces)?)
}

/// The mesh with its faces turned outward (its exact orientation positive).
fn outward(mesh: Mesh) -> crate::Result<Mesh> {
    match mesh.orientation() {
        Ordering::Less => reversed(&mesh),
        _ => Ok(mesh),
    }
}

/// The mesh with every face reversed: inside out.
fn reversed(mesh: &Mesh) -> crate::Result<Mesh> {
    let faces = mesh
        .polygons()
        .into_iter()
        .map(|mut f| {
            f.reverse();
            f
        })
        .collect();
    Ok(Mesh::from_polygons(mesh.vertices().to_vec(), faces)?)
}

/// The seeded choices of a scene. [`SplitMix64`] (shared with the BOXTREE sphere experiment)
/// is a dozen lines where a random-number crate would be a dependency, and gives the same
/// scenes on every machine.
struct Rng(SplitMix64);

impl Rng {
    /// A uniform integer in `0..n` (for `n > 0`).
    fn below(&mut self, n: usize) -> usize {
        ((self.0.unit() * n as f64) as usize).min(n - 1)
    }

    /// A uniform multiple of 1/8 in `[lo, hi]` (the first above `lo` when there is none).
    fn eighths(&mut self, lo: f64, hi: f64) -> f64 {
        let (a, b) = ((lo * 8.0).ceil(), (hi * 8.0).floor());
        let steps = if b > a { (b - a) as usize + 1 } else { 1 };
        (a + self.below(steps) as f64) / 8.0
    }

    /// One of `items` (not empty).
    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }

    /// 1 or −1.
    fn sign(&mut self) -> f64 {
        if self.below(2) == 0 { 1.0 } else { -1.0 }
    }
}
