//! Kernel accuracy and speed report.
//!
//! For every kernel and backend: the largest error seen on a dense sweep of
//! its domain against the `f64` reference of the platform's C library (the
//! *proven* bounds come from the exhaustive engine, see docs/verification.md), and the host
//! time per call (x86 host numbers, for orientation only; target instruction
//! counts are measured separately). Then the fixed-point unit table.
//!
//! Run: `cargo run --release --example kernel_report`

use mrr_control::scalar::q15::{self, BinaryAngle, Q15};
use mrr_control::scalar::{kernels, units, Scalar, I16F16};
use std::hint::black_box;
use std::time::Instant;

struct Kernel {
    name: &'static str,
    reference: fn(f64) -> f64,
    f32: fn(f32) -> f32,
    fixed: fn(I16F16) -> I16F16,
    /// Sweep interval for the report.
    lo: f64,
    hi: f64,
}

fn ulp_f32(got: f32, r: f64) -> f64 {
    let e = if r == 0.0 {
        -126
    } else {
        (r.abs().log2().floor() as i32).clamp(-126, 127)
    };
    (got as f64 - r).abs() / 2f64.powi(e - 23)
}

fn time_per_call<T: Copy>(inputs: &[T], f: impl Fn(T) -> T) -> f64 {
    let t = Instant::now();
    let mut reps = 0u32;
    while t.elapsed().as_millis() < 50 {
        for &x in inputs {
            black_box(f(black_box(x)));
        }
        reps += 1;
    }
    t.elapsed().as_nanos() as f64 / (reps as f64 * inputs.len() as f64)
}

fn main() {
    let kernels: [Kernel; 7] = [
        Kernel {
            name: "atan",
            reference: f64::atan,
            f32: kernels::f32::atan,
            fixed: kernels::i16f16::atan,
            lo: -100.0,
            hi: 100.0,
        },
        Kernel {
            name: "tan",
            reference: f64::tan,
            f32: kernels::f32::tan,
            fixed: kernels::i16f16::tan,
            lo: -1.5,
            hi: 1.5,
        },
        Kernel {
            name: "exp",
            reference: f64::exp,
            f32: kernels::f32::exp,
            fixed: kernels::i16f16::exp,
            lo: -10.0,
            hi: 10.0,
        },
        Kernel {
            name: "sin",
            reference: f64::sin,
            f32: kernels::f32::sin,
            fixed: kernels::i16f16::sin,
            lo: -700.0,
            hi: 700.0,
        },
        Kernel {
            name: "cos",
            reference: f64::cos,
            f32: kernels::f32::cos,
            fixed: kernels::i16f16::cos,
            lo: -700.0,
            hi: 700.0,
        },
        Kernel {
            name: "acos",
            reference: f64::acos,
            f32: kernels::f32::acos,
            fixed: kernels::i16f16::acos,
            lo: -1.0,
            hi: 1.0,
        },
        Kernel {
            name: "sqrt",
            reference: f64::sqrt,
            f32: kernels::f32::sqrt,
            fixed: kernels::i16f16::sqrt,
            lo: 0.0,
            hi: 1e4,
        },
    ];
    const N: usize = 1 << 20;
    println!(
        "Kernel accuracy on a {N}-point sweep (reference: platform f64) and x86 host time per call"
    );
    println!(
        "{:<6} {:<22} {:>14} {:>10} {:>16} {:>10}",
        "kernel", "sweep", "f32 max ulp", "f32 ns", "I16F16 max LSB", "I16F16 ns"
    );
    for k in &kernels {
        let xs: Vec<f64> = (0..N)
            .map(|i| k.lo + (k.hi - k.lo) * i as f64 / (N - 1) as f64)
            .collect();
        let (mut e32, mut efx) = (0.0f64, 0.0f64);
        let xs32: Vec<f32> = xs.iter().map(|&x| x as f32).collect();
        let xsfx: Vec<I16F16> = xs.iter().map(|&x| I16F16::from_f64(x)).collect();
        for i in 0..N {
            e32 = e32.max(ulp_f32((k.f32)(xs32[i]), (k.reference)(xs32[i] as f64)));
            let r = (k.reference)(xsfx[i].to_f64());
            if r.abs() < 32767.0 {
                efx = efx.max(((k.fixed)(xsfx[i]).to_f64() - r).abs() * 65536.0);
            }
        }
        let t32 = time_per_call(&xs32[..4096], k.f32);
        let tfx = time_per_call(&xsfx[..4096], k.fixed);
        println!(
            "{:<6} [{:>8}, {:>8}]   {:>14.3} {:>10.2} {:>16.3} {:>10.2}",
            k.name, k.lo, k.hi, e32, t32, efx, tfx
        );
    }

    println!();
    println!("Q15 kernels over all 2^16 inputs (angles: binary, 2^16 codes per turn)");
    println!("{:<8} {:>14} {:>10}", "kernel", "max err (LSB)", "ns/call");
    let codes: Vec<i16> = (i16::MIN..=i16::MAX).collect();
    let lsb = 1.0 / 32768.0;
    let angle = |c: i16| BinaryAngle::from_bits(c);
    let q = |c: i16| Q15::from_bits(c);
    type Q15Row<'a> = (&'a str, Box<dyn Fn(i16) -> f64>, Box<dyn Fn(i16) -> f64>);
    let rows: Vec<Q15Row> = vec![
        (
            "sin",
            Box::new(move |c| q15::to_f64(q15::sin(angle(c)))),
            Box::new(move |c| angle(c).to_radians().sin()),
        ),
        (
            "cos",
            Box::new(move |c| q15::to_f64(q15::cos(angle(c)))),
            Box::new(move |c| angle(c).to_radians().cos()),
        ),
        (
            "atan",
            Box::new(move |c| q15::to_f64(q15::atan(q(c)))),
            Box::new(move |c| q15::to_f64(q(c)).atan()),
        ),
        (
            "sqrt",
            Box::new(move |c| q15::to_f64(q15::sqrt(q(c)))),
            Box::new(move |c| q15::to_f64(q(c)).max(0.0).sqrt()),
        ),
        (
            "exp_neg",
            Box::new(move |c| q15::to_f64(q15::exp_neg(q(c)))),
            Box::new(move |c| q15::to_f64(q(c)).min(0.0).exp().min(q15::to_f64(q15::MAX))),
        ),
    ];
    for (name, kernel, reference) in &rows {
        let err = codes
            .iter()
            .map(|&c| (kernel(c) - reference(c)).abs() / lsb)
            .fold(0.0, f64::max);
        let t = time_per_call(&codes[..4096], |c| {
            black_box(kernel(c));
            c
        });
        println!("{name:<8} {err:>14.3} {t:>10.2}");
    }

    println!();
    println!("Fixed-point (I16F16) unit scales and the quantization of the thesis's values");
    println!(
        "{:<16} {:<14} {:>12} {:>12}  relative quantization error of thesis values",
        "quantity", "stored unit", "range (SI)", "LSB (SI)"
    );
    for q in units::QUANTITIES {
        let errs: Vec<String> = q
            .thesis_values
            .iter()
            .map(|&(v, src)| {
                format!(
                    "{v:e} ({src}): {:.1e}",
                    units::relative_quantization_error::<I16F16>(v, q.scale)
                )
            })
            .collect();
        println!(
            "{:<16} {:<14} {:>12.4e} {:>12.3e}  {}",
            q.name,
            q.unit,
            32768.0 / q.scale,
            1.0 / 65536.0 / q.scale,
            errs.join("; ")
        );
    }
}
