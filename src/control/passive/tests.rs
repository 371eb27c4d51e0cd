use super::*;
use crate::scalar::I16F16;
use proptest::prelude::*;

fn params(kp: f64) -> PassiveParams {
    PassiveParams::table_4_1(kp).unwrap()
}

/// Errata E4.1: simulate eq. (4.2) under eq. (4.32) with exact friction
/// compensation and `τ_td = 0`; the motor acceleration is
/// `−K_p τ̂_t / N` (the corrected eq. 4.33), not `−K_p τ̂_t` (printed).
#[test]
fn closed_loop_is_a_free_body_of_inertia_n_over_kp() {
    let kp = 2000.0;
    let p = params(kp);
    let cfg = PassiveConfig::<f64>::new(&p);
    let f = p.nominal_friction;
    let i_m = 1.14e-5;
    for &(qd, tau) in &[(0.3, 0.5), (-2.0, -0.2), (0.001, 1.0), (5.0, -0.05)] {
        let x = ControlInput {
            motor_velocity: qd,
            joint_torque: tau,
            ..Default::default()
        };
        let tau_m = cfg.update(&x).torque;
        // Eq. (4.2): I_m q̈ = τ_m − f(q̇) − τ_t/N, with the model's own
        // boundary-layer friction (the "uncertain part" neglected).
        let qdd = (tau_m - f.nominal(qd, 0.01) - tau / 100.0) / i_m;
        let corrected = -kp * tau / 100.0;
        assert!(
            (qdd - corrected).abs() <= 1e-9 * corrected.abs(),
            "{qdd} vs {corrected}"
        );
        assert!((qdd - (-kp * tau)).abs() > 0.5 * (kp * tau).abs());
    }
    assert_eq!(p.apparent_motor_inertia(), 100.0 / kp);
}

#[test]
fn try_new_names_the_bad_value() {
    assert!(matches!(
        PassiveParams::table_4_1(-1.0),
        Err(ParamError::Negative { name: "gain", .. })
    ));
    let f = RobustFriction::nominal();
    let s = PassiveSettings {
        rotor_inertia: 1e-5,
        gain: 1.0,
        ratio: 0.5,
        eps_velocity: 0.01,
        nominal_friction: f,
        torque_limit: 0.1,
    };
    assert!(matches!(
        PassiveParams::try_new(s),
        Err(ParamError::OutOfRange { name: "ratio", .. })
    ));
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings {
            ratio: 100.0,
            torque_limit: 17.0,
            ..s
        }),
        Err(ParamError::OutOfRange {
            name: "torque_limit",
            ..
        })
    ));
}

/// Each named setting reaches its own getter and its own place in
/// eq. (4.32): six distinct values, the law's output recomputed here
/// from the equation. (With positional arguments `Î_m`, `K_p`, `N`,
/// `ε_q̇` and the limit, all `f64`, could be swapped and still pass
/// validation.)
#[test]
fn named_settings_reach_their_getters_and_the_law() {
    let friction = FrictionParams {
        viscous: 2e-4,
        coulomb: 3e-3,
        stribeck: 1e-3,
        stribeck_shape: 0.5,
    }
    .validated()
    .unwrap();
    let s = PassiveSettings {
        rotor_inertia: 2e-5,
        gain: 3000.0,
        ratio: 80.0,
        eps_velocity: 0.02,
        nominal_friction: friction,
        torque_limit: 0.7,
    };
    let p = PassiveParams::try_new(s).unwrap();
    assert_eq!(p.rotor_inertia(), 2e-5);
    assert_eq!(p.gain(), 3000.0);
    assert_eq!(p.ratio(), 80.0);
    assert_eq!(p.eps_velocity(), 0.02);
    assert_eq!(p.nominal_friction(), friction);
    assert_eq!(p.torque_limit(), 0.7);
    assert_eq!(p.settings(), s);
    assert_eq!(PassiveParams::try_new(p.settings()), Ok(p));
    let cfg = PassiveConfig::<f64>::new(&p);
    let x = ControlInput {
        motor_velocity: 0.3,
        joint_torque: 1.5,
        desired_joint_torque: -0.5,
        ..Default::default()
    };
    // Eq. (4.32) with eq. (4.17), written out: f̂ = b q̇ + (f_c + f_s
    // e^{−f_τ q̇²}) · sat(q̇/ε).
    let qd: f64 = 0.3;
    let sat = (qd / 0.02).clamp(-1.0, 1.0);
    let f_hat = 2e-4 * qd + (3e-3 + 1e-3 * (-0.5 * qd * qd).exp()) * sat;
    let want = f_hat + 1.5 / 80.0 + 2e-5 * 3000.0 * (-0.5 - 1.5) / 80.0;
    let got = cfg.update(&x).torque;
    assert!((got - want).abs() <= 1e-12, "{got} vs {want}");
    // The limit is the named one.
    let big = ControlInput {
        joint_torque: 1e3,
        ..x
    };
    assert_eq!(cfg.update(&big).torque, 0.7);
}

/// Roots of a complex-coefficient-free monic polynomial
/// `xⁿ + c[0] xⁿ⁻¹ + … + c[n−1]` by the Durand–Kerner (Weierstrass)
/// iteration, as `(re, im)` pairs: an independent root finder.
fn durand_kerner(c: &[f64]) -> std::vec::Vec<(f64, f64)> {
    type C = (f64, f64);
    let mul = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let sub = |a: C, b: C| (a.0 - b.0, a.1 - b.1);
    let div = |a: C, b: C| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let n = c.len();
    let eval = |x: C| {
        let mut v: C = (1.0, 0.0);
        for &k in c {
            v = mul(v, x);
            v.0 += k;
        }
        v
    };
    let scale = 1.0 + c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut z: std::vec::Vec<C> = (0..n)
        .map(|k| {
            let a = 0.4 + core::f64::consts::TAU * k as f64 / n as f64;
            (scale * 0.5 * a.cos(), scale * 0.5 * a.sin())
        })
        .collect();
    for _ in 0..2000 {
        for i in 0..n {
            let mut den: C = (1.0, 0.0);
            for j in 0..n {
                if j != i {
                    den = mul(den, sub(z[i], z[j]));
                }
            }
            z[i] = sub(z[i], div(eval(z[i]), den));
        }
    }
    z
}

/// The distance from each computed pole to the nearest reference root.
fn match_roots(poles: &[Pole], roots: &[(f64, f64)]) -> f64 {
    poles
        .iter()
        .map(|p| {
            roots
                .iter()
                .map(|r| libm::hypot(p.re - r.0, p.im - r.1))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn frictionless(i_m: f64, kp: f64, n: f64) -> PassiveParams {
    let f = FrictionParams {
        viscous: 0.0,
        coulomb: 0.0,
        stribeck: 0.0,
        stribeck_shape: 1.0,
    }
    .validated()
    .unwrap();
    PassiveParams::try_new(PassiveSettings {
        rotor_inertia: i_m,
        gain: kp,
        ratio: n,
        eps_velocity: 0.01,
        nominal_friction: f,
        torque_limit: 16.0,
    })
    .unwrap()
}

/// The sampled passive loop simulated from its physical description,
/// independently of `characteristics`: the rigid joint
/// `J₀ q̈_l = N τ_m + τ_h` (RK4, 2000 steps per period), the joint torque
/// measured before each command as `τ_t = I_l q̈_l − τ_h` with the held
/// torque, and the command from the library's own law (eq. 4.32,
/// `PassiveConfig<f64>`, frictionless). Its one-period map on
/// `(q, q̇, N τ_m,prev)` (linear: columns from unit states) has a
/// characteristic polynomial whose roots (Durand–Kerner) must be the
/// discrete poles. Tolerance 1e-6: RK4's error over a period is
/// `≲ 2000·(ω h)⁵/120` with `ω h ≤ 0.01` here (`< 2e-10`), the
/// Durand–Kerner and bisection roots are near roundoff for these
/// simple roots, and the margin covers the conditioning of the roots.
#[test]
fn discrete_poles_match_a_simulated_period_map() {
    let cases = [
        // (I_m, K_p, N, K_h, B_h, I_l, T)
        (1.14e-5, 2.0 / 1.14e-5, 100.0, 200.0, 5.0, 0.05, 1e-4),
        (1.14e-5, 0.5 / 1.14e-5, 100.0, 200.0, 5.0, 0.2, 4e-3),
        (1.14e-5, 2000.0, 100.0, 50.0, 0.5, 0.02, 4e-3),
        (1.05e-6, 3.0 / 1.05e-6, 531.0, 1000.0, 2.0, 0.01, 4e-3),
    ];
    for (i_m, kp, n, kh, bh, il, t) in cases {
        let p = frictionless(i_m, kp, n);
        let hand = HandContact {
            stiffness: kh,
            damping: bh,
            link_inertia: il,
        };
        let ch = p.characteristics(&hand, t).unwrap();
        let cfg = PassiveConfig::<f64>::new(&p);
        let j0 = il + n * n * i_m;
        let period = |z: [f64; 3]| -> [f64; 3] {
            let (mut q, mut v, u_prev) = (z[0], z[1], z[2]);
            let tau_h = -kh * q - bh * v;
            let qdd = (u_prev + tau_h) / j0;
            let tau_t = il * qdd - tau_h;
            let x = ControlInput {
                joint_torque: tau_t,
                ..Default::default()
            };
            let u = n * cfg.update(&x).torque;
            let f = |q: f64, v: f64| (v, (u - kh * q - bh * v) / j0);
            let h = t / 2000.0;
            for _ in 0..2000 {
                let k1 = f(q, v);
                let k2 = f(q + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
                let k3 = f(q + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
                let k4 = f(q + h * k3.0, v + h * k3.1);
                q += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            }
            [q, v, u]
        };
        // Unit states of comparable size (1 mrad, 1 mrad/s, 1 mN·m).
        let scales = [1e-3, 1e-3, 1e-3];
        let mut m = [[0.0; 3]; 3];
        for col in 0..3 {
            let mut z = [0.0; 3];
            z[col] = scales[col];
            let y = period(z);
            for row in 0..3 {
                m[row][col] = y[row] / scales[col];
            }
        }
        let tr = m[0][0] + m[1][1] + m[2][2];
        let minors = m[0][0] * m[1][1] - m[0][1] * m[1][0] + m[0][0] * m[2][2] - m[0][2] * m[2][0]
            + m[1][1] * m[2][2]
            - m[1][2] * m[2][1];
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let roots = durand_kerner(&[-tr, minors, -det]);
        let err = match_roots(&ch.discrete_poles, &roots);
        std::println!(
            "K_p Î_m = {:.2}, K_h = {kh}, I_l = {il}, T = {t}: J = {:.4}, ω_n = {:.2}, ζ = {:.3}, σ = {:.2}, |z|max = {:.5}, σ_d = {:.2}; pole error {err:.1e}",
            kp * i_m, ch.apparent_inertia, ch.natural_frequency, ch.damping_ratio, ch.decay_rate, ch.spectral_radius, ch.discrete_decay_rate
        );
        assert!(err <= 1e-6, "{err}: {:?} vs {roots:?}", ch.discrete_poles);
    }
}

/// The continuous characteristics against the roots of
/// `J s² + B_h s + K_h` (Durand–Kerner), with `J = I_l + N²/K_p`
/// recomputed, `ω_n² = s₁ s₂` and `2ζω_n = −(s₁ + s₂)`; and as `T → 0`
/// the sampled loop's two slow poles tend to `e^{sT}`, so its decay
/// rate tends to the continuous one (within 1 % at `T = 1 µs`).
#[test]
fn continuous_characteristics_match_the_characteristic_roots() {
    for (kp, kh, bh, il) in [
        (2000.0, 200.0, 5.0, 0.05),
        (5000.0, 50.0, 40.0, 0.01),
        (1e4, 1000.0, 1.0, 0.0),
    ] {
        let p = frictionless(1.14e-5, kp, 100.0);
        let hand = HandContact {
            stiffness: kh,
            damping: bh,
            link_inertia: il,
        };
        let ch = p.characteristics(&hand, 1e-6).unwrap();
        let j = il + 1e4 / kp;
        assert!((ch.apparent_inertia - j).abs() <= 1e-12 * j);
        let roots = durand_kerner(&[bh / j, kh / j]);
        let err = match_roots(&ch.continuous_poles, &roots);
        let mag = roots
            .iter()
            .map(|r| libm::hypot(r.0, r.1))
            .fold(0.0, f64::max);
        assert!(err <= 1e-9 * mag, "{err}");
        let (s1, s2) = (roots[0], roots[1]);
        let prod = s1.0 * s2.0 - s1.1 * s2.1;
        assert!((ch.natural_frequency.powi(2) - prod).abs() <= 1e-9 * prod);
        let sum = -(s1.0 + s2.0);
        assert!((2.0 * ch.damping_ratio * ch.natural_frequency - sum).abs() <= 1e-9 * sum);
        let slowest = roots.iter().map(|r| -r.0).fold(f64::INFINITY, f64::min);
        assert!((ch.decay_rate - slowest).abs() <= 1e-9 * slowest);
        assert!(
            (ch.discrete_decay_rate - ch.decay_rate).abs() <= 0.01 * ch.decay_rate,
            "{} vs {}",
            ch.discrete_decay_rate,
            ch.decay_rate
        );
    }
    let p = frictionless(1.14e-5, 2000.0, 100.0);
    let bad = HandContact {
        stiffness: -1.0,
        damping: 0.0,
        link_inertia: 0.0,
    };
    assert!(matches!(
        p.characteristics(&bad, 1e-3),
        Err(ParamError::Negative {
            name: "stiffness",
            ..
        })
    ));
    let free = HandContact {
        stiffness: 0.0,
        damping: 0.0,
        link_inertia: 0.0,
    };
    assert!(matches!(
        p.characteristics(&free, 0.0),
        Err(ParamError::NotPositive {
            name: "sample_period",
            ..
        })
    ));
    assert!(matches!(
        frictionless(1.14e-5, 0.0, 100.0).characteristics(&free, 1e-3),
        Err(ParamError::NotPositive { name: "gain", .. })
    ));
}

/// The sampled torque loop's pole `(1 − Î_m K_p) I_l/J₀` limits the
/// gain whatever the period: on the thesis joint with its bare link
/// (`I_l = 0.64·0.45²/3 = 0.0432 kg·m²`, `J₀ = I_l + N² I_m = 0.1572`)
/// the loop is unstable for `Î_m K_p > 1 + J₀/I_l = 4.64`, at 1 ms and
/// at 10 µs alike (hand 200 N·m/rad, 5 N·m·s/rad).
#[test]
fn sampled_torque_loop_limits_the_gain() {
    let il = 0.64 * 0.45 * 0.45 / 3.0;
    let j0 = il + 1e4 * 1.14e-5;
    let limit = 1.0 + j0 / il;
    assert!((limit - 4.64).abs() < 0.01, "{limit}");
    let hand = HandContact {
        stiffness: 200.0,
        damping: 5.0,
        link_inertia: il,
    };
    for t in [1e-3, 1e-5] {
        for (c, stable) in [(0.95 * limit, true), (1.05 * limit, false)] {
            let ch = frictionless(1.14e-5, c / 1.14e-5, 100.0)
                .characteristics(&hand, t)
                .unwrap();
            assert_eq!(ch.spectral_radius < 1.0, stable, "c = {c}, T = {t}: {ch:?}");
        }
    }
}

struct RobustFriction;
impl RobustFriction {
    fn nominal() -> FrictionParams {
        super::super::RobustAdaptiveDesign::table_4_1().initial_friction
    }
}

proptest! {
    /// Output bounded and NaN-free; backends agree with f64 on the same
    /// (quantized) inputs: I16F16 within 4 LSB of mN·m per stored
    /// product (friction ≤ 8 products, feedback 2) plus the exp kernel
    /// on `f_s` (≤ 2 LSB relative to f_s = 6 mN·m); f32 within
    /// 16 ulp of the largest term.
    #[test]
    fn bounded_and_backends_agree(qd in -100.0f64..100.0, tau in -30.0f64..30.0, kp in 0.0f64..5000.0) {
        let p = params(kp);
        let c64 = PassiveConfig::<f64>::new(&p);
        let cx = PassiveConfig::<I16F16>::new(&p);
        let c32 = PassiveConfig::<f32>::new(&p);
        let xq = ControlInput { motor_velocity: I16F16::from_f64(qd), joint_torque: I16F16::from_f64(tau), ..Default::default() };
        let x64 = ControlInput { motor_velocity: xq.motor_velocity.to_f64(), joint_torque: xq.joint_torque.to_f64(), ..Default::default() };
        let x32 = ControlInput { motor_velocity: qd as f32, joint_torque: tau as f32, ..Default::default() };
        let a = c64.update(&x64);
        let b = cx.update(&xq);
        let c = c32.update(&x32);
        prop_assert!(b.torque.abs() <= cx.torque_limit() && c.torque.abs() <= c32.torque_limit());
        let lsb = 1.0 / 65536.0;
        // Rounding of the products, plus, inside the velocity layer, the
        // quantized layer width: I16F16 stores `ε` to the nearest code
        // (0.01 → 655/65536) and scales by its exact reciprocal so the
        // layer meets ±1 continuously, which moves `sat(q̇/ε)` by the
        // relative width error times `|q̇/ε|` (weighted by the Coulomb
        // and Stribeck levels, stored mN·m).
        let (e64, ex) = (c64.friction.eps_velocity(), cx.friction.eps_velocity().to_f64());
        let layer = (x64.motor_velocity / e64).abs().min(1.0) * (1.0 - e64 / ex).abs();
        let levels = cx.nominal[1].to_f64().abs() + cx.nominal[2].to_f64().abs();
        let tol_x = (4.0 * 10.0 * lsb + 6.0 * 2.0 * lsb + levels * layer) / 1e3;
        prop_assert!((b.torque.to_f64() / 1e3 - a.torque).abs() <= tol_x, "{} vs {}", b.torque, a.torque);
        let a32 = c64.update(&ControlInput { motor_velocity: x32.motor_velocity as f64, joint_torque: x32.joint_torque as f64, ..Default::default() });
        let big = a32.law_torque.abs() + (tau / 100.0).abs() * (1.0 + 1.14e-5 * kp) + 0.03;
        prop_assert!((c.torque as f64 - a32.torque).abs() <= 16.0 * f32::EPSILON as f64 * big);
    }
}

/// A valid setting to move one field of at a time (every check passes
/// with room: `Î_m K_p/N = 0.5`).
fn settings() -> PassiveSettings {
    PassiveSettings {
        rotor_inertia: 0.5,
        gain: 2.0,
        ratio: 2.0,
        eps_velocity: 0.01,
        nominal_friction: RobustFriction::nominal(),
        torque_limit: 1.0,
    }
}

/// Every validated range of `try_new` at its documented edge: the edge
/// accepted, the next `f64` beyond it rejected with the field's name.
#[test]
fn try_new_ranges_at_their_edges() {
    let ok = |s: PassiveSettings| PassiveParams::try_new(s).map(|p| p.settings() == s);
    let name = |s: PassiveSettings| PassiveParams::try_new(s).unwrap_err().name();
    let s = settings();
    // Î_m > 0.
    assert_eq!(
        ok(PassiveSettings {
            rotor_inertia: 1e-300,
            ..s
        }),
        Ok(true)
    );
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings {
            rotor_inertia: 0.0,
            ..s
        }),
        Err(ParamError::NotPositive {
            name: "rotor_inertia",
            ..
        })
    ));
    // K_p ≥ 0, finite.
    assert_eq!(ok(PassiveSettings { gain: 0.0, ..s }), Ok(true));
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings { gain: -1e-300, ..s }),
        Err(ParamError::Negative { name: "gain", .. })
    ));
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings {
            gain: f64::NAN,
            ..s
        }),
        Err(ParamError::NotFinite { name: "gain", .. })
    ));
    // N ≥ 1.
    assert_eq!(ok(PassiveSettings { ratio: 1.0, ..s }), Ok(true));
    assert_eq!(
        name(PassiveSettings {
            ratio: 1.0f64.next_down(),
            ..s
        }),
        "ratio"
    );
    // ε_q̇ ≥ 2⁻¹⁶.
    let eps = 1.0 / 65536.0;
    assert_eq!(
        ok(PassiveSettings {
            eps_velocity: eps,
            ..s
        }),
        Ok(true)
    );
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings { eps_velocity: eps.next_down(), ..s }),
        Err(ParamError::OutOfRange { name: "eps_velocity", min, .. }) if min == eps
    ));
    assert_eq!(
        name(PassiveSettings {
            eps_velocity: 0.0,
            ..s
        }),
        "eps_velocity"
    );
    // The limit in (0, 16].
    assert_eq!(
        ok(PassiveSettings {
            torque_limit: 16.0,
            ..s
        }),
        Ok(true)
    );
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings { torque_limit: 16.0f64.next_up(), ..s }),
        Err(ParamError::OutOfRange { name: "torque_limit", max, .. }) if max == 16.0
    ));
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings {
            torque_limit: 0.0,
            ..s
        }),
        Err(ParamError::NotPositive {
            name: "torque_limit",
            ..
        })
    ));
    // Î_m K_p / N ≤ 10⁶: with Î_m = 0.5 and N = 2 the largest gain is
    // 4·10⁶ (0.5·4e6/2 = 1e6 exactly, every operation exact).
    assert_eq!(ok(PassiveSettings { gain: 4e6, ..s }), Ok(true));
    assert!(matches!(
        PassiveParams::try_new(PassiveSettings { gain: 4e6f64.next_up(), ..s }),
        Err(ParamError::OutOfRange { name: "gain", max, .. }) if max == 4e6
    ));
    // The nominal friction is validated under its own path.
    let mut f = s.nominal_friction;
    f.coulomb = -1e-3;
    assert_eq!(
        name(PassiveSettings {
            nominal_friction: f,
            ..s
        }),
        "nominal_friction.coulomb"
    );
    // K_p = 0 has no finite apparent inertia.
    let free = PassiveParams::try_new(PassiveSettings { gain: 0.0, ..s }).unwrap();
    assert_eq!(free.apparent_motor_inertia(), f64::INFINITY);
}

/// `characteristics`' inputs at their edges and the two degenerate hands
/// (no stiffness): a damper alone leaves one pole at 0 (decay 0, `ζ = ∞`),
/// nothing at all leaves the joint free (`ω_n = ζ = 0`).
#[test]
fn characteristics_edges_and_degenerate_hands() {
    let p = frictionless(1.14e-5, 2000.0, 100.0);
    let j = 1e4 / 2000.0 + 0.05;
    let damper = HandContact {
        stiffness: 0.0,
        damping: 2.0,
        link_inertia: 0.05,
    };
    let ch = p.characteristics(&damper, 1.0).unwrap();
    assert_eq!(ch.natural_frequency, 0.0);
    assert_eq!(ch.damping_ratio, f64::INFINITY);
    assert_eq!(ch.decay_rate, 0.0);
    let mut re = [ch.continuous_poles[0].re, ch.continuous_poles[1].re];
    re.sort_by(f64::total_cmp);
    assert!(
        (re[0] + 2.0 / j).abs() <= 1e-12 / j && re[1] == 0.0,
        "{re:?}"
    );
    assert!(ch.continuous_poles.iter().all(|p| p.im == 0.0));
    let free = HandContact {
        damping: 0.0,
        ..damper
    };
    let ch = p.characteristics(&free, 1e-3).unwrap();
    assert_eq!((ch.natural_frequency, ch.damping_ratio), (0.0, 0.0));
    assert_eq!(ch.decay_rate, 0.0);
    // A free joint keeps its position and speed: a double discrete pole
    // at 1, which rounding splits by about √ε (1e-8).
    assert!((ch.spectral_radius - 1.0).abs() < 1e-7, "{ch:?}");
    // T in (0, 1] s.
    assert!(matches!(
        p.characteristics(&free, 1.0f64.next_up()),
        Err(ParamError::OutOfRange { name: "sample_period", max, .. }) if max == 1.0
    ));
    for (hand, field) in [
        (
            HandContact {
                damping: -1e-300,
                ..free
            },
            "damping",
        ),
        (
            HandContact {
                link_inertia: -1e-300,
                ..free
            },
            "link_inertia",
        ),
        (
            HandContact {
                stiffness: f64::NAN,
                ..free
            },
            "stiffness",
        ),
    ] {
        assert_eq!(p.characteristics(&hand, 1e-3).unwrap_err().name(), field);
    }
}

/// The eigenvalues of 3×3 matrices with known spectra: a triangular one
/// (its diagonal), real roots of either sign (both branches of the
/// cancellation-free quadratic formula) and a rotation block (a complex
/// pair `a ± ib`).
#[test]
fn eigenvalues3_of_known_spectra() {
    let sorted = |p: [Pole; 3]| {
        let mut v: std::vec::Vec<(f64, f64)> = p.iter().map(|p| (p.re, p.im)).collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        v
    };
    let close = |got: std::vec::Vec<(f64, f64)>, want: [(f64, f64); 3]| {
        for (g, w) in got.iter().zip(want.iter()) {
            assert!(
                (g.0 - w.0).abs() < 1e-9 && (g.1 - w.1).abs() < 1e-9,
                "{got:?} vs {want:?}"
            );
        }
    };
    let tri = [[0.5, 3.0, -1.0], [0.0, -0.25, 2.0], [0.0, 0.0, 0.9]];
    close(
        sorted(eigenvalues3(&tri)),
        [(-0.25, 0.0), (0.5, 0.0), (0.9, 0.0)],
    );
    let neg = [[-0.7, 1.0, 0.0], [0.0, -0.2, 0.0], [0.0, 0.0, 0.4]];
    close(
        sorted(eigenvalues3(&neg)),
        [(-0.7, 0.0), (-0.2, 0.0), (0.4, 0.0)],
    );
    let pos = [[0.7, 0.0, 0.0], [1.0, 0.2, 0.0], [0.0, 5.0, -0.4]];
    close(
        sorted(eigenvalues3(&pos)),
        [(-0.4, 0.0), (0.2, 0.0), (0.7, 0.0)],
    );
    let rot = [[0.3, -0.4, 0.0], [0.4, 0.3, 0.0], [0.0, 0.0, -0.6]];
    close(
        sorted(eigenvalues3(&rot)),
        [(-0.6, 0.0), (0.3, -0.4), (0.3, 0.4)],
    );
    // e^A of a diagonal and of a nilpotent matrix, by hand.
    // (Norm 5: 20 Taylor terms need the scaling and squaring here.)
    let e = expm3([[5.0, 0.0, 0.0], [0.0, -3.0, 0.0], [0.0, 0.0, 0.0]]);
    let want = [
        [5f64.exp(), 0.0, 0.0],
        [0.0, (-3f64).exp(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let n = expm3([[0.0, 3.0, 0.0], [0.0, 0.0, 2.0], [0.0, 0.0, 0.0]]);
    // I + N + N²/2 with N² = [[0, 0, 6], 0, 0].
    let want_n = [[1.0, 3.0, 3.0], [0.0, 1.0, 2.0], [0.0, 0.0, 1.0]];
    for r in 0..3 {
        for c in 0..3 {
            assert!((e[r][c] - want[r][c]).abs() <= 1e-14 * want[r][c].abs().max(1.0));
            assert!((n[r][c] - want_n[r][c]).abs() <= 1e-14 * want_n[r][c].abs().max(1.0));
        }
    }
}

/// The output flags on every backend: a law inside the limit is returned
/// unflagged, one beyond it is clamped to `±limit` and flagged saturated,
/// and a non-finite input gives 0 with both flags. The configured
/// nominal friction and limit read back in stored units (mN·m on I16F16).
#[test]
fn output_flags_and_stored_settings_on_every_backend() {
    fn check<S: Scalar + core::fmt::Debug>(nan: Option<S>) {
        let p = params(2000.0);
        let cfg = PassiveConfig::<S>::new(&p);
        let mt = S::UNITS.motor_torque;
        assert_eq!(cfg.torque_limit(), S::from_f64(0.188 * mt));
        assert_eq!(
            cfg.nominal_friction(),
            FrictionConfig::<S>::quantize(&p.nominal_friction())
        );
        let input = |tau: f64| ControlInput {
            joint_torque: S::from_f64(tau),
            ..Default::default()
        };
        // At rest: τ_m = τ̂_t/N (1 − Î_m K_p) = 0.977 τ̂_t/100 N·m.
        let small = cfg.update(&input(1.0));
        assert!(!small.saturated && !small.invalid_input);
        assert_eq!(small.torque, small.law_torque);
        let want = 0.977 / 100.0 * mt;
        assert!((small.torque.to_f64() - want).abs() <= 1e-3 * want);
        for (tau, sign) in [(30.0, 1.0), (-30.0, -1.0)] {
            let out = cfg.update(&input(tau));
            assert!(out.saturated && !out.invalid_input, "{out:?}");
            assert_eq!(out.torque.to_f64(), sign * cfg.torque_limit().to_f64());
            assert!(out.law_torque.to_f64().abs() > cfg.torque_limit().to_f64());
        }
        if let Some(nan) = nan {
            let bad = ControlInput {
                joint_torque: nan,
                ..Default::default()
            };
            let out = cfg.update(&bad);
            assert_eq!(out.torque, S::ZERO);
            assert_eq!(out.law_torque, S::ZERO);
            assert!(out.saturated && out.invalid_input);
            // A non-finite desired torque alone (the law is then ±∞, not
            // NaN) is an invalid input too.
            let wish = ControlInput {
                desired_joint_torque: nan,
                ..Default::default()
            };
            let out = cfg.update(&wish);
            assert_eq!(out.torque, S::ZERO);
            assert!(out.saturated && out.invalid_input, "{out:?}");
        }
    }
    check::<f64>(Some(f64::NAN));
    check::<f32>(Some(f32::INFINITY));
    check::<I16F16>(None);
}

/// An underdamped hand gives a conjugate pair, by hand: `J = 0.05 +
/// 100²/2000 = 5.05`, `s = (−5 ± i√(4·5.05·200 − 25))/(2·5.05)`; an
/// overdamped one two distinct real poles `(−B ± √(B² − 4JK))/(2J)`.
#[test]
fn continuous_poles_by_hand() {
    let p = frictionless(1.14e-5, 2000.0, 100.0);
    let j: f64 = 5.05;
    let hand = HandContact {
        stiffness: 200.0,
        damping: 5.0,
        link_inertia: 0.05,
    };
    let [a, b] = p.characteristics(&hand, 1e-3).unwrap().continuous_poles;
    let (re, im) = (
        -5.0 / (2.0 * j),
        (4.0 * j * 200.0 - 25.0).sqrt() / (2.0 * j),
    );
    assert!((a.re - re).abs() < 1e-12 && (b.re - re).abs() < 1e-12);
    assert!(
        (a.im - im).abs() < 1e-12 && (b.im + im).abs() < 1e-12,
        "{a:?} {b:?}"
    );
    let stiff = HandContact {
        damping: 100.0,
        ..hand
    };
    let [a, b] = p.characteristics(&stiff, 1e-3).unwrap().continuous_poles;
    let r = (100.0f64 * 100.0 - 4.0 * j * 200.0).sqrt();
    assert!((a.re - (-100.0 + r) / (2.0 * j)).abs() < 1e-12, "{a:?}");
    assert!((b.re - (-100.0 - r) / (2.0 * j)).abs() < 1e-12, "{b:?}");
    assert_eq!((a.im, b.im), (0.0, 0.0));
}
