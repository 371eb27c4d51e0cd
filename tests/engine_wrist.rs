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
}

fn fk_sweep(settings: EngineSettings, n: usize) -> (FkErrors, Vec<[f64; 3]>) {
    let p = WristParams::thesis();
    let cfg = WristConfig::<f64>::new(&p);
    let mut m = DaujMechanism::try_new(&p, TOOL, settings).unwrap();
    let mut e = FkErrors::default();
    let mut first = true;
    let mut samples = Vec::new();
    for (t1, t3) in motor_grid(n) {
        let ramp = if first { 0.5 } else { 0.05 };
        first = false;
        let speed = m.move_to(t1, t3, ramp, 0.1);
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
}

#[test]
fn probe() {
    let p = WristParams::thesis();
    let cfg = WristConfig::<f64>::new(&p);
    let mut m = DaujMechanism::try_new(&p, TOOL, EngineSettings::default()).unwrap();
    for (k, (t1, t3)) in motor_grid(24).into_iter().enumerate().take(60) {
        let speed = m.move_to(t1, t3, if k == 0 { 0.5 } else { 0.05 }, 0.1);
        let a = m.angles();
        let f = cfg.forward(MotorAngles { theta1: a.theta1, theta3: a.theta3 });
        println!("{k} t=({:.3},{:.3}) meas=({:.4},{:.4}) th4 {:.5} lib {:.5} dg eng ({:.4},{:.4}) lib ({:.4},{:.4}) loop {:.2e} speed {:.2e}",
            t1, t3, a.theta1, a.theta3, a.theta4, f.theta4, a.delta, a.gamma, f.pose.delta, f.pose.gamma, a.loop_error, speed);
    }
}
