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
//! # Estimate feedback: the derived `ε̄`
//! A second check feeds the law the 4 ms preset joint's own estimate
//! `τ̂_t` ([`JointConfig::measure`] of `JointParams::table_4_1_at(0.004)`:
//! eq. 3.8–3.10 from the quantized link and motor encoders, the previous
//! command as `τ_w`) in place of `T_f + n`. Its error at a sample,
//! `ε_k = τ̂_t,k − T_f(t_k)`, is held over the tick as the noise is (the
//! continuous law is fed `T_f(t) + ε_k`), so eq. (4.14) reads
//! `|T_f(t) + ε_k − L(t)| ≤ |M| + N|T_f||∂e_k/∂θ_m| + |ε_k|` and
//! `ρ_τt = 2.0 + 4.22 + ε̄` with `|ε_k| ≤ ε̄`.
//!
//! **History.** `ε̄` was first an allowance, `ε̄ = 6.0 N·m` as first
//! measured: set before measuring, then the largest `|ε_k|` over 48 runs on
//! seeds 0–47 was 5.09 N·m (and 5.43 N·m on the check's own seeds). It is
//! now derived below, over the family, from the plants' constants and
//! curves ([`estimate_error_bound`]).
//!
//! **The estimator** (chapter-4 signs: the joint negates the motor counter
//! and returns `τ̂_t = −estimate`). From the measured total twist
//! `φ̂ = θ̂_m/N − θ̂_l` (eq. 2.13) it forms the flexspline twist of
//! eq. (3.9), `ψ̂ = φ̂ − w(τ_w) + θ_err`, with `w(τ) = sgn τ (1 −
//! e^{−c_w|τ|})/(c_w N K_w0)` (eq. 2.29, the model's wave-generator term:
//! its hysteresis, driven by the command) and `θ_err` eq. (3.7) with
//! Table 3.2's coefficients, and returns `τ̂ = g(ψ̂) = tan(c_f K_f0 ψ̂)/c_f`
//! (eq. 3.10; `g` odd and increasing, saturated at ±60 N·m, which only
//! moves `τ̂` towards `T_f` while `|T_f| ≤ 60`).
//!
//! **The plant** (`JointPlant`). Its total deformation
//! `D = θ_m/N − θ_l + e_k` is the bearing twist plus the flexspline
//! twist: `D = W⁻¹(T_f + M) + y` with `T_f = B(y) + H`, the mesh friction
//! `|M| ≤ M̄` (its break-away, 2.0 N·m) and the flexspline hysteresis
//! `|H| ≤ H̄` (its break-away; 0 when all of `Ψ` is at the node). `W`, `B`
//! are increasing, so a flexspline torque `T` is compatible only with
//! `D ∈ [D_lo(T), D_hi(T)] = [W⁻¹(T − M̄) + B⁻¹(T − H̄),
//! W⁻¹(T + M̄) + B⁻¹(T + H̄)]` (the friction and hysteresis anywhere in
//! their bands, whatever their memory).
//!
//! **The twist error** `|ψ̂_k − D_k| ≤ δ + w̄`, the sum of:
//! * `δ_q`, the encoders: a reading is `round(x + 0.1 g)` counts with `g`
//!   the Box–Muller draw, `|g| ≤ √(106 ln 2) = 8.572` (its `u₁ ≥ 2⁻⁵³`),
//!   so each reading is off by at most `ν̄ = 0.5 + 0.857 = 1.357` counts;
//!   the motor position is the start's position plus counter differences,
//!   so both the sample's and the start's readings count:
//!   `δ_q = 2ν̄(2π/(MN) + 2π/L) = 2.15e-4 rad` (`M = 2000`, `N = 100`,
//!   `L = 2¹⁷`);
//! * `δ_e`, the kinematic error: the estimator subtracts `θ_err` where the
//!   plant has `e_k`, at the sample and (through the start, below) at the
//!   start: `δ_e = 2(A_m + A_p)`, `A_m = |a_0| + Σ R_j = 1.78e-4 rad`
//!   (Table 3.2, eq. 3.7) and `A_p = 2.2e-4 rad` (every draw's amplitude
//!   sum is at most half the catalogue's 4.4e-4 rad peak to peak: the
//!   draw scales down to it), `7.96e-4 rad`;
//! * `δ_0`, the start: `JointConfig::state` starts from the motor count
//!   `⌊c_l MN/L⌋`, where `|ψ̂| < 2π/(MN) + A_m`, and accepts only moves
//!   that shrink `|ψ̂|`: `δ_0 = A_m + 2π/(MN) = 2.09e-4 rad`. (With
//!   `ψ̂_k − D_k = ψ̂_0 + (θ_err,k − θ_err,0) − (e_k,k − e_k,0) + q_k −
//!   w(τ_w) + D_0`, these three are every term but the last two.)
//! * `δ_r`, the plant's rest: `D_0` after the sixty damped fixed-point
//!   steps of `rest`, a contraction by `(1 + N g)/2 ≤ 0.923` from at most
//!   `N A_p` of motor angle (`g` = 8.45e-3, the gradient bound above):
//!   `0.923⁶⁰ A_p (1 + N g) ≈ 3e-6 rad`;
//! * `w̄ = w(0.188 N·m) = 1.45e-4 rad`: the command is within the torque
//!   limit, and `w(τ_w)` is taken anywhere in `[−w̄, w̄]`.
//!
//! **The bound.** `ε_k = g(ψ̂_k) − T_f ∈ [g(D_lo(T_f) − c) − T_f,
//! g(D_hi(T_f) + c) − T_f]`, `c = δ + w̄`, so for each member
//! `ε̄_p = sup_{|T| ≤ T_max} max(g(D_hi(T) + c) − T, T − g(D_lo(T) − c))`
//! with `T_max = 5 N·m` ([`FLEXSPLINE_TORQUE_MAX`], here a premise,
//! checked in every run). The supremum is taken on a grid of step
//! `h = 2.5e-3 N·m` with its margin: on `[T_j, T_j + h]` the first term is
//! at most `g(D_hi(T_j + h) + c) − T_j` and the second at most
//! `T_j + h − g(D_lo(T_j) − c)` (`g`, `D_hi`, `D_lo` non-decreasing), so
//! the grid value bounds the interval, not only its ends. `ε̄` is the
//! largest `ε̄_p` over the 24 members. The other premises: no counter jump
//! (a rejected jump would shift the motor position for good), the
//! command within the torque limit (the law saturates it), the link and
//! twist within the estimator's range (far inside).
//!
//! **Criteria, written before the rerun with the derived `ε̄`.** The
//! estimate-feedback check is *supported* on the family at 4 ms only if
//! (1) the design with `ρ_τt = 2.0 + 4.22 + ε̄` has `K_r` below the
//! 0.188 N·m torque limit (the robust term can be delivered), and in every
//! case (2) the E4.4 step ratio at the trajectory's peak speed is below 1,
//! (3) no sample is at the torque limit, (4) `|F_ms| ≤ ρ_fq`, (5) the
//! premises of `ε̄` hold (`|T_f| ≤ 5 N·m`, no counter jump), and
//! (6) `|r| ≤ r̄(δ)` after the reaching time; *refuted* if (1)–(5) hold and
//! (6) fails; *undecided* if (1) or, in some case, (2)–(5) fail. Whatever
//! the verdict, `|ε_k| ≤ ε̄` and eq. (4.14) (`≤ ρ_τt`) must hold in every
//! run: those are derived, and a run outside them is a failure.
//!
//! **Outcome** (one run of `cargo test --release --all-features --test
//! theorem_family -- --nocapture`; `estimator_error_observation` and
//! `estimate_feedback_with_the_derived_bound_is_undecided` print these):
//! `ε̄ = 18.13 N·m` (members 17.30–18.13), three times the first
//! allowance. The widening `c = 1.369e-3 rad` is `δ_q = 2.15e-4`,
//! `δ_e = 7.96e-4`, `δ_0 = 2.09e-4`, `δ_r = 3.2e-6`, `w̄ = 1.45e-4`; at the
//! model's stiffness of about 8,500 N·m/rad near 5 N·m that alone is
//! about 12 N·m, the kinematic-error terms the largest part, and the rest
//! is the two springs' difference (the mesh friction's band adds only
//! 0.16 N·m: the hyperbolic bearing is nearly at its limit). Then
//! `ρ_τt = 2.0 + 4.22 + 18.13 = 24.36 N·m` and `K_r = 0.0138 + 0.2436 =
//! 0.257 N·m`, above the 0.188 N·m limit: **premise (1) fails, and
//! Theorem 1 with the estimate fed back is undecided on this family at
//! 4 ms**, not supported. The law so designed is still valid and was run:
//! the E4.4 step ratio at the fastest trajectory is 0.494 (0.41–0.48 in
//! the 50 cases of one run of the check, 48 drawn plus two kept
//! regressions), no sample saturated, `|r|` was 26–66 rad/s against
//! `r̄(δ)` 373–445 rad/s. But in 3 of those 50 cases `|T_f(t_k)|` went
//! beyond 5 N·m (up to 9.66 N·m at a sample, 17 samples in one case: the
//! larger `K_r` makes the link ring harder against the spring; 1 case of
//! 50, 6.36 N·m, on a second run), outside `ε̄`'s own premise, so those
//! samples are not covered by the derivation (they are counted, and
//! `|ε_k| ≤ ε̄` is checked on the others). The largest `|ε_k|` seen was
//! 4.86 N·m over seeds 0–47 and 4.86 and 5.18 N·m over the check's cases
//! on two runs, within `ε̄` with a wide margin: the bound is sound, not
//! tight (each term is taken at its worst at once).
#![cfg(feature = "sim")]

use core::f64::consts::TAU;
use mrr_control::control::{
    ControlInput, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams, UltimateBound,
};
use mrr_control::joint::{JointConfig, JointParams, JointReadings};
use mrr_control::sim::closed_loop::{raised_cosine, sampled_sliding_radius};
use mrr_control::sim::plants::drive::{BACKDRIVE_TORQUE, RATIO};
use mrr_control::sim::plants::elements::{
    FlexsplineBackbone, WaveGeneratorCompliance, KINEMATIC_ERROR_PEAK_TO_PEAK,
};
use mrr_control::sim::plants::joint::{
    joint_family, JointPlant, ENCODER_NOISE_COUNTS, LINK_COUNTS, MOTOR_ASYMMETRY, MOTOR_BREAKAWAYS,
    MOTOR_COUNTS, MOTOR_VISCOUS, STEP,
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

/// `ρ_τt` (module docs), N·m: the derived part (mesh friction and the
/// kinematic error's share) plus the feedback's own error, the noise bound
/// for [`Feedback::Sensor`] or the derived estimator bound `ε̄`
/// ([`estimate_error_bound`]) for [`Feedback::Estimate`].
fn torque_error_bound(feedback: Feedback) -> f64 {
    let own = match feedback {
        Feedback::Sensor => NOISE,
        Feedback::Estimate => estimate_error_bound().total,
    };
    BACKDRIVE_TORQUE + RATIO * FLEXSPLINE_TORQUE_MAX * kinematic_gradient_max() + own
}

/// Largest `|g|` of the Box–Muller draw of [`SplitMix64::gaussian`]: its
/// `u₁ = 1 − u` is at least `2⁻⁵³` (53-bit uniforms), so
/// `|g| ≤ √(−2 ln 2⁻⁵³) = √(106 ln 2) ≈ 8.572`.
fn gaussian_max() -> f64 {
    (106.0 * core::f64::consts::LN_2).sqrt()
}

/// The terms of the derived estimator error bound `ε̄` (module docs,
/// "Estimate feedback: the derived `ε̄`"). Angles are output-side rad,
/// torques N·m.
#[derive(Debug, Clone)]
struct EstimateErrorBound {
    /// `ν̄`: largest error of one encoder reading, counts
    /// (`0.5 + 0.1·g_max`).
    reading_error_counts: f64,
    /// `δ_q`: both encoders, at the sample and at the start, rad.
    quantization: f64,
    /// `A_m`: the estimator's kinematic-error bound (Table 3.2, eq. 3.7), rad.
    model_kinematic_error: f64,
    /// `A_p`: the largest amplitude sum of the family's draws, rad.
    plant_kinematic_error: f64,
    /// `δ_e = 2(A_m + A_p)`, rad.
    kinematic: f64,
    /// `δ_0 = A_m + 2π/(MN)`: the start's residual model twist, rad.
    start: f64,
    /// `δ_r`: the plant's residual twist at its rest start, rad.
    rest: f64,
    /// `w̄`: the model's wave-generator term at the command limit, rad.
    wave_generator: f64,
    /// `δ = δ_q + δ_e + δ_0 + δ_r`, rad.
    twist: f64,
    /// The grid step of `T_f`, N·m.
    grid_step: f64,
    /// `ε̄` per member of [`family`], N·m.
    members: Vec<f64>,
    /// `ε̄`: the largest over the family, N·m.
    total: f64,
}

/// Number of intervals of the `T_f` grid over `[−T_max, T_max]`.
const GRID_INTERVALS: usize = 4000;

/// The plant's band of total twist `D = φ + e_k` (rad) for a flexspline
/// torque `T_f` (N·m): `[W⁻¹(T_f − M̄) + B⁻¹(T_f − H̄),
/// W⁻¹(T_f + M̄) + B⁻¹(T_f + H̄)]`, with `M̄` the mesh friction's and
/// `H̄` the flexspline hysteresis's break-away, widened by `1e-12` rad
/// for the bisection of `B⁻¹` (its bracket is `1e-16` relative) and the
/// plant's node solve (to `1e-13` rad).
fn twist_band(p: &JointPlant, flexspline_torque: f64) -> (f64, f64) {
    let m = p.mesh_friction.breakaway();
    let h = p.hysteresis.breakaway();
    let t = flexspline_torque;
    let lo = p.bearing.torsion(t - m) + p.backbone.torsion(t - h) - 1e-12;
    let hi = p.bearing.torsion(t + m) + p.backbone.torsion(t + h) + 1e-12;
    (lo, hi)
}

/// The 4 ms preset estimator's torque (N·m) for a model flexspline twist
/// (rad), eq. (3.10) (the library's own `f64` evaluation, saturated
/// beyond its branch).
fn model_torque(twist: f64) -> f64 {
    preset_params()
        .settings()
        .estimator
        .drive()
        .flexspline()
        .torque(twist)
        .torque
}

/// `JointParams::table_4_1_at(0.004)`, made once.
fn preset_params() -> &'static JointParams {
    static P: OnceLock<JointParams> = OnceLock::new();
    P.get_or_init(|| JointParams::table_4_1_at(PERIOD).expect("the 4 ms preset"))
}

/// The bound of `|τ̂_t,k − T_f(t_k)|` for one member, N·m, given the
/// widening `c = δ + w̄` (rad): over the grid `T_j` of
/// `[−T_max, T_max]`, the largest of `g(D_hi(T_{j+1}) + c) − T_j` and
/// `T_{j+1} − g(D_lo(T_j) − c)`; `g`, `D_hi`, `D_lo` are
/// non-decreasing, so each bounds its expression over the whole interval
/// `[T_j, T_{j+1}]`.
fn member_estimate_error(p: &JointPlant, widening: f64) -> f64 {
    let step = 2.0 * FLEXSPLINE_TORQUE_MAX / GRID_INTERVALS as f64;
    let at = |j: usize| -FLEXSPLINE_TORQUE_MAX + j as f64 * step;
    let bands: Vec<(f64, f64)> = (0..=GRID_INTERVALS).map(|j| twist_band(p, at(j))).collect();
    (0..GRID_INTERVALS)
        .map(|j| {
            let over = model_torque(bands[j + 1].1 + widening) - at(j);
            let under = at(j + 1) - model_torque(bands[j].0 - widening);
            over.max(under)
        })
        .fold(0.0, f64::max)
}

/// `ε̄` derived over the family (module docs), with its terms.
fn estimate_error_bound() -> &'static EstimateErrorBound {
    static B: OnceLock<EstimateErrorBound> = OnceLock::new();
    B.get_or_init(|| {
        let est = preset_params().settings().estimator;
        let drive = est.drive();
        let n = drive.ratio();
        let motor_counts = est.motor_counts_per_rev() as f64;
        let link_counts = est.link_counts_per_rev() as f64;
        assert_eq!(motor_counts, MOTOR_COUNTS as f64);
        assert_eq!(link_counts, LINK_COUNTS as f64);
        assert_eq!(n, RATIO);
        let nu = 0.5 + ENCODER_NOISE_COUNTS * gaussian_max();
        let motor_count = TAU / (motor_counts * n);
        let link_count = TAU / link_counts;
        let quantization = 2.0 * nu * (motor_count + link_count);
        let model = est.kinematic_error().map_or(0.0, |k| k.amplitude_bound());
        let plant = 0.5 * KINEMATIC_ERROR_PEAK_TO_PEAK * (1.0 + 1e-12);
        let kinematic = 2.0 * (model + plant);
        let start = model + motor_count;
        // `rest` iterates m ← m/2 + N(θ_l − e_k(m))/2 sixty times from
        // `Nθ_l`: a contraction by at most `(1 + N g)/2` (`g` the largest
        // `|∂e_k/∂θ_m|`) from at most `N A_p` away; the twist is off by
        // `(1/N + g)` times the motor's residual.
        let g = kinematic_gradient_max();
        let rest = (0.5 * (1.0 + n * g)).powi(60) * n * plant * (1.0 / n + g);
        let limit = design_with(0.0).torque_limit;
        let wave_generator = drive.wave_generator().torsion(limit) / n;
        let twist = quantization + kinematic + start + rest;
        let members: Vec<f64> = family()
            .iter()
            .map(|p| member_estimate_error(p, twist + wave_generator))
            .collect();
        let total = members.iter().cloned().fold(0.0, f64::max);
        EstimateErrorBound {
            reading_error_counts: nu,
            quantization,
            model_kinematic_error: model,
            plant_kinematic_error: plant,
            kinematic,
            start,
            rest,
            wave_generator,
            twist,
            grid_step: 2.0 * FLEXSPLINE_TORQUE_MAX / GRID_INTERVALS as f64,
            members,
            total,
        }
    })
}

/// The 4 ms preset's law with the family's uncertainty bounds.
fn design(feedback: Feedback) -> RobustAdaptiveDesign {
    design_with(torque_error_bound(feedback))
}

/// The 4 ms preset's law with the family's friction and base bounds and
/// `ρ_τt = torque_estimate` (N·m).
fn design_with(torque_estimate: f64) -> RobustAdaptiveDesign {
    let preset = JointParams::table_4_1_at(PERIOD).expect("the 4 ms preset");
    let mut d = *preset.settings().mode.settings().active.design();
    d.uncertainty.boundary_layer = 0.0;
    d.uncertainty.nonparametric_friction = friction_gap();
    d.uncertainty.base_acceleration = 0.0;
    d.uncertainty.torque_estimate = torque_estimate;
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
    /// Largest `|T_f(t_k)|` at the sample instants, N·m (`ε̄` covers a
    /// sample only if it is at most [`FLEXSPLINE_TORQUE_MAX`]).
    max_sample_flexspline: f64,
    /// Largest `|τ_fb,k − T_f(t_k)|` over the samples `ε̄` covers
    /// (`|T_f(t_k)| ≤ T_max`), N·m.
    max_covered_error: f64,
    /// Samples with `|T_f(t_k)| > T_max`, outside `ε̄`'s premise.
    uncovered_samples: usize,
    /// Samples whose motor counter the joint rejected as a jump
    /// ([`Feedback::Estimate`] only).
    counter_jumps: usize,
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
        max_sample_flexspline: 0.0,
        max_covered_error: 0.0,
        uncovered_samples: 0,
        counter_jumps: 0,
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
                let m = joint.measure(&mut joint_state, &readings);
                out.counter_jumps += m.counter_jump as usize;
                m.joint_torque_si() - sampled_flexspline
            }
        };
        out.max_sample_error = out.max_sample_error.max(noise.abs());
        out.max_sample_flexspline = out.max_sample_flexspline.max(sampled_flexspline.abs());
        if sampled_flexspline.abs() <= FLEXSPLINE_TORQUE_MAX {
            out.max_covered_error = out.max_covered_error.max(noise.abs());
        } else {
            out.uncovered_samples += 1;
        }
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
/// on a grid of motor angles). The sensor design is a valid law whose
/// `K_r` is below the torque limit; the estimate design (with the derived
/// `ε̄`) is a valid law with `ρ_τt = 2.0 + 4.22 + ε̄` (its `K_r` is above
/// the limit: `estimate_feedback_with_the_derived_bound_is_undecided`).
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
    // With the estimate fed back: ρ_τt = 2.0 + 100·5·8.4495e-3 + ε̄, a
    // valid law (its K_r against the limit: see
    // `estimate_feedback_with_the_derived_bound_is_undecided`).
    let e = design(Feedback::Estimate);
    let rho = torque_error_bound(Feedback::Estimate);
    let eps = estimate_error_bound().total;
    assert!(
        (rho - (2.0 + 500.0 * 8.4495e-3 + eps)).abs() < 1e-4,
        "{rho}"
    );
    assert!(RobustAdaptiveParams::try_new(e).is_ok());
    assert!((e.robust_gain() - (0.0138 + rho / 100.0)).abs() < 1e-12);
}

/// The derivation's inputs for one member, by hand. Member 16 of the
/// family: quadratic backbone `B(y) = K_a y + K_b y|y|`, all of `Ψ` at the
/// node (no flexspline hysteresis, `H̄ = 0`), hyperbolic bearing
/// `W⁻¹(T) = δ_m T/(|T| + T_h)`, mesh break-away `M̄ = 2.0 N·m`. At
/// `T = 5 N·m`: `D_hi = δ_m·7/(7 + T_h) + (−K_a + √(K_a² + 4 K_b·5))/(2K_b)`
/// and `D_lo = δ_m·3/(3 + T_h) + B⁻¹(5)`, the closed forms. The widening
/// by hand: `ν̄ = 0.5 + 0.1·8.5717 = 1.35717` counts, `δ_q =
/// 2·1.35717·(2π/2e5 + 2π/2¹⁷) = 2.1539e-4 rad`, `A_p = 2.2e-4 rad`,
/// `w̄ = (1 − e^{−0.188 c_w})/(c_w N K_w0)` from the identified drive.
/// The member's `ε̄_p` is at least the upper error at `T = 5`,
/// `tan(c_f K_f0 (D_hi + c))/c_f − 5`, and at least the lower one at
/// `T = −5` (eq. 3.10 written out here, not the library's).
#[test]
fn estimate_error_bound_by_hand() {
    let b = estimate_error_bound();
    assert!((b.reading_error_counts - 1.35717).abs() < 1e-5, "{b:?}");
    assert!((b.quantization - 2.1539e-4).abs() < 1e-8, "{b:?}");
    assert!((b.plant_kinematic_error - 2.2e-4).abs() < 1e-15, "{b:?}");
    assert!(
        (b.kinematic - 2.0 * (b.model_kinematic_error + 2.2e-4)).abs() < 1e-15,
        "{b:?}"
    );
    assert!((b.start - (b.model_kinematic_error + TAU / 2e5)).abs() < 1e-15);
    assert!(b.rest > 0.0 && b.rest < 1e-5, "{b:?}");
    assert!((b.grid_step - 2.5e-3).abs() < 1e-15);
    let drive = preset_params().settings().estimator.drive();
    let wg = drive.wave_generator();
    let w = (1.0 - (-0.188 * wg.c_w()).exp()) / (wg.c_w() * 100.0 * wg.k_w0());
    assert!((b.wave_generator - w).abs() < 1e-12 * w, "{b:?} {w}");
    let p = &family()[16];
    assert_eq!(p.backbone.name(), "quadratic");
    assert_eq!(p.hysteresis.breakaway(), 0.0);
    let (ka, kb) = match p.backbone {
        FlexsplineBackbone::QuadraticStiffening { linear, quadratic } => (linear, quadratic),
        _ => unreachable!("member 16 is quadratic"),
    };
    let (dm, th) = match p.bearing {
        WaveGeneratorCompliance::Hyperbolic { limit, knee } => (limit, knee),
        _ => unreachable!("the joint family's bearing is hyperbolic"),
    };
    assert!((p.mesh_friction.breakaway() - 2.0).abs() < 1e-12);
    let y5 = (-ka + (ka * ka + 20.0 * kb).sqrt()) / (2.0 * kb);
    let hi = dm * 7.0 / (7.0 + th) + y5;
    let lo = dm * 3.0 / (3.0 + th) + y5;
    let (blo, bhi) = twist_band(p, 5.0);
    assert!(
        (bhi - hi).abs() < 1e-11 && (blo - lo).abs() < 1e-11,
        "{blo} {bhi} vs {lo} {hi}"
    );
    let (blo, bhi) = twist_band(p, -5.0);
    assert!(
        (blo + hi).abs() < 1e-11 && (bhi + lo).abs() < 1e-11,
        "{blo} {bhi}"
    );
    let f = drive.flexspline();
    let g = |x: f64| (f.c_f() * f.k_f0() * x).tan() / f.c_f();
    let c = b.twist + b.wave_generator;
    let upper = g(hi + c) - 5.0;
    let lower = -5.0 - g(-hi - c);
    let member = b.members[16];
    assert!(
        member >= upper && member >= lower,
        "{member} vs {upper} {lower}"
    );
    // For this member the supremum is at the ends: the grid value is the
    // end value plus at most the grid's margin.
    assert!(
        member <= upper.max(lower) + 0.01,
        "{member} vs {upper} {lower}"
    );
    eprintln!("member 16: ε̄_p = {member:.3} N·m; at T = ±5: {upper:.3}, {lower:.3}");
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

/// The derived `ε̄` against what the estimator does: its error at the
/// sample instants, `|τ̂_t,k − T_f(t_k)|`, over 48 closed-loop runs on
/// seeds 0–47 (two per plant, trajectories drawn from a fixed generator
/// over the check's ranges; the law designed with the derived `ε̄`), must
/// stay within `ε̄` ([`estimate_error_bound`]) at every sample where `ε̄`'s
/// premises hold (`|T_f(t_k)| ≤ 5 N·m`; no counter jump, asserted). It
/// prints the bound's terms, the largest error seen, and how many samples
/// fell outside the premise. (Before the derivation these runs
/// measured the allowance `ε̄ = 6.0 N·m`: 5.09 N·m.)
#[test]
fn estimator_error_observation() {
    let b = estimate_error_bound();
    let mut g = SplitMix64::new(0xE57_0B5);
    let (mut worst, mut overall, mut largest_torque, mut uncovered) = (0.0f64, 0.0f64, 0.0f64, 0);
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
        assert_eq!(r.counter_jumps, 0, "{c:?} {r:?}");
        worst = worst.max(r.max_covered_error);
        overall = overall.max(r.max_sample_error);
        uncovered += r.uncovered_samples;
        largest_torque = largest_torque.max(r.max_sample_flexspline);
    }
    let members = b.members.iter().cloned().fold(f64::INFINITY, f64::min);
    eprintln!(
        "derived ε̄ = {:.3} N·m (members {members:.3}–{:.3}); twist widening c = {:.4e} rad: \
         δ_q {:.4e} (ν̄ {:.4} counts), δ_e {:.4e} (A_m {:.4e}, A_p {:.4e}), δ_0 {:.4e}, \
         δ_r {:.2e}, w̄ {:.4e}; grid step {} N·m",
        b.total,
        b.total,
        b.twist + b.wave_generator,
        b.quantization,
        b.reading_error_counts,
        b.kinematic,
        b.model_kinematic_error,
        b.plant_kinematic_error,
        b.start,
        b.rest,
        b.wave_generator,
        b.grid_step,
    );
    let d = design(Feedback::Estimate);
    eprintln!(
        "ρ_τt = {:.3} N·m, K_r = {:.4} N·m (limit {}); largest |estimate - T_f| at a sample \
         over seeds 0-47: {worst:.3} N·m where |T_f| ≤ 5 N·m ({overall:.3} N·m at any sample; \
         {uncovered} samples beyond 5 N·m, largest |T_f(t_k)| {largest_torque:.2} N·m)",
        torque_error_bound(Feedback::Estimate),
        d.robust_gain(),
        d.torque_limit,
    );
    assert!(worst <= b.total, "{worst} > {}", b.total);
}

/// Premise (1) of the estimate-feedback criteria (module docs) fails: with
/// the derived `ε̄`, `K_r = ρ_fq + ρ_τt/N` is above the torque limit, so
/// the law cannot deliver its robust term and Theorem 1's conclusion with
/// the estimate fed back is **undecided** on this family at 4 ms. The E4.4
/// step ratio at the family's fastest trajectory (`N·0.2·2π/1.5` =
/// 83.8 rad/s) is reported, with `K_r` and `ρ_τt`. This test records the
/// finding: it fails if a tighter `ε̄` (or another design) brings `K_r`
/// below the limit, and the check must then be decided again.
#[test]
fn estimate_feedback_with_the_derived_bound_is_undecided() {
    let d = design(Feedback::Estimate);
    let rho = torque_error_bound(Feedback::Estimate);
    let k_r = d.robust_gain();
    let peak = RATIO * 0.2 * TAU / 1.5;
    let ratio = UltimateBound::step_ratio_at_speed(&d, peak);
    eprintln!(
        "ε̄ = {:.3} N·m, ρ_τt = {rho:.3} N·m, K_r = {k_r:.4} N·m (limit {}), \
         step ratio at {peak:.1} rad/s: {ratio:.3}",
        estimate_error_bound().total,
        d.torque_limit
    );
    assert!(RobustAdaptiveParams::try_new(d).is_ok());
    assert!(k_r >= d.torque_limit, "premise (1) holds now: {k_r}");
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

    /// The library's own joint-torque estimate fed back, the law designed
    /// with the derived `ε̄` (module docs, "Estimate feedback: the derived
    /// `ε̄`"): the derived parts must hold in every case — no counter jump,
    /// the estimator error within `ε̄` at every sample where its premise
    /// `|T_f(t_k)| ≤ 5 N·m` holds (samples beyond it are counted and
    /// printed: the derivation says nothing there), and eq. (4.14),
    /// `|T_f(t) + ε_k − L(t)| ≤ ρ_τt`, checked directly.
    /// Theorem 1's conclusion is not asserted: premise (1) fails
    /// ([`estimate_feedback_with_the_derived_bound_is_undecided`]), so the
    /// verdict is undecided; each case prints its premises (step ratio,
    /// saturated samples) and `|r|` against `r̄(δ)` for the record. Seeds
    /// from `[2³², 2⁶⁴)`, disjoint from the observation's.
    ///
    /// 48 cases (about 9 s in release). Seen on two runs (with the two
    /// kept regressions, 50 cases each): `|ε_k|` 1.1–4.86 and 1.2–5.18 N·m
    /// against `ε̄` = 18.13, the feedback error 3.2–8.6 and 3.1–7.6 N·m
    /// against `ρ_τt` = 24.36 N·m, `|T_f(t_k)|` up to 9.66 and 6.36 N·m (3
    /// and 1 cases beyond 5 N·m, up to 17 samples each), the step ratio
    /// 0.41–0.48, no saturated sample, `|r|` at most 0.17 and 0.18 of
    /// `r̄(δ)`.
    #[test]
    fn estimate_feedback_with_the_derived_bound(c in estimate_case()) {
        let r = run(&c);
        eprintln!(
            "estimate case: plant {} A {:.3} P {:.2}: |ε_k| ≤ {:.3} ({} samples beyond 5 N·m), \
             feedback error {:.3}, \
             |T_f(t_k)| ≤ {:.2} (any t: {:.2}), step ratio {:.3}, saturated {}, \
             |r| {:.1} vs r̄(δ) {:.1}",
            c.plant, c.amplitude, c.period, r.max_sample_error, r.uncovered_samples,
            r.max_feedback_error,
            r.max_sample_flexspline, r.max_flexspline, r.step_ratio, r.saturated,
            r.max_sliding, r.radius
        );
        prop_assert_eq!(r.counter_jumps, 0, "{:?} {:?}", c, r);
        prop_assert!(r.max_covered_error <= estimate_error_bound().total, "{c:?} {r:?}");
        prop_assert!(r.max_feedback_error <= torque_error_bound(c.feedback), "{c:?} {r:?}");
    }
}
