//! A plant family the library did not write (DESIGN.md, "Evidence").
//!
//! The drive plants of [`transmission`](super::transmission) are built
//! from the shapes they are used to test (eq. 2.11's backbone, eq. 2.29's
//! bearing compliance). The plants here are written from their own
//! physics and call no model of `harmonic_drive`, `estimation` or
//! `control` (a test in `tests/claims.rs` scans these sources):
//!
//! | element | shapes | calibrated to (thesis §2.4 unless noted) |
//! |---|---|---|
//! | flexspline backbone | rounded-knee `ln cosh` integral, monotone Hermite spline, quadratic stiffening | `K1 = 8.4e3`, `K2 = 9.4e3` N·m/rad, `T1 = 3.9`, `T2 = 12` N·m; `K3 = 1.3e4` assumed |
//! | bearing compliance | hyperbolic saturation, bilinear play + stop | its share of `Ψ = 2.9e-4` rad |
//! | mesh friction (node) | Maxwell-slip, 4 elements | break-away `N τ_fs = 1.2` or `τ_fb = 2.0` N·m |
//! | flexspline hysteresis | Maxwell-slip, 4 elements | the rest of `Ψ` |
//! | kinematic error | wave-generator harmonics 1–4, tooth-pass ripple, output eccentricity | Table 3.2 magnitudes, Table 3.1 bound 4.4e-4 rad p-p |
//! | sensors | quantizing encoders (2000 and 2^17 counts/rev), torque sensor 1/376 N·m, ±2 % torque constant | §3.2 (Mini45) ; counts assumed |
//!
//! The dynamic joint of [`joint`] (rotor, drive, link, payload, 4 ms
//! sensors) reuses the backbone, hysteresis and kinematic-error elements
//! with an asymmetric Maxwell-slip motor friction for chapters 3–4.
//!
//! What the thesis leaves open is swept, not picked: the Fig. 2.17
//! amplitude, the split of `Ψ` between the mesh/bearing mechanism and the
//! flexspline, the mesh break-away between the two measured torques, the
//! backbone and bearing shapes and the ripple ([`drive::family`]).
//!
//! Left out on purpose or for now: the motor's own brush friction between
//! the torque command and the bearing (only a ±2 % torque-constant error
//! separates them), the position controller's finite stiffness in the
//! held-input test (the input is held rigidly), and any rate dependence
//! (the plant is quasi-static and rate-independent).

pub mod drive;
pub mod elements;
pub mod joint;

pub use drive::{family, quick_family, DrivePlant, Sample};
pub use joint::{joint_family, quick_joint_family, JointPlant};
