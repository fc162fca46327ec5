//! The visible-surface pass against an exact reference.
//!
//! For every face F of every mesh, the expected answer is computed here in rational arithmetic
//! (`BigRational`) from the scene's input coordinates and the view's rows and eye taken as
//! exact, independently of the library's algorithm:
//!
//! - a point X of F is hidden when some other face G (of any mesh, F's own included) lies
//!   strictly between X and the eye: X strictly behind G's plane (on the side away from the
//!   eye) and the line of sight through X crossing G's interior (X strictly inside every sight
//!   plane of G's edges: the plane through the edge and the eye, or through the edge along
//!   the view direction for an eye at infinity);
//! - F (a convex planar polygon) is split into convex cells by the planes of every face G that
//!   may hide some of it and by the sight planes of G's edges. Every cell edge is kept as its
//!   supporting plane and every new vertex is the intersection of three planes (F's, the
//!   cutting plane and the edge's) by Cramer's rule, so rationals never chain;
//! - each cell's vertex mean lies strictly inside the cell, so strictly off every cutting
//!   plane (asserted), and decides the whole cell;
//! - F is VISIBLE when every cell is visible, HIDDEN when none is, else MIXED; its visible
//!   area is the sum of the shoelace areas of the exact pictures of the visible cells.
//!
//! The scenes are convex solids with exactly planar faces: axis-aligned boxes and
//! parallelepipeds with dyadic vertices, and triangle-faced solids (octahedra, tetrahedra,
//! icosahedra) turned at will; orthographic and perspective views, general and along lattice
//! directions (faces seen exactly edge-on, coplanar and touching faces).
//!
//! The library's answer (`visible_surfaces`) must agree, face by face:
//!
//! - the same status; a face seen exactly edge-on reported `edge_on`, VISIBLE, without
//!   polygons; a VISIBLE face's polygon is the face's picture (`Picture::point` of its
//!   vertices) bit for bit; a HIDDEN face has no polygons, a MIXED one has some;
//! - the area of its polygons within `1e-12` of the largest face's picture area of the exact
//!   visible area;
//! - every vertex of its polygons (outer rings and holes) near some exact vertex of a visible
//!   cell: within [`MAX_ULPS`] units in the last place of the scene's scale (the largest
//!   picture coordinate of its vertices) per coordinate. A vertex farther than `1e-9` of the
//!   scale from all of them is a stray (a ring without area, a spike, a visible part where
//!   there is none).
//!
//! Why ulps of the scale: every vertex is built once from the input (a ratio of exact
//! polynomials, each rounded once), but the picture of an input vertex off F's plane stands for
//! the point where its line of sight meets F's plane, and for an orthographic view the rounded
//! rows of the picture are not exactly orthogonal to the view direction: the two pictures differ
//! by about an ulp of the picture's magnitude, not of their own coordinates (a vertex near the
//! picture's origin may have exact coordinates of 1e-17, whose own ulps mean nothing there). The
//! summaries also print, for information, the worst error in ulps of each exact coordinate (of
//! the scale for an exact 0).
//!
//! There must be no disagreement at all.

use geo::{Area, MultiPolygon};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::scene::{ObjectId, Scene};
use kepler::solids;
use kepler::surfaces::{FaceReport, Status, visible_surfaces};
use kepler::views::{Picture, View};
use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::collections::{BTreeMap, BTreeSet};

use crate::common::exact::{
    P2, RefEye, RefView, V, cuboid_at, f2, parallelepiped, qp, ulp_of, ulps2,
};
use crate::common::{Q, SplitMix64, q, qcross, qdot, qsign, qsub, scene_and_ids};

/// The largest error allowed for a vertex of a visible polygon, per coordinate, in units in the
/// last place of the scene's scale.
const MAX_ULPS: f64 = 2.0;

/// The largest error allowed for the area of a face's visible polygons, relative to the largest
/// face's picture area in the scene.
const AREA_TOLERANCE: f64 = 1e-12;

// ---------------------------------------------------------------------------------------------
// Planes and points, exactly, in integers.
//
// Every input number is a double, so every plane built from input points, the eye and the
// view's rows has dyadic coefficients: scaled by a power of two they are integers. A vertex of
// a cell is kept in homogeneous integer coordinates `x / w` (`w > 0`) straight from the three
// planes that make it, so no rational is ever normalised on the way.

type Z = BigInt;

/// A point `x / w`, `w > 0`, in integers.
#[derive(Clone, Debug)]
struct Hp {
    x: [Z; 3],
    w: Z,
}

impl Hp {
    /// A point with dyadic coordinates.
    fn of(v: &V) -> Hp {
        assert!(
            v.iter().all(|c| power_of_two(c.denom())),
            "dyadic coordinates"
        );
        let w = v
            .iter()
            .map(|c| c.denom().clone())
            .max()
            .expect("three coordinates");
        let x = v
            .clone()
            .map(|c| (c * Q::from_integer(w.clone())).to_integer());
        Hp { x, w }
    }

    /// The point, as rationals.
    fn rational(&self) -> V {
        self.x.clone().map(|c| Q::new(c, self.w.clone()))
    }
}

/// Whether `x` is a power of two.
fn power_of_two(x: &Z) -> bool {
    x.trailing_zeros().map(|z| Z::from(1) << z as usize) == Some(x.clone())
}

/// Dyadic rationals scaled by their largest denominator, as integers, with their common powers
/// of two taken out.
fn dyadic_integers(values: &[Q]) -> Vec<Z> {
    assert!(
        values.iter().all(|c| power_of_two(c.denom())),
        "dyadic coefficients"
    );
    let scale = values
        .iter()
        .map(|c| c.denom().clone())
        .max()
        .expect("values");
    let ints: Vec<Z> = values
        .iter()
        .map(|c| (c * Q::from_integer(scale.clone())).to_integer())
        .collect();
    let shift = ints
        .iter()
        .filter_map(|i| i.trailing_zeros())
        .min()
        .unwrap_or(0);
    ints.into_iter().map(|i| i >> shift as usize).collect()
}

/// The plane `n·x = h`, in integers.
#[derive(Clone, Debug)]
struct Plane {
    n: [Z; 3],
    h: Z,
}

impl Plane {
    fn new(n: V, h: Q) -> Plane {
        let ints = dyadic_integers(&[n[0].clone(), n[1].clone(), n[2].clone(), h]);
        Plane {
            n: [ints[0].clone(), ints[1].clone(), ints[2].clone()],
            h: ints[3].clone(),
        }
    }

    /// The plane through `a`, `b` and `c` (zero normal when they are collinear).
    fn through(a: &V, b: &V, c: &V) -> Plane {
        let n = qcross(&qsub(b, a), &qsub(c, a));
        let h = qdot(&n, a);
        Plane::new(n, h)
    }

    /// The plane through the segment `cd` and the eye (for an eye at infinity, the plane
    /// through `cd` along the view direction).
    fn sight(rv: &RefView, c: &V, d: &V) -> Plane {
        let n = match &rv.eye {
            RefEye::Point(e) => qcross(&qsub(c, e), &qsub(d, e)),
            RefEye::Direction(u) => qcross(&qsub(d, c), u),
        };
        let h = qdot(&n, c);
        Plane::new(n, h)
    }

    fn degenerate(&self) -> bool {
        self.n.iter().all(Zero::is_zero)
    }

    /// The side of the plane `p` is on.
    fn side(&self, p: &Hp) -> Ordering {
        let v = &self.n[0] * &p.x[0] + &self.n[1] * &p.x[1] + &self.n[2] * &p.x[2] - &self.h * &p.w;
        v.cmp(&Z::zero())
    }

    /// The side the eye is on (`Equal` when the plane contains it or, for an eye at infinity,
    /// the view direction).
    fn eye_side(&self, rv: &RefView) -> Ordering {
        let n: V = self.n.clone().map(Q::from_integer);
        match &rv.eye {
            RefEye::Point(e) => qsign(&(qdot(&n, e) - Q::from_integer(self.h.clone()))),
            RefEye::Direction(u) => qsign(&qdot(&n, u)),
        }
    }
}

fn zcross(a: &[Z; 3], b: &[Z; 3]) -> [Z; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn zdot(a: &[Z; 3], b: &[Z; 3]) -> Z {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// The point common to three planes (Cramer's rule); they must meet in one point.
fn meet(a: &Plane, b: &Plane, c: &Plane) -> Hp {
    let bc = zcross(&b.n, &c.n);
    let ca = zcross(&c.n, &a.n);
    let ab = zcross(&a.n, &b.n);
    let det = zdot(&a.n, &bc);
    assert!(!det.is_zero(), "three planes without a single common point");
    let x = [0, 1, 2].map(|k| &a.h * &bc[k] + &b.h * &ca[k] + &c.h * &ab[k]);
    if det.is_negative() {
        Hp {
            x: x.map(|c| -c),
            w: -det,
        }
    } else {
        Hp { x, w: det }
    }
}

/// The mean of some points (strictly inside their convex hull when it has area).
fn mean(points: &[Hp]) -> Hp {
    let mut acc = points[0].clone();
    for p in &points[1..] {
        acc = Hp {
            x: [0, 1, 2].map(|k| &acc.x[k] * &p.w + &p.x[k] * &acc.w),
            w: &acc.w * &p.w,
        };
    }
    acc.w *= Z::from(points.len());
    acc
}

/// Twice the signed area of a polygon of exact picture points (shoelace).
fn shoelace2(p: &[P2]) -> Q {
    let n = p.len();
    (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            &p[i][0] * &p[j][1] - &p[j][0] * &p[i][1]
        })
        .fold(Q::zero(), |s, t| s + t)
}

// ---------------------------------------------------------------------------------------------
// Faces, exactly.

/// A face of the scene, exactly.
struct RefFace {
    object: ObjectId,
    face: usize,
    /// Its vertex loop.
    v: Vec<Hp>,
    plane: Plane,
    /// The side of its plane the eye is on (`Equal`: seen edge-on).
    eye_side: Ordering,
    /// The sight planes of its edges `v[i] v[i + 1]` (none when seen edge-on).
    edges: Vec<Plane>,
    /// The bounding box of its exact picture (rounded), to skip faces far apart.
    bounds: [[f64; 2]; 2],
    /// Its picture by the library's map (`Picture::point`): a VISIBLE face's polygon, bit for
    /// bit.
    picture: Vec<[f64; 2]>,
    /// Its exact picture area (0 when seen edge-on).
    area: Q,
}

impl RefFace {
    fn new(rv: &RefView, picture: &Picture, object: ObjectId, mesh: &Mesh, face: usize) -> Self {
        let loop_ = mesh.faces()[face].vertices();
        let points: Vec<Point3> = loop_.iter().map(|&i| mesh.vertices()[i as usize]).collect();
        let exact: Vec<V> = points.iter().map(qp).collect();
        let v: Vec<Hp> = exact.iter().map(Hp::of).collect();
        let plane = (1..exact.len() - 1)
            .map(|i| Plane::through(&exact[0], &exact[i], &exact[i + 1]))
            .find(|p| !p.degenerate())
            .expect("a face with area");
        assert!(
            v.iter().all(|x| plane.side(x) == Ordering::Equal),
            "the scenes' faces are exactly planar"
        );
        let eye_side = plane.eye_side(rv);
        let n = exact.len();
        let (edges, pictures) = if eye_side == Ordering::Equal {
            (Vec::new(), Vec::new())
        } else {
            let edges = (0..n)
                .map(|i| Plane::sight(rv, &exact[i], &exact[(i + 1) % n]))
                .collect();
            (
                edges,
                exact.iter().map(|x| rv.picture(x)).collect::<Vec<P2>>(),
            )
        };
        let approx: Vec<[f64; 2]> = exact.iter().map(|x| f2(&rv.picture(x))).collect();
        let lo = [0, 1].map(|k| approx.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
        let hi = [0, 1].map(|k| {
            approx
                .iter()
                .map(|p| p[k])
                .fold(f64::NEG_INFINITY, f64::max)
        });
        let area = if pictures.is_empty() {
            Q::zero()
        } else {
            shoelace2(&pictures).abs() / Q::from_integer(BigInt::from(2))
        };
        RefFace {
            object,
            face,
            v,
            plane,
            eye_side,
            edges,
            bounds: [lo, hi],
            picture: points.iter().map(|p| picture.point(p)).collect(),
            area,
        }
    }

    /// Whether this face hides `x` (a point strictly off its plane and off its edges' sight
    /// planes, asserted): `x` strictly behind its plane and strictly inside all its edges'
    /// sight planes.
    fn hides(&self, x: &Hp) -> bool {
        let behind = self.plane.side(x);
        assert_ne!(
            behind,
            Ordering::Equal,
            "a cell's centre on an occluder's plane"
        );
        let signs: Vec<Ordering> = self.edges.iter().map(|e| e.side(x)).collect();
        assert!(
            !signs.contains(&Ordering::Equal),
            "a cell's centre on an occluder's sight plane"
        );
        behind == self.eye_side.reverse() && signs.iter().all(|&s| s == signs[0])
    }
}

/// A convex cell of a face: its vertices and, for each, the plane supporting the edge to the
/// next (an index into the face's list of planes).
#[derive(Clone)]
struct Cell {
    points: Vec<Hp>,
    sides: Vec<usize>,
}

/// The cell split by plane `k` (one or two cells; the same one when the plane does not cross
/// it properly).
fn split(cell: Cell, k: usize, planes: &[Plane], face: &Plane) -> Vec<Cell> {
    let n = cell.points.len();
    let s: Vec<Ordering> = cell.points.iter().map(|x| planes[k].side(x)).collect();
    if !s.contains(&Ordering::Greater) || !s.contains(&Ordering::Less) {
        return vec![cell];
    }
    // Where edge i crosses the plane (when it does), built once for both halves.
    let cross: Vec<Option<Hp>> = (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            (s[i] != Ordering::Equal && s[j] == s[i].reverse())
                .then(|| meet(face, &planes[k], &planes[cell.sides[i]]))
        })
        .collect();
    let half = |keep: Ordering| {
        let drop = keep.reverse();
        let mut out = Cell {
            points: Vec::new(),
            sides: Vec::new(),
        };
        for i in 0..n {
            let j = (i + 1) % n;
            if s[i] != drop {
                // The edge leaving a vertex on the plane towards the dropped side is replaced
                // by the cut.
                let side = if s[i] == Ordering::Equal && s[j] == drop {
                    k
                } else {
                    cell.sides[i]
                };
                out.points.push(cell.points[i].clone());
                out.sides.push(side);
                if let Some(x) = cross[i].as_ref().filter(|_| s[i] == keep) {
                    out.points.push(x.clone());
                    out.sides.push(k);
                }
            } else if let Some(x) = &cross[i] {
                out.points.push(x.clone());
                out.sides.push(cell.sides[i]);
            }
        }
        out
    };
    vec![half(Ordering::Greater), half(Ordering::Less)]
}

/// The exact answer for one face.
#[derive(Clone, Debug)]
struct Expected {
    object: ObjectId,
    face: usize,
    edge_on: bool,
    status: Status,
    /// The visible area of the picture (each cell's exact area rounded, summed).
    area: f64,
    /// The vertices of the visible cells.
    vertices: Vec<Candidate>,
    /// Cells visible, cells in all.
    cells: (usize, usize),
}

/// A vertex of a visible cell: its exact picture, rounded, and whether it is the picture of
/// an input vertex.
#[derive(Clone, Debug)]
struct Candidate {
    exact: P2,
    approx: [f64; 2],
    input: bool,
}

/// The exact answer for face `f` of `faces` against the faces of the objects `among` (`inputs`:
/// the exact pictures of all input vertices).
fn expect_face(
    rv: &RefView,
    faces: &[RefFace],
    f: usize,
    among: &[ObjectId],
    margin: f64,
    inputs: &BTreeSet<P2>,
) -> Expected {
    let face = &faces[f];
    let mut out = Expected {
        object: face.object,
        face: face.face,
        edge_on: face.eye_side == Ordering::Equal,
        status: Status::Visible,
        area: 0.0,
        vertices: Vec::new(),
        cells: (0, 0),
    };
    if out.edge_on {
        return out;
    }
    let [lo, hi] = face.bounds;
    // The faces that may hide some of F: not seen edge-on, with a point strictly in front of
    // F's plane while F has one strictly behind theirs, and pictures that may overlap.
    let occluders: Vec<&RefFace> = faces
        .iter()
        .enumerate()
        .filter(|&(g, other)| {
            let [glo, ghi] = other.bounds;
            g != f
                && among.contains(&other.object)
                && other.eye_side != Ordering::Equal
                && (0..2).all(|k| glo[k] <= hi[k] + margin && ghi[k] >= lo[k] - margin)
                && other.v.iter().any(|x| face.plane.side(x) == face.eye_side)
                && face
                    .v
                    .iter()
                    .any(|x| other.plane.side(x) == other.eye_side.reverse())
        })
        .map(|(_, other)| other)
        .collect();
    let mut planes: Vec<Plane> = face.edges.clone();
    for g in &occluders {
        planes.push(g.plane.clone());
        planes.extend(g.edges.iter().cloned());
    }
    let n = face.v.len();
    let mut cells = vec![Cell {
        points: face.v.clone(),
        sides: (0..n).collect(),
    }];
    for k in n..planes.len() {
        cells = cells
            .into_iter()
            .flat_map(|c| split(c, k, &planes, &face.plane))
            .collect();
    }
    let mut pictures: BTreeMap<V, P2> = BTreeMap::new();
    for cell in &cells {
        // Every occluder is asked (each asserts the centre is off its planes).
        let centre = mean(&cell.points);
        if occluders.iter().filter(|g| g.hides(&centre)).count() > 0 {
            continue;
        }
        let ring: Vec<P2> = cell
            .points
            .iter()
            .map(|x| {
                pictures
                    .entry(x.rational())
                    .or_insert_with_key(|v| rv.picture(v))
                    .clone()
            })
            .collect();
        let area = shoelace2(&ring).abs();
        assert!(area.is_positive(), "a cell without area");
        out.cells.0 += 1;
        out.area += area.to_f64().unwrap() / 2.0;
    }
    out.cells.1 = cells.len();
    out.status = if out.cells.0 == out.cells.1 {
        Status::Visible
    } else if out.cells.0 == 0 {
        Status::Hidden
    } else {
        Status::Mixed
    };
    out.vertices = pictures
        .into_values()
        .map(|exact| Candidate {
            approx: f2(&exact),
            input: inputs.contains(&exact),
            exact,
        })
        .collect();
    out
}

/// VISOBJ(A, B) exactly: VISIBLE when the faces of `a` hide nothing of any face of `b` not seen
/// edge-on, HIDDEN when they hide all of each, else MIXED.
fn expect_visobj(scene: &Scene, ids: &[ObjectId], view: &View, a: ObjectId, b: ObjectId) -> Status {
    let rv = RefView::new(view);
    let faces = ref_faces(scene, ids, view, &rv);
    let margin = 1e-9 * scale_of(&faces);
    let statuses: Vec<Status> = (0..faces.len())
        .filter(|&f| faces[f].object == b)
        .map(|f| expect_face(&rv, &faces, f, &[a], margin, &BTreeSet::new()))
        .filter(|e| !e.edge_on)
        .map(|e| e.status)
        .collect();
    if statuses.iter().all(|&s| s == Status::Visible) {
        Status::Visible
    } else if statuses.iter().all(|&s| s == Status::Hidden) {
        Status::Hidden
    } else {
        Status::Mixed
    }
}

/// The exact answers for a whole scene, with the scales the comparison needs.
struct Reference {
    /// The mesh objects, in the order of the case's meshes.
    ids: Vec<ObjectId>,
    faces: Vec<Expected>,
    /// The scene's scale: its largest picture coordinate magnitude (vertex errors are in its
    /// ulps).
    scale: f64,
    /// The largest face's picture area.
    largest_area: f64,
    /// The library's picture of every face, by (object, face).
    pictures: BTreeMap<(ObjectId, usize), Vec<[f64; 2]>>,
}

/// Every face of the meshes `ids`, exactly.
fn ref_faces(scene: &Scene, ids: &[ObjectId], view: &View, rv: &RefView) -> Vec<RefFace> {
    let picture = Picture::of(view);
    ids.iter()
        .flat_map(|&id| {
            let mesh = scene[id].mesh().expect("a mesh object");
            (0..mesh.faces().len()).map(move |f| (id, mesh, f))
        })
        .map(|(id, mesh, f)| RefFace::new(rv, &picture, id, mesh, f))
        .collect()
}

/// The largest picture coordinate magnitude of the faces' vertices.
fn scale_of(faces: &[RefFace]) -> f64 {
    faces
        .iter()
        .flat_map(|f| f.picture.iter())
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
}

fn reference(scene: &Scene, ids: &[ObjectId], view: &View) -> Reference {
    let rv = RefView::new(view);
    let faces = ref_faces(scene, ids, view, &rv);
    let scale = scale_of(&faces);
    let largest_area = faces
        .iter()
        .map(|f| f.area.to_f64().unwrap())
        .fold(0.0f64, f64::max);
    let margin = 1e-9 * scale.max(f64::MIN_POSITIVE);
    let inputs: BTreeSet<P2> = ids
        .iter()
        .flat_map(|&id| scene[id].mesh().unwrap().vertices())
        .map(|p| rv.picture(&qp(p)))
        .collect();
    let expected = (0..faces.len())
        .map(|f| expect_face(&rv, &faces, f, ids, margin, &inputs))
        .collect();
    let pictures = faces
        .iter()
        .map(|f| ((f.object, f.face), f.picture.clone()))
        .collect();
    Reference {
        ids: ids.to_vec(),
        faces: expected,
        scale,
        largest_area,
        pictures,
    }
}

// ---------------------------------------------------------------------------------------------
// The comparison.

/// The kinds of disagreement with the exact reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    /// A face reported twice, or not at all.
    Report,
    /// Edge-on exactly but not reported so, or the other way round, or edge-on with polygons.
    EdgeOn,
    /// Another status.
    Status,
    /// The polygons do not fit the reported status: VISIBLE but not the face's picture bit
    /// for bit, HIDDEN with polygons, MIXED without.
    Shape,
    /// The visible area is off by more than the tolerance.
    Area,
    /// A vertex of the polygons farther than `1e-9` of the scene's scale from every exact
    /// vertex of a visible cell (a sliver, a spike, or a visible part where none is).
    Stray,
    /// A vertex near an exact one but more than [`MAX_ULPS`] from it.
    Ulps,
}

/// One disagreement: the case, the object's index in the case's list of meshes, the face.
#[derive(Clone, Debug)]
struct Disagreement {
    case: String,
    object: usize,
    face: usize,
    kind: Kind,
    detail: String,
}

impl std::fmt::Display for Disagreement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: mesh {} face {}: {:?}: {}",
            self.case, self.object, self.face, self.kind, self.detail
        )
    }
}

/// What a comparison found.
#[derive(Debug, Default)]
struct Outcome {
    disagreements: Vec<Disagreement>,
    faces: usize,
    edge_on: usize,
    statuses: BTreeMap<&'static str, usize>,
    cells: usize,
    /// Vertices matched to the picture of an input vertex, and their largest error (in ulps
    /// of the scene's scale).
    input_vertices: usize,
    worst_input: f64,
    /// Vertices matched to an exact crossing, and their largest error (likewise).
    crossing_vertices: usize,
    worst_crossing: f64,
    /// The largest error of a matched vertex in ulps of its exact coordinate (of the scene's
    /// scale for an exact 0), for information: see the module docs.
    worst_per_coordinate: f64,
}

impl Outcome {
    fn add(&mut self, o: Outcome) {
        self.disagreements.extend(o.disagreements);
        self.faces += o.faces;
        self.edge_on += o.edge_on;
        for (k, n) in o.statuses {
            *self.statuses.entry(k).or_insert(0) += n;
        }
        self.cells += o.cells;
        self.input_vertices += o.input_vertices;
        self.worst_input = self.worst_input.max(o.worst_input);
        self.crossing_vertices += o.crossing_vertices;
        self.worst_crossing = self.worst_crossing.max(o.worst_crossing);
        self.worst_per_coordinate = self.worst_per_coordinate.max(o.worst_per_coordinate);
    }
}

fn status_name(s: Status) -> &'static str {
    match s {
        Status::Visible => "visible",
        Status::Hidden => "hidden",
        Status::Mixed => "mixed",
    }
}

/// The rings of some polygons, without their closing points.
fn rings(polygons: &MultiPolygon<f64>) -> Vec<Vec<[f64; 2]>> {
    polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|r| {
            let mut points: Vec<[f64; 2]> = r.coords().map(|c| [c.x, c.y]).collect();
            if points.len() > 1 && points.first() == points.last() {
                points.pop();
            }
            points
        })
        .collect()
}

/// Whether `ring` is `face` (bit for bit), from any start, either way round.
fn same_ring(ring: &[[f64; 2]], face: &[[f64; 2]]) -> bool {
    let n = face.len();
    let bits = |p: &[f64; 2]| [p[0].to_bits(), p[1].to_bits()];
    let r: Vec<[u64; 2]> = ring.iter().map(bits).collect();
    let f: Vec<[u64; 2]> = face.iter().map(bits).collect();
    r.len() == n
        && (0..n).any(|s| {
            (0..n).all(|i| r[i] == f[(s + i) % n]) || (0..n).all(|i| r[i] == f[(s + n - i) % n])
        })
}

/// The error of a vertex against an exact point, per coordinate, in ulps of the scene's scale
/// (`unit`).
fn vertex_error(p: [f64; 2], exact: &P2, unit: &Q) -> f64 {
    (0..2)
        .map(|k| ((q(p[k]) - &exact[k]).abs() / unit).to_f64().unwrap())
        .fold(0.0, f64::max)
}

/// What a stray vertex `ring[i]` is part of: a ring of no area (within `tolerance`), a spike
/// (collinear with its neighbours, outside the segment between them), a needless vertex on an
/// edge (collinear, between them), or a corner where none should be.
fn stray_shape(ring: &[[f64; 2]], i: usize, tolerance: f64) -> &'static str {
    let n = ring.len();
    let area = (0..n)
        .map(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        .abs()
        / 2.0;
    if area <= tolerance {
        return "a ring without area";
    }
    let (a, p, b) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
    let (d, e) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let length2 = d[0] * d[0] + d[1] * d[1];
    let cross = d[0] * e[1] - d[1] * e[0];
    if cross.abs() > 1e-12 * length2.max(e[0] * e[0] + e[1] * e[1]) {
        return "a corner";
    }
    let t = (d[0] * e[0] + d[1] * e[1]) / length2;
    if (0.0..=1.0).contains(&t) {
        "on an edge"
    } else {
        "a spike"
    }
}

/// Compares the library's reports with the exact answers.
fn compare(case: &str, want: &Reference, got: &[FaceReport]) -> Outcome {
    let mut out = Outcome::default();
    let disagree = |out: &mut Outcome, object: usize, face: usize, kind: Kind, detail: String| {
        out.disagreements.push(Disagreement {
            case: case.to_string(),
            object,
            face,
            kind,
            detail,
        })
    };
    let index = |id: ObjectId| want.ids.iter().position(|&i| i == id).unwrap_or(usize::MAX);
    let mut reports: BTreeMap<(ObjectId, usize), &FaceReport> = BTreeMap::new();
    for r in got {
        if reports.insert((r.object, r.face), r).is_some() {
            disagree(
                &mut out,
                index(r.object),
                r.face,
                Kind::Report,
                "reported twice".into(),
            );
        }
    }
    for r in got {
        if !want
            .faces
            .iter()
            .any(|e| (e.object, e.face) == (r.object, r.face))
        {
            disagree(
                &mut out,
                index(r.object),
                r.face,
                Kind::Report,
                "no such face".into(),
            );
        }
    }
    let area_tolerance = AREA_TOLERANCE * want.largest_area;
    let near = 1e-9 * want.scale.max(f64::MIN_POSITIVE);
    let unit = ulp_of(&q(want.scale.max(f64::MIN_POSITIVE)));
    for e in &want.faces {
        let (object, face) = (index(e.object), e.face);
        let Some(r) = reports.get(&(e.object, e.face)) else {
            disagree(&mut out, object, face, Kind::Report, "no report".into());
            continue;
        };
        out.faces += 1;
        out.cells += e.cells.1;
        let v = &r.visible;
        if e.edge_on || v.edge_on {
            out.edge_on += 1;
            if !(e.edge_on && v.edge_on && v.status == Status::Visible && v.polygons.0.is_empty()) {
                let detail = format!(
                    "exactly edge-on: {}; reported edge-on: {}, {:?}, {} polygons",
                    e.edge_on,
                    v.edge_on,
                    v.status,
                    v.polygons.0.len()
                );
                disagree(&mut out, object, face, Kind::EdgeOn, detail);
            }
            continue;
        }
        *out.statuses.entry(status_name(e.status)).or_insert(0) += 1;
        let area = v.polygons.unsigned_area();
        if v.status != e.status {
            let detail = format!(
                "reported {:?} (visible area {area:e}), exactly {:?} ({} of {} cells visible, \
                 visible area {:e})",
                v.status, e.status, e.cells.0, e.cells.1, e.area
            );
            disagree(&mut out, object, face, Kind::Status, detail);
        }
        if (area - e.area).abs() > area_tolerance {
            let detail = format!(
                "visible area {area:e}, exactly {:e} (tolerance {area_tolerance:e})",
                e.area
            );
            disagree(&mut out, object, face, Kind::Area, detail);
        }
        let rs = rings(&v.polygons);
        let shape = match v.status {
            Status::Visible => {
                let whole = &want.pictures[&(e.object, e.face)];
                (rs.len() != 1 || v.polygons.0.len() != 1 || !same_ring(&rs[0], whole)).then(|| {
                    format!("VISIBLE with polygons {rs:?}, not the face's picture {whole:?}")
                })
            }
            Status::Hidden => (!rs.is_empty()).then(|| format!("HIDDEN with polygons {rs:?}")),
            Status::Mixed => rs.is_empty().then(|| "MIXED without polygons".to_string()),
        };
        if let Some(detail) = shape {
            disagree(&mut out, object, face, Kind::Shape, detail);
        }
        let (mut stray, mut off) = (Vec::new(), Vec::new());
        for (ring, i) in rs.iter().flat_map(|r| (0..r.len()).map(move |i| (r, i))) {
            let p = &ring[i];
            let best = e
                .vertices
                .iter()
                .filter(|c| {
                    (c.approx[0] - p[0]).abs() <= near && (c.approx[1] - p[1]).abs() <= near
                })
                .map(|c| (vertex_error(*p, &c.exact, &unit), c))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            match best {
                None => stray.push(format!("{p:?} ({})", stray_shape(ring, i, area_tolerance))),
                Some((error, c)) if error <= MAX_ULPS => {
                    if c.input {
                        out.input_vertices += 1;
                        out.worst_input = out.worst_input.max(error);
                    } else {
                        out.crossing_vertices += 1;
                        out.worst_crossing = out.worst_crossing.max(error);
                    }
                    out.worst_per_coordinate = out
                        .worst_per_coordinate
                        .max(ulps2(*p, &c.exact, want.scale));
                }
                Some((error, c)) => off.push(format!(
                    "{p:?}: {error:.3} ulps from {} {:?}",
                    if c.input { "input vertex" } else { "crossing" },
                    c.approx
                )),
            }
        }
        if !stray.is_empty() {
            let detail = format!(
                "{} of {} vertices near no exact visible vertex: {} (reported {:?}, visible area \
                 {area:e}; exactly {:?}, {:e})",
                stray.len(),
                rs.iter().map(Vec::len).sum::<usize>(),
                stray.join(", "),
                v.status,
                e.status,
                e.area
            );
            disagree(&mut out, object, face, Kind::Stray, detail);
        }
        if !off.is_empty() {
            disagree(&mut out, object, face, Kind::Ulps, off.join("; "));
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Scenes.

/// The axis-aligned box `[lo, hi]` (integer corners in the lattice scenes).
fn lattice_box(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    cuboid_at(
        [0, 1, 2].map(|k| hi[k] - lo[k]),
        [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0),
    )
}

fn ortho(d: [f64; 3]) -> View {
    let up = if d[0] == 0.0 && d[1] == 0.0 {
        Vector3::y()
    } else {
        Vector3::z()
    };
    View::orthographic(Vector3::new(d[0], d[1], d[2]), up).unwrap()
}

fn perspective(eye: [f64; 3], target: [f64; 3]) -> View {
    View::perspective(
        Point3::new(eye[0], eye[1], eye[2]),
        Point3::new(target[0], target[1], target[2]),
        Vector3::z(),
        40.0,
    )
    .unwrap()
}

/// The pass on `meshes` from `view` against the exact reference.
fn run(case: &str, meshes: &[Mesh], view: &View) -> Outcome {
    let (scene, ids) = scene_and_ids(meshes);
    let want = reference(&scene, &ids, view);
    let got = visible_surfaces(&scene, view).unwrap();
    compare(case, &want, &got)
}

/// Runs every case, prints a summary and checks that there is no disagreement.
fn check_cases(title: &str, cases: &[Case]) -> Outcome {
    let mut total = Outcome::default();
    for (case, meshes, view) in cases {
        total.add(run(case, meshes, view));
    }
    println!(
        "{title}: {} cases, {} faces ({} edge-on, {:?}), {} exact cells; vertices within ulps \
         of the scale: {} input vertices {:.3}, {} crossings {:.3}; per coordinate {:.3e} ulps; \
         {} disagreements",
        cases.len(),
        total.faces,
        total.edge_on,
        total.statuses,
        total.cells,
        total.input_vertices,
        total.worst_input,
        total.crossing_vertices,
        total.worst_crossing,
        total.worst_per_coordinate,
        total.disagreements.len()
    );
    for d in &total.disagreements {
        println!("  {d}");
    }
    assert!(
        total.disagreements.is_empty(),
        "{} disagreements with the exact reference:\n{}",
        total.disagreements.len(),
        total
            .disagreements
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("\n")
    );
    total
}

/// (a) The cube and the box partly behind it (as in `hidden_exact`).
fn two_boxes() -> Vec<Mesh> {
    vec![
        solids::cube(2.0).unwrap(),
        cuboid_at([3.0, 1.5, 2.5], [-2.25, -1.0, -3.5]),
    ]
}

/// A named scene and view.
type Case = (String, Vec<Mesh>, View);

fn two_boxes_cases() -> Vec<Case> {
    [[-1.0, -2.0, -3.0], [2.0, -1.0, -0.5], [-0.3, -0.7, 1.9]]
        .into_iter()
        .map(|d| (format!("two boxes {d:?}"), two_boxes(), ortho(d)))
        .collect()
}

#[test]
fn box_partly_behind_another() {
    let total = check_cases("two boxes", &two_boxes_cases());
    assert!(total.statuses.get("mixed").copied().unwrap_or(0) >= 2);
}

/// (b) A long thin rod through a cube, in and out through opposite faces (as in
/// `hidden_exact`), and a bar through an octahedron.
fn crossing_cases() -> Vec<Case> {
    let rod = parallelepiped(
        [-2.5, -0.375, -0.25],
        [5.0, 0.5, 0.25],
        [0.125, 0.5, 0.0625],
        [-0.0625, 0.125, 0.5],
    );
    let cube = solids::cube(2.0).unwrap();
    let octahedron = solids::octahedron(3.0).unwrap();
    let bar = cuboid_at([4.0, 0.5, 0.75], [0.25, 0.125, 0.5]);
    let mut cases = Vec::new();
    for d in [[-1.0, -2.0, -3.0], [0.5, 1.0, -0.25], [-1.0, 0.25, 0.5]] {
        cases.push((
            format!("rod through cube {d:?}"),
            vec![cube.clone(), rod.clone()],
            ortho(d),
        ));
        cases.push((
            format!("bar through octahedron {d:?}"),
            vec![octahedron.clone(), bar.clone()],
            ortho(d),
        ));
    }
    cases
}

#[test]
fn faces_crossing_in_depth() {
    let total = check_cases("crossing in depth", &crossing_cases());
    assert!(total.statuses.get("mixed").copied().unwrap_or(0) >= 6);
}

/// (c) Three boxes in perspective.
fn perspective_cases() -> Vec<Case> {
    let meshes = vec![
        solids::cube(2.0).unwrap(),
        cuboid_at([1.0, 3.0, 1.5], [-0.5, 3.0, -1.5]),
        cuboid_at([0.5, 0.75, 0.5], [1.5, -1.25, 1.75]),
    ];
    [
        ([7.0, -9.0, 11.0], [0.0, 0.0, 0.0]),
        ([4.0, -5.0, 3.0], [0.0, 0.0, 0.0]),
        ([-6.0, 7.5, 2.5], [0.25, 0.5, -0.5]),
    ]
    .into_iter()
    .map(|(e, t)| {
        (
            format!("three boxes from {e:?}"),
            meshes.clone(),
            perspective(e, t),
        )
    })
    .collect()
}

#[test]
fn three_boxes_in_perspective() {
    let total = check_cases("three boxes in perspective", &perspective_cases());
    assert!(total.statuses.get("mixed").copied().unwrap_or(0) >= 2);
}

/// The lattice scenes: axis-aligned boxes with integer corners touching, stacked, sharing
/// coplanar faces and passing through each other.
fn lattice_scenes() -> Vec<(&'static str, Vec<Mesh>)> {
    let slab = lattice_box([0.0, 0.0, 0.0], [4.0, 4.0, 1.0]);
    vec![
        (
            "post through slab",
            vec![slab.clone(), lattice_box([1.0, 1.0, -1.0], [2.0, 2.0, 3.0])],
        ),
        (
            "box resting on box, neighbour sharing a face",
            vec![
                slab.clone(),
                lattice_box([1.0, 1.0, 1.0], [3.0, 3.0, 2.0]),
                lattice_box([4.0, 0.0, 0.0], [5.0, 4.0, 1.0]),
            ],
        ),
        (
            "wall through slab",
            vec![slab.clone(), lattice_box([2.0, 0.0, -1.0], [3.0, 4.0, 2.0])],
        ),
        (
            "wall through a slab's edge",
            vec![
                lattice_box([0.0, 0.0, 0.0], [3.0, 4.0, 1.0]),
                lattice_box([2.0, 0.0, -1.0], [3.0, 4.0, 2.0]),
                lattice_box([3.0, 1.0, 0.0], [5.0, 3.0, 1.0]),
            ],
        ),
        (
            "stack of unit cubes",
            vec![
                lattice_box([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
                lattice_box([0.0, 0.0, 1.0], [1.0, 1.0, 2.0]),
                lattice_box([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
                lattice_box([1.0, 1.0, 0.0], [2.0, 2.0, 2.0]),
            ],
        ),
    ]
}

/// The lattice views, named: along lattice diagonals and axes, and from integer eyes (some on
/// the boxes' planes, which see those faces edge-on).
fn lattice_views() -> Vec<(String, View)> {
    let mut views: Vec<(String, View)> = [
        [1.0, 1.0, 1.0],
        [-1.0, -1.0, -1.0],
        [1.0, 2.0, 3.0],
        [-1.0, -2.0, -3.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.0, -1.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ]
    .into_iter()
    .map(|d| (format!("along {d:?}"), ortho(d)))
    .collect();
    views.extend(
        [
            ([9.0, -7.0, 6.0], [2.0, 2.0, 1.0]),
            ([3.0, -6.0, 1.0], [2.0, 2.0, 1.0]),
            ([2.0, -8.0, 2.0], [2.0, 2.0, 0.0]),
            ([-5.0, 6.0, 8.0], [2.0, 2.0, 0.0]),
        ]
        .into_iter()
        .map(|(e, t)| (format!("from {e:?} to {t:?}"), perspective(e, t))),
    );
    views
}

/// (d) The lattice scenes from every lattice view.
fn lattice_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for (name, meshes) in lattice_scenes() {
        for (view_name, view) in lattice_views() {
            cases.push((format!("{name}, {view_name}"), meshes.clone(), view));
        }
    }
    cases
}

#[test]
fn lattice_scenes_touching_and_interpenetrating() {
    let total = check_cases("lattice scenes", &lattice_cases());
    assert!(total.edge_on > 0);
}

/// A random parallelepiped with dyadic vertices: a box of random size turned by a random
/// rotation rounded to sixteenths (so its faces are exactly planar), anywhere in `[-2, 2]^3`.
fn random_parallelepiped(rng: &mut SplitMix64) -> Mesh {
    let axis = nalgebra::Unit::new_normalize(rng.vector(1.0) + Vector3::new(1e-3, 0.0, 0.0));
    let r = nalgebra::Rotation3::from_axis_angle(&axis, rng.range(0.0, 6.3));
    let m = r.matrix().map(|x| (x * 16.0).round() / 16.0);
    let size = [0, 1, 2].map(|_| rng.int(4, 20) / 8.0);
    let mut cols = [0, 1, 2].map(|k| [0, 1, 2].map(|i| m[(i, k)] * size[k]));
    if m.determinant() < 0.0 {
        cols.swap(1, 2);
    }
    let centre = [0, 1, 2].map(|_| rng.int(-16, 16) / 8.0);
    let p0 = [0, 1, 2].map(|i| centre[i] - (cols[0][i] + cols[1][i] + cols[2][i]) / 2.0);
    parallelepiped(p0, cols[0], cols[1], cols[2])
}

/// A randomly turned octahedron (triangles: planar however rounded).
fn random_octahedron(rng: &mut SplitMix64) -> Mesh {
    let axis = nalgebra::Unit::new_normalize(rng.vector(1.0) + Vector3::new(0.0, 1e-3, 0.0));
    let r = nalgebra::Rotation3::from_axis_angle(&axis, rng.range(0.0, 6.3));
    let t = nalgebra::Translation3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), 0.0);
    let m = nalgebra::Matrix4::from(t) * r.to_homogeneous();
    solids::octahedron(rng.range(1.5, 3.0))
        .unwrap()
        .transformed(&m)
        .unwrap()
}

/// A random box with integer corners in `[0, 4]^3`.
fn random_lattice_box(rng: &mut SplitMix64) -> Mesh {
    let lo = [0, 1, 2].map(|_| rng.int(0, 3));
    let hi = [0, 1, 2].map(|k| (lo[k] + rng.int(1, 2)).min(4.0));
    lattice_box(lo, hi)
}

/// A random general view: orthographic from any direction, or perspective from 12 to 18 away.
fn random_view(rng: &mut SplitMix64) -> View {
    if rng.below(2) == 0 {
        let d = rng.vector(1.0) + Vector3::new(0.0, 0.0, 1e-3);
        View::orthographic(d, Vector3::z()).unwrap()
    } else {
        let d = rng.vector(1.0) + Vector3::new(0.0, 0.0, 1e-3);
        let eye = Point3::from(d.normalize() * rng.range(12.0, 18.0));
        let target = Point3::from(rng.vector(1.0));
        View::perspective(eye, target, Vector3::z(), rng.range(30.0, 60.0)).unwrap()
    }
}

/// (e) Random scenes: turned boxes and octahedra from random views, and lattice boxes from
/// lattice views.
fn random_cases() -> Vec<Case> {
    let mut rng = SplitMix64(0x005e_ed0f_5a7f);
    let lattice = lattice_views();
    let mut cases = Vec::new();
    for case in 0..24 {
        let count = 2 + rng.below(3);
        let (meshes, view): (Vec<Mesh>, View) = if case % 2 == 0 {
            let meshes = (0..count)
                .map(|_| {
                    if rng.below(4) == 0 {
                        random_octahedron(&mut rng)
                    } else {
                        random_parallelepiped(&mut rng)
                    }
                })
                .collect();
            (meshes, random_view(&mut rng))
        } else {
            let meshes = (0..count).map(|_| random_lattice_box(&mut rng)).collect();
            (meshes, lattice[rng.below(lattice.len())].1.clone())
        };
        cases.push((format!("random case {case}"), meshes, view));
    }
    cases
}

#[test]
fn random_scenes() {
    check_cases("random scenes", &random_cases());
}

/// (f) A convex solid alone: its faces turned away from the eye are hidden exactly by the union
/// of those turned towards it (no one of which hides a whole face). The first seven cases are
/// the minimal forms of faces of the scenes above that the union of other faces hides.
fn single_solid_cases() -> Vec<Case> {
    let from = |e: [f64; 3], t: [f64; 3]| perspective(e, t);
    vec![
        (
            "octahedron alone along [-1.0, -2.0, -3.0]",
            solids::octahedron(3.0).unwrap(),
            ortho([-1.0, -2.0, -3.0]),
        ),
        (
            "bar alone along [-1.0, -2.0, -3.0]",
            cuboid_at([4.0, 0.5, 0.75], [0.25, 0.125, 0.5]),
            ortho([-1.0, -2.0, -3.0]),
        ),
        (
            "small box alone from [4.0, -5.0, 3.0]",
            cuboid_at([0.5, 0.75, 0.5], [1.5, -1.25, 1.75]),
            from([4.0, -5.0, 3.0], [0.0; 3]),
        ),
        (
            "box [4, 5]x[0, 4]x[0, 1] alone from [2.0, -8.0, 2.0]",
            lattice_box([4.0, 0.0, 0.0], [5.0, 4.0, 1.0]),
            from([2.0, -8.0, 2.0], [2.0, 2.0, 0.0]),
        ),
        (
            "box [0, 1]x[3, 4]x[0, 2] alone from [2.0, -8.0, 2.0]",
            lattice_box([0.0, 3.0, 0.0], [1.0, 4.0, 2.0]),
            from([2.0, -8.0, 2.0], [2.0, 2.0, 0.0]),
        ),
        (
            "box [1, 2]x[0, 1]x[0, 1] alone from [9.0, -7.0, 6.0]",
            lattice_box([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
            from([9.0, -7.0, 6.0], [2.0, 2.0, 1.0]),
        ),
        (
            "box [1, 2]x[2, 4]x[1, 2] alone along [1.0, -1.0, -1.0]",
            lattice_box([1.0, 2.0, 1.0], [2.0, 4.0, 2.0]),
            ortho([1.0, -1.0, -1.0]),
        ),
        (
            "cube alone along [-1.0, -2.0, -3.0]",
            solids::cube(2.0).unwrap(),
            ortho([-1.0, -2.0, -3.0]),
        ),
        (
            "tetrahedron alone from [4.0, -5.0, 3.0]",
            solids::tetrahedron(2.0).unwrap(),
            from([4.0, -5.0, 3.0], [0.0; 3]),
        ),
        (
            "icosahedron alone along [0.3, -1.0, -0.45]",
            solids::icosahedron(2.0).unwrap(),
            ortho([0.3, -1.0, -0.45]),
        ),
        (
            "icosahedron alone from [4.0, -5.0, 3.0]",
            solids::icosahedron(2.0).unwrap(),
            from([4.0, -5.0, 3.0], [0.0; 3]),
        ),
    ]
    .into_iter()
    .map(|(name, mesh, view)| (name.to_string(), vec![mesh], view))
    .collect()
}

#[test]
fn a_convex_solid_alone_hides_its_back_faces() {
    let total = check_cases("single solids", &single_solid_cases());
    // Every face is VISIBLE or HIDDEN exactly: a face turned away is hidden, one turned
    // towards the eye is whole.
    assert_eq!(total.statuses.get("mixed"), None);
}

/// VISOBJ(A, B) for every ordered pair of meshes (A = B included) of every case above agrees
/// with the exact answer.
#[test]
fn visobj_agrees_with_the_exact_answer() {
    let mut statuses: BTreeMap<&'static str, usize> = BTreeMap::new();
    let mut wrong = Vec::new();
    for (case, meshes, view) in two_boxes_cases()
        .into_iter()
        .chain(crossing_cases())
        .chain(perspective_cases())
        .chain(lattice_cases())
        .chain(random_cases())
    {
        let (scene, ids) = scene_and_ids(&meshes);
        for &a in &ids {
            for &b in &ids {
                let want = expect_visobj(&scene, &ids, &view, a, b);
                let got = kepler::surfaces::visobj(&scene, a, b, &view).unwrap();
                *statuses.entry(status_name(want)).or_insert(0) += 1;
                if got != want {
                    let index = |x| ids.iter().position(|&i| i == x).unwrap_or(usize::MAX);
                    wrong.push(format!(
                        "{case}: VISOBJ({}, {}) is {got:?}, exactly {want:?}",
                        index(a),
                        index(b)
                    ));
                }
            }
        }
    }
    println!("VISOBJ: {statuses:?}");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // All three answers occur (HIDDEN rarely: B has faces turned away from the eye).
    assert_eq!(statuses.len(), 3, "{statuses:?}");
}

// ---------------------------------------------------------------------------------------------
// The comparison itself can fail.

#[test]
fn the_comparison_rejects_wrong_answers() {
    let (scene, ids) = scene_and_ids(two_boxes());
    let view = ortho([-1.0, -2.0, -3.0]);
    let want = reference(&scene, &ids, &view);
    let good = visible_surfaces(&scene, &view).unwrap();
    let kinds = |reports: &[FaceReport]| -> Vec<Kind> {
        let mut k: Vec<Kind> = compare("probe", &want, reports)
            .disagreements
            .iter()
            .map(|d| d.kind)
            .collect();
        k.sort();
        k.dedup();
        k
    };
    assert_eq!(kinds(&good), []);
    // The reference by hand: the cube's three far faces and the back box's three far faces
    // are hidden; the cube's near faces whole; the back box's near faces partly hidden.
    let count = |s: Status| want.faces.iter().filter(|e| e.status == s).count();
    assert_eq!(
        (
            count(Status::Visible),
            count(Status::Hidden),
            count(Status::Mixed)
        ),
        (3, 6, 3)
    );

    let mixed = good
        .iter()
        .position(|r| r.visible.status == Status::Mixed)
        .expect("a MIXED face");
    let visible = good
        .iter()
        .position(|r| r.visible.status == Status::Visible)
        .expect("a VISIBLE face");
    // A vertex of the MIXED face's polygons that is the picture of an input vertex, and one
    // that is a crossing.
    let inputs: Vec<[f64; 2]> = want.pictures.values().flatten().copied().collect();
    let ring = &rings(&good[mixed].visible.polygons)[0];
    let corner = ring
        .iter()
        .position(|p| inputs.contains(p))
        .expect("a corner");
    let crossing = ring
        .iter()
        .position(|p| !inputs.contains(p))
        .expect("a crossing");
    let moved = |f: usize, i: usize, by: &dyn Fn(f64) -> f64| {
        let mut w = good.clone();
        let p = &mut w[f].visible.polygons.0[0];
        let mut coords: Vec<geo::Coord<f64>> = p.exterior().coords().copied().collect();
        coords[i].x = by(coords[i].x);
        if i == 0 {
            let last = coords.len() - 1;
            coords[last].x = coords[0].x;
        }
        *p = geo::Polygon::new(geo::LineString::new(coords), p.interiors().to_vec());
        w
    };
    let ulp = ulp_of(&q(want.scale)).to_f64().unwrap();
    let steps = |n: usize| {
        move |x: f64| (0..n).fold(x, |x, _| if x > 0.0 { x.next_up() } else { x.next_down() })
    };
    // A corner 1 ulp of the scale off is accepted, 3 are not.
    assert_eq!(kinds(&moved(mixed, corner, &|x| x + ulp)), []);
    assert_eq!(
        kinds(&moved(mixed, corner, &|x| x + 3.0 * ulp)),
        [Kind::Ulps]
    );
    // A crossing 1e-6 off is near no exact vertex.
    assert_eq!(
        kinds(&moved(mixed, crossing, &|x| x + 1e-6)),
        [Kind::Area, Kind::Stray]
    );
    // A crossing 3 ulps of the scale off is too far.
    assert_eq!(
        kinds(&moved(mixed, crossing, &|x| x + 3.0 * ulp)),
        [Kind::Ulps]
    );
    // A VISIBLE face must be its picture bit for bit.
    assert_eq!(kinds(&moved(visible, 1, &steps(1))), [Kind::Shape]);
    // Wrong statuses.
    let mut w = good.clone();
    w[mixed].visible.status = Status::Hidden;
    assert_eq!(kinds(&w), [Kind::Status, Kind::Shape]);
    let mut w = good.clone();
    w[visible].visible.status = Status::Mixed;
    assert_eq!(kinds(&w), [Kind::Status]);
    let hidden = good
        .iter()
        .position(|r| r.visible.status == Status::Hidden)
        .expect("a HIDDEN face");
    let mut w = good.clone();
    w[hidden].visible.status = Status::Mixed;
    assert_eq!(kinds(&w), [Kind::Status, Kind::Shape]);
    // A HIDDEN face given a sliver: its area is within the tolerance, its vertices are not.
    let mut w = good.clone();
    w[hidden].visible = w[mixed].visible.clone();
    w[hidden].visible.status = Status::Mixed;
    let sliver = rings(&good[mixed].visible.polygons)[0][..3].to_vec();
    let thin: Vec<geo::Coord<f64>> = [sliver[0], sliver[1], [sliver[1][0], sliver[1][1].next_up()]]
        .iter()
        .map(|&[x, y]| geo::Coord { x, y })
        .collect();
    w[hidden].visible.polygons =
        MultiPolygon::new(vec![geo::Polygon::new(geo::LineString::new(thin), vec![])]);
    let k = kinds(&w);
    assert!(k.contains(&Kind::Status) && k.contains(&Kind::Stray) && !k.contains(&Kind::Area));
    // A missing piece, a face missing, a face claimed edge-on.
    let mut w = good.clone();
    w[mixed].visible.polygons.0.clear();
    assert_eq!(kinds(&w), [Kind::Shape, Kind::Area]);
    assert!(kinds(&w).is_sorted());
    let mut w = good.clone();
    w.remove(mixed);
    assert_eq!(kinds(&w), [Kind::Report]);
    let mut w = good.clone();
    w[visible].visible.edge_on = true;
    assert_eq!(kinds(&w), [Kind::EdgeOn]);
}

// ---------------------------------------------------------------------------------------------
// The same bits under mirroring and power-of-two scaling.

/// A view by its parameters, so that it can be mirrored and scaled with the scene.
#[derive(Clone, Copy, Debug)]
enum ViewSpec {
    /// Orthographic along a direction, `z` up.
    Along([f64; 3]),
    /// Perspective from an eye towards a target, `z` up, with a field of view in degrees.
    From([f64; 3], [f64; 3], f64),
}

impl ViewSpec {
    fn random(rng: &mut SplitMix64) -> ViewSpec {
        let d = rng.vector(1.0) + Vector3::new(0.0, 0.0, 1e-3);
        if rng.below(2) == 0 {
            ViewSpec::Along([d.x, d.y, d.z])
        } else {
            let eye = d.normalize() * rng.range(12.0, 18.0);
            let target = rng.vector(1.0);
            ViewSpec::From(
                [eye.x, eye.y, eye.z],
                [target.x, target.y, target.z],
                rng.range(30.0, 60.0),
            )
        }
    }

    /// The view of the scene mapped by `x ↦ (s_x x, s_y y, s_z z)` (`s` powers of two, or
    /// their negatives).
    fn view(&self, s: [f64; 3]) -> View {
        let map = |p: [f64; 3]| Vector3::new(s[0] * p[0], s[1] * p[1], s[2] * p[2]);
        let up = Vector3::new(0.0, 0.0, s[2].signum());
        match *self {
            // An orthographic view's direction is kept by scaling: only its signs change.
            ViewSpec::Along(d) => View::orthographic(
                Vector3::from(s.map(f64::signum)).component_mul(&Vector3::from(d)),
                up,
            )
            .unwrap(),
            ViewSpec::From(eye, target, fov) => {
                View::perspective(Point3::from(map(eye)), Point3::from(map(target)), up, fov)
                    .unwrap()
            }
        }
    }
}

/// A ring's points, `-0` taken as `0`, from its least point, the way round that makes the
/// second point least: the same for the same points whatever the start and the way round.
fn canonical_ring(points: &[[f64; 2]]) -> Vec<[u64; 2]> {
    let bits: Vec<[u64; 2]> = points
        .iter()
        .map(|p| p.map(|x| (x + 0.0).to_bits()))
        .collect();
    let n = bits.len();
    let forward = |s: usize| -> Vec<[u64; 2]> { (0..n).map(|i| bits[(s + i) % n]).collect() };
    let backward = |s: usize| -> Vec<[u64; 2]> { (0..n).map(|i| bits[(s + n - i) % n]).collect() };
    (0..n)
        .flat_map(|s| [forward(s), backward(s)])
        .min()
        .unwrap_or_default()
}

/// Every face's status and its polygons' rings (outer or hole, canonical), with every picture
/// point mapped by `picture` and every texture point by `texture` first.
type Faces = BTreeMap<
    (usize, usize),
    (
        Status,
        BTreeSet<(bool, Vec<[u64; 2]>)>,
        Option<BTreeSet<(bool, Vec<[u64; 2]>)>>,
    ),
>;

fn faces_of(
    meshes: &[Mesh],
    view: &View,
    picture: impl Fn([f64; 2]) -> [f64; 2],
    texture: Option<&dyn Fn([f64; 2]) -> [f64; 2]>,
) -> Faces {
    let (scene, ids) = scene_and_ids(meshes);
    let rings = |polygons: &MultiPolygon<f64>, f: &dyn Fn([f64; 2]) -> [f64; 2]| {
        polygons
            .iter()
            .flat_map(|p| {
                std::iter::once((true, p.exterior()))
                    .chain(p.interiors().iter().map(|r| (false, r)))
            })
            .map(|(outer, r)| {
                let mut points: Vec<[f64; 2]> = r.coords().map(|c| f([c.x, c.y])).collect();
                points.pop();
                (outer, canonical_ring(&points))
            })
            .collect::<BTreeSet<_>>()
    };
    visible_surfaces(&scene, view)
        .unwrap()
        .iter()
        .map(|r| {
            let object = ids.iter().position(|&i| i == r.object).unwrap();
            (
                (object, r.face),
                (
                    r.visible.status,
                    rings(&r.visible.polygons, &picture),
                    texture.map(|t| rings(&r.texture, t)),
                ),
            )
        })
        .collect()
}

/// A random prism, turned by a rotation rounded to sixteenths (so its faces stay exactly
/// planar): over a convex polygon with dyadic vertices (caps of 3 to 8 corners whose triangles
/// differ in area), or over an L-shape (caps that are not convex).
fn random_prism(rng: &mut SplitMix64) -> Mesh {
    use geo::ConvexHull;
    let outline = if rng.below(4) == 0 {
        let (a, b) = (rng.int(2, 6) / 4.0, rng.int(1, 3) / 4.0);
        geo::Polygon::new(
            geo::LineString::from(vec![(0.0, 0.0), (a, 0.0), (a, b), (b, b), (b, a), (0.0, a)]),
            vec![],
        )
    } else {
        let points: Vec<geo::Point<f64>> = (0..3 + rng.below(6))
            .map(|_| geo::Point::new(rng.int(-12, 12) / 8.0, rng.int(-12, 12) / 8.0))
            .collect();
        geo::MultiPoint::new(points).convex_hull()
    };
    let prism = solids::prism(&outline, rng.int(2, 12) / 8.0)
        .unwrap_or_else(|_| lattice_box([0.0; 3], [1.0, 1.5, 0.75]));
    let axis = nalgebra::Unit::new_normalize(rng.vector(1.0) + Vector3::new(1e-3, 0.0, 0.0));
    let r = nalgebra::Rotation3::from_axis_angle(&axis, rng.range(0.0, 6.3));
    let m = r.matrix().map(|x| (x * 16.0).round() / 16.0);
    let t = [0, 1, 2].map(|_| rng.int(-16, 16) / 8.0);
    let mut h = nalgebra::Matrix4::identity();
    h.fixed_view_mut::<3, 3>(0, 0).copy_from(&m);
    h[(0, 3)] = t[0];
    h[(1, 3)] = t[1];
    h[(2, 3)] = t[2];
    prism.transformed(&h).unwrap_or(prism)
}

/// Random scenes of turned boxes, prisms and octahedra (and of lattice boxes), each from a random view,
/// mirrored in each axis and scaled by powers of two from `2^-40` to `2^40`: the same statuses
/// and the same polygons, bit for bit (the picture of a mirrored scene is mirrored in `x`; the
/// texture coordinates of a scaled scene are scaled).
#[test]
fn the_polygons_are_the_same_bits_mirrored_and_scaled() {
    let mut rng = SplitMix64(0x0000_5eed_0b17);
    let mut mixed = 0;
    for case in 0..400 {
        let count = 2 + rng.below(3);
        let meshes: Vec<Mesh> = (0..count)
            .map(|_| match (case % 2, rng.below(4)) {
                (1, _) => random_lattice_box(&mut rng),
                (_, 0) => random_octahedron(&mut rng),
                (_, 1) => random_parallelepiped(&mut rng),
                _ => random_prism(&mut rng),
            })
            .collect();
        let spec = ViewSpec::random(&mut rng);
        let transformed = |s: [f64; 3]| -> Vec<Mesh> {
            let m = nalgebra::Matrix4::new_nonuniform_scaling(&Vector3::from(s));
            meshes.iter().map(|x| x.transformed(&m).unwrap()).collect()
        };
        let base = faces_of(&meshes, &spec.view([1.0; 3]), |p| p, Some(&|p| p));
        mixed += base.values().filter(|f| f.0 == Status::Mixed).count();
        let perspective = matches!(spec, ViewSpec::From(..));
        for k in [-40, -3, 1, 17, 40] {
            let s = 2f64.powi(k);
            let scene = transformed([s; 3]);
            let picture = if perspective { 1.0 } else { s };
            let scaled = faces_of(
                &scene,
                &spec.view([s; 3]),
                |p| p.map(|x| x / picture),
                Some(&|p| p.map(|x| x / s)),
            );
            assert_eq!(scaled, base, "case {case}, scaled by 2^{k}");
        }
        // Mirrored in each axis, with the view: the picture is mirrored in x (the texture frames
        // of the reversed faces are other frames).
        let base = faces_of(&meshes, &spec.view([1.0; 3]), |p| p, None);
        for axis in 0..3 {
            let mut s = [1.0; 3];
            s[axis] = -1.0;
            let mirrored = faces_of(&transformed(s), &spec.view(s), |[x, y]| [-x, y], None);
            assert_eq!(mirrored, base, "case {case}, mirrored in axis {axis}");
        }
    }
    assert!(mixed > 400, "{mixed} MIXED faces");
}
