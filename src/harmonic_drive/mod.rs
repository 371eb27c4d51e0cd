//! Harmonic-drive models (thesis ch. 2): rigid kinematics and statics,
//! the catalogue and cubic stiffness models, the proposed flexspline +
//! wave-generator compliance, its identification from catalogue numbers,
//! and encoder calibration.

pub mod calibration;
pub mod compliance;
pub mod identification;
pub mod kinematic_error;
pub mod kinematics;
pub mod two_spring;
pub mod wave_generator_torque;

pub use compliance::{
    CatalogueCurve, CataloguePiecewise, CubicStiffness, CubicStiffnessSettings, FlexsplineConfig,
    FlexsplineParams, FlexsplineSettings, FlexsplineTorque, HarmonicDriveParams,
    WaveGeneratorConfig, WaveGeneratorParams, WaveGeneratorSettings,
};
pub use identification::CatalogueData;
pub use wave_generator_torque::{
    WaveGeneratorTorqueConfig, WaveGeneratorTorqueParams, WaveGeneratorTorqueSettings,
    WaveGeneratorTorqueState,
};
