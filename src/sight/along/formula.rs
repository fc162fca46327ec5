//! Polynomials written once over any [`Ring`]: the [`Formula`] vocabulary, the ring of
//! [`Filtered`] estimates (the kernel's certified bounds) and that of [`Expanded`] (exact
//! expansions), and the sign from the rational value.

use crate::geometry::exact::{expansion_product, expansion_sum, negated};
use crate::geometry::kernel::{Estimate, Exponents, Polynomial, Ring};
use num_rational::BigRational;
use num_traits::{Signed, Zero as _};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Neg, Sub};

/// A polynomial of the input written once over any [`Ring`]: its estimate (with the
/// kernel's certified bound, in [`Filtered`]), its exact expansion (in [`Expanded`]) and its
/// rational value all come from the one formula, so that they cannot disagree.
pub(crate) trait Formula {
    /// The formula in the ring `R`.
    fn value<R: Ring>(&self) -> R;

    /// Its degree in the inputs (see [`Polynomial::degree`]).
    fn formula_degree(&self) -> u32;

    /// The binary exponents of its inputs (see [`Polynomial::exponents`]).
    fn formula_exponents(&self) -> Exponents;
}

impl<F: Formula> Polynomial for F {
    fn estimate(&self) -> Estimate {
        self.value::<Filtered>().0
    }

    fn expansion(&self) -> Vec<f64> {
        self.value::<Expanded>().0
    }

    fn evaluate<R: Ring>(&self) -> R {
        self.value()
    }

    fn degree(&self) -> u32 {
        self.formula_degree()
    }

    fn exponents(&self) -> Exponents {
        self.formula_exponents()
    }
}

/// The ring of [`Estimate`]s: each operation's value rounded, its bound the kernel's
/// ([`Estimate::product`], [`Estimate::difference`]; a sum is the difference with the negated
/// operand, a negation is exact), so a formula evaluated here carries a certified bound.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Filtered(pub Estimate);

impl Add for Filtered {
    type Output = Filtered;
    #[inline]
    fn add(self, other: Filtered) -> Filtered {
        self - (-other)
    }
}

impl Sub for Filtered {
    type Output = Filtered;
    #[inline]
    fn sub(self, other: Filtered) -> Filtered {
        Filtered(self.0.difference(&other.0))
    }
}

impl Mul for Filtered {
    type Output = Filtered;
    #[inline]
    fn mul(self, other: Filtered) -> Filtered {
        Filtered(self.0.product(&other.0))
    }
}

impl Neg for Filtered {
    type Output = Filtered;
    #[inline]
    fn neg(self) -> Filtered {
        Filtered(Estimate {
            value: -self.0.value,
            bound: self.0.bound,
        })
    }
}

impl Ring for Filtered {
    #[inline]
    fn from_f64(x: f64) -> Filtered {
        Filtered(Estimate::exact(x))
    }
}

/// The ring of expansions: exact while no product overflows or underflows (see
/// [`Exponents::exact_for`]).
#[derive(Debug, Clone)]
pub(crate) struct Expanded(pub Vec<f64>);

impl Add for Expanded {
    type Output = Expanded;
    fn add(self, other: Expanded) -> Expanded {
        Expanded(expansion_sum(&self.0, &other.0))
    }
}

impl Sub for Expanded {
    type Output = Expanded;
    fn sub(self, other: Expanded) -> Expanded {
        Expanded(expansion_sum(&self.0, &negated(&other.0)))
    }
}

impl Mul for Expanded {
    type Output = Expanded;
    fn mul(self, other: Expanded) -> Expanded {
        Expanded(expansion_product(&self.0, &other.0))
    }
}

impl Neg for Expanded {
    type Output = Expanded;
    fn neg(self) -> Expanded {
        Expanded(negated(&self.0))
    }
}

impl Ring for Expanded {
    fn from_f64(x: f64) -> Expanded {
        Expanded(if x == 0.0 { Vec::new() } else { vec![x] })
    }
}

/// The sign of `p` from its rational value.
#[cold]
pub(crate) fn exact_sign_rational<P: Polynomial>(p: &P) -> Ordering {
    let x = p.evaluate::<BigRational>();
    if x.is_zero() {
        Ordering::Equal
    } else if x.is_positive() {
        Ordering::Greater
    } else {
        Ordering::Less
    }
}
