//! Joint-torque estimation from a motor-side and a link-side encoder
//! (thesis ch. 3), and collision detection on the estimate.

pub mod collision;
pub mod torque;

pub use collision::{
    CollisionConfig, CollisionOutput, CollisionParams, CollisionReaction, CollisionSettings,
    CollisionState,
};
pub use torque::{
    AgreementBound, TorqueEstimate, TorqueEstimatorConfig, TorqueEstimatorParams,
    TorqueEstimatorSettings, TorqueEstimatorState,
};
