//! I16F16 kernel properties (`src/scalar/kernels/i16f16.rs`).
//!
//! Each property is a plain function of raw inputs, run by:
//!
//! * **Exhaustive** (`exhaustive_*_i16f16`, `#[ignore]`d, run in release):
//!   every one of the 2³² `I16F16` bit patterns (for `atan2`, every pair of
//!   a 16-bit lattice packed into the `u32` code). A complete proof for the
//!   type. Each test prints one `PROOF …` line.
//!   `cargo test --release --lib -- --ignored exhaustive_ --test-threads 1 --nocapture`
//! * **Kani** (`kani_*`): the same bodies with `kani::any()` inputs, plus
//!   cheap integer properties of the building blocks (exact `mulhi`,
//!   `div_frac`, `sqrt_q16`), output ranges and monotone pairs, which Kani
//!   decides bit-precisely.
//! * **Random** (proptest, plain `cargo test`): bounded physical ranges.
//!
//! Reference: `f64` functions (std's in tests, `libm` elsewhere), exact
//! `f64` conversion of the input; error in LSB (2⁻¹⁶) by
//! [`lsb_error`](super::engine::lsb_error).

use super::engine::{lsb_error, Verdict};
use crate::scalar::kernels::i16f16 as k;
use crate::scalar::{Scalar, I16F16};

/// One LSB of `I16F16`.
pub const LSB: f64 = 1.0 / 65536.0;
/// `I16F16::MAX` as `f64`.
const MAX_F: f64 = 32768.0 - LSB;

/// f64 reference functions: std in tests (glibc), `libm` otherwise (no_std
/// Kani builds). Both are within 1 ulp of `f64`, i.e. 2⁻³⁶ LSB here.
mod reference {
    #[cfg(test)]
    mod imp {
        pub fn atan(x: f64) -> f64 {
            x.atan()
        }
        pub fn tan(x: f64) -> f64 {
            x.tan()
        }
        pub fn exp(x: f64) -> f64 {
            x.exp()
        }
        pub fn sin(x: f64) -> f64 {
            x.sin()
        }
        pub fn cos(x: f64) -> f64 {
            x.cos()
        }
        pub fn atan2(y: f64, x: f64) -> f64 {
            y.atan2(x)
        }
        pub fn acos(x: f64) -> f64 {
            x.acos()
        }
        pub fn sqrt(x: f64) -> f64 {
            x.sqrt()
        }
    }
    #[cfg(not(test))]
    mod imp {
        pub use libm::{acos, atan, atan2, cos, exp, sin, sqrt, tan};
    }
    pub use imp::*;
}

/// Raw bit pattern → value.
pub fn from_code(code: u32) -> I16F16 {
    I16F16::from_bits(code as i32)
}

/// Code whose value order is the code order: `MIN` at 0, `MAX` at `u32::MAX`.
pub fn ordered(code: u32) -> I16F16 {
    I16F16::from_bits((code ^ 0x8000_0000) as i32)
}

/// The next representable value (`x < MAX`).
fn next_up(x: I16F16) -> I16F16 {
    I16F16::from_bits(x.to_bits() + 1)
}

/// `f(x) ≤ f(x + 2⁻¹⁶)` (vacuous at `MAX`).
pub fn monotone_at(f: fn(I16F16) -> I16F16, x: I16F16) -> Verdict {
    Verdict::logical(x == I16F16::MAX || f(x) <= f(next_up(x)))
}

/// `f(−x) = −f(x)` (vacuous at `MIN`, which has no negation).
pub fn odd_at(f: fn(I16F16) -> I16F16, x: I16F16) -> Verdict {
    Verdict::logical(x == I16F16::MIN || f(-x) == -f(x))
}

/// `atan`: `≤ 1 LSB`, odd.
pub fn atan_within_bound(x: I16F16) -> Verdict {
    let err = lsb_error(k::atan(x).to_f64(), reference::atan(x.to_f64()), LSB);
    Verdict::bounded(err, 1.0).and(odd_at(k::atan, x))
}

/// The `tan` reference: `tan x` on `|x| < π/2`, `±MAX` outside, saturated.
pub fn tan_reference(x: I16F16) -> f64 {
    let v = x.to_f64();
    if v.abs() >= core::f64::consts::FRAC_PI_2 {
        if v > 0.0 {
            MAX_F
        } else {
            -MAX_F
        }
    } else {
        reference::tan(v).clamp(-MAX_F, MAX_F)
    }
}

/// `tan`: `|err| ≤ 1 LSB + 2⁻²⁶·|tan x|` (i.e. `1 + |tan x|/1024` LSB),
/// exact `±MAX` outside the branch, odd.
pub fn tan_within_bound(x: I16F16) -> Verdict {
    let r = tan_reference(x);
    let err = lsb_error(k::tan(x).to_f64(), r, LSB);
    Verdict::bounded(err, 1.0 + r.abs() / 1024.0).and(odd_at(k::tan, x))
}

/// `exp`: `|err| ≤ 1 LSB + 2⁻²⁸·e^x` (i.e. `1 + e^x/4096` LSB); the
/// reference is saturated at `MAX` like the kernel.
pub fn exp_within_bound(x: I16F16) -> Verdict {
    let r = reference::exp(x.to_f64()).min(MAX_F);
    let err = lsb_error(k::exp(x).to_f64(), r, LSB);
    Verdict::bounded(err, 1.0 + r / 4096.0)
}

/// `sin`: `≤ 1 LSB`, odd, and equal to `sin_cos(x).0`.
pub fn sin_within_bound(x: I16F16) -> Verdict {
    let s = k::sin(x);
    let err = lsb_error(s.to_f64(), reference::sin(x.to_f64()), LSB);
    Verdict::bounded(err, 1.0)
        .and(Verdict::logical(k::sin_cos(x).0 == s))
        .and(odd_at(k::sin, x))
}

/// `cos`: `≤ 1 LSB`, even, and equal to `sin_cos(x).1`.
pub fn cos_within_bound(x: I16F16) -> Verdict {
    let c = k::cos(x);
    let err = lsb_error(c.to_f64(), reference::cos(x.to_f64()), LSB);
    let even = x == I16F16::MIN || k::cos(-x) == c;
    Verdict::bounded(err, 1.0)
        .and(Verdict::logical(k::sin_cos(x).1 == c))
        .and(Verdict::logical(even))
}

/// `atan2(y, x)`: `≤ 1 LSB`, `atan2(0, 0) = 0`.
pub fn atan2_within_bound(y: I16F16, x: I16F16) -> Verdict {
    let got = k::atan2(y, x);
    if y == I16F16::ZERO && x == I16F16::ZERO {
        return Verdict::logical(got == I16F16::ZERO);
    }
    let err = lsb_error(got.to_f64(), reference::atan2(y.to_f64(), x.to_f64()), LSB);
    Verdict::bounded(err, 1.0)
}

/// The 16-bit lattice of the `atan2` proof: `code = (y_k << 16) | x_k`,
/// value `k·2⁻⁸` (every pair of `I8F8` values, embedded in `I16F16`).
pub fn lattice_pair(code: u32) -> (I16F16, I16F16) {
    let y = ((code >> 16) as u16 as i16 as i32) << 8;
    let x = (code as u16 as i16 as i32) << 8;
    (I16F16::from_bits(y), I16F16::from_bits(x))
}

/// `acos`: `≤ 1 LSB` against `acos(clamp(x, −1, 1))`.
pub fn acos_within_bound(x: I16F16) -> Verdict {
    let r = reference::acos(x.to_f64().clamp(-1.0, 1.0));
    Verdict::bounded(lsb_error(k::acos(x).to_f64(), r, LSB), 1.0)
}

/// `sqrt`: correctly rounded (`≤ 0.5 LSB`), 0 for negative inputs.
pub fn sqrt_within_bound(x: I16F16) -> Verdict {
    let r = reference::sqrt(x.to_f64().max(0.0));
    Verdict::bounded(lsb_error(k::sqrt(x).to_f64(), r, LSB), 0.5)
}

/// `sin_cos(x) == (sin x, cos x)` bit for bit.
pub fn sin_cos_is_sin_and_cos(x: I16F16) -> Verdict {
    Verdict::logical(k::sin_cos(x) == (k::sin(x), k::cos(x)))
}

/// Output ranges that need no reference: `|atan| ≤ π/2`, `|sin|, |cos| ≤ 1`,
/// `acos ∈ [0, π]`, `sqrt ≥ 0`, `exp ≥ 0` (all as rounded `I16F16`).
pub fn outputs_in_range(x: I16F16) -> Verdict {
    let one = I16F16::ONE;
    let (s, c) = k::sin_cos(x);
    let a = k::atan(x);
    let ac = k::acos(x);
    Verdict::logical(
        a.abs() <= I16F16::FRAC_PI_2
            && s.abs() <= one
            && c.abs() <= one
            && ac >= I16F16::ZERO
            && ac <= I16F16::PI
            && k::sqrt(x) >= I16F16::ZERO
            && k::exp(x) >= I16F16::ZERO,
    )
}

/// `mulhi(a, b) = ⌊a·b/2³²⌋` exactly.
pub fn mulhi_is_exact(a: u32, b: u32) -> bool {
    k::mulhi(a, b) as u64 == (a as u64 * b as u64) >> 32
}

/// `div_frac(n, d, 32) = ⌊n·2³²/d⌋` for `n < d ≤ 2³¹` (the `atan2` use).
pub fn div_frac_is_exact(n: u32, d: u32) -> bool {
    k::div_frac(n, d, 32) as u64 == ((n as u64) << 32) / d as u64
}

/// `sqrt_q16(n) = (⌊√(n·2¹⁶)⌋, remainder)`.
pub fn sqrt_q16_is_exact(n: u32) -> bool {
    let (root, rem) = k::sqrt_q16(n);
    let v = (n as u64) << 16;
    let r = root as u64;
    r * r + rem as u64 == v && v < (r + 1) * (r + 1)
}

// ---- Kani ------------------------------------------------------------------

#[cfg(kani)]
mod kani_proofs {
    use super::*;

    fn any_fixed() -> I16F16 {
        I16F16::from_bits(kani::any())
    }

    #[kani::proof]
    fn kani_mulhi_exact() {
        assert!(mulhi_is_exact(kani::any(), kani::any()));
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_div_frac_exact() {
        let n: u32 = kani::any();
        let d: u32 = kani::any();
        kani::assume(n < d && d <= 1 << 31); // precondition of div_frac's atan2 use
        assert!(div_frac_is_exact(n, d));
    }

    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_q16_exact() {
        assert!(sqrt_q16_is_exact(kani::any()));
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_outputs_in_range_i16f16() {
        assert!(outputs_in_range(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_monotone_pair_i16f16() {
        assert!(monotone_at(k::sqrt, any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan_monotone_pair_i16f16() {
        assert!(monotone_at(k::atan, any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_tan_monotone_pair_i16f16() {
        assert!(monotone_at(k::tan, any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_exp_monotone_pair_i16f16() {
        assert!(monotone_at(k::exp, any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_sin_cos_is_sin_and_cos_i16f16() {
        assert!(sin_cos_is_sin_and_cos(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan_i16f16() {
        assert!(atan_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_tan_i16f16() {
        assert!(tan_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_exp_i16f16() {
        let x = any_fixed();
        // solver budget: the float reference is costly; restrict to the
        // non-saturated, non-flushed range (the rest is constant-valued).
        kani::assume(x.to_bits() > -12 << 16 && x.to_bits() < 681392);
        assert!(exp_within_bound(x).holds);
    }

    #[kani::proof]
    fn kani_sin_i16f16() {
        assert!(sin_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_cos_i16f16() {
        assert!(cos_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan2_i16f16() {
        assert!(atan2_within_bound(any_fixed(), any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_acos_i16f16() {
        assert!(acos_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_i16f16() {
        assert!(sqrt_within_bound(any_fixed()).holds);
    }
}

// ---- exhaustive and random ---------------------------------------------------

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::{exhaustive_u32, Report};
    use super::*;
    use proptest::prelude::*;
    use std::println;
    use std::time::Instant;

    fn report(kernel: &str, domain: &str, bound: &str, r: &Report, decode: fn(u32) -> std::string::String, t: Instant) {
        println!(
            "PROOF kernel={kernel} backend=I16F16 domain={domain} bound={bound} max_err={:.6} LSB at={} checked={} engine=exhaustive",
            r.max_error,
            decode(r.argmax),
            r.checked,
        );
        std::eprintln!("({kernel}: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(
            r.failures,
            0,
            "{kernel}: {} failures, first at {}",
            r.failures,
            r.first_failure.map(decode).unwrap_or_default()
        );
    }

    fn show(code: u32) -> std::string::String {
        std::format!("{}", from_code(code))
    }

    fn show_ordered(code: u32) -> std::string::String {
        std::format!("{}", ordered(code))
    }

    fn show_pair(code: u32) -> std::string::String {
        let (y, x) = lattice_pair(code);
        std::format!("(y={y},x={x})")
    }

    fn run(kernel: &str, domain: &str, bound: &str, p: fn(I16F16) -> Verdict) {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, |c| p(from_code(c)));
        report(kernel, domain, bound, &r, show, t);
    }

    fn run_monotone(kernel: &str, f: fn(I16F16) -> I16F16) {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, |c| monotone_at(f, ordered(c)));
        report(kernel, "all", "monotone", &r, show_ordered, t);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_i16f16() {
        run("atan", "all", "1 LSB", atan_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_monotone_i16f16() {
        run_monotone("atan", k::atan);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_i16f16() {
        run(
            "tan",
            "|x|<pi/2,outside=+-MAX",
            "1+|tan(x)|/1024 LSB",
            tan_within_bound,
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_monotone_i16f16() {
        run_monotone("tan", k::tan);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_i16f16() {
        run("exp", "all,sat=MAX", "1+e^x/4096 LSB", exp_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_monotone_i16f16() {
        run_monotone("exp", k::exp);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_i16f16() {
        run("sin", "all", "1 LSB", sin_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_i16f16() {
        run("cos", "all", "1 LSB", cos_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan2_i16f16() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let (y, x) = lattice_pair(c);
            atan2_within_bound(y, x)
        });
        report("atan2", "all-I8F8-pairs", "1 LSB", &r, show_pair, t);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_acos_i16f16() {
        run("acos", "[-1,1],clamped", "1 LSB", acos_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_i16f16() {
        run("sqrt", "x>=0,neg=0", "0.5 LSB", sqrt_within_bound);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_monotone_i16f16() {
        run_monotone("sqrt", k::sqrt);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_ranges_i16f16() {
        run("ranges", "all", "logical", outputs_in_range);
    }

    // -- fast, non-ignored checks ------------------------------------------

    fn fx(v: f64) -> I16F16 {
        <I16F16 as Scalar>::from_f64(v)
    }

    #[test]
    fn hand_values() {
        assert_eq!(k::atan(I16F16::ZERO), I16F16::ZERO);
        assert_eq!(k::atan(I16F16::ONE), fx(core::f64::consts::FRAC_PI_4));
        assert_eq!(k::sqrt(fx(2.25)), fx(1.5));
        assert_eq!(k::sqrt(fx(-1.0)), I16F16::ZERO);
        assert_eq!(k::exp(I16F16::ZERO), I16F16::ONE);
        assert_eq!(k::exp(I16F16::MAX), I16F16::MAX);
        assert_eq!(k::exp(I16F16::MIN), I16F16::ZERO);
        assert_eq!(k::tan(fx(2.0)), I16F16::MAX);
        assert_eq!(k::tan(fx(-2.0)), -I16F16::MAX);
        assert_eq!(k::tan(I16F16::MIN), -I16F16::MAX);
        assert_eq!(k::acos(fx(1.0)), I16F16::ZERO);
        assert_eq!(k::acos(fx(5.0)), I16F16::ZERO);
        assert_eq!(k::acos(fx(-5.0)), fx(core::f64::consts::PI));
        assert_eq!(k::atan2(I16F16::ZERO, I16F16::ZERO), I16F16::ZERO);
        assert_eq!(k::atan2(I16F16::ZERO, -I16F16::ONE), fx(core::f64::consts::PI));
        assert_eq!(k::sin_cos(I16F16::ZERO), (I16F16::ZERO, I16F16::ONE));
    }

    #[test]
    fn building_blocks_on_edges() {
        for &a in &[0u32, 1, 0xFFFF, 0x1_0000, 0x8000_0000, u32::MAX] {
            for &b in &[0u32, 1, 0xFFFF, 0x1_0000, 0x8000_0000, u32::MAX] {
                assert!(mulhi_is_exact(a, b));
            }
        }
        assert!(div_frac_is_exact(0x7FFF_FFFF, 0x8000_0000));
        assert!(div_frac_is_exact(1, 0x8000_0000));
        assert!(sqrt_q16_is_exact(u32::MAX));
        assert!(sqrt_q16_is_exact(0));
    }

    /// Dense grid at the axes and at tiny magnitudes, where a known I16F16
    /// `atan2` is off by up to 2.3 rad: `y, x ∈ {±0..64 LSB}` and one
    /// coordinate tiny while the other spans large values.
    #[test]
    fn atan2_dense_near_axes_and_tiny() {
        let mut worst = 0.0f64;
        for yb in -64..=64 {
            for xb in -64..=64 {
                let v = atan2_within_bound(I16F16::from_bits(yb), I16F16::from_bits(xb));
                assert!(v.holds, "atan2({yb}, {xb}) LSB err {}", v.error);
                worst = worst.max(v.error);
            }
        }
        let big = [1i32, 3, 255, 65535, 65536, 1 << 20, 1 << 24, i32::MAX, i32::MIN, -(1 << 24)];
        for tiny in -16..=16 {
            for &b in &big {
                for (y, x) in [(tiny, b), (b, tiny)] {
                    let v = atan2_within_bound(I16F16::from_bits(y), I16F16::from_bits(x));
                    assert!(v.holds, "atan2 bits ({y}, {x}) LSB err {}", v.error);
                    worst = worst.max(v.error);
                }
            }
        }
        assert!(worst <= 1.0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Full-range I16F16 pairs (every bit pattern equally likely).
        #[test]
        fn atan2_full_range(y in any::<i32>(), x in any::<i32>()) {
            let v = atan2_within_bound(I16F16::from_bits(y), I16F16::from_bits(x));
            prop_assert!(v.holds, "err {}", v.error);
        }

        /// Joint angles within ±4 turns.
        #[test]
        fn sin_cos_joint_angles(a in -25.0f64..25.0) {
            let x = fx(a);
            prop_assert!(sin_within_bound(x).holds);
            prop_assert!(cos_within_bound(x).holds);
        }

        /// Slopes and ratios met by the kinematics.
        #[test]
        fn atan_ratios(a in -200.0f64..200.0) {
            let x = fx(a);
            prop_assert!(atan_within_bound(x).holds);
            prop_assert!(monotone_at(k::atan, x).holds);
        }

        /// Angles inside the principal branch.
        #[test]
        fn tan_branch(a in -1.5707f64..1.5707) {
            let x = fx(a);
            prop_assert!(tan_within_bound(x).holds);
            prop_assert!(monotone_at(k::tan, x).holds);
        }

        /// Stribeck / exponential-decay exponents.
        #[test]
        fn exp_exponents(a in -13.0f64..10.5) {
            let x = fx(a);
            prop_assert!(exp_within_bound(x).holds);
            prop_assert!(monotone_at(k::exp, x).holds);
        }

        /// Cosines of joint angles and a margin outside [-1, 1].
        #[test]
        fn acos_cosines(a in -1.2f64..1.2) {
            prop_assert!(acos_within_bound(fx(a)).holds);
        }

        /// Squared norms of forces/velocities.
        #[test]
        fn sqrt_norms(a in -10.0f64..30000.0) {
            let x = fx(a);
            prop_assert!(sqrt_within_bound(x).holds);
            prop_assert!(monotone_at(k::sqrt, x).holds);
        }

        #[test]
        fn building_blocks_exact(a in any::<u32>(), b in any::<u32>(), d in 1u32..=(1 << 31)) {
            prop_assert!(mulhi_is_exact(a, b));
            prop_assert!(div_frac_is_exact(a % d, d));
            prop_assert!(sqrt_q16_is_exact(a));
        }
    }
}
