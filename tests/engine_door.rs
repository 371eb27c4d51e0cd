//! The door opening of thesis §6.4.4 on the engine
//! ([`mrr_control::sim::engine::door`]): checks that can fail.
//!
//! * On each seed of a quick set, the passive run's peak interaction torque
//!   is below the held-active contrast's (the thesis's point: the passive
//!   modes relieve the internal forces), and every run opens the door to
//!   the thesis's 90° (within 5°: the base runs open loop on a planned
//!   circle, with slip).
//! * The engine step converges: halving it moves the peaks of one seed by
//!   less than 3 % (measured and true).
//! * Bad inputs are typed errors naming the field.
//!
//! The 20-seed sweep of the claims is the example:
//! `cargo run --release --features sim --example door_opening -- --seeds 20`
//! (and, slower, `cargo test --release --all-features --test engine_door -- --ignored`).

use std::sync::OnceLock;

use mrr_control::sim::door::{DoorConfig, DoorControl};
use mrr_control::sim::engine::door::{
    door_engine_settings, engine_door_opening, Backend, DoorBody, EngineDoorRun,
};
use mrr_control::sim::engine::EngineSettings;
use mrr_control::ParamError;

/// Seeds of the quick set.
const QUICK: [u64; 2] = [1, 2];

/// Per seed of the quick set: (seed, passive run, held-active run), the
/// seed's door and base processes, the wrist grasping at 10° of pitch.
fn quick() -> &'static Vec<(u64, EngineDoorRun, EngineDoorRun)> {
    static RUNS: OnceLock<Vec<(u64, EngineDoorRun, EngineDoorRun)>> = OnceLock::new();
    RUNS.get_or_init(|| {
        let e = door_engine_settings();
        let run = move |seed: u64, control| {
            engine_door_opening(
                &DoorConfig::thesis(control, 0.0, seed),
                &DoorBody::draw(seed),
                10f64.to_radians(),
                &e,
                Backend::F32,
            )
            .expect("valid scene")
        };
        // One thread per seed (the debug build is slow).
        std::thread::scope(|scope| {
            let handles: Vec<_> = QUICK
                .iter()
                .map(|&s| {
                    scope.spawn(move || {
                        (
                            s,
                            run(s, DoorControl::Passive),
                            run(s, DoorControl::ActiveHold),
                        )
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("seed thread"))
                .collect()
        })
    })
}

#[test]
fn passive_peaks_are_below_the_held_active_ones_on_every_seed() {
    for (seed, passive, hold) in quick() {
        eprintln!(
            "seed {seed}: peaks passive {:.2} (true {:.2}), held {:.2} (true {:.2}) N·m",
            passive.peak(),
            passive.peak_true(),
            hold.peak(),
            hold.peak_true()
        );
        // The wrist itself yields (its admittance reference follows the
        // knob) where the held one does not move: over a degree of yaw
        // against a hundredth. And the relief is the wrist's as well as the
        // turret's: with the wrist forced Active and only the turret
        // passive the ratio was 0.60 and 0.56 on these seeds (measured by
        // breaking the run), with both passive about 0.36, so half
        // separates them.
        eprintln!(
            "  wrist yaw range passive {:.3}°, held {:.3}°",
            passive.wrist_range[1].to_degrees(),
            hold.wrist_range[1].to_degrees()
        );
        assert!(
            passive.wrist_range[1].to_degrees() >= 1.0 && hold.wrist_range[1].to_degrees() <= 0.1,
            "seed {seed}: wrist yaw ranges {:?} {:?}",
            passive.wrist_range,
            hold.wrist_range
        );
        assert!(
            passive.peak() <= 0.5 * hold.peak() && passive.peak_true() <= 0.5 * hold.peak_true(),
            "seed {seed}: passive {:.2} N·m not below half the held {:.2} N·m",
            passive.peak(),
            hold.peak()
        );
        // The F/T chain reads what the engine transmits: the measured peak
        // within 20 % of the true one (2 % calibration error, noise and the
        // gripper's own inertia between them).
        for r in [passive, hold] {
            let (meas, truth) = (r.peak(), r.peak_true());
            assert!(
                (meas - truth).abs() <= 0.2 * truth,
                "seed {seed}: measured {meas:.3} vs true {truth:.3} N·m"
            );
        }
    }
}

/// The thesis's "less than 2 N·m" (§6.4.4, claim `6.20-passive`) does not
/// hold on the quick seeds: the passive peak, measured and true, is above
/// 2 N·m on each (the 20-seed verdict, refuted, is the claims registry's:
/// errata E6.8).
#[test]
fn passive_peaks_exceed_the_thesis_two_newton_metres() {
    for (seed, passive, _) in quick() {
        assert!(
            passive.peak() > 2.0 && passive.peak_true() > 2.0,
            "seed {seed}: passive peak {:.2} (true {:.2}) N·m",
            passive.peak(),
            passive.peak_true()
        );
    }
}

#[test]
fn every_run_opens_the_door_to_ninety_degrees() {
    for (seed, passive, hold) in quick() {
        for r in [passive, hold] {
            let a = r.door_angle.to_degrees();
            assert!((a - 90.0).abs() <= 5.0, "seed {seed}: door at {a:.1}°");
        }
    }
}

/// The passive run of seed 1 at `engine`; `fast` opens the door in 6 s
/// instead of 12 (the same scene driven twice as hard, for a cheaper
/// convergence check in the debug build).
fn passive_run(engine: &EngineSettings, fast: bool) -> EngineDoorRun {
    let mut cfg = DoorConfig::thesis(DoorControl::Passive, 0.0, 1);
    if fast {
        cfg.opening_time = 6.0;
    }
    engine_door_opening(
        &cfg,
        &DoorBody::draw(1),
        10f64.to_radians(),
        engine,
        Backend::F32,
    )
    .expect("valid scene")
}

/// Halving the engine step (0.25 → 0.125 ms) moves the peak torques of a
/// passive run by less than 3 % and keeps the mechanism's loop closed (on
/// the 6 s opening; the 12 s one is reported by the example with
/// `--half-step`).
#[test]
fn the_engine_step_converges_by_halving() {
    let e = door_engine_settings();
    let a = passive_run(&e, true);
    let b = passive_run(&e.with_half_step(), true);
    for (name, x, y) in [
        ("measured", a.peak(), b.peak()),
        ("true", a.peak_true(), b.peak_true()),
        ("door angle", a.door_angle, b.door_angle),
    ] {
        eprintln!("{name}: dt {x:.4}, dt/2 {y:.4}");
        assert!((x - y).abs() <= 0.03 * y.abs(), "{name}: {x} vs {y}");
    }
    assert!(
        a.loop_error < 5e-3 && b.loop_error < 5e-3,
        "{} {}",
        a.loop_error,
        b.loop_error
    );
}

#[test]
fn bad_inputs_are_named_errors() {
    let cfg = DoorConfig::thesis(DoorControl::Passive, 0.0, 1);
    let e = door_engine_settings();
    let err = |door: &DoorBody, pitch: f64, e: &EngineSettings| {
        engine_door_opening(&cfg, door, pitch, e, Backend::F32).err()
    };
    let heavy = DoorBody {
        mass: -1.0,
        ..DoorBody::nominal()
    };
    assert!(matches!(
        err(&heavy, 0.1, &e),
        Some(ParamError::NotPositive {
            name: "door.mass",
            ..
        })
    ));
    let sticky = DoorBody {
        hinge_coulomb: f64::NAN,
        ..DoorBody::nominal()
    };
    assert!(matches!(
        err(&sticky, 0.1, &e),
        Some(ParamError::NotFinite {
            name: "door.hinge_coulomb",
            ..
        })
    ));
    assert!(matches!(
        err(&DoorBody::nominal(), 0.5, &e),
        Some(ParamError::OutOfRange {
            name: "start_pitch",
            ..
        })
    ));
    let odd = EngineSettings::try_new(3e-4, 1, 20.0, 0.4).unwrap();
    assert!(matches!(
        err(&DoorBody::nominal(), 0.1, &odd),
        Some(ParamError::OutOfRange { name: "dt", .. })
    ));
}

/// The f64 and I16F16 backends on one seed: the same scene with the
/// library's steps in another number type (slow in a debug build).
#[test]
#[ignore = "slow in debug builds: cargo test --release --all-features --test engine_door -- --ignored"]
fn other_backends_open_the_door_with_peaks_like_f32() {
    let e = door_engine_settings();
    let cfg = DoorConfig::thesis(DoorControl::Passive, 0.0, 1);
    let f32_run = passive_run(&e, false);
    for b in [Backend::F64, Backend::I16F16] {
        let r = engine_door_opening(&cfg, &DoorBody::draw(1), 10f64.to_radians(), &e, b).unwrap();
        eprintln!(
            "{b:?}: peak {:.3} (f32 {:.3}) N·m, door {:.1}°",
            r.peak(),
            f32_run.peak(),
            r.door_angle.to_degrees()
        );
        assert!((r.door_angle.to_degrees() - 90.0).abs() <= 5.0);
        assert!((r.peak() - f32_run.peak()).abs() <= 0.25 * f32_run.peak());
    }
}
