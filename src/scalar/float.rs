//! `f32` and `f64` backends.
//!
//! Arithmetic is plain IEEE-754 except for [`Scalar::div`], which returns
//! `±MAX` instead of an infinity on division by zero and `0` for `0/0`.
//! Conversions from `f64` saturate at `±MAX` and map NaN to 0.
//! The kernels are those of [`kernels::f32`] and [`kernels::f64`].

use super::{kernels, Scalar};

/// `c as f32`, the same correctly rounded value, without the
/// `__aeabi_l2f` library call on 32-bit cores: for `|c| < 2⁴⁷` the high
/// part `⌊c/2²⁴⌋` and the low part `c mod 2²⁴` are exact in `f32`, and so
/// is `hi·2²⁴`, so the one rounding of their sum is the rounding of `c`
/// itself. Larger counts first take `t = ⌊c/2¹⁶⌋` with the lost bits kept
/// as a sticky bit (`t | 1` when any is set), which rounds as `c` does,
/// and scale the rounded `t` back by 2¹⁶ (exact).
#[inline]
fn count_to_f32(c: i64) -> f32 {
    // −2⁴⁷ ≤ c < 2⁴⁷ exactly when the high word `⌊c/2³²⌋` is in
    // [−2¹⁵, 2¹⁵): one add and one shift on a 32-bit core.
    let high = (c >> 32) as i32;
    // The split `t = hi·2²⁴ + lo` of `t = c` or of `t = ⌊c/2¹⁶⌋ | sticky`,
    // each part from the words of `c` directly.
    let (hi, lo, scale) = if ((high as u32).wrapping_add(1 << 15)) >> 16 == 0 {
        ((c >> 24) as i32, c as i32 & 0xFF_FFFF, 1.0)
    } else {
        // |c| ≥ 2⁴⁷: the f32 values near `c` are multiples of 2²⁴ and the
        // rounding midpoints multiples of 2²³, so all are multiples of
        // 2¹⁶. `t·2¹⁶` is `c` itself, or (a bit lost) an odd multiple of
        // 2¹⁶ between the same two consecutive multiples of 2¹⁶ as `c`
        // (the floor when it is odd, one above when it is even): never a
        // midpoint, and no midpoint or f32 value between it and `c`, so
        // both round alike. `t ∈ [−2⁴⁷, 2⁴⁷)` splits exactly as below:
        // `⌊t/2²⁴⌋ = ⌊c/2⁴⁰⌋` (the sticky bit is bit 0) and `t mod 2²⁴`
        // is bits 16..40 of `c` with bit 0 set by the sticky bit.
        let sticky = (c as u32 & 0xFFFF != 0) as i32;
        (high >> 8, ((c >> 16) as i32 & 0xFF_FFFF) | sticky, 65_536.0)
    };
    // |hi| < 2²³ and 0 ≤ lo < 2²⁴: both exact, and so is hi·2²⁴; the sum
    // rounds once; times 1 or 2¹⁶: exact.
    (hi as f32 * 16_777_216.0 + lo as f32) * scale
}

/// `c as f64` (correctly rounded; not on a hot path of any target).
#[inline]
fn count_to_f64(c: i64) -> f64 {
    c as f64
}

/// `v` limited to `[lo, hi]`, or `keep` limited to it when `v` is NaN:
/// two comparisons on the common path (a NaN fails both).
#[inline(always)]
fn clamp_or_keep<T: Scalar>(v: T, keep: T, lo: T, hi: T) -> (T, bool) {
    if v >= lo {
        if v > hi {
            (hi, true)
        } else {
            (v, false)
        }
    } else if v < lo {
        (lo, true)
    } else {
        (keep.clamp(lo, hi), true)
    }
}

/// [`Scalar::integrate`] on `f32`: a compensated sum. The step plus the
/// carried residual, `b = step + residual`, is added to the value and the
/// rounding error of that addition, `b − (s − v)`, becomes the new residual
/// (Fast2Sum, exact when `|v| ≥ |b|`, the case of a slow integrator; when
/// not, the residual is still within an ulp of `s`). So the value plus
/// residual carries about 48 bits, and a step far below half an ulp of the
/// value (`2⁻²⁵` relative: Table 4.1's `f̂_τ` steps are ~`5e-8` of `f̂_τ ≈ 1`)
/// accumulates instead of being lost. A clamped (or NaN) sum has residual 0.
#[inline(always)]
#[allow(clippy::eq_op)] // `lo − lo`: the +0 residual, formed where it is needed
fn integrate_f32(v: f32, residual: f32, step: f32, lo: f32, hi: f32) -> (f32, f32) {
    let b = step + residual;
    let s = v + b;
    // `clamp_or_keep(s, v, lo, hi)` with the NaN case first replaced by
    // `v` (one select), so the range tests serve both: the same value and
    // flag (`float_integrate_is_clamp_or_keep`).
    let nan = s.is_nan();
    let w = if nan { v } else { s };
    // The residual 0 of a clamped sum as `lo − lo` and `hi − hi` (+0 for
    // finite bounds, the box's): each in its own branch, where the common
    // path does not pay for a hoisted constant.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(w >= lo) {
        (lo, lo - lo)
    } else if w > hi {
        (hi, hi - hi)
    } else if nan {
        (w, 0.0)
    } else {
        (s, b - (s - v))
    }
}

/// [`Scalar::integrate`] on `f64`: `v + step`, clamped (a NaN sum keeps
/// `v`). A step is lost only below `2⁻⁵³` of the value: Table 4.1's `f̂_τ`
/// steps (`≳ 1e-12` of the value whenever `r Y_4` is above `1e-9`) are
/// kept.
#[inline(always)]
fn integrate_f64(v: f64, _residual: (), step: f64, lo: f64, hi: f64) -> (f64, ()) {
    (clamp_or_keep(v + step, v, lo, hi).0, ())
}

macro_rules! float_scalar {
    ($t:ident, $name:literal, $k:ident, $countfn:ident, $conv:ident, $res:ty, $integrate:ident,
     $coarse:path, $sin_cos_coarse:path, $tan_bounded:path) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MIN: Self = $t::MIN;
            const MAX: Self = $t::MAX;
            const RESOLUTION: Self = $t::EPSILON;
            const PI: Self = core::$t::consts::PI;
            const FRAC_PI_2: Self = core::$t::consts::FRAC_PI_2;
            const UNITS: super::units::Units = super::units::SI;

            #[inline]
            fn from_f64(x: f64) -> Self {
                if x.is_nan() {
                    0.0
                } else {
                    // `as` rounds to nearest; clamp the overflow to ±MAX.
                    let y = x as $t;
                    if y.is_infinite() {
                        if y > 0.0 {
                            $t::MAX
                        } else {
                            $t::MIN
                        }
                    } else {
                        y
                    }
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn from_i32(x: i32) -> Self {
                x as $t
            }
            #[inline]
            fn from_counts(counts: i64, scale: &super::Coef) -> Self {
                $conv(counts) * scale.$countfn()
            }
            #[inline]
            fn mul_coef(self, c: &super::Coef) -> Self {
                self * c.$countfn()
            }
            type Residual = $res;
            #[inline]
            fn integrate(
                self,
                residual: $res,
                x: Self,
                c: &super::Coef,
                lo: Self,
                hi: Self,
            ) -> (Self, $res) {
                $integrate(self, residual, x * c.$countfn(), lo, hi)
            }
            #[inline]
            fn add(self, rhs: Self) -> Self {
                self + rhs
            }
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                self - rhs
            }
            #[inline]
            fn mul(self, rhs: Self) -> Self {
                self * rhs
            }
            #[inline]
            fn div(self, rhs: Self) -> Self {
                if rhs == 0.0 {
                    if self > 0.0 {
                        $t::MAX
                    } else if self < 0.0 {
                        $t::MIN
                    } else {
                        0.0
                    }
                } else {
                    self / rhs
                }
            }
            #[inline]
            fn neg(self) -> Self {
                -self
            }
            #[inline]
            fn abs(self) -> Self {
                // Clear the sign bit: exact, no libm call in no_std.
                $t::from_bits(
                    self.to_bits() & !(1 << ($t::MANTISSA_DIGITS + $t::MAX_EXP.trailing_zeros())),
                )
            }
            #[inline]
            fn copysign(self, sign: Self) -> Self {
                // The sign bit of `sign` on the magnitude of `self`: two bit
                // operations instead of comparisons and a product.
                let s = 1 << ($t::MANTISSA_DIGITS + $t::MAX_EXP.trailing_zeros());
                $t::from_bits((self.to_bits() & !s) | (sign.to_bits() & s))
            }
            #[inline]
            fn atan(self) -> Self {
                kernels::$k::atan(self)
            }
            #[inline]
            fn tan(self) -> Self {
                kernels::$k::tan(self)
            }
            #[inline]
            fn exp(self) -> Self {
                kernels::$k::exp(self)
            }
            #[inline]
            fn exp_neg_abs(self) -> Self {
                kernels::$k::exp_neg_abs(self)
            }
            #[inline]
            fn sin(self) -> Self {
                kernels::$k::sin(self)
            }
            #[inline]
            fn cos(self) -> Self {
                kernels::$k::cos(self)
            }
            #[inline]
            fn sin_cos(self) -> (Self, Self) {
                kernels::$k::sin_cos(self)
            }
            #[inline]
            fn cos_turn(turn: u32) -> Self {
                kernels::$k::cos_turn(turn)
            }
            #[inline]
            fn sin_cos_turn(turn: u32) -> (Self, Self) {
                kernels::$k::sin_cos_turn(turn)
            }
            #[inline]
            fn atan2(self, x: Self) -> Self {
                kernels::$k::atan2(self, x)
            }
            #[inline]
            fn acos(self) -> Self {
                kernels::$k::acos(self)
            }
            #[inline]
            fn sqrt(self) -> Self {
                kernels::$k::sqrt(self)
            }
        }

        impl super::sealed::Sealed for $t {
            #[inline]
            fn from_counts_i32(counts: i32, scale: &super::CountCoef) -> Self {
                // `as` rounds an `i32` to nearest (even), as the `i64`
                // conversion of `from_counts` does: the same value, with
                // one hardware conversion.
                counts as $t * scale.coef().$countfn()
            }
            #[inline]
            fn tan_bounded(self) -> Self {
                $tan_bounded(self)
            }
            #[inline]
            fn cos_turn_coarse(turn: u32) -> Self {
                $coarse(turn)
            }
            #[inline]
            fn sin_cos_turn_coarse(turn: u32) -> (Self, Self) {
                $sin_cos_coarse(turn)
            }
        }
    };
}

// f32 takes the table kernels for the small model terms and the
// estimator's bounded `tan`; f64 keeps its full-accuracy `cos_turn` and
// its `tan` there.
float_scalar!(
    f32,
    "f32",
    f32,
    f32_value,
    count_to_f32,
    f32,
    integrate_f32,
    kernels::f32::cos_turn_coarse,
    kernels::f32::sin_cos_turn_coarse,
    kernels::f32::tan_bounded
);
float_scalar!(
    f64,
    "f64",
    f64,
    value,
    count_to_f64,
    (),
    integrate_f64,
    kernels::f64::cos_turn,
    kernels::f64::sin_cos_turn,
    kernels::f64::tan
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_to_f32_is_the_correctly_rounded_conversion() {
        let mut xs = vec![0i64, 1, -1, i64::MAX, i64::MIN, 1 << 47, -(1 << 47)];
        for k in 0..63 {
            for d in [-3i64, -1, 0, 1, 3] {
                xs.extend([(1i64 << k) + d, -(1i64 << k) + d]);
            }
            // Halfway cases of the 24-bit mantissa (round to even).
            if k > 25 {
                xs.extend([
                    (1i64 << k) + (1 << (k - 24)),
                    (1i64 << k) + 3 * (1 << (k - 25)),
                    // just above and below the halfway point, by one
                    (1i64 << k) + (1 << (k - 24)) + 1,
                    (1i64 << k) + (1 << (k - 24)) - 1,
                    -(1i64 << k) - (1 << (k - 24)) - 1,
                    // an odd mantissa at the halfway point (ties to even up)
                    (1i64 << k) + (1 << (k - 23)) + (1 << (k - 24)),
                ]);
            }
        }
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..200_000 {
            let x = crate::scalar::xorshift64(&mut state);
            xs.push((x as i64) >> (x % 40));
        }
        for c in xs {
            assert_eq!(count_to_f32(c).to_bits(), (c as f32).to_bits(), "{c}");
        }
    }

    /// `integrate_f32` as it was first written (`clamp_or_keep` of the
    /// sum, residual 0 when clamped), the reference of its test.
    fn integrate_f32_reference(v: f32, residual: f32, step: f32, lo: f32, hi: f32) -> (f32, f32) {
        let b = step + residual;
        let s = v + b;
        let (out, clamped) = clamp_or_keep(s, v, lo, hi);
        if clamped {
            (out, 0.0)
        } else {
            (s, b - (s - v))
        }
    }

    /// Bit for bit the reference on every combination of special and
    /// ordinary values, inside and outside the range, NaN included, and on
    /// random ones, for finite bounds.
    #[test]
    fn integrate_f32_equals_its_reference_bit_for_bit() {
        let vals = [
            f32::NAN,
            -f32::NAN,
            f32::NEG_INFINITY,
            f32::MIN,
            -3.0,
            -1.0,
            -0.5,
            -1e-30,
            -0.0,
            0.0,
            1e-30,
            0.5,
            1.0,
            3.0,
            f32::MAX,
            f32::INFINITY,
        ];
        let ranges = [
            (-1.0f32, 1.0f32),
            (0.0, 0.0),
            (-0.0, 2.0),
            (0.5, 1.0),
            (0.0, 0.012),
        ];
        let check = |v: f32, r: f32, x: f32, lo: f32, hi: f32| {
            let got = integrate_f32(v, r, x, lo, hi);
            let want = integrate_f32_reference(v, r, x, lo, hi);
            assert_eq!(
                (got.0.to_bits(), got.1.to_bits()),
                (want.0.to_bits(), want.1.to_bits()),
                "{v} {r} {x} [{lo}, {hi}]"
            );
        };
        for &v in &vals {
            for &r in &vals {
                for &x in &vals {
                    for &(lo, hi) in &ranges {
                        check(v, r, x, lo, hi);
                    }
                }
            }
        }
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..200_000 {
            let w = crate::scalar::xorshift64(&mut state);
            let f = |k: u32| f32::from_bits((w >> k) as u32) * 1e-30;
            let (a, b) = (f(0).abs() * 1e30, f(8).abs() * 1e30 + 1.0);
            // Finite bounds (the contract of `Scalar::integrate`).
            if !(a.is_finite() && b.is_finite()) {
                continue;
            }
            check(f(16) * 1e30, f(24), f(32) * 1e30, a.min(b), a.max(b));
        }
    }

    #[test]
    fn abs_clears_only_the_sign_bit() {
        assert_eq!(Scalar::abs(-2.5f32), 2.5);
        assert_eq!(Scalar::abs(-2.5f64), 2.5);
        assert_eq!(Scalar::abs(-0.0f64).to_bits(), 0);
        assert_eq!(Scalar::abs(f32::MIN), f32::MAX);
    }

    #[test]
    fn from_f64_saturates_and_maps_nan_to_zero() {
        assert_eq!(<f32 as Scalar>::from_f64(1e300), f32::MAX);
        assert_eq!(<f32 as Scalar>::from_f64(-1e300), f32::MIN);
        assert_eq!(<f32 as Scalar>::from_f64(f64::NAN), 0.0);
        assert_eq!(<f64 as Scalar>::from_f64(f64::INFINITY), f64::MAX);
    }

    #[test]
    fn div_by_zero_saturates() {
        assert_eq!(Scalar::div(3.0f32, 0.0), f32::MAX);
        assert_eq!(Scalar::div(-3.0f64, 0.0), f64::MIN);
        assert_eq!(Scalar::div(0.0f64, 0.0), 0.0);
        assert_eq!(Scalar::div(3.0f64, 2.0), 1.5);
    }
}
