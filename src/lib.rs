#![doc = include_str!("../README.md")]
#![cfg_attr(not(any(feature = "std", test)), no_std)]

pub mod error;
pub mod scalar;

pub use error::ParamError;
pub use scalar::{Scalar, I16F16};

#[cfg(any(kani, test))]
#[path = "../proofs/mod.rs"]
mod proofs;
