//! Fuzz the sign and saturation functions (thesis eqs. 2.17, 4.18) on every
//! backend with arbitrary bit patterns: no panic, and the same properties the
//! Kani and exhaustive engines check (`proofs/sat_sgn.rs`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::sat_sgn::*;
use mrr_control::scalar::{Scalar, I16F16};

fn check<S: Scalar>(x: S, y: S, x_next: Option<S>) {
    assert!(sgn_exact(x).holds, "sgn({x:?})");
    assert!(sat_in_range(x, y).holds, "sat({x:?}, {y:?}) out of range");
    assert!(
        sat_matches_definition(x, y).holds,
        "sat({x:?}, {y:?}) off the definition"
    );
    assert!(sat_odd(x, y).holds, "sat({x:?}, {y:?}) not odd");
    if let Some(xn) = x_next {
        assert!(
            sat_monotone_step(x, xn, y).holds,
            "sat step at {x:?}, {y:?}"
        );
    }
}

fuzz_target!(|data: [u64; 2]| {
    let [a, b] = data;
    let (x32, y32) = (f32::from_bits(a as u32), f32::from_bits(b as u32));
    check(
        x32,
        y32,
        (x32.is_finite() && x32 < f32::MAX).then(|| next_up(x32)),
    );
    let (x64, y64) = (f64::from_bits(a), f64::from_bits(b));
    let next64 = (x64.is_finite() && x64 < f64::MAX).then(|| {
        if x64 == 0.0 {
            f64::from_bits(1)
        } else if x64 > 0.0 {
            f64::from_bits(x64.to_bits() + 1)
        } else {
            f64::from_bits(x64.to_bits() - 1)
        }
    });
    check(x64, y64, next64);
    let (xf, yf) = (I16F16::from_bits(a as i32), I16F16::from_bits(b as i32));
    let nextf = (xf < I16F16::MAX).then(|| I16F16::from_bits(xf.to_bits() + 1));
    check(xf, yf, nextf);
});
