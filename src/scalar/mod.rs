//! The numeric core: one small [`Scalar`] trait with float and fixed-point
//! backends, and the math kernels every model in this crate is built from.
//!
//! # Backends
//!
//! | backend | type | use |
//! |---|---|---|
//! | `f64` | [`f64`] | design, identification, simulation, reference |
//! | `f32` | [`f32`] | Cortex-M4F and other single-precision FPUs |
//! | `I16F16` | [`I16F16`] | MCUs without FPU (Cortex-M0+); Q16.16, range ±32768, LSB 2⁻¹⁶ |
//!
//! Models are *designed* in `f64` (`XxxParams`) and *quantized once* into a
//! backend (`XxxConfig<S>`); the hot path only uses the methods of this trait.
//! See [`units`] for how physical quantities are scaled into the fixed-point
//! range and what resolution that leaves.
//!
//! # Arithmetic semantics
//!
//! * Fixed point: every operation saturates at [`Scalar::MIN`]/[`Scalar::MAX`];
//!   nothing wraps and nothing panics (division by zero saturates, `0/0 = 0`).
//! * Floats: IEEE-754 arithmetic, except that [`Scalar::div`] by zero returns
//!   `±MAX` (or `0` for `0/0`) instead of an infinity or NaN.
//! * Kernels never return NaN: a NaN argument (floats only) is treated as `0`,
//!   and arguments outside a kernel's domain return the documented saturated
//!   value. Domains and proven error bounds are listed on each kernel of the
//!   backends in [`kernels`].

use core::fmt::Debug;

pub mod fixed;
pub mod float;
pub mod kernels;
pub mod q15;
pub mod units;

pub use ::fixed::types::I16F16;

/// The scalar a component computes in: `f32`, `f64` or [`I16F16`].
///
/// Only operations that every backend implements exactly (with its stated,
/// proven error bound) belong here. The trait is sealed: the proofs in
/// `proofs/` cover exactly the implementations in this crate.
pub trait Scalar:
    Copy + PartialEq + PartialOrd + Debug + Default + Send + Sync + sealed::Sealed + 'static
{
    /// Short backend name used in reports (`"f32"`, `"f64"`, `"I16F16"`).
    const NAME: &'static str;
    /// Additive identity.
    const ZERO: Self;
    /// Multiplicative identity.
    const ONE: Self;
    /// Most negative finite value.
    const MIN: Self;
    /// Largest finite value.
    const MAX: Self;
    /// Spacing of representable values at 1.0 (float: machine epsilon;
    /// fixed: one LSB).
    const RESOLUTION: Self;
    /// π rounded to nearest.
    const PI: Self;
    /// π/2 rounded to nearest.
    const FRAC_PI_2: Self;
    /// The unit scales this backend stores physical quantities with
    /// ([`units::SI`] for floats, [`units::FIXED`] for `I16F16`).
    const UNITS: units::Units;

    /// Nearest representable value; saturates at `MIN`/`MAX`; NaN maps to 0.
    fn from_f64(x: f64) -> Self;
    /// The exact value as `f64` (every backend here converts exactly).
    fn to_f64(self) -> f64;
    /// Nearest representable value of an integer; saturates.
    fn from_i32(x: i32) -> Self;

    /// `self + rhs` (fixed: saturating).
    fn add(self, rhs: Self) -> Self;
    /// `self - rhs` (fixed: saturating).
    fn sub(self, rhs: Self) -> Self;
    /// `self * rhs` (fixed: saturating, rounded to nearest).
    fn mul(self, rhs: Self) -> Self;
    /// `self / rhs`; division by zero gives `±MAX` with the sign of `self`,
    /// and `0 / 0 = 0` (fixed: saturating).
    fn div(self, rhs: Self) -> Self;
    /// `-self` (fixed: `-MIN` saturates to `MAX`).
    fn neg(self) -> Self;
    /// `|self|` (fixed: `|MIN|` saturates to `MAX`; float: NaN stays NaN).
    fn abs(self) -> Self;
    /// `true` when the value is NaN (always `false` for fixed point).
    #[inline]
    fn is_nan(self) -> bool {
        #[allow(clippy::eq_op)]
        let nan = self != self;
        nan
    }
    /// The smaller of two values (a NaN operand loses).
    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self || self.is_nan() {
            other
        } else {
            self
        }
    }
    /// The larger of two values (a NaN operand loses).
    #[inline]
    fn max(self, other: Self) -> Self {
        if other > self || self.is_nan() {
            other
        } else {
            self
        }
    }
    /// `self` limited to `[lo, hi]` (`lo <= hi` assumed); NaN maps to `lo`.
    #[inline]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        if self.is_nan() || self < lo {
            lo
        } else if self > hi {
            hi
        } else {
            self
        }
    }

    /// Arctangent, in radians, in `[-π/2, π/2]`; every input is in the domain.
    fn atan(self) -> Self;
    /// Tangent of an angle in the principal branch `(-π/2, π/2)`. Outside it,
    /// returns `±` the backend's largest in-domain tangent (sign of the input),
    /// so `tan` is non-decreasing over every input.
    fn tan(self) -> Self;
    /// `e^self`; saturates at `MAX` and flushes to 0 below the backend's range.
    fn exp(self) -> Self;
    /// Sine of an angle in radians.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// `(sin, cos)` of one angle, sharing the argument reduction.
    fn sin_cos(self) -> (Self, Self);
    /// Four-quadrant arctangent of `self / x` (`self` is `y`), in `[-π, π]`;
    /// `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// Arccosine in `[0, π]`; inputs outside `[-1, 1]` are clamped to it.
    fn acos(self) -> Self;
    /// Square root; negative inputs return 0.
    fn sqrt(self) -> Self;

    /// Sign function of thesis eq. (2.17): `1` for `x > 0`, `0` for `x = 0`
    /// (including `-0.0` and NaN), `-1` for `x < 0`. Exact on every backend.
    #[inline]
    fn sgn(self) -> Self {
        if self > Self::ZERO {
            Self::ONE
        } else if self < Self::ZERO {
            Self::ONE.neg()
        } else {
            Self::ZERO
        }
    }

    /// Boundary-layer saturation of thesis eq. (4.18), `sat(x, y)` with
    /// `x = self`:
    ///
    /// $$ \mathrm{sat}(x,y)=\begin{cases} x/|x| & |x|>y \\ x/|y| & |x|\le y \end{cases} $$
    ///
    /// Note the `|y|`: for `y ≤ 0` every `x ≠ 0` is outside the boundary
    /// layer and the result is [`sgn`](Scalar::sgn)`(x)`; `sat(0, y) = 0`.
    /// The result always lies in `[-1, 1]`, is odd in `x`, non-decreasing in
    /// `x`, and continuous at `|x| = y` for `y > 0`. A NaN `x` gives 0, a NaN
    /// `y` gives `sgn(x)`.
    #[inline]
    fn sat(self, y: Self) -> Self {
        let x = self;
        if x.is_nan() {
            return Self::ZERO;
        }
        if y.is_nan() || y <= Self::ZERO {
            return x.sgn();
        }
        if x > y {
            Self::ONE
        } else if x < y.neg() {
            Self::ONE.neg()
        } else {
            // |x| <= y with y > 0: |x / y| <= 1 exactly on every backend
            // (IEEE division and the fixed division are monotone and exact
            // at ±1), so no clamp is needed. The one NaN case is
            // `±∞ / +∞` (floats), whose limit along |x| = y is sgn(x).
            let q = x.div(y);
            if q.is_nan() {
                x.sgn()
            } else {
                q
            }
        }
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
    impl Sealed for super::I16F16 {}
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sat_examples<S: Scalar>() {
        let f = S::from_f64;
        let eps = f(0.5);
        assert_eq!(f(2.0).sat(eps), S::ONE);
        assert_eq!(f(-2.0).sat(eps), S::ONE.neg());
        assert_eq!(f(0.25).sat(eps), f(0.5));
        assert_eq!(f(-0.25).sat(eps), f(-0.5));
        assert_eq!(S::ZERO.sat(S::ZERO), S::ZERO);
        // y <= 0: thesis condition |x| > y holds for every x != 0.
        assert_eq!(f(0.001).sat(f(-1.0)), S::ONE);
        assert_eq!(f(-0.001).sat(S::ZERO), S::ONE.neg());
    }

    #[test]
    fn sat_matches_hand_values_on_every_backend() {
        sat_examples::<f32>();
        sat_examples::<f64>();
        sat_examples::<I16F16>();
    }

    #[test]
    fn sgn_is_exact_including_negative_zero_and_nan() {
        assert_eq!((-0.0f64).sgn(), 0.0);
        assert_eq!(f64::NAN.sgn(), 0.0);
        assert_eq!(f32::NAN.sat(1.0), 0.0);
        assert_eq!(1.0f32.sat(f32::NAN), 1.0);
        assert_eq!(I16F16::MIN.sgn(), I16F16::from_num(-1));
        assert_eq!(I16F16::ZERO.sgn(), I16F16::ZERO);
    }
}
