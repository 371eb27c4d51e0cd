//! Every public `*_si` reader on every backend (`f64`, `f32`, `I16F16`),
//! checked two ways:
//!
//! 1. **Conversion.** The reader equals the stored field times the stored
//!    unit, both computed here without the crate's unit tables: a float
//!    stores plain SI; an `I16F16` stores `bits · 2^-FRAC_NBITS` of its
//!    documented unit (mN·m for motor torque and mrad for torsion, N·m,
//!    rad and rad/s otherwise; `src/scalar/units.rs`). Every value
//!    checked is made to be none of `0`, `1`, `−1`, so a reader replaced
//!    by a constant fails, as does one scaled by a wrong unit.
//! 2. **Physics.** The same inputs on `f32` and `I16F16` give readings
//!    within the documented agreement of the `f64` reading, so a stored
//!    field that is right in its unit but read in the wrong one (a factor
//!    1000 on `I16F16`) fails too.

use mrr_control::control::{
    ControlInput, ModeOutput, PassiveConfig, PassiveParams, RobustAdaptiveConfig,
    RobustAdaptiveParams,
};
use mrr_control::estimation::torque::{AgreementBound, TorqueEstimate};
use mrr_control::joint::{JointConfig, JointOutput, JointParams, JointReadings, JointTarget};
use mrr_control::scalar::q15::{self, FullScale};
use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::wrist::step::{
    WristOutput, WristReadings, WristStepConfig, WristStepParams, WristTarget,
};
use mrr_control::wrist::{MotorAngles, PitchYaw, WristConfig, WristParams};

/// The physical quantity a field holds, for its stored unit.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Q {
    LinkTorque,
    MotorTorque,
    Torsion,
    Angle,
    Speed,
}

/// A backend's stored number read independently of the crate.
trait Stored: Scalar {
    /// The stored number (in its stored unit) as `f64`, exactly.
    fn stored(self) -> f64;
    /// SI per stored unit of `q` (the documented unit table).
    fn unit(q: Q) -> f64;
}

impl Stored for f64 {
    fn stored(self) -> f64 {
        self
    }
    fn unit(_: Q) -> f64 {
        1.0
    }
}

impl Stored for f32 {
    fn stored(self) -> f64 {
        self as f64
    }
    fn unit(_: Q) -> f64 {
        1.0
    }
}

impl Stored for I16F16 {
    fn stored(self) -> f64 {
        self.to_bits() as f64 * libm::exp2(-(I16F16::FRAC_NBITS as f64))
    }
    fn unit(q: Q) -> f64 {
        match q {
            Q::MotorTorque | Q::Torsion => 1e-3,
            Q::LinkTorque | Q::Angle | Q::Speed => 1.0,
        }
    }
}

/// The reader `got` of field `name` equals the stored value times its
/// unit, and that value is not a constant a mutated reader could return.
fn conv<S: Stored>(name: &str, got: f64, stored: S, q: Q) -> f64 {
    let want = stored.stored() * S::unit(q);
    for c in [0.0, 1.0, -1.0] {
        assert!(
            (want - c).abs() > 1e-7,
            "{} {name}: the scenario gives the trivial value {want}",
            S::NAME
        );
    }
    assert!(
        (got - want).abs() <= 1e-12 * want.abs(),
        "{} {name}: reader {got}, stored × unit {want}",
        S::NAME
    );
    got
}

/// `|b − a| ≤ tol`, named.
fn near(name: &str, backend: &str, a: f64, b: f64, tol: f64) {
    assert!(
        (b - a).abs() <= tol,
        "{backend} {name}: {b} vs f64 {a} (tolerance {tol:e})"
    );
}

// ---------------------------------------------------------------- joint

/// The Table 4.1 joint at rest at link count 0, then one tick on which the
/// motor counter jumped 10 counts ahead (a torsion of 10·2π/(2000·100) rad,
/// a motor speed of 10·2π/(2000·4 ms) = 7.85 rad/s) while the target asks
/// for 0.5 rad (the active law saturates at its ±0.188 N·m limit).
/// Returns the readers of the output, of [`JointConfig::measure`] on the
/// same tick, and of the estimate and the mode output.
fn joint<S: Stored>() -> [f64; 14] {
    let p = JointParams::table_4_1().unwrap();
    let cfg = JointConfig::<S>::new(&p);
    let readings = JointReadings {
        link_count: 0,
        motor_counter: 10,
        motor_torque: Some(S::from_f64(0.05 * S::UNITS.motor_torque)),
    };
    let target = JointTarget::<S>::from_si(0.5, 0.0, 0.0);
    let mut st = cfg.state_at(0, 0);
    let out: JointOutput<S> = cfg.update(&mut st, &readings, &target);
    assert!(out.control.saturated && !out.invalid_input, "{out:?}");
    let mut st = cfg.state_at(0, 0);
    let m = cfg.measure(&mut st, &readings);
    let e: TorqueEstimate<S> = out.estimate;
    let c: ModeOutput<S> = out.control;
    [
        conv(
            "JointOutput::motor_torque_si",
            out.motor_torque_si(),
            out.motor_torque,
            Q::MotorTorque,
        ),
        conv(
            "JointOutput::joint_torque_si",
            out.joint_torque_si(),
            out.joint_torque,
            Q::LinkTorque,
        ),
        conv(
            "JointOutput::motor_position_si",
            out.motor_position_si(),
            out.motor_position,
            Q::Angle,
        ),
        conv(
            "JointOutput::motor_velocity_si",
            out.motor_velocity_si(),
            out.motor_velocity,
            Q::Speed,
        ),
        conv(
            "JointMeasurement::joint_torque_si",
            m.joint_torque_si(),
            m.joint_torque,
            Q::LinkTorque,
        ),
        conv(
            "JointMeasurement::motor_position_si",
            m.motor_position_si(),
            m.motor_position,
            Q::Angle,
        ),
        conv(
            "JointMeasurement::motor_velocity_si",
            m.motor_velocity_si(),
            m.motor_velocity,
            Q::Speed,
        ),
        conv(
            "TorqueEstimate::torque_si",
            e.torque_si(),
            e.torque,
            Q::LinkTorque,
        ),
        conv(
            "TorqueEstimate::torsion_si",
            e.torsion_si(),
            e.torsion,
            Q::Torsion,
        ),
        conv(
            "TorqueEstimate::flexspline_torsion_si",
            e.flexspline_torsion_si(),
            e.flexspline_torsion,
            Q::Torsion,
        ),
        conv(
            "ModeOutput::torque_si",
            c.torque_si(),
            c.torque,
            Q::MotorTorque,
        ),
        conv(
            "ModeOutput::interaction_si",
            c.interaction_si(),
            c.interaction,
            Q::LinkTorque,
        ),
        conv(
            "ModeOutput::reference_position_si",
            c.reference_position_si(),
            c.reference_position,
            Q::Angle,
        ),
        conv(
            "ModeConfig::torque_limit_si",
            cfg.mode().torque_limit_si(),
            cfg.mode().torque_limit(),
            Q::MotorTorque,
        ),
    ]
}

#[test]
fn joint_readers_are_the_stored_value_in_si_and_agree_across_backends() {
    let a = joint::<f64>();
    // Independent physics of the tick, in f64 (module docs of `joint`):
    // q_m = 10·2π/2000 rad, q̇_m = q_m/T, and the command at the
    // +0.188 N·m limit of Table 4.1 (the link is 0.5 rad behind).
    let qm = 10.0 * core::f64::consts::TAU / 2000.0;
    assert!((a[2] - qm).abs() < 1e-12 && (a[5] - qm).abs() < 1e-12);
    assert!((a[3] - qm / 0.004).abs() < 1e-9 && (a[6] - qm / 0.004).abs() < 1e-9);
    assert!((a[0] - 0.188).abs() < 1e-12, "{}", a[0]);
    assert!((a[13] - 0.188).abs() < 1e-12);
    // The estimate's torque is the negated joint torque (eq. 4.1 sign).
    assert!((a[7] + a[1]).abs() < 1e-12 && a[1] > 0.0);
    let p = JointParams::table_4_1().unwrap();
    let est = p.settings().estimator;
    let check = |b: [f64; 14], backend: &str, bound: AgreementBound, lsb: f64| {
        // Torque (estimator sign): the documented agreement interval at
        // the f64 flexspline torsion; the joint torque and the interaction
        // (nothing expected) are its negation.
        let (lo, hi) = bound.torque_interval(&est, a[9]);
        for (name, v) in [
            ("estimate", b[7]),
            ("joint torque", -b[1]),
            ("measured joint torque", -b[4]),
            ("interaction", -b[11]),
        ] {
            assert!(
                lo <= v && v <= hi,
                "{backend} {name} {v} not in [{lo}, {hi}]"
            );
        }
        near("flexspline torsion", backend, a[9], b[9], bound.torsion);
        near("torsion", backend, a[8], b[8], bound.torsion);
        // Counts times 2π/M, rounded once: one LSB (fixed) or relative.
        for i in [2, 3, 5, 6] {
            near(
                "motor position/speed",
                backend,
                a[i],
                b[i],
                lsb + 1e-6 * a[i].abs(),
            );
        }
        // The saturated command is the limit, quantized once.
        for i in [0, 10, 13] {
            near("motor torque", backend, a[i], b[i], 1e-6);
        }
        // The motor-side reference N·q_d = 50 rad, within one LSB.
        near("reference", backend, a[12], b[12], lsb + 1e-6 * a[12].abs());
    };
    check(joint::<f32>(), "f32", est.agreement_bound::<f32>(), 0.0);
    check(
        joint::<I16F16>(),
        "I16F16",
        est.agreement_bound::<I16F16>(),
        libm::exp2(-16.0),
    );
}

// ------------------------------------------------------------ control laws

/// The Table 4.1 active and passive laws on one sample whose error
/// saturates the active law (0.5 rad of motor error) and whose joint
/// torque (3 N·m against 1 N·m desired) drives the passive law.
fn laws<S: Stored>() -> [f64; 10] {
    let x = ControlInput::<S>::from_si(&ControlInput {
        desired_position: 0.7,
        desired_velocity: 0.3,
        desired_acceleration: 2.0,
        motor_position: 0.2,
        motor_velocity: -0.4,
        joint_torque: 3.0,
        desired_joint_torque: 1.0,
        expected_joint_torque: 0.25,
    });
    let si = x.to_si();
    let active = RobustAdaptiveConfig::<S>::new(&RobustAdaptiveParams::table_4_1().unwrap());
    let mut st = active.initial_state();
    let a = active.update(&mut st, &x);
    let passive = PassiveConfig::<S>::new(&PassiveParams::table_4_1_default().unwrap());
    let pa = passive.update(&x);
    [
        conv(
            "ControlInput::to_si desired_position",
            si.desired_position,
            x.desired_position,
            Q::Angle,
        ),
        conv(
            "ControlInput::to_si motor_velocity",
            si.motor_velocity,
            x.motor_velocity,
            Q::Speed,
        ),
        conv(
            "ControlInput::to_si joint_torque",
            si.joint_torque,
            x.joint_torque,
            Q::LinkTorque,
        ),
        conv(
            "ActiveOutput::torque_si",
            a.torque_si(),
            a.torque,
            Q::MotorTorque,
        ),
        conv(
            "ActiveOutput::law_torque_si",
            a.law_torque_si(),
            a.law_torque,
            Q::MotorTorque,
        ),
        conv(
            "ActiveOutput::tracking_error_si",
            a.tracking_error_si(),
            a.tracking_error,
            Q::Angle,
        ),
        conv(
            "RobustAdaptiveConfig::torque_limit_si",
            active.torque_limit_si(),
            active.torque_limit(),
            Q::MotorTorque,
        ),
        conv(
            "PassiveOutput::torque_si",
            pa.torque_si(),
            pa.torque,
            Q::MotorTorque,
        ),
        conv(
            "PassiveOutput::law_torque_si",
            pa.law_torque_si(),
            pa.law_torque,
            Q::MotorTorque,
        ),
        conv(
            "PassiveConfig::torque_limit_si",
            passive.torque_limit_si(),
            passive.torque_limit(),
            Q::MotorTorque,
        ),
    ]
}

#[test]
fn control_law_readers_are_the_stored_value_in_si_and_agree_across_backends() {
    let a = laws::<f64>();
    // Independent: the sample itself, the error e = q_m − q_m^d = −0.5
    // rad, the active limit 0.188 N·m of Table 4.1, saturated forward.
    assert_eq!([a[0], a[1], a[2]], [0.7, -0.4, 3.0]);
    assert!((a[5] + 0.5).abs() < 1e-12);
    assert!((a[6] - 0.188).abs() < 1e-12 && (a[3] - 0.188).abs() < 1e-12);
    for (b, backend, lsb) in [
        (laws::<f32>(), "f32", 0.0),
        (laws::<I16F16>(), "I16F16", libm::exp2(-16.0)),
    ] {
        // The sample: rounded once (half a step, or f32's relative 2⁻²⁴).
        for (x, y) in a[..3].iter().zip(&b[..3]) {
            near("sample", backend, *x, *y, lsb / 2.0 + 1e-7 * x.abs());
        }
        near("tracking error", backend, a[5], b[5], lsb + 1e-7);
        // Limits and the saturated command: the limit quantized once
        // (mN·m on I16F16: 2⁻¹⁶ mN·m).
        for i in [3, 6, 9] {
            near("limit", backend, a[i], b[i], 1e-7);
        }
        // Law values before the limit and the passive command: a few
        // products of the sample; 1e-3 relative covers the roundings of
        // both backends (the sample's own is 1e-5 relative at most).
        for i in [4, 7, 8] {
            near("law torque", backend, a[i], b[i], 1e-3 * a[i].abs() + 1e-6);
        }
    }
}

#[test]
fn q15_full_scale_reader_is_the_stored_fraction_times_the_full_scale() {
    let fs = FullScale::try_new("test", 0.75).unwrap();
    for v in [0.3, -0.61, 0.05] {
        let q = fs.quantize(v);
        // Q1.15: bits · 2⁻¹⁵ of the full scale.
        let want = q.to_bits() as f64 * libm::exp2(-15.0) * 0.75;
        assert!((fs.to_si(q) - want).abs() < 1e-15, "{v}");
        assert!((fs.to_si(q) - v).abs() <= 0.75 * libm::exp2(-16.0));
        assert_eq!(q15::to_f64(q) * 0.75, fs.to_si(q));
    }
}

// ---------------------------------------------------------------- wrist

/// The Table 6.1 wrist at rest at (0.2, −0.1) rad, then one tick with a
/// wrench `(F_x, F_y, F_z, τ_x, τ_y, τ_z) = (0, 0, 0, 1.5, −2, 0.7)` at
/// the sensor, the target moved to (0.21, −0.11) rad and the measured
/// motors 0.3 rad behind their references (both laws saturate).
fn wrist<S: Stored>() -> [[f64; 2]; 9] {
    let p = WristStepParams::table_6_1().unwrap();
    let cfg = WristStepConfig::<S>::new(&p);
    let pose = PitchYaw {
        delta: 0.2,
        gamma: -0.1,
    };
    let motors = WristConfig::<f64>::new(&WristParams::thesis())
        .inverse(pose)
        .motors;
    let mut st = cfg.state(MotorAngles {
        theta1: S::from_f64(motors.theta1),
        theta3: S::from_f64(motors.theta3),
    });
    let sg = p
        .settings()
        .sensor
        .decoupling()
        .gauge_signals(&[0.0, 0.0, 0.0, 1.5, -2.0, 0.7]);
    let r = WristReadings::<S>::from_si(sg, [motors.theta1 - 0.3, motors.theta3 + 0.3], [0.0; 2]);
    let out: WristOutput<S> = cfg.update(&mut st, &r, &WristTarget::from_si(0.21, -0.11, 0.0, 0.0));
    assert!(out.torque_saturated && !out.invalid_input, "{out:?}");
    let pair = |name: &str, got: [f64; 2], stored: [S; 2], q: Q| {
        [
            conv(name, got[0], stored[0], q),
            conv(name, got[1], stored[1], q),
        ]
    };
    let l = out.laws;
    [
        pair(
            "WristOutput::motor_torque_si",
            out.motor_torque_si(),
            out.motor_torque,
            Q::MotorTorque,
        ),
        pair(
            "WristOutput::interaction_si",
            out.interaction_si(),
            out.interaction,
            Q::LinkTorque,
        ),
        pair(
            "WristOutput::joint_torque_si",
            out.joint_torque_si(),
            out.joint_torque,
            Q::LinkTorque,
        ),
        pair(
            "WristOutput::reference_si",
            out.reference_si(),
            [out.reference.delta, out.reference.gamma],
            Q::Angle,
        ),
        pair(
            "WristOutput::motor_reference_si",
            out.motor_reference_si(),
            [out.motor_reference.theta1, out.motor_reference.theta3],
            Q::Angle,
        ),
        pair(
            "WristOutput::motor_reference_rate_si",
            out.motor_reference_rate_si(),
            out.motor_reference_rate,
            Q::Speed,
        ),
        pair(
            "ActiveOutput::torque_si",
            [l[0].torque_si(), l[1].torque_si()],
            [l[0].torque, l[1].torque],
            Q::MotorTorque,
        ),
        pair(
            "ActiveOutput::law_torque_si",
            [l[0].law_torque_si(), l[1].law_torque_si()],
            [l[0].law_torque, l[1].law_torque],
            Q::MotorTorque,
        ),
        pair(
            "ActiveOutput::tracking_error_si",
            [l[0].tracking_error_si(), l[1].tracking_error_si()],
            [l[0].tracking_error, l[1].tracking_error],
            Q::Angle,
        ),
    ]
}

#[test]
fn wrist_readers_are_the_stored_value_in_si_and_agree_across_backends() {
    let a = wrist::<f64>();
    // Independent physics: eq. (6.3) at γ = −0.1 (the start pose's yaw):
    // τ_δ = cγ m_x − sγ τ_z with m_x = τ_x − l F_y = 1.5, and τ_γ = −m_y
    // with m_y = τ_y + l F_x = −2 (the module docs' corrected signs).
    let (s, c) = libm::sincos(-0.1);
    let want = [c * 1.5 - s * 0.7, 2.0];
    for i in 0..2 {
        assert!((a[1][i] - want[i]).abs() < 1e-6, "{:?} {want:?}", a[1]);
        // Both laws at the 0.6 N·m limit of Table 6.1, pushing each
        // motor back towards its reference (θ1 behind, θ3 ahead).
        assert!((a[0][i].abs() - 0.6).abs() < 1e-12, "{:?}", a[0]);
    }
    assert!(a[0][0] > 0.0 && a[0][1] < 0.0);
    // The tracking errors e = θ − θ_r: −0.3 and +0.3 rad less the
    // reference's motion on this tick (below 0.05 rad).
    assert!((a[8][0] + 0.3).abs() < 0.05 && (a[8][1] - 0.3).abs() < 0.05);
    // Bounds per backend (`step::tests::backends_agree_with_f64` and the
    // inverse-kinematics bound of `WristStepConfig`): angles 2e-5 rad on
    // f32 and 5e-3 rad on I16F16 at this bend, rates those over T = 4 ms
    // (twice: two references), the torques of eq. (6.3) and (6.1) a few
    // products of gauge signals of order 1 V.
    for (b, backend, angle) in [
        (wrist::<f32>(), "f32", 2e-5),
        (wrist::<I16F16>(), "I16F16", 5e-3),
    ] {
        for i in 0..2 {
            near("motor torque", backend, a[0][i], b[0][i], 1e-7);
            near("interaction", backend, a[1][i], b[1][i], 1e-3);
            near("joint torque", backend, a[2][i], b[2][i], 1e-2);
            near("reference", backend, a[3][i], b[3][i], angle);
            near("motor reference", backend, a[4][i], b[4][i], angle);
            near(
                "motor reference rate",
                backend,
                a[5][i],
                b[5][i],
                2.0 * angle / 0.004,
            );
            near("law torque", backend, a[6][i], b[6][i], 1e-7);
            near("tracking error", backend, a[8][i], b[8][i], angle);
        }
    }
}

/// `pose_reference` is the pose the last reference reached: the forward
/// kinematics of the start motors, then the step's reference.
#[test]
fn pose_reference_is_the_last_reference() {
    let p = WristStepParams::table_6_1().unwrap();
    let cfg = WristStepConfig::<f64>::new(&p);
    let kin = WristConfig::<f64>::new(&WristParams::thesis());
    let pose = PitchYaw {
        delta: 0.2,
        gamma: -0.1,
    };
    let motors = kin.inverse(pose).motors;
    let mut st = cfg.state(motors);
    let r0 = st.pose_reference();
    assert!(
        (r0.delta - 0.2).abs() < 1e-9 && (r0.gamma + 0.1).abs() < 1e-9,
        "{r0:?}"
    );
    let out = cfg.update(
        &mut st,
        &WristReadings::from_si([0.0; 6], [motors.theta1, motors.theta3], [0.0; 2]),
        &WristTarget::from_si(0.25, -0.05, 0.0, 0.0),
    );
    assert_eq!(st.pose_reference(), out.reference);
    // It moved towards the target (not the start pose, not the default).
    assert!(st.pose_reference().delta > 0.2 && st.pose_reference().gamma > -0.1);
}

/// `with_request` keeps the target and adds the request; the step obeys
/// it on the same tick.
#[test]
fn with_request_keeps_the_target_and_switches_the_mode() {
    use mrr_control::wrist::WristMode;
    let t = WristTarget::<f64>::from_si(0.2, -0.1, 0.3, -0.4);
    let r = t.with_request(WristMode::Passive);
    assert_eq!(r.request, Some(WristMode::Passive));
    assert_eq!((r.pose, r.rate), (t.pose, t.rate));
    assert_eq!(
        t.with_request(WristMode::Active).request,
        Some(WristMode::Active)
    );
    let p = WristStepParams::table_6_1().unwrap();
    let cfg = WristStepConfig::<f64>::new(&p);
    let motors = WristConfig::<f64>::new(&WristParams::thesis())
        .inverse(PitchYaw {
            delta: 0.2,
            gamma: -0.1,
        })
        .motors;
    let mut st = cfg.state(motors);
    let still = WristReadings::from_si([0.0; 6], [motors.theta1, motors.theta3], [0.0; 2]);
    let out = cfg.update(&mut st, &still, &r);
    assert!(out.switched && out.mode == WristMode::Passive, "{out:?}");
}
