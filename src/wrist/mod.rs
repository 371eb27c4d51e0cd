//! The compact DAUJ wrist (double active universal joint), thesis ch. 5–6:
//! universal-joint transmission, forward and inverse kinematics, the α/β
//! (polar) description, differential kinematics and the force mapping
//! (ch. 5); sensing and control (ch. 6):
//!
//! * [`ft_sensor`] — the F/T sensor chain: gauge amplifier (eq. 6.34),
//!   decoupling matrix (eq. 6.35) and the interaction torques about the
//!   wrist axes (eq. 6.3).
//! * [`active`] — the robust adaptive law of both wrist motors (eq.
//!   6.12–6.15, Theorem 2), the arm-motion coupling (eq. 6.4, 6.9–6.10),
//!   Table 6.1 and the ultimate bound (eq. 6.24–6.27).
//! * [`admittance`] — the passive mode by the admittance law (eq.
//!   6.28–6.33) in task space, with its discrete-time stability range.
//! * [`modes`] — active ↔ passive switching of the wrist's task-space
//!   reference, bumpless.
//! * [`step`] — the whole wrist in one call per tick: gauge signals →
//!   interaction torques → mode manager → inverse kinematics → both motor
//!   laws ([`WristStepConfig::update`]).
//!
//! Angles are in rad, torques in any one unit (the maps are linear in
//! torque and dimensionless). Conventions and the corrections to the
//! printed equations are in [`kinematics`] and `docs/ERRATA.md` (E5.x).
//!
//! The entry points a controller needs:
//! * [`WristConfig::inverse`] / [`WristConfig::update`] — `(δ, γ)` to the
//!   motor angles `(θ1, θ3)`, saturating and flagged outside the workspace;
//! * [`WristConfig::forward`] — motor angles to `(δ, γ)`
//!   ([`WristConfig::forward_plus_root`]: the other root of eq. 5.10, which
//!   the thesis rejects in §5.2, to rerun that test);
//! * [`ForceMapping`] — interaction torques `(τ_δ, τ_γ)` to motor torques
//!   `(τ1, τ3)`, eq. (5.28)/(6.1), and back, eq. (5.29); the exact
//!   Jacobian by default.
//!
//! ```
//! use mrr_control::wrist::{
//!     ForceMapping, JacobianKind, PitchYaw, WristConfig, WristParams,
//! };
//! let p = WristParams::thesis(); // φ = 16°, workspace: bend ≤ 32°
//! let cfg = WristConfig::<f32>::new(&p);
//! let target = PitchYaw { delta: 0.2f32, gamma: -0.1 };
//! let ik = cfg.inverse(target);
//! assert!(!ik.saturated);
//! let back = cfg.forward(ik.motors).pose;
//! assert!((back.delta - 0.2).abs() < 1e-5 && (back.gamma + 0.1).abs() < 1e-5);
//! // Motor torques that balance 1 N·m of pitch torque, eq. (5.28)/(6.1).
//! let fm = ForceMapping::<f32>::new(&p, JacobianKind::Exact);
//! let t = fm.motor_torques(ik.motors, [1.0, 0.0]);
//! assert!(!t.singular && t.torque.iter().all(|x| x.abs() < 1.5));
//! // Outside the workspace the pose is projected and flagged.
//! assert!(cfg.inverse(PitchYaw { delta: 0.5, gamma: 0.5 }).saturated);
//! ```

pub mod active;
pub mod admittance;
pub mod alpha_beta;
pub mod figures;
pub mod ft_sensor;
pub mod jacobian;
pub mod kinematics;
pub mod modes;
pub mod step;
pub mod ujoint;

pub use alpha_beta::AlphaBeta;
pub use jacobian::{ForceMapping, Jacobian, JacobianKind, MappedTorques};
pub use kinematics::{
    Forward, IkState, Inverse, MotorAngles, PitchYaw, Unreachable, WristConfig, WristParams,
};
pub use modes::WristMode;
pub use step::{
    WristOutput, WristReadings, WristStepConfig, WristStepParams, WristStepSettings,
    WristStepState, WristTarget,
};
