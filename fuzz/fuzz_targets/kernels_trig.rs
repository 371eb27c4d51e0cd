//! Fuzz the trigonometric kernels (sin, cos, sin_cos, tan) of every backend
//! with arbitrary bit patterns: no panic, and the bounds the exhaustive
//! engine proves (the same property bodies, `proofs/kernels_*.rs`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::{kernels_f32 as f, kernels_i16f16 as x, kernels_q15 as q};
use mrr_control::scalar::I16F16;

fuzz_target!(|data: (u32, i32, i16)| {
    let (a, b, c) = data;
    let v = f32::from_bits(a);
    for (name, verdict) in [
        ("f32 sin", f::sin_within_bound(v)),
        ("f32 cos", f::cos_within_bound(v)),
        ("f32 sin_cos", f::sin_cos_consistent_and_symmetric_at(v)),
        ("f32 tan", f::tan_within_bound(v)),
        ("I16F16 sin", x::sin_within_bound(I16F16::from_bits(b))),
        ("I16F16 cos", x::cos_within_bound(I16F16::from_bits(b))),
        (
            "I16F16 sin_cos",
            x::sin_cos_is_sin_and_cos(I16F16::from_bits(b)),
        ),
        ("I16F16 tan", x::tan_within_bound(I16F16::from_bits(b))),
        ("Q15 sin", q::sin_within_bound(c)),
        ("Q15 cos", q::cos_within_bound(c)),
        ("Q15 sin_cos", q::sin_cos_matches(c)),
    ] {
        assert!(
            verdict.holds,
            "{name} at {a:#x}/{b}/{c}: error {}",
            verdict.error
        );
    }
});
