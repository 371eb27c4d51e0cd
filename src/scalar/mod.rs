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
pub(crate) mod target;
pub mod units;

pub use ::fixed::types::I16F16;

/// The scalar a component computes in: `f32`, `f64` or [`I16F16`].
///
/// Only operations that every backend implements exactly (with its stated,
/// proven error bound) belong here. The trait is sealed: the proofs in
/// `proofs/` cover exactly the implementations in this crate.
///
/// The methods, by group:
/// * **constants and conversions**: `NAME`, `ZERO`, `ONE`, `MIN`, `MAX`,
///   `RESOLUTION`, `PI`, `FRAC_PI_2`, `UNITS`; [`from_f64`](Self::from_f64),
///   [`to_f64`](Self::to_f64), [`from_i32`](Self::from_i32),
///   [`from_counts`](Self::from_counts), [`to_turn`](Self::to_turn);
/// * **arithmetic**: [`add`](Self::add), [`sub`](Self::sub),
///   [`mul`](Self::mul), [`mul_unit_range`](Self::mul_unit_range),
///   [`div`](Self::div), [`neg`](Self::neg), [`abs`](Self::abs); by prepared
///   constants: [`mul_coef`](Self::mul_coef), [`dot_coef`](Self::dot_coef),
///   [`mul_int`](Self::mul_int), [`integrate`](Self::integrate);
/// * **comparisons and tests**: [`min`](Self::min), [`max`](Self::max),
///   [`clamp`](Self::clamp), [`is_nan`](Self::is_nan),
///   [`all_finite`](Self::all_finite), [`sgn`](Self::sgn),
///   [`copysign`](Self::copysign), [`sat`](Self::sat);
/// * **proven kernels**: [`sin`](Self::sin), [`cos`](Self::cos),
///   [`sin_cos`](Self::sin_cos), [`cos_turn`](Self::cos_turn),
///   [`sin_cos_turn`](Self::sin_cos_turn), [`tan`](Self::tan),
///   [`atan`](Self::atan), [`atan2`](Self::atan2), [`acos`](Self::acos),
///   [`sqrt`](Self::sqrt), [`exp`](Self::exp),
///   [`exp_neg_abs`](Self::exp_neg_abs), [`unit_vector`](Self::unit_vector).
///
/// Kernel variants made for one call site of the crate (a cheaper kernel
/// where the caller bounds the argument, a product by a factor prepared for
/// counts) are crate-private.
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
    /// and a [`Coef`] built once from `factor`. Fixed point computes it
    /// in integer arithmetic (no rounding of `counts` first), so an encoder
    /// reading keeps its full resolution even when one count is far below
    /// one LSB of the scaled unit. Rounded to nearest; saturates.
    fn from_counts(counts: i64, scale: &Coef) -> Self;
    /// `self · c` for a prepared constant `c`; in fixed point with the
    /// coefficient's full 31-bit precision, rounded to nearest, saturating.
    fn mul_coef(self, c: &Coef) -> Self;
    /// `Σⱼ xⱼ·cⱼ` for a prepared row of constants ([`CoefRow`]).
    ///
    /// * floats: `mul_coef` of each term, summed in order;
    /// * `I16F16`: the exact sum of the products with the row's common
    ///   mantissas, rounded once (to nearest, ties up) and saturated:
    ///   error `≤ ½ LSB + 2⁻²⁸·max|cⱼ|·Σ|xⱼ|` (the mantissas' rounding,
    ///   [`CoefRow::new`]; `2⁻⁶³·Σ|xⱼ|` for a row below `2⁻³⁵`),
    ///   instead of `½ LSB` per term.
    #[inline]
    fn dot_coef<const N: usize>(x: &[Self; N], row: &CoefRow<N>) -> Self {
        // −0 on floats, the exact identity of the sum (−0 + p = p for
        // every p), so the sum starts at the first product.
        let mut acc = Self::ZERO.neg();
        for (x, c) in x.iter().zip(row.coefs.iter()) {
            acc = acc.add(x.mul_coef(c));
        }
        acc
    }

    /// The part of a slowly integrated value below this backend's
    /// resolution, carried between samples by
    /// [`integrate`](Scalar::integrate): on `I16F16` an `i32` in units of
    /// `2⁻³²` LSB (`2⁻⁴⁸`), so that value and residual together are a
    /// Q16.48 number, `value·2³² + residual`, with
    /// `residual ∈ [−2³¹, 2³¹)` (the value is the nearest `I16F16`); on
    /// `f32` the rounding error of the last sum (a compensated sum, about
    /// 48 significant bits together); on `f64` nothing (`()`).
    /// The default (`0`/`()`) is the residual of a freshly set value.
    type Residual: Copy + PartialEq + Debug + Default + Send + Sync + 'static;

    /// One step of a slow integrator (adapted parameters): the value
    /// `v = self + residual` advanced by `x·c` and kept within `[lo, hi]`
    /// (`lo ≤ hi`, both finite, assumed), returned as the new value (the
    /// one a law reads) and residual. A clamped sum has residual 0; a NaN step (floats)
    /// keeps `self`, clamped.
    ///
    /// * `I16F16`: `x·c` is rounded to `2⁻⁴⁸` (the coefficient's 31-bit
    ///   mantissa; saturated to the `i64` range) and added exactly to the
    ///   Q16.48 value `self·2³² + residual`; the new value is that sum rounded to nearest
    ///   `I16F16`, the residual what rounding left. So an increment far
    ///   below one LSB (Table 4.1's `f̂_τ` step, `≈ 4e-7·r·Y₄` stored) is
    ///   kept and accumulates instead of being rounded away at every
    ///   sample. The Q16.48 value never leaves the box.
    /// * `f32`: a compensated (Fast2Sum) sum of `x·c` into the value, the
    ///   rounding error carried as the residual: steps down to about
    ///   `2⁻⁴⁸` of the value accumulate.
    /// * `f64`: `self + x·c`; a step is lost only below `2⁻⁵³` of the value.
    fn integrate(
        self,
        residual: Self::Residual,
        x: Self,
        c: &Coef,
        lo: Self,
        hi: Self,
    ) -> (Self, Self::Residual);

    /// `self + rhs` (fixed: saturating).
    fn add(self, rhs: Self) -> Self;
    /// `self - rhs` (fixed: saturating).
    fn sub(self, rhs: Self) -> Self;
    /// `self * rhs` (fixed: saturating, rounded to nearest).
    fn mul(self, rhs: Self) -> Self;
    /// `self · n` for an integer factor prepared as an [`IntFactor`]: the
    /// value of [`mul_coef`](Self::mul_coef) by its coefficient, bit for
    /// bit. Fixed point multiplies the bits by the integer after one range
    /// comparison per side (saturating outside it); floats use the
    /// coefficient product.
    #[inline]
    fn mul_int(self, n: &IntFactor) -> Self {
        self.mul_coef(&n.coef)
    }
    /// `self * u` for a factor `|u| ≤ 1` (a `sat` value, a cosine, an
    /// `e^{−x}`): the value of [`mul`](Self::mul), bit for bit, for every
    /// such `u`. Fixed point takes a short product for every `u` of that
    /// range (two 32-bit multiplies on Armv6-M instead of the general
    /// product's four) and uses `u` clamped to `[−1, 1]`; floats multiply.
    #[inline]
    fn mul_unit_range(self, u: Self) -> Self {
        self.mul(u)
    }
    /// Whether `self·u + c·v > 0`, for `self`, `c` in `[−1, 1]` and
    /// `(u, v)` a unit vector (as stored: `u² + v² ≤ 1 + 2⁻¹⁴`): the sign
    /// of the dot product of a vector of the unit disc with a direction.
    /// Floats multiply; fixed point forms the two products with `u`, `v`
    /// short by two bits, one 32-bit multiply each, and misjudges the
    /// sign only where `|self·u + c·v| ≤ 3·2⁻¹⁶(|self| + |c|)`.
    #[inline]
    fn dot_direction_positive(self, u: Self, c: Self, v: Self) -> bool {
        self.mul(u).add(c.mul(v)) > Self::ZERO
    }
    /// `self / rhs`; division by zero gives `±MAX` with the sign of `self`,
    /// and `0 / 0 = 0` (fixed: saturating).
    fn div(self, rhs: Self) -> Self;
    /// `-self` (fixed: `-MIN` saturates to `MAX`).
    fn neg(self) -> Self;
    /// `|self|` (fixed: `|MIN|` saturates to `MAX`; float: NaN stays NaN).
    fn abs(self) -> Self;
    /// `true` when every value is finite: neither NaN nor infinite (always
    /// for fixed point). Floats test `Σ (v − v) = 0`: each term is exactly
    /// 0 for a finite value and NaN for NaN and ±∞, and a NaN survives the
    /// sum, so `N` values cost one comparison.
    #[inline]
    fn all_finite<const N: usize>(values: &[Self; N]) -> bool {
        let Some((&first, rest)) = values.split_first() else {
            return true;
        };
        let mut sum = first.sub(first);
        for &v in rest {
            sum = sum.add(v.sub(v));
        }
        sum == Self::ZERO
    }
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
        // One comparison is false for NaN and for values below `lo`.
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(self >= lo) {
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
    /// `e^{−|self|}`, the decaying exponential of the wave-generator
    /// torsion (eq. (2.29)) and of the Stribeck friction term (eq. (4.7)),
    /// whose exponents are never positive. In `[0, 1]` for every input, even
    /// in `self`, 1 at 0 and NaN → 1 on floats; 0 only where `e^{−|self|}`
    /// is below the backend's resolution (`f32`: `|self| > 87.342`, where
    /// `e^{−|self|} < 1.17e-38`, below the smallest normal `f32`; `I16F16`:
    /// `|self| > 17·ln 2`, below half an LSB). The default is
    /// `self.abs().neg().exp()` (kept by `I16F16`; `f64` computes the same
    /// through `libm`); `f32` has its own table kernel
    /// [`kernels::f32::exp_neg_abs`], within 2 ulp (proven at every `f32`)
    /// and non-increasing in `|self|`.
    #[inline]
    fn exp_neg_abs(self) -> Self {
        self.abs().neg().exp()
    }
    /// Sine of an angle in radians.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// `(sin, cos)` of one angle, sharing the argument reduction.
    fn sin_cos(self) -> (Self, Self);
    /// Cosine of a binary angle, `cos(2π · turn / 2³²)`: `turn` is an
    /// angle in units of `2⁻³²` turn, so angle sums, differences and
    /// multiples are exact wrapping `u32` operations and the kernel's range
    /// reduction is exact integer work. Exactly even
    /// (`cos_turn(t) = cos_turn(t.wrapping_neg())`) and `|result| ≤ 1` on
    /// every backend. Bounds (`proofs/kernels_turn.rs`): `f32` ≤ 2⁻²²
    /// absolute and `I16F16` ≤ 1 LSB (2⁻¹⁶), both proven at all 2³²
    /// angles; `f64` < 1e-15 (tested at the edges, a stride and random
    /// angles).
    /// Used by the kinematic error of eq. (3.7) in the torque estimator.
    fn cos_turn(turn: u32) -> Self;
    /// `(sin, cos)` of a binary angle (units of `2⁻³²` turn): by default
    /// `(cos_turn(turn − 2³⁰), cos_turn(turn))`, a quarter turn apart, so
    /// both components have [`cos_turn`](Scalar::cos_turn)'s proven bound;
    /// a backend may share the range reduction between them as long as it
    /// returns exactly these values.
    #[inline]
    fn sin_cos_turn(turn: u32) -> (Self, Self) {
        (
            Self::cos_turn(turn.wrapping_sub(1 << 30)),
            Self::cos_turn(turn),
        )
    }
    /// This angle (radians) as a binary angle (units of `2⁻³²` turn,
    /// wrapped), for [`cos_turn`](Scalar::cos_turn) and
    /// [`sin_cos_turn`](Scalar::sin_cos_turn). `I16F16`: from the raw bits
    /// by one widening product with `2¹⁶/(2π)`, within 0.52 units
    /// ([`kernels::i16f16::turn_of_radians`]), so `sin_cos_turn` of it is
    /// within 1 LSB of `(sin, cos)` at every input, with no division or
    /// argument reduction; the default rounds the `f64` value
    /// ([`turn_from_radians`]; a non-finite angle gives 0).
    #[inline]
    fn to_turn(self) -> u32 {
        turn_from_radians(self.to_f64())
    }
    /// Four-quadrant arctangent of `self / x` (`self` is `y`), in `[-π, π]`;
    /// `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// The unit vector `(self, b)/|(self, b)|` of two components of
    /// magnitude at most 1 (e.g. the azimuth of a wrist's output axis),
    /// `None` for the zero vector. `I16F16` scales both by a power of two
    /// and multiplies by a table reciprocal root
    /// ([`kernels::i16f16::unit_vector`]: within 1 LSB per component, no
    /// division); the default divides both by their `hypot`.
    #[inline]
    fn unit_vector(self, b: Self) -> Option<(Self, Self)> {
        let h = hypot(self, b);
        if h > Self::ZERO {
            Some((self.div(h), b.div(h)))
        } else {
            None
        }
    }
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

    /// `|self|` with the sign of `sign`: `-|self|` when `sign` is negative,
    /// `|self|` otherwise. Floats read the sign bit (IEEE `copysign`: `-0.0`
    /// and a NaN with its sign bit set count as negative; a NaN `self`
    /// stays NaN); fixed point tests `sign < 0` and saturates `|MIN|` to
    /// `MAX`. For `self ≥ 0` and `sign ≠ 0` this is
    /// [`sgn`](Scalar::sgn)`(sign) · self` without the product.
    #[inline]
    fn copysign(self, sign: Self) -> Self {
        let m = self.abs();
        if sign < Self::ZERO {
            m.neg()
        } else {
            m
        }
    }

    /// Boundary-layer saturation of thesis eq. (4.18), `sat(x, y)` with
    /// `x = self`:
    ///
    /// ```text
    /// sat(x, y) = x/|x|   if |x| > y
    ///            x/|y|   if |x| ≤ y
    /// ```
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

/// Conversion of an encoder count to a binary angle (a `u32` in units of
/// `2⁻³²` turn, the argument of [`Scalar::cos_turn`]) for an encoder of `L`
/// counts per revolution, prepared once with no run-time division.
///
/// `turn(c) = c·k_hi + ⌊c·k_lo / 2³²⌋ (mod 2³²)` with
/// `k_hi = ⌊2³²/L⌋ mod 2³²` and `k_lo = round(frac(2³²/L)·2³²)`. For
/// `c < L` the result differs from the exact `c·2³²/L` by less than
/// `1 + c·2⁻³³ < 1.5` units of `2⁻³²` turn (`1.5 · 2π/2³² = 2.2e-9` rad):
/// `k_lo` is within ½ of `frac(2³²/L)·2³²` (at most `c/2³³` after the
/// product) and the floor loses less than 1. A power-of-two `L` is exact
/// (`k_lo = 0`). On Armv6-M the high word comes from
/// `fixed::wide_mul` (four 16-bit products, no `__aeabi_lmul`).
///
/// ```
/// use mrr_control::scalar::CountToTurn;
/// // 90° of a 1000-count encoder: a quarter turn, 2³⁰, within 1.5 units.
/// let t = CountToTurn::new(1000).turn(250);
/// assert!((t as i64 - (1i64 << 30)).abs() <= 1);
/// // A power-of-two resolution is exact.
/// assert_eq!(CountToTurn::new(1 << 17).turn(3), 3 << 15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CountToTurn {
    hi: u32,
    lo: u32,
}

impl CountToTurn {
    /// Prepare the conversion for `counts_per_rev = L ≥ 1` counts per
    /// revolution (`L = 0` is treated as 1: every angle is 0).
    pub fn new(counts_per_rev: u32) -> Self {
        let l = counts_per_rev.max(1) as u64;
        let whole = (1u64 << 32) / l; // 2³² for L = 1: wraps to 0 below
        let rem = (1u64 << 32) % l;
        // round(rem·2³²/L) < 2³² because rem ≤ L − 1 < 2³².
        let lo = ((rem << 32) + l / 2) / l;
        CountToTurn {
            hi: whole as u32,
            lo: lo as u32,
        }
    }

    /// The binary angle (units of `2⁻³²` turn) of count `c`, for `c < L`
    /// within 1.5 units of `c·2³²/L` (see the type docs).
    #[inline]
    pub fn turn(&self, c: u32) -> u32 {
        if cfg!(armv6m) && self.lo == 0 {
            // L a power of two (or 1): exact with one multiply (Armv6-M,
            // where the wide product is four).
            return c.wrapping_mul(self.hi);
        }
        let (frac, _) = fixed::wide_mul(c, self.lo);
        c.wrapping_mul(self.hi).wrapping_add(frac)
    }
}

/// A phase in radians as a binary angle (units of `2⁻³²` turn), rounded to
/// nearest (error `≤ π/2³² = 7.3e-10` rad), wrapped to `[0, 2³²)`;
/// non-finite input gives 0.
pub fn turn_from_radians(rad: f64) -> u32 {
    if !rad.is_finite() {
        return 0;
    }
    let turns = rad / core::f64::consts::TAU;
    let frac = turns - libm::floor(turns); // [0, 1]
    (libm::round(frac * 4_294_967_296.0) as u64 & 0xFFFF_FFFF) as u32
}

/// A positive integer factor (a gear ratio `N`), prepared once: its
/// [`Coef`] and, for the `I16F16` product of [`Scalar::mul_int`], the
/// integer (saturated to `i32`) and the range of bit patterns whose product
/// by it fits `i32`. Built by the library from a validated ratio (the
/// joint's `N`); not constructible outside the crate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntFactor {
    pub(crate) coef: Coef,
    /// `n` (at least 1, at most `i32::MAX`).
    pub(crate) n: i32,
    /// `⌊i32::MAX / n⌋` and `⌈i32::MIN / n⌉`: `x·n` fits `i32` exactly for
    /// `x` in `[low, high]`.
    pub(crate) high: i32,
    pub(crate) low: i32,
}

impl IntFactor {
    /// Prepare `n ≥ 1` (an integer; validated by the caller). A value
    /// that is not an integer in `[1, 2³¹)` is rounded and clamped for the
    /// integer form; the coefficient keeps `n` as given, so the two forms
    /// would differ: only the library builds an `IntFactor`, from a
    /// validated gear ratio, which keeps [`Scalar::mul_int`] equal to
    /// [`Scalar::mul_coef`] bit for bit.
    pub(crate) fn new(n: f64) -> Self {
        let i = if n.is_nan() {
            1
        } else {
            libm::round(n).clamp(1.0, i32::MAX as f64) as i32
        };
        IntFactor {
            coef: Coef::new(n),
            n: i,
            high: i32::MAX / i,
            // Division truncates toward zero: the ceiling for a negative
            // quotient.
            low: i32::MIN / i,
        }
    }
}

/// A constant factor of a control law: a [`Coef`], plus the backend's own
/// value of it when that value is exact (fixed point; e.g. `λ = 120`,
/// `1/N = 0.01` in mN·m per N·m, `ω² = 100`). An exact value's product
/// [`Scalar::mul`] rounds `x·c` to nearest with ties up and saturates, as
/// [`Scalar::mul_coef`] does, so the results are bit-identical; on
/// Armv6-M it is the cheaper product (a fixed shift, and two multiplies
/// when an operand is below 0.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Gain<S> {
    coef: Coef,
    exact: Option<S>,
}

impl<S: Scalar> Gain<S> {
    /// Prepare `value` (configuration time).
    pub(crate) fn new(value: f64) -> Self {
        let coef = Coef::new(value);
        let fixed = S::RESOLUTION.to_f64() >= 1e-6;
        // The coefficient's own (31-bit) value: when the backend holds it
        // exactly, both products round the same real number.
        let q = coef.quantized();
        let v = S::from_f64(q);
        let exact = fixed && q != 0.0 && v.to_f64() == q;
        Gain {
            coef,
            exact: exact.then_some(v),
        }
    }

    /// `x · value`.
    #[inline]
    pub(crate) fn apply(&self, x: S) -> S {
        // Floats never hold an exact value (folded at compile time).
        if S::RESOLUTION.to_f64() >= 1e-6 {
            if let Some(v) = self.exact {
                return x.mul(v);
            }
        }
        x.mul_coef(&self.coef)
    }
}

/// A constant coefficient prepared once for every backend: the factor of
/// [`Scalar::mul_coef`] and [`Scalar::from_counts`].
///
/// Fixed point stores it as a 31-bit mantissa and a binary exponent
/// (`c ≈ mult · 2^-shift`), so a small coefficient such as `c_f = 0.045 1/(N·m)`
/// keeps 31 significant bits instead of the 12 an `I16F16` constant would
/// have. Floats store the rounded value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coef {
    value: f64,
    value_f32: f32,
    mult: i64,
    shift: i32,
    /// `|mult|` (at most 2³¹) and its sign, prepared for the 32-bit
    /// product of [`scale_i32`](Self::scale_i32).
    mag: u32,
    negative: bool,
    /// The prepared signed path of [`scale_i32`](Self::scale_i32), when it
    /// applies: every coefficient below `2³⁰` in magnitude, zero included
    /// (see [`SignedCoef::new`]).
    signed: Option<SignedCoef>,
    /// The results of [`scale_i32`](Self::scale_i32) for `x = 1` and
    /// `x = −1` when `signed` is `None` (`|c| ≥ 2³⁰`: every larger `|x|`
    /// saturates).
    units: [i32; 2],
    /// The mantissa and exponent of [`scale_wide`](Self::scale_wide) on
    /// Armv6-M.
    #[cfg(any(test, armv6m))]
    wide: WideCoef,
}

/// The coefficient `mult · 2^−shift` with a mantissa below `2³¹` in
/// magnitude, for the signed product of [`Coef::scale_wide`] on Armv6-M:
/// `mult` itself, or, for `|mult| = 2³¹`, `mult/2` with `shift − 1` (the
/// same value), as its halves `m_hi = (m + 2¹⁵) >> 16` (arithmetic) and
/// `m_lo = m as i16` for [`fixed::signed_wide_mul_add_split`].
#[cfg(any(test, armv6m))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct WideCoef {
    m_hi: i32,
    m_lo: i32,
    shift: i32,
}

#[cfg(any(test, armv6m))]
impl WideCoef {
    /// From the coefficient's mantissa (`|mult| ≤ 2³¹`) and exponent.
    pub(crate) const fn new(mult: i64, shift: i32) -> Self {
        let (m, shift) = if mult == 1 << 31 || mult == -(1 << 31) {
            (mult / 2, shift - 1)
        } else {
            (mult, shift)
        };
        WideCoef {
            m_hi: ((m + (1 << 15)) >> 16) as i32,
            m_lo: m as i32 as i16 as i32,
            shift,
        }
    }

    /// The exact signed product `x·m` as `(high word, low word)`
    /// (`|x·m| < 2⁶²`).
    #[inline(always)]
    fn product(&self, x: i32) -> (i32, u32) {
        fixed::signed_wide_mul_add_split(x, self.m_hi, self.m_lo, 0)
    }
}

/// A count-to-value factor for the crate's count conversions (`from_counts_i32`): the
/// [`Coef`] of [`Scalar::from_counts`] and, for fixed point, the same
/// mantissa 16 bits up (so a count read as `I16F16` bits times it is the
/// count product).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CountCoef {
    coef: Coef,
    bits: Coef,
    /// `scale_int(2³¹, 16)` of `coef`: the `I16F16` bits of `2³¹` counts.
    top: i32,
}

impl CountCoef {
    /// Prepare the factor `value` (as [`Coef::new`]).
    pub fn new(value: f64) -> Self {
        let coef = Coef::new(value);
        CountCoef {
            coef,
            bits: coef.times_pow2(16),
            top: coef.scale_int(1 << 31, 16),
        }
    }

    /// The factor as a [`Coef`] (for [`Scalar::from_counts`]).
    pub fn coef(&self) -> &Coef {
        &self.coef
    }

    /// The factor times `2¹⁶`, same mantissa: `scale_i32` of a count by it
    /// is `scale_int(count, 16)` by [`coef`](Self::coef).
    pub(crate) fn bits(&self) -> &Coef {
        &self.bits
    }

    /// The `I16F16` bits of `2³¹` counts.
    pub(crate) fn top(&self) -> i32 {
        self.top
    }
}

/// `mult` as an `i32` with its rounding constant and shift amounts prepared
/// for [`Coef::scale_i32`] (`sh` = `shift`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct SignedCoef {
    m: i32,
    /// `(m + 2¹⁵) >> 16` (arithmetic) and `m as i16`: the halves of the
    /// 16×16 partial products on Armv6-M
    /// ([`fixed::signed_wide_mul_add_split`]).
    #[cfg(any(test, armv6m))]
    m_hi: i32,
    #[cfg(any(test, armv6m))]
    m_lo: i32,
    /// The rounding constant added to the low word: `round` (`sh ≤ 32`)
    /// or 0 (`sh ≥ 33`).
    #[cfg(any(test, armv6m))]
    round_lo: u32,
    /// `sh ≥ 33`: the rounding and shift apply to the high word alone.
    high_only: bool,
    /// `2^(sh−1)` (`sh ≤ 32`, added to the low word) or `2^(sh−33)`
    /// (`sh ≥ 33`, added to the high word).
    round: u32,
    /// `sh − 1` (`sh ≤ 32`) or `sh − 32` (`sh ≥ 33`).
    rs: u32,
}

impl SignedCoef {
    /// The signed form of `mult · 2^−shift`, exact, for every coefficient
    /// below `2³⁰` in magnitude:
    /// * `1 ≤ shift ≤ 62` and `|mult| < 2³¹`: `mult` itself;
    /// * `|mult| = 2³¹` (a mantissa rounded up to the next power of two)
    ///   with `2 ≤ shift ≤ 62`: `±2³⁰ · 2^−(shift−1)`, the same value;
    /// * `shift ≥ 63` (below `2⁻³²`, where `|x·mult| ≤ 2⁶²` rounds to 0
    ///   for every `x`) and the zero coefficient: `m = 0`.
    ///
    /// `None` for `shift ≤ 0` or `2³¹ · 2⁻¹` (`|c| ≥ 2³⁰`).
    fn new(mult: i64, shift: i32) -> Option<Self> {
        if shift >= 63 || mult == 0 {
            return Some(SignedCoef {
                m: 0,
                #[cfg(any(test, armv6m))]
                m_hi: 0,
                #[cfg(any(test, armv6m))]
                m_lo: 0,
                #[cfg(any(test, armv6m))]
                round_lo: 0,
                high_only: true,
                round: 0,
                rs: 1,
            });
        }
        let (mult, shift) = if mult.unsigned_abs() == 1 << 31 && shift >= 2 {
            (mult / 2, shift - 1)
        } else {
            (mult, shift)
        };
        if !(1..=62).contains(&shift) || mult.unsigned_abs() >= 1 << 31 {
            return None;
        }
        let high_only = shift > 32;
        let round = if high_only {
            1 << (shift - 33)
        } else {
            1 << (shift - 1)
        };
        Some(SignedCoef {
            m: mult as i32,
            #[cfg(any(test, armv6m))]
            m_hi: ((mult + (1 << 15)) >> 16) as i32,
            #[cfg(any(test, armv6m))]
            m_lo: mult as i32 as i16 as i32,
            #[cfg(any(test, armv6m))]
            round_lo: if high_only { 0 } else { round },
            high_only,
            round,
            rs: if high_only { shift - 32 } else { shift - 1 } as u32,
        })
    }
}

/// `√(a² + b²)` without squaring small values (scaled by the larger
/// magnitude, `m·√(1 + (n/m)²)`), so fixed point keeps its resolution for
/// tiny vectors; 0 for two zeros.
#[inline]
pub(crate) fn hypot<S: Scalar>(a: S, b: S) -> S {
    let (a, b) = (a.abs(), b.abs());
    let (m, n) = if a >= b { (a, b) } else { (b, a) };
    if m <= S::ZERO {
        return S::ZERO;
    }
    let r = n.div_unit_range(m);
    // r ≤ 1: the short product (bit for bit `mul`) and the root of a value
    // below 4 (bit for bit `sqrt`).
    m.mul(S::ONE.add(r.mul_unit_range(r)).sqrt_small())
}

/// A row of constants for [`Scalar::dot_coef`]: each as a [`Coef`] (the
/// floats' products) and, for `I16F16`, as integer mantissas `Mⱼ` on one
/// common shift `S`: `cⱼ ≈ Mⱼ·2^−S` with `S = 27 − ⌊log₂ max|cⱼ|⌋`
/// (clamped to `[−62, 62]`), so `|Mⱼ| ≤ 2²⁸`, split once into
/// `Mⱼ = hⱼ·2¹⁶ + lⱼ` (`|hⱼ| ≤ 2¹²`, `0 ≤ lⱼ < 2¹⁶`) for the 32-bit
/// partial products of [`Scalar::dot_coef`]. The mantissas round each
/// constant to `2^−(S+1)`, at most `2⁻²⁸·max|cⱼ|` (`2⁻⁶³` for a row below
/// `2⁻³⁵`): a constant far below
/// the largest of its row loses relative precision, and one below
/// `2^−(S+1)` acts as 0. Rows above `2⁹⁰` are clamped (every non-zero
/// product of such a constant saturates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoefRow<const N: usize> {
    coefs: [Coef; N],
    mant: [i32; N],
    /// `(hⱼ, lⱼ)`: `Mⱼ >> 16` and `Mⱼ mod 2¹⁶`.
    split: [(i32, i32); N],
    shift: i32,
}

impl<const N: usize> CoefRow<N> {
    /// Prepare a row (at most six constants: the sum's headroom). A zero
    /// or non-finite value acts as 0, as in [`Coef::new`].
    pub fn new(values: [f64; N]) -> Self {
        const { assert!(N <= 6, "CoefRow holds at most six constants") };
        let v = values.map(|c| if c.is_finite() { c } else { 0.0 });
        let max = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let shift = if max == 0.0 {
            0
        } else {
            (27 - libm::floor(libm::log2(max)) as i32).clamp(-62, 62)
        };
        let lim = (1u32 << 28) as f64;
        let mant = v.map(|c| libm::round(c * libm::exp2(shift as f64)).clamp(-lim, lim) as i32);
        CoefRow {
            coefs: values.map(Coef::new),
            mant,
            split: mant.map(|m| (m >> 16, m & 0xFFFF)),
            shift,
        }
    }

    /// The constants as given to [`new`](Self::new).
    pub fn values(&self) -> [f64; N] {
        self.coefs.map(|c| c.value())
    }

    /// The `I16F16` form: the mantissas and the common shift.
    pub(crate) fn fixed(&self) -> (&[i32; N], i32) {
        (&self.mant, self.shift)
    }

    /// The mantissas split into `(Mⱼ >> 16, Mⱼ mod 2¹⁶)`.
    pub(crate) fn split(&self) -> &[(i32, i32); N] {
        &self.split
    }
}

/// A boundary-layer slope `k/ε` prepared so that its product at the layer's
/// edge never exceeds the saturation value `k` in the backend's
/// arithmetic: the first candidate `make(value·f)` with `fits` true, for
/// `f = 1, 1 − 2⁻²³, 1 − 2·2⁻²³, …` (64 steps: the prepared value and
/// the product each round by at most about 2⁻²³ relative), then
/// `f = 1 − 2⁻²², …, 1 − 2⁻¹` as a guard. A rounded product by a positive
/// factor is non-decreasing in the other operand on every backend, so a
/// slope that fits at `±ε` fits on the whole layer and the layer's value
/// needs no clamp. Usually the first candidate fits and nothing changes.
pub(crate) fn slope_within<T>(value: f64, make: impl Fn(f64) -> T, fits: impl Fn(&T) -> bool) -> T {
    const ULP23: f64 = 1.0 / 8_388_608.0;
    let fine = (0..64u32).map(|k| 1.0 - k as f64 * ULP23);
    let coarse = (1..=22u32).rev().map(|j| 1.0 - 1.0 / (1u64 << j) as f64);
    for f in fine.chain(coarse) {
        let t = make(value * f);
        if fits(&t) {
            return t;
        }
    }
    make(value * 0.5)
}

/// `⌊(V + 2^(sh−1)) / 2^sh⌋` of the signed 64-bit `V = hi·2³² + lo` for
/// `sh ∈ [1, 62]`, in 32-bit words, given `|V| + 2^(sh−1) < 2⁶³` (so the
/// rounding constant carries into `hi` without overflow): the rounding
/// shift shared by [`Coef::scale_wide`] and its Armv6-M form.
#[inline(always)]
fn round_shift_words(mut hi: i32, mut lo: u32, sh: u32) -> i64 {
    if sh <= 32 {
        let (l, c) = lo.overflowing_add(1 << (sh - 1));
        lo = l;
        hi += c as i32;
    } else {
        hi += 1 << (sh - 33);
    }
    let (h, l) = if sh >= 32 {
        (hi >> 31, (hi >> (sh - 32)) as u32)
    } else {
        (hi >> sh, ((hi as u32) << (32 - sh)) | (lo >> sh))
    };
    ((h as u32 as u64) << 32 | l as u64) as i64
}

impl Coef {
    /// Prepare a coefficient. A zero or non-finite value yields the zero
    /// coefficient. Magnitudes are limited to `[2^-60, 2^40]`; smaller
    /// values act as 0 in fixed point, larger ones saturate every product.
    pub fn new(value: f64) -> Self {
        if !value.is_finite() || value == 0.0 {
            return Coef {
                value: 0.0,
                value_f32: 0.0,
                mult: 0,
                shift: 0,
                mag: 0,
                negative: false,
                signed: SignedCoef::new(0, 0),
                units: [0; 2],
                #[cfg(any(test, armv6m))]
                wide: WideCoef::new(0, 0),
            };
        }
        // |value| · 2^shift ∈ [2^30, 2^31). Beyond 2^40 the fixed-point
        // mantissa stays at 2^31 (|x · mult| ≤ 2^62 in `scale_int`): every
        // non-zero product of such a coefficient saturates anyway.
        let e = libm::floor(libm::log2(value.abs())) as i32;
        let shift = (30 - e).clamp(-10, 90);
        let mult = libm::round(value.abs() * libm::exp2(shift as f64)).min(2_147_483_648.0) as i64;
        let signed_mult = if value < 0.0 { -mult } else { mult };
        Self::from_mantissa(value, signed_mult, shift)
    }

    /// The coefficient `signed_mult · 2^−shift` (fixed point) built from
    /// `value` (floats), with its prepared products.
    fn from_mantissa(value: f64, signed_mult: i64, shift: i32) -> Self {
        let value_f32 = (value as f32).clamp(f32::MIN, f32::MAX);
        Self::from_parts(value, value_f32, value < 0.0, signed_mult, shift)
    }

    /// The coefficient with the given value, `f32` value, sign and
    /// fixed-point mantissa and shift; the prepared products with integer
    /// operations only.
    fn from_parts(
        value: f64,
        value_f32: f32,
        negative: bool,
        signed_mult: i64,
        shift: i32,
    ) -> Self {
        let mult = signed_mult.abs();
        // ±mult·2^−shift saturated (used only when `shift ≤ 1`, where it
        // is an integer or 2³⁰).
        let unit = |s: i64| -> i32 {
            let v = (s * signed_mult) as i128;
            let v = if shift <= 0 {
                v << (-shift).min(64)
            } else {
                v >> shift.min(127)
            };
            v.clamp(i32::MIN as i128, i32::MAX as i128) as i32
        };
        Coef {
            value,
            value_f32,
            mult: signed_mult,
            shift,
            mag: mult as u32,
            negative,
            signed: SignedCoef::new(signed_mult, shift),
            units: [unit(1), unit(-1)],
            #[cfg(any(test, armv6m))]
            wide: WideCoef::new(signed_mult, shift),
        }
    }

    /// The coefficient [`Coef::new`] prepares from `value`, built from its
    /// stored quantization instead: `value_f32` (the `f32` rounding),
    /// `signed_mult` and `shift` (`value ≈ signed_mult·2^−shift`), with
    /// integer operations only. For proof harnesses, whose solver would
    /// otherwise evaluate `new`'s `log2`, `exp2` and rounding on its own;
    /// tests compare every use with `Coef::new` field by field.
    #[cfg(any(kani, test))]
    pub(crate) fn from_quantized(value: f64, value_f32: f32, signed_mult: i64, shift: i32) -> Self {
        Self::from_parts(value, value_f32, value < 0.0, signed_mult, shift)
    }

    /// `self · 2^k` with the same mantissa (the fixed-point exponent
    /// moved by `k`, the float value scaled by `2^k`): the fixed-point
    /// products of the result are those of `self` with `k` more bits of
    /// scale, exactly (`scale_int(x, e + k)` of `self` equals
    /// `scale_int(x, e)` of the result), which [`Coef::new`] of the scaled
    /// value does not promise (its exponent comes from a rounded `log2`).
    pub(crate) fn times_pow2(&self, k: i32) -> Coef {
        if self.mult == 0 {
            return *self;
        }
        Self::from_mantissa(self.value * libm::exp2(k as f64), self.mult, self.shift - k)
    }

    /// The value this coefficient was built from.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// The value the fixed-point products use, `mult · 2^-shift` (the
    /// 31-bit rounding of [`value`](Self::value)).
    pub(crate) fn quantized(&self) -> f64 {
        self.mult as f64 * libm::exp2(-self.shift as f64)
    }

    /// `round(x · c · 2^extra)` saturated to `i32`, for an integer `x`
    /// clamped to `±2^31` (`extra` = 16 turns counts into `I16F16` bits).
    ///
    /// Sign and magnitude are handled apart, and the magnitude product and
    /// its rounding shift use 32-bit words only
    /// ([`fixed::scaled_product`]): on Armv6-M no `__aeabi_lmul` and no
    /// 64-bit shift. Equal to [`scale_int_reference`](Self::scale_int_reference)
    /// (the 64-bit formula) for every input (tests below).
    #[inline(always)]
    pub(crate) fn scale_int(&self, x: i64, extra: i32) -> i32 {
        let x = x.clamp(-(1i64 << 31), 1i64 << 31);
        // |x|, |mult| ≤ 2^31 fit u32.
        let a = x.unsigned_abs() as u32;
        fixed::scaled_product((x < 0) != self.negative, a, self.mag, self.shift - extra)
    }

    /// [`scale_int`](Self::scale_int)`(x, 0)` for an `i32` (the product of
    /// [`Scalar::mul_coef`] on `I16F16` bits): the same result for every
    /// `x` (tests below), in fewer 32-bit operations.
    ///
    /// For `1 ≤ shift ≤ 62` (coefficients in `[2^-32, 2^30)`, which
    /// covers the prepared control-law constants) the product is the signed
    /// `V = x·m` of [`fixed::signed_wide_mul`] (`|V| < 2⁶²`), then
    /// `⌊(V + 2^(sh−1)) / 2^sh⌋`:
    /// * `sh ≥ 33`: the rounding constant `2^(sh−1)` has no low-word bits,
    ///   and `⌊(hi·2³² + lo + 2^(sh−1)) / 2^sh⌋ = ⌊(hi + 2^(sh−33)) /
    ///   2^(sh−32)⌋` because `lo < 2³²` cannot carry the integer numerator
    ///   past a multiple of `2^(sh−32)`; the result is below `2²⁹` in
    ///   magnitude, so it never saturates.
    /// * `sh ≤ 32`: [`fixed::round_shift_sat`].
    ///
    /// On Armv6-M the product comes from the prepared 16-bit halves of `m`
    /// with the low-word rounding constant in its carry chain
    /// (`scale_i32_split`).
    ///
    /// No absolute values and no sign fix-up of the result; the rounding
    /// constant and shift are prepared per coefficient (a mantissa of 2³¹
    /// halved, a coefficient below 2⁻³² or zero as `m = 0`:
    /// [`SignedCoef::new`]). The coefficients of `|c| ≥ 2³⁰` saturate
    /// every product with `|x| ≥ 2`; their products with 0 and ±1 are
    /// prepared (`units`): a few comparisons, no multiply.
    #[inline(always)]
    pub(crate) fn scale_i32(&self, x: i32) -> i32 {
        let Some(c) = self.signed else {
            return match x {
                0 => 0,
                1 => self.units[0],
                -1 => self.units[1],
                _ if (x < 0) != self.negative => i32::MIN,
                _ => i32::MAX,
            };
        };
        #[cfg(armv6m)]
        {
            Self::scale_i32_split(&c, x)
        }
        #[cfg(not(armv6m))]
        {
            let (hi, lo) = fixed::signed_wide_mul(x, c.m);
            if c.high_only {
                // |hi| ≤ 2³⁰ and round = 2^(sh−33) ≤ 2²⁹: no overflow.
                return (hi + c.round as i32) >> c.rs;
            }
            fixed::round_shift_sat(hi, lo, c.round, c.rs)
        }
    }

    /// The prepared signed path of [`scale_i32`](Self::scale_i32) on
    /// Armv6-M (built on every target so the host tests check it): the
    /// product from the prepared halves of `m` with the rounding constant
    /// (for `sh ≤ 32`) added to the low word in the same carry chain
    /// ([`fixed::signed_wide_mul_add_split`]), then the shift
    /// ([`fixed::shift_sat`]; for `sh ≥ 33` the rounding of the high word
    /// alone, as in [`scale_i32`](Self::scale_i32)).
    #[inline(always)]
    #[cfg(any(test, armv6m))]
    fn scale_i32_split(c: &SignedCoef, x: i32) -> i32 {
        let (hi, lo) = fixed::signed_wide_mul_add_split(x, c.m_hi, c.m_lo, c.round_lo);
        if c.high_only {
            // round_lo = 0: the high word of x·m; |hi| ≤ 2³⁰ and round =
            // 2^(sh−33) ≤ 2²⁹, no overflow.
            return (hi + c.round as i32) >> c.rs;
        }
        fixed::shift_sat(hi, lo, c.round, c.rs)
    }

    /// `round(x · c · 2^extra)` (ties up) saturated to `i64`: the
    /// increment of a Q16.48 accumulator for `extra = 32` and `x` the bits
    /// of an `I16F16` ([`Scalar::integrate`]). The product `x·mult` is
    /// exact (`|x·mult| ≤ 2⁶²`): on Armv6-M the signed product from the
    /// prepared halves of the mantissa (`scale_wide_split`, no
    /// `__aeabi_lmul`, no absolute values or negation), elsewhere the
    /// unsigned [`fixed::wide_mul`] of the magnitudes with the sign applied
    /// ([`scale_wide_magnitude`](Self::scale_wide_magnitude)); one form for
    /// every coefficient.
    ///
    /// The rounding shift works on the two 32-bit words (a shift by less
    /// than 32 and a word move), so Armv6-M calls no 64-bit shift
    /// (`__aeabi_lasr`, `__aeabi_llsl`); equal to the exact formula for
    /// every coefficient, argument and `extra` (tests below).
    #[inline(always)]
    pub(crate) fn scale_wide(&self, x: i32, extra: i32) -> i64 {
        #[cfg(armv6m)]
        {
            self.scale_wide_split(x, extra)
        }
        #[cfg(not(armv6m))]
        {
            self.scale_wide_magnitude(x, extra)
        }
    }

    /// [`scale_wide`](Self::scale_wide) from the unsigned product of the
    /// magnitudes (the form of targets with a widening multiply).
    #[inline]
    #[cfg_attr(armv6m, allow(dead_code))]
    fn scale_wide_magnitude(&self, x: i32, extra: i32) -> i64 {
        let (hi, lo) = fixed::wide_mul(x.unsigned_abs(), self.mag);
        let neg = (x < 0) != self.negative;
        let sh = self.shift - extra;
        if sh <= 0 {
            // P·2^s with P = |x·mult| ≤ 2⁶², saturated: it fits exactly
            // when P < 2^(63 − s).
            let s = sh.unsigned_abs();
            if hi == 0 && lo == 0 {
                return 0;
            }
            let fits = if s >= 32 {
                // s ≤ 63 here, or nothing fits: P < 2^(63 − s) ≤ 2³¹.
                s < 63 && hi == 0 && lo >> (63 - s) == 0
            } else {
                hi >> (31 - s) == 0
            };
            if !fits {
                return if neg { i64::MIN } else { i64::MAX };
            }
            let (h, l) = if s >= 32 {
                (lo << (s - 32), 0)
            } else {
                // `(lo >> 1) >> (31 − s)` is `lo >> (32 − s)`, and 0 for
                // `s = 0`.
                ((hi << s) | ((lo >> 1) >> (31 - s)), lo << s)
            };
            let p = ((h as u64) << 32 | l as u64) as i64;
            return if neg { -p } else { p };
        }
        if sh >= 63 {
            // |V| ≤ 2⁶²: |V/2^sh| ≤ ½, rounded (ties up) to 1 only for
            // V = 2⁶², sh = 63.
            return (sh == 63 && !neg && hi == 1 << 30 && lo == 0) as i64;
        }
        // V = ±P in two's complement words, then ⌊(V + 2^(sh−1)) / 2^sh⌋
        // (|V| + 2^(sh−1) < 2⁶³: no overflow).
        let (mut hi, mut lo) = (hi as i32, lo);
        if neg {
            lo = lo.wrapping_neg();
            hi = (!hi).wrapping_add((lo == 0) as i32);
        }
        round_shift_words(hi, lo, sh as u32)
    }

    /// [`scale_wide`](Self::scale_wide) on Armv6-M (built on every target
    /// so the host tests check it): the product `V = x·m` is the exact
    /// signed product by the mantissa of [`WideCoef`] (below `2³¹`, so
    /// `|V| < 2⁶²`) from its prepared 16-bit halves
    /// ([`fixed::signed_wide_mul_add_split`]): no absolute values and no
    /// negation. Then the same saturating shift or rounding shift on the
    /// two words.
    #[inline(never)]
    #[cfg(any(test, armv6m))]
    fn scale_wide_split(&self, x: i32, extra: i32) -> i64 {
        let w = &self.wide;
        let sh = w.shift - extra;
        if sh >= 63 {
            // |V| < 2⁶²: |V/2^sh| < ½ rounds to 0.
            return 0;
        }
        let (hi, lo) = w.product(x);
        if sh <= 0 {
            // V·2^s saturated: it fits exactly when the top s + 1 bits of
            // the 64-bit V are copies of its sign bit.
            let s = sh.unsigned_abs();
            let fits = if s >= 64 {
                hi == 0 && lo == 0
            } else if s >= 32 {
                // V fits an i32 and has 63 − s bits besides the sign.
                let t = (lo as i32) >> (63 - s);
                hi == (lo as i32) >> 31 && (t == 0 || t == -1)
            } else {
                let t = hi >> (31 - s);
                t == 0 || t == -1
            };
            if !fits {
                return if hi < 0 { i64::MIN } else { i64::MAX };
            }
            let (h, l) = if s >= 32 {
                (lo << (s - 32), 0)
            } else {
                // `(lo >> 1) >> (31 − s)` is `lo >> (32 − s)`, and 0 for
                // `s = 0`.
                (((hi as u32) << s) | ((lo >> 1) >> (31 - s)), lo << s)
            };
            return ((h as u64) << 32 | l as u64) as i64;
        }
        // ⌊(V + 2^(sh−1)) / 2^sh⌋ (|V| + 2^(sh−1) < 2⁶³: no overflow).
        round_shift_words(hi, lo, sh as u32)
    }

    /// The straightforward 64-bit form of [`scale_int`](Self::scale_int),
    /// the reference of its tests.
    #[cfg(test)]
    pub(crate) fn scale_int_reference(&self, x: i64, extra: i32) -> i32 {
        let x = x.clamp(-(1i64 << 31), 1i64 << 31);
        let p = x * self.mult; // |p| ≤ 2^62
        let sh = self.shift - extra;
        let r = if sh > 0 {
            if sh >= 63 {
                0
            } else {
                (p + (1i64 << (sh - 1))) >> sh
            }
        } else if p == 0 {
            0
        } else if -sh >= 32 || p.unsigned_abs() > (i64::MAX as u64 >> -sh) {
            if p > 0 {
                i64::MAX
            } else {
                i64::MIN
            }
        } else {
            p << -sh
        };
        fixed::sat_i64(r)
    }

    /// The `f32` value.
    #[inline]
    pub(crate) fn f32_value(&self) -> f32 {
        self.value_f32
    }
}

/// Marsaglia's xorshift64 step: the seeded argument generator of tests
/// that need many reproducible words without a proptest runner.
#[cfg(test)]
pub(crate) fn xorshift64(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// The crate-private part of every backend: kernel variants and prepared
/// forms made for one call site each (a cheaper kernel where the caller
/// bounds the argument, a product by a factor prepared for counts). Its
/// methods are callable wherever `S: Scalar` is, inside the crate; a user
/// neither sees nor implements them (the trait also seals [`Scalar`]: the
/// proofs in `proofs/` cover exactly the implementations in this crate).
pub(crate) mod sealed {
    #[allow(unused_imports)]
    use super::{hypot, CountCoef, Scalar};

    /// See the module.
    pub trait Sealed: Sized {
        /// A binary floating-point backend (`f32`, `f64`): NaN and ±∞
        /// exist and rounding is relative to the magnitude; `false` for
        /// fixed point. For code whose best form differs between the two
        /// (a constant, folded at compile time).
        const FLOAT: bool = true;
        /// [`from_counts`](Self::from_counts) for a count that fits `i32` (a
        /// difference of two wrapping counter readings) and a factor prepared
        /// as a [`CountCoef`]: the same value, bit for bit. `I16F16` takes the
        /// 32-bit product of [`mul_coef`](Self::mul_coef) by the factor moved
        /// up 16 bits instead of the general 64-bit count product.
        #[inline]
        fn from_counts_i32(counts: i32, scale: &CountCoef) -> Self
        where
            Self: Scalar,
        {
            Self::from_counts(counts as i64, &scale.coef)
        }
        /// `√(self² + b²)` for components of magnitude at most 1 (the sine
        /// of a bend from its two components). `I16F16` scales both by a
        /// power of two instead of dividing by the larger and takes the root
        /// as the product of the scaled sum of squares and its table
        /// reciprocal root ([`kernels::i16f16::hypot_unit`]: within 1 LSB,
        /// inputs clamped to `±(1 − 2⁻¹⁶)`); the default is
        /// `m·√(1 + (n/m)²)` with `m ≥ n` the magnitudes, free of overflow and
        /// of the loss of squaring tiny values.
        #[inline]
        fn hypot_unit(self, b: Self) -> Self
        where
            Self: Scalar,
        {
            hypot(self, b)
        }
        /// `1/√self` for `self ∈ [¼, 1]` (inputs clamped to it): the
        /// reciprocal of a cosine known to be at least ½. `I16F16` takes a
        /// 24-piece cubic table ([`kernels::i16f16::rsqrt_quarter`]: within
        /// 1 LSB, no root or division); the default is `1/√x`.
        #[inline]
        fn rsqrt_quarter(self) -> Self
        where
            Self: Scalar,
        {
            let quarter = Self::from_f64(0.25);
            // A NaN fails both tests and stays NaN.
            let x = if self > Self::ONE {
                Self::ONE
            } else if self < quarter {
                quarter
            } else {
                self
            };
            Self::ONE.div(x.sqrt())
        }
        /// [`atan`](Self::atan) of a value below 2 in magnitude (the tangent
        /// of an angle within ±63°, e.g. formed from a bounded ratio without
        /// a division). `I16F16` evaluates it without the division `atan`
        /// needs above 1 ([`kernels::i16f16::atan_small`]: bit for bit `atan`
        /// below 1, within the same 1 LSB bound up to 2, inputs of 2 and above
        /// clamped to `2 − 2⁻¹⁶`); floats take `atan`.
        #[inline]
        fn atan_small(self) -> Self
        where
            Self: Scalar,
        {
            self.atan()
        }
        /// [`sqrt`](Self::sqrt) of a value below 4 (a sum of squares of
        /// values bounded by 1, `1 + r²` with `|r| ≤ 1`): the value of `sqrt`,
        /// bit for bit, for every input below 4. `I16F16` takes a shorter root
        /// (seven trial steps fewer: [`kernels::i16f16::sqrt_small`]) and
        /// clamps inputs of 4 and above to `4 − 2⁻¹⁶`; floats take `sqrt`.
        #[inline]
        fn sqrt_small(self) -> Self
        where
            Self: Scalar,
        {
            self.sqrt()
        }
        /// [`from_counts`](Scalar::from_counts) by a factor prepared as a
        /// [`CountCoef`]: the same value, bit for bit. `I16F16` takes the
        /// product of [`from_counts_i32`](Scalar::from_counts_i32) for every count
        /// below `2³¹` (`from_counts` clamps the ones below `−2³¹` to `−2³¹`)
        /// and the prepared value of `2³¹` counts, where `from_counts` clamps
        /// the larger ones, above.
        #[inline]
        fn from_counts_prepared(counts: i64, scale: &CountCoef) -> Self
        where
            Self: Scalar,
        {
            Self::from_counts(counts, &scale.coef)
        }
        /// `self / rhs` for a ratio `|self| ≤ |rhs|` (a normalized component,
        /// a ratio of magnitudes): the value of [`div`](Scalar::div), bit for
        /// bit, for every such pair. Fixed point returns it within `[−1, 1]`
        /// and with the sign of the quotient (0 for `self = 0`) by
        /// construction, and clamps to `±1` outside the precondition; floats
        /// divide (IEEE rounding keeps `|self/rhs| ≤ 1`).
        #[inline]
        fn div_unit_range(self, rhs: Self) -> Self
        where
            Self: Scalar,
        {
            self.div(rhs)
        }
        /// [`tan`](Scalar::tan) for an argument known to lie in
        /// `|x| ≤ atan 8 = 1.446441` rad (the torque estimator's, by the
        /// validated `c_f·max_torque ≤ 7.5`). `I16F16`: one table polynomial
        /// without the quotient near the pole ([`kernels::i16f16::tan_bounded`](super::kernels::i16f16::tan_bounded),
        /// within 1 LSB, odd, non-decreasing; beyond the bound the argument is
        /// clamped to it); `f32`: `tan` itself with a cheaper limiting of the
        /// argument ([`kernels::f32::tan_bounded`](super::kernels::f32::tan_bounded), bit for bit `tan` on the
        /// domain); the default is `tan`.
        #[inline]
        fn tan_bounded(self) -> Self
        where
            Self: Scalar,
        {
            self.tan()
        }
        /// [`cos_turn`](Scalar::cos_turn) at the accuracy a small model term
        /// needs (the harmonics of the kinematic error, eq. (3.7), whose
        /// amplitudes are arcseconds). `f32`: linear interpolation in a
        /// 1025-knot table, ≤ 4.8e-6 absolute
        /// ([`kernels::f32::cos_turn_coarse`](super::kernels::f32::cos_turn_coarse)); the default is `cos_turn`.
        #[inline]
        fn cos_turn_coarse(turn: u32) -> Self
        where
            Self: Scalar,
        {
            Self::cos_turn(turn)
        }
        /// `(sin, cos)` by [`cos_turn_coarse`](Self::cos_turn_coarse):
        /// exactly `(cos_turn_coarse(turn − 2³⁰), cos_turn_coarse(turn))`; the
        /// default is [`sin_cos_turn`](Scalar::sin_cos_turn).
        #[inline]
        fn sin_cos_turn_coarse(turn: u32) -> (Self, Self)
        where
            Self: Scalar,
        {
            Self::sin_cos_turn(turn)
        }
        /// `n·self` for a whole number `n` whose product the backend holds,
        /// `|n·self| ≤ MAX` (the caller bounds `n`, e.g. by
        /// `⌊MAX/|self|⌋`): fixed point multiplies its bits by `n`, one
        /// 32-bit product that cannot wrap under the precondition (and
        /// wraps, never panics, outside it); floats convert `n` and multiply.
        #[inline]
        fn mul_whole(self, n: i32) -> Self
        where
            Self: Scalar,
        {
            Self::from_i32(n).mul(self)
        }
    }
}

#[cfg(any(kani, test))]
pub(crate) mod words;

#[cfg(test)]
mod tests;
