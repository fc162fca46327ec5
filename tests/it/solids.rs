//! Tests of the built-in solids: the 18 Platonic and Archimedean polyhedra against their known
//! counts, face kinds, vertex configurations and closed-form volumes and areas; prisms; and the
//! faceted solids of revolution against the closed-form volumes of the polyhedra they are.

use geo::{Area, LineString, Polygon, polygon};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::solids::{self, Polyhedron, SolidError};
use proptest::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::{PI, TAU};

/// Relative difference.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Undirected edges of a mesh, from its input polygons (a polygon rounding made not exactly
/// planar is split into triangle faces; its diagonals are not edges of the solid).
fn edges(m: &Mesh) -> BTreeSet<(u32, u32)> {
    m.polygons()
        .into_iter()
        .flat_map(|v| {
            (0..v.len()).map(move |i| {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                (a.min(b), a.max(b))
            })
        })
        .collect()
}

/// The known data of each solid: vertices, edges, faces, faces by number of sides, and the
/// vertex configuration (sizes of the faces around a vertex, sorted).
struct Known {
    solid: Polyhedron,
    v: usize,
    e: usize,
    f: usize,
    kinds: &'static [(usize, usize)],
    config: &'static [usize],
}

const KNOWN: [Known; 18] = {
    use Polyhedron::*;
    const fn k(
        solid: Polyhedron,
        v: usize,
        e: usize,
        f: usize,
        kinds: &'static [(usize, usize)],
        config: &'static [usize],
    ) -> Known {
        Known {
            solid,
            v,
            e,
            f,
            kinds,
            config,
        }
    }
    [
        k(Tetrahedron, 4, 6, 4, &[(3, 4)], &[3, 3, 3]),
        k(Cube, 8, 12, 6, &[(4, 6)], &[4, 4, 4]),
        k(Octahedron, 6, 12, 8, &[(3, 8)], &[3, 3, 3, 3]),
        k(Dodecahedron, 20, 30, 12, &[(5, 12)], &[5, 5, 5]),
        k(Icosahedron, 12, 30, 20, &[(3, 20)], &[3, 3, 3, 3, 3]),
        k(
            TruncatedTetrahedron,
            12,
            18,
            8,
            &[(3, 4), (6, 4)],
            &[3, 6, 6],
        ),
        k(Cuboctahedron, 12, 24, 14, &[(3, 8), (4, 6)], &[3, 3, 4, 4]),
        k(TruncatedCube, 24, 36, 14, &[(3, 8), (8, 6)], &[3, 8, 8]),
        k(
            TruncatedOctahedron,
            24,
            36,
            14,
            &[(4, 6), (6, 8)],
            &[4, 6, 6],
        ),
        k(
            Rhombicuboctahedron,
            24,
            48,
            26,
            &[(3, 8), (4, 18)],
            &[3, 4, 4, 4],
        ),
        k(
            TruncatedCuboctahedron,
            48,
            72,
            26,
            &[(4, 12), (6, 8), (8, 6)],
            &[4, 6, 8],
        ),
        k(SnubCube, 24, 60, 38, &[(3, 32), (4, 6)], &[3, 3, 3, 3, 4]),
        k(
            Icosidodecahedron,
            30,
            60,
            32,
            &[(3, 20), (5, 12)],
            &[3, 3, 5, 5],
        ),
        k(
            TruncatedDodecahedron,
            60,
            90,
            32,
            &[(3, 20), (10, 12)],
            &[3, 10, 10],
        ),
        k(
            TruncatedIcosahedron,
            60,
            90,
            32,
            &[(5, 12), (6, 20)],
            &[5, 6, 6],
        ),
        k(
            Rhombicosidodecahedron,
            60,
            120,
            62,
            &[(3, 20), (4, 30), (5, 12)],
            &[3, 4, 4, 5],
        ),
        k(
            TruncatedIcosidodecahedron,
            120,
            180,
            62,
            &[(4, 30), (6, 20), (10, 12)],
            &[4, 6, 10],
        ),
        k(
            SnubDodecahedron,
            60,
            150,
            92,
            &[(3, 80), (5, 12)],
            &[3, 3, 3, 3, 5],
        ),
    ]
};

/// Checks everything about one polyhedron at one edge length.
fn check_polyhedron(k: &Known, edge: f64) {
    let p = k.solid;
    let name = p.name();
    let m = p.mesh(edge).unwrap();
    assert!(m.is_solid(), "{name}");
    assert_eq!(m.merged_vertices(), 0, "{name}");

    // Counts, from the table and from the library, and Euler's formula.
    let es = edges(&m);
    let polygons = m.polygons();
    let (v, e, f) = (m.vertices().len(), es.len(), polygons.len());
    assert_eq!((v, e, f), (k.v, k.e, k.f), "{name}");
    assert_eq!(
        (p.vertices(), p.edges(), p.faces()),
        (k.v, k.e, k.f),
        "{name}"
    );
    // A split polygon of n sides is n - 2 triangle faces meeting along n - 3 diagonals.
    let diagonals = m.faces().len() - f;
    assert_eq!(m.topology().edges, e + diagonals, "{name}");
    assert_eq!(v + f, e + 2, "{name}");

    // Faces by number of sides.
    let mut kinds = BTreeMap::new();
    for polygon in &polygons {
        *kinds.entry(polygon.len()).or_insert(0) += 1;
    }
    assert_eq!(kinds.into_iter().collect::<Vec<_>>(), k.kinds, "{name}");

    // Every vertex has the same configuration.
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); v];
    for polygon in &polygons {
        for &i in polygon {
            around[i as usize].push(polygon.len());
        }
    }
    for (i, mut sizes) in around.into_iter().enumerate() {
        sizes.sort_unstable();
        assert_eq!(sizes, k.config, "{name} vertex {i}");
    }

    // All edges have the given length.
    for &(a, b) in &es {
        let d = (m.vertices()[a as usize] - m.vertices()[b as usize]).norm();
        assert!(rel(d, edge) < 1e-12, "{name}: edge {a}-{b} has length {d}");
    }

    // Centred at the origin, all vertices on one sphere.
    let centre = m
        .vertices()
        .iter()
        .fold(Vector3::zeros(), |s, q| s + q.coords)
        / v as f64;
    assert!(centre.norm() < 1e-12 * edge, "{name}: centre {centre:?}");
    let radius = m.vertices()[0].coords.norm();
    for q in m.vertices() {
        assert!(
            rel(q.coords.norm(), radius) < 1e-12,
            "{name}: {q:?} off the sphere"
        );
    }

    // Every face is a regular polygon: equal sides (checked above), planar to rounding, its
    // vertices on the circle of radius a / (2 sin(π/k)) about their centroid. Faces point
    // outward and the solid is convex: every vertex is on the inner side of every face.
    for face in m.faces() {
        let fi = face.polygon();
        let pts: Vec<Point3> = polygons[fi]
            .iter()
            .map(|&i| m.vertices()[i as usize])
            .collect();
        let sides = pts.len() as f64;
        let c = pts.iter().fold(Vector3::zeros(), |s, q| s + q.coords) / sides;
        let circumradius = edge / (2.0 * (PI / sides).sin());
        for q in &pts {
            assert!(
                rel((q.coords - c).norm(), circumradius) < 1e-12,
                "{name}: face {fi}"
            );
            assert!(
                face.plane().evaluate(q).abs() < 1e-12 * edge,
                "{name}: face {fi}"
            );
        }
        assert!(
            face.plane().normal.dot(&c) > 0.0,
            "{name}: face {fi} points inward"
        );
        let tolerance = 1e-12 * edge;
        assert!(
            m.vertices()
                .iter()
                .all(|q| face.plane().evaluate(q) < tolerance),
            "{name}: not convex at face {fi}"
        );
    }

    // Volume and area against the closed forms, and the area against the sum of the regular
    // polygons' areas (k a² / (4 tan(π/k))).
    assert!(
        rel(m.volume(), p.volume(edge)) < 1e-12,
        "{name}: volume {} vs {}",
        m.volume(),
        p.volume(edge)
    );
    assert!(
        rel(m.surface_area(), p.surface_area(edge)) < 1e-12,
        "{name}: area"
    );
    let polygons: f64 = k
        .kinds
        .iter()
        .map(|&(s, count)| count as f64 * s as f64 * edge * edge / (4.0 * (PI / s as f64).tan()))
        .sum();
    assert!(
        rel(p.surface_area(edge), polygons) < 1e-12,
        "{name}: area formula"
    );
}

#[test]
fn all_polyhedra_are_right() {
    assert_eq!(
        Polyhedron::ALL.to_vec(),
        KNOWN.iter().map(|k| k.solid).collect::<Vec<_>>()
    );
    for k in &KNOWN {
        check_polyhedron(k, 1.0);
        check_polyhedron(k, 2.5);
        check_polyhedron(k, 1e-3);
    }
}

#[test]
fn closed_forms_agree_with_literature_decimals() {
    // Values for unit edge quoted in the literature (Wikipedia, MathWorld).
    let quoted = [
        (Polyhedron::Dodecahedron, 7.663_118_960_624_632),
        (Polyhedron::TruncatedIcosahedron, 55.287_730_758_122_74),
        (Polyhedron::SnubDodecahedron, 37.616_649_962_733_36),
        (
            Polyhedron::TruncatedIcosidodecahedron,
            206.803_398_874_989_5,
        ),
    ];
    for (p, v) in quoted {
        assert!(rel(p.volume(1.0), v) < 1e-13, "{}", p.name());
    }
    assert!(rel(Polyhedron::SnubCube.volume(1.0), 7.889_477_4) < 1e-8);
    assert!(
        rel(
            Polyhedron::SnubDodecahedron.surface_area(1.0),
            55.286_744_958_445_15
        ) < 1e-13
    );
    // Volumes scale with the cube of the edge.
    for p in Polyhedron::ALL {
        assert!(rel(p.volume(3.0), 27.0 * p.volume(1.0)) < 1e-15);
        assert!(rel(p.surface_area(3.0), 9.0 * p.surface_area(1.0)) < 1e-15);
    }
}

#[test]
fn names_round_trip() {
    let names: BTreeSet<&str> = Polyhedron::ALL.iter().map(|p| p.name()).collect();
    assert_eq!(names.len(), 18);
    for p in Polyhedron::ALL {
        let kebab = p.name();
        assert!(kebab.chars().all(|c| c.is_ascii_lowercase() || c == '-'));
        assert_eq!(p.to_string(), kebab);
        assert_eq!(Polyhedron::from_name(kebab), Some(p));
        assert_eq!(Polyhedron::from_name(&kebab.replace('-', "_")), Some(p));
        assert_eq!(
            Polyhedron::from_name(&kebab.replace('-', " ").to_uppercase()),
            Some(p)
        );
        assert_eq!(
            Polyhedron::from_name(&format!("  {}  ", kebab.replace('-', "  "))),
            Some(p)
        );
    }
    assert_eq!(
        Polyhedron::from_name("Truncated_Icosahedron"),
        Some(Polyhedron::TruncatedIcosahedron)
    );
    for bad in [
        "",
        "cubes",
        "truncated",
        "snub",
        "great-rhombicuboctahedron",
        "-",
    ] {
        assert_eq!(Polyhedron::from_name(bad), None, "{bad:?}");
    }
}

#[test]
fn platonic_shorthands() {
    type Make = fn(f64) -> Result<Mesh, SolidError>;
    let pairs: [(Make, Polyhedron); 5] = [
        (solids::tetrahedron, Polyhedron::Tetrahedron),
        (solids::cube, Polyhedron::Cube),
        (solids::octahedron, Polyhedron::Octahedron),
        (solids::dodecahedron, Polyhedron::Dodecahedron),
        (solids::icosahedron, Polyhedron::Icosahedron),
    ];
    for (make, p) in pairs {
        assert_eq!(make(1.5).unwrap(), p.mesh(1.5).unwrap());
        assert!(make(0.0).is_err());
    }
    // The cube is exact: vertices ±edge/2, each face's plane at distance edge/2.
    let c = solids::cube(2.0).unwrap();
    assert!(
        c.vertices()
            .iter()
            .all(|q| q.iter().all(|x| x.abs() == 1.0))
    );
    assert_eq!(c.surface_area(), 24.0);
    assert!(
        c.faces()
            .iter()
            .all(|f| f.area() == 4.0 && f.plane().d == -1.0)
    );
}

#[test]
fn cuboid_is_an_exact_box() {
    let b = solids::cuboid(Vector3::new(1.0, 2.0, 4.0)).unwrap();
    assert!(b.is_solid());
    assert_eq!((b.vertices().len(), b.faces().len()), (8, 6));
    assert_eq!(b.volume(), 8.0);
    assert_eq!(b.surface_area(), 2.0 * (2.0 + 4.0 + 8.0));
    let normals = [
        Vector3::new(-1.0, 0.0, 0.0),
        Vector3::x(),
        Vector3::new(0.0, -1.0, 0.0),
        Vector3::y(),
        Vector3::new(0.0, 0.0, -1.0),
        Vector3::z(),
    ];
    for (f, n) in b.faces().iter().zip(normals) {
        assert_eq!(f.plane().normal, n);
    }
    for q in b.vertices() {
        assert_eq!((q.x.abs(), q.y.abs(), q.z.abs()), (0.5, 1.0, 2.0));
    }
    let e = solids::cuboid(Vector3::new(1.0, f64::NAN, 1.0)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "cuboid: size.y must be a finite number greater than 0, got NaN"
    );
    assert!(solids::cuboid(Vector3::new(1.0, 1.0, -1.0)).is_err());
}

#[test]
fn bad_edges_are_errors_never_panics() {
    for p in Polyhedron::ALL {
        for bad in [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            match p.mesh(bad) {
                Err(SolidError::InvalidParameter {
                    solid, parameter, ..
                }) => {
                    assert_eq!((solid, parameter), (p.name(), "edge"));
                }
                other => panic!("{}: edge {bad}: {other:?}", p.name()),
            }
        }
        // Extreme but valid numbers: either a mesh or a mesh error, never a panic.
        for edge in [
            f64::MIN_POSITIVE,
            1e-310,
            1e-300,
            1e90,
            1e101,
            1e300,
            f64::MAX,
        ] {
            match p.mesh(edge) {
                Ok(m) => assert!(m.is_solid()),
                Err(SolidError::Mesh(_)) => {}
                Err(e) => panic!("{}: edge {edge}: {e}", p.name()),
            }
        }
        // Scaling keeps faces planar over a wide range.
        for edge in [1e-9, 1e-3, 0.1, 7.3, 1e6, 1e12] {
            assert!(p.mesh(edge).is_ok(), "{} at {edge}", p.name());
        }
    }
    assert_eq!(
        solids::dodecahedron(-2.0).unwrap_err().to_string(),
        "dodecahedron: edge must be a finite number greater than 0, got -2"
    );
    // Every finite size is accepted.
    assert!(solids::cube(1e300).unwrap().is_solid());
}

// ---------------------------------------------------------------------------------------
// Prisms

fn poly(points: &[(f64, f64)]) -> Polygon<f64> {
    Polygon::new(LineString::from(points.to_vec()), vec![])
}

/// A star with `points` tips (radius 2) and notches (radius 1): not convex.
fn star(points: usize) -> Vec<(f64, f64)> {
    (0..2 * points)
        .map(|k| {
            let r = if k % 2 == 0 { 2.0 } else { 1.0 };
            let a = k as f64 * PI / points as f64;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

/// The faces of a mesh as sets of coordinate loops, each rotated to start at its smallest
/// vertex, so that two meshes of the same solid compare equal.
fn face_loops(m: &Mesh) -> BTreeSet<Vec<[u64; 3]>> {
    (0..m.faces().len())
        .map(|f| {
            let mut l: Vec<[u64; 3]> = m
                .face_points(f)
                .map(|q| [q.x.to_bits(), q.y.to_bits(), q.z.to_bits()])
                .collect();
            let start = (0..l.len()).min_by_key(|&i| l[i]).unwrap();
            l.rotate_left(start);
            l
        })
        .collect()
}

/// Checks a prism over `outline` of `height`: solid, caps single faces at z = 0 and
/// z = height, quads for walls, volume = area × height.
fn check_prism(outline: &Polygon<f64>, height: f64) -> Mesh {
    let m = solids::prism(outline, height).unwrap();
    let n = outline.exterior().0.len() - 1;
    assert!(m.is_solid());
    assert_eq!((m.vertices().len(), m.faces().len()), (2 * n, n + 2));
    let caps: Vec<_> = m
        .faces()
        .iter()
        .filter(|f| f.vertices().len() == n)
        .collect();
    assert!(n == 4 || caps.len() == 2);
    let bottom = m
        .faces()
        .iter()
        .filter(|f| f.plane().normal == -Vector3::z())
        .count();
    let top = m
        .faces()
        .iter()
        .filter(|f| f.plane().normal == Vector3::z())
        .count();
    assert_eq!((bottom, top), (1, 1));
    assert!(
        m.faces()
            .iter()
            .all(|f| f.vertices().len() == 4 || f.vertices().len() == n)
    );
    let expected = outline.unsigned_area() * height;
    assert!(
        rel(m.volume(), expected) < 1e-12,
        "{} vs {expected}",
        m.volume()
    );
    m
}

#[test]
fn prism_of_non_convex_outlines() {
    let l = polygon![(x: 0.0, y: 0.0), (x: 3.0, y: 0.0), (x: 3.0, y: 1.0),
                     (x: 1.0, y: 1.0), (x: 1.0, y: 2.5), (x: 0.0, y: 2.5)];
    let m = check_prism(&l, 1.5);
    assert_eq!(m.volume(), 4.5 * 1.5);
    check_prism(&poly(&star(5)), 0.25);
    check_prism(&poly(&star(17)), 10.0);

    // Either winding gives the same solid.
    for outline in [star(7), l.exterior().coords().map(|c| (c.x, c.y)).collect()] {
        let ccw = solids::prism(&poly(&outline), 2.0).unwrap();
        let mut reversed = outline.clone();
        reversed.reverse();
        let cw = solids::prism(&poly(&reversed), 2.0).unwrap();
        assert!(cw.is_solid() && cw.volume() > 0.0);
        assert_eq!(face_loops(&ccw), face_loops(&cw));
    }
}

#[test]
fn prism_cleans_repeated_points() {
    // Repeated consecutive points and an explicit closing point are dropped; a point in the
    // middle of a straight edge is kept.
    let square = poly(&[
        (0.0, 0.0),
        (0.0, 0.0),
        (1.0, 0.0),
        (2.0, 0.0),
        (2.0, 2.0),
        (0.0, 2.0),
        (0.0, 0.0),
    ]);
    let m = solids::prism(&square, 1.0).unwrap();
    assert!(m.is_solid());
    assert_eq!((m.vertices().len(), m.faces().len()), (10, 7));
    assert_eq!(m.volume(), 4.0);
}

#[test]
fn prism_errors() {
    let square = poly(&[(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]);
    let hole = LineString::from(vec![(1.0, 1.0), (2.0, 1.0), (2.0, 2.0)]);
    let holed = Polygon::new(square.exterior().clone(), vec![hole]);
    let msg = |p: &Polygon<f64>, h: f64| solids::prism(p, h).unwrap_err().to_string();
    assert_eq!(
        msg(&holed, 1.0),
        "prism: the outline has 1 hole; a prism's outline must have none"
    );
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            msg(&square, h).starts_with("prism: height must be a finite number greater than 0")
        );
    }
    let bow_tie = poly(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)]);
    assert_eq!(
        msg(&bow_tie, 1.0),
        "prism: the outline is not simple: its edges 0 and 2 (0-based, edge k from point k to k + 1) cross, touch or overlap"
    );
    let not_simple = [
        // A vertex touching another edge.
        vec![(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (2.0, 0.0), (0.0, 4.0)],
        // Two vertices at the same place (a pinched ring).
        vec![
            (0.0, 0.0),
            (2.0, 1.0),
            (4.0, 0.0),
            (4.0, 2.0),
            (2.0, 1.0),
            (0.0, 2.0),
        ],
        // A spike folding back along an edge.
        vec![(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (4.0, 2.0), (0.0, 4.0)],
        // All points on one line.
        vec![(0.0, 0.0), (1.0, 1.0), (3.0, 3.0)],
        // Edges overlapping along a line.
        vec![
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 1.0),
            (3.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
        ],
    ];
    for ring in not_simple {
        assert!(msg(&poly(&ring), 1.0).contains("is not simple"), "{ring:?}");
    }
    assert_eq!(
        msg(&poly(&[(0.0, 0.0), (1.0, 0.0)]), 1.0),
        "prism: the outline has 2 distinct consecutive points; at least 3 are needed"
    );
    assert!(
        msg(
            &poly(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 0.0)]),
            1.0
        )
        .contains("2 distinct")
    );
    assert!(msg(&poly(&[]), 1.0).contains("0 distinct"));
    assert!(msg(&poly(&[(0.0, 0.0), (f64::NAN, 0.0), (1.0, 1.0)]), 1.0).contains("not finite"));
    assert!(msg(&poly(&[(0.0, 0.0), (1e200, 0.0), (1.0, 1.0)]), 1.0).contains("beyond 1e100"));
    let many: Vec<(f64, f64)> = (0..10_001)
        .map(|k| (k as f64 * TAU / 10_001.0).sin_cos())
        .collect();
    assert!(msg(&poly(&many), 1.0).contains("at most 10000"));
    // Degenerate heights reach the mesh validation as errors, not panics.
    // Every finite height is decided exactly: a subnormal height still makes a solid.
    assert!(solids::prism(&square, 1e-320).unwrap().is_solid());
    assert!(solids::prism(&square, 1e200).unwrap().is_solid());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random star-shaped outlines (radii at increasing angles) are simple; their prisms
    /// hold area × height.
    #[test]
    fn prism_of_random_star_shapes(
        radii in prop::collection::vec(0.1f64..10.0, 3..40),
        height in 0.01f64..100.0,
        clockwise in any::<bool>(),
    ) {
        let n = radii.len();
        let mut ring: Vec<(f64, f64)> = radii
            .iter()
            .enumerate()
            .map(|(k, r)| {
                let (s, c) = (k as f64 * TAU / n as f64).sin_cos();
                (r * c, r * s)
            })
            .collect();
        if clockwise {
            ring.reverse();
        }
        let outline = poly(&ring);
        let m = solids::prism(&outline, height).unwrap();
        prop_assert!(m.is_solid());
        prop_assert_eq!(m.faces().len(), n + 2);
        prop_assert!(rel(m.volume(), outline.unsigned_area() * height) < 1e-12);
    }
}

// ---------------------------------------------------------------------------------------
// Solids of revolution

/// Volume of the faceted UV sphere: a stack of frusta of regular n-gon pyramids.
fn uv_sphere_volume(r: f64, n: u32, rings: u32) -> f64 {
    let ngon = n as f64 / 2.0 * (TAU / n as f64).sin();
    (0..rings)
        .map(|i| {
            let t0 = i as f64 * PI / rings as f64;
            let t1 = (i + 1) as f64 * PI / rings as f64;
            let (p0, p1) = (r * t0.sin(), r * t1.sin());
            ngon * (r * t0.cos() - r * t1.cos()) / 3.0 * (p0 * p0 + p0 * p1 + p1 * p1)
        })
        .sum()
}

/// Volume of the faceted torus: n·sin(2π/n)·A·R (Pappus for the faceted revolution), with A
/// the area of the regular m-gon tube.
fn torus_volume(big: f64, small: f64, n: u32, m: u32) -> f64 {
    let tube = m as f64 / 2.0 * small * small * (TAU / m as f64).sin();
    n as f64 * (TAU / n as f64).sin() * tube * big
}

/// Volume of the faceted cylinder: a regular n-gon prism.
fn cylinder_volume(r: f64, h: f64, n: u32) -> f64 {
    n as f64 / 2.0 * r * r * (TAU / n as f64).sin() * h
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn uv_sphere_matches_closed_form(n in 3u32..64, rings in 2u32..24, r in 0.01f64..100.0) {
        let m = solids::uv_sphere(r, n, rings).unwrap();
        prop_assert!(m.is_solid());
        let (nv, nf) = ((n * (rings - 1) + 2) as usize, (n * rings) as usize);
        let polygons = m.polygons();
        prop_assert_eq!((m.vertices().len(), polygons.len()), (nv, nf));
        // Quads that rounding left not exactly planar are split into two triangle faces.
        let diagonals = m.faces().len() - nf;
        prop_assert_eq!(diagonals, m.split_polygons());
        prop_assert_eq!(m.topology().edges, (n * (2 * rings - 1)) as usize + diagonals);
        let triangles = polygons.iter().filter(|p| p.len() == 3).count();
        prop_assert_eq!(triangles, 2 * n as usize);
        prop_assert!(m.vertices().iter().all(|q| rel(q.coords.norm(), r) < 1e-14));
        let v = uv_sphere_volume(r, n, rings);
        prop_assert!(rel(m.volume(), v) < 1e-12, "{} vs {}", m.volume(), v);
        prop_assert!(v < 4.0 / 3.0 * PI * r * r * r);
    }

    #[test]
    fn torus_matches_closed_form(
        n in 3u32..64,
        sides in 3u32..24,
        big in 0.5f64..50.0,
        ratio in 0.01f64..0.99,
    ) {
        let small = big * ratio;
        let m = solids::torus(big, small, n, sides).unwrap();
        prop_assert!(m.is_solid());
        let nm = (n * sides) as usize;
        let polygons = m.polygons();
        let diagonals = m.split_polygons();
        prop_assert_eq!(m.faces().len(), nm + diagonals);
        prop_assert_eq!((m.vertices().len(), polygons.len(), m.topology().edges), (nm, nm, 2 * nm + diagonals));
        prop_assert!(polygons.iter().all(|p| p.len() == 4));
        let v = torus_volume(big, small, n, sides);
        prop_assert!(rel(m.volume(), v) < 1e-12, "{} vs {}", m.volume(), v);
    }

    #[test]
    fn cylinder_matches_closed_form(n in 3u32..64, r in 0.01f64..100.0, h in 0.01f64..100.0) {
        let m = solids::cylinder(r, h, n).unwrap();
        prop_assert!(m.is_solid());
        let n = n as usize;
        prop_assert_eq!((m.vertices().len(), m.faces().len(), m.topology().edges), (2 * n, n + 2, 3 * n));
        let caps = m.faces().iter().filter(|f| f.vertices().len() == n).count();
        prop_assert!(n == 4 || caps == 2);
        let zs: BTreeSet<u64> = m.vertices().iter().map(|q| q.z.to_bits()).collect();
        prop_assert_eq!(zs, BTreeSet::from([(-h / 2.0).to_bits(), (h / 2.0).to_bits()]));
        let v = cylinder_volume(r, h, n as u32);
        prop_assert!(rel(m.volume(), v) < 1e-12, "{} vs {}", m.volume(), v);
    }
}

#[test]
fn round_solids_at_fixed_resolutions() {
    for (n, rings) in [(3, 2), (4, 2), (8, 3), (64, 32), (100, 50)] {
        let m = solids::uv_sphere(1.0, n, rings).unwrap();
        assert!(rel(m.volume(), uv_sphere_volume(1.0, n, rings)) < 1e-12);
    }
    // The octahedron is the UV sphere with 4 segments and 2 rings.
    let o = solids::uv_sphere(1.0, 4, 2).unwrap();
    assert!(rel(o.volume(), 4.0 / 3.0) < 1e-15);
    let t = solids::torus(3.0, 1.0, 4, 4).unwrap();
    assert!(rel(t.volume(), torus_volume(3.0, 1.0, 4, 4)) < 1e-15);
    assert!(rel(t.volume(), 4.0 * 2.0 * 3.0) < 1e-12);
    // Fine resolutions approach the smooth volumes.
    let fine = solids::torus(2.0, 0.5, 100, 50).unwrap();
    assert!(rel(fine.volume(), 2.0 * PI * PI * 2.0 * 0.25) < 5e-3);
    let c = solids::cylinder(1.0, 1.0, 256).unwrap();
    assert!(rel(c.volume(), PI) < 2e-4);
}

#[test]
fn round_solid_errors() {
    let msg = |r: Result<Mesh, SolidError>| r.unwrap_err().to_string();
    assert_eq!(
        msg(solids::uv_sphere(1.0, 2, 8)),
        "sphere: segments must be at least 3, got 2"
    );
    assert_eq!(
        msg(solids::uv_sphere(1.0, 8, 1)),
        "sphere: rings must be at least 2, got 1"
    );
    assert_eq!(
        msg(solids::uv_sphere(0.0, 8, 8)),
        "sphere: radius must be a finite number greater than 0, got 0"
    );
    assert_eq!(
        msg(solids::uv_sphere(f64::NAN, 8, 8)),
        "sphere: radius must be a finite number greater than 0, got NaN"
    );
    assert_eq!(
        msg(solids::uv_sphere(-1e300, 8, 8)),
        "sphere: radius must be a finite number greater than 0, got -1e300"
    );
    assert_eq!(
        msg(solids::uv_sphere(1.0, u32::MAX, u32::MAX)),
        "sphere: segments × rings must be at most 1000000, got 18446744065119617025"
    );
    assert_eq!(
        msg(solids::torus(1.0, 1.0, 8, 8)),
        "torus: minor radius must be less than the major radius 1, got 1"
    );
    assert_eq!(
        msg(solids::torus(1.0, 0.5, 2, 8)),
        "torus: segments must be at least 3, got 2"
    );
    assert_eq!(
        msg(solids::torus(1.0, 0.5, 8, 0)),
        "torus: sides must be at least 3, got 0"
    );
    assert_eq!(
        msg(solids::torus(f64::INFINITY, 0.5, 8, 8)),
        "torus: major radius must be a finite number greater than 0, got inf"
    );
    assert_eq!(
        msg(solids::torus(1.0, -0.5, 8, 8)),
        "torus: minor radius must be a finite number greater than 0, got -0.5"
    );
    assert_eq!(
        msg(solids::torus(2.0, 1.0, 2000, 501)),
        "torus: segments × sides must be at most 1000000, got 1002000"
    );
    assert_eq!(
        msg(solids::cylinder(1.0, 1.0, 0)),
        "cylinder: segments must be at least 3, got 0"
    );
    assert_eq!(
        msg(solids::cylinder(1.0, 1.0, u32::MAX)),
        "cylinder: segments must be at most 10000, got 4294967295"
    );
    assert_eq!(
        msg(solids::cylinder(-1.0, 1.0, 8)),
        "cylinder: radius must be a finite number greater than 0, got -1"
    );
    assert!(solids::cylinder(1.0, 1e-5, 8).is_ok());
    // Extreme sizes give meshes (vertices that round together merge, the faces that then
    // have zero area are dropped) or mesh errors, not panics.
    for m in [
        solids::uv_sphere(1e-310, 8, 8),
        solids::uv_sphere(1e200, 8, 8),
        solids::cylinder(1.0, 1e-320, 8),
    ] {
        match m {
            Ok(m) => assert!(!m.faces().is_empty()),
            Err(SolidError::Mesh(_)) => {}
            Err(e) => panic!("{e}"),
        }
    }
    for minor in [1.0 - 1e-16, 1e-300] {
        match solids::torus(1.0, minor, 8, 8) {
            Ok(m) => assert!(m.is_solid()),
            Err(SolidError::Mesh(_)) => {}
            Err(e) => panic!("{e}"),
        }
    }
}
