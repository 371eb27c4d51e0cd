#![doc = include_str!("../README.md")]
#![cfg_attr(not(any(feature = "std", test, kani)), no_std)]

pub mod control;
pub mod error;
pub mod estimation;
pub mod friction;
pub mod harmonic_drive;
pub mod scalar;
#[cfg(feature = "sim")]
pub mod sim;

pub use error::ParamError;
pub use scalar::{Scalar, I16F16};

/// The types a joint's firmware or simulator uses, in one import:
/// `use mrr_control::prelude::*;`. Every parameter type is built by its
/// validating `try_new` (or a named-field settings struct), and every step
/// reads and writes SI values through the `from_si` / `*_si` conversions.
pub mod prelude {
    pub use crate::control::{
        ControlInput, JointMode, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState,
        PassiveParams, RobustAdaptiveParams,
    };
    pub use crate::error::ParamError;
    pub use crate::estimation::{
        AgreementBound, CollisionParams, CollisionReaction, TorqueEstimate, TorqueEstimatorConfig,
        TorqueEstimatorParams, TorqueEstimatorState,
    };
    pub use crate::harmonic_drive::kinematic_error::KinematicErrorModel;
    pub use crate::harmonic_drive::{
        CatalogueData, FlexsplineParams, HarmonicDriveParams, WaveGeneratorParams,
    };
    pub use crate::scalar::{Scalar, I16F16};
}

/// Verification properties (see `proofs/mod.rs`), compiled for the test,
/// Kani and fuzz engines only.
#[cfg(any(kani, test, feature = "proofs"))]
#[doc(hidden)]
#[path = "../proofs/mod.rs"]
pub mod proofs;
