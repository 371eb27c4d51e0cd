//! `f32` and `f64` backends.
//!
//! Arithmetic is plain IEEE-754 except for [`Scalar::div`], which returns
//! `±MAX` instead of an infinity on division by zero and `0` for `0/0`.
//! Conversions from `f64` saturate at `±MAX` and map NaN to 0.
//! The kernels are those of [`kernels::f32`] and [`kernels::f64`].

use super::{kernels, Scalar};

macro_rules! float_scalar {
    ($t:ident, $name:literal, $k:ident, $countfn:ident) => {
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
                counts as $t * scale.$countfn()
            }
            #[inline]
            fn mul_coef(self, c: &super::Coef) -> Self {
                self * c.$countfn()
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
    };
}

float_scalar!(f32, "f32", f32, f32_value);
float_scalar!(f64, "f64", f64, value);

#[cfg(test)]
mod tests {
    use super::*;

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
