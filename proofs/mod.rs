//! Verification properties of `mrr-control`.
//!
//! Each property is a plain function of its inputs, written once, and run by
//! every engine that can reach it (DESIGN.md, "one harness, several engines"):
//!
//! 1. **Kani** — `#[cfg_attr(kani, kani::proof)]` entries that draw inputs
//!    with `kani::any()`; run with `cargo kani` where Kani is installed.
//! 2. **Exhaustive** — the same body over *every* input of a type
//!    (`engine::exhaustive_u32`); a complete proof for that type. These are
//!    `#[ignore]`d unit tests named `exhaustive_*`, run in release:
//!    `cargo test --release --lib -- --ignored exhaustive --test-threads 1 --nocapture`.
//!    CI runs them through `proofs/proof_cache.py`, which fingerprints each
//!    proof by the LLVM IR its test reaches in the release test binary and
//!    runs only those whose fingerprint is not in `proofs/exhaustive-record.tsv`
//!    (the others are cited with their recorded bounds, commit and time).
//! 3. **Random** — proptest strategies over physically meaningful ranges, run
//!    by plain `cargo test`.
//!
//! Every `kani::assume` says whether it is a *precondition* of the property
//! or a *solver budget* (a restriction only to keep the proof tractable).

#![allow(dead_code)]

pub mod compliance;
pub mod control;
pub mod engine;
pub mod estimator_sizes;
pub mod joint_step;
pub mod kernels_f32;
pub mod kernels_f64;
pub mod kernels_i16f16;
pub mod kernels_q15;
pub mod kernels_turn;
pub mod law_budget;
pub mod sat_sgn;
#[cfg(kani)]
pub mod uninterpreted;
pub mod wrist_ik;
