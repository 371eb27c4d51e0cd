//! The compact DAUJ wrist (double active universal joint), thesis ch. 5:
//! universal-joint transmission, forward and inverse kinematics, the α/β
//! (polar) description, differential kinematics and the force mapping.
//!
//! Angles are in rad, torques in any one unit (the maps are linear in
//! torque and dimensionless). Conventions and the corrections to the
//! printed equations are in [`kinematics`] and `docs/ERRATA.md` (E5.x).
//!
//! The entry points a controller needs:
//! * [`WristConfig::inverse`] / [`WristConfig::update`] — `(δ, γ)` to the
//!   motor angles `(θ1, θ3)`, saturating and flagged outside the workspace;
//! * [`WristConfig::forward`] — motor angles to `(δ, γ)`;
//! * [`ForceMapping`] — interaction torques `(τ_δ, τ_γ)` to motor torques
//!   `(τ1, τ3)`, eq. (5.28)/(6.1), and back, eq. (5.29); the exact
//!   Jacobian by default.

pub mod alpha_beta;
pub mod figures;
pub mod jacobian;
pub mod kinematics;
pub mod ujoint;

pub use alpha_beta::AlphaBeta;
pub use jacobian::{ForceMapping, Jacobian, JacobianKind, MappedTorques};
pub use kinematics::{
    Forward, IkState, Inverse, MotorAngles, PitchYaw, Unreachable, WristConfig, WristParams,
};
