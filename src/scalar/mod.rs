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
    /// `counts · factor` for an exact integer measurement (encoder counts)
    /// and a [`CountScale`] built once from `factor`. Fixed point computes it
    /// in integer arithmetic (no rounding of `counts` first), so an encoder
    /// reading keeps its full resolution even when one count is far below
    /// one LSB of the scaled unit. Rounded to nearest; saturates.
    fn from_counts(counts: i64, scale: &CountScale) -> Self;

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

/// A conversion factor from integer counts to a backend value, prepared
/// once for every backend (see [`Scalar::from_counts`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CountScale {
    factor: f64,
    factor_f32: f32,
    /// Fixed point: `value_bits = (counts · mult) >> shift` (rounded).
    mult: i64,
    shift: u32,
}

impl CountScale {
    /// Prepare `factor` (value per count, e.g. stored mrad per encoder
    /// count). For `I16F16` the factor is held to 31 significant bits.
    /// A zero or non-finite factor yields a scale that maps every count to 0.
    pub fn new(factor: f64) -> Self {
        if !factor.is_finite() || factor == 0.0 {
            return CountScale {
                factor: 0.0,
                factor_f32: 0.0,
                mult: 0,
                shift: 0,
            };
        }
        // factor · 2^16 · 2^shift ∈ [2^30, 2^31): the largest shift whose
        // multiplier still fits 31 bits, capped so counts (≤ 2^31 after
        // clamping) times mult (< 2^31) stays below 2^62.
        let bits = factor.abs() * 65536.0;
        let e = libm::floor(libm::log2(bits)) as i32;
        let shift = (30 - e).clamp(0, 62) as u32;
        let mult = libm::round(bits * libm::exp2(shift as f64)) as i64;
        CountScale {
            factor,
            factor_f32: factor as f32,
            mult: if factor < 0.0 { -mult } else { mult },
            shift,
        }
    }

    /// The factor this scale was built from.
    pub fn factor(&self) -> f64 {
        self.factor
    }

    /// `I16F16` bits of `counts · factor`, rounded to nearest, saturated.
    #[inline]
    pub(crate) fn fixed_bits(&self, counts: i64) -> i32 {
        let c = counts.clamp(-(1i64 << 31), 1i64 << 31);
        let p = c * self.mult; // |p| < 2^62
        let r = if self.shift == 0 {
            p
        } else {
            (p + (1i64 << (self.shift - 1))) >> self.shift
        };
        fixed::sat_i64(r)
    }

    /// `f32` value of `counts · factor`.
    #[inline]
    pub(crate) fn f32_value(&self, counts: i64) -> f32 {
        counts as f32 * self.factor_f32
    }

    /// `f64` value of `counts · factor`.
    #[inline]
    pub(crate) fn f64_value(&self, counts: i64) -> f64 {
        counts as f64 * self.factor
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

    proptest::proptest! {
        /// `from_counts` on I16F16 is the correctly rounded product within
        /// the 31-bit precision of the prepared factor: |error| ≤ ½ LSB plus
        /// |counts·factor|·2⁻³⁰ (relative error of the multiplier).
        #[test]
        fn from_counts_is_rounded_product(
            counts in -(1i64 << 31)..(1i64 << 31),
            mant in 1.0f64..2.0, exp in -40i32..10,
        ) {
            let factor = mant * 2f64.powi(exp);
            let sc = CountScale::new(factor);
            let exact = counts as f64 * factor;
            proptest::prop_assume!(exact.abs() < 32767.0);
            let got = I16F16::from_counts(counts, &sc).to_f64();
            let bound = 0.5 / 65536.0 + exact.abs() * 2f64.powi(-30);
            proptest::prop_assert!((got - exact).abs() <= bound, "{got} vs {exact}");
        }
    }

    #[test]
    fn from_counts_saturates_and_handles_zero_factor() {
        let sc = CountScale::new(1.0);
        assert_eq!(I16F16::from_counts(1 << 40, &sc), I16F16::MAX);
        assert_eq!(I16F16::from_counts(-(1 << 40), &sc), I16F16::MIN);
        let z = CountScale::new(0.0);
        assert_eq!(I16F16::from_counts(12345, &z), I16F16::ZERO);
        assert_eq!(f32::from_counts(12345, &CountScale::new(f64::NAN)), 0.0);
        let neg = CountScale::new(-0.25);
        assert_eq!(I16F16::from_counts(6, &neg).to_f64(), -1.5);
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
