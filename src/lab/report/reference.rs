//! A hidden-line reference in exact rational arithmetic: the drawing decided by brute force,
//! slowly and obviously, so that "exact" is a measured claim (issue 15).
//!
//! **What it decides.** A point `m` of a line is *hidden* when some triangle `T` of the scene
//! hides it: `m` lies strictly on the far side of `T`'s plane from the eye, and the line of
//! sight from `m` towards the eye meets the closed triangle `T`. A triangle whose plane
//! contains `m` does not hide it, and a triangle whose plane passes through the eye (seen
//! edge-on, or of zero area) hides nothing: it has no far side. This is the rule the engine
//! states for its VISP queries (see [`crate::hidden`]); here it is applied to every triangle,
//! with nothing skipped that could matter.
//!
//! **How.** Every input double converts exactly to a [`BigRational`]; every sign below is the
//! sign of an exact rational, never of an estimate. For each line `ab`, with `m(t) = a +
//! t·(b − a)`, each triangle `T` gives four affine functions of `m`:
//! - its plane, `n·(m − c₀)` with `n = (c₁ − c₀) × (c₂ − c₀)`, turned so that the eye's side is
//!   positive (the eye's side is `n·(e − c₀)` for an eye point `e`, `n·v` for an eye at
//!   infinity in direction `v`);
//! - for each side `cd`, the plane of sight through it: `det[c − e, d − e, m − e]` for an eye
//!   point (the plane through `e`, `c`, `d`), `det[v, d − c, m − c]` for an eye at infinity (the
//!   plane through `cd` parallel to `v`).
//!
//! When `m` is strictly behind `T`'s plane, the line of sight through `m` crosses that plane at
//! one point `X`, and the three side functions at `m` are the barycentric coordinates of `X`
//! in `T` times one nonzero factor (moving `m` along its line of sight changes none of them);
//! so `X` lies in the closed triangle exactly when no two of them have strictly opposite
//! signs. `T` hides `m(t)` is thus a fixed Boolean combination of the signs of four affine
//! functions of `t`, each of which changes sign at most once along `ab`, where it vanishes:
//! at `t = f(a) / (f(a) − f(b))`. Between consecutive such parameters (over all triangles)
//! nothing changes, so the midpoint of each interval decides the whole interval; since each
//! function is affine, its sign at the midpoint is that of `f(a) + t·(f(b) − f(a))`, taken
//! over a common positive denominator (integers only, no reductions).
//! Consecutive intervals of one line with the same visibility merge into a run, drawn as the
//! picture of its two ends.
//!
//! Three shortcuts leave out triangles that cannot hide any point of the line, each by an
//! exact argument: a triangle with no far side (above); a triangle with neither end of the
//! line strictly behind its plane (an affine function negative somewhere on a segment is
//! negative at an end); and a triangle whose picture's bounding box misses the line's (the
//! picture of a hidden point is the picture of the point `X` of the triangle that hides it;
//! the boxes are of exact rational pictures, and a perspective picture of a triangle in front
//! of the eye is the triangle of its corners' pictures). They save time, not correctness.
//!
//! **Why it is independent of the engine.** The engine decides visibility with floating-point
//! filters backed by exact expansions, Franklin's uniform grid over the pictures to find
//! candidate crossings, contour edges only (a crossing with a non-contour edge cannot change
//! visibility), CBOX and INBOX filters through the object hierarchy, an R-tree of faces near
//! the line of sight, exact orderings of cuts along intersection lines, and the chaining of
//! pieces into polylines. None of that is used here: no filters, no expansions, no grid, no
//! R-tree, no ordering tricks, no notion of contour; every triangle against every line, with
//! every side of every triangle (not just contours) proposing cuts, in a different number
//! system. A bug in any of those parts shows up as a disagreement.
//!
//! **What it shares, and why that is acceptable.** Two things:
//! - The lines to draw: [`strokes`], the engine's classified edges and intersection segments
//!   before visibility. Which edges are silhouettes, creases or smooth, and where faces pierce
//!   each other, is a separate question, checked elsewhere ([`crate::hidden::verify`] and the
//!   tests' oracles); this module measures visibility on the same lines, so that two drawings
//!   can be compared class by class.
//! - The view: the eye ([`View::eye`]) and the picture map's rows and origin
//!   ([`Picture::rows`]), taken as exact. The picture of a point is computed here, in
//!   rationals, and each coordinate rounded once to the nearest double (ties to even) by
//!   `nearest`, one integer division written here. `num-rational`'s own `to_f64` also rounds
//!   correctly in the version locked (0.4.2: the unit tests check both against the two
//!   neighbouring doubles, on ties, subnormals and ratios of large integers), but the
//!   dependency's requirement (`0.4`) admits other releases, and the reference should not
//!   depend on which.
//!
//! **One tolerance, to find where intersection segments lie.** An edge's ends are input
//! vertices, exact. An intersection segment's ends come from [`strokes`] rounded (within
//! `2⁻⁴²` of the magnitude of the points that define them), so the segment between them lies
//! on the two faces that meet along it only up to that rounding. Decided as given, its points
//! would be a hair behind one of its own faces half the time (and hidden by it); and where a
//! face it lies on is nearly edge-on, the plane of sight through that face's side is nearly
//! the face's plane, so whether a neighbouring face hides the segment would be decided by the
//! rounding (a random scene of icosahedra, whose faces are nearly edge-on from `(1, 2, −3)`,
//! showed both). So, for an intersection segment only:
//! - it is put back on its exact line: each end is replaced by the nearest point of the line
//!   where the planes of the two triangles it lies on meet ([`Stroke::planes`], exactly, by
//!   Cramer's rule), so every decision strictly inside it is exact; its ends stay within
//!   about `2⁻⁴²·M` of the engine's (`M` the scene's largest coordinate), and a run of about
//!   that length may appear at an end where the segment leaves a face across an edge;
//! - the planes that pass within `2⁻⁴⁸·M` of both of its ends hide nothing of it, as the
//!   engine's own faces of an intersection line hide nothing (measured as `|n·(p − c₀)| ≤
//!   2⁻⁴⁸·M·|n|₁`: the two planes it lies on contain it exactly; the others are the second
//!   triangles of faces that are not exactly flat, off by the rounding of their corners, or
//!   faces through the same line). `2⁻⁴⁸·M` is far below the features of the stiff scenes
//!   (offsets of `10^k` with unit features up to `k = 14`).
//!
//! The cost is `O(lines × triangles²)` rational operations in the worst case: for scenes of up
//! to a few hundred triangles. A perspective view needs every vertex strictly in front of its
//! eye (the engine would clip to its frustum; the reference does not).

use crate::Error;
use crate::geometry::Point3;
use crate::geometry::exact::ldexp;
use crate::hidden::{Drawing, EdgeClass, Options, Polyline, Stroke, strokes};
use crate::scene::Scene;
use crate::views::{Eye, Picture, View, ViewError};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rayon::prelude::*;
use std::cmp::Ordering;

/// Exact rationals.
type Q = BigRational;

/// A point or vector in exact rationals.
type V = [Q; 3];

/// The drawing of `scene` from `view` decided in exact rational arithmetic, by brute force, on
/// the lines the engine draws ([`strokes`]): see the module documentation. Each run of one
/// visibility along a line is a polyline of two points, the pictures of its ends, each
/// coordinate the exact value rounded once; runs are not chained across lines, and a run whose
/// rounded ends coincide is left out (a drawing holds no segment of zero length). With
/// `options.hidden` false, only visible runs are kept. For scenes of up to a few hundred
/// triangles; a perspective view needs the whole scene strictly in front of its eye.
///
/// ```
/// use kepler::{hidden::{EdgeClass, Options, draw}, scene::Scene, views::View};
/// use kepler::lab::report::reference::reference;
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// // Straight down: the bottom square lies under the top one, hidden.
/// let d = reference(&scene, &View::standard(), &Options::default()).unwrap();
/// assert_eq!(d.length(EdgeClass::Silhouette, false), 4.0);
/// assert_eq!(d.length(EdgeClass::Silhouette, true), 4.0);
/// let engine = draw(&scene, &View::standard(), &Options::default()).unwrap();
/// assert_eq!(engine.length(EdgeClass::Silhouette, false), 4.0);
/// ```
pub fn reference(scene: &Scene, view: &View, options: &Options) -> Result<Drawing, Error> {
    let map = Map::of(view)?;
    let viewer = match view.eye() {
        Eye::Point(e) => Viewer::Point(point(e)?),
        Eye::Infinity(v) => Viewer::Direction(exact([v.x, v.y, v.z])?),
    };
    let mut hiders = Vec::new();
    let mut largest = 0.0f64;
    for (id, mesh) in scene.mesh_objects(scene.roots()) {
        let mut corners = Vec::with_capacity(mesh.vertices().len());
        for (i, p) in mesh.vertices().iter().enumerate() {
            largest = largest.max(p.x.abs()).max(p.y.abs()).max(p.z.abs());
            let x = point(p)?;
            let picture = map.picture(&x).ok_or_else(|| ViewError::NotInFront {
                object: scene.path(id),
                vertex: i,
                point: *p,
            })?;
            corners.push((x, picture));
        }
        for t in mesh.triangles() {
            let [c0, c1, c2] = t.map(|i| &corners[i as usize]);
            let plane = Plane::through([&c0.0, &c1.0, &c2.0]);
            if plane.normal.iter().any(|x| !x.is_zero()) {
                hiders.extend(Hider::of(&plane, [c0, c1, c2], &viewer));
            }
        }
    }
    let slack = rational(ldexp(largest, -48))?;
    let lines = strokes(scene, view, options)?;
    let runs = lines
        .par_iter()
        .map(|s| runs(s, (&hiders, &slack), &map, options.hidden))
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(Drawing {
        polylines: runs.into_iter().flatten().collect(),
        stages: Vec::new(),
    })
}

/// The runs of one line: see [`reference`].
fn runs(
    stroke: &Stroke,
    (hiders, slack): (&[Hider], &Q),
    map: &Map,
    keep_hidden: bool,
) -> Result<Vec<Polyline>, Error> {
    let ends = [point(&stroke.ends[0])?, point(&stroke.ends[1])?];
    let [a, b] = match stroke.planes {
        Some(meet) => {
            let through = |t: &[Point3; 3]| -> Result<Plane, Error> {
                let [c0, c1, c2] = [point(&t[0])?, point(&t[1])?, point(&t[2])?];
                Ok(Plane::through([&c0, &c1, &c2]))
            };
            on_meet(ends, [&through(&meet[0])?, &through(&meet[1])?])
        }
        None => ends,
    };
    if a == b {
        return Ok(Vec::new());
    }
    let behind = || ViewError::Options("the reference draws only scenes in front of the eye");
    let ends = [
        map.picture(&a).ok_or_else(behind)?,
        map.picture(&b).ok_or_else(behind)?,
    ];
    let bounds = span(&ends);
    let forms = hider_forms(stroke, (hiders, slack), [&a, &b], &bounds);
    let (params, spans) = visibility_spans(&forms);
    let mut polylines = Vec::new();
    for (i, j, visible) in spans {
        if !visible && !keep_hidden {
            continue;
        }
        let mut points = Vec::with_capacity(2);
        for t in [&params[i], &params[j]] {
            let p = [0, 1, 2].map(|k| &a[k] + t * (&b[k] - &a[k]));
            points.push(map.picture(&p).ok_or_else(behind)?.map(|x| nearest(&x)));
        }
        if points[0] != points[1] {
            polylines.push(Polyline {
                class: stroke.class,
                visible,
                points,
            });
        }
    }
    Ok(polylines)
}

/// The four affine functions of each triangle that may hide part of the line from `a` to `b`
/// (whose picture lies in `bounds`), valued at `a` and at `b`: its plane (positive on the
/// eye's side), then its three sides' planes of sight.
fn hider_forms(
    stroke: &Stroke,
    (hiders, slack): (&[Hider], &Q),
    [a, b]: [&V; 2],
    bounds: &[[Q; 2]; 2],
) -> Vec<[Along; 4]> {
    let mut forms: Vec<[Along; 4]> = Vec::new();
    for h in hiders {
        if !overlap(bounds, &h.bounds) {
            continue;
        }
        let plane = (h.plane.at(a), h.plane.at(b));
        if !plane.0.is_negative() && !plane.1.is_negative() {
            continue;
        }
        if stroke.class == EdgeClass::Intersection
            && passes_near(&h.plane, &[a.clone(), b.clone()], slack)
        {
            continue;
        }
        let [s0, s1, s2] = &h.sides;
        forms.push([
            Along::new(&plane.0, &plane.1),
            Along::new(&s0.at(a), &s0.at(b)),
            Along::new(&s1.at(a), &s1.at(b)),
            Along::new(&s2.at(a), &s2.at(b)),
        ]);
    }
    forms
}

/// The parameters along the line where some of the `forms` vanishes strictly inside it, with
/// 0 and 1, and the runs of one visibility between them: (first parameter, last parameter,
/// visible), as indices into the parameters.
fn visibility_spans(forms: &[[Along; 4]]) -> (Vec<Q>, Vec<(usize, usize, bool)>) {
    // Where some function vanishes strictly inside the line.
    let (zero, one) = (Q::zero(), Q::one());
    let mut cuts: Vec<Q> = forms
        .iter()
        .flatten()
        .filter_map(Along::zero)
        .filter(|t| *t > zero && *t < one)
        .collect();
    cuts.sort();
    cuts.dedup();
    let params: Vec<Q> = std::iter::once(zero)
        .chain(cuts)
        .chain(std::iter::once(one))
        .collect();
    // Runs of one visibility: (first parameter, last parameter, visible), as indices.
    let mut spans: Vec<(usize, usize, bool)> = Vec::new();
    for i in 0..params.len() - 1 {
        let mid = (&params[i] + &params[i + 1]) / Q::from_integer(BigInt::from(2));
        let visible = !forms.iter().any(|f| hides(f, &mid));
        match spans.last_mut() {
            Some(last) if last.2 == visible => last.1 = i + 1,
            _ => spans.push((i, i + 1, visible)),
        }
    }
    (params, spans)
}

/// Whether the triangle with these four functions along the line hides the point at
/// parameter `t`: strictly behind its plane, and no two sides' planes of sight with strictly
/// opposite signs (the line of sight meets the closed triangle).
fn hides(forms: &[Along; 4], t: &Q) -> bool {
    if forms[0].sign(t) != Ordering::Less {
        return false;
    }
    let (mut above, mut below) = (false, false);
    for f in &forms[1..] {
        match f.sign(t) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    !(above && below)
}

/// An affine function along a line `a + t·(b − a)`, times a positive integer: it has the sign
/// of `x + t·y`.
struct Along {
    x: BigInt,
    y: BigInt,
}

impl Along {
    /// The function with values `fa` at `a` and `fb` at `b`: with `fa = A/α` and `fb − fa =
    /// B/β` (reduced ratios keep their denominators positive), `αβ·(fa + t·(fb − fa)) = Aβ +
    /// t·Bα`.
    fn new(fa: &Q, fb: &Q) -> Along {
        let d = fb - fa;
        Along {
            x: fa.numer() * d.denom(),
            y: d.numer() * fa.denom(),
        }
    }

    /// Its sign at `t = p/q` (`q > 0`): that of `q·x + p·y`.
    fn sign(&self, t: &Q) -> Ordering {
        (t.denom() * &self.x + t.numer() * &self.y).cmp(&BigInt::zero())
    }

    /// Where it vanishes, `t = −x/y`, unless it is constant.
    fn zero(&self) -> Option<Q> {
        (!self.y.is_zero()).then(|| Q::new(-&self.x, self.y.clone()))
    }
}

/// The eye in rationals.
enum Viewer {
    /// A perspective eye point.
    Point(V),
    /// An orthographic eye at infinity in this direction (from the scene towards the viewer).
    Direction(V),
}

/// The affine function `x ↦ normal·(x − at)`, whose sign is the side of a plane.
struct Plane {
    normal: V,
    at: V,
}

impl Plane {
    /// The plane through three points (its normal zero when they are collinear), positive on
    /// the side from which they turn counter-clockwise.
    fn through([c0, c1, c2]: [&V; 3]) -> Plane {
        Plane {
            normal: cross(&sub(c1, c0), &sub(c2, c0)),
            at: c0.clone(),
        }
    }

    /// Its value at `x`, exactly.
    fn at(&self, x: &V) -> Q {
        dot(&self.normal, &sub(x, &self.at))
    }
}

/// A triangle that may hide something: its plane turned so that the eye's side is positive,
/// the planes of sight through its three sides, and its picture's bounding box.
struct Hider {
    plane: Plane,
    sides: [Plane; 3],
    bounds: [[Q; 2]; 2],
}

impl Hider {
    /// The triangle with this plane and these corners (each with its picture), or `None` when
    /// its plane passes through the eye (seen edge-on): it has no far side, so hides nothing.
    fn of(plane: &Plane, corners: [&(V, [Q; 2]); 3], viewer: &Viewer) -> Option<Hider> {
        let [c0, c1, c2] = corners.map(|(x, _)| x);
        let n = &plane.normal;
        let eye_side = match viewer {
            Viewer::Point(e) => plane.at(e),
            Viewer::Direction(v) => dot(n, v),
        };
        let normal = match eye_side.cmp(&Q::zero()) {
            Ordering::Equal => return None,
            Ordering::Greater => n.clone(),
            Ordering::Less => n.clone().map(|x| -x),
        };
        let side = |c: &V, d: &V| match viewer {
            Viewer::Point(e) => Plane {
                normal: cross(&sub(c, e), &sub(d, e)),
                at: e.clone(),
            },
            Viewer::Direction(v) => Plane {
                normal: cross(v, &sub(d, c)),
                at: c.clone(),
            },
        };
        Some(Hider {
            plane: Plane {
                normal,
                at: c0.clone(),
            },
            sides: [side(c0, c1), side(c1, c2), side(c2, c0)],
            bounds: span(&corners.map(|(_, p)| p.clone())),
        })
    }
}

/// An intersection segment's ends moved onto the exact line where the planes of the two
/// triangles it lies on meet (see the module documentation): each end becomes the point of
/// their line nearest to it, `x` with `n₁·x = n₁·p₁`, `n₂·x = n₂·p₂` and `d·x = d·end` for
/// `d = n₁ × n₂`, by Cramer's rule (the determinant of those rows is `d·d`). The ends as given
/// when the planes are parallel.
fn on_meet(ends: [V; 2], [first, second]: [&Plane; 2]) -> [V; 2] {
    let (n1, n2) = (&first.normal, &second.normal);
    let d = cross(n1, n2);
    let dd = dot(&d, &d);
    if dd.is_zero() {
        return ends;
    }
    let (k1, k2) = (dot(n1, &first.at), dot(n2, &second.at));
    let (u, w) = (cross(n2, &d), cross(&d, n1));
    ends.map(|e| {
        let s = dot(&d, &e);
        [0, 1, 2].map(|i| (&k1 * &u[i] + &k2 * &w[i] + &s * &d[i]) / &dd)
    })
}

/// Whether `plane` passes within `slack` of both `ends`, measured as `|n·(p − c₀)| ≤
/// slack·|n|₁`.
fn passes_near(plane: &Plane, ends: &[V; 2], slack: &Q) -> bool {
    let reach = slack * norm1(&plane.normal);
    ends.iter().all(|e| plane.at(e).abs() <= reach)
}

/// The picture map in rationals: `rows[k]·(p − origin)`, divided by the depth for a
/// perspective view.
struct Map {
    rows: [V; 3],
    origin: V,
    perspective: bool,
}

impl Map {
    /// The view's picture map, its rows and origin taken as exact.
    fn of(view: &View) -> Result<Map, Error> {
        let picture = Picture::of(view);
        let (rows, origin) = picture.rows();
        let [r0, r1, r2] = rows.map(|r| exact([r.x, r.y, r.z]));
        Ok(Map {
            rows: [r0?, r1?, r2?],
            origin: point(&origin)?,
            perspective: picture.is_perspective(),
        })
    }

    /// The exact picture of `p`, or `None` when `p` is not strictly in front of a perspective
    /// eye.
    fn picture(&self, p: &V) -> Option<[Q; 2]> {
        let d = sub(p, &self.origin);
        let [x, y] = [0, 1].map(|k| dot(&self.rows[k], &d));
        if !self.perspective {
            return Some([x, y]);
        }
        let depth = dot(&self.rows[2], &d);
        depth.is_positive().then(|| [x / &depth, y / &depth])
    }
}

/// The bounding box `[min, max]` of some pictures.
fn span(points: &[[Q; 2]]) -> [[Q; 2]; 2] {
    let mut lo = points[0].clone();
    let mut hi = points[0].clone();
    for p in &points[1..] {
        for k in 0..2 {
            if p[k] < lo[k] {
                lo[k] = p[k].clone();
            }
            if p[k] > hi[k] {
                hi[k] = p[k].clone();
            }
        }
    }
    [lo, hi]
}

/// Whether two closed boxes meet.
fn overlap(a: &[[Q; 2]; 2], b: &[[Q; 2]; 2]) -> bool {
    (0..2).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
}

/// A finite double, exactly.
fn rational(x: f64) -> Result<Q, Error> {
    Q::from_float(x).ok_or(Error::View(ViewError::NotFinite))
}

/// Three finite doubles, exactly.
fn exact(c: [f64; 3]) -> Result<V, Error> {
    let [x, y, z] = c.map(rational);
    Ok([x?, y?, z?])
}

/// A point, exactly.
fn point(p: &Point3) -> Result<V, Error> {
    exact([p.x, p.y, p.z])
}

fn sub(a: &V, b: &V) -> V {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn dot(a: &V, b: &V) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn cross(a: &V, b: &V) -> V {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn norm1(a: &V) -> Q {
    a[0].abs() + a[1].abs() + a[2].abs()
}

/// `x` rounded to the nearest double, ties to even (infinite beyond the largest double, with
/// subnormals below the normal range): `|x| = q·2^e + r` with `q` of at most 53 bits and
/// `e ≥ −1074`, by one integer division, then `q` rounded by its remainder.
///
/// ```text
/// nearest(1/3) == 1.0 / 3.0; nearest(2⁵³ + 1) == 2⁵³ (a tie, to the even neighbour)
/// ```
fn nearest(x: &Q) -> f64 {
    if x.is_zero() {
        return 0.0;
    }
    // A reduced ratio keeps its sign in the numerator: the denominator is positive.
    let (n, d) = (x.numer().abs(), x.denom().clone());
    // 2^(bits(n) − 1) ≤ n < 2^bits(n), likewise d: n/d lies in (2^(s−1), 2^(s+1)) for
    // s = bits(n) − bits(d), so n/d / 2^(s − 53) lies in (2^52, 2^54).
    let s = n.bits() as i64 - d.bits() as i64;
    let scaled = |e: i64| {
        if e >= 0 {
            (n.clone(), &d << (e as u64))
        } else {
            (&n << (e.unsigned_abs()), d.clone())
        }
    };
    let mut e = s - 53;
    let (num, den) = scaled(e);
    if num >= (&den << 53u64) {
        e += 1;
    }
    // Subnormals: the last place is 2^−1074.
    let e = e.max(-1074);
    let (num, den) = scaled(e);
    let q = &num / &den;
    let r = &num - &q * &den;
    let twice = &r << 1u64;
    let odd = q.bit(0);
    let q = if twice > den || (twice == den && odd) {
        q + 1u32
    } else {
        q
    };
    // q ≤ 2^53 is a double exactly; the product by a power of two rounds only on overflow.
    let q = q.iter_u64_digits().next().unwrap_or(0) as f64;
    let e = e.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
    let magnitude = ldexp(q, e);
    if x.is_negative() {
        -magnitude
    } else {
        magnitude
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::ToPrimitive;

    /// Whether `r` is the double nearest `x`, ties to even: checked exactly against its two
    /// neighbours.
    fn is_nearest(x: &Q, r: f64) -> bool {
        let off = |y: f64| (x - Q::from_float(y).unwrap()).abs();
        let closer = |n: f64| {
            !n.is_finite() || off(r) < off(n) || (off(r) == off(n) && r.to_bits().is_multiple_of(2))
        };
        r.is_finite() && closer(r.next_up()) && closer(r.next_down())
    }

    fn ratio(n: BigInt, d: BigInt) -> Q {
        Q::new(n, d)
    }

    #[test]
    fn nearest_rounds_correctly_and_num_rational_agrees() {
        let two = BigInt::from(2);
        let mut cases = vec![
            ratio(1.into(), 3.into()),
            ratio((-2).into(), 3.into()),
            // Ties between two doubles, either way to the even one.
            ratio(two.pow(53u32) + 1, 1.into()),
            ratio(two.pow(53u32) + 3, 1.into()),
            ratio(-(two.pow(53u32) + BigInt::one()), 1.into()),
            // Just off a tie: the remainder decides.
            ratio(
                two.pow(60u32) * 2 + two.pow(60u32) / two.pow(52u32) + 1,
                two.pow(60u32),
            ),
            // Subnormal and beyond the normal range.
            ratio(1.into(), two.pow(1074u32)),
            ratio(3.into(), two.pow(1075u32)),
            ratio(1.into(), two.pow(1075u32)),
            ratio(1.into(), two.pow(1076u32)),
            ratio(7.into(), two.pow(1050u32) * 3),
            // Huge numerators and denominators with a modest quotient.
            ratio(
                BigInt::from(10).pow(200u32) + 7,
                BigInt::from(10).pow(199u32) * 3,
            ),
            ratio(two.pow(1023u32) * 3, 2.into()),
        ];
        // Pseudo-random ratios of big integers.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..2000 {
            let big = |next: &mut dyn FnMut() -> u64, words: u64| {
                (0..words).fold(BigInt::from(next() | 1), |acc, _| (acc << 64u32) + next())
            };
            let (wn, wd) = (next() % 5, next() % 5);
            let n = big(&mut next, wn);
            let d = big(&mut next, wd);
            let n = if next() % 2 == 0 { -n } else { n };
            cases.push(ratio(n, d));
        }
        for x in &cases {
            let r = nearest(x);
            assert!(is_nearest(x, r), "{x} -> {r:e}");
            assert_eq!(
                x.to_f64().map(f64::to_bits),
                Some(r.to_bits()),
                "num-rational on {x}"
            );
        }
        assert_eq!(nearest(&Q::zero()), 0.0);
        assert_eq!(nearest(&ratio(two.pow(1024u32), 1.into())), f64::INFINITY);
        assert_eq!(nearest(&ratio(1.into(), two.pow(1076u32))), 0.0);
    }
}
