//! Fuzz the exponential and square-root kernels of every backend with
//! arbitrary bit patterns: no panic, and the proven bounds.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::{kernels_f32 as f, kernels_i16f16 as x, kernels_q15 as q};
use mrr_control::scalar::I16F16;

fuzz_target!(|data: (u32, i32, i16)| {
    let (a, b, c) = data;
    let v = f32::from_bits(a);
    let y = I16F16::from_bits(b);
    for (name, verdict) in [
        ("f32 exp", f::exp_within_bound(v)),
        ("f32 sqrt", f::sqrt_correctly_rounded(v)),
        ("I16F16 exp", x::exp_within_bound(y)),
        ("I16F16 sqrt", x::sqrt_within_bound(y)),
        ("Q15 exp_neg", q::exp_neg_within_bound(c)),
        ("Q15 sqrt", q::sqrt_correctly_rounded(c)),
    ] {
        assert!(verdict.holds, "{name} at {data:?}: error {}", verdict.error);
    }
});
