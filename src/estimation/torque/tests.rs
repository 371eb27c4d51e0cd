use super::*;
use crate::harmonic_drive::CatalogueData;
use crate::scalar::target::mul_wide_split;
use crate::scalar::I16F16;
use proptest::prelude::*;
use std::string::ToString;

const L: u32 = 1 << 17;
const M: u32 = 2000;

/// The reciprocal division, and the division that skips `x < d`, equal
/// `/` and `%` on edges of every kind:
/// divisors 1, 2, powers of two and their neighbours, the estimator's
/// M, N and L, the largest `u32`; dividends around multiples of `d`
/// and at the ends of the `u32` range.
#[test]
fn reciprocal_division_is_exact_on_edges() {
    let mut ds = vec![1u32, 2, 3, 7, 100, 160, M, L, u32::MAX, u32::MAX - 1];
    for k in 1..32 {
        ds.extend([(1u32 << k) - 1, 1 << k, (1 << k) + 1]);
    }
    for &d in &ds {
        let mut xs = vec![0u32, 1, d - 1, d, d.wrapping_add(1), u32::MAX, u32::MAX - 1];
        xs.extend([1u32 << 31, (1 << 31) - 1, (1 << 31) + 1]);
        let top = u32::MAX / d;
        for q in [1, 2, top / 2, top - 1, top] {
            let base = q.wrapping_mul(d);
            xs.extend([base, base.wrapping_sub(1), base.wrapping_add(1)]);
        }
        for x in xs {
            assert_eq!(
                div_rem_reciprocal(x, d, reciprocal(d)),
                (x / d, x % d),
                "{x} / {d}"
            );
            // Both forms of the skip: with and without a divide instruction.
            let div = Divisor::new(d);
            assert_eq!(
                div.div_rem_or_skip::<false>(x, d),
                (x / d, x % d),
                "{x} / {d}"
            );
            assert_eq!(
                div.div_rem_or_skip::<true>(x, d),
                (x / d, x % d),
                "{x} / {d}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100_000))]
    /// The reciprocal division equals `/` and `%` for random operands.
    #[test]
    fn reciprocal_division_is_exact(x: u32, d in 1u32.., small in 1u32..5000) {
        for d in [d, small] {
            prop_assert_eq!(div_rem_reciprocal(x, d, reciprocal(d)), (x / d, x % d));
            prop_assert_eq!(Divisor::new(d).div_rem_or_skip::<false>(x, d), (x / d, x % d));
        }
    }
}

fn params(ke: Option<KinematicErrorModel>) -> TorqueEstimatorParams {
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: ke,
        link_counts_per_rev: L,
        motor_counts_per_rev: M,
        max_torque: 60.0,
    })
    .unwrap()
}

/// The SHD-17-100 estimator with other encoders `L`, `M` and ratio `N`.
fn params_sized(ke: Option<KinematicErrorModel>, l: u32, m: u32, n: u32) -> TorqueEstimatorParams {
    let d = CatalogueData::SHD_17_100.identify().unwrap();
    let drive = HarmonicDriveParams::try_new(d.flexspline(), d.wave_generator(), n as f64).unwrap();
    TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: ke,
        link_counts_per_rev: l,
        motor_counts_per_rev: m,
        max_torque: 60.0,
    })
    .unwrap()
}

/// Encoder readings for a joint at link angle `link` (rad) carrying a
/// flexspline torque `tau` with motor torque `tau_w` (forward model,
/// eq. 2.30 and 3.8), and the half-width of the torsion quantization.
fn readings(p: &TorqueEstimatorParams, link: f64, tau: f64, tau_w: f64) -> (u32, i64, f64) {
    let n = p.drive.ratio();
    let base = p.drive.torsion(tau, tau_w);
    let mut torsion = base;
    if let Some(k) = p.kinematic_error {
        // θ_err depends on the measured motor angle θ_wi = N(Δθ − θ_fo),
        // which depends on the torsion: solve Δθ = base + θ_err by
        // fixed-point iteration (a contraction: N·|dθ_err/dθ_wi| < 0.02).
        for _ in 0..30 {
            torsion = base + k.evaluate(link, n * (torsion - link));
        }
    }
    let motor = n * (torsion - link); // eq. (2.13) solved for θ_wi
    let c_l = libm::round(link / TAU * L as f64) as i64;
    let p_m = libm::round(motor / TAU * M as f64) as i64;
    let q = TAU / L as f64 * 0.5 + TAU / (M as f64 * n) * 0.5;
    (c_l.rem_euclid(L as i64) as u32, p_m, q)
}

proptest! {
    /// Round trip through the forward model: the estimate lies between
    /// the torques of the flexspline torsions ± the encoder quantization
    /// (plus the kinematic error's change over one count), by
    /// monotonicity of eq. (3.10).
    #[test]
    fn estimate_inverts_the_forward_model(
        link in 0.0f64..TAU, tau in -40.0f64..40.0, tau_w in -0.2f64..0.2, with_ke: bool,
    ) {
        let ke = with_ke.then(KinematicErrorModel::table_3_2);
        let p = params(ke);
        let (c_l, p_m, q) = readings(&p, link, tau, tau_w);
        let cfg = TorqueEstimatorConfig::<f64>::new(&p);
        let mut st = cfg.state(p_m, 12345);
        let est = cfg.update(&mut st, c_l, 12345, tau_w);
        prop_assert!(!est.saturated);
        let ke_slope = ke.map_or(0.0, |k| {
            let c = k.coefficients();
            (c[1].abs() + c[2].abs()) * TAU / L as f64 + (c[3].abs() + c[4].abs() + 2.0 * (c[5].abs() + c[6].abs())) * TAU / M as f64
        });
        let d = q + ke_slope + 1e-12;
        let f = p.drive.flexspline();
        let true_tf = f.torsion(tau);
        let (lo, hi) = (f.torque(true_tf - d).torque, f.torque(true_tf + d).torque);
        prop_assert!(est.torque >= lo - 1e-9 && est.torque <= hi + 1e-9, "{} not in [{lo}, {hi}] (τ = {tau})", est.torque);
    }

    /// The motor position follows a wrapping 32-bit counter through any
    /// sequence of moves (each under 2³¹ counts).
    #[test]
    fn motor_position_follows_wrapping_counter(
        start in any::<u32>(), pos0 in -1_000_000i64..1_000_000,
        moves in proptest::collection::vec(-5_000_000i64..5_000_000, 1..50),
    ) {
        let p = params(None);
        let cfg = TorqueEstimatorConfig::<f64>::new(&p);
        let mut st = cfg.state(pos0, start);
        let (mut counter, mut pos) = (start, pos0);
        let mn = (M * 100) as i64;
        for mv in moves {
            counter = counter.wrapping_add(mv as i32 as u32);
            pos += mv;
            cfg.advance(&mut st, counter);
            let want = pos.rem_euclid(mn);
            prop_assert_eq!(st.motor_turn as i64 * M as i64 + st.motor_in_turn as i64, want);
            prop_assert_eq!(cfg.motor_position_counts(&st) as i64, want);
        }
    }

    /// I16F16 agrees with f64 on the count path (the full-range
    /// exhaustive sweep is in proofs/); here: within 0.5 % of the rated
    /// 16 N·m over the torque range.
    #[test]
    fn fixed_agrees_with_f64(link in 0.0f64..TAU, tau in -40.0f64..40.0, tau_w in -0.2f64..0.2) {
        let p = params(Some(KinematicErrorModel::table_3_2()));
        let (c_l, p_m, _) = readings(&p, link, tau, tau_w);
        let cf = TorqueEstimatorConfig::<f64>::new(&p);
        let cx = TorqueEstimatorConfig::<I16F16>::new(&p);
        let a = cf.update(&mut cf.state(p_m, 0), c_l, 0, tau_w).torque;
        let b = cx.update(&mut cx.state(p_m, 0), c_l, 0, I16F16::from_f64(tau_w * 1e3)).torque.to_f64();
        prop_assert!((a - b).abs() <= 0.005 * 16.0, "{a} vs {b}");
    }
}

proptest! {
    /// f32 and I16F16 lie within their documented `AgreementBound` of
    /// f64 on the SHD-17-100 (with and without Table 3.2), over the
    /// torque range and beyond (saturation), on the count path.
    #[test]
    fn backends_within_the_agreement_bound(
        link in 0.0f64..TAU, tau in -80.0f64..80.0, tau_w in -0.2f64..0.2, with_ke: bool,
    ) {
        let p = params(with_ke.then(KinematicErrorModel::table_3_2));
        let (c_l, p_m, _) = readings(&p, link, tau, tau_w);
        let cf = TorqueEstimatorConfig::<f64>::new(&p);
        let a = cf.update(&mut cf.state(p_m, 0), c_l, 0, tau_w);
        fn backend<S: Scalar>(p: &TorqueEstimatorParams, c_l: u32, p_m: i64, tau_w: f64) -> TorqueEstimate<S> {
            let c = TorqueEstimatorConfig::<S>::new(p);
            c.update(&mut c.state(p_m, 0), c_l, 0, S::from_f64(tau_w * S::UNITS.motor_torque))
        }
        for (b, bound) in [
            (backend::<f32>(&p, c_l, p_m, tau_w), p.agreement_bound::<f32>()),
        ].into_iter().map(|(b, bd)| ((b.torque_si(), b.flexspline_torsion_si()), bd))
            .chain([{
                let b = backend::<I16F16>(&p, c_l, p_m, tau_w);
                ((b.torque_si(), b.flexspline_torsion_si()), p.agreement_bound::<I16F16>())
            }])
        {
            let (lo, hi) = bound.torque_interval(&p, a.flexspline_torsion);
            prop_assert!(lo <= b.0 && b.0 <= hi, "{} not in [{lo}, {hi}]", b.0);
            prop_assert!((b.1 - a.flexspline_torsion).abs() <= bound.torsion);
        }
    }
}

/// f32 stays within its agreement bound with harmonics of millirad
/// (the `api_params` fuzz target found a drive with a 7.3 mrad one
/// beyond the bound that ignored the table cosine's error).
#[test]
fn f32_agreement_bound_covers_a_large_kinematic_error() {
    let k =
        KinematicErrorModel::try_new([4.4e-5, 1e-7, 6.4e-5, -6.2e-5, -1e-7, 7.3e-3, 1e-7]).unwrap();
    let p = params(Some(k));
    let bound = p.agreement_bound::<f32>();
    let (c64, c32) = (
        TorqueEstimatorConfig::<f64>::new(&p),
        TorqueEstimatorConfig::<f32>::new(&p),
    );
    let rigid = params(None);
    let mut worst = 0.0f64;
    for i in 0..2000 {
        let link = TAU * i as f64 / 2000.0;
        for tau in [-30.0, -3.0, 0.0, 5.0, 40.0] {
            let (c_l, p_m, _) = readings(&rigid, link, tau, 0.0);
            let a = c64.update(&mut c64.state(p_m, 0), c_l, 0, 0.0);
            let b = c32.update(&mut c32.state(p_m, 0), c_l, 0, 0.0);
            let e = (b.flexspline_torsion_si() - a.flexspline_torsion).abs();
            assert!(
                e <= bound.torsion,
                "{e} > {} at {c_l}, {p_m}",
                bound.torsion
            );
            worst = worst.max(e);
        }
    }
    // Above what the full-accuracy cosines allowed (the former bound,
    // `2(8u·range + 8u·A_w + (30u + e_θ)·A)`): the test fails without
    // the table cosine's term.
    let u = libm::exp2(-24.0);
    let e_theta = 3.5 * TAU / 4_294_967_296.0;
    let former = 2.0
        * (8.0 * u * p.torsion_range()
            + 8.0 * u * p.drive.output_wave_generator_torsion()
            + (30.0 * u + e_theta) * k.amplitude_bound());
    std::eprintln!(
        "f32 Δθ_f worst {worst:e}, bound {:e}, former {former:e}",
        bound.torsion
    );
    assert!(worst > former, "{worst:e} <= {former:e}");
}

/// The agreement bound is the sum its documentation states, evaluated
/// here term by term with the documented constants (`2⁻¹⁵`, `2⁻¹⁷`,
/// `e_θ = 3.5 · 2π/2³²`, `ε_c = 4.8e-6`), on a drive whose three
/// harmonic amplitudes differ (5e-5, 1e-4, 2e-4 rad, offset 1e-5 rad), so
/// that every term moves the result; `torsion_range` and the parameter
/// getters likewise.
#[test]
fn agreement_bound_is_the_documented_sum() {
    let k = KinematicErrorModel::try_new([1e-5, 3e-5, 4e-5, 6e-5, 8e-5, 1.2e-4, 1.6e-4]).unwrap();
    let p = params(Some(k));
    assert_eq!(p.kinematic_error(), Some(k));
    assert_eq!(params(None).kinematic_error(), None);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    let d = CatalogueData::SHD_17_100.identify().unwrap();
    let (c_f, k_f0) = (d.flexspline().c_f(), d.flexspline().k_f0());
    let (c_w, k_w0) = (d.wave_generator().c_w(), d.wave_generator().k_w0());
    let a_w = 1.0 / (c_w * 100.0 * k_w0); // rad at the output, N = 100
    let amp = 1e-5 + 5e-5 + 1e-4 + 2e-4; // |a_0| + R_l + R_1 + R_2
    let range = 1.01 * (core::f64::consts::FRAC_PI_2 / (c_f * k_f0) + a_w + amp);
    assert!(
        close(p.torsion_range(), range),
        "{} vs {range}",
        p.torsion_range()
    );
    let e_theta = 3.5 * TAU / 4_294_967_296.0;

    // I16F16, in mrad: q = 2⁻¹⁶ mrad.
    let q = libm::exp2(-16.0);
    let a_w_mrad = 1e3 * a_w;
    let wave = a_w_mrad * (libm::exp2(-15.0) + libm::exp2(-17.0) * (1.0 + c_w / 1e3)) + q / 2.0;
    let harmonics: f64 = [5e-5, 1e-4, 2e-4]
        .iter()
        .map(|r| q + 1e3 * r * (q + e_theta))
        .sum();
    let kin = q / 2.0 + harmonics;
    let angle = 1e3 * libm::exp2(-17.0) / (c_f * k_f0);
    let b = p.agreement_bound::<I16F16>();
    let torsion = 2.0 * (q / 2.0 + wave + kin + angle) * 1e-3;
    assert!(close(b.torsion, torsion), "{} vs {torsion}", b.torsion);
    assert_eq!(b.torque_relative, libm::exp2(-28.0));
    let absolute = 2.0 * (q / c_f + q);
    assert!(
        close(b.torque_absolute, absolute),
        "{} vs {absolute}",
        b.torque_absolute
    );

    // f32: u = 2⁻²⁴.
    let u = libm::exp2(-24.0);
    let b = p.agreement_bound::<f32>();
    let torsion =
        2.0 * (8.0 * u * range + 8.0 * u * a_w + (30.0 * u + 8.0 * (4.8e-6 + e_theta)) * amp);
    assert!(close(b.torsion, torsion), "{} vs {torsion}", b.torsion);
    assert_eq!(b.torque_relative, libm::exp2(-19.0));

    // f64 is the reference.
    let b = p.agreement_bound::<f64>();
    assert_eq!(
        (b.torsion, b.torque_relative, b.torque_absolute),
        (0.0, 0.0, 0.0)
    );
}

/// `torque_interval` is eq. (3.10) at `Δθ_f ∓ torsion`, widened by the
/// relative and the absolute bound, each computed here by hand; beyond
/// the `tan` branch it is `±max_torque`.
#[test]
fn torque_interval_widens_eq_3_10_by_both_bounds() {
    let p = params(None);
    let f = p.drive().flexspline();
    let b = AgreementBound {
        torsion: 1e-4,
        torque_relative: 0.01,
        torque_absolute: 0.5,
    };
    let eq_3_10 = |x: f64| libm::tan(x * f.c_f() * f.k_f0()) / f.c_f();
    let x = f.torsion(10.0);
    let (lo, hi) = b.torque_interval(&p, x);
    let (t_lo, t_hi) = (eq_3_10(x - 1e-4), eq_3_10(x + 1e-4));
    assert!(0.0 < t_lo && t_lo < 10.0 && 10.0 < t_hi, "{t_lo} {t_hi}");
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(
        close(lo, 0.99 * t_lo - 0.5),
        "{lo} vs {}",
        0.99 * t_lo - 0.5
    );
    assert!(
        close(hi, 1.01 * t_hi + 0.5),
        "{hi} vs {}",
        1.01 * t_hi + 0.5
    );
    // Negative torsion: the relative term widens away from zero again.
    let (lo, hi) = b.torque_interval(&p, -x);
    assert!(
        close(lo, -1.01 * t_hi - 0.5) && close(hi, -0.99 * t_lo + 0.5),
        "{lo} {hi}"
    );
    // Past the branch (and past the limit) both ends are the limit, widened.
    let (lo, hi) = b.torque_interval(&p, 2.0 * f.max_torsion());
    assert!(
        close(lo, 60.0 * 0.99 - 0.5) && close(hi, 60.0 * 1.01 + 0.5),
        "{lo} {hi}"
    );
}

/// `last_counter` is the counter given to `state` and then to each
/// `update`, whatever the direction of the move.
#[test]
fn last_counter_is_the_last_counter_given() {
    let p = params(None);
    let c = TorqueEstimatorConfig::<f64>::new(&p);
    let mut st = c.state(12_345, 777);
    assert_eq!(st.last_counter(), 777);
    for counter in [900u32, 5, u32::MAX - 3, 41] {
        let _ = c.update(&mut st, 0, counter, 0.0);
        assert_eq!(st.last_counter(), counter);
    }
}

/// The agreement bound is not vacuous: at a loaded torsion the
/// interval excludes 0 (a silent 0 fails it) and is narrower than
/// 0.01 N·m on I16F16 and 1e-3 N·m on f32.
#[test]
fn agreement_bound_rejects_a_silent_zero() {
    let p = params(Some(KinematicErrorModel::table_3_2()));
    let torsion = p.drive().flexspline().torsion(10.0);
    for (bound, width) in [
        (p.agreement_bound::<I16F16>(), 0.01),
        (p.agreement_bound::<f32>(), 1e-3),
    ] {
        let (lo, hi) = bound.torque_interval(&p, torsion);
        assert!(lo > 0.0 && hi - lo < width, "[{lo}, {hi}]");
        assert!(lo <= 10.0 && 10.0 <= hi);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]
    /// The 32-bit `advance` equals the 64-bit formula from any state
    /// for any counter (moves up to ±2³¹ counts), on the Table 3.2
    /// drive and on encoder/ratio sizes with M, N near the edges.
    #[test]
    fn advance_equals_the_64_bit_formula(
        pos in 0i64..1 << 40, last in any::<u32>(), counter in any::<u32>(), small: bool,
        size in 0usize..4,
    ) {
        let (m, n) = [(M, 100u32), (1, 1), (3, 65535), (1 << 20, 160)][size];
        // The link encoder plays no part in `advance`; L = 1 keeps every
        // size within the validated `L·M·N`.
        let p = params_sized(None, 1, m, n);
        let cfg = TorqueEstimatorConfig::<f64>::new(&p);
        let counter = if small { last.wrapping_add(counter % 8001).wrapping_sub(4000) } else { counter };
        let mut a = cfg.state(pos, last);
        let mut b = a;
        cfg.advance(&mut a, counter);
        cfg.advance_reference(&mut b, counter);
        prop_assert_eq!(a, b);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]
    /// `update` forms the torsion count `D` of eq. (2.13) exactly: equal
    /// to the i128 formula `c_l·MN + p·L` reduced to `[−LMN/2, LMN/2)`.
    #[test]
    fn update_uses_the_exact_torsion_count(
        c_l in 0u32..L, pos in -(1i64 << 40)..(1i64 << 40), tw in -200i32..200,
    ) {
        let cfg = TorqueEstimatorConfig::<I16F16>::new(&params(None));
        let tw = I16F16::from_num(tw);
        let mut st = cfg.state(pos, 7);
        let got = cfg.update(&mut st, c_l, 7, tw);
        let (l, mn) = (L as i128, (M * 100) as i128);
        let p = (pos as i128).rem_euclid(mn);
        let d = (c_l as i128 * mn + p * l + l * mn / 2).rem_euclid(l * mn) - l * mn / 2;
        let want = cfg.estimate_from_torsion_counts(d as i64, I16F16::ZERO, tw, false);
        prop_assert_eq!(got, want);
    }

    /// `mul_wide` is the exact product on both of its paths.
    #[test]
    fn mul_wide_is_exact(a in any::<u32>(), b in 0i64..1 << 48, narrow: bool) {
        // Products below 2⁶⁴, as at the call sites.
        let (a, b) = if narrow { (a >> 1, b & 0xFFFF_FFFF) } else { (a >> 17, b) };
        prop_assert_eq!(mul_wide(a, b) as u128, a as u128 * b as u128);
    }

    /// The Armv6-M form of `mul_wide` is the exact product (bits of the
    /// 64-bit product) for a 32-bit `b` and for every product below
    /// 2⁶³ (the call sites' range).
    #[test]
    fn mul_wide_split_is_exact(a in any::<u32>(), b in 0i64..1 << 48, narrow: bool) {
        let (a, b) = if narrow { (a, b & 0xFFFF_FFFF) } else { (a >> 17, b) };
        prop_assert_eq!(mul_wide_split(a, b) as u64 as u128, a as u128 * b as u128);
    }
}

/// The split conversion of a torsion count equals `from_counts` bit
/// for bit on floats for every `|d| < 2⁴⁷`: the edges, both sides of
/// every power of two and of the 2²⁴ split, halfway cases, random
/// counts (`from_counts` on `f32` is the correctly rounded
/// `count_to_f32`, tested against `as` in `scalar::float`).
#[test]
fn torsion_of_counts_equals_from_counts_below_2_47() {
    let mut ds = vec![
        0i64,
        1,
        -1,
        (1 << 47) - 1,
        -(1 << 47),
        (1 << 24) - 1,
        1 << 24,
    ];
    for k in 0..47 {
        for e in [-3i64, -1, 0, 1, 2, 3] {
            ds.extend([(1i64 << k) + e, -(1i64 << k) + e]);
        }
        if k > 25 {
            // Halfway between two f32 values, and one count off it.
            let h = (1i64 << k) + (1 << (k - 24));
            ds.extend([h, h - 1, h + 1, -h, -h + 1, -h - 1]);
        }
    }
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    for _ in 0..200_000 {
        let x = crate::scalar::xorshift64(&mut state);
        ds.push((x as i64) >> (17 + x % 40));
    }
    for c in [
        Coef::new(1.0),
        Coef::new(TAU / 2.62144e10),
        Coef::new(3.7e-7),
    ] {
        for &d in &ds {
            assert!(d.unsigned_abs() <= 1 << 47, "{d}");
            if d == 1 << 47 {
                continue;
            }
            let (a, b): (f32, f32) = (torsion_of_counts(d, &c), f32::from_counts(d, &c));
            assert_eq!(a.to_bits(), b.to_bits(), "f32 {d}");
            let (a, b): (f64, f64) = (torsion_of_counts(d, &c), f64::from_counts(d, &c));
            assert_eq!(a.to_bits(), b.to_bits(), "f64 {d}");
        }
    }
}

/// The error bound of the module docs ("Kinematic error from counts")
/// for backend `S`, in stored torsion units, plus the `f64`
/// reference's own rounding (`8 ε A`).
fn ke_count_bound<S: Scalar>(k: &KinematicErrorModel) -> f64 {
    let f = k.phase_form();
    let t = S::UNITS.torsion;
    let (a0, r) = (f.offset.abs() * t, f.amplitudes.map(|r| r * t));
    let a = a0 + r.iter().sum::<f64>();
    let e_theta = 3.5 * TAU / 4_294_967_296.0;
    let reference = 8.0 * f64::EPSILON * a;
    let bound = if S::NAME == "I16F16" {
        let q = 1.0 / 65536.0;
        q / 2.0
            + r.iter()
                .map(|&rj| q / 2.0 * (1.0 + q) + rj * (q + e_theta) + q / 2.0)
                .sum::<f64>()
    } else {
        assert_eq!(S::NAME, "f32");
        // The double-angle form of the motor harmonics (module docs).
        let u = f32::EPSILON as f64 / 2.0; // 2⁻²⁴
                                           // cos_turn_coarse, sin_cos_turn_coarse: 4.8e-6.
        let c = crate::scalar::kernels::f32::COS_TURN_COARSE_BOUND;
        a0 * u
            + r[0] * (2.0 * u + c + e_theta)
            + (r[1] + 8.0 * r[2]) * (c + e_theta)
            + u * (2.0 * r[1] + 15.0 * r[2])
            + 2.0 * u * (a0 + r[0] + r[1] + 3.0 * r[2])
            + 4.0 * r[2] * (c + e_theta) * (c + e_theta)
            + 40.0 * u * u * a
    };
    bound + reference
}

/// Counts to test for an encoder of `n` counts: 0, `n − 1`, the
/// quadrant boundaries and their neighbours, and a stride.
fn test_counts(n: u32) -> Vec<u32> {
    let mut v = vec![0, 1, n - 1];
    for q in 1..4u32 {
        let b = (n as u64 * q as u64 / 4) as u32;
        v.extend([b.saturating_sub(1), b, b + 1]);
    }
    let step = (n / 157).max(1);
    v.extend((0..n).step_by(step as usize));
    v.retain(|&c| c < n);
    v
}

/// The largest error of the count-based eq. (3.7) of backend `S`
/// against `f64` [`KinematicErrorModel::evaluate`] at the count angles
/// `2π c_l/L`, `2π p/M` (stored units), over the test counts; panics
/// beyond [`ke_count_bound`].
fn ke_count_worst<S: Scalar>(k: KinematicErrorModel, l: u32, m: u32) -> f64 {
    let p = params_sized(Some(k), l, m, 100);
    let cfg = TorqueEstimatorConfig::<S>::new(&p);
    let bound = ke_count_bound::<S>(&k);
    let mut worst = 0.0f64;
    for c in test_counts(l) {
        for q in test_counts(m) {
            let want =
                k.evaluate(TAU * c as f64 / l as f64, TAU * q as f64 / m as f64) * S::UNITS.torsion;
            let got = cfg.kinematic_error_from_counts(c, q).to_f64();
            let e = (got - want).abs();
            assert!(
                e <= bound,
                "{} L = {l}, M = {m}, c_l = {c}, p = {q}: {got} vs {want} (bound {bound})",
                S::NAME
            );
            worst = worst.max(e / bound);
        }
    }
    worst
}

/// The count-based kinematic error (phase form, binary angles,
/// `cos_turn`) agrees with `f64` eq. (3.7) within the derived bound on
/// I16F16 and f32, for Table 3.2 and a larger model with an offset,
/// with power-of-two and other encoder resolutions.
#[test]
fn kinematic_error_from_counts_within_bound() {
    let larger =
        KinematicErrorModel::try_new([2e-4, 3e-4, -1e-4, -2e-4, 1.5e-4, 1e-4, -3e-4]).unwrap();
    let mut worst = [0.0f64; 2];
    for k in [KinematicErrorModel::table_3_2(), larger] {
        for (l, m) in [(L, M), (100_000, 4096), (36_000, 1000), (1 << 20, 3)] {
            worst[0] = worst[0].max(ke_count_worst::<I16F16>(k, l, m));
            worst[1] = worst[1].max(ke_count_worst::<f32>(k, l, m));
        }
    }
    std::eprintln!(
        "kinematic error from counts, worst error / bound: I16F16 {:.3}, f32 {:.3}",
        worst[0],
        worst[1]
    );
    // The bound is not vacuous: the errors reach a visible part of it.
    assert!(worst.iter().all(|&w| w > 0.05), "worst / bound: {worst:?}");
}

/// `update` subtracts exactly the count-based kinematic error.
#[test]
fn update_subtracts_the_count_based_kinematic_error() {
    let p = params(Some(KinematicErrorModel::table_3_2()));
    let cfg = TorqueEstimatorConfig::<I16F16>::new(&p);
    let tw = I16F16::from_num(3);
    // Motor positions near the rigid one, `−c_l·MN/L`, so that the
    // torsion stays inside the model's range.
    let mn = M as i64 * 100;
    for (c_l, off) in [(0u32, 0i64), (L / 4, 5), (L - 1, -3), (77_777, 2)] {
        let pos = -(c_l as i64 * mn / L as i64) + off;
        let with = cfg.update(&mut cfg.state(pos, 0), c_l, 0, tw);
        let ke = cfg.kinematic_error_from_counts(c_l, pos.rem_euclid(M as i64) as u32);
        assert_ne!(ke, I16F16::ZERO);
        assert_eq!(with.flexspline_torsion, {
            let none = TorqueEstimatorConfig::<I16F16>::new(&params(None));
            none.update(&mut none.state(pos, 0), c_l, 0, tw)
                .flexspline_torsion
                - ke
        });
    }
}

#[test]
fn out_of_branch_torsion_saturates_at_max_torque_with_flag() {
    let p = params(None);
    let cfg = TorqueEstimatorConfig::<f32>::new(&p);
    let n = 100i64;
    // A link angle of +0.01 rad with the motor at rest: Δθ = 10 mrad,
    // beyond the flexspline's 4.2 mrad maximum.
    let c_l = (0.01 / TAU * L as f64) as u32;
    let mut st = cfg.state(0, 0);
    let e = cfg.update(&mut st, c_l, 0, 0.0);
    assert!(e.saturated && e.torque == 60.0, "{e:?}");
    let mut st = cfg.state(0, 0);
    let e = cfg.update(&mut st, L - c_l, 0, 0.0);
    assert!(e.saturated && e.torque == -60.0, "{e:?}");
    // An invalid link count is reduced and flagged.
    let mut st = cfg.state(0, 0);
    let e = cfg.update(&mut st, L, 0, 0.0);
    assert!(e.link_count_invalid && e.torque == 0.0);
    let _ = n;
}

/// The saturation of `finish` by one comparison against the prepared
/// `torsion_limit` equals the two direct tests it replaces (the `tan`
/// argument beyond `atan 8`, the domain of `tan_bounded`, then
/// `|τ| > max_torque`) at every torsion tried: on `I16F16` every code
/// within twice the branch edge, on the floats a thousand codes either
/// side of the limit and a log sweep. The limit is tight: the direct
/// test passes at it and fails at the next code up, and it is set by
/// `max_torque`, not by the domain. Two set-ups: SHD-17-100 at 60 N·m
/// and at the largest accepted `max_torque`, `7.5/c_f = 166.9` N·m; a
/// limit above that is rejected by name.
#[test]
fn saturation_by_torsion_limit_equals_the_direct_tests() {
    fn direct<S: Scalar>(cfg: &TorqueEstimatorConfig<S>, ft: S) -> (S, bool) {
        let f = &cfg.flexspline;
        let angle = f.angle_of(ft);
        let bound = S::from_f64(crate::harmonic_drive::compliance::TAN_BOUNDED_ARGUMENT);
        let t = f.torque_in_branch(ft);
        let sat = angle.abs() > bound || t.abs() > cfg.max_torque;
        let m = cfg.max_torque;
        let torque = match (sat, ft < S::ZERO) {
            (false, _) => t,
            (true, true) => m.neg(),
            (true, false) => m,
        };
        (torque, sat)
    }
    fn agree<S: Scalar + core::fmt::Debug>(cfg: &TorqueEstimatorConfig<S>, ft: S) {
        let e = cfg.finish(ft, None, S::ZERO, S::ZERO, false, false);
        assert_eq!((e.torque, e.saturated), direct(cfg, ft), "at {ft:?}");
    }
    /// Whether the torque (not the domain) fails just above the limit.
    fn torque_bound<S: Scalar>(cfg: &TorqueEstimatorConfig<S>, up: S) -> bool {
        let t = |x: S| cfg.flexspline.torque_in_branch(x).abs() > cfg.max_torque;
        t(up) || t(up.neg())
    }
    /// Checks one float configuration; returns whether the next torsion
    /// above the limit fails by its torque.
    fn floats<S: Scalar + core::fmt::Debug>(
        cfg: &TorqueEstimatorConfig<S>,
        step: impl Fn(S, i32) -> S,
    ) -> bool {
        let a = cfg.torsion_limit;
        assert!(!direct(cfg, a).1 && !direct(cfg, a.neg()).1);
        let up = step(a, 1);
        assert!(direct(cfg, up).1 || direct(cfg, up.neg()).1);
        for k in -1000..=1000 {
            let t = step(a, k);
            agree(cfg, t);
            agree(cfg, t.neg());
        }
        let edge = a.to_f64();
        for i in 0..=4000 {
            let t = S::from_f64(edge * 1e-6 * libm::pow(2e6, i as f64 / 4000.0));
            agree(cfg, t);
            agree(cfg, t.neg());
        }
        for t in [S::ZERO, S::MAX, S::MAX.neg()] {
            agree(cfg, t);
        }
        torque_bound(cfg, up)
    }
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    let c_f = drive.flexspline().c_f();
    let settings = |max_torque: f64| TorqueEstimatorSettings {
        drive,
        kinematic_error: None,
        link_counts_per_rev: L,
        motor_counts_per_rev: M,
        max_torque,
    };
    let largest = MAX_STIFFENING_TORQUE / c_f;
    for max in [60.0, largest] {
        let p = TorqueEstimatorParams::try_new(settings(max)).unwrap();
        assert!(floats(&TorqueEstimatorConfig::<f32>::new(&p), |x, k| {
            f32::from_bits((x.to_bits() as i32 + k) as u32)
        }));
        assert!(floats(&TorqueEstimatorConfig::<f64>::new(&p), |x, k| {
            f64::from_bits((x.to_bits() as i64 + k as i64) as u64)
        }));
        let cfg = TorqueEstimatorConfig::<I16F16>::new(&p);
        let a = cfg.torsion_limit.to_bits();
        assert!(!direct(&cfg, cfg.torsion_limit).1);
        let up = I16F16::from_bits(a + 1);
        assert!(direct(&cfg, up).1 || direct(&cfg, up.neg()).1);
        assert!(torque_bound(&cfg, up));
        let edge = (drive.flexspline().max_torsion() * I16F16::UNITS.torsion * 65536.0) as i32;
        for b in -2 * edge..=2 * edge {
            agree(&cfg, I16F16::from_bits(b));
        }
        for b in [i32::MIN, i32::MIN + 1, i32::MAX] {
            agree(&cfg, I16F16::from_bits(b));
        }
    }
    let over = largest * (1.0 + 1e-9);
    assert_eq!(
        TorqueEstimatorParams::try_new(settings(over)).unwrap_err(),
        ParamError::CombinationOutOfRange {
            name: "drive.c_f·max_torque",
            value: c_f * over,
            min: 0.0,
            max: MAX_STIFFENING_TORQUE,
        }
    );
}

#[test]
fn rejects_non_integer_ratio_and_coarse_encoders() {
    let d = CatalogueData::SHD_17_100.identify().unwrap();
    let drive = HarmonicDriveParams::try_new(d.flexspline(), d.wave_generator(), 100.5).unwrap();
    let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: None,
        link_counts_per_rev: L,
        motor_counts_per_rev: M,
        max_torque: 60.0,
    })
    .unwrap_err();
    assert_eq!(
        e,
        ParamError::NotInteger {
            name: "drive.ratio",
            value: 100.5,
            min: 1.0,
            max: 65535.0
        }
    );
    assert_eq!(
        e.to_string(),
        "parameter `drive.ratio` must be an integer in [1, 65535], got 100.5"
    );
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    assert!(matches!(
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: 0,
            motor_counts_per_rev: M,
            max_torque: 60.0
        }),
        Err(ParamError::NotPositive {
            name: "link_counts_per_rev",
            ..
        })
    ));
    assert!(matches!(
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: L,
            motor_counts_per_rev: M,
            max_torque: -1.0
        }),
        Err(ParamError::NotPositive {
            name: "max_torque",
            ..
        })
    ));
    // 2^31 counts must span the torsion range: 2^26 link counts with a
    // 2^16-count motor encoder is too fine.
    assert!(matches!(
        TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: 1 << 26,
            motor_counts_per_rev: 1 << 16,
            max_torque: 60.0
        }),
        Err(ParamError::CombinationOutOfRange { name: LMN_NAME, .. })
    ));
}

/// The named encoder resolutions reach their own getters and their own
/// roles: one link count is a torsion of `2π/L`, one motor count one of
/// `2π/(M N)` (eq. 2.13, computed here from the definitions). With
/// positional `u32` arguments `L` and `M` could be swapped and still
/// validate; swapped, these torsions would be `2π/M` and `2π/(L N)`.
#[test]
fn named_encoder_resolutions_reach_their_roles() {
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    let (l, m) = (1u32 << 17, 2000u32);
    let s = TorqueEstimatorSettings {
        drive,
        kinematic_error: None,
        link_counts_per_rev: l,
        motor_counts_per_rev: m,
        max_torque: 50.0,
    };
    let p = TorqueEstimatorParams::try_new(s).unwrap();
    assert_eq!(
        (
            p.link_counts_per_rev(),
            p.motor_counts_per_rev(),
            p.max_torque()
        ),
        (l, m, 50.0)
    );
    assert_eq!(p.settings(), s);
    assert_eq!(TorqueEstimatorParams::try_new(p.settings()), Ok(p));
    let cfg = TorqueEstimatorConfig::<f64>::new(&p);
    let one_link = cfg.update(&mut cfg.state(0, 0), 1, 0, 0.0).torsion;
    let want = TAU / l as f64;
    assert!(
        (one_link - want).abs() <= 1e-12 * want,
        "{one_link} vs {want}"
    );
    let one_motor = cfg.update(&mut cfg.state(0, 0), 0, 1, 0.0).torsion;
    let want = TAU / (m as f64 * 100.0);
    assert!(
        (one_motor.abs() - want).abs() <= 1e-12 * want,
        "{one_motor} vs {want}"
    );
}

/// A zero motor resolution used to reach `state()` through a struct
/// literal and divide by zero; now it is rejected by name, as is a zero
/// link resolution (which used to give a silent 0).
#[test]
fn zero_encoder_resolutions_are_rejected_by_name() {
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    for (l, m, name) in [
        (L, 0, "motor_counts_per_rev"),
        (0, M, "link_counts_per_rev"),
    ] {
        let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: None,
            link_counts_per_rev: l,
            motor_counts_per_rev: m,
            max_torque: 60.0,
        })
        .unwrap_err();
        assert_eq!(e, ParamError::NotPositive { name, value: 0.0 });
        assert_eq!(
            e.to_string(),
            std::format!("parameter `{name}` must be > 0, got 0")
        );
    }
}

/// `L = M = u32::MAX` breaks the product rule, and the error names the
/// whole product `L·M·N` with its value, not `L` alone.
#[test]
fn oversized_encoder_product_names_the_product() {
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    let e = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: None,
        link_counts_per_rev: u32::MAX,
        motor_counts_per_rev: u32::MAX,
        max_torque: 60.0,
    })
    .unwrap_err();
    let lmn = u32::MAX as f64 * u32::MAX as f64 * 100.0;
    match e {
        ParamError::CombinationOutOfRange {
            name,
            value,
            min,
            max,
        } => {
            assert_eq!(name, "link_counts_per_rev·motor_counts_per_rev·drive.ratio");
            assert_eq!(value, lmn);
            assert_eq!(min, 1.0);
            // The torsion range rule binds before 2⁴⁶ for this drive:
            // 2³¹ counts of 2π/(LMN) must cover twice the range.
            let p = params(None);
            let want = libm::floor(2_147_483_648.0 * TAU / (2.0 * p.torsion_range()));
            assert_eq!(max, want);
            assert!(max < MAX_COUNTS_PER_OUTPUT_REV);
        }
        other => panic!("{other:?}"),
    }
    assert!(e
        .to_string()
        .starts_with("`link_counts_per_rev·motor_counts_per_rev·drive.ratio` must lie in [1, "));
}

/// `update_radians` subtracts eq. (3.7) evaluated by the model itself at
/// the two angles: with and without the model, the flexspline torsions
/// of the same readings differ by `e_k(θ_fo, θ_wi)` and the total
/// torsions not at all.
#[test]
fn update_radians_subtracts_the_kinematic_error() {
    let k = KinematicErrorModel::table_3_2();
    let (with, without) = (
        TorqueEstimatorConfig::<f64>::new(&params(Some(k))),
        TorqueEstimatorConfig::<f64>::new(&params(None)),
    );
    let mut largest = 0.0f64;
    for i in 0..64 {
        let link = TAU * i as f64 / 64.0 + 0.01;
        // θ_wi = N(Δθ − θ_fo), eq. (2.13), at torsions of −3 to +3 mrad.
        let motor = 100.0 * (3e-3 - 1e-4 * i as f64 - link);
        let (a, b) = (
            with.update_radians(link, motor, 0.02),
            without.update_radians(link, motor, 0.02),
        );
        let e_k = k.evaluate(link, motor);
        assert_eq!(a.torsion, b.torsion);
        assert!(
            (b.flexspline_torsion - a.flexspline_torsion - e_k).abs() <= 1e-15,
            "{i}: {} vs {e_k}",
            b.flexspline_torsion - a.flexspline_torsion
        );
        largest = largest.max(e_k.abs());
    }
    assert!(largest > 1e-4, "{largest}");
}

/// `update_radians` with NaN or infinite readings: every field finite,
/// `invalid_input` set, on every backend that has non-finite values;
/// and a NaN or infinite motor torque on the count path is flagged
/// (it used to count as 0, or be clamped, silently).
#[test]
fn non_finite_readings_are_flagged() {
    fn check<S: Scalar + core::fmt::Debug>(bad: [S; 3]) {
        let p = params(Some(KinematicErrorModel::table_3_2()));
        let cfg = TorqueEstimatorConfig::<S>::new(&p);
        let ok = S::from_f64(0.01);
        let finite = |e: &TorqueEstimate<S>| {
            [e.torque, e.torsion, e.flexspline_torsion]
                .iter()
                .all(|v| v.to_f64().is_finite())
        };
        for &x in &bad {
            for (la, ma, tw) in [(x, x, x), (x, ok, ok), (ok, x, ok), (ok, ok, x)] {
                let e = cfg.update_radians(la, ma, tw);
                assert!(e.invalid_input && finite(&e), "{la:?} {ma:?} {tw:?}: {e:?}");
                assert!(e.torque.abs() <= cfg.max_torque);
            }
            let e = cfg.update(&mut cfg.state(0, 0), 5, 0, x);
            assert!(e.invalid_input && finite(&e), "{x:?}: {e:?}");
            // Taken as zero motor torque.
            let zero = cfg.update(&mut cfg.state(0, 0), 5, 0, S::ZERO);
            assert_eq!((e.torque, e.torsion), (zero.torque, zero.torsion));
            assert!(!zero.invalid_input);
        }
        // Finite readings of a small torsion (1 µrad) are not flagged.
        let e = cfg.update_radians(S::from_f64(0.002), S::from_f64(-0.1999), ok);
        assert!(!e.invalid_input && finite(&e));
    }
    check::<f32>([f32::NAN, f32::INFINITY, f32::NEG_INFINITY]);
    check::<f64>([f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
}

/// A counter jump that no torque can produce (here half an output
/// revolution of torsion) is flagged, the torque saturates with its
/// flag, and the reported torsion is the documented clamp
/// `±torsion_range` on every backend (it used to be 2.628 rad on f32
/// and 0.515 rad on I16F16 for the same readings).
#[test]
fn impossible_counter_jump_is_flagged_and_agrees_across_backends() {
    fn jump<S: Scalar>(p: &TorqueEstimatorParams, counts: u32) -> TorqueEstimate<S> {
        let cfg = TorqueEstimatorConfig::<S>::new(p);
        let mut st = cfg.state(0, 0);
        cfg.update(&mut st, 0, counts, S::ZERO)
    }
    let p = params(None);
    let range = p.torsion_range();
    // Motor counts (of MN = 200 000 per output revolution) for a torsion
    // of +2.6 rad and of −1.3 rad.
    for (counts, sign) in [(82_761u32, 1.0), (u32::MAX - 41_380, -1.0)] {
        let a = jump::<f32>(&p, counts);
        let b = jump::<f64>(&p, counts);
        let c = jump::<I16F16>(&p, counts);
        for (e, flagged, q) in [
            (a.torsion_si(), a.invalid_input && a.saturated, 1e-7 * range),
            (b.torsion_si(), b.invalid_input && b.saturated, 1e-15),
            (c.torsion_si(), c.invalid_input && c.saturated, 1e-8),
        ] {
            assert!(flagged);
            assert!((e - sign * range).abs() <= q, "{e} vs {}", sign * range);
        }
        assert_eq!(a.torque_si(), sign * 60.0);
        assert_eq!(b.torque_si(), sign * 60.0);
        assert_eq!(c.torque_si(), sign * 60.0);
    }
    // The largest torsion the model can produce is not flagged.
    let cfg = TorqueEstimatorConfig::<f64>::new(&p);
    let edge = (p.drive().flexspline().max_torsion() / TAU * (M as f64 * 100.0)) as u32;
    let e = cfg.update(&mut cfg.state(0, 0), 0, edge, 0.0);
    assert!(!e.invalid_input && e.torsion > 0.0, "{e:?}");
}
