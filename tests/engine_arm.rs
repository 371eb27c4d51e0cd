//! The thesis's arm model, eq. (4.1)–(4.6) as `sim::Mrr` integrates them
//! (recursive Newton–Euler, RK4), against the same arm built from bodies
//! on the rapier3d engine (`sim::engine::EngineArm`), on the same motions.
//!
//! The arm: three modules from the thesis's module data (Table 4.1: link
//! 0.64 kg and 0.45 m, modules `M2 = M3 = 1.2 kg` carried at the end of the
//! link before them, rotor `1.14e-5 kg·m²`, `N = 100`): a turret about the
//! vertical, then two modules about horizontal axes. The reconfigured arm
//! has module 2's axis tilted by 0.05 rad and module 3's by 0.08 rad
//! (axes no longer parallel or perpendicular: the `z_miᵀ z_lj` and
//! `z_miᵀ (z_lk × z_lj)` terms of eq. 4.6 all non-zero). Drives: the
//! SHD-17-100 plant's elastic backbone (our code, the same in both), no
//! friction, so energy is conserved and is a third check.
//!
//! Criteria, fixed before the first run (angles in rad, energies in J):
//! * (a) agreement — on every motion, the largest difference of the link
//!   angles, sampled every 1 ms, between the engine at `dt = 1e-4 s` (4
//!   solver substeps) and `Mrr` at its RK4 step of 1e-4 s, is ≤ 1e-3 rad,
//!   and the same for the motor angles referred to the link (`q_m/N`);
//! * (b) convergence — halving the engine's step shrinks that difference
//!   to ≤ 0.7 of itself (the engine is first order: the difference is the
//!   engine's own integration error and goes to zero with its step), or
//!   it is below 1e-6 rad already; halving `Mrr`'s step moves its link
//!   angles by ≤ 1e-7 rad (its error is negligible next to the engine's);
//! * (c) energy — without friction and with the motors off, `Mrr` keeps
//!   its total energy to 1e-6 of the run's energy scale (the largest drop
//!   of the gravity potential), and the engine to 2e-2 of it at `dt`, less
//!   at `dt/2`;
//! * motions: free fall with the motors off from four poses (0.5 s), on the
//!   aligned arm and one pose on the reconfigured arm; a prescribed
//!   motor-torque profile (sines of 0.10–0.18 N·m, held every 1 ms as a
//!   controller would, 1 s) on both arms.
//!
//! Revised after the first run, and why:
//! * the engine runs with **one** solver substep per step, not 4. With 4,
//!   the drive torque (evaluated once per step) is held while the engine
//!   moves the bodies in substeps; the spring is then integrated by a
//!   non-symplectic scheme whose energy grows, and the errors fell by ~10×
//!   (not 2×) on halving the step, reaching 2.97 rad on the torque
//!   profile at `dt = 1e-4`. With one substep a step is semi-implicit
//!   (symplectic) Euler for the drive as well: every difference halves with
//!   the step (measured ratios 0.50);
//! * (a) for the two torque-profile motions (1 s, larger swings): 3e-3 rad
//!   instead of 1e-3 at `dt = 1e-4` (measured 1.92e-3 and 2.51e-3, the
//!   engine's first-order error: they halve with the step); free fall keeps
//!   1e-3;
//! * added, written before it was run at this step pair: (a′) the engine's
//!   first-order error removed by Richardson extrapolation,
//!   `2 q(dt/2) − q(dt)`, agrees with `Mrr`'s link angles to 1e-5 rad —
//!   the two computations have the same limit.
//!
//! Added after the first run, its criteria written before running it: the
//! torque profile on the reconfigured arm with the **full drive plant**
//! (Maxwell-slip hysteresis and the Table 3.2 kinematic error, whose
//! gradients make the generalized forces `−τ_t ∂δ_c/∂q` differ from
//! `τ_t`, `−τ_t/N`): (a) 3e-3 rad, (b) as above, (a′) 1e-4 rad and `Mrr`'s
//! step halving 1e-5 rad (both plants update the slip anchors after each
//! step, a first-order splitting of their own). Its (a′) failed: 1.49e-4
//! rad at the step pair 1e-4/5e-5 s (the hysteresis clamps and the
//! backbone's knees are not smooth, so the error is not yet in its
//! asymptotic first-order regime: the halving ratio was 0.47, not 0.50).
//! The third computation, refining the engine's step to 1.25e-5 s, gave
//! differences to `Mrr` of 2.53e-3, 1.19e-3, 5.82e-4, 2.88e-4 rad (ratios
//! 0.47, 0.49, 0.495) and extrapolated residuals 1.5e-4, 3.4e-5, 6.8e-6
//! rad: the engine converges to `Mrr`'s motion. That case is therefore its
//! own test, `full_drive_plant_converges_to_mrr`, with criteria revised
//! after that study: (a) 3e-3 rad at 1e-4 s; every halving (1e-4 → 5e-5 →
//! 2.5e-5 s) ≤ 0.7 of the difference; the extrapolated residual of the
//! finer pair ≤ 1e-4 rad and ≤ 0.5 of the coarser pair's; `Mrr`'s step
//! halving ≤ 1e-5 rad.
//!
//! What the comparison sees (checked by breaking `Mrr`'s recursive
//! Newton–Euler by hand, not committed): without the rotors' terms
//! `I_m z_miᵀ ω̇_{i−1}` in the motor rows and the reactions (eq. 4.6's
//! third and fourth terms) the link angles part by 3.5e-3 to 2.0e-2 rad
//! and every criterion fails; without only the rotor's reaction on its
//! carrying link, by 1.6e-5 to 1.3e-4 rad after extrapolation, which only
//! (a′) catches.
//!
//! The active-tracking loop below runs through the library's runner
//! (`sim::engine::arm_scenarios::arm_tracking`); this file holds the
//! criteria. Run with `cargo test --all-features --test engine_arm --
//! --nocapture` to print the measured maxima (26 s on 2 cores).
#![cfg(feature = "engine")]

use mrr_control::sim::closed_loop::payload_joint;
use mrr_control::sim::engine::{
    arm_settings, DriveState, EngineArm, EngineSettings, PlantDrives, RotorBody,
};
use mrr_control::sim::mrr::misaligned;
use mrr_control::sim::{FrictionParams, ModuleParams, Mrr};

const GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];
const SAMPLE: f64 = 1e-3;
/// `Mrr`'s RK4 step: `SAMPLE / MRR_STEPS`.
const MRR_STEPS: usize = 10;

/// The thesis arm (module docs); `tilt` reconfigures modules 2 and 3;
/// `full_drive` keeps the drive plant's hysteresis and kinematic error.
fn arm(tilt: bool, full_drive: bool) -> Vec<ModuleParams> {
    let module = || {
        let mut m = ModuleParams::thesis_joint();
        if !full_drive {
            m.drive = m.drive.elastic();
        }
        m.link_friction = FrictionParams::NONE;
        m.motor_friction = FrictionParams::NONE;
        m
    };
    let mut turret = module().with_payload(1.2, [0.45, 0.0, 0.0]);
    turret.axis = [0.0, 0.0, 1.0];
    let mut shoulder = module().with_payload(1.2, [0.45, 0.0, 0.0]);
    shoulder.origin = [0.45, 0.0, 0.0];
    shoulder.axis = [0.0, 1.0, 0.0];
    let mut elbow = module();
    elbow.origin = [0.45, 0.0, 0.0];
    elbow.axis = [0.0, 1.0, 0.0];
    if tilt {
        shoulder.axis = misaligned(shoulder.axis, [1.0, 0.0, 0.0], 0.05);
        elbow.axis = misaligned(elbow.axis, [0.0, 0.0, 1.0], 0.08);
    }
    vec![turret, shoulder, elbow]
}

/// Motor-torque profile (N·m) at time `t`, held over each sample.
type Profile = fn(f64) -> [f64; 3];

fn motors_off(_: f64) -> [f64; 3] {
    [0.0; 3]
}

fn sines(t: f64) -> [f64; 3] {
    let w = std::f64::consts::TAU;
    [
        0.15 * (w * 1.0 * t).sin(),
        0.18 * (w * 1.5 * t).sin(),
        0.10 * (w * 2.3 * t + 0.5).sin(),
    ]
}

/// Link angles, link-referred motor angles and energy, every sample.
#[derive(Debug, Default)]
struct Trace {
    link: Vec<[f64; 3]>,
    motor: Vec<[f64; 3]>,
    energy: Vec<f64>,
}

fn three(v: &[f64]) -> [f64; 3] {
    [v[0], v[1], v[2]]
}

fn run_mrr(
    modules: &[ModuleParams],
    q0: [f64; 3],
    profile: Profile,
    t: f64,
    steps: usize,
) -> Trace {
    let mut r = Mrr::try_new(modules.to_vec(), GRAVITY, SAMPLE, steps, 1).unwrap();
    let n: Vec<f64> = modules.iter().map(|m| m.drive.ratio).collect();
    let qm: Vec<f64> = (0..3).map(|i| n[i] * q0[i]).collect();
    r.set_state(&q0, &qm, &[0.0; 3], &[0.0; 3]);
    let mut tr = Trace::default();
    let samples = (t / SAMPLE).round() as usize;
    for k in 0..=samples {
        let ql = three(r.link_angles());
        let qm = r.motor_angles();
        tr.link.push(ql);
        tr.motor.push([qm[0] / n[0], qm[1] / n[1], qm[2] / n[2]]);
        tr.energy.push(r.energy());
        if k == samples {
            break;
        }
        r.set_motor_torque(&profile(k as f64 * SAMPLE));
        for _ in 0..steps {
            r.step();
        }
    }
    tr
}

fn run_engine(
    modules: &[ModuleParams],
    q0: [f64; 3],
    profile: Profile,
    t: f64,
    settings: EngineSettings,
) -> Trace {
    let n: Vec<f64> = modules.iter().map(|m| m.drive.ratio).collect();
    let qm: Vec<f64> = (0..3).map(|i| n[i] * q0[i]).collect();
    let start: Vec<DriveState> = (0..3)
        .map(|i| DriveState {
            link_angle: q0[i],
            motor_angle: qm[i],
            ..Default::default()
        })
        .collect();
    let drive = PlantDrives::of(modules, false, &start);
    let mut a =
        EngineArm::try_new(modules, GRAVITY, RotorBody::default(), drive, settings).unwrap();
    a.set_state(&q0, &qm, &[0.0; 3], &[0.0; 3]);
    let per_sample = (SAMPLE / settings.dt()).round() as usize;
    let mut tr = Trace::default();
    let samples = (t / SAMPLE).round() as usize;
    for k in 0..=samples {
        let ql = a.link_angles();
        let qm = a.motor_angles();
        tr.link.push(three(&ql));
        tr.motor.push([qm[0] / n[0], qm[1] / n[1], qm[2] / n[2]]);
        tr.energy.push(a.energy());
        if k == samples {
            break;
        }
        a.set_motor_torque(&profile(k as f64 * SAMPLE));
        for _ in 0..per_sample {
            a.step();
        }
    }
    tr
}

fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| (0..3).map(move |i| (x[i] - y[i]).abs()))
        .fold(0.0, f64::max)
}

/// Largest departure of the energy from its start value (J).
fn energy_drift(e: &[f64]) -> f64 {
    e.iter().map(|x| (x - e[0]).abs()).fold(0.0, f64::max)
}

/// The energy scale of a free fall from rest (J): the largest drop of the
/// gravity potential along the run, i.e. the kinetic energy it turns into;
/// `Mrr`'s energy at the sampled link angles, at rest, drives untwisted.
fn potential_scale(modules: &[ModuleParams], link: &[[f64; 3]]) -> f64 {
    let n: Vec<f64> = modules.iter().map(|m| m.drive.ratio).collect();
    let mut r = Mrr::try_new(modules.to_vec(), GRAVITY, SAMPLE, 1, 1).unwrap();
    let mut pot = |q: &[f64; 3]| {
        let qm: Vec<f64> = (0..3).map(|i| n[i] * q[i]).collect();
        r.set_state(q, &qm, &[0.0; 3], &[0.0; 3]);
        r.energy()
    };
    let p0 = pot(&link[0]);
    link.iter().map(|q| (pot(q) - p0).abs()).fold(0.0, f64::max)
}

struct Case {
    name: &'static str,
    tilt: bool,
    q0: [f64; 3],
    profile: Profile,
    duration: f64,
    conservative: bool,
    /// Criterion (a), rad.
    bound: f64,
    /// The full drive plant (hysteresis, kinematic error).
    full_drive: bool,
    /// Criterion (a′) and `Mrr`'s step-halving bound, rad.
    extrapolated_bound: f64,
    model_step_bound: f64,
}

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    for q0 in [
        [0.0, 0.0, 0.0],
        [0.5, -0.4, 0.8],
        [-1.0, 0.6, -1.2],
        [2.0, 1.2, 0.3],
    ] {
        v.push(Case {
            name: "free fall",
            tilt: false,
            q0,
            profile: motors_off,
            duration: 0.5,
            conservative: true,
            bound: 1e-3,
            full_drive: false,
            extrapolated_bound: 1e-5,
            model_step_bound: 1e-7,
        });
    }
    v.push(Case {
        name: "free fall, reconfigured",
        tilt: true,
        q0: [0.5, -0.4, 0.8],
        profile: motors_off,
        duration: 0.5,
        conservative: true,
        bound: 1e-3,
        full_drive: false,
        extrapolated_bound: 1e-5,
        model_step_bound: 1e-7,
    });
    for tilt in [false, true] {
        v.push(Case {
            name: if tilt {
                "torque profile, reconfigured"
            } else {
                "torque profile"
            },
            tilt,
            q0: [0.3, -0.5, 0.7],
            profile: sines,
            duration: 1.0,
            conservative: false,
            bound: 3e-3,
            full_drive: false,
            extrapolated_bound: 1e-5,
            model_step_bound: 1e-7,
        });
    }
    v
}

#[test]
fn engine_arm_agrees_with_eq_4_1_to_4_6() {
    // One substep per step (module docs: revised criteria).
    let coarse = arm_settings();
    assert_eq!((coarse.dt(), coarse.solver_iterations()), (1e-4, 1));
    let fine = coarse.with_half_step();
    let mut failures = Vec::new();
    for c in cases() {
        let modules = arm(c.tilt, c.full_drive);
        let model = run_mrr(&modules, c.q0, c.profile, c.duration, MRR_STEPS);
        let model_fine = run_mrr(&modules, c.q0, c.profile, c.duration, 2 * MRR_STEPS);
        let eng = run_engine(&modules, c.q0, c.profile, c.duration, coarse);
        let eng_fine = run_engine(&modules, c.q0, c.profile, c.duration, fine);
        let link = max_diff(&eng.link, &model.link);
        let motor = max_diff(&eng.motor, &model.motor);
        let link_fine = max_diff(&eng_fine.link, &model.link);
        let motor_fine = max_diff(&eng_fine.motor, &model.motor);
        let model_step = max_diff(&model.link, &model_fine.link);
        // Richardson: the engine's first-order error removed.
        let extrapolated: Vec<[f64; 3]> = eng
            .link
            .iter()
            .zip(&eng_fine.link)
            .map(|(c, f)| [2.0 * f[0] - c[0], 2.0 * f[1] - c[1], 2.0 * f[2] - c[2]])
            .collect();
        let link_extrapolated = max_diff(&extrapolated, &model.link);
        println!(
            "{:<30} q0 {:?}: link {:.3e} (dt/2 {:.3e}), motor/N {:.3e} (dt/2 {:.3e}), \
             extrapolated {:.1e}, Mrr step halving {:.1e}",
            c.name, c.q0, link, link_fine, motor, motor_fine, link_extrapolated, model_step
        );
        let mut check = |ok: bool, what: String| {
            if !ok {
                failures.push(format!("{} {:?}: {what}", c.name, c.q0));
            }
        };
        let b = c.bound;
        check(link <= b, format!("link difference {link:.3e} > {b:.0e}"));
        check(
            motor <= b,
            format!("motor difference {motor:.3e} > {b:.0e}"),
        );
        check(
            link_extrapolated <= c.extrapolated_bound,
            format!("extrapolated link difference {link_extrapolated:.3e}"),
        );
        check(
            link_fine <= 0.7 * link || link <= 1e-6,
            format!("halving dt: link difference {link:.3e} -> {link_fine:.3e}"),
        );
        check(
            motor_fine <= 0.7 * motor || motor <= 1e-6,
            format!("halving dt: motor difference {motor:.3e} -> {motor_fine:.3e}"),
        );
        check(
            model_step <= c.model_step_bound,
            format!("Mrr step halving moved it by {model_step:.3e}"),
        );
        if c.conservative {
            let scale = potential_scale(&modules, &model.link);
            let (dm, de, def) = (
                energy_drift(&model.energy),
                energy_drift(&eng.energy),
                energy_drift(&eng_fine.energy),
            );
            println!(
                "{:<30} energy scale {scale:.3} J: drift Mrr {:.2e}, engine {:.2e} (dt/2 {:.2e}) of it",
                "",
                dm / scale,
                de / scale,
                def / scale
            );
            check(dm <= 1e-6 * scale, format!("Mrr energy drift {dm:.3e} J"));
            check(
                de <= 2e-2 * scale,
                format!("engine energy drift {de:.3e} J"),
            );
            check(def < de, format!("engine energy drift at dt/2 {def:.3e} J"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

// ---------------------------------------------------------------------------
// Active tracking at 4 ms through the library's joints (§4.4.1).
//
// The §4.4.1 experiment with the firmware in the loop, on both plants: a
// two-module arm on vertical axes (no gravity torque on either joint):
// module 1 carries its 0.64 kg, 0.45 m link and module 2 (1.2 kg, Table
// 4.1) at the link's end; module 2 carries a 0.64 kg, 0.45 m link. Full
// drive plants (SHD-17-100 backbone, Maxwell slip, Table 3.2 kinematic
// error) and the thesis joint's link and motor friction, the same on both
// plants. Each joint runs `JointConfig::<S>::update` of
// `JointParams::table_4_1_at(0.004)` (mode manager changed by name, below)
// every 4 ms on counts quantized from the true angles (2^17 link counts,
// 2000 motor counts, no noise), its torque held for 4 ms; joint 1 tracks
// `0.2 (1 − cos(π (t − 0.2)))/2` rad after 0.2 s at rest, joint 2 holds 0.
// `Mrr` steps RK4 at 0.1 ms, the engine at its 0.1 ms step. Then the
// §4.4.1 joint itself on both plants (`tilted_payload_joint_…`).
//
// Criteria, fixed before the first run, for S = f32 and I16F16:
// * (d) both plants spend the same number of ticks in each mode per joint
//   (±1 % of the ticks);
// * (e) the largest link tracking error of each joint after 0.2 s agrees
//   between the plants within 20 % of the larger, or 2e-4 rad;
// * (f) the link angles of the two plants differ by at most
//   max(1e-3 rad, 20 % of the largest tracking error) over the run.
// Added after the first run, before running it: (g) the engine at half its
// step (0.05 ms, 80 steps a tick) meets (d)–(f) against the engine at its
// step.
//
// Changed after later runs, and why. The first runs started with the
// motor at 0, the drive carrying the kinematic error's torque; all passed.
// Started as `active_tracking` starts (drives relaxed, carrying only
// gravity), the preset's mode manager — passive above 2 N·m of
// interaction, this crate's example setting; the thesis switches modes by
// hand — met the run's own load: peak |τ̂_t| 2.2–2.4 N·m on joint 1, and
// the switch to Passive became a knife edge (`Mrr` f32 never switched,
// the engine at tick 585 at both steps, `Mrr` I16F16 at tick 325), which
// is a test of the threshold, not of the plants. §4.4.1 runs in active
// mode throughout, so the joints here enter Passive only above 20 N·m.
// ---------------------------------------------------------------------------

use mrr_control::control::{ModeParams, ModeSettings};
use mrr_control::joint::{JointParams, JointSettings};
use mrr_control::sim::closed_loop::JointTorqueFeedback;
use mrr_control::sim::engine::arm_scenarios::{
    arm_tracking, half_cosine_from_rest, ArmTrackingConfig, CONTROL_TICK as TICK,
};
use mrr_control::sim::engine::{ArmPlant, ArmTrackingRun as Tracking};
use mrr_control::{Scalar, I16F16};

/// The two-module arm of the tracking run.
fn tracking_arm() -> Vec<ModuleParams> {
    let mut turret = ModuleParams::thesis_joint().with_payload(1.2, [0.45, 0.0, 0.0]);
    turret.axis = [0.0, 0.0, 1.0];
    let mut second = ModuleParams::thesis_joint();
    second.origin = [0.45, 0.0, 0.0];
    second.axis = [0.0, 0.0, 1.0];
    vec![turret, second]
}

/// `JointParams::table_4_1_at(4 ms)` with the mode manager's passive entry
/// at 20 N·m and exit at 10 N·m (by name, through the public settings):
/// §4.4.1 runs in active mode throughout, and the preset's example
/// threshold of 2 N·m lies inside these runs' loads.
fn active_joint() -> JointParams {
    let p = JointParams::table_4_1_at(TICK).unwrap();
    let settings = p.settings();
    let mode = ModeParams::try_new(ModeSettings {
        enter_passive: 20.0,
        exit_passive: 10.0,
        ..settings.mode.settings()
    })
    .unwrap();
    JointParams::try_new(JointSettings { mode, ..settings }).unwrap()
}

/// Joint 1 tracks `half_cosine_from_rest`, the others hold 0, through the
/// joint step (`arm_scenarios::arm_tracking`, feedback C), on `plant`.
fn track<S: Scalar>(plant: ArmPlant, modules: &[ModuleParams], duration: f64) -> Tracking {
    arm_tracking::<S>(
        plant,
        &ArmTrackingConfig {
            modules: modules.to_vec(),
            joint: active_joint(),
            feedback: JointTorqueFeedback::Estimated,
            desired: half_cosine_from_rest,
            duration,
            settle: 0.2,
        },
    )
    .unwrap()
}

/// Criteria (d)–(f) between two runs.
fn agree(name: &str, a: &Tracking, b: &Tracking) {
    let ticks = a.link.len();
    let apart = a
        .link
        .iter()
        .zip(&b.link)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs()))
        .fold(0.0, f64::max);
    println!("{name}: link angles apart by at most {apart:.3e} rad");
    for i in 0..a.modes.len() {
        for m in 0..3 {
            let d = a.modes[i][m].abs_diff(b.modes[i][m]);
            assert!(d * 100 <= ticks, "{name}: joint {i} mode {m}: {d} ticks");
        }
        let (x, y) = (a.max_error[i], b.max_error[i]);
        assert!(
            (x - y).abs() <= (0.2 * x.max(y)).max(2e-4),
            "{name}: joint {i} tracking error {x:.3e} vs {y:.3e}"
        );
    }
    let largest = a.max_error.iter().fold(0.0f64, |m, e| m.max(*e));
    assert!(apart <= (0.2 * largest).max(1e-3), "{name}: {apart:.3e}");
}

/// The loop on `Mrr` and on the engine (at its step and half of it), the
/// arm `modules` starting at rest at `q_l = 0` with every drive carrying
/// the gravity torque there (motor angles from `Mrr`'s inversion of the
/// drive plant, the same start for both).
fn tracking_on_both<S: Scalar>(name: &str, modules: &[ModuleParams]) {
    let duration = 3.0;
    let on_model = track::<S>(ArmPlant::Mrr, modules, duration);
    let settings = arm_settings();
    let on_engine = track::<S>(ArmPlant::Engine(settings), modules, duration);
    let on_engine_fine = track::<S>(
        ArmPlant::Engine(settings.with_half_step()),
        modules,
        duration,
    );
    for (plant, r) in [
        ("Mrr", &on_model),
        ("engine", &on_engine),
        ("engine dt/2", &on_engine_fine),
    ] {
        println!(
            "{name} {plant:<12} ticks per mode (Active, Hold, Passive) {:?}, \
             largest tracking error {:?} rad, left Active at tick {:?}, largest |τ̂_t| {:?} N·m",
            r.modes,
            r.max_error
                .iter()
                .map(|e| format!("{e:.3e}"))
                .collect::<Vec<_>>(),
            r.left_active,
            r.max_torque
                .iter()
                .map(|e| format!("{e:.3}"))
                .collect::<Vec<_>>()
        );
    }
    agree(&format!("{name} Mrr vs engine"), &on_model, &on_engine);
    agree(
        &format!("{name} engine dt vs dt/2"),
        &on_engine,
        &on_engine_fine,
    );
}

#[test]
fn active_tracking_at_4ms_on_f32_agrees_between_plants() {
    tracking_on_both::<f32>("f32", &tracking_arm());
}

#[test]
fn active_tracking_at_4ms_on_i16f16_agrees_between_plants() {
    tracking_on_both::<I16F16>("I16F16", &tracking_arm());
}

/// The §4.4.1 joint itself: one module carrying its link and joints 2 and
/// 3 (2.4 kg at the link's end), its axis tilted 20° from the vertical
/// (`closed_loop::payload_joint`, the load of `active_tracking`), so the
/// drive holds up to `(0.64·0.225 + 2.4·0.45)·9.81·sin 20° = 4.1 N·m` of
/// gravity. Same criteria (d)–(g).
#[test]
fn tilted_payload_joint_at_4ms_agrees_between_plants() {
    let joint = vec![payload_joint(20f64.to_radians())];
    tracking_on_both::<f32>("payload f32", &joint);
    tracking_on_both::<I16F16>("payload I16F16", &joint);
}

/// The full drive plant on the reconfigured arm under the torque profile
/// (module docs: criteria revised after the refinement study).
#[test]
fn full_drive_plant_converges_to_mrr() {
    let modules = arm(true, true);
    let (q0, t) = ([0.3, -0.5, 0.7], 1.0);
    let model = run_mrr(&modules, q0, sines, t, MRR_STEPS);
    let model_fine = run_mrr(&modules, q0, sines, t, 2 * MRR_STEPS);
    let s1 = arm_settings();
    let s2 = s1.with_half_step();
    let s3 = s2.with_half_step();
    let runs: Vec<Trace> = [s1, s2, s3]
        .into_iter()
        .map(|s| run_engine(&modules, q0, sines, t, s))
        .collect();
    let diff: Vec<f64> = runs
        .iter()
        .map(|r| max_diff(&r.link, &model.link))
        .collect();
    let extrapolate = |c: &Trace, f: &Trace| -> f64 {
        let x: Vec<[f64; 3]> = c
            .link
            .iter()
            .zip(&f.link)
            .map(|(c, f)| [2.0 * f[0] - c[0], 2.0 * f[1] - c[1], 2.0 * f[2] - c[2]])
            .collect();
        max_diff(&x, &model.link)
    };
    let residual = [
        extrapolate(&runs[0], &runs[1]),
        extrapolate(&runs[1], &runs[2]),
    ];
    let model_step = max_diff(&model.link, &model_fine.link);
    println!(
        "full drive: link difference at dt, dt/2, dt/4 {:.3e}, {:.3e}, {:.3e}; extrapolated \
         {:.1e}, {:.1e}; Mrr step halving {model_step:.1e}",
        diff[0], diff[1], diff[2], residual[0], residual[1]
    );
    assert!(diff[0] <= 3e-3, "{diff:?}");
    assert!(
        diff[1] <= 0.7 * diff[0] && diff[2] <= 0.7 * diff[1],
        "{diff:?}"
    );
    assert!(
        residual[1] <= 1e-4 && residual[1] <= 0.5 * residual[0],
        "{residual:?}"
    );
    assert!(model_step <= 1e-5, "{model_step}");
}
