//! One tick of the whole joint ([`JointConfig::update`]: torque estimator
//! of ch. 3, eq. 3.8–3.10, then the mode manager of ch. 4 with the active
//! law eq. 4.19 and the passive law eq. 4.32), for the Table 4.1 joint
//! ([`JointParams::table_4_1`](crate::joint::JointParams::table_4_1)), written once and run by every engine.
//!
//! | property | I16F16 | f32 | f64 |
//! |---|---|---|---|
//! | `joint_step_bounded` — the step returns (no panic, no integer overflow), the command is within `±L` and is the state's last command, the integral within its limit, the friction estimates inside the projection box | Kani `kani_joint_step_products_i16f16` (kernels and products by contract, see below): VERIFIED in 480.8 s on `1e9a0ede65` (limit 5,400 s; the record is `proofs/KANI_RESULTS.md`); random | random | random |
//! | `mode_step_bounded` — the mode manager alone (the second half of the step), the same bounds | Kani `kani_joint_mode_step_i16f16` (`exp_neg_abs` and products by contract): VERIFIED in 891.9 s on `1e9a0ede65`; random | in `joint_step_bounded` | in `joint_step_bounded` |
//!
//! **The configuration is constant.** Both Kani harnesses take the
//! configuration from `joint::TABLE_4_1_I16F16`:
//! the value of `JointConfig::<I16F16>::new(&JointParams::table_4_1())`
//! stored as 789 `u32` words and read back by `const fn`s that only
//! reassemble bits (`src/joint/prepared.rs`, `src/scalar/words.rs`; test
//! and Kani builds only), so the compiler evaluates it and the solver
//! receives constants. `JointConfig::new` itself runs `f64` and `libm`
//! code (`turn_from_radians` of the kinematic-error phases reaches
//! `rem_pio2_large`) and slope searches with products
//! (`scalar::slope_within`), which the solver's front end did not reduce
//! to constants: from it the harnesses verified a symbolic configuration
//! and timed out. The result holds for the constructor's own
//! configuration because `prepared_is_the_constructors` (a unit test)
//! checks that the stored words are, word for word, those written from
//! `JointConfig::new`'s output, and that the two configurations are equal
//! (`PartialEq` over every field); it fails when a single stored bit is
//! changed. The mode harness uses the joint's manager (`JointConfig::mode`,
//! equal to `ModeConfig::new(&joint_mode_params())` by
//! `joint_mode_params_are_the_joints`).
//!
//! **The states and inputs.** The state of the whole-step harness is the
//! joint at rest at link count 0
//! and motor counter 0 (`JointConfig::state(0, 0)`), and the tick's
//! readings and target are symbolic: every link count (also the invalid
//! ones `≥ L`, which the estimator reduces and flags), every motor
//! counter, every motor torque (`None`: the previous command), and every
//! `I16F16` target. From that state a counter jump of any `i32` reaches
//! every estimator position `(turn, in_turn)` of the `M·N` motor counts
//! of an output revolution, and the speed meter (window 1) any count
//! difference, so the estimator half of the step is decided for every
//! state it can be in; the motor position reaches `±2³¹` counts, far
//! beyond `I16F16`'s saturation (`2³¹·2π/2000` rad). The mode manager
//! starts in its initial state (Active, initial estimates, no bias or
//! offset) and may switch on this tick; the mode harness gives it every
//! `I16F16` input (all eight of `ControlInput`). Later mode-manager states
//! are the random engine's (`joint_step_random`: sequences of up to 60
//! ticks on all three backends). No `kani::assume` restricts a reading,
//! a target or an input.
//!
//! The transcendental kernels of the step are replaced by their
//! contracts (`#[kani::stub]`, `-Z stubbing`): each stub returns *any*
//! value its contract allows, so a verified harness holds for the real
//! kernel too. The contracts, and what proves them for the real kernel:
//!
//! | kernel | contract | proven by |
//! |---|---|---|
//! | `kernels::i16f16::tan_bounded` (eq. 3.10 in the estimator) | the sign of the argument, 0 at 0 | `tan_bounded_is_within_one_lsb_at_every_input` (odd and non-decreasing at every input: every magnitude of its domain and beyond, where it clamps) |
//! | `kernels::i16f16::exp_neg_abs` (the Stribeck term `e^{−f_τ q̇²}`, eq. 4.17, and the wave generator's `e^{−c_w|τ_w|}`, eq. 2.29) | `[0, 1]` | `exhaustive_exp_neg_abs_i16f16` (≤ 1 LSB, in `[0, 1]`, even and non-increasing in `|x|` at all 2³² inputs) |
//! | `kernels::i16f16::cos_turn` (kinematic error, eq. 3.7) | `[−1, 1]` | `exhaustive_cos_turn_i16f16` (`|result| ≤ 1` at all 2³² turns) |
//!
//! Both harnesses replace, in addition, the fixed-point product
//! `mul_bits` by its contract (any value of the sign rule `sgn(ab)`,
//! `|ab|` below `|a|` when `|b| ≤ 1`, and 0 when a factor is 0), proven
//! for the real product by `joint_step_mul_contract_is_the_products`
//! (edge classes) and `joint_step_mul_contract_random` (random pairs): the
//! harnesses decide the composition (the estimator's integer arithmetic,
//! the coefficient products, the saturation and mode logic) on every value
//! the products can take. With the configuration a constant, the stub is
//! the contract throughout (the configuration is no longer built under
//! it).

use super::engine::Verdict;
use crate::control::{
    ControlInput, ModeConfig, ModeParams, ModeSettings, ModeState, PassiveParams,
};
use crate::joint::{JointConfig, JointReadings, JointState, JointTarget};
use crate::scalar::Scalar;

/// One tick from `st`: returns without panicking, `|τ_m| ≤ L` (the mode
/// manager's limit) and is the state's last command, the integral within
/// its limit and the friction estimates inside the projection box.
pub fn joint_step_bounded<S: Scalar>(
    cfg: &JointConfig<S>,
    st: &mut JointState<S>,
    readings: &JointReadings<S>,
    target: &JointTarget<S>,
) -> Verdict {
    let out = cfg.update(st, readings, target);
    let mode = cfg.mode();
    let lim = mode.torque_limit();
    let tau = out.motor_torque;
    let mut ok = !tau.is_nan() && tau.abs() <= lim && tau >= lim.neg();
    ok &= st.last_command() == tau;
    let act = mode.active();
    let a = st.mode_state().active_state();
    ok &= a.integral.abs() <= act.integral_limit();
    let (lo, hi) = (act.lower_bounds(), act.upper_bounds());
    for j in 0..4 {
        ok &= a.friction[j] >= lo[j] && a.friction[j] <= hi[j];
    }
    ok &=
        !out.joint_torque.is_nan() && !out.motor_position.is_nan() && !out.motor_velocity.is_nan();
    Verdict::logical(ok)
}

/// The mode manager's settings of [`JointParams::table_4_1`](crate::joint::JointParams::table_4_1):
/// the Table 4.1 active law and manager settings with the default passive
/// law (no collision detector).
pub fn joint_mode_params() -> ModeParams {
    // The Table 4.1 constants validate (joint and mode tests).
    ModeParams::try_new(ModeSettings {
        passive: PassiveParams::table_4_1_default().expect("Table 4.1 passive law"),
        ..ModeSettings::table_4_1(1.0).expect("Table 4.1 manager")
    })
    .expect("Table 4.1 manager settings")
}

/// One tick of the mode manager on `x`: `|τ_m| ≤ L`, the command is the
/// state's last torque, the integral within its limit and the friction
/// estimates inside the projection box.
pub fn mode_step_bounded<S: Scalar>(
    cfg: &ModeConfig<S>,
    st: &mut ModeState<S>,
    x: &ControlInput<S>,
) -> Verdict {
    let o = cfg.update(st, x);
    let lim = cfg.torque_limit();
    let mut ok = !o.torque.is_nan() && o.torque <= lim && o.torque >= lim.neg();
    ok &= st.last_torque() == o.torque;
    let act = cfg.active();
    let a = st.active_state();
    ok &= a.integral.abs() <= act.integral_limit();
    let (lo, hi) = (act.lower_bounds(), act.upper_bounds());
    for j in 0..4 {
        ok &= a.friction[j] >= lo[j] && a.friction[j] <= hi[j];
    }
    Verdict::logical(ok)
}

#[cfg(kani)]
pub(crate) mod kani_entries {
    use super::*;
    use crate::scalar::I16F16;

    /// Postcondition of the stubbed `tan_bounded`: the sign of the
    /// argument.
    fn tan_bounded_as_contract(x: I16F16) -> I16F16 {
        let (x, y) = (x.to_bits(), kani::any::<i32>());
        // Postcondition of the stubbed function (odd and non-decreasing at
        // every input: tan_bounded_is_within_one_lsb_at_every_input).
        kani::assume(if x > 0 {
            y >= 0
        } else if x < 0 {
            y <= 0
        } else {
            y == 0
        });
        I16F16::from_bits(y)
    }

    /// Postcondition of the stubbed `exp_neg_abs`: `[0, 1]`.
    pub(crate) fn exp_neg_abs_as_contract(_x: I16F16) -> I16F16 {
        let y = kani::any::<i32>();
        // Postcondition of the stubbed function
        // (exhaustive_exp_neg_abs_i16f16).
        kani::assume((0..=1 << 16).contains(&y));
        I16F16::from_bits(y)
    }

    /// Postcondition of the stubbed `cos_turn`: `[−1, 1]`.
    fn cos_turn_as_contract(_turn: u32) -> I16F16 {
        let y = kani::any::<i32>();
        // Postcondition of the stubbed function (exhaustive_cos_turn_i16f16).
        kani::assume((-(1 << 16)..=1 << 16).contains(&y));
        I16F16::from_bits(y)
    }

    /// Postcondition of the stubbed `mul_bits` (I16F16 product, bits):
    /// the sign of `a·b` (0 when a factor is 0), and no larger in
    /// magnitude than `|a|` when `|b| ≤ 1` (and than `|b|` when
    /// `|a| ≤ 1`).
    pub(crate) fn mul_bits_as_contract(a: i32, b: i32) -> i32 {
        let y = kani::any::<i32>();
        let (ua, ub, uy) = (a.unsigned_abs(), b.unsigned_abs(), y.unsigned_abs());
        // Postcondition of the stubbed function
        // (joint_step_mul_contract_is_the_products, _random).
        kani::assume(if a == 0 || b == 0 {
            y == 0
        } else if (a > 0) == (b > 0) {
            y >= 0
        } else {
            y <= 0
        });
        kani::assume(ub > 1 << 16 || uy <= ua);
        kani::assume(ua > 1 << 16 || uy <= ub);
        y
    }

    /// `JointConfig::<I16F16>::new(&JointParams::table_4_1())` as stored
    /// words: a compile-time constant (`joint::prepared`; equal to the
    /// constructor's value by `prepared_is_the_constructors`).
    pub(crate) fn joint() -> JointConfig<I16F16> {
        crate::joint::TABLE_4_1_I16F16
    }

    fn any_target() -> JointTarget<I16F16> {
        JointTarget {
            turns: kani::any(),
            position: I16F16::from_bits(kani::any()),
            velocity: I16F16::from_bits(kani::any()),
            acceleration: I16F16::from_bits(kani::any()),
            joint_torque: I16F16::from_bits(kani::any()),
            expected_joint_torque: I16F16::from_bits(kani::any()),
        }
    }

    fn any_readings() -> JointReadings<I16F16> {
        JointReadings {
            link_count: kani::any(),
            motor_counter: kani::any(),
            motor_torque: if kani::any() {
                Some(I16F16::from_bits(kani::any()))
            } else {
                None
            },
        }
    }

    /// One joint tick from rest, every reading and target (kernels and
    /// `I16F16` products by contract).
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::tan_bounded, tan_bounded_as_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::exp_neg_abs, exp_neg_abs_as_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::cos_turn, cos_turn_as_contract)]
    #[kani::stub(crate::scalar::fixed::mul_bits, mul_bits_as_contract)]
    fn kani_joint_step_products_i16f16() {
        let cfg = joint();
        let mut st = cfg.state_at(0, 0);
        assert!(joint_step_bounded(&cfg, &mut st, &any_readings(), &any_target()).holds);
    }

    /// The mode manager of the Table 4.1 joint (the second half of
    /// `JointConfig::update`) on every input: one tick from its initial
    /// state (kernels and `I16F16` products by contract).
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::exp_neg_abs, exp_neg_abs_as_contract)]
    #[kani::stub(crate::scalar::fixed::mul_bits, mul_bits_as_contract)]
    fn kani_joint_mode_step_i16f16() {
        let cfg = *joint().mode();
        let mut st = cfg.initial_state();
        let any = || I16F16::from_bits(kani::any());
        let x = ControlInput {
            desired_position: any(),
            desired_velocity: any(),
            desired_acceleration: any(),
            motor_position: any(),
            motor_velocity: any(),
            joint_torque: any(),
            desired_joint_torque: any(),
            expected_joint_torque: any(),
        };
        assert!(mode_step_bounded(&cfg, &mut st, &x).holds);
    }
}

/// The `I16F16` product by its 64-bit definition: `a·b·2⁻¹⁶` rounded to
/// nearest (ties up), saturated; equal to `mul_bits` (tests here and in
/// `src/scalar/fixed.rs`): the reference the product's contract is
/// tested against.
pub fn mul_bits_formula(a: i32, b: i32) -> i32 {
    let p = ((a as i64) * (b as i64) + (1 << 15)) >> 16;
    p.clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

/// The contract of the `I16F16` product `y = mul_bits(a, b)` used by
/// `kani_joint_step_products_i16f16`: the sign rule (0 when a factor is
/// 0), and `|y| ≤ |a|` when `|b| ≤ 1`, `|y| ≤ |b|` when `|a| ≤ 1`.
pub fn mul_contract(a: i32, b: i32, y: i32) -> bool {
    let (ua, ub, uy) = (a.unsigned_abs(), b.unsigned_abs(), y.unsigned_abs());
    let sign = if a == 0 || b == 0 {
        y == 0
    } else if (a > 0) == (b > 0) {
        y >= 0
    } else {
        y <= 0
    };
    sign && (ub > 1 << 16 || uy <= ua) && (ua > 1 << 16 || uy <= ub)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::JointParams;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    fn run<S: Scalar>(seq: &[(u32, i32, Option<f64>, [f64; 5])]) -> bool {
        let cfg = JointConfig::<S>::new(&JointParams::table_4_1().unwrap());
        let mut st = cfg.state_at(0, 0);
        let mut counter = 0u32;
        let u = S::UNITS;
        seq.iter().all(|&(link, step, tau, t)| {
            counter = counter.wrapping_add(step as u32);
            let r = JointReadings {
                link_count: link,
                motor_counter: counter,
                motor_torque: tau.map(|v| S::from_f64(v * u.motor_torque)),
            };
            let target = JointTarget {
                turns: 0,
                position: S::from_f64(t[0] * u.angle),
                velocity: S::from_f64(t[1] * u.speed),
                acceleration: S::from_f64(t[2] * u.speed),
                joint_torque: S::from_f64(t[3] * u.link_torque),
                expected_joint_torque: S::from_f64(t[4] * u.link_torque),
            };
            joint_step_bounded(&cfg, &mut st, &r, &target).holds
        })
    }

    /// The check fails on a state whose command is beyond the limit: a
    /// limit of 0 would reject any non-zero command, so a tick with a
    /// non-zero command shows the comparison is live.
    #[test]
    fn joint_step_check_sees_a_nonzero_command() {
        let cfg = JointConfig::<f64>::new(&JointParams::table_4_1().unwrap());
        let mut st = cfg.state_at(0, 0);
        let r = JointReadings::counts(0, 50);
        let out = cfg.update(&mut st, &r, &JointTarget::from_si(0.5, 0.0, 0.0));
        assert!(out.motor_torque != 0.0);
        assert!(out.motor_torque.abs() <= cfg.mode().torque_limit());
    }

    /// The Kani harness's mode manager is the joint's (the joint also
    /// gives it its output revolution, the hold point's step between turn
    /// frames, which a manager run in frame 0 never reads).
    #[test]
    fn joint_mode_params_are_the_joints() {
        let joint = JointParams::table_4_1().unwrap();
        assert_eq!(joint.settings().mode, super::joint_mode_params());
        let a = JointConfig::<I16F16>::new(&joint);
        let b = crate::control::ModeConfig::<I16F16>::new(&super::joint_mode_params());
        assert_eq!(
            a.mode(),
            &b.with_output_revolution(a.mode().output_revolution())
        );
    }

    proptest! {
        #[test]
        fn joint_mode_step_random(v in proptest::array::uniform8(-2.0e4f64..2.0e4)) {
            use crate::control::{ControlInput, ModeConfig};
            let cfg = ModeConfig::<I16F16>::new(&super::joint_mode_params());
            let mut st = cfg.initial_state();
            let q = I16F16::from_f64;
            let x = ControlInput {
                desired_position: q(v[0]),
                desired_velocity: q(v[1]),
                desired_acceleration: q(v[2]),
                motor_position: q(v[3]),
                motor_velocity: q(v[4]),
                joint_torque: q(v[5]),
                desired_joint_torque: q(v[6]),
                expected_joint_torque: q(v[7]),
            };
            prop_assert!(super::mode_step_bounded(&cfg, &mut st, &x).holds);
        }

        #[test]
        fn joint_step_mul_contract_random(a: i32, b: i32, small in -(1i32 << 16)..=1 << 16) {
            use crate::scalar::fixed::mul_bits;
            prop_assert!(super::mul_contract(a, b, mul_bits(a, b)));
            prop_assert_eq!(super::mul_bits_formula(a, b), mul_bits(a, b));
            prop_assert_eq!(super::mul_bits_formula(a, small), mul_bits(a, small));
            prop_assert!(super::mul_contract(a, small, mul_bits(a, small)));
            prop_assert!(super::mul_contract(small, b, mul_bits(small, b)));
        }

        #[test]
        fn joint_step_random(
            seq in proptest::collection::vec(
                (
                    0u32..(1 << 17) + 100,
                    -3000i32..3000,
                    proptest::option::of(-20.0f64..20.0),
                    proptest::array::uniform5(-40.0f64..40.0),
                ),
                1..60,
            )
        ) {
            prop_assert!(run::<f64>(&seq));
            prop_assert!(run::<f32>(&seq));
            prop_assert!(run::<I16F16>(&seq));
        }
    }

    /// The stubbed product's contract holds for the real `mul_bits`.
    #[test]
    fn joint_step_mul_contract_is_the_products() {
        use crate::scalar::fixed::mul_bits;
        let mut w = vec![
            0,
            1,
            -1,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            1 << 16,
            -(1 << 16),
        ];
        for k in 0..31 {
            let p = 1i32 << k;
            w.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
        }
        for &a in &w {
            for &b in &w {
                assert!(super::mul_contract(a, b, mul_bits(a, b)), "{a} {b}");
                assert_eq!(super::mul_bits_formula(a, b), mul_bits(a, b), "{a} {b}");
            }
        }
    }
}
