//! Fuzz the wrist kinematics (thesis eq. 5.1–5.29) on every backend with
//! arbitrary bit patterns: forward and inverse kinematics, the tracking
//! inverse, α/β, both Jacobians, the force mapping both ways and the
//! universal joint. No panic, no NaN, every output within its documented
//! range, and at reachable poses the branch property of
//! `proofs/wrist_ik.rs`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::wrist_ik::{branch_and_round_trip, branch_slack, wrist};
use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::wrist::jacobian::MAX_TORQUE;
use mrr_control::wrist::ujoint::{transmit, MAX_BEND};
use mrr_control::wrist::{ForceMapping, IkState, JacobianKind, MotorAngles, PitchYaw, WristConfig};

fn finite<S: Scalar>(x: S) -> bool {
    !x.is_nan() && x.abs() <= S::MAX
}

fn check<S: Scalar>(v: [S; 6]) {
    let p = wrist();
    let cfg = WristConfig::<S>::new(&p);
    // Rounding allowance on the ranges: 64 units of the backend.
    let tol = 64.0
        * if S::RESOLUTION.to_f64() > 1e-6 {
            1.0 / 65536.0
        } else {
            2e-6
        };
    let pi = core::f64::consts::PI;
    let motors = MotorAngles {
        theta1: v[0],
        theta3: v[1],
    };
    let pose = PitchYaw {
        delta: v[2],
        gamma: v[3],
    };

    let f = cfg.forward(motors);
    for x in [f.pose.delta, f.pose.gamma, f.theta4] {
        assert!(finite(x), "forward {motors:?} -> {f:?}");
    }
    assert!(f.pose.delta.to_f64().abs() <= p.max_bend() + tol, "{f:?}");
    assert!(f.pose.gamma.to_f64().abs() <= p.max_bend() + tol, "{f:?}");
    assert!(f.theta4.to_f64().abs() <= pi + tol);

    let r = cfg.inverse(pose);
    let (t1, t3) = (r.motors.theta1.to_f64(), r.motors.theta3.to_f64());
    assert!(
        finite(r.motors.theta1) && finite(r.motors.theta3),
        "inverse {pose:?} -> {r:?}"
    );
    assert!(t1.abs() <= pi + tol, "{r:?}");
    let eps = branch_slack(&p);
    assert!(t1 + t3 >= -pi - eps - tol && t1 + t3 <= eps + tol, "{r:?}");
    assert!(r.theta4.to_f64() >= -tol && r.theta4.to_f64() <= pi + tol);
    assert!(
        branch_and_round_trip(&cfg, &p, v[2], v[3]).holds,
        "branch at {pose:?}: {r:?}"
    );
    if cfg.try_inverse(pose).is_ok() {
        assert!(!pose.delta.is_nan());
    }

    let mut st = IkState::new(motors);
    let u = cfg.update(&mut st, pose);
    assert!(finite(u.motors.theta1) && finite(u.motors.theta3));

    let ab = cfg.alpha_beta(motors);
    let ap = cfg.alpha_beta_approx(motors);
    for x in [ab.alpha, ab.beta, ap.alpha, ap.beta] {
        assert!(finite(x) && x.to_f64().abs() <= pi + tol);
    }
    assert!(ab.beta.to_f64() <= p.max_bend() + tol && ap.beta.to_f64() <= p.max_bend() + tol);

    for kind in [JacobianKind::Exact, JacobianKind::Thesis] {
        let fm = ForceMapping::<S>::new(&p, kind);
        let j = fm.jacobian(motors);
        for row in j.m {
            for x in row {
                assert!(finite(x) && x.to_f64().abs() <= 1.5 + tol, "{kind:?} {j:?}");
            }
        }
        let tm = fm.motor_torques(motors, [v[4], v[5]]);
        let lim = 2.0 * 1.5 * MAX_TORQUE * (1.0 + 1e-3);
        for x in tm.torque {
            assert!(finite(x) && x.to_f64().abs() <= lim, "{tm:?}");
        }
        let tt = fm.task_torques(motors, [v[4], v[5]]);
        for x in tt.torque {
            assert!(finite(x) || (x.abs() == S::MAX), "{tt:?}");
            assert!(!x.is_nan());
        }
    }

    let tr = transmit(v[2], v[0], v[4], v[5]);
    for x in [tr.angle, tr.speed, tr.torque] {
        assert!(!x.is_nan(), "{tr:?}");
    }
    let _ = MAX_BEND;
}

fuzz_target!(|data: [u64; 6]| {
    check(data.map(|x| f64::from_bits(x)));
    check(data.map(|x| f32::from_bits(x as u32)));
    check(data.map(|x| I16F16::from_bits((x >> 32) as i32)));
    // Physically scaled inputs: angles within ±4 rad, torques ±50.
    let scaled = |x: u64, r: f64| ((x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * r;
    let s = [
        scaled(data[0], 4.0),
        scaled(data[1], 4.0),
        scaled(data[2], 0.7),
        scaled(data[3], 0.7),
        scaled(data[4], 50.0),
        scaled(data[5], 50.0),
    ];
    check(s);
    check(s.map(|x| x as f32));
    check(s.map(I16F16::from_f64));
});
