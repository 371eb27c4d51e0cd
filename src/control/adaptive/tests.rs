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
    d.lambda = 1e9;
    assert!(matches!(
        RobustAdaptiveParams::try_new(d),
        Err(ParamError::OutOfRange { name: "lambda", .. })
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
        let st = RobustAdaptiveState { friction: f.to_array(), integral: z };
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

/// First-order error budget of the stored-unit law on backend `S`
/// against exact arithmetic on the same (stored) inputs and parameters,
/// in SI N·m. It follows the implementation's operations one by one:
/// each rounding of a value of stored magnitude `m` costs
/// `½ LSB + 2·2⁻³⁰ m` in fixed point (product, prepared coefficient) and
/// `u·m` in floats (`u = RESOLUTION/2`); fixed additions are exact, float
/// additions cost `u·|sum|`; `exp` costs 1 LSB (fixed, `e^x ≤ 1`) or 2 ulp
/// (f32); `sat(x, ε)` is `1/ε`-Lipschitz, its error capped at 2.
fn law_error_budget<S: Scalar>(
    cfg: &RobustAdaptiveConfig<S>,
    st: &RobustAdaptiveState<S>,
    x: &ControlInput<S>,
) -> f64 {
    let fixed = S::RESOLUTION.to_f64() >= 1.0 / 65536.0;
    let q = S::RESOLUTION.to_f64();
    let u = q / 2.0;
    let rnd = |m: f64| {
        if fixed {
            0.5 * q + 2.0 * m.abs() * 2f64.powi(-30)
        } else {
            u * m.abs()
        }
    };
    let add = |m: f64| if fixed { 0.0 } else { u * m.abs() };
    let d = cfg.quantized_design();
    let un = S::UNITS;
    let mt = un.motor_torque;
    let g = |v: S| v.to_f64();
    let e = g(x.motor_position) - g(x.desired_position);
    let ed = g(x.motor_velocity) - g(x.desired_velocity);
    let (de, ded) = (add(e), add(ed));
    let lam = d.lambda * un.speed / un.angle;
    let r = ed + lam * e;
    let dr = ded + lam * de + rnd(lam * e) + add(r);
    let c_acc = d.rotor_inertia * mt / un.speed;
    let c_ed = 2.0 * d.lambda * d.rotor_inertia * mt / un.speed;
    let c_e = d.lambda * d.lambda * d.rotor_inertia * mt / un.angle;
    let ia = [g(x.desired_acceleration) * c_acc, ed * c_ed, e * c_e];
    let dia = rnd(ia[0])
        + c_ed * ded
        + rnd(ia[1])
        + c_e * de
        + rnd(ia[2])
        + 2.0 * add(ia.iter().map(|v| v.abs()).sum());
    // Friction.
    let th: [f64; 4] = [
        g(st.friction[0]),
        g(st.friction[1]),
        g(st.friction[2]),
        g(st.friction[3]),
    ];
    let v = g(x.motor_velocity);
    let eps_v = d.eps_velocity * un.speed;
    let s = v.sat(eps_v);
    let ds = rnd(1.0);
    let q2 = v * v;
    let dq2 = rnd(q2);
    let arg = th[3] * q2;
    let darg = th[3] * dq2 + rnd(arg);
    let ex = (-arg).exp();
    let dex = ex * darg + if fixed { q } else { 4.0 * u * ex };
    let es = ex * s;
    let des = dex * s.abs() + ex * ds + rnd(es);
    let q2e = q2 * ex;
    let dq2e = dq2 * ex + q2 * dex + rnd(q2e);
    let y4 = -th[2] * q2e * s;
    let dy4 = th[2].abs() * (dq2e * s.abs() + q2e * ds) + rnd(th[2] * q2e) + rnd(y4);
    let f = th[0] * v + th[1] * s + th[2] * es;
    let df = rnd(th[0] * v)
        + th[1].abs() * ds
        + rnd(th[1] * s)
        + th[2].abs() * des
        + rnd(th[2] * es)
        + 2.0 * add(f);
    let y = [v, s, es, y4];
    let dy = [0.0, ds, des, dy4];
    // Robust terms.
    let eps_r = d.eps_r * un.speed;
    let kr = d.robust_gain() * mt;
    let drob = kr * (dr / eps_r + rnd(1.0)).min(2.0) + rnd(kr);
    let ys = crate::friction::regressor_scales::<S>();
    let rho = d.friction_bounds.variable();
    let mut dparam = 0.0;
    let mut mag = 0.0;
    for j in 0..4 {
        let ry = r * y[j];
        let dry = r.abs() * dy[j] + y[j].abs() * dr + rnd(ry);
        let eps_j = d.eps_f[j] * un.speed * ys[j];
        let dss = (dry / eps_j + rnd(1.0)).min(2.0);
        let rj = rho[j] * mt / ys[j];
        let ry_term = rj * y[j];
        let term = ry_term * ry.sat(eps_j);
        dparam +=
            (rj * dy[j] + rnd(ry_term)) + ry_term.abs() * dss + rnd(term) + add(mag + term.abs());
        mag += term.abs();
    }
    let fb = g(x.joint_torque) * mt / (d.ratio * un.link_torque);
    let total = ia.iter().map(|v| v.abs()).sum::<f64>()
        + fb.abs()
        + f.abs()
        + g(st.integral).abs()
        + kr
        + mag;
    let budget = dia + rnd(fb) + df + drob + dparam + 5.0 * add(total);
    (budget * 1.01 + q) / mt
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
    let st = RobustAdaptiveState {
        friction: FrictionConfig::<S>::quantize(f),
        integral: S::from_f64(z * S::UNITS.motor_torque),
    };
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
    let st64 = RobustAdaptiveState {
        friction: FrictionConfig::<S>::dequantize(&st.friction).to_array(),
        integral: st.integral.to_f64() / u.motor_torque,
    };
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
        let st = RobustAdaptiveState { friction: f.to_array(), integral: 0.0 };
        let tau = cfg.law(&st, &x).law;
        let qdd = (tau - f.nominal(x.motor_velocity, d.eps_velocity) - x.joint_torque / d.ratio) / d.rotor_inertia;
        let ed = x.motor_velocity - x.desired_velocity;
        let e = x.motor_position - x.desired_position;
        let r_dot = qdd - x.desired_acceleration + d.lambda * ed;
        let r = ed + d.lambda * e;
        prop_assert!((r_dot + d.lambda * r).abs() <= 1e-6 * (1.0 + x.desired_acceleration.abs() + d.lambda * d.lambda * e.abs()), "{r_dot} vs {}", -d.lambda * r);
    }
}

/// The fixed-point resolution note on `RobustAdaptiveState`: at
/// `|r| = 1 rad/s`, `q̇ = 0.7 rad/s` (near the peak of `|Y_4|`) the f64 law
/// moves `f̂_τ` every step while I16F16 leaves it exactly at its initial
/// value; `f̂_c` moves on both.
#[test]
fn stribeck_shape_adaptation_is_below_fixed_point_resolution() {
    let p = table();
    let x64 = ControlInput {
        motor_velocity: 0.7,
        desired_velocity: -0.3,
        ..Default::default()
    };
    let c64 = RobustAdaptiveConfig::<f64>::new(&p);
    let mut s64 = c64.initial_state();
    let cx = RobustAdaptiveConfig::<I16F16>::new(&p);
    let mut sx = cx.initial_state();
    let xx = ControlInput {
        motor_velocity: I16F16::from_f64(0.7),
        desired_velocity: I16F16::from_f64(-0.3),
        ..Default::default()
    };
    for _ in 0..100 {
        c64.update(&mut s64, &x64);
        cx.update(&mut sx, &xx);
    }
    assert!((s64.friction[3] - 1.0).abs() > 1e-6);
    assert_eq!(sx.friction[3], cx.initial_state().friction[3]);
    assert!(sx.friction[1] != cx.initial_state().friction[1]);
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
