//! The adapted state of the active law (§4.2, eq. 4.19 and Theorem 1) read
//! in SI: the same physical value on every backend, and no way to build a
//! state that holds NaN or leaves the projection box.

use mrr_control::control::{
    ControlInput, RobustAdaptiveConfig, RobustAdaptiveParams, RobustAdaptiveState,
};
use mrr_control::friction::FrictionParams;
use mrr_control::{JointConfig, JointParams, JointReadings, JointTarget, ParamError};
use mrr_control::{Scalar, I16F16};

fn table() -> RobustAdaptiveParams {
    RobustAdaptiveParams::table_4_1().unwrap()
}

/// One step of Table 4.1's law from its initial state, the motor at the
/// reference position, turning at `q̇ = 0.5` rad/s while the reference
/// turns at `0.55` rad/s: `e = 0`, `ė = −0.05`, `r = −0.05` rad/s.
fn one_step<S: Scalar>() -> RobustAdaptiveState<S> {
    let cfg = RobustAdaptiveConfig::<S>::new(&table());
    let mut st = cfg.initial_state();
    let x = ControlInput::<f64> {
        desired_velocity: 0.55,
        motor_velocity: 0.5,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &ControlInput::<S>::from_si(&x));
    assert!(!o.invalid_input && !o.saturated, "{o:?}");
    st
}

/// The state after [`one_step`], computed by hand from Table 4.1
/// (`K_I = 10`, `T = 4 ms`, `μ = 0.1`, `ε_q̇ = 0.01`, `F̂(0) = [5e-5,
/// 0.006, 0.006, 1]`), returned as `[b̂, f̂_c, f̂_s, z]` in SI:
/// `z = K_I T r`, `F̂_j ← F̂_j − μ T r Y_j` with `Y_1 = q̇`,
/// `Y_2 = sat(q̇/ε_q̇) = 1`, `Y_3 = e^{−f̂_τ q̇²}·1` (eq. 4.17).
fn by_hand() -> [f64; 4] {
    let (k_i, t, mu, r, qd) = (10.0, 0.004, 0.1, -0.05, 0.5_f64);
    let f_tau = 1.0;
    let y = [qd, 1.0, (-f_tau * qd * qd).exp()];
    [
        5e-5 - mu * t * r * y[0],
        0.006 - mu * t * r * y[1],
        0.006 - mu * t * r * y[2],
        k_i * t * r,
    ]
}

/// Check one backend: the SI readers against the hand computation within
/// `tol` (SI), and against the stored readers divided by the scales the
/// docs state (`torque` for N·m → stored motor torque, `torque/speed` for
/// `b̂`, `1/speed²` for `f̂_τ`), computed here.
fn check<S: Scalar>(torque: f64, speed: f64, tol: f64) -> FrictionParams {
    let st = one_step::<S>();
    let want = by_hand();
    let f = st.friction_si();
    let got = [f.viscous, f.coulomb, f.stribeck, st.integral_si()];
    for j in 0..4 {
        assert!(
            (got[j] - want[j]).abs() <= tol,
            "{}: component {j}: {} vs {} (tol {tol})",
            S::NAME,
            got[j],
            want[j]
        );
    }
    let stored = st.friction();
    let scales = [torque / speed, torque, torque, 1.0 / (speed * speed)];
    let si = f.to_array();
    for j in 0..4 {
        assert_eq!(stored[j].to_f64(), si[j] * scales[j], "{} F̂_{j}", S::NAME);
    }
    assert_eq!(
        st.integral().to_f64(),
        st.integral_si() * torque,
        "{} z",
        S::NAME
    );
    f
}

#[test]
fn si_readers_give_the_same_physical_state_on_every_backend() {
    // Stored units: SI on floats; mN·m and rad/s on I16F16.
    let f64s = check::<f64>(1.0, 1.0, 1e-12);
    let f32s = check::<f32>(1.0, 1.0, 1e-8);
    // I16F16: the inputs 0.55 and 0.5 rad/s quantize within 2⁻¹⁷ rad/s,
    // which moves z by at most K_I T 2⁻¹⁷ = 3e-7 N·m; one LSB of mN·m is
    // 1.5e-8 N·m.
    let fxs = check::<I16F16>(1e3, 1.0, 1e-6);
    // The Stribeck shape has no hand value here (its regressor is the
    // product of three small terms); it must agree across backends.
    let shape = |f: FrictionParams| f.stribeck_shape;
    assert!(
        (shape(f32s) - shape(f64s)).abs() < 1e-6,
        "{f32s:?} {f64s:?}"
    );
    // Stored in s²/rad² on I16F16, LSB 2⁻¹⁶.
    assert!(
        (shape(fxs) - shape(f64s)).abs() < 2.0 / 65536.0,
        "{fxs:?} {f64s:?}"
    );
}

fn friction(v: [f64; 4]) -> FrictionParams {
    FrictionParams::from_array(v)
}

fn names<S: Scalar>(f: [f64; 4], z: f64) -> Result<RobustAdaptiveState<S>, ParamError> {
    RobustAdaptiveConfig::<S>::new(&table()).state(friction(f), z)
}

fn field(e: ParamError) -> &'static str {
    match e {
        ParamError::NotFinite { name, .. } | ParamError::OutOfRange { name, .. } => name,
        other => panic!("unexpected error {other:?}"),
    }
}

fn refuses_every_bad_state<S: Scalar>() {
    let good = [5e-5, 0.006, 0.006, 1.0];
    let fields = [
        "friction.viscous",
        "friction.coulomb",
        "friction.stribeck",
        "friction.stribeck_shape",
    ];
    for j in 0..4 {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, 1e3] {
            let mut f = good;
            f[j] = bad;
            let e = names::<S>(f, 0.0).expect_err("bad estimate accepted");
            assert_eq!(field(e), fields[j], "{} {f:?}", S::NAME);
            if bad.is_finite() {
                assert!(matches!(e, ParamError::OutOfRange { .. }), "{e:?}");
            }
        }
    }
    // The integral limit of Table 4.1 is 0.1 N·m.
    for z in [f64::NAN, f64::INFINITY, 0.1000001, -0.11] {
        let e = names::<S>(good, z).expect_err("bad integral accepted");
        assert_eq!(field(e), "integral", "{} {z}", S::NAME);
    }
    // The box corners and the limit are accepted and read back.
    let cfg = RobustAdaptiveConfig::<S>::new(&table());
    let st = cfg.state(friction([1e-4, 0.0, 0.012, 10.0]), -0.1).unwrap();
    let (lo, hi) = (cfg.lower_bounds(), cfg.upper_bounds());
    assert_eq!(st.friction(), [hi[0], lo[1], hi[2], hi[3]], "{}", S::NAME);
    assert_eq!(st.integral(), cfg.integral_limit().neg());
}

#[test]
fn a_state_from_the_public_api_is_finite_and_in_the_box() {
    refuses_every_bad_state::<f64>();
    refuses_every_bad_state::<f32>();
    refuses_every_bad_state::<I16F16>();
}

#[test]
fn joint_state_readers_in_si() {
    let p = JointParams::table_4_1_at(0.004).unwrap();
    let cfg = JointConfig::<I16F16>::new(&p);
    let mut st = cfg.state(0, 0);
    let target = JointTarget::from_si(0.01, 0.0, 0.0);
    let mut out = None;
    for k in 0..20u32 {
        out = Some(cfg.update(&mut st, &JointReadings::counts(0, k), &target));
    }
    let out = out.unwrap();
    assert_eq!(st.last_command_si(), out.motor_torque_si());
    assert_eq!(st.last_command().to_f64(), st.last_command_si() * 1e3);
    assert_ne!(st.last_command_si(), 0.0);
    let a = st.active_state();
    assert_eq!(a, st.mode_state().active_state());
    assert_eq!(a.integral().to_f64(), a.integral_si() * 1e3);
    assert!(a.integral_si().abs() <= 0.1, "{}", a.integral_si());
    let m = st.mode_state();
    assert_eq!(m.bias().to_f64(), m.bias_si() * 1e3);
    let (o, od) = m.rejoin_offset();
    assert_eq!((o.to_f64(), od.to_f64()), m.rejoin_offset_si());
}

/// The flags of the joint's output keep the meaning of the `joint` module
/// docs ("Status flags"): a NaN target is an invalid sample (torque 0,
/// `control.saturated` set, `torque_saturated()` not), a far target is a
/// valid law value limited to the torque limit (`torque_saturated()`).
#[test]
fn joint_flags_separate_invalid_samples_from_the_limit() {
    let p = JointParams::table_4_1_at(0.004).unwrap();
    fn run<S: Scalar>(p: &JointParams) {
        let cfg = JointConfig::<S>::new(p);
        let limit = cfg.mode().torque_limit().to_f64() / S::UNITS.motor_torque;
        let mut st = cfg.state(0, 0);
        let before = *st.active_state();
        // `from_si` keeps a NaN on floats (I16F16 cannot hold one).
        let nan = JointTarget::<S>::from_si(f64::NAN, 0.0, 0.0);
        if S::NAME != "I16F16" {
            let o = cfg.update(&mut st, &JointReadings::counts(0, 0), &nan);
            assert!(o.invalid_input && o.control.invalid_input, "{o:?}");
            assert!(o.control.saturated && !o.torque_saturated(), "{o:?}");
            assert_eq!(o.motor_torque_si(), 0.0);
            assert_eq!(*st.active_state(), before);
        }
        // One rad ahead on the link (100 rad at the motor), the joint held
        // at 0: once the rejoin offset has decayed, far beyond the limit.
        let far = JointTarget::from_si(1.0, 0.0, 0.0);
        let mut limited = 0;
        for _ in 0..500 {
            let o = cfg.update(&mut st, &JointReadings::counts(0, 0), &far);
            assert!(!o.invalid_input, "{} {o:?}", S::NAME);
            assert_eq!(o.torque_saturated(), o.control.saturated);
            if o.torque_saturated() {
                assert!(
                    (o.motor_torque_si() - limit).abs() < 1e-6,
                    "{} {o:?}",
                    S::NAME
                );
                limited += 1;
            }
        }
        assert!(limited > 0, "{}", S::NAME);
    }
    run::<f64>(&p);
    run::<f32>(&p);
    run::<I16F16>(&p);
}

/// The wrist's adapted state is read per motor through `motors()` (its
/// field is private) and gives the same SI values on every backend: at the
/// start, Table 6.1's initial friction estimate of each motor.
#[test]
fn wrist_state_reads_in_si_on_every_backend() {
    use mrr_control::wrist::active::{WristActiveConfig, WristActiveParams};
    let p = WristActiveParams::table_6_1().unwrap();
    let a = WristActiveConfig::<f64>::new(&p).initial_state();
    let b = WristActiveConfig::<I16F16>::new(&p).initial_state();
    for i in 0..2 {
        let fa = a.motors()[i].friction_si();
        let fb = b.motors()[i].friction_si();
        let want = p.laws()[i].design().initial_friction;
        for (x, y, w) in [
            (fa.viscous, fb.viscous, want.viscous),
            (fa.coulomb, fb.coulomb, want.coulomb),
            (fa.stribeck, fb.stribeck, want.stribeck),
        ] {
            assert!((x - w).abs() <= 1e-12 * w.abs(), "motor {i}: {x} vs {w}");
            assert!(
                (y - w).abs() <= 2e-5 + 1e-3 * w.abs(),
                "motor {i}: {y} vs {w}"
            );
        }
        assert_eq!(a.motors()[i].integral_si(), 0.0);
        assert_eq!(b.motors()[i].integral_si(), 0.0);
    }
}
