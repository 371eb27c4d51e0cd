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
pub mod wrist;

pub use error::ParamError;
pub use scalar::{Scalar, I16F16};

/// Verification properties (see `proofs/mod.rs`), compiled for the test,
/// Kani and fuzz engines only.
#[cfg(any(kani, test, feature = "proofs"))]
#[doc(hidden)]
#[path = "../proofs/mod.rs"]
pub mod proofs;
