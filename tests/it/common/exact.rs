//! Exact references shared by the tests that compare the library with rational arithmetic
//! (`hidden_exact`, `surfaces_exact`): rational points, the exact picture map and sight
//! planes of a view, and errors measured in units in the last place.

use super::{Q, q, qcross, qdot, qsign, qsub, qv};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::solids;
use kepler::views::{Eye, Picture, View};
use nalgebra::Matrix4;
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;

pub type V = [Q; 3];
pub type P2 = [Q; 2];

pub fn qp(p: &Point3) -> V {
    qv([p.x, p.y, p.z])
}

pub fn qadd(a: &V, b: &V) -> V {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

pub fn qscale(a: &V, s: &Q) -> V {
    [&a[0] * s, &a[1] * s, &a[2] * s]
}

pub fn qlerp(a: &V, b: &V, t: &Q) -> V {
    qadd(a, &qscale(&qsub(b, a), t))
}

pub fn qdet(a: &V, b: &V, c: &V) -> Q {
    qdot(a, &qcross(b, c))
}

pub fn f2(p: &P2) -> [f64; 2] {
    [p[0].to_f64().unwrap(), p[1].to_f64().unwrap()]
}

/// Whether `x` and `y` are nonzero with opposite signs.
pub fn opposite(x: &Q, y: &Q) -> bool {
    let (sx, sy) = (qsign(x), qsign(y));
    sx != Ordering::Equal && sy == sx.reverse()
}

/// `2^e`, exactly.
pub fn pow2(e: i32) -> Q {
    if e >= 0 {
        Q::from_integer(BigInt::one() << e as usize)
    } else {
        Q::new(BigInt::one(), BigInt::one() << (-e) as usize)
    }
}

/// The unit in the last place of the doubles around the nonzero rational `x`.
pub fn ulp_of(x: &Q) -> Q {
    let ax = x.abs();
    let approx = ax.to_f64().unwrap();
    let mut e = if approx > 0.0 {
        approx.log2().floor() as i32
    } else {
        -1074
    };
    loop {
        if pow2(e) > ax {
            e -= 1;
        } else if pow2(e + 1) <= ax {
            e += 1;
        } else {
            break;
        }
    }
    pow2((e - 52).max(-1074))
}

/// The error of `got` in units in the last place of `exact` (of `scale` when `exact` is 0).
pub fn ulps(got: f64, exact: &Q, scale: f64) -> f64 {
    let unit = if exact.is_zero() {
        ulp_of(&q(scale.max(f64::MIN_POSITIVE)))
    } else {
        ulp_of(exact)
    };
    ((q(got) - exact).abs() / unit).to_f64().unwrap()
}

/// The larger coordinate error of `got` against `exact`, in ulps.
pub fn ulps2(got: [f64; 2], exact: &P2, scale: f64) -> f64 {
    ulps(got[0], &exact[0], scale).max(ulps(got[1], &exact[1], scale))
}

// ---------------------------------------------------------------------------------------------
// The view, exactly.

pub enum RefEye {
    Point(V),
    Direction(V),
}

pub struct RefView {
    pub rows: [V; 3],
    pub origin: V,
    pub eye: RefEye,
}

impl RefView {
    pub fn new(view: &View) -> RefView {
        let picture = Picture::of(view);
        let (rows, origin) = picture.rows();
        let eye = match view.eye() {
            Eye::Point(e) => RefEye::Point(qp(e)),
            Eye::Infinity(u) => RefEye::Direction(qv([u.x, u.y, u.z])),
        };
        assert_eq!(picture.is_perspective(), matches!(eye, RefEye::Point(_)));
        RefView {
            rows: rows.map(|r| qv([r.x, r.y, r.z])),
            origin: qp(&origin),
            eye,
        }
    }

    /// The exact picture of `x`.
    pub fn picture(&self, x: &V) -> P2 {
        let d = qsub(x, &self.origin);
        let (px, py) = (qdot(&self.rows[0], &d), qdot(&self.rows[1], &d));
        match &self.eye {
            RefEye::Point(_) => {
                let w = qdot(&self.rows[2], &d);
                assert!(w.is_positive(), "point behind the eye");
                [px / &w, py / &w]
            }
            RefEye::Direction(_) => [px, py],
        }
    }

    /// `O(x)`: zero on the plane through `c`, `d` and the eye (the picture of line `cd`).
    pub fn sight(&self, c: &V, d: &V, x: &V) -> Q {
        match &self.eye {
            RefEye::Point(e) => qdet(&qsub(c, e), &qsub(d, e), &qsub(x, e)),
            RefEye::Direction(u) => qdet(&qsub(c, x), &qsub(d, x), u),
        }
    }

    /// Where the picture of edge `ab` crosses the picture of `cd` (both proper), as the point
    /// of `ab` by the crossing definition.
    pub fn crossing(&self, a: &V, b: &V, c: &V, d: &V) -> Option<V> {
        let (oa, ob) = (self.sight(c, d, a), self.sight(c, d, b));
        if !opposite(&oa, &ob) {
            return None;
        }
        let (oc, od) = (self.sight(a, b, c), self.sight(a, b, d));
        if qsign(&oc) == qsign(&od) && !oc.is_zero() {
            return None;
        }
        let t = &oa / (&oa - &ob);
        Some(qlerp(a, b, &t))
    }

    /// The side of a face (outward normal `n`, through `p`) the eye is on: `Greater` when
    /// the face is turned towards it.
    pub fn facing(&self, n: &V, p: &V) -> Ordering {
        match &self.eye {
            RefEye::Point(e) => qsign(&qdot(n, &qsub(e, p))),
            RefEye::Direction(u) => qsign(&qdot(n, u)),
        }
    }

    /// The ray from `x` towards the eye: `x + s·w` for `0 < s < smax`.
    pub fn ray(&self, x: &V) -> (V, Option<Q>) {
        match &self.eye {
            RefEye::Point(e) => (qsub(e, x), Some(Q::one())),
            RefEye::Direction(u) => (u.clone(), None),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Solids with exact (dyadic) vertices.

/// The mesh moved by `t`.
pub fn translated(mesh: Mesh, t: [f64; 3]) -> Mesh {
    mesh.transformed(&Matrix4::new_translation(&Vector3::new(t[0], t[1], t[2])))
        .unwrap()
}

/// A box of edge lengths `size` centred at `at` (exact for dyadic input).
pub fn cuboid_at(size: [f64; 3], at: [f64; 3]) -> Mesh {
    translated(
        solids::cuboid(Vector3::new(size[0], size[1], size[2])).unwrap(),
        at,
    )
}

/// A long thin parallelepiped `p0 + i·d + j·u + k·v` (i, j, k in {0, 1}), with faces
/// numbered as [`solids::box_between`]'s (d, u, v right-handed, so counter-clockwise outside).
pub fn parallelepiped(p0: [f64; 3], d: [f64; 3], u: [f64; 3], v: [f64; 3]) -> Mesh {
    // The unit box under x ↦ p0 + x·d + y·u + z·v: with dyadic inputs every vertex is exact.
    let m = Matrix4::new(
        d[0], u[0], v[0], p0[0], d[1], u[1], v[1], p0[1], d[2], u[2], v[2], p0[2], 0.0, 0.0, 0.0,
        1.0,
    );
    solids::box_between([0.0; 3], [1.0; 3])
        .unwrap()
        .transformed(&m)
        .unwrap()
}
