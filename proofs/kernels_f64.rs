//! Properties of the `f64` kernels (the design and reference backend).
//!
//! The `f64` kernels wrap the pure-Rust `libm` crate. No engine can visit
//! every `f64`, so their bound is checked by the **random** engine only:
//! proptest draws arguments over each kernel's physically relevant range and
//! compares against the platform's C library (`std`'s `f64` methods, an
//! independent implementation). Both claim < 1 ulp, so they may differ by up
//! to 2 ulp; the saturation rules are checked at their edges by unit tests.

use super::engine::Verdict;

/// Distance between two `f64` values in units in the last place of `b`.
pub fn ulp_error_f64(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        return f64::INFINITY;
    }
    let diff = (a - b).abs();
    if diff == 0.0 {
        return 0.0;
    }
    let e = (((b.abs().to_bits() >> 52) & 0x7ff) as i32 - 1023).max(-1022);
    diff / libm::exp2((e - 52) as f64)
}

/// An `f64` kernel result is within 2 ulp of the reference and is finite.
pub fn f64_within_2ulp(got: f64, reference: f64) -> Verdict {
    Verdict::bounded(ulp_error_f64(got, reference), 2.0).and(Verdict::logical(got.is_finite()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::kernels::f64 as k;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        #[test]
        fn atan_f64(x in -1e6f64..1e6) {
            prop_assert!(f64_within_2ulp(k::atan(x), x.atan()).holds);
        }

        #[test]
        fn tan_f64(x in -k::TAN_DOMAIN_EDGE..k::TAN_DOMAIN_EDGE) {
            prop_assert!(f64_within_2ulp(k::tan(x), x.tan()).holds);
        }

        #[test]
        fn exp_f64(x in -700.0f64..700.0) {
            prop_assert!(f64_within_2ulp(k::exp(x), x.exp()).holds);
        }

        #[test]
        fn sin_cos_f64(x in -1e4f64..1e4) {
            let (s, c) = k::sin_cos(x);
            prop_assert!(f64_within_2ulp(s, x.sin()).holds);
            prop_assert!(f64_within_2ulp(c, x.cos()).holds);
            prop_assert!(f64_within_2ulp(k::sin(x), x.sin()).holds);
            prop_assert!(f64_within_2ulp(k::cos(x), x.cos()).holds);
        }

        #[test]
        fn atan2_f64(y in -1e3f64..1e3, x in -1e3f64..1e3) {
            prop_assert!(f64_within_2ulp(k::atan2(y, x), y.atan2(x)).holds);
        }

        #[test]
        fn acos_sqrt_f64(x in -1.0f64..=1.0, s in 0.0f64..1e9) {
            prop_assert!(f64_within_2ulp(k::acos(x), x.acos()).holds);
            prop_assert!(f64_within_2ulp(k::sqrt(s), s.sqrt()).holds);
        }
    }

    #[test]
    fn saturation_rules_hold_at_the_edges() {
        assert_eq!(k::atan(f64::NAN), 0.0);
        assert_eq!(k::exp(1000.0), f64::MAX);
        assert_eq!(k::exp(-1000.0), 0.0);
        assert_eq!(k::sqrt(-4.0), 0.0);
        assert_eq!(k::sqrt(f64::INFINITY), f64::MAX);
        assert_eq!(k::acos(2.0), 0.0);
        assert_eq!(k::acos(-2.0), core::f64::consts::PI);
        assert_eq!(k::sin(f64::INFINITY), 0.0);
        assert_eq!(k::cos(f64::NEG_INFINITY), 1.0);
        assert_eq!(k::sin_cos(f64::NAN), (0.0, 1.0));
        assert_eq!(k::atan2(0.0, 0.0), 0.0);
        // tan is non-decreasing across the branch edge and saturates.
        let edge = k::tan(k::TAN_DOMAIN_EDGE);
        assert!(edge > 1e15);
        assert_eq!(k::tan(2.0), edge);
        assert_eq!(k::tan(-2.0), -edge);
    }

    #[test]
    fn ulp_measure_is_exact_on_neighbours() {
        let one_up = f64::from_bits(1.0f64.to_bits() + 1);
        assert_eq!(ulp_error_f64(one_up, 1.0), 1.0);
        assert_eq!(ulp_error_f64(1.0, 1.0), 0.0);
        assert!(!f64_within_2ulp(f64::from_bits(1.0f64.to_bits() + 3), 1.0).holds);
    }
}
