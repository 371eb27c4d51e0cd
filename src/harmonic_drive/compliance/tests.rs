use super::*;
use crate::scalar::I16F16;
use proptest::prelude::*;

/// The named settings reach their own getters and roles: the slope of
/// eq. (3.10) at zero torsion is `K_f0` (a finite difference), the cubic
/// of eq. (2.10) is `a1 Δθ + a3 Δθ³` written out. Positional `f64`
/// pairs could be swapped and still validate (`K_f0 = 0.02`,
/// `c_f = 8000` is accepted).
#[test]
fn named_settings_reach_their_getters_and_roles() {
    let fs = FlexsplineSettings {
        k_f0: 8000.0,
        c_f: 0.02,
    };
    let f = FlexsplineParams::try_new(fs).unwrap();
    assert_eq!((f.k_f0(), f.c_f()), (8000.0, 0.02));
    assert_eq!(f.settings(), fs);
    let h = 1e-7;
    let slope = (f.torque(h).torque - f.torque(-h).torque) / (2.0 * h);
    assert!((slope - 8000.0).abs() < 1e-3, "{slope}");
    assert!(FlexsplineParams::try_new(FlexsplineSettings {
        k_f0: 0.02,
        c_f: 8000.0
    })
    .is_ok());
    let ws = WaveGeneratorSettings {
        k_w0: 5e4,
        c_w: 0.3,
    };
    let w = WaveGeneratorParams::try_new(ws).unwrap();
    assert_eq!((w.k_w0(), w.c_w()), (5e4, 0.3));
    assert_eq!(WaveGeneratorParams::try_new(w.settings()), Ok(w));
    let cs = CubicStiffnessSettings {
        a1: 7000.0,
        a3: 3e9,
    };
    let c = CubicStiffness::try_new(cs).unwrap();
    assert_eq!((c.a1(), c.a3(), c.settings()), (7000.0, 3e9, cs));
    let d: f64 = 2e-3;
    let want = 7000.0 * d + 3e9 * d * d * d;
    assert!((c.torque(d) - want).abs() <= 1e-12 * want);
}

fn shd17() -> FlexsplineParams {
    FlexsplineParams::try_new(FlexsplineSettings {
        k_f0: 8.336e3,
        c_f: 0.0449,
    })
    .unwrap()
}

/// The SHD-17-100's catalogue curve with a third slope of 1.2e4 N·m/rad.
fn shd17_curve() -> CataloguePiecewise {
    CataloguePiecewise::try_new(CatalogueCurve {
        k1: 8.4e3,
        k2: 9.4e3,
        k3: 1.2e4,
        t1: 3.9,
        t2: 12.0,
    })
    .unwrap()
}

#[test]
fn piecewise_is_continuous_at_the_knees_and_odd() {
    let c = shd17_curve();
    for t in [3.9, 12.0] {
        let below = c.torsion(t - 1e-9);
        let above = c.torsion(t + 1e-9);
        assert!((above - below).abs() < 1e-12, "jump at {t}");
    }
    assert_eq!(c.torsion(-5.0), -c.torsion(5.0));
    // Hand values: 3.9/8400 and 3.9/8400 + 8.1/9400 + 3/12000.
    assert!((c.torsion(3.9) - 3.9 / 8400.0).abs() < 1e-15);
    assert!((c.torsion(15.0) - (3.9 / 8400.0 + 8.1 / 9400.0 + 3.0 / 12000.0)).abs() < 1e-15);
}

/// Huge torques used to overflow the cubic inside Newton's method and
/// return NaN; the inverse is now finite and still inverts.
#[test]
fn cubic_inverse_is_finite_for_huge_torques() {
    let q = CubicStiffness::try_new(CubicStiffnessSettings {
        a1: 8.0e3,
        a3: 2.0e9,
    })
    .unwrap();
    for t in [1e100, 1e250, 1e300, f64::MAX] {
        let x = q.torsion(t);
        assert!(x.is_finite() && x > 0.0, "{t}: {x}");
        let tt = t.min(1e300);
        assert!(
            (q.torque(x) - tt).abs() <= 1e-12 * tt,
            "{t}: {}",
            q.torque(x)
        );
        assert_eq!(q.torsion(-t), -x);
    }
}

/// The local stiffness is the slope of the segment a torque lies on,
/// the knee itself on the lower one, either sign; inside a segment it is
/// the slope of [`CataloguePiecewise::torque`] (a central difference).
#[test]
fn piecewise_local_stiffness_is_the_segment_slope() {
    let c = shd17_curve();
    for (t, k) in [
        (0.0, 8.4e3),
        (2.0, 8.4e3),
        (3.9, 8.4e3),
        (3.9f64.next_up(), 9.4e3),
        (8.0, 9.4e3),
        (12.0, 9.4e3),
        (12.0f64.next_up(), 1.2e4),
        (40.0, 1.2e4),
    ] {
        assert_eq!(c.local_stiffness(t), k, "{t}");
        assert_eq!(c.local_stiffness(-t), k, "{}", -t);
    }
    // Inside each segment it is the slope of the inverse curve.
    for (t, k) in [(2.0, 8.4e3), (8.0, 9.4e3), (40.0, 1.2e4)] {
        let x = c.torsion(t);
        let h = 1e-9 * x;
        let slope = (c.torque(x + h) - c.torque(x - h)) / (2.0 * h);
        assert!((slope - k).abs() <= 1e-4 * k, "{t}: {slope}");
    }
}

/// `a3 ≥ 0`: zero accepted (the linear spring), the next `f64` below
/// rejected by name; `a1 > 0`.
#[test]
fn cubic_ranges_at_their_edges() {
    let ok = CubicStiffness::try_new(CubicStiffnessSettings {
        a1: 1e-300,
        a3: 0.0,
    })
    .unwrap();
    assert_eq!(
        ok.settings(),
        CubicStiffnessSettings {
            a1: 1e-300,
            a3: 0.0
        }
    );
    assert!(matches!(
        CubicStiffness::try_new(CubicStiffnessSettings {
            a1: 1.0,
            a3: -1e-300
        }),
        Err(ParamError::Negative { name: "a3", .. })
    ));
    assert!(matches!(
        CubicStiffness::try_new(CubicStiffnessSettings {
            a1: 1.0,
            a3: f64::NAN
        }),
        Err(ParamError::NotFinite { name: "a3", .. })
    ));
    assert!(matches!(
        CubicStiffness::try_new(CubicStiffnessSettings { a1: 0.0, a3: 1.0 }),
        Err(ParamError::NotPositive { name: "a1", .. })
    ));
}

/// The cubic through the knees, by hand where the numbers are exact, and
/// every curve no admissible cubic fits rejected as `NotRepresentable`
/// naming `a3`: knees that soften (`K2 < K1`, `a3 < 0`), knees that
/// stiffen so fast that `a1 ≤ 0`, and knees whose cube overflows.
#[test]
fn cubic_through_knees_accepts_exactly_the_admissible_curves() {
    let curve = |k1: f64, k2: f64, t1: f64, t2: f64| {
        CataloguePiecewise::try_new(CatalogueCurve {
            k1,
            k2,
            k3: 1.0,
            t1,
            t2,
        })
        .unwrap()
    };
    // A linear curve (K1 = K2 = 1, knees at 1 and 2 N·m): x1 = 1, x2 = 2,
    // det = 1·8 − 2·1 = 6, a1 = (1·8 − 2·1)/6 = 1, a3 = (1·2 − 2·1)/6 = 0.
    let q = CubicStiffness::through_catalogue_knees(&curve(1.0, 1.0, 1.0, 2.0)).unwrap();
    assert_eq!((q.a1(), q.a3()), (1.0, 0.0));
    // Softening: K2 = 0.5 K1 puts the second knee at x2 = 3; the cubic
    // through (1, 1) and (3, 2): a3 = (1·2 − 3·1)/(1·27 − 3·1) = −1/24.
    match CubicStiffness::through_catalogue_knees(&curve(1.0, 0.5, 1.0, 2.0)) {
        Err(ParamError::NotRepresentable { name: "a3", value }) => {
            assert!((value + 1.0 / 24.0).abs() < 1e-15, "{value}")
        }
        other => panic!("{other:?}"),
    }
    // Stiffening fast: (1, 1) and (1.099, 100) need a1 < 0 (a3 > 0).
    let stiff = curve(1.0, 1000.0, 1.0, 100.0);
    let (x1, x2) = (stiff.torsion_at_t1(), stiff.torsion_at_t2());
    let det = x1 * x2.powi(3) - x2 * x1.powi(3);
    assert!((1.0 * x2.powi(3) - 100.0 * x1.powi(3)) / det < 0.0);
    assert!(matches!(
        CubicStiffness::through_catalogue_knees(&stiff),
        Err(ParamError::NotRepresentable { name: "a3", value }) if value > 0.0
    ));
    // Knees at 1e308 and 1.5e308 N·m (x1 = 1, x2 = 1.5 rad): T1 x2³
    // overflows, so a1 = ∞ while a3 = (1.5e308 − 1.5e308)/det = 0.
    assert!(matches!(
        CubicStiffness::through_catalogue_knees(&curve(1e308, 1e308, 1e308, 1.5e308)),
        Err(ParamError::NotRepresentable { name: "a3", value }) if value == 0.0
    ));
    // x1 = 1e300 rad: its cube overflows, the solution is not finite.
    assert!(matches!(
        CubicStiffness::through_catalogue_knees(&curve(1e-300, 1e-300, 1.0, 2.0)),
        Err(ParamError::NotRepresentable { name: "a3", .. })
    ));
}

/// A linear spring (`a3 = 0`) inverts to `τ/a1` exactly, up to the
/// largest torque taken (1e300 N·m), with no overflow on the way (for a
/// stiff one too: `τ a1` would overflow at `a1 = 2e9`).
#[test]
fn linear_cubic_inverts_exactly() {
    for a1 in [8.0e3, 2.0e9] {
        let q = CubicStiffness::try_new(CubicStiffnessSettings { a1, a3: 0.0 }).unwrap();
        for t in [5.0, -2.5e-3, 1e200, 1e300, -f64::MAX] {
            let want = t.clamp(-1e300, 1e300) / a1;
            let got = q.torsion(t);
            assert!((got - want).abs() <= 1e-15 * want.abs(), "{a1}, {t}: {got}");
        }
    }
}

/// Newton's stop is relative to the torsion: a tiny torque on a spring
/// whose torsion is far below 1 rad still inverts to full precision
/// (`τ(Δθ(τ)) = τ` within 1e-13), from 1e-11 N·m up to 1e300 N·m.
#[test]
fn cubic_inverse_is_exact_for_tiny_torsions() {
    for (a1, a3) in [(1.166e-3, 1.743e11), (8.0e3, 2.0e9), (1e-3, 1e12)] {
        let q = CubicStiffness::try_new(CubicStiffnessSettings { a1, a3 }).unwrap();
        for t in [1.5e-11, 3e-9, 1e-6, 1e-3, 1.0, 1e3, 1e100, 1e300] {
            let x = q.torsion(t);
            let back = q.torque(x);
            assert!(
                (back - t).abs() <= 1e-13 * t,
                "{a1}, {a3}, {t}: {x} gives {back}"
            );
        }
    }
}

#[test]
fn piecewise_rejects_unordered_knees() {
    assert_eq!(
        CataloguePiecewise::try_new(CatalogueCurve {
            k1: 1.0,
            k2: 2.0,
            k3: 3.0,
            t1: 5.0,
            t2: 5.0
        }),
        Err(ParamError::NotIncreasing {
            lower: "t1",
            lower_value: 5.0,
            upper: "t2",
            upper_value: 5.0
        })
    );
    assert!(matches!(
        CataloguePiecewise::try_new(CatalogueCurve {
            k1: -1.0,
            k2: 2.0,
            k3: 3.0,
            t1: 1.0,
            t2: 5.0
        }),
        Err(ParamError::NotPositive { name: "k1", .. })
    ));
}

#[test]
fn cubic_passes_through_the_knees() {
    let c = shd17_curve();
    let q = CubicStiffness::through_catalogue_knees(&c).unwrap();
    assert!((q.torque(c.torsion_at_t1()) - 3.9).abs() < 1e-9);
    assert!((q.torque(c.torsion_at_t2()) - 12.0).abs() < 1e-9);
    // A softening catalogue (K2 < K1) has no admissible cubic.
    let soft = CataloguePiecewise::try_new(CatalogueCurve {
        k1: 9.4e3,
        k2: 8.4e3,
        k3: 8e3,
        t1: 3.9,
        t2: 12.0,
    })
    .unwrap();
    assert!(CubicStiffness::through_catalogue_knees(&soft).is_err());
}

/// The values the issue found accepted (NaN, negative or zero
/// stiffness and stiffening coefficients) are rejected, each naming
/// the parameter, the value and the rule in its message.
#[test]
fn bad_drive_parameters_are_rejected_by_name() {
    extern crate std;
    use std::string::ToString;
    let f = |k, c| {
        FlexsplineParams::try_new(FlexsplineSettings { k_f0: k, c_f: c })
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let w = |k, c| {
        WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: k, c_w: c })
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let cases = [
        (
            f(8.3e3, f64::NAN),
            "parameter `c_f` must be finite, got NaN",
        ),
        (f(-8.3e3, 0.045), "parameter `k_f0` must be > 0, got -8300"),
        (f(0.0, 0.045), "parameter `k_f0` must be > 0, got 0"),
        (
            f(8.3e3, -0.045),
            "parameter `c_f` must lie in [1e-6, 1e6], got -0.045",
        ),
        (
            f(f64::INFINITY, 0.045),
            "parameter `k_f0` must be finite, got inf",
        ),
        (
            w(f64::NAN, 83.0),
            "parameter `k_w0` must be finite, got NaN",
        ),
        (
            w(0.83, -83.0),
            "parameter `c_w` must lie in [1e-6, 1e6], got -83",
        ),
        (
            w(0.83, 0.0),
            "parameter `c_w` must lie in [1e-6, 1e6], got 0",
        ),
    ];
    for (got, want) in cases {
        assert_eq!(got, want);
    }
    // The composite: a flexspline so stiff that its inverse's domain
    // π/(2 c_f K_f0) is below a micro-radian (here 1.9e-8 rad).
    let e = FlexsplineParams::try_new(FlexsplineSettings {
        k_f0: 8.3e7,
        c_f: 1.0,
    })
    .unwrap_err();
    let domain = core::f64::consts::FRAC_PI_2 / 8.3e7;
    assert_eq!(
        e,
        ParamError::CombinationOutOfRange {
            name: "π/(2·c_f·k_f0)",
            value: domain,
            min: 1e-6,
            max: 1.0
        }
    );
    // A drive whose wave generator twists by more than a radian on the
    // output side.
    let fl = FlexsplineParams::try_new(FlexsplineSettings {
        k_f0: 8.3e3,
        c_f: 0.045,
    })
    .unwrap();
    let wg = WaveGeneratorParams::try_new(WaveGeneratorSettings {
        k_w0: 1e-3,
        c_w: 1e-3,
    })
    .unwrap();
    let e = HarmonicDriveParams::try_new(fl, wg, 2.0).unwrap_err();
    assert!(
        matches!(e, ParamError::CombinationOutOfRange { name: "1/(wave_generator.c_w·ratio·wave_generator.k_w0)", value, .. } if value == 1.0 / (1e-3 * 2.0 * 1e-3)),
        "{e:?}"
    );
    let e = HarmonicDriveParams::try_new(
        fl,
        WaveGeneratorParams::try_new(WaveGeneratorSettings {
            k_w0: 0.83,
            c_w: 83.0,
        })
        .unwrap(),
        0.5,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "parameter `ratio` must lie in [1, inf], got 0.5"
    );
}

#[test]
fn flexspline_torsion_saturates_at_max_torsion() {
    let p = shd17();
    // atan(u) = π/2 − 1/u + O(u⁻³): the torsion approaches the maximum
    // from below by 1/(c_f τ) / (c_f K_f0).
    let t = 1e9;
    let expected = p.max_torsion() - 1.0 / (p.c_f * t) / (p.c_f * p.k_f0);
    assert!((p.torsion(t) - expected).abs() <= 1e-15 * p.max_torsion());
    let r = p.torque(1.5 * p.max_torsion());
    assert!(r.saturated && r.torque > 0.0 && r.torque.is_finite());
    let r = p.torque(-1.5 * p.max_torsion());
    assert!(r.saturated && r.torque < 0.0);
}

/// The sign transfer in `output_torsion` equals the product form
/// `sgn(τ_w)·(1 − e^{−c_w|τ_w|})·A` of eq. (2.29): bit for bit on every
/// `I16F16` torque, and on `f32` for a sweep of torques including ±0,
/// subnormals, ±∞ and NaN (up to the sign of a zero).
#[test]
fn wave_generator_sign_transfer_equals_the_product_form() {
    fn product_form<S: Scalar>(w: &WaveGeneratorConfig<S>, t: S) -> S {
        let e = t.abs().mul_coef(&w.c_w).exp_neg_abs();
        t.sgn().mul(S::ONE.sub(e)).mul_coef(&w.amplitude)
    }
    let p = WaveGeneratorParams::try_new(WaveGeneratorSettings {
        k_w0: 0.8276,
        c_w: 83.33,
    })
    .unwrap();
    let w = WaveGeneratorConfig::<I16F16>::new(&p, 100.0);
    for bits in (i32::MIN..=i32::MAX)
        .step_by(97)
        .chain([-1, 0, 1, i32::MAX])
    {
        let t = I16F16::from_bits(bits);
        assert_eq!(w.output_torsion(t), product_form(&w, t), "τ bits {bits}");
    }
    let w = WaveGeneratorConfig::<f32>::new(&p, 100.0);
    let mut specials = std::vec![
        0.0f32,
        -0.0,
        f32::MIN_POSITIVE / 8.0,
        f32::INFINITY,
        f32::NAN
    ];
    specials.extend((0..4000).map(|i| 1e-6 * 1.01f32.powi(i)));
    for t in specials {
        for t in [t, -t] {
            let (a, b) = (w.output_torsion(t), product_form(&w, t));
            assert!(a == b || (a.is_nan() && b.is_nan()), "τ {t}: {a} vs {b}");
        }
    }
}

proptest! {
    /// Eq. (2.25): the torsion is the integral of 1/K_fl; its derivative
    /// (central difference) must equal 1/K_fl of eq. (2.24).
    #[test]
    fn flexspline_torsion_derivative_is_inverse_local_stiffness(t in -150.0f64..150.0) {
        let p = shd17();
        let h = 1e-4;
        let fd = (p.torsion(t + h) - p.torsion(t - h)) / (2.0 * h);
        let exact = 1.0 / p.local_stiffness(t);
        prop_assert!((fd - exact).abs() <= 1e-6 * exact, "{fd} vs {exact}");
    }

    /// Eq. (2.28): same for the wave generator and eq. (2.27).
    #[test]
    fn wave_generator_torsion_derivative_is_inverse_local_stiffness(t in 0.001f64..0.1) {
        let p = WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 0.8276, c_w: 83.33 }).unwrap();
        let h = 1e-7;
        for t in [t, -t] {
            let fd = (p.torsion(t + h) - p.torsion(t - h)) / (2.0 * h);
            let exact = 1.0 / p.local_stiffness(t);
            prop_assert!((fd - exact).abs() <= 1e-5 * exact, "{fd} vs {exact}");
        }
    }

    /// Eq. (3.10) inverts eq. (2.26) inside the domain.
    #[test]
    fn flexspline_round_trip_f64(t in -500.0f64..500.0) {
        let p = shd17();
        let back = p.torque(p.torsion(t));
        prop_assert!(!back.saturated);
        prop_assert!((back.torque - t).abs() <= 1e-9 * (1.0 + t.abs()));
    }

    /// The cubic's inverse is exact to rounding.
    #[test]
    fn cubic_round_trip(t in -100.0f64..100.0) {
        let q = CubicStiffness::try_new(CubicStiffnessSettings { a1: 8.0e3, a3: 2.0e9 }).unwrap();
        prop_assert!((q.torque(q.torsion(t)) - t).abs() <= 1e-9 * (1.0 + t.abs()));
    }

    /// The piecewise inverse is exact to rounding.
    #[test]
    fn piecewise_round_trip(t in -100.0f64..100.0) {
        let c = CataloguePiecewise::try_new(CatalogueCurve { k1: 8.4e3, k2: 9.4e3, k3: 1.2e4, t1: 3.9, t2: 12.0 }).unwrap();
        prop_assert!((c.torque(c.torsion(t)) - t).abs() <= 1e-10 * (1.0 + t.abs()));
    }

    /// The fixed-point configuration agrees with f64 within its error
    /// budget, derived term by term in stored units (LSB = 2⁻¹⁶):
    /// quantizing τ costs ½ LSB, moving u = c_f τ by ½ c_f LSB; the
    /// product with the 31-bit c_f rounds (½ LSB, plus |u|·2⁻³⁰); atan
    /// errs by ≤ 2 LSB (its proven bound) and shrinks the first two by
    /// 1/(1+u²); the scale 1/(c_f K_f0) multiplies all of it, and the
    /// last product rounds (½ LSB, plus 2⁻³⁰ relative).
    #[test]
    fn fixed_config_tracks_f64(t in -150.0f64..150.0) {
        let p = shd17();
        let cfg = FlexsplineConfig::<I16F16>::new(&p);
        let got = cfg.torsion(I16F16::from_f64(t)).to_f64(); // mrad
        let exact = p.torsion(t) * 1e3;
        let u = p.c_f * t;
        let scale = 1e3 / (p.c_f * p.k_f0);
        let bound_lsb = ((0.5 * p.c_f + 0.5 + u.abs() * 65536.0 * 2f64.powi(-30)) / (1.0 + u * u) + 2.0) * scale
            + 0.5
            + exact.abs() * 65536.0 * 2f64.powi(-30);
        prop_assert!((got - exact).abs() <= bound_lsb / 65536.0, "{got} vs {exact}");
    }
}

/// The estimator's torsion limit is the torsion of eq. (2.26) at the
/// limit torque, `atan(c_f τ_max)/(c_f K_f0)`, on every backend (up to
/// the backend's rounding of the torque at that torsion), and the
/// in-branch torque there is within the limit: the torque test binds
/// before the `tan` domain does (`c_f τ_max ≤ 7.5 < 8`).
#[test]
fn torsion_within_is_the_torsion_of_the_limit() {
    fn check<S: Scalar>(tol: f64) {
        let p = shd17();
        let cfg = FlexsplineConfig::<S>::new(&p);
        let u = S::UNITS;
        for tau_max in [20.0, 100.0, 7.5 / 0.0449] {
            let limit = S::from_f64(tau_max * u.link_torque);
            let a = cfg.torsion_within(limit, p.max_torsion() * u.torsion);
            let want = libm::atan(0.0449 * tau_max) / (0.0449 * 8.336e3);
            let got = a.to_f64() / u.torsion;
            assert!(
                (got - want).abs() <= tol * want,
                "{tau_max}: {got} vs {want} ({})",
                (got - want) / want
            );
            assert!(cfg.torque_in_branch(a).abs() <= limit);
            assert!(cfg.torque_in_branch(a.neg()).abs() <= limit);
        }
    }
    check::<f64>(1e-12);
    check::<f32>(1e-6);
    check::<I16F16>(1e-3);
}

/// The wave generator's largest torsion is the limit of eq. (2.29) as the
/// torque grows, `1/(c_w K_w0)`, approached from below; the product
/// `c_w K_w0` must be at least `1/f64::MAX` (so that limit is finite),
/// named as the product when it is not.
#[test]
fn wave_generator_max_torsion_and_its_product_range() {
    let p = WaveGeneratorParams::try_new(WaveGeneratorSettings {
        k_w0: 400.0,
        c_w: 0.5,
    })
    .unwrap();
    assert_eq!(p.max_torsion(), 1.0 / 200.0);
    // Eq. (2.27): K_w0 e^{c_w |τ|}, 400 e at ±2 N·m.
    for t in [2.0, -2.0] {
        assert!((p.local_stiffness(t) - 400.0 * 1f64.exp()).abs() < 1e-12);
    }
    for t in [4.0, 10.0, 40.0] {
        let x = p.torsion(t);
        let gap = (1.0 - x / p.max_torsion()).abs();
        assert!(
            x < p.max_torsion() && gap <= 2.0 * (-0.5 * t).exp(),
            "{t}: {x}"
        );
    }
    // c_w at its smallest (1e-6): K_w0 = 1e-300 gives a product of
    // 1e-306 (accepted), K_w0 = 1e-303 one of 1e-309 < 1/f64::MAX.
    assert!(WaveGeneratorParams::try_new(WaveGeneratorSettings {
        k_w0: 1e-300,
        c_w: 1e-6,
    })
    .is_ok());
    assert!(matches!(
        WaveGeneratorParams::try_new(WaveGeneratorSettings {
            k_w0: 1e-303,
            c_w: 1e-6,
        }),
        Err(ParamError::CombinationOutOfRange {
            name: "c_w·k_w0",
            ..
        })
    ));
}
