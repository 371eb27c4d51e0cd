//! Joint-torque estimation from a motor-side and a link-side encoder
//! (thesis ch. 3).

pub mod torque;

pub use torque::{
    TorqueEstimate, TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorState,
};
