use super::*;

#[test]
fn mul_rounds_to_nearest_and_saturates() {
    // 1.5 * 1.5 = 2.25 exactly.
    assert_eq!(mul_bits(3 << 15, 3 << 15), 9 << 14);
    // LSB * 0.5 = 2^-17 rounds (ties up) to one LSB.
    assert_eq!(mul_bits(1, 1 << 15), 1);
    assert_eq!(mul_bits(i32::MAX, i32::MAX), i32::MAX);
    assert_eq!(mul_bits(i32::MIN, i32::MAX), i32::MIN);
}

/// Edge classes of operands: 0, ±1, powers of two and their
/// neighbours, the extremes.
fn edge_words() -> Vec<i32> {
    let mut v = vec![0, 1, -1, i32::MAX, i32::MIN, i32::MIN + 1];
    for k in 0..31 {
        let p = 1i32 << k;
        v.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
    }
    v
}

#[test]
fn mul_bits_short_path_equals_the_64_bit_formula_at_its_edges() {
    // Every operand of the short range (and one beyond each end),
    // against every edge word and the magnitudes that maximize l·b.
    let mut w = edge_words();
    w.extend([0xFFFF, -0xFFFF, 0x7FFF_FFFF, 0x1_FFFF, -0x1_0001]);
    for b in (-32769..=32768).step_by(1) {
        for &a in &w {
            assert_eq!(mul_bits(a, b), mul_bits_reference(a, b), "{a} {b}");
            assert_eq!(mul_bits(b, a), mul_bits_reference(b, a), "{b} {a}");
        }
    }
}

/// The unit-range product equals the general one for every factor of
/// `[−1, 1]` (and one LSB beyond each end, clamped) against every edge
/// word.
#[test]
fn mul_bits_unit_equals_mul_bits_on_the_unit_range() {
    let mut w = edge_words();
    w.extend([0xFFFF, -0xFFFF, 0x7FFF_FFFF, 0x1_FFFF, -0x1_0001]);
    for u in -65536..=65536 {
        for &a in &w {
            assert_eq!(mul_bits_unit(a, u), mul_bits_reference(a, u), "{a} {u}");
        }
    }
    for &a in &w {
        assert_eq!(mul_bits_unit(a, 65537), a, "{a}");
        assert_eq!(mul_bits_unit(a, -65537), mul_bits_reference(a, -65536));
    }
}

#[test]
fn mul_bits_equals_the_64_bit_formula_on_edge_classes() {
    let w = edge_words();
    for &a in &w {
        for &b in &w {
            assert_eq!(mul_bits(a, b), mul_bits_reference(a, b), "{a} {b}");
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(20_000))]
    /// The split product equals the 64-bit formula for random operands.
    #[test]
    fn mul_bits_equals_the_64_bit_formula(a in proptest::prelude::any::<i32>(), b in proptest::prelude::any::<i32>()) {
        proptest::prop_assert_eq!(mul_bits(a, b), mul_bits_reference(a, b));
    }

    /// The unit-range product for random operands.
    #[test]
    fn mul_bits_unit_equals_the_64_bit_formula(a in proptest::prelude::any::<i32>(), u in -65536i32..=65536) {
        proptest::prop_assert_eq!(mul_bits_unit(a, u), mul_bits_reference(a, u));
    }

    /// The same with one operand in the short range (the fast path).
    #[test]
    fn mul_bits_short_equals_the_64_bit_formula(a in proptest::prelude::any::<i32>(), b in -32768i32..32768) {
        proptest::prop_assert_eq!(mul_bits(a, b), mul_bits_reference(a, b));
        proptest::prop_assert_eq!(mul_bits(b, a), mul_bits_reference(b, a));
    }

    /// `scaled_product` equals the i128 formula for every shift.
    #[test]
    fn scaled_product_equals_i128_formula(
        a in 0u32..=(1 << 31), b in 0u32..=(1 << 31), neg: bool, sh in -40i32..70,
        small in 0u32..4,
    ) {
        // Mix in small magnitudes (the rounding edges matter there).
        let a = if small == 0 { a >> 20 } else { a };
        let p = a as i128 * b as i128 * if neg { -1 } else { 1 };
        let want = if sh > 0 {
            if sh >= 63 { 0 } else { (p + (1i128 << (sh - 1))) >> sh }
        } else {
            p << (-sh).min(100)
        };
        let want = want.clamp(i32::MIN as i128, i32::MAX as i128) as i32;
        proptest::prop_assert_eq!(scaled_product(neg, a, b, sh), want);
    }
}

#[test]
fn wide_mul_is_exact_on_edges() {
    for a in [0u32, 1, 0xFFFF, 0x10000, 0x8000_0000, u32::MAX, 0x1234_5678] {
        for b in [0u32, 1, 0xFFFF, 0x10000, 0x8000_0000, u32::MAX, 0x9ABC_DEF0] {
            for (hi, lo) in [wide_mul(a, b), wide_mul_split(a, b)] {
                assert_eq!((hi as u64) << 32 | lo as u64, a as u64 * b as u64);
            }
        }
    }
}

/// The Q16.16-scale form is the rounded, saturated 64-bit formula on
/// every pair of edge words.
#[test]
fn mul_bits_long_split_equals_the_64_bit_formula_on_edges() {
    let w = edge_words();
    for &a in &w {
        for &b in &w {
            assert_eq!(
                mul_bits_long_split(a, b),
                mul_bits_reference(a, b),
                "{a} * {b}"
            );
        }
    }
}

/// The signed four-partial-product form is the exact signed product on
/// every pair of edge words.
#[test]
fn signed_wide_mul_split_is_exact_on_edges() {
    let w = edge_words();
    for &a in &w {
        for &b in &w {
            let (hi, lo) = signed_wide_mul_split(a, b);
            assert_eq!(
                ((hi as i64) << 32) | lo as i64,
                a as i64 * b as i64,
                "{a} {b}"
            );
        }
    }
}

/// [`signed_wide_mul_add_split`] with the halves of `m` prepared as
/// the coefficients prepare them.
fn mul_add_split(x: i32, m: i32, r: u32) -> i64 {
    let (mh, ml) = (((m as i64 + (1 << 15)) >> 16) as i32, m as i16 as i32);
    let (hi, lo) = signed_wide_mul_add_split(x, mh, ml, r);
    ((hi as i64) << 32) | lo as i64
}

/// The signed-halves form with its rounding constant is the exact
/// `x·m + r` on every pair of edge words (`|m| < 2³¹`) and constants
/// `0`, `1`, `2³⁰`, `2³¹`, `2³² − 1`.
#[test]
fn signed_wide_mul_add_split_is_exact_on_edges() {
    // Plus the words whose signed halves are at their ends (x_h or
    // m_h = ±2¹⁵, x_l or m_l = −2¹⁵), where the middle sum is largest.
    let mut w = edge_words();
    for h in [0x7FFF_i32, -0x8000, 0x7FFE, -0x7FFF] {
        for l in [0x7FFF_i32, 0x8000, 0x8001, 0xFFFF, 0] {
            w.push(((h as u32) << 16 | l as u32) as i32);
        }
    }
    for &x in &w {
        for &m in w.iter().filter(|&&m| m != i32::MIN) {
            for r in [0u32, 1, 1 << 30, 1 << 31, u32::MAX] {
                assert_eq!(
                    mul_add_split(x, m, r),
                    x as i64 * m as i64 + r as i64,
                    "{x} {m} {r}"
                );
            }
        }
    }
}

/// `sat(⌊(V + 2^rs) / 2^(rs+1)⌋)` in `i128`, the reference of
/// [`round_shift_sat`].
fn round_shift_reference(hi: i32, lo: u32, rs: u32) -> i32 {
    let v = ((hi as i128) << 32) + lo as i128 + (1i128 << rs);
    (v >> (rs + 1)).clamp(i32::MIN as i128, i32::MAX as i128) as i32
}

/// [`round_shift_sat`] equals the `i128` formula at the edges of its
/// range test: the high words just inside and outside `±2^rs` (with
/// and without the carry of the low word), `±2³⁰`, for every shift.
#[test]
fn round_shift_sat_equals_the_128_bit_formula_on_edges() {
    let los = [0u32, 1, (1 << 31) - 1, 1 << 31, u32::MAX - 1, u32::MAX];
    for rs in 0..32u32 {
        let p = 1i64 << rs;
        let mut his = vec![
            0i64,
            1,
            -1,
            1 << 30,
            -(1 << 30),
            (1 << 30) - 1,
            -(1 << 30) + 1,
        ];
        for d in -2..=2 {
            his.extend([p + d, -p + d]);
        }
        for &hi in his.iter().filter(|h| h.unsigned_abs() <= 1 << 30) {
            for &lo in &los {
                let lo = lo.rotate_right(rs) ^ (lo >> 7);
                for lo in [lo, lo.wrapping_neg(), u32::MAX - (1 << rs) + 1] {
                    assert_eq!(
                        round_shift_sat(hi as i32, lo, 1 << rs, rs),
                        round_shift_reference(hi as i32, lo, rs),
                        "hi {hi} lo {lo} rs {rs}"
                    );
                }
            }
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(50_000))]
    /// [`round_shift_sat`] equals the `i128` formula.
    #[test]
    fn round_shift_sat_equals_the_128_bit_formula(
        hi in -(1i32 << 30)..=(1 << 30),
        lo in proptest::prelude::any::<u32>(),
        rs in 0u32..32,
    ) {
        proptest::prop_assert_eq!(round_shift_sat(hi, lo, 1 << rs, rs), round_shift_reference(hi, lo, rs));
    }

    /// Near the saturation bounds of each shift.
    #[test]
    fn round_shift_sat_equals_the_128_bit_formula_near_the_bounds(
        rs in 0u32..31,
        d in -3i32..=3,
        neg in proptest::prelude::any::<bool>(),
        lo in proptest::prelude::any::<u32>(),
    ) {
        let hi = if neg { -(1i32 << rs) + d } else { (1i32 << rs) + d };
        proptest::prop_assert_eq!(round_shift_sat(hi, lo, 1 << rs, rs), round_shift_reference(hi, lo, rs));
    }

    /// The signed four-partial-product form is exact.
    #[test]
    fn mul_bits_long_split_equals_the_64_bit_formula(a in proptest::prelude::any::<i32>(), b in proptest::prelude::any::<i32>()) {
        proptest::prop_assert_eq!(mul_bits_long_split(a, b), mul_bits_reference(a, b));
    }

    #[test]
    fn signed_wide_mul_add_split_is_exact(
        x in proptest::prelude::any::<i32>(),
        m in (i32::MIN + 1)..=i32::MAX,
        r in proptest::prelude::any::<u32>(),
    ) {
        proptest::prop_assert_eq!(mul_add_split(x, m, r), x as i64 * m as i64 + r as i64);
    }

    #[test]
    fn signed_wide_mul_split_is_exact(a in proptest::prelude::any::<i32>(), b in proptest::prelude::any::<i32>()) {
        let (hi, lo) = signed_wide_mul_split(a, b);
        proptest::prop_assert_eq!(((hi as i64) << 32) | lo as i64, a as i64 * b as i64);
    }

    /// The four-partial-product form (the Armv6-M path) is exact.
    #[test]
    fn wide_mul_split_is_exact(a in proptest::prelude::any::<u32>(), b in proptest::prelude::any::<u32>()) {
        let (hi, lo) = wide_mul_split(a, b);
        proptest::prop_assert_eq!((hi as u64) << 32 | lo as u64, a as u64 * b as u64);
    }
}

/// Signed edge values of the `i32` bit range: 0, ±1, the extremes and
/// every power of two with its neighbours.
fn div_edges() -> Vec<i32> {
    let mut v = vec![
        0,
        1,
        -1,
        2,
        -2,
        3,
        -3,
        i32::MIN,
        i32::MIN + 1,
        i32::MAX,
        i32::MAX - 1,
    ];
    for k in 1..31 {
        let p = 1i32 << k;
        v.extend([p - 1, p, p + 1, -(p - 1), -p, -(p + 1)]);
    }
    v.sort_unstable();
    v.dedup();
    v
}

/// Every pair of edge values, and every operand next to the
/// saturation boundary `|a| = |b|·2¹⁵` (the quotient `2³¹`).
#[test]
fn div_bits_equals_the_64_bit_formula_on_edges() {
    let e = div_edges();
    for &a in &e {
        for &b in &e {
            assert_eq!(div_bits(a, b), div_bits_reference(a, b), "{a} / {b}");
        }
    }
    for b in (1i32..1 << 16)
        .step_by(7)
        .chain([1, 2, 3, (1 << 16) - 1, 1 << 16])
    {
        let edge = (b as i64) << 15;
        for a in [edge - 2, edge - 1, edge, edge + 1] {
            if a <= i32::MAX as i64 {
                let a = a as i32;
                for (x, y) in [(a, b), (-a, b), (a, -b), (-a, -b)] {
                    assert_eq!(div_bits(x, y), div_bits_reference(x, y), "{x} / {y}");
                }
            }
        }
    }
}

/// Every numerator in `[−2¹², 2¹²]` over every divisor in `[−2⁹, 2⁹]`
/// and the edge divisors.
#[test]
fn div_bits_equals_the_64_bit_formula_on_small_operands() {
    let divisors: Vec<i32> = (-512..=512).chain(div_edges()).collect();
    for a in -4096..=4096 {
        for &b in &divisors {
            assert_eq!(div_bits(a, b), div_bits_reference(a, b), "{a} / {b}");
        }
    }
}

/// The rounding ties `|a|·2¹⁶/|b| = q + ½` (`|b| = c·2¹⁷`,
/// `|a| = c·(2q + 1)`) round away from zero, as the reference does;
/// their neighbours round to the nearer quotient.
#[test]
fn div_bits_rounds_ties_away_from_zero() {
    assert_eq!(div_bits(1, 1 << 17), 1); // ½ LSB
    assert_eq!(div_bits(-1, 1 << 17), -1);
    assert_eq!(div_bits(3, 1 << 17), 2); // 1½ LSB
    assert_eq!(div_bits(3, -(1 << 17)), -2);
    assert_eq!(div_bits(1, (1 << 17) + 1), 0); // just under ½ LSB
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(100_000))]
    /// Any operands; divisors drawn over every magnitude (a random
    /// word shifted right by a random amount).
    #[test]
    fn div_bits_equals_the_64_bit_formula(
        a in proptest::prelude::any::<i32>(), b in proptest::prelude::any::<i32>(),
        sa in 0u32..32, sb in 0u32..32,
    ) {
        for (x, y) in [(a, b), (a >> sa, b >> sb), (a >> sa, b), (a, b >> sb)] {
            proptest::prop_assert_eq!(div_bits(x, y), div_bits_reference(x, y), "{} / {}", x, y);
        }
    }

    /// `div_bits_unit` equals the 64-bit formula on ratios
    /// `|a| ≤ |b|` of every magnitude, and stays in `[−2¹⁶, 2¹⁶]` with
    /// the quotient's sign on any operands.
    #[test]
    fn div_bits_unit_equals_the_64_bit_formula_on_ratios(
        a in proptest::prelude::any::<i32>(), b in proptest::prelude::any::<i32>(),
        sa in 0u32..32, sb in 0u32..32,
    ) {
        for (x, y) in [(a, b), (a >> sa, b >> sb), (a >> sa, b), (a, b >> sb)] {
            let q = div_bits_unit(x, y);
            if x.unsigned_abs() <= y.unsigned_abs() {
                proptest::prop_assert_eq!(q, div_bits_reference(x, y), "{} / {}", x, y);
            }
            proptest::prop_assert!((-(1 << 16)..=1 << 16).contains(&q), "{} / {}", x, y);
            proptest::prop_assert!(x == 0 || q == 0 || (q < 0) == ((x < 0) != (y < 0)), "{} / {}", x, y);
            proptest::prop_assert!(x != 0 || q == 0);
        }
    }

    /// Ties and their neighbours at every scale: `|b| = c·2ʲ`,
    /// `|a| = c·(2q + 1)·2^(j−17)` (`j ≥ 17`) is a tie, `a ± 1` are not.
    #[test]
    fn div_bits_equals_the_64_bit_formula_at_ties(
        c in 0i64..(1 << 14), j in 17u32..32, q in 0i64..(1 << 31), neg_a: bool, neg_b: bool,
    ) {
        // c·2ʲ ≤ 2³¹ and c·(2q + 1)·2^(j−17) ≤ 2³¹.
        let c = 1 + c % (1 << (31 - j));
        let q = q % ((((1i64 << (48 - j)) / c - 1) / 2) + 1);
        let (a, b) = ((c * (2 * q + 1)) << (j - 17), c << j);
        for a in [a - 1, a, a + 1] {
            let x = if neg_a { -a } else { a };
            let y = if neg_b { -b } else { b };
            if (i32::MIN as i64..=i32::MAX as i64).contains(&x) && (i32::MIN as i64..=i32::MAX as i64).contains(&y) {
                let (x, y) = (x as i32, y as i32);
                proptest::prop_assert_eq!(div_bits(x, y), div_bits_reference(x, y), "{} / {}", x, y);
            }
        }
    }
}

/// `div_bits_unit` against the 64-bit formula on every ratio
/// `|a| ≤ |b|` with `|b| ≤ 2¹⁰` (both signs), at the layer's ends and
/// ties, and its clamp outside the ratio domain.
#[test]
fn div_bits_unit_is_the_quotient_of_every_small_ratio() {
    for b in -1024i32..=1024 {
        for a in -b.abs()..=b.abs() {
            assert_eq!(div_bits_unit(a, b), div_bits_reference(a, b), "{a} / {b}");
        }
    }
    for b in div_edges().into_iter().filter(|&b| b != 0) {
        let m = b.unsigned_abs().min(i32::MAX as u32) as i32;
        for a in [0, 1, -1, m, -m, m - 1, 1 - m, m / 2, -(m / 2), m / 3] {
            assert_eq!(div_bits_unit(a, b), div_bits_reference(a, b), "{a} / {b}");
        }
    }
    // Outside |a| ≤ |b|: ±1 with the quotient's sign; 0/0 = 0.
    assert_eq!(div_bits_unit(5, 3), 1 << 16);
    assert_eq!(div_bits_unit(-5, 3), -(1 << 16));
    assert_eq!(div_bits_unit(5, -3), -(1 << 16));
    assert_eq!(div_bits_unit(i32::MIN, 1), -(1 << 16));
    assert_eq!(div_bits_unit(7, 0), 1 << 16);
    assert_eq!(div_bits_unit(0, 0), 0);
}

#[test]
fn div_rounds_to_nearest_and_saturates() {
    assert_eq!(div_bits(1 << 16, 3 << 16), 21845); // 1/3 = 21845.33 LSB
    assert_eq!(div_bits(2 << 16, 3 << 16), 43691); // 2/3 = 43690.67 LSB
    assert_eq!(div_bits(-(2 << 16), 3 << 16), -43691);
    assert_eq!(div_bits(5, 0), i32::MAX);
    assert_eq!(div_bits(-5, 0), i32::MIN);
    assert_eq!(div_bits(0, 0), 0);
    assert_eq!(div_bits(i32::MIN, -(1 << 16)), i32::MAX);
}

#[test]
fn conversions_round_trip_and_saturate() {
    let x = I16F16::from_bits(-123_457);
    assert_eq!(<I16F16 as Scalar>::from_f64(x.to_f64()), x);
    assert_eq!(<I16F16 as Scalar>::from_f64(1e9), I16F16::MAX);
    assert_eq!(<I16F16 as Scalar>::from_f64(f64::NAN), I16F16::ZERO);
    assert_eq!(<I16F16 as Scalar>::from_i32(40_000), I16F16::MAX);
    assert_eq!(<I16F16 as Scalar>::from_i32(-7).to_f64(), -7.0);
}

/// `dot_direction_positive` on `I16F16`: for directions `(u, v)` at 4,096
/// angles (the stored sine and cosine, both signs of every quadrant and
/// the axes) and vectors `(a, c)` of the unit disc on a polar grid down to
/// a few LSB, the sign is that of the exact dot product of the stored
/// values (in `f64`) wherever that product exceeds the documented margin
/// `3·2⁻¹⁶(|a| + |c|)`, and the test never overflows (the extreme words
/// `±2¹⁶` included).
#[test]
fn dot_direction_sign_is_exact_beyond_its_margin() {
    use crate::scalar::Scalar;
    let lsb = 1.0 / 65536.0;
    let mut checked = 0usize;
    let mut undecided = 0usize;
    for k in 0..4096 {
        let t = k as f64 * core::f64::consts::TAU / 4096.0;
        let (v, u) = (I16F16::from_num(t.sin()), I16F16::from_num(t.cos()));
        for r in [1.0, 0.7, 0.1, 1e-2, 1e-3, 2e-4, 4.0 * lsb] {
            for j in 0..64 {
                let w = j as f64 * core::f64::consts::TAU / 64.0 + 0.013;
                let a = I16F16::from_num(r * w.cos());
                let c = I16F16::from_num(r * w.sin());
                let exact = a.to_f64() * u.to_f64() + c.to_f64() * v.to_f64();
                let margin = 3.0 * lsb * (a.to_f64().abs() + c.to_f64().abs());
                let got = a.dot_direction_positive(u, c, v);
                if exact.abs() > margin {
                    assert_eq!(got, exact > 0.0, "a {a} u {u} c {c} v {v}: {exact}");
                    checked += 1;
                } else {
                    undecided += 1;
                }
            }
        }
    }
    // The margin leaves only a thin band near the perpendicular undecided.
    assert!(undecided * 50 < checked, "{undecided} of {checked}");
    // The extremes: (±1, ±1) against (±1, 0), (0, ±1).
    let one = I16F16::ONE;
    for (a, c) in [(one, one), (-one, one), (one, -one), (-one, -one)] {
        for (u, v) in [
            (one, I16F16::ZERO),
            (I16F16::ZERO, one),
            (-one, I16F16::ZERO),
        ] {
            let exact = a.to_f64() * u.to_f64() + c.to_f64() * v.to_f64();
            assert_eq!(a.dot_direction_positive(u, c, v), exact > 0.0);
        }
    }
}
