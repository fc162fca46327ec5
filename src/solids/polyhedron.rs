//! The 5 Platonic and 13 Archimedean solids.

use super::coordinates::{Family, Perms, Signs, expand, phi, snub_xi, tribonacci};
use super::hull::{Template, faces_of};
use super::{SolidError, positive};
use crate::geometry::Point3;
use crate::mesh::Mesh;
use std::sync::OnceLock;

/// One of the 5 Platonic and 13 Archimedean solids.
///
/// Meshes are centred at the origin, built from the standard vertex coordinates (all
/// vertices on one sphere) with the convex hull's faces as polygons. The snub cube and snub
/// dodecahedron are chiral; the mesh is one fixed enantiomorph of each.
///
/// ```
/// use kepler::solids::Polyhedron;
/// let p = Polyhedron::from_name("Truncated Icosahedron").unwrap();
/// assert_eq!(p, Polyhedron::TruncatedIcosahedron);
/// assert_eq!((p.vertices(), p.edges(), p.faces()), (60, 90, 32));
/// let m = p.mesh(2.0).unwrap();
/// assert!((m.volume() - p.volume(2.0)).abs() < 1e-12 * p.volume(2.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Polyhedron {
    /// 4 triangles.
    Tetrahedron,
    /// 6 squares.
    Cube,
    /// 8 triangles.
    Octahedron,
    /// 12 pentagons.
    Dodecahedron,
    /// 20 triangles.
    Icosahedron,
    /// 4 triangles, 4 hexagons.
    TruncatedTetrahedron,
    /// 8 triangles, 6 squares.
    Cuboctahedron,
    /// 8 triangles, 6 octagons.
    TruncatedCube,
    /// 6 squares, 8 hexagons.
    TruncatedOctahedron,
    /// 8 triangles, 18 squares.
    Rhombicuboctahedron,
    /// 12 squares, 8 hexagons, 6 octagons.
    TruncatedCuboctahedron,
    /// 32 triangles, 6 squares.
    SnubCube,
    /// 20 triangles, 12 pentagons.
    Icosidodecahedron,
    /// 20 triangles, 12 decagons.
    TruncatedDodecahedron,
    /// 12 pentagons, 20 hexagons.
    TruncatedIcosahedron,
    /// 20 triangles, 30 squares, 12 pentagons.
    Rhombicosidodecahedron,
    /// 30 squares, 20 hexagons, 12 decagons.
    TruncatedIcosidodecahedron,
    /// 80 triangles, 12 pentagons.
    SnubDodecahedron,
}

use Polyhedron::*;

/// Name, vertices, edges, faces of each solid, in the order of [`Polyhedron::ALL`].
const TABLE: [(&str, usize, usize, usize); 18] = [
    ("tetrahedron", 4, 6, 4),
    ("cube", 8, 12, 6),
    ("octahedron", 6, 12, 8),
    ("dodecahedron", 20, 30, 12),
    ("icosahedron", 12, 30, 20),
    ("truncated-tetrahedron", 12, 18, 8),
    ("cuboctahedron", 12, 24, 14),
    ("truncated-cube", 24, 36, 14),
    ("truncated-octahedron", 24, 36, 14),
    ("rhombicuboctahedron", 24, 48, 26),
    ("truncated-cuboctahedron", 48, 72, 26),
    ("snub-cube", 24, 60, 38),
    ("icosidodecahedron", 30, 60, 32),
    ("truncated-dodecahedron", 60, 90, 32),
    ("truncated-icosahedron", 60, 90, 32),
    ("rhombicosidodecahedron", 60, 120, 62),
    ("truncated-icosidodecahedron", 120, 180, 62),
    ("snub-dodecahedron", 60, 150, 92),
];

impl Polyhedron {
    /// All 18 solids: the Platonic ones, then the Archimedean ones.
    ///
    /// ```
    /// use kepler::solids::Polyhedron;
    /// assert_eq!(Polyhedron::ALL.len(), 18);
    /// assert_eq!(Polyhedron::ALL[1], Polyhedron::Cube);
    /// ```
    pub const ALL: [Polyhedron; 18] = [
        Tetrahedron,
        Cube,
        Octahedron,
        Dodecahedron,
        Icosahedron,
        TruncatedTetrahedron,
        Cuboctahedron,
        TruncatedCube,
        TruncatedOctahedron,
        Rhombicuboctahedron,
        TruncatedCuboctahedron,
        SnubCube,
        Icosidodecahedron,
        TruncatedDodecahedron,
        TruncatedIcosahedron,
        Rhombicosidodecahedron,
        TruncatedIcosidodecahedron,
        SnubDodecahedron,
    ];

    /// The kebab-case name, e.g. `"truncated-icosahedron"`.
    ///
    /// ```
    /// assert_eq!(kepler::solids::Polyhedron::SnubCube.name(), "snub-cube");
    /// ```
    pub fn name(&self) -> &'static str {
        TABLE[*self as usize].0
    }

    /// The solid with this name, in kebab-case, snake_case or words separated by spaces, in
    /// any letter case.
    ///
    /// ```
    /// use kepler::solids::Polyhedron;
    /// assert_eq!(Polyhedron::from_name("snub_dodecahedron"), Some(Polyhedron::SnubDodecahedron));
    /// assert_eq!(Polyhedron::from_name("Truncated Cube"), Some(Polyhedron::TruncatedCube));
    /// assert_eq!(Polyhedron::from_name("hypercube"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Polyhedron> {
        let key = name
            .split(|c: char| c == '-' || c == '_' || c.is_whitespace())
            .filter(|w| !w.is_empty())
            .map(str::to_lowercase)
            .collect::<Vec<_>>()
            .join("-");
        Polyhedron::ALL.into_iter().find(|p| p.name() == key)
    }

    /// Number of vertices.
    ///
    /// ```
    /// assert_eq!(kepler::solids::Polyhedron::TruncatedIcosidodecahedron.vertices(), 120);
    /// ```
    pub fn vertices(&self) -> usize {
        TABLE[*self as usize].1
    }

    /// Number of edges.
    ///
    /// ```
    /// assert_eq!(kepler::solids::Polyhedron::SnubDodecahedron.edges(), 150);
    /// ```
    pub fn edges(&self) -> usize {
        TABLE[*self as usize].2
    }

    /// Number of faces.
    ///
    /// ```
    /// assert_eq!(kepler::solids::Polyhedron::Rhombicuboctahedron.faces(), 26);
    /// ```
    pub fn faces(&self) -> usize {
        TABLE[*self as usize].3
    }

    /// The mesh with the given edge length (finite and greater than 0), centred at the
    /// origin. The unit-edge solid is built once and scaled.
    ///
    /// ```
    /// use kepler::solids::Polyhedron;
    /// let m = Polyhedron::SnubCube.mesh(1.0).unwrap();
    /// assert!(m.is_solid());
    /// assert_eq!(m.faces().len(), 38);
    /// assert!(Polyhedron::SnubCube.mesh(f64::NAN).is_err());
    /// ```
    pub fn mesh(&self, edge: f64) -> Result<Mesh, SolidError> {
        let edge = positive(self.name(), "edge", edge)?;
        let t = self.template();
        let vertices = t.vertices.iter().map(|p| p * edge).collect();
        Ok(Mesh::from_polygons(vertices, t.faces.clone())?)
    }

    /// The volume at the given edge length, from its closed form in the literature
    /// (independent of the mesh).
    ///
    /// ```
    /// use kepler::solids::Polyhedron;
    /// assert!((Polyhedron::Cube.volume(2.0) - 8.0).abs() < 1e-15);
    /// let v = Polyhedron::TruncatedIcosahedron.volume(1.0);
    /// assert!((v - (125.0 + 43.0 * 5f64.sqrt()) / 4.0).abs() < 1e-12);
    /// ```
    pub fn volume(&self, edge: f64) -> f64 {
        let (r2, r5) = (2f64.sqrt(), 5f64.sqrt());
        let unit = match self {
            Tetrahedron => r2 / 12.0,
            Cube => 1.0,
            Octahedron => r2 / 3.0,
            Dodecahedron => (15.0 + 7.0 * r5) / 4.0,
            Icosahedron => 5.0 * (3.0 + r5) / 12.0,
            TruncatedTetrahedron => 23.0 * r2 / 12.0,
            Cuboctahedron => 5.0 * r2 / 3.0,
            TruncatedCube => (21.0 + 14.0 * r2) / 3.0,
            TruncatedOctahedron => 8.0 * r2,
            Rhombicuboctahedron => (12.0 + 10.0 * r2) / 3.0,
            TruncatedCuboctahedron => 22.0 + 14.0 * r2,
            SnubCube => {
                let t = tribonacci();
                (3.0 * (t - 1.0).sqrt() + 4.0 * (t + 1.0).sqrt()) / (3.0 * (2.0 - t).sqrt())
            }
            Icosidodecahedron => (45.0 + 17.0 * r5) / 6.0,
            TruncatedDodecahedron => 5.0 * (99.0 + 47.0 * r5) / 12.0,
            TruncatedIcosahedron => (125.0 + 43.0 * r5) / 4.0,
            Rhombicosidodecahedron => (60.0 + 29.0 * r5) / 3.0,
            TruncatedIcosidodecahedron => 95.0 + 50.0 * r5,
            SnubDodecahedron => {
                // Coxeter et al. (1954), with ξ the real root of ξ³ − 2ξ = φ.
                let (f, x) = (phi(), snub_xi());
                let numerator =
                    12.0 * x * x * (3.0 * f + 1.0) - x * (36.0 * f + 7.0) - (53.0 * f + 6.0);
                numerator / (6.0 * (3.0 - x * x).powi(3).sqrt())
            }
        };
        unit * edge * edge * edge
    }

    /// The surface area at the given edge length, from its closed form.
    ///
    /// ```
    /// use kepler::solids::Polyhedron;
    /// assert!((Polyhedron::Cube.surface_area(3.0) - 54.0).abs() < 1e-12);
    /// let m = Polyhedron::SnubDodecahedron.mesh(1.0).unwrap();
    /// assert!((m.surface_area() - Polyhedron::SnubDodecahedron.surface_area(1.0)).abs() < 1e-12);
    /// ```
    pub fn surface_area(&self, edge: f64) -> f64 {
        let (r2, r3) = (2f64.sqrt(), 3f64.sqrt());
        // Areas of a unit pentagon ×4 and a unit decagon ÷5·2, as they appear in the formulas.
        let p = (25.0 + 10.0 * 5f64.sqrt()).sqrt();
        let d = (5.0 + 2.0 * 5f64.sqrt()).sqrt();
        let unit = match self {
            Tetrahedron => r3,
            Cube => 6.0,
            Octahedron => 2.0 * r3,
            Dodecahedron => 3.0 * p,
            Icosahedron => 5.0 * r3,
            TruncatedTetrahedron => 7.0 * r3,
            Cuboctahedron => 6.0 + 2.0 * r3,
            TruncatedCube => 2.0 * (6.0 + 6.0 * r2 + r3),
            TruncatedOctahedron => 6.0 + 12.0 * r3,
            Rhombicuboctahedron => 18.0 + 2.0 * r3,
            TruncatedCuboctahedron => 12.0 * (2.0 + r2 + r3),
            SnubCube => 6.0 + 8.0 * r3,
            Icosidodecahedron => 5.0 * r3 + 3.0 * p,
            TruncatedDodecahedron => 5.0 * (r3 + 6.0 * d),
            TruncatedIcosahedron => 3.0 * (10.0 * r3 + p),
            Rhombicosidodecahedron => 30.0 + 5.0 * r3 + 3.0 * p,
            TruncatedIcosidodecahedron => 30.0 * (1.0 + r3 + d),
            SnubDodecahedron => 20.0 * r3 + 3.0 * p,
        };
        unit * edge * edge
    }

    /// The unit-edge template, built on first use.
    fn template(&self) -> &'static Template {
        static CACHE: [OnceLock<Template>; 18] = [const { OnceLock::new() }; 18];
        CACHE[*self as usize].get_or_init(|| faces_of(&self.coordinates()))
    }

    /// The standard vertex coordinates (at the literature's edge length, not 1).
    fn coordinates(&self) -> Vec<Point3> {
        let f = phi();
        let r2 = 2f64.sqrt();
        let families = match self {
            Tetrahedron => vec![Family {
                base: [1.0, 1.0, 1.0],
                perms: Perms::Even,
                signs: Signs::EvenFlips,
            }],
            Cube => vec![Family::all([1.0, 1.0, 1.0])],
            Octahedron => vec![Family::all([1.0, 0.0, 0.0])],
            Dodecahedron => vec![
                Family::all([1.0, 1.0, 1.0]),
                Family::even([0.0, f, 1.0 / f]),
            ],
            Icosahedron => vec![Family::even([0.0, 1.0, f])],
            TruncatedTetrahedron => vec![Family {
                base: [3.0, 1.0, 1.0],
                perms: Perms::All,
                signs: Signs::EvenFlips,
            }],
            Cuboctahedron => vec![Family::all([1.0, 1.0, 0.0])],
            TruncatedCube => vec![Family::all([r2 - 1.0, 1.0, 1.0])],
            TruncatedOctahedron => vec![Family::all([0.0, 1.0, 2.0])],
            Rhombicuboctahedron => vec![Family::all([1.0, 1.0, 1.0 + r2])],
            TruncatedCuboctahedron => vec![Family::all([1.0, 1.0 + r2, 1.0 + 2.0 * r2])],
            SnubCube => snub_cube_families(),
            Icosidodecahedron => vec![
                Family::even([0.0, 0.0, f]),
                Family::even([0.5, f / 2.0, f * f / 2.0]),
            ],
            TruncatedDodecahedron => vec![
                Family::even([0.0, 1.0 / f, 2.0 + f]),
                Family::even([1.0 / f, f, 2.0 * f]),
                Family::even([f, 2.0, f + 1.0]),
            ],
            TruncatedIcosahedron => vec![
                Family::even([0.0, 1.0, 3.0 * f]),
                Family::even([1.0, 2.0 + f, 2.0 * f]),
                Family::even([f, 2.0, 2.0 * f + 1.0]),
            ],
            Rhombicosidodecahedron => vec![
                Family::even([1.0, 1.0, 2.0 * f + 1.0]),
                Family::even([f + 1.0, f, 2.0 * f]),
                Family::even([2.0 + f, 0.0, f + 1.0]),
            ],
            TruncatedIcosidodecahedron => vec![
                Family::even([1.0 / f, 1.0 / f, 3.0 + f]),
                Family::even([2.0 / f, f, 1.0 + 2.0 * f]),
                Family::even([1.0 / f, f + 1.0, 3.0 * f - 1.0]),
                Family::even([2.0 * f - 1.0, 2.0, 2.0 + f]),
                Family::even([f, 3.0, 2.0 * f]),
            ],
            SnubDodecahedron => snub_dodecahedron_families(f),
        };
        expand(&families)
    }
}

/// The snub cube's vertex families: even permutations of `(1, 1/t, t)` (`t` the tribonacci
/// constant) with an even number of plus signs (an odd number of flips of the all-plus
/// triple), odd permutations with an odd number.
fn snub_cube_families() -> Vec<Family> {
    let t = tribonacci();
    let base = [1.0, 1.0 / t, t];
    vec![
        Family {
            base,
            perms: Perms::Even,
            signs: Signs::OddFlips,
        },
        Family {
            base,
            perms: Perms::Odd,
            signs: Signs::EvenFlips,
        },
    ]
}

/// The snub dodecahedron's vertex families (`f` the golden ratio φ): even permutations with
/// an even number of plus signs, where α = ξ − 1/ξ and β = ξφ + φ² + φ/ξ.
fn snub_dodecahedron_families(f: f64) -> Vec<Family> {
    let x = snub_xi();
    let a = x - 1.0 / x;
    let b = x * f + f * f + f / x;
    [
        [2.0 * a, 2.0, 2.0 * b],
        [a + b / f + f, -a * f + b + 1.0 / f, a / f + b * f - 1.0],
        [-a / f + b * f + 1.0, -a + b / f - f, a * f + b - 1.0 / f],
        [-a / f + b * f - 1.0, a - b / f - f, a * f + b + 1.0 / f],
        [a + b / f - f, a * f - b + 1.0 / f, a / f + b * f + 1.0],
    ]
    .into_iter()
    .map(|base| Family {
        base,
        perms: Perms::Even,
        signs: Signs::OddFlips,
    })
    .collect()
}

/// Writes the kebab-case [`name`](Polyhedron::name).
///
/// ```
/// assert_eq!(kepler::solids::Polyhedron::TruncatedCube.to_string(), "truncated-cube");
/// ```
impl std::fmt::Display for Polyhedron {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
