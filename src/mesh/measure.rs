//! The measures of a mesh: its signed volume, accurate to the last bits, the exact sign of
//! that volume (its orientation), and its surface area.

use super::{
    Face, Mesh, PARALLEL_POLYGONS, largest_coordinate, normalising_exponent, times_power_of_two,
};
use crate::geometry::Point3;
use crate::geometry::exact::{compress, estimate, expansion_sum};
use crate::geometry::kernel::{
    Estimate, Exponents, Polynomial, UNIT_ROUNDOFF, expansion_sign, sum_error_bound,
};
use crate::geometry::predicates::Orient3d;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use std::cmp::Ordering;

impl Mesh {
    /// The signed volume enclosed (divergence theorem over the triangles): positive for a
    /// closed mesh whose faces point outward, negative for one turned inside out. Meaningful
    /// only for closed meshes. Accurate to the last few bits: the sum of the triangles'
    /// determinants is taken in floating point when its certified error is below `2^-40` of
    /// it, else exactly (as [`Mesh::orientation`] does) and rounded once, so a needle of a
    /// solid has its true tiny volume.
    ///
    /// ```
    /// use kepler::{geometry::Point3, mesh::Mesh};
    /// assert!((kepler::solids::cube(3.0).unwrap().volume() - 27.0).abs() < 1e-12);
    /// // A needle 1e8 long with a 1e-9 wide base: the rounded sum cancels to noise.
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let v = vec![p(1e8, 0.0, 0.0), p(1e8, 1e-9, 0.0), p(1e8, 0.0, 1e-9), p(2e8, 0.0, 0.0)];
    /// let needle = Mesh::from_polygons(v, vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]]).unwrap();
    /// let exact = 1e8 * 1e-9 * 1e-9 / 6.0;
    /// assert!((needle.volume() - exact).abs() < 1e-12 * exact);
    /// ```
    pub fn volume(&self) -> f64 {
        let Some(o) = self.vertices.first() else {
            return 0.0;
        };
        // On coordinates scaled by a power of two when they are very large or very small, so
        // that the products neither overflow nor underflow; scaled back, the value may
        // overflow to an infinity of the right sign.
        let e = normalising_exponent(largest_coordinate(&self.vertices), 300);
        let scaled = |p: &Point3| p.map(|c| times_power_of_two(c, e));
        let o = scaled(o);
        let dets = || {
            self.triangles.iter().map(move |t| {
                let [a, b, c] = t.map(|i| scaled(&self.vertices[i as usize]));
                Orient3d([a, b, c, o])
            })
        };
        let (mut value, mut bound) = (0.0f64, 0.0f64);
        for d in dets() {
            let e = d.estimate();
            value += e.value;
            bound += e.bound + 2.0 * UNIT_ROUNDOFF * (value.abs() + e.value.abs());
        }
        let six_v = if value.is_finite() && bound <= value.abs() / (1u64 << 40) as f64 {
            value
        } else {
            let points: Vec<Point3> = self.vertices.iter().map(scaled).collect();
            match exact_sum(&points, dets()) {
                ExactSum::Expansion(sum) => estimate(&sum),
                ExactSum::Rational(sum) => sum.to_f64().unwrap_or(f64::NAN),
            }
        };
        times_power_of_two(six_v / 6.0, -3 * e)
    }

    /// The exact sign of the signed volume ([`Mesh::volume`]): `Greater` for a closed mesh
    /// whose faces point outward, `Less` for one turned inside out, `Equal` for none (or a
    /// flat one). The volume is the sum over the triangles of `orient3d(a, b, c, o)` / 6 for
    /// any point `o` (here the first vertex); the sum of their estimates decides when its
    /// certified bound allows, else the exact sum (expansions, compressed as they grow, or
    /// rationals where the coordinates' exponents are too far apart for expansions). A thin
    /// solid whose rounded volume has the wrong sign is oriented rightly.
    ///
    /// ```
    /// use std::cmp::Ordering;
    /// let cube = kepler::solids::cube(2.0).unwrap();
    /// assert_eq!(cube.orientation(), Ordering::Greater);
    /// ```
    pub fn orientation(&self) -> Ordering {
        let Some(o) = self.vertices.first() else {
            return Ordering::Equal;
        };
        let det = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            Orient3d([a, b, c, *o])
        };
        let dets = || self.triangles.iter().map(det);
        // The estimates summed in any order (in parallel for a large mesh): the error bound
        // of a sum of n terms holds for every order of the additions.
        let add =
            |(v, b, m): (f64, f64, f64), e: Estimate| (v + e.value, b + e.bound, m + e.value.abs());
        let (value, bound, magnitude) = if self.triangles.len() >= PARALLEL_POLYGONS {
            use rayon::prelude::*;
            self.triangles
                .par_iter()
                .map(|t| det(t).estimate())
                .fold(|| (0.0, 0.0, 0.0), add)
                .reduce(|| (0.0, 0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1, x.2 + y.2))
        } else {
            dets().map(|d| d.estimate()).fold((0.0, 0.0, 0.0), add)
        };
        let bound = (bound + sum_error_bound(self.triangles.len() + 1, magnitude))
            * (1.0 + 1.0 / (1u64 << 20) as f64);
        let filtered = Estimate { value, bound }.sign();
        if let Some(sign) = filtered {
            return sign;
        }
        match exact_sum(&self.vertices, dets()) {
            ExactSum::Expansion(sum) => expansion_sign(&sum),
            ExactSum::Rational(sum) => sum.cmp(&BigRational::zero()),
        }
    }

    /// The total area of the faces.
    ///
    /// ```
    /// assert_eq!(kepler::solids::cube(2.0).unwrap().surface_area(), 24.0);
    /// ```
    pub fn surface_area(&self) -> f64 {
        self.faces.iter().map(Face::area).sum()
    }
}

/// A sum of determinants of a mesh's points, exactly.
enum ExactSum {
    /// As an expansion (when the points' exponents allow exact expansions of degree 3).
    Expansion(Vec<f64>),
    /// As a rational.
    Rational(BigRational),
}

/// The exact sum of `dets` (determinants of `points`): expansions, compressed as they grow,
/// or rationals where the points' exponents are too far apart for expansions.
fn exact_sum(points: &[Point3], dets: impl Iterator<Item = Orient3d>) -> ExactSum {
    let exponents = Exponents::of(
        &points
            .iter()
            .flat_map(|p| p.coords.iter().copied())
            .collect::<Vec<f64>>(),
    );
    if exponents.exact_for(3) {
        let mut sum: Vec<f64> = Vec::new();
        for (k, d) in dets.enumerate() {
            sum = expansion_sum(&sum, &d.expansion());
            if k % 64 == 63 {
                sum = compress(&sum);
            }
        }
        return ExactSum::Expansion(compress(&sum));
    }
    ExactSum::Rational(dets.fold(BigRational::zero(), |s, d| s + d.evaluate::<BigRational>()))
}
