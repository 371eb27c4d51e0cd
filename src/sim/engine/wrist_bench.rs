//! The wrist bench of thesis §6.4.2–6.4.3 (Fig. 6.10–6.17) on the engine: a
//! finger pushes the output link of the DAUJ, built from its parts, with
//! the motors off (Case 1) or under the library's wrist step in the
//! admittance-passive mode (Case 2).
//!
//! # The bench
//! The wrist of [`super::door`] (the same parts, masses, drives and F/T
//! sensor) on a fixed base, its frame the world's: `z` along `L1`, the pitch
//! `δ` about `y`, the yaw `γ` about the cross's `x` (module [`super::wrist`]).
//! Gravity is off.
//!
//! * **Motors and gears** — each motor is a rotor body
//!   (`I_m = 1.05e-6 kg·m²`, `N = 531`) coupled to its joint (`J1`, and `J3`
//!   through the inner universal joint taken as 1 : 1) by the stiff-spring
//!   drive of the door scene, `k_w = 400 N·m/rad`, `c_w = 2 N·m·s/rad`,
//!   with motor friction with presliding. The gear's friction is an
//!   **assumption**: Table 6.1 gives none, and the only source is Case 1
//!   itself ("the wrist does not move even when more than 10Nm pitch
//!   torque is generated"). As [`crate::sim::wrist_bench::BREAKAWAY`]
//!   does, the break-away at the joint is taken near 12 N·m (drawn per
//!   seed in 11–13 N·m, [`FingerPush::draw`]), two thirds of it Coulomb;
//!   at the motor that is `B/N`. What the engine adds is the mechanism:
//!   the finger's force reaches the two gears through the DAUJ's parts, not
//!   through the library's `Jᵀ`, so the task torque they hold is the
//!   engine's answer, not the assumption's. At the start pose a pitch push
//!   reaches each gear as 0.27 of itself (eq. 6.1 with the exact
//!   Jacobian), so the gears hold about `3.7 B` of pitch torque; the
//!   engine holds 0–20 % more than that prediction
//!   (`tests/engine_wrist_bench.rs`), and the thesis's 10 N·m needs only
//!   `B ≈ 2.7 N·m` per gear there.
//! * **F/T sensor and tool** — the tool (0.3 kg) on a fixed joint to `L2`
//!   at the sensor origin (`l = 0.05 m`); the wrench it puts through that
//!   joint by momentum balance, averaged over each 4 ms tick, turned into
//!   gauge voltages by a [`StrainGaugeSensor`] off the certificate by ±2 %
//!   (seeded) with 0.3 mV noise.
//! * **Finger** — a flat, frictionless fingertip pressing the tool point
//!   (`L_f = 0.2 m` along `L2`) along a world direction `n` in the `xy`
//!   plane at the angle `ψ` from `+x` toward `−y` (`ψ = 0`: a pure pitch
//!   push, `ψ = 90°`: yaw). It touches the tool where it finds it, moves
//!   along `n` by `L_f · travel` on a raised cosine over `rise` s, stays
//!   0.5 s, returns over `rise` s and lets go. The contact is a
//!   spring-damper that only pushes: `k = 60/L_f² N/m` (the home-made
//!   bench's 60 N·m/rad at the tool, [`crate::sim::wrist_bench::FINGER_STIFFNESS`]),
//!   `c = 0.5/L_f² N·s/m`.
//!
//! # The two cases
//! * [`FingerCase::MotorsOff`] (Case 1): no motor torque. The finger's
//!   travel is [`CASE1_TRAVEL`] (25°: 26 N·m of push if the wrist did not
//!   give), so the run finds what the gears hold. The metric is the largest
//!   measured torque `|(τ_δ, τ_γ)|` while both rotors are still within
//!   [`HELD`] of their start (the gear has not slipped).
//! * [`FingerCase::Admittance`] (Case 2): every 4 ms the library's public
//!   wrist step ([`WristStepConfig`]: gauges → `(τ_δ, τ_γ)`, the
//!   mode manager held Passive with the admittance law of eq. 6.32 at the
//!   thesis's `K_c = 0.1`, the inverse kinematics, both motor laws of
//!   eq. 6.15 with [`door_wrist_design`](crate::sim::door::door_wrist_design)). The metric is the peak measured
//!   `|(τ_δ, τ_γ)|`. In the steady push the admittance law moves the
//!   reference at `K_c τ`, so a finger moving at `ẋ_f` rad/s is followed
//!   with `τ ≈ ẋ_f / K_c`: the thesis's "below 2 Nm" needs the finger
//!   slower than about 0.2 rad/s; the seeds draw its speed
//!   ([`FingerPush::peak_speed`]).
//!
//! # Backends
//! The wrist step runs on the backend chosen ([`Backend`],
//! [`engine_finger_push_on`], [`engine_wrist_tracking_on`]): `f32`, as the
//! thesis's DSP would run it and the claims' operating point
//! ([`engine_finger_push`] and [`engine_wrist_tracking`] are these), or
//! `I16F16` fixed point as on a Cortex-M0+ (or `f64`). On the 20 seeds of
//! the claims' sweep, `I16F16`'s Case 2 peaks are within 0.05 N·m of
//! `f32`'s and its Case 1 held torques within 0.02 N·m (the `wrist_bench`
//! example prints both; `tests/engine_wrist_bench.rs` checks the nominal
//! push).
//!
//! # Active tracking
//! [`engine_wrist_tracking`] (§6.4.2, Fig. 6.10): the same wrist step held
//! Active tracks the home-made bench's task trajectory
//! ([`crate::sim::wrist_bench::tracking_trajectory`]); the errors are the
//! mechanism's universal-joint angles against the desired pose, so the
//! library's inverse kinematics, motor laws and 4 ms sampling are checked
//! together on parts that know nothing of them.
//!
//! The norm `|(τ_δ, τ_γ)|` is used (not the larger component, as the door
//! claims do): the finger's direction is drawn, and the norm is the
//! torque the finger puts on the wrist whatever its direction.
//!
//! # Start pose
//! The wrist starts at [`START`] (10° of pitch, set through the library's
//! inverse kinematics, the loop then closed by the engine) and the finger
//! pushes away from the straight pose (`|ψ| ≤ 45°`): the library's
//! kinematics describe one assembly mode of the DAUJ, which meets the other
//! at the straight pose ([`super::door`]).
//!
//! A push through the straight pose is a separate study
//! ([`engine_finger_push_from`]; `--straight` of the `wrist_bench`
//! example): from 3° of pitch, the nominal push toward negative pitch
//! (`ψ = 180°`) peaks at 2.15 N·m in Case 2, against 2.07 N·m for the same
//! push away from it (`ψ = 0`), with travels of 12.1° and 12.2° and a
//! loop-closure error of 1.6e-5 rad. Before the wrist step took the root
//! of eq. (5.13) nearest the previous motor angle (errata E5.5), its
//! references turned by about π where the path crossed the straight pose,
//! and the same push peaked at 12.9 N·m (22.8° of travel, loop error
//! 4e-3 rad).
//!
//! # The engine step
//! `dt = 0.25 ms`, one solver substep ([`super::door::door_engine_settings`]):
//! the fastest explicit mode is the drive spring on a semi-sphere,
//! `√(400/1e-3) = 632 rad/s`, `dt ω = 0.16`. Convergence by halving is
//! checked in `tests/engine_wrist_bench.rs`.

use rapier3d_f64::na::UnitQuaternion;
use rapier3d_f64::prelude::*;

use super::dauj::{
    insert_dauj, DaujJointAngles, DaujOptions, DaujRotors, DaujTool, WorldAxis, WristDrives,
};
use super::door::{
    wrist_step_params, Backend, CONTROL_PERIOD, WRIST_DRIVE, WRIST_RATIO, WRIST_ROTOR,
};
use super::ft_sensor::{GaugeErrors, StrainGaugeSensor, V_REF};
use super::world::{Coord, EngineSettings, World};
use crate::error::ParamError;
use crate::scalar::{Scalar, I16F16};
use crate::sim::{FrictionParams, SplitMix64};
use crate::wrist::ft_sensor::DecouplingMatrix;
use crate::wrist::modes::WristMode;
use crate::wrist::step::{WristReadings, WristStepConfig, WristStepParams, WristTarget};
use crate::wrist::{PitchYaw, WristParams};

/// The start pose `[δ, γ]`, rad (10° of pitch).
pub const START: [f64; 2] = [0.174_532_925_199_432_95, 0.0];
/// The F/T sensor origin along `L2`, m.
pub const SENSOR_OFFSET: f64 = 0.05;
/// Where the finger presses, along `L2`, m.
pub const FINGER_ARM: f64 = 0.2;
/// The finger's stiffness at the tool, N·m/rad (linear `k = 60/L_f²`).
pub const FINGER_STIFFNESS: f64 = 60.0;
const FINGER_DAMPING: f64 = 0.5;
/// The finger's travel in Case 1, rad (25°).
pub const CASE1_TRAVEL: f64 = 0.436_332_312_998_582_4;
/// A rotor within this angle (rad, at the joint) of its start has not
/// slipped: four times the presliding range of the motor friction
/// (`0.1 rad / N`).
pub const HELD: f64 = 7.5e-4;
/// Time the wrist settles in Active mode before the finger comes, s.
const PRE: f64 = 0.3;
/// Time the finger stays pressed between its push and its return, s.
const DWELL: f64 = 0.5;
const TOOL_MASS: f64 = 0.3;
const TOOL_INERTIA: f64 = 5e-4;

/// What drives the wrist while the finger pushes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FingerCase {
    /// Case 1: the motors are off (zero torque); the gears' friction holds.
    MotorsOff,
    /// Case 2: the library's wrist step in the admittance-passive mode.
    Admittance,
}

/// One finger push and the gear friction of a run (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FingerPush {
    /// Direction `ψ` of the push, rad, in `[−π, π]`: from `+x` (pitch
    /// `δ` increasing) toward `−y` (yaw `γ` increasing). The claims' sweep
    /// stays in `[−π/4, π/4]`, away from the straight pose.
    pub direction: f64,
    /// How far the fingertip moves, as an angle at the tool, rad, in
    /// `(0, 0.5]` (Case 1 uses [`CASE1_TRAVEL`] instead).
    pub travel: f64,
    /// Time of the push (and of the return), s, in `[0.5, 5]`.
    pub rise: f64,
    /// The gear's break-away at the joint, N·m, in `(0, 30]`.
    pub breakaway: f64,
    /// The seed of the sensor's calibration error and noise.
    pub seed: u64,
}

impl FingerPush {
    /// The home-made bench's push ([`crate::sim::wrist_bench`]): pure
    /// pitch, 12° over 1.5 s, a 12 N·m break-away.
    pub fn nominal(seed: u64) -> Self {
        FingerPush {
            direction: 0.0,
            travel: 0.2094,
            rise: 1.5,
            breakaway: 12.0,
            seed,
        }
    }

    /// A push drawn uniformly from the sweep's ranges: direction −45°…45°
    /// (away from the straight pose), travel 10°–14°, rise 1.25–2.5 s (a
    /// peak fingertip speed of 0.10–0.29 rad/s at the tool), break-away
    /// 11–13 N·m (module docs). The thesis states none of them.
    pub fn draw(seed: u64) -> Self {
        let mut rng = SplitMix64::new(seed ^ 0xF1A6_E200_0000_0643);
        let mut u = |a: f64, b: f64| a + (b - a) * rng.uniform();
        FingerPush {
            direction: u(-45.0, 45.0).to_radians(),
            travel: u(10.0, 14.0).to_radians(),
            rise: u(1.25, 2.5),
            breakaway: u(11.0, 13.0),
            seed,
        }
    }

    /// The fingertip's peak speed as a rotation at the tool, rad/s
    /// (`π · travel / (2 · rise)`).
    pub fn peak_speed(&self) -> f64 {
        core::f64::consts::PI * self.travel / (2.0 * self.rise)
    }

    fn validate(&self) -> Result<(), ParamError> {
        let pi = core::f64::consts::PI;
        crate::error::in_range("finger.direction", self.direction, -pi, pi)?;
        crate::error::in_range("finger.travel", self.travel, 1e-6, 0.5)?;
        crate::error::in_range("finger.rise", self.rise, 0.5, 5.0)?;
        crate::error::in_range("finger.breakaway", self.breakaway, 1e-6, 30.0)?;
        Ok(())
    }
}

/// One 4 ms sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristBenchSample {
    /// Time from the finger's touch, s.
    pub time: f64,
    /// Pose `[δ, γ]` of the mechanism's universal joint, rad.
    pub pose: [f64; 2],
    /// `(τ_δ, τ_γ)` the library's step read from the gauges, N·m (in Case 1
    /// the same F/T chain is read with the motors off).
    pub measured: [f64; 2],
    /// `(τ_δ, τ_γ)` the finger puts on the wrist about its pitch and yaw
    /// axes (engine, noise-free), N·m.
    pub interaction: [f64; 2],
    /// Motor torques commanded, N·m (motor side; zero in Case 1).
    pub motor_torque: [f64; 2],
    /// Rotor slip `|q_m/N − q_m0/N|`, larger of the two, rad.
    pub slip: f64,
}

/// The result of a bench run.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineWristBenchRun {
    /// Samples at 4 ms from the touch.
    pub samples: Vec<WristBenchSample>,
    /// Peak measured `|(τ_δ, τ_γ)|`, N·m.
    pub peak_measured: f64,
    /// Peak true `|(τ_δ, τ_γ)|`, N·m.
    pub peak_interaction: f64,
    /// Peak measured `|(τ_δ, τ_γ)|` while both rotors are within [`HELD`]
    /// of their start, N·m.
    pub held: f64,
    /// Largest distance `|(δ, γ) − (δ₀, γ₀)|` from the start pose, rad.
    pub travel: f64,
    /// Largest rotor slip (joint side), rad.
    pub slip: f64,
    /// Largest loop-closure error of the DAUJ, rad.
    pub loop_error: f64,
    /// Ticks (Case 2) whose step left the Passive mode after the touch.
    pub off_mode_ticks: usize,
}

struct Scene {
    world: World,
    output: RigidBodyHandle,
    tool: RigidBodyHandle,
    joint: [Coord; 2],
    motor: [Coord; 2],
    pitch: Coord,
    yaw: Coord,
}

fn build(start: PitchYaw<f64>, settings: &EngineSettings) -> Result<Scene, ParamError> {
    let mut world = World::new(settings);
    let ground = world.base();
    // The wrist on the ground, its frame the world's; the start pose from
    // the library's inverse kinematics (branch θ4 ≥ 0), the rotors at N
    // times their joints; the engine closes the loop from there.
    let wrist = insert_dauj(
        &mut world,
        ground,
        Vector::zeros(),
        (WorldAxis::X, WorldAxis::Y),
        &DaujOptions {
            kinematics: WristParams::thesis(),
            rotors: Some(DaujRotors {
                ratio: WRIST_RATIO,
                mass: 0.05,
                inertia: [1e-5, 1e-5, WRIST_ROTOR],
            }),
            tool: Some(DaujTool {
                mount: SENSOR_OFFSET,
                com: 0.5 * (FINGER_ARM - SENSOR_OFFSET),
                mass: TOOL_MASS,
                inertia: TOOL_INERTIA,
            }),
            start: Some(DaujJointAngles::from_pose(&WristParams::thesis(), start)),
            undamped: true,
        },
    )?;
    let fail = |name| ParamError::NotFinite {
        name,
        value: f64::NAN,
    };
    Ok(Scene {
        world,
        output: wrist.output,
        tool: wrist.tool.ok_or(fail("tool"))?,
        joint: wrist.joints(),
        motor: wrist.motors().ok_or(fail("rotors"))?,
        pitch: wrist.pitch(),
        yaw: wrist.yaw(),
    })
}

/// The library's wrist step of the bench: the door's ([`super::door::door_wrist_step`])
/// with the admittance validated for the finger's stiffness (the thesis's
/// `K_c = 0.1`) and the sensor at [`SENSOR_OFFSET`].
pub fn bench_wrist_step() -> Result<WristStepParams, ParamError> {
    wrist_step_params(2.0 * FINGER_STIFFNESS, SENSOR_OFFSET, WristMode::Active)
}

/// The fingertip's position along `n` from its touch (m) and its speed
/// (m/s) at `t` s after the touch.
fn finger_path(push: &FingerPush, travel: f64, t: f64) -> (f64, f64) {
    let a = FINGER_ARM * travel;
    let r = push.rise;
    let w = core::f64::consts::PI / r;
    let ramp = |u: f64| (0.5 * a * (1.0 - (w * u).cos()), 0.5 * a * w * (w * u).sin());
    if t <= 0.0 {
        (0.0, 0.0)
    } else if t < r {
        ramp(t)
    } else if t < r + DWELL {
        (a, 0.0)
    } else if t < 2.0 * r + DWELL {
        let (p, v) = ramp(t - r - DWELL);
        (a - p, -v)
    } else {
        (0.0, 0.0)
    }
}

/// Runs one push on the engine from [`START`] with the wrist step on
/// `f32` (the thesis's DSP; the claims' operating point):
/// [`engine_finger_push_on`] with [`Backend::F32`].
pub fn engine_finger_push(
    case: FingerCase,
    push: &FingerPush,
    engine: &EngineSettings,
) -> Result<EngineWristBenchRun, ParamError> {
    engine_finger_push_on(case, push, engine, Backend::F32)
}

/// Runs one push on the engine from [`START`] with the library's wrist
/// step on `backend`. Errors: a `push` field outside its range (named
/// `finger.<field>`); an engine step that does not divide the 4 ms period
/// (named `dt`) or under which the state diverges.
pub fn engine_finger_push_on(
    case: FingerCase,
    push: &FingerPush,
    engine: &EngineSettings,
    backend: Backend,
) -> Result<EngineWristBenchRun, ParamError> {
    engine_finger_push_from(case, push, START[0], engine, backend)
}

/// [`engine_finger_push_on`] from the pose `(start_pitch, 0)` (rad, within
/// ±20°, named `start_pitch`): the study of a push through the straight
/// pose (module docs, "Start pose"). A start of exactly 0 is not the
/// straight pose's own assembly; use a few degrees.
pub fn engine_finger_push_from(
    case: FingerCase,
    push: &FingerPush,
    start_pitch: f64,
    engine: &EngineSettings,
    backend: Backend,
) -> Result<EngineWristBenchRun, ParamError> {
    push.validate()?;
    let limit = 20f64.to_radians();
    let start_pitch = crate::error::in_range("start_pitch", start_pitch, -limit, limit)?;
    match backend {
        Backend::F32 => push_run::<f32>(case, push, start_pitch, engine),
        Backend::F64 => push_run::<f64>(case, push, start_pitch, engine),
        Backend::I16F16 => push_run::<I16F16>(case, push, start_pitch, engine),
    }
}

/// Engine steps per 4 ms control tick; an error (named `dt`) if the engine
/// step does not divide the tick.
fn steps_per_tick(engine: &EngineSettings) -> Result<usize, ParamError> {
    let dt = engine.dt();
    let per_tick = (CONTROL_PERIOD / dt).round();
    if per_tick < 1.0 || (per_tick * dt - CONTROL_PERIOD).abs() > 1e-12 {
        return Err(ParamError::OutOfRange {
            name: "dt",
            value: dt,
            min: 1e-6,
            max: CONTROL_PERIOD,
        });
    }
    Ok(per_tick as usize)
}

/// The motor friction of a gear whose break-away at the joint is
/// `breakaway` N·m: two thirds of it Coulomb, at the motor (`/N`), with
/// presliding (module docs).
fn gear_friction(breakaway: f64) -> FrictionParams {
    let b = breakaway / WRIST_RATIO;
    FrictionParams {
        coulomb: b * 2.0 / 3.0,
        static_excess: b / 3.0,
        stribeck: 1e-3,
        viscous: 2e-6,
        presliding: 0.1,
        presliding_damping: 0.0,
    }
}

/// The strain gauges: off the certificate by ±2 % and 0.3 mV of noise,
/// drawn from `seed`.
fn bench_gauges(seed: u64) -> Result<StrainGaugeSensor, ParamError> {
    StrainGaugeSensor::try_new(
        DecouplingMatrix::example().matrix(),
        GaugeErrors::try_new(0.02, 0.0, 3e-4, seed)?,
    )
}

fn push_run<S: Scalar>(
    case: FingerCase,
    push: &FingerPush,
    start_pitch: f64,
    engine: &EngineSettings,
) -> Result<EngineWristBenchRun, ParamError> {
    let home = [start_pitch, 0.0];
    let dt = engine.dt();
    let per_tick = steps_per_tick(engine)?;
    let travel = match case {
        FingerCase::MotorsOff => CASE1_TRAVEL,
        FingerCase::Admittance => push.travel,
    };
    let start = PitchYaw {
        delta: home[0],
        gamma: home[1],
    };
    let mut sc = build(start, engine)?;
    let n = Vector::new(push.direction.cos(), -push.direction.sin(), 0.0);
    let (kf, cf) = (
        FINGER_STIFFNESS / (FINGER_ARM * FINGER_ARM),
        FINGER_DAMPING / (FINGER_ARM * FINGER_ARM),
    );
    let friction = gear_friction(push.breakaway);
    let mut gauges = bench_gauges(push.seed ^ 0x5E45_0000)?;
    let params = bench_wrist_step()?;
    let step = WristStepConfig::<S>::new(&params);
    let q0 = [0, 1].map(|i| sc.joint[i].angle(&sc.world.bodies, 0.0));
    let mut state = step.state(WristReadings::<S>::from_si([0.0; 6], q0, [0.0; 2]).motors);
    let count = core::f64::consts::TAU / 2000.0;
    let quant = |x: f64| (x / count).round() * count;
    // Joint and rotor angles (unwrapping memory), friction anchors.
    let mut drives = WristDrives::new(sc.joint, sc.motor, WRIST_RATIO, WRIST_DRIVE, friction, q0);
    let rotor0 = q0;
    let mut last_enc = q0;
    let mut wrench = [0.0f64; 6];
    let mut true_tau = [0.0f64; 2];
    let mut touch: Option<f64> = None;
    let mut out = EngineWristBenchRun {
        samples: Vec::new(),
        peak_measured: 0.0,
        peak_interaction: 0.0,
        held: 0.0,
        travel: 0.0,
        slip: 0.0,
        loop_error: 0.0,
        off_mode_ticks: 0,
    };
    let pre = (PRE / CONTROL_PERIOD).round() as usize;
    let ticks = ((2.0 * push.rise + DWELL + 0.5) / CONTROL_PERIOD).round() as usize;
    let mut held = true;
    for k in 0..pre + ticks {
        let time = (k as f64 - pre as f64) * CONTROL_PERIOD;
        let b = &sc.world.bodies;
        let enc = [0, 1].map(|i| quant(drives.rotor_angle(b, i)) / WRIST_RATIO);
        let enc_v = [0, 1].map(|i| (enc[i] - last_enc[i]) / CONTROL_PERIOD);
        last_enc = enc;
        let sg = gauges.read(&wrench).map(|v| v - V_REF);
        let request = if k < pre {
            WristMode::Active
        } else {
            WristMode::Passive
        };
        let target = WristTarget::<S>::from_si(home[0], home[1], 0.0, 0.0).with_request(request);
        let o = step.update(
            &mut state,
            &WristReadings::<S>::from_si(sg, enc, enc_v),
            &target,
        );
        let measured = o.interaction_si();
        let motor = match case {
            FingerCase::MotorsOff => [0.0; 2],
            FingerCase::Admittance => {
                if k >= pre && o.mode != WristMode::Passive {
                    out.off_mode_ticks += 1;
                }
                o.motor_torque_si()
            }
        };
        if k >= pre {
            let b = &sc.world.bodies;
            let pose = [sc.pitch.angle(b, 0.0), sc.yaw.angle(b, 0.0)];
            let slip = [0, 1]
                .map(|i| (drives.rotor_angles()[i] / WRIST_RATIO - rotor0[i]).abs())
                .into_iter()
                .fold(0.0, f64::max);
            let m = measured[0].hypot(measured[1]);
            held &= slip < HELD;
            if held {
                out.held = out.held.max(m);
            }
            out.peak_measured = out.peak_measured.max(m);
            out.peak_interaction = out.peak_interaction.max(true_tau[0].hypot(true_tau[1]));
            out.travel = out.travel.max((pose[0] - home[0]).hypot(pose[1] - home[1]));
            out.slip = out.slip.max(slip);
            out.loop_error = out.loop_error.max(loop_error(&sc, pose));
            out.samples.push(WristBenchSample {
                time,
                pose,
                measured,
                interaction: true_tau,
                motor_torque: motor,
                slip,
            });
        }
        let finger = Finger {
            push,
            travel,
            k: kf,
            c: cf,
            n,
        };
        let tick = Tick { time, dt, per_tick };
        wrench = run_tick(
            &mut sc,
            &mut drives,
            &tick,
            motor,
            Some((&finger, &mut touch)),
            &mut true_tau,
        )?;
    }
    Ok(out)
}

/// The finger of a push: its path's `push` and `travel` (rad at the tool),
/// the contact's `k` (N/m) and `c` (N·s/m), and its direction `n` (world).
struct Finger<'a> {
    push: &'a FingerPush,
    travel: f64,
    k: f64,
    c: f64,
    n: Vector<Real>,
}

/// A control tick's engine steps: from `time` (s from the touch), `dt`
/// (s) each, `per_tick` of them.
struct Tick {
    time: f64,
    dt: f64,
    per_tick: usize,
}

/// The engine steps of one control tick, with the finger (and the memory
/// of its touch) if it pushes; returns the sensor wrench averaged over the
/// tick (the gauge amplifiers' anti-aliasing filter, as in the door scene).
fn run_tick(
    sc: &mut Scene,
    drives: &mut WristDrives,
    tick: &Tick,
    motor: [f64; 2],
    mut finger: Option<(&Finger<'_>, &mut Option<f64>)>,
    true_tau: &mut [f64; 2],
) -> Result<[f64; 6], ParamError> {
    let dt = tick.dt;
    let mut sum = [0.0; 6];
    for s in 0..tick.per_tick {
        let t = tick.time + s as f64 * dt;
        let now = match finger.as_mut() {
            Some((f, touch)) if t >= 0.0 => {
                let (p, v) = finger_path(f.push, f.travel, t);
                Some((p, v, f.k, f.c, f.n, &mut **touch))
            }
            _ => None,
        };
        let w = step_engine(sc, dt, drives, motor, now, true_tau).ok_or(ParamError::NotFinite {
            name: "dt (the engine state diverged: the step is too coarse for the drive springs)",
            value: dt,
        })?;
        for (a, b) in sum.iter_mut().zip(w) {
            *a += b;
        }
    }
    Ok(sum.map(|x| x / tick.per_tick as f64))
}

/// The angle (rad) between `L2`'s orientation and the one the universal
/// joint's `(δ, γ)` give it.
fn loop_error(sc: &Scene, pose: [f64; 2]) -> f64 {
    let r = *sc.world.bodies[sc.output].rotation();
    let uj = UnitQuaternion::from_axis_angle(&Vector::y_axis(), pose[0])
        * UnitQuaternion::from_axis_angle(&Vector::x_axis(), pose[1]);
    r.angle_to(&uj)
}

/// The finger of one engine step: its position along `n` from the touch
/// (m), its speed (m/s), `k`, `c`, `n`, and the touch's memory.
type FingerNow<'a> = Option<(f64, f64, f64, f64, Vector<Real>, &'a mut Option<f64>)>;

/// One engine step; returns the sensor wrench over it (sensor frame).
#[allow(clippy::too_many_arguments)]
fn step_engine(
    sc: &mut Scene,
    dt: f64,
    drives: &mut WristDrives,
    motor: [f64; 2],
    finger: FingerNow<'_>,
    true_tau: &mut [f64; 2],
) -> Option<[f64; 6]> {
    if !sc.world.is_finite() {
        return None;
    }
    sc.world.clear_forces();
    let bodies = &mut sc.world.bodies;
    drives.push(bodies, motor);
    // The finger at the tool point.
    let t = &bodies[sc.tool];
    let tip = t.position() * Point::new(0.0, 0.0, FINGER_ARM - SENSOR_OFFSET);
    let force = match finger {
        Some((p, v, k, c, n, touch)) => {
            let s0 = *touch.get_or_insert(n.dot(&tip.coords));
            let vt = t.velocity_at_point(&tip);
            let f = k * (s0 + p - n.dot(&tip.coords)) + c * (v - n.dot(&vt));
            n * f.max(0.0)
        }
        None => Vector::zeros(),
    };
    let moment = tip.coords.cross(&force);
    *true_tau = [
        moment.dot(&sc.pitch.world_axis(bodies)),
        moment.dot(&sc.yaw.world_axis(bodies)),
    ];
    let o = &bodies[sc.output];
    let origin = (o.position() * Point::new(0.0, 0.0, SENSOR_OFFSET)).coords;
    let frame = o.rotation()
        * UnitQuaternion::from_axis_angle(&Vector::z_axis(), core::f64::consts::FRAC_PI_2);
    let t = &bodies[sc.tool];
    let (v0, w0, com) = (*t.linvel(), *t.angvel(), t.center_of_mass().coords);
    bodies[sc.tool].add_force_at_point(force, tip, true);
    sc.world.step();
    let bodies = &sc.world.bodies;
    drives.advance(bodies);
    // Momentum balance of the tool (as the door scene's sensor).
    let t = &bodies[sc.tool];
    let alpha = (t.angvel() - w0) / dt;
    let f_joint = TOOL_MASS * (t.linvel() - v0) / dt - force;
    let m_joint = TOOL_INERTIA * alpha - (tip.coords - com).cross(&force);
    let f_s = -f_joint;
    let m_s = -(m_joint + (com - origin).cross(&f_joint));
    let f = frame.inverse() * f_s;
    let m = frame.inverse() * m_s;
    Some([f.x, f.y, f.z, m.x, m.y, m.z])
}

/// The result of [`engine_wrist_tracking`].
#[derive(Debug, Clone, PartialEq)]
pub struct EngineTrackingRun {
    /// Per 4 ms sample: time (s), desired `[δ_d, γ_d]` and the mechanism's
    /// `[δ, γ]` (rad).
    pub samples: Vec<(f64, [f64; 2], [f64; 2])>,
    /// Largest `|δ − δ_d|`, `|γ − γ_d|` after the settling time, rad.
    pub max_error: [f64; 2],
    /// RMS of `δ − δ_d`, `γ − γ_d` after the settling time, rad.
    pub rms_error: [f64; 2],
    /// Largest loop-closure error of the DAUJ, rad.
    pub loop_error: f64,
    /// Ticks whose step left the Active mode.
    pub off_mode_ticks: usize,
}

/// §6.4.2 (Fig. 6.10–6.11) on the engine with the wrist step on `f32`:
/// [`engine_wrist_tracking_on`] with [`Backend::F32`].
pub fn engine_wrist_tracking(
    duration: f64,
    settle: f64,
    engine: &EngineSettings,
) -> Result<EngineTrackingRun, ParamError> {
    engine_wrist_tracking_on(duration, settle, engine, Backend::F32)
}

/// §6.4.2 (Fig. 6.10–6.11) on the engine: the library's wrist step on
/// `backend`, held Active, tracks [`crate::sim::wrist_bench::tracking_trajectory`]
/// (the home-made bench's: a bend of 12°–24° swinging from pitch through
/// yaw; its rate by central differences, 1 ms) for `duration` s on the
/// nominal gears (12 N·m break-away), starting at rest at its first pose;
/// errors are those of the mechanism's universal joint, counted after
/// `settle` s. Errors: `duration` or `settle` not finite or out of
/// `[0, 60]` s (named), an engine step that does not divide 4 ms (`dt`) or
/// under which the state diverges.
pub fn engine_wrist_tracking_on(
    duration: f64,
    settle: f64,
    engine: &EngineSettings,
    backend: Backend,
) -> Result<EngineTrackingRun, ParamError> {
    let duration = crate::error::in_range("duration", duration, 0.0, 60.0)?;
    let settle = crate::error::in_range("settle", settle, 0.0, 60.0)?;
    match backend {
        Backend::F32 => tracking_run::<f32>(duration, settle, engine),
        Backend::F64 => tracking_run::<f64>(duration, settle, engine),
        Backend::I16F16 => tracking_run::<I16F16>(duration, settle, engine),
    }
}

fn tracking_run<S: Scalar>(
    duration: f64,
    settle: f64,
    engine: &EngineSettings,
) -> Result<EngineTrackingRun, ParamError> {
    use crate::sim::wrist_bench::tracking_trajectory;
    let dt = engine.dt();
    let per_tick = steps_per_tick(engine)?;
    let x0 = tracking_trajectory(0.0);
    let mut sc = build(
        PitchYaw {
            delta: x0[0],
            gamma: x0[1],
        },
        engine,
    )?;
    let friction = gear_friction(12.0);
    let mut gauges = bench_gauges(0x5E45_0001)?;
    let params = bench_wrist_step()?;
    let step = WristStepConfig::<S>::new(&params);
    let q0 = [0, 1].map(|i| sc.joint[i].angle(&sc.world.bodies, 0.0));
    let mut state = step.state(WristReadings::<S>::from_si([0.0; 6], q0, [0.0; 2]).motors);
    let count = core::f64::consts::TAU / 2000.0;
    let quant = |x: f64| (x / count).round() * count;
    let mut drives = WristDrives::new(sc.joint, sc.motor, WRIST_RATIO, WRIST_DRIVE, friction, q0);
    let mut last_enc = q0;
    let mut wrench = [0.0f64; 6];
    let mut true_tau = [0.0f64; 2];
    let mut out = EngineTrackingRun {
        samples: Vec::new(),
        max_error: [0.0; 2],
        rms_error: [0.0; 2],
        loop_error: 0.0,
        off_mode_ticks: 0,
    };
    let mut sum_sq = [0.0f64; 2];
    let mut counted = 0usize;
    let h = 1e-3;
    for k in 0..(duration / CONTROL_PERIOD).round() as usize {
        let time = k as f64 * CONTROL_PERIOD;
        let b = &sc.world.bodies;
        let enc = [0, 1].map(|i| quant(drives.rotor_angle(b, i)) / WRIST_RATIO);
        let enc_v = [0, 1].map(|i| (enc[i] - last_enc[i]) / CONTROL_PERIOD);
        last_enc = enc;
        let pose = [sc.pitch.angle(b, 0.0), sc.yaw.angle(b, 0.0)];
        let sg = gauges.read(&wrench).map(|v| v - V_REF);
        let xd = tracking_trajectory(time);
        let (xp, xm) = (tracking_trajectory(time + h), tracking_trajectory(time - h));
        let rate = [0, 1].map(|i| (xp[i] - xm[i]) / (2.0 * h));
        let target = WristTarget::<S>::from_si(xd[0], xd[1], rate[0], rate[1])
            .with_request(WristMode::Active);
        let o = step.update(
            &mut state,
            &WristReadings::<S>::from_si(sg, enc, enc_v),
            &target,
        );
        out.off_mode_ticks += (o.mode != WristMode::Active) as usize;
        let motor = o.motor_torque_si();
        if time >= settle {
            for i in 0..2 {
                let e = pose[i] - xd[i];
                out.max_error[i] = out.max_error[i].max(e.abs());
                sum_sq[i] += e * e;
            }
            counted += 1;
        }
        out.loop_error = out.loop_error.max(loop_error(&sc, pose));
        out.samples.push((time, xd, pose));
        let tick = Tick { time, dt, per_tick };
        wrench = run_tick(&mut sc, &mut drives, &tick, motor, None, &mut true_tau)?;
    }
    if counted > 0 {
        out.rms_error = sum_sq.map(|s| (s / counted as f64).sqrt());
    }
    Ok(out)
}
