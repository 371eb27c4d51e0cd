//! Theorem 1 (thesis ch. 4, eq. 4.28–4.31) on plants the law's model does
//! not describe: the joint family of `sim::plants::joint` (two-inertia
//! drive, asymmetric Maxwell-slip motor friction with pre-sliding, mesh
//! friction at the drive's node, kinematic error, quantizing encoders), run
//! at the thesis's 4 ms tick with the sampled law of the 4 ms preset
//! (`JointParams::table_4_1_at(0.004)`), its uncertainty bounds derived
//! from the family below.
//!
//! # The plant in Theorem 1's terms (eq. 4.1)
//! The family's rotor obeys `I_m θ̈_m = τ_m − F_m − L/N` with
//! `L = T_w + N T_f ∂e_k/∂θ_m` ([`JointPlant::motor_load`]): the bearing
//! torque `T_w` (the flexspline torque `T_f` plus the mesh friction `M` at
//! the node) and the kinematic error's share of `T_f`. Eq. (4.1) reads
//! `I_m q̈_m + f_m + τ_t/N = τ_m`, so `f_m = F_m` and `τ_t = L`. The law is
//! fed `T_f` (what a torque sensor on the flexspline reads) plus bounded
//! noise; its error against `L` is what eq. (4.14) bounds.
//!
//! # Derived bounds (Assumptions 3–6)
//! * **Friction, `ρ_f + ρ_fq`.** The plant's motor friction is
//!   `F_m = F_ms + b_m θ̇_m`, `F_ms` the Maxwell-slip sum with each element
//!   `clamp(k_i(θ − z_i) + c_i θ̇, −F_i⁻, F_i⁺)`, so
//!   `F_ms ∈ [−F(1 − a), F(1 + a)]` (`F` the break-away level, `a` the
//!   asymmetry). The (4.8) forms in the law's box are
//!   `b q̇ + (f_c + f_s e^{−f_τ q̇²}) sat(q̇/ε_q̇)`, all zero at `q̇ = 0`, while
//!   the plant in pre-sliding after a reversal holds any `F_ms` in its range
//!   with `θ̇_m` arbitrarily near 0: every (4.8) form is off by at least
//!   `F(1 + a)` somewhere. The form `F* = (b_m, 0, 0, f_τ)` (in the box:
//!   `b_m = 5e-5 ≤ 1e-4`) attains it: its gap is `|F_ms| ≤ F(1 + a)`
//!   everywhere. So the nearest (4.8) form leaves `f_q = F_ms`, with
//!   `ρ_fq = F_max(1 + a) = 0.012·1.15 = 0.0138 N·m`, and `f̌ = 0` (its
//!   `f_c = f_s = 0`), `ρ_f = 0`. (Eq. 4.19 and 4.28 use only `ρ_f + ρ_fq`.)
//! * **Torque feedback, `ρ_τt`.** `|T_f + n − L| ≤ |M| + N|T_f||∂e_k/∂θ_m|
//!   + |n|`: the mesh friction is at most its break-away (≤ the drive's
//!   back-driving torque, 2.0 N·m); the kinematic error's gradient is at most
//!   `Σ_h h a_h + 2(N + 1) a_r` over the draw's largest amplitudes
//!   (`a_h = 6.45e-5, 9e-5, 1.5e-5, 2e-5`, ripple `a_r = 4e-5`):
//!   `3.695e-4 + 202·4e-5 = 8.45e-3` rad/rad; `|T_f| ≤ 5 N·m` (an
//!   allowance; the trajectory alone needs about 2.3 N·m — payload
//!   `4 sin(0.4) = 1.56`, link inertia `0.1·0.2·(2π/1.5)² = 0.35`, link
//!   friction `0.3 + 0.05·0.84` — but at the 4 ms tick the link rings
//!   against the drive's spring and `T_f` swings by up to 2.5 N·m within
//!   a tick; 3.4 N·m was seen, so a first allowance of 3 N·m was not
//!   enough); the noise is at most 0.5 N·m. Sum
//!   `2.0 + 100·5·8.45e-3 + 0.5 = 6.72 N·m`.
//!
//!   The feedback is held over the tick; its change within the tick
//!   (the ringing above) is a sampling effect and is measured in `δ` (the
//!   continuous law `τ_c(t)` is fed `T_f(t)` plus the held noise), so
//!   `ρ_τt` needs no allowance for it.
//! * **Base, `ρ_base = 0`**: the family's base is fixed.
//!
//! Every other number (λ, the layers, the friction box with `f_τ` known,
//! `K_I = 0`, the limits, `T = 4 ms`) is the preset's. Premises checked in
//! each run, not assumed: the E4.4 step ratio at the trajectory's peak speed
//! below 1, no sample at the torque limit, `|F_ms| ≤ ρ_fq`, and eq. (4.14)
//! itself, `|T_f(t) + n_k − L(t)| ≤ ρ_τt` at the sample instants and after
//! every integration step (the `|T_f| ≤ 5 N·m` allowance is how `ρ_τt` was
//! sized, not a premise: the error it bounds is checked directly).
//!
//! # Estimate feedback (a measured allowance, not a derived bound)
//! A second check feeds the law the 4 ms preset joint's own estimate
//! `τ̂_t` ([`JointConfig::measure`] of `JointParams::table_4_1_at(0.004)`:
//! eq. 3.8–3.10 from the quantized link and motor encoders, the previous
//! command as `τ_w`) in place of `T_f + n`. Its error at a sample,
//! `ε_k = τ̂_t,k − T_f(t_k)`, is held over the tick as the noise is (the
//! continuous law is fed `T_f(t) + ε_k`), so eq. (4.14) reads
//! `|T_f(t) + ε_k − L(t)| ≤ |M| + N|T_f||∂e_k/∂θ_m| + |ε_k|` and
//! `ρ_τt = 2.0 + 4.22 + ε̄`. The first two terms are derived above; `ε̄`
//! is **not**: the estimator's model (the catalogue spring of eq. 2.11,
//! Table 3.2's kinematic error, its hysteresis) differs from each plant
//! of the family in shape and in the kinematic error's draw, and no bound
//! of that difference over the family is derived here. `ε̄ = 6.0 N·m` was
//! set before measuring and then measured: over 48 runs on seeds 0–47
//! (two per plant) the largest `|ε_k|` was 5.09 N·m
//! (`estimator_error_observation`, which asserts `≤ ε̄` and prints it;
//! those runs use the design with this `ε̄`, so the allowance and the
//! loop it shapes are not independent). The check
//! (`estimate_feedback_stays_within_the_bound_under_a_measured_allowance`)
//! draws its seeds from `[2³², 2⁶⁴)`, disjoint from those, and checks
//! eq. (4.14) directly in each run as above. Its verdict is therefore
//! conditional: Theorem 1's bound holds on these cases *given* an
//! estimator error within an allowance that was observed, not proven.
#![cfg(feature = "sim")]

use core::f64::consts::TAU;
use mrr_control::control::{
    ControlInput, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams, UltimateBound,
};
use mrr_control::joint::{JointConfig, JointParams, JointReadings};
use mrr_control::sim::closed_loop::{raised_cosine, sampled_sliding_radius};
use mrr_control::sim::plants::drive::{BACKDRIVE_TORQUE, RATIO};
use mrr_control::sim::plants::joint::{
    joint_family, JointPlant, MOTOR_ASYMMETRY, MOTOR_BREAKAWAYS, MOTOR_COUNTS, MOTOR_VISCOUS, STEP,
};
use mrr_control::sim::SplitMix64;
use proptest::prelude::*;
use std::sync::OnceLock;

/// The thesis's controller period, s.
const PERIOD: f64 = 0.004;
/// Largest noise added to the fed-back flexspline torque, N·m.
const NOISE: f64 = 0.5;
/// Largest `|T_f|` the derivation of `ρ_τt` allows, N·m (module docs).
const FLEXSPLINE_TORQUE_MAX: f64 = 5.0;
/// Largest `|∂e_k/∂θ_m|` of the family's kinematic-error draw, rad/rad
/// (module docs): harmonics `Σ h a_h` plus the ripple `2(N + 1) a_r`.
fn kinematic_gradient_max() -> f64 {
    let harmonics = [4.3e-5 * 1.5, 6.0e-5 * 1.5, 1.5e-5, 2.0e-5];
    let h: f64 = harmonics
        .iter()
        .enumerate()
        .map(|(i, a)| (i as f64 + 1.0) * a)
        .sum();
    h + 2.0 * (RATIO + 1.0) * 4e-5
}

/// `ρ_fq`: the largest `|F_ms|` of the family, `F_max (1 + a)`, N·m.
fn friction_gap() -> f64 {
    MOTOR_BREAKAWAYS.iter().fold(0.0f64, |m, &f| m.max(f)) * (1.0 + MOTOR_ASYMMETRY)
}

/// Which torque the law is fed back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Feedback {
    /// The flexspline torque `T_f(t_k)` plus noise within [`NOISE`].
    Sensor,
    /// The 4 ms preset joint's own estimate `τ̂_t` from the quantized
    /// encoders ([`JointConfig::measure`]).
    Estimate,
}

/// The estimator's error allowance `ε̄`, N·m: **measured, not derived**
/// (module docs, "Estimate feedback"); see
/// [`estimator_error_observation`].
const ESTIMATE_ERROR_ALLOWANCE: f64 = 6.0;

/// `ρ_τt` (module docs), N·m: the derived part (mesh friction and the
/// kinematic error's share) plus the feedback's own error, the noise bound
/// for [`Feedback::Sensor`] (derived) or the measured allowance for
/// [`Feedback::Estimate`].
fn torque_error_bound(feedback: Feedback) -> f64 {
    let own = match feedback {
        Feedback::Sensor => NOISE,
        Feedback::Estimate => ESTIMATE_ERROR_ALLOWANCE,
    };
    BACKDRIVE_TORQUE + RATIO * FLEXSPLINE_TORQUE_MAX * kinematic_gradient_max() + own
}

/// The 4 ms preset's law with the family's uncertainty bounds.
fn design(feedback: Feedback) -> RobustAdaptiveDesign {
    let preset = JointParams::table_4_1_at(PERIOD).expect("the 4 ms preset");
    let mut d = *preset.settings().mode.settings().active.design();
    d.uncertainty.boundary_layer = 0.0;
    d.uncertainty.nonparametric_friction = friction_gap();
    d.uncertainty.base_acceleration = 0.0;
    d.uncertainty.torque_estimate = torque_error_bound(feedback);
    d
}

/// The 4 ms preset joint whose estimator [`Feedback::Estimate`] uses.
fn preset_joint() -> &'static JointConfig<f64> {
    static J: OnceLock<JointConfig<f64>> = OnceLock::new();
    J.get_or_init(|| JointConfig::new(&JointParams::table_4_1_at(PERIOD).expect("the 4 ms preset")))
}

fn family() -> &'static [JointPlant] {
    static F: OnceLock<Vec<JointPlant>> = OnceLock::new();
    F.get_or_init(joint_family)
}

/// One closed-loop case.
#[derive(Debug, Clone, Copy)]
struct Case {
    plant: usize,
    seed: u64,
    /// Link amplitude `A`, rad.
    amplitude: f64,
    /// Period `P`, s (the run lasts one period).
    period: f64,
    /// Fraction of [`NOISE`] used by the feedback noise.
    noise: f64,
    /// Factor on the motor friction's levels (1: the family's plant).
    friction_scale: f64,
    /// The torque fed back.
    feedback: Feedback,
}

#[derive(Debug, Clone, Copy)]
struct Run {
    /// `c` and `I_m λ` of the design.
    bound: UltimateBound,
    /// Largest `|τ_k − τ_c(t)|` over the run, N·m.
    delta: f64,
    /// `r̄(δ)`, rad/s.
    radius: f64,
    /// Eq. (4.31) from `V(0)`, s.
    reaching_time: f64,
    /// Largest true `|r|` after the reaching time, rad/s.
    max_sliding: f64,
    /// Largest `|T_f(t) + n_k − L(t)|`, N·m.
    max_feedback_error: f64,
    /// Largest change of `T_f` within a tick, `|T_f(t) − T_f(t_k)|`, N·m
    /// (reported: its effect is in `delta`).
    max_hold_change: f64,
    /// Largest `|F_ms|`, N·m.
    max_friction: f64,
    /// Largest `|T_f|`, N·m.
    max_flexspline: f64,
    /// Largest error of the fed-back torque at a sample instant against
    /// the flexspline torque then, `|τ_fb,k − T_f(t_k)|`, N·m.
    max_sample_error: f64,
    saturated: usize,
    step_ratio: f64,
}

/// `r = ė + λ e`, `e = θ_m − N q_d`, motor side, rad/s.
fn sliding(lambda: f64, x: &[f64; 4], qd: f64, vd: f64) -> f64 {
    (x[1] - RATIO * vd) + lambda * (x[0] - RATIO * qd)
}

fn run(case: &Case) -> Run {
    let design = design(case.feedback);
    let params = RobustAdaptiveParams::try_new(design).expect("valid derived design");
    let law = RobustAdaptiveConfig::<f64>::new(&params);
    let bound = UltimateBound::new(&design);
    let n = RATIO;
    let mut plant = family()[case.plant].clone();
    if case.friction_scale != 1.0 {
        let s = case.friction_scale;
        for e in plant.motor_friction.elements.iter_mut() {
            // Same pre-sliding displacements and damping ratio, levels × s.
            *e = (e.0 * s, e.1 * s, e.2 * s, e.3 * s.sqrt());
        }
    }
    let mut st = plant.rest(0.0, case.seed);
    let mut rng = SplitMix64::new(case.seed ^ 0x7E57);
    let rad = TAU / MOTOR_COUNTS as f64;
    // V(0) of eq. (4.20) for F* = (b_m, 0, 0, f_τ): r(0) from the true
    // state, no integral, F̃ = F* − F̂(0).
    let f0 = design.initial_friction.to_array();
    let f_tilde = [MOTOR_VISCOUS - f0[0], -f0[1], -f0[2], 0.0];
    let r0 = sliding(design.lambda, &st.x, 0.0, 0.0);
    let v0 = UltimateBound::lyapunov(&design, r0, 0.0, &f_tilde);
    let reaching_time = bound.reaching_time(v0, 0.0);
    let peak_speed = n * case.amplitude * TAU / case.period;
    let step_ratio = UltimateBound::step_ratio_at_speed(&design, peak_speed);
    let mut ls = law.initial_state();
    let first_reading = plant.read(&st, &mut rng);
    let first = first_reading.motor_counter;
    let (mut counter, mut count) = (first, first as i32 as i64);
    let joint = preset_joint();
    let mut joint_state = joint.state(first_reading.link_count, first);
    let mut last_command = 0.0;
    let mut out = Run {
        bound,
        delta: 0.0,
        radius: 0.0,
        reaching_time,
        max_sliding: 0.0,
        max_feedback_error: 0.0,
        max_hold_change: 0.0,
        max_friction: 0.0,
        max_flexspline: 0.0,
        max_sample_error: 0.0,
        saturated: 0,
        step_ratio,
    };
    let ticks = (case.period / PERIOD).round() as usize;
    let steps = (PERIOD / STEP).round() as usize;
    let h = PERIOD / steps as f64;
    for k in 0..ticks {
        let t = k as f64 * PERIOD;
        let sens = plant.read(&st, &mut rng);
        let step = sens.motor_counter.wrapping_sub(counter) as i32 as i64;
        counter = sens.motor_counter;
        let previous = count;
        count += step;
        let speed = if k == 0 {
            0.0
        } else {
            (count - previous) as f64 * rad / PERIOD
        };
        let sensor_noise = case.noise * NOISE * (2.0 * rng.uniform() - 1.0);
        let sampled_flexspline = plant.transmitted(&st, &st.x);
        // The fed-back torque's error at the sample, held over the tick.
        let noise = match case.feedback {
            Feedback::Sensor => sensor_noise,
            Feedback::Estimate => {
                let readings = JointReadings {
                    link_count: sens.link_count,
                    motor_counter: sens.motor_counter,
                    motor_torque: Some(last_command),
                };
                joint.measure(&mut joint_state, &readings).joint_torque_si() - sampled_flexspline
            }
        };
        out.max_sample_error = out.max_sample_error.max(noise.abs());
        let fb = sampled_flexspline + noise;
        let (qd, vd, ad) = raised_cosine(case.amplitude, case.period, t);
        let x = ControlInput {
            desired_position: n * qd,
            desired_velocity: n * vd,
            desired_acceleration: n * ad,
            motor_position: count as f64 * rad,
            motor_velocity: speed,
            joint_torque: fb,
            ..Default::default()
        };
        let held = ls;
        let o = law.update(&mut ls, &x);
        last_command = o.torque;
        out.saturated += o.saturated as usize;
        // The hold interval [t_k, t_k + T]: the sample instant, then the
        // end of every integration step.
        for i in 0..=steps {
            if i > 0 {
                plant.advance(&mut st, o.torque, h, |_, _| 0.0);
            }
            let tt = t + i as f64 * h;
            let (qd, vd, ad) = raised_cosine(case.amplitude, case.period, tt);
            // The continuous law τ_c(t) of `sampled_sliding_radius`: the
            // true state and the torque fed back now (the flexspline torque
            // at t plus the held noise), with the held integral and
            // estimates. Holding `τ̂_t` over the tick is part of the
            // sampling, so its effect lands in δ, and eq. (4.14) bounds
            // the continuous feedback's error against `L(t)`.
            let flexspline = plant.transmitted(&st, &st.x);
            let fbc = flexspline + noise;
            let xc = ControlInput {
                desired_position: n * qd,
                desired_velocity: n * vd,
                desired_acceleration: n * ad,
                motor_position: st.x[0],
                motor_velocity: st.x[1],
                joint_torque: fbc,
                ..Default::default()
            };
            let mut scratch = held;
            let tc = law.update(&mut scratch, &xc).law_torque;
            out.delta = out.delta.max((o.law_torque - tc).abs());
            out.max_feedback_error = out
                .max_feedback_error
                .max((fbc - plant.motor_load(&st, &st.x)).abs());
            out.max_hold_change = out
                .max_hold_change
                .max((flexspline - sampled_flexspline).abs());
            out.max_friction = out.max_friction.max(
                plant
                    .motor_friction
                    .torque(&st.motor, st.x[0], st.x[1])
                    .abs(),
            );
            out.max_flexspline = out.max_flexspline.max(flexspline.abs());
            if tt >= reaching_time {
                out.max_sliding = out
                    .max_sliding
                    .max(sliding(design.lambda, &st.x, qd, vd).abs());
            }
        }
    }
    out.radius = sampled_sliding_radius(bound.damping, bound.dissipation, out.delta);
    out
}

/// The derivation's inputs hold for every member of the family: the motor
/// friction's largest level is within `ρ_fq`, the mesh friction's
/// break-away within the 2.0 N·m of `ρ_τt`, and the kinematic-error draws
/// of 64 seeds have gradients within [`kinematic_gradient_max`] (evaluated
/// on a grid of motor angles). The design is a valid law whose `K_r` is
/// below the torque limit.
#[test]
fn derived_bounds_cover_the_family() {
    let rho_fq = friction_gap();
    assert!((rho_fq - 0.0138).abs() < 1e-12, "{rho_fq}");
    let g = kinematic_gradient_max();
    assert!((g - 8.4495e-3).abs() < 1e-7, "{g}");
    for p in family() {
        assert!(p.motor_friction.breakaway_forward() <= rho_fq + 1e-15);
        assert!(p.motor_friction.breakaway_backward() <= rho_fq);
        assert!(p.mesh_friction.breakaway() <= BACKDRIVE_TORQUE + 1e-12);
    }
    let p = &family()[0];
    for seed in 0..64u64 {
        let st = p.rest(0.0, seed);
        let dm = 1e-6;
        for j in 0..4000 {
            let m = j as f64 * TAU / 4000.0;
            let d = (p.kinematic_error(&st, m + dm, 0.0) - p.kinematic_error(&st, m - dm, 0.0))
                / (2.0 * dm);
            assert!(d.abs() <= g * (1.0 + 1e-6), "seed {seed} at {m}: {d} > {g}");
        }
    }
    let d = design(Feedback::Sensor);
    assert!(RobustAdaptiveParams::try_new(d).is_ok());
    assert!(d.robust_gain() < d.torque_limit, "{}", d.robust_gain());
    // With the estimate fed back: ρ_τt = 2.0 + 100·5·8.4495e-3 + 6.0.
    let e = design(Feedback::Estimate);
    let rho = torque_error_bound(Feedback::Estimate);
    assert!(
        (rho - (2.0 + 500.0 * 8.4495e-3 + 6.0)).abs() < 1e-4,
        "{rho}"
    );
    assert!(RobustAdaptiveParams::try_new(e).is_ok());
    assert!((e.robust_gain() - (0.0138 + rho / 100.0)).abs() < 1e-12);
    assert!(e.robust_gain() < e.torque_limit, "{}", e.robust_gain());
}

fn case() -> impl Strategy<Value = Case> {
    (
        0..24usize,
        any::<u64>(),
        0.02..0.2f64,
        1.5..3.0f64,
        0.0..1.0f64,
    )
        .prop_map(|(plant, seed, amplitude, period, noise)| Case {
            plant,
            seed,
            amplitude,
            period,
            noise,
            friction_scale: 1.0,
            feedback: Feedback::Sensor,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Theorem 1 on the family at 4 ms: after the reaching time of
    /// eq. (4.31), the true `|r|` (plant state at the sample instants and
    /// after every 50 µs integration step) stays within `r̄(δ)`, the set of
    /// eq. (4.29)–(4.30) widened by the sampling disturbance `δ` measured on
    /// the same run ([`sampled_sliding_radius`]). Cases: any of the 24
    /// plants, any seed (kinematic-error draw, encoder and feedback noise),
    /// a link trajectory of amplitude 0.02–0.2 rad over 1.5–3 s (peak motor
    /// speed at most 84 rad/s, within the preset's 100 rad/s), one full
    /// period, feedback noise up to 0.5 N·m.
    ///
    /// 96 cases (about 15 s under the test profile). Seen on one run of 96:
    /// `|r|` 33–56 rad/s against `r̄(δ)` 256–284 rad/s (at most 0.20 of
    /// it; `r_S` = 253 rad/s), `δ` 0.003–0.038 N·m, the feedback error
    /// 2.1–5.4 N·m against `ρ_τt` = 6.72 N·m, `|T_f|` up to 4.7 N·m, the
    /// step ratio 0.30–0.37. The bound is loose at 4 ms: with `ε_r` =
    /// 525 rad/s the robust term's slope `K_r/ε_r` is about an eighth of the
    /// damping `2 I_m λ`, and a law with that term's sign flipped still
    /// passes this test: at this design the check cannot tell that sign.
    #[test]
    fn sliding_variable_stays_within_the_bound_on_family_plants(c in case()) {
        let r = run(&c);
        prop_assert!(r.step_ratio < 1.0, "{c:?} {r:?}");
        prop_assert!(r.reaching_time < 0.5 * c.period, "{c:?} {r:?}");
        prop_assert_eq!(r.saturated, 0, "{:?} {:?}", c, r);
        prop_assert!(r.max_friction <= friction_gap() + 1e-12, "{c:?} {r:?}");
        prop_assert!(r.max_feedback_error <= torque_error_bound(c.feedback), "{c:?} {r:?}");
        prop_assert!(r.max_sliding <= r.radius, "{c:?} {r:?}");
    }
}

/// The check can fail: the same plant with its motor friction levels
/// scaled by 25 (break-away `25·0.012·0.85 = 0.255` N·m backward, 0.345
/// forward, outside `ρ_fq = 0.0138` and above the 0.188 N·m torque limit)
/// cannot leave pre-sliding, so the motor stays within twice the largest
/// pre-sliding displacement (8e-3 rad) of its start, itself within
/// `N·2.2e-4 = 0.022` rad of 0. At the trajectory's turning point
/// `t = P/2` (`q_d = 2A`, `q̇_d = 0`): `|r| ≥ λ(2NA − 0.038) − |θ̇_m|`; for
/// `A = 0.1` rad that is `λ·19.96` ≈ 1134 rad/s with `λ = 56.8`, less a
/// pre-sliding speed; the test asks for 0.9 of `2λNA`, several times
/// `r̄`. The unscaled plant on the same case stays inside.
#[test]
fn friction_outside_the_bound_exceeds_the_ultimate_bound() {
    // Plant 2: rounded-knee backbone, all of Ψ at the node, F = 0.012 N·m.
    let mut c = Case {
        plant: 2,
        seed: 3,
        amplitude: 0.1,
        period: 2.0,
        noise: 0.5,
        friction_scale: 1.0,
        feedback: Feedback::Sensor,
    };
    let ok = run(&c);
    assert!(ok.max_sliding <= ok.radius, "{ok:?}");
    assert_eq!(ok.saturated, 0, "{ok:?}");
    c.friction_scale = 25.0;
    let bad = run(&c);
    assert!(bad.max_friction > 10.0 * friction_gap(), "{bad:?}");
    let lambda = design(Feedback::Sensor).lambda;
    let expected = 0.9 * 2.0 * lambda * RATIO * c.amplitude;
    // r̄(δ) ≥ r_S: the widening only adds.
    assert!(bad.radius >= bad.bound.sliding_radius, "{bad:?}");
    assert!(expected > 2.0 * bad.radius, "{expected} vs {bad:?}");
    assert!(bad.max_sliding >= expected, "{expected} vs {bad:?}");
}

/// The measurement behind [`ESTIMATE_ERROR_ALLOWANCE`]: the estimate's
/// error at the sample instants, `|τ̂_t,k − T_f(t_k)|`, over 48 closed-loop
/// runs on seeds 0–47 (two per plant, trajectories drawn from a fixed
/// generator over the check's ranges), which the check's seeds (at least
/// 2³²) never use. It asserts that the allowance covers what it saw, so
/// the observation is rerun with the file.
#[test]
fn estimator_error_observation() {
    let mut g = SplitMix64::new(0xE57_0B5);
    let mut worst = 0.0f64;
    for seed in 0..48u64 {
        let c = Case {
            plant: (seed % 24) as usize,
            seed,
            amplitude: 0.02 + 0.18 * g.uniform(),
            period: 1.5 + 1.5 * g.uniform(),
            noise: 0.0,
            friction_scale: 1.0,
            feedback: Feedback::Estimate,
        };
        let r = run(&c);
        worst = worst.max(r.max_sample_error);
    }
    eprintln!("largest |estimate - T_f| at a sample over seeds 0-47: {worst:.3} N·m");
    assert!(worst <= ESTIMATE_ERROR_ALLOWANCE, "{worst}");
}

fn estimate_case() -> impl Strategy<Value = Case> {
    (
        0..24usize,
        (1u64 << 32)..u64::MAX,
        0.02..0.2f64,
        1.5..3.0f64,
    )
        .prop_map(|(plant, seed, amplitude, period)| Case {
            plant,
            seed,
            amplitude,
            period,
            noise: 0.0,
            friction_scale: 1.0,
            feedback: Feedback::Estimate,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Theorem 1 on the family at 4 ms with the library's own joint-torque
    /// estimate fed back, **under a measured allowance** `ε̄ = 6.0 N·m` for
    /// the estimator's error (module docs, "Estimate feedback"): the same
    /// premises and assertion as the sensor check, with
    /// `ρ_τt = 2.0 + 4.22 + 6.0 = 12.22 N·m` (`K_r = 0.136 N·m`, below
    /// the 0.188 N·m limit). Seeds disjoint from the measurement's.
    ///
    /// 48 cases (about 14 s under the test profile, as many again for
    /// `estimator_error_observation`). Seen on one run of 48
    /// (`PROPTEST_RNG_SEED=4242`): `|ε_k|` 1.2–5.43 N·m — above the 5.09
    /// the measurement saw, within `ε̄` by 0.57 N·m, so other seeds may well
    /// exceed it (such a case is rejected with `prop_assume!`: the
    /// allowance is a premise of the conclusion, not a bound; proptest
    /// fails the test if it rejects more than its global limit) — the
    /// feedback error 3.1–9.0 N·m against `ρ_τt` = 12.22
    /// N·m, `|r|` 33–79 rad/s against `r̄(δ)` 298–321 rad/s (at most 0.25
    /// of it), `δ` 0.005–0.033 N·m, the step ratio 0.33–0.40.
    #[test]
    fn estimate_feedback_stays_within_the_bound_under_a_measured_allowance(c in estimate_case()) {
        let r = run(&c);
        prop_assert!(r.step_ratio < 1.0, "{c:?} {r:?}");
        prop_assert!(r.reaching_time < 0.5 * c.period, "{c:?} {r:?}");
        prop_assert_eq!(r.saturated, 0, "{:?} {:?}", c, r);
        prop_assert!(r.max_friction <= friction_gap() + 1e-12, "{c:?} {r:?}");
        // The allowance is the theorem's premise here, not a derived
        // bound: a case whose estimator error exceeds it is outside what
        // the check can conclude, and is rejected (proptest fails the
        // test if too many are), not counted as a pass or a failure.
        prop_assume!(r.max_sample_error <= ESTIMATE_ERROR_ALLOWANCE);
        prop_assert!(r.max_feedback_error <= torque_error_bound(c.feedback), "{c:?} {r:?}");
        prop_assert!(r.max_sliding <= r.radius, "{c:?} {r:?}");
    }
}
