//! Clean-up: [`Tribox::cleaned`], the exact intersection of the 18 half-spaces with equal
//! vertices merged and degenerate faces dropped (bounds first tightened symbolically), and
//! [`Tribox::simplified`], planes moved outward by a tolerance so that small faces vanish.

use std::cmp::Ordering;

use super::cases::CORNER_PLANES;
use super::corners::{LocalBound, clamped_chamfers, corner, reflected};
use super::directions::{CHAMFER_PARENTS, normal_norm};
use super::faces::{MAX_FACE, MAX_VERTICES};
use super::polytope::Tribox;
use super::slabs::TriboxBounds;
use super::support::{
    adjugate, det3, eval_form, normal_rows, round_up_form, sign_of_form, support_without,
    tight_forms,
};
use crate::geometry::Point3;

/// A tight bound as a linear form in the 18 offsets, in half-units: `Σ_k coef_k β_k / 2`.
#[derive(Clone, Copy)]
pub(super) struct OffsetForm<'a> {
    pub(super) coef: [i32; 18],
    pub(super) beta: &'a [f64; 18],
}

impl OffsetForm<'_> {
    /// The sum of the forms' coefficients.
    fn combine(forms: &[Self]) -> [i32; 18] {
        std::array::from_fn(|k| forms.iter().map(|f| f.coef[k]).sum())
    }
}

impl LocalBound for OffsetForm<'_> {
    fn neg(self) -> Self {
        OffsetForm {
            coef: self.coef.map(|c| -c),
            beta: self.beta,
        }
    }
    fn value(self) -> f64 {
        eval_form(&self.coef, self.beta) * 0.5
    }
    fn sum2(a: Self, b: Self) -> f64 {
        eval_form(&OffsetForm::combine(&[a, b]), a.beta) * 0.5
    }
    fn sum3(a: Self, b: Self, c: Self) -> f64 {
        eval_form(&OffsetForm::combine(&[a, b, c]), a.beta) * 0.5
    }
    fn positive5(a: Self, b: Self, c: Self, d: Self, e: Self) -> bool {
        sign_of_form(&OffsetForm::combine(&[a, b, c, d, e]), a.beta) == Ordering::Greater
    }
}

impl Tribox {
    /// The exact boundary of the intersection of the 18 half-spaces, cleaned up: exactly equal
    /// vertices merged, zero-length edges removed and faces left with fewer than 3 vertices
    /// dropped. An axis-aligned box cleans to its 8 vertices and 6 faces.
    ///
    /// The corner classification presumes that every plane touches the tribox, as exact bounds
    /// of points do; a diagonal bound rounded outward may miss it by less than an ulp and then
    /// leave a sliver face. So each bound is first tightened to the exact maximum of its
    /// direction over the tribox (linear programming duality: the least nonnegative combination
    /// of other bounds, kept symbolic, as clamping does), the corners are classified with these
    /// tight bounds, and two vertices are merged when the exact values of their coordinates, as
    /// sums of bounds, are equal (not when their rounded values are). The result is the exact
    /// polytope with every vertex coordinate correctly rounded.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // A needle along (1, 1, 1): the differences x−z, y−x, z−y are pinned to 0, so the tribox
    /// // is the segment, although 0.1 + 0.1 and 0.7 + 0.7 are rounded.
    /// let b = TriboxBounds::from_points(&[Point3::new(0.1, 0.1, 0.1), Point3::new(0.7, 0.7, 0.7)]);
    /// let t = b.boundary().cleaned();
    /// assert_eq!(t.vertices().len(), 2);
    /// assert_eq!(t.face_count(), 0);
    /// ```
    pub fn cleaned(&self) -> Tribox {
        if self.bounds.is_empty() {
            return Tribox::blank(&self.bounds);
        }
        let beta = self.bounds.offsets();
        let tight = tight_forms(&beta);
        // When tightening only clamped chamfers at their block corners (the common case), the
        // fast evaluation gives the same boundary: same exact values, same correct roundings.
        let clamped = clamped_chamfers(&beta);
        let only_clamps = (0..18).all(|j| {
            let mut own = [0; 18];
            own[j] = 2;
            tight[j] == own
                || (j >= 6 && {
                    let mut corner = [0; 18];
                    for p in CHAMFER_PARENTS[j] {
                        corner[p as usize] = 2;
                    }
                    clamped[j] && tight[j] == corner
                })
        });
        let raw = if only_clamps {
            Tribox::new(&self.bounds)
        } else {
            Tribox::from_corners(&self.bounds, |c| {
                let planes = CORNER_PLANES[c];
                let (case, v) = corner(std::array::from_fn(|k| OffsetForm {
                    coef: tight[planes[k] as usize],
                    beta: &beta,
                }));
                (case, reflected(c, &v))
            })
        };
        let n = raw.vertex_count as usize;
        let forms: Vec<VertexForm> = raw
            .vertex_planes()
            .iter()
            .map(|p| VertexForm::new(p, &tight))
            .collect();
        // Representatives: the first vertex of each class of exactly equal vertices.
        let mut new_index = [0u8; MAX_VERTICES];
        let mut kept: Vec<usize> = Vec::with_capacity(n);
        for i in 0..n {
            let found = kept.iter().position(|&r| {
                close(&raw.vertices()[r], &raw.vertices()[i]) && forms[r].equals(&forms[i], &beta)
            });
            new_index[i] = match found {
                Some(k) => k as u8,
                None => {
                    kept.push(i);
                    (kept.len() - 1) as u8
                }
            };
        }
        let mut t = Tribox::blank(&self.bounds);
        t.cases = raw.cases;
        for (k, &r) in kept.iter().enumerate() {
            t.vertices.as_flattened_mut()[k] = raw.vertices()[r];
            t.vertex_planes.as_flattened_mut()[k] =
                touching_planes(&raw.vertex_planes()[r], &tight, &clamped);
        }
        t.vertex_count = kept.len() as u8;
        for j in 0..18 {
            let mut out = [0u8; MAX_FACE];
            let mut len = 0;
            for &v in raw.face(j) {
                let v = new_index[v as usize];
                if len == 0 || out[len - 1] != v {
                    out[len] = v;
                    len += 1;
                }
            }
            while len > 1 && out[len - 1] == out[0] {
                len -= 1;
            }
            t.faces[j] = out;
            t.face_len[j] = if len >= 3 { len as u8 } else { 0 };
        }
        t
    }

    /// A simplified tribox: planes moved outward by at most `tol` so that small faces vanish,
    /// then cleaned (the paper's "small outward displacement on the bounding planes").
    ///
    /// Planes are taken in order 0..18. For plane j, the bound is compared with the largest
    /// value its direction takes on the polytope of the other 17 constraints (the position at
    /// which plane j stops touching the tribox: for a chamfer at most the block's corner). If
    /// moving plane j there is a displacement of at most `tol`, measured along its unit normal,
    /// and does not increase the number of faces, the bound is moved there (rounded outward).
    /// A plane never moves inward, so the simplified tribox contains the original one and every
    /// point it contained; `tol` is a distance in the units of the coordinates, and each plane
    /// moves at most once. A negative or NaN `tol` moves nothing.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// // A unit cube with its edge x = y = 1 shaved by 0.001: the chamfer face x + y = 1.999 is
    /// // a thin strip.
    /// let mut pts: Vec<Point3> = (0..8)
    ///     .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
    ///     .filter(|p| p.x + p.y < 2.0)
    ///     .collect();
    /// for z in [0.0, 1.0] {
    ///     pts.push(Point3::new(1.0, 0.999, z));
    ///     pts.push(Point3::new(0.999, 1.0, z));
    /// }
    /// let t = TriboxBounds::from_points(&pts).boundary();
    /// assert_eq!(t.cleaned().face_count(), 7);
    /// let s = t.simplified(0.01);
    /// assert_eq!(s.face_count(), 6);
    /// assert!(pts.iter().all(|p| s.bounds().contains_point(p)));
    /// ```
    pub fn simplified(&self, tol: f64) -> Tribox {
        let mut current = self.cleaned();
        if current.is_empty() || tol.is_nan() || tol < 0.0 {
            return current;
        }
        let mut beta = self.bounds.offsets();
        for j in 0..18 {
            let Some(support) = support_without(j, &beta) else {
                continue;
            };
            // Displacement d = support − β_j, exactly, in half-units: 2d = Σ halves·β − 2β_j.
            let mut coef = support.dense();
            coef[j] -= 2;
            if sign_of_form(&coef, &beta) != Ordering::Greater {
                continue;
            }
            let distance = eval_form(&coef, &beta) * 0.5 / normal_norm(j);
            if distance.is_nan() || distance > tol {
                continue;
            }
            let mut moved = beta;
            moved[j] = round_up_form(support, &beta);
            let candidate = Tribox::new(&TriboxBounds::from_offsets(&moved)).cleaned();
            if candidate.face_count() <= current.face_count() {
                beta = moved;
                current = candidate;
            }
        }
        current
    }
}

/// Whether two computed points may be the same exact point: each coordinate is the correct
/// rounding of an exact sum, halved at most twice (exact but for subnormal results), so equal
/// exact values give doubles at most two steps apart.
pub(super) fn close(p: &Point3, q: &Point3) -> bool {
    // Doubles ordered as integers (NaN and overflow aside): consecutive doubles differ by 1.
    let key = |x: f64| {
        let b = x.to_bits() as i64;
        if b < 0 { i64::MIN - b } else { b }
    };
    (0..3).all(|i| key(p[i]).abs_diff(key(q[i])) <= 2)
}

/// The exact coordinates of a vertex as linear forms in the 18 offsets β: coordinate i is
/// `Σ_k num[i][k] β_k / (2 den)`, solved by the adjugate from its three planes, each at its
/// tight offset (a form in half-units, see [`tight_forms`]).
pub(super) struct VertexForm {
    num: [[i32; 18]; 3],
    den: i32,
}

impl VertexForm {
    /// The form of the vertex on `planes`, each at its tight offset.
    fn new(planes: &[u8; 3], tight: &[[i32; 18]; 18]) -> Self {
        let p = planes.map(usize::from);
        let m = normal_rows(p);
        let adj = adjugate(m);
        let num = std::array::from_fn(|i| {
            std::array::from_fn(|k| (0..3).map(|r| adj[i][r] * tight[p[r]][k]).sum())
        });
        VertexForm { num, den: det3(m) }
    }

    /// Whether both forms have exactly the same value for every coordinate.
    fn equals(&self, other: &VertexForm, beta: &[f64; 18]) -> bool {
        (0..3).all(|i| {
            let coef: [i32; 18] =
                std::array::from_fn(|k| other.den * self.num[i][k] - self.den * other.num[i][k]);
            sign_of_form(&coef, beta) == Ordering::Equal
        })
    }
}

/// Three planes with independent normals through a vertex of the cleaned boundary, each
/// touching the tribox, principal planes first: a plane whose bound was tightened stands for
/// the planes of its tight form, and a chamfer at its block corner for its two principal
/// planes (the vertex is on all of them, since their combination is an equality there).
pub(super) fn touching_planes(
    planes: &[u8; 3],
    tight: &[[i32; 18]; 18],
    clamped: &[bool; 18],
) -> [u8; 3] {
    let mut cand: Vec<u8> = Vec::with_capacity(9);
    for &j in planes {
        let form = &tight[j as usize];
        if form[j as usize] != 2 {
            cand.extend((0..18u8).filter(|&k| form[k as usize] != 0));
        } else if clamped[j as usize] {
            cand.extend(CHAMFER_PARENTS[j as usize]);
        } else {
            cand.push(j);
        }
    }
    cand.sort_unstable();
    cand.dedup();
    for a in 0..cand.len() {
        for b in a + 1..cand.len() {
            for c in b + 1..cand.len() {
                let p = [cand[a], cand[b], cand[c]];
                if det3(normal_rows(p.map(usize::from))) != 0 {
                    return p;
                }
            }
        }
    }
    *planes
}
