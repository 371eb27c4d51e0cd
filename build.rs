//! One named configuration for the one target family whose code differs.
//!
//! `armv6m` is set when building for an Arm core without 32-bit atomics
//! (Armv6-M: Cortex-M0/M0+/M1): no hardware divide, no long multiply, no
//! floating-point unit. The scalar backends and kernels (`src/scalar/`)
//! choose their instruction sequences on it; nothing else in the crate
//! reads the target.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(armv6m)");
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let atomics = std::env::var("CARGO_CFG_TARGET_HAS_ATOMIC").unwrap_or_default();
    if arch == "arm" && !atomics.split(',').any(|w| w == "32") {
        println!("cargo::rustc-cfg=armv6m");
    }
    println!("cargo::rerun-if-changed=build.rs");
}
