use super::*;
use crate::proofs::law_budget::{law_error_budget, regressor_budget, rounding};
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
        Err(ParamError::OutOfRange {
            name: "eps_f[0]",
            ..
        })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.initial_friction.coulomb = 0.02;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange {
            name: "initial_friction.coulomb",
            ..
        })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.lambda = 1e9;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::CombinationOutOfRange {
            name: "lambda²·rotor_inertia",
            ..
        })
    ));
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.sample_period = 1e-300;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange {
            name: "sample_period",
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
        let st = RobustAdaptiveState::from_stored(f.to_array(), z);
        let got = cfg.law(&st, &x).law;
        let want = reference_law(&d, &f, z, &x);
        prop_assert!((got - want).abs() <= 1e-12 * (1.0 + want.abs()), "{got} vs {want}");
    }

    /// Theorem 1 with the hat restored (errata E4.2): one adaptation step
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
        let mut st = RobustAdaptiveState::from_stored(f.to_array(), 0.0);
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
        let st = RobustAdaptiveState::from_stored(f.to_array(), 0.0);
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

fn to_backend<S: Scalar>(x: &ControlInput<f64>) -> ControlInput<S> {
    let u = S::UNITS;
    ControlInput {
        desired_position: S::from_f64(x.desired_position * u.angle),
        desired_velocity: S::from_f64(x.desired_velocity * u.speed),
        desired_acceleration: S::from_f64(x.desired_acceleration * u.speed),
        motor_position: S::from_f64(x.motor_position * u.angle),
        motor_velocity: S::from_f64(x.motor_velocity * u.speed),
        joint_torque: S::from_f64(x.joint_torque * u.link_torque),
        ..Default::default()
    }
}

/// The backend's law against the f64 law on the same stored inputs and
/// parameters (dequantized exactly), within [`law_error_budget`].
fn agree<S: Scalar>(
    x: &ControlInput<f64>,
    f: &FrictionParams,
    z: f64,
) -> Result<(f64, f64), TestCaseError> {
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.torque_limit = 16.0;
    d.integral_limit = 1.0;
    let p = RobustAdaptiveParams::try_new(d).unwrap();
    let cfg = RobustAdaptiveConfig::<S>::new(&p);
    let xs = to_backend::<S>(x);
    let st = RobustAdaptiveState::from_stored(
        FrictionConfig::<S>::quantize(f),
        S::from_f64(z * S::UNITS.motor_torque),
    );
    let got = cfg.law(&st, &xs).law.to_f64() / S::UNITS.motor_torque;
    // Reference: f64, the backend's quantized layers and parameters.
    let pq = RobustAdaptiveParams::try_new(cfg.quantized_design()).unwrap();
    let c64 = RobustAdaptiveConfig::<f64>::new(&pq);
    let u = S::UNITS;
    let x64 = ControlInput {
        desired_position: xs.desired_position.to_f64() / u.angle,
        desired_velocity: xs.desired_velocity.to_f64() / u.speed,
        desired_acceleration: xs.desired_acceleration.to_f64() / u.speed,
        motor_position: xs.motor_position.to_f64() / u.angle,
        motor_velocity: xs.motor_velocity.to_f64() / u.speed,
        joint_torque: xs.joint_torque.to_f64() / u.link_torque,
        ..Default::default()
    };
    let st64 = RobustAdaptiveState::from_stored(
        FrictionConfig::<S>::dequantize(&st.friction).to_array(),
        st.integral.to_f64() / u.motor_torque,
    );
    let want = c64.law(&st64, &x64).law;
    let tol = law_error_budget(&cfg, &st, &xs);
    prop_assert!(
        (got - want).abs() <= tol,
        "{}: {got} vs {want}, tol {tol}",
        S::NAME
    );
    Ok(((got - want).abs(), tol))
}

proptest! {
    /// Backend agreement of eq. (4.19): f32 and I16F16 against f64 within
    /// the derived budget (which is dominated, in I16F16, by the 7-LSB
    /// boundary layer ε_F1 and by K_r/ε_r times the rounding of r).
    #[test]
    fn backends_agree_within_the_derived_budget(x in sample(), f in estimate(), z in -0.1f64..0.1) {
        agree::<f32>(&x, &f, z)?;
        agree::<I16F16>(&x, &f, z)?;
    }
}

/// The budget is not vacuous: over a fixed sweep of samples the I16F16
/// budget averages below 1 % of the 0.188 N·m torque limit, so an
/// implementation error of that size (e.g. an integral 4 % off at
/// z = 0.05 N·m) would fail the agreement test on most samples.
#[test]
fn agreement_budget_is_tight_enough_to_catch_errors() {
    let mut total_tol = 0.0;
    let n = 200;
    for k in 0..n {
        let t = k as f64 / n as f64;
        let x = ControlInput {
            desired_position: 2.0 * t,
            desired_velocity: 10.0 * (t - 0.5),
            desired_acceleration: 100.0 * (t - 0.3),
            motor_position: 2.0 * t + 0.01 * (t - 0.5),
            motor_velocity: 10.0 * (t - 0.5) + 0.3,
            joint_torque: 5.0 * (t - 0.5),
            ..Default::default()
        };
        let (_, tol) = agree::<I16F16>(
            &x,
            &RobustAdaptiveDesign::table_4_1().initial_friction,
            0.05,
        )
        .unwrap();
        total_tol += tol;
    }
    let mean = total_tol / n as f64;
    assert!(mean < 0.01 * 0.188, "mean budget {mean}");
}
/// Theorem 1 in closed loop: a rotor of inertia `I_m` (eq. 4.6 reduced to
/// one joint) with friction inside the Table 4.1 box plus a varying part
/// within `ρ_F`, nonparametric friction within `ρ_fq`, base disturbance
/// within `I_m ρ_base`, and a joint-torque estimate off by up to half of
/// `ρ_τ`, under the law sampled at 10 µs (inside the boundary-layer limit
/// of 13.4 µs from `UltimateBound::boundary_layer_step_ratio`). After the
/// reaching-time bound of eq. (4.31) (here met long before), `|r|` stays
/// within the radius `r_S` and `|e|` within `r_S/λ`; the estimates stay in
/// the box.
#[test]
fn closed_loop_stays_within_the_ultimate_bound() {
    use crate::control::bound::UltimateBound;
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.torque_limit = 1.0;
    d.integral_limit = 0.5;
    d.sample_period = 1e-5;
    let p = RobustAdaptiveParams::try_new(d).unwrap();
    let b = UltimateBound::new(&d);
    assert!(b.boundary_layer_step_ratio < 2.0);
    let cfg = RobustAdaptiveConfig::<f64>::new(&p);
    let mut st = cfg.initial_state();
    let truth_c = FrictionParams {
        viscous: 8e-5,
        coulomb: 0.010,
        stribeck: 0.008,
        stribeck_shape: 2.0,
    };
    let i_m = d.rotor_inertia;
    let (mut q, mut qd) = (0.2, 0.0);
    let dt = d.sample_period;
    let f_tilde: [f64; 4] =
        core::array::from_fn(|j| truth_c.to_array()[j] - d.initial_friction.to_array()[j]);
    let v0 = UltimateBound::lyapunov(&d, d.lambda * 0.2, 0.0, &f_tilde);
    let t_reach = b.reaching_time(v0, 0.0);
    let (mut max_r, mut max_e, mut first_in) = (0.0f64, 0.0f64, None);
    let steps = 150_000;
    for k in 0..steps {
        let t = k as f64 * dt;
        let (w, amp) = (2.0, 3.0);
        let x = ControlInput {
            desired_position: amp * (w * t).sin(),
            desired_velocity: amp * w * (w * t).cos(),
            desired_acceleration: -amp * w * w * (w * t).sin(),
            motor_position: q,
            motor_velocity: qd,
            joint_torque: 5.0 * (2.0 * t).sin() + 0.5 * (37.0 * t).sin(),
            ..Default::default()
        };
        let o = cfg.update(&mut st, &x);
        assert!(!o.saturated);
        if first_in.is_none() && o.sliding.abs() <= b.sliding_radius {
            first_in = Some(t);
        }
        if t > 0.5 {
            max_r = max_r.max(o.sliding.abs());
            max_e = max_e.max(o.tracking_error.abs());
        }
        // Plant, 4 sub-steps with the torque held.
        let tau_t = 5.0 * (2.0 * t).sin();
        let mut truth = truth_c;
        truth.coulomb += 0.005 * (3.0 * t).sin();
        for _ in 0..4 {
            let h = dt / 4.0;
            let friction = truth.torque(qd) + 1.5e-3 * (3.0 * q).sin();
            let base = i_m * 5000.0 * (11.0 * t).sin();
            let qdd = (o.torque - friction - tau_t / d.ratio - base) / i_m;
            qd += h * qdd;
            q += h * qd;
        }
        for j in 0..4 {
            assert!(
                st.friction[j] >= cfg.lower_bounds()[j] && st.friction[j] <= cfg.upper_bounds()[j]
            );
        }
    }
    assert!(first_in.unwrap() <= t_reach, "{first_in:?} > {t_reach}");
    assert!(max_r <= b.sliding_radius, "{max_r} > {}", b.sliding_radius);
    assert!(max_e <= b.tracking_error, "{max_e} > {}", b.tracking_error);
    std::println!("closed loop: max |r| = {max_r:.3e} rad/s (r_S = {:.3}), max |e| = {max_e:.3e} rad (bound {:.3e})", b.sliding_radius, b.tracking_error);
}

/// The sampled-loop caveat of `UltimateBound::step_ratio_at_speed`: with
/// Table 4.1's gains the robust terms flip sign from sample to sample
/// (mean |Δτ| between samples above half of K_r = 0.170 N·m) at 4 ms
/// (ratio ≈ 600 from the ε_r layer alone) and still at 10 µs, where the
/// ε_r layer alone would be resolved (ratio 1.5) but the viscous layer
/// `ρ_F1 q̇²/ε_F1 = 1e-3·36/1e-4 = 360 N·m·s/rad` at 6 rad/s gives a ratio
/// near 320. With the parametric terms removed (ρ_F = 0) the 10 µs
/// command is smooth.
#[test]
fn table_4_1_gains_chatter_when_sampled() {
    use crate::control::bound::UltimateBound;
    fn mean_step(dt: f64, seconds: f64, with_rho_f: bool) -> f64 {
        let mut d = RobustAdaptiveDesign::table_4_1();
        d.torque_limit = 1.0;
        d.sample_period = dt;
        if !with_rho_f {
            d.friction_bounds = FrictionBounds::from_checked(
                d.friction_bounds.min(),
                d.friction_bounds.max(),
                [0.0; 4],
            );
        }
        let cfg = RobustAdaptiveConfig::<f64>::new(&RobustAdaptiveParams::try_new(d).unwrap());
        let mut st = cfg.initial_state();
        let (mut q, mut qd, mut last, mut sum, mut n) = (0.0f64, 0.0f64, 0.0f64, 0.0, 0);
        let steps = (seconds / dt) as usize;
        let sub = ((dt / 2.5e-6) as usize).max(1);
        for k in 0..steps {
            let t = k as f64 * dt;
            let x = ControlInput {
                desired_position: 3.0 * (2.0 * t).sin(),
                desired_velocity: 6.0 * (2.0 * t).cos(),
                desired_acceleration: -12.0 * (2.0 * t).sin(),
                motor_position: q,
                motor_velocity: qd,
                ..Default::default()
            };
            let o = cfg.update(&mut st, &x);
            if k > steps / 2 {
                sum += (o.torque - last).abs();
                n += 1;
            }
            last = o.torque;
            let truth = d.initial_friction;
            for _ in 0..sub {
                let h = dt / sub as f64;
                qd += h * (o.torque - truth.torque(qd)) / d.rotor_inertia;
                q += h * qd;
            }
        }
        sum / n as f64
    }
    let d = RobustAdaptiveDesign::table_4_1();
    let mut fast = d;
    fast.sample_period = 1e-5;
    assert!(UltimateBound::step_ratio_at_speed(&d, 6.0) > 2.0);
    assert!(UltimateBound::step_ratio_at_speed(&fast, 6.0) > 300.0);
    assert!(UltimateBound::new(&fast).boundary_layer_step_ratio < 2.0);
    assert!(mean_step(4e-3, 2.0, true) > 0.085);
    assert!(mean_step(1e-5, 0.5, true) > 0.085);
    let smooth = mean_step(1e-5, 0.5, false);
    assert!(smooth < 1e-3 * 0.170, "{smooth}");
}

proptest! {
    /// The step from eq. (4.19) to eq. (4.22): with the robust gains and
    /// `K_I` zero, exact friction compensation and an exact torque
    /// estimate, eq. (4.2) under the law gives `ṙ = −λ r` (the `2λ` of `a`
    /// in eq. 4.15 leaves exactly one `−λ r`).
    #[test]
    fn nominal_closed_loop_gives_r_dot_minus_lambda_r(x in sample(), f in estimate()) {
        let mut d = RobustAdaptiveDesign::table_4_1();
        d.torque_limit = 16.0;
        d.uncertainty = UncertaintyBounds { boundary_layer: 0.0, nonparametric_friction: 0.0, base_acceleration: 0.0, torque_estimate: 0.0 };
        d.friction_bounds = FrictionBounds::from_checked(d.friction_bounds.min(), d.friction_bounds.max(), [0.0; 4]);
        let cfg = RobustAdaptiveConfig::<f64>::new(&RobustAdaptiveParams::try_new(d).unwrap());
        let st = RobustAdaptiveState::from_stored(f.to_array(), 0.0);
        let tau = cfg.law(&st, &x).law;
        let qdd = (tau - f.nominal(x.motor_velocity, d.eps_velocity) - x.joint_torque / d.ratio) / d.rotor_inertia;
        let ed = x.motor_velocity - x.desired_velocity;
        let e = x.motor_position - x.desired_position;
        let r_dot = qdd - x.desired_acceleration + d.lambda * ed;
        let r = ed + d.lambda * e;
        prop_assert!((r_dot + d.lambda * r).abs() <= 1e-6 * (1.0 + x.desired_acceleration.abs() + d.lambda * d.lambda * e.abs()), "{r_dot} vs {}", -d.lambda * r);
    }
}

/// Table 6.1's design of the wrist motors (ch. 6) in this law's form:
/// `I_m = 10.5e-4 g·m² = 1.05e-6 kg·m²`, `N = 531`, `λ = 160`, `K_I = 10`,
/// `μ = 0.1`, `ρ_fq = 0.5 N·m`, the same layers and `ρ_F` as Table 4.1;
/// the friction box, limits and `T = 4 ms` as for Table 4.1.
fn table_6_1() -> RobustAdaptiveParams {
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.rotor_inertia = 1.05e-6;
    d.ratio = 531.0;
    d.lambda = 160.0;
    d.integral_gain = 10.0;
    d.adaptation_gain = [0.1; 4];
    d.uncertainty.nonparametric_friction = 0.5;
    RobustAdaptiveParams::try_new(d).unwrap()
}

/// One sample of the adaptation scenario at time `t` (SI): the motor
/// sweeps `±2 rad/s` through the peak of `|Y_4|` (at `1/√f̂_τ ≈ 1 rad/s`)
/// with a speed error of `0.3 rad/s` and a position error of `2 mrad`, so
/// `|r| ≲ 0.6 rad/s`; every value is rounded to the I16F16 grid, so the
/// backends see the same numbers (f32 holds them exactly: below 2¹⁸ LSB).
fn adaptation_sample(t: f64) -> ControlInput<f64> {
    let qd = 2.0 * t.sin();
    let x = ControlInput {
        desired_position: qd,
        desired_velocity: 2.0 * t.cos(),
        desired_acceleration: -qd,
        motor_position: qd + 0.002 * (1.7 * t).sin(),
        motor_velocity: 2.0 * t.cos() + 0.3 * (3.1 * t).sin(),
        ..Default::default()
    };
    let g = |v: f64| I16F16::from_f64(v).to_f64();
    ControlInput {
        desired_position: g(x.desired_position),
        desired_velocity: g(x.desired_velocity),
        desired_acceleration: g(x.desired_acceleration),
        motor_position: g(x.motor_position),
        motor_velocity: g(x.motor_velocity),
        ..x
    }
}

/// Per-parameter bound on `|∂(r Y_j)/∂F̂_i|` (stored units, exact
/// arithmetic) over the segment between two estimates whose smallest
/// shape is `shape_min` and largest static level `static_max`, at sliding
/// value `r` and speed `v`: `r Y_3 = r s e^{−f_τ v²}` and
/// `r Y_4 = −r f_s v² s e^{−f_τ v²}` (`|s| ≤ 1`) give
/// `∂(rY_3)/∂f_τ ≤ |r| v² e^{−f_τ,min v²}`,
/// `∂(rY_4)/∂f_s ≤ |r| v² e^{−f_τ,min v²}` and
/// `∂(rY_4)/∂f_τ ≤ |r| f_s,max v⁴ e^{−f_τ,min v²}`; `rY_1`, `rY_2` do not
/// depend on `F̂`.
fn regressor_lipschitz(r: f64, v: f64, shape_min: f64, static_max: f64) -> [[f64; 4]; 4] {
    let v2 = v * v;
    let ex = (-shape_min.max(0.0) * v2).exp();
    let mut l = [[0.0; 4]; 4];
    l[2][3] = r.abs() * v2 * ex;
    l[3][2] = r.abs() * v2 * ex;
    l[3][3] = r.abs() * static_max.abs() * v2 * v2 * ex;
    l
}

/// The adaptation of backend `S` against `f64` on the same input sequence
/// (open loop, so only arithmetic separates them), with the bound `D_k`
/// on `|F̂_S − F̂_64|` (per parameter, `S`'s stored units) carried along:
///
/// `D_{k+1} = max(D_k + c_j (δ_S + δ_64 + Σ_i L_ji (D_i + h)) + a_j, b)`,
///
/// where `c_j = μ_j T` in stored units, `δ` the budget of the computed
/// `r Y_j` against exact arithmetic ([`regressor_budget`], for `f64`
/// converted to `S`'s units), `L` [`regressor_lipschitz`] (the law reads
/// the value without its residual, `h_j` = ½ LSB on `I16F16`, `u|F̂_j|`
/// on `f32`, `u = 2⁻²⁴`), `a_j` the rounding of the step itself
/// (`I16F16`: the coefficient's 2⁻³¹ relative and ½ of the 2⁻⁴⁸
/// accumulator unit; `f32`: its coefficient, product and the sum with the
/// residual, `3u` of the step, and the compensated sum's `u²|F̂|`, or
/// `u|F̂ + step|` when the step exceeds the value and Fast2Sum is not
/// exact; plus the `f64` reference's own `2·2⁻⁵³`), and `b` the
/// quantization of the box corners (the clamp is 1-Lipschitz in the value
/// and in its bounds). `D_0` is the quantization of the initial estimate.
/// Returns, per parameter, the largest `|F̂_S − F̂_64| / D` seen, `D_N`,
/// and the movement `|F̂_64,N − F̂_64,0|` (stored units).
fn adaptation_agreement<S: Scalar>(
    p: &RobustAdaptiveParams,
    steps: usize,
    accumulator: impl Fn(S, S::Residual) -> f64,
) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let d = p.design();
    let cs = RobustAdaptiveConfig::<S>::new(p);
    let c64 = RobustAdaptiveConfig::<f64>::new(p);
    let (mut ss, mut s64) = (cs.initial_state(), c64.initial_state());
    let ps = crate::friction::parameter_scales::<S>();
    let ys = regressor_scales::<S>();
    let un = S::UNITS;
    let q = S::RESOLUTION.to_f64();
    let fixed = q >= 1.0 / 65536.0;
    let u = q / 2.0;
    let c: [f64; 4] = core::array::from_fn(|j| {
        d.adaptation_gain[j] * d.sample_period * ps[j] / (un.speed * ys[j])
    });
    let box_q: [f64; 4] = core::array::from_fn(|j| {
        let lo = (cs.lower_bounds()[j].to_f64() - d.friction_bounds.min()[j] * ps[j]).abs();
        let hi = (cs.upper_bounds()[j].to_f64() - d.friction_bounds.max()[j] * ps[j]).abs();
        lo.max(hi)
    });
    let f0 = d.initial_friction.to_array();
    let mut bound: [f64; 4] =
        core::array::from_fn(|j| (cs.initial_state().friction[j].to_f64() - f0[j] * ps[j]).abs());
    let mut worst = [0.0f64; 4];
    for k in 0..steps {
        let x64 = adaptation_sample(k as f64 * d.sample_period);
        let xs = to_backend::<S>(&x64);
        let bs = regressor_budget(&cs, &ss, &xs);
        let b64 = regressor_budget(&c64, &s64, &x64);
        // The two estimates in S's stored units, and the segment's extremes.
        let fs: [f64; 4] = core::array::from_fn(|j| ss.friction[j].to_f64());
        let f64s: [f64; 4] = core::array::from_fn(|j| s64.friction[j] * ps[j]);
        let h: [f64; 4] = core::array::from_fn(|j| {
            if fixed {
                q / 2.0
            } else {
                u * fs[j].abs() * 1.01
            }
        });
        let shape_min = fs[3].min(f64s[3]) - h[3];
        let static_max = fs[2].abs().max(f64s[2].abs()) + h[2];
        let l = regressor_lipschitz(bs.r, xs.motor_velocity.to_f64(), shape_min, static_max);
        let ts = cs.law(&ss, &xs);
        let t64 = c64.law(&s64, &x64);
        cs.commit(&mut ss, &ts);
        c64.commit(&mut s64, &t64);
        let mut next = bound;
        for j in 0..4 {
            let to_s = un.speed * ys[j];
            let dry = bs.r.abs() * bs.dy[j] + bs.y[j].abs() * bs.dr + rounding::<S>(bs.r * bs.y[j]);
            let dry64 = (b64.r.abs() * b64.dy[j]
                + b64.y[j].abs() * b64.dr
                + rounding::<f64>(b64.r * b64.y[j]))
                * to_s;
            let couple: f64 = (0..4).map(|i| l[j][i] * (bound[i] + h[i])).sum();
            let step = c[j] * (bs.r * bs.y[j]).abs();
            let own = if fixed {
                step * 2f64.powi(-31) + 2f64.powi(-49)
            } else {
                let inexact = if step > fs[j].abs() {
                    u * (fs[j].abs() + step)
                } else {
                    0.0
                };
                3.0 * u * step + u * u * fs[j].abs() * 1.01 + inexact
            };
            let reference = 2.0 * f64::EPSILON * (step + f64s[j].abs());
            next[j] = (bound[j] + c[j] * (dry + dry64 + couple) + own + reference).max(box_q[j]);
        }
        bound = next;
        for j in 0..4 {
            let diff = (accumulator(ss.friction[j], ss.friction_residual[j])
                - s64.friction[j] * ps[j])
                .abs();
            worst[j] = worst[j].max(diff / bound[j]);
        }
    }
    let moved: [f64; 4] = core::array::from_fn(|j| (s64.friction[j] - f0[j]).abs() * ps[j]);
    (worst, bound, moved)
}

/// Every adapted parameter follows the `f64` trajectory on `I16F16` and
/// `f32` within the bound derived in [`adaptation_agreement`], at Table
/// 4.1's and Table 6.1's gains, over 10 s at 4 ms; and the bound is far
/// below how far `f̂_τ` moves (at least 10×), so an `f̂_τ` that does not
/// adapt (the rounding of every step to the backend, which leaves it at its
/// initial value on `I16F16`: checked below) fails this test.
#[test]
fn adaptation_trajectories_agree_across_backends() {
    let fixed_acc = |v: I16F16, res: i32| v.to_f64() + res as f64 * 2f64.powi(-48);
    let sci =
        |a: [f64; 4]| std::format!("[{:.2e}, {:.2e}, {:.2e}, {:.2e}]", a[0], a[1], a[2], a[3]);
    for (name, p) in [("Table 4.1", table()), ("Table 6.1", table_6_1())] {
        let (w, b, m) = adaptation_agreement::<I16F16>(&p, 2500, fixed_acc);
        std::println!(
            "{name} I16F16: worst |ΔF|/D = {w:.3?}, D_N = {}, f64 moved {}",
            sci(b),
            sci(m)
        );
        for (j, wj) in w.iter().enumerate() {
            assert!(*wj <= 1.0, "{name} I16F16 parameter {j}: {wj} of the bound");
        }
        assert!(
            m[3] > 10.0 * b[3],
            "{name}: f̂_τ moved {} vs bound {}",
            m[3],
            b[3]
        );
        let (w, b, m) =
            adaptation_agreement::<f32>(&p, 2500, |v: f32, res: f32| v as f64 + res as f64);
        std::println!(
            "{name} f32: worst |ΔF|/D = {w:.3?}, D_N = {}, f64 moved {}",
            sci(b),
            sci(m)
        );
        for (j, wj) in w.iter().enumerate() {
            assert!(*wj <= 1.0, "{name} f32 parameter {j}: {wj} of the bound");
        }
        assert!(
            m[3] > 10.0 * b[3],
            "{name}: f̂_τ moved {} vs bound {}",
            m[3],
            b[3]
        );
    }
}

/// The defect the accumulator removes: on the same scenario, rounding
/// each `f̂_τ` step to `I16F16` (the step `F̂ ← F̂ − μT rY`, as a plain
/// product and sum) never moves it, while the accumulated `f̂_τ` does; and
/// with Table 4.1's and 6.1's gains every stored step of `f̂_τ` is below
/// half an LSB on this scenario (the reason).
#[test]
fn rounded_steps_leave_the_stribeck_shape_at_its_initial_value() {
    for p in [table(), table_6_1()] {
        let cfg = RobustAdaptiveConfig::<I16F16>::new(&p);
        let mut st = cfg.initial_state();
        let mut rounded = cfg.initial_state().friction[3];
        let mut largest_step = 0.0f64;
        for k in 0..2500 {
            let x = to_backend::<I16F16>(&adaptation_sample(k as f64 * 0.004));
            let t = cfg.law(&st, &x);
            largest_step = largest_step.max(t.ry[3].to_f64().abs() * cfg.adapt[3].value().abs());
            rounded = rounded.add(t.ry[3].mul_coef(&cfg.adapt[3]));
            cfg.commit(&mut st, &t);
        }
        assert!(largest_step < 0.5 * 2f64.powi(-16), "{largest_step}");
        assert_eq!(rounded, cfg.initial_state().friction[3]);
        assert!(st.friction[3] != cfg.initial_state().friction[3]);
    }
}

/// Why `f32` carries a residual too. From `f̂_τ(0) = 1` a plain `f32`
/// sum `f̂_τ + μT rY_4` (the same steps, taken from the compensated run)
/// happens to end near the `f64` value (its per-step error, up to half an
/// ulp `6e-8` against steps of about `5e-8`, is not systematic there), but
/// from `f̂_τ(0) = 4` (inside Table 4.1's box `[0.01, 10]`) every step is
/// below half an ulp (`2.4e-7`) and the plain sum never moves, while the
/// compensated value follows `f64` within 1 % of its movement.
#[test]
fn plain_f32_sum_loses_the_stribeck_shape_adaptation() {
    for (start, plain_moves) in [(1.0, true), (4.0, false)] {
        let mut d = RobustAdaptiveDesign::table_4_1();
        d.initial_friction.stribeck_shape = start;
        let p = RobustAdaptiveParams::try_new(d).unwrap();
        let c32 = RobustAdaptiveConfig::<f32>::new(&p);
        let c64 = RobustAdaptiveConfig::<f64>::new(&p);
        let (mut s32, mut s64) = (c32.initial_state(), c64.initial_state());
        let mut plain = s32.friction[3];
        for k in 0..2500 {
            let x64 = adaptation_sample(k as f64 * 0.004);
            let x32 = to_backend::<f32>(&x64);
            let t = c32.law(&s32, &x32);
            plain = (plain + t.ry[3] * c32.adapt[3].f32_value()).clamp(c32.lower[3], c32.upper[3]);
            c32.commit(&mut s32, &t);
            let t64 = c64.law(&s64, &x64);
            c64.commit(&mut s64, &t64);
        }
        let moved = (s64.friction[3] - start).abs();
        let plain_err = (plain as f64 - s64.friction[3]).abs();
        let comp_err =
            (s32.friction[3] as f64 + s32.friction_residual[3] as f64 - s64.friction[3]).abs();
        std::println!(
            "f̂_τ(0) = {start}: f64 moved {moved:.3e}; plain f32 off by {plain_err:.3e}, compensated by {comp_err:.3e}"
        );
        assert_eq!(plain != start as f32, plain_moves);
        assert!(comp_err < 0.01 * moved, "{comp_err} vs {moved}");
    }
}

/// The other integrators at the tables' gains: one LSB of `r` moves the
/// integral `z` by `K_I T` (stored), which must be at least one LSB on
/// `I16F16` (it is 40 LSB: `10·0.004·1e3` mN·m per rad/s); and the
/// smallest non-zero `f̂` step (one LSB of `rY_j`) is at least 1000 units
/// of the Q16.48 accumulator for every parameter.
#[test]
fn slow_integrators_move_at_table_gains() {
    for p in [table(), table_6_1()] {
        let cfg = RobustAdaptiveConfig::<I16F16>::new(&p);
        let lsb = I16F16::RESOLUTION;
        let dz = cfg.integral_step.apply(lsb);
        assert!(dz >= lsb, "{dz:?}");
        assert_eq!(dz.to_bits(), 40);
        for j in 0..4 {
            let step = cfg.adapt[j].scale_wide(1, 32).unsigned_abs();
            assert!(step >= 1000, "parameter {j}: {step}");
        }
    }
}

/// `K_r sat(r/ε_r)` inside the layer is the prepared slope's product
/// without a clamp: it must stay within `±K_r` at the layer's edge (the
/// extreme: the product is monotone) for every layer width, on every
/// backend; on `I16F16` with Table 4.1 it is checked at every `r` of the
/// layer, non-decreasing and within ½ LSB + the slope's relative
/// preparation (64·2⁻²³) of `K_r r/ε_r`.
#[test]
fn robust_layer_slope_stays_within_the_gain() {
    fn edge_fits<S: Scalar>(p: &RobustAdaptiveParams) {
        let c = RobustAdaptiveConfig::<S>::new(p);
        let [hi, lo] = c.robust_gain_value;
        for r in [c.eps_r, c.eps_r.neg()] {
            let v = r.mul_coef(&c.robust_slope);
            assert!(
                v <= hi && v >= lo,
                "ε_r {}: {} outside ±{}",
                c.eps_r.to_f64(),
                v.to_f64(),
                hi.to_f64()
            );
        }
    }
    let mut w = 2e-4f64;
    while w < 20.0 {
        let mut d = table().design;
        d.eps_r = w;
        let p = RobustAdaptiveParams::try_new(d).unwrap();
        edge_fits::<I16F16>(&p);
        edge_fits::<f32>(&p);
        edge_fits::<f64>(&p);
        w *= 1.003;
    }
    let c = RobustAdaptiveConfig::<I16F16>::new(&table());
    let k = c.robust_gain_value[0].to_f64();
    let e = c.eps_r.to_bits();
    let mut prev = I16F16::MIN;
    for bits in -e..=e {
        let r = I16F16::from_bits(bits);
        let v = r.mul_coef(&c.robust_slope);
        let exact = k * bits as f64 / e as f64;
        let tol = 0.5 / 65536.0 + k * 64.0 / 8_388_608.0 + 1e-12;
        assert!(
            (v.to_f64() - exact).abs() <= tol,
            "r bits {bits}: {} vs {exact}",
            v.to_f64()
        );
        assert!(v >= prev);
        prev = v;
    }
}

/// Every boundary layer is validated against `[2⁻¹⁶, 30 000]` in its
/// stored unit, written here in SI: `ε_r` and `ε_velocity` in rad/s
/// (scale 1), `ε_F4` in mN·m·s²/rad² (scale 10³, its regressor
/// component's unit on `I16F16`). Both ends are accepted, the next `f64`
/// outward is rejected with the field's name and the SI range.
#[test]
fn boundary_layers_are_accepted_to_their_quantization_limits() {
    let base = RobustAdaptiveDesign::table_4_1();
    type Field = fn(&mut RobustAdaptiveDesign) -> &mut f64;
    let cases: [(&str, f64, Field); 3] = [
        ("eps_r", 1.0, |d| &mut d.eps_r),
        ("eps_velocity", 1.0, |d| &mut d.eps_velocity),
        ("eps_f[3]", 1e3, |d| &mut d.eps_f[3]),
    ];
    for (name, scale, field) in cases {
        let (min, max) = (libm::exp2(-16.0) / scale, 30_000.0 / scale);
        for (v, ok) in [
            (min, true),
            (max, true),
            (min.next_down(), false),
            (max.next_up(), false),
        ] {
            let mut d = base;
            *field(&mut d) = v;
            match RobustAdaptiveParams::try_new(d) {
                Ok(_) => assert!(ok, "{name} = {v:e} accepted"),
                Err(e) => {
                    assert!(!ok, "{name} = {v:e} rejected: {e}");
                    assert_eq!(
                        e,
                        ParamError::OutOfRange {
                            name,
                            value: v,
                            min,
                            max
                        },
                        "{name} = {v:e}"
                    );
                }
            }
        }
    }
}

/// Each combination and range of `try_new` at its edge, on the Table 4.1
/// design with one field moved: the largest accepted value passes, the
/// next `f64` is rejected under the field's (or the combination's) name.
/// The edges, from the documentation: `ρ_τt ≤ 30·N` (with the other
/// uncertainties 0, so that `K_r` is exactly 30), `λ² I_m ≤ 1e8`,
/// `K_I T ≤ 1e8`, `μ_j T ≤ [1e8, 1e8, 1e8, 1e14]`,
/// `ρ_Fj ≤ [1e8, 1e8, 1e8, 1e11]`.
#[test]
fn combinations_are_accepted_to_their_documented_edges() {
    let base = RobustAdaptiveDesign::table_4_1();
    let check = |what: &str, name: &str, at: RobustAdaptiveDesign, past: RobustAdaptiveDesign| {
        if let Err(e) = RobustAdaptiveParams::try_new(at) {
            panic!("{what} at its edge rejected: {e}");
        }
        match RobustAdaptiveParams::try_new(past) {
            Ok(_) => panic!("{what} past its edge accepted"),
            Err(e) => assert_eq!(e.name(), name, "{what}: {e}"),
        }
    };
    // ρ_τt ≤ 30·N (N = 100).
    let mut at = base;
    at.uncertainty = UncertaintyBounds {
        boundary_layer: 0.0,
        nonparametric_friction: 0.0,
        base_acceleration: 0.0,
        torque_estimate: 3000.0,
    };
    assert_eq!(at.ratio, 100.0);
    let mut past = at;
    past.uncertainty.torque_estimate = 3000f64.next_up();
    check("rho_tau", "uncertainty.torque_estimate", at, past);
    // λ² I_m ≤ 1e8 with I_m = 1 kg·m² (and no base acceleration).
    let (mut at, mut past) = (base, base);
    for d in [&mut at, &mut past] {
        d.rotor_inertia = 1.0;
        d.uncertainty.base_acceleration = 0.0; // `≤ 30/I_m`
    }
    at.lambda = 1e4;
    past.lambda = 1e4f64.next_up();
    check("lambda", "lambda²·rotor_inertia", at, past);
    // K_I T ≤ 1e8.
    let t = base.sample_period;
    let (mut at, mut past) = (base, base);
    at.integral_gain = 1e8 / t;
    past.integral_gain = (1e8 / t).next_up();
    assert!(at.integral_gain * t <= 1e8 && past.integral_gain * t > 1e8);
    check("K_I", "integral_gain·sample_period", at, past);
    // μ_j T and ρ_Fj.
    for (j, (mu_t, rho)) in [(1e8, 1e8), (1e8, 1e8), (1e8, 1e8), (1e14, 1e11)]
        .into_iter()
        .enumerate()
    {
        let (mut at, mut past) = (base, base);
        at.adaptation_gain[j] = mu_t / t;
        past.adaptation_gain[j] = (mu_t / t).next_up();
        assert!(at.adaptation_gain[j] * t <= mu_t && past.adaptation_gain[j] * t > mu_t);
        check("mu", ADAPTATION_STEP[j], at, past);
        let b = base.friction_bounds;
        let (lo, hi) = (
            FrictionParams::from_array(b.min()),
            FrictionParams::from_array(b.max()),
        );
        let with = |v: f64| {
            let mut var = b.variable();
            var[j] = v;
            let mut d = base;
            d.friction_bounds = FrictionBounds::try_new(lo, hi, var).unwrap();
            d
        };
        check("rho_F", VARIABLE_BOUND[j], with(rho), with(rho.next_up()));
    }
}

/// A state made from SI values reads them back on every backend: the
/// stored integral is `z` times the motor-torque scale (10³ on `I16F16`,
/// 1 on floats), `integral_si` is `z` again, the stored friction is the
/// SI estimate times its parameter scales; the integral range is closed
/// at `±integral_limit` and named past it. After steps of the law on
/// `I16F16` the getters return the state's fields, residual included (it
/// is non-zero there).
#[test]
fn state_from_si_reads_back_on_every_backend() {
    fn check<S: Scalar + core::fmt::Debug>(scale: f64, ps: [f64; 4]) {
        let p = table();
        let cfg = RobustAdaptiveConfig::<S>::new(&p);
        let d = p.design();
        let f = d.initial_friction;
        let lim = d.integral_limit;
        for z in [-lim, -0.3 * lim, 0.7 * lim, lim] {
            let st = cfg.state(f, z).unwrap();
            let stored = S::from_f64(z * scale);
            assert_eq!(st.integral(), stored, "{}", S::NAME);
            // The documented reading, and within one rounding of `z`: half
            // a step of the backend's resolution (relative on the floats,
            // 2⁻¹⁶ stored units on I16F16) in the stored scale.
            assert_eq!(st.integral_si(), stored.to_f64() / scale, "{}", S::NAME);
            let half_step = 0.5 * S::RESOLUTION.to_f64() * (z.abs() * scale).max(1.0) / scale;
            assert!((st.integral_si() - z).abs() <= half_step, "{}", S::NAME);
            let want = f.to_array();
            for j in 0..4 {
                assert_eq!(
                    st.friction()[j],
                    S::from_f64(want[j] * ps[j]),
                    "{} {j}",
                    S::NAME
                );
            }
        }
        for z in [lim.next_up(), (-lim).next_down()] {
            let e = cfg.state(f, z).unwrap_err();
            assert_eq!(e.name(), "integral", "{}: {e}", S::NAME);
        }
    }
    check::<f64>(1.0, [1.0; 4]);
    check::<f32>(1.0, [1.0; 4]);
    check::<I16F16>(1e3, [1e3, 1e3, 1e3, 1.0]);

    let p = table();
    let cfg = RobustAdaptiveConfig::<I16F16>::new(&p);
    let mut st = cfg.initial_state();
    let x = ControlInput {
        desired_velocity: I16F16::from_f64(0.5),
        motor_velocity: I16F16::from_f64(0.8),
        motor_position: I16F16::from_f64(0.01),
        ..Default::default()
    };
    for _ in 0..50 {
        let _ = cfg.update(&mut st, &x);
    }
    assert_eq!(st.friction(), st.friction);
    assert_eq!(st.integral(), st.integral);
    assert_eq!(st.friction_residual(), st.friction_residual);
    assert!(
        st.friction_residual.iter().any(|&r| r != 0),
        "{:?}",
        st.friction_residual
    );
    assert!(st.integral != I16F16::ZERO);
    assert_eq!(st.integral_si(), st.integral.to_f64() / 1e3);
}

/// Layers that every backend represents exactly come back unchanged from
/// `quantized_design`, on all three backends; chosen at or above 1 rad/s
/// (a layer below 1 is its own remainder modulo 1), with `ε_F4 = 0.5`
/// stored as 500 on `I16F16`.
#[test]
fn quantized_design_returns_exact_layers_unchanged() {
    let mut d = RobustAdaptiveDesign::table_4_1();
    d.eps_r = 2.5;
    d.eps_velocity = 1.5;
    d.eps_f = [1.25, 3.0, 2.0, 0.5];
    let p = RobustAdaptiveParams::try_new(d).unwrap();
    fn layers(d: RobustAdaptiveDesign) -> (f64, f64, [f64; 4]) {
        (d.eps_r, d.eps_velocity, d.eps_f)
    }
    let want = layers(d);
    assert_eq!(
        layers(RobustAdaptiveConfig::<f64>::new(&p).quantized_design()),
        want
    );
    assert_eq!(
        layers(RobustAdaptiveConfig::<f32>::new(&p).quantized_design()),
        want
    );
    assert_eq!(
        layers(RobustAdaptiveConfig::<I16F16>::new(&p).quantized_design()),
        want
    );
}

/// The torque limit is closed: a law of exactly `±torque_limit` passes
/// unflagged, one step beyond is clamped and flagged, on every backend.
#[test]
fn torque_limit_is_closed_and_flags_only_beyond() {
    fn check<S: Scalar + core::fmt::Debug>(beyond: impl Fn(S) -> S) {
        let cfg = RobustAdaptiveConfig::<S>::new(&table());
        let l = cfg.torque_limit();
        assert!(l > S::ZERO);
        assert_eq!(cfg.limit(l), (l, false), "{}", S::NAME);
        assert_eq!(cfg.limit(l.neg()), (l.neg(), false), "{}", S::NAME);
        assert_eq!(cfg.limit(beyond(l)), (l, true), "{}", S::NAME);
        assert_eq!(cfg.limit(beyond(l).neg()), (l.neg(), true), "{}", S::NAME);
    }
    check::<f64>(|l| l.next_up());
    check::<f32>(|l| l.next_up());
    check::<I16F16>(|l| I16F16::from_bits(l.to_bits() + 1));
}

/// The integral's anti-windup (eq. 4.19's `z = K_I ∫ r dt`, frozen while
/// the law is saturated and `r` would drive it further): with the law
/// inside `±torque_limit` (its edges included) `z` moves by `K_I T r`
/// whatever the signs; with the law beyond `+limit` it moves only for
/// `r > 0`, beyond `−limit` only for `r < 0`.
#[test]
fn integral_freezes_only_when_it_would_wind_up() {
    let p = table();
    let d = p.design();
    let cfg = RobustAdaptiveConfig::<f64>::new(&p);
    let l = cfg.torque_limit();
    let step = |law: f64, r: f64| {
        let mut st = cfg.initial_state();
        let t = ActiveTerms {
            law,
            e: 0.0,
            r,
            ry: [0.0; 4],
            valid: true,
        };
        cfg.commit_valid(&mut st, &t);
        st.integral_si()
    };
    let moved = |r: f64| d.integral_gain * d.sample_period * r;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-15;
    for (law, r, moves) in [
        (0.5 * l, 0.1, true),
        (0.5 * l, -0.1, true),
        (-0.5 * l, 0.1, true),
        (l, -0.1, true),
        (-l, 0.1, true),
        (2.0 * l, 0.1, true),
        (2.0 * l, -0.1, false),
        (-2.0 * l, -0.1, true),
        (-2.0 * l, 0.1, false),
    ] {
        let z = step(law, r);
        let want = if moves { moved(r) } else { 0.0 };
        assert!(close(z, want), "law {law}, r {r}: z {z}, want {want}");
        assert!(want == 0.0 || want.abs() > 1e-4);
    }
}
