use super::*;
use crate::scalar::I16F16;
use proptest::prelude::*;

fn table() -> RobustAdaptiveParams {
    RobustAdaptiveParams::table_4_1().unwrap()
}

/// Eq. (4.19) written out in SI with the f64 friction model, as an
/// independent reference for the stored-unit implementation.
fn reference_law(
    d: &RobustAdaptiveDesign,
    f: &FrictionParams,
    z: f64,
    x: &ControlInput<f64>,
) -> f64 {
    let e = x.motor_position - x.desired_position;
    let ed = x.motor_velocity - x.desired_velocity;
    let r = ed + d.lambda * e;
    let a = x.desired_acceleration - 2.0 * d.lambda * ed - d.lambda * d.lambda * e;
    let y = f.regressor(x.motor_velocity, d.eps_velocity);
    let rho = d.friction_bounds.variable();
    let mut param = 0.0;
    for j in 0..4 {
        param += rho[j] * y[j] * (r * y[j]).sat(d.eps_f[j]);
    }
    d.rotor_inertia * a + x.joint_torque / d.ratio + f.nominal(x.motor_velocity, d.eps_velocity)
        - z
        - d.robust_gain() * r.sat(d.eps_r)
        - param
}

prop_compose! {
    fn sample()(qd in -3.0f64..3.0, dq in -0.05f64..0.05, vd in -20.0f64..20.0, dv in -2.0f64..2.0,
                ad in -500.0f64..500.0, tau in -20.0f64..20.0) -> ControlInput<f64> {
        ControlInput {
            desired_position: qd, desired_velocity: vd, desired_acceleration: ad,
            motor_position: qd + dq, motor_velocity: vd + dv, joint_torque: tau,
            ..Default::default()
        }
    }
}

prop_compose! {
    fn estimate()(b in 0.0f64..1e-4, fc in 0.0f64..0.012, fs in 0.0f64..0.012, ft in 0.01f64..10.0)
        -> FrictionParams {
        FrictionParams { viscous: b, coulomb: fc, stribeck: fs, stribeck_shape: ft }
    }
}

#[test]
fn table_4_1_validates_and_its_robust_gain_is_recomputed() {
    let p = table();
    // K_r = ρ_f + ρ_fq + I_m ρ_base + ρ_τ/N
    //     = 0.044 + 0.002 + 1.14e-5·1e4 + 1/100 = 0.170 N·m.
    assert!((p.design().robust_gain() - 0.170).abs() < 1e-12);
    assert!((p.design().uncertainty.boundary_layer - 0.044).abs() < 1e-15);
}

#[test]
fn try_new_names_the_bad_value() {
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.lambda = -1.0;
    assert_eq!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::NotPositive {
            name: "lambda",
            value: -1.0
        })
    );
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.torque_limit = 20.0;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange {
            name: "torque_limit",
            ..
        })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.eps_f[0] = 1e-6;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::NotRepresentable { name: "eps_f", .. })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.initial_friction.coulomb = 0.02;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange {
            name: "coulomb",
            ..
        })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.ratio = 0.5;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange { name: "ratio", .. })
    ));
}

proptest! {
    /// The stored-unit law equals the SI reference of eq. (4.19) (f64).
    #[test]
    fn law_matches_the_si_reference(x in sample(), f in estimate(), z in -0.1f64..0.1) {
        let p = table();
        let mut d = *p.design();
        d.torque_limit = 16.0;
        let p = RobustAdaptiveParams::try_new(d).unwrap();
        let cfg = RobustAdaptiveConfig::<f64>::new(&p);
        let st = RobustAdaptiveState { friction: f.to_array(), integral: z };
        let got = cfg.law(&st, &x).law;
        let want = reference_law(&d, &f, z, &x);
        prop_assert!((got - want).abs() <= 1e-12 * (1.0 + want.abs()), "{got} vs {want}");
    }

    /// Theorem 1 with the hat restored (errata E20): one adaptation step
    /// ΔF̂ = −Γ T Yᵀ r makes the adaptation term of V̇ (eq. 4.21),
    /// `−(ΔF̂/T)ᵀ Γ⁻¹ F̃`, equal to `+r Y F̃`, cancelling the parametric term
    /// `−r Y F̃` that eq. (4.16) puts into eq. (4.22).
    #[test]
    fn adaptation_cancels_the_parametric_term(x in sample(), f in estimate(), truth in estimate()) {
        let p = table();
        let d = *p.design();
        // Wide box so the projection is inactive.
        let mut wide = d;
        wide.friction_bounds = FrictionBounds::try_new(
            FrictionParams::from_array([-1.0, -1.0, -1.0, 1e-3]),
            FrictionParams::from_array([1.0, 1.0, 1.0, 1e3]), [0.0; 4]).unwrap_or(d.friction_bounds);
        wide.friction_bounds = FrictionBounds::from_checked([-1.0, -1.0, -1.0, 1e-3], [1.0, 1.0, 1.0, 1e3], [0.0; 4]);
        let p = RobustAdaptiveParams::try_new(wide).unwrap();
        let cfg = RobustAdaptiveConfig::<f64>::new(&p);
        let mut st = RobustAdaptiveState { friction: f.to_array(), integral: 0.0 };
        let before = st.friction;
        cfg.update(&mut st, &x);
        let r = (x.motor_velocity - x.desired_velocity) + d.lambda * (x.motor_position - x.desired_position);
        let y = f.regressor(x.motor_velocity, d.eps_velocity);
        let t = d.sample_period;
        let mut adaptation_term = 0.0;
        let mut parametric = 0.0;
        for j in 0..4 {
            let f_tilde = truth.to_array()[j] - before[j];
            let dfhat = st.friction[j] - before[j];
            adaptation_term += -(dfhat / t) / d.adaptation_gain[j] * f_tilde;
            parametric += -r * y[j] * f_tilde;
        }
        let scale = 1e-9 * (1.0 + parametric.abs());
        prop_assert!((adaptation_term + parametric).abs() <= scale, "{adaptation_term} + {parametric}");
    }

    /// The robust terms of eq. (4.19) oppose r: `r · (robust part) ≥ 0`
    /// where the robust part enters with a minus sign, term by term, and
    /// each `sat(·, ε)` factor lies in [−1, 1] with the sign of its
    /// argument (the facts eq. 4.24–4.27 use).
    #[test]
    fn robust_terms_oppose_the_sliding_variable(x in sample(), f in estimate()) {
        let d = *table().design();
        let r = (x.motor_velocity - x.desired_velocity) + d.lambda * (x.motor_position - x.desired_position);
        let kr = d.robust_gain() * r.sat(d.eps_r);
        prop_assert!(r * kr >= 0.0 && r.sat(d.eps_r).abs() <= 1.0);
        let y = f.regressor(x.motor_velocity, d.eps_velocity);
        let rho = d.friction_bounds.variable();
        for j in 0..4 {
            let s = (r * y[j]).sat(d.eps_f[j]);
            prop_assert!(s.abs() <= 1.0 && s * (r * y[j]) >= 0.0);
            prop_assert!(r * (rho[j] * y[j] * s) >= 0.0);
        }
        // And the implementation's robust part (law with ρ's minus law
        // without them) has the opposite sign of r.
        let cfg = RobustAdaptiveConfig::<f64>::new(&table());
        let mut no_rho = d;
        no_rho.uncertainty = UncertaintyBounds { boundary_layer: 0.0, nonparametric_friction: 0.0, base_acceleration: 0.0, torque_estimate: 0.0 };
        no_rho.friction_bounds = FrictionBounds::from_checked(d.friction_bounds.min(), d.friction_bounds.max(), [0.0; 4]);
        let cfg0 = RobustAdaptiveConfig::<f64>::new(&RobustAdaptiveParams::try_new(no_rho).unwrap());
        let st = RobustAdaptiveState { friction: f.to_array(), integral: 0.0 };
        let robust = cfg.law(&st, &x).law - cfg0.law(&st, &x).law;
        prop_assert!(r * robust <= 1e-15);
    }

    /// Bounded, NaN-free output and bounded state on every backend, for
    /// sequences of bounded inputs (and the estimates stay in the box).
    #[test]
    fn output_and_state_stay_bounded(xs in proptest::collection::vec(sample(), 1..40)) {
        fn run<S: Scalar>(xs: &[ControlInput<f64>]) -> Result<(), TestCaseError> {
            let cfg = RobustAdaptiveConfig::<S>::new(&table());
            let mut st = cfg.initial_state();
            let lim = cfg.torque_limit();
            let u = S::UNITS;
            for x in xs {
                let xq = ControlInput {
                    desired_position: S::from_f64(x.desired_position * u.angle),
                    desired_velocity: S::from_f64(x.desired_velocity * u.speed),
                    desired_acceleration: S::from_f64(x.desired_acceleration * u.speed),
                    motor_position: S::from_f64(x.motor_position * u.angle),
                    motor_velocity: S::from_f64(x.motor_velocity * u.speed),
                    joint_torque: S::from_f64(x.joint_torque * u.link_torque),
                    ..Default::default()
                };
                let o = cfg.update(&mut st, &xq);
                prop_assert!(!o.torque.is_nan() && o.torque.abs() <= lim && !o.invalid_input);
                prop_assert!(st.integral.abs() <= cfg.integral_limit());
                for j in 0..4 {
                    prop_assert!(st.friction[j] >= cfg.lower_bounds()[j] && st.friction[j] <= cfg.upper_bounds()[j]);
                }
            }
            Ok(())
        }
        run::<f64>(&xs)?;
        run::<f32>(&xs)?;
        run::<I16F16>(&xs)?;
    }
}

#[test]
fn invalid_input_gives_zero_torque_and_keeps_state() {
    let cfg = RobustAdaptiveConfig::<f32>::new(&table());
    let mut st = cfg.initial_state();
    let before = st;
    let x = ControlInput {
        motor_velocity: f32::NAN,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &x);
    assert!(o.invalid_input && o.torque == 0.0 && st == before);
    let x = ControlInput {
        desired_position: f32::INFINITY,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &x);
    assert!(o.invalid_input && o.torque == 0.0 && st == before);
    // Finite but huge inputs saturate instead.
    let x = ControlInput {
        desired_position: 3e38,
        motor_position: -3e38,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &x);
    assert!(!o.torque.is_nan() && o.torque.abs() <= cfg.torque_limit());
}

/// Projection: a persistent error drives an estimate to its bound and no
/// further; without projection the same gradient would leave the box.
#[test]
fn projection_holds_the_estimate_at_its_bound() {
    let cfg = RobustAdaptiveConfig::<f64>::new(&table());
    let mut st = cfg.initial_state();
    // Moving at +1 rad/s, permanently ahead of the reference (r > 0):
    // f̂_c decreases each step until it reaches its lower bound 0.
    let x = ControlInput {
        motor_velocity: 1.0,
        desired_velocity: 0.0,
        motor_position: 0.01,
        ..Default::default()
    };
    for _ in 0..200_000 {
        cfg.update(&mut st, &x);
    }
    assert_eq!(st.friction[1], 0.0);
    assert_eq!(st.friction[0], 0.0);
    assert!(st.friction[3] >= 0.01 && st.friction[3] <= 10.0);
}
