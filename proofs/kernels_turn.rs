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
//! * **Shared reduction** (`exhaustive_sin_cos_turn_f32`): the `f32`
//!   [`Scalar::sin_cos_turn`] kernel equals `(cos_turn(t − 2³⁰),
//!   cos_turn(t))` bit for bit at every one of the 2³² angles, so both of
//!   its components carry the proven `cos_turn` bound.
//!   `cargo test --release --lib -- --ignored exhaustive_sin_cos_turn_f32 --nocapture`
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

/// `f32` `sin_cos_turn(turn)` against two `cos_turn` calls a quarter turn
/// apart: bit-equal components (a logical property, error 0).
pub fn sin_cos_turn_f32_check(turn: u32) -> Verdict {
    let (s, c) = f32::sin_cos_turn(turn);
    let s_ref = f32::cos_turn(turn.wrapping_sub(1 << 30));
    let c_ref = f32::cos_turn(turn);
    Verdict::logical(s.to_bits() == s_ref.to_bits() && c.to_bits() == c_ref.to_bits())
}

/// `f32` table kernel `cos_turn_coarse`: within
/// [`COS_TURN_COARSE_BOUND`](crate::scalar::kernels::f32::COS_TURN_COARSE_BOUND)
/// absolute, `|c| ≤ 1`, and `sin_cos_turn_coarse(turn)` is bit for bit
/// `(cos_turn_coarse(turn − 2³⁰), cos_turn_coarse(turn))`; error in units
/// of 1e-6.
pub fn cos_turn_coarse_f32_check(turn: u32) -> Verdict {
    use crate::scalar::kernels::f32::{
        cos_turn_coarse, sin_cos_turn_coarse, COS_TURN_COARSE_BOUND,
    };
    let got = cos_turn_coarse(turn);
    let err = (got as f64 - reference_cos_turn(turn)).abs() / 1e-6;
    let (s, c) = sin_cos_turn_coarse(turn);
    let same = s.to_bits() == cos_turn_coarse(turn.wrapping_sub(1 << 30)).to_bits()
        && c.to_bits() == got.to_bits();
    Verdict::bounded(err, COS_TURN_COARSE_BOUND / 1e-6)
        .and(Verdict::logical(same && (got as f64).abs() <= 1.0))
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
    use crate::scalar::kernels::i16f16::{turn_of_radians, TURN_OF_RADIANS_UNITS};
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

    /// Every knot of the `f32` table is `cos(2π i/1024)` correctly
    /// rounded (within half an ulp of the `f64` cosine, whose own error is
    /// far below), the quarter turns exactly 0 and ±1, and every slope is
    /// the `f32` difference to the next knot (1 after the last) times 2⁻²².
    #[test]
    fn cos_turn_table_is_correctly_rounded() {
        let t = crate::scalar::kernels::f32::COS_TURN_COARSE_TABLE;
        assert_eq!(t.len(), 1024);
        for (i, &[v, slope]) in t.iter().enumerate() {
            let r = (i as f64 * core::f64::consts::PI / 512.0).cos();
            let half_ulp = if v == 0.0 {
                0.0
            } else {
                (f32::from_bits(v.to_bits() + 1) - v).abs() as f64 / 2.0
            };
            if i % 256 == 0 {
                assert_eq!(v as f64, r.round(), "knot {i}");
            } else {
                assert!(
                    (v as f64 - r).abs() <= half_ulp * (1.0 + 1e-9),
                    "knot {i}: {v} vs {r}"
                );
            }
            let next = if i == 1023 { 1.0 } else { t[i + 1][0] };
            assert_eq!(slope, (next - v) * (1.0 / 4_194_304.0), "slope {i}");
        }
    }

    /// The table kernel is within its bound at every knot and its
    /// neighbours, every midpoint (where the interpolation error peaks), a
    /// dense stride and random angles, and its `(sin, cos)` equals two
    /// calls; the worst error reaches most of the bound (not vacuous).
    #[test]
    fn cos_turn_coarse_within_its_bound() {
        let knots = (0..1024u32).flat_map(|i| {
            let b = i << 22;
            [
                b,
                b.wrapping_sub(1),
                b + 1,
                b + (1 << 21),
                b + (1 << 21) + 1,
            ]
        });
        let stride = (0..=u32::MAX / 4099).map(|k| k * 4099);
        let mut worst = 0.0f64;
        for t in knots
            .chain(stride)
            .chain(edge_turns())
            .chain(sample_turns(200_000))
        {
            let v = cos_turn_coarse_f32_check(t);
            assert!(v.holds, "at {t:#010x}: error {} e-6", v.error);
            worst = worst.max(v.error);
        }
        eprintln!("cos_turn_coarse: worst {worst:.4}e-6");
        assert!(
            worst > 4.5,
            "worst {worst}e-6: the h²/8 remainder (4.71e-6) is reached"
        );
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

    /// Every multiple of an eighth turn (the quadrant boundaries of the
    /// shared reduction are the odd ones) and its neighbours within ±3
    /// units, 0, 2³¹, `u32::MAX`.
    fn sin_cos_turn_edges() -> impl Iterator<Item = u32> {
        (0..8u32)
            .flat_map(|k| (-3i32..=3).map(move |o| (k << 29).wrapping_add(o as u32)))
            .chain([0, 1 << 31, u32::MAX])
    }

    /// Seeded sample of `n` angles (xorshift64).
    fn sample_turns(n: usize) -> impl Iterator<Item = u32> {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        (0..n).map(move |_| (crate::scalar::xorshift64(&mut state) >> 32) as u32)
    }

    #[test]
    fn sin_cos_turn_ties_evaluate_equal_polynomials() {
        // The two reductions of `sin_cos_turn` and `cos_turn` differ only
        // at the ties d = −2²⁹ of negative signed angles, where one side
        // takes the sine polynomial at π/4 and the other the cosine
        // polynomial: cos_turn(2²⁹) is `sin_poly(π/4)` (k = 1, −s(−π/4)),
        // cos_turn(3·2²⁹) is `−cos_poly(π/4)` (k = 2, d = −2²⁹).
        let s = f32::cos_turn(1 << 29);
        let c = -f32::cos_turn(3 << 29);
        assert_eq!(s.to_bits(), c.to_bits(), "s(π/4) = {s}, c(π/4) = {c}");
        // And both are the correctly rounded √½.
        assert_eq!(s, core::f64::consts::FRAC_1_SQRT_2 as f32);
    }

    #[test]
    fn sin_cos_turn_f32_equals_two_cos_turn_at_edges_and_at_random() {
        for t in sin_cos_turn_edges().chain(sample_turns(300_000)) {
            let v = sin_cos_turn_f32_check(t);
            assert!(v.holds, "at {t:#010x}: {:?}", f32::sin_cos_turn(t));
        }
    }

    #[test]
    fn sin_cos_turn_f64_and_i16f16_equal_two_cos_turn() {
        for t in sin_cos_turn_edges().chain(sample_turns(20_000)) {
            let a = t.wrapping_sub(1 << 30);
            let (s, c) = f64::sin_cos_turn(t);
            assert_eq!(
                (s.to_bits(), c.to_bits()),
                (f64::cos_turn(a).to_bits(), f64::cos_turn(t).to_bits()),
                "f64 at {t:#010x}"
            );
            assert_eq!(
                I16F16::sin_cos_turn(t),
                (I16F16::cos_turn(a), I16F16::cos_turn(t)),
                "I16F16 at {t:#010x}"
            );
        }
    }

    #[test]
    fn sin_cos_turn_f32_within_2_pow_m22_of_f64_sin_cos() {
        // Independent reference: libm's f64 sine and cosine of the signed
        // angle in [−π, π), no quarter-turn folding.
        let bound = 2.0 * ULP1_F32; // 2⁻²²
        let mut worst = 0.0f64;
        for t in sin_cos_turn_edges().chain(sample_turns(300_000)) {
            let x = (t as i32) as f64 * (TAU / 4_294_967_296.0);
            let (s, c) = f32::sin_cos_turn(t);
            let es = (s as f64 - libm::sin(x)).abs();
            let ec = (c as f64 - libm::cos(x)).abs();
            assert!(es <= bound, "sin at {t:#010x}: {s} vs {}", libm::sin(x));
            assert!(ec <= bound, "cos at {t:#010x}: {c} vs {}", libm::cos(x));
            assert!(s.abs() <= 1.0 && c.abs() <= 1.0, "at {t:#010x}");
            worst = worst.max(es).max(ec);
        }
        // The sample reaches well above half the bound (the proven maximum
        // of cos_turn is 0.905 ulp of 1), so the check is not vacuous.
        assert!(worst > 0.5 * ULP1_F32, "worst error {worst:e}");
    }

    /// Every `u32` angle: the `f32` `sin_cos_turn` equals
    /// `(cos_turn(t − 2³⁰), cos_turn(t))` bit for bit.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_cos_turn_f32() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, sin_cos_turn_f32_check);
        eprintln!("(sin_cos_turn f32: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(r.failures, 0, "first failure at {:?}", r.first_failure);
        println!(
            "PROOF kernel=sin_cos_turn backend=f32 domain=all bound=bit-identical to (cos_turn(t-2^30), cos_turn(t)), hence 2 ulp of 1 mismatches={} checked={} engine=exhaustive",
            r.failures, r.checked
        );
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
        // Radians through `turn_of_radians` (within its bound of
        // `TURN_OF_RADIANS_UNITS` turn units, `turn_of_radians_is_within_its_bound`):
        // cos and sin (a quarter turn back, the same kernel) are within
        // this maximum plus the angle error, `|Δ cos| ≤ |Δθ|`.
        let conv = TURN_OF_RADIANS_UNITS * TAU / 4_294_967_296.0 / LSB;
        assert!(r.max_error + conv <= 1.0, "{} + {conv}", r.max_error);
        println!(
            "PROOF kernel=sin_cos_turn(turn_of_radians(x)) backend=I16F16 domain=all bound=1 LSB max_err<={:.6} LSB (cos_turn max {:.6} + conversion {conv:.6}) checked={} engine=exhaustive",
            r.max_error + conv,
            r.max_error,
            r.checked
        );
    }

    /// `turn_of_radians` against the exact product with a 64-bit fraction
    /// of `2¹⁶/(2π)` (`⌊2⁸⁰/(2π)⌉`, from a 60-digit π): within
    /// `TURN_OF_RADIANS_UNITS` at the edge words, a stride through all
    /// words and random words; the sample reaches most of the bound.
    #[test]
    fn turn_of_radians_is_within_its_bound() {
        // 2¹⁶/(2π)·2⁶⁴, rounded.
        const K: i128 = 192_406_520_023_089_232_379_658;
        let mut worst = 0.0f64;
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let random = (0..400_000).map(|_| (crate::scalar::xorshift64(&mut state) >> 32) as i32);
        let stride = (0..=u32::MAX / 9973).map(|k| (k * 9973) as i32);
        let edges = [
            0,
            1,
            -1,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            102_944,
            -102_944,
            205_887,
            -205_887,
        ];
        for b in edges.into_iter().chain(stride).chain(random) {
            let got = turn_of_radians(I16F16::from_bits(b));
            // (got − b·K/2⁶⁴) modulo 2³², as a signed multiple of 2⁻⁶⁴.
            let exact = b as i128 * K;
            let diff = ((got as i128) << 64).wrapping_sub(exact) & ((1i128 << 96) - 1);
            let diff = if diff >= 1i128 << 95 {
                diff - (1i128 << 96)
            } else {
                diff
            };
            let units = diff as f64 / 18_446_744_073_709_551_616.0;
            assert!(
                units.abs() <= TURN_OF_RADIANS_UNITS,
                "bits {b}: {units} units"
            );
            worst = worst.max(units.abs());
        }
        assert!(worst > 0.49, "worst {worst}");
    }

    /// `sin_cos_turn(turn_of_radians(x))` against `f64` `sin`/`cos` of
    /// `x`: within 1 LSB on every input of `|x| ≤ 8` rad and a random
    /// sample of all words (the exhaustive proof is the composition in
    /// `exhaustive_cos_turn_i16f16`).
    #[test]
    fn sin_cos_of_turn_of_radians_is_within_one_lsb() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let random = (0..200_000).map(|_| (crate::scalar::xorshift64(&mut state) >> 32) as i32);
        let mut worst = 0.0f64;
        for b in (-(8 << 16)..=(8 << 16)).step_by(3).chain(random) {
            let x = I16F16::from_bits(b);
            let (s, c) = I16F16::sin_cos_turn(x.to_turn());
            let xf = x.to_f64();
            let es = (s.to_f64() - libm::sin(xf)).abs() / LSB;
            let ec = (c.to_f64() - libm::cos(xf)).abs() / LSB;
            assert!(es <= 1.0 && ec <= 1.0, "at {xf}: {es} {ec} LSB");
            worst = worst.max(es).max(ec);
        }
        assert!(worst > 0.7, "worst {worst} LSB");
    }

    /// Every `u32` angle: `f32` within 2⁻²² absolute, even, `|c| ≤ 1`.
    /// Every `u32` angle: the `f32` table kernel within 4.8e-6, `|c| ≤ 1`,
    /// and its `(sin, cos)` equal to two calls.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_turn_coarse_f32() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, cos_turn_coarse_f32_check);
        eprintln!("(cos_turn_coarse f32: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(r.failures, 0, "first failure at {:?}", r.first_failure);
        println!(
            "PROOF kernel=cos_turn_coarse backend=f32 domain=all bound=4.8e-6 max_err={:.6}e-6 at=turn:{:#010x} checked={} engine=exhaustive (sin_cos_turn_coarse bit-identical to two calls)",
            r.max_error, r.argmax, r.checked
        );
    }

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
