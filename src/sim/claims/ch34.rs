//! Chapters 3 and 4 on the dynamic [`JointPlant`] at the thesis's 4 ms
//! controller period (§6.3): the experiments behind Fig. 3.1–3.3, Table
//! 3.1, Table 3.3, Fig. 3.6, Fig. 3.8, Fig. 4.3, Theorem 1 and Fig. 4.11,
//! each run
//! through the public API ([`JointConfig`], and for the figures that
//! compare feedback sources the laws' own configurations fed by
//! [`JointConfig::measure`]).
//!
//! The kinematic-error model is what the thesis did (§3.1): eq. (3.7)
//! fitted by [`KinematicErrorFit`] to one output revolution of the
//! plant's encoders at zero load, both directions averaged. Two shadow
//! estimators on the same readings give the error without a
//! kinematic-error model and with Table 3.2's coefficients.

use core::f64::consts::{PI, TAU};

use super::{rule, Claim, ClaimError, Condition, Criterion, Metric};
use crate::control::{
    ControlInput, JointMode, PassiveConfig, PassiveParams, RobustAdaptiveConfig, UltimateBound,
};
use crate::error::ParamError;
use crate::estimation::{TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings};
use crate::harmonic_drive::kinematic_error::{KinematicErrorFit, KinematicErrorModel};
use crate::joint::{JointConfig, JointParams, JointReadings, JointSettings, JointTarget};
use crate::sim::plants::drive::RATIO;
use crate::sim::plants::joint::{JointPlant, JointPlantState, JointSensors, MOTOR_COUNTS};
use crate::sim::sensors::SplitMix64;

/// The controller period of every run here, s (thesis §6.3).
pub const PERIOD: f64 = 0.004;

/// Per-run metrics of the joint experiments (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointRunMetrics {
    /// Index of the plant in the family.
    pub plant: usize,
    /// Seed of the run.
    pub seed: u64,
    /// Eq. (3.7) fitted to the plant's kinematic error: RMS of the
    /// residual over RMS of the error, one output revolution
    /// (dimensionless).
    pub ke_fit_residual: f64,
    /// Tracking run, peak `|τ̂_t − τ_t|` with the fitted (3.7), N·m.
    pub est_peak_fit: f64,
    /// Same, RMS, N·m.
    pub est_rms_fit: f64,
    /// Same run, a shadow estimator without a kinematic-error model: peak, N·m.
    pub est_peak_none: f64,
    /// Same, RMS, N·m.
    pub est_rms_none: f64,
    /// Same run, a shadow estimator with Table 3.2's coefficients: RMS, N·m.
    pub est_rms_table: f64,
    /// 4 ms preset, law (4.19) alone fed the estimate (the Fig. 4.3 (C)
    /// run): largest `|θ_m − N q_d|` after the reaching time over the
    /// preset's own Theorem 1 criterion (dimensionless).
    pub preset_bound_ratio: f64,
    /// 4 ms preset: share of ticks in Active.
    pub preset_active_share: f64,
    /// Table 4.1's own gains at 4 ms, law (4.19) alone fed the estimate:
    /// the same ratio to their own bound.
    pub thesis_bound_ratio: f64,
    /// Fig. 4.3 (A): RMS link error with no joint-torque feedback, rad.
    pub link_rms_none: f64,
    /// Fig. 4.3 (B): with the torque sensor's feedback, rad.
    pub link_rms_sensor: f64,
    /// Fig. 4.3 (C): with the estimate's feedback, rad.
    pub link_rms_estimate: f64,
    /// Fig. 3.8: share of the true step that the estimate shows 40–100 ms
    /// after the payload is cut.
    pub step_share: f64,
    /// Fig. 4.11 (A): RMS hand torque back-driving with eq. (4.32) and no
    /// joint-torque feedback, N·m.
    pub hand_rms_none: f64,
    /// Fig. 4.11 (B): with the estimate, best over [`PASSIVE_GAINS`], N·m.
    pub hand_rms_estimate: f64,
    /// Fig. 4.11 (C): with the torque sensor, best over [`PASSIVE_GAINS`], N·m.
    pub hand_rms_sensor: f64,
    /// Table 3.3: the largest `|τ̂_t − τ_t|` over the seven open-loop
    /// motor torques ([`TABLE_3_3_COMMANDS`]) with a hand moving the link,
    /// N·m.
    pub table_3_3_peak: f64,
}

impl JointRunMetrics {
    /// `1 − RMS(fitted 3.7)/RMS(none)`.
    pub fn ke_reduction(&self) -> f64 {
        1.0 - self.est_rms_fit / self.est_rms_none
    }
    /// `1 − RMS(Table 3.2)/RMS(none)`.
    pub fn table_3_2_reduction(&self) -> f64 {
        1.0 - self.est_rms_table / self.est_rms_none
    }
    /// `1 − RMS link error (C)/(A)`.
    pub fn jtf_reduction(&self) -> f64 {
        1.0 - self.link_rms_estimate / self.link_rms_none
    }
    /// RMS link error (C)/(B).
    pub fn jtf_estimate_over_sensor(&self) -> f64 {
        self.link_rms_estimate / self.link_rms_sensor
    }
    /// `1 − RMS hand torque (B)/(A)`.
    pub fn passive_reduction(&self) -> f64 {
        1.0 - self.hand_rms_estimate / self.hand_rms_none
    }
    /// RMS hand torque (B)/(C).
    pub fn passive_estimate_over_sensor(&self) -> f64 {
        self.hand_rms_estimate / self.hand_rms_sensor
    }
}

/// Smooth link trajectory `q_d = A (1 − cos(2π (t − 0.2)/P))/2` for
/// `0.2 ≤ t ≤ 0.2 + P`, at rest otherwise; `A = 0.8` rad, `P = 3` s (peak
/// 0.84 rad/s at the link, 84 rad/s at the motor, below the preset's
/// 100 rad/s).
fn trajectory(t: f64) -> (f64, f64, f64) {
    let (a, p) = (0.8, 3.0);
    let s = t - 0.2;
    if !(0.0..=p).contains(&s) {
        return (0.0, 0.0, 0.0);
    }
    let w = TAU / p;
    (
        a * (1.0 - (w * s).cos()) / 2.0,
        a * w * (w * s).sin() / 2.0,
        a * w * w * (w * s).cos() / 2.0,
    )
}

/// The passive gains `Î_m K_p` swept for Fig. 4.11 (the best is kept):
/// 0.2, the largest errata E4.6 finds stable at 4 ms (the joint then
/// feels heavier than its rotor), and 1.5 and 3, which make it lighter
/// but which the sampled loop may not hold (errata E4.12).
pub const PASSIVE_GAINS: [f64; 3] = [0.2, 1.5, 3.0];

/// Duration of the tracking runs, s.
const TRACK_TIME: f64 = 3.6;
/// Start of the judged window, s (the motor's first counts).
const SETTLE: f64 = 0.2;

/// Fit eq. (3.7) to one output revolution at zero load, in both
/// directions (the thesis's §3.1 measurement), through the plant's
/// encoders. Returns the model and the residual share over the true error.
fn fit_kinematic_error(
    plant: &JointPlant,
    st: &JointPlantState,
    rng: &mut SplitMix64,
) -> Result<(KinematicErrorModel, f64), ClaimError> {
    fit_kinematic_error_samples(plant, st, rng).map(|(m, r, _)| (m, r))
}

/// [`fit_kinematic_error`], also returning the true error at each
/// calibration point.
fn fit_kinematic_error_samples(
    plant: &JointPlant,
    st: &JointPlantState,
    rng: &mut SplitMix64,
) -> Result<(KinematicErrorModel, f64, Vec<CalibrationSample>), ClaimError> {
    let mut fit = KinematicErrorFit::new();
    let n = 100 * 61;
    let mut truth = Vec::with_capacity(2 * n);
    for dir in [1.0, -1.0] {
        for i in 0..n {
            let link = dir * TAU * i as f64 / n as f64;
            let motor = plant.zero_load_motor_angle(st, link);
            let r: JointSensors = plant.read_at(st, motor, link, rng);
            let link_read = r.link_count as f64 * TAU / (1u64 << 17) as f64;
            let motor_read = r.motor_counter as i32 as f64 * TAU / MOTOR_COUNTS as f64;
            // Estimator convention: θ_wi = −θ_m, error = θ_fo + θ_wi/N.
            let e = wrap(link_read - motor_read / RATIO);
            fit.add_sample(link_read, -motor_read, e)?;
            truth.push(CalibrationSample {
                link,
                motor,
                error: plant.kinematic_error(st, motor, link),
            });
        }
    }
    let model = fit.solve()?;
    let (mut res, mut tot) = (0.0, 0.0);
    for c in &truth {
        res += (c.error - model.evaluate(c.link, -c.motor)).powi(2);
        tot += c.error * c.error;
    }
    Ok((model, (res / tot).sqrt(), truth))
}

/// An angle difference brought into `[−π, π)`.
fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// `params` with its estimator's kinematic-error model replaced.
fn with_kinematic_error(
    params: &JointParams,
    model: Option<KinematicErrorModel>,
) -> Result<JointParams, ClaimError> {
    let s = params.settings();
    let e = s.estimator;
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive: e.drive(),
        kinematic_error: model,
        link_counts_per_rev: e.link_counts_per_rev(),
        motor_counts_per_rev: e.motor_counts_per_rev(),
        max_torque: e.max_torque(),
    })?;
    Ok(JointParams::try_new(JointSettings { estimator, ..s })?)
}

/// The tracking criterion of a joint's own Theorem 1 bound (motor side,
/// rad) and its reaching time (s), as in `tests/preset_4ms.rs`: `r_S/λ`
/// plus one motor count, after the time of eq. (4.31) from `V(0)` of
/// eq. (4.20) with `r = 0` and the initial friction estimate as the
/// parameter error.
fn criterion(p: &JointParams) -> (f64, f64) {
    let d = *p.settings().mode.settings().active.design();
    let b = UltimateBound::new(&d);
    let f0 = d.initial_friction.to_array();
    let v0 = UltimateBound::lyapunov(&d, 0.0, 0.0, &[-f0[0], -f0[1], -f0[2], 0.0]);
    (
        b.tracking_error + TAU / p.settings().estimator.motor_counts_per_rev() as f64,
        b.reaching_time(v0, 0.0),
    )
}

/// The joint's state at power-up from its first readings, with the motor
/// position a user who knows the kinematic error computes: the link
/// angle `θ_l` from the absolute link encoder, and
/// `q_m = N (θ_l − e(θ_l, −q_m))` by the model `model` (fixed-point
/// iteration), rather than [`JointConfig::state`]'s `N θ_l`, which
/// assumes zero kinematic error and so starts the estimate `K e(θ_l)` off.
fn start_state(
    cfg: &JointConfig<f64>,
    r: &JointSensors,
    model: &KinematicErrorModel,
) -> crate::joint::JointState<f64> {
    let l = (1i64 << 17) as f64;
    let mut c = r.link_count as f64;
    if c >= l / 2.0 {
        c -= l;
    }
    let link = c * TAU / l;
    let mut motor = RATIO * link;
    for _ in 0..40 {
        motor = RATIO * (link - model.evaluate(link.rem_euclid(TAU), -motor));
    }
    let counts = (motor / TAU * MOTOR_COUNTS as f64).round() as i64;
    cfg.state_at(counts, r.motor_counter)
}

fn readings(r: &JointSensors, command: f64) -> JointReadings<f64> {
    JointReadings {
        link_count: r.link_count,
        motor_counter: r.motor_counter,
        motor_torque: Some(command),
    }
}

fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

struct Tracking {
    est_fit: Vec<f64>,
    est_none: Vec<f64>,
    est_table: Vec<f64>,
    active_share: f64,
    trace: Vec<TorqueSample>,
}

/// The tracking run of Fig. 3.6 on the full joint step: the payload `G
/// sin θ_l` changes slowly along the trajectory; the user's expected
/// joint torque is the payload's `G sin q_d`.
fn tracking(
    plant: &JointPlant,
    seed: u64,
    params: &JointParams,
    shadows: &[TorqueEstimatorConfig<f64>; 2],
    model: &KinematicErrorModel,
) -> Tracking {
    let cfg = JointConfig::<f64>::new(params);
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 11);
    let mut st = plant.rest(0.0, seed);
    let r0 = plant.read(&st, &mut rng);
    let mut js = start_state(&cfg, &r0, model);
    let mut sh = [*js.estimator_state(); 2];
    let mut out = Tracking {
        est_fit: vec![],
        est_none: vec![],
        est_table: vec![],
        active_share: 0.0,
        trace: vec![],
    };
    let ticks = (TRACK_TIME / PERIOD).round() as usize;
    let mut command = 0.0;
    let mut active = 0usize;
    for k in 0..ticks {
        let t = k as f64 * PERIOD;
        let (q, qd, qdd) = trajectory(t);
        let r = plant.read(&st, &mut rng);
        let truth = plant.transmitted(&st, &st.x);
        let mut target = JointTarget::from_si(q, qd, qdd);
        target.expected_joint_torque = plant.payload * q.sin();
        let o = cfg.update(&mut js, &readings(&r, command), &target);
        let shadow: Vec<f64> = shadows
            .iter()
            .zip(sh.iter_mut())
            .map(|(c, s)| {
                -c.update(s, r.link_count, r.motor_counter.wrapping_neg(), command)
                    .torque_si()
            })
            .collect();
        if o.mode == JointMode::Active {
            active += 1;
        }
        if t >= SETTLE {
            out.est_fit.push(o.joint_torque_si() - truth);
            out.est_none.push(shadow[0] - truth);
            out.est_table.push(shadow[1] - truth);
            out.trace.push(TorqueSample {
                time: t,
                truth,
                estimate: o.joint_torque_si(),
            });
        }
        command = o.motor_torque_si();
        plant.advance(&mut st, command, PERIOD, |_, _| 0.0);
    }
    out.active_share = active as f64 / ticks as f64;
    out
}

/// Which joint torque the law of a comparison run is fed.
#[derive(Clone, Copy, PartialEq)]
enum Feedback {
    None,
    Sensor,
    Estimate,
}

/// Fig. 4.3: the active law (eq. 4.19) alone, fed by `JointConfig::measure`,
/// with the joint-torque feedback of `source`. Returns the RMS link error.
fn active_law_run(
    plant: &JointPlant,
    seed: u64,
    params: &JointParams,
    model: &KinematicErrorModel,
    source: Feedback,
) -> (f64, f64) {
    let (bound, reach) = criterion(params);
    let mut ratio = 0.0f64;
    let jc = JointConfig::<f64>::new(params);
    let law = RobustAdaptiveConfig::<f64>::new(&params.settings().mode.settings().active);
    let mut ls = law.initial_state();
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 13);
    let mut st = plant.rest(0.0, seed);
    let r0 = plant.read(&st, &mut rng);
    let mut js = start_state(&jc, &r0, model);
    let mut command = 0.0;
    let mut err = Vec::new();
    let ticks = (TRACK_TIME / PERIOD).round() as usize;
    for k in 0..ticks {
        let t = k as f64 * PERIOD;
        let (q, qd, qdd) = trajectory(t);
        let r = plant.read(&st, &mut rng);
        let m = jc.measure(&mut js, &readings(&r, command));
        let x = ControlInput {
            desired_position: RATIO * q,
            desired_velocity: RATIO * qd,
            desired_acceleration: RATIO * qdd,
            motor_position: m.motor_position,
            motor_velocity: m.motor_velocity,
            joint_torque: match source {
                Feedback::None => 0.0,
                Feedback::Sensor => r.torque,
                Feedback::Estimate => m.joint_torque,
            },
            desired_joint_torque: 0.0,
            expected_joint_torque: 0.0,
        };
        command = law.update(&mut ls, &x).torque;
        if t >= SETTLE {
            err.push(st.x[2] - q);
        }
        if t >= reach.max(SETTLE) {
            ratio = ratio.max((st.x[0] - RATIO * q).abs() / bound);
        }
        plant.advance(&mut st, command, PERIOD, |_, _| 0.0);
    }
    (rms(&err), ratio)
}

/// Fig. 3.8: the joint holds `q_d = 0` under a 1.5 N·m payload that is cut
/// at 1 s. Returns the share of the true step the estimate shows as its
/// mean over 40–100 ms after the cut.
fn payload_cut(
    plant: &JointPlant,
    seed: u64,
    params: &JointParams,
    model: &KinematicErrorModel,
) -> (f64, Vec<TorqueSample>) {
    const LOAD: f64 = 1.5;
    const CUT: usize = 250;
    let cfg = JointConfig::<f64>::new(params);
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 17);
    let mut p = plant.clone();
    p.payload = 0.0;
    let mut st = p.rest(0.0, seed);
    let r0 = p.read(&st, &mut rng);
    let mut js = start_state(&cfg, &r0, model);
    let mut command = 0.0;
    let (mut est, mut truth) = (Vec::new(), Vec::new());
    for k in 0..CUT + 50 {
        let r = p.read(&st, &mut rng);
        truth.push(p.transmitted(&st, &st.x));
        let o = cfg.update(
            &mut js,
            &readings(&r, command),
            &JointTarget::from_si(0.0, 0.0, 0.0),
        );
        est.push(o.joint_torque_si());
        command = o.motor_torque_si();
        let load = if k < CUT { -LOAD } else { 0.0 };
        p.advance(&mut st, command, PERIOD, |_, _| load);
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    // The estimate at tick k reflects the state after k − 1 steps: the cut
    // acts from tick CUT + 1 on.
    let before = CUT - 50..CUT + 1;
    let after = CUT + 11..CUT + 26;
    let de = mean(&est[after.clone()]) - mean(&est[before.clone()]);
    let dt = mean(&truth[after]) - mean(&truth[before]);
    let trace = truth
        .iter()
        .zip(&est)
        .enumerate()
        .map(|(k, (&truth, &estimate))| TorqueSample {
            time: k as f64 * PERIOD,
            truth,
            estimate,
        })
        .collect();
    (de / dt, trace)
}

/// Fig. 4.11: a hand back-drives the link along `0.5 (1 − cos(π t))/2`
/// rad for 2 s through a stiff contact (300 N·m/rad, 3 N·m·s/rad) while
/// the motor runs eq. (4.32) with `τ_td = 0` and `Î_m K_p = gain`, fed the
/// joint torque of `source` (`None`: friction compensation alone). Returns
/// the RMS hand torque, N·m.
///
/// The thesis gives no `K_p`. With `Î_m K_p = 1` (the library's
/// [`PassiveParams::table_4_1_default`]) eq. (4.32)'s two joint-torque
/// terms cancel, `τ_m = f̂`, and the feedback does nothing; the runs
/// sweep `Î_m K_p ∈` [`PASSIVE_GAINS`] and keep the best.
fn passive_run(
    plant: &JointPlant,
    seed: u64,
    params: &JointParams,
    model: &KinematicErrorModel,
    source: Feedback,
    gain: f64,
) -> Result<f64, ClaimError> {
    let jc = JointConfig::<f64>::new(params);
    let rotor = params
        .settings()
        .mode
        .settings()
        .active
        .design()
        .rotor_inertia;
    let law = PassiveConfig::<f64>::new(&PassiveParams::table_4_1(gain / rotor)?);
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 19);
    let mut p = plant.clone();
    p.payload = 0.0;
    let mut st = p.rest(0.0, seed);
    let r0 = p.read(&st, &mut rng);
    let mut js = start_state(&jc, &r0, model);
    let mut command = 0.0;
    let mut hand = Vec::new();
    let hand_path = |t: f64| {
        let w = PI;
        (0.25 * (1.0 - (w * t).cos()), 0.25 * w * (w * t).sin())
    };
    for k in 0..500 {
        let t0 = k as f64 * PERIOD;
        let r = p.read(&st, &mut rng);
        let m = jc.measure(&mut js, &readings(&r, command));
        let x = ControlInput {
            desired_position: 0.0,
            desired_velocity: 0.0,
            desired_acceleration: 0.0,
            motor_position: m.motor_position,
            motor_velocity: m.motor_velocity,
            joint_torque: match source {
                Feedback::None => 0.0,
                Feedback::Sensor => r.torque,
                Feedback::Estimate => m.joint_torque,
            },
            desired_joint_torque: 0.0,
            expected_joint_torque: 0.0,
        };
        command = law.update(&x).torque;
        p.advance(&mut st, command, PERIOD, |dt, x| {
            let (q, qd) = hand_path(t0 + dt);
            let tau = 300.0 * (q - x[2]) + 3.0 * (qd - x[3]);
            hand.push(tau);
            tau
        });
    }
    Ok(rms(&hand))
}

/// The motor torques of Table 3.3's open-loop runs, N·m at the motor
/// (the table's 0, ±3, ±5, ±10 N·cm).
pub const TABLE_3_3_COMMANDS: [f64; 7] = [0.0, 0.03, -0.03, 0.05, -0.05, 0.10, -0.10];

/// Table 3.3: the joint open-loop in torque mode at a constant motor
/// torque `command` (the thesis's first experiment of §3.2), while a hand
/// moves the link: from 0.2 s it guides the link out and back along
/// `±A (1 − cos(2π t/T))/2`, `T = 1` s, `A = 0.477` rad (peak 1.5 rad/s,
/// the table's speeds; the sign of the command's), through the stiff
/// contact of [`passive_run`] limited to the drive's rated 16 N·m (§3.2;
/// the unlimited contact pulled up to 48 N·m on a plant whose link stuck);
/// at zero command it holds the link still (the table's 0.02 rad/s). The estimator runs through
/// [`JointConfig::measure`] with the command as the motor-torque reading.
/// Returns the largest `|τ̂_t − τ_t|` from 0.2 s on, N·m.
///
/// The thesis states neither the hand's path nor its force; the path is
/// chosen to reach the table's speeds, and the hand's torque follows from
/// the motor's and the joint's dynamics.
fn table_3_3_run(
    plant: &JointPlant,
    seed: u64,
    params: &JointParams,
    model: &KinematicErrorModel,
    command: f64,
) -> Table33Run {
    const T: f64 = 1.0;
    const A: f64 = 1.5 * T / PI;
    // The drive's rated torque (§3.2): the hand pushes no harder.
    const HAND_LIMIT: f64 = 16.0;
    let jc = JointConfig::<f64>::new(params);
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 23);
    let mut p = plant.clone();
    p.payload = 0.0;
    let mut st = p.rest(0.0, seed);
    let r0 = p.read(&st, &mut rng);
    let mut js = start_state(&jc, &r0, model);
    let amplitude = A * command.signum();
    let hand_path = |t: f64| {
        let s = t - SETTLE;
        if !(0.0..=T).contains(&s) {
            return (0.0, 0.0);
        }
        let w = TAU / T;
        (
            amplitude * (1.0 - (w * s).cos()) / 2.0,
            amplitude * w * (w * s).sin() / 2.0,
        )
    };
    let mut out = Table33Run {
        command,
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
        trace: Vec::new(),
    };
    let ticks = ((SETTLE + T + 0.2) / PERIOD).round() as usize;
    for k in 0..ticks {
        let t0 = k as f64 * PERIOD;
        let r = p.read(&st, &mut rng);
        let truth = p.transmitted(&st, &st.x);
        let m = jc.measure(&mut js, &readings(&r, command));
        if t0 >= SETTLE {
            let e = m.joint_torque_si() - truth;
            out.min = out.min.min(e);
            out.max = out.max.max(e);
            out.trace.push(TorqueSample {
                time: t0,
                truth,
                estimate: m.joint_torque_si(),
            });
        }
        p.advance(&mut st, command, PERIOD, |dt, x| {
            let (q, qd) = hand_path(t0 + dt);
            (300.0 * (q - x[2]) + 3.0 * (qd - x[3])).clamp(-HAND_LIMIT, HAND_LIMIT)
        });
    }
    out
}

/// One sample of a figure's torque trace (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueSample {
    /// Time from the start of the run, s.
    pub time: f64,
    /// The plant's transmitted joint torque `τ_t`, N·m (what the F/T
    /// sensor of §3.2 measures).
    pub truth: f64,
    /// The library's estimate `τ̂_t` (eq. 3.8–3.10), N·m.
    pub estimate: f64,
}

/// One point of the §3.1 calibration: the plant's true kinematic error at
/// one link angle of the zero-load revolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationSample {
    /// Link (output) angle `θ_fo`, rad.
    pub link: f64,
    /// Motor (wave-generator) angle `θ_m` at zero load, rad; the
    /// estimator's `θ_wi` is `−θ_m`.
    pub motor: f64,
    /// The plant's kinematic error there, output-side rad.
    pub error: f64,
}

/// One Table 3.3 run ([`TABLE_3_3_COMMANDS`]): the signed extremes of
/// `τ̂_t − τ_t` and the trace, from 0.2 s on.
#[derive(Debug, Clone, PartialEq)]
pub struct Table33Run {
    /// Constant motor torque, N·m.
    pub command: f64,
    /// Smallest `τ̂_t − τ_t`, N·m.
    pub min: f64,
    /// Largest `τ̂_t − τ_t`, N·m.
    pub max: f64,
    /// The trace.
    pub trace: Vec<TorqueSample>,
}

impl Table33Run {
    /// Largest `|τ̂_t − τ_t|`, N·m.
    pub fn peak(&self) -> f64 {
        self.max.abs().max(self.min.abs()).max(0.0)
    }
}

/// The traces behind the chapter-3 figures for one `(plant, seed)` of the
/// joint family: the same runs as [`run_joint`]'s (same seeds, the 4 ms
/// preset `table_4_1_at(0.004)` with the fitted eq. (3.7)), so the numbers
/// they give equal its metrics for that run.
#[derive(Debug, Clone, PartialEq)]
pub struct JointFigureRun {
    /// Index of the plant in the family.
    pub plant: usize,
    /// Seed of the run.
    pub seed: u64,
    /// Eq. (3.7) fitted from the plant's encoders (§3.1).
    pub fitted: KinematicErrorModel,
    /// RMS of the fit's residual over RMS of the true error
    /// ([`JointRunMetrics::ke_fit_residual`]).
    pub ke_fit_residual: f64,
    /// The true kinematic error at the calibration points, both
    /// directions (forward first).
    pub calibration: Vec<CalibrationSample>,
    /// Fig. 3.6: the tracking run with the payload `G sin θ_l`, from 0.2 s.
    pub tracking: Vec<TorqueSample>,
    /// Fig. 3.8: the payload cut at 1 s (whole run).
    pub payload_cut: Vec<TorqueSample>,
    /// [`JointRunMetrics::step_share`].
    pub step_share: f64,
    /// Table 3.3: one run per entry of [`TABLE_3_3_COMMANDS`], in order.
    pub table_3_3: Vec<Table33Run>,
}

/// The chapter-3 figure runs on `family[index]` with `seed`: the runs the
/// registry makes for that plant and seed (equal metrics), with their
/// traces. Errors: an index outside the family, or a library parameter
/// error.
pub fn figure_run(
    family: &[JointPlant],
    index: usize,
    seed: u64,
) -> Result<JointFigureRun, ClaimError> {
    let plant = family
        .get(index)
        .ok_or(ClaimError::NoRuns { name: "family" })?;
    let preset = JointParams::table_4_1_at(PERIOD).map_err(|_| ClaimError::NoRuns {
        name: "table_4_1_at(0.004)",
    })?;
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 7);
    let st = plant.rest(0.0, seed);
    let (model, residual, calibration) = fit_kinematic_error_samples(plant, &st, &mut rng)?;
    let fitted = with_kinematic_error(&preset, Some(model))?;
    let shadows = [
        TorqueEstimatorConfig::<f64>::new(
            &with_kinematic_error(&preset, None)?.settings().estimator,
        ),
        TorqueEstimatorConfig::<f64>::new(
            &with_kinematic_error(&preset, Some(KinematicErrorModel::table_3_2()))?
                .settings()
                .estimator,
        ),
    ];
    let tr = tracking(plant, seed, &fitted, &shadows, &model);
    let (step_share, payload_cut) = payload_cut(plant, seed, &fitted, &model);
    Ok(JointFigureRun {
        plant: index,
        seed,
        fitted: model,
        ke_fit_residual: residual,
        calibration,
        tracking: tr.trace,
        payload_cut,
        step_share,
        table_3_3: TABLE_3_3_COMMANDS
            .iter()
            .map(|&c| table_3_3_run(plant, seed, &fitted, &model, c))
            .collect(),
    })
}

/// Everything one `(plant, seed)` run measures.
fn run_one(
    plant: &JointPlant,
    index: usize,
    seed: u64,
    preset: &JointParams,
    thesis: &JointParams,
) -> Result<JointRunMetrics, ClaimError> {
    let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9) ^ 7);
    let st = plant.rest(0.0, seed);
    let (model, residual) = fit_kinematic_error(plant, &st, &mut rng)?;
    let fitted = with_kinematic_error(preset, Some(model))?;
    let shadows = [
        TorqueEstimatorConfig::<f64>::new(
            &with_kinematic_error(preset, None)?.settings().estimator,
        ),
        TorqueEstimatorConfig::<f64>::new(
            &with_kinematic_error(preset, Some(KinematicErrorModel::table_3_2()))?
                .settings()
                .estimator,
        ),
    ];
    let tr = tracking(plant, seed, &fitted, &shadows, &model);
    let thesis_fitted = with_kinematic_error(thesis, Some(model))?;
    let peak = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (link_none, _) = active_law_run(plant, seed, &fitted, &model, Feedback::None);
    let (link_sensor, _) = active_law_run(plant, seed, &fitted, &model, Feedback::Sensor);
    let (link_estimate, preset_ratio) =
        active_law_run(plant, seed, &fitted, &model, Feedback::Estimate);
    let (_, thesis_ratio) = active_law_run(plant, seed, &thesis_fitted, &model, Feedback::Estimate);
    let best = |source: Feedback| -> Result<f64, ClaimError> {
        let mut b = f64::INFINITY;
        for g in PASSIVE_GAINS {
            b = b.min(passive_run(plant, seed, &fitted, &model, source, g)?);
        }
        Ok(b)
    };
    Ok(JointRunMetrics {
        plant: index,
        seed,
        ke_fit_residual: residual,
        est_peak_fit: peak(&tr.est_fit),
        est_rms_fit: rms(&tr.est_fit),
        est_peak_none: peak(&tr.est_none),
        est_rms_none: rms(&tr.est_none),
        est_rms_table: rms(&tr.est_table),
        preset_bound_ratio: preset_ratio,
        preset_active_share: tr.active_share,
        thesis_bound_ratio: thesis_ratio,
        link_rms_none: link_none,
        link_rms_sensor: link_sensor,
        link_rms_estimate: link_estimate,
        step_share: payload_cut(plant, seed, &fitted, &model).0,
        hand_rms_none: passive_run(plant, seed, &fitted, &model, Feedback::None, 1.0)?,
        hand_rms_estimate: best(Feedback::Estimate)?,
        hand_rms_sensor: best(Feedback::Sensor)?,
        table_3_3_peak: TABLE_3_3_COMMANDS
            .iter()
            .map(|&c| table_3_3_run(plant, seed, &fitted, &model, c).peak())
            .fold(0.0, f64::max),
    })
}

/// Run every plant of `family` with seeds `0..seeds` on `threads` worker
/// threads (at least one). Errors: an empty family or zero seeds, or a
/// library parameter error.
pub fn run_joint(
    family: &[JointPlant],
    seeds: u64,
    threads: usize,
) -> Result<Vec<JointRunMetrics>, ClaimError> {
    if family.is_empty() {
        return Err(ClaimError::NoRuns { name: "family" });
    }
    if seeds == 0 {
        return Err(ClaimError::NoRuns { name: "seeds" });
    }
    let preset = JointParams::table_4_1_at(PERIOD).map_err(|_| ClaimError::NoRuns {
        name: "table_4_1_at(0.004)",
    })?;
    let thesis = JointParams::table_4_1()?;
    let jobs: Vec<(usize, u64)> = (0..family.len())
        .flat_map(|p| (0..seeds).map(move |s| (p, s)))
        .collect();
    let threads = threads.clamp(1, jobs.len());
    let results: Vec<Result<JointRunMetrics, ClaimError>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|w| {
                let jobs = &jobs;
                let (preset, thesis) = (&preset, &thesis);
                scope.spawn(move || {
                    jobs.iter()
                        .skip(w)
                        .step_by(threads)
                        .map(|&(p, s)| run_one(&family[p], p, s, preset, thesis))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let mut per: Vec<Vec<_>> = handles
            .into_iter()
            .map(|h| h.join().unwrap_or_default())
            .collect();
        // Back into job order.
        let mut out = Vec::with_capacity(jobs.len());
        for i in 0..jobs.len() {
            let w = i % threads;
            if !per[w].is_empty() {
                out.push(per[w].remove(0));
            }
        }
        out
    });
    if results.len() != jobs.len() {
        return Err(ClaimError::NoMetrics);
    }
    results.into_iter().collect()
}

/// The chapter 3–4 claims, criteria fixed here before any run. Every one
/// is judged at the thesis's 4 ms (§6.3) on the joint family.
pub fn claims() -> Result<Vec<Claim>, ParamError> {
    use Condition::{AtLeast, AtMost};
    let c =
        |s: Condition, ss: f64, r: Condition, rs: f64| Criterion::try_new(rule(s, ss), rule(r, rs));
    const CUT: &str = "a claim that one variant is better: a cut of at least the stated \
        share in 80 % of the runs supports it, no cut (or worse) in half of them refutes it";
    const PAIR: &str = "'comparable': within 1.5 times the torque sensor's result in 80 % of \
        the runs supports it; twice it or more in half of them refutes it";
    // Theorem 1 is a guarantee: it must hold in every run; a violation in
    // 5 % of the runs (one in 20 seeds) refutes it.
    let theorem = c(AtMost(1.0), 1.0, AtLeast(1.0 + 1e-9), 0.05)?;
    Ok(vec![
        Claim {
            id: "3.1-fit",
            quote: "By using Fourier curve fitting, we can model the kinematic error as \
                    following [eq. 3.3-3.7]",
            figure: "Fig. 3.1-3.3, Table 3.2",
            metric_name: "RMS(e_k - fitted 3.7)/RMS(e_k) over one output revolution, fit from \
                the plant's encoders at zero load, both directions",
            unit: "",
            metric: Metric::Joint(|m| m.ke_fit_residual),
            operating_point: "quasi-static calibration",
            criterion: c(AtMost(0.5), 0.8, AtLeast(0.8), 0.5)?,
            justification: "the figures show the fit following the measured error; a residual \
                of half the error's RMS (75 % of its variance explained) is the least such a \
                figure shows; at 0.8 the model explains under 36 % of it",
        },
        Claim {
            id: "3.1-low",
            quote: "the torque estimation accuracy will be very low if we don't consider \
                    kinematic errors",
            figure: "Table 3.1 (SHD-17-100: 4.1 N·m, 25 %)",
            metric_name: "peak |τ̂_t − τ_t| without a kinematic-error model, tracking run",
            unit: "N·m",
            metric: Metric::Joint(|m| m.est_peak_none),
            operating_point: "4 ms",
            criterion: c(AtLeast(1.6), 0.8, AtMost(1.0), 0.5)?,
            justification: "'very low accuracy': at least 10 % of the 16 N·m rated torque; at \
                1 N·m or less it is as good as the thesis says its full method is (Fig. 3.6)",
        },
        Claim {
            id: "3.1-bound",
            quote: "Max Torque error (Nm) 4.1 [SHD-17-100] = K_2 × max kinematic error (3.1)",
            figure: "Table 3.1",
            metric_name: "peak |τ̂_t − τ_t| without a kinematic-error model, tracking run",
            unit: "N·m",
            metric: Metric::Joint(|m| m.est_peak_none),
            operating_point: "4 ms",
            criterion: c(AtMost(4.1), 0.8, AtLeast(5.2), 0.5)?,
            justification: "recomputed: 9.4e3 N·m/rad × 4.4e-4 rad = 4.14 N·m; the table \
                bounds the error the kinematic error causes, so it holds if the peak stays \
                under it; 25 % beyond it (5.2 N·m) in half the runs refutes it",
        },
        Claim {
            id: "3.3-reduction",
            quote: "To achieve a relative accurate torque estimation, the kinematic error \
                    must be included",
            figure: "§3.1, eq. (3.7)-(3.9)",
            metric_name: "1 − RMS error(fitted 3.7)/RMS error(no model), same readings",
            unit: "",
            metric: Metric::Joint(JointRunMetrics::ke_reduction),
            operating_point: "4 ms",
            criterion: c(AtLeast(0.25), 0.8, AtMost(0.0), 0.5)?,
            justification: CUT,
        },
        Claim {
            id: "3.6-level",
            quote: "The error in torque estimation is around 1Nm, which is comparable with \
                    the commercial F/T sensor",
            figure: "Fig. 3.6 (slow load changes)",
            metric_name: "peak |τ̂_t − τ_t|, fitted (3.7), 4 ms preset tracking a slow sine \
                with a payload G sin θ_l",
            unit: "N·m",
            metric: Metric::Joint(|m| m.est_peak_fit),
            operating_point: "4 ms",
            criterion: c(AtMost(1.5), 0.8, AtLeast(2.0), 0.5)?,
            justification: "'around 1 N·m' read as within +50 %; 2 N·m is twice the claim \
                and the mode manager's entry threshold",
        },
        Claim {
            id: "3.3-table",
            quote: "Max Torque Error (Nm) 0.3 0.2 0.6 0.8 0.7 1.0 0.6; Min Torque Error \
                    (Nm) -0.5 -1.2 -1.1 -1.2 -1.3 -0.9 -2.3",
            figure: "Table 3.3 (open loop, 0, ±3, ±5, ±10 N·cm)",
            metric_name: "largest |τ̂_t − τ_t| over the seven motor torques, fitted (3.7), a \
                hand moving the link at up to 1.5 rad/s",
            unit: "N·m",
            metric: Metric::Joint(|m| m.table_3_3_peak),
            operating_point: "4 ms",
            criterion: c(AtMost(2.3), 0.8, AtLeast(3.0), 0.5)?,
            justification: "2.3 N·m is the table's largest error (−2.3 at −10 N·cm); 3 N·m, \
                30 % above it, is an error the table does not describe",
        },
        Claim {
            id: "3.8-step",
            quote: "The result shows the proposed estimation has a relatively good dynamic \
                    response",
            figure: "Fig. 3.8 (payload cut)",
            metric_name: "share of the true torque step the estimate shows 40-100 ms after \
                a 1.5 N·m payload is cut, joint holding position",
            unit: "",
            metric: Metric::Joint(|m| m.step_share),
            operating_point: "4 ms",
            criterion: c(AtLeast(0.8), 0.8, AtMost(0.5), 0.5)?,
            justification: "a 'good dynamic response' shows most of a step within 25 ticks: \
                80 %; half of it or less is not good",
        },
        Claim {
            id: "4.3-jtf",
            quote: "To demonstrate the efficiency of the proposed torque estimation method, \
                    an active control with the joint torque feedback ... (A) zero, (C) estimated",
            figure: "Fig. 4.3, areas (A) vs (C)",
            metric_name: "1 − RMS link error with the estimate's feedback/with none, law 4.19 \
                of the 4 ms preset",
            unit: "",
            metric: Metric::Joint(JointRunMetrics::jtf_reduction),
            operating_point: "4 ms",
            criterion: c(AtLeast(0.2), 0.8, AtMost(0.0), 0.5)?,
            justification: CUT,
        },
        Claim {
            id: "4.3-sensor",
            quote: "(B) JTF from the F/T sensor, (C) JTF with the estimated torque",
            figure: "Fig. 4.3, areas (C) vs (B)",
            metric_name: "RMS link error with the estimate's feedback/with the sensor's",
            unit: "",
            metric: Metric::Joint(JointRunMetrics::jtf_estimate_over_sensor),
            operating_point: "4 ms",
            criterion: c(AtMost(1.5), 0.8, AtLeast(2.0), 0.5)?,
            justification: PAIR,
        },
        Claim {
            id: "T1-preset",
            quote: "the tracking error of each joint is uniformly ultimately bounded under \
                    the control law given by Eq.(4.19)",
            figure: "Theorem 1, eq. (4.29)-(4.31), 4 ms preset table_4_1_at(0.004)",
            metric_name: "max |θ_m − N q_d| after the reaching time / (r_S/λ + one count)",
            unit: "",
            metric: Metric::Joint(|m| m.preset_bound_ratio),
            operating_point: "4 ms",
            criterion: theorem,
            justification: "a theorem: every run within its bound",
        },
        Claim {
            id: "T1-table4.1",
            quote: "Theorem 1 with the design and control parameters of Table 4.1",
            figure: "Theorem 1, Table 4.1's gains (table_4_1())",
            metric_name: "max |θ_m − N q_d| after the reaching time / (r_S/λ + one count)",
            unit: "",
            metric: Metric::Joint(|m| m.thesis_bound_ratio),
            operating_point: "4 ms",
            criterion: theorem,
            justification: "a theorem: every run within its bound; the thesis's gains at \
                its own 4 ms period",
        },
        Claim {
            id: "4.5-active",
            quote: "While working in active mode, the developed robust adaptive controller \
                    ... can suppress uncertainties caused by sensor inaccuracies and noises",
            figure: "§4.5; mode manager of the 4 ms preset",
            metric_name: "share of ticks in Active while tracking (no interaction applied)",
            unit: "",
            metric: Metric::Joint(|m| m.preset_active_share),
            operating_point: "4 ms",
            criterion: c(AtLeast(0.999), 0.8, AtMost(0.99), 0.5)?,
            justification: "with no interaction the joint must stay in Active: any switch is \
                a false alarm; a run out of Active for 1 % of its ticks has failed",
        },
        Claim {
            id: "4.11-passive",
            quote: "With the proposed interactive force compensation technique, the joint \
                    can move freely without generating excessive internal force",
            figure: "Fig. 4.11, areas (A) vs (B); eq. (4.32)",
            metric_name: "1 − RMS hand torque with the estimate's feedback/with friction \
                compensation alone, hand back-driving 0.5 rad in 2 s",
            unit: "",
            metric: Metric::Joint(JointRunMetrics::passive_reduction),
            operating_point: "4 ms",
            criterion: c(AtLeast(0.3), 0.8, AtMost(0.0), 0.5)?,
            justification: "'move freely': the feedback must remove at least 30 % of the \
                hand's effort in 80 % of the runs; none removed in half refutes it",
        },
        Claim {
            id: "4.11-sensor",
            quote: "The estimated joint torque as well as the F/T sensor measurements are \
                    used as JTF to the passive mode controller",
            figure: "Fig. 4.11, areas (B) vs (C)",
            metric_name: "RMS hand torque with the estimate's feedback/with the sensor's",
            unit: "",
            metric: Metric::Joint(JointRunMetrics::passive_estimate_over_sensor),
            operating_point: "4 ms",
            criterion: c(AtMost(1.5), 0.8, AtLeast(2.0), 0.5)?,
            justification: PAIR,
        },
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::plants::joint::quick_joint_family;

    /// On a plant whose kinematic error has only eq. (3.7)'s content (one
    /// harmonic per output turn, two per wave-generator turn), the fit
    /// through the encoders recovers it: the residual is below 10 % of its
    /// RMS (the 2¹⁷-count link encoder's step is 4.8e-5 rad, averaged over
    /// 12 200 samples). A sign or angle convention mismatch with the
    /// estimator's `θ_wi = −θ_m` leaves a residual near or above 1.
    #[test]
    fn fit_recovers_a_kinematic_error_of_the_model_form() {
        let plant = quick_joint_family().remove(0);
        for seed in 0..3 {
            let mut st = plant.rest(0.0, seed);
            st.kinematic_error.wave_generator[2].0 = 0.0;
            st.kinematic_error.wave_generator[3].0 = 0.0;
            st.kinematic_error.ripple.0 = 0.0;
            let mut rng = SplitMix64::new(seed);
            let (_, residual) = fit_kinematic_error(&plant, &st, &mut rng).unwrap();
            assert!(residual < 0.1, "seed {seed}: {residual}");
        }
    }

    /// The power-up state: started from the kinematic-error-aware motor
    /// position, the estimate of an unloaded joint at rest is within
    /// 0.5 N·m (two motor counts seen as torque) of zero, and so is
    /// `JointConfig::state`'s; started with the motor at `N θ_l` (no
    /// kinematic error) it is off by `K e_k(θ_l)`, more than 0.5 N·m for
    /// some of the seeds.
    #[test]
    fn power_up_state_accounts_for_the_kinematic_error() {
        let mut plant = quick_joint_family().remove(0);
        plant.payload = 0.0;
        let preset = JointParams::table_4_1_at(PERIOD).unwrap();
        let mut worst_naive = 0.0f64;
        for seed in 0..6 {
            let st = plant.rest(0.0, seed);
            let mut rng = SplitMix64::new(seed);
            let (model, _) = fit_kinematic_error(&plant, &st, &mut rng).unwrap();
            let params = with_kinematic_error(&preset, Some(model)).unwrap();
            let cfg = JointConfig::<f64>::new(&params);
            let r = plant.read(&st, &mut rng);
            let hold = JointTarget::from_si(0.0, 0.0, 0.0);
            let mut js = start_state(&cfg, &r, &model);
            let aware = cfg
                .update(&mut js, &readings(&r, 0.0), &hold)
                .joint_torque_si();
            // The library's own power-up state finds the same start.
            let mut js = cfg.state(r.link_count, r.motor_counter);
            let library = cfg
                .update(&mut js, &readings(&r, 0.0), &hold)
                .joint_torque_si();
            // The motor at `N θ_l`, ignoring the kinematic error.
            let l = 1i64 << 17;
            let c = r.link_count as i64;
            let c = if c >= l / 2 { c - l } else { c };
            let motor = (c * MOTOR_COUNTS as i64 * RATIO as i64).div_euclid(l);
            let mut js = cfg.state_at(motor, r.motor_counter);
            let naive = cfg
                .update(&mut js, &readings(&r, 0.0), &hold)
                .joint_torque_si();
            assert!(aware.abs() < 0.5, "seed {seed}: {aware} (naive {naive})");
            assert!(
                library.abs() < 0.5,
                "seed {seed}: {library} (naive {naive})"
            );
            worst_naive = worst_naive.max(naive.abs());
        }
        assert!(worst_naive > 0.5, "{worst_naive}");
    }

    /// The figure runs are the registry's runs: on the same plant and
    /// seed they give the same fit residual, tracking peak, step share and
    /// Table 3.3 peak as [`run_joint`].
    #[test]
    fn figure_run_matches_the_registry_run() {
        let family = quick_joint_family();
        let m = run_joint(&family[..1], 1, 1).unwrap().remove(0);
        let f = figure_run(&family, 0, 0).unwrap();
        assert_eq!((f.plant, f.seed), (m.plant, m.seed));
        assert_eq!(f.ke_fit_residual, m.ke_fit_residual);
        assert_eq!(f.step_share, m.step_share);
        let peak = f
            .tracking
            .iter()
            .map(|s| (s.estimate - s.truth).abs())
            .fold(0.0, f64::max);
        assert_eq!(peak, m.est_peak_fit);
        let table = f.table_3_3.iter().map(Table33Run::peak).fold(0.0, f64::max);
        assert_eq!(table, m.table_3_3_peak);
        assert_eq!(f.table_3_3.len(), TABLE_3_3_COMMANDS.len());
        assert_eq!(f.calibration.len(), 2 * 100 * 61);
        assert!(figure_run(&family, family.len(), 0).is_err());
    }

    #[test]
    fn wrap_brings_angles_into_half_open_range() {
        assert!((wrap(3.0 * PI) + PI).abs() < 1e-12);
        assert!((wrap(0.25) - 0.25).abs() < 1e-15);
        assert!((wrap(-TAU + 0.5) - 0.5).abs() < 1e-12);
    }
}
