//! Fuzz the inverse trigonometric kernels (atan, atan2, acos; on I16F16
//! also atan_small, hypot_unit, unit_vector and rsqrt_quarter) of every backend with arbitrary bit
//! patterns: no panic, and the proven bounds.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::{kernels_f32 as f, kernels_i16f16 as x, kernels_q15 as q};
use mrr_control::scalar::I16F16;

fuzz_target!(|data: (u32, u32, i32, i32, i16, i16)| {
    let (a, a2, b, b2, c, c2) = data;
    let (v, w) = (f32::from_bits(a), f32::from_bits(a2));
    let (y, z) = (I16F16::from_bits(b), I16F16::from_bits(b2));
    for (name, verdict) in [
        ("f32 atan", f::atan_within_bound(v)),
        ("f32 atan2", f::atan2_within_bound(v, w)),
        ("f32 acos", f::acos_within_bound(v)),
        ("I16F16 atan", x::atan_within_bound(y)),
        ("I16F16 atan2", x::atan2_within_bound(y, z)),
        ("I16F16 acos", x::acos_within_bound(y)),
        ("I16F16 atan_small", x::atan_small_within_bound(y)),
        ("I16F16 hypot_unit", x::hypot_unit_within_bound(y, z)),
        ("I16F16 unit_vector", x::unit_vector_within_bound(y, z)),
        ("I16F16 rsqrt_quarter", x::rsqrt_quarter_within_bound(y)),
        ("Q15 atan", q::atan_within_bound(c)),
        ("Q15 atan2", q::atan2_within_bound(c, c2)),
    ] {
        assert!(verdict.holds, "{name} at {data:?}: error {}", verdict.error);
    }
});
