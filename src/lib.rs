// Link targets of the README's reference-style links when it is read as
// the crate's front page (the first definition of a label wins, so these
// intra-doc paths take precedence over the README's own docs.rs links,
// which serve the repository page and crates.io).
#![doc = "[equations]: crate::docs::equations\n[errata]: crate::docs::errata\n[guide]: crate::docs::guide\n"]
#![doc = "[verification]: crate::docs::verification\n[kani]: crate::docs::verification#kani\n[kernel-bounds]: crate::docs::verification#kernel-bounds\n"]
#![doc = "[performance]: crate::docs::performance\n[reproduction]: crate::docs::reproduction\n[figures]: crate::docs::reproduction#figures-thesis-against-reproduction\n"]
#![doc = "[Scalar]: crate::scalar::Scalar\n[api]: crate\n[design]: crate::control::design\n[claims]: crate::sim::claims\n[mutants]: crate::docs::mutants\n[engine]: crate::sim::engine\n"]
#![doc = include_str!("../README.md")]
#![cfg_attr(not(any(feature = "std", test, kani)), no_std)]
// docs.rs (nightly, `--cfg docsrs`): mark feature-gated items with their feature.
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod control;
pub mod error;
pub mod estimation;
pub mod friction;
pub mod harmonic_drive;
pub mod joint;
pub mod scalar;
#[cfg(feature = "sim")]
#[cfg_attr(docsrs, doc(cfg(feature = "sim")))]
pub mod sim;
pub mod wrist;

/// Reference pages shipped with the crate: the guide from a catalogue sheet
/// to a running joint, the equation index, the errata of the thesis, the
/// verification record, the performance on target and the thesis
/// reproductions.
pub mod docs {
    /// From a harmonic-drive catalogue sheet to a torque estimator and a
    /// joint controller on a microcontroller.
    #[doc = ""]
    #[doc = "[performance]: crate::docs::performance"]
    #[doc = "[errata]: crate::docs::errata"]
    #[doc = ""]
    #[doc = include_str!("../docs/GUIDE.md")]
    pub mod guide {}

    /// Every numbered equation of the thesis and the item implementing it.
    #[doc = ""]
    #[doc = "[errata]: crate::docs::errata"]
    #[doc = ""]
    #[doc = include_str!("../docs/EQUATIONS.md")]
    pub mod equations {}

    /// Where the thesis is wrong, the form implemented and the evidence.
    #[doc = ""]
    #[doc = include_str!("../docs/ERRATA.md")]
    pub mod errata {}

    /// What is proven and how: the Kani harnesses, the exhaustive kernel
    /// bounds and the commands that rerun them.
    #[doc = ""]
    #[doc = "[reproduction]: crate::docs::reproduction"]
    #[doc = ""]
    #[doc = include_str!("../docs/verification.md")]
    pub mod verification {}

    /// Instruction counts and budgets of every kernel and step on a
    /// Cortex-M4F and a Cortex-M0+, and what the counts assume.
    #[doc = ""]
    #[doc = include_str!("../docs/performance.md")]
    pub mod performance {}

    /// The thesis's experiments and figures rerun by the library and its
    /// simulator, with the commands that print the numbers.
    #[doc = ""]
    #[doc = "[errata]: crate::docs::errata"]
    #[doc = ""]
    #[doc = include_str!("../docs/reproduction.md")]
    pub mod reproduction {}

    /// Mutation testing: per module, how many mutants of the code the
    /// library's own tests catch, and why each survivor is equivalent.
    #[doc = ""]
    #[doc = include_str!("../docs/MUTANTS.md")]
    pub mod mutants {}
}

pub use error::ParamError;
pub use joint::{
    JointConfig, JointMeasurement, JointOutput, JointParams, JointReadings, JointSettings,
    JointState, JointTarget,
};
pub use scalar::{Scalar, I16F16};

/// The types a joint's or a wrist's firmware or simulator uses, in one import:
/// `use mrr_control::prelude::*;`. Every parameter type is built by its
/// validating `try_new` (or a named-field settings struct), and every step
/// reads and writes SI values through the `from_si` / `*_si` conversions.
pub mod prelude {
    pub use crate::control::{
        ControlInput, JointMode, ModeConfig, ModeOutput, ModeParams, ModeSettings, ModeState,
        PassiveParams, PassiveSettings, RobustAdaptiveParams,
    };
    pub use crate::error::ParamError;
    pub use crate::estimation::{
        AgreementBound, CollisionParams, CollisionReaction, CollisionSettings, TorqueEstimate,
        TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
        TorqueEstimatorState,
    };
    pub use crate::harmonic_drive::kinematic_error::KinematicErrorModel;
    pub use crate::harmonic_drive::{
        CatalogueData, FlexsplineParams, FlexsplineSettings, HarmonicDriveParams,
        WaveGeneratorParams, WaveGeneratorSettings,
    };
    pub use crate::joint::{
        JointConfig, JointMeasurement, JointOutput, JointParams, JointReadings, JointSettings,
        JointState, JointTarget,
    };
    pub use crate::scalar::{Scalar, I16F16};
    pub use crate::wrist::{
        MotorAngles, PitchYaw, WristMode, WristOutput, WristReadings, WristStepConfig,
        WristStepParams, WristStepSettings, WristStepState, WristTarget,
    };
}

/// Helpers shared by unit tests of several modules.
#[cfg(test)]
mod test_support;

/// Verification properties (see `proofs/mod.rs`), compiled for the test,
/// Kani and fuzz engines only.
#[cfg(any(kani, test, feature = "proofs"))]
#[doc(hidden)]
#[path = "../proofs/mod.rs"]
pub mod proofs;
