//! The robust adaptive law of thesis §4.2 (active mode), eq. (4.15)–(4.19),
//! with the adaptation law of Theorem 1.
//!
//! Per sample, with `e = q_m − q_m^d`, `r = ė + λe` and
//! `a = q̈_m^d − 2λė − λ²e` (eq. 4.15):
//!
//! ```text
//! τ_m = I_m a + τ̂_t/N + f̂^c(q̇_m) − z
//!       − K_r sat(r, ε_r)
//!       − Σ_{j=1..4} ρ_Fj Y_j sat(r Y_j, ε_Fj)
//! ```
//!
//! (eq. 4.19), where `K_r = ρ_f + ρ_fq + I_m ρ_base + ρ_τ/N`, `f̂^c` and `Y`
//! are the nominal friction and regressor of eq. (4.17)
//! ([`crate::friction`]), and `z = K_I ∫ r dt` is the integral term. Then
//! the states advance by one sample `T` (forward Euler):
//!
//! * integral: `z ← clamp(z + K_I T r, ±z_max)`, skipped while the output
//!   is saturated and `r` would push it further (conditional integration);
//! * adaptation (Theorem 1, with the hat restored — errata E4.2):
//!   `F̂^c ← Proj(F̂^c − Γ T Yᵀ r)` with `Γ = diag(μ_j)` and `Proj` the
//!   projection onto the box of [`FrictionBounds`]. For a box, projecting
//!   is clamping each component; when the true `F^c` is in the box it never
//!   increases `F̃ᵀΓ⁻¹F̃`, so the Lyapunov argument of eq. (4.20)–(4.28)
//!   holds unchanged, and the estimates stay bounded (the pure gradient law
//!   drifts under the bounded disturbances of Assumptions 3–6).
//!
//! The output is saturated at `±torque_limit` and flagged.
//!
//! # Derivation check (eq. 4.20–4.23)
//! Substituting eq. (4.19) into eq. (4.6) written as
//! `I_m q̈_m + f_m + τ_base + τ_t/N = τ_m` gives
//! `I_m ṙ = −I_m λ r − z − (f_m − f̂^c) − τ_base − τ̃_t/N − (robust terms)`
//! (the `2λ` of `a` leaves exactly `−λ r`). With eq. (4.16),
//! `f_m − f̂^c = Y(F̃^c + F^v) + f_q + f̌`, so `V̇` of eq. (4.21) contains
//! `−r Y F̃^c + (d F̃^c/dt)ᵀ Γ⁻¹ F̃^c`, which vanishes iff
//! `d F̂^c/dt = −Γ Yᵀ r` (`F^c` constant). This is the printed law with the
//! hat on `F^c`; the sign is as printed. Checked numerically by
//! `adaptation_cancels_the_parametric_term`.
//!
//! # Cost
//! No division and one `exp` per step; every rate and unit factor is a
//! prepared [`Coef`] (on fixed point, a factor whose value the backend
//! holds exactly uses the backend's own, bit-identical product).

use super::{clamp_or_keep_symmetric, ControlInput};
use crate::error::{combination, in_range, non_negative, positive, ParamError};
use crate::friction::{
    mul_unit, parameter_scales, regressor_scales, FrictionBounds, FrictionConfig, FrictionParams,
};
use crate::scalar::{slope_within, units, Coef, Gain, Scalar};

/// The uncertainty bounds of Assumptions 3–6, eq. (4.11)–(4.14).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UncertaintyBounds {
    /// `ρ_f`, bound of the boundary-layer residual `f̌` (Assumption 6), N·m
    /// (see [`FrictionBounds::boundary_layer_bound`] for a derived value).
    pub boundary_layer: f64,
    /// `ρ_fq`, bound of the nonparametric friction `f_q` (eq. 4.11), N·m.
    pub nonparametric_friction: f64,
    /// `ρ_base`, bound of the base-motion acceleration terms (eq. 4.12),
    /// rad/s²; the torque bound is `I_m ρ_base` (eq. 4.13).
    pub base_acceleration: f64,
    /// `ρ_τt`, bound of the joint-torque estimation error (eq. 4.14), N·m
    /// (link side).
    pub torque_estimate: f64,
}

/// The design of the active-mode law in SI units (all fields public; use
/// [`RobustAdaptiveParams::try_new`] to validate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobustAdaptiveDesign {
    /// Rotor inertia `I_m`, kg·m².
    pub rotor_inertia: f64,
    /// Reduction ratio `N ≥ 1`.
    pub ratio: f64,
    /// `λ > 0` of eq. (4.15), 1/s.
    pub lambda: f64,
    /// Integral gain `K_I ≥ 0`, N·m/rad (motor side).
    pub integral_gain: f64,
    /// Adaptation gains `μ_j ≥ 0` (Theorem 1's `μ_Fic`, one per component
    /// of `F` so that each has consistent units; Table 4.1 uses one value
    /// for all). Unit of `μ_j`: the unit of `F_j` per unit of `r Y_j` per
    /// second.
    pub adaptation_gain: [f64; 4],
    /// Boundary layer `ε_r > 0` of the robust term, rad/s.
    pub eps_r: f64,
    /// Boundary layer `ε_q̇ > 0` of the friction model, rad/s.
    pub eps_velocity: f64,
    /// Boundary layers `ε_Fj > 0` of the parametric robust terms, in units
    /// of `r Y_j`: `[rad²/s², rad/s, rad/s, N·m·rad³/s³]`.
    pub eps_f: [f64; 4],
    /// Assumptions 3–6.
    pub uncertainty: UncertaintyBounds,
    /// Projection box of `F^c` and the variable-part bounds `ρ_F`.
    pub friction_bounds: FrictionBounds,
    /// Initial estimate `F̂^c(0)`, inside the box.
    pub initial_friction: FrictionParams,
    /// Limit of the integral torque `|z|`, N·m (motor side), `[0, 16]`.
    pub integral_limit: f64,
    /// Motor torque limit, N·m, `(0, 16]`.
    pub torque_limit: f64,
    /// Sampling period `T`, s, in `[1e-7, 1]`.
    pub sample_period: f64,
}

impl RobustAdaptiveDesign {
    /// The design and control parameters of thesis Table 4.1 (joint 1,
    /// SHD-17-100 with the Maxon 218014 motor), completed where the table
    /// is silent:
    ///
    /// * printed: `I_m = 1.14e-5 kg·m²`, `N = 100`, `λ = 120`, `K_I = 10`,
    ///   `μ = 0.1` (all components), `ε_r = 0.1`, `ε_q̇ = 0.01`,
    ///   `ε_F = [1e-4, 1e-3, 1e-3, 0.1]`, `ρ_F = [1e-3, 1e-2, 1e-2, 1.0]`,
    ///   `ρ_base = 1e4 rad/s²`, `ρ_fq = 2e-3 N·m`, `ρ_τt = 1 N·m`;
    /// * not printed, chosen here: the friction box
    ///   `b ∈ [0, 1e-4]`, `f_c, f_s ∈ [0, 0.012]` (the drive's 0.012 N·m
    ///   starting torque, ch. 2), `f_τ ∈ [0.01, 10]`, the initial estimate
    ///   at the box centre in `b, f_c, f_s` and `f_τ = 1`; `ρ_f` derived
    ///   from the box ([`FrictionBounds::boundary_layer_bound`],
    ///   0.044 N·m); the motor torque limit 0.188 N·m (the motor's rated
    ///   maximum, §2.4); the integral limit 0.1 N·m; `T = 4 ms` (§6.3).
    pub fn table_4_1() -> Self {
        let bounds = FrictionBounds::from_checked(
            [0.0, 0.0, 0.0, 0.01],
            [1e-4, 0.012, 0.012, 10.0],
            [1e-3, 1e-2, 1e-2, 1.0],
        );
        RobustAdaptiveDesign {
            rotor_inertia: 1.14e-5,
            ratio: 100.0,
            lambda: 120.0,
            integral_gain: 10.0,
            adaptation_gain: [0.1; 4],
            eps_r: 0.1,
            eps_velocity: 0.01,
            eps_f: [1e-4, 1e-3, 1e-3, 0.1],
            uncertainty: UncertaintyBounds {
                boundary_layer: bounds.boundary_layer_bound(),
                nonparametric_friction: 2e-3,
                base_acceleration: 1e4,
                torque_estimate: 1.0,
            },
            friction_bounds: bounds,
            initial_friction: FrictionParams {
                viscous: 5e-5,
                coulomb: 0.006,
                stribeck: 0.006,
                stribeck_shape: 1.0,
            },
            integral_limit: 0.1,
            torque_limit: 0.188,
            sample_period: 0.004,
        }
    }

    /// `K_r = ρ_f + ρ_fq + I_m ρ_base + ρ_τ/N`, the gain of
    /// `sat(r, ε_r)` in eq. (4.19), N·m.
    pub fn robust_gain(&self) -> f64 {
        let u = &self.uncertainty;
        u.boundary_layer
            + u.nonparametric_friction
            + self.rotor_inertia * u.base_acceleration
            + u.torque_estimate / self.ratio
    }
}

/// A validated [`RobustAdaptiveDesign`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobustAdaptiveParams {
    design: RobustAdaptiveDesign,
}

fn at_most(name: &'static str, value: f64, max: f64) -> Result<f64, ParamError> {
    if value > max {
        Err(ParamError::OutOfRange {
            name,
            value,
            min: 0.0,
            max,
        })
    } else {
        Ok(value)
    }
}

/// Largest stored value of a boundary layer (`I16F16` units).
const LAYER_MAX_STORED: f64 = 30_000.0;

/// A boundary layer must survive quantization on every backend: at least
/// one `I16F16` LSB and at most `30 000` in its stored unit (`scale` per
/// SI unit); the error states the range in SI.
fn layer(name: &'static str, value: f64, scale: f64) -> Result<f64, ParamError> {
    let value = positive(name, value)?;
    // The bounds in SI, compared as printed.
    let (min, max) = (1.0 / 65536.0 / scale, LAYER_MAX_STORED / scale);
    if value < min || value > max {
        return Err(ParamError::OutOfRange {
            name,
            value,
            min,
            max,
        });
    }
    Ok(value)
}

/// Field paths of [`RobustAdaptiveDesign::eps_f`]'s components.
const EPS_F: [&str; 4] = ["eps_f[0]", "eps_f[1]", "eps_f[2]", "eps_f[3]"];
/// Field paths of [`RobustAdaptiveDesign::adaptation_gain`]'s components.
const ADAPTATION_GAIN: [&str; 4] = [
    "adaptation_gain[0]",
    "adaptation_gain[1]",
    "adaptation_gain[2]",
    "adaptation_gain[3]",
];
/// Each `μ_j T` (SI) at most `1e11` once scaled to the stored `I16F16`
/// units of the step `F̂_j ← F̂_j − μ_j T r Y_j`.
const ADAPTATION_STEP: [&str; 4] = [
    "adaptation_gain[0]·sample_period",
    "adaptation_gain[1]·sample_period",
    "adaptation_gain[2]·sample_period",
    "adaptation_gain[3]·sample_period",
];
/// Field paths of the variable-part bounds `ρ_F` in the design.
const VARIABLE_BOUND: [&str; 4] = [
    "friction_bounds.variable[0]",
    "friction_bounds.variable[1]",
    "friction_bounds.variable[2]",
    "friction_bounds.variable[3]",
];
/// Field paths of the initial estimate's components.
const INITIAL_FRICTION: [&str; 4] = [
    "initial_friction.viscous",
    "initial_friction.coulomb",
    "initial_friction.stribeck",
    "initial_friction.stribeck_shape",
];

/// Largest magnitude of a prepared coefficient in stored units (the range
/// a `Coef` represents exactly is `2⁴⁰ ≈ 1.1e12`).
const COEF_MAX: f64 = 1e11;

/// Largest robust gain `K_r`, N·m (motor side).
pub const ROBUST_GAIN_MAX: f64 = 30.0;

impl RobustAdaptiveParams {
    /// Validate a design. Every field is checked on its own first, in
    /// declaration order, and each error names the field as written
    /// (`uncertainty.boundary_layer`, `eps_f[2]`,
    /// `initial_friction.viscous`, …) with the value given:
    /// `I_m ∈ (0, 30]` kg·m², `N ≥ 1`, `λ ∈ (0, 1e11]`, `K_I, μ_j ≥ 0`,
    /// boundary layers positive and representable on every backend (at
    /// least one `I16F16` LSB, at most `30 000`, in their stored units),
    /// `ρ_f, ρ_fq ∈ [0, 30]` N·m, `ρ_base ∈ [0, 30/I_m]`,
    /// `ρ_τt ∈ [0, 30·N]` N·m, torque and integral limits in `(0, 16]` and
    /// `[0, 16]` N·m (so that sums of two limits stay inside the `I16F16`
    /// range of mN·m, which the bumpless switching of [`super::mode`]
    /// relies on), `T ∈ [1e-7, 1]` s, the initial estimate a valid
    /// [`FrictionParams`] inside the friction box. Then the combinations,
    /// named in the fields' names ([`ParamError::CombinationOutOfRange`]):
    /// the robust gain `K_r` at most [`ROBUST_GAIN_MAX`] N·m, and every
    /// prepared coefficient at most `1e11` in fixed-point units:
    /// `λ² I_m ≤ 1e8` (SI), `K_I T ≤ 1e8`,
    /// `μ_j T ≤ [1e8, 1e8, 1e8, 1e14]`, and the variable-part bounds
    /// `ρ_Fj ≤ [1e8, 1e8, 1e8, 1e11]`.
    pub fn try_new(d: RobustAdaptiveDesign) -> Result<Self, ParamError> {
        let fx = units::FIXED;
        let mt = fx.motor_torque;
        let im = at_most(
            "rotor_inertia",
            positive("rotor_inertia", d.rotor_inertia)?,
            30.0,
        )?;
        let n = crate::error::gear_ratio(d.ratio)?;
        let lambda = at_most("lambda", positive("lambda", d.lambda)?, COEF_MAX)?;
        let k_i = non_negative("integral_gain", d.integral_gain)?;
        for (j, m) in d.adaptation_gain.iter().enumerate() {
            non_negative(ADAPTATION_GAIN[j], *m)?;
        }
        layer("eps_r", d.eps_r, fx.speed)?;
        layer("eps_velocity", d.eps_velocity, fx.speed)?;
        let ys = regressor_scales::<crate::scalar::I16F16>();
        for (j, e) in d.eps_f.iter().enumerate() {
            layer(EPS_F[j], *e, fx.speed * ys[j])?;
        }
        let u = d.uncertainty;
        let k_max = ROBUST_GAIN_MAX;
        in_range("uncertainty.boundary_layer", u.boundary_layer, 0.0, k_max)?;
        in_range(
            "uncertainty.nonparametric_friction",
            u.nonparametric_friction,
            0.0,
            k_max,
        )?;
        in_range(
            "uncertainty.base_acceleration",
            u.base_acceleration,
            0.0,
            k_max / im,
        )?;
        in_range(
            "uncertainty.torque_estimate",
            u.torque_estimate,
            0.0,
            k_max * n,
        )?;
        at_most(
            "torque_limit",
            positive("torque_limit", d.torque_limit)?,
            16.0,
        )?;
        at_most(
            "integral_limit",
            non_negative("integral_limit", d.integral_limit)?,
            16.0,
        )?;
        let t = positive("sample_period", d.sample_period)?;
        in_range("sample_period", t, 1e-7, 1.0)?;
        let f = d.initial_friction;
        FrictionParams {
            viscous: f.viscous,
            coulomb: f.coulomb,
            stribeck: f.stribeck,
            stribeck_shape: f.stribeck_shape,
        }
        .validated()
        .map_err(|e| e.map_names(crate::friction::initial_friction_path))?;
        let (lo, hi, a) = (
            d.friction_bounds.min(),
            d.friction_bounds.max(),
            f.to_array(),
        );
        for j in 0..4 {
            in_range(INITIAL_FRICTION[j], a[j], lo[j], hi[j])?;
        }
        // The combinations, every factor already finite and in range.
        combination(
            "uncertainty.boundary_layer + uncertainty.nonparametric_friction \
             + rotor_inertia·uncertainty.base_acceleration + uncertainty.torque_estimate/ratio",
            d.robust_gain(),
            0.0,
            k_max,
        )?;
        // Every prepared coefficient (in the largest, fixed-point, unit
        // scales) within the range a `Coef` represents exactly; stated in
        // SI. `K_r/ε_r` needs no check: `K_r ≤ 30` N·m and `ε_r ≥ 2⁻¹⁶`
        // rad/s keep it below `2e9` stored; nor does `2λ I_m`, at most
        // `2·√(1e8 · 30) ≈ 1.1e5` N·m·s/rad once `λ² I_m ≤ 1e8` and
        // `I_m ≤ 30`.
        combination(
            "lambda²·rotor_inertia",
            lambda * lambda * im,
            0.0,
            COEF_MAX / mt,
        )?;
        combination("integral_gain·sample_period", k_i * t, 0.0, COEF_MAX / mt)?;
        let ps = parameter_scales::<crate::scalar::I16F16>();
        let rho = d.friction_bounds.variable();
        for j in 0..4 {
            let ry = fx.speed * ys[j];
            combination(
                ADAPTATION_STEP[j],
                d.adaptation_gain[j] * t,
                0.0,
                COEF_MAX * ry / ps[j],
            )?;
            in_range(VARIABLE_BOUND[j], rho[j], 0.0, COEF_MAX * ys[j] / mt)?;
        }
        Ok(RobustAdaptiveParams { design: d })
    }

    /// Table 4.1 ([`RobustAdaptiveDesign::table_4_1`]), validated.
    pub fn table_4_1() -> Result<Self, ParamError> {
        Self::try_new(RobustAdaptiveDesign::table_4_1())
    }

    /// The validated design.
    pub fn design(&self) -> &RobustAdaptiveDesign {
        &self.design
    }
}

/// The active-mode law quantized for backend `S`.
///
/// `repr(C)`, the fields in the order the step reads them, the small
/// backend values first: on the Cortex-M4F a single-precision load reaches
/// 1020 bytes past its base register, so the step reads them without
/// forming their addresses (the joint's configuration is about 3 kB).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct RobustAdaptiveConfig<S> {
    /// `±1 · K_r` as the coefficient `K_r` (stored motor torque) rounds
    /// them: the robust term outside the layer `|r| > ε_r`.
    robust_gain_value: [S; 2],
    eps_r: S,
    eps_f: [S; 4],
    lower: [S; 4],
    upper: [S; 4],
    integral_limit: S,
    torque_limit: S,
    friction: FrictionConfig<S>,
    /// `λ` from stored angle to stored speed.
    lambda: Gain<S>,
    /// `1/N` from stored link torque to stored motor torque.
    feedback: Gain<S>,
    /// `K_I T` from stored speed to stored motor torque.
    integral_step: Gain<S>,
    /// `I_m` from stored acceleration to stored motor torque.
    accel_inertia: Coef,
    /// `λ I_m` from stored speed to stored motor torque (`I_m a` is
    /// formed as `I_m q̈_d − λ I_m (ė + r)`, see [`law`](Self::law)).
    lambda_inertia: Coef,
    /// `K_r / ε_r` from stored speed to stored motor torque: the robust
    /// term inside the layer.
    robust_slope: Coef,
    /// `ρ_Fj` from stored `Y_j` to stored motor torque.
    rho_param: [Coef; 4],
    /// `−μ_j T` from stored `r Y_j` to stored `F_j` (the step
    /// `F̂_j ← F̂_j − μ_j T r Y_j`).
    adapt: [Coef; 4],
    /// `ρ_Fj / ε_Fj` from stored `Y_j` to stored motor torque per stored
    /// `r Y_j`: the parametric robust term inside its layer.
    rho_slope: [Coef; 4],
    initial: [S; 4],
    params: RobustAdaptiveParams,
}

/// The adapted state: `F̂^c` (stored parameter units, see
/// [`crate::friction`]) with its sub-resolution residual, and the integral
/// torque `z = K_I ∫ r dt` (stored motor-torque units).
///
/// # Resolution of the slow integrators
/// One step changes `F̂_j` by `μ_j T r Y_j`. Rounded to the backend at every
/// sample, a step below half an LSB would be lost: on `I16F16` with Table
/// 4.1's `μ = 0.1`, `T = 4 ms` that is `|r Y_4| < 0.019 N·m·rad³/s³` for
/// the Stribeck shape `f̂_τ` (stored in s²/rad², step `4e-7·r·Y_4` in
/// stored units with `Y_4` in mN·m·rad²/s²), while `|Y_4| ≤ f̂_s/(e f̂_τ)`
/// (`≤ 4.4e-3 N·m·rad²/s²` in the Table 4.1 box at `f̂_τ ≥ 1`): `f̂_τ` would
/// only move for `|r| ≳ 4 rad/s`. The estimates are therefore advanced by
/// [`Scalar::integrate`], which carries what rounding leaves in
/// [`friction_residual`](Self::friction_residual): on `I16F16` a Q16.48
/// accumulator (resolution `2⁻⁴⁸ ≈ 3.6e-15` stored units), so every
/// non-zero `r Y_j` product moves it (the smallest, one LSB of
/// `r Y_4` times `4e-7`, is `6e-12`, `1.7e3` accumulator steps). The same
/// holds at Table 6.1's gains (`μ = 0.1`, `T = 4 ms`: the same
/// coefficients). `f64` keeps its value as the accumulator (a step is
/// lost only below `2⁻⁵³` of the value: `rY_4 ≲ 1e-12` at `f̂_τ ≈ 1`).
/// A plain `f32` sum would lose every step below `2⁻²⁴` of the value
/// (`|r Y_4| < 1.5e-4` at `f̂_τ ≈ 1`, `< 6e-4` at `f̂_τ = 4`): in the
/// test scenario a plain `f32` `f̂_τ` started at 4 never moves
/// (`plain_f32_sum_loses_the_stribeck_shape_adaptation`), so `f32` carries
/// the rounding error of each sum as its residual (a compensated sum).
/// All three backends are compared against `f64` within a derived bound by
/// `adaptation_trajectories_agree_across_backends`.
///
/// The integral `z` is not a slow integrator in this sense: its step
/// `K_I T r` is `40·r` stored (Table 4.1 and 6.1: `K_I = 10`, `T = 4 ms`,
/// mN·m per rad/s), so the smallest non-zero `r` (one LSB) moves `z` by 40
/// LSB: nothing is lost (checked by `slow_integrators_move_at_table_gains`).
///
/// # Reading and building a state
/// The fields are private: a state comes from
/// [`RobustAdaptiveConfig::initial_state`], from
/// [`RobustAdaptiveConfig::state`] (SI values, validated against the
/// configuration's box and integral limit) or from the steps, so every
/// state reachable through the public API is finite, has `F̂^c` inside the
/// projection box and `|z| ≤ integral_limit`. Writing a field does not
/// compile:
///
/// ```compile_fail,E0616
/// use mrr_control::control::{RobustAdaptiveConfig, RobustAdaptiveParams};
/// let cfg = RobustAdaptiveConfig::<f32>::new(&RobustAdaptiveParams::table_4_1().unwrap());
/// let mut st = cfg.initial_state();
/// st.friction = [f32::NAN; 4];
/// ```
///
/// Read the values in SI with [`friction_si`](Self::friction_si) and
/// [`integral_si`](Self::integral_si) (the same physical value on every
/// backend, within its resolution), or in the backend's stored units with
/// [`friction`](Self::friction) and [`integral`](Self::integral).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobustAdaptiveState<S: Scalar> {
    /// `F̂^c = [b̂, f̂_c, f̂_s, f̂_τ]`, stored units; always inside the box.
    pub(crate) friction: [S; 4],
    /// What rounding `F̂^c` to the backend left over
    /// ([`Scalar::Residual`]).
    pub(crate) friction_residual: [S::Residual; 4],
    /// `z = K_I ∫ r dt`, stored motor torque; `|z| ≤ integral_limit`.
    pub(crate) integral: S,
}

impl<S: Scalar> RobustAdaptiveState<S> {
    /// A state with estimates `friction` (stored units) and integral
    /// `integral` (stored motor torque), and no residual; unchecked, for
    /// the crate's own tests and proofs (users call
    /// [`RobustAdaptiveConfig::state`]).
    pub(crate) fn from_stored(friction: [S; 4], integral: S) -> Self {
        RobustAdaptiveState {
            friction,
            friction_residual: Default::default(),
            integral,
        }
    }

    /// The friction estimate `F̂^c = [b̂, f̂_c, f̂_s, f̂_τ]` of eq. (4.16) in
    /// SI, motor side: `viscous` `b̂` in N·m·s/rad, `coulomb` `f̂_c` and
    /// `stribeck` `f̂_s` in N·m, `stribeck_shape` `f̂_τ` in s²/rad². Signs:
    /// every component is inside the projection box of
    /// [`FrictionBounds`] (non-negative for a box that is); the friction
    /// torque they give opposes the motion (eq. 4.17). Each is the stored
    /// value divided by its scale: `motor_torque/speed`, `motor_torque`,
    /// `motor_torque` and `1/speed²` of [`Scalar::UNITS`] (all `1` on
    /// floats; on `I16F16` the stored units are mN·m and rad/s, so
    /// `b̂` and `f̂_c`, `f̂_s` are stored 1000 times larger than in SI).
    pub fn friction_si(&self) -> FrictionParams {
        FrictionConfig::<S>::dequantize(&self.friction)
    }

    /// The integral torque `z = K_I ∫ r dt` of eq. (4.19) in N·m, motor
    /// side: the stored value divided by `S::UNITS.motor_torque` (`1` on
    /// floats, `1000` on `I16F16`). It enters the law with a minus sign
    /// (`τ_m = … − z`): a positive `z` (the motor has run ahead of its
    /// reference, `r > 0`) lowers the command. `|z| ≤ integral_limit`.
    pub fn integral_si(&self) -> f64 {
        self.integral.to_f64() / S::UNITS.motor_torque
    }

    /// `F̂^c` in the backend's stored units (see
    /// [`friction_si`](Self::friction_si) for SI and the scales).
    pub fn friction(&self) -> [S; 4] {
        self.friction
    }

    /// What rounding `F̂^c` to the backend left over
    /// ([`Scalar::Residual`], the sub-resolution part of each estimate).
    pub fn friction_residual(&self) -> [S::Residual; 4] {
        self.friction_residual
    }

    /// `z` in stored motor-torque units (see
    /// [`integral_si`](Self::integral_si) for N·m).
    pub fn integral(&self) -> S {
        self.integral
    }
}

/// One step of the active law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveOutput<S> {
    /// Motor torque command, stored motor-torque units, `|τ| ≤ limit`.
    pub torque: S,
    /// The law's value before the output limit (eq. 4.19).
    pub law_torque: S,
    /// The torque is not the law's value: it was limited to
    /// `±torque_limit`, or the sample was invalid (then also
    /// `invalid_input`); the limit alone is `saturated && !invalid_input`
    /// ([status flags](crate::joint#status-flags)).
    pub saturated: bool,
    /// An input was NaN or infinite, or the law overflowed to NaN: the
    /// torque is 0 and the state was not advanced. The state itself cannot
    /// be the cause (it is always finite and in its box).
    pub invalid_input: bool,
    /// Tracking error `e = q_m − q_m^d`, stored angle units.
    pub tracking_error: S,
    /// `r = ė + λ e`, stored speed units.
    pub sliding: S,
}

/// The law's intermediate values, for the state update and the mode
/// manager.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ActiveTerms<S> {
    pub law: S,
    pub e: S,
    pub r: S,
    pub ry: [S; 4],
    pub valid: bool,
}

impl<S: Scalar> RobustAdaptiveConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &RobustAdaptiveParams) -> Self {
        let d = &p.design;
        let u = S::UNITS;
        let mt = u.motor_torque;
        let ps = parameter_scales::<S>();
        let ys = regressor_scales::<S>();
        let eps_r = S::from_f64(d.eps_r * u.speed);
        let mut eps_f = [S::ZERO; 4];
        let mut rho_slope = [Coef::new(0.0); 4];
        let mut rho_param = [Coef::new(0.0); 4];
        let mut adapt = [Coef::new(0.0); 4];
        let rho = d.friction_bounds.variable();
        for j in 0..4 {
            let ry_scale = u.speed * ys[j];
            eps_f[j] = S::from_f64(d.eps_f[j] * ry_scale);
            rho_param[j] = Coef::new(rho[j] * mt / ys[j]);
            rho_slope[j] = Coef::new(rho[j] * mt / ys[j] / eps_f[j].to_f64());
            adapt[j] = Coef::new(-d.adaptation_gain[j] * d.sample_period * ps[j] / ry_scale);
        }
        let lo = d.friction_bounds.min();
        let hi = d.friction_bounds.max();
        let q = |a: [f64; 4]| {
            let mut o = [S::ZERO; 4];
            for j in 0..4 {
                o[j] = S::from_f64(a[j] * ps[j]);
            }
            o
        };
        let gain = Coef::new(d.robust_gain() * mt);
        let robust_gain_value = [S::ONE.mul_coef(&gain), S::ONE.neg().mul_coef(&gain)];
        // K_r/ε_r at most rounded down so that `±ε_r·(K_r/ε_r)` stays within
        // `[−K_r, K_r]`: the layer's value needs no clamp.
        let robust_slope = slope_within(d.robust_gain() * mt / eps_r.to_f64(), Coef::new, |c| {
            eps_r.mul_coef(c) <= robust_gain_value[0]
                && eps_r.neg().mul_coef(c) >= robust_gain_value[1]
        });
        RobustAdaptiveConfig {
            friction: FrictionConfig::new(d.eps_velocity),
            accel_inertia: Coef::new(d.rotor_inertia * mt / u.speed),
            lambda_inertia: Coef::new(d.lambda * d.rotor_inertia * mt / u.speed),
            lambda: Gain::new(d.lambda * u.speed / u.angle),
            feedback: Gain::new(mt / (d.ratio * u.link_torque)),
            integral_step: Gain::new(d.integral_gain * d.sample_period * mt / u.speed),
            robust_gain_value,
            eps_r,
            robust_slope,
            rho_param,
            eps_f,
            rho_slope,
            adapt,
            lower: q(lo),
            upper: q(hi),
            initial: q(d.initial_friction.to_array()),
            integral_limit: S::from_f64(d.integral_limit * mt),
            torque_limit: S::from_f64(d.torque_limit * mt),
            params: *p,
        }
    }

    /// The initial state: `F̂^c(0)` of the design, `z = 0`.
    pub fn initial_state(&self) -> RobustAdaptiveState<S> {
        RobustAdaptiveState::from_stored(self.initial, S::ZERO)
    }

    /// A state with the friction estimate `friction` (SI, see
    /// [`RobustAdaptiveState::friction_si`]) and the integral torque
    /// `integral` (N·m, motor side, sign of
    /// [`RobustAdaptiveState::integral_si`]), and no residual: e.g. to
    /// resume from estimates saved with those readers.
    ///
    /// # Errors
    /// [`ParamError::NotFinite`] for a NaN or infinite value and
    /// [`ParamError::OutOfRange`] for an estimate outside the projection
    /// box of the design's [`FrictionBounds`] or an integral with
    /// `|z| > integral_limit`, each naming the argument's field
    /// (`friction.viscous`, `friction.coulomb`, `friction.stribeck`,
    /// `friction.stribeck_shape`, `integral`).
    ///
    /// ```
    /// use mrr_control::control::{RobustAdaptiveConfig, RobustAdaptiveParams};
    /// use mrr_control::friction::FrictionParams;
    /// use mrr_control::scalar::I16F16;
    /// let cfg = RobustAdaptiveConfig::<I16F16>::new(&RobustAdaptiveParams::table_4_1()?);
    /// let f = FrictionParams { viscous: 2e-5, coulomb: 0.004, stribeck: 0.003, stribeck_shape: 2.0 };
    /// let st = cfg.state(f, 0.05)?;
    /// assert!((st.integral_si() - 0.05).abs() < 1e-3);
    /// assert!((st.friction_si().coulomb - 0.004).abs() < 1e-3);
    /// // A NaN estimate is refused, naming the field.
    /// let bad = FrictionParams { coulomb: f64::NAN, ..f };
    /// assert!(cfg.state(bad, 0.0).unwrap_err().to_string().contains("friction.coulomb"));
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn state(
        &self,
        friction: FrictionParams,
        integral: f64,
    ) -> Result<RobustAdaptiveState<S>, ParamError> {
        const NAMES: [&str; 4] = [
            "friction.viscous",
            "friction.coulomb",
            "friction.stribeck",
            "friction.stribeck_shape",
        ];
        let d = &self.params.design;
        let (lo, hi, a) = (
            d.friction_bounds.min(),
            d.friction_bounds.max(),
            friction.to_array(),
        );
        for j in 0..4 {
            in_range(NAMES[j], a[j], lo[j], hi[j])?;
        }
        in_range("integral", integral, -d.integral_limit, d.integral_limit)?;
        let ps = parameter_scales::<S>();
        let mut f = [S::ZERO; 4];
        for j in 0..4 {
            // Rounding is monotone, so the quantized value is inside the
            // quantized box; the clamp only guards that statement.
            f[j] = S::from_f64(a[j] * ps[j]).clamp(self.lower[j], self.upper[j]);
        }
        let z = S::from_f64(integral * S::UNITS.motor_torque)
            .clamp(self.integral_limit.neg(), self.integral_limit);
        Ok(RobustAdaptiveState::from_stored(f, z))
    }

    /// The friction model of the law (`eq. 4.17` with the layer `ε_v`),
    /// for the proof harnesses that start from a stored configuration.
    #[cfg(any(kani, test))]
    pub(crate) fn friction_config(&self) -> &FrictionConfig<S> {
        &self.friction
    }

    /// The validated parameters this configuration was built from.
    pub fn params(&self) -> &RobustAdaptiveParams {
        &self.params
    }

    /// The motor torque limit, stored units.
    pub fn torque_limit(&self) -> S {
        self.torque_limit
    }

    /// The integral limit, stored motor-torque units.
    pub fn integral_limit(&self) -> S {
        self.integral_limit
    }

    /// Lower corner of the projection box, stored units.
    pub fn lower_bounds(&self) -> [S; 4] {
        self.lower
    }

    /// Upper corner of the projection box, stored units.
    pub fn upper_bounds(&self) -> [S; 4] {
        self.upper
    }

    /// The design with the boundary layers as this backend quantized them
    /// (for the ultimate-bound calculator: a layer quantized wider
    /// weakens the bound, e.g. Table 4.1's `ε_F1 = 1e-4` becomes
    /// `7·2⁻¹⁶` on `I16F16`).
    pub fn quantized_design(&self) -> RobustAdaptiveDesign {
        let mut d = self.params.design;
        let u = S::UNITS;
        let ys = regressor_scales::<S>();
        d.eps_r = self.eps_r.to_f64() / u.speed;
        d.eps_velocity = self.friction.eps_velocity().to_f64() / u.speed;
        for ((out, stored), y) in d.eps_f.iter_mut().zip(self.eps_f.iter()).zip(ys.iter()) {
            *out = stored.to_f64() / (u.speed * y);
        }
        d
    }

    /// Eq. (4.15)–(4.19) on one sample with the current state, without
    /// advancing it.
    #[inline]
    pub(crate) fn law(&self, st: &RobustAdaptiveState<S>, x: &ControlInput<S>) -> ActiveTerms<S> {
        let mut t = self.law_of_checked_input(st, x);
        t.valid &= x.is_finite();
        t
    }

    /// [`law`](Self::law) for a caller that has already rejected a
    /// non-finite sample (the mode manager checks its input once, before
    /// it shifts the reference): `valid` then only tests the law and `r`
    /// for NaN.
    #[cfg_attr(not(armv6m), inline(always))]
    #[cfg_attr(armv6m, inline)]
    pub(crate) fn law_of_checked_input(
        &self,
        st: &RobustAdaptiveState<S>,
        x: &ControlInput<S>,
    ) -> ActiveTerms<S> {
        let e = x.motor_position.sub(x.desired_position);
        let ed = x.motor_velocity.sub(x.desired_velocity);
        let r = ed.add(self.lambda.apply(e));
        // I_m a = I_m q̈_d − 2λ I_m ė − λ² I_m e = I_m q̈_d − λ I_m (ė + r)
        // (r = ė + λe): two products instead of three.
        let ia = x
            .desired_acceleration
            .mul_coef(&self.accel_inertia)
            .sub(ed.add(r).mul_coef(&self.lambda_inertia));
        // The speed is a number here (checked by the caller) or the law is NaN
        // anyway (`F̂_1 q̇`): the sat without its NaN test.
        let fr = self
            .friction
            .evaluate_number(&st.friction, x.motor_velocity);
        // K_r sat(r/ε_r): ±K_r outside the layer, (K_r/ε_r)·r inside it
        // (one product; the same value up to its rounding).
        // One magnitude test for the common inside-layer case (a NaN `r`
        // fails it too, and its law is NaN either way).
        // sign(r): ±1, for the robust terms outside their layers on floats.
        let r_sign = if r > S::ZERO { S::ONE } else { S::ONE.neg() };
        let robust = if r.abs() > self.eps_r {
            if r > S::ZERO {
                self.robust_gain_value[0]
            } else {
                self.robust_gain_value[1]
            }
        } else {
            // Never beyond ±K_r: the slope is prepared for that (`new`).
            r.mul_coef(&self.robust_slope)
        };
        // Written out for the four parameters (a counted loop is not
        // unrolled on Armv6-M, where its iterator costs more than the body).
        let y = fr.regressor;
        // Y_2 = sat(q̇, ε_q̇) is in [−1, 1] (usually ±1): the unit-range
        // product.
        // Y_3 = e^{−f̂_τ q̇²} sat(q̇, ε_q̇) is in [−1, 1] too.
        let ry = [
            r.mul(y[0]),
            mul_unit(r, y[1]),
            mul_unit(r, y[2]),
            r.mul(y[3]),
        ];
        let param_robust = self
            .param_robust_term(0, y[0], ry[0], r_sign)
            .add(self.param_robust_term(1, y[1], ry[1], r_sign))
            .add(self.param_robust_term(2, y[2], ry[2], r_sign))
            .add(self.param_robust_term(3, y[3], ry[3], r_sign));
        let law = ia
            .add(self.feedback.apply(x.joint_torque))
            .add(fr.torque)
            .sub(st.integral)
            .sub(robust)
            .sub(param_robust);
        ActiveTerms {
            law,
            e,
            r,
            ry,
            valid: !law.is_nan() && !r.is_nan(),
        }
    }

    /// `ρ_j Y_j sat(r Y_j / ε_j)` of eq. (4.19): `±ρ_j Y_j` outside the
    /// layer, `(ρ_j/ε_j) Y_j · r Y_j` inside it. `r_sign` is `1` for
    /// `r > 0`, else `−1`.
    #[inline(always)]
    fn param_robust_term(&self, j: usize, y: S, ry: S, r_sign: S) -> S {
        // One magnitude test on the inside-layer path (a NaN `ry` takes it
        // and stays NaN, as with two one-sided tests; `|MIN|` saturates to
        // `MAX` on fixed point and takes the negative branch, as before).
        if ry.abs() > self.eps_f[j] {
            // Floats: outside the layer `r Y_j` is a nonzero number (`ε_j`
            // is not negative), so `r` and `Y_j` are nonzero and
            // sign(r Y_j)·Y_j = sign(r)·|Y_j|, and rounding to nearest is
            // symmetric: `(sign(r)|Y_j|)·ρ_j` is `±(Y_j ρ_j)` bit for bit,
            // without a test per term (`sign(r)|Y_j|` is exact).
            // Fixed point rounds ties up, not symmetrically: its own test.
            if S::FLOAT {
                return y.abs().mul(r_sign).mul_coef(&self.rho_param[j]);
            }
            let t = y.mul_coef(&self.rho_param[j]);
            if ry > S::ZERO {
                t
            } else {
                t.neg()
            }
        } else {
            y.mul_coef(&self.rho_slope[j]).mul(ry)
        }
    }

    /// `law` limited to `±torque_limit`, and whether it was limited.
    #[inline]
    pub(crate) fn limit(&self, law: S) -> (S, bool) {
        let l = self.torque_limit;
        if law > l {
            (l, true)
        } else if law < l.neg() {
            (l.neg(), true)
        } else {
            (law, false)
        }
    }

    /// Advance integral and adaptation by one sample after `law`.
    #[inline]
    pub(crate) fn commit(&self, st: &mut RobustAdaptiveState<S>, t: &ActiveTerms<S>) {
        if t.valid {
            self.commit_valid(st, t);
        }
    }

    /// [`commit`](Self::commit) for terms already known to be valid.
    #[inline(always)]
    pub(crate) fn commit_valid(&self, st: &mut RobustAdaptiveState<S>, t: &ActiveTerms<S>) {
        let l = self.torque_limit;
        // z enters with a minus sign: r > 0 raises z and lowers τ.
        // One magnitude test on the common unsaturated path (`l` is at most
        // 16 N·m, inside every backend's range, so `|law| > l` is exactly
        // `law > l || law < −l`).
        let winding = t.law.abs() > l
            && if t.law > S::ZERO {
                t.r < S::ZERO
            } else {
                t.r > S::ZERO
            };
        if !winding {
            let z = st.integral.add(self.integral_step.apply(t.r));
            st.integral = clamp_or_keep_symmetric(z, st.integral, self.integral_limit);
        }
        // Written out for the four parameters (straight-line code: no loop
        // counter, constant offsets).
        self.adapt_one(st, t, 0);
        self.adapt_one(st, t, 1);
        self.adapt_one(st, t, 2);
        self.adapt_one(st, t, 3);
    }

    /// `F̂_j ← Proj(F̂_j − μ_j T r Y_j)` with its residual.
    #[inline(always)]
    fn adapt_one(&self, st: &mut RobustAdaptiveState<S>, t: &ActiveTerms<S>, j: usize) {
        (st.friction[j], st.friction_residual[j]) = st.friction[j].integrate(
            st.friction_residual[j],
            t.ry[j],
            &self.adapt[j],
            self.lower[j],
            self.upper[j],
        );
    }

    /// One control step: eq. (4.19) on the sample, then the integral and
    /// adaptation updates. Never panics; an invalid input gives torque 0
    /// with `invalid_input` set and leaves the state untouched.
    ///
    /// ```
    /// use mrr_control::control::{ControlInput, RobustAdaptiveConfig, RobustAdaptiveParams};
    /// let cfg = RobustAdaptiveConfig::<f32>::new(&RobustAdaptiveParams::table_4_1()?);
    /// let mut st = cfg.initial_state();
    /// // On the trajectory, at rest, no load: r = 0 and every term is 0.
    /// let o = cfg.update(&mut st, &ControlInput::default());
    /// assert_eq!(o.torque, 0.0);
    /// // 1 mrad ahead of the reference (motor side), at rest: e = 1e-3,
    /// // r = λe = 0.12 rad/s beyond ε_r = 0.1, Y = 0 at q̇ = 0, so
    /// // τ = −λ²I_m e − K_r = −1.6416e-4 − 0.170 = −0.17016 N·m.
    /// let x = ControlInput { motor_position: 1e-3, ..Default::default() };
    /// let o = cfg.update(&mut st, &x);
    /// assert!(!o.saturated && (o.torque + 0.17016).abs() < 1e-5);
    /// // The integral has moved by K_I T r = 10·0.004·0.12 = 4.8e-3 N·m.
    /// assert!((st.integral_si() - 4.8e-3).abs() < 1e-7);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(&self, st: &mut RobustAdaptiveState<S>, x: &ControlInput<S>) -> ActiveOutput<S> {
        let t = self.law(st, x);
        self.commit(st, &t);
        self.output(&t)
    }

    #[inline]
    pub(crate) fn output(&self, t: &ActiveTerms<S>) -> ActiveOutput<S> {
        if !t.valid {
            return ActiveOutput {
                torque: S::ZERO,
                law_torque: S::ZERO,
                saturated: true,
                invalid_input: true,
                tracking_error: S::ZERO,
                sliding: S::ZERO,
            };
        }
        let (torque, saturated) = self.limit(t.law);
        ActiveOutput {
            torque,
            law_torque: t.law,
            saturated,
            invalid_input: false,
            tracking_error: t.e,
            sliding: t.r,
        }
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::{FrictionBounds, FrictionConfig, FrictionParams, UncertaintyBounds};
    use super::{RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams};
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, Gain, I16F16};

    impl RobustAdaptiveParams {
        pub(crate) const fn take(r: &mut Words) -> Self {
            RobustAdaptiveParams {
                design: RobustAdaptiveDesign {
                    rotor_inertia: r.f64(),
                    ratio: r.f64(),
                    lambda: r.f64(),
                    integral_gain: r.f64(),
                    adaptation_gain: [r.f64(), r.f64(), r.f64(), r.f64()],
                    eps_r: r.f64(),
                    eps_velocity: r.f64(),
                    eps_f: [r.f64(), r.f64(), r.f64(), r.f64()],
                    uncertainty: UncertaintyBounds {
                        boundary_layer: r.f64(),
                        nonparametric_friction: r.f64(),
                        base_acceleration: r.f64(),
                        torque_estimate: r.f64(),
                    },
                    friction_bounds: FrictionBounds::take(r),
                    initial_friction: FrictionParams::take(r),
                    integral_limit: r.f64(),
                    torque_limit: r.f64(),
                    sample_period: r.f64(),
                },
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            let d = &self.design;
            for v in [d.rotor_inertia, d.ratio, d.lambda, d.integral_gain] {
                s.f64(v);
            }
            d.adaptation_gain.iter().for_each(|&v| s.f64(v));
            s.f64(d.eps_r);
            s.f64(d.eps_velocity);
            d.eps_f.iter().for_each(|&v| s.f64(v));
            let u = &d.uncertainty;
            for v in [
                u.boundary_layer,
                u.nonparametric_friction,
                u.base_acceleration,
                u.torque_estimate,
            ] {
                s.f64(v);
            }
            d.friction_bounds.put(s);
            d.initial_friction.put(s);
            for v in [d.integral_limit, d.torque_limit, d.sample_period] {
                s.f64(v);
            }
        }
    }

    /// `take`/`put` of a backend's configuration, with that backend's
    /// value readers and writers (`$val` one value, `$val4` four, `$vals`
    /// the writer of a slice).
    macro_rules! stored {
        ($t:ty, $val:ident, $val4:ident, $vals:ident) => {
            impl RobustAdaptiveConfig<$t> {
                pub(crate) const fn take(r: &mut Words) -> Self {
                    RobustAdaptiveConfig {
                        friction: FrictionConfig::<$t>::take(r),
                        accel_inertia: Coef::take(r),
                        lambda_inertia: Coef::take(r),
                        lambda: Gain::<$t>::take(r),
                        feedback: Gain::<$t>::take(r),
                        integral_step: Gain::<$t>::take(r),
                        robust_gain_value: [r.$val(), r.$val()],
                        eps_r: r.$val(),
                        robust_slope: Coef::take(r),
                        rho_param: Coef::take4(r),
                        eps_f: r.$val4(),
                        rho_slope: Coef::take4(r),
                        adapt: Coef::take4(r),
                        lower: r.$val4(),
                        upper: r.$val4(),
                        initial: r.$val4(),
                        integral_limit: r.$val(),
                        torque_limit: r.$val(),
                        params: RobustAdaptiveParams::take(r),
                    }
                }

                #[cfg(test)]
                pub(crate) fn put(&self, s: &mut Sink) {
                    self.friction.put(s);
                    self.accel_inertia.put(s);
                    self.lambda_inertia.put(s);
                    self.lambda.put(s);
                    self.feedback.put(s);
                    self.integral_step.put(s);
                    s.$vals(&self.robust_gain_value);
                    s.$val(self.eps_r);
                    self.robust_slope.put(s);
                    Coef::put_all(&self.rho_param, s);
                    s.$vals(&self.eps_f);
                    Coef::put_all(&self.rho_slope, s);
                    Coef::put_all(&self.adapt, s);
                    s.$vals(&self.lower);
                    s.$vals(&self.upper);
                    s.$vals(&self.initial);
                    s.$val(self.integral_limit);
                    s.$val(self.torque_limit);
                    self.params.put(s);
                }
            }
        };
    }
    stored!(I16F16, fixed, fixed4, fixeds);
    stored!(f32, f32, f32x4, f32s);
}

#[cfg(test)]
mod tests;
