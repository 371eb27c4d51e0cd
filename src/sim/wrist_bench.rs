//! The compact wrist on the bench (thesis §6.4.2–6.4.3): tracking in
//! active mode (Fig. 6.10–6.11) and a finger pushing the output link with
//! the motors off or under the admittance-passive mode (Fig. 6.13–6.17).
//!
//! # The bench
//! The wrist alone on a fixed base, both axes at the thesis's 4 ms tick,
//! the plant integrated at 0.25 ms. Each plant axis is the door
//! simulation's wrist axis ([`super::door`]) with more friction: a Table 6.1 rotor
//! (`I_m = 1.05e-6 kg·m²`) behind `N = 531`, a 0.004 kg·m² output load and
//! the gear's Karnopp friction ([`FrictionAxis`]: a break-away of
//! [`BREAKAWAY`] = 12 N·m at the output, from the thesis's own Case 1,
//! two thirds of it Coulomb; `N·1e-3` N·m·s/rad viscous). The door
//! simulation's axis keeps its smaller assumed friction (break-away
//! `N·0.012 = 6.4` N·m). The two axes are the
//! DAUJ's motor-side angles `(θ1, θ3)`; the pose is their forward
//! kinematics (ch. 5, [`WristConfig`]), its rate `J θ̇` (exact Jacobian),
//! and a task torque reaches the motor axes as `Jᵀ τ` ([`ForceMapping`],
//! eq. 6.1). The two axes are uncoupled (the output link's inertia is
//! lumped on each). The encoders give
//! `2000·N` counts per output turn; the speed is the one-sample count
//! difference. The interaction torque the controller reads is the true
//! task torque plus uniform noise of ±0.05 N·m (the F/T chain of eq.
//! 6.34–6.35, 6.3 is exercised by the door run).
//!
//! # Control in the loop (the library's components)
//! * [`wrist_tracking`]: the desired task trajectory is mapped to joint
//!   space by the continuous inverse kinematics ([`WristConfig::update`],
//!   eq. 5.14–5.15; rates and accelerations by central differences of it,
//!   the thesis's Fig. 6.8–6.9), and both motors run the active law
//!   ([`WristActiveConfig`], eq. 6.15) on it with [`door_wrist_design`]'s
//!   gains (Table 6.1's chatter at 4 ms, errata E6.3); the task-space
//!   errors are those of the forward kinematics, the rates through the
//!   exact Jacobian ([`WristConfig::jacobian`]).
//! * [`wrist_finger_push`]: [`FingerCase::MotorsOff`] applies no motor
//!   torque (the thesis's Case 1); [`FingerCase::Admittance`] runs the
//!   wrist mode manager ([`WristModeConfig`]) held in Passive — the
//!   admittance law of eq. (6.32) with the thesis's `K_c = 0.1` — whose
//!   task reference goes through the continuous inverse kinematics to the
//!   active law of both motors, the measured torque mapped to them by
//!   eq. (6.1) (Case 2).
//!
//! # Validated on the engine
//! [`crate::sim::engine::wrist_bench`] (feature `engine`) reruns the finger
//! push with the DAUJ built from its parts (no forward kinematics, no `Jᵀ`:
//! the finger is a contact force at the tool point), the gears as rotors
//! behind stiff springs with motor friction, the F/T sensor as strain
//! gauges off their certificate, and the library's public wrist step on
//! `f32`. On this bench's nominal push (pitch, 12° over 1.5 s, 12 N·m
//! break-away) Case 2 peaks at 2.06 N·m here and 2.10 N·m on the engine
//! (2.09 N·m true), the wrist following the finger by 11.7° here and 12.5°
//! there; Case 1 holds the whole push in both. Over 20 drawn pushes the
//! engine gives Case 1 a hold of median 24.1 N·m (min 23.2: every push,
//! capped by the finger's 25°, was held), Case 2 a peak of median
//! 1.72 N·m (1.23–2.71), tracking the finger's speed over `K_c`
//! (`cargo run --release --features sim --example wrist_bench`). In
//! active mode ([`wrist_tracking`], 6 s, errors after 1 s) the engine's
//! mechanism stays within 0.076° (pitch) and 0.053° (yaw) of the desired
//! pose, this bench within 0.125° and 0.079°. One
//! difference in reading [`BREAKAWAY`]: it is a torque at each gear's
//! output, and a pitch push reaches each gear through `Jᵀ` as only 0.27 of
//! itself at 10° of pitch, so the wrist holds about `3.7 B` of pitch torque
//! there (the library's `Jᵀ`, which this bench applies, predicts `3.7 B`;
//! the engine holds 0–20 % more): the thesis's "more than 10Nm" needs only
//! `B ≈ 2.7 N·m` per gear at that pose, and the 12 N·m assumed here is an
//! upper reading, not "20 % above" the bound.

use super::door::{door_wrist_design, FrictionAxis};
use super::experiments::ErrorStats;
use super::SplitMix64;
use crate::wrist::active::{WristActiveConfig, WristActiveParams, WristJointSample};
use crate::wrist::admittance::{AdmittanceParams, AdmittanceSettings};
use crate::wrist::modes::{WristMode, WristModeConfig, WristModeInput, WristModeParams};
use crate::wrist::{
    ForceMapping, IkState, JacobianKind, MotorAngles, PitchYaw, WristConfig, WristParams,
};
use core::f64::consts::PI;
use std::vec::Vec;

/// Control period, s (§6.3).
pub const BENCH_PERIOD: f64 = 0.004;
const SUBSTEPS: usize = 16;
const RATIO: f64 = 531.0;
const ROTOR: f64 = 1.05e-6;
const LOAD: f64 = 0.004;
/// Break-away torque of each gear at its output, N·m. Table 6.1 gives no
/// friction; the source is the thesis's own Case 1 (§6.4.3): with the
/// motors off "the wrist does not move even when more than 10Nm pitch
/// torque is generated". The bench takes 20 % above that bound, split
/// two thirds Coulomb, one third static excess.
pub const BREAKAWAY: f64 = 12.0;

/// One output axis of the bench wrist at `position` (rad), at rest.
pub fn bench_axis(position: f64) -> FrictionAxis {
    FrictionAxis {
        inertia: ROTOR * RATIO * RATIO + LOAD,
        coulomb: BREAKAWAY * 2.0 / 3.0,
        static_excess: BREAKAWAY / 3.0,
        stribeck: 1.0,
        viscous: RATIO * 1e-3,
        position,
        velocity: 0.0,
        acceleration: 0.0,
    }
}

/// One control sample of a bench run (true plant values unless stated).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WristBenchSample {
    /// Time, s.
    pub time: f64,
    /// Desired (tracking) or reference (passive) pose `[δ, γ]`, rad.
    pub desired: [f64; 2],
    /// Its rate, rad/s.
    pub desired_rate: [f64; 2],
    /// Pose `[δ, γ]`, rad.
    pub pose: [f64; 2],
    /// Pose rate, rad/s.
    pub rate: [f64; 2],
    /// Interaction torque of the environment (finger) on the wrist,
    /// `[τ_δ, τ_γ]`, N·m.
    pub interaction: [f64; 2],
    /// Motor torques commanded, N·m (motor side).
    pub motor_torque: [f64; 2],
}

/// A bench run.
#[derive(Debug, Clone, PartialEq)]
pub struct WristBenchRun {
    /// One record per control sample.
    pub samples: Vec<WristBenchSample>,
    /// Pose error `x − x_d` per axis after the settling time, rad.
    pub position_error: [ErrorStats; 2],
    /// Rate error `ẋ − ẋ_d` per axis after the settling time, rad/s.
    pub velocity_error: [ErrorStats; 2],
    /// Largest `|τ|` of the interaction per axis, N·m.
    pub peak_interaction: [f64; 2],
    /// Largest `|τ_m|` per motor, N·m.
    pub peak_motor_torque: [f64; 2],
    /// Travel of `δ`, `γ` over the run (largest minus smallest), rad.
    pub travel: [f64; 2],
    /// Samples with a motor command at its limit.
    pub saturated_samples: usize,
}

/// The desired task trajectory of [`wrist_tracking`] at `t` (s), rad: the
/// output axis bent by `b = 12° + 6°(1 − cos 2πt/4 s)` in the direction
/// `a = 90°(1 − cos 2πt/6 s)`, `(δ_d, γ_d) = b (cos a, sin a)`: it swings
/// from pitch to negative pitch through yaw and back while the bend
/// breathes, starts at rest, stays inside the ±30° workspace and away
/// from the straight pose (where the motor angles are not a function of
/// the pose), and reverses both motors.
pub fn tracking_trajectory(t: f64) -> [f64; 2] {
    let b = (12.0 + 6.0 * (1.0 - libm::cos(2.0 * PI * t / 4.0))).to_radians();
    let a = 0.5 * PI * (1.0 - libm::cos(2.0 * PI * t / 6.0));
    [b * libm::cos(a), b * libm::sin(a)]
}

/// Central-difference step of the joint trajectory, s.
const DIFF_STEP: f64 = 1e-3;

struct Bench {
    axes: [FrictionAxis; 2],
    last: [f64; 2],
    rad: f64,
}

impl Bench {
    fn new() -> Self {
        Bench {
            axes: [bench_axis(0.0), bench_axis(0.0)],
            last: [0.0; 2],
            rad: 2.0 * PI / (2000.0 * RATIO),
        }
    }
    /// Encoder positions and one-sample speeds.
    fn read(&mut self) -> ([f64; 2], [f64; 2]) {
        let q = [0, 1].map(|i| libm::round(self.axes[i].position / self.rad) * self.rad);
        let v = [0, 1].map(|i| (q[i] - self.last[i]) / BENCH_PERIOD);
        self.last = q;
        (q, v)
    }
    /// Hold `motor` (N·m) for one period under the environment torque
    /// `env(t, pose, rate)`.
    fn advance(
        &mut self,
        time: f64,
        motor: [f64; 2],
        env: &mut dyn FnMut(f64, [f64; 2], [f64; 2]) -> [f64; 2],
    ) {
        let dt = BENCH_PERIOD / SUBSTEPS as f64;
        for s in 0..SUBSTEPS {
            let t = time + s as f64 * dt;
            let e = env(t, self.pose(), self.rate());
            for i in 0..2 {
                self.axes[i].step(dt, RATIO * motor[i] + e[i]);
            }
        }
    }
    fn pose(&self) -> [f64; 2] {
        [self.axes[0].position, self.axes[1].position]
    }
    fn rate(&self) -> [f64; 2] {
        [self.axes[0].velocity, self.axes[1].velocity]
    }
}

fn finish(samples: Vec<WristBenchSample>, settle: f64, saturated: usize) -> WristBenchRun {
    let after = || samples.iter().filter(|s| s.time >= settle);
    let stat = |f: &dyn Fn(&WristBenchSample) -> f64| ErrorStats::of(after().map(f));
    let peak = |f: &dyn Fn(&WristBenchSample) -> f64| {
        samples.iter().map(f).fold(0.0f64, |a, x| a.max(x.abs()))
    };
    WristBenchRun {
        position_error: [
            stat(&|s| s.pose[0] - s.desired[0]),
            stat(&|s| s.pose[1] - s.desired[1]),
        ],
        velocity_error: [
            stat(&|s| s.rate[0] - s.desired_rate[0]),
            stat(&|s| s.rate[1] - s.desired_rate[1]),
        ],
        peak_interaction: [peak(&|s| s.interaction[0]), peak(&|s| s.interaction[1])],
        peak_motor_torque: [peak(&|s| s.motor_torque[0]), peak(&|s| s.motor_torque[1])],
        travel: [0, 1].map(|i| {
            let (lo, hi) = samples.iter().fold((f64::MAX, f64::MIN), |(lo, hi), s| {
                (lo.min(s.pose[i]), hi.max(s.pose[i]))
            });
            if hi >= lo {
                hi - lo
            } else {
                0.0
            }
        }),
        saturated_samples: saturated,
        samples,
    }
}

/// §6.4.2 (Fig. 6.8–6.11): the DAUJ wrist tracks [`tracking_trajectory`]
/// for `duration` s in active mode (no interaction), starting at rest at
/// its first pose; errors are counted after `settle` s. The samples'
/// `pose` and `rate` are task space (forward kinematics and exact
/// Jacobian of the true motor angles).
pub fn wrist_tracking(duration: f64, settle: f64) -> WristBenchRun {
    let params =
        WristActiveParams::try_new([door_wrist_design(BENCH_PERIOD); 2]).expect("valid design");
    let law = WristActiveConfig::<f64>::new(&params);
    let kin = WristConfig::<f64>::new(&WristParams::thesis());
    let at = |x: [f64; 2]| PitchYaw {
        delta: x[0],
        gamma: x[1],
    };
    let start = kin.inverse(at(tracking_trajectory(0.0))).motors;
    let mut ik = IkState::new(start);
    let mut st = law.initial_state();
    let mut bench = Bench::new();
    bench.axes = [bench_axis(start.theta1), bench_axis(start.theta3)];
    bench.last = bench.read().0;
    let mut samples = Vec::new();
    let mut saturated = 0;
    let total = (duration / BENCH_PERIOD).round() as usize;
    let h = DIFF_STEP;
    for k in 0..total {
        let time = k as f64 * BENCH_PERIOD;
        let (q, v) = bench.read();
        // Joint trajectory: continuous IK at t, t ± h (eq. 5.14–5.15).
        let xd = tracking_trajectory(time);
        let m0 = kin.update(&mut ik, at(xd)).motors;
        let side = |dt: f64| {
            let mut s = ik;
            kin.update(&mut s, at(tracking_trajectory(time + dt)))
                .motors
        };
        let (mp, mm) = (side(h), side(-h));
        let qd = [m0.theta1, m0.theta3];
        let (p, m) = ([mp.theta1, mp.theta3], [mm.theta1, mm.theta3]);
        let x = [0, 1].map(|i| WristJointSample {
            desired_position: qd[i],
            desired_velocity: (p[i] - m[i]) / (2.0 * h),
            desired_acceleration: (p[i] - 2.0 * qd[i] + m[i]) / (h * h),
            position: q[i],
            velocity: v[i],
            interaction_torque: 0.0,
        });
        let out = law.update(&mut st, &x);
        let motor = [out[0].torque, out[1].torque];
        saturated += out.iter().filter(|o| o.saturated).count();
        // Task space: the pose of the true motor angles and its rate
        // J θ̇; the desired rate by central differences of x_d.
        let true_m = MotorAngles {
            theta1: bench.axes[0].position,
            theta3: bench.axes[1].position,
        };
        let pose = kin.forward(true_m).pose;
        let j = kin.jacobian(true_m).m;
        let r = bench.rate();
        let (xp, xm) = (tracking_trajectory(time + h), tracking_trajectory(time - h));
        samples.push(WristBenchSample {
            time,
            desired: xd,
            desired_rate: [0, 1].map(|i| (xp[i] - xm[i]) / (2.0 * h)),
            pose: [pose.delta, pose.gamma],
            rate: [0, 1].map(|i| j[i][0] * r[0] + j[i][1] * r[1]),
            interaction: [0.0; 2],
            motor_torque: motor,
        });
        bench.advance(time, motor, &mut |_, _, _| [0.0; 2]);
    }
    finish(samples, settle, saturated)
}

/// What drives the wrist while a finger pushes it (§6.4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FingerCase {
    /// Case 1: the motors are disabled (zero torque).
    MotorsOff,
    /// Case 2: the admittance-passive mode (eq. 6.32, `K_c = 0.1`) and the
    /// active law on its reference.
    Admittance,
}

/// Finger stiffness, N·m/rad, and damping, N·m·s/rad (a fingertip on the
/// link through the F/T sensor).
pub const FINGER_STIFFNESS: f64 = 60.0;
const FINGER_DAMPING: f64 = 0.5;
/// How far the finger moves, rad (12°).
pub const FINGER_TRAVEL: f64 = 0.2094;
/// The pose `[δ, γ]` the finger finds the wrist in, rad (10° of pitch:
/// away from the straight pose, where the motor angles are not a function
/// of the pose).
pub const FINGER_START: [f64; 2] = [0.1745, 0.0];

/// The finger's torque at `t` (N·m) on axis 0 (pitch, 0.5–3.5 s) then
/// axis 1 (yaw, 4.5–7.5 s): it touches the link where it is, moves
/// [`FINGER_TRAVEL`] along a raised cosine over 1.5 s and back, and lets
/// go; the torque is a spring-damper between finger and link that only
/// pushes.
struct Finger {
    start: [Option<f64>; 2],
}

impl Finger {
    fn torque(&mut self, t: f64, pose: [f64; 2], rate: [f64; 2]) -> [f64; 2] {
        let mut out = [0.0; 2];
        for (i, t0) in [0.5, 4.5].into_iter().enumerate() {
            let u = (t - t0) / 3.0;
            if !(0.0..1.0).contains(&u) {
                continue;
            }
            let p0 = *self.start[i].get_or_insert(pose[i]);
            let w = 2.0 * PI / 3.0;
            let (s, c) = libm::sincos(2.0 * PI * u);
            let (pf, vf) = (
                p0 + 0.5 * FINGER_TRAVEL * (1.0 - c),
                0.5 * FINGER_TRAVEL * w * s,
            );
            let f = FINGER_STIFFNESS * (pf - pose[i]) + FINGER_DAMPING * (vf - rate[i]);
            // A finger pushes in the +direction only.
            out[i] = f.max(0.0);
        }
        out
    }
}

/// §6.4.3 (Fig. 6.13–6.17): a finger pushes the link along pitch, then
/// yaw, for `duration` s (8 s covers both pushes); the interaction torque
/// is the finger's (what the F/T sensor reads), `seed` its noise.
pub fn wrist_finger_push(case: FingerCase, duration: f64, seed: u64) -> WristBenchRun {
    let params =
        WristActiveParams::try_new([door_wrist_design(BENCH_PERIOD); 2]).expect("valid design");
    let law = WristActiveConfig::<f64>::new(&params);
    let mut st = law.initial_state();
    let limit = 30f64.to_radians();
    let adm = AdmittanceParams::try_new(AdmittanceSettings {
        gain: [0.1, 0.1],
        stiffness: FINGER_STIFFNESS,
        sample_period: BENCH_PERIOD,
        lag_samples: 1,
        limits: [limit, limit],
        max_rate: 1.0,
        deadband: 0.0,
        desired_torque: [0.0; 2],
    })
    .expect("K_c = 0.1 inside its discrete-time range");
    let modes = WristModeConfig::<f64>::new(
        &WristModeParams::try_new(crate::wrist::modes::WristModeSettings {
            admittance: adm,
            enter_passive: 1.0,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 5,
            dwell: 250,
            rejoin_bandwidth: 5.0,
        })
        .expect("valid mode params"),
    );
    let wp = WristParams::thesis();
    let kin = WristConfig::<f64>::new(&wp);
    let map = ForceMapping::<f64>::new(&wp, JacobianKind::Exact);
    let at = |x: [f64; 2]| PitchYaw {
        delta: x[0],
        gamma: x[1],
    };
    let motors = |q: [f64; 2]| MotorAngles {
        theta1: q[0],
        theta3: q[1],
    };
    // Task pose and rate of motor angles and rates: FK and J θ̇.
    let task = |q: [f64; 2], r: [f64; 2]| {
        let p = kin.forward(motors(q)).pose;
        let j = kin.jacobian(motors(q)).m;
        (
            [p.delta, p.gamma],
            [0, 1].map(|i| j[i][0] * r[0] + j[i][1] * r[1]),
        )
    };
    let start = kin.inverse(at(FINGER_START)).motors;
    let mut ik = IkState::new(start);
    let mut mode_state = modes.initial_state(WristMode::Passive, FINGER_START);
    let mut bench = Bench::new();
    bench.axes = [bench_axis(start.theta1), bench_axis(start.theta3)];
    bench.last = bench.read().0;
    let mut finger = Finger { start: [None; 2] };
    let mut rng = SplitMix64::new(seed);
    let mut samples = Vec::new();
    let mut saturated = 0;
    let mut touch = [0.0f64; 2];
    let total = (duration / BENCH_PERIOD).round() as usize;
    let h = DIFF_STEP;
    for k in 0..total {
        let time = k as f64 * BENCH_PERIOD;
        let (q, v) = bench.read();
        let measured = [0, 1].map(|i| touch[i] + 0.05 * (2.0 * rng.uniform() - 1.0));
        let (reference, rate, motor) = match case {
            FingerCase::MotorsOff => (FINGER_START, [0.0; 2], [0.0; 2]),
            FingerCase::Admittance => {
                let o = modes.update(
                    &mut mode_state,
                    &WristModeInput {
                        interaction: measured,
                        request: Some(WristMode::Passive),
                        ..Default::default()
                    },
                );
                // Task reference → motor references (continuous IK), the
                // rate by central differences along the reference's rate.
                let m0 = kin.update(&mut ik, at(o.reference)).motors;
                let side = |sgn: f64| {
                    let mut s = ik;
                    let x = [0, 1].map(|i| o.reference[i] + sgn * h * o.reference_rate[i]);
                    kin.update(&mut s, at(x)).motors
                };
                let (mp, mm) = (side(1.0), side(-1.0));
                let qr = [m0.theta1, m0.theta3];
                let vr = [
                    (mp.theta1 - mm.theta1) / (2.0 * h),
                    (mp.theta3 - mm.theta3) / (2.0 * h),
                ];
                // The measured task torque on the motor axes, eq. (6.1).
                let on_motors = map.motor_torques(motors(q), measured).torque;
                let x = [0, 1].map(|i| WristJointSample {
                    desired_position: qr[i],
                    desired_velocity: vr[i],
                    desired_acceleration: 0.0,
                    position: q[i],
                    velocity: v[i],
                    // τ_t = −(environment torque on the wrist), eq. (6.4).
                    interaction_torque: -on_motors[i],
                });
                let out = law.update(&mut st, &x);
                saturated += out.iter().filter(|m| m.saturated).count();
                (
                    o.reference,
                    o.reference_rate,
                    [out[0].torque, out[1].torque],
                )
            }
        };
        let (pose, rates) = task(bench.pose(), bench.rate());
        let now = finger.torque(time, pose, rates);
        samples.push(WristBenchSample {
            time,
            desired: reference,
            desired_rate: rate,
            pose,
            rate: rates,
            interaction: now,
            motor_torque: motor,
        });
        // The finger's task torque on the motor axes: Jᵀ τ (virtual work).
        bench.advance(time, motor, &mut |t, qa, ra| {
            let (p, r) = task(qa, ra);
            map.motor_torques(motors(qa), finger.torque(t, p, r)).torque
        });
        let (p, r) = task(bench.pose(), bench.rate());
        touch = finger.torque(time + BENCH_PERIOD, p, r);
    }
    finish(samples, 0.0, saturated)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bench axis's breakaway at the output is 20 % above the
    /// thesis's 10 N·m: a constant push just below it leaves the axis at
    /// rest, one just above moves it.
    #[test]
    fn breakaway_is_a_fifth_above_the_thesis_bound() {
        let b = 1.2 * 10.0;
        for (push, moves) in [(0.99 * b, false), (1.01 * b, true)] {
            let mut a = bench_axis(0.0);
            for _ in 0..4000 {
                a.step(2.5e-4, push);
            }
            assert_eq!(a.position > 1e-6, moves, "{push}");
        }
    }

    /// The thesis's contrast (§6.4.3): with the motors off the gears'
    /// friction holds the wrist against the finger (travel below a tenth
    /// of the admittance case's, at least three times its peak torque);
    /// under the admittance mode the wrist follows the finger over more
    /// than half the finger's travel on both axes.
    #[test]
    fn admittance_mode_lets_the_finger_move_the_wrist() {
        let off = wrist_finger_push(FingerCase::MotorsOff, 8.0, 1);
        let on = wrist_finger_push(FingerCase::Admittance, 8.0, 1);
        // Case 1 as the thesis states it: more than 10 N·m of pitch
        // torque with the wrist at rest.
        assert!(off.peak_interaction[0] > 10.0, "{:?}", off.peak_interaction);
        for i in 0..2 {
            assert!(on.travel[i] > 0.5 * FINGER_TRAVEL, "{:?}", on.travel);
            assert!(off.travel[i] < 0.1 * on.travel[i], "{:?}", off.travel);
            assert!(
                off.peak_interaction[i] > 3.0 * on.peak_interaction[i],
                "{:?} {:?}",
                off.peak_interaction,
                on.peak_interaction
            );
        }
    }

    /// Tracking through the DAUJ: the pose error after the first second
    /// stays below 1° on both axes (the bend reaches 24°), and the
    /// recorded task rate (exact Jacobian times the motor rates) agrees
    /// with the finite difference of the recorded poses.
    #[test]
    fn active_mode_tracks_the_task_trajectory() {
        let r = wrist_tracking(6.0, 1.0);
        for e in &r.position_error {
            assert!(e.max.abs().max(e.min.abs()) < 1f64.to_radians(), "{e:?}");
        }
        let s = &r.samples;
        let mut worst = 0.0f64;
        for k in 1..s.len() - 1 {
            for i in 0..2 {
                let fd = (s[k + 1].pose[i] - s[k - 1].pose[i]) / (2.0 * BENCH_PERIOD);
                let mean = 0.5 * (s[k + 1].rate[i] + s[k - 1].rate[i]);
                worst = worst.max((fd - mean).abs());
            }
        }
        // Stick–slip makes the rate jump within a period; the agreement
        // is to a few percent of the 0.16 rad/s task speed.
        assert!(worst < 0.05, "{worst}");
    }
}
