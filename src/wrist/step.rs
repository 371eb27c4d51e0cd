//! One wrist, wired once: F/T gauge signals → interaction torques
//! `(τ_δ, τ_γ)` (eq. 6.35, 6.3) → active ↔ passive mode manager in task
//! space ([`super::modes`], admittance law eq. 6.28–6.33) → inverse
//! kinematics of the task reference (eq. 5.13–5.15) → the robust adaptive
//! law of both motors (eq. 6.12–6.15) in one [`WristStepConfig::update`]
//! per servo tick.
//!
//! The component has the crate's shape: [`WristStepParams`] (SI, validated
//! by [`WristStepParams::try_new`] from named [`WristStepSettings`], or the
//! [`WristStepParams::table_6_1`] preset) → [`WristStepConfig<S>`]
//! (quantized once for backend `S`) → [`WristStepState<S>`] →
//! `update(&self, &mut state, &readings, &target)` → [`WristOutput<S>`].
//! The step never panics, never allocates and never returns NaN.
//!
//! # The step, in order
//! 1. **Sensing.** The six gauge signals `SG` (V) give the interaction
//!    torques `τ = (τ_δ, τ_γ)` of eq. (6.35) and (6.3) (corrected, errata
//!    E6.1). Eq. (6.3) uses three combinations of the wrench's rows only,
//!    `m_x = τ_x − l F_y`, `m_y = τ_y + l F_x` and `τ_z`: the step combines
//!    those rows of the decoupling matrix once, at configuration (18
//!    products per tick instead of 36). Eq. (6.3) needs the yaw `γ`: the
//!    step uses the pose of the previous tick's reference as reached
//!    through the inverse kinematics (the wrist tracks it within the
//!    position loop's error `e_γ`, which rotates the `(m_x, τ_z)` part of
//!    `τ_δ` by `e_γ`: a relative error below `|e_γ|`). This saves the
//!    forward kinematics (eq. 5.8–5.12) on every tick.
//! 2. **Mode manager** ([`WristModeConfig`]): in Active mode the reference
//!    follows the target (with a bumpless offset that decays after a
//!    switch); in Passive mode the admittance law integrates the reference
//!    from `τ` (eq. 6.32). Switching: by `τ` and the reference's rest
//!    (automatic) or by [`WristTarget::request`].
//! 3. **Inverse kinematics** of the task reference `x_r = (δ_r, γ_r)` to the
//!    motor references `(θ1_r, θ3_r)`: the map of
//!    [`WristConfig::inverse`] (eq. 5.13–5.14, same branch, same
//!    projection) written in vector form so that its sines and cosines are
//!    shared with steps 5 and 1 (two `atan2`, no half-angle sines; see
//!    `ik` in the source; `tests::vector_inverse_kinematics_matches_the_library_inverse`
//!    compares the two on every backend), then made continuous in time
//!    like [`IkState`](super::kinematics::IkState): of the two roots of
//!    eq. (5.13) (`θ4 ≥ 0` and `θ4 ≤ 0`, the two motor positions of a
//!    pose) the one whose `θ1` is nearer the previous `θ1_r` (the sign of
//!    two products, [`super::kinematics`] "Two roots"), and each motor
//!    moves by the multiple of `2π` nearest its previous value. A path
//!    through the straight pose reverses the direction of the bend: the
//!    root `θ4 ≥ 0` alone would turn both motor references by about `π`
//!    in one tick there, while the nearer root carries them on
//!    continuously (`tests::motor_references_are_continuous_through_the_straight_pose`).
//!    The first tick after [`WristStepConfig::state`] takes the root of
//!    the measured motors it starts from. A reference outside the
//!    reachable cone (bend above `2φ`; the mode manager's box
//!    `|δ|, |γ| ≤ 30°` contains poses bent up to 42°) is projected onto its
//!    boundary along its azimuth and flagged
//!    ([`WristOutput::reference_saturated`]).
//! 4. **Motor reference rates by difference**, not by the Jacobian:
//!    `θ̇_r[k] = (θ_r[k] − θ_r[k−1])/T` and
//!    `θ̈_r[k] = (θ̇_r[k] − θ̇_r[k−1])/T`. The inverse Jacobian is singular
//!    at the straight pose and on the boundary (see [`super::jacobian`]);
//!    the difference is bounded everywhere, costs two subtractions, and
//!    lags the exact rate by half a tick. Near the straight pose the motor
//!    angles turn fast for a small pose motion that passes beside it (the
//!    direction of the bend is undefined there): such a target gives large
//!    reference rates (up to `π/2` in a tick, where the choice of root
//!    halves the turn), and on `I16F16` the stored acceleration saturates
//!    at ±32 768 rad/s². A target straight through it does not (step 3).
//! 5. **Force mapping**, eq. (6.1): the load torque of each motor law,
//!    `τ_t = −Jᵀ τ` (the torque the joint applies to the environment
//!    side, the ch. 4 sign of eq. 4.1/6.4; `τ` is the environment's torque
//!    on the wrist), with the exact Jacobian of [`super::jacobian`]
//!    evaluated at the reference (`θ1_r` and the pose reached, whose sines
//!    and cosines step 3 computed: no forward kinematics). Motor 2 drives
//!    `θ3` through the inner universal joint (eq. 5.1–5.3), so the load on
//!    its shaft is not the `θ3` component of `−Jᵀτ` but, by virtual work,
//!    that component times `dθ3/dθ2 = (cos²θ3 + cos²β sin²θ3)/cos β`
//!    (eq. 5.3, `β` the bend, `cos β = cos δ cos γ`), a factor in
//!    `[cos 2φ, 1/cos 2φ]` = `[0.848, 1.179]` for `φ = 16°`; eq. (6.1)
//!    applies the `θ3` torque of eq. (5.28) to motor 2 unchanged (errata
//!    E6.6). The step feeds motor 2's law the shaft torque. As in eq.
//!    (5.1)–(5.3), the inner joint is taken at the wrist's bend `β` with
//!    `θ3` as its angle, and the change of `β` along a motion is not
//!    modelled. Motor 2's law still tracks in `θ3`, the coordinate the
//!    readings give: its speed differs from the shaft's by the same factor,
//!    which its robust and adaptive terms absorb (not compensated here).
//! 6. **Both motor laws** ([`WristActiveConfig`], eq. 6.12–6.15) on the
//!    joint coordinates `(θ1, θ3)`: reference, rates, measured position and
//!    speed, and `τ_t`.
//!
//! # Sign conventions, handled here once
//! * Angles: `θ1` about the base `z` axis, `θ3` about the output `z` axis
//!   ([`MotorAngles`]), both in rad at the gear output, zero at the
//!   thesis's initial status; `δ` about the base `y` axis, `γ` about the
//!   pitched `x` axis ([`PitchYaw`]). A firmware whose second encoder
//!   reads the motor-2 shaft angle `θ2` converts it to `θ3` through the
//!   universal joint of eq. (5.1) ([`super::ujoint`]) before the step.
//! * Torques: [`WristOutput::motor_torque`] is positive driving its joint
//!   coordinate forward (`θ1`, `θ3` increasing; for motor 2 the torque of
//!   its shaft `θ2`, which turns the same way as `θ3`);
//!   [`WristOutput::interaction`] is the environment's torque on the wrist,
//!   positive tending to increase `δ` (`γ`) (eq. 6.3 as corrected);
//!   [`WristOutput::joint_torque`] is `τ_t = −Jᵀ·interaction` with its
//!   second component carried to motor 2's shaft by eq. (5.3).
//!
//! # Units
//! [`WristReadings`] and [`WristTarget`] hold stored values: gauge signals
//! in V, angles in rad, speeds in rad/s on every backend (`S::UNITS` scales
//! them by 1; the `from_si` constructors apply the scales anyway). The
//! motor torques are in stored motor-torque units (N·m on floats, mN·m on
//! `I16F16`), the interaction and joint torques in stored link-torque units
//! (N·m); the `*_si` readers give SI on every backend.
//!
//! # Example
//! The Table 6.1 wrist held at a pose; then a 2 N·m push about the yaw
//! axis (a pure torque `τ_y = −2 N·m` at the sensor, eq. 6.3) switches it
//! to the passive mode, where the reference yields in `+γ` at
//! `K_c τ = 0.1·2 = 0.2 rad/s` (eq. 6.32).
//!
//! ```
//! use mrr_control::wrist::{PitchYaw, WristConfig, WristMode, WristParams};
//! use mrr_control::wrist::step::{WristReadings, WristStepConfig, WristStepParams, WristTarget};
//! let p = WristStepParams::table_6_1()?;
//! let cfg = WristStepConfig::<f64>::new(&p);
//! // Start at rest where the pose (0.2, −0.1) rad is reached.
//! let pose = PitchYaw { delta: 0.2, gamma: -0.1 };
//! let motors = WristConfig::<f64>::new(&WristParams::thesis()).inverse(pose).motors;
//! let mut st = cfg.state(motors);
//! let hold = WristTarget::from_si(0.2, -0.1, 0.0, 0.0);
//! let still = WristReadings::from_si([0.0; 6], [motors.theta1, motors.theta3], [0.0; 2]);
//! let out = cfg.update(&mut st, &still, &hold);
//! assert_eq!(out.mode, WristMode::Active);
//! assert!(out.motor_torque_si()[0].abs() < 1e-9 && !out.saturated && !out.invalid_input);
//! // A 2 N·m push about the yaw axis, as the gauges read it.
//! let sg = p.settings().sensor.decoupling().gauge_signals(&[0.0, 0.0, 0.0, 0.0, -2.0, 0.0]);
//! let pushed = WristReadings::from_si(sg, [motors.theta1, motors.theta3], [0.0; 2]);
//! let (mut last, mut passive_ticks) = (out, 0);
//! for _ in 0..60 {
//!     last = cfg.update(&mut st, &pushed, &hold);
//!     passive_ticks += (last.mode == WristMode::Passive) as u32;
//! }
//! assert!((last.interaction_si()[1] - 2.0).abs() < 1e-6);
//! assert_eq!(last.mode, WristMode::Passive); // after the 50-tick dwell
//! // The reference yielded by T·K_c·τ = 8e-4 rad per passive tick.
//! let yielded = last.reference_si()[1] + 0.1;
//! assert!((yielded - 8e-4 * passive_ticks as f64).abs() < 1e-4, "{yielded}");
//! # Ok::<(), mrr_control::ParamError>(())
//! ```

// Two-element arrays indexed in parallel (axes): index loops read better
// than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use super::active::{WristActiveConfig, WristActiveParams, WristActiveState, WristJointSample};
use super::admittance::{AdmittanceParams, AdmittanceSettings};
use super::ft_sensor::{DecouplingMatrix, FtSensorConfig, FtSensorParams};
use super::jacobian::DET_MIN;
use super::kinematics::{denan, wrap, MotorAngles, PitchYaw, WristConfig, WristParams};
use super::modes::{
    WristMode, WristModeConfig, WristModeInput, WristModeParams, WristModeSettings, WristModeState,
};
use crate::control::ActiveOutput;
use crate::error::ParamError;
use crate::scalar::units::{dequantize, quantize_keep_non_finite};
use crate::scalar::{Coef, CoefRow, Scalar};

/// The settings of a wrist by name, for [`WristStepParams::try_new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristStepSettings {
    /// The DAUJ kinematics (the inclination `φ`).
    pub kinematics: WristParams,
    /// The F/T sensor: decoupling matrix (eq. 6.35) and offset `l`
    /// (eq. 6.3).
    pub sensor: FtSensorParams,
    /// The robust adaptive laws of both motors (eq. 6.12–6.15); their
    /// sample period is the wrist's tick `T`.
    pub active: WristActiveParams,
    /// The mode manager and its admittance law (eq. 6.28–6.33); the
    /// admittance law's sample period must be `T`.
    pub modes: WristModeParams,
    /// The mode a new state starts in.
    pub initial_mode: WristMode,
}

/// Parameters of one wrist, SI; built only by [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristStepParams {
    settings: WristStepSettings,
}

impl WristStepParams {
    /// Validate: the admittance law's sample period equals the motor laws'
    /// (`ParamError::OutOfRange` named `modes.admittance.sample_period`,
    /// with the motor laws' period as both bounds). The parts were
    /// validated by their own `try_new`.
    pub fn try_new(settings: WristStepSettings) -> Result<Self, ParamError> {
        let t = settings.active.laws()[0].design().sample_period;
        let ta = settings.modes.admittance().sample_period();
        if ta != t {
            return Err(ParamError::OutOfRange {
                name: "modes.admittance.sample_period",
                value: ta,
                min: t,
                max: t,
            });
        }
        Ok(WristStepParams { settings })
    }

    /// The Table 6.1 wrist: `φ = 16°` ([`WristParams::thesis`]); both
    /// motors by Table 6.1 ([`WristActiveParams::table_6_1`], `T = 4 ms`);
    /// the thesis's passive mode, `K_c = 0.1 rad/(s·N·m)` on the ±30°
    /// workspace (§6.4.3, [`AdmittanceParams::thesis`]) validated for
    /// environments up to 1000 N·m/rad; starts Active.
    ///
    /// Not printed in the thesis, and documented defaults here: the sensor
    /// calibration ([`DecouplingMatrix::example`], **replace it with your
    /// sensor's certificate**) at `l = 0.05 m`; the switching rule — enter
    /// Passive above 1 N·m, leave below 0.5 N·m with the reference at rest
    /// (below 0.01 rad/s), debounce 5 ticks (20 ms), dwell 50 ticks
    /// (200 ms) in a mode before an automatic switch, bumpless rejoin at
    /// 5 rad/s.
    pub fn table_6_1() -> Result<Self, ParamError> {
        let l = 30f64.to_radians();
        let admittance = AdmittanceParams::try_new(AdmittanceSettings {
            gain: [0.1, 0.1],
            stiffness: 1000.0,
            sample_period: 0.004,
            lag_samples: 1,
            limits: [l, l],
            max_rate: 1.0,
            deadband: 0.0,
            desired_torque: [0.0; 2],
        })?;
        Self::try_new(WristStepSettings {
            kinematics: WristParams::thesis(),
            sensor: FtSensorParams::try_new(DecouplingMatrix::example(), 0.05)?,
            active: WristActiveParams::table_6_1()?,
            modes: WristModeParams::try_new(WristModeSettings {
                admittance,
                enter_passive: 1.0,
                exit_passive: 0.5,
                rest_speed: 0.01,
                debounce: 5,
                dwell: 50,
                rejoin_bandwidth: 5.0,
            })?,
            initial_mode: WristMode::Active,
        })
    }

    /// The settings, by name.
    pub fn settings(&self) -> WristStepSettings {
        self.settings
    }

    /// The tick `T`, s.
    pub fn sample_period(&self) -> f64 {
        self.settings.active.laws()[0].design().sample_period
    }
}

/// The wrist quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristStepConfig<S> {
    kinematics: WristConfig<S>,
    sensor: FtSensorConfig<S>,
    active: WristActiveConfig<S>,
    modes: WristModeConfig<S>,
    initial_mode: WristMode,
    /// The three rows of eq. (6.35) that eq. (6.3) needs, combined once:
    /// `M₃ − l M₁` (moment `m_x` about the wrist centre), `M₄ + l M₀`
    /// (`m_y`) and `M₅` (`τ_z`), in stored link-torque units per volt;
    /// on `I16F16` each row's six products are summed exactly and rounded
    /// once ([`Scalar::dot_coef`]).
    rows: [CoefRow<6>; 3],
    cos_phi: S,
    sin_2phi: S,
    cos_2phi: S,
    /// `tan 2φ` (below `tan 60°`).
    tan_2phi: S,
    /// `1/(2 sin φ)`.
    inv_2_sin_phi: Coef,
    /// `cos φ/(2 sin φ)`.
    cot_phi_half: Coef,
    sin_phi: S,
    /// Below this `sin β` the pose counts as straight.
    min_bend: S,
    det_min: S,
    /// `1/T`, stored angle → stored speed.
    inv_t: Coef,
    /// `1/T`, stored speed → stored speed per second.
    inv_t_rate: Coef,
}

/// The wrist's state: the mode manager's, the motor laws', the motor
/// references (continuous, and reduced to `(−π, π]`), the pose they reach
/// and the previous reference rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristStepState<S: Scalar> {
    modes: WristModeState<S>,
    laws: WristActiveState<S>,
    /// `(θ1_r, θ3_r)`, continuous (turns accumulated), stored angle units.
    theta: [S; 2],
    /// The same reduced to `(−π, π]`.
    reduced: [S; 2],
    /// The pose the last reference reached.
    pose: PitchYaw<S>,
    /// `(sin γ, cos γ)` of that pose, for eq. (6.3).
    yaw_sin_cos: (S, S),
    /// `(sin θ1_r, cos θ1_r)`, for the Jacobian at the straight pose.
    theta1_sin_cos: (S, S),
    /// `θ̇_r[k−1]`, stored speed units.
    rate: [S; 2],
}

impl<S: Scalar> WristStepState<S> {
    /// The current mode.
    pub fn mode(&self) -> WristMode {
        self.modes.mode()
    }
    /// The mode manager's state.
    pub fn mode_state(&self) -> &WristModeState<S> {
        &self.modes
    }
    /// The motor laws' state (integrals, adapted friction).
    pub fn law_state(&self) -> &WristActiveState<S> {
        &self.laws
    }
    /// The last motor references `(θ1_r, θ3_r)`, stored angle units.
    pub fn motor_reference(&self) -> MotorAngles<S> {
        MotorAngles {
            theta1: self.theta[0],
            theta3: self.theta[1],
        }
    }
    /// The pose the last reference reached, stored angle units.
    pub fn pose_reference(&self) -> PitchYaw<S> {
        self.pose
    }
}

/// The readings of one tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristReadings<S> {
    /// The six gauge signals `SG_i = V_out,i − V_ref,i` (V) of the F/T
    /// sensor (eq. 6.34), in the order of the decoupling matrix's columns.
    pub gauges: [S; 6],
    /// Measured joint coordinates `(θ1, θ3)`, stored angle units (rad),
    /// continuous (turns accumulated).
    pub motors: MotorAngles<S>,
    /// Measured `(θ̇1, θ̇3)`, stored speed units (rad/s).
    pub motor_velocity: [S; 2],
}

impl<S: Scalar> WristReadings<S> {
    /// Readings from SI values: gauge signals (V), `[θ1, θ3]` (rad),
    /// `[θ̇1, θ̇3]` (rad/s). A NaN or infinity stays one on floats (the step
    /// then flags it); fixed point saturates it.
    pub fn from_si(gauges: [f64; 6], motors: [f64; 2], motor_velocity: [f64; 2]) -> Self {
        let u = S::UNITS;
        let mut g = [S::ZERO; 6];
        for i in 0..6 {
            g[i] = quantize_keep_non_finite(gauges[i], 1.0);
        }
        WristReadings {
            gauges: g,
            motors: MotorAngles {
                theta1: quantize_keep_non_finite(motors[0], u.angle),
                theta3: quantize_keep_non_finite(motors[1], u.angle),
            },
            motor_velocity: [
                quantize_keep_non_finite(motor_velocity[0], u.speed),
                quantize_keep_non_finite(motor_velocity[1], u.speed),
            ],
        }
    }
}

/// What the wrist should do on this tick, in task space.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WristTarget<S> {
    /// Desired pose `(δ_d, γ_d)`, stored angle units (rad); followed in
    /// Active mode.
    pub pose: PitchYaw<S>,
    /// Desired `[δ̇_d, γ̇_d]`, stored speed units (rad/s).
    pub rate: [S; 2],
    /// A mode to switch to now (`None`: the automatic rule).
    pub request: Option<WristMode>,
}

impl<S: Scalar> WristTarget<S> {
    /// A target from SI values (rad, rad/s), no mode request. A NaN or
    /// infinity stays one on floats (the step then flags it); fixed point
    /// saturates it.
    pub fn from_si(delta: f64, gamma: f64, delta_rate: f64, gamma_rate: f64) -> Self {
        let u = S::UNITS;
        WristTarget {
            pose: PitchYaw {
                delta: quantize_keep_non_finite(delta, u.angle),
                gamma: quantize_keep_non_finite(gamma, u.angle),
            },
            rate: [
                quantize_keep_non_finite(delta_rate, u.speed),
                quantize_keep_non_finite(gamma_rate, u.speed),
            ],
            request: None,
        }
    }

    /// This target with a mode request.
    pub fn with_request(mut self, mode: WristMode) -> Self {
        self.request = Some(mode);
        self
    }
}

/// One tick of the wrist. Every field is finite on every backend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristOutput<S> {
    /// Motor torque commands `[τ1, τ3]`, stored motor-torque units,
    /// positive driving `θ1` (`θ3`) forward, within each law's limit.
    pub motor_torque: [S; 2],
    /// The mode that produced them.
    pub mode: WristMode,
    /// The mode changed on this tick.
    pub switched: bool,
    /// `[τ_δ, τ_γ]` (eq. 6.3), the environment's torque on the wrist,
    /// stored link-torque units, positive tending to increase `δ` (`γ`);
    /// 0 when the sensor reading was invalid.
    pub interaction: [S; 2],
    /// `[τ_t1, τ_t2]` fed to each motor law (eq. 6.1, ch. 4 sign), stored
    /// link-torque units: `τ_t1 = (−Jᵀ·interaction)_1` and, for motor 2,
    /// which drives `θ3` through the inner universal joint,
    /// `τ_t2 = (−Jᵀ·interaction)_3 · dθ3/dθ2` (eq. 5.3; errata E6.6);
    /// 0 when the sensor reading was
    /// invalid or, on floats, when this product overflows (flagged
    /// [`invalid_input`](Self::invalid_input)).
    pub joint_torque: [S; 2],
    /// The task reference reached, `(δ_r, γ_r)`, stored angle units:
    /// the mode manager's, projected onto the reachable cone when
    /// `reference_saturated`.
    pub reference: PitchYaw<S>,
    /// The motor references `(θ1_r, θ3_r)`, stored angle units.
    pub motor_reference: MotorAngles<S>,
    /// `[θ̇1_r, θ̇3_r]` by difference (module docs), stored speed units.
    pub motor_reference_rate: [S; 2],
    /// `reference_saturated || torque_saturated`: something valid was
    /// limited; never set by an invalid sample alone (the flags are shared
    /// with the joint: [status flags](crate::joint#status-flags)).
    pub saturated: bool,
    /// The task reference was limited: by the mode manager (workspace box,
    /// admittance rate limit) or by the inverse kinematics (outside the
    /// reachable cone, projected).
    pub reference_saturated: bool,
    /// A motor law's valid value was limited to its torque limit:
    /// `laws[i].saturated && !laws[i].invalid_input` for either motor. An
    /// invalid sample never sets it (the law's own `saturated` is set then:
    /// [status flags](crate::joint#status-flags); the joint's equivalent
    /// is [`JointOutput::torque_saturated`](crate::joint::JointOutput::torque_saturated)).
    pub torque_saturated: bool,
    /// The Jacobian at the reference is singular (`|det J| < DET_MIN`,
    /// near the straight pose or the boundary); the mapping stays bounded.
    pub singular: bool,
    /// The sample could not be used in full ([status
    /// flags](crate::joint#status-flags)). An input was NaN or infinite: a
    /// gauge signal (the interaction reads
    /// 0), the target (the reference holds), or a measured position or
    /// speed (that motor's torque is 0 and its law's state is kept). On
    /// floats, finite readings so large that a product overflows (a
    /// wrench beyond the float range or whose joint torque `−Jᵀτ` is, or
    /// a motor law whose value turns
    /// NaN — e.g. a speed above about `1.8e19` rad/s on `f32`, whose square
    /// overflows) are flagged and handled the same way: the safe reaction
    /// to an encoder or gauge fault.
    pub invalid_input: bool,
    /// The two motor laws' outputs.
    pub laws: [ActiveOutput<S>; 2],
}

impl<S: Scalar> WristOutput<S> {
    /// [`motor_torque`](Self::motor_torque) in N·m.
    pub fn motor_torque_si(&self) -> [f64; 2] {
        let u = S::UNITS.motor_torque;
        [
            dequantize(self.motor_torque[0], u),
            dequantize(self.motor_torque[1], u),
        ]
    }
    /// [`interaction`](Self::interaction) `[τ_δ, τ_γ]` in N·m.
    pub fn interaction_si(&self) -> [f64; 2] {
        let u = S::UNITS.link_torque;
        [
            dequantize(self.interaction[0], u),
            dequantize(self.interaction[1], u),
        ]
    }
    /// [`joint_torque`](Self::joint_torque) in N·m.
    pub fn joint_torque_si(&self) -> [f64; 2] {
        let u = S::UNITS.link_torque;
        [
            dequantize(self.joint_torque[0], u),
            dequantize(self.joint_torque[1], u),
        ]
    }
    /// [`reference`](Self::reference) `[δ_r, γ_r]` in rad.
    pub fn reference_si(&self) -> [f64; 2] {
        let u = S::UNITS.angle;
        [
            dequantize(self.reference.delta, u),
            dequantize(self.reference.gamma, u),
        ]
    }
    /// [`motor_reference`](Self::motor_reference) `[θ1_r, θ3_r]` in rad.
    pub fn motor_reference_si(&self) -> [f64; 2] {
        let u = S::UNITS.angle;
        [
            dequantize(self.motor_reference.theta1, u),
            dequantize(self.motor_reference.theta3, u),
        ]
    }
    /// [`motor_reference_rate`](Self::motor_reference_rate) in rad/s.
    pub fn motor_reference_rate_si(&self) -> [f64; 2] {
        let u = S::UNITS.speed;
        [
            dequantize(self.motor_reference_rate[0], u),
            dequantize(self.motor_reference_rate[1], u),
        ]
    }
}

/// The inverse kinematics of one reference, with the trigonometric values
/// the rest of the step reuses.
struct Ik<S> {
    /// The pose reached (the reference, or its projection).
    pose: PitchYaw<S>,
    sd: S,
    cd: S,
    sg: S,
    cg: S,
    /// `θ1`, `θ3` reduced to `(−π, π]` and `(sin θ1, cos θ1)` on the root
    /// taken; `None` at the straight pose.
    reduced: Option<([S; 2], (S, S))>,
    saturated: bool,
    /// `dθ3/dθ2` of the inner universal joint at this pose, eq. (5.3):
    /// `(cos²θ3 + cos²β sin²θ3)/cos β`, in `[cos 2φ, 1/cos 2φ]`.
    transmission: S,
}

impl<S: Scalar> WristStepConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &WristStepParams) -> Self {
        let s = &p.settings;
        let u = S::UNITS;
        let t = p.sample_period();
        let phi = s.kinematics.phi();
        let m = s.sensor.decoupling().matrix();
        let l = s.sensor.offset();
        let mut rows = [[0.0; 6]; 3];
        for j in 0..6 {
            rows[0][j] = (m[3][j] - l * m[1][j]) * u.link_torque;
            rows[1][j] = (m[4][j] + l * m[0][j]) * u.link_torque;
            rows[2][j] = m[5][j] * u.link_torque;
        }
        let rows = rows.map(CoefRow::new);
        let sin_phi = libm::sin(phi);
        WristStepConfig {
            kinematics: WristConfig::new(&s.kinematics),
            sensor: FtSensorConfig::new(&s.sensor),
            active: WristActiveConfig::new(&s.active),
            modes: WristModeConfig::new(&s.modes),
            initial_mode: s.initial_mode,
            rows,
            cos_phi: S::from_f64(libm::cos(phi)),
            sin_2phi: S::from_f64(libm::sin(2.0 * phi)),
            cos_2phi: S::from_f64(libm::cos(2.0 * phi)),
            tan_2phi: S::from_f64(libm::tan(2.0 * phi)),
            inv_2_sin_phi: Coef::new(0.5 / sin_phi),
            cot_phi_half: Coef::new(0.5 * libm::cos(phi) / sin_phi),
            sin_phi: S::from_f64(sin_phi),
            min_bend: S::from_f64((64.0 * S::RESOLUTION.to_f64()).max(1e-6)),
            det_min: S::from_f64(DET_MIN),
            inv_t: Coef::new(u.speed / (t * u.angle)),
            inv_t_rate: Coef::new(1.0 / t),
        }
    }

    /// The kinematics.
    pub fn kinematics(&self) -> &WristConfig<S> {
        &self.kinematics
    }
    /// The F/T sensing chain (the step evaluates the same map with its
    /// rows combined once, module docs).
    pub fn sensor(&self) -> &FtSensorConfig<S> {
        &self.sensor
    }
    /// The two motor laws.
    pub fn active(&self) -> &WristActiveConfig<S> {
        &self.active
    }
    /// The mode manager.
    pub fn modes(&self) -> &WristModeConfig<S> {
        &self.modes
    }

    /// A state for a wrist at rest at the measured joint coordinates
    /// `motors` (rad): the reference starts at the pose they reach (forward
    /// kinematics, once), the motor references at `motors` (the inverse
    /// kinematics of that pose on the root nearest them, unwrapped to
    /// them), in the settings'
    /// initial mode, every rate 0.
    pub fn state(&self, motors: MotorAngles<S>) -> WristStepState<S> {
        let pose = self.kinematics.forward(motors).pose;
        let m = [denan(motors.theta1), denan(motors.theta3)];
        let reduce = |x: S| {
            let (s, c) = x.sin_cos();
            s.atan2(c)
        };
        let mut st = WristStepState {
            modes: self
                .modes
                .initial_state(self.initial_mode, [pose.delta, pose.gamma]),
            laws: self.active.initial_state(),
            theta: m,
            reduced: [reduce(m[0]), reduce(m[1])],
            pose,
            yaw_sin_cos: pose.gamma.sin_cos(),
            theta1_sin_cos: m[0].sin_cos(),
            rate: [S::ZERO; 2],
        };
        let ik = self.ik(pose, Some(st.theta1_sin_cos));
        self.advance(&mut st, &ik);
        st.rate = [S::ZERO; 2];
        st
    }

    /// Eq. (6.35) and (6.3) on the combined rows, at the stored yaw.
    /// `None` when an input or the result is NaN or infinite.
    #[inline]
    fn interaction(&self, gauges: &[S; 6], (s, c): (S, S)) -> Option<[S; 2]> {
        let m = [
            S::dot_coef(gauges, &self.rows[0]),
            S::dot_coef(gauges, &self.rows[1]),
            S::dot_coef(gauges, &self.rows[2]),
        ];
        let tau = [
            m[0].mul_unit_range(c).sub(m[2].mul_unit_range(s)),
            m[1].neg(),
        ];
        // `v − v` is 0 for a finite value and NaN for NaN and ±∞.
        let d = |v: S| v.sub(v);
        let mut probe = d(tau[0]).add(d(tau[1]));
        for g in gauges.iter() {
            probe = probe.add(d(*g));
        }
        if probe != S::ZERO {
            None
        } else {
            Some(tau)
        }
    }

    /// The inverse kinematics of eq. (5.13)–(5.14) in vector form (module
    /// docs of [`super::kinematics`]): with `A = (cγ sδ, −sγ)` (the output
    /// axis's azimuth), `B = (sδ, cδ sγ)` and `P = (cos(θ4/2),
    /// cos φ sin(θ4/2))` (so `ψ = arg P`), `θ1 = arg(−A·P̄)` and
    /// `θ3 = arg(−B·P̄)`. The bend enters through `cos β = cδ cγ` only:
    /// `sin(θ4/2) = sin β /(2 sin φ cos(β/2))` with `sin β = |A|` and
    /// `cos(β/2) = √((1 + cos β)/2)`, and
    /// `cos(θ4/2) = √((cos β − cos 2φ)/2) / sin φ`, free of cancellation
    /// at the straight pose. A pose with `cos β < cos 2φ` is projected
    /// along its azimuth onto the cone `β = 2φ` (as
    /// [`WristConfig::inverse`] does).
    ///
    /// Evaluated with as few roots and quotients as the arithmetic allows
    /// (inside the cone `|A|` by [`Scalar::hypot_unit`], then one root,
    /// `P` scaled by `cos(β/2)`, and `(sin θ1, cos θ1)` as the unit vector
    /// of `V1` ([`Scalar::unit_vector`]); beyond it `U = A/|A|` by
    /// [`Scalar::unit_vector`], `1/cos γ_b` by [`Scalar::rsqrt_quarter`],
    /// and the projected pose's angles from their tangents by
    /// [`Scalar::atan_small`]; on `I16F16` none of these divides or takes
    /// a root; see the comments): the same map
    /// in exact arithmetic, and on `I16F16` and `f32` the same map up to
    /// rounding. Bound, checked by
    /// `tests::vector_inverse_kinematics_matches_the_library_inverse` on a
    /// 121 × 121 grid: motor angles, `(sin θ1, cos θ1)` and the projected
    /// pose within `2e-5` (`f32`) and `5e-3` (`I16F16`, dominated by bends
    /// of a few resolution steps) of [`WristConfig::inverse`].
    ///
    /// The root: with `prev_theta1 = (sin θ1_r, cos θ1_r)` of the previous
    /// reference, the root whose `θ1` is nearer `θ1_r` (`θ4 ≤ 0` when
    /// `A·(cos θ1_r, sin θ1_r) > 0`; module docs of
    /// [`super::kinematics`]), by negating `P`'s first component; without
    /// one, `θ4 ≥ 0` (as [`WristConfig::inverse`]). On the cone both roots
    /// are `θ4 = ±π` (`P = (0, cos φ)`): nothing to choose.
    #[inline(always)]
    fn ik(&self, r: PitchYaw<S>, prev_theta1: Option<(S, S)>) -> Ik<S> {
        // Fixed point (folded at compile time): through the binary angle,
        // a table lookup instead of a reduction modulo π/2 and polynomials
        // (the same 1-LSB bound: `Scalar::to_turn`).
        let sin_cos = |a: S| {
            if !S::FLOAT {
                S::sin_cos_turn(a.to_turn())
            } else {
                a.sin_cos()
            }
        };
        let (mut sd, mut cd) = sin_cos(r.delta);
        let (mut sg, mut cg) = sin_cos(r.gamma);
        let (ax, ay) = (sd.mul_unit_range(cg), sg.neg());
        let cb = cd.mul_unit_range(cg);
        let saturated = cb < self.cos_2phi;
        let mut pose = r;
        // dθ3/dθ2 of eq. (5.3); 1 at the straight pose (cos β = 1).
        let mut transmission = S::ONE;
        // −X·P̄ = (−(x px + y py), x py − y px) for X = (x, y).
        let rot = |x: S, y: S, px: S, py: S| {
            (
                px.mul_unit_range(x).add(py.mul_unit_range(y)).neg(),
                py.mul_unit_range(x).sub(px.mul_unit_range(y)),
            )
        };
        let reduced = if saturated {
            // The boundary pose of the same azimuth: z = (sin 2φ·U, cos 2φ)
            // with U = A/|A|; there θ4 = π, P = (0, cos φ), and its yaw
            // γ_b has cos γ_b = w/|A| with w = √(A_x² + cos²2φ·A_y²), so
            // cos²γ_b = 1 − sin²2φ·u_y² ∈ [cos²2φ, 1] ⊂ [¼, 1] (φ ≤ 30°):
            // 1/cos γ_b from `rsqrt_quarter`, and cos γ_b = cos²γ_b/cos γ_b.
            let ay_c = ay.mul_unit_range(self.cos_2phi);
            // θ1 = arg A + π/2, θ3 = arg B + π/2 with B ∝ (U_x, cos 2φ·U_y)
            // (B = (sd, cd·sg) scaled by cos γ_b/sin 2φ),
            // (cos θ1, sin θ1) = (−u_y, u_x). At A = 0: θ1 = θ3 =
            // atan2(1, 0), U = (1, 0).
            let (ux, uy, inv_cg, tan_g, theta) = match ax.unit_vector(ay) {
                Some((ux, uy)) => {
                    let theta = [ax.atan2(ay.neg()), ax.atan2(ay_c)];
                    let s_uy = uy.mul_unit_range(self.sin_2phi);
                    let cg2 = S::ONE.sub(s_uy.mul_unit_range(s_uy));
                    let inv_cg = cg2.rsqrt_quarter();
                    cg = inv_cg.mul_unit_range(cg2);
                    // The boundary pose's yaw from its tangent:
                    // tan γ_b = s_γ/c_γ = −sin 2φ·u_y/cos γ_b.
                    (ux, uy, inv_cg, inv_cg.mul_unit_range(s_uy).neg(), theta)
                }
                None => {
                    cg = S::ONE;
                    (S::ONE, S::ZERO, S::ONE, S::ZERO, [S::ONE.atan2(S::ZERO); 2])
                }
            };
            let (bx, by) = (
                ux.mul_unit_range(self.sin_2phi),
                uy.mul_unit_range(self.sin_2phi),
            );
            // Eq. (5.3) on the cone (cos β = cos 2φ): (sin θ3, cos θ3) ∝
            // (u_x, cos 2φ·u_y), so 1 − sin²β sin²θ3 = cos²2φ/w with
            // w = u_x² + cos²2φ·u_y², and dθ3/dθ2 = cos 2φ/w.
            let uy_c = uy.mul_unit_range(self.cos_2phi);
            transmission = self
                .cos_2phi
                .div(ux.mul_unit_range(ux).add(uy_c.mul_unit_range(uy_c)));
            sg = by.neg();
            sd = inv_cg.mul_unit_range(bx);
            cd = inv_cg.mul_unit_range(self.cos_2phi);
            pose = PitchYaw {
                // tan δ_b = b_x / cos 2φ = u_x tan 2φ. Both tangents are at
                // most tan 2φ < 2 in magnitude (2φ ≤ 60°): `atan_small`,
                // no quotient.
                delta: self.tan_2phi.mul_unit_range(ux).atan_small(),
                gamma: tan_g.atan_small(),
            };
            Some((theta, (ux, uy.neg())))
        } else {
            // sin β = |A| (components within [−1, 1]).
            let n = ax.hypot_unit(ay);
            if n < self.min_bend {
                None
            } else {
                // cos(β/2) = √((1 + cos β)/2); sin(θ4/2) = sin β/(2 sin φ cos(β/2));
                // cos(θ4/2) = √((cos β − cos 2φ)/2)/sin φ. The arguments θ1, θ3
                // do not change when P is scaled by a positive factor: the step
                // uses P' = P·cos(β/2) = (√((1 + cos β)(cos β − cos 2φ)),
                // sin β cos φ)/(2 sin φ), of modulus cos²(β/2) = (1 + cos β)/2,
                // which needs one square root and no quotient.
                let one_cb = S::ONE.add(cb);
                let px = one_cb
                    .mul_unit_range(cb.sub(self.cos_2phi).max(S::ZERO))
                    .sqrt_small()
                    .mul_coef(&self.inv_2_sin_phi);
                let py = n.mul_coef(&self.cot_phi_half);
                // The branch: the root cos(θ4/2) ≤ 0 of eq. (5.13) is P
                // with px negated (θ1 = arg A + ψ instead of arg A + π − ψ,
                // mirror images about arg A ± π/2), so the θ1 nearer the
                // previous θ1_r is that root's exactly when
                // A·(cos θ1_r, sin θ1_r) > 0. Without a previous
                // reference, θ4 ≥ 0.
                let px = match prev_theta1 {
                    Some((s1, c1)) if ax.dot_direction_positive(c1, ay, s1) => px.neg(),
                    _ => px,
                };
                let v1 = rot(ax, ay, px, py);
                let v3 = rot(sd, cd.mul_unit_range(sg), px, py);
                // (sin θ1, cos θ1) = V1/|V1| (|V1| = |A|·|P'| = sin β (1 +
                // cos β)/2 ≤ 1), normalized by its own computed length;
                // (0, 1) with atan2(0, 0) = 0 should both round to 0.
                let s1c1 = v1.1.unit_vector(v1.0).unwrap_or((S::ZERO, S::ONE));
                // Eq. (5.3), dθ3/dθ2 = (1 − sin²β sin²θ3)/cos β. |V3| =
                // |B|·|P'| with |B| = sin β and |P'| = (1 + cos β)/2, so
                // sin β sin θ3 = 2 V3_y/(1 + cos β) and
                // dθ3/dθ2 = ((1 + cos β)² − 4 V3_y²)/((1 + cos β)² cos β):
                // one quotient, no root.
                let q2 = one_cb.mul(one_cb);
                let y2 = v3.1.add(v3.1);
                transmission = q2.sub(y2.mul(y2)).div(q2.mul_unit_range(cb));
                Some(([v1.1.atan2(v1.0), v3.1.atan2(v3.0)], s1c1))
            }
        };
        Ik {
            pose,
            sd,
            cd,
            sg,
            cg,
            reduced,
            saturated,
            transmission,
        }
    }

    /// Move the motor references to the inverse kinematics `ik` (on the
    /// root `ik` took, nearest the previous `θ1_r`), each by
    /// the multiple of `2π` nearest its previous value (at the straight
    /// pose `θ1` stays and `θ3 → −θ1`, as [`IkState`](super::kinematics::IkState) does); returns the
    /// steps `Δθ` (stored angle units) and `(sin θ1, cos θ1)`.
    #[inline]
    fn advance(&self, st: &mut WristStepState<S>, ik: &Ik<S>) -> ([S; 2], (S, S)) {
        let (target, s1c1) = match ik.reduced {
            Some(t) => t,
            None => (
                [st.reduced[0], wrap(st.reduced[0].neg())],
                st.theta1_sin_cos,
            ),
        };
        let mut step = [S::ZERO; 2];
        for i in 0..2 {
            step[i] = wrap(target[i].sub(st.reduced[i]));
            st.theta[i] = st.theta[i].add(step[i]);
            st.reduced[i] = target[i];
        }
        st.pose = ik.pose;
        st.yaw_sin_cos = (ik.sg, ik.cg);
        st.theta1_sin_cos = s1c1;
        (step, s1c1)
    }

    /// One tick: sensing, mode manager, inverse kinematics, reference
    /// rates, force mapping and both motor laws (module docs).
    ///
    /// The force mapping forms `τ_t = −Jᵀτ` with one product by `1/D` per
    /// component and tests `|det J| < DET_MIN` through the closed form
    /// `det J = sin φ (cos θ1 cγ sδ − sin θ1 sγ)/D` (eq. 6.1 with the
    /// exact Jacobian of [`super::jacobian`]; the same values in exact
    /// arithmetic, rounding apart on `I16F16` and `f32`).
    pub fn update(
        &self,
        st: &mut WristStepState<S>,
        readings: &WristReadings<S>,
        target: &WristTarget<S>,
    ) -> WristOutput<S> {
        // 1. Eq. (6.35), (6.3) at the previous reference's yaw.
        let sensed = self.interaction(&readings.gauges, st.yaw_sin_cos);
        let interaction = sensed.unwrap_or([S::ZERO; 2]);
        // 2. Mode manager in task space.
        let m = self.modes.update_with(
            &mut st.modes,
            &WristModeInput {
                desired: [target.pose.delta, target.pose.gamma],
                desired_rate: target.rate,
                interaction,
                request: target.request,
            },
            false,
        );
        // 3. Inverse kinematics, continuous in time.
        let ik = self.ik(
            PitchYaw {
                delta: m.reference[0],
                gamma: m.reference[1],
            },
            Some(st.theta1_sin_cos),
        );
        let (step, (s1, c1)) = self.advance(st, &ik);
        // 4. Reference rates and accelerations by difference.
        let mut rate = [S::ZERO; 2];
        let mut acc = [S::ZERO; 2];
        for i in 0..2 {
            rate[i] = step[i].mul_coef(&self.inv_t);
            acc[i] = rate[i].sub(st.rate[i]).mul_coef(&self.inv_t_rate);
        }
        st.rate = rate;
        // 5. Eq. (6.1): τ_t = −Jᵀ τ, the exact Jacobian at the reference
        // (module docs of `super::jacobian`; D ≥ cos 3φ > 0 on the cone),
        // its θ3 component carried to motor 2's shaft by eq. (5.3).
        let (sd, cd, sg, cg) = (ik.sd, ik.cd, ik.sg, ik.cg);
        let sp_s1 = s1.mul_unit_range(self.sin_phi);
        let sp_c1 = c1.mul_unit_range(self.sin_phi);
        let d = sd
            .mul_unit_range(sp_s1)
            .add(cd.mul_unit_range(self.cos_phi));
        let inv_d = S::ONE.div(d);
        // With a = sin φ cos θ1, b = sin φ sin θ1 and e = sδ cos φ − cδ b:
        // J = [[cδ a, a cγ − sγ D], [−b, cγ e]]/D, so
        // τ_t = −Jᵀτ = (−(cδ a τ_δ − b τ_γ)/D, sγ τ_δ − (a cγ τ_δ + cγ e τ_γ)/D)
        // with one product by 1/D each, and, since cδ e + b = sδ D,
        // det J = (a cγ sδ − b sγ)/D: singular when |a cγ sδ − b sγ| < DET_MIN·D.
        let a_cg = sp_c1.mul_unit_range(cg);
        let cg_e = sd
            .mul_unit_range(self.cos_phi)
            .sub(cd.mul_unit_range(sp_s1))
            .mul_unit_range(cg);
        let [td, tg] = interaction;
        let mut joint_torque = [
            td.mul_unit_range(cd.mul_unit_range(sp_c1))
                .sub(tg.mul_unit_range(sp_s1))
                .mul(inv_d)
                .neg(),
            td.mul_unit_range(sg)
                .sub(
                    td.mul_unit_range(a_cg)
                        .add(tg.mul_unit_range(cg_e))
                        .mul(inv_d),
                )
                .mul(ik.transmission),
        ];
        // A finite wrench within a factor ‖J‖ of the float range can
        // overflow here: handled like an invalid gauge reading (0, flagged).
        // Fixed point saturates, so the test is `false` there.
        let nf = |v: S| v.sub(v); // 0 when finite, NaN for NaN and ±∞
        let overflow = nf(joint_torque[0]).add(nf(joint_torque[1])) != S::ZERO;
        if overflow {
            joint_torque = [S::ZERO; 2];
        }
        let det_num = a_cg.mul_unit_range(sd).sub(sg.mul_unit_range(sp_s1));
        let singular = det_num.abs() < d.mul_unit_range(self.det_min);
        // 6. Both motor laws.
        let position = [readings.motors.theta1, readings.motors.theta3];
        let sample = |i: usize| WristJointSample {
            desired_position: st.theta[i],
            desired_velocity: rate[i],
            desired_acceleration: acc[i],
            position: position[i],
            velocity: readings.motor_velocity[i],
            interaction_torque: joint_torque[i],
        };
        let samples = [sample(0), sample(1)];
        let laws = self.active.update(&mut st.laws, &samples);
        let reference_saturated = m.saturated || ik.saturated;
        let torque_saturated = (laws[0].saturated && !laws[0].invalid_input)
            || (laws[1].saturated && !laws[1].invalid_input);
        WristOutput {
            motor_torque: [laws[0].torque, laws[1].torque],
            mode: m.mode,
            switched: m.switched,
            interaction,
            joint_torque,
            reference: ik.pose,
            motor_reference: st.motor_reference(),
            motor_reference_rate: rate,
            saturated: reference_saturated || torque_saturated,
            reference_saturated,
            torque_saturated,
            singular,
            invalid_input: sensed.is_none()
                || overflow
                || m.invalid_input
                || laws[0].invalid_input
                || laws[1].invalid_input,
            laws,
        }
    }
}

#[cfg(test)]
mod tests;
