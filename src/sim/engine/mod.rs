//! Mechanisms on a rigid-body engine (feature `engine`): the library's
//! kinematics and force mappings checked against bodies and joints that
//! know nothing of its equations.
//!
//! The engine is [rapier3d](https://rapier.rs) in `f64` (crate
//! `rapier3d-f64` 0.27, the last release on the library's nalgebra 0.33).
//! Every mechanism here is built from its parts — bodies with mass, and
//! revolute joints at the places the thesis draws them — and is driven and
//! loaded only through joint motors and external forces. Its poses come from
//! the engine's constraint solver; its holding torques from the deflection
//! of stiff motor springs at rest.
//!
//! * [`wrist`] — the DAUJ wrist (thesis ch. 5): two motors, the oblique
//!   joint between the semi-spheres, the output link and the outer
//!   universal joint, as a closed loop.
//! * [`ft_sensor`] — the wrist's F/T sensor as measured: the wrench the
//!   tool puts through the sensor, read from the engine, and the strain
//!   gauges that turn it into voltages through a sensitivity matrix off the
//!   certificate by a stated calibration error, with offsets and noise.
//! * [`arm`] — the modular arm of ch. 4: links and rotors as bodies on
//!   multibody revolute joints, coupled by the library's drive models; the
//!   independent check of eq. (4.1)–(4.6) of [`crate::sim::Mrr`]; a ball
//!   on a link can hit a fixed wall through the engine's contacts.
//! * [`family_drives`] — the independent joint family's members
//!   ([`crate::sim::plants::JointPlant`]) as the arm's drives, in place of
//!   the library's drive and friction models.
//! * [`arm_scenarios`] — the chapter-4 experiments with the library's joint
//!   step at 4 ms on that arm (or on [`crate::sim::Mrr`]): active tracking
//!   (§4.4.1, Fig. 4.3), back-driving (§4.4.2, Fig. 4.11–4.12), mode
//!   switching and collision detection, with their traces.
//! * [`door`] — the door opening of §6.4.4: the mobile base, the turret on
//!   a drive of the independent joint family ([`FamilyDrives`]), the DAUJ
//!   and its F/T sensor on the arm, a hinged door,
//!   with the library's wrist step and passive law in the loop at 4 ms.
//! * [`universal_joint`] — the inner universal joint of eq. (5.1)–(5.3):
//!   two shafts bent by `β` and the cross between them.
//! * [`wrist_bench`] — the wrist bench of §6.4.3: a finger pushing the
//!   output link with the motors off (Case 1) and under the library's wrist
//!   step in the admittance-passive mode (Case 2).
//!
//! Gravity is off in the wrist mechanisms: their checks are kinematic,
//! static, or (the sensor in motion) about the inertia of the moving parts
//! alone. The arm carries its gravity as a force on every body.

pub mod arm;
pub mod arm_scenarios;
mod dauj;
pub mod door;
pub mod family_drives;
pub mod ft_sensor;
pub mod universal_joint;
mod world;
pub mod wrist;
pub mod wrist_bench;

pub use arm::{
    arm_settings, DriveModel, DriveState, DriveTorques, EngineArm, LinearDrives, PlantDrives,
    RotorBody, TipBall, Wall, ARM_DT,
};
pub use arm_scenarios::{ArmPlant, ArmTrackingRun, JointRun};
pub use door::{engine_door_opening, Backend, DoorBody, EngineDoorRun, EngineDoorSample};
pub use family_drives::FamilyDrives;
pub use ft_sensor::{GaugeErrors, SensedWrist, StrainGaugeSensor};
pub use universal_joint::UniversalJointBench;
pub use world::EngineSettings;
pub use wrist::{DaujMechanism, MechanismAngles};
