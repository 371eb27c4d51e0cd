//! Plausibility of the joint's readings (issue 38, D2): a motor counter
//! that moves farther in one tick than the motor's maximum speed allows is
//! a counter fault. It is flagged `invalid_input`, the command is 0 N·m,
//! the joint holds its last valid state (motor position, speed meter,
//! estimator, adapted law), and the next reading is measured from the
//! jumped counter, so the joint recovers on the next tick with the jump
//! left out of its position. Checked on `f32`, `f64` and `I16F16`.

use core::f64::consts::TAU;
use mrr_control::friction::FrictionParams;
use mrr_control::joint::{JointOutput, JointState, TABLE_4_1_MAX_MOTOR_SPEED};
use mrr_control::{JointConfig, JointParams, JointReadings, JointTarget, Scalar, I16F16};

fn params() -> JointParams {
    JointParams::table_4_1_at(0.004).unwrap()
}

/// The most counts one 4 ms tick may move at 1000 rad/s and 2000 counts
/// per revolution, computed here: `⌊1000·0.004·2000/(2π)⌋ + 1 =
/// ⌊1273.24⌋ + 1 = 1274` (one count of quantization above the speed).
const MAX_COUNTS: u32 = 1274;

#[test]
fn the_limit_is_the_motor_speed_in_counts_per_tick() {
    let p = params();
    assert_eq!(p.settings().max_motor_speed, TABLE_4_1_MAX_MOTOR_SPEED);
    let c = TABLE_4_1_MAX_MOTOR_SPEED * 0.004 * 2000.0 / TAU;
    assert!((c - 1273.24).abs() < 0.01 && MAX_COUNTS == c.floor() as u32 + 1);
}

/// The adapted state, the mode state's bias and last command, and the
/// motor position: what "holds" means, read through the public readers.
fn snapshot<S: Scalar>(st: &JointState<S>) -> ((FrictionParams, f64), f64, i64) {
    let a = st.active_state();
    (
        (a.friction_si(), a.integral_si()),
        st.mode_state().bias_si(),
        st.motor_position_counts(),
    )
}

/// A joint at rest for a few ticks, holding its start; returns the state
/// and the last output.
fn at_rest<S: Scalar>(cfg: &JointConfig<S>) -> (JointState<S>, JointOutput<S>) {
    let mut st = cfg.state_at(0, 0);
    let hold = JointTarget::from_si(0.0, 0.0, 0.0);
    let mut out = cfg.update(&mut st, &JointReadings::counts(0, 0), &hold);
    // A small motion first, so the adapted state is not its initial one.
    for k in 1..20u32 {
        out = cfg.update(&mut st, &JointReadings::counts(0, k), &hold);
        assert!(!out.invalid_input, "{out:?}");
    }
    (st, out)
}

fn whole_revolution_jump<S: Scalar>() {
    let cfg = JointConfig::<S>::new(&params());
    let hold = JointTarget::from_si(0.0, 0.0, 0.0);
    let (mut st, before) = at_rest(&cfg);
    let counter = 19u32;
    let held = snapshot(&st);
    assert_eq!(held.2, 19);
    // The jump: exactly 10⁹ counts (5000 output revolutions at
    // M·N = 2·10⁵, so the torsion cannot see it) in one tick.
    let jumped = counter.wrapping_add(1_000_000_000);
    let out = cfg.update(&mut st, &JointReadings::counts(0, jumped), &hold);
    assert!(out.invalid_input, "{} {out:?}", S::NAME);
    assert!(out.control.invalid_input && !out.torque_saturated());
    assert_eq!(out.motor_torque_si(), 0.0);
    assert_eq!(out.motor_velocity_si(), 0.0, "{}", S::NAME);
    // The position held: 19 counts, as before the jump.
    let q19 = 19.0 * TAU / 2000.0;
    assert!(
        (out.motor_position_si() - q19).abs() < 1e-4,
        "{} {out:?}",
        S::NAME
    );
    assert!((out.motor_position_si() - before.motor_position_si()).abs() < 1e-12);
    let after = snapshot(&st);
    assert_eq!(after.0, held.0, "{}: adapted state moved", S::NAME);
    assert_eq!(after.2, held.2);
    assert_eq!(st.last_command_si(), 0.0);
    // Recovery: the next reading is measured from the jumped counter. The
    // counter staying at its jumped value is a motor at rest: valid, the
    // position still 19 counts, the offset gone for good.
    for k in 0..50u32 {
        let out = cfg.update(
            &mut st,
            &JointReadings::counts(0, jumped.wrapping_add(k)),
            &hold,
        );
        assert!(!out.invalid_input, "{} tick {k} after: {out:?}", S::NAME);
        let want = (19.0 + k as f64) * TAU / 2000.0;
        assert!(
            (out.motor_position_si() - want).abs() < 1e-4,
            "{} {k}: {out:?}",
            S::NAME
        );
        assert!(
            out.motor_torque_si().abs() < 0.2,
            "{} {k}: {out:?}",
            S::NAME
        );
    }
    assert_eq!(st.motor_position_counts(), 19 + 49);
}

#[test]
fn a_whole_revolution_jump_is_flagged_held_and_recovered_f32() {
    whole_revolution_jump::<f32>();
}
#[test]
fn a_whole_revolution_jump_is_flagged_held_and_recovered_f64() {
    whole_revolution_jump::<f64>();
}
#[test]
fn a_whole_revolution_jump_is_flagged_held_and_recovered_i16f16() {
    whole_revolution_jump::<I16F16>();
}

/// The boundary: `MAX_COUNTS` in one tick (either way) is motion, one more
/// is a jump; a one-tick spike of one motor revolution costs two flagged
/// ticks (out and back) and leaves the position where it was.
fn boundary_and_spike<S: Scalar>() {
    let cfg = JointConfig::<S>::new(&params());
    let hold = JointTarget::from_si(0.0, 0.0, 0.0);
    for (step, flagged) in [
        (MAX_COUNTS as i32, false),
        (-(MAX_COUNTS as i32), false),
        (MAX_COUNTS as i32 + 1, true),
        (-(MAX_COUNTS as i32) - 1, true),
    ] {
        let (mut st, _) = at_rest(&cfg);
        let c = 19u32.wrapping_add(step as u32);
        // The link moved with the motor (no torsion): `c·L/(M·N)` counts.
        let link = ((19 + step as i64) * (1 << 17))
            .div_euclid(200_000)
            .rem_euclid(1 << 17);
        let out = cfg.update(&mut st, &JointReadings::counts(link as u32, c), &hold);
        assert_eq!(
            out.invalid_input,
            flagged,
            "{} step {step}: {out:?}",
            S::NAME
        );
        let want = if flagged { 19 } else { 19 + step as i64 };
        assert_eq!(st.motor_position_counts(), want, "{} step {step}", S::NAME);
        let m = cfg.measure(&mut st.clone(), &JointReadings::counts(link as u32, c));
        // `measure` from the state after: the counter did not move.
        assert!(!m.counter_jump);
    }
    let (mut st, _) = at_rest(&cfg);
    let spike = cfg.update(&mut st, &JointReadings::counts(0, 19 + 2000), &hold);
    let back = cfg.update(&mut st, &JointReadings::counts(0, 19), &hold);
    let next = cfg.update(&mut st, &JointReadings::counts(0, 19), &hold);
    assert!(spike.invalid_input && back.invalid_input && !next.invalid_input);
    assert_eq!(st.motor_position_counts(), 19);
}

#[test]
fn the_limit_and_a_spike_f32() {
    boundary_and_spike::<f32>();
}
#[test]
fn the_limit_and_a_spike_f64() {
    boundary_and_spike::<f64>();
}
#[test]
fn the_limit_and_a_spike_i16f16() {
    boundary_and_spike::<I16F16>();
}

/// `measure` flags the jump too, and its position holds.
#[test]
fn measure_reports_the_counter_jump() {
    let cfg = JointConfig::<f32>::new(&params());
    let mut st = cfg.state_at(0, 0);
    let m = cfg.measure(&mut st, &JointReadings::counts(0, 1_000_000_000));
    assert!(m.counter_jump && m.motor_position == 0.0 && m.motor_velocity == 0.0);
    let m = cfg.measure(&mut st, &JointReadings::counts(0, 1_000_000_005));
    assert!(!m.counter_jump);
    assert!((m.motor_position_si() - 5.0 * TAU / 2000.0).abs() < 1e-6);
}
