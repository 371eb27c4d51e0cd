//! Active mode of the wrist, thesis §6.1: the robust adaptive law of eq.
//! (6.12)–(6.15) with Theorem 2's adaptation for both motors, the
//! arm-motion coupling `τ_base` of eq. (6.4), (6.9)–(6.10), Table 6.1 and
//! the ultimate bound of eq. (6.24)–(6.27).
//!
//! # One law, shared with chapter 4
//! Eq. (6.4) is eq. (4.6) written in the wrist joint coordinate `q_i`
//! (the gear output, `q_m = N_i q_i`):
//!
//! `I_mi N_i q̈_i + f_i(q_i, q̇_i) + τ_base,i + τ_ti/N_i = τ_mi`,
//!
//! an equation in motor torque whose "inertia" is `I_mi N_i` and whose
//! friction is a function of the joint speed. Eq. (6.12)–(6.15) are eq.
//! (4.15)–(4.19) for that equation term by term, except the robust gain
//! of the base term, written `I_mi ρ_base` with the rotor inertia alone
//! (`τ_base,i = I_mi · (arm acceleration along the rotor axis)`, eq. 6.10).
//! So each motor runs the ch. 4 law ([`RobustAdaptiveConfig`]) on a design
//! with
//!
//! * `rotor_inertia = I_mi N_i` (kg·m², the coefficient of `q̈_i`),
//! * `uncertainty.base_acceleration = ρ_base / N_i`, so that the ch. 4
//!   gain `rotor_inertia · base_acceleration` is `I_mi ρ_base` of (6.15),
//! * positions, speeds and accelerations in joint coordinates (rad, rad/s,
//!   rad/s² of `q_i`), the friction model `F = [b, f_c, f_s, f_τ]` of eq.
//!   (6.5) in motor torque as a function of `q̇_i`, and the joint torque
//!   `τ̂_ti` of eq. (6.1) as the fed-back torque (its `1/N_i` is the ch. 4
//!   feedback term).
//!
//! [`WristMotorDesign::law_design`] does this; the law, the adaptation
//! `dF̂_i/dt = −μ_Fic Y_iᵀ r_i` (Theorem 2; projected onto the friction box
//! as in ch. 4), the integral clamp and the output limit are the ch. 4
//! code. Theorem 2's bound is then Theorem 1's calculator on the same
//! design ([`WristActiveParams::ultimate_bound`]): eq. (6.24)–(6.27) are
//! eq. (4.28)–(4.31) with `I_m → I_mi N_i` (checked against the printed
//! ch. 6 formulas in `table_6_1_bound_matches_eq_6_25_by_hand`).
//!
//! The uncertainty bounds are the ch. 4 ones in ch. 6 numbering: the
//! friction box and `ρ_F` of Property 2, eq. (6.6)–(6.7)
//! ([`FrictionBounds`]); `ρ_fq` of Assumption 7, eq. (6.8); `ρ_base` of
//! Assumption 8, eq. (6.9)–(6.10); `ρ_τt` of Assumption 9, eq. (6.11)
//! (`ρ_τδ, ρ_τγ` enter only through `ρ_τt`); `ρ_f` of Assumption 10.
//! The proof of Theorem 2, eq. (6.16)–(6.23), is the proof of Theorem 1,
//! eq. (4.20)–(4.27), with `I_m → I_mi N_i` term by term (the shared code
//! and its tests check it; the printed proof's typos are errata E6.4).
//!
//! The joint references `q_id, q̇_id, q̈_id` come from the task-space
//! reference `(δ_d, γ_d)` through the inverse and differential kinematics
//! of ch. 5 (eq. 6.12's note); that mapping is the caller's step.
//!
//! # Table 6.1's inertia
//! Table 6.1 prints `I_m = 10.5×10⁻⁴ gm²`. Read as g·m², that is
//! `1.05×10⁻³ g·m² = 1.05×10⁻⁶ kg·m²` = 10.5 g·cm², the catalogue rotor
//! inertia class of the Maxon RE 25 motors that drive GP 32 A heads (a
//! 25 mm rotor of ~60 g: `½·0.06·0.0125² ≈ 4.7e-6` as a solid cylinder,
//! a few 1e-6 for the real, hollow-wound rotor). Read as kg·m², 1.05e-3
//! kg·m², it would be the inertia of a 1 kg disc of 9 cm diameter, the
//! motor of a heavy arm joint, not a wrist motor. The preset uses
//! 1.05e-6 kg·m².

// Two- and six-element arrays indexed in parallel (axes, rows): index loops
// read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use crate::control::{
    ActiveOutput, ControlInput, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams,
    RobustAdaptiveState, UltimateBound, UncertaintyBounds,
};
use crate::error::{non_negative, positive, ParamError};
use crate::friction::{FrictionBounds, FrictionParams};
use crate::scalar::Scalar;

/// Eq. (6.9)–(6.10) without `I_m`: the angular acceleration of the base
/// arm along the rotor axis (rad/s²),
///
/// `a_base = Σ_j z_mᵀ z_lj q̈_lj + Σ_{j≥2} Σ_{k<j} z_mᵀ (z_lk × z_lj) q̇_lk q̇_lj`,
///
/// for the rotor axis `z_m` and the arm joint axes `z_lj` (unit vectors in
/// one frame, e.g. the base frame, at the current configuration), arm
/// joint speeds `q̇_l` (rad/s) and accelerations `q̈_l` (rad/s²). It is
/// `z_mᵀ ω̇` for the arm's last-link angular velocity
/// `ω = Σ_j z_lj q̇_lj`: `ż_lj = (Σ_{k<j} z_lk q̇_lk) × z_lj`. The torque of
/// eq. (6.4) is `τ_base,i = I_mi · a_base`. Axes need not be normalized
/// exactly; no normalization is applied.
pub fn base_acceleration<const NJ: usize>(
    rotor_axis: [f64; 3],
    joint_axes: &[[f64; 3]; NJ],
    speeds: &[f64; NJ],
    accelerations: &[f64; NJ],
) -> f64 {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut a = 0.0;
    for j in 0..NJ {
        a += dot(rotor_axis, joint_axes[j]) * accelerations[j];
        for k in 0..j {
            a += dot(rotor_axis, cross(joint_axes[k], joint_axes[j])) * speeds[k] * speeds[j];
        }
    }
    a
}

/// A bound `ρ_base` of eq. (6.9) valid for every configuration (rad/s²):
/// with unit axes `|z_mᵀ z_lj| ≤ 1` and `|z_mᵀ(z_lk × z_lj)| ≤ 1`, so
/// `|a_base| ≤ Σ_j q̈_j,max + Σ_{k<j} q̇_k,max q̇_j,max` (Assumption 8).
pub fn base_acceleration_bound<const NJ: usize>(
    max_speeds: &[f64; NJ],
    max_accelerations: &[f64; NJ],
) -> f64 {
    let mut a = 0.0;
    for j in 0..NJ {
        a += libm::fabs(max_accelerations[j]);
        for k in 0..j {
            a += libm::fabs(max_speeds[k]) * libm::fabs(max_speeds[j]);
        }
    }
    a
}

/// The design of one wrist motor in the thesis's ch. 6 symbols.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristMotorDesign {
    /// Rotor inertia `I_mi`, kg·m² (Table 6.1: 1.05e-6, module docs).
    pub rotor_inertia: f64,
    /// `ρ_base` of eq. (6.9)–(6.10), rad/s²: a bound of the base arm's
    /// angular acceleration along the rotor axis
    /// ([`base_acceleration_bound`]).
    pub base_acceleration: f64,
    /// The rest of eq. (6.15) in joint coordinates, as a ch. 4 design:
    /// `ratio = N_i`, `λ_i` (1/s), `K_Ii` (N·m per rad of `q_i`, motor
    /// torque), `μ_Fic`, `ε_ri` (rad/s of `q̇_i`), `ε_q̇i`, `ε_Fij`, `ρ_fi`,
    /// `ρ_fqi` (N·m, motor side), `ρ_τti` (N·m, joint side), the friction
    /// box and `ρ_Fi` (`b` in N·m·s/rad of `q̇_i`), limits (N·m, motor) and
    /// `T`. Its `rotor_inertia` and `uncertainty.base_acceleration` are
    /// set by [`law_design`](Self::law_design) from the two fields above:
    /// leave them `0` (or give exactly the value they are set to);
    /// [`WristActiveParams::try_new`] rejects anything else rather than
    /// ignore it.
    pub law: RobustAdaptiveDesign,
}

impl WristMotorDesign {
    /// The ch. 4 design the motor's law runs (module docs):
    /// `rotor_inertia = I_mi N_i`, `base_acceleration = ρ_base/N_i`.
    pub fn law_design(&self) -> RobustAdaptiveDesign {
        let mut d = self.law;
        d.rotor_inertia = self.rotor_inertia * d.ratio;
        d.uncertainty.base_acceleration = self.base_acceleration / d.ratio;
        d
    }

    /// Table 6.1 for one motor, completed where the table is silent.
    ///
    /// * printed: `I_m = 10.5e-4 g·m²` (= 1.05e-6 kg·m²), `N = 531`,
    ///   `λ = 160`, `K_I = 10`, `μ_Fic = 0.1`, `ε_r = 0.1`, `ε_q̇ = 0.01`,
    ///   `ε_F = [1e-4, 1e-3, 1e-3, 0.1]`,
    ///   `ρ_F = [1e-3 N·m·s/rad, 1e-2 N·m, 1e-2 N·m, 1.0 s²/rad²]`,
    ///   `ρ_fq = 0.5 N·m`, `ρ_τt = 1.0 N·m`;
    /// * not printed, chosen here: `ρ_base = 50 rad/s²` (the door-opening
    ///   arm: turret speed ≤ 1 rad/s and acceleration ≤ 10 rad/s², base
    ///   yaw rate ≤ 1 rad/s and acceleration ≤ 30 rad/s² in jerks, by
    ///   [`base_acceleration_bound`]: `10 + 30 + 1·1 ≤ 50`); the friction
    ///   box `b ∈ [0, 2e-3]` N·m·s/rad, `f_c, f_s ∈ [0, 0.01]` N·m,
    ///   `f_τ ∈ [0.1, 10]` s²/rad² with the initial estimate at its centre
    ///   (`f_τ = 1`); `ρ_f` derived from the box
    ///   ([`FrictionBounds::boundary_layer_bound`], 0.04 N·m); motor torque
    ///   limit 0.6 N·m and integral limit 0.1 N·m; `T = 4 ms` (§6.3).
    ///
    /// *Note.* The robust gain is
    /// `ρ_f + ρ_fq + I_m ρ_base + ρ_τt/N = 0.04 + 0.5 + 5.3e-5 + 1.9e-3 =
    /// 0.542 N·m` at the motor, dominated by Table 6.1's `ρ_fq = 0.5 N·m`,
    /// more than a 25 mm motor's stall torque: outside its boundary layer
    /// the printed law asks for the torque limit. `ρ_fq` reads like a
    /// joint-side value (0.5/531 ≈ 1e-3 N·m at the motor); the preset keeps
    /// the printed number.
    pub fn table_6_1() -> Self {
        let bounds = FrictionBounds::try_new(
            FrictionParams {
                viscous: 0.0,
                coulomb: 0.0,
                stribeck: 0.0,
                stribeck_shape: 0.1,
            },
            FrictionParams {
                viscous: 2e-3,
                coulomb: 0.01,
                stribeck: 0.01,
                stribeck_shape: 10.0,
            },
            [1e-3, 1e-2, 1e-2, 1.0],
        );
        // The box is valid (asserted by `table_6_1_is_valid`); fall back to
        // a fixed-shape box otherwise.
        let bounds = match bounds {
            Ok(b) => b,
            Err(_) => return Self::fallback(),
        };
        WristMotorDesign {
            rotor_inertia: 1.05e-6,
            base_acceleration: 50.0,
            law: RobustAdaptiveDesign {
                rotor_inertia: 1.05e-6 * 531.0,
                ratio: 531.0,
                lambda: 160.0,
                integral_gain: 10.0,
                adaptation_gain: [0.1; 4],
                eps_r: 0.1,
                eps_velocity: 0.01,
                eps_f: [1e-4, 1e-3, 1e-3, 0.1],
                uncertainty: UncertaintyBounds {
                    boundary_layer: bounds.boundary_layer_bound(),
                    nonparametric_friction: 0.5,
                    base_acceleration: 50.0 / 531.0,
                    torque_estimate: 1.0,
                },
                friction_bounds: bounds,
                initial_friction: FrictionParams {
                    viscous: 1e-3,
                    coulomb: 0.005,
                    stribeck: 0.005,
                    stribeck_shape: 1.0,
                },
                integral_limit: 0.1,
                torque_limit: 0.6,
                sample_period: 0.004,
            },
        }
    }

    fn fallback() -> Self {
        let mut d = RobustAdaptiveDesign::table_4_1();
        d.ratio = 531.0;
        // Set by `law_design` from the two fields below.
        d.rotor_inertia = 0.0;
        d.uncertainty.base_acceleration = 0.0;
        WristMotorDesign {
            rotor_inertia: 1.05e-6,
            base_acceleration: 50.0,
            law: d,
        }
    }
}

/// `designs[i].<name>` for the motor's own fields.
fn design_path(i: usize, name: &'static str) -> &'static str {
    const OWN: [(&str, [&str; 2]); 4] = [
        (
            "rotor_inertia",
            ["designs[0].rotor_inertia", "designs[1].rotor_inertia"],
        ),
        (
            "base_acceleration",
            [
                "designs[0].base_acceleration",
                "designs[1].base_acceleration",
            ],
        ),
        (
            "rotor_inertia·law.ratio",
            [
                "designs[0].rotor_inertia·designs[0].law.ratio",
                "designs[1].rotor_inertia·designs[1].law.ratio",
            ],
        ),
        (
            "law.ratio",
            ["designs[0].law.ratio", "designs[1].law.ratio"],
        ),
    ];
    OWN.iter().find(|(n, _)| *n == name).map_or_else(
        || law_path(i, name.trim_start_matches("law.")),
        |(_, p)| p[i.min(1)],
    )
}

macro_rules! law_fields {
    ($($name:literal),* $(,)?) => {
        [$(($name, [concat!("designs[0].law.", $name), concat!("designs[1].law.", $name)])),*]
    };
}

/// Every name [`RobustAdaptiveParams::try_new`] reports, with its path
/// under `designs[i].law.`.
const LAW_FIELDS: [(&str, [&str; 2]); 35] = law_fields![
    "rotor_inertia",
    "ratio",
    "lambda",
    "integral_gain",
    "adaptation_gain[0]",
    "adaptation_gain[1]",
    "adaptation_gain[2]",
    "adaptation_gain[3]",
    "eps_r",
    "eps_velocity",
    "eps_f[0]",
    "eps_f[1]",
    "eps_f[2]",
    "eps_f[3]",
    "uncertainty.boundary_layer",
    "uncertainty.nonparametric_friction",
    "uncertainty.base_acceleration",
    "uncertainty.torque_estimate",
    "torque_limit",
    "integral_limit",
    "sample_period",
    "initial_friction.viscous",
    "initial_friction.coulomb",
    "initial_friction.stribeck",
    "initial_friction.stribeck_shape",
    "friction_bounds.variable[0]",
    "friction_bounds.variable[1]",
    "friction_bounds.variable[2]",
    "friction_bounds.variable[3]",
    "lambda²·rotor_inertia",
    "integral_gain·sample_period",
    "adaptation_gain[0]·sample_period",
    "adaptation_gain[1]·sample_period",
    "adaptation_gain[2]·sample_period",
    "adaptation_gain[3]·sample_period",
];

/// `designs[i].law.<name>` for a name of the law's validation (names not
/// in the table, such as the robust-gain sum, pass unchanged).
fn law_path(i: usize, name: &'static str) -> &'static str {
    LAW_FIELDS
        .iter()
        .find(|(n, _)| *n == name)
        .map_or(name, |(_, p)| p[i.min(1)])
}

/// Validated designs of both wrist motors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristActiveParams {
    designs: [WristMotorDesign; 2],
    laws: [RobustAdaptiveParams; 2],
}

impl WristActiveParams {
    /// Validate both motors. For motor `i`, every error names the field
    /// as written, `designs[i].<field>` (e.g. `designs[0].law.ratio`),
    /// with the value given: `I_mi > 0` and `I_mi N_i ≤ 30` kg·m²,
    /// `ρ_base ≥ 0` (finite), then the law design by
    /// [`RobustAdaptiveParams::try_new`] (its field names prefixed by
    /// `designs[i].law.`), and one sample period for both.
    ///
    /// `law.rotor_inertia` and `law.uncertainty.base_acceleration` are
    /// set by [`WristMotorDesign::law_design`] from the motor's own
    /// fields: each must be left `0` or equal the value it would be set
    /// to, otherwise [`ParamError::Overridden`] names it (a value there
    /// would be ignored).
    pub fn try_new(designs: [WristMotorDesign; 2]) -> Result<Self, ParamError> {
        let mut laws = [RobustAdaptiveParams::table_4_1()?; 2];
        for (i, (law, d)) in laws.iter_mut().zip(designs.iter()).enumerate() {
            let path = |name: &'static str| design_path(i, name);
            let im = positive(path("rotor_inertia"), d.rotor_inertia)?;
            non_negative(path("base_acceleration"), d.base_acceleration)?;
            let n =
                crate::error::gear_ratio(d.law.ratio).map_err(|e| e.renamed(path("law.ratio")))?;
            crate::error::combination(path("rotor_inertia·law.ratio"), im * n, 0.0, 30.0)?;
            let derived = d.law_design();
            let set = [
                (
                    "law.rotor_inertia",
                    d.law.rotor_inertia,
                    derived.rotor_inertia,
                ),
                (
                    "law.uncertainty.base_acceleration",
                    d.law.uncertainty.base_acceleration,
                    derived.uncertainty.base_acceleration,
                ),
            ];
            for (name, value, expected) in set {
                if value != 0.0 && value != expected {
                    return Err(ParamError::Overridden {
                        name: path(name),
                        value,
                        expected,
                    });
                }
            }
            *law = RobustAdaptiveParams::try_new(derived).map_err(|e| {
                e.map_names(|name| match name {
                    // Set from the motor's fields, checked above; only a
                    // rounding edge of `ρ_base/N` can reach here.
                    "rotor_inertia" => path("rotor_inertia"),
                    "uncertainty.base_acceleration" => path("base_acceleration"),
                    other => law_path(i, other),
                })
            })?;
        }
        let (t0, t1) = (designs[0].law.sample_period, designs[1].law.sample_period);
        if t0 != t1 {
            return Err(ParamError::OutOfRange {
                name: "designs[1].law.sample_period",
                value: t1,
                min: t0,
                max: t0,
            });
        }
        Ok(WristActiveParams { designs, laws })
    }

    /// Table 6.1 for both motors ([`WristMotorDesign::table_6_1`]).
    pub fn table_6_1() -> Result<Self, ParamError> {
        Self::try_new([WristMotorDesign::table_6_1(); 2])
    }

    /// The ch. 6 designs.
    pub fn designs(&self) -> &[WristMotorDesign; 2] {
        &self.designs
    }

    /// The validated ch. 4 law parameters of each motor.
    pub fn laws(&self) -> &[RobustAdaptiveParams; 2] {
        &self.laws
    }

    /// Theorem 2, eq. (6.24)–(6.27), for motor `i` (0 or 1; other values
    /// give motor 1), in joint coordinates: `dissipation` is the constant
    /// of eq. (6.24) (N·m·rad/s), `damping = I_mi N_i λ_i`,
    /// `decrease_threshold` the radius of eq. (6.25) and `sliding_radius`
    /// the set `S` (rad/s of `r_i`), `tracking_error = r_S/λ_i` the
    /// ultimate bound of the joint error `|e_i|` (rad of `q_i`; ignore the
    /// `link_*` field, which divides by `N` once more), and
    /// [`UltimateBound::reaching_time`] is eq. (6.27).
    pub fn ultimate_bound(&self, i: usize) -> UltimateBound {
        UltimateBound::new(self.laws[i.min(1)].design())
    }
}

/// Both motors' laws quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristActiveConfig<S> {
    laws: [RobustAdaptiveConfig<S>; 2],
}

/// The adapted state of both motors (ch. 4 state: `F̂^c_i` and the
/// integral), made only by [`WristActiveConfig::initial_state`] and
/// advanced only by [`WristActiveConfig::update`]: its fields are private,
/// so no public call puts a NaN or a value outside the projection box in
/// it. Read it per motor with [`motors`](Self::motors) and the SI readers
/// of [`RobustAdaptiveState`] (`friction_si`, `integral_si`).
///
/// ```compile_fail
/// use mrr_control::wrist::active::{WristActiveConfig, WristActiveParams};
/// let cfg = WristActiveConfig::<f64>::new(&WristActiveParams::table_6_1().unwrap());
/// let mut st = cfg.initial_state();
/// st.motors[0] = st.motors[1]; // private: does not compile
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristActiveState<S: Scalar> {
    motors: [RobustAdaptiveState<S>; 2],
}

impl<S: Scalar> WristActiveState<S> {
    /// The adapted state of motor 1 and motor 2 (index 0 and 1): friction
    /// estimate and integral, read in SI with
    /// [`RobustAdaptiveState::friction_si`] and
    /// [`RobustAdaptiveState::integral_si`].
    pub fn motors(&self) -> &[RobustAdaptiveState<S>; 2] {
        &self.motors
    }
}

/// One sample of one wrist joint, stored units of `S::UNITS`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WristJointSample<S> {
    /// `q_id` (rad of the joint `q_i`), from the IK of `(δ_d, γ_d)`.
    pub desired_position: S,
    /// `q̇_id`, rad/s.
    pub desired_velocity: S,
    /// `q̈_id`, rad/s².
    pub desired_acceleration: S,
    /// Measured `q_i` (motor encoder / `N_i`), rad.
    pub position: S,
    /// Measured `q̇_i`, rad/s.
    pub velocity: S,
    /// `τ̂_ti` of eq. (6.1), N·m (joint side, stored link-torque units):
    /// the torque the interaction loads joint `i` with, entering eq. (6.4)
    /// as `+τ_ti/N_i`.
    pub interaction_torque: S,
}

impl<S: Scalar> WristJointSample<S> {
    /// The ch. 4 law's input for this sample.
    pub fn to_control_input(&self) -> ControlInput<S> {
        ControlInput {
            desired_position: self.desired_position,
            desired_velocity: self.desired_velocity,
            desired_acceleration: self.desired_acceleration,
            motor_position: self.position,
            motor_velocity: self.velocity,
            joint_torque: self.interaction_torque,
            ..Default::default()
        }
    }
}

impl<S: Scalar> WristActiveConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &WristActiveParams) -> Self {
        WristActiveConfig {
            laws: [
                RobustAdaptiveConfig::new(&p.laws[0]),
                RobustAdaptiveConfig::new(&p.laws[1]),
            ],
        }
    }

    /// The initial state of both motors.
    pub fn initial_state(&self) -> WristActiveState<S> {
        WristActiveState {
            motors: [self.laws[0].initial_state(), self.laws[1].initial_state()],
        }
    }

    /// The ch. 4 configuration of motor `i` (0 or 1; others give 1).
    pub fn law(&self, i: usize) -> &RobustAdaptiveConfig<S> {
        &self.laws[i.min(1)]
    }

    /// Eq. (6.15) for both motors, then Theorem 2's adaptation and the
    /// integral (ch. 4 [`RobustAdaptiveConfig::update`]). Motor torques in
    /// stored motor-torque units; never panics, never NaN (an invalid
    /// sample gives 0 for that motor, flagged).
    ///
    /// ```
    /// use mrr_control::wrist::active::{WristActiveConfig, WristActiveParams, WristJointSample};
    /// let cfg = WristActiveConfig::<f64>::new(&WristActiveParams::table_6_1()?);
    /// let mut st = cfg.initial_state();
    /// // Joint 1 at rest 0.1 mrad behind its reference: e = −1e-4,
    /// // r = λe = −0.016 rad/s inside ε_r = 0.1, Y = [0, 0, 0, 0] at rest:
    /// // τ = −λ² I_m N e − K_r r/ε_r = 0.0142 + 0.0867 = 0.1010 N·m.
    /// let x = [
    ///     WristJointSample { desired_position: 1e-4, ..Default::default() },
    ///     WristJointSample::default(),
    /// ];
    /// let o = cfg.update(&mut st, &x);
    /// let kr = 0.04 + 0.5 + 1.05e-6 * 50.0 + 1.0 / 531.0;
    /// let want = 160.0f64.powi(2) * 1.05e-6 * 531.0 * 1e-4 + kr * 0.016 / 0.1;
    /// assert!((o[0].torque - want).abs() < 1e-9 && o[1].torque == 0.0);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(
        &self,
        st: &mut WristActiveState<S>,
        x: &[WristJointSample<S>; 2],
    ) -> [ActiveOutput<S>; 2] {
        [
            self.laws[0].update(&mut st.motors[0], &x[0].to_control_input()),
            self.laws[1].update(&mut st.motors[1], &x[1].to_control_input()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_6_1_is_valid() {
        let p = WristActiveParams::table_6_1().unwrap();
        let d = p.laws()[0].design();
        assert!((d.rotor_inertia - 1.05e-6 * 531.0).abs() < 1e-18);
        assert!((d.robust_gain() - (0.04 + 0.5 + 1.05e-6 * 50.0 + 1.0 / 531.0)).abs() < 1e-12);
        // Not the fallback.
        assert_eq!(p.designs()[0].law.lambda, 160.0);
    }

    /// Eq. (6.24)–(6.25) computed from the printed ch. 6 formula with
    /// Table 6.1's numbers, independently of the ch. 4 calculator:
    /// `c = ε_r/4 (ρ_f + ρ_τt/N + ρ_fq + I_m ρ_base) + Σ ρ_Fj ε_Fj/4`,
    /// `r* = √(c/(I_m N λ))`, `r_S = √(2c/(I_m N λ))`.
    /// By hand: `ρ_f + ρ_τt/N + ρ_fq + I_m ρ_base =
    /// 0.04 + 0.0018832 + 0.5 + 5.25e-5 = 0.5419357`,
    /// `c = 0.025·0.5419357 + (1e-7 + 1e-5 + 1e-5 + 0.1)/4 =
    /// 0.013548 + 0.025005025 = 0.038553`,
    /// `I_m N λ = 1.05e-6·531·160 = 0.089208`,
    /// `r_S = √(2·0.038553/0.089208) = 0.92970 rad/s`,
    /// `|e| ≤ r_S/λ = 5.81e-3 rad` (0.33° of joint).
    #[test]
    fn table_6_1_bound_matches_eq_6_25_by_hand() {
        let p = WristActiveParams::table_6_1().unwrap();
        let b = p.ultimate_bound(0);
        let (im, n, lam) = (1.05e-6, 531.0, 160.0);
        let lumped: f64 = 0.04 + 1.0 / n + 0.5 + im * 50.0;
        let c = 0.1 / 4.0 * lumped + (1e-3 * 1e-4 + 1e-2 * 1e-3 + 1e-2 * 1e-3 + 1.0 * 0.1) / 4.0;
        assert!((b.dissipation - c).abs() < 1e-12 * c, "{b:?}");
        assert!((b.damping - im * n * lam).abs() < 1e-15);
        assert!((b.decrease_threshold - (c / (im * n * lam)).sqrt()).abs() < 1e-12);
        assert!((b.sliding_radius - (2.0 * c / (im * n * lam)).sqrt()).abs() < 1e-12);
        assert!(
            (b.sliding_radius - 0.92970).abs() < 1e-4,
            "{}",
            b.sliding_radius
        );
        assert!((b.tracking_error - 0.92970 / 160.0).abs() < 1e-6);
        // Eq. (6.26): on ∂S the bound of eq. (6.24) is −c.
        let vdot = -b.damping * b.sliding_radius.powi(2) + c;
        assert!((vdot + c).abs() < 1e-12);
    }

    /// Eq. (6.9): `z_mᵀ ω̇` of the arm's last link, by finite differences
    /// of the angular velocity of a 3-joint arm whose axes are rotated by
    /// the joints before them (Rodrigues), against the closed form.
    #[test]
    fn base_acceleration_is_the_projected_arm_angular_acceleration() {
        fn rot(axis: [f64; 3], a: f64) -> [[f64; 3]; 3] {
            let (s, c) = (a.sin(), a.cos());
            let [x, y, z] = axis;
            let t = 1.0 - c;
            [
                [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
                [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
                [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
            ]
        }
        fn mv(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
            [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
        }
        fn mm(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
            let mut o = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    o[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
                }
            }
            o
        }
        // Local axes: turret z, shoulder y, elbow y (a generic tilt added).
        let local = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [0.6, 0.8, 0.0]];
        let zm_local = [0.0, 0.6, 0.8]; // rotor axis in the last link
        let q = |t: f64| [0.3 + 0.7 * t, -0.2 + 0.4 * t * t, 1.1 * (2.0 * t).sin()];
        // Axes in the base frame and ω at time t.
        let axes = |t: f64| {
            let qq = q(t);
            let mut r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            let mut z = [[0.0; 3]; 3];
            for j in 0..3 {
                z[j] = mv(&r, local[j]);
                r = mm(&r, &rot(local[j], qq[j]));
            }
            (z, mv(&r, zm_local))
        };
        let dq = |t: f64| {
            let h = 1e-6;
            let (a, b) = (q(t + h), q(t - h));
            [0, 1, 2].map(|i| (a[i] - b[i]) / (2.0 * h))
        };
        let omega = |t: f64| {
            let (z, _) = axes(t);
            let v = dq(t);
            [0, 1, 2].map(|i| (0..3).map(|j| z[j][i] * v[j]).sum::<f64>())
        };
        for &t in &[0.1, 0.45, 0.9] {
            let h = 1e-4;
            let (wp, wm) = (omega(t + h), omega(t - h));
            let wdot = [0, 1, 2].map(|i| (wp[i] - wm[i]) / (2.0 * h));
            let (z, zm) = axes(t);
            let want: f64 = (0..3).map(|i| zm[i] * wdot[i]).sum();
            let v = dq(t);
            let acc = {
                let h = 1e-4;
                let (a, b) = (dq(t + h), dq(t - h));
                [0, 1, 2].map(|i| (a[i] - b[i]) / (2.0 * h))
            };
            let got = base_acceleration(zm, &z, &v, &acc);
            assert!((got - want).abs() < 1e-5, "t={t}: {got} vs {want}");
            // And the bound of eq. (6.9) holds.
            assert!(got.abs() <= base_acceleration_bound(&v.map(f64::abs), &acc.map(f64::abs)));
        }
    }

    #[test]
    fn invalid_designs_are_rejected() {
        let mut d = [WristMotorDesign::table_6_1(); 2];
        d[1].law.sample_period = 0.002;
        assert!(matches!(
            WristActiveParams::try_new(d),
            Err(ParamError::OutOfRange {
                name: "designs[1].law.sample_period",
                ..
            })
        ));
        let mut d = [WristMotorDesign::table_6_1(); 2];
        d[0].rotor_inertia = -1.0;
        assert!(WristActiveParams::try_new(d).is_err());
        let mut d = [WristMotorDesign::table_6_1(); 2];
        d[0].base_acceleration = f64::NAN;
        assert!(WristActiveParams::try_new(d).is_err());
    }

    /// Every backend runs the same law: `f32` and `I16F16` agree with
    /// `f64` on a sample inside the layers.
    #[test]
    fn backends_agree() {
        use crate::scalar::I16F16;
        let p = WristActiveParams::table_6_1().unwrap();
        let x = |v: [f64; 6]| WristJointSample {
            desired_position: v[0],
            desired_velocity: v[1],
            desired_acceleration: v[2],
            position: v[3],
            velocity: v[4],
            interaction_torque: v[5],
        };
        let s = [
            x([0.1, 0.05, 0.2, 0.1002, 0.04, 1.5]),
            x([-0.2, 0.0, 0.0, -0.2001, 0.002, -0.7]),
        ];
        let c64 = WristActiveConfig::<f64>::new(&p);
        let o64 = c64.update(&mut c64.initial_state(), &s);
        let c32 = WristActiveConfig::<f32>::new(&p);
        let s32 = s.map(|j| WristJointSample {
            desired_position: j.desired_position as f32,
            desired_velocity: j.desired_velocity as f32,
            desired_acceleration: j.desired_acceleration as f32,
            position: j.position as f32,
            velocity: j.velocity as f32,
            interaction_torque: j.interaction_torque as f32,
        });
        let o32 = c32.update(&mut c32.initial_state(), &s32);
        let cfx = WristActiveConfig::<I16F16>::new(&p);
        let sfx = s.map(|j| WristJointSample {
            desired_position: I16F16::from_f64(j.desired_position),
            desired_velocity: I16F16::from_f64(j.desired_velocity),
            desired_acceleration: I16F16::from_f64(j.desired_acceleration),
            position: I16F16::from_f64(j.position),
            velocity: I16F16::from_f64(j.velocity),
            interaction_torque: I16F16::from_f64(j.interaction_torque),
        });
        let ofx = cfx.update(&mut cfx.initial_state(), &sfx);
        for i in 0..2 {
            assert!(!o64[i].saturated);
            assert!(
                (o32[i].torque as f64 - o64[i].torque).abs() < 1e-4,
                "{o32:?} {o64:?}"
            );
            // I16F16 stores mN·m; angles quantized to 2⁻¹⁷ rad move e by up
            // to 1.5e-5 rad: λ K_r/ε_r · 1.5e-5 ≈ 0.013 N·m at most.
            let got = ofx[i].torque.to_f64() / 1e3;
            assert!((got - o64[i].torque).abs() < 0.015, "{got} {:?}", o64[i]);
        }
    }
}
