//! Fuzz the ch. 4 laws: the robust adaptive law (eq. 4.19), the passive law
//! (eq. 4.32) and the mode manager with collision detection, on every
//! backend, with arbitrary designs and arbitrary input sequences: no panic,
//! no NaN, the output within its limit, the estimates within their box,
//! and every mode switch within the documented torque-jump bound.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::control::{
    ControlInput, ModeConfig, ModeParams, ModeSettings, PassiveConfig, PassiveParams,
    PassiveSettings, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams,
};
use mrr_control::estimation::{CollisionParams, CollisionReaction, CollisionSettings};
use mrr_control::scalar::{Scalar, I16F16};

fn input<S: Scalar>(v: &[f32; 8]) -> ControlInput<S> {
    let f = |x: f32| S::from_f64(x as f64);
    ControlInput {
        desired_position: f(v[0]),
        desired_velocity: f(v[1]),
        desired_acceleration: f(v[2]),
        motor_position: f(v[3]),
        motor_velocity: f(v[4]),
        joint_torque: f(v[5]),
        desired_joint_torque: f(v[6]),
        expected_joint_torque: f(v[7]),
    }
}

fn run<S: Scalar>(
    active: &RobustAdaptiveParams,
    mode: &ModeParams,
    passive: &PassiveParams,
    seq: &[[f32; 8]],
    ack: u8,
) {
    let a = RobustAdaptiveConfig::<S>::new(active);
    let mut st = a.initial_state();
    let p = PassiveConfig::<S>::new(passive);
    let m = ModeConfig::<S>::new(mode);
    let mut ms = m.initial_state();
    let bound = m.switch_jump_bound();
    let mut prev = S::ZERO;
    for (k, v) in seq.iter().enumerate() {
        let x = input::<S>(v);
        let o = a.update(&mut st, &x);
        assert!(!o.torque.is_nan() && o.torque.abs() <= a.torque_limit());
        assert!(st.integral().abs() <= a.integral_limit());
        for j in 0..4 {
            let f = st.friction()[j];
            assert!(f >= a.lower_bounds()[j] && f <= a.upper_bounds()[j]);
        }
        let po = p.update(&x);
        assert!(!po.torque.is_nan() && po.torque.abs() <= p.torque_limit());
        if k as u8 == ack {
            m.acknowledge_collision(&mut ms);
        }
        let before = m.evaluate(&ms, &x);
        let mo = m.update(&mut ms, &x);
        assert!(!mo.torque.is_nan() && mo.torque.abs() <= m.torque_limit());
        if mo.switched {
            assert!(
                mo.torque.sub(prev).abs() <= bound,
                "{} {:?} → {:?}",
                S::NAME,
                prev,
                mo.torque
            );
        } else if !mo.invalid_input {
            assert!(
                mo.torque == before,
                "{} {:?} {:?} {:?} {:?}",
                S::NAME,
                mo,
                before,
                ms,
                x
            );
        }
        prev = mo.torque;
    }
}

fuzz_target!(|data: ([f64; 8], [f64; 4], u8, u8, bool, Vec<[f32; 8]>)| {
    let (g, th, debounce, ack, stop, seq) = data;
    let mut d = RobustAdaptiveDesign::table_4_1();
    // Perturb the design; invalid designs are rejected cleanly.
    d.lambda = g[0];
    d.integral_gain = g[1];
    d.adaptation_gain = [g[2]; 4];
    d.eps_r = g[3];
    d.torque_limit = g[4];
    d.integral_limit = g[5];
    d.sample_period = g[6];
    d.uncertainty.torque_estimate = g[7];
    let active = RobustAdaptiveParams::try_new(d)
        .unwrap_or_else(|_| RobustAdaptiveParams::table_4_1().unwrap());
    let limit = active.design().torque_limit;
    let ad = active.design();
    let passive = PassiveParams::try_new(PassiveSettings {
        rotor_inertia: ad.rotor_inertia,
        gain: th[0],
        ratio: ad.ratio,
        eps_velocity: ad.eps_velocity,
        nominal_friction: ad.initial_friction,
        torque_limit: limit,
    })
    .unwrap_or_else(|_| {
        PassiveParams::try_new(PassiveSettings {
            rotor_inertia: ad.rotor_inertia,
            gain: 2000.0,
            ratio: ad.ratio,
            eps_velocity: ad.eps_velocity,
            nominal_friction: ad.initial_friction,
            torque_limit: limit,
        })
        .unwrap()
    });
    let reaction = if stop {
        CollisionReaction::Stop
    } else {
        CollisionReaction::Passive
    };
    let collision = CollisionParams::try_new(CollisionSettings {
        threshold: th[1],
        release_threshold: th[2],
        debounce: debounce.max(1) as u16,
        release: 2,
        reaction,
    })
    .ok();
    let mode = ModeParams::try_new(ModeSettings {
        active,
        passive,
        enter_passive: th[3],
        exit_passive: th[3] * 0.5,
        debounce: debounce.max(1) as u16,
        dwell: 3,
        rejoin_bandwidth: (0.1 / ad.sample_period).min(1e5),
        bias_time_constant: 0.1,
        collision,
    })
    .or_else(|_| {
        ModeParams::try_new(ModeSettings {
            active,
            passive,
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: (0.1 / ad.sample_period).min(1e5),
            bias_time_constant: 0.1_f64.max(ad.sample_period),
            collision,
        })
    })
    .unwrap();
    let seq = &seq[..seq.len().min(128)];
    run::<f32>(&active, &mode, &passive, seq, ack);
    run::<f64>(&active, &mode, &passive, seq, ack);
    run::<I16F16>(&active, &mode, &passive, seq, ack);
});
