//! The wrist bench of thesis §6.4.3 on the engine
//! ([`mrr_control::sim::engine::wrist_bench`]): checks that can fail.
//!
//! * Case 1 (motors off) holds the thesis's 10 N·m without a gear slipping,
//!   and Case 2 (the library's wrist step, admittance-passive) peaks at a
//!   small fraction of it while the wrist follows the finger.
//! * Case 2's peak is the admittance law's steady following torque
//!   `ẋ_f / K_c` (computed here from the finger's path, not from the run).
//! * The F/T chain reads the engine's torque; the DAUJ's loop stays closed.
//! * The engine step converges: halving it moves the metrics by < 2 %.
//! * Active mode (§6.4.2): the library's step, its inverse kinematics and
//!   its motor laws drive the mechanism along the task trajectory within
//!   the home-made bench's 1° after the first second.
//! * The same on the `I16F16` backend (the wrist step in fixed point, as on
//!   a Cortex-M0+): its readings are on the fixed-point grid, it holds and
//!   relieves as `f32` does, follows the finger at `ẋ_f / K_c` and tracks
//!   within 1°.
//! * Bad inputs are typed errors naming the field.
//!
//! The 20-seed sweep of the claims is the example:
//! `cargo run --release --features sim --example wrist_bench`.

use std::sync::OnceLock;

use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::sim::engine::door::{door_engine_settings, Backend};
use mrr_control::sim::engine::wrist_bench::{
    engine_finger_push, engine_finger_push_from, engine_finger_push_on, engine_wrist_tracking,
    engine_wrist_tracking_on, EngineWristBenchRun, FingerCase, FingerPush, CASE1_TRAVEL, HELD,
    START,
};
use mrr_control::sim::engine::EngineSettings;
use mrr_control::wrist::{ForceMapping, JacobianKind, PitchYaw, WristConfig, WristParams};

/// The thesis's admittance gain `K_c`, rad/(s·N·m) (§6.4.3).
const K_C: f64 = 0.1;

/// The nominal push (pitch, 12° over 1.5 s, 12 N·m break-away) in both
/// cases at the bench's engine step.
fn nominal() -> &'static (EngineWristBenchRun, EngineWristBenchRun) {
    static RUNS: OnceLock<(EngineWristBenchRun, EngineWristBenchRun)> = OnceLock::new();
    RUNS.get_or_init(|| both(&FingerPush::nominal(1), &door_engine_settings()))
}

fn both(push: &FingerPush, e: &EngineSettings) -> (EngineWristBenchRun, EngineWristBenchRun) {
    let run = |case| engine_finger_push(case, push, e).expect("valid bench");
    (run(FingerCase::MotorsOff), run(FingerCase::Admittance))
}

/// The nominal push in both cases with the wrist step on `I16F16`.
fn nominal_fixed() -> &'static (EngineWristBenchRun, EngineWristBenchRun) {
    static RUNS: OnceLock<(EngineWristBenchRun, EngineWristBenchRun)> = OnceLock::new();
    RUNS.get_or_init(|| {
        let (push, e) = (FingerPush::nominal(1), door_engine_settings());
        let run = |case| engine_finger_push_on(case, &push, &e, Backend::I16F16).expect("valid");
        (run(FingerCase::MotorsOff), run(FingerCase::Admittance))
    })
}

/// Whether a torque (N·m) the wrist step returned is a whole number of
/// `I16F16` steps (2⁻¹⁶) of the backend's stored torque unit.
fn on_fixed_grid(tau: f64) -> bool {
    let q = tau * <I16F16 as Scalar>::UNITS.link_torque * 65536.0;
    (q - q.round()).abs() < 1e-6
}

#[test]
fn motors_off_hold_ten_newton_metres_and_admittance_relieves_them() {
    let (off, on) = nominal();
    // Case 1: more than 10 N·m read by the F/T chain before any rotor
    // slipped, and no slip at all over the push.
    // Case 2: its peak a small fraction of what the gears held.
    cases_hold(on, off);
}

/// Case 1 with weaker gears, where the push breaks them away: the torque
/// held is what the library's force mapping (eq. 6.1, exact Jacobian) says
/// the two gears can take at the start pose, `B / max_i |(Jᵀ e_δ)_i|` for
/// a pitch push — the mechanism and the library agree on where the wrist
/// gives, to within the presliding and the push's dynamics (the engine
/// holds 0–20 % more).
#[test]
fn motors_off_give_where_the_library_force_mapping_says() {
    let wp = WristParams::thesis();
    let m = WristConfig::<f64>::new(&wp)
        .inverse(PitchYaw {
            delta: START[0],
            gamma: START[1],
        })
        .motors;
    let t = ForceMapping::<f64>::new(&wp, JacobianKind::Exact)
        .motor_torques(m, [1.0, 0.0])
        .torque;
    let share = t[0].abs().max(t[1].abs());
    let e = door_engine_settings();
    for b in [3.0, 6.0] {
        let push = FingerPush {
            breakaway: b,
            ..FingerPush::nominal(1)
        };
        let off = engine_finger_push(FingerCase::MotorsOff, &push, &e).expect("valid bench");
        // The push (26 N·m if held) breaks the gears away.
        assert!(off.slip > 100.0 * HELD, "B {b}: slip {}", off.slip);
        let r = off.held / (b / share);
        assert!(
            (1.0..1.2).contains(&r),
            "B {b}: held {} vs {}",
            off.held,
            b / share
        );
    }
}

/// The bench on the `I16F16` backend: the step did run in fixed point (its
/// readings lie on the fixed-point grid, the `f32` run's do not), and the
/// checks of the `f32` run hold, its Case 2 peak within 10 % of `f32`'s.
#[test]
fn i16f16_holds_and_relieves_as_f32_does() {
    let (off, on) = nominal_fixed();
    let (_, on_f32) = nominal();
    let all_on_grid = |r: &EngineWristBenchRun| {
        r.samples
            .iter()
            .all(|s| s.measured.iter().all(|&m| on_fixed_grid(m)))
    };
    assert!(all_on_grid(on) && all_on_grid(off));
    assert!(!all_on_grid(on_f32));
    cases_hold(on, off);
    let push = FingerPush::nominal(1);
    assert!(on.travel > 0.8 * push.travel, "{}", on.travel);
    assert!(on.loop_error < 1e-3, "{}", on.loop_error);
    assert!(
        (on.peak_measured - on_f32.peak_measured).abs() < 0.1 * on_f32.peak_measured,
        "{} vs {}",
        on.peak_measured,
        on_f32.peak_measured
    );
}

#[test]
fn the_wrist_yields_under_admittance_and_not_with_the_motors_off() {
    let (off, on) = nominal();
    let push = FingerPush::nominal(1);
    // The wrist follows the finger over at least 80 % of its travel…
    assert!(
        on.travel > 0.8 * push.travel,
        "{} vs {}",
        on.travel,
        push.travel
    );
    // …its motors turn (the rotors leave their start by far more than
    // the friction's presliding)…
    assert!(on.slip > 100.0 * HELD, "{}", on.slip);
    // …along the push (pitch, δ increasing)…
    let last = on.samples.last().expect("samples").pose;
    assert!(last[0] - START[0] > 0.8 * push.travel, "{last:?}");
    // …while with the motors off, under a push twice as far, the pose
    // moves only by the drives' compliance.
    assert!(CASE1_TRAVEL > 2.0 * push.travel);
    assert!(
        off.travel < 0.1 * on.travel,
        "{} vs {}",
        off.travel,
        on.travel
    );
}

/// The admittance law `ẋ_d = K_c τ` follows a finger moving at `ẋ_f` with
/// `τ = ẋ_f / K_c`; at the finger's peak speed (`π·travel/(2·rise)`) the
/// peak torque is that within 15 % (the lag of the loop and the gears'
/// friction make the rest), for a fast and a slow push, on `f32` and on
/// `I16F16`.
#[test]
fn case2_peak_is_the_finger_speed_over_k_c() {
    let e = door_engine_settings();
    for backend in [Backend::F32, Backend::I16F16] {
        for rise in [1.2, 3.0] {
            let push = FingerPush {
                rise,
                ..FingerPush::nominal(2)
            };
            let expected = core::f64::consts::PI * push.travel / (2.0 * rise) / K_C;
            let on = engine_finger_push_on(FingerCase::Admittance, &push, &e, backend)
                .expect("valid bench");
            let r = on.peak_measured / expected;
            assert!(
                (0.85..1.15).contains(&r),
                "{backend:?}, rise {rise}: {} vs {expected}",
                on.peak_measured
            );
        }
    }
}

#[test]
fn the_ft_chain_reads_the_engine_and_the_loop_stays_closed() {
    let (off, on) = nominal();
    for r in [off, on] {
        let rel = (r.peak_measured - r.peak_interaction).abs() / r.peak_interaction;
        // ±2 % calibration error and noise of the gauges (module docs).
        assert!(rel < 0.05, "{} vs {}", r.peak_measured, r.peak_interaction);
        // Component by component (signs included): the reading, averaged
        // over the tick before, within a tenth of the peak of the engine's.
        let worst = r
            .samples
            .iter()
            .map(|s| (s.measured[0] - s.interaction[0]).hypot(s.measured[1] - s.interaction[1]))
            .fold(0.0, f64::max);
        assert!(worst < 0.1 * r.peak_interaction, "{worst}");
        assert!(r.loop_error < 1e-3, "{}", r.loop_error);
    }
}

#[test]
fn the_engine_step_converges_by_halving() {
    let (off, on) = nominal();
    let (off2, on2) = both(
        &FingerPush::nominal(1),
        &door_engine_settings().with_half_step(),
    );
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    for (a, b, what) in [
        (off.held, off2.held, "Case 1 held"),
        (on.peak_measured, on2.peak_measured, "Case 2 peak"),
        (on.travel, on2.travel, "Case 2 travel"),
    ] {
        assert!(rel(a, b) < 0.02, "{what}: {a} vs {b}");
    }
}

/// Fig. 6.10 on the engine: the pose of the mechanism's universal joint
/// follows the desired 12°–24° bend within 1° (the bound of the home-made
/// bench's test) after the first second, in Active mode throughout, with
/// the DAUJ's loop closed, on `f32` and on `I16F16`.
#[test]
fn active_mode_tracks_the_task_trajectory_on_the_mechanism() {
    for backend in [Backend::F32, Backend::I16F16] {
        let r = engine_wrist_tracking_on(6.0, 1.0, &door_engine_settings(), backend)
            .expect("valid run");
        for e in r.max_error {
            assert!(e < 1f64.to_radians(), "{backend:?}: {:?}", r.max_error);
        }
        assert_eq!(r.off_mode_ticks, 0);
        assert!(r.loop_error < 1e-3, "{backend:?}: {}", r.loop_error);
        // The run covers the trajectory (a bend of 24° at t = 2 s).
        let (_, xd, x) = r.samples[500];
        assert!(
            xd[0].hypot(xd[1]) > 0.4 && x[0].hypot(x[1]) > 0.4,
            "{backend:?}: {xd:?} {x:?}"
        );
    }
}

#[test]
fn bad_inputs_are_named_errors() {
    let e = door_engine_settings();
    let p = FingerPush::nominal(1);
    let name = |push: FingerPush, e: &EngineSettings| {
        engine_finger_push(FingerCase::Admittance, &push, e)
            .err()
            .map(|x| x.name())
    };
    assert_eq!(
        name(
            FingerPush {
                travel: f64::NAN,
                ..p
            },
            &e
        ),
        Some("finger.travel")
    );
    assert_eq!(name(FingerPush { rise: 0.1, ..p }, &e), Some("finger.rise"));
    assert_eq!(
        name(
            FingerPush {
                direction: 4.0,
                ..p
            },
            &e
        ),
        Some("finger.direction")
    );
    assert_eq!(
        name(
            FingerPush {
                breakaway: -1.0,
                ..p
            },
            &e
        ),
        Some("finger.breakaway")
    );
    let coarse = EngineSettings::try_new(3e-4, 1, 20.0, 0.4).expect("valid settings");
    assert_eq!(name(p, &coarse), Some("dt"));
    assert_eq!(
        engine_finger_push_from(FingerCase::Admittance, &p, 0.5, &e, Backend::I16F16)
            .err()
            .map(|x| x.name()),
        Some("start_pitch")
    );
    let tracking = |d: f64, s: f64| engine_wrist_tracking(d, s, &e).err().map(|x| x.name());
    // The same names whatever the backend.
    for backend in [Backend::F64, Backend::I16F16] {
        let r = engine_finger_push_on(FingerCase::Admittance, &p, &coarse, backend);
        assert_eq!(r.err().map(|x| x.name()), Some("dt"));
        let r = engine_wrist_tracking_on(1.0, 2.0 * 60.0, &e, backend);
        assert_eq!(r.err().map(|x| x.name()), Some("settle"));
    }
    assert_eq!(tracking(f64::NAN, 0.0), Some("duration"));
    assert_eq!(tracking(1.0, -1.0), Some("settle"));
}

/// Case 1 (motors off) held more than 10 N·m read by the F/T chain with no
/// rotor slipped; Case 2 (admittance-passive) peaked below a quarter of
/// that and never left the Passive mode after the touch.
fn cases_hold(on: &EngineWristBenchRun, off: &EngineWristBenchRun) {
    assert!(off.held > 10.0, "held {}", off.held);
    assert!(off.slip < HELD, "slip {}", off.slip);
    assert!(
        on.peak_measured < 0.25 * off.held,
        "{} vs {}",
        on.peak_measured,
        off.held
    );
    assert_eq!(on.off_mode_ticks, 0);
}
