use super::*;

/// `check` at every pair of a grid of each magnitude class of `[−1, 1]`
/// (powers of two and their neighbours, a 64-LSB stride) with both
/// signs, at edge words beyond the range, and at 200,000 random pairs
/// of about that range.
fn for_each_unit_pair(check: impl Fn(i32, i32)) {
    let mut mags: Vec<i32> = vec![0, 1, 2, 3, 0xFFFF, 1 << 16];
    for i in 1..16 {
        let p = 1i32 << i;
        mags.extend([p - 1, p, p + 1, p + (p >> 1)]);
    }
    for i in 0..=1024 {
        mags.push(i * 64);
    }
    for &x in &mags {
        for &y in &mags {
            check(x, y);
            check(-x, y);
            check(x, -y);
        }
    }
    // Clamped beyond 1, and the extreme words.
    for (x, y) in [
        (i32::MAX, 0),
        (i32::MIN, 5),
        (1 << 20, 1 << 17),
        (-(1 << 16), -(1 << 16)),
    ] {
        check(x, y);
    }
    let mut z = 0x2545_F491_4F6C_DD1Du64;
    for _ in 0..200_000 {
        z ^= z << 13;
        z ^= z >> 7;
        z ^= z << 17;
        let (x, y) = ((z as i32) >> 14, ((z >> 32) as i32) >> 14);
        check(x, y);
    }
}

/// `hypot_unit` against the exact `hypot` (f64) of the clamped inputs:
/// every pair of a grid covering each magnitude class (powers of two
/// and their neighbours, from 1 LSB to 1) with both signs, plus a
/// random sweep; the bound is 1 LSB, and tiny vectors stay precise.
#[test]
fn hypot_unit_is_within_one_lsb() {
    let check = |a: i32, b: i32| {
        let got = hypot_unit(I16F16::from_bits(a), I16F16::from_bits(b)).to_bits();
        let (ca, cb) = (
            (a.unsigned_abs().min(0xFFFF)) as f64,
            (b.unsigned_abs().min(0xFFFF)) as f64,
        );
        let exact = ca.hypot(cb);
        assert!(
            (got as f64 - exact).abs() <= 1.0,
            "hypot_unit({a}, {b}) = {got}, exact {exact}"
        );
    };
    for_each_unit_pair(check);
}

/// `rsqrt_quarter` at every input of `[¼, 1]` and the clamps beyond:
/// within 1 LSB of the exact `1/√x` of the clamped input, and
/// non-increasing.
#[test]
fn rsqrt_quarter_is_within_one_lsb() {
    let mut prev = i32::MAX;
    let mut worst = 0.0f64;
    for bits in (1 << 14) - 3..=(1 << 16) + 3 {
        let got = rsqrt_quarter(I16F16::from_bits(bits)).to_bits();
        let c = bits.clamp(1 << 14, 1 << 16) as f64 / 65536.0;
        let err = (got as f64 - 65536.0 / c.sqrt()).abs();
        worst = worst.max(err);
        assert!(err <= 1.0, "rsqrt_quarter({bits}) = {got}, error {err} LSB");
        assert!(got <= prev, "rsqrt_quarter not monotone at {bits}");
        prev = got;
    }
    assert!(worst > 0.0);
    for bits in [i32::MIN, -1, 0, 1, i32::MAX] {
        let want = if bits > 1 << 16 { 1 << 16 } else { 1 << 17 };
        assert_eq!(
            rsqrt_quarter(I16F16::from_bits(bits)).to_bits(),
            want,
            "{bits}"
        );
    }
}

/// `unit_vector` against the exact direction of the clamped inputs:
/// every pair of a grid of each magnitude class and sign, edge words
/// and random pairs; `None` only for the zero vector.
#[test]
fn unit_vector_is_within_one_lsb() {
    let check = |a: i32, b: i32| {
        let got = unit_vector(I16F16::from_bits(a), I16F16::from_bits(b));
        let cl = |v: i32| (v.unsigned_abs().min(0xFFFF) as f64).copysign(v as f64);
        let (ca, cb) = (cl(a), cl(b));
        let h = ca.hypot(cb);
        match got {
            None => assert!(h == 0.0, "unit_vector({a}, {b}) = None"),
            Some((u, v)) => {
                let (eu, ev) = (65536.0 * ca / h, 65536.0 * cb / h);
                assert!(
                    (u.to_bits() as f64 - eu).abs() <= 1.0
                        && (v.to_bits() as f64 - ev).abs() <= 1.0,
                    "unit_vector({a}, {b}) = ({}, {}), exact ({eu}, {ev})",
                    u.to_bits(),
                    v.to_bits()
                );
            }
        }
    };
    for_each_unit_pair(check);
}

/// `atan_small` at every input below 2 in magnitude: within 1 LSB of
/// the exact arctangent (f64), equal to `atan` below 1, odd and
/// non-decreasing; the clamp beyond.
#[test]
fn atan_small_is_within_one_lsb() {
    let lsb = 1.0 / 65536.0;
    let mut prev = i32::MIN;
    for b in -(2 << 16) + 1..2 << 16 {
        let x = I16F16::from_bits(b);
        let got = atan_small(x).to_bits();
        let exact = (b as f64 * lsb).atan() / lsb;
        assert!(
            (got as f64 - exact).abs() <= 1.0,
            "bits {b}: {got} vs {exact}"
        );
        assert!(got >= prev, "not monotone at bits {b}");
        prev = got;
        assert_eq!(
            atan_small(I16F16::from_bits(-b)).to_bits(),
            -got,
            "odd at {b}"
        );
        if b.unsigned_abs() < 1 << 16 {
            assert_eq!(got, atan(x).to_bits(), "bits {b}");
        }
    }
    let top = atan_small(I16F16::from_bits((2 << 16) - 1));
    for b in [2 << 16, (2 << 16) + 1, 1 << 20, i32::MAX] {
        assert_eq!(atan_small(I16F16::from_bits(b)), top, "bits {b}");
        assert_eq!(atan_small(I16F16::from_bits(-b)), -top, "bits {}", -b);
    }
    assert_eq!(atan_small(I16F16::MIN), -top);
}

/// The shortened root against the full one at every `n < 2¹⁸`, and
/// `sqrt_small` against `sqrt` below 4, at the clamp and beyond.
#[test]
fn sqrt_q16_small_equals_sqrt_q16() {
    for n in 0u32..1 << 18 {
        assert_eq!(sqrt_q16_small(n), sqrt_q16(n), "n = {n}");
    }
    for b in [i32::MIN, -1, 0, 1, 1 << 16, (1 << 18) - 1] {
        let x = I16F16::from_bits(b);
        assert_eq!(sqrt_small(x), sqrt(x), "bits {b}");
    }
    let top = sqrt(I16F16::from_bits((1 << 18) - 1));
    for b in [1 << 18, (1 << 18) + 1, 1 << 20, i32::MAX] {
        assert_eq!(sqrt_small(I16F16::from_bits(b)), top, "bits {b}");
    }
    // Independent: the correctly rounded root of bits·2¹⁶ in f64.
    for b in (0i32..1 << 18).step_by(37) {
        let exact = ((b as f64) * 65536.0).sqrt();
        let got = sqrt_small(I16F16::from_bits(b)).to_bits() as f64;
        assert!(
            (got - exact).abs() <= 0.5 + 1e-9,
            "bits {b}: {got} vs {exact}"
        );
    }
}

/// `⌊n·2ᵏ/d⌋` in 128-bit arithmetic: the reference of both divisions.
fn floor_quotient(n: u32, d: u32, k: u32) -> u128 {
    ((n as u128) << k) / d as u128
}

/// `tan` as it was before [`div_frac_wide`]: the same operands through
/// the bit-serial [`div_frac`].
fn tan_bit_serial(x: I16F16) -> I16F16 {
    tan_with(x, |a| {
        if a <= PIO4_BITS {
            tan_small_quotient(a)
        } else {
            let (n, d, k) = cot_quotient_operands(a);
            div_frac(n, d, k)
        }
    })
}

/// Every input of `tan`'s domain beyond π/4: the operands satisfy the
/// documented ranges, both divisions equal the 128-bit floor quotient,
/// the final correction is 0 or 1 (both occur); and `tan` is
/// bit-identical to the bit-serial version at every input (both
/// signs, and past the saturation).
/// `tan_bounded` at every magnitude of its domain and beyond: within 1
/// LSB of the `f64` tangent (of the clamped argument beyond the bound),
/// exactly odd, non-decreasing; and its table matches the generator's
/// function at every piece's ends.
#[test]
fn tan_bounded_is_within_one_lsb_at_every_input() {
    let lsb = 1.0 / 65536.0;
    let (mut worst, mut at) = (0.0f64, 0);
    let mut prev = i32::MIN;
    for a in 0..=TAN_BOUNDED_MAX_BITS as i32 + 2000 {
        let got = tan_bounded(I16F16::from_bits(a)).to_bits();
        let want = libm::tan(a.min(TAN_BOUNDED_MAX_BITS as i32) as f64 * lsb);
        let err = (got as f64 * lsb - want).abs() / lsb;
        assert!(err <= 1.0, "a = {a}: {got} vs {want}");
        if err > worst {
            (worst, at) = (err, a);
        }
        assert!(got >= prev, "decreases at {a}");
        prev = got;
        assert_eq!(
            tan_bounded(I16F16::from_bits(-a)).to_bits(),
            -got,
            "odd at {a}"
        );
    }
    std::eprintln!("tan_bounded: max {worst:.6} LSB at bits {at}");
    // The fit's share is visible: the worst input is above half an LSB.
    assert!(worst > 0.5);
    for bits in [i32::MIN, i32::MIN + 1, i32::MAX] {
        let got = tan_bounded(I16F16::from_bits(bits)).to_bits();
        let edge = tan_bounded(I16F16::from_bits(TAN_BOUNDED_MAX_BITS as i32)).to_bits();
        assert_eq!(got, if bits < 0 { -edge } else { edge });
    }
    assert!((libm::atan(8.0) * 65536.0).floor() as u32 == TAN_BOUNDED_MAX_BITS);
    // The estimator's domain bound is the same angle.
    assert_eq!(
        crate::harmonic_drive::compliance::TAN_BOUNDED_ARGUMENT,
        libm::atan(8.0)
    );
}

#[test]
fn tan_quotients_are_exact() {
    let mut max_steps = 0;
    for a in PIO4_BITS + 1..TAN_SAT_BITS {
        let (n, d, k) = cot_quotient_operands(a);
        assert!((1 << 30..1 << 31).contains(&d), "a = {a}: d = {d}");
        assert!((17..=31).contains(&k), "a = {a}: k = {k}");
        assert!(
            n as f64 >= 2f64.powf(30.6) && n <= 1 << 31,
            "a = {a}: n = {n}"
        );
        let want = floor_quotient(n, d, k);
        assert!(want < 1 << 32);
        let (q, steps) = div_frac_wide_steps(n, d, k);
        assert_eq!(q as u128, want, "a = {a}: n = {n}, d = {d}, k = {k}");
        assert_eq!(div_frac(n, d, k) as u128, want, "a = {a}");
        max_steps = max_steps.max(steps);
    }
    assert_eq!(max_steps, 1);
    for a in 0..TAN_SAT_BITS as i32 + 100 {
        for bits in [a, -a] {
            let x = I16F16::from_bits(bits);
            assert_eq!(tan(x), tan_bit_serial(x), "bits = {bits}");
        }
    }
    for bits in [i32::MIN, i32::MIN + 1, i32::MAX] {
        let x = I16F16::from_bits(bits);
        assert_eq!(tan(x), tan_bit_serial(x), "bits = {bits}");
    }
}

/// `atan2_mag` as it was before [`div_ratio`]: the ratio by the
/// bit-serial [`div_frac`].
fn atan2_mag_bit_serial(a: u32, b: u32) -> u32 {
    if a == b {
        PIO4_Q30
    } else if a < b {
        atan_unit(div_frac(a, b, 32)) >> 2
    } else {
        PIO2_Q30 - (atan_unit(div_frac(b, a, 32)) >> 2)
    }
}

/// Magnitudes at the edges of `atan2_mag`'s domain `[0, 2³¹]`: 0, 1,
/// every power of two and its neighbours, the `I16F16` one (`2¹⁶`) and
/// its neighbours, `i32::MIN`'s magnitude `2³¹` and `i32::MAX`.
fn edge_magnitudes() -> Vec<u32> {
    let mut v = vec![
        0u32,
        1,
        2,
        3,
        5,
        7,
        0xFFFF,
        0x1_0000,
        0x1_0001,
        0x7FFF_FFFF,
        1 << 31,
    ];
    for i in 1..=31 {
        let p = 1u32 << i;
        v.extend([p - 1, p, p + 1, p + (p >> 1), p - (p >> 2)]);
    }
    v.retain(|&m| m <= 1 << 31);
    v.sort_unstable();
    v.dedup();
    v
}

/// `⌊n·2³²/d⌋` of [`div_ratio`] against the 128-bit floor quotient and
/// the bit-serial [`div_frac`], on every pair of edge magnitudes with
/// `n < d` and at `n` just below `d` (ratios next to 1), for divisors up
/// to `u32::MAX`; both values of the final correction occur.
#[test]
fn div_ratio_matches_on_edges() {
    let mut ds = edge_magnitudes();
    ds.extend([(1 << 31) + 1, 0xC000_0000, u32::MAX - 1, u32::MAX]);
    let mut seen = [false; 2];
    for &d in ds.iter().filter(|&&d| d >= 1) {
        let near = [
            d - 1,
            d.saturating_sub(2),
            d.saturating_sub(3),
            d / 2,
            d / 3,
        ];
        for n in ds.iter().copied().filter(|&n| n < d).chain(near) {
            let want = floor_quotient(n, d, 32);
            let (q, step) = div_ratio_steps(n, d);
            assert_eq!(q as u128, want, "n = {n}, d = {d}");
            if d <= 1 << 31 {
                assert_eq!(div_frac(n, d, 32), q, "n = {n}, d = {d}");
            }
            seen[step as usize] = true;
        }
    }
    assert_eq!(seen, [true, true]);
}

/// [`sqrt_q16`] equals the 24-step recurrence and the exact 64-bit
/// definition: every `n` below 2²⁰, every power of two with its
/// neighbours, perfect squares and their neighbours, and a stride over
/// the whole range.
#[test]
fn sqrt_q16_equals_the_digit_by_digit_form() {
    let check = |n: u32| {
        let (root, rem) = sqrt_q16(n);
        assert_eq!((root, rem), sqrt_q16_digit_by_digit(n), "n = {n}");
        let v = (n as u64) << 16;
        let r = root as u64;
        assert!(r * r + rem as u64 == v && v < (r + 1) * (r + 1), "n = {n}");
    };
    for n in 0..1u32 << 20 {
        check(n);
    }
    for i in 0..32 {
        let p = 1u32 << i;
        for n in [p - 1, p, p + 1, u32::MAX >> (31 - i)] {
            check(n);
        }
    }
    for r in (0u32..1 << 16).step_by(13).chain([(1 << 16) - 1]) {
        let sq = r * r;
        for n in [sq.wrapping_sub(1), sq, sq + 1] {
            check(n);
        }
    }
    let mut n = 0u32;
    while let Some(m) = n.checked_add(4093) {
        check(m);
        n = m;
    }
    check(u32::MAX);
}

/// Every divisor below 2²⁰ and every power of two with its neighbours.
#[test]
fn leading_zeros_32_is_exact() {
    for d in 1..1u32 << 20 {
        assert_eq!(leading_zeros_32(d), d.leading_zeros(), "d = {d}");
    }
    for i in 0..32 {
        let p = 1u32 << i;
        for d in [p - 1, p, p + 1, p | (p - 1), u32::MAX >> (31 - i)] {
            if d >= 1 {
                assert_eq!(leading_zeros_32(d), d.leading_zeros(), "d = {d}");
            }
        }
    }
}

/// `atan2_mag` with [`div_ratio`] equals the bit-serial version on
/// every pair of edge magnitudes (including equal ones and 0), on
/// ratios next to 1 and next to 0 around every edge magnitude, and at
/// every operand pair of `acos` (all 2¹⁶ − 1 inputs `0 < |x| < 1`).
#[test]
fn atan2_mag_is_bit_identical() {
    let v = edge_magnitudes();
    let mut count = 0u32;
    let mut check = |a: u32, b: u32| {
        if (a, b) != (0, 0) && a <= 1 << 31 && b <= 1 << 31 {
            assert_eq!(
                atan2_mag(a, b),
                atan2_mag_bit_serial(a, b),
                "a = {a}, b = {b}"
            );
            count += 1;
        }
    };
    for &a in &v {
        for &b in &v {
            check(a, b);
        }
        for j in 1..=8 {
            check(a, a.wrapping_sub(j));
            check(a.wrapping_sub(j), a);
            check(a, a + j);
            check(a + j, a);
            check(j, a);
            check(a, j);
        }
    }
    for a in 1..1u32 << 16 {
        let (s, _) = sqrt_q16(((1 << 16) - a) * ((1 << 16) + a));
        check(s, a << 8);
    }
    assert!(count > 80_000, "{count}");
}

/// Every input of `atan` (`b = 2¹⁶`, `a` every magnitude up to 2³¹):
/// bit-identical to the bit-serial division, and for `a > 2¹⁶` the
/// ratio `div_ratio(2¹⁶, a)` at least `2¹⁶` (the contract a Kani
/// harness assumes). 2³¹ pairs, run in release by
/// `.ci/run` with the other exhaustive checks:
/// `cargo test --release --lib exhaustive_atan_bit_identity_i16f16 -- --ignored`.
#[test]
#[ignore = "exhaustive: run in release by .ci/run"]
fn exhaustive_atan_bit_identity_i16f16() {
    for a in 0..=1u32 << 31 {
        if atan2_mag(a, 1 << 16) != atan2_mag_bit_serial(a, 1 << 16) {
            panic!("a = {a}");
        }
        // The contract of `atan`'s ratio for |x| > 1 that the Kani
        // harness `kani_atan_in_range_large_i16f16` assumes.
        if a > 1 << 16 && div_ratio(1 << 16, a) < 1 << 16 {
            panic!("div_ratio(2^16, {a}) < 2^16");
        }
    }
}

#[test]
fn leading_zeros_16_is_exact() {
    for h in 1..1u32 << 16 {
        assert_eq!(leading_zeros_16(h), h.leading_zeros(), "h = {h}");
    }
}

/// The seed table from an independent (`f64`) evaluation of its
/// definition, and the seed error bound `ε₀ < 2⁻⁹` (with `|e| < 2²⁴`)
/// at both ends of every interval, in exact 128-bit arithmetic.
#[test]
fn recip_seed_matches_an_independent_computation() {
    let mut max_eps = 0f64;
    for (i, &seed) in RECIP_SEED.iter().enumerate() {
        let a = 2f64.powi(31) + i as f64 * 2f64.powi(23);
        let b = a + 2f64.powi(23);
        let best = 2f64.powi(65) / (a + b); // equal relative error at a and b
        let want = (best / 65536.0).round() - 65536.0;
        assert_eq!(seed as f64, want, "entry {i}");
        let x0 = (1u128 << 32) + ((seed as u128) << 16);
        for dn in [
            (1u128 << 31) + ((i as u128) << 23),
            (1u128 << 31) + ((i as u128 + 1) << 23) - 1,
        ] {
            let e = (1i128 << 64) - (x0 * dn) as i128;
            assert!(e.abs() < 1i128 << 56, "entry {i}: e = {e}");
            max_eps = max_eps.max(e.abs() as f64 / 2f64.powi(64));
        }
    }
    // Equality at D = 2³¹ (x₀ = 2³³ − 2²⁴).
    assert!(max_eps <= 2f64.powi(-9), "{max_eps}");
}

/// Edge cases of the precondition domain of [`div_frac_wide`]: the
/// divisor at `2²⁹`, `2³⁰`, `2³¹` and their neighbours, near `2³²`, with
/// the largest numerator whose quotient stays below `2³²` and a few
/// below it, for every `k`.
#[test]
fn div_frac_wide_matches_on_edges() {
    let divisors = [
        1u32 << 29,
        (1 << 29) + 1,
        (1 << 30) - 1,
        1 << 30,
        (1 << 30) + 1,
        (1 << 31) - 1,
        1 << 31,
        (1 << 31) + 1,
        0xC000_0000,
        u32::MAX - 1,
        u32::MAX,
    ];
    let mut max_steps = 0;
    for d in divisors {
        for k in 1..=31u32 {
            // Largest n with ⌊n·2ᵏ/d⌋ < 2³²: n·2ᵏ < d·2³².
            let n_max = ((((d as u128) << 32) - 1) >> k).min(u32::MAX as u128) as u32;
            for n in [
                0,
                1,
                2,
                d - 1,
                d,
                d.wrapping_add(1),
                n_max,
                n_max - 1,
                n_max / 2,
                n_max / 3,
            ] {
                if floor_quotient(n, d, k) >= 1 << 32 {
                    continue;
                }
                let (q, steps) = div_frac_wide_steps(n, d, k);
                assert_eq!(
                    q as u128,
                    floor_quotient(n, d, k),
                    "n = {n}, d = {d}, k = {k}"
                );
                max_steps = max_steps.max(steps);
            }
        }
    }
    assert_eq!(max_steps, 1);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200_000))]
    /// Over the whole documented domain (`d ≥ 2²⁹`, `1 ≤ k ≤ 31`,
    /// quotient `< 2³²`): the exact floor quotient, with a final correction
    /// of 0 or 1. `n` is drawn below the largest admissible
    /// numerator `⌊(d·2³² − 1)/2ᵏ⌋`, as a fraction of it or near it.
    #[test]
    fn div_frac_wide_is_exact(
        d in (1u32 << 29)..=u32::MAX,
        k in 1u32..=31,
        frac in proptest::prelude::any::<u32>(),
        near in 0u32..3,
    ) {
        let n_max = ((((d as u128) << 32) - 1) >> k).min(u32::MAX as u128) as u32;
        let n = match near {
            0 => ((n_max as u64 * frac as u64) >> 32) as u32,
            1 => n_max - (frac % 1024).min(n_max),
            _ => frac % (n_max.max(1)),
        };
        proptest::prop_assert_eq!(div_frac_wide(n, d, k) as u128, floor_quotient(n, d, k));
    }

    /// Over the whole documented domain of [`div_ratio`] (`n < d`, any
    /// `d ≥ 1`): the exact floor quotient, equal to the bit-serial
    /// `div_frac(n, d, 32)` where that applies (`d ≤ 2³¹`). `d` is drawn
    /// uniformly or as a power of two times a small factor (tiny and
    /// round divisors), `n` as a fraction of `d` or just below it.
    #[test]
    fn div_ratio_is_exact(
        d_any in 1u32..=u32::MAX,
        shift in 0u32..32,
        pick in 0u32..3,
        frac in proptest::prelude::any::<u32>(),
        near in 0u32..2,
    ) {
        let d = match pick {
            0 => d_any,
            1 => (d_any >> shift).max(1),
            _ => (d_any & 0xFF).max(1) << shift.min(23),
        };
        let n = if near == 0 {
            ((d as u64 * frac as u64) >> 32) as u32
        } else {
            d - 1 - (frac % 1024).min(d - 1)
        };
        let q = div_ratio(n, d);
        proptest::prop_assert_eq!(q as u128, floor_quotient(n, d, 32));
        if d <= 1 << 31 {
            proptest::prop_assert_eq!(q, div_frac(n, d, 32));
        }
    }

    /// `atan2_mag` with [`div_ratio`] equals the bit-serial version on
    /// random magnitude pairs over `[0, 2³¹]`: uniform, both scaled down
    /// by a common random shift (tiny magnitudes), and ratios next to 1.
    #[test]
    fn atan2_mag_bit_identical_random(
        a in 0u32..=(1 << 31),
        b in 0u32..=(1 << 31),
        shift in 0u32..32,
        pick in 0u32..3,
        j in 0u32..64,
    ) {
        let (a, b) = match pick {
            0 => (a, b),
            1 => (a >> shift, b >> shift),
            _ if b & 1 == 0 => (a, a.saturating_sub(j)),
            _ => (a, (a + j).min(1 << 31)),
        };
        if (a, b) != (0, 0) {
            proptest::prop_assert_eq!(atan2_mag(a, b), atan2_mag_bit_serial(a, b), "a = {}, b = {}", a, b);
        }
    }
}
