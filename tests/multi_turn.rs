//! A joint that turns in one direction for 10⁴ output revolutions keeps its
//! control on every backend (issue 38, D1).
//!
//! The closed loop: the 4 ms preset joint ([`JointParams::table_4_1_at`],
//! its estimator without the kinematic-error model) driving a rigid plant
//! written here (rotor plus reflected link inertia, Coulomb and viscous
//! friction at the motor), whose encoders are read as the firmware reads
//! them: a wrapping 32-bit motor counter and a link count in `[0, L)`. The
//! target is a link angle ramped up to a constant speed, given in SI
//! through [`JointTarget::from_si`].
//!
//! Criterion, written before the run: over the last output revolution of
//! the run (after 10⁴), the largest link-side tracking error
//! `|q_l − q_d|` (plant angle, in `f64`) is at most that of the first
//! revolution at constant speed plus two motor counts seen at the link,
//! `2·2π/(M·N) = 6.3e-5` rad; the first revolution's error is itself
//! below 0.05 rad (the loop tracks at all); and no tick is flagged
//! `invalid_input`.

use core::f64::consts::TAU;
use mrr_control::estimation::torque::{TorqueEstimatorParams, TorqueEstimatorSettings};
use mrr_control::joint::JointSettings;
use mrr_control::{JointConfig, JointParams, JointReadings, JointTarget, Scalar, I16F16};

const T: f64 = 0.004;
/// Link speed at the plateau, rad/s (300 rad/s at the motor).
const SPEED: f64 = 3.0;
/// Seconds of the speed ramp.
const RAMP: f64 = 2.0;
/// Rotor inertia (Table 4.1) plus an assumed 0.05 kg·m² link through
/// `N² = 10⁴`, kg·m² at the motor.
const INERTIA: f64 = 1.14e-5 + 0.05 / 1e4;
/// Friction at the motor: Coulomb N·m and viscous N·m·s/rad.
const COULOMB: f64 = 0.005;
const VISCOUS: f64 = 5e-6;

fn params() -> JointParams {
    let p = JointParams::table_4_1_at(T).unwrap();
    let s = p.settings();
    // The plant is rigid and has no kinematic error: the estimator without
    // its model, so that the torque it reads is the plant's (zero torsion).
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        kinematic_error: None,
        ..s.estimator.settings()
    })
    .unwrap();
    JointParams::try_new(JointSettings { estimator, ..s }).unwrap()
}

/// The desired link angle, speed and acceleration at `t`: a cosine ramp
/// to [`SPEED`] over [`RAMP`] seconds, then constant speed.
fn reference(t: f64) -> (f64, f64, f64) {
    if t < RAMP {
        let w = core::f64::consts::PI / RAMP;
        let v = 0.5 * SPEED * (1.0 - (w * t).cos());
        let a = 0.5 * SPEED * w * (w * t).sin();
        let q = 0.5 * SPEED * (t - (w * t).sin() / w);
        (q, v, a)
    } else {
        (0.5 * SPEED * RAMP + SPEED * (t - RAMP), SPEED, 0.0)
    }
}

/// What one run saw: the largest link error over the first and over the
/// last revolution at constant speed, rad, and the flagged ticks.
#[derive(Debug)]
struct Run {
    first_turn: f64,
    last_turn: f64,
    flagged: u64,
    turns: f64,
}

/// Run the closed loop until the reference has made `revolutions` output
/// revolutions.
fn run<S: Scalar>(revolutions: f64) -> Run {
    let p = params();
    let cfg = JointConfig::<S>::new(&p);
    let est = p.settings().estimator;
    let (l, m) = (
        est.link_counts_per_rev() as f64,
        est.motor_counts_per_rev() as f64,
    );
    let n = p.ratio();
    let mut st = cfg.state(0, 0);
    // Plant state at the motor: angle and speed.
    let (mut q, mut qd) = (0.0f64, 0.0f64);
    let period = TAU / SPEED;
    let end = RAMP + (revolutions * TAU - 0.5 * SPEED * RAMP) / SPEED;
    let ticks = (end / T).ceil() as u64;
    let first = (RAMP, RAMP + period);
    let last = (ticks as f64 * T - period, ticks as f64 * T);
    let (mut first_turn, mut last_turn, mut flagged) = (0.0f64, 0.0f64, 0u64);
    for k in 0..ticks {
        let t = k as f64 * T;
        let motor_count = (q * m / TAU).floor() as i64;
        let link_count = ((q / n / TAU * l).floor() as i64).rem_euclid(l as i64) as u32;
        let readings = JointReadings::counts(link_count, motor_count as u32);
        let (qr, vr, ar) = reference(t);
        let out = cfg.update(&mut st, &readings, &JointTarget::from_si(qr, vr, ar));
        flagged += out.invalid_input as u64;
        let err = (q / n - qr).abs();
        if (first.0..first.1).contains(&t) {
            first_turn = first_turn.max(err);
        }
        if (last.0..=last.1).contains(&t) {
            last_turn = last_turn.max(err);
        }
        // Zero-order hold over the tick, eight semi-implicit Euler steps.
        let tau = out.motor_torque_si();
        let h = T / 8.0;
        for _ in 0..8 {
            let friction = COULOMB * qd.signum() + VISCOUS * qd;
            qd += h * (tau - friction) / INERTIA;
            q += h * qd;
        }
    }
    Run {
        first_turn,
        last_turn,
        flagged,
        turns: q / n / TAU,
    }
}

fn check<S: Scalar>(revolutions: f64) {
    let r = run::<S>(revolutions);
    let p = params();
    let count_at_link = TAU / (p.settings().estimator.motor_counts_per_rev() as f64 * p.ratio());
    eprintln!("{} {revolutions} revolutions: {r:?}", S::NAME);
    assert!(r.turns > revolutions - 1.0, "{} {r:?}", S::NAME);
    assert_eq!(r.flagged, 0, "{} flagged ticks: {r:?}", S::NAME);
    assert!(
        r.first_turn < 0.05,
        "{} does not track at all: {r:?}",
        S::NAME
    );
    assert!(
        r.last_turn <= r.first_turn + 2.0 * count_at_link,
        "{} lost its tracking after {revolutions} revolutions: {r:?}",
        S::NAME
    );
}

#[test]
fn i16f16_tracks_after_ten_thousand_output_revolutions() {
    check::<I16F16>(1e4);
}

#[test]
fn f32_tracks_after_ten_thousand_output_revolutions() {
    check::<f32>(1e4);
}

#[test]
fn f64_tracks_after_ten_thousand_output_revolutions() {
    check::<f64>(1e4);
}

/// The case on `I16F16`: a motor 34 000 rad out (link at 340 rad,
/// 54 output revolutions). Given in SI the target carries its whole
/// turns, and the measured position is the motor's in the target's frame,
/// exact to the count; a target without turns leaves the range the
/// backend's angle carries and is flagged, never read as 0 error.
#[test]
fn i16f16_beyond_its_angle_range_is_carried_or_flagged() {
    let p = params();
    let cfg = JointConfig::<I16F16>::new(&p);
    let m = p.settings().estimator.motor_counts_per_rev() as f64;
    let n = p.ratio();
    let link = 340.0;
    let counts = (link * n / TAU * m).round() as i64;
    let link_count = ((link / TAU).fract() * 131072.0).floor() as u32;
    let mut st = cfg.state_at(counts, counts as u32);
    let out = cfg.update(
        &mut st,
        &JointReadings::counts(link_count, counts as u32),
        &JointTarget::from_si(link, 0.0, 0.0),
    );
    assert!(!out.invalid_input, "{out:?}");
    // The motor relative to 54 whole output turns, computed here in f64.
    let turns = (link / TAU).round();
    let want = (counts as f64 - turns * m * n) * TAU / m;
    assert!(
        (out.motor_position_si() - want).abs() < 1e-4,
        "{out:?} vs {want}"
    );
    // The same target without its turns: 34 000 rad is past the 16 384 rad
    // the frame allows on I16F16.
    let mut st = cfg.state_at(counts, counts as u32);
    let flat = JointTarget::<I16F16> {
        turns: 0,
        ..JointTarget::from_si(link, 0.0, 0.0)
    };
    let flat = JointTarget {
        position: I16F16::from_num(link),
        ..flat
    };
    let out = cfg.update(
        &mut st,
        &JointReadings::counts(link_count, counts as u32),
        &flat,
    );
    assert!(
        out.invalid_input && out.motor_torque == I16F16::ZERO,
        "{out:?}"
    );
    assert!(out.control.invalid_input);
}

/// On `f32` the frame ends where the angle no longer resolves half a count:
/// 2²² counts from the target's whole turns (13 176 rad at M = 2000). A
/// target without turns is flagged past it; the same angle with its turns
/// is not.
#[test]
fn f32_frame_ends_at_half_count_resolution_and_is_flagged() {
    let p = params();
    let cfg = JointConfig::<f32>::new(&p);
    let m = p.settings().estimator.motor_counts_per_rev() as f64;
    let n = p.ratio();
    assert_eq!(JointConfig::<f32>::frame_limit_counts(TAU / m), 1 << 22);
    // f32's spacing at 2²² counts' angle is at most half a count: checked
    // here from the float itself.
    let at = ((1u64 << 22) as f64 * TAU / m) as f32;
    assert!(((at.next_up() - at) as f64) <= 0.5 * TAU / m);
    for (counts, flagged) in [((1i64 << 22) - 1000, false), ((1 << 22) + 1000, true)] {
        let link = counts as f64 * TAU / m / n;
        let mut st = cfg.state_at(counts, 0);
        let flat = JointTarget {
            turns: 0,
            position: link as f32,
            ..JointTarget::default()
        };
        let link_count = ((link / TAU).rem_euclid(1.0) * 131072.0).floor() as u32;
        let out = cfg.update(&mut st, &JointReadings::counts(link_count, 0), &flat);
        assert_eq!(out.invalid_input, flagged, "{counts}: {out:?}");
        let mut st = cfg.state_at(counts, 0);
        let split = JointTarget::<f32>::from_si(link, 0.0, 0.0);
        let out = cfg.update(&mut st, &JointReadings::counts(link_count, 0), &split);
        assert!(!out.invalid_input, "{counts}: {out:?}");
    }
}

/// `from_si` splits an SI angle into whole output turns and the rest in
/// `[−π, π]`, on the nearest integer.
#[test]
fn from_si_splits_whole_turns() {
    for (angle, turns) in [
        (0.0, 0),
        (3.0, 0),
        (3.2, 1),
        (-3.2, -1),
        (62_832.0, 10_000),
        (-62_832.0, -10_000),
        (1e4 * TAU + 0.25, 10_000),
    ] {
        let t = JointTarget::<f64>::from_si(angle, 0.0, 0.0);
        assert_eq!(t.turns, turns, "{angle}");
        assert!(t.position.abs() <= core::f64::consts::PI, "{angle}: {t:?}");
        assert!(
            (t.turns as f64 * TAU + t.position - angle).abs() < 1e-9,
            "{angle}"
        );
    }
    // NaN stays a NaN on floats (flagged by the step), turns 0.
    let t = JointTarget::<f32>::from_si(f64::NAN, 0.0, 0.0);
    assert!(t.turns == 0 && t.position.is_nan());
}

/// On `I16F16` the frame is also capped at `2³¹ − 1` counts, where the
/// fixed-point count product ends: with a high-resolution motor encoder
/// (2²¹ counts per revolution; with a 4096-count link encoder, within
/// the estimator's `L·M·N` rule) half the angle range, 16 384 rad, would
/// be 5.5·10⁹ counts. A motor 2³¹ + 10⁶ counts (6 437 rad) from a target's
/// whole turns is flagged, not read as the angle of 2³¹ counts; 10⁶
/// counts inside the cap it is measured to the count.
#[test]
fn i16f16_frame_is_capped_at_32_bit_counts() {
    let p = params();
    let s = p.settings();
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        motor_counts_per_rev: 1 << 21,
        link_counts_per_rev: 4096,
        ..s.estimator.settings()
    })
    .unwrap();
    let p = JointParams::try_new(JointSettings { estimator, ..s }).unwrap();
    let cfg = JointConfig::<I16F16>::new(&p);
    let m = (1u64 << 21) as f64;
    let n = p.ratio();
    assert_eq!(
        JointConfig::<I16F16>::frame_limit_counts(TAU / m),
        i32::MAX as u64
    );
    for (counts, flagged) in [
        ((1i64 << 31) - 1_000_000, false),
        ((1 << 31) + 1_000_000, true),
    ] {
        let link = counts as f64 * TAU / m / n;
        let link_count = ((link / TAU).rem_euclid(1.0) * 4096.0).round() as u32 % 4096;
        let mut st = cfg.state_at(counts, counts as u32);
        let flat = JointTarget {
            turns: 0,
            position: I16F16::from_num(link),
            ..JointTarget::default()
        };
        let out = cfg.update(
            &mut st,
            &JointReadings::counts(link_count, counts as u32),
            &flat,
        );
        assert_eq!(out.invalid_input, flagged, "{counts}: {out:?}");
        if !flagged {
            let want = counts as f64 * TAU / m;
            assert!(
                (out.motor_position_si() - want).abs() < 1e-3,
                "{counts}: {out:?} vs {want}"
            );
        }
    }
}

/// The frame's origin `turns·M·N` on both sides of zero and at both ends
/// of the `i32` turns: a motor `r` counts from `turns` whole output
/// revolutions reads `r` counts in the frame of a target with those turns,
/// on every backend (the count formed here in `i128`). A sign or a high
/// word of the origin lost would read it billions of counts away, and be
/// flagged or saturate.
fn reads_its_count_in_every_turn_frame<S: Scalar>(tol: f64) {
    let p = params();
    let cfg = JointConfig::<S>::new(&p);
    let est = p.settings().estimator;
    let (m, l) = (
        est.motor_counts_per_rev() as i128,
        est.link_counts_per_rev() as i128,
    );
    let mn = m * p.ratio().round() as i128;
    for turns in [
        i32::MIN,
        i32::MIN + 1,
        -54,
        -1,
        0,
        1,
        54,
        i32::MAX - 1,
        i32::MAX,
    ] {
        for r in [-1234i128, -1, 0, 1, 1234] {
            let counts = turns as i128 * mn + r;
            let counts = i64::try_from(counts).unwrap();
            let link_count = (r.rem_euclid(mn) * l / mn) as u32;
            let mut st = cfg.state_at(counts, counts as u32);
            let target = JointTarget {
                turns,
                ..JointTarget::default()
            };
            let out = cfg.update(
                &mut st,
                &JointReadings::counts(link_count, counts as u32),
                &target,
            );
            assert!(!out.invalid_input, "{} {turns} {r}: {out:?}", S::NAME);
            let want = r as f64 * TAU / m as f64;
            assert!(
                (out.motor_position_si() - want).abs() <= tol,
                "{} {turns} {r}: {} vs {want}",
                S::NAME,
                out.motor_position_si()
            );
        }
    }
}

#[test]
fn every_backend_reads_its_count_in_every_turn_frame() {
    reads_its_count_in_every_turn_frame::<f64>(1e-12);
    reads_its_count_in_every_turn_frame::<f32>(1e-6);
    reads_its_count_in_every_turn_frame::<I16F16>(1e-4);
}
