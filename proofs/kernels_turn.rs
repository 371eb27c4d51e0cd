//! Properties of the binary-angle cosine [`Scalar::cos_turn`]
//! (`src/scalar/kernels/{f32,f64,i16f16}.rs`), the kernel of the
//! kinematic error of eq. (3.7) in the torque estimator.
//!
//! For every backend: the error bound against an independent `f64`
//! reference, exact evenness `cos_turn(t) = cos_turn(t.wrapping_neg())`,
//! and `|cos_turn| ≤ 1`.
//!
//! * **Exhaustive** (`exhaustive_cos_turn_*`, `#[ignore]`d, run in
//!   release): every one of the 2³² `u32` angles for `I16F16` and `f32`
//!   (each prints one `PROOF …` line).
//!   `cargo test --release --lib -- --ignored exhaustive_cos_turn --nocapture`
//! * **Plain tests**: the edges (0, octant and quadrant boundaries, the
//!   table knots, 2³¹, `u32::MAX`), a dense stride and random angles.
//!
//! Reference: `libm::cos` (< 1 ulp) of the *signed* angle
//! `(turn as i32)·2π/2³² ∈ [−π, π)` — none of the kernels' quarter-turn
//! folding. Its own error (< 1e-15) is far below every bound here.

use super::engine::Verdict;
use crate::scalar::{Scalar, I16F16};
use core::f64::consts::TAU;

/// One LSB of `I16F16`.
pub const LSB: f64 = 1.0 / 65536.0;
/// One ulp of `1.0f32` (2⁻²³).
pub const ULP1_F32: f64 = 1.0 / 8_388_608.0;

/// `cos(2π·turn/2³²)` in `f64`, from the signed angle in `[−π, π)`.
pub fn reference_cos_turn(turn: u32) -> f64 {
    libm::cos((turn as i32) as f64 * (TAU / 4_294_967_296.0))
}

/// Evenness and `|c| ≤ 1` of backend `S` at `turn`.
fn even_and_bounded<S: Scalar>(turn: u32, got: S) -> bool {
    got == S::cos_turn(turn.wrapping_neg()) && got.to_f64().abs() <= 1.0
}

/// `I16F16`: `≤ 1 LSB`, even, `|c| ≤ 1`; error in LSB.
pub fn cos_turn_i16f16_check(turn: u32) -> Verdict {
    let got = I16F16::cos_turn(turn);
    let err = (got.to_f64() - reference_cos_turn(turn)).abs() / LSB;
    Verdict::bounded(err, 1.0).and(Verdict::logical(even_and_bounded(turn, got)))
}

/// `f32`: `≤ 2⁻²²` absolute (2 ulp of 1), even, `|c| ≤ 1`; error in ulp
/// of 1.
pub fn cos_turn_f32_check(turn: u32) -> Verdict {
    let got = f32::cos_turn(turn);
    let err = (got as f64 - reference_cos_turn(turn)).abs() / ULP1_F32;
    Verdict::bounded(err, 2.0).and(Verdict::logical(even_and_bounded(turn, got)))
}

/// `f64`: `< 1e-15` absolute, even, `|c| ≤ 1`; error in units of 1e-15.
pub fn cos_turn_f64_check(turn: u32) -> Verdict {
    let got = f64::cos_turn(turn);
    let err = (got - reference_cos_turn(turn)).abs() / 1e-15;
    Verdict::bounded(err, 1.0).and(Verdict::logical(even_and_bounded(turn, got)))
}

/// The edge angles: 0, every multiple of an eighth turn and its
/// neighbours (±1, ±64: the I16F16 kernel drops 6 bits), the I16F16
/// table knots of the first quadrant (multiples of 2²²), 2³¹ and
/// `u32::MAX`.
pub fn edge_turns() -> impl Iterator<Item = u32> {
    let octants = (0..8u32).flat_map(|k| {
        let b = k << 29;
        [0u32, 1, 63, 64, 65]
            .into_iter()
            .flat_map(move |o| [b.wrapping_add(o), b.wrapping_sub(o)])
    });
    let knots = (0..=256u32).flat_map(|i| {
        let b = i << 22;
        [b, b.wrapping_sub(1), b + 1, b.wrapping_neg()]
    });
    octants
        .chain(knots)
        .chain([0, 1, 1 << 31, (1 << 31) - 1, (1 << 31) + 1, u32::MAX])
}

#[cfg(test)]
mod tests {
    use super::super::engine::exhaustive_u32;
    use super::*;
    use proptest::prelude::*;
    use std::time::Instant;
    use std::{eprintln, println};

    fn line(backend: &str, bound: &str, unit: &str, err: f64, at: u32, checked: u64) {
        println!(
            "PROOF kernel=cos_turn backend={backend} domain=all bound={bound} max_err={err:.6} {unit} at=turn:{at:#010x} checked={checked} engine=exhaustive"
        );
    }

    #[test]
    fn cos_turn_table_matches_its_generator() {
        let t = &crate::scalar::kernels::i16f16::COS_TURN_Q23;
        for (i, &v) in t.iter().enumerate() {
            let r = (i as f64 * core::f64::consts::PI / 512.0).cos() * 8_388_608.0;
            assert_eq!(v as f64, r.round(), "COS_TURN_Q23[{i}]");
        }
        assert_eq!(t.len(), 257);
    }

    #[test]
    fn cos_turn_known_values() {
        // Exact quarter turns on every backend.
        for (t, c) in [(0u32, 1.0), (1 << 30, 0.0), (1 << 31, -1.0), (3 << 30, 0.0)] {
            assert_eq!(I16F16::cos_turn(t).to_f64(), c, "I16F16 at {t:#x}");
            assert!((f32::cos_turn(t) as f64 - c).abs() <= 1e-7, "f32 at {t:#x}");
            assert!((f64::cos_turn(t) - c).abs() <= 1e-16, "f64 at {t:#x}");
        }
        // 60° = 2³²/6: cos = 1/2 (hand value, not the reference function).
        let t = (4_294_967_296.0f64 / 6.0).round() as u32;
        assert!((I16F16::cos_turn(t).to_f64() - 0.5).abs() <= LSB);
        assert!((f32::cos_turn(t) as f64 - 0.5).abs() <= 2.0 * ULP1_F32);
        assert!((f64::cos_turn(t) - 0.5).abs() <= 1e-9); // t rounded: 1e-9
    }

    #[test]
    fn cos_turn_within_bounds_at_edges() {
        for t in edge_turns() {
            for (name, v) in [
                ("I16F16", cos_turn_i16f16_check(t)),
                ("f32", cos_turn_f32_check(t)),
                ("f64", cos_turn_f64_check(t)),
            ] {
                assert!(v.holds, "{name} at {t:#010x}: error {}", v.error);
            }
        }
    }

    #[test]
    fn cos_turn_within_bounds_on_a_dense_stride() {
        // 2³² / 65_537 ≈ 65_535 angles, every residue pattern of the
        // low bits (the stride is odd).
        let mut t = 0u32;
        for _ in 0..65_537 {
            for v in [
                cos_turn_i16f16_check(t),
                cos_turn_f32_check(t),
                cos_turn_f64_check(t),
            ] {
                assert!(v.holds, "at {t:#010x}: error {}", v.error);
            }
            t = t.wrapping_add(65_537);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        #[test]
        fn cos_turn_within_bounds_at_random(t in any::<u32>()) {
            prop_assert!(cos_turn_i16f16_check(t).holds);
            prop_assert!(cos_turn_f32_check(t).holds);
            prop_assert!(cos_turn_f64_check(t).holds);
        }
    }

    /// Every `u32` angle: `I16F16` within 1 LSB, even, `|c| ≤ 1`.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_turn_i16f16() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, cos_turn_i16f16_check);
        eprintln!("(cos_turn I16F16: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(r.failures, 0, "first failure at {:?}", r.first_failure);
        line("I16F16", "1 LSB", "LSB", r.max_error, r.argmax, r.checked);
    }

    /// Every `u32` angle: `f32` within 2⁻²² absolute, even, `|c| ≤ 1`.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_turn_f32() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, cos_turn_f32_check);
        eprintln!("(cos_turn f32: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(r.failures, 0, "first failure at {:?}", r.first_failure);
        line(
            "f32",
            "2 ulp of 1",
            "ulp(1)",
            r.max_error,
            r.argmax,
            r.checked,
        );
    }
}
