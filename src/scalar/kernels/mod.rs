//! Math kernels, one module per backend.
//!
//! Every kernel states its domain, its saturated value outside the domain and
//! its error bound; the bounds are proven by the properties in `proofs/`
//! (see the kernel table in [`docs::verification`](crate::docs::verification#kernel-bounds)
//! for the engine and the command that reproduces each one).

pub mod f32;
pub mod f64;
pub mod i16f16;
