use super::*;
use crate::control::{ModeOutput, RobustAdaptiveParams};
use crate::estimation::collision::{CollisionParams, CollisionReaction, CollisionSettings};
use crate::scalar::{Coef, I16F16};

/// The firmware's joint (the estimator and manager of
/// `embedded/src/joint.rs`): Table 4.1 laws with passive gain 2000, a
/// collision detector stopping the joint above 4 N·m.
fn firmware_params() -> JointParams {
    params_with(Some(KinematicErrorModel::table_3_2()), 2000)
}

/// [`firmware_params`] with the kinematic-error model `ke` and `m` motor
/// counts per revolution.
fn params_with(ke: Option<KinematicErrorModel>, m: u32) -> JointParams {
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive: CatalogueData::SHD_17_100.identify().unwrap(),
        kinematic_error: ke,
        link_counts_per_rev: 1 << 17,
        motor_counts_per_rev: m,
        max_torque: 60.0,
    })
    .unwrap();
    let mode = ModeParams::try_new(ModeSettings {
        active: RobustAdaptiveParams::table_4_1().unwrap(),
        passive: PassiveParams::table_4_1(2000.0).unwrap(),
        enter_passive: 2.0,
        exit_passive: 1.0,
        debounce: 3,
        dwell: 5,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.1,
        collision: Some(
            CollisionParams::try_new(CollisionSettings {
                threshold: 4.0,
                release_threshold: 3.0,
                debounce: 2,
                release: 2,
                reaction: CollisionReaction::Stop,
            })
            .unwrap(),
        ),
    })
    .unwrap();
    JointParams::try_new(JointSettings {
        estimator,
        mode,
        speed_window: 3,
        max_motor_speed: crate::joint::TABLE_4_1_MAX_MOTOR_SPEED,
    })
    .unwrap()
}

fn xorshift(s: &mut u64) -> u64 {
    crate::scalar::xorshift64(s)
}

/// Uniform in `[-a, a]`.
fn sym(s: &mut u64, a: f64) -> f64 {
    a * ((xorshift(s) >> 11) as f64 / (1u64 << 52) as f64 - 1.0)
}

/// The firmware's wiring, written out as `embedded/src/joint.rs` does it
/// (estimator fed the negated counter and the previous command; the
/// manager fed `−torque`), with its own position and speed meter.
struct Reference<S: Scalar> {
    est: TorqueEstimatorConfig<S>,
    mode: ModeConfig<S>,
    est_st: TorqueEstimatorState,
    mode_st: ModeState<S>,
    count: i64,
    counters: std::vec::Vec<u32>,
    window: usize,
    rad_per_count: f64,
    period: f64,
}

impl<S: Scalar> Reference<S> {
    fn new(p: &JointParams, motor_position: i64, counter: u32) -> Self {
        let s = p.settings();
        let est = TorqueEstimatorConfig::new(&s.estimator);
        let mode = ModeConfig::new(&s.mode);
        Reference {
            est_st: est.state(motor_position.wrapping_neg(), counter.wrapping_neg()),
            mode_st: mode.initial_state(),
            est,
            mode,
            count: motor_position,
            counters: std::vec![counter; s.speed_window as usize + 1],
            window: s.speed_window as usize,
            rad_per_count: TAU / s.estimator.motor_counts_per_rev() as f64,
            period: p.sample_period(),
        }
    }

    fn step(
        &mut self,
        l: u32,
        m: u32,
        a: [S; 3],
        td: S,
        expected: S,
    ) -> (TorqueEstimate<S>, ModeOutput<S>) {
        let u = S::UNITS;
        let e = self.est.update(
            &mut self.est_st,
            l,
            m.wrapping_neg(),
            self.mode_st.last_torque(),
        );
        let last = *self.counters.last().unwrap();
        self.count += m.wrapping_sub(last) as i32 as i64;
        self.counters.remove(0);
        self.counters.push(m);
        let moved = m.wrapping_sub(self.counters[0]) as i32 as i64;
        let n = Coef::new(100.0);
        let x = ControlInput {
            desired_position: a[0].mul_coef(&n),
            desired_velocity: a[1].mul_coef(&n),
            desired_acceleration: a[2].mul_coef(&n),
            motor_position: S::from_counts(self.count, &Coef::new(self.rad_per_count * u.angle)),
            motor_velocity: S::from_counts(
                moved,
                &Coef::new(self.rad_per_count / (self.window as f64 * self.period) * u.speed),
            ),
            joint_torque: e.torque.neg(),
            desired_joint_torque: td,
            expected_joint_torque: expected,
        };
        let o = self.mode.update(&mut self.mode_st, &x);
        (e, o)
    }
}

fn reproduces_the_firmware_wiring<S: Scalar>() {
    let p = firmware_params();
    let cfg = JointConfig::<S>::new(&p);
    let mut seed = 0x5EED_u64 ^ S::NAME.len() as u64;
    let (l, mn) = (1i64 << 17, 200_000i64);
    // Start near the top of the counter so that it wraps.
    let start_counter = u32::MAX - 5000;
    let link0 = 1000u32;
    let motor0 = link0 as i64 * mn / l;
    let mut st = cfg.state_at(motor0, start_counter);
    let mut r = Reference::<S>::new(&p, motor0, start_counter);
    let mut modes = [0usize; 3];
    let mut q_l = link0 as f64 / l as f64 * TAU;
    for k in 0..4000 {
        // The link wanders; the motor follows at N q_l plus a torsion of
        // up to ±40 counts (≈ ±10 N·m), sometimes held for a while.
        q_l += sym(&mut seed, 2e-3);
        let torsion = if (k / 50) % 3 == 0 {
            sym(&mut seed, 40.0)
        } else {
            sym(&mut seed, 4.0)
        };
        let lc = (q_l / TAU * l as f64).round() as i64;
        let mc = (q_l / TAU * mn as f64 + torsion).round() as i64 + start_counter as i64 - motor0;
        let (lc, mc) = (lc.rem_euclid(l) as u32, mc as u32);
        let target = JointTarget::<S> {
            turns: 0,
            position: S::from_f64(q_l + sym(&mut seed, 0.01)),
            velocity: S::from_f64(sym(&mut seed, 0.5)),
            acceleration: S::from_f64(sym(&mut seed, 20.0)),
            joint_torque: S::from_f64(sym(&mut seed, 0.5)),
            expected_joint_torque: S::from_f64(sym(&mut seed, 0.5)),
        };
        let out = cfg.update(&mut st, &JointReadings::counts(lc, mc), &target);
        let (e, o) = r.step(
            lc,
            mc,
            [target.position, target.velocity, target.acceleration],
            target.joint_torque,
            target.expected_joint_torque,
        );
        assert_eq!(out.estimate, e, "estimate at tick {k}");
        assert_eq!(out.control, o, "mode output at tick {k}");
        assert_eq!(out.motor_torque, o.torque);
        assert_eq!(out.joint_torque, e.torque.neg());
        assert_eq!(st.motor_position_counts(), r.count);
        modes[match o.mode {
            JointMode::Active => 0,
            JointMode::Hold => 1,
            JointMode::Passive => 2,
        }] += 1;
        if k % 400 == 399 {
            cfg.acknowledge_collision(&mut st);
            r.mode.acknowledge_collision(&mut r.mode_st);
        }
    }
    // The walk visited every mode.
    assert!(modes.iter().all(|&c| c > 20), "{modes:?}");
}

#[test]
fn reproduces_the_firmware_wiring_f32() {
    reproduces_the_firmware_wiring::<f32>();
}

#[test]
fn reproduces_the_firmware_wiring_i16f16() {
    reproduces_the_firmware_wiring::<I16F16>();
}

#[test]
fn reproduces_the_firmware_wiring_f64() {
    reproduces_the_firmware_wiring::<f64>();
}

/// Position and speed from a counter that wraps through `u32::MAX`,
/// against the counts written out in `f64`.
#[test]
fn motor_position_and_speed_follow_the_counter() {
    let p = firmware_params();
    let cfg = JointConfig::<f64>::new(&p);
    let start = u32::MAX - 100;
    let mut st = cfg.state_at(-7, start);
    let rad = TAU / 2000.0;
    let mut counter = start;
    let mut total = -7i64;
    let steps = [13i64, 13, 13, -4, 250, 0, 0, 0];
    let mut hist = std::vec![start; 4];
    for (k, &d) in steps.iter().cycle().take(40).enumerate() {
        counter = counter.wrapping_add(d as i32 as u32);
        total += d;
        hist.remove(0);
        hist.push(counter);
        let out = cfg.update(
            &mut st,
            &JointReadings::counts(0, counter),
            &JointTarget::default(),
        );
        assert!(
            (out.motor_position - total as f64 * rad).abs() < 1e-9,
            "tick {k}"
        );
        let moved = hist[3].wrapping_sub(hist[0]) as i32 as f64;
        let want = moved * rad / (3.0 * 0.004);
        assert!(
            (out.motor_velocity - want).abs() < 1e-9 * want.abs().max(1.0),
            "tick {k}"
        );
        assert!((out.motor_velocity_si() - want).abs() < 1e-9 * want.abs().max(1.0));
    }
    assert_eq!(st.motor_position_counts(), total);
}

/// `measure` is the first half of `update`: on twin states fed the same
/// readings it returns the fields `update` reports, and it leaves the mode
/// manager's state as it was.
#[test]
fn measure_is_the_measuring_half_of_update() {
    let p = firmware_params();
    let cfg = JointConfig::<f64>::new(&p);
    let mut a = cfg.state_at(40, 12);
    let mut b = a;
    let target = JointTarget::from_si(0.01, 0.0, 0.0);
    let mut seed = 7u64;
    let mut counter = 12u32;
    for k in 0..60 {
        counter = counter.wrapping_add((sym(&mut seed, 9.0)) as i32 as u32);
        let link = (xorshift(&mut seed) % 40) as u32;
        let r = JointReadings {
            link_count: link,
            motor_counter: counter,
            motor_torque: Some(sym(&mut seed, 0.1)),
        };
        let mode_before = *b.mode_state();
        let m = cfg.measure(&mut b, &r);
        assert_eq!(*b.mode_state(), mode_before, "tick {k}");
        let o = cfg.update(&mut a, &r, &target);
        assert_eq!(m.joint_torque, o.joint_torque, "tick {k}");
        assert_eq!(m.motor_position, o.motor_position, "tick {k}");
        assert_eq!(m.motor_velocity, o.motor_velocity, "tick {k}");
        assert_eq!(m.estimate, o.estimate, "tick {k}");
        assert_eq!(m.joint_torque, -o.estimate.torque);
        // Keep the twins' mode managers equal so the next tick's `None`
        // torque (unused here) could not differ either.
        b = b.with_mode_state(*a.mode_state());
    }
}

#[test]
fn state_starts_the_motor_at_n_times_the_link_angle() {
    // Without a kinematic-error model zero torsion is `q_m = N θ_l`.
    let cfg = JointConfig::<f32>::new(&params_with(None, 2000));
    let l = 1u32 << 17;
    // A quarter turn forward and a quarter turn back (count 3L/4).
    assert_eq!(cfg.state(l / 4, 0).motor_position_counts(), 50_000);
    assert_eq!(cfg.state(3 * l / 4, 0).motor_position_counts(), -50_000);
    // A count beyond L is taken modulo L.
    assert_eq!(cfg.state(l + l / 4, 0).motor_position_counts(), 50_000);
    // Between counts it is the floor `⌊c·M·N/L⌋` (M·N = 200 000), also
    // where the nearest count is the one above (fraction over one half),
    // as documented: no search on a drive without the model.
    for c in [1i64, 3, 5, 1000, -1, -3, -(l as i64) / 2] {
        let want = (c * 200_000).div_euclid(l as i64);
        let frac = (c * 200_000).rem_euclid(l as i64) as f64 / l as f64;
        let count = c.rem_euclid(l as i64) as u32;
        assert_eq!(
            cfg.state(count, 0).motor_position_counts(),
            want,
            "c = {c} (fraction {frac})"
        );
    }
}

/// With the Table 3.2 kinematic-error model the unloaded motor stands
/// `N·e_k` away from `N θ_l` (eq. 3.7), and `state` starts it there: the
/// first reading at rest is a torsion of at most half a motor count,
/// `π/(M N)` (plus the backend's torsion resolution), where a start at
/// `N θ_l` reads the whole kinematic error — checked here to be several
/// counts at some of the angles, so the test tells the two apart (a
/// 2¹⁶-count motor encoder: with the firmware's 2000 counts the Table 3.2
/// error stays within a count).
#[test]
fn state_starts_at_zero_torsion_with_the_kinematic_error() {
    fn check<S: Scalar>() -> f64 {
        const M: u32 = 1 << 16;
        let cfg = JointConfig::<S>::new(&params_with(Some(KinematicErrorModel::table_3_2()), M));
        let (l, mn) = (1i64 << 17, M as f64 * 100.0);
        let count = core::f64::consts::TAU / mn;
        let tol = 0.5 * count + 2.0 * S::RESOLUTION.to_f64() / S::UNITS.torsion;
        let mut worst_naive = 0.0f64;
        for k in 0..64i64 {
            let c = (k * 2047 + 11) % l;
            let counter = (k as u32).wrapping_mul(0x9E37_79B9);
            let r = JointReadings {
                link_count: c as u32,
                motor_counter: counter,
                motor_torque: Some(S::ZERO),
            };
            let mut st = cfg.state(c as u32, counter);
            let m = cfg.measure(&mut st, &r);
            assert!(!m.estimate.invalid_input && !m.counter_jump, "{}", S::NAME);
            let t = m.estimate.flexspline_torsion_si();
            assert!(t.abs() <= tol, "{} count {c}: torsion {t} > {tol}", S::NAME);
            // The start at `N θ_l` (⌊c·M·N/L⌋, link angle in [−π, π)).
            let cc = if c >= l / 2 { c - l } else { c };
            let mut naive = cfg.state_at((cc * mn as i64).div_euclid(l), counter);
            let n = cfg.measure(&mut naive, &r).estimate.flexspline_torsion_si();
            worst_naive = worst_naive.max(n.abs() / count);
        }
        worst_naive
    }
    for worst in [check::<f64>(), check::<f32>(), check::<I16F16>()] {
        assert!(worst > 3.0, "the naive start reads at most {worst} counts");
    }
}

#[test]
fn invalid_readings_are_flagged_and_outputs_stay_finite() {
    fn check<S: Scalar>(bad_torque: Option<S>) {
        let cfg = JointConfig::<S>::new(&firmware_params());
        let mut st = cfg.state_at(0, 0);
        let rest = JointTarget::<S>::default();
        let good = cfg.update(&mut st, &JointReadings::counts(0, 0), &rest);
        assert!(!good.invalid_input);
        let cases = [
            // Link count not below L.
            JointReadings::counts(1 << 17, 0),
            // A counter jump no torsion can produce.
            JointReadings::counts(0, 1 << 30),
            JointReadings {
                link_count: 0,
                motor_counter: 0,
                motor_torque: bad_torque,
            },
        ];
        for (i, r) in cases.iter().enumerate() {
            if i == 2 && bad_torque.is_none() {
                continue;
            }
            let mut s2 = cfg.state_at(0, 0);
            let o = cfg.update(&mut s2, r, &rest);
            assert!(o.invalid_input, "case {i} on {}", S::NAME);
            for v in [
                o.motor_torque,
                o.joint_torque,
                o.motor_position,
                o.motor_velocity,
            ] {
                assert!(!v.is_nan());
            }
        }
    }
    check::<f32>(Some(f32::NAN));
    check::<f64>(Some(f64::INFINITY));
    check::<I16F16>(None);
    // A NaN target on a float backend: flagged, torque 0.
    let cfg = JointConfig::<f32>::new(&firmware_params());
    let mut st = cfg.state_at(0, 0);
    let o = cfg.update(
        &mut st,
        &JointReadings::counts(0, 0),
        &JointTarget::from_si(f64::NAN, 0.0, 0.0),
    );
    assert!(o.invalid_input && o.motor_torque == 0.0);
}

#[test]
fn parameters_are_validated() {
    let p = firmware_params().settings();
    for w in [0u8, MAX_SPEED_WINDOW + 1] {
        let e = JointParams::try_new(JointSettings {
            speed_window: w,
            ..p
        })
        .unwrap_err();
        assert!(
            matches!(
                e,
                ParamError::OutOfRange {
                    name: "speed_window",
                    ..
                }
            ),
            "{e:?}"
        );
    }
    // A drive of ratio 50 under a law designed for N = 100.
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    let half = crate::harmonic_drive::HarmonicDriveParams::try_new(
        drive.flexspline(),
        drive.wave_generator(),
        50.0,
    );
    if let Ok(half) = half {
        let est = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive: half,
            kinematic_error: None,
            link_counts_per_rev: 1 << 17,
            motor_counts_per_rev: 2000,
            max_torque: 60.0,
        })
        .unwrap();
        let e = JointParams::try_new(JointSettings {
            estimator: est,
            ..p
        })
        .unwrap_err();
        assert!(
            matches!(
                e,
                ParamError::OutOfRange {
                    name: "mode.active.ratio",
                    ..
                }
            ),
            "{e:?}"
        );
    } else {
        panic!("a ratio-50 drive should be valid: {half:?}");
    }
    assert!(JointParams::table_4_1().is_ok());
}

/// The signs against the simulated joint (`sim`): holding the link with a
/// push on it, the estimate has the plant's sign and size, the measured
/// motor position is the plant's, and the closed loop holds; a larger push
/// switches to passive and the link then yields in the push's direction.
#[cfg(feature = "sim")]
#[test]
fn signs_match_the_simulated_joint() {
    use crate::control::PassiveSettings;
    use crate::sim::closed_loop::{bound_design, fine_motor_encoder, identified_motor_friction};
    use crate::sim::mrr::{ModuleParams, Mrr};
    let module = fine_motor_encoder(ModuleParams::thesis_joint());
    let mut design = bound_design(1.0);
    design.sample_period = 1e-4;
    let active = RobustAdaptiveParams::try_new(design).unwrap();
    let passive = PassiveParams::try_new(PassiveSettings {
        rotor_inertia: design.rotor_inertia,
        gain: 1.0 / design.rotor_inertia,
        ratio: design.ratio,
        eps_velocity: design.eps_velocity,
        nominal_friction: identified_motor_friction(),
        torque_limit: design.torque_limit,
    })
    .unwrap();
    let mode = ModeParams::try_new(ModeSettings {
        active,
        passive,
        enter_passive: 4.0,
        exit_passive: 1.0,
        debounce: 20,
        dwell: 100,
        rejoin_bandwidth: 10.0,
        bias_time_constant: 0.05,
        collision: None,
    })
    .unwrap();
    let estimator = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive: crate::sim::experiments::Models::shd_17_100().proposed,
        kinematic_error: Some(KinematicErrorModel::table_3_2()),
        link_counts_per_rev: module.link_encoder.counts_per_rev,
        motor_counts_per_rev: module.motor_encoder.counts_per_rev,
        max_torque: 60.0,
    })
    .unwrap();
    let p = JointParams::try_new(JointSettings {
        estimator,
        mode,
        speed_window: 4,
        // The simulated motor, back-driven by the push in Passive, turns
        // faster than the presets' limit; the simulator's counters never
        // jump.
        max_motor_speed: 100.0 * crate::joint::TABLE_4_1_MAX_MOTOR_SPEED,
    })
    .unwrap();
    let cfg = JointConfig::<f64>::new(&p);
    let mut robot = Mrr::try_new(std::vec![module.clone()], [0.0, 0.0, -9.81], 1e-4, 1, 3).unwrap();
    let s = robot.read_sensors();
    let l = module.link_encoder.counts_per_rev as i64;
    // Started at the plant's motor position (the initial torsion is not
    // zero, so `state`'s zero-torsion start would offset the estimate).
    let mut st = cfg.state_at(s.motor_counts[0], s.motor_counts[0] as u32);
    let hold = JointTarget::from_si(0.0, 0.0, 0.0);
    let push = |t: f64| {
        if t < 0.5 {
            0.0
        } else if t < 1.5 {
            2.0
        } else {
            6.0
        }
    };
    let (mut est_err, mut pos_err, mut max_q) = (0.0f64, 0.0f64, 0.0f64);
    let mut passive_at = None;
    let mut sums = [0.0f64; 3];
    for k in 0..25_000 {
        let t = k as f64 * 1e-4;
        let s = robot.read_sensors();
        let r = JointReadings::counts(
            s.link_counts[0].rem_euclid(l) as u32,
            s.motor_counts[0] as u32,
        );
        let o = cfg.update(&mut st, &r, &hold);
        assert!(!o.invalid_input);
        if (0.8..1.5).contains(&t) {
            // Held against a 2 N·m push: τ_t = −2 N·m on the link.
            est_err = est_err.max((o.joint_torque - robot.transmission_torques()[0]).abs());
            pos_err = pos_err.max((o.motor_position - robot.motor_angles()[0]).abs());
            max_q = max_q.max(robot.link_angles()[0].abs());
            assert_eq!(o.mode, JointMode::Active);
        }
        if (1.6..2.5).contains(&t) {
            sums[0] += o.joint_torque;
            sums[1] += robot.transmission_torques()[0];
            sums[2] += 1.0;
        }
        if o.mode == JointMode::Passive && passive_at.is_none() {
            passive_at = Some(t);
        }
        robot.set_motor_torque(&[o.motor_torque]);
        robot.external_torque[0] = push(t);
        robot.step();
    }
    // The drive holds the push (its torque on the link about −1.5 N·m, the
    // link's friction taking the rest) and the estimate is within the
    // estimator's static error (the drive's hysteresis, errata E2.9).
    assert!(est_err < 2.5, "estimate error {est_err}");
    assert!(pos_err < 2.0 * TAU / 65536.0, "position error {pos_err}");
    assert!(max_q < 0.01, "held link moved {max_q} rad");
    // The 6 N·m push switches to passive and the link yields forward.
    let t = passive_at.expect("switched to passive");
    assert!((1.5..1.6).contains(&t), "switched at {t}");
    assert!(
        robot.link_angles()[0] > 0.1,
        "link at {}",
        robot.link_angles()[0]
    );
    // While the hand pushes the free joint, the drive resists it (τ_t < 0)
    // and the estimate says so, in sign and size.
    let (est, truth) = (sums[0] / sums[2], sums[1] / sums[2]);
    assert!(
        truth < -3.0 && est < -3.0,
        "mean estimate {est}, true {truth}"
    );
    assert!(
        (est - truth).abs() < 1.0,
        "mean estimate {est}, true {truth}"
    );
}

/// The default passive gain `K_p = 1/Î_m` keeps the sampled passive loop
/// (errata E4.12) stable for a light and a heavy link, a soft and a stiff
/// hand, from 0.1 ms to 10 ms; twice the limit gain `1 + J₀/I_l` (the
/// same analysis) is unstable, so the check can fail.
#[test]
fn default_passive_gain_is_stable_when_sampled() {
    use crate::control::HandContact;
    let p = PassiveParams::table_4_1_default().unwrap();
    let im = crate::control::RobustAdaptiveDesign::table_4_1().rotor_inertia;
    assert!((p.gain() * im - 1.0).abs() < 1e-12);
    for link_inertia in [0.01, 0.043, 1.0] {
        for (stiffness, damping) in [(0.0, 0.0), (200.0, 5.0), (2000.0, 1.0)] {
            let hand = HandContact {
                stiffness,
                damping,
                link_inertia,
            };
            for t in [1e-4, 1e-3, 4e-3, 1e-2] {
                let c = p.characteristics(&hand, t).unwrap();
                assert!(
                    c.spectral_radius <= 1.0 + 1e-9,
                    "{link_inertia} {stiffness} {t}: {c:?}"
                );
            }
        }
    }
    // A gain far above the limit 1 + J0/I_l (J0 = N² Î_m = 0.114) on a
    // 0.043 kg·m² link is unstable in the same analysis.
    let limit = 1.0 + 100.0 * 100.0 * im / 0.043;
    let hot = PassiveParams::table_4_1(2.0 * limit / im).unwrap();
    let hand = HandContact {
        stiffness: 0.0,
        damping: 0.0,
        link_inertia: 0.043,
    };
    assert!(hot.characteristics(&hand, 4e-3).unwrap().spectral_radius > 1.0);
}

/// A state resumed with a mode state reached elsewhere steps exactly as the
/// joint that reached it.
#[test]
fn with_mode_state_resumes_the_manager() {
    let cfg = JointConfig::<f32>::new(&firmware_params());
    let mut a = cfg.state_at(0, 0);
    let push = JointReadings::counts(0, 30); // ≈ 7 N·m of torsion
    for _ in 0..8 {
        cfg.update(&mut a, &push, &JointTarget::default());
    }
    assert_ne!(a.mode(), JointMode::Active);
    let mut b = cfg.state_at(30, 30).with_mode_state(*a.mode_state());
    let mut a2 = a;
    let ra = cfg.update(&mut a2, &push, &JointTarget::default());
    let rb = cfg.update(&mut b, &push, &JointTarget::default());
    assert_eq!(ra.control, rb.control);
    assert_eq!(ra.estimate, rb.estimate);
}

/// The largest accepted window is `MAX_SPEED_WINDOW` (inclusive bound of
/// `JointSettings::speed_window`), the next is rejected naming the field,
/// and the smallest accepted is 1; an accepted window is the one used
/// (the speed resolution `2π/(M w T)`).
#[test]
fn speed_window_bounds_are_inclusive() {
    let p = firmware_params().settings();
    let with = |w: u8| {
        JointParams::try_new(JointSettings {
            speed_window: w,
            ..p
        })
    };
    for w in [1, 2, MAX_SPEED_WINDOW - 1, MAX_SPEED_WINDOW] {
        let j = with(w).unwrap_or_else(|e| panic!("window {w} rejected: {e:?}"));
        let want = TAU / (2000.0 * w as f64 * 0.004);
        assert!((j.speed_resolution() - want).abs() < 1e-12 * want, "{w}");
    }
    for w in [0, MAX_SPEED_WINDOW + 1, u8::MAX] {
        match with(w) {
            Err(ParamError::OutOfRange { name, value, .. }) => {
                assert_eq!((name, value), ("speed_window", w as f64));
            }
            other => panic!("window {w}: {other:?}"),
        }
    }
}

use crate::test_support::Stored;

/// `got` equals `stored` times its unit, and is none of 0, 1, −1 (so a
/// reader replaced by a constant cannot pass).
fn conv<S: Stored>(name: &str, got: f64, stored: S, motor: bool) -> f64 {
    let want = stored.stored() * S::unit(motor);
    assert!(
        [0.0, 1.0, -1.0].iter().all(|c| (want - c).abs() > 1e-7),
        "{} {name}: trivial value {want}",
        S::NAME
    );
    assert!(
        (got - want).abs() <= 1e-12 * want.abs(),
        "{} {name}: reader {got}, stored × unit {want}",
        S::NAME
    );
    got
}

/// The Table 4.1 joint at rest at count 0, then one tick with the motor
/// counter 10 counts ahead (a torsion; a speed of 10·2π/(2000·4 ms)) and
/// a target 0.5 rad ahead (the law saturates): the seven readers of
/// `JointOutput` and `JointMeasurement`, and the estimate's flexspline
/// torsion (rad, for the agreement bound).
fn si_tick<S: Stored>() -> ([f64; 7], f64) {
    let p = JointParams::table_4_1().unwrap();
    let cfg = JointConfig::<S>::new(&p);
    let readings = JointReadings {
        link_count: 0,
        motor_counter: 10,
        motor_torque: Some(S::ZERO),
    };
    let mut st = cfg.state_at(0, 0);
    let out = cfg.update(&mut st, &readings, &JointTarget::from_si(0.5, 0.0, 0.0));
    assert!(out.control.saturated && !out.invalid_input, "{out:?}");
    let mut st = cfg.state_at(0, 0);
    let m = cfg.measure(&mut st, &readings);
    let o = &out;
    (
        [
            conv(
                "JointOutput::motor_torque_si",
                o.motor_torque_si(),
                o.motor_torque,
                true,
            ),
            conv(
                "JointOutput::joint_torque_si",
                o.joint_torque_si(),
                o.joint_torque,
                false,
            ),
            conv(
                "JointOutput::motor_position_si",
                o.motor_position_si(),
                o.motor_position,
                false,
            ),
            conv(
                "JointOutput::motor_velocity_si",
                o.motor_velocity_si(),
                o.motor_velocity,
                false,
            ),
            conv(
                "JointMeasurement::joint_torque_si",
                m.joint_torque_si(),
                m.joint_torque,
                false,
            ),
            conv(
                "JointMeasurement::motor_position_si",
                m.motor_position_si(),
                m.motor_position,
                false,
            ),
            conv(
                "JointMeasurement::motor_velocity_si",
                m.motor_velocity_si(),
                m.motor_velocity,
                false,
            ),
        ],
        o.estimate.flexspline_torsion.to_f64() / S::UNITS.torsion,
    )
}

/// Every SI reader of the joint on every backend: the stored value times
/// its unit, and, physically, the `f64` tick computed independently and
/// the other backends within their documented bounds of it.
#[test]
fn si_readers_are_the_stored_value_in_si_on_every_backend() {
    let (a, dtheta_f) = si_tick::<f64>();
    // Independent: q_m = 10·2π/2000 rad, q̇_m = q_m/T (one-tick window),
    // the command at the +0.188 N·m limit of Table 4.1, and the joint
    // torque of eq. (3.9)–(3.10) as the module example computes it.
    let qm = 10.0 * TAU / 2000.0;
    for (i, want) in [
        (0, 0.188),
        (2, qm),
        (3, qm / 0.004),
        (5, qm),
        (6, qm / 0.004),
    ] {
        assert!((a[i] - want).abs() < 1e-9, "{i}: {} vs {want}", a[i]);
    }
    let drive = CatalogueData::SHD_17_100.identify().unwrap();
    let ke = KinematicErrorModel::table_3_2();
    let theta_wi = -qm;
    let f = drive.flexspline();
    let tau_t =
        -(f.c_f() * f.k_f0() * (theta_wi / 100.0 - ke.evaluate(0.0, theta_wi))).tan() / f.c_f();
    assert!(tau_t > 1.0, "{tau_t}");
    for i in [1, 4] {
        assert!((a[i] - tau_t).abs() < 1e-3 * tau_t, "{} vs {tau_t}", a[i]);
    }
    let est = JointParams::table_4_1().unwrap().settings().estimator;
    for (b, bound, lsb) in [
        (si_tick::<f32>().0, est.agreement_bound::<f32>(), 0.0),
        (
            si_tick::<I16F16>().0,
            est.agreement_bound::<I16F16>(),
            libm::exp2(-16.0),
        ),
    ] {
        // Estimated torque: the documented agreement interval (estimator
        // sign, so negated) at the f64 flexspline torsion.
        let (lo, hi) = bound.torque_interval(&est, dtheta_f);
        for i in [1, 4] {
            assert!(
                lo <= -b[i] && -b[i] <= hi,
                "{i}: {} not in [{lo}, {hi}]",
                -b[i]
            );
        }
        // Counts times 2π/M (2π/(M w T)), rounded once: one LSB on
        // I16F16, f32's relative rounding.
        for i in [2, 3, 5, 6] {
            assert!(
                (b[i] - a[i]).abs() <= lsb + 1e-6 * a[i].abs(),
                "{i}: {} vs {}",
                b[i],
                a[i]
            );
        }
        // The saturated command: the limit, quantized once.
        assert!((b[0] - a[0]).abs() < 1e-7, "{} vs {}", b[0], a[0]);
    }
}

/// The hold point read in the target's frame is the stored one moved by
/// the whole output revolutions `2πN` between the frame it was stored in
/// and the target's (expected values from `f64` here), on `I16F16` by at
/// most the turns its angle holds (`⌊32 768/(200π)⌋ = 52` at `N = 100`),
/// however many turn changes came between: back at the stored frame it is
/// the stored point again. A target outside the frame moves nothing.
#[test]
fn turn_changes_move_the_hold_point_by_whole_revolutions() {
    fn run<S: Scalar>(turns: &[(i32, i64, bool)], tol: f64) -> f64 {
        let p = firmware_params();
        let cfg = JointConfig::<S>::new(&p);
        let mn = cfg.motor_counts_per_output_rev;
        let mut st = cfg.state_at(0, 0);
        // The hold point of the initial state, stored in frame 0.
        let mut want = 0.0;
        for &(t, rev_from_origin, flagged) in turns {
            // The motor `rev_from_origin` output revolutions from the
            // target's whole turns, the link where zero torsion puts it.
            let counts = (t as i64 + rev_from_origin) * mn;
            st.motor_count = counts;
            st.last_counter = counts as u32;
            let target = JointTarget::<S> {
                turns: t,
                ..JointTarget::default()
            };
            let out = cfg.update(&mut st, &JointReadings::counts(0, counts as u32), &target);
            assert_eq!(out.invalid_input, flagged, "{t}: {out:?}");
            if !flagged {
                let whole = if S::FLOAT { t } else { t.clamp(-52, 52) };
                want = -(whole as f64) * TAU * 100.0;
            }
            let got = cfg.mode.hold_point(&st.mode).to_f64();
            assert!(
                (got - want).abs() <= tol * want.abs().max(1.0),
                "{t}: {got} vs {want}"
            );
        }
        want
    }
    let f64_turns = [
        (1, 0, false),
        (3, 0, false),
        (-2, 0, false),
        (7, 1 << 40, true),
    ];
    let two_revs = 2.0 * TAU * 100.0;
    assert!((run::<f64>(&f64_turns, 1e-12) - two_revs).abs() < 1e-9);
    assert!((run::<f32>(&f64_turns[..3], 1e-6) - two_revs).abs() < 1e-9);
    // I16F16: 60 and 59 turns from the stored frame move the hold point
    // by 52; back in the stored frame it is where it was stored.
    let i_turns = [(60, 0, false), (59, 0, false), (62, 100, true)];
    let want = run::<I16F16>(&i_turns, 1e-6);
    assert!((want + 52.0 * TAU * 100.0).abs() < 1e-9);
    let round_trip = [(60, 0, false), (59, 0, false), (0, 0, false)];
    assert_eq!(run::<I16F16>(&round_trip, 1e-6), 0.0);
}

/// In Hold (a collision latched under `CollisionReaction::Stop`) the law
/// holds the hold point in the target's frame: the reference of each
/// tick is the point where the joint stopped, in the frame of the target
/// it stopped under (`t0` whole turns), minus `2πN` per whole turn of the
/// target since (expected values from `f64`), through turn changes there
/// and back.
#[test]
fn hold_reference_follows_the_target_frame() {
    fn run<S: Scalar>(t0: i32, turns: &[i32], tol: f64) {
        let p = firmware_params();
        let cfg = JointConfig::<S>::new(&p);
        // The link at π/4 (2¹⁷/8 counts), the motor at N times it
        // (25 000 counts, zero torsion), at rest.
        let (link, counts) = (1u32 << 14, 25_000u32);
        let mut st = cfg.state_at(counts as i64, counts);
        let readings = JointReadings::counts(link, counts);
        // An expected joint torque 10 N·m away from the estimate: a
        // collision (threshold 4 N·m), and the joint stops.
        let mut target = JointTarget::<S> {
            turns: t0,
            expected_joint_torque: S::from_f64(10.0),
            ..JointTarget::default()
        };
        let mut out = cfg.update(&mut st, &readings, &target);
        for _ in 0..10 {
            if out.mode == JointMode::Hold {
                break;
            }
            out = cfg.update(&mut st, &readings, &target);
        }
        assert_eq!(out.mode, JointMode::Hold, "{out:?}");
        assert_eq!(st.motor_position_counts(), counts as i64);
        let rev = TAU * 100.0;
        let stored = counts as f64 * TAU / 2000.0 - t0 as f64 * rev;
        let got = out.control.reference_position.to_f64();
        assert!(
            (got - stored).abs() <= tol * 20.0 * rev,
            "{got} vs {stored}"
        );
        for &t in turns {
            target.turns = t;
            let out = cfg.update(&mut st, &readings, &target);
            assert!(!out.invalid_input, "{t}: {out:?}");
            assert_eq!(out.mode, JointMode::Hold);
            let want = stored - (t - t0) as f64 * rev;
            let got = out.control.reference_position.to_f64();
            // (Within `tol` of the largest hold point visited, 20
            // revolutions: `f32` rounds each move.)
            assert!(
                (got - want).abs() <= tol * 20.0 * rev,
                "{t}: {got} vs {want}"
            );
        }
    }
    // Within every backend's frame (I16F16: 26 output revolutions, f32:
    // 20 at M = 2000).
    let turns = [1, 3, -2, 0, 20, 19, 0, 2];
    for t0 in [0, 2] {
        run::<f64>(t0, &turns, 1e-12);
        run::<f32>(t0, &turns, 1e-6);
        run::<I16F16>(t0, &turns, 1e-6);
    }
}
