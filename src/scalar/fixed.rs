//! The `I16F16` fixed-point backend (Q16.16: 16 integer bits including the
//! sign, 16 fractional bits).
//!
//! Range `[-32768, 32768 - 2⁻¹⁶]`, resolution `2⁻¹⁶ ≈ 1.53e-5`. Every
//! operation saturates; nothing wraps or panics. Products are rounded to
//! nearest (ties up), quotients to nearest (ties away from zero).
//!
//! The kernels are those of [`kernels::i16f16`].

use super::{kernels, Scalar, I16F16};

/// Saturate a 64-bit intermediate to the `i32` bit range.
#[inline]
pub(crate) const fn sat_i64(v: i64) -> i32 {
    if v > i32::MAX as i64 {
        i32::MAX
    } else if v < i32::MIN as i64 {
        i32::MIN
    } else {
        v as i32
    }
}

/// Rounded, saturating Q16.16 product of two raw bit patterns.
#[inline]
pub(crate) const fn mul_bits(a: i32, b: i32) -> i32 {
    sat_i64(((a as i64) * (b as i64) + (1 << 15)) >> 16)
}

/// Rounded (to nearest, ties away from zero), saturating Q16.16 quotient of
/// two raw bit patterns; `x/0` saturates with the sign of `x`, `0/0 = 0`.
#[inline]
pub(crate) const fn div_bits(a: i32, b: i32) -> i32 {
    if b == 0 {
        return if a > 0 {
            i32::MAX
        } else if a < 0 {
            i32::MIN
        } else {
            0
        };
    }
    let n = (a as i64) << 16;
    let d = b as i64;
    let mut q = n / d;
    let r = n % d;
    if 2 * r.unsigned_abs() >= d.unsigned_abs() {
        q += if (n < 0) == (d < 0) { 1 } else { -1 };
    }
    sat_i64(q)
}

impl Scalar for I16F16 {
    const NAME: &'static str = "I16F16";
    const ZERO: Self = I16F16::ZERO;
    const ONE: Self = I16F16::ONE;
    const MIN: Self = I16F16::MIN;
    const MAX: Self = I16F16::MAX;
    const RESOLUTION: Self = I16F16::DELTA;
    const PI: Self = I16F16::PI;
    const FRAC_PI_2: Self = I16F16::FRAC_PI_2;
    const UNITS: super::units::Units = super::units::FIXED;

    #[inline]
    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            I16F16::ZERO
        } else {
            // Rounds to nearest (ties to even) and saturates.
            I16F16::saturating_from_num(x)
        }
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.to_bits() as f64 / 65536.0
    }
    #[inline]
    fn from_i32(x: i32) -> Self {
        I16F16::from_bits(sat_i64((x as i64) << 16))
    }
    #[inline]
    fn from_counts(counts: i64, scale: &super::Coef) -> Self {
        I16F16::from_bits(scale.scale_int(counts, 16))
    }
    #[inline]
    fn mul_coef(self, c: &super::Coef) -> Self {
        I16F16::from_bits(c.scale_int(self.to_bits() as i64, 0))
    }
    #[inline]
    fn add(self, rhs: Self) -> Self {
        self.saturating_add(rhs)
    }
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self.saturating_sub(rhs)
    }
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        I16F16::from_bits(mul_bits(self.to_bits(), rhs.to_bits()))
    }
    #[inline]
    fn div(self, rhs: Self) -> Self {
        I16F16::from_bits(div_bits(self.to_bits(), rhs.to_bits()))
    }
    #[inline]
    fn neg(self) -> Self {
        self.saturating_neg()
    }
    #[inline]
    fn abs(self) -> Self {
        self.saturating_abs()
    }
    #[inline]
    fn atan(self) -> Self {
        kernels::i16f16::atan(self)
    }
    #[inline]
    fn tan(self) -> Self {
        kernels::i16f16::tan(self)
    }
    #[inline]
    fn exp(self) -> Self {
        kernels::i16f16::exp(self)
    }
    #[inline]
    fn sin(self) -> Self {
        kernels::i16f16::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        kernels::i16f16::cos(self)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        kernels::i16f16::sin_cos(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        kernels::i16f16::atan2(self, x)
    }
    #[inline]
    fn acos(self) -> Self {
        kernels::i16f16::acos(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        kernels::i16f16::sqrt(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_rounds_to_nearest_and_saturates() {
        // 1.5 * 1.5 = 2.25 exactly.
        assert_eq!(mul_bits(3 << 15, 3 << 15), 9 << 14);
        // LSB * 0.5 = 2^-17 rounds (ties up) to one LSB.
        assert_eq!(mul_bits(1, 1 << 15), 1);
        assert_eq!(mul_bits(i32::MAX, i32::MAX), i32::MAX);
        assert_eq!(mul_bits(i32::MIN, i32::MAX), i32::MIN);
    }

    #[test]
    fn div_rounds_to_nearest_and_saturates() {
        assert_eq!(div_bits(1 << 16, 3 << 16), 21845); // 1/3 = 21845.33 LSB
        assert_eq!(div_bits(2 << 16, 3 << 16), 43691); // 2/3 = 43690.67 LSB
        assert_eq!(div_bits(-(2 << 16), 3 << 16), -43691);
        assert_eq!(div_bits(5, 0), i32::MAX);
        assert_eq!(div_bits(-5, 0), i32::MIN);
        assert_eq!(div_bits(0, 0), 0);
        assert_eq!(div_bits(i32::MIN, -(1 << 16)), i32::MAX);
    }

    #[test]
    fn conversions_round_trip_and_saturate() {
        let x = I16F16::from_bits(-123_457);
        assert_eq!(<I16F16 as Scalar>::from_f64(x.to_f64()), x);
        assert_eq!(<I16F16 as Scalar>::from_f64(1e9), I16F16::MAX);
        assert_eq!(<I16F16 as Scalar>::from_f64(f64::NAN), I16F16::ZERO);
        assert_eq!(<I16F16 as Scalar>::from_i32(40_000), I16F16::MAX);
        assert_eq!(<I16F16 as Scalar>::from_i32(-7).to_f64(), -7.0);
    }
}
