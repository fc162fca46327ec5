//! VISP and ray shooting: hand-made cases with answers worked out by hand, and random scenes
//! against brute force over every triangle (no bounds) and against an independent exact
//! reference (a floating-point filter with an exact fallback: 128-bit fixed point for lattice
//! inputs, `BigRational` otherwise; the symbolic perturbation evaluated as the sign of a
//! polynomial in ε).

use kepler::geometry::ray::Ray;
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::queries::Stage;
use kepler::queries::visp::{Hit, Visibility, VisibilityIndex, hides, visp};
use kepler::scene::{ObjectId, Scene};
use kepler::solids;
use kepler::views::{Eye, View};
use nalgebra::{Matrix4, Rotation3, Unit};
use num_traits::{Signed, Zero};
use std::cmp::Ordering;

use crate::common::{Q, SplitMix64, q, qcross, qdot, qsign, qsub, qv};

use Visibility::{Hidden, Visible};

// ---------------------------------------------------------------------------------------------
// Helpers.

fn pt(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(x, y, z)
}

/// A scene holding one mesh at the top level.
fn single(mesh: Mesh) -> (Scene, ObjectId) {
    let mut s = Scene::new();
    let id = s.add_mesh(None, "object", mesh).unwrap();
    (s, id)
}

fn unit_cube() -> (Scene, ObjectId) {
    single(solids::cube(2.0).unwrap())
}

/// Every triangle of every mesh of the scene, with its object and index.
fn all_triangles(scene: &Scene) -> Vec<(ObjectId, usize, [Point3; 3])> {
    let mut out = Vec::new();
    for (id, _) in scene.walk() {
        if let Some(m) = scene[id].mesh() {
            for t in 0..m.triangles().len() {
                out.push((id, t, m.triangle(t)));
            }
        }
    }
    out
}

/// Brute force with the library's exact triangle test: hidden iff some triangle hides `p`.
fn brute_force(eye: &Eye, triangles: &[(ObjectId, usize, [Point3; 3])], p: &Point3) -> Visibility {
    if triangles.iter().any(|(_, _, t)| hides(eye, t, p)) {
        Hidden
    } else {
        Visible
    }
}

/// VISP with no preprocessing over every top-level object.
fn visp_roots(scene: &Scene, view: &View, p: &Point3) -> Visibility {
    let hidden = scene
        .roots()
        .iter()
        .any(|&id| visp(scene, id, view, p).0 == Hidden);
    if hidden { Hidden } else { Visible }
}

/// Checks a hand-made expectation through every path: the index, VISP without
/// preprocessing, brute force with `hides`, and the independent exact reference.
fn expect(scene: &Scene, view: &View, p: Point3, expected: Visibility, why: &str) {
    let index = VisibilityIndex::whole_scene(scene, view.clone());
    let triangles = all_triangles(scene);
    let what = format!("{p:?} from {:?}: {why}", view.eye());
    assert_eq!(index.visp(&p).0, expected, "index, {what}");
    assert_eq!(visp_roots(scene, view, &p), expected, "visp, {what}");
    assert_eq!(
        brute_force(view.eye(), &triangles, &p),
        expected,
        "brute force, {what}"
    );
    let reference = Reference::new(view.eye(), &triangles);
    assert_eq!(reference.visibility(&p).0, expected, "reference, {what}");
}

fn standard() -> View {
    View::standard()
}

/// Looking along (-1, -1, -1): the eye is at infinity towards (1, 1, 1).
fn diagonal() -> View {
    View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap()
}

/// The eye at (0, 0, 10) looking at the origin.
fn above() -> View {
    View::perspective(pt(0.0, 0.0, 10.0), Point3::origin(), Vector3::y(), 40.0).unwrap()
}

// ---------------------------------------------------------------------------------------------
// An independent exact reference.

fn arr(p: &Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

const ZERO: [f64; 3] = [0.0; 3];

/// The exact sign of det[x₀ - y₀, x₁ - y₁, x₂ - y₂] (rows): a floating-point value with a
/// generous error bound decides most calls, exact rationals the rest.
fn det_sign(rows: [([f64; 3], [f64; 3]); 3]) -> Ordering {
    let r = rows.map(|(x, y)| [x[0] - y[0], x[1] - y[1], x[2] - y[2]]);
    let terms = [
        r[0][0] * r[1][1] * r[2][2],
        -r[0][0] * r[1][2] * r[2][1],
        r[0][1] * r[1][2] * r[2][0],
        -r[0][1] * r[1][0] * r[2][2],
        r[0][2] * r[1][0] * r[2][1],
        -r[0][2] * r[1][1] * r[2][0],
    ];
    let value: f64 = terms.iter().sum();
    let permanent: f64 = terms.iter().map(|t| t.abs()).sum();
    // Each difference is off by at most half an ulp, each product by a few more, the sum by
    // five: about 10·2⁻⁵³ of the permanent in all. 1e-12 is a wide margin.
    if value.abs() > 1e-12 * permanent {
        return value.partial_cmp(&0.0).unwrap();
    }
    if let Some(r) = fixed_rows(&rows) {
        let c = cross_i(&r[1], &r[2]);
        return (r[0][0] * c[0] + r[0][1] * c[1] + r[0][2] * c[2]).cmp(&0);
    }
    let r = rows.map(|(x, y)| qsub(&qv(x), &qv(y)));
    qsign(&qdot(&r[0], &qcross(&r[1], &r[2])))
}

/// `x` as an integer multiple of 2⁻⁸ below 2³⁶ in magnitude, if it is one: lattice inputs
/// take this exact shortcut (products of three differences stay below 2¹¹⁵ in an i128).
fn fixed(x: f64) -> Option<i128> {
    let y = x * 256.0;
    (y.fract() == 0.0 && y.abs() < (1u64 << 36) as f64).then_some(y as i128)
}

fn fixed_rows(rows: &[([f64; 3], [f64; 3]); 3]) -> Option<[[i128; 3]; 3]> {
    let mut out = [[0i128; 3]; 3];
    for (i, (x, y)) in rows.iter().enumerate() {
        for k in 0..3 {
            out[i][k] = fixed(x[k])? - fixed(y[k])?;
        }
    }
    Some(out)
}

fn cross_i(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The reference eye, as plain coordinates.
#[derive(Debug, Clone, Copy)]
enum RefEye {
    Point([f64; 3]),
    Infinity([f64; 3]),
}

impl RefEye {
    fn of(eye: &Eye) -> RefEye {
        match eye {
            Eye::Point(e) => RefEye::Point(arr(e)),
            Eye::Infinity(u) => RefEye::Infinity([u.x, u.y, u.z]),
        }
    }

    /// orient3d(a, b, c, eye): det[a - e, b - e, c - e], or -det[a - c, b - c, u] at infinity.
    fn side(self, t: &[[f64; 3]; 3]) -> Ordering {
        let [a, b, c] = *t;
        match self {
            RefEye::Point(e) => det_sign([(a, e), (b, e), (c, e)]),
            RefEye::Infinity(u) => det_sign([(a, c), (b, c), (u, ZERO)]).reverse(),
        }
    }

    /// orient3d(p', a, b, eye) for p' = p + (ε, ε², ε³): the value is linear in p', so its
    /// sign is that of the first nonzero of (value at p, gx, gy, gz) with g its gradient in p.
    /// Returns the sign and whether the perturbation was needed.
    fn sight(self, p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> (Ordering, bool) {
        let exact = match self {
            // det[p - e, a - e, b - e] = (p - e)·((a - e) × (b - e)).
            RefEye::Point(e) => det_sign([(p, e), (a, e), (b, e)]),
            // -det[p - b, a - b, u] = -(p - b)·((a - b) × u).
            RefEye::Infinity(u) => det_sign([(p, b), (a, b), (u, ZERO)]).reverse(),
        };
        if exact != Ordering::Equal {
            return (exact, false);
        }
        // The gradient's signs: exactly in fixed point for lattice inputs, else rationals.
        let rows = match self {
            RefEye::Point(e) => [(a, e), (b, e)],
            RefEye::Infinity(u) => [(a, b), (u, ZERO)],
        };
        let fixed = fixed_rows(&[rows[0], rows[1], (ZERO, ZERO)]);
        if let Some(r) = fixed {
            let g = cross_i(&r[0], &r[1]);
            let flip = matches!(self, RefEye::Infinity(_));
            let s = g
                .iter()
                .map(|x| if flip { 0.cmp(x) } else { x.cmp(&0) })
                .find(|s| *s != Ordering::Equal)
                .unwrap_or(Ordering::Equal);
            return (s, true);
        }
        let gradient = match self {
            RefEye::Point(e) => {
                let e = qv(e);
                qcross(&qsub(&qv(a), &e), &qsub(&qv(b), &e))
            }
            RefEye::Infinity(u) => qcross(&qsub(&qv(a), &qv(b)), &qv(u)).map(|x| -x),
        };
        let s = gradient
            .iter()
            .map(qsign)
            .find(|s| *s != Ordering::Equal)
            .unwrap_or(Ordering::Equal);
        (s, true)
    }
}

/// The semantics of VISP written out from the module documentation: a triangle hides P iff
/// the eye is not in its plane, P is strictly on the other side of it, and the perturbed line
/// of sight passes through it (the three orientations with the edges agree).
struct Reference {
    eye: RefEye,
    /// Each triangle's corners and the side of its plane the eye is on.
    triangles: Vec<([[f64; 3]; 3], Ordering)>,
}

impl Reference {
    fn new(eye: &Eye, triangles: &[(ObjectId, usize, [Point3; 3])]) -> Reference {
        let eye = RefEye::of(eye);
        let triangles = triangles
            .iter()
            .map(|(_, _, t)| {
                let t = t.map(|p| arr(&p));
                (t, eye.side(&t))
            })
            .collect();
        Reference { eye, triangles }
    }

    /// The answer, and whether it needed the perturbation (some triangle with P behind it has
    /// a line of sight exactly through an edge or a vertex).
    fn visibility(&self, p: &Point3) -> (Visibility, bool) {
        let p = arr(p);
        let mut degenerate = false;
        for (t, eye_side) in &self.triangles {
            let [a, b, c] = *t;
            if *eye_side == Ordering::Equal
                || det_sign([(a, p), (b, p), (c, p)]) != eye_side.reverse()
            {
                continue;
            }
            let signs = [
                self.eye.sight(p, a, b),
                self.eye.sight(p, b, c),
                self.eye.sight(p, c, a),
            ];
            let unperturbed: Vec<Ordering> = signs
                .iter()
                .filter(|(_, perturbed)| !perturbed)
                .map(|(s, _)| *s)
                .collect();
            let mixed =
                unperturbed.contains(&Ordering::Less) && unperturbed.contains(&Ordering::Greater);
            if !mixed && unperturbed.len() < 3 {
                degenerate = true;
            }
            if signs[0].0 == signs[1].0 && signs[1].0 == signs[2].0 {
                assert_ne!(signs[0].0, Ordering::Equal);
                return (Hidden, degenerate);
            }
        }
        (Visible, degenerate)
    }
}

// ---------------------------------------------------------------------------------------------
// Hand-made cases: the unit cube (corners ±1) in the standard view.

/// The standard view looks down from (0, 0, +∞). Faces x = ±1 and y = ±1 are edge-on, so only
/// the top (z = 1, in front) and the bottom (z = -1, behind) can hide anything. The
/// perturbation moves P by (+ε, +ε², +ε³): a line of sight exactly through the edge x = 1 of
/// the top face passes outside the cube, one through the edge x = -1 passes inside.
#[test]
fn cube_in_the_standard_view() {
    let (s, _) = unit_cube();
    let v = standard();
    let cases = [
        (
            pt(0.5, 0.5, -3.0),
            Hidden,
            "below the cube: the bottom and top faces are in the way",
        ),
        (
            pt(0.5, 0.5, 1.0),
            Visible,
            "on the top face, the frontmost face containing it",
        ),
        (pt(0.5, 0.5, 3.0), Visible, "above the cube"),
        (
            pt(0.2, -0.3, 0.4),
            Hidden,
            "inside the cube, under the top face",
        ),
        (
            pt(0.5, 0.5, -1.0),
            Hidden,
            "on the bottom face: the top face is above it",
        ),
        (
            pt(3.0, 0.5, -3.0),
            Visible,
            "beside and below: the line of sight misses",
        ),
        // On the side face x = 1: that face is edge-on, and the line of sight x = 1 + ε
        // passes just outside the top face's edge.
        (pt(1.0, 0.3, 0.0), Visible, "on the silhouette side x = 1"),
        // On the side face x = -1: the line of sight x = -1 + ε passes just inside the top
        // face, which hides the point (as it hides every point just inside the cube there).
        (
            pt(-1.0, 0.3, 0.0),
            Hidden,
            "on the side x = -1, inside by +ε",
        ),
        // y is moved by +ε²: the side y = 1 is outside, y = -1 inside.
        (pt(0.3, 1.0, 0.0), Visible, "on the side y = 1"),
        (pt(0.3, -1.0, 0.0), Hidden, "on the side y = -1"),
        // On the silhouette edges of the top face: on the top plane, so not behind it.
        (pt(1.0, 0.3, 1.0), Visible, "on the top edge x = 1"),
        (pt(-1.0, 0.3, 1.0), Visible, "on the top edge x = -1"),
        (pt(1.0, 1.0, 1.0), Visible, "a top corner"),
        (pt(-1.0, -1.0, 1.0), Visible, "the other top corner"),
        // Below the cube, exactly under the edges of the top and bottom faces.
        (
            pt(1.0, 0.3, -3.0),
            Visible,
            "under the edge x = 1: beside the cube by +ε",
        ),
        (
            pt(-1.0, 0.3, -3.0),
            Hidden,
            "under the edge x = -1: inside by +ε",
        ),
        (pt(0.3, 1.0, -3.0), Visible, "under the edge y = 1"),
        (pt(0.3, -1.0, -3.0), Hidden, "under the edge y = -1"),
        // Under the diagonal y = x shared by the two triangles of the top (and bottom) face:
        // the perturbed line of sight passes through exactly one of them.
        (
            pt(0.3, 0.3, -3.0),
            Hidden,
            "under the diagonal of the top face",
        ),
        (
            pt(0.0, 0.0, -3.0),
            Hidden,
            "under the centre, on the diagonal",
        ),
        (
            pt(0.0, 0.0, 0.0),
            Hidden,
            "the centre of the cube, under the diagonal",
        ),
        // Under the corners: (x + ε, y + ε²) is inside only at (-1, -1).
        (
            pt(-1.0, -1.0, -3.0),
            Hidden,
            "under the corner (-1, -1): inside",
        ),
        (
            pt(1.0, 1.0, -3.0),
            Visible,
            "under the corner (1, 1): x beyond",
        ),
        (
            pt(1.0, -1.0, -3.0),
            Visible,
            "under the corner (1, -1): x beyond",
        ),
        (
            pt(-1.0, 1.0, -3.0),
            Visible,
            "under the corner (-1, 1): y beyond",
        ),
        (
            pt(-1.0, -1.0, -1.0),
            Hidden,
            "the bottom corner (-1, -1, -1)",
        ),
        (pt(1.0, 1.0, -1.0), Visible, "the bottom corner (1, 1, -1)"),
    ];
    for (p, expected, why) in cases {
        expect(&s, &v, p, expected, why);
    }
}

/// Under the diagonal of a face the line of sight passes through exactly one of its two
/// triangles (the perturbation is antisymmetric in the shared edge), so the point is counted
/// hidden once per face, never zero or twice.
#[test]
fn a_line_of_sight_through_a_diagonal_meets_one_triangle() {
    let cube = solids::cube(2.0).unwrap();
    let eye = Eye::Infinity(Vector3::z());
    let faces = |p: &Point3, normal_z: f64| {
        cube.faces()
            .iter()
            .filter(|f| f.plane().normal.z == normal_z)
            .flat_map(|f| f.triangle_range())
            .filter(|&t| hides(&eye, &cube.triangle(t), p))
            .count()
    };
    for p in [pt(0.3, 0.3, -3.0), pt(0.0, 0.0, -3.0), pt(-0.7, -0.7, -5.0)] {
        assert_eq!(faces(&p, 1.0), 1, "top, {p:?}");
        assert_eq!(faces(&p, -1.0), 1, "bottom, {p:?}");
    }
}

/// A cube whose top is a fan of four triangles around (0, 0, 1), and a lattice octahedron:
/// lines of sight exactly through a vertex shared by four front (or back) faces meet exactly
/// one of them.
#[test]
fn a_line_of_sight_through_a_vertex_meets_one_face() {
    let fan = fan_top_cube();
    let eye = Eye::Infinity(Vector3::z());
    let top: Vec<usize> = (0..fan.faces().len())
        .filter(|&f| fan.faces()[f].plane().normal.z > 0.5)
        .collect();
    assert_eq!(top.len(), 4);
    let count = |mesh: &Mesh, faces: &[usize], p: &Point3| {
        faces
            .iter()
            .filter(|&&f| {
                mesh.faces()[f]
                    .triangle_range()
                    .any(|t| hides(&eye, &mesh.triangle(t), p))
            })
            .count()
    };
    for p in [pt(0.0, 0.0, -3.0), pt(0.0, 0.0, 0.0), pt(0.0, 0.0, 0.5)] {
        assert_eq!(count(&fan, &top, &p), 1, "{p:?}");
        let (s, _) = single(fan.clone());
        expect(&s, &standard(), p, Hidden, "under the fan's centre");
    }
    // The octahedron's apexes (0, 0, ±1): four front faces meet at the top, four back faces
    // at the bottom; below both, the perturbed line of sight passes through one of each.
    let octa = lattice_octahedron(1.0, [0.0; 3]);
    let upper: Vec<usize> = (0..8)
        .filter(|&f| octa.faces()[f].plane().normal.z > 0.0)
        .collect();
    let lower: Vec<usize> = (0..8)
        .filter(|&f| octa.faces()[f].plane().normal.z < 0.0)
        .collect();
    for p in [pt(0.0, 0.0, -5.0), pt(0.0, 0.0, -1.0), pt(0.0, 0.0, 0.0)] {
        assert_eq!(count(&octa, &upper, &p), 1, "{p:?}");
        let behind_lower = if p.z < -1.0 { 1 } else { 0 };
        assert_eq!(count(&octa, &lower, &p), behind_lower, "{p:?}");
        let (s, _) = single(octa.clone());
        expect(&s, &standard(), p, Hidden, "under the octahedron's apex");
    }
    let (s, _) = single(octa);
    expect(&s, &standard(), pt(0.0, 0.0, 1.0), Visible, "the top apex");
    // The octahedron's outline from above is the diamond |x| + |y| <= 1. Under the vertex
    // (1, 0, 0) the line of sight (1 + ε, ε²) passes beside; under (-1, 0, 0) the line
    // (-1 + ε, ε²) passes through (|x| + |y| = 1 - ε + ε²).
    expect(
        &s,
        &standard(),
        pt(1.0, 0.0, -4.0),
        Visible,
        "under (1, 0, 0)",
    );
    expect(
        &s,
        &standard(),
        pt(-1.0, 0.0, -4.0),
        Hidden,
        "under (-1, 0, 0)",
    );
    expect(
        &s,
        &standard(),
        pt(0.0, 1.0, -4.0),
        Visible,
        "under (0, 1, 0)",
    );
    // (ε, -1 + ε²): |x| + |y| = 1 + ε - ε² > 1, outside the diamond too.
    expect(
        &s,
        &standard(),
        pt(0.0, -1.0, -4.0),
        Visible,
        "under (0, -1, 0)",
    );
}

/// The unit cube seen along (-1, -1, -1). Front faces (eye outside their plane): x = 1, y = 1,
/// z = 1; back faces: x = -1, y = -1, z = -1; none is edge-on. The silhouette is the hexagon
/// of the six edges between a front and a back face, through the corners that have both a
/// coordinate 1 and a coordinate -1.
#[test]
fn cube_seen_along_a_diagonal() {
    let (s, _) = unit_cube();
    let v = diagonal();
    let cases = [
        (pt(1.0, 1.0, 1.0), Visible, "the front corner"),
        (
            pt(-1.0, -1.0, -1.0),
            Hidden,
            "the back corner: behind the front faces",
        ),
        (pt(0.0, 0.0, 0.0), Hidden, "the centre"),
        (pt(3.0, 3.0, 3.0), Visible, "in front of the cube"),
        (pt(-3.0, -3.0, -3.0), Hidden, "behind the cube"),
        // On front faces: the line of sight leaves the convex cube at once.
        (pt(1.0, 0.25, -0.5), Visible, "on the front face x = 1"),
        (pt(0.5, 1.0, -0.75), Visible, "on the front face y = 1"),
        (pt(-0.5, 0.5, 1.0), Visible, "on the front face z = 1"),
        (
            pt(1.0, 1.0, 0.25),
            Visible,
            "on the edge between two front faces",
        ),
        // On back faces: the line of sight crosses the cube and leaves by a front face.
        (pt(-1.0, 0.25, -0.5), Hidden, "on the back face x = -1"),
        (pt(0.5, -1.0, 0.75), Hidden, "on the back face y = -1"),
        (pt(0.5, -0.5, -1.0), Hidden, "on the back face z = -1"),
        (
            pt(-1.0, 0.25, 0.875),
            Hidden,
            "on the back face x = -1 near the silhouette",
        ),
        (
            pt(-1.0, -1.0, 0.25),
            Hidden,
            "on the edge between two back faces",
        ),
        // On the silhouette: each such point lies on a front face's plane, so that face does
        // not hide it, and the line of sight along (1, 1, 1) misses the other front faces.
        (
            pt(1.0, -1.0, 0.25),
            Visible,
            "on the silhouette edge x = 1, y = -1",
        ),
        (
            pt(-1.0, 1.0, 0.25),
            Visible,
            "on the silhouette edge x = -1, y = 1",
        ),
        (
            pt(0.25, -1.0, 1.0),
            Visible,
            "on the silhouette edge z = 1, y = -1",
        ),
        (pt(1.0, -1.0, -1.0), Visible, "a silhouette corner"),
        (pt(1.0, 1.0, -1.0), Visible, "a silhouette corner"),
        (pt(-1.0, 1.0, -1.0), Visible, "a silhouette corner"),
        (pt(-1.0, 1.0, 1.0), Visible, "a silhouette corner"),
        (pt(-1.0, -1.0, 1.0), Visible, "a silhouette corner"),
        (pt(1.0, -1.0, 1.0), Visible, "a silhouette corner"),
        // Behind the silhouette edge x = 1, y = -1: P + 2(1, 1, 1) = (1, -1, 0.25). With
        // P' = P + (ε, ε², ε³) the line reaches x = 1 at y = -1 - ε + ε² < -1, and y = -1 at
        // x = 1 + ε - ε² > 1: it passes beside the cube.
        (
            pt(-1.0, -3.0, -1.75),
            Visible,
            "behind the silhouette edge x = 1, y = -1",
        ),
        // Behind the edge x = -1, y = 1: P + 2(1, 1, 1) = (-1, 1, 0.25). The perturbed line
        // reaches y = 1 at x = -1 + ε - ε² > -1: through the front face y = 1.
        (
            pt(-3.0, -1.0, -1.75),
            Hidden,
            "behind the silhouette edge x = -1, y = 1",
        ),
    ];
    for (p, expected, why) in cases {
        expect(&s, &v, p, expected, why);
    }
}

/// The unit cube from the eye (0, 0, 10). The top face is in front; the four sides are back
/// faces (the eye is inside their planes); the silhouette is the top face's boundary.
#[test]
fn cube_in_perspective() {
    let (s, _) = unit_cube();
    let v = above();
    let cases = [
        (
            pt(0.5, 0.5, -3.0),
            Hidden,
            "below the cube: the sight line crosses z = -1 at 0.42",
        ),
        (pt(0.5, 0.5, 1.0), Visible, "on the top face"),
        (pt(0.0, 0.0, 0.0), Hidden, "the centre"),
        (pt(1.0, 1.0, 1.0), Visible, "a top corner"),
        (
            pt(1.0, 0.25, 1.0),
            Visible,
            "on the top edge x = 1, the silhouette",
        ),
        // A side face is a back face here: the sight line from (1, 0.25, 0) to the eye
        // crosses z = 1 at (0.9, 0.225), inside the top face.
        (pt(1.0, 0.25, 0.0), Hidden, "on the side face x = 1"),
        (
            pt(1.0, 1.0, -1.0),
            Hidden,
            "a bottom corner: seen through the top at (9/11, 9/11)",
        ),
        (pt(0.0, 0.0, 5.0), Visible, "between the eye and the cube"),
        (pt(0.0, 0.0, 9.999), Visible, "just in front of the eye"),
        // Behind the eye: the segment to the eye does not reach the cube (the line beyond
        // the eye does).
        (pt(0.0, 0.0, 20.0), Visible, "behind the eye"),
        (pt(0.5, 0.5, 15.0), Visible, "behind the eye"),
        (pt(3.0, 0.0, 0.0), Visible, "beside the cube"),
        // The sight line from (2, 0.5, -8) to the eye passes exactly through (1, 0.25, 1) on
        // the top edge x = 1. With P' = P + (ε, ε², ε³) it crosses z = 1 at x ≈ 1 + ε/2 and
        // x = 1 at z ≈ 1 + 4.5ε: beside the cube.
        (
            pt(2.0, 0.5, -8.0),
            Visible,
            "behind the silhouette edge x = 1",
        ),
        // Mirrored, it crosses z = 1 at x ≈ -1 + ε/2: through the top face.
        (
            pt(-2.0, 0.5, -8.0),
            Hidden,
            "behind the silhouette edge x = -1",
        ),
    ];
    for (p, expected, why) in cases {
        expect(&s, &v, p, expected, why);
    }
}

/// With the eye inside the cube every face is a back face: the eye is inside all their
/// planes, so a point outside is behind some face its line of sight crosses.
#[test]
fn eye_inside_a_cube_sees_nothing_outside() {
    let (s, _) = unit_cube();
    let v = View::perspective(
        pt(0.25, 0.125, 0.375),
        pt(0.0, 0.0, -1.0),
        Vector3::y(),
        60.0,
    )
    .unwrap();
    for p in [
        pt(5.0, 0.0, 0.0),
        pt(0.0, 0.0, 5.0),
        pt(0.25, 0.125, -5.0),
        pt(-3.0, -4.0, 2.0),
        pt(1.0, 1.0, 3.0),
    ] {
        expect(&s, &v, p, Hidden, "outside, the eye inside the cube");
    }
}

/// With the eye inside the cube a point also inside it is not behind any face (both are
/// strictly inside every face's plane), and a point on a face is on that face's plane and
/// inside every other one: by the face semantics both are VISIBLE, as brute force and the
/// reference say. The INBOX shortcut (a line of sight through the open INBOX is HIDDEN) must
/// not change the answer, but it does: the segment from such a point to the eye runs through
/// the open INBOX (the eye is inside it), so `visp` and `VisibilityIndex::visp` answer HIDDEN
/// at Stage::Inbox.
#[test]
fn eye_inside_a_cube_sees_points_inside_and_on_it() {
    let (s, c) = unit_cube();
    let v = View::perspective(
        pt(0.25, 0.125, 0.375),
        pt(0.0, 0.0, -1.0),
        Vector3::y(),
        60.0,
    )
    .unwrap();
    let triangles = all_triangles(&s);
    for p in [pt(0.5, -0.5, -0.5), pt(-0.75, 0.5, 0.25), pt(0.0, 0.0, 0.0)] {
        assert_eq!(brute_force(v.eye(), &triangles, &p), Visible);
        expect(&s, &v, p, Visible, "inside, with the eye inside too");
    }
    for p in [pt(1.0, 0.5, 0.5), pt(-0.5, -1.0, 0.25), pt(1.0, 1.0, 1.0)] {
        assert_eq!(brute_force(v.eye(), &triangles, &p), Visible);
        expect(
            &s,
            &v,
            p,
            Visible,
            "on the boundary, the eye inside the cube",
        );
    }
    assert_eq!(
        visp(&s, c, &v, &pt(0.5, -0.5, -0.5)),
        (Visible, Stage::Faces)
    );
}

/// The same bug with the eye inside the solid but outside its INBOX: the octahedron
/// |x| + |y| + |z| <= 3 and the eye (0, 0, 2.5) inside it, above its INBOX. A point inside,
/// below the INBOX, is not separated from the eye by any face plane (both are strictly inside
/// all of them), so it is VISIBLE; its line of sight crosses the INBOX. And with the eye on a
/// face of the cube (in that face's plane, inside every other one), a point inside the cube is
/// VISIBLE for the same reason, while the open segment to the eye runs through the INBOX.
#[test]
fn eye_inside_an_object_but_outside_its_inbox() {
    let (s, o) = single(lattice_octahedron(3.0, [0.0; 3]));
    let inbox = s.inbox(o).unwrap().aabb;
    let eye = pt(0.0, 0.0, 2.5);
    assert!(eye.z > inbox.max[2], "{inbox:?}");
    let v = View::perspective(eye, Point3::origin(), Vector3::y(), 60.0).unwrap();
    let p = pt(0.0, 0.25, -2.5);
    assert!(p.z < inbox.min[2], "{inbox:?}");
    assert_eq!(brute_force(v.eye(), &all_triangles(&s), &p), Visible);
    expect(&s, &v, p, Visible, "inside, with the eye inside the solid");
    assert_eq!(visp(&s, o, &v, &p), (Visible, Stage::Faces));

    let (s, c) = unit_cube();
    let v = View::perspective(pt(0.25, 0.125, 1.0), Point3::origin(), Vector3::y(), 60.0).unwrap();
    let p = pt(-0.5, 0.5, -0.5);
    assert_eq!(brute_force(v.eye(), &all_triangles(&s), &p), Visible);
    expect(&s, &v, p, Visible, "inside, with the eye on the top face");
    assert_eq!(visp(&s, c, &v, &p), (Visible, Stage::Faces));
}

/// Stages: the CBOX decides lines of sight that miss the object, the INBOX those through its
/// inside, the faces the rest; and the counters of a batch add up.
#[test]
fn stages_and_counters() {
    let (s, c) = unit_cube();
    let v = standard();
    assert_eq!(
        visp(&s, c, &v, &pt(10.0, 10.0, 10.0)),
        (Visible, Stage::Cbox)
    );
    assert_eq!(visp(&s, c, &v, &pt(3.0, 0.0, -5.0)), (Visible, Stage::Cbox));
    assert_eq!(visp(&s, c, &v, &pt(0.5, 0.5, -3.0)), (Hidden, Stage::Inbox));
    assert_eq!(visp(&s, c, &v, &pt(0.5, 0.5, 1.0)), (Visible, Stage::Faces));
    // Grazing the INBOX's boundary does not cross its open interior: the faces decide.
    assert_eq!(
        visp(&s, c, &v, &pt(-1.0, 0.3, -3.0)),
        (Hidden, Stage::Faces)
    );
    assert_eq!(
        visp(&s, c, &v, &pt(1.0, 0.3, -3.0)),
        (Visible, Stage::Faces)
    );
    let index = VisibilityIndex::whole_scene(&s, v.clone());
    assert_eq!(index.visp(&pt(10.0, 10.0, 10.0)), (Visible, Stage::Cbox));
    assert_eq!(index.visp(&pt(0.5, 0.5, -3.0)), (Hidden, Stage::Inbox));
    let p = diagonal();
    assert_eq!(
        visp(&s, c, &p, &pt(-3.0, -3.0, -3.0)),
        (Hidden, Stage::Inbox)
    );
    assert_eq!(visp(&s, c, &above(), &pt(0.0, 0.0, 20.0)).0, Visible);

    // A batch over a scene with a group: answers in order, counters summing to the count.
    let mut scene = Scene::new();
    let g = scene.add_group(None, "g").unwrap();
    scene
        .add_mesh(Some(g), "a", solids::cube(2.0).unwrap())
        .unwrap();
    let moved = solids::cube(1.0)
        .unwrap()
        .transformed(&Matrix4::new_translation(&Vector3::new(4.0, 0.0, 0.0)))
        .unwrap();
    scene.add_mesh(Some(g), "b", moved).unwrap();
    let mut points: Vec<Point3> = (0..200)
        .map(|i| {
            let f = f64::from(i);
            pt(
                (f * 0.37) % 7.0 - 2.0,
                (f * 0.61) % 3.0 - 1.5,
                (f * 0.23) % 6.0 - 3.0,
            )
        })
        .collect();
    // Points the faces decide: on the top faces and exactly under their edges.
    points.extend([
        pt(0.5, 0.5, 1.0),
        pt(4.25, 0.25, 0.5),
        pt(-1.0, 0.3, -3.0),
        pt(1.0, 0.3, -3.0),
        pt(3.5, 0.0, -3.0),
    ]);
    let index = VisibilityIndex::whole_scene(&scene, v.clone());
    let (answers, counters) = index.visp_all(&points);
    assert_eq!(counters.total(), points.len() as u64);
    assert!(
        counters.inbox > 0 && counters.cbox > 0 && counters.faces > 0,
        "{counters:?}"
    );
    let triangles = all_triangles(&scene);
    let mut stages = kepler::queries::Counters::default();
    for (p, a) in points.iter().zip(&answers) {
        let (single, stage) = index.visp(p);
        stages.record(stage);
        assert_eq!(*a, single, "{p:?}");
        assert_eq!(*a, brute_force(v.eye(), &triangles, p), "{p:?}");
        assert_eq!(visp(&scene, g, &v, p).0, *a, "{p:?}");
    }
    assert_eq!(stages, counters);
}

// ---------------------------------------------------------------------------------------------
// Meshes with exact (lattice) coordinates.

/// The cube (corners ±1) with its top as four triangles around (0, 0, 1).
fn fan_top_cube() -> Mesh {
    // Corner k has x = ±1 by bit 0, y by bit 1, z by bit 2; vertex 8 is the top's centre.
    let mut v: Vec<Point3> = (0..8)
        .map(|k| {
            let s = |bit: u32| if k & (1 << bit) != 0 { 1.0 } else { -1.0 };
            pt(s(0), s(1), s(2))
        })
        .collect();
    v.push(pt(0.0, 0.0, 1.0));
    let faces = vec![
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 2, 3, 1],
        vec![4, 5, 8],
        vec![5, 7, 8],
        vec![7, 6, 8],
        vec![6, 4, 8],
    ];
    Mesh::from_polygons(v, faces).unwrap()
}

/// The octahedron with vertices (±r, 0, 0), (0, ±r, 0), (0, 0, ±r), moved by `at`.
fn lattice_octahedron(r: f64, at: [f64; 3]) -> Mesh {
    let axis = |k: usize, s: f64| {
        let mut p = at;
        p[k] += s * r;
        pt(p[0], p[1], p[2])
    };
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                let i = vertices.len() as u32;
                vertices.extend([axis(0, sx), axis(1, sy), axis(2, sz)]);
                // (X, Y, Z) is counter-clockwise from outside when sx·sy·sz > 0.
                faces.push(if sx * sy * sz > 0.0 {
                    vec![i, i + 1, i + 2]
                } else {
                    vec![i, i + 2, i + 1]
                });
            }
        }
    }
    Mesh::from_polygons(vertices, faces).unwrap()
}

/// The tetrahedron (1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1), scaled and moved.
fn lattice_tetrahedron(r: f64, at: [f64; 3]) -> Mesh {
    let v = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ]
    .map(|c| pt(at[0] + r * c[0], at[1] + r * c[1], at[2] + r * c[2]))
    .to_vec();
    let faces = vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]];
    // Each face is counter-clockwise seen from outside: its normal points away from the
    // fourth vertex.
    Mesh::from_polygons(v, faces).unwrap()
}

fn translated(mesh: Mesh, by: [f64; 3]) -> Mesh {
    mesh.transformed(&Matrix4::new_translation(&Vector3::new(
        by[0], by[1], by[2],
    )))
    .unwrap()
}

/// An L-shaped (non-convex) prism over integer corners.
fn lattice_l_prism(at: [f64; 3]) -> Mesh {
    let l = geo::Polygon::new(
        geo::LineString::from(vec![
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 3.0),
            (0.0, 3.0),
        ]),
        vec![],
    );
    translated(solids::prism(&l, 2.0).unwrap(), at)
}

/// A random mesh (a solid of several kinds) turned, scaled and moved at random.
fn random_mesh(rng: &mut SplitMix64) -> Mesh {
    let mesh = match rng.below(8) {
        0 => solids::cube(rng.range(0.5, 2.0)).unwrap(),
        1 => solids::cuboid(Vector3::new(
            rng.range(0.3, 2.0),
            rng.range(0.3, 2.0),
            rng.range(0.3, 2.0),
        ))
        .unwrap(),
        2 => solids::tetrahedron(rng.range(1.0, 2.5)).unwrap(),
        3 => solids::octahedron(rng.range(1.0, 2.5)).unwrap(),
        4 => solids::icosahedron(rng.range(0.8, 1.5)).unwrap(),
        5 => solids::torus(rng.range(1.2, 2.0), rng.range(0.3, 0.8), 10, 6).unwrap(),
        6 => solids::uv_sphere(rng.range(0.5, 1.5), 8, 5).unwrap(),
        _ => lattice_l_prism([-1.5, -1.5, -1.0]),
    };
    if rng.below(6) == 0 {
        // Unturned, at an exact position: faces parallel to the axes.
        return translated(mesh, [rng.int(-3, 3), rng.int(-3, 3), rng.int(-3, 3)]);
    }
    let axis = Unit::new_normalize(rng.vector(1.0) + Vector3::new(1e-3, 0.0, 0.0));
    let turn = Rotation3::from_axis_angle(&axis, rng.range(0.0, std::f64::consts::TAU));
    let m = Matrix4::new_translation(&rng.vector(3.0))
        * turn.to_homogeneous()
        * Matrix4::new_scaling(rng.range(0.6, 1.4));
    mesh.transformed(&m).unwrap()
}

/// A scene of 3 to 5 random meshes: at the top level, in a group, and in a group inside it;
/// each mesh then moved by `world`.
fn random_scene(rng: &mut SplitMix64, world: &Matrix4<f64>) -> Scene {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let h = s.add_group(Some(g), "h").unwrap();
    let n = 3 + rng.below(3);
    for i in 0..n {
        let parent = match i {
            0 => None,
            1 => Some(g),
            2 => Some(h),
            _ => rng.pick(&[None, Some(g), Some(h)]),
        };
        let mesh = random_mesh(rng).transformed(world).unwrap();
        s.add_mesh(parent, format!("m{i}"), mesh).unwrap();
    }
    s
}

/// The union of the CBOXes of the top-level objects, as (min, max).
fn scene_box(s: &Scene) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &r in s.roots() {
        let b = s.cbox(r);
        for k in 0..3 {
            lo[k] = lo[k].min(b.min[k]);
            hi[k] = hi[k].max(b.max[k]);
        }
    }
    (lo, hi)
}

fn up_for(direction: &Vector3) -> Vector3 {
    [Vector3::z(), Vector3::y(), Vector3::x()]
        .into_iter()
        .find(|u| direction.cross(u).norm() > 1e-3 * direction.norm())
        .unwrap()
}

/// The centre of the scene's box and its largest half-size.
fn centre_and_extent(s: &Scene) -> (Point3, f64) {
    let (lo, hi) = scene_box(s);
    let centre = Point3::from(std::array::from_fn::<f64, 3, _>(|k| (lo[k] + hi[k]) / 2.0));
    let extent = (0..3).map(|k| (hi[k] - lo[k]) / 2.0).fold(0.0, f64::max);
    (centre, extent)
}

/// A random orthographic view (general, with zero components, or along an axis) or a
/// perspective view from an eye outside the scene's box.
fn random_view(rng: &mut SplitMix64, s: &Scene) -> View {
    let (lo, hi) = scene_box(s);
    let (centre, extent) = centre_and_extent(s);
    match rng.below(5) {
        0 | 1 => {
            let mut d = rng.vector(1.0);
            if rng.below(3) == 0 {
                d[rng.below(3)] = 0.0;
            }
            if d == Vector3::zeros() {
                d = Vector3::x();
            }
            View::orthographic(d, up_for(&d)).unwrap()
        }
        2 => {
            let mut d = Vector3::zeros();
            d[rng.below(3)] = rng.pick(&[-1.0, 1.0, 0.5, -3.0]);
            View::orthographic(d, up_for(&d)).unwrap()
        }
        _ => loop {
            let e = centre + rng.vector(4.0 * extent);
            let margin = 0.2 * extent;
            let outside = (0..3).any(|k| e[k] < lo[k] - margin || e[k] > hi[k] + margin);
            if outside {
                let target = centre + rng.vector(0.2 * extent);
                break View::perspective(e, target, up_for(&(target - e)), 50.0).unwrap();
            }
        },
    }
}

/// Test points: uniform in and around the scene's box, vertices, edge midpoints, centroids,
/// lattice points, points on lines of sight through vertices and edge midpoints, and points
/// beyond a perspective eye.
fn random_points(rng: &mut SplitMix64, s: &Scene, eye: &Eye, n: usize) -> Vec<Point3> {
    let (lo, hi) = scene_box(s);
    let (_, extent) = centre_and_extent(s);
    let margin = 0.2 * extent;
    // A power of two near a tenth of the scene: lattice points are exact multiples of it.
    let step = 2f64.powi((extent / 10.0).log2().round() as i32);
    let triangles = all_triangles(s);
    let mut out = Vec::new();
    while out.len() < n {
        let (_, _, t) = triangles[rng.below(triangles.len())];
        let i = rng.below(3);
        let (a, b) = (t[i], t[(i + 1) % 3]);
        let choice = rng.below(9);
        let mut around = |k: usize| rng.range(lo[k] - margin, hi[k] + margin);
        let p = match choice {
            0 | 1 => Point3::from(std::array::from_fn::<f64, 3, _>(around)),
            2 => a,
            3 => nalgebra::center(&a, &b),
            4 => Point3::from((t[0].coords + t[1].coords + t[2].coords) / 3.0),
            5 => Point3::from(std::array::from_fn::<f64, 3, _>(|k| {
                (around(k) / step).round() * step
            })),
            // On the line through the eye and a vertex, beyond the eye (for a point eye).
            6 => match eye {
                Eye::Point(e) => e + (e - a) * rng.range(0.01, 1.0),
                Eye::Infinity(u) => a + u.normalize() * (extent * rng.range(0.01, 3.0)),
            },
            // On the line of sight through a vertex or an edge's midpoint, behind it.
            _ => {
                let v = if rng.below(2) == 0 {
                    a
                } else {
                    nalgebra::center(&a, &b)
                };
                let s = rng.range(0.02, 0.3);
                match eye {
                    Eye::Point(e) => v + (v - e) * s,
                    Eye::Infinity(u) => v - u.normalize() * (extent * s),
                }
            }
        };
        out.push(p);
    }
    out
}

/// What a comparison saw: points, points the reference decided without the perturbation,
/// hidden points.
#[derive(Debug, Default)]
struct Tally {
    points: usize,
    plain: usize,
    hidden: usize,
}

/// Compares every path on every point: the index, the batch, VISP with no preprocessing, brute
/// force with `hides`, and the exact reference; and, on every fourth point, an index and VISP
/// for each top-level object alone against brute force over its subtree.
fn compare_all(s: &Scene, view: &View, points: &[Point3], what: &str, tally: &mut Tally) {
    let index = VisibilityIndex::whole_scene(s, view.clone());
    let triangles = all_triangles(s);
    let reference = Reference::new(view.eye(), &triangles);
    let (batch, counters) = index.visp_all(points);
    assert_eq!(counters.total(), points.len() as u64, "{what}");
    for (p, answer) in points.iter().zip(batch) {
        let (expected, degenerate) = reference.visibility(p);
        tally.points += 1;
        tally.plain += usize::from(!degenerate);
        tally.hidden += usize::from(expected == Hidden);
        let eye = view.eye();
        let brute = brute_force(eye, &triangles, p);
        assert_eq!(brute, expected, "hides, {what}, {view:?}, {p:?}");
        assert_eq!(index.visp(p).0, expected, "index, {what}, {view:?}, {p:?}");
        assert_eq!(answer, expected, "visp_all, {what}, {view:?}, {p:?}");
        let single = visp_roots(s, view, p);
        assert_eq!(single, expected, "visp, {what}, {view:?}, {p:?}");
    }
    for &root in s.roots() {
        let part = VisibilityIndex::new(s, &[root], view.clone());
        let mine: Vec<_> = triangles
            .iter()
            .filter(|(id, _, _)| is_in(s, *id, root))
            .cloned()
            .collect();
        for p in points.iter().step_by(4) {
            let expected = brute_force(view.eye(), &mine, p);
            assert_eq!(
                part.visp(p).0,
                expected,
                "{what}, {root:?} alone, {view:?}, {p:?}"
            );
            let single = visp(s, root, view, p).0;
            assert_eq!(
                single, expected,
                "{what}, visp of {root:?}, {view:?}, {p:?}"
            );
        }
    }
}

/// Whether `id` is `root` or below it.
fn is_in(s: &Scene, mut id: ObjectId, root: ObjectId) -> bool {
    loop {
        if id == root {
            return true;
        }
        match s[id].parent() {
            Some(p) => id = p,
            None => return false,
        }
    }
}

#[test]
fn random_scenes_against_brute_force() {
    let mut rng = SplitMix64(0x5eed_0001);
    let mut tally = Tally::default();
    for scene_number in 0..12 {
        let s = random_scene(&mut rng, &Matrix4::identity());
        for _ in 0..2 {
            let view = random_view(&mut rng, &s);
            let points = random_points(&mut rng, &s, view.eye(), 150);
            compare_all(
                &s,
                &view,
                &points,
                &format!("scene {scene_number}"),
                &mut tally,
            );
        }
    }
    // Points on lines of sight through vertices and edges are rounded off them: nearly all
    // points are decided without the perturbation. Both answers are common.
    assert!(tally.plain * 10 >= tally.points * 9, "{tally:?}");
    assert!(
        tally.hidden * 5 > tally.points && tally.hidden * 5 < tally.points * 4,
        "{tally:?}"
    );
    eprintln!("{tally:?}");
}

/// The same far from the origin, and at tiny and huge scales: the bounds' rounded slab tests
/// must keep their margins (never miss a box the exact line of sight meets).
#[test]
fn far_and_scaled_scenes_against_brute_force() {
    let mut rng = SplitMix64(0x5eed_0002);
    let mut tally = Tally::default();
    let worlds = [
        Matrix4::new_translation(&Vector3::new(1e6, -2.5e6, 7e5)),
        Matrix4::new_scaling(1e-6),
        Matrix4::new_translation(&Vector3::new(3.0, -1.0, 2.0)) * Matrix4::new_scaling(1e-9),
        Matrix4::new_scaling(1e7),
        Matrix4::new_translation(&Vector3::new(-4e12, 1e12, 3e11)) * Matrix4::new_scaling(1e5),
    ];
    for (w, world) in worlds.iter().enumerate() {
        for scene_number in 0..2 {
            let s = random_scene(&mut rng, world);
            for _ in 0..2 {
                let view = random_view(&mut rng, &s);
                let points = random_points(&mut rng, &s, view.eye(), 60);
                let what = format!("world {w}, scene {scene_number}");
                compare_all(&s, &view, &points, &what, &mut tally);
            }
        }
    }
    assert!(tally.hidden * 10 > tally.points, "{tally:?}");
}

/// Scenes, eyes and points with exact small coordinates: lines of sight through edges and
/// vertices abound, and every one is checked against the perturbation worked out exactly.
#[test]
fn lattice_scenes_against_the_exact_perturbation() {
    let mut rng = SplitMix64(0x1a77_1ce5);
    let mut tally = Tally::default();
    for scene_number in 0..8 {
        let mut s = Scene::new();
        let g = s.add_group(None, "g").unwrap();
        let mut spot = || {
            [
                rng.int(-3, 3) / 2.0,
                rng.int(-3, 3) / 2.0,
                rng.int(-3, 3) / 2.0,
            ]
        };
        let meshes = [
            translated(solids::cuboid(Vector3::new(2.0, 1.0, 3.0)).unwrap(), spot()),
            translated(fan_top_cube(), spot()),
            lattice_octahedron(1.5, spot()),
            lattice_tetrahedron(1.0, spot()),
            lattice_l_prism(spot()),
        ];
        for (i, m) in meshes.into_iter().enumerate() {
            if (scene_number + i) % 3 != 0 {
                s.add_mesh(if i % 2 == 0 { None } else { Some(g) }, format!("m{i}"), m)
                    .unwrap();
            }
        }
        if s[g].subobjects().is_empty() {
            s.add_mesh(Some(g), "cube", solids::cube(1.0).unwrap())
                .unwrap();
        }
        let views = [
            View::standard(),
            View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap(),
            View::orthographic(Vector3::new(1.0, -2.0, 0.0), Vector3::z()).unwrap(),
            View::orthographic(Vector3::new(0.0, 1.0, 2.0), Vector3::x()).unwrap(),
            View::orthographic(Vector3::new(2.0, 1.0, -1.0), Vector3::z()).unwrap(),
            View::perspective(pt(9.0, 7.0, 8.0), Point3::origin(), Vector3::z(), 60.0).unwrap(),
            View::perspective(pt(0.0, 0.0, 12.0), pt(0.0, 1.0, 0.0), Vector3::y(), 60.0).unwrap(),
            View::perspective(pt(-8.0, 2.0, -1.0), Point3::origin(), Vector3::z(), 60.0).unwrap(),
        ];
        // The half-integer lattice over the scene's box, and every vertex and edge midpoint.
        let (lo, hi) = scene_box(&s);
        let mut points = Vec::new();
        let steps = |k: usize| ((lo[k] - 1.0) * 2.0).floor() as i32..=((hi[k] + 1.0) * 2.0) as i32;
        for x in steps(0) {
            for y in steps(1) {
                for z in steps(2) {
                    if rng.below(5) == 0 {
                        points.push(pt(
                            f64::from(x) / 2.0,
                            f64::from(y) / 2.0,
                            f64::from(z) / 2.0,
                        ));
                    }
                }
            }
        }
        for (_, _, t) in all_triangles(&s) {
            points.push(t[0]);
            points.push(nalgebra::center(&t[0], &t[1]));
        }
        for view in &views {
            let what = format!("lattice scene {scene_number}");
            compare_all(&s, view, &points, &what, &mut tally);
        }
    }
    // Many answers needed the perturbation; both answers are common.
    let degenerate = tally.points - tally.plain;
    assert!(degenerate * 10 > tally.points, "{tally:?}");
    assert!(
        tally.hidden * 5 > tally.points && tally.hidden * 5 < tally.points * 4,
        "{tally:?}"
    );
    eprintln!("{tally:?}");
}

// ---------------------------------------------------------------------------------------------
// Ray shooting.

/// The exact reference for a ray: among the triangles whose closed triangle the ray meets at
/// some t > 0 (not parallel to its plane, the origin not in its plane), the least t, the
/// triangles that reach it, and the exact point.
struct RayReference {
    t: Q,
    first: Vec<(ObjectId, usize)>,
    point: [Q; 3],
}

fn ray_reference(triangles: &[(ObjectId, usize, [Point3; 3])], ray: &Ray) -> Option<RayReference> {
    let o = arr(&ray.origin);
    let u = [ray.direction.x, ray.direction.y, ray.direction.z];
    let mut best: Option<RayReference> = None;
    for (id, i, t) in triangles {
        let [a, b, c] = t.map(|p| arr(&p));
        // The sides of the plane of the origin and of the far end of the ray: orient3d(a, b,
        // c, o) and -det[a - c, b - c, u].
        let origin_side = det_sign([(a, o), (b, o), (c, o)]);
        let far_side = det_sign([(a, c), (b, c), (u, ZERO)]).reverse();
        if origin_side == Ordering::Equal || far_side != origin_side.reverse() {
            continue;
        }
        // The line o + t·u passes through the closed triangle iff the three orientations of
        // (line, edge) do not disagree.
        let s = [(a, b), (b, c), (c, a)].map(|(p, r)| det_sign([(o, r), (p, r), (u, ZERO)]));
        if s.contains(&Ordering::Less) && s.contains(&Ordering::Greater) {
            continue;
        }
        // t = n·(a - o) / n·u, and the point, exactly.
        let (qa, qb, qc, qo, qu) = (qv(a), qv(b), qv(c), qv(o), qv(u));
        let n = qcross(&qsub(&qb, &qa), &qsub(&qc, &qa));
        let t = qdot(&n, &qsub(&qa, &qo)) / qdot(&n, &qu);
        assert!(t.is_positive());
        let x: [Q; 3] = std::array::from_fn(|k| &qo[k] + &t * &qu[k]);
        // Double-check the reference: x is on the plane, inside the closed triangle.
        assert!(qdot(&n, &qsub(&x, &qa)).is_zero());
        for (p, r) in [(&qa, &qb), (&qb, &qc), (&qc, &qa)] {
            assert!(!qdot(&qcross(&qsub(r, p), &qsub(&x, p)), &n).is_negative());
        }
        match &mut best {
            Some(r) if t > r.t => {}
            Some(r) if t == r.t => r.first.push((*id, *i)),
            _ => {
                best = Some(RayReference {
                    t,
                    first: vec![(*id, *i)],
                    point: x,
                })
            }
        }
    }
    best
}

/// Checks `first_hit` against the reference: the same answer (None or the least t, among
/// the triangles reaching it), the right face, and a point within 4 ulps of the exact one.
fn check_ray(scene: &Scene, index: &VisibilityIndex, ray: &Ray, what: &str) -> Option<Hit> {
    let triangles = all_triangles(scene);
    let hit = index.first_hit(ray);
    let expected = ray_reference(&triangles, ray);
    let what = format!("{what}, {ray:?}");
    match (&hit, &expected) {
        (None, None) => {}
        (Some(h), Some(r)) => {
            assert!(
                r.first.contains(&(h.object, h.triangle)),
                "{what}: hit {h:?}, expected one of {:?} at t = {}",
                r.first,
                r.t
            );
            let mesh = scene[h.object].mesh().unwrap();
            assert!(mesh.faces()[h.face].triangle_range().contains(&h.triangle));
            let scale = (0..3)
                .map(|k| {
                    let tu = (&r.t * q(ray.direction[k])).abs();
                    let tu: f64 = num_traits::ToPrimitive::to_f64(&tu).unwrap();
                    ray.origin[k].abs().max(tu)
                })
                .fold(0.0, f64::max);
            for k in 0..3 {
                let error = (q(h.point[k]) - &r.point[k]).abs();
                assert!(
                    error <= q(4.0 * f64::EPSILON * scale),
                    "{what}: hit point {:?}, coordinate {k} off by {error}",
                    h.point
                );
            }
        }
        _ => panic!(
            "{what}: hit {hit:?}, expected {:?}",
            expected.map(|r| (r.first, r.t))
        ),
    }
    hit
}

#[test]
fn rays_hand_made() {
    let (s, c) = unit_cube();
    let index = VisibilityIndex::whole_scene(&s, standard());
    let normal = |h: &Hit| s[c].mesh().unwrap().faces()[h.face].plane().normal;
    let (x, z) = (Vector3::x(), Vector3::z());
    let down = -z;
    // (origin, direction, the point hit, the normals of the faces it may be on, why).
    let hits: [(Point3, Vector3, Point3, &[Vector3], &str); 12] = [
        (
            pt(0.25, 0.5, -5.0),
            z,
            pt(0.25, 0.5, -1.0),
            &[down],
            "straight up into the bottom",
        ),
        (
            pt(0.25, 0.5, -5.0),
            Vector3::new(0.0, 0.0, 1e-3),
            pt(0.25, 0.5, -1.0),
            &[down],
            "the direction need not be a unit vector",
        ),
        (
            pt(3.0, 0.0, -3.0),
            Vector3::new(-1.0, 0.0, 1.0),
            pt(1.0, 0.0, -1.0),
            &[down, x],
            "through the edge x = 1, z = -1: the bottom and the side meet it at t = 2",
        ),
        (
            pt(3.0, 3.0, 3.0),
            Vector3::new(-1.0, -1.0, -1.0),
            pt(1.0, 1.0, 1.0),
            &[x, Vector3::y(), z],
            "through the corner (1, 1, 1)",
        ),
        (
            pt(0.5, 0.0, 0.0),
            x,
            pt(1.0, 0.0, 0.0),
            &[x],
            "from inside, out through a face",
        ),
        (
            Point3::origin(),
            Vector3::new(1.0, 1.0, 1.0),
            pt(1.0, 1.0, 1.0),
            &[x, Vector3::y(), z],
            "from inside, out through a corner",
        ),
        (
            pt(-5.0, 0.25, 1.0),
            x,
            pt(-1.0, 0.25, 1.0),
            &[-x],
            "in the top's plane: the top is not met, the side x = -1 is, at its edge",
        ),
        (
            pt(1.0, 1.0, -4.0),
            z,
            pt(1.0, 1.0, -1.0),
            &[down],
            "along the edge line x = y = 1: the sides are in its plane, the bottom's corner is met",
        ),
        (
            pt(0.5, 0.5, 1.0),
            down,
            pt(0.5, 0.5, -1.0),
            &[down],
            "from a point on the top, inwards: out through the bottom",
        ),
        (
            pt(0.0, 0.0, -1.0),
            Vector3::new(1.0, 0.0, 1.0),
            pt(1.0, 0.0, 0.0),
            &[x],
            "from the bottom's centre (its plane holds the origin) to the side",
        ),
        (
            pt(-3.0, 0.5, 0.0),
            Vector3::new(2.0, 0.0, 1.0),
            pt(-1.0, 0.5, 1.0),
            &[-x, z],
            "through the top edge x = -1 from outside",
        ),
        (
            pt(0.5, 0.5, -1.5),
            Vector3::new(0.5, 0.5, 0.5),
            pt(1.0, 1.0, -1.0),
            &[down, x, Vector3::y()],
            "through the bottom corner (1, 1, -1) from below",
        ),
    ];
    for (origin, direction, point, normals, why) in hits {
        let ray = Ray { origin, direction };
        let h = check_ray(&s, &index, &ray, why).unwrap_or_else(|| panic!("no hit: {why}"));
        assert_eq!((h.object, h.point), (c, point), "{why}");
        assert!(normals.contains(&normal(&h)), "{why}: {:?}", normal(&h));
    }
    let misses = [
        (
            pt(0.5, 0.5, 1.0),
            z,
            "from a point on the top, outwards: its plane holds the origin",
        ),
        (pt(3.0, 0.0, -5.0), z, "beside the cube"),
        (pt(0.0, 0.0, 2.0), z, "away from the cube"),
        (
            pt(1.5, 0.0, -5.0),
            Vector3::new(0.0, 1.0, 1.0),
            "skew, beside the cube",
        ),
        (pt(-5.0, 0.25, 1.0), -x, "in the top's plane, away"),
        (pt(0.0, 0.0, -5.0), Vector3::zeros(), "a zero direction"),
        (
            Point3::origin(),
            Vector3::zeros(),
            "a zero direction from inside",
        ),
    ];
    for (origin, direction, why) in misses {
        let ray = Ray { origin, direction };
        assert_eq!(index.first_hit(&ray), None, "{why}");
        if direction != Vector3::zeros() {
            check_ray(&s, &index, &ray, why);
        }
    }

    // Two objects in a row: the nearer one, from either side.
    let mut two = Scene::new();
    let near = two
        .add_mesh(None, "near", solids::cube(2.0).unwrap())
        .unwrap();
    let g = two.add_group(None, "g").unwrap();
    let far = translated(solids::cube(2.0).unwrap(), [0.0, 0.0, 5.0]);
    let far = two.add_mesh(Some(g), "far", far).unwrap();
    let index = VisibilityIndex::whole_scene(&two, standard());
    let up = Ray {
        origin: pt(0.0, 0.5, -9.0),
        direction: z,
    };
    let h = check_ray(&two, &index, &up, "two, up").unwrap();
    assert_eq!((h.object, h.point), (near, pt(0.0, 0.5, -1.0)));
    let back = Ray {
        origin: pt(0.0, 0.5, 9.0),
        direction: down,
    };
    let h = check_ray(&two, &index, &back, "two, down").unwrap();
    assert_eq!((h.object, h.point), (far, pt(0.0, 0.5, 6.0)));
    // Only the objects the index was built for.
    let only_far = VisibilityIndex::new(&two, &[g], standard());
    let h = only_far.first_hit(&up).unwrap();
    assert_eq!((h.object, h.point), (far, pt(0.0, 0.5, 4.0)));
}

#[test]
fn random_rays_against_exact_reference() {
    let mut rng = SplitMix64(0x0a7e_5eed_1234);
    let mut hits = 0;
    let mut total = 0;
    for scene_number in 0..10 {
        let s = random_scene(&mut rng, &Matrix4::identity());
        let index = VisibilityIndex::whole_scene(&s, View::standard());
        let triangles = all_triangles(&s);
        let (lo, hi) = scene_box(&s);
        for _ in 0..45 {
            let origin = Point3::from(std::array::from_fn::<f64, 3, _>(|k| {
                rng.range(lo[k] - 2.0, hi[k] + 2.0)
            }));
            let (_, _, t) = triangles[rng.below(triangles.len())];
            let direction = match rng.below(6) {
                0 => rng.vector(1.0),
                1 => t[0] - origin,
                2 => nalgebra::center(&t[0], &t[1]) - origin,
                3 => (t[0].coords + t[1].coords + t[2].coords) / 3.0 - origin.coords,
                4 => {
                    let mut d = Vector3::zeros();
                    d[rng.below(3)] = rng.pick(&[1.0, -1.0, 1e-3, -7.5]);
                    d
                }
                _ => (t[0] - origin) * 1e5,
            };
            let ray = Ray { origin, direction };
            if check_ray(&s, &index, &ray, &format!("scene {scene_number}")).is_some() {
                hits += 1;
            }
            total += 1;
        }
    }
    assert!(hits * 3 > total, "{hits} of {total}");
}

/// Rays with exact coordinates through vertices, edge midpoints and along faces of lattice
/// meshes: every tie and grazing case.
#[test]
fn lattice_rays_against_exact_reference() {
    let mut rng = SplitMix64(0x1a77_1ce5_0002);
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    s.add_mesh(
        None,
        "box",
        translated(
            solids::cuboid(Vector3::new(2.0, 1.0, 3.0)).unwrap(),
            [1.5, 0.0, 0.0],
        ),
    )
    .unwrap();
    s.add_mesh(Some(g), "fan", translated(fan_top_cube(), [-2.0, 0.5, 0.0]))
        .unwrap();
    s.add_mesh(Some(g), "octa", lattice_octahedron(1.5, [0.0, -2.0, 1.0]))
        .unwrap();
    s.add_mesh(None, "tetra", lattice_tetrahedron(1.0, [0.0, 2.0, -1.0]))
        .unwrap();
    s.add_mesh(None, "l", lattice_l_prism([-1.0, -1.0, 2.5]))
        .unwrap();
    let index = VisibilityIndex::whole_scene(&s, View::standard());
    let triangles = all_triangles(&s);
    let mut hits = 0;
    for i in 0..1500 {
        let origin = pt(rng.int(-5, 5), rng.int(-5, 5), rng.int(-5, 5));
        let (_, _, t) = triangles[rng.below(triangles.len())];
        let direction = match i % 4 {
            0 => t[rng.below(3)] - origin,
            1 => nalgebra::center(&t[0], &t[1]) - origin,
            2 => Vector3::new(rng.int(-2, 2), rng.int(-2, 2), rng.int(-2, 2)),
            _ => {
                // Along a face's plane: from a vertex towards another vertex of its triangle.
                let ray = Ray {
                    origin: t[0] + (t[0] - t[1]),
                    direction: t[1] - t[0],
                };
                if check_ray(&s, &index, &ray, "along an edge").is_some() {
                    hits += 1;
                }
                continue;
            }
        };
        if direction == Vector3::zeros() {
            assert!(index.first_hit(&Ray { origin, direction }).is_none());
            continue;
        }
        if check_ray(&s, &index, &Ray { origin, direction }, "lattice").is_some() {
            hits += 1;
        }
    }
    assert!(hits > 500, "{hits}");
}
