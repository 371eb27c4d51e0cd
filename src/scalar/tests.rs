use super::sealed::Sealed;
use super::*;

/// Coefficients beyond 2^40 saturate every non-zero product instead of
/// overflowing the 64-bit intermediate (found by fuzzing the control
/// configurations), and their `f32` value stays finite.
#[test]
fn gain_with_an_exact_value_equals_the_coefficient_product() {
    let mut xs: Vec<i32> = vec![
        0,
        1,
        -1,
        i32::MAX,
        i32::MIN,
        1 << 15,
        -(1 << 15),
        32767,
        -32769,
    ];
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    for _ in 0..20_000 {
        let v = xorshift64(&mut state) as u32;
        xs.push((v as i32) >> (v % 24));
    }
    for value in [
        120.0,
        10.0,
        100.0,
        20.0,
        0.01f64,
        0.5,
        -3.25,
        1.0 / 65536.0,
        32767.0,
        1e-3,
        0.1,
    ] {
        let g = Gain::<I16F16>::new(value);
        let c = Coef::new(value);
        let q = c.quantized();
        let exact = q != 0.0 && I16F16::from_f64(q).to_f64() == q;
        assert_eq!(g.exact.is_some(), exact, "{value}");
        for &x in &xs {
            let x = I16F16::from_bits(x);
            assert_eq!(g.apply(x), x.mul_coef(&c), "{value} {x}");
        }
        let gf = Gain::<f32>::new(value);
        assert!(gf.exact.is_none());
        assert_eq!(gf.apply(1.5f32), 1.5f32.mul_coef(&c));
    }
}

/// `Scalar::exp_neg_abs` on every backend: even, in `[0, 1]`, equal to
/// `exp(−|x|)` of the same backend (bit for bit for `f64`; within
/// 1 LSB for `I16F16`), and against the `f64` exponential for the value
/// (`f32`: within its 2 ulp up to the flush threshold, 0 above).
#[test]
fn exp_neg_abs_is_the_exponential_of_minus_the_magnitude() {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut xs: Vec<f64> = vec![0.0, 1e-9, 0.25, 1.0, 5.0, 11.7, 11.8, 30.0, 87.0, 88.0, 1e3];
    for _ in 0..5_000 {
        let u = (xorshift64(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
        xs.push(u * u * 100.0);
    }
    for &m in &xs {
        for x in [m, -m] {
            let want = (-m).exp();
            // f64: the libm exponential of −|x|, within 1e-15 relative.
            let d = Scalar::exp_neg_abs(x);
            assert_eq!(d.to_bits(), Scalar::exp(-m).to_bits(), "f64 {x}");
            assert!((d - want).abs() <= 1e-15 * want, "f64 {x}");
            // f32: within 2 ulp of e^{−|x|} up to the threshold, 0 above.
            let xf = x as f32;
            let mf = xf.abs();
            let f = Scalar::exp_neg_abs(xf);
            assert_eq!(f.to_bits(), Scalar::exp_neg_abs(-xf).to_bits(), "f32 {x}");
            if mf <= kernels::f32::EXP_NEG_ABS_MAX_ARG {
                let r = (-(mf as f64)).exp();
                assert!(
                    ((f as f64) - r).abs()
                        <= 2.0 * r * f32::EPSILON as f64 + 2.0 * f64::from(f32::from_bits(1)),
                    "f32 {x}"
                );
            } else {
                assert_eq!(f.to_bits(), 0, "f32 {x}");
            }
            // I16F16: its own kernel, even, within 1 LSB of e^{−|x|}
            // (the argument quantized first) and of `exp(−|x|)`.
            if m < 32767.0 {
                let q = I16F16::from_f64(x);
                let e = Scalar::exp_neg_abs(q);
                // Both within 1 LSB of e^{−|x|}, `exp_neg_abs` within
                // 0.531 (exhaustive maxima): they differ by less than
                // 2 LSB, so by at most 1 in whole words.
                let via_exp = Scalar::exp(q.abs().neg());
                assert!((e.to_bits() - via_exp.to_bits()).abs() <= 1, "I16F16 {x}");
                assert_eq!(e, Scalar::exp_neg_abs(q.neg()), "I16F16 {x}");
                let r = (-q.to_f64().abs()).exp();
                assert!((e.to_f64() - r).abs() <= 1.0 / 65536.0, "I16F16 {x}");
                assert!(e >= I16F16::ZERO && e <= I16F16::ONE, "I16F16 {x}");
            }
        }
    }
    // NaN → 1 on floats; the extremes of I16F16 (|MIN| saturates).
    assert_eq!(Scalar::exp_neg_abs(f32::NAN), 1.0);
    assert_eq!(Scalar::exp_neg_abs(f64::NAN), 1.0);
    assert_eq!(Scalar::exp_neg_abs(f64::INFINITY), 0.0);
    assert_eq!(Scalar::exp_neg_abs(I16F16::MIN), I16F16::ZERO);
    assert_eq!(Scalar::exp_neg_abs(I16F16::MAX), I16F16::ZERO);
    assert_eq!(Scalar::exp_neg_abs(I16F16::ZERO), I16F16::ONE);
}

#[test]
fn huge_coefficients_saturate() {
    for v in [2f64.powi(41), 1e15, 1e300, f64::MAX] {
        for sign in [1.0, -1.0] {
            let c = Coef::new(sign * v);
            for x in [1i64, -1, 1 << 31, -(1 << 31), 12345] {
                let want = if (x > 0) == (sign > 0.0) {
                    i32::MAX
                } else {
                    i32::MIN
                };
                assert_eq!(c.scale_int(x, 16), want, "{v} {x}");
                assert_eq!(c.scale_int(x, 0), want, "{v} {x}");
            }
            assert_eq!(c.scale_int(0, 16), 0);
            assert!(c.f32_value().is_finite());
            let y = I16F16::from_bits(3).mul_coef(&c);
            assert_eq!(y, if sign > 0.0 { I16F16::MAX } else { I16F16::MIN });
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(20_000))]
    /// The 32-bit `scale_int` equals the 64-bit formula for coefficients
    /// over the whole prepared range (2^-60 … beyond 2^40), both signs,
    /// both `extra` values, any count up to and beyond ±2^31.
    #[test]
    fn scale_int_equals_the_64_bit_formula(
        mant in 1.0f64..2.0, exp in -62i32..45, neg: bool,
        x in proptest::prelude::any::<i64>(), narrow in 0u32..3, extra16: bool,
    ) {
        let c = Coef::new(if neg { -mant } else { mant } * 2f64.powi(exp));
        let x = match narrow { 0 => x >> 33, 1 => x >> 50, _ => x };
        let extra = if extra16 { 16 } else { 0 };
        proptest::prop_assert_eq!(c.scale_int(x, extra), c.scale_int_reference(x, extra));
        let x32 = x as i32;
        proptest::prop_assert_eq!(c.scale_i32(x32), c.scale_int_reference(x32 as i64, 0));
        if let Some(s) = &c.signed {
            proptest::prop_assert_eq!(Coef::scale_i32_split(s, x32), c.scale_int_reference(x32 as i64, 0));
        }
    }
}

#[test]
fn scale_int_equals_the_64_bit_formula_on_edges() {
    let mut xs = vec![
        0i64,
        1,
        -1,
        1 << 31,
        -(1 << 31),
        (1 << 31) - 1,
        i64::MAX,
        i64::MIN,
    ];
    for k in 0..31 {
        xs.extend([1i64 << k, -(1i64 << k), (1i64 << k) + 1, -(1i64 << k) - 1]);
    }
    for e in -62..=45 {
        for m in [1.0, 1.5, 2.0 - 1e-12] {
            for sign in [1.0, -1.0] {
                let c = Coef::new(sign * m * 2f64.powi(e));
                for &x in &xs {
                    for extra in [0, 16] {
                        assert_eq!(
                            c.scale_int(x, extra),
                            c.scale_int_reference(x, extra),
                            "{e} {m} {x} {extra}"
                        );
                    }
                    let x32 = x as i32;
                    assert_eq!(
                        c.scale_i32(x32),
                        c.scale_int_reference(x32 as i64, 0),
                        "{e} {m} {x32}"
                    );
                }
            }
        }
    }
}

/// `mul_int` is `mul_coef` by the same integer, bit for bit, on every
/// backend, at edge words and both ends of the fitting range.
#[test]
fn mul_int_equals_mul_coef_by_the_integer() {
    let mut xs = vec![0i32, 1, -1, i32::MAX, i32::MIN, i32::MIN + 1];
    for k in 0..31 {
        xs.extend([1i32 << k, -(1i32 << k), (1i32 << k) - 1, -(1i32 << k) + 1]);
    }
    for n in [
        1.0,
        2.0,
        3.0,
        50.0,
        100.0,
        101.0,
        160.0,
        32768.0,
        65535.0,
        1e6,
        2147483647.0,
    ] {
        let f = IntFactor::new(n);
        let mut all = xs.clone();
        all.extend([
            f.high,
            f.high.saturating_add(1),
            f.low,
            f.low.saturating_sub(1),
        ]);
        for &x in &all {
            let v = I16F16::from_bits(x);
            assert_eq!(v.mul_int(&f), v.mul_coef(&f.coef), "{n} {x}");
            let y = x as f32 * 1e-3;
            assert_eq!(y.mul_int(&f), y.mul_coef(&f.coef), "{n} {y}");
        }
    }
}

/// The coefficient classes `scale_i32` prepares apart (zero, below
/// 2⁻³², a mantissa rounded up to 2³¹, 2³⁰ and beyond) against the
/// 64-bit formula, and `scale_wide` against the exact product, at
/// every edge argument.
#[test]
fn scale_i32_and_scale_wide_on_every_coefficient_class() {
    let mut xs = vec![0i32, 1, -1, 2, -2, 3, i32::MAX, i32::MIN, i32::MIN + 1];
    for k in 0..31 {
        xs.extend([
            1i32 << k,
            -(1i32 << k),
            (1i32 << k).wrapping_add(1),
            -(1i32 << k) - 1,
        ]);
    }
    let mut values = vec![0.0, f64::NAN, f64::INFINITY, 1e-300, -1e-300];
    for e in -100..=60 {
        for m in [1.0, 1.5, 2.0 - 1e-12, 2.0 - 1e-9] {
            values.extend([m * 2f64.powi(e), -m * 2f64.powi(e)]);
        }
    }
    let mut halved = 0;
    for &v in &values {
        let c = Coef::new(v);
        if c.mag == 1 << 31 && c.signed.is_some() {
            halved += 1;
        }
        for &x in &xs {
            assert_eq!(
                c.scale_i32(x),
                c.scale_int_reference(x as i64, 0),
                "{v} {x}"
            );
            if let Some(s) = &c.signed {
                assert_eq!(
                    Coef::scale_i32_split(s, x),
                    c.scale_int_reference(x as i64, 0),
                    "split {v} {x}"
                );
            }
            for extra in [0, 16, 32] {
                assert_eq!(
                    c.scale_wide(x, extra),
                    scale_wide_reference(&c, x, extra),
                    "{v} {x} {extra}"
                );
                assert_eq!(
                    c.scale_wide_split(x, extra),
                    scale_wide_reference(&c, x, extra),
                    "split {v} {x} {extra}"
                );
                assert_eq!(
                    c.scale_wide_magnitude(x, extra),
                    scale_wide_reference(&c, x, extra),
                    "magnitude {v} {x} {extra}"
                );
            }
        }
    }
    // The halved-mantissa form was exercised.
    assert!(halved > 10, "{halved}");
}

fn sat_examples<S: Scalar>() {
    let f = S::from_f64;
    let eps = f(0.5);
    assert_eq!(f(2.0).sat(eps), S::ONE);
    assert_eq!(f(-2.0).sat(eps), S::ONE.neg());
    assert_eq!(f(0.25).sat(eps), f(0.5));
    assert_eq!(f(-0.25).sat(eps), f(-0.5));
    assert_eq!(S::ZERO.sat(S::ZERO), S::ZERO);
    // y <= 0: thesis condition |x| > y holds for every x != 0.
    assert_eq!(f(0.001).sat(f(-1.0)), S::ONE);
    assert_eq!(f(-0.001).sat(S::ZERO), S::ONE.neg());
}

#[test]
fn sat_matches_hand_values_on_every_backend() {
    sat_examples::<f32>();
    sat_examples::<f64>();
    sat_examples::<I16F16>();
}

proptest::proptest! {
    /// `from_counts` on I16F16 is the correctly rounded product within
    /// the 31-bit precision of the prepared factor: |error| ≤ ½ LSB plus
    /// |counts·factor|·2⁻³⁰ (relative error of the multiplier).
    #[test]
    fn from_counts_is_rounded_product(
        counts in -(1i64 << 31)..(1i64 << 31),
        mant in 1.0f64..2.0, exp in -40i32..10,
    ) {
        let factor = mant * 2f64.powi(exp);
        let sc = Coef::new(factor);
        let exact = counts as f64 * factor;
        proptest::prop_assume!(exact.abs() < 32767.0);
        let got = I16F16::from_counts(counts, &sc).to_f64();
        let bound = 0.5 / 65536.0 + exact.abs() * 2f64.powi(-30);
        proptest::prop_assert!((got - exact).abs() <= bound, "{got} vs {exact}");
    }
}

/// `from_counts_i32` against the 64-bit count formula
/// (`scale_int_reference` with 16 extra bits) of the unshifted factor,
/// and against `from_counts`, on every backend.
fn check_from_counts_i32(counts: i32, factor: f64) {
    let cc = CountCoef::new(factor);
    let want = cc.coef().scale_int_reference(counts as i64, 16);
    let got = I16F16::from_counts_i32(counts, &cc);
    assert_eq!(got.to_bits(), want, "{counts} × {factor}");
    assert_eq!(got, I16F16::from_counts(counts as i64, cc.coef()));
    assert_eq!(
        f32::from_counts_i32(counts, &cc).to_bits(),
        f32::from_counts(counts as i64, cc.coef()).to_bits()
    );
    assert_eq!(
        f64::from_counts_i32(counts, &cc).to_bits(),
        f64::from_counts(counts as i64, cc.coef()).to_bits()
    );
}

#[test]
fn from_counts_i32_equals_the_count_product_at_the_edges() {
    // Small counts, the 16-bit edge, the `i32` ends and counts whose
    // `f32` conversion rounds (halfway cases of the 24-bit mantissa).
    let counts = [
        0,
        1,
        -1,
        2,
        -2,
        3,
        1 << 15,
        -(1 << 15),
        i32::MAX,
        i32::MIN,
        i32::MIN + 1,
        (1 << 24) + 1,
        (1 << 25) + 2,
        (1 << 25) + 6,
        -(1 << 25) - 2,
        (1 << 30) + (1 << 6) + 1,
    ];
    // Zero, a mantissa rounded up to 2³¹ (just below a power of two),
    // the range ends of `Coef::new`, factors whose `2¹⁶` multiple
    // reaches `2³⁰` (the unit products) and ordinary ones.
    let factors = [
        0.0,
        1.0,
        -1.0,
        2.0 - 1e-12,
        -(2.0 - 1e-12),
        1e-18,
        1e-13,
        3e-5,
        0.5 / 65536.0,
        1.0 / 65536.0,
        2f64.powi(14),
        2f64.powi(14) * (1.0 - 1e-12),
        -(2f64.powi(14)),
        2f64.powi(40),
        1e13,
        0.001_234_567,
        -7.25,
    ];
    for c in counts {
        for f in factors {
            check_from_counts_i32(c, f);
        }
    }
}

/// `from_counts_prepared` against `from_counts` (itself tested against
/// the 64-bit count formula) on every backend.
fn check_from_counts_prepared(counts: i64, factor: f64) {
    let cc = CountCoef::new(factor);
    assert_eq!(
        I16F16::from_counts_prepared(counts, &cc),
        I16F16::from_counts(counts, cc.coef()),
        "{counts} × {factor}"
    );
    assert_eq!(
        I16F16::from_counts_prepared(counts, &cc).to_bits(),
        cc.coef().scale_int_reference(counts, 16)
    );
    assert_eq!(
        f32::from_counts_prepared(counts, &cc).to_bits(),
        f32::from_counts(counts, cc.coef()).to_bits()
    );
    assert_eq!(
        f64::from_counts_prepared(counts, &cc).to_bits(),
        f64::from_counts(counts, cc.coef()).to_bits()
    );
}

#[test]
fn from_counts_prepared_equals_the_count_product_at_the_edges() {
    let t = 1i64 << 31;
    let counts = [
        0,
        1,
        -1,
        t - 1,
        t,
        t + 1,
        -t,
        -t - 1,
        -t + 1,
        1 << 32,
        -(1 << 32),
        1 << 47,
        i64::MAX,
        i64::MIN,
    ];
    let factors = [
        0.0,
        1.0,
        -1.0,
        2.0 - 1e-12,
        1e-18,
        1e-13,
        0.5 / 65536.0,
        3e-6,
        2f64.powi(14),
        2f64.powi(40),
        -7.25,
    ];
    for c in counts {
        for f in factors {
            check_from_counts_prepared(c, f);
        }
    }
}

proptest::proptest! {
    #[test]
    fn from_counts_prepared_equals_the_count_product(
        bits in proptest::prelude::any::<i64>(), sh in 0u32..40,
        mant in 1.0f64..2.0, exp in -60i32..42, neg: bool,
    ) {
        check_from_counts_prepared(bits >> sh, if neg { -mant } else { mant } * 2f64.powi(exp));
    }
}

proptest::proptest! {
    #[test]
    fn from_counts_i32_equals_the_count_product(
        counts in proptest::prelude::any::<i32>(),
        mant in 1.0f64..2.0, exp in -60i32..42, neg: bool,
    ) {
        check_from_counts_i32(counts, if neg { -mant } else { mant } * 2f64.powi(exp));
    }
}

proptest::proptest! {
    /// `mul_coef` on I16F16: |error| ≤ ½ LSB + |x·c|·2⁻³⁰.
    #[test]
    fn mul_coef_is_rounded_product(
        bits in proptest::prelude::any::<i32>(), mant in 1.0f64..2.0, exp in -40i32..20, neg: bool,
    ) {
        let c = if neg { -mant } else { mant } * 2f64.powi(exp);
        let x = I16F16::from_bits(bits);
        let exact = x.to_f64() * c;
        proptest::prop_assume!(exact.abs() < 32767.0);
        let got = x.mul_coef(&Coef::new(c)).to_f64();
        let bound = 0.5 / 65536.0 + exact.abs() * 2f64.powi(-30);
        proptest::prop_assert!((got - exact).abs() <= bound, "{got} vs {exact}");
    }
}

proptest::proptest! {
    /// `dot_coef` on `I16F16` is the exact sum of the products with the
    /// row's mantissas, rounded once (ties up) and saturated, and
    /// within its stated bound of the exact sum with the given
    /// constants; on floats it is the sum of `mul_coef` products.
    #[test]
    fn dot_coef_is_the_once_rounded_sum(
        mant in proptest::collection::vec(-2.0f64..2.0, 6),
        exps in proptest::collection::vec(-40i32..30, 6),
        bits in proptest::collection::vec(proptest::prelude::any::<i32>(), 6),
        narrow in 0u32..28,
    ) {
        let c: [f64; 6] = core::array::from_fn(|j| mant[j] * 2f64.powi(exps[j]));
        let x: [I16F16; 6] = core::array::from_fn(|j| I16F16::from_bits(bits[j] >> narrow));
        let row = CoefRow::new(c);
        let (m, s) = row.fixed();
        proptest::prop_assert!(m.iter().all(|m| m.unsigned_abs() <= 1 << 28));
        let sum: i128 = (0..6).map(|j| x[j].to_bits() as i128 * m[j] as i128).sum();
        let want = if s > 0 { (sum + (1i128 << (s - 1))) >> s } else { sum << -s };
        let want = want.clamp(i32::MIN as i128, i32::MAX as i128) as i32;
        let got = I16F16::dot_coef(&x, &row);
        proptest::prop_assert_eq!(got.to_bits(), want);
        // Against the exact sum with the given constants (bits).
        let exact: f64 = (0..6).map(|j| x[j].to_bits() as f64 * c[j]).sum();
        let max = c.iter().fold(0.0f64, |a, c| a.max(c.abs()));
        let sx: f64 = x.iter().map(|x| (x.to_bits() as f64).abs()).sum();
        if exact.abs() < 2e9 {
            let bound = 0.5 + 2f64.powi(-28) * max * sx + 1e-9 * exact.abs();
            proptest::prop_assert!((got.to_bits() as f64 - exact).abs() <= bound, "{} vs {}", got.to_bits(), exact);
        }
        // Floats: the default, term by term.
        let xf: [f64; 6] = core::array::from_fn(|j| x[j].to_f64());
        let mut acc = 0.0f64;
        for j in 0..6 {
            acc += xf[j].mul_coef(&Coef::new(c[j]));
        }
        proptest::prop_assert_eq!(f64::dot_coef(&xf, &row), acc);
    }
}

/// Rows of zeros, of non-finite values (read as 0), of one huge and of
/// tiny constants keep the `I16F16` sum exact or saturated.
#[test]
fn dot_coef_edge_rows() {
    let one = I16F16::ONE;
    let x = [
        one,
        one.neg(),
        I16F16::MAX,
        I16F16::MIN,
        I16F16::ZERO,
        I16F16::DELTA,
    ];
    assert_eq!(I16F16::dot_coef(&x, &CoefRow::new([0.0; 6])), I16F16::ZERO);
    let nan = CoefRow::new([f64::NAN, f64::INFINITY, 0.0, 0.0, 0.0, 1.0]);
    assert_eq!(I16F16::dot_coef(&x, &nan), I16F16::DELTA);
    // 1·3 − 1·3 + 0·1e12 = 0 (beside 1e12 the 3s quantize to 0; the
    // rounding bound, 2⁻²⁸·1e12 per unit of x, allows it).
    let big = CoefRow::new([3.0, 3.0, 0.0, 0.0, 1e12, 0.0]);
    assert_eq!(I16F16::dot_coef(&x, &big), I16F16::ZERO);
    let sat = CoefRow::new([1e12, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(I16F16::dot_coef(&x, &sat), I16F16::MAX);
    assert_eq!(I16F16::dot_coef(&[one.neg(); 6], &sat), I16F16::MIN);
    // MAX·2 + MIN·2 = −2 LSB·… exactly: (2³¹ − 1)·2 − 2³¹·2 = −2 bits.
    let two = CoefRow::new([0.0, 0.0, 2.0, 2.0, 0.0, 0.0]);
    assert_eq!(I16F16::dot_coef(&x, &two).to_bits(), -2);
    // A constant far below the resolution: ½·2⁻¹⁶ rounds up (ties up).
    let half = CoefRow::new([0.0, 0.0, 0.0, 0.0, 0.0, 0.5]);
    assert_eq!(I16F16::dot_coef(&x, &half).to_bits(), 1);
    let tiny = CoefRow::new([1e-25; 6]);
    assert_eq!(I16F16::dot_coef(&x, &tiny), I16F16::ZERO);
}

/// `round(x·c·2^extra)` in exact (`i128`) arithmetic, saturated.
fn scale_wide_reference(c: &Coef, x: i32, extra: i32) -> i64 {
    let p = x as i128 * c.mult as i128;
    let sh = c.shift - extra;
    let r = if sh > 0 {
        if sh >= 126 {
            0
        } else {
            (p + (1i128 << (sh - 1))) >> sh
        }
    } else if -sh >= 64 {
        if p > 0 {
            i128::MAX
        } else if p < 0 {
            i128::MIN
        } else {
            0
        }
    } else {
        p << -sh
    };
    r.clamp(i64::MIN as i128, i64::MAX as i128) as i64
}

/// [`Scalar::integrate`] on `I16F16` in exact arithmetic: the Q16.48
/// sum (saturated), rounded to nearest with ties up, clamped (residual
/// 0 when the Q16.48 value leaves the box).
fn integrate_reference(
    v: I16F16,
    res: i32,
    x: I16F16,
    c: &Coef,
    lo: I16F16,
    hi: I16F16,
) -> (I16F16, i32) {
    let total = ((v.to_bits() as i128) << 32)
        + res as i128
        + scale_wide_reference(c, x.to_bits(), 32) as i128;
    let total = total.clamp(i64::MIN as i128, i64::MAX as i128);
    let (l, h) = ((lo.to_bits() as i128) << 32, (hi.to_bits() as i128) << 32);
    if total > h {
        return (hi, 0);
    }
    if total < l {
        return (lo, 0);
    }
    let q = (total + (1i128 << 31)) >> 32;
    (I16F16::from_bits(q as i32), (total - (q << 32)) as i32)
}

proptest::proptest! {
    #[test]
    fn scale_wide_is_the_exact_rounded_product(
        x in proptest::prelude::any::<i32>(),
        mant in 1.0f64..2.0,
        exp in -60i32..40,
        neg: bool,
        extra in 0i32..48,
    ) {
        let v = mant * 2f64.powi(exp) * if neg { -1.0 } else { 1.0 };
        let c = Coef::new(v);
        proptest::prop_assert_eq!(c.scale_wide(x, extra), scale_wide_reference(&c, x, extra));
        proptest::prop_assert_eq!(c.scale_wide_split(x, extra), scale_wide_reference(&c, x, extra));
        proptest::prop_assert_eq!(c.scale_wide_magnitude(x, extra), scale_wide_reference(&c, x, extra));
    }

    #[test]
    fn fixed_integrate_is_the_exact_rounded_q16_48_sum(
        v in -2_000_000i32..2_000_000,
        res in proptest::prelude::any::<i32>(),
        x in proptest::prelude::any::<i32>(),
        mant in 1.0f64..2.0,
        exp in -50i32..4,
        neg: bool,
        lo in -3_000_000i32..0,
        width in 0i32..6_000_000,
    ) {
        let c = Coef::new(mant * 2f64.powi(exp) * if neg { -1.0 } else { 1.0 });
        let (lo, hi) = (I16F16::from_bits(lo), I16F16::from_bits(lo.saturating_add(width)));
        let v = Scalar::clamp(I16F16::from_bits(v), lo, hi);
        let x = I16F16::from_bits(x);
        let got = v.integrate(res, x, &c, lo, hi);
        let want = integrate_reference(v, res, x, &c, lo, hi);
        proptest::prop_assert_eq!(got, want);
    }
}

/// The exact Q16.48 sum at the ends of the range: extreme values and
/// residuals, steps that saturate, boxes at the range's ends.
#[test]
fn fixed_integrate_is_exact_at_the_range_ends() {
    let words = [
        i32::MIN,
        i32::MIN + 1,
        -65536,
        -1,
        0,
        1,
        65536,
        i32::MAX - 1,
        i32::MAX,
    ];
    let boxes = [
        (i32::MIN, i32::MAX),
        (i32::MIN, 0),
        (0, i32::MAX),
        (-65536, 65536),
    ];
    for c in [1e-12, -3e-7, 0.4, -0.4, 1.0, 1e6, -1e6, 1e11] {
        let c = Coef::new(c);
        for (lo, hi) in boxes {
            let (lo, hi) = (I16F16::from_bits(lo), I16F16::from_bits(hi));
            for v in words {
                let v = Scalar::clamp(I16F16::from_bits(v), lo, hi);
                for res in words {
                    for x in words {
                        let x = I16F16::from_bits(x);
                        assert_eq!(
                            v.integrate(res, x, &c, lo, hi),
                            integrate_reference(v, res, x, &c, lo, hi),
                            "{v} {res} {x} {c:?}"
                        );
                    }
                }
            }
        }
    }
}

/// A step of a tenth of an LSB moves the Q16.48 value at every sample
/// and the `I16F16` value after five; the saturated ends hold.
#[test]
fn fixed_integrate_accumulates_sub_lsb_steps() {
    let c = Coef::new(0.1);
    let (lo, hi) = (I16F16::MIN, I16F16::MAX);
    let (mut v, mut res) = (I16F16::ZERO, 0i32);
    let one = I16F16::from_bits(1);
    let mut moved_at = None;
    for k in 1..=20 {
        (v, res) = v.integrate(res, one, &c, lo, hi);
        if moved_at.is_none() && v != I16F16::ZERO {
            moved_at = Some(k);
        }
    }
    assert_eq!(moved_at, Some(5));
    assert_eq!(v.to_bits(), 2);
    assert_eq!(
        I16F16::MAX.integrate(0, I16F16::MAX, &Coef::new(1.0), lo, hi),
        (I16F16::MAX, 0)
    );
    assert_eq!(
        I16F16::MIN.integrate(0, I16F16::MIN, &Coef::new(1.0), lo, hi),
        (I16F16::MIN, 0)
    );
}

#[test]
fn mul_coef_saturates() {
    let big = Coef::new(1e6);
    assert_eq!(I16F16::from_num(2).mul_coef(&big), I16F16::MAX);
    assert_eq!(I16F16::from_num(-2).mul_coef(&big), I16F16::MIN);
    assert_eq!(3.0f32.mul_coef(&Coef::new(0.5)), 1.5);
}

#[test]
fn from_counts_saturates_and_handles_zero_factor() {
    let sc = Coef::new(1.0);
    assert_eq!(I16F16::from_counts(1 << 40, &sc), I16F16::MAX);
    assert_eq!(I16F16::from_counts(-(1 << 40), &sc), I16F16::MIN);
    let z = Coef::new(0.0);
    assert_eq!(I16F16::from_counts(12345, &z), I16F16::ZERO);
    assert_eq!(f32::from_counts(12345, &Coef::new(f64::NAN)), 0.0);
    let neg = Coef::new(-0.25);
    assert_eq!(I16F16::from_counts(6, &neg).to_f64(), -1.5);
}

#[test]
fn sgn_is_exact_including_negative_zero_and_nan() {
    assert_eq!((-0.0f64).sgn(), 0.0);
    assert_eq!(f64::NAN.sgn(), 0.0);
    assert_eq!(f32::NAN.sat(1.0), 0.0);
    assert_eq!(1.0f32.sat(f32::NAN), 1.0);
    assert_eq!(I16F16::MIN.sgn(), I16F16::from_num(-1));
    assert_eq!(I16F16::ZERO.sgn(), I16F16::ZERO);
}

/// `slope_within` returns the first candidate that fits, stepping down
/// from the value: with a `fits` that accepts only values at most
/// `v·(1 − k·2⁻²³)` it returns exactly that candidate, and past the fine
/// steps it takes the coarse ones.
#[test]
fn slope_within_steps_down_to_the_first_fit() {
    let v = 3.0f64;
    assert_eq!(slope_within(v, |x| x, |_| true), v);
    for k in [1u32, 2, 17, 63] {
        let lim = v * (1.0 - k as f64 / 8_388_608.0);
        assert_eq!(slope_within(v, |x| x, |&x| x <= lim), lim);
    }
    // Below every fine step (the last is 1 − 63·2⁻²³): the first coarse
    // candidate under the limit 1 − 2⁻¹⁷ = 1 − 64·2⁻²³ is 1 − 2⁻¹⁶.
    let lim = v * (1.0 - 64.0 / 8_388_608.0);
    let got = slope_within(v, |x| x, |&x| x < lim);
    assert_eq!(got, v * (1.0 - 1.0 / 65_536.0));
    // Nothing fits: half the value.
    assert_eq!(slope_within(v, |x| x, |_| false), v * 0.5);
}

/// `copysign` against `f32::copysign`/`f64::copysign` (std) on floats,
/// and against the defining cases on `I16F16`.
#[test]
fn copysign_matches_its_definition() {
    let vals = [
        0.0f64,
        -0.0,
        1.5,
        -2.25,
        f64::MIN_POSITIVE,
        f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for &a in &vals {
        for &b in &vals {
            assert_eq!(Scalar::copysign(a, b).to_bits(), a.copysign(b).to_bits());
            let (a32, b32) = (a as f32, b as f32);
            assert_eq!(
                Scalar::copysign(a32, b32).to_bits(),
                a32.copysign(b32).to_bits()
            );
        }
    }
    assert!(Scalar::copysign(f32::NAN, -1.0).is_nan());
    assert_eq!(Scalar::copysign(2.0f32, -f32::NAN), -2.0);
    let q = |v: f64| I16F16::from_num(v);
    assert_eq!(Scalar::copysign(q(1.5), q(-0.25)), q(-1.5));
    assert_eq!(Scalar::copysign(q(-1.5), q(0.25)), q(1.5));
    assert_eq!(Scalar::copysign(q(-1.5), I16F16::ZERO), q(1.5));
    assert_eq!(Scalar::copysign(I16F16::MIN, q(1.0)), I16F16::MAX);
    assert_eq!(Scalar::copysign(I16F16::MIN, q(-1.0)), -I16F16::MAX);
}

/// `c·2³²/L` exactly, as a rational: (numerator in 2⁻³² turn units
/// times `L`), reduced modulo one turn.
fn exact_turn_times_l(c: u32, l: u32) -> i128 {
    ((c as i128) << 32).rem_euclid((l as i128) << 32)
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(20_000))]
    /// `CountToTurn` is within `1 + c·2⁻³³` units of the exact
    /// `c·2³²/L` (the documented bound), for any `L` and `c < L`.
    #[test]
    fn count_to_turn_within_its_bound(l in 1u32..=u32::MAX, c in proptest::prelude::any::<u32>(), pow2 in 0u32..32, use_pow2: bool) {
        let l = if use_pow2 { 1 << pow2 } else { l };
        let c = c % l;
        let got = CountToTurn::new(l).turn(c) as i128;
        let exact = exact_turn_times_l(c, l); // units·L
        // Signed distance modulo 2³², in units·L.
        let m = (1i128 << 32) * l as i128;
        let mut d = (got * l as i128 - exact).rem_euclid(m);
        if d > m / 2 {
            d -= m;
        }
        let bound = l as f64 * (1.0 + c as f64 / 8_589_934_592.0);
        proptest::prop_assert!((d.abs() as f64) < bound, "L = {l}, c = {c}: {d}/{l}");
        if use_pow2 {
            proptest::prop_assert_eq!(d, 0);
        }
    }
}

#[test]
fn turn_from_radians_rounds_and_wraps() {
    use core::f64::consts::{PI, TAU};
    assert_eq!(turn_from_radians(0.0), 0);
    assert_eq!(turn_from_radians(PI), 1 << 31);
    assert_eq!(turn_from_radians(-PI / 2.0), 3 << 30);
    assert_eq!(turn_from_radians(TAU), 0);
    assert_eq!(turn_from_radians(5.0 * TAU + PI / 2.0), 1 << 30);
    assert_eq!(turn_from_radians(f64::NAN), 0);
    // Just below a full turn rounds up to 2³² and wraps to 0.
    assert_eq!(turn_from_radians(TAU - 1e-12), 0);
}

/// `all_finite` is false exactly when one of the values is NaN or ±∞, at
/// every position and whatever the other values (huge finite values whose
/// sum would overflow included); fixed point is always finite.
#[test]
fn all_finite_finds_every_non_finite_value() {
    fn check<S: Scalar>(huge: S, bad: &[S]) {
        let good = [S::ONE, huge, huge.neg(), S::ZERO, huge];
        assert!(S::all_finite(&good));
        assert!(S::all_finite::<0>(&[]));
        for &b in bad {
            for i in 0..good.len() {
                let mut v = good;
                v[i] = b;
                assert!(!S::all_finite(&v), "{} {:?} at {i}", S::NAME, b);
            }
            assert!(!S::all_finite(&[b]));
        }
    }
    check(f32::MAX, &[f32::NAN, f32::INFINITY, f32::NEG_INFINITY]);
    check(f64::MAX, &[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
    check(I16F16::MAX, &[]);
    assert!(I16F16::all_finite(&[I16F16::MIN, I16F16::MAX]));
}
