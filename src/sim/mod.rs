//! Simulation (feature `sim`): plants, fixed-step integration, sensors and
//! the thesis's chapter 2–3 experiments reproduced on a simulated joint.
//!
//! Nothing here runs in a control loop; the models under test (compliance,
//! estimator) are called from the library, never re-implemented, and the
//! plant deliberately contains what they leave out (Maxwell-slip
//! hysteresis, kinematic error, friction with stiction, encoder
//! quantization and noise) so that a comparison can come out either way.
//!
//! * [`integrator`] — classical RK4 at a fixed step, and its exact energy
//!   error on an oscillator.
//! * [`sensors`] — SplitMix64 noise, quantizing encoders, a torque sensor.
//! * [`friction`] — elasto-plastic friction with the Stribeck level of
//!   eq. (4.7)/(4.8).
//! * [`transmission`] — the simulated SHD-17-100.
//! * [`mrr`] — `n`-module robot dynamics (eq. 4.1–4.6) with a sampled
//!   controller hook.
//! * [`closed_loop`] — the chapter-4 experiments in closed loop (tracking
//!   with and without joint-torque feedback, Theorem 1's bound on random
//!   cases, the passive mode, the payload drop, the mode manager).
//! * [`door`] — door opening with the compact wrist (§6.4.4).
//! * [`wrist_bench`] — the wrist alone: active tracking and a finger
//!   pushing it with the motors off or in admittance-passive mode
//!   (§6.4.2–6.4.3).
//! * `engine` (feature `engine`) — mechanisms on the rapier3d engine that
//!   check the wrist's kinematics and force mapping.
//! * [`experiments`] — the locked-output (Fig. 2.17–2.20), back-driven
//!   (Fig. 2.21–2.22) and torque-estimation (Table 3.3) experiments.

// Numerical code indexes several parallel arrays (state, stages, rows) by
// one index; iterator chains over four zipped slices would read worse.
#![allow(clippy::needless_range_loop)]

pub mod claims;
pub mod closed_loop;
pub mod door;
#[cfg(feature = "engine")]
pub mod engine;
pub mod experiments;
pub mod friction;
pub mod integrator;
pub mod mrr;
pub mod plants;
pub mod sensors;
pub mod transmission;
pub mod wrist_bench;

pub use friction::FrictionParams;
pub use integrator::Rk4;
pub use mrr::{Controller, ModuleParams, Mrr, Sensors};
pub use sensors::{Encoder, SplitMix64, TorqueSensor};
pub use transmission::{Backbone, BackboneShape, DrivePlantParams};
