//! Closed-loop scenarios of thesis ch. 4 on the simulated robot: active
//! tracking with and without joint-torque feedback (§4.4.1, Fig. 4.2–4.3),
//! the passive mode back-driven by a hand (§4.4.2, Fig. 4.11–4.12), the
//! payload drop of §3.2 (Fig. 3.8), and the mode manager switching on the
//! interaction torque and reacting to a collision.
//!
//! The control laws, the estimator and the mode manager are the library's
//! ([`crate::control`], [`crate::estimation`]) on `f64`; the plant is
//! [`Mrr`]. The controller sees only the sampled sensors: motor encoder
//! counts, link encoder counts, the F/T sensor, and its own previous
//! command.
//!
//! # Signs
//! The plant's motor angle is `q_m = N q_l` at zero torsion (chapter 4),
//! its transmission torque `τ_t` is the torque the drive applies to the
//! link (eq. 4.1), which is what the F/T sensor reads and what
//! [`ControlInput::joint_torque`] expects. The estimator is fed as errata
//! E13 prescribes ([`estimator_counts`]: motor counter negated) and returns
//! `−τ_t`, so the feedback is `τ̂_t = −estimate`.
//!
//! # Motor speed
//! The laws need `q̇_m`. It is measured as the count difference over a
//! fixed window `w` (at least one sample): `q̇_m ≈ (c_k − c_{k−w})·Δ/(w T)`
//! with `Δ = 2π/M`. A window of 4 ms gives the same speed resolution
//! (`Δ/4 ms = 0.785 rad/s` for the thesis's 2000-count encoder) at every
//! sample period, with a lag of half the window.

use super::experiments::{estimator_counts, ErrorStats, Models};
use super::mrr::{misaligned, ModuleParams, Mrr, Sensors};
use crate::control::{
    ControlInput, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams,
    RobustAdaptiveState,
};
use crate::estimation::torque::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorState,
};
use crate::harmonic_drive::kinematic_error::KinematicErrorModel;
use core::f64::consts::TAU;
use std::collections::VecDeque;
use std::vec::Vec;

/// Which joint torque the active law feeds back (the areas of Fig. 4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointTorqueFeedback {
    /// (A): no joint-torque feedback, `τ̂_t = 0`.
    None,
    /// (B): the F/T sensor's reading.
    Sensor,
    /// (C): the estimate of eq. (3.8)–(3.10) from the two encoders.
    Estimated,
}

impl JointTorqueFeedback {
    /// Label for tables: `"A: none"`, `"B: F/T sensor"`, `"C: estimate"`.
    pub fn label(self) -> &'static str {
        match self {
            JointTorqueFeedback::None => "A: none",
            JointTorqueFeedback::Sensor => "B: F/T sensor",
            JointTorqueFeedback::Estimated => "C: estimate",
        }
    }
}

/// Windowed count-difference speed of one encoder (module docs).
#[derive(Debug, Clone)]
pub struct CountSpeed {
    history: VecDeque<i64>,
    window: usize,
    scale: f64,
}

impl CountSpeed {
    /// A meter over `window` seconds (at least one sample of `period`) for
    /// an encoder of `rad_per_count`.
    pub fn new(window: f64, period: f64, rad_per_count: f64) -> Self {
        let w = ((window / period).round() as usize).max(1);
        CountSpeed {
            history: VecDeque::with_capacity(w + 1),
            window: w,
            scale: rad_per_count / (w as f64 * period),
        }
    }

    /// Push a reading; the speed in rad/s (0 until the window is full,
    /// then the windowed difference).
    pub fn update(&mut self, counts: i64) -> f64 {
        self.history.push_back(counts);
        if self.history.len() > self.window + 1 {
            self.history.pop_front();
        }
        if self.history.len() <= self.window {
            // Shorter history at start: difference over what is there.
            let n = self.history.len() - 1;
            if n == 0 {
                return 0.0;
            }
            let d = counts - self.history[0];
            return d as f64 * self.scale * self.window as f64 / n as f64;
        }
        (counts - self.history[0]) as f64 * self.scale
    }
}

/// The ch. 3 estimator on `f64` for the thesis joint (eq. 2.30 model,
/// Table 3.2 kinematic error, which is the plant's), with its state.
#[derive(Debug, Clone)]
pub struct JointTorqueEstimator {
    config: TorqueEstimatorConfig<f64>,
    state: TorqueEstimatorState,
    module: ModuleParams,
}

impl JointTorqueEstimator {
    /// An estimator for `module` initialized from the readings `s` of
    /// joint `i`.
    pub fn new(module: &ModuleParams, s: &Sensors, i: usize) -> Self {
        let models = Models::shd_17_100();
        let p = TorqueEstimatorParams::try_new(
            models.proposed,
            Some(KinematicErrorModel::table_3_2()),
            module.link_encoder.counts_per_rev,
            module.motor_encoder.counts_per_rev,
            60.0,
        )
        .expect("thesis estimator parameters are valid");
        let config = TorqueEstimatorConfig::new(&p);
        let (_, c0) = estimator_counts(module, s, i);
        let state = config.state(-s.motor_counts[i], c0);
        JointTorqueEstimator {
            config,
            state,
            module: module.clone(),
        }
    }

    /// `τ̂_t` (eq. 4.1 sign, N·m) from the readings of joint `i` and the
    /// motor torque being applied (chapter-4 sign, N·m).
    pub fn joint_torque(&mut self, s: &Sensors, i: usize, motor_torque: f64) -> f64 {
        let (cl, cm) = estimator_counts(&self.module, s, i);
        -self
            .config
            .update(&mut self.state, cl, cm, motor_torque)
            .torque
    }
}

/// The thesis joint of §4.4.1 carrying joints 2 and 3 and the link as
/// payload (Table 4.1: link 0.64 kg, 0.45 m; `M2 = M3 = 1.2 kg`, here both
/// at the link's end, where the wrist of Fig. 3.5a sits), with its axis
/// tilted by `tilt` (rad) from the vertical about the base `x` axis so
/// that gravity loads it by `m g d sin(tilt)` at most.
pub fn payload_joint(tilt: f64) -> ModuleParams {
    let mut m = ModuleParams::thesis_joint().with_payload(2.4, [0.45, 0.0, 0.0]);
    m.axis = misaligned([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], tilt);
    m
}

/// Configuration of the active-mode tracking experiment (Fig. 4.2–4.3).
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingConfig {
    /// The law's design (its `sample_period` is the control period).
    pub design: RobustAdaptiveDesign,
    /// The joint-torque feedback used.
    pub feedback: JointTorqueFeedback,
    /// Axis tilt from the vertical, rad ([`payload_joint`]).
    pub tilt: f64,
    /// Link-side desired trajectory `q_l^d = A (1 − cos(2π t/P))`:
    /// amplitude `A`, rad.
    pub amplitude: f64,
    /// Its period `P`, s.
    pub period: f64,
    /// Duration, s.
    pub duration: f64,
    /// Errors before this time are not counted (start transient), s.
    pub settle: f64,
    /// Speed window, s (module docs).
    pub speed_window: f64,
    /// RK4 steps per control period.
    pub steps_per_period: usize,
    /// Noise seed.
    pub seed: u64,
}

impl TrackingConfig {
    /// Table 4.1's law at sample period `t`, the trajectory
    /// `0.25 (1 − cos(2π t/4 s))` rad (link), 12 s (three periods) with
    /// 2 s settling, a 20° axis tilt, a 4 ms speed window and 0.1 ms
    /// integration steps.
    pub fn table_4_1(feedback: JointTorqueFeedback, t: f64) -> Self {
        let mut design = RobustAdaptiveDesign::table_4_1();
        design.sample_period = t;
        TrackingConfig {
            design,
            feedback,
            tilt: 20f64.to_radians(),
            amplitude: 0.25,
            period: 4.0,
            duration: 12.0,
            settle: 2.0,
            speed_window: 4e-3,
            steps_per_period: ((t / 1e-4).round() as usize).max(1),
            seed: 11,
        }
    }
}

/// Results of one tracking run.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingResult {
    /// The feedback used.
    pub feedback: JointTorqueFeedback,
    /// Sample period, s.
    pub sample_period: f64,
    /// Link-side tracking error `q_l − q_l^d` (true plant angle), rad.
    pub link_error: ErrorStats,
    /// Motor-side tracking error `q_m − q_m^d` (true plant angle), rad.
    pub motor_error: ErrorStats,
    /// Fed-back joint torque minus the true `τ_t`, N·m (zeros for A: its
    /// "error" is then `−τ_t`, reported too).
    pub feedback_error: ErrorStats,
    /// Fraction of samples with the motor torque at its limit.
    pub saturated_fraction: f64,
    /// Largest |r| the law computed after settling, rad/s.
    pub max_sliding: f64,
}

impl ErrorStats {
    /// `max(|max|, |min|)`.
    pub fn max_abs(&self) -> f64 {
        self.max.abs().max(self.min.abs())
    }
}

/// Desired link trajectory `A (1 − cos ω t)` and its two derivatives.
fn raised_cosine(a: f64, period: f64, t: f64) -> (f64, f64, f64) {
    let w = TAU / period;
    let (s, c) = libm::sincos(w * t);
    (a * (1.0 - c), a * w * s, a * w * w * c)
}

/// The active-mode experiment of §4.4.1: eq. (4.19) with Table 4.1's
/// design tracks [`TrackingConfig`]'s trajectory with the chosen feedback.
pub fn active_tracking(cfg: &TrackingConfig) -> TrackingResult {
    let module = payload_joint(cfg.tilt);
    let t = cfg.design.sample_period;
    let n = module.drive.ratio;
    let params = RobustAdaptiveParams::try_new(cfg.design).expect("valid design");
    let law = RobustAdaptiveConfig::<f64>::new(&params);
    let mut st: RobustAdaptiveState<f64> = law.initial_state();
    let mut robot = Mrr::try_new(
        vec![module.clone()],
        [0.0, 0.0, -9.81],
        t,
        cfg.steps_per_period,
        cfg.seed,
    )
    .expect("valid plant");
    // Start holding the initial position: the drive carries the gravity
    // torque (as after a power-up in position hold).
    let g0 = robot.gravity_torques()[0];
    let qm0 = robot.motor_angles_for_torque(&[0.0], &[g0])[0];
    robot.set_state(&[0.0], &[qm0], &[0.0], &[0.0]);
    let rad = module.motor_encoder.rad_per_count();
    let mut speed = CountSpeed::new(cfg.speed_window, t, rad);
    let s0 = robot.read_sensors();
    let mut est = JointTorqueEstimator::new(&module, &s0, 0);
    let mut last_torque = 0.0;
    let (mut le, mut me, mut fe) = (Vec::new(), Vec::new(), Vec::new());
    let (mut sat, mut count, mut max_r) = (0usize, 0usize, 0.0f64);
    let total = (cfg.duration / t).round() as usize;
    for k in 0..total {
        let time = k as f64 * t;
        let s = robot.read_sensors();
        let qm = s.motor_counts[0] as f64 * rad;
        let vm = speed.update(s.motor_counts[0]);
        let tau_est = est.joint_torque(&s, 0, last_torque);
        let fb = match cfg.feedback {
            JointTorqueFeedback::None => 0.0,
            JointTorqueFeedback::Sensor => s.link_torque[0],
            JointTorqueFeedback::Estimated => tau_est,
        };
        let (qd, vd, ad) = raised_cosine(cfg.amplitude, cfg.period, time);
        let x = ControlInput {
            desired_position: n * qd,
            desired_velocity: n * vd,
            desired_acceleration: n * ad,
            motor_position: qm,
            motor_velocity: vm,
            joint_torque: fb,
            ..Default::default()
        };
        let o = law.update(&mut st, &x);
        if time >= cfg.settle {
            let truth = robot.transmission_torques()[0];
            le.push(robot.link_angles()[0] - qd);
            me.push(robot.motor_angles()[0] - n * qd);
            fe.push(fb - truth);
            sat += o.saturated as usize;
            count += 1;
            max_r = max_r.max(o.sliding.abs());
        }
        last_torque = o.torque;
        robot.set_motor_torque(&[o.torque]);
        for _ in 0..robot.steps_per_period {
            robot.step();
        }
    }
    TrackingResult {
        feedback: cfg.feedback,
        sample_period: t,
        link_error: ErrorStats::of(le),
        motor_error: ErrorStats::of(me),
        feedback_error: ErrorStats::of(fe),
        saturated_fraction: sat as f64 / count.max(1) as f64,
        max_sliding: max_r,
    }
}

/// One random case of the ultimate-bound check (Theorem 1, eq.
/// 4.28–4.31): a plant, a reconfiguration, a trajectory and a torque
/// feedback whose error is bounded.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundCase {
    /// Motor friction of the plant (elasto-plastic, [`super::FrictionParams`]):
    /// viscous `b` (N·m·s/rad), Coulomb `f_c` and static excess `f_s` (N·m).
    pub friction: [f64; 3],
    /// Stribeck shape of the plant `f_τ`, s²/rad² (known to the law, see
    /// [`bound_design`]).
    pub stribeck: f64,
    /// Axis misalignment from the vertical, rad (reconfiguration).
    pub tilt: f64,
    /// Direction (rad, about the vertical) of the misalignment's axis.
    pub tilt_direction: f64,
    /// Payload mass, kg, at `payload_distance` m along the link.
    pub payload: f64,
    /// Payload distance, m.
    pub payload_distance: f64,
    /// Link trajectory `A (1 − cos(2π t/P))`: `A`, rad.
    pub amplitude: f64,
    /// Its period `P`, s.
    pub period: f64,
    /// Fraction of `ρ_τt` used by the feedback error: the fed-back torque
    /// is the true `τ_t(t_k)` plus a uniform error in
    /// `±error_fraction·ρ_τt`. Above 1 the assumption of eq. (4.14) is
    /// violated.
    pub error_fraction: f64,
    /// Period of the feedback error's sign (a square wave of
    /// `error_fraction·ρ_τt` with uniform jitter of the same amplitude
    /// when positive; 0 for pure uniform noise), s.
    pub error_square_period: f64,
    /// Noise seed.
    pub seed: u64,
}

/// The design used by the ultimate-bound check: Table 4.1's structure with
/// boundary layers wide enough that the sampled law at `T = 50 µs` stays
/// inside its layers (the step ratio of errata E22 below 1 at the
/// trajectory speeds), and bounds that cover the simulated plant:
///
/// * friction box `b ∈ [0, 1e-4]`, `f_c, f_s ∈ [0, 0.012]` N·m, the
///   Stribeck shape fixed at the plant's `f_τ` (min = max, `μ_4 = 0`):
///   with `f_τ` known, the friction is linear in the adapted parameters
///   (eq. 4.16–4.17); an unknown `f_τ` leaves a linearization remainder up
///   to `f_s Δf_τ/(e f_τ)` that no bound of Table 4.1 names;
/// * `ρ_f = f_c,max + f_s,max` (`FrictionBounds::boundary_layer_bound`)
///   and `ρ_fq = f_c,max + f_s,max`: the plant's elasto-plastic friction
///   is `clamp(σ0(q − z) + σ1 q̇, ±F(q̇)) + b q̇`, so
///   `|f_m − b q̇ − F(q̇) sat(q̇, ε_q̇)| ≤ 2F(q̇) ≤ 2(f_c + f_s)`, which
///   `ρ_f + ρ_fq` covers (they enter eq. 4.19 and 4.28 only as a sum);
/// * `ρ_base = 100 rad/s²`: the base is fixed (`τ_base = 0`);
/// * `ρ_τt = 1 N·m` (Table 4.1); the case's feedback error stays below it;
/// * the plant's kinematic error is removed (its gradient term
///   `τ_t ∂θ_err/∂θ_w` would be one more motor-side disturbance);
/// * `λ = 120`, `K_I = 10`, `μ = 0.1` (Table 4.1), `ε_r = 2 rad/s`,
///   `ε_q̇ = 2 rad/s`, `ε_F = [1000, 1, 1, 0.1]`,
///   `ρ_F = [1e-4, 1e-2, 1e-2, 1.0]`, `T = 50 µs`.
pub fn bound_design(stribeck: f64) -> RobustAdaptiveDesign {
    use crate::friction::{FrictionBounds, FrictionParams as Fp};
    let bounds = FrictionBounds::try_new(
        Fp::try_new(0.0, 0.0, 0.0, stribeck).expect("valid"),
        Fp::try_new(1e-4, 0.012, 0.012, stribeck).expect("valid"),
        [1e-4, 1e-2, 1e-2, 1.0],
    )
    .expect("valid box");
    let rho_f = bounds.boundary_layer_bound();
    RobustAdaptiveDesign {
        rotor_inertia: 1.14e-5,
        ratio: 100.0,
        lambda: 120.0,
        integral_gain: 10.0,
        adaptation_gain: [0.1, 0.1, 0.1, 0.0],
        eps_r: 2.0,
        eps_velocity: 2.0,
        eps_f: [1000.0, 1.0, 1.0, 0.1],
        uncertainty: crate::control::UncertaintyBounds {
            boundary_layer: rho_f,
            nonparametric_friction: 0.024,
            base_acceleration: 100.0,
            torque_estimate: 1.0,
        },
        friction_bounds: bounds,
        initial_friction: Fp {
            viscous: 5e-5,
            coulomb: 0.006,
            stribeck: 0.006,
            stribeck_shape: stribeck,
        },
        integral_limit: 0.1,
        torque_limit: 0.188,
        sample_period: 5e-5,
    }
}

/// The radius of Theorem 1's set with an extra, unmatched torque
/// disturbance `|d| ≤ δ` (N·m) in the motor equation — what sampling,
/// holding and quantization add to the continuous-time law.
///
/// *Derivation.* Let the applied (held, sampled) torque be
/// `τ_k = τ_c(t) + d(t)`, with `τ_c(t)` the law of eq. (4.19) evaluated on
/// the true continuous state at time `t` (same `τ̂_t`, integral and
/// estimates as the sample used). Eq. (4.22) gains `−d` on the right, and
/// eq. (4.28) becomes `V̇ ≤ −I_m λ r² + δ|r| + c`. On the surface
/// `|r| = r̄` of the set `S' = {|r| ≤ r̄}` the analogue of eq. (4.30),
/// `V̇ ≤ −c`, holds when `I_m λ r̄² − δ r̄ − 2c = 0`:
///
/// `r̄ = (δ + √(δ² + 8 I_m λ c)) / (2 I_m λ)`,
///
/// which is `r_S = √(2c/(I_m λ))` for `δ = 0`; eq. (4.31) then bounds the
/// time to reach `∂S'` by `(V(0) − V(t_s))/c` unchanged.
pub fn sampled_sliding_radius(damping: f64, dissipation: f64, delta: f64) -> f64 {
    (delta + libm::sqrt(delta * delta + 8.0 * damping * dissipation)) / (2.0 * damping)
}

/// What one [`BoundCase`] run observed.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundRun {
    /// The design's bound (continuous time).
    pub bound: crate::control::UltimateBound,
    /// Largest `|τ_k − τ_c(t)|` over the run (the `δ` of
    /// [`sampled_sliding_radius`]; `τ_k` the law's value before the torque
    /// limit — a limited sample is a violated premise, counted in
    /// `saturated_samples`), N·m.
    pub sampling_disturbance: f64,
    /// `r̄(δ)`, rad/s.
    pub radius: f64,
    /// Reaching-time bound of eq. (4.31) from `V(0)`, s.
    pub reaching_time: f64,
    /// Largest true `|r|` (plant state) after the reaching time, rad/s.
    pub max_sliding: f64,
    /// Largest `|τ̂_t(t_k) − τ_t(t)|` over each hold interval, N·m (the
    /// quantity eq. 4.14 bounds by `ρ_τt`).
    pub max_feedback_error: f64,
    /// Samples whose command hit the torque limit.
    pub saturated_samples: usize,
    /// The E22 step ratio at the largest motor speed of the trajectory.
    pub step_ratio: f64,
}

/// Run one [`BoundCase`] for `duration` s on the [`bound_design`] law:
/// motor encoder of 2²⁰ counts per revolution without noise, speed from
/// the one-sample count difference, two RK4 steps per sample; `d(t)` and
/// `r(t)` are evaluated after every step.
pub fn bound_run(case: &BoundCase, duration: f64) -> BoundRun {
    use super::SplitMix64;
    let design = bound_design(case.stribeck);
    let t = design.sample_period;
    let n = design.ratio;
    let params = RobustAdaptiveParams::try_new(design).expect("valid design");
    let law = RobustAdaptiveConfig::<f64>::new(&params);
    let bound = crate::control::UltimateBound::new(&design);
    let mut module = ModuleParams::thesis_joint();
    if case.payload > 0.0 {
        module = module.with_payload(case.payload, [case.payload_distance, 0.0, 0.0]);
    }
    let (s, c) = libm::sincos(case.tilt_direction);
    module.axis = misaligned([0.0, 0.0, 1.0], [c, s, 0.0], case.tilt);
    module.drive.kinematic_error = None;
    module.motor_friction.viscous = case.friction[0];
    module.motor_friction.coulomb = case.friction[1];
    module.motor_friction.static_excess = case.friction[2];
    module.motor_friction.stribeck = case.stribeck;
    module.motor_encoder.counts_per_rev = 1 << 20;
    let rad = module.motor_encoder.rad_per_count();
    let mut robot =
        Mrr::try_new(vec![module], [0.0, 0.0, -9.81], t, 2, case.seed).expect("valid plant");
    let g0 = robot.gravity_torques()[0];
    let qm0 = robot.motor_angles_for_torque(&[0.0], &[g0])[0];
    robot.set_state(&[0.0], &[qm0], &[0.0], &[0.0]);
    let mut rng = SplitMix64::new(case.seed ^ 0x5EED);
    let mut st = law.initial_state();
    // V(0) of eq. (4.20): r(0) from the true state, ∫r = 0, F̃ = F − F̂(0).
    let r0 = sliding(&design, qm0, 0.0, 0.0, 0.0);
    let f_true = [
        case.friction[0],
        case.friction[1],
        case.friction[2],
        case.stribeck,
    ];
    let f0 = design.initial_friction.to_array();
    let mut f_tilde = [0.0; 4];
    for j in 0..4 {
        f_tilde[j] = f_true[j] - f0[j];
    }
    let v0 = crate::control::UltimateBound::lyapunov(&design, r0, 0.0, &f_tilde);
    let reaching_time = bound.reaching_time(v0, 0.0);
    let peak_speed = n * case.amplitude * TAU / case.period;
    let step_ratio = crate::control::UltimateBound::step_ratio_at_speed(&design, peak_speed);
    let mut last_count: Option<i64> = None;
    let (mut delta, mut max_r, mut max_fe, mut sat) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    let total = (duration / t).round() as usize;
    for k in 0..total {
        let time = k as f64 * t;
        let sens = robot.read_sensors();
        let cnt = sens.motor_counts[0];
        let vm = last_count.map_or(0.0, |p| (cnt - p) as f64 * rad / t);
        last_count = Some(cnt);
        let tau_t = robot.transmission_torques()[0];
        let amp = case.error_fraction * design.uncertainty.torque_estimate;
        let err = if case.error_square_period > 0.0 {
            let sign = if (time / case.error_square_period).fract() < 0.5 {
                1.0
            } else {
                -1.0
            };
            sign * amp * (0.5 + 0.5 * rng.uniform())
        } else {
            amp * (2.0 * rng.uniform() - 1.0)
        };
        let fb = tau_t + err;
        let (qd, vd, ad) = raised_cosine(case.amplitude, case.period, time);
        let x = ControlInput {
            desired_position: n * qd,
            desired_velocity: n * vd,
            desired_acceleration: n * ad,
            motor_position: cnt as f64 * rad,
            motor_velocity: vm,
            joint_torque: fb,
            ..Default::default()
        };
        let held = st;
        let o = law.update(&mut st, &x);
        sat += o.saturated as usize;
        robot.set_motor_torque(&[o.torque]);
        for _ in 0..robot.steps_per_period {
            robot.step();
            let tt = robot.time();
            let (qd, vd, ad) = raised_cosine(case.amplitude, case.period, tt);
            let qm = robot.motor_angles()[0];
            let vm = robot.motor_speeds()[0];
            // The continuous law on the true state with the held feedback,
            // integral and estimates.
            let xc = ControlInput {
                desired_position: n * qd,
                desired_velocity: n * vd,
                desired_acceleration: n * ad,
                motor_position: qm,
                motor_velocity: vm,
                joint_torque: fb,
                ..Default::default()
            };
            let mut scratch = held;
            let tc = law.update(&mut scratch, &xc).law_torque;
            delta = delta.max((o.law_torque - tc).abs());
            max_fe = max_fe.max((fb - robot.transmission_torques()[0]).abs());
            if tt >= reaching_time {
                max_r = max_r.max(sliding(&design, qm, vm, n * qd, n * vd).abs());
            }
        }
    }
    BoundRun {
        bound,
        sampling_disturbance: delta,
        radius: sampled_sliding_radius(bound.damping, bound.dissipation, delta),
        reaching_time,
        max_sliding: max_r,
        max_feedback_error: max_fe,
        saturated_samples: sat,
        step_ratio,
    }
}

/// `r = ė + λ e` with `e = q_m − q_m^d`.
fn sliding(d: &RobustAdaptiveDesign, qm: f64, vm: f64, qd: f64, vd: f64) -> f64 {
    (vm - vd) + d.lambda * (qm - qd)
}
