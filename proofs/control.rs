//! Properties of the ch. 4 control components (friction model eq. 4.17,
//! robust adaptive law eq. 4.19 with projection, mode manager), for the
//! Table 4.1 example configuration.
//!
//! | property | I16F16 | f32 | f64 |
//! |---|---|---|---|
//! | `sat_reciprocal` — the division-free `sat(x, ε)` of the hot path is in `[−1, 1]`, within 1 LSB/ulp of eq. (4.18), odd | Kani; exhaustive (all 2³² `x`, ε = ε_r) | Kani; random | random |
//! | `friction_sign_and_bound` — `f̂^c(q̇)` never opposes `q̇` and `|f̂^c| ≤ b̂|q̇| + f̂_c + f̂_s` (+ rounding) | Kani (every speed, in four parts); exhaustive (all 2²⁴ speeds in ±128 rad/s) | random | random |
//! | `law_monotone_in_position` — eq. (4.19) is non-increasing in the measured motor position (every term is: `−λ²I_m e`, `−K_r sat(r)`, `−ρ_j Y_j sat(r Y_j)`) | exhaustive (2²⁴ consecutive positions, chained) | random | random |
//! | `step_bounded` — output within the limit, never NaN; integral within its limit; estimates within the projection box | Kani (`exp_neg_abs`, product by contracts); random | Kani (the law by its contract: any terms); random | random |
//! | `switch_bumpless` — at a mode switch, `|τ_after − τ_before| ≤` [`ModeConfig::switch_jump_bound`](crate::control::ModeConfig::switch_jump_bound) | random (proptest in `control::mode`), fuzz | same | same |

use super::engine::Verdict;
use crate::control::{
    ControlInput, ModeConfig, ModeState, RobustAdaptiveConfig, RobustAdaptiveParams,
    RobustAdaptiveState,
};
use crate::friction::{sat_with_reciprocal, FrictionConfig};
use crate::scalar::{Coef, Scalar, I16F16};

/// The Table 4.1 active law for backend `S`.
pub fn table_4_1<S: Scalar>() -> RobustAdaptiveConfig<S> {
    // The shipped constants validate (`control::adaptive` tests).
    RobustAdaptiveConfig::new(
        &RobustAdaptiveParams::table_4_1().expect("Table 4.1 constants are valid"),
    )
}

/// `sat_with_reciprocal(x, ε, 1/ε)` lies in `[−1, 1]`, is not NaN, is odd
/// (for `x ≠ MIN`), and is within one resolution unit (plus the
/// coefficient's relative `2⁻³⁰`) of eq. (4.18) evaluated exactly.
pub fn sat_reciprocal<S: Scalar>(x: S, eps: S, inv_eps: &Coef) -> Verdict {
    let s = sat_with_reciprocal(x, eps, inv_eps);
    let in_range = !s.is_nan() && s >= S::ONE.neg() && s <= S::ONE;
    let odd = x == S::MIN || x.is_nan() || sat_with_reciprocal(x.neg(), eps, inv_eps) == s.neg();
    Verdict::logical(in_range && odd).and(sat_reciprocal_value(x, eps, s))
}

/// The value check of [`sat_reciprocal`] for a computed result `s`.
pub fn sat_reciprocal_value<S: Scalar>(x: S, eps: S, s: S) -> Verdict {
    let (xf, ef) = (x.to_f64(), eps.to_f64());
    let exact = if x.is_nan() {
        0.0
    } else if xf.abs() > ef {
        xf.signum()
    } else {
        xf / ef
    };
    let res = S::RESOLUTION.to_f64();
    let err = (s.to_f64() - exact).abs() / res;
    Verdict::bounded(err, 1.0 + 2f64.powi(-29) / res)
}

/// [`sat_reciprocal`] on `f32` without an `f64` division, for the Kani
/// harness (whose solver does not finish one in 600 s): in range, odd,
/// and the value check with the quotient cross-multiplied: inside the
/// layer (`ε > 0`), `|s − x/ε| ≤ (1 + 2⁻⁶)·2⁻²³` is
/// `|s·ε − x| ≤ (1 + 2⁻⁶)·2⁻²³·ε`; outside, `s = sgn x`; `s = 0` for NaN.
/// The products are exact in `f64` (`s·ε`: 24 + 24 bits; the right side
/// a power of two times a 7-bit factor) and the one difference rounds by
/// `2⁻⁵³` relative; `sat_reciprocal_product_form_agrees` compares the two
/// forms on random and constructed results, failing ones included.
pub fn sat_reciprocal_f32_products(x: f32, eps: f32, inv_eps: &Coef) -> bool {
    let s = sat_with_reciprocal(x, eps, inv_eps);
    let in_range = !s.is_nan() && (-1.0..=1.0).contains(&s);
    let odd = x == f32::MIN || x.is_nan() || sat_with_reciprocal(-x, eps, inv_eps) == -s;
    in_range && odd && sat_reciprocal_value_f32_products(x, eps, s)
}

/// The value check of [`sat_reciprocal_f32_products`] for a result `s`.
pub fn sat_reciprocal_value_f32_products(x: f32, eps: f32, s: f32) -> bool {
    if x.is_nan() {
        return s.abs() <= f32::EPSILON * (1.0 + 1.0 / 64.0);
    }
    let (xf, ef, sf) = (x as f64, eps as f64, s as f64);
    let tol = (1.0 + 1.0 / 64.0) * f32::EPSILON as f64;
    if xf.abs() > ef {
        (sf - xf.signum()).abs() <= tol
    } else {
        (sf * ef - xf).abs() <= tol * ef
    }
}

/// [`sat_reciprocal`] on `I16F16`, decided on integers (no `f64` of the
/// symbolic input): with `X`, `E`, `Q` the bits of `x`, `ε` (`> 0`) and the
/// result, `Q ∈ [−2¹⁶, 2¹⁶]`, odd for `X ≠ MIN`, `Q = 2¹⁶·sgn X` for
/// `|X| > E`, and otherwise `|Q − 2¹⁶X/E| ≤ 1 + 2⁻¹³` LSB (the same bound:
/// one LSB plus the coefficient's relative `2⁻²⁹` at `|x/ε| ≤ 1`), i.e.
/// `8192·|Q·E − 2¹⁶X| ≤ 8193·E` (below 2⁶² in magnitude).
pub fn sat_reciprocal_i16f16(x: I16F16, eps: I16F16, inv_eps: &Coef) -> Verdict {
    let s = sat_with_reciprocal(x, eps, inv_eps);
    let odd = x == I16F16::MIN || sat_with_reciprocal(x.neg(), eps, inv_eps) == s.neg();
    sat_reciprocal_bits_match(s.to_bits(), x.to_bits(), eps.to_bits()).and(Verdict::logical(odd))
}

/// The value check of [`sat_reciprocal_i16f16`] for a computed result `q`
/// (bits), input `x` and layer `e > 0` (bits).
pub fn sat_reciprocal_bits_match(q: i32, x: i32, e: i32) -> Verdict {
    const ONE: i64 = 1 << 16;
    let (q, x, e) = (q as i64, x as i64, e as i64);
    let in_range = (-ONE..=ONE).contains(&q);
    let value = if x.abs() > e {
        q == ONE * x.signum()
    } else {
        8192 * (q * e - ONE * x).abs() <= 8193 * e
    };
    Verdict::logical(in_range && value)
}

/// The nominal friction of eq. (4.17) with non-negative estimates never
/// opposes the speed (`f̂ · q̇ ≥ 0`, exactly, since every product keeps its
/// sign under rounding) and is bounded by `b̂|q̇| + f̂_c + f̂_s` plus four
/// roundings; never NaN.
pub fn friction_sign_and_bound<S: Scalar>(
    cfg: &FrictionConfig<S>,
    theta: &[S; 4],
    qd: S,
) -> Verdict {
    let f = cfg.evaluate(theta, qd).torque;
    if qd.is_nan() {
        // Precondition: a speed (the laws reject NaN samples before this).
        return Verdict::logical(true);
    }
    let sign_ok = if qd > S::ZERO {
        f >= S::ZERO
    } else if qd < S::ZERO {
        f <= S::ZERO
    } else {
        f == S::ZERO
    };
    let bound = theta[0].to_f64() * qd.to_f64().abs()
        + theta[1].to_f64()
        + theta[2].to_f64()
        + 4.0 * S::RESOLUTION.to_f64() * (1.0 + theta[0].to_f64() * qd.to_f64().abs());
    Verdict::logical(!f.is_nan() && sign_ok && f.to_f64().abs() <= bound)
}

/// [`friction_sign_and_bound`] on `I16F16`, decided on integers (no `f64`
/// of the symbolic speed): with `F`, `Q`, `T_j` the bits of `f̂`, `q̇` and
/// `θ_j`, `F` has the sign of `Q` (0 at 0) and
/// `|F|·2³² ≤ T₀|Q|·2¹⁶ + (T₁ + T₂)·2³² + 4·2³² + 4·T₀|Q|` — the same bound
/// times `2⁴⁸` (four roundings of `2⁻¹⁶` each, one of them scaled by
/// `1 + b̂|q̇|`). Requires `θ ≥ 0`.
pub fn friction_sign_and_bound_i16f16(
    cfg: &FrictionConfig<I16F16>,
    theta: &[I16F16; 4],
    qd: I16F16,
) -> Verdict {
    let f = cfg.evaluate(theta, qd).torque.to_bits();
    friction_bits_match(f, qd.to_bits(), theta.map(|v| v.to_bits()))
}

/// The check of [`friction_sign_and_bound_i16f16`] on bits: result `f`,
/// speed `q`, parameters `t` (`≥ 0`).
pub fn friction_bits_match(f: i32, q: i32, t: [i32; 4]) -> Verdict {
    let (f, q) = (f as i128, q as i128);
    let t = t.map(|v| v as i128);
    let sign_ok = if q > 0 {
        f >= 0
    } else if q < 0 {
        f <= 0
    } else {
        f == 0
    };
    let tq = t[0] * q.abs();
    let bound = (tq << 16) + ((t[1] + t[2] + 4) << 32) + 4 * tq;
    Verdict::logical(sign_ok && (f.abs() << 32) <= bound)
}

/// Eq. (4.19) does not increase when the measured motor position
/// increases, all else fixed: `law(x with q_m) ≥ law(x with q_m')` for
/// `q_m < q_m'`.
pub fn law_monotone_in_position<S: Scalar>(law_lo: S, law_hi: S) -> Verdict {
    Verdict::logical(!law_lo.is_nan() && !law_hi.is_nan() && law_lo >= law_hi)
}

/// One step of the active law: output in `[−L, L]` and not NaN, integral
/// in `[−z_max, z_max]`, estimates in the projection box.
pub fn step_bounded<S: Scalar>(
    cfg: &RobustAdaptiveConfig<S>,
    st: &mut RobustAdaptiveState<S>,
    x: &ControlInput<S>,
) -> Verdict {
    let o = cfg.update(st, x);
    let lim = cfg.torque_limit();
    let mut ok = !o.torque.is_nan() && o.torque.abs() <= lim;
    ok &= st.integral.abs() <= cfg.integral_limit();
    let (lo, hi) = (cfg.lower_bounds(), cfg.upper_bounds());
    for j in 0..4 {
        ok &= st.friction[j] >= lo[j] && st.friction[j] <= hi[j];
    }
    Verdict::logical(ok)
}

/// One step of the mode manager after a previous command `prev`: bounded,
/// NaN-free output; at a switch the jump from `prev` is within the
/// documented bound; otherwise the output is the current mode's command.
pub fn switch_bumpless<S: Scalar>(
    cfg: &ModeConfig<S>,
    st: &mut ModeState<S>,
    x: &ControlInput<S>,
    prev: S,
) -> Verdict {
    let before = cfg.evaluate(st, x);
    let o = cfg.update(st, x);
    let mut ok = !o.torque.is_nan() && o.torque.abs() <= cfg.torque_limit();
    if o.switched {
        ok &= o.torque.sub(prev).abs() <= cfg.switch_jump_bound();
    } else if !o.invalid_input {
        ok &= o.torque == before;
    }
    Verdict::logical(ok)
}

/// `ε_r = 0.1 rad/s` of Table 4.1 as `I16F16` (bits 6554, the rounding of
/// 6553.6) and its reciprocal `65536/6554` as a [`Coef`], from their stored
/// quantization (`Coef::from_quantized`: no floating-point work for the
/// solver). `prepared_constants_are_the_constructors` checks both equal
/// `I16F16::from_f64(0.1)` and `Coef::new(1/ε)`.
#[cfg(any(kani, test))]
fn eps_r_i16f16_prepared() -> (I16F16, Coef) {
    const INV: f64 = 65536.0 / 6554.0;
    (
        I16F16::from_bits(6554),
        Coef::from_quantized(INV, INV as f32, 1_342_095_365, 27),
    )
}

/// `ε_r = 0.1` as `f32` and its reciprocal `1/0.1f32` (in `f64`) as a
/// [`Coef`], from their stored quantization (as
/// [`eps_r_i16f16_prepared`]).
#[cfg(any(kani, test))]
fn eps_r_f32_prepared() -> (f32, Coef) {
    const INV: f64 = 1.0 / (0.1f32 as f64);
    (
        0.1f32,
        Coef::from_quantized(INV, INV as f32, F32_INV_MULT, 27),
    )
}

/// The contract of `RobustAdaptiveConfig::law_of_checked_input` that
/// `kani_step_bounded_f32` stands on: any law, errors and products `r·Y_j`
/// (NaN and infinities included), `valid` exactly when neither the law nor
/// `r` is NaN (the function's own last line), and no `r·Y_j` NaN when
/// valid (a NaN `r·Y_j` makes its robust term, hence the law, NaN).
/// `law_validity_is_the_nan_test` checks both on the real law.
#[cfg(kani)]
pub(crate) fn law_as_contract<S: Scalar + kani::Arbitrary>(
    _cfg: &RobustAdaptiveConfig<S>,
    _st: &RobustAdaptiveState<S>,
    _x: &ControlInput<S>,
) -> crate::control::adaptive::ActiveTerms<S> {
    let law: S = kani::any();
    let r: S = kani::any();
    let ry: [S; 4] = [kani::any(), kani::any(), kani::any(), kani::any()];
    let valid = !law.is_nan() && !r.is_nan();
    // Postcondition of the stubbed function (law_validity_is_the_nan_test).
    kani::assume(!valid || ry.iter().all(|v| !v.is_nan()));
    crate::control::adaptive::ActiveTerms {
        law,
        e: kani::any(),
        r,
        ry,
        valid,
    }
}

/// `table_4_1::<f32>()` from stored words (a compile-time constant read by
/// `const fn`s that only reassemble bits): built by the constructor inside
/// a harness, the configuration's `f64` quantization and slope searches
/// reach the solver as a formula (CBMC ran out of memory). The unit test
/// `stored_f32_law_is_the_constructors` checks the words against the
/// constructor's; regenerate them with `cargo test --all-features --lib
/// stored_f32_law_words_print -- --ignored --nocapture`.
#[cfg(any(kani, test))]
pub(crate) const TABLE_4_1_F32: RobustAdaptiveConfig<f32> = {
    let mut r = crate::scalar::words::Words::new(&TABLE_4_1_F32_WORDS);
    let c = RobustAdaptiveConfig::<f32>::take(&mut r);
    assert!(r.is_done(), "stored words left over");
    c
};

/// The words of `table_4_1::<f32>()`, as written by its `put`.
#[cfg(any(kani, test))]
#[rustfmt::skip]
const TABLE_4_1_F32_WORDS: [u32; 386] = [
    0x3c23d70a, 0x09600004, 0x40590000, 0x42c80000, 0x64000026, 0x00000000, 0x00000018, 0x64000026,
    0x00000000, 0x00000001, 0x64000026, 0x00000000, 0x00800000, 0x00000017, 0x00000064, 0xffffff9b,
    0x00000001, 0x42c80000, 0x11d00c1c, 0x3ee7e854, 0x373f42a1, 0x5fa15047, 0x00000000, 0x0000002f,
    0x5fa15047, 0x00000000, 0x00000001, 0x5fa15047, 0x00000001, 0x00004000, 0x0000000f, 0x00000000,
    0xffffffff, 0xd0b30b5a, 0x3f5669ce, 0x3ab34e77, 0x59a73b43, 0x00000000, 0x00000028, 0x59a73b43,
    0x00000000, 0x00000001, 0x59a73b43, 0x00000001, 0x00000080, 0x00000008, 0x00000000, 0xffffffff,
    0x00000000, 0x405e0000, 0x42f00000, 0x78000000, 0x00000000, 0x00000018, 0x78000000, 0x00000000,
    0x00000001, 0x78000000, 0x00000000, 0x00800000, 0x00000017, 0x00000078, 0xffffff88, 0x00000000,
    0x47ae147b, 0x3f847ae1, 0x3c23d70a, 0x51eb851f, 0x00000000, 0x00000025, 0x51eb851f, 0x00000000,
    0x00000001, 0x51eb851f, 0x00000001, 0x00000010, 0x00000005, 0x00000000, 0xffffffff, 0x00000000,
    0x47ae147b, 0x3fa47ae1, 0x3d23d70a, 0x51eb851f, 0x00000000, 0x00000023, 0x51eb851f, 0x00000000,
    0x00000001, 0x51eb851f, 0x00000001, 0x00000004, 0x00000003, 0x00000000, 0xffffffff, 0x00000000,
    0x3e2e147b, 0xbe2e147b, 0x3dcccccd, 0x2c666669, 0x3ffb3333, 0x3fd99999, 0x6cccccb2, 0x00000000,
    0x0000001e, 0x6cccccb2, 0x00000000, 0x00000001, 0x6cccccb2, 0x00000000, 0x20000000, 0x0000001d,
    0x00000001, 0xfffffffe, 0xd2f1a9fc, 0x3f50624d, 0x3a83126f, 0x4189374c, 0x00000000, 0x00000028,
    0x4189374c, 0x00000000, 0x00000001, 0x4189374c, 0x00000001, 0x00000080, 0x00000008, 0x00000000,
    0xffffffff, 0x47ae147b, 0x3f847ae1, 0x3c23d70a, 0x51eb851f, 0x00000000, 0x00000025, 0x51eb851f,
    0x00000000, 0x00000001, 0x51eb851f, 0x00000001, 0x00000010, 0x00000005, 0x00000000, 0xffffffff,
    0x47ae147b, 0x3f847ae1, 0x3c23d70a, 0x51eb851f, 0x00000000, 0x00000025, 0x51eb851f, 0x00000000,
    0x00000001, 0x51eb851f, 0x00000001, 0x00000010, 0x00000005, 0x00000000, 0xffffffff, 0x00000000,
    0x3ff00000, 0x3f800000, 0x40000000, 0x00000000, 0x0000001e, 0x40000000, 0x00000000, 0x00000001,
    0x40000000, 0x00000000, 0x20000000, 0x0000001d, 0x00000001, 0xffffffff, 0x38d1b717, 0x3a83126f,
    0x3a83126f, 0x3dcccccd, 0x087a0004, 0x40240000, 0x41200000, 0x50000022, 0x00000000, 0x0000001b,
    0x50000022, 0x00000000, 0x00000001, 0x50000022, 0x00000000, 0x04000000, 0x0000001a, 0x0000000a,
    0xfffffff5, 0xf010000d, 0x4023ffff, 0x41200000, 0x4fffffc0, 0x00000000, 0x0000001b, 0x4fffffc0,
    0x00000000, 0x00000001, 0x4fffffc0, 0x00000000, 0x04000000, 0x0000001a, 0x00000009, 0xfffffff6,
    0xf010000d, 0x4023ffff, 0x41200000, 0x4fffffc0, 0x00000000, 0x0000001b, 0x4fffffc0, 0x00000000,
    0x00000001, 0x4fffffc0, 0x00000000, 0x04000000, 0x0000001a, 0x00000009, 0xfffffff6, 0xfb000001,
    0x4023ffff, 0x41200000, 0x4fffffec, 0x00000000, 0x0000001b, 0x4fffffec, 0x00000000, 0x00000001,
    0x4fffffec, 0x00000000, 0x04000000, 0x0000001a, 0x00000009, 0xfffffff6, 0xeb1c432d, 0xbf3a36e2,
    0xb9d1b717, 0x97247454, 0xffffffff, 0x0000002a, 0x68db8bac, 0x00000001, 0x00000001, 0x97247454,
    0x00000001, 0x00000200, 0x0000000a, 0xffffffff, 0x00000000, 0xeb1c432d, 0xbf3a36e2, 0xb9d1b717,
    0x97247454, 0xffffffff, 0x0000002a, 0x68db8bac, 0x00000001, 0x00000001, 0x97247454, 0x00000001,
    0x00000200, 0x0000000a, 0xffffffff, 0x00000000, 0xeb1c432d, 0xbf3a36e2, 0xb9d1b717, 0x97247454,
    0xffffffff, 0x0000002a, 0x68db8bac, 0x00000001, 0x00000001, 0x97247454, 0x00000001, 0x00000200,
    0x0000000a, 0xffffffff, 0x00000000, 0xeb1c432d, 0xbf3a36e2, 0xb9d1b717, 0x97247454, 0xffffffff,
    0x0000002a, 0x68db8bac, 0x00000001, 0x00000001, 0x97247454, 0x00000001, 0x00000200, 0x0000000a,
    0xffffffff, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x3c23d70a, 0x38d1b717, 0x3c449ba6,
    0x3c449ba6, 0x41200000, 0x3851b717, 0x3bc49ba6, 0x3bc49ba6, 0x3f800000, 0x3dcccccd, 0x3e408312,
    0x11d00c1c, 0x3ee7e854, 0x00000000, 0x40590000, 0x00000000, 0x405e0000, 0x00000000, 0x40240000,
    0x9999999a, 0x3fb99999, 0x9999999a, 0x3fb99999, 0x9999999a, 0x3fb99999, 0x9999999a, 0x3fb99999,
    0x9999999a, 0x3fb99999, 0x47ae147b, 0x3f847ae1, 0xeb1c432d, 0x3f1a36e2, 0xd2f1a9fc, 0x3f50624d,
    0xd2f1a9fc, 0x3f50624d, 0x9999999a, 0x3fb99999, 0x020c49bb, 0x3fa6872b, 0xd2f1a9fc, 0x3f60624d,
    0x00000000, 0x40c38800, 0x00000000, 0x3ff00000, 0x00000000, 0x00000000, 0x00000000, 0x00000000,
    0x00000000, 0x00000000, 0x47ae147b, 0x3f847ae1, 0xeb1c432d, 0x3f1a36e2, 0xbc6a7efa, 0x3f889374,
    0xbc6a7efa, 0x3f889374, 0x00000000, 0x40240000, 0xd2f1a9fc, 0x3f50624d, 0x47ae147b, 0x3f847ae1,
    0x47ae147b, 0x3f847ae1, 0x00000000, 0x3ff00000, 0xeb1c432d, 0x3f0a36e2, 0xbc6a7efa, 0x3f789374,
    0xbc6a7efa, 0x3f789374, 0x00000000, 0x3ff00000, 0x9999999a, 0x3fb99999, 0x4dd2f1aa, 0x3fc81062,
    0xd2f1a9fc, 0x3f70624d,
];

/// The 31-bit mantissa of `1/0.1f32` at shift 27.
#[cfg(any(kani, test))]
const F32_INV_MULT: i64 = 1_342_177_260;

#[cfg(kani)]
mod kani_entries {
    use super::*;

    fn any_i16f16() -> I16F16 {
        I16F16::from_bits(kani::any())
    }

    /// [`sat_reciprocal_i16f16`] inside the layer `|x| ≤ ε` (and one LSB
    /// beyond it), where the product by `1/ε` decides the value; the
    /// outside is `kani_sat_reciprocal_outside_i16f16`, and
    /// `exhaustive_sat_reciprocal_i16f16` covers all 2³² inputs.
    #[kani::proof]
    fn kani_sat_reciprocal_i16f16() {
        let (eps, inv) = super::eps_r_i16f16_prepared();
        let x = any_i16f16();
        // Solver budget: the layer (split domain; outside: the next harness).
        kani::assume(x.to_bits() >= -eps.to_bits() - 1 && x.to_bits() <= eps.to_bits() + 1);
        assert!(sat_reciprocal_i16f16(x, eps, &inv).holds);
    }

    /// [`sat_reciprocal_i16f16`] outside the layer, `|x| > ε`.
    #[kani::proof]
    fn kani_sat_reciprocal_outside_i16f16() {
        let (eps, inv) = super::eps_r_i16f16_prepared();
        let x = any_i16f16();
        // Split domain: the complement of `kani_sat_reciprocal_i16f16`'s.
        kani::assume(x.to_bits() < -eps.to_bits() - 1 || x.to_bits() > eps.to_bits() + 1);
        assert!(sat_reciprocal_i16f16(x, eps, &inv).holds);
    }

    #[kani::proof]
    fn kani_sat_reciprocal_f32() {
        let (eps, inv) = super::eps_r_f32_prepared();
        // The check in its division-free form (`sat_reciprocal_f32_products`).
        assert!(sat_reciprocal_f32_products(kani::any(), eps, &inv));
    }

    /// The joint's stored friction configuration and initial estimates
    /// (`FrictionConfig::new(0.01)` and those of `table_4_1::<I16F16>()`, a
    /// compile-time constant; `friction_harness_config_is_the_constructors`).
    fn friction_of_the_joint() -> (FrictionConfig<I16F16>, [I16F16; 4]) {
        let law = *crate::proofs::joint_step::kani_entries::joint()
            .mode()
            .active();
        (*law.friction_config(), law.initial_state().friction)
    }

    /// [`friction_sign_and_bound_i16f16`] at the speeds whose magnitude
    /// bits `m` satisfy `part(m, e)` (`e` the layer's bits; split domain,
    /// the four parts below together take every speed), `exp_neg_abs` by
    /// its contract (`[0, 1]`: `exhaustive_exp_neg_abs_i16f16`). The
    /// single every-speed harness timed out at 605 s;
    /// `exhaustive_friction_i16f16` covers all 2²⁴ speeds in ±128 rad/s.
    fn friction_sign_on(part: impl Fn(u32, u32) -> bool) {
        let (cfg, theta) = friction_of_the_joint();
        let e = cfg.eps_velocity().to_bits().unsigned_abs();
        let q = any_i16f16();
        kani::assume(part(q.to_bits().unsigned_abs(), e));
        assert!(friction_sign_and_bound_i16f16(&cfg, &theta, q).holds);
    }

    /// Inside the velocity layer `|q̇| ≤ ε_q̇`, and one LSB beyond.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::exp_neg_abs,
        crate::proofs::joint_step::kani_entries::exp_neg_abs_as_contract
    )]
    fn kani_friction_sign_inside_i16f16() {
        friction_sign_on(|m, e| m <= e + 1);
    }

    /// Outside the layer up to 1 rad/s, where `sat(q̇) = ±1`.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::exp_neg_abs,
        crate::proofs::joint_step::kani_entries::exp_neg_abs_as_contract
    )]
    fn kani_friction_sign_outside_slow_i16f16() {
        friction_sign_on(|m, e| m > e + 1 && m <= 1 << 16);
    }

    /// `1 < |q̇| ≤ 128` rad/s.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::exp_neg_abs,
        crate::proofs::joint_step::kani_entries::exp_neg_abs_as_contract
    )]
    fn kani_friction_sign_outside_medium_i16f16() {
        friction_sign_on(|m, _| m > 1 << 16 && m <= 1 << 23);
    }

    /// Above 128 rad/s (`q̇²` saturates from 181 rad/s).
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::exp_neg_abs,
        crate::proofs::joint_step::kani_entries::exp_neg_abs_as_contract
    )]
    fn kani_friction_sign_outside_fast_i16f16() {
        friction_sign_on(|m, _| m > 1 << 23);
    }

    /// [`step_bounded`] from every state inside the box and the integral
    /// limit, on every input; `exp_neg_abs` and the `I16F16` product by their
    /// contracts (`proofs/joint_step.rs`).
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::exp_neg_abs,
        crate::proofs::joint_step::kani_entries::exp_neg_abs_as_contract
    )]
    #[kani::stub(
        crate::scalar::fixed::mul_bits,
        crate::proofs::joint_step::kani_entries::mul_bits_as_contract
    )]
    fn kani_step_bounded_i16f16() {
        // `table_4_1::<I16F16>()` as stored words, a compile-time constant
        // (`table_4_1_is_the_joints_active_law`).
        let cfg = *crate::proofs::joint_step::kani_entries::joint()
            .mode()
            .active();
        let mut st = cfg.initial_state();
        // Any state inside the box and the integral limit (precondition:
        // the states the law itself produces).
        for j in 0..4 {
            let v = any_i16f16();
            kani::assume(v >= cfg.lower_bounds()[j] && v <= cfg.upper_bounds()[j]);
            st.friction[j] = v;
        }
        let z = any_i16f16();
        // `Scalar::abs` (saturating): the inherent `I16F16::abs` overflows
        // at `MIN`, which the precondition excludes anyway.
        kani::assume(Scalar::abs(z) <= cfg.integral_limit());
        st.integral = z;
        let x = ControlInput {
            desired_position: any_i16f16(),
            desired_velocity: any_i16f16(),
            desired_acceleration: any_i16f16(),
            motor_position: any_i16f16(),
            motor_velocity: any_i16f16(),
            joint_torque: any_i16f16(),
            desired_joint_torque: I16F16::ZERO,
            expected_joint_torque: I16F16::ZERO,
        };
        assert!(step_bounded(&cfg, &mut st, &x).holds);
    }

    /// [`step_bounded`] on `f32` from every state inside the box and the
    /// integral limit (any finite residuals), on every finite input, with the law
    /// itself by its contract ([`law_as_contract`]: any terms, NaN and
    /// infinities included): the limit, the NaN test and the projected
    /// updates bound the step whatever value the law takes. The whole law
    /// with six symbolic `f32` readings ran out of memory after 240 s, and
    /// so did this harness (351 s) with the configuration built by its
    /// constructor.
    #[kani::proof]
    #[kani::stub(
        crate::control::adaptive::RobustAdaptiveConfig::law_of_checked_input,
        super::law_as_contract
    )]
    fn kani_step_bounded_f32() {
        // `table_4_1::<f32>()` as stored words, a compile-time constant
        // (`stored_f32_law_is_the_constructors`).
        let cfg = super::TABLE_4_1_F32;
        let mut st = cfg.initial_state();
        // Precondition: the states the step itself produces.
        let (lo, hi) = (cfg.lower_bounds(), cfg.upper_bounds());
        for j in 0..4 {
            let v: f32 = kani::any();
            kani::assume(v >= lo[j] && v <= hi[j]);
            st.friction[j] = v;
            // Precondition: a finite residual, as the step leaves it (the
            // rounding remainder of an in-box sum, or 0).
            let res: f32 = kani::any();
            kani::assume(res.is_finite());
            st.friction_residual[j] = res;
        }
        let z: f32 = kani::any();
        kani::assume(z.abs() <= cfg.integral_limit());
        st.integral = z;
        let x = ControlInput {
            desired_position: kani::any(),
            desired_velocity: kani::any(),
            desired_acceleration: kani::any(),
            motor_position: kani::any(),
            motor_velocity: kani::any(),
            joint_torque: kani::any(),
            desired_joint_torque: 0.0,
            expected_joint_torque: 0.0,
        };
        // Precondition: finite readings. Kani's NaN check fails any
        // operation that makes a NaN, and the step's finiteness test makes
        // one on purpose (`v − v` of an infinite reading); non-finite
        // readings (output 0, flagged, state untouched) are the random
        // engine's and the unit tests'.
        // (Tested with `f32::is_finite`, which makes no NaN.)
        kani::assume(
            [
                x.desired_position,
                x.desired_velocity,
                x.desired_acceleration,
                x.motor_position,
                x.motor_velocity,
                x.joint_torque,
            ]
            .iter()
            .all(|v: &f32| v.is_finite()),
        );
        assert!(step_bounded(&cfg, &mut st, &x).holds);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::{exhaustive_u32, exhaustive_u32_chained};
    use super::*;
    use crate::control::{ModeParams, ModeSettings, PassiveParams};
    use crate::estimation::{CollisionParams, CollisionReaction, CollisionSettings};
    use crate::scalar::I16F16;

    /// The Kani harnesses' stored constants are what the library's
    /// constructors build, field by field, so their results hold for the
    /// library's own `ε_r` and `1/ε_r`; and the comparison can fail (a
    /// mantissa one unit off differs).
    #[test]
    fn prepared_constants_are_the_constructors() {
        let (eps, inv) = eps_r_i16f16_prepared();
        assert_eq!(eps, I16F16::from_f64(0.1));
        assert_eq!(inv, Coef::new(1.0 / I16F16::from_f64(0.1).to_f64()));
        let (eps, inv) = eps_r_f32_prepared();
        assert_eq!(eps, 0.1f32);
        assert_eq!(inv, Coef::new(1.0 / 0.1f32 as f64));
        const INV: f64 = 1.0 / (0.1f32 as f64);
        assert_ne!(
            Coef::from_quantized(INV, INV as f32, F32_INV_MULT + 1, 27),
            Coef::new(INV)
        );
    }
    use proptest::prelude::*;
    use std::println;

    /// `kani_friction_sign_{inside,outside}_i16f16` take their friction model and estimates
    /// from the joint's stored configuration: they are
    /// `FrictionConfig::new(0.01)` and this module's `table_4_1` initial
    /// estimates.
    #[test]
    fn friction_harness_config_is_the_constructors() {
        let law = crate::joint::TABLE_4_1_I16F16.mode().active();
        assert_eq!(law.friction_config(), &FrictionConfig::<I16F16>::new(0.01));
        assert_eq!(
            law.initial_state().friction,
            table_4_1::<I16F16>().initial_state().friction
        );
    }

    /// The contract `law_as_contract` stands for: the real law's `valid`
    /// is exactly "neither the law nor `r` is NaN", on readings that make
    /// both true and false (infinite and NaN readings, huge and ordinary
    /// ones), from states across the box. The check fails if `valid`
    /// tested anything else (e.g. `e`, or finiteness instead of NaN).
    #[test]
    fn law_validity_is_the_nan_test() {
        let cfg = table_4_1::<f32>();
        let mut next = super::super::engine::xorshift64(0x9E37_79B9_7F4A_7C15);
        let special = [
            0.0f32,
            -0.0,
            1e-3,
            -2.5,
            3.0e38,
            -3.0e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let pick = |next: &mut dyn FnMut() -> u64| -> f32 {
            let w = next();
            match w % 4 {
                0 => special[(w >> 8) as usize % special.len()],
                1 => f32::from_bits((w >> 16) as u32),
                _ => ((w >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0) as f32,
            }
        };
        let (mut valid, mut invalid, mut finite_invalid) = (0, 0, 0);
        for _ in 0..200_000 {
            let mut st = cfg.initial_state();
            let (lo, hi) = (cfg.lower_bounds(), cfg.upper_bounds());
            for j in 0..4 {
                let u = (next() >> 11) as f32 / (1u64 << 53) as f32;
                st.friction[j] = lo[j] + (hi[j] - lo[j]) * u;
            }
            let x = ControlInput {
                desired_position: pick(&mut next),
                desired_velocity: pick(&mut next),
                desired_acceleration: pick(&mut next),
                motor_position: pick(&mut next),
                motor_velocity: pick(&mut next),
                joint_torque: pick(&mut next),
                desired_joint_torque: 0.0,
                expected_joint_torque: 0.0,
            };
            let t = cfg.law_of_checked_input(&st, &x);
            assert_eq!(t.valid, !t.law.is_nan() && !t.r.is_nan(), "{x:?}");
            assert!(!t.valid || t.ry.iter().all(|v| !v.is_nan()), "{x:?}");
            if t.valid {
                valid += 1;
            } else {
                invalid += 1;
                finite_invalid += x.is_finite() as u32;
            }
        }
        // Both outcomes reached, and invalid ones from finite readings
        // too (an overflowing law), not only from NaN inputs.
        assert!(
            valid > 10_000 && invalid > 10_000 && finite_invalid > 0,
            "{valid} {invalid} {finite_invalid}"
        );
    }

    fn f32_words_of(c: &RobustAdaptiveConfig<f32>) -> std::vec::Vec<u32> {
        let mut s = crate::scalar::words::Sink::default();
        c.put(&mut s);
        s.0
    }

    /// `kani_step_bounded_f32`'s stored configuration is
    /// `table_4_1::<f32>()`: word for word, and as a value.
    #[test]
    fn stored_f32_law_is_the_constructors() {
        let c = table_4_1::<f32>();
        let w = f32_words_of(&c);
        crate::scalar::words::assert_same_words(&w, &TABLE_4_1_F32_WORDS);
        assert_eq!(TABLE_4_1_F32, c);
        assert_eq!(f32_words_of(&TABLE_4_1_F32), w);
    }

    /// Prints the stored words of `table_4_1::<f32>()` (`--ignored
    /// --nocapture`).
    #[test]
    #[ignore]
    fn stored_f32_law_words_print() {
        let w = f32_words_of(&table_4_1::<f32>());
        crate::scalar::words::print_words(
            &std::format!("const TABLE_4_1_F32_WORDS: [u32; {}] = [", w.len()),
            &w,
        );
        println!("];");
    }

    /// `kani_step_bounded_i16f16` takes the active law from the joint's
    /// stored configuration: it is this module's `table_4_1::<I16F16>()`.
    #[test]
    fn table_4_1_is_the_joints_active_law() {
        assert_eq!(
            crate::joint::TABLE_4_1_I16F16.mode().active(),
            &table_4_1::<I16F16>()
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sat_reciprocal_i16f16() {
        let eps = I16F16::from_f64(0.1);
        let inv = Coef::new(1.0 / eps.to_f64());
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let x = I16F16::from_bits(c as i32);
            sat_reciprocal(x, eps, &inv).and(sat_reciprocal_i16f16(x, eps, &inv))
        });
        println!(
            "PROOF kernel=sat_with_reciprocal(eps_r) backend=I16F16 domain=all bound=1 LSB, odd, in [-1,1] max_err={:.3} LSB at={} checked={} engine=exhaustive",
            r.max_error, r.argmax as i32, r.checked
        );
        assert_eq!(
            r.failures,
            0,
            "first failure at bits {:?}",
            r.first_failure.map(|c| c as i32)
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_friction_i16f16() {
        let cfg = FrictionConfig::<I16F16>::new(0.01);
        let act = table_4_1::<I16F16>();
        // The initial estimate and the box's upper corner (largest terms).
        for theta in [act.initial_state().friction, act.upper_bounds()] {
            // Speeds in ±128 rad/s: bits −2²³ … 2²³ − 1.
            let r = exhaustive_u32(0, (1 << 24) - 1, |c| {
                let qd = I16F16::from_bits(c as i32 - (1 << 23));
                friction_sign_and_bound(&cfg, &theta, qd)
                    .and(friction_sign_and_bound_i16f16(&cfg, &theta, qd))
            });
            println!(
                "PROOF kernel=friction-nominal(eq. 4.17) backend=I16F16 domain=|qd|<128 rad/s bound=sign and magnitude checked={} engine=exhaustive",
                r.checked
            );
            assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
        }
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_law_monotone_in_position_i16f16() {
        let cfg = table_4_1::<I16F16>();
        let st = cfg.initial_state();
        for (qd, tau) in [(0.0, 0.0), (3.0, 2.0), (-40.0, -10.0)] {
            let base = ControlInput {
                desired_position: I16F16::from_f64(1.0),
                desired_velocity: I16F16::from_f64(qd),
                motor_velocity: I16F16::from_f64(qd + 0.01),
                joint_torque: I16F16::from_f64(tau),
                ..Default::default()
            };
            // 2²⁴ consecutive motor positions centred on the reference
            // (±128 rad): every LSB step of the position.
            let x_at = |c: u32| ControlInput {
                motor_position: I16F16::from_bits(
                    c as i32 - (1 << 23) + base.desired_position.to_bits(),
                ),
                ..base
            };
            let r = exhaustive_u32_chained(
                0,
                (1 << 24) - 1,
                |c| cfg.law(&st, &x_at(c)).law,
                |_, cur, prev| match prev {
                    Some(p) => law_monotone_in_position(*p, *cur),
                    None => Verdict::logical(true),
                },
            );
            println!(
                "PROOF kernel=robust-adaptive-law(eq. 4.19) backend=I16F16 domain=2^24 motor positions (qd={qd}) bound=non-increasing checked={} engine=exhaustive",
                r.checked
            );
            assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
        }
    }

    fn input<S: Scalar>(v: [f64; 6]) -> ControlInput<S> {
        let u = S::UNITS;
        ControlInput {
            desired_position: S::from_f64(v[0] * u.angle),
            desired_velocity: S::from_f64(v[1] * u.speed),
            desired_acceleration: S::from_f64(v[2] * u.speed),
            motor_position: S::from_f64(v[3] * u.angle),
            motor_velocity: S::from_f64(v[4] * u.speed),
            joint_torque: S::from_f64(v[5] * u.link_torque),
            ..Default::default()
        }
    }

    fn mode<S: Scalar>() -> ModeConfig<S> {
        let p = ModeParams::try_new(ModeSettings {
            active: RobustAdaptiveParams::table_4_1().unwrap(),
            passive: PassiveParams::table_4_1(2000.0).unwrap(),
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: 10.0,
            bias_time_constant: 0.1,
            collision: Some(
                CollisionParams::try_new(CollisionSettings {
                    threshold: 4.0,
                    release_threshold: 3.0,
                    debounce: 2,
                    release: 1,
                    reaction: CollisionReaction::Passive,
                })
                .unwrap(),
            ),
        })
        .unwrap();
        ModeConfig::new(&p)
    }

    /// The division-free value check of `kani_sat_reciprocal_f32` agrees
    /// with the quotient form of `sat_reciprocal` on the real results and
    /// on results moved a few units either side of the allowance (ties
    /// within 1e-9 of it relative apart), and it can fail.
    #[test]
    fn sat_reciprocal_product_form_agrees() {
        let (eps, inv) = eps_r_f32_prepared();
        let mut next = super::super::engine::xorshift64(0x2545_f491_4f6c_dd1du64);
        let (mut pass, mut fail, mut ties) = (0, 0, 0);
        for i in 0..300_000 {
            let r = next();
            let x = match i % 3 {
                0 => f32::from_bits(r as u32),
                // Inside and just around the layer.
                _ => ((r >> 40) as f32 / (1u64 << 24) as f32 * 2.2 - 1.1) * eps,
            };
            let real = sat_with_reciprocal(x, eps, &inv);
            let allowed = (1.0 + 1.0 / 64.0) * f32::EPSILON as f64;
            let exact = if x.is_nan() {
                0.0
            } else if (x as f64).abs() > eps as f64 {
                (x as f64).signum()
            } else {
                x as f64 / eps as f64
            };
            let s = match (r >> 62) & 1 {
                0 => real,
                // A candidate near the edge of the allowance.
                _ => {
                    let side = if r & 1 == 0 { allowed } else { -allowed };
                    let mut s = (exact + side) as f32;
                    for _ in 0..((r >> 56) & 3) {
                        s = if r & 2 == 0 {
                            super::super::sat_sgn::next_down(s)
                        } else {
                            super::super::kernels_f32::next_up(s)
                        };
                    }
                    s
                }
            };
            let quotient = sat_reciprocal_value(x, eps, s).holds;
            // Away from ties: the forms round differently (by 2⁻⁵³
            // relative; the quotient form's `x/ε` can vanish in the
            // difference), so a result within 1e-9 of the allowance may be
            // decided either way. Most ties are exact: `±1 ± allowance`.
            let margin = (s as f64 - exact).abs() - allowed;
            if margin.abs() <= 1e-9 * allowed {
                ties += 1;
                continue;
            }
            assert_eq!(
                sat_reciprocal_value_f32_products(x, eps, s),
                quotient,
                "x {x:e} s {s:e}"
            );
            if quotient {
                pass += 1;
            } else {
                fail += 1;
            }
        }
        assert!(
            pass > 10_000 && fail > 10_000 && ties < 6_000,
            "{pass} pass, {fail} fail, {ties} ties"
        );
        // And the whole product-form check holds for the library's sat.
        for x in [
            0.0f32,
            1e-30,
            0.05,
            0.1,
            0.10000001,
            -0.1,
            3.0,
            f32::NAN,
            f32::INFINITY,
        ] {
            assert!(sat_reciprocal_f32_products(x, eps, &inv), "{x:e}");
        }
    }

    /// The friction bits check rejects a wrong sign and a value one LSB
    /// beyond its bound.
    #[test]
    fn friction_bits_check_can_fail() {
        // θ = (1, 2, 3, 0) LSB at q̇ = 2¹⁶ (1 rad/s): bound T₀|Q|/2¹⁶ + T₁ + T₂ + 4
        // + 4T₀|Q|/2³² = 1 + 5 + 4 + 2⁻¹⁴ → 10 LSB.
        let t = [1, 2, 3, 0];
        assert!(friction_bits_match(10, 1 << 16, t).holds);
        assert!(!friction_bits_match(11, 1 << 16, t).holds);
        assert!(!friction_bits_match(-1, 1 << 16, t).holds);
        assert!(!friction_bits_match(1, 0, t).holds);
        assert!(friction_bits_match(-10, -(1 << 16), t).holds);
    }

    /// The integer check rejects a result one LSB beyond its bound and a
    /// wrong saturation value.
    #[test]
    fn sat_reciprocal_bits_check_can_fail() {
        let e = 6554; // 0.1 in bits
                      // x = e/2: exact 32768 LSB.
        assert!(sat_reciprocal_bits_match(32768, e / 2, e).holds);
        assert!(sat_reciprocal_bits_match(32769, e / 2, e).holds);
        assert!(!sat_reciprocal_bits_match(32770, e / 2, e).holds);
        assert!(sat_reciprocal_bits_match(-65536, -e - 1, e).holds);
        assert!(!sat_reciprocal_bits_match(-65535, -e - 1, e).holds);
        assert!(!sat_reciprocal_bits_match(65537, e, e).holds);
    }

    proptest! {
        #[test]
        fn sat_reciprocal_random(x in -1.0f64..1.0, eps in 1e-4f64..0.5) {
            let inv = Coef::new(1.0 / eps);
            prop_assert!(sat_reciprocal(x, eps, &inv).holds);
            let (xf, ef) = (x as f32, eps as f32);
            prop_assert!(sat_reciprocal(xf, ef, &Coef::new(1.0 / ef as f64)).holds);
            let (xi, ei) = (I16F16::from_f64(x), I16F16::from_f64(eps.max(1e-4)));
            prop_assert!(sat_reciprocal(xi, ei, &Coef::new(1.0 / ei.to_f64())).holds);
            prop_assert!(sat_reciprocal_i16f16(xi, ei, &Coef::new(1.0 / ei.to_f64())).holds);
        }

        #[test]
        fn friction_integer_check_agrees(qd in -500.0f64..500.0) {
            let a = table_4_1::<I16F16>();
            let c = FrictionConfig::<I16F16>::new(0.01);
            for theta in [a.initial_state().friction, a.upper_bounds()] {
                let q = I16F16::from_f64(qd);
                prop_assert_eq!(
                    friction_sign_and_bound_i16f16(&c, &theta, q).holds,
                    friction_sign_and_bound(&c, &theta, q).holds
                );
            }
        }

        #[test]
        fn friction_sign_random(qd in -500.0f64..500.0) {
            let a = table_4_1::<f64>();
            let c = FrictionConfig::<f64>::new(0.01);
            prop_assert!(friction_sign_and_bound(&c, &a.upper_bounds(), qd).holds);
            let a = table_4_1::<f32>();
            let c = FrictionConfig::<f32>::new(0.01);
            prop_assert!(friction_sign_and_bound(&c, &a.upper_bounds(), qd as f32).holds);
            let a = table_4_1::<I16F16>();
            let c = FrictionConfig::<I16F16>::new(0.01);
            prop_assert!(friction_sign_and_bound(&c, &a.upper_bounds(), I16F16::from_f64(qd)).holds);
        }

        #[test]
        fn law_monotone_random(v in proptest::array::uniform6(-50.0f64..50.0), dq in 1e-4f64..1.0) {
            fn check<S: Scalar>(v: [f64; 6], dq: f64) -> bool {
                let cfg = table_4_1::<S>();
                let st = cfg.initial_state();
                let lo = input::<S>(v);
                let mut w = v;
                w[3] += dq;
                let hi = input::<S>(w);
                law_monotone_in_position(cfg.law(&st, &lo).law, cfg.law(&st, &hi).law).holds
            }
            prop_assert!(check::<f64>(v, dq));
            prop_assert!(check::<I16F16>(v, dq));
        }

        #[test]
        fn step_and_switch_random(seq in proptest::collection::vec(proptest::array::uniform6(-30.0f64..30.0), 1..60)) {
            fn run<S: Scalar>(seq: &[[f64; 6]]) -> bool {
                let cfg = table_4_1::<S>();
                let mut st = cfg.initial_state();
                let m = mode::<S>();
                let mut ms = m.initial_state();
                let mut ok = true;
                let mut prev = S::ZERO;
                for v in seq {
                    let mut w = *v;
                    w[5] /= 6.0; // interaction torques ±5 N·m cross both thresholds
                    let x = input::<S>(w);
                    ok &= step_bounded(&cfg, &mut st, &x).holds;
                    ok &= switch_bumpless(&m, &mut ms, &x, prev).holds;
                    prev = ms.last_torque();
                }
                ok
            }
            prop_assert!(run::<f64>(&seq));
            prop_assert!(run::<f32>(&seq));
            prop_assert!(run::<I16F16>(&seq));
        }
    }
}
