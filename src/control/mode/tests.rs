use super::*;
use crate::estimation::CollisionSettings;
use crate::scalar::I16F16;
use proptest::prelude::*;

fn params(debounce: u16, dwell: u16, collision: Option<CollisionParams>) -> ModeParams {
    ModeParams::try_new(ModeSettings {
        active: RobustAdaptiveParams::table_4_1().unwrap(),
        passive: PassiveParams::table_4_1(2000.0).unwrap(),
        enter_passive: 2.0,
        exit_passive: 1.0,
        debounce,
        dwell,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.1,
        collision,
    })
    .unwrap()
}

/// A physically bounded sample in SI (motor side: ±30 rad, ±50 rad/s,
/// ±2000 rad/s², link torques ±5 N·m), quantized for `S`.
fn quantize<S: Scalar>(x: &ControlInput<f64>) -> ControlInput<S> {
    let u = S::UNITS;
    ControlInput {
        desired_position: S::from_f64(x.desired_position * u.angle),
        desired_velocity: S::from_f64(x.desired_velocity * u.speed),
        desired_acceleration: S::from_f64(x.desired_acceleration * u.speed),
        motor_position: S::from_f64(x.motor_position * u.angle),
        motor_velocity: S::from_f64(x.motor_velocity * u.speed),
        joint_torque: S::from_f64(x.joint_torque * u.link_torque),
        desired_joint_torque: S::from_f64(x.desired_joint_torque * u.link_torque),
        expected_joint_torque: S::from_f64(x.expected_joint_torque * u.link_torque),
    }
}

prop_compose! {
    fn sample()(qd in -30.0f64..30.0, dq in -0.5f64..0.5, vd in -50.0f64..50.0, dv in -5.0f64..5.0,
                ad in -2000.0f64..2000.0, tau in -5.0f64..5.0, exp in -1.0f64..1.0) -> ControlInput<f64> {
        ControlInput {
            desired_position: qd, desired_velocity: vd, desired_acceleration: ad,
            motor_position: qd + dq, motor_velocity: vd + dv, joint_torque: tau,
            desired_joint_torque: 0.0, expected_joint_torque: exp,
        }
    }
}

/// Runs a sequence through the manager; at every switching sample checks
/// `|τ_after − τ_before| ≤ switch_jump_bound` with `τ_before` the previous
/// command (tracked here, 0 initially), that the reference starts at the
/// measured position
/// when entering Active or Hold, and everywhere that the output is
/// bounded and NaN-free and equals the current mode's command when no
/// switch happens.
fn check_sequence<S: Scalar>(
    cfg: &ModeConfig<S>,
    xs: &[ControlInput<f64>],
    ack_at: usize,
) -> Result<u32, TestCaseError> {
    let mut st = cfg.initial_state();
    let bound = cfg.switch_jump_bound();
    let mut switches = 0;
    let mut prev = S::ZERO;
    for (k, x) in xs.iter().enumerate() {
        if k == ack_at {
            cfg.acknowledge_collision(&mut st);
        }
        let xq = quantize::<S>(x);
        let before = cfg.evaluate(&st, &xq);
        let o = cfg.update(&mut st, &xq);
        prop_assert!(!o.torque.is_nan() && o.torque.abs() <= cfg.torque_limit());
        if o.switched {
            switches += 1;
            let jump = o.torque.sub(prev).abs();
            prop_assert!(
                jump <= bound,
                "{:?}: jump {:?} > {:?} ({:?} → {:?})",
                o.mode,
                jump,
                bound,
                prev,
                o.torque
            );
            if o.mode != JointMode::Passive {
                let d = o.reference_position.sub(xq.motor_position).abs();
                prop_assert!(
                    d.to_f64()
                        <= 4.0 * S::RESOLUTION.to_f64() * (1.0 + xq.motor_position.abs().to_f64())
                );
            }
        } else {
            prop_assert_eq!(o.torque, before);
        }
        prev = o.torque;
    }
    Ok(switches)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// The bumpless-transfer bound of the module docs over random states
    /// and random switching sequences, on every backend.
    #[test]
    fn switching_is_bumpless(prefix in proptest::collection::vec(sample(), 0..120), tail in sample()) {
        let p = params(1, 0, Some(CollisionParams::try_new(CollisionSettings {
            threshold: 4.0,
            release_threshold: 3.0,
            debounce: 2,
            release: 2,
            reaction: CollisionReaction::Stop,
        }).unwrap()));
        // Interaction torques beyond ±2 N·m switch to passive, below ±1
        // back; the random prefix leaves a random state, and the tail
        // forces at least two switches from it (Active → Passive →
        // Active, or Passive → Active → Passive; a latched collision is
        // acknowledged first).
        let mut xs = prefix;
        let ack = xs.len();
        for tau in [3.0, 0.0, 3.0] {
            xs.push(ControlInput { joint_torque: tau, expected_joint_torque: 0.0, ..tail });
        }
        for n in [
            check_sequence(&ModeConfig::<f64>::new(&p), &xs, ack)?,
            check_sequence(&ModeConfig::<f32>::new(&p), &xs, ack)?,
            check_sequence(&ModeConfig::<I16F16>::new(&p), &xs, ack)?,
        ] {
            prop_assert!(n >= 2);
        }
    }
}

fn step<S: Scalar>(cfg: &ModeConfig<S>, st: &mut ModeState<S>, tau: f64) -> ModeOutput<S> {
    let x = quantize::<S>(&ControlInput {
        joint_torque: tau,
        ..Default::default()
    });
    cfg.update(st, &x)
}

#[test]
fn hysteresis_debounce_and_dwell() {
    let cfg = ModeConfig::<I16F16>::new(&params(3, 10, None));
    let mut st = cfg.initial_state();
    // Inside the hysteresis band nothing happens.
    for _ in 0..20 {
        assert_eq!(step(&cfg, &mut st, 1.5).mode, JointMode::Active);
    }
    // Over `enter` for 2 samples, then back: debounce prevents a switch.
    step(&cfg, &mut st, 2.5);
    step(&cfg, &mut st, 2.5);
    assert_eq!(step(&cfg, &mut st, 1.5).mode, JointMode::Active);
    // Three in a row switch.
    step(&cfg, &mut st, -2.5);
    step(&cfg, &mut st, -2.5);
    let o = step(&cfg, &mut st, -2.5);
    assert!(o.switched && o.mode == JointMode::Passive);
    // Below `exit` at once: the dwell time (10 samples) holds Passive.
    let mut k = 0;
    while step(&cfg, &mut st, 0.0).mode == JointMode::Passive {
        k += 1;
        assert!(k < 100);
    }
    assert_eq!(k, 10);
    // Between the thresholds Passive would stay.
    let o = step(&cfg, &mut st, 0.0);
    assert_eq!(o.mode, JointMode::Active);
}

/// The release rule on every backend: a Passive joint below `exit` but
/// moving faster than `v_rest` stays Passive however long; at rest it
/// returns after exactly `n_release` consecutive samples, and a single
/// moving sample restarts the count. The torque-only rule (the default)
/// returns after `debounce` samples whatever the speed.
#[test]
fn release_rule_requires_rest_for_its_samples() {
    fn run<S: Scalar>() {
        let rule = ReleaseRule {
            speed: 1.0,
            samples: 7,
        };
        let p = params(3, 0, None);
        assert_eq!(p.release(), ReleaseRule::torque_only(3));
        let cfg = ModeConfig::<S>::new(&p.with_release(rule).unwrap());
        let at = |tau: f64, speed: f64| {
            quantize::<S>(&ControlInput {
                joint_torque: tau,
                motor_velocity: speed,
                desired_velocity: speed,
                ..Default::default()
            })
        };
        let mut st = cfg.initial_state();
        for _ in 0..3 {
            cfg.update(&mut st, &at(5.0, 0.0));
        }
        assert_eq!(st.mode(), JointMode::Passive);
        // Guided: small torque, moving.
        for _ in 0..500 {
            assert_eq!(cfg.update(&mut st, &at(0.1, 3.0)).mode, JointMode::Passive);
        }
        // At rest for 6 samples, one moving sample, then at rest again.
        for _ in 0..6 {
            assert_eq!(cfg.update(&mut st, &at(0.1, 0.5)).mode, JointMode::Passive);
        }
        assert_eq!(cfg.update(&mut st, &at(0.1, -1.5)).mode, JointMode::Passive);
        let mut k = 0;
        while cfg.update(&mut st, &at(0.1, -0.5)).mode == JointMode::Passive {
            k += 1;
            assert!(k < 100);
        }
        assert_eq!(k + 1, 7, "{}", S::NAME);
        // The default rule: back after `debounce` samples while moving.
        let cfg = ModeConfig::<S>::new(&p);
        let mut st = cfg.initial_state();
        for _ in 0..3 {
            cfg.update(&mut st, &at(5.0, 0.0));
        }
        let mut k = 0;
        while cfg.update(&mut st, &at(0.1, 3.0)).mode == JointMode::Passive {
            k += 1;
            assert!(k < 100);
        }
        assert_eq!(k + 1, 3);
    }
    run::<f32>();
    run::<f64>();
    run::<I16F16>();
}

#[test]
fn release_rule_is_validated() {
    let p = params(5, 0, None);
    assert!(matches!(
        p.with_release(ReleaseRule {
            speed: 0.0,
            samples: 10
        }),
        Err(ParamError::NotPositive {
            name: "rule.speed",
            ..
        })
    ));
    assert!(matches!(
        p.with_release(ReleaseRule {
            speed: f64::NAN,
            samples: 10
        }),
        Err(ParamError::NotFinite {
            name: "rule.speed",
            ..
        })
    ));
    assert!(matches!(
        p.with_release(ReleaseRule {
            speed: 4e4,
            samples: 10
        }),
        Err(ParamError::OutOfRange {
            name: "rule.speed",
            ..
        })
    ));
    assert!(matches!(
        p.with_release(ReleaseRule {
            speed: 1.0,
            samples: 4
        }),
        Err(ParamError::OutOfRange {
            name: "rule.samples",
            ..
        })
    ));
    assert!(p
        .with_release(ReleaseRule {
            speed: 1.0,
            samples: 5
        })
        .is_ok());
}

#[test]
fn collision_stop_holds_the_position_until_acknowledged() {
    let col = CollisionParams::try_new(CollisionSettings {
        threshold: 3.0,
        release_threshold: 1.0,
        debounce: 2,
        release: 2,
        reaction: CollisionReaction::Stop,
    })
    .unwrap();
    let cfg = ModeConfig::<f64>::new(&params(1, 0, Some(col)));
    let mut st = cfg.initial_state();
    let mut x = ControlInput {
        motor_position: 0.7,
        desired_position: 0.7,
        joint_torque: 3.5,
        expected_joint_torque: 0.0,
        ..Default::default()
    };
    // First sample over 3 N·m: the interaction rule (2 N·m, debounce 1)
    // already switches to Passive. Use expected torque to keep the
    // interaction small while the residual is large? Both use the same
    // residual, so give the detector its own debounce: on the second
    // sample the collision onset forces Stop even from Passive? No: the
    // reaction applies from Active only; here test from Active with a
    // detector faster than the interaction rule.
    let cfg = ModeConfig::<f64>::new(&params(5, 0, Some(col)));
    let mut st2 = cfg.initial_state();
    let _ = &mut st;
    assert_eq!(cfg.update(&mut st2, &x).mode, JointMode::Active);
    let o = cfg.update(&mut st2, &x);
    assert!(o.switched && o.mode == JointMode::Hold && o.collision);
    assert_eq!(o.reference_position, 0.7);
    // The user trajectory moves on; the hold point stays.
    x.desired_position = 2.0;
    x.joint_torque = 0.0;
    for _ in 0..50 {
        let o = cfg.update(&mut st2, &x);
        assert_eq!(o.mode, JointMode::Hold);
        assert_eq!(o.reference_position, 0.7);
    }
    cfg.acknowledge_collision(&mut st2);
    let mut o = cfg.update(&mut st2, &x);
    let mut k = 0;
    while o.mode != JointMode::Active {
        o = cfg.update(&mut st2, &x);
        k += 1;
        assert!(k < 10);
    }
    // Re-entering Active starts from the measured position.
    assert!(o.switched && (o.reference_position - 0.7).abs() < 1e-15);
}

#[test]
fn collision_passive_reaction_latches_passive() {
    let col = CollisionParams::try_new(CollisionSettings {
        threshold: 3.0,
        release_threshold: 1.0,
        debounce: 1,
        release: 1,
        reaction: CollisionReaction::Passive,
    })
    .unwrap();
    let cfg = ModeConfig::<f32>::new(&params(5, 0, Some(col)));
    let mut st = cfg.initial_state();
    let o = step(&cfg, &mut st, 3.5);
    assert!(o.switched && o.mode == JointMode::Passive && o.collision);
    for _ in 0..20 {
        assert_eq!(step(&cfg, &mut st, 0.0).mode, JointMode::Passive);
    }
    cfg.acknowledge_collision(&mut st);
    let mut k = 0;
    while step(&cfg, &mut st, 0.0).mode != JointMode::Active {
        k += 1;
        assert!(k < 10);
    }
}

/// A collision onset on the very sample a Passive joint would be released
/// (detector threshold 0.5 N·m below `exit` = 1 N·m, its debounce ending
/// there) latches and keeps the joint Passive, on every backend: the latch
/// blocks the release from its onset on, until it is acknowledged.
#[test]
fn collision_onset_in_passive_blocks_the_release_on_its_sample() {
    fn check<S: Scalar>() {
        let col = CollisionParams::try_new(CollisionSettings {
            threshold: 0.5,
            release_threshold: 0.25,
            debounce: 2,
            release: 1,
            reaction: CollisionReaction::Stop,
        })
        .unwrap();
        let cfg = ModeConfig::<S>::new(&params(1, 0, Some(col)));
        let mut st = cfg.initial_state();
        // 3 N·m: the interaction rule switches to Passive; the detector
        // counts its first sample over 0.5 N·m.
        let o = step(&cfg, &mut st, 3.0);
        assert!(
            o.switched && o.mode == JointMode::Passive && !o.collision,
            "{}",
            S::NAME
        );
        // 0.8 N·m: below `exit` at rest (the release rule would switch to
        // Active) and the detector's second sample over its threshold.
        let o = step(&cfg, &mut st, 0.8);
        assert!(o.collision, "{}", S::NAME);
        assert!(
            !o.switched && o.mode == JointMode::Passive,
            "{} {:?}",
            S::NAME,
            o.mode
        );
        for _ in 0..20 {
            assert_eq!(
                step(&cfg, &mut st, 0.0).mode,
                JointMode::Passive,
                "{}",
                S::NAME
            );
        }
        cfg.acknowledge_collision(&mut st);
        let mut k = 0;
        while step(&cfg, &mut st, 0.0).mode != JointMode::Active {
            k += 1;
            assert!(k < 10, "{}", S::NAME);
        }
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

/// After entering Active away from the desired trajectory, the rejoin
/// offset decays like the critically damped continuous system
/// `o(t) = (o₀ + (ȯ₀ + ω o₀) t) e^{−ωt}` (to the forward-difference error
/// of the semi-implicit Euler step, ωT = 0.04) and never changes sign.
#[test]
fn rejoin_offset_decays_critically_damped() {
    let cfg = ModeConfig::<f64>::new(&params(1, 0, None));
    let mut st = cfg.initial_state();
    let x = ControlInput {
        joint_torque: 3.0,
        ..Default::default()
    };
    cfg.update(&mut st, &x);
    assert_eq!(st.mode(), JointMode::Passive);
    let x = ControlInput {
        motor_position: 0.5,
        joint_torque: 0.0,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &x);
    assert!(o.switched && o.mode == JointMode::Active);
    let w = 10.0;
    let t_s = 0.004;
    for k in 1..1000 {
        cfg.update(&mut st, &x);
        let (off, _) = st.rejoin_offset();
        let t = k as f64 * t_s;
        let want = 0.5 * (1.0 + w * t) * (-w * t).exp();
        assert!(off >= 0.0);
        assert!((off - want).abs() <= 0.03 * 0.5, "k={k}: {off} vs {want}");
    }
    assert!(st.rejoin_offset().0 < 1e-6);
}

#[test]
fn invalid_input_gives_zero_and_keeps_state() {
    let cfg = ModeConfig::<f64>::new(&params(1, 0, None));
    let mut st = cfg.initial_state();
    let before = st;
    let o = cfg.update(
        &mut st,
        &ControlInput {
            joint_torque: f64::NAN,
            ..Default::default()
        },
    );
    assert!(o.invalid_input && o.torque == 0.0 && st == before);
}

/// A NaN or infinite motor position is flagged and no output field is NaN
/// (the reference position used to echo the NaN reading), on both float
/// backends; a finite position is echoed.
#[test]
fn invalid_position_gives_no_nan_field() {
    fn check<S: Scalar>() {
        let cfg = ModeConfig::<S>::new(&params(1, 0, None));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut st = cfg.initial_state();
            let x = ControlInput::<S>::from_si(&ControlInput {
                desired_position: bad,
                motor_position: bad,
                ..Default::default()
            });
            let o = cfg.update(&mut st, &x);
            assert!(o.invalid_input && o.torque == S::ZERO, "{o:?}");
            assert!(!o.reference_position.is_nan() && !o.interaction.is_nan());
            assert_eq!(o.reference_position, S::ZERO);
        }
        let mut st = cfg.initial_state();
        let x = ControlInput::<S>::from_si(&ControlInput {
            motor_position: 0.25,
            joint_torque: f64::NAN,
            ..Default::default()
        });
        let o = cfg.update(&mut st, &x);
        assert!(o.invalid_input);
        assert_eq!(o.reference_position.to_f64(), 0.25 * S::UNITS.angle);
    }
    check::<f64>();
    check::<f32>();
}

/// The preset is the settings the tests above use, field by field, and
/// validated parameters give their settings back unchanged.
#[test]
fn table_4_1_preset_and_settings_round_trip() {
    let s = ModeSettings::table_4_1(2000.0).unwrap();
    assert_eq!(s.active, RobustAdaptiveParams::table_4_1().unwrap());
    assert_eq!(s.passive, PassiveParams::table_4_1(2000.0).unwrap());
    assert_eq!(
        (s.enter_passive, s.exit_passive, s.debounce, s.dwell),
        (2.0, 1.0, 3, 5)
    );
    assert_eq!((s.rejoin_bandwidth, s.bias_time_constant), (10.0, 0.1));
    assert!(s.collision.is_none());
    let p = ModeParams::try_new(ModeSettings {
        debounce: 7,
        dwell: 11,
        ..s
    })
    .unwrap();
    let back = p.settings();
    assert_eq!((back.debounce, back.dwell), (7, 11));
    assert_eq!(ModeParams::try_new(back), Ok(p));
    // A zero debounce is named.
    assert_eq!(
        ModeParams::try_new(ModeSettings { debounce: 0, ..s }),
        Err(ParamError::NotPositive {
            name: "debounce",
            value: 0.0
        })
    );
}

#[test]
fn rejects_inverted_thresholds_and_fast_rejoin() {
    let a = RobustAdaptiveParams::table_4_1().unwrap();
    let p = PassiveParams::table_4_1(2000.0).unwrap();
    assert!(matches!(
        ModeParams::try_new(ModeSettings {
            active: a,
            passive: p,
            enter_passive: 1.0,
            exit_passive: 2.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: 10.0,
            bias_time_constant: 0.1,
            collision: None
        }),
        Err(ParamError::NotIncreasing { .. })
    ));
    assert!(matches!(
        ModeParams::try_new(ModeSettings {
            active: a,
            passive: p,
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: 200.0,
            bias_time_constant: 0.1,
            collision: None
        }),
        Err(ParamError::OutOfRange {
            name: "rejoin_bandwidth",
            ..
        })
    ));
    assert!(matches!(
        ModeParams::try_new(ModeSettings {
            active: a,
            passive: p,
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: 10.0,
            bias_time_constant: 0.001,
            collision: None
        }),
        Err(ParamError::OutOfRange {
            name: "bias_time_constant",
            ..
        })
    ));
}

/// The one-comparison `limit` equals `clamp(−limit, limit)` at every
/// `I16F16` value of a stride (with the extremes) and at `f32`/`f64` values
/// around the limit, including ±∞.
#[test]
fn limit_equals_the_clamp() {
    fn check<S: Scalar>(cfg: &ModeConfig<S>, v: S) {
        let got = cfg.limit(v);
        let want = v.clamp(cfg.limit.neg(), cfg.limit);
        assert!(
            got == want,
            "{} -> {} vs {}",
            v.to_f64(),
            got.to_f64(),
            want.to_f64()
        );
    }
    let p = params(3, 10, None);
    let q = ModeConfig::<I16F16>::new(&p);
    for bits in (i32::MIN..=i32::MAX)
        .step_by(4099)
        .chain([i32::MIN, i32::MAX, -1, 0, 1])
    {
        check(&q, I16F16::from_bits(bits));
    }
    let l = q.limit.to_bits();
    for bits in [l - 1, l, l + 1, -l - 1, -l, -l + 1] {
        check(&q, I16F16::from_bits(bits));
    }
    let f = ModeConfig::<f32>::new(&p);
    let d = ModeConfig::<f64>::new(&p);
    for k in -2000..=2000 {
        let v = k as f64 * 1e-3;
        check(&f, v as f32);
        check(&d, v);
    }
    for v in [
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        f32::MIN,
        0.0,
        -0.0,
        f.limit,
        -f.limit,
    ] {
        check(&f, v);
    }
    for v in [f64::INFINITY, f64::NEG_INFINITY, d.limit, -d.limit] {
        check(&d, v);
    }
}

/// `command` equals its two-limit definition: `law` (NaN as 0) clamped,
/// the bias re-seeded at a switch to `before − clamped`, then `clamped +
/// bias` clamped; `saturated` when either clamp changed its value or the
/// law was NaN. Over a grid of laws (±∞ and NaN included on floats),
/// biases and previous commands around and beyond the limit (finite: the
/// state only ever holds finite commands and biases), switched or not.
#[test]
fn command_equals_the_two_clamps() {
    fn reference<S: Scalar>(
        l: S,
        law: S,
        before: S,
        switched: bool,
        bias: &mut S,
    ) -> (S, bool, bool) {
        let overflow = law.is_nan();
        let law = if overflow { S::ZERO } else { law };
        let limited = law.clamp(l.neg(), l);
        if switched {
            *bias = before.sub(limited);
        }
        let sum = limited.add(*bias);
        let torque = sum.clamp(l.neg(), l);
        (
            torque,
            limited != law || torque != sum || overflow,
            overflow,
        )
    }
    fn check<S: Scalar>(cfg: &ModeConfig<S>, values: &[S]) -> usize {
        let mut saturated = 0;
        let state: Vec<S> = values
            .iter()
            .copied()
            .filter(|v| v.to_f64().is_finite())
            .collect();
        for &law in values {
            for &before in &state {
                for &b0 in &state {
                    for switched in [false, true] {
                        let (mut b1, mut b2) = (b0, b0);
                        let got = cfg.command(law, before, switched, &mut b1);
                        let want = reference(cfg.limit, law, before, switched, &mut b2);
                        let same = |a: S, b: S| a == b || (a.is_nan() && b.is_nan());
                        assert!(
                            same(got.0, want.0)
                                && got.1 == want.1
                                && got.2 == want.2
                                && same(b1, b2),
                            "law {} before {} bias {} switched {switched}: {:?} vs {:?}",
                            law.to_f64(),
                            before.to_f64(),
                            b0.to_f64(),
                            (got.0.to_f64(), got.1, got.2, b1.to_f64()),
                            (want.0.to_f64(), want.1, want.2, b2.to_f64()),
                        );
                        saturated += usize::from(got.1);
                    }
                }
            }
        }
        saturated
    }
    let p = params(3, 10, None);
    let f = ModeConfig::<f32>::new(&p);
    let l = f.limit;
    let up = f32::from_bits(l.to_bits() + 1);
    let down = f32::from_bits(l.to_bits() - 1);
    let mut vf = vec![
        0.0f32,
        -0.0,
        0.25 * l,
        0.5 * l,
        down,
        l,
        up,
        2.0 * l,
        f32::MAX,
        f32::INFINITY,
        f32::NAN,
    ];
    vf.extend(vf.clone().iter().map(|v| -v));
    let n = check(&f, &vf);
    // Both outcomes occur.
    assert!(n > 0 && n < 2 * vf.len().pow(3));
    let d = ModeConfig::<f64>::new(&p);
    let l = d.limit;
    let mut vd = vec![0.0f64, 0.5 * l, l, 1.5 * l, f64::INFINITY, f64::NAN];
    vd.extend(vd.clone().iter().map(|v| -v));
    check(&d, &vd);
    let q = ModeConfig::<I16F16>::new(&p);
    let lb = q.limit.to_bits();
    let mut vq: Vec<I16F16> = [0, 1, lb / 2, lb - 1, lb, lb + 1, 2 * lb, i32::MAX]
        .iter()
        .map(|&b| I16F16::from_bits(b))
        .collect();
    vq.extend(vq.clone().iter().map(|v| v.neg()));
    vq.push(I16F16::from_bits(i32::MIN));
    check(&q, &vq);
}

/// The rejoin offset on `I16F16` stops where both of its increments round
/// to zero: `|ȯ T| < ½ LSB` and `|acc T| < ½ LSB` with
/// `acc = −2ω ȯ − ω² o`, so `|o| < (1 + 2ω) 2⁻¹⁷/(ω² T)` (the bound
/// checked here, 20 000 samples at 4 ms after a 0.5 rad offset). At
/// `ω = 1 rad/s` that is 5.7e-3 rad motor side (5.7e-5 rad at the link
/// for `N = 100`, a third of the 0.01° link encoder's count); `f64` rejoins
/// exactly (below 1e-9 rad).
#[test]
fn rejoin_offset_stall_is_within_its_bound() {
    for w in [1.0, 3.0, 10.0, 100.0] {
        let p = ModeParams::try_new(ModeSettings {
            active: RobustAdaptiveParams::table_4_1().unwrap(),
            passive: PassiveParams::table_4_1(2000.0).unwrap(),
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 1,
            dwell: 0,
            rejoin_bandwidth: w,
            bias_time_constant: 0.1,
            collision: None,
        })
        .unwrap();
        fn run<S: Scalar>(p: &ModeParams) -> f64 {
            let cfg = ModeConfig::<S>::new(p);
            let mut st = cfg.initial_state();
            step(&cfg, &mut st, 3.0);
            let x = quantize::<S>(&ControlInput {
                motor_position: 0.5,
                ..Default::default()
            });
            cfg.update(&mut st, &x);
            for _ in 0..20_000 {
                cfg.update(&mut st, &x);
            }
            st.rejoin_offset().0.to_f64()
        }
        let stall = run::<I16F16>(&p);
        let bound = (1.0 + 2.0 * w) * 2f64.powi(-17) / (w * w * 0.004);
        assert!(stall.abs() <= bound, "ω = {w}: {stall} > {bound}");
        assert!(run::<f64>(&p).abs() < 1e-9);
    }
}

/// Entering Active with a measured and a desired position of opposite
/// sign near the `f32` range: `q_m − q_m^d` overflows to infinity. The
/// offset is dropped (the reference is the desired trajectory), so no
/// later sample carries an infinity or a NaN out of the state. Before
/// the offset was checked, the next sample's reference was NaN.
#[test]
fn overflowing_rejoin_offset_is_dropped() {
    let cfg = ModeConfig::<f32>::new(&params(1, 0, None));
    let mut st = cfg.initial_state();
    let push = ControlInput {
        joint_torque: 3000.0,
        ..Default::default()
    };
    cfg.update(&mut st, &push);
    assert_eq!(st.mode(), JointMode::Passive);
    let far = ControlInput {
        motor_position: 3.0e38,
        desired_position: -3.0e38,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &far);
    assert!(o.switched && o.mode == JointMode::Active);
    assert_eq!(st.rejoin_offset(), (0.0, 0.0));
    // A finite offset whose ω² o overflows is dropped too.
    let mut st2 = cfg.initial_state();
    cfg.update(&mut st2, &push);
    let big = ControlInput {
        motor_position: 3.0e38,
        ..Default::default()
    };
    cfg.update(&mut st2, &big);
    assert!(st2.rejoin_offset().0.is_finite());
    for _ in 0..50 {
        let o = cfg.update(&mut st, &far);
        assert!(o.torque.is_finite() && o.reference_position.is_finite());
        let (a, b) = st.rejoin_offset();
        assert!(a.is_finite() && b.is_finite());
    }
    // An offset that fits is kept (the check does not drop ordinary ones).
    let mut st3 = cfg.initial_state();
    cfg.update(&mut st3, &push);
    let near = ControlInput {
        motor_position: 500.0,
        ..Default::default()
    };
    cfg.update(&mut st3, &near);
    assert!(st3.rejoin_offset().0 > 490.0);
}

/// Every validated range of `try_new` and `with_release` at its edge: the
/// edge is accepted, the next `f64` past it is rejected under the field's
/// name (`enter_passive ≤ 30 000` N·m, `rejoin_bandwidth ≤ 0.5/T`
/// (= 125 rad/s at Table 4.1's 4 ms, below the 1e5 cap), the bias time
/// constant `≥ T`, the release speed `≤ 30 000` rad/s).
#[test]
fn ranges_are_accepted_to_their_edges() {
    let settings = |f: &dyn Fn(&mut ModeSettings)| {
        let mut s = ModeSettings {
            active: RobustAdaptiveParams::table_4_1().unwrap(),
            passive: PassiveParams::table_4_1(2000.0).unwrap(),
            enter_passive: 2.0,
            exit_passive: 1.0,
            debounce: 3,
            dwell: 0,
            rejoin_bandwidth: 10.0,
            bias_time_constant: 0.1,
            collision: None,
        };
        f(&mut s);
        ModeParams::try_new(s)
    };
    let t = RobustAdaptiveParams::table_4_1()
        .unwrap()
        .design()
        .sample_period;
    assert_eq!(t, 0.004);
    type Set = fn(&mut ModeSettings, f64);
    let edges: [(&str, f64, f64, Set); 3] = [
        ("enter_passive", 30_000.0, 30_000f64.next_up(), |s, v| {
            s.enter_passive = v
        }),
        ("rejoin_bandwidth", 125.0, 125f64.next_up(), |s, v| {
            s.rejoin_bandwidth = v
        }),
        ("bias_time_constant", 0.004, 0.004f64.next_down(), |s, v| {
            s.bias_time_constant = v
        }),
    ];
    for (name, at, past, set) in edges {
        assert!(settings(&|s| set(s, at)).is_ok(), "{name} = {at}");
        let e = settings(&|s| set(s, past)).unwrap_err();
        assert_eq!(e.name(), name, "{name} = {past}: {e}");
    }
    let p = settings(&|_| {}).unwrap();
    let rule = |speed| ReleaseRule { speed, samples: 3 };
    assert!(p.with_release(rule(30_000.0)).is_ok());
    let e = p.with_release(rule(30_000f64.next_up())).unwrap_err();
    assert_eq!(e.name(), "rule.speed", "{e}");
}

/// The state's getters after a switch, on every backend: the bias and the
/// last command are the stored values and read in N·m as those over the
/// motor-torque scale (10³ on `I16F16`), non-zero after the switch; the frame is the one set;
/// the collision latch reads the latch, before and after a collision.
#[test]
fn state_getters_read_the_state() {
    fn check<S: Scalar + core::fmt::Debug>(scale: f64) {
        let cfg = ModeConfig::<S>::new(&params(1, 0, None));
        let mut st = cfg.initial_state();
        // A motor ahead of its reference: an active command, then a torque
        // over `enter` switches to Passive with a bias.
        let mut x = quantize::<S>(&ControlInput {
            motor_position: 2e-3,
            ..Default::default()
        });
        let before = cfg.update(&mut st, &x);
        assert!(!before.switched && before.torque != S::ZERO, "{}", S::NAME);
        x.joint_torque = S::from_f64(3.0 * S::UNITS.link_torque);
        let o = cfg.update(&mut st, &x);
        assert!(o.switched, "{}", S::NAME);
        assert_eq!(st.bias(), st.bias, "{}", S::NAME);
        assert!(st.bias != S::ZERO, "{}", S::NAME);
        assert_eq!(st.bias_si(), st.bias.to_f64() / scale, "{}", S::NAME);
        assert_eq!(st.last_torque(), o.torque, "{}", S::NAME);
        assert!(o.torque != S::ZERO, "{}", S::NAME);
        assert_eq!(
            st.last_torque_si(),
            o.torque.to_f64() / scale,
            "{}",
            S::NAME
        );
        st.set_frame(-3);
        assert_eq!(st.frame(), -3);
        st.set_frame(7);
        assert_eq!(st.frame(), 7);
        x.joint_torque = S::ZERO;
        let _ = cfg.update(&mut st, &x);
        assert!(!st.collision_latched() && !st.latched);
    }
    check::<f64>(1.0);
    check::<f32>(1.0);
    check::<I16F16>(1e3);

    let col = CollisionParams::try_new(CollisionSettings {
        threshold: 3.0,
        release_threshold: 1.0,
        debounce: 1,
        release: 2,
        reaction: CollisionReaction::Stop,
    })
    .unwrap();
    let cfg = ModeConfig::<f64>::new(&params(5, 0, Some(col)));
    let mut st = cfg.initial_state();
    let x = ControlInput {
        joint_torque: 3.5,
        ..Default::default()
    };
    assert!(!st.collision_latched());
    let mut k = 0;
    while !cfg.update(&mut st, &x).collision {
        k += 1;
        assert!(k < 5);
    }
    assert!(st.latched && st.collision_latched());
}

/// The rejoin offset in SI is the stored offset and rate (angle and speed
/// scales are 1 on every backend), read a few samples after a return to
/// Active 2.5 rad away from the reference, when both are beyond ±1.
#[test]
fn rejoin_offset_reads_in_si_on_every_backend() {
    fn check<S: Scalar + core::fmt::Debug>() {
        let cfg = ModeConfig::<S>::new(&params(1, 0, None));
        let mut st = cfg.initial_state();
        let push = quantize::<S>(&ControlInput {
            joint_torque: 3.0,
            ..Default::default()
        });
        cfg.update(&mut st, &push);
        let x = quantize::<S>(&ControlInput {
            motor_position: 2.5,
            ..Default::default()
        });
        for _ in 0..5 {
            cfg.update(&mut st, &x);
        }
        assert_eq!(st.mode(), JointMode::Active);
        let (o, r) = st.rejoin_offset();
        let (o_si, r_si) = st.rejoin_offset_si();
        assert_eq!((o_si, r_si), (o.to_f64(), r.to_f64()), "{}", S::NAME);
        // Beyond ±1, so that neither is its own remainder modulo 1.
        assert!(o_si > 1.5 && o_si < 2.5, "{}: {o_si}", S::NAME);
        assert!(r_si < -2.0, "{}: {r_si}", S::NAME);
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

/// The documented switching bound by hand: `2·ε·L` on the floats (`ε` the
/// machine epsilon, `L` the stored limit, 0.188 N·m for Table 4.1), 0 on
/// `I16F16`, whose bumpless transfer is exact.
#[test]
fn switch_jump_bound_by_hand() {
    let p = params(1, 0, None);
    let l = 0.188;
    let b64 = ModeConfig::<f64>::new(&p).switch_jump_bound();
    assert_eq!(b64, 2.0 * f64::EPSILON * l);
    let c32 = ModeConfig::<f32>::new(&p);
    assert_eq!(c32.torque_limit(), 0.188f32);
    let b32 = c32.switch_jump_bound();
    assert_eq!(b32, (2.0 * f32::EPSILON as f64 * 0.188f32 as f64) as f32);
    assert_eq!(
        ModeConfig::<I16F16>::new(&p).switch_jump_bound(),
        I16F16::ZERO
    );
}

/// Both switching thresholds are strict (module docs): with debounce 1
/// and no dwell, an interaction of exactly `enter` (2 N·m) keeps Active
/// and the next `f64` above switches; in Passive exactly `exit` (1 N·m)
/// keeps Passive and the next `f64` below returns.
#[test]
fn switching_thresholds_are_strict() {
    let cfg = ModeConfig::<f64>::new(&params(1, 0, None));
    let mut st = cfg.initial_state();
    for tau in [2.0, -2.0] {
        assert_eq!(step(&cfg, &mut st, tau).mode, JointMode::Active, "{tau}");
    }
    assert_eq!(
        step(&cfg, &mut st, -(2f64.next_up())).mode,
        JointMode::Passive
    );
    for tau in [1.0, -1.0] {
        assert_eq!(step(&cfg, &mut st, tau).mode, JointMode::Passive, "{tau}");
    }
    assert_eq!(
        step(&cfg, &mut st, 1f64.next_down()).mode,
        JointMode::Active
    );
}

/// A second collision while the Stop reaction holds the joint keeps the
/// first hold point and is not a switch (the motor has been pushed on
/// meanwhile: a re-seeded hold would move to where it is now).
#[test]
fn a_second_collision_in_hold_keeps_the_hold_point() {
    let col = CollisionParams::try_new(CollisionSettings {
        threshold: 3.0,
        release_threshold: 1.0,
        debounce: 1,
        release: 2,
        reaction: CollisionReaction::Stop,
    })
    .unwrap();
    let cfg = ModeConfig::<f64>::new(&params(5, 0, Some(col)));
    let mut st = cfg.initial_state();
    let mut x = ControlInput {
        motor_position: 0.7,
        desired_position: 0.7,
        joint_torque: 3.5,
        ..Default::default()
    };
    let o = cfg.update(&mut st, &x);
    assert!(o.switched && o.mode == JointMode::Hold && o.collision);
    // The detector releases; the motor is pushed to 0.9 rad.
    x.joint_torque = 0.0;
    x.motor_position = 0.9;
    for _ in 0..4 {
        let o = cfg.update(&mut st, &x);
        assert_eq!((o.mode, o.reference_position), (JointMode::Hold, 0.7));
    }
    // A new onset in Hold.
    x.joint_torque = 3.5;
    let mut onset = false;
    for _ in 0..3 {
        let o = cfg.update(&mut st, &x);
        onset |= o.collision;
        assert!(!o.switched && o.mode == JointMode::Hold);
        assert_eq!(o.reference_position, 0.7);
    }
    assert!(onset && st.collision_latched());
}

/// `output_revolution` (used by the joint-step proofs to copy a manager's
/// revolution) returns what `with_output_revolution` set.
#[test]
fn output_revolution_reads_back() {
    let cfg = ModeConfig::<f64>::new(&params(1, 0, None));
    for rev in [628.3185307179587, 314.1592653589793] {
        assert_eq!(cfg.with_output_revolution(rev).output_revolution(), rev);
    }
}
