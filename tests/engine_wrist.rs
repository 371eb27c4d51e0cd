//! The library's wrist (thesis ch. 5–6) against the DAUJ built from its
//! parts on the rapier3d engine (`sim::engine`), over the whole reachable
//! workspace.
//!
//! Criteria, fixed before the first run (angles in rad, torques in N·m):
//! * (a) forward kinematics — over a 24 × 24 grid of the motor torus
//!   (`θ1, θ3` every 15°, which covers every reachable pose), the angle
//!   between the engine's output orientation and `R_y(δ) R_x(γ)` of the
//!   library's `forward` at the engine's own motor angles is ≤ 1e-4, and the
//!   engine's `θ4`, `δ`, `γ` agree with the library's to 1e-4;
//! * (b) inverse kinematics — over a 25 × 25 grid of `(δ, γ)` in
//!   `[−2φ, 2φ]²` (the reachable points, bend ≤ 2φ), the motor angles of the
//!   library's `IkState` driven into the mechanism reach the requested
//!   orientation to 1e-4;
//! * (c) force mapping — at 12 × 12 motor poses, each with its own wrench on
//!   the tool (force ≤ 20 N at 6 cm, couple ≤ 0.5 N·m), the motor torques
//!   the engine needs to hold it agree with `−Jᵀ (τ_δ, τ_γ)` of the
//!   library's exact `ForceMapping` (eq. 5.28, 6.1) to 1e-3 N·m, where
//!   `(τ_δ, τ_γ)` is the wrench's moment about the wrist centre projected by
//!   hand on the pitch axis (base `y`) and the yaw axis (`R_y(δ) x`);
//! * (d) the inner universal joint — bent by 0°…32° (the wrist's bends) and
//!   turned every 22.5°, the engine's `θ2(θ3)` agrees with eq. (5.1) of
//!   `ujoint::transmit` to 1e-4, and the torque motor 2 needs to hold a load
//!   on the driven shaft with its eq. (5.3) factor to 1e-3 relative;
//! * convergence — the same checks at half the step move the engine's
//!   answers by less than the bounds above.
//!
//! Run with `cargo test --features engine --test engine_wrist -- --nocapture`
//! to print the measured maxima.

use std::f64::consts::PI;

use mrr_control::sim::engine::{DaujMechanism, EngineSettings, UniversalJointBench};
use mrr_control::sim::SplitMix64;
use mrr_control::wrist::ujoint::transmit;
use mrr_control::wrist::{
    ForceMapping, IkState, JacobianKind, MotorAngles, PitchYaw, WristConfig, WristParams,
};
use nalgebra::{UnitQuaternion, Vector3};

/// Tool point distance along the output axis (m).
const TOOL: f64 = 0.06;

/// A pose is read when every body turns slower than this (rad/s).
const SPEED_TOL: f64 = 1e-6;

/// Ramp time (s) for a motor move of `jump` rad: at most 3 rad/s.
fn ramp_for(jump: f64) -> f64 {
    (jump / 3.0).max(0.05)
}

/// Eq. (5.6), written here: pitch about the base `y`, then yaw about the
/// new `x`.
fn pose_rotation(delta: f64, gamma: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::y_axis(), delta)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), gamma)
}

fn wrap(x: f64) -> f64 {
    x - 2.0 * PI * (x / (2.0 * PI)).round()
}

/// The `n × n` motor grid in serpentine order (neighbours one step apart).
fn motor_grid(n: usize) -> Vec<(f64, f64)> {
    let step = 2.0 * PI / n as f64;
    let mut v = Vec::new();
    for i in 0..n {
        let t1 = -PI + (i as f64 + 0.5) * step;
        for j in 0..n {
            let jj = if i % 2 == 0 { j } else { n - 1 - j };
            v.push((t1, -PI + (jj as f64 + 0.5) * step));
        }
    }
    v
}

#[derive(Debug, Default, Clone, Copy)]
struct FkErrors {
    orientation: f64,
    theta4: f64,
    pitch_yaw: f64,
    loop_error: f64,
    speed: f64,
    /// Smallest distance to the rejected root of eq. (5.10).
    other_root: f64,
}

fn fk_sweep(settings: EngineSettings, n: usize) -> (FkErrors, Vec<[f64; 3]>) {
    let p = WristParams::thesis();
    let cfg = WristConfig::<f64>::new(&p);
    let mut m = DaujMechanism::try_new(&p, TOOL, settings).unwrap();
    let mut e = FkErrors {
        other_root: f64::MAX,
        ..FkErrors::default()
    };
    let mut first = true;
    let mut samples = Vec::new();
    for (t1, t3) in motor_grid(n) {
        let ramp = if first { 0.5 } else { 0.05 };
        first = false;
        m.move_to(t1, t3, ramp);
        let speed = m.settle(SPEED_TOL, 0.02, 1.0);
        let a = m.angles();
        let f = cfg.forward(MotorAngles {
            theta1: a.theta1,
            theta3: a.theta3,
        });
        let lib = pose_rotation(f.pose.delta, f.pose.gamma);
        e.orientation = e.orientation.max(m.output_rotation().angle_to(&lib));
        e.theta4 = e.theta4.max(wrap(a.theta4 - f.theta4).abs());
        e.pitch_yaw = e
            .pitch_yaw
            .max((a.delta - f.pose.delta).abs())
            .max((a.gamma - f.pose.gamma).abs());
        e.loop_error = e.loop_error.max(a.loop_error);
        e.speed = e.speed.max(speed);
        let g = cfg.forward_plus_root(MotorAngles {
            theta1: a.theta1,
            theta3: a.theta3,
        });
        let other = pose_rotation(g.pose.delta, g.pose.gamma);
        e.other_root = e.other_root.min(m.output_rotation().angle_to(&other));
        samples.push([a.theta4, a.delta, a.gamma]);
    }
    (e, samples)
}

#[test]
fn forward_kinematics_matches_the_mechanism() {
    let (e, _) = fk_sweep(EngineSettings::default(), 24);
    println!("(a) FK, 24 x 24 motor grid, dt = 1 ms: {e:?}");
    assert!(e.orientation <= 1e-4, "{e:?}");
    assert!(e.theta4 <= 1e-4 && e.pitch_yaw <= 1e-4, "{e:?}");
    // The check tells the roots apart: the rejected one is far everywhere.
    assert!(e.other_root > 0.5, "{e:?}");
}

#[test]
fn inverse_kinematics_reference_is_reached_by_the_mechanism() {
    let p = WristParams::thesis();
    let cfg = WristConfig::<f64>::new(&p);
    let mut m = DaujMechanism::try_new(&p, TOOL, EngineSettings::default()).unwrap();
    let mut ik = IkState::new(MotorAngles {
        theta1: 0.0,
        theta3: 0.0,
    });
    let n = 25;
    let lim = 2.0 * p.phi();
    let (mut worst, mut count, mut speed) = (0.0f64, 0, 0.0f64);
    for i in 0..n {
        let delta = -lim + 2.0 * lim * i as f64 / (n - 1) as f64;
        for j in 0..n {
            let jj = if i % 2 == 0 { j } else { n - 1 - j };
            let gamma = -lim + 2.0 * lim * jj as f64 / (n - 1) as f64;
            if !p.is_reachable(delta, gamma) {
                continue;
            }
            let inv = cfg.update(&mut ik, PitchYaw { delta, gamma });
            let [a1, a3] = m.targets();
            let jump = (inv.motors.theta1 - a1)
                .abs()
                .max((inv.motors.theta3 - a3).abs());
            m.move_to(inv.motors.theta1, inv.motors.theta3, ramp_for(jump));
            speed = speed.max(m.settle(SPEED_TOL, 0.02, 1.0));
            let err = m.output_rotation().angle_to(&pose_rotation(delta, gamma));
            worst = worst.max(err);
            count += 1;
        }
    }
    println!(
        "(b) IK reference, {count} reachable poses of a {n} x {n} grid of [-2phi, 2phi]^2, dt = 1 ms: \
         max orientation error {worst:.3e} rad, max residual speed {speed:.2e} rad/s"
    );
    assert!(count > 300);
    assert!(worst <= 1e-4, "{worst}");
}

/// One pose of the force check: the engine's holding torques and the
/// library's, at the engine's pose.
#[derive(Debug, Clone, Copy)]
struct HoldSample {
    engine: [f64; 2],
    exact: [f64; 2],
    thesis: [f64; 2],
}

fn hold_sweep(settings: EngineSettings, n: usize, seed: u64) -> Vec<HoldSample> {
    let p = WristParams::thesis();
    let exact = ForceMapping::<f64>::new(&p, JacobianKind::Exact);
    let thesis = ForceMapping::<f64>::new(&p, JacobianKind::Thesis);
    let mut m = DaujMechanism::try_new(&p, TOOL, settings).unwrap();
    let mut rng = SplitMix64::new(seed);
    let mut out = Vec::new();
    let mut first = true;
    for (t1, t3) in motor_grid(n) {
        let ramp = if first { 0.5 } else { 0.05 };
        first = false;
        m.set_tool_wrench([0.0; 3], [0.0; 3]);
        m.move_to(t1, t3, ramp);
        let mut u = || 2.0 * rng.uniform() - 1.0;
        let force = [20.0 * u(), 20.0 * u(), 20.0 * u()];
        let couple = [0.5 * u(), 0.5 * u(), 0.5 * u()];
        m.set_tool_wrench(force, couple);
        m.settle(SPEED_TOL, 0.05, 1.0);
        let a = m.angles();
        // Moment about the wrist centre (the origin), then its projections
        // on the pitch axis (base y) and the yaw axis (R_y(delta) x): the
        // generalized forces of delta and gamma by virtual work.
        let tool = Vector3::from(m.tool_point());
        let moment = Vector3::from(couple) + tool.cross(&Vector3::from(force));
        let yaw_axis = Vector3::new(a.delta.cos(), 0.0, -a.delta.sin());
        let task = [moment.y, moment.dot(&yaw_axis)];
        let motors = MotorAngles {
            theta1: a.theta1,
            theta3: a.theta3,
        };
        let e = exact.motor_torques(motors, task).torque;
        let t = thesis.motor_torques(motors, task).torque;
        out.push(HoldSample {
            engine: m.motor_torques(),
            exact: [-e[0], -e[1]],
            thesis: [-t[0], -t[1]],
        });
    }
    out
}

#[test]
fn holding_torques_match_the_force_mapping() {
    let samples = hold_sweep(EngineSettings::default(), 12, 37);
    let (mut worst, mut worst_thesis, mut largest) = (0.0f64, 0.0f64, 0.0f64);
    for s in &samples {
        for i in 0..2 {
            worst = worst.max((s.engine[i] - s.exact[i]).abs());
            worst_thesis = worst_thesis.max((s.engine[i] - s.thesis[i]).abs());
            largest = largest.max(s.engine[i].abs());
        }
    }
    println!(
        "(c) holding torques, 12 x 12 motor poses, dt = 1 ms: max |engine - (-J^T tau)| = {worst:.3e} N m \
         (exact J), {worst_thesis:.3e} N m (thesis chain J2 Jc); largest motor torque {largest:.3} N m"
    );
    assert!(largest > 0.3, "the wrenches load the motors: {largest}");
    assert!(worst <= 1e-3, "{worst}");
    // The check can tell Jacobians apart: the corrected thesis chain J2 Jc
    // (E5.10) misses the mechanism by more than the bound.
    assert!(worst_thesis > 1e-3, "{worst_thesis}");
}

#[test]
fn motor_2_torque_through_the_universal_joint() {
    let settings = EngineSettings::default();
    let load = 0.5;
    let (mut angle_err, mut torque_err, mut fmin, mut fmax) = (0.0f64, 0.0f64, f64::MAX, 0.0f64);
    // Motor 2 given the θ3 torque itself, as eq. (6.1) prints it (E6.6).
    let mut printed_err = 0.0f64;
    for bend_deg in [0.0, 8.0, 16.0, 24.0, 32.0] {
        let bend = f64::to_radians(bend_deg);
        let mut b = UniversalJointBench::try_new(bend, settings).unwrap();
        for i in 1..=16 {
            let theta2 = f64::to_radians(22.5 * i as f64);
            b.set_load(0.0);
            b.move_and_settle(theta2, 0.05, SPEED_TOL, 0.02, 1.0);
            let [t2, t3] = b.angles();
            let lib = transmit(bend, t3, 0.0, 0.0).angle;
            angle_err = angle_err.max(wrap(t2 - lib).abs());
            b.set_load(load);
            b.move_and_settle(theta2, 0.0, SPEED_TOL, 0.05, 1.0);
            let [_, t3] = b.angles();
            let expected = -transmit(bend, t3, 0.0, load).torque;
            torque_err = torque_err.max((b.motor_torque() - expected).abs() / load);
            printed_err = printed_err.max((b.motor_torque() + load).abs() / load);
            fmin = fmin.min(-expected / load);
            fmax = fmax.max(-expected / load);
        }
    }
    println!(
        "(d) universal joint, bends 0..32 deg x 16 shaft angles, dt = 1 ms: max eq. (5.1) angle error \
         {angle_err:.3e} rad, max eq. (5.3) torque error {torque_err:.3e} (relative to the load); \
         factor range {fmin:.4}..{fmax:.4}; without the factor (eq. 6.1 as printed) {printed_err:.3e}"
    );
    assert!(printed_err > 0.1, "{printed_err}");
    assert!(angle_err <= 1e-4, "{angle_err}");
    assert!(torque_err <= 1e-3, "{torque_err}");
    // The bench reaches the factor's extremes at the wrist's largest bend,
    // cos(2 phi) and 1/cos(2 phi) (E6.6).
    let c = f64::to_radians(32.0).cos();
    assert!(
        (fmin - c).abs() < 1e-3 && (fmax - 1.0 / c).abs() < 1e-3,
        "{fmin} {fmax}"
    );
}

#[test]
fn halving_the_step_moves_the_answers_less_than_the_bounds() {
    let coarse = EngineSettings::default();
    let fine = coarse.with_half_step();
    let (_, a1) = fk_sweep(coarse, 8);
    let (_, a2) = fk_sweep(fine, 8);
    let pose_change = a1
        .iter()
        .zip(&a2)
        .flat_map(|(x, y)| (0..3).map(move |i| (x[i] - y[i]).abs()))
        .fold(0.0f64, f64::max);
    let h1 = hold_sweep(coarse, 6, 5);
    let h2 = hold_sweep(fine, 6, 5);
    let torque_change = h1
        .iter()
        .zip(&h2)
        .flat_map(|(x, y)| (0..2).map(move |i| (x.engine[i] - y.engine[i]).abs()))
        .fold(0.0f64, f64::max);
    let torque_err_fine = h2
        .iter()
        .flat_map(|s| (0..2).map(move |i| (s.engine[i] - s.exact[i]).abs()))
        .fold(0.0f64, f64::max);
    println!(
        "convergence, dt = 1 ms vs 0.5 ms: theta4/delta/gamma change {pose_change:.3e} rad (8 x 8 motor grid), \
         holding torque change {torque_change:.3e} N m (6 x 6 poses); at 0.5 ms max |engine - (-J^T tau)| = {torque_err_fine:.3e} N m"
    );
    assert!(pose_change <= 1e-4, "{pose_change}");
    assert!(
        torque_change <= 1e-3 && torque_err_fine <= 1e-3,
        "{torque_change} {torque_err_fine}"
    );
}
