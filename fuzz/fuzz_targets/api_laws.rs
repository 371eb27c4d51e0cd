//! The control-law parameter types built from raw fields, then every law
//! run on arbitrary samples on `f32`, `f64` and `I16F16`: the robust
//! adaptive law (eq. 4.19, `RobustAdaptiveParams`), the passive law
//! (eq. 4.32, `PassiveSettings`), the mode manager with collision detection
//! (`ModeSettings`, `CollisionSettings`), the joint (`JointSettings`: raw
//! counts → estimate → mode manager), the estimator's radian path
//! (`TorqueEstimatorSettings`, `update_radians`) and the wrist's admittance
//! law (`AdmittanceSettings`, eq. 6.32).
//!
//! The joint also runs multi-turn sequences (a motor up to ±2²⁰ output
//! revolutions out, turning within its speed limit, readings and SI target
//! consistent with it; a whole-revolution counter jump that stays), with
//! the target's whole turns drawn raw, and `max_motor_speed` scaled or
//! raw. Laws: no panic, no NaN or ∞ output, the torque within its limit,
//! the state readers finite (the last command within the limit), a counter
//! move beyond the speed limit flagged and left out of the position and
//! every other move counted exactly, the motor position in the target's
//! frame within half an output revolution, and — for the table's
//! parameters and a link encoder of at least 2¹⁴ counts — no tick of a
//! multi-turn sequence flagged.
//!
//! Asserted, for every input: a typed error (its message names the
//! parameter in backticks), or finite outputs within their stated range
//! with the flags telling the truth (`invalid_input` exactly when a float
//! input is NaN or infinite; a flagged step returns 0 and leaves the state
//! alone; `saturated` exactly when the limit cut the law).
//!
//! For accepted parameters drawn near the thesis's tables (each field
//! scaled by a factor in `[1/4, 4]`, not from raw bits) and samples in the
//! physical domain (below), each backend's SI output is compared with the
//! `f64` output on the same stored inputs (so a silent 0 or a factor of
//! 1000 fails):
//! * robust adaptive law: within `proofs::law_budget::law_error_budget`,
//!   the first-order budget of the law's own backend-agreement test
//!   (`backends_agree_within_the_derived_budget`), the `f64` law evaluated
//!   with the backend's quantized design and state, plus the rounding of
//!   the torque limit;
//! * passive law (the `f64` law with the backend's quantized friction and
//!   boundary layer): the bound of its own agreement test
//!   (`bounded_and_backends_agree`) generalised to the drawn parameters:
//!   `I16F16` within `(40 + 4(f_c + f_s)) LSB` of mN·m (4 LSB per stored
//!   product, the `sat` quotient's half LSB times the sliding level, the
//!   `exp` kernel) plus `2⁻²⁶` of the sum of the terms' magnitudes
//!   (31-bit coefficients); `f32` within 16 ulp of the largest term;
//! * `update_radians`: within the estimator's `AgreementBound`
//!   (`torque_interval`), its torsion widened by what the radian path adds
//!   to the count path: in `I16F16` one angle LSB (`2⁻¹⁶` rad: the
//!   rounding of `θ_wi/N` and of the scaling to torsion units) and
//!   `2⁻¹⁰` of the kinematic-error amplitude (the `sin_cos` kernel's phase
//!   error on the stored angles); in `f32`, `2⁻²⁰(|θ_fo| + |θ_wi|/N)` and
//!   `2⁻¹⁹(|θ_fo| + |θ_wi| + 1)` of the amplitude (four roundings of each
//!   angle, the phase error of the angle's own rounding).
//!
//! The physical domain of the compared samples: `|q|, |q_d| ≤ 100` rad,
//! `|e| ≤ 1` rad, `|q̇|, |q̇_d| ≤ 100` rad/s, `|q̈_d| ≤ 2000` rad/s²,
//! joint torques `≤ 20` N·m (the ranges of the laws' own agreement tests,
//! widened). At most 16 samples per input keep an execution cheap.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::control::{
    ControlInput, ModeConfig, ModeParams, ModeSettings, PassiveConfig, PassiveParams,
    PassiveSettings, RobustAdaptiveConfig, RobustAdaptiveDesign, RobustAdaptiveParams,
    RobustAdaptiveState,
};
use mrr_control::estimation::{
    CollisionParams, CollisionReaction, CollisionSettings, TorqueEstimatorConfig,
    TorqueEstimatorParams, TorqueEstimatorSettings,
};
use mrr_control::friction::{FrictionConfig, FrictionParams};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::joint::{
    JointConfig, JointParams, JointReadings, JointSettings, JointState, JointTarget,
};
use mrr_control::proofs::law_budget::law_error_budget;
use mrr_control::scalar::units::quantize_keep_non_finite;
use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::wrist::admittance::{AdmittanceConfig, AdmittanceParams, AdmittanceSettings};
use mrr_control::ParamError;

/// A field: the raw bits as an `f64` when `raw`, else `base` times a
/// factor log-uniform in `[1/4, 4]`.
fn field(bits: u64, raw: bool, base: f64) -> f64 {
    if raw {
        return f64::from_bits(bits);
    }
    let frac = (bits >> 11) as f64 / (1u64 << 53) as f64;
    base * 16f64.powf(frac) / 4.0
}

/// A rejected parameter: its message names something in backticks.
fn typed(e: ParamError) {
    let s = e.to_string();
    assert!(s.contains('`') && s.len() > 10, "{s}");
}

/// One sample in SI from fuzz data: each field `i·2⁻¹⁶·2⁻ᵏ` (`k` from
/// `scales`, 0..7: up to ±32 768), or raw `f64` bits for field `j` when
/// `raw & 1 << j` (NaN, ±∞, huge).
fn sample(v: &[i32; 8], scales: u32, raw: u8, bits: u64) -> ControlInput<f64> {
    let f = |j: usize| {
        if raw & (1 << j) != 0 {
            f64::from_bits(bits.rotate_left(8 * j as u32))
        } else {
            v[j] as f64 / 65536.0 / (1u32 << ((scales >> (3 * j)) & 7)) as f64
        }
    };
    ControlInput {
        desired_position: f(0),
        desired_velocity: f(1),
        desired_acceleration: f(2),
        motor_position: f(0) + v[3] as f64 / 2f64.powi(31),
        motor_velocity: f(4),
        joint_torque: f(5),
        desired_joint_torque: f(6),
        expected_joint_torque: f(7),
    }
}

fn all_finite(x: &ControlInput<f64>) -> bool {
    [
        x.desired_position,
        x.desired_velocity,
        x.desired_acceleration,
        x.motor_position,
        x.motor_velocity,
        x.joint_torque,
        x.desired_joint_torque,
        x.expected_joint_torque,
    ]
    .iter()
    .all(|v| v.is_finite())
}

/// The domain where the backends are compared (module docs).
fn physical(x: &ControlInput<f64>) -> bool {
    all_finite(x)
        && x.desired_position.abs() <= 100.0
        && x.motor_position.abs() <= 100.0
        && (x.motor_position - x.desired_position).abs() <= 1.0
        && x.desired_velocity.abs() <= 100.0
        && x.motor_velocity.abs() <= 100.0
        && x.desired_acceleration.abs() <= 2000.0
        && x.joint_torque.abs() <= 20.0
        && x.desired_joint_torque.abs() <= 20.0
        && x.expected_joint_torque.abs() <= 20.0
}

/// Eq. (4.19) on backend `S` over the samples: invariants always; against
/// `f64` within the law's budget when `compare` and the sample is physical.
fn active<S: Scalar>(p: &RobustAdaptiveParams, xs: &[ControlInput<f64>], compare: bool) {
    let cfg = RobustAdaptiveConfig::<S>::new(p);
    let limit = cfg.torque_limit_si();
    let reference = RobustAdaptiveParams::try_new(cfg.quantized_design())
        .ok()
        .map(|q| RobustAdaptiveConfig::<f64>::new(&q));
    let mut st = cfg.initial_state();
    for x in xs {
        let xq = ControlInput::<S>::from_si(x);
        let before = st;
        let o = cfg.update(&mut st, &xq);
        assert!(!o.torque.is_nan() && o.torque_si().abs() <= limit, "{o:?}");
        assert!(!st.integral().is_nan() && st.integral().abs() <= cfg.integral_limit());
        for j in 0..4 {
            let f = st.friction()[j];
            assert!(
                f >= cfg.lower_bounds()[j] && f <= cfg.upper_bounds()[j],
                "{st:?}"
            );
        }
        if S::NAME != "I16F16" && !all_finite(x) {
            assert!(o.invalid_input, "{} {x:?} {o:?}", S::NAME);
        }
        if o.invalid_input {
            assert!(o.torque == S::ZERO && st == before, "{o:?}");
            continue;
        }
        assert_eq!(o.saturated, o.torque != o.law_torque, "{o:?}");
        let Some(c64) = reference.as_ref().filter(|_| compare && physical(x)) else {
            continue;
        };
        // The same state in SI, kept in the box that the reference
        // validates against (dequantizing can leave it by a rounding).
        let d = c64.params().design();
        let (lo, hi) = (d.friction_bounds.min(), d.friction_bounds.max());
        let f = before.friction_si().to_array();
        let f = FrictionParams::from_array(core::array::from_fn(|j| f[j].clamp(lo[j], hi[j])));
        let z = before
            .integral_si()
            .clamp(-d.integral_limit, d.integral_limit);
        let mut st64: RobustAdaptiveState<f64> = c64.state(f, z).expect("a state inside the box");
        let a = c64.update(&mut st64, &xq.to_si());
        let tol = law_error_budget(&cfg, &before, &xq) + (c64.torque_limit() - limit).abs();
        assert!(
            (o.torque_si() - a.torque).abs() <= tol,
            "active {}: {} vs f64 {} (tol {tol}) {x:?} {p:?}",
            S::NAME,
            o.torque_si(),
            a.torque
        );
    }
}

/// Eq. (4.32) on backend `S`: invariants; against `f64` (the backend's
/// quantized nominal friction) when `compare`.
fn passive<S: Scalar>(p: &PassiveParams, xs: &[ControlInput<f64>], compare: bool) {
    let cfg = PassiveConfig::<S>::new(p);
    let limit = cfg.torque_limit_si();
    let mut s = p.settings();
    let f = FrictionConfig::<S>::dequantize(&FrictionConfig::<S>::quantize(&s.nominal_friction));
    s.nominal_friction = f;
    // The boundary layer as the backend quantized it.
    s.eps_velocity = FrictionConfig::<S>::new(s.eps_velocity)
        .eps_velocity()
        .to_f64()
        / S::UNITS.speed;
    let reference = PassiveParams::try_new(s)
        .ok()
        .map(|q| PassiveConfig::<f64>::new(&q));
    for x in xs {
        let xq = ControlInput::<S>::from_si(x);
        let o = cfg.update(&xq);
        assert!(!o.torque.is_nan() && o.torque_si().abs() <= limit, "{o:?}");
        if S::NAME != "I16F16" && !all_finite(x) {
            assert!(o.invalid_input);
        }
        if o.invalid_input {
            assert!(o.torque == S::ZERO);
            continue;
        }
        assert_eq!(o.saturated, o.torque != o.law_torque, "{o:?}");
        let Some(c64) = reference.as_ref().filter(|_| compare && physical(x)) else {
            continue;
        };
        let xs64 = xq.to_si();
        let a = c64.update(&xs64);
        let (qd, tau, tau_d) = (
            xs64.motor_velocity,
            xs64.joint_torque,
            xs64.desired_joint_torque,
        );
        let n = p.ratio();
        let gain = p.rotor_inertia() * p.gain();
        let sliding = f.coulomb + f.stribeck;
        let terms = (f.viscous * qd).abs()
            + sliding
            + (tau / n).abs()
            + gain * (tau_d.abs() + tau.abs()) / n;
        let tol = if S::NAME == "I16F16" {
            let lsb = 1.0 / 65536.0;
            (lsb * (40.0 + 4.0 * sliding * 1e3) + 2f64.powi(-26) * terms * 1e3) / 1e3
        } else {
            16.0 * f32::EPSILON as f64 * (terms + a.law_torque.abs())
        } + (c64.torque_limit() - limit).abs();
        assert!(
            (o.torque_si() - a.torque).abs() <= tol,
            "passive {}: {} vs f64 {} (tol {tol}) {x:?} {p:?}",
            S::NAME,
            o.torque_si(),
            a.torque
        );
    }
}

/// The mode manager: invariants and truthful flags.
fn mode<S: Scalar>(p: &ModeParams, xs: &[ControlInput<f64>], ack: u8) {
    let cfg = ModeConfig::<S>::new(p);
    let limit = cfg.torque_limit_si();
    let mut st = cfg.initial_state();
    for (k, x) in xs.iter().enumerate() {
        if k as u8 == ack {
            cfg.acknowledge_collision(&mut st);
        }
        let xq = ControlInput::<S>::from_si(x);
        let o = cfg.update(&mut st, &xq);
        assert!(!o.torque.is_nan() && o.torque_si().abs() <= limit, "{o:?}");
        assert!(
            !o.interaction.is_nan() && !o.reference_position.is_nan(),
            "{} {x:?} {o:?}",
            S::NAME
        );
        if S::NAME != "I16F16" && !all_finite(x) {
            assert!(o.invalid_input, "{x:?} {o:?}");
        }
    }
}

/// The state readers after a step: finite SI values, the last command
/// within the limit.
fn readers_finite<S: Scalar>(st: &JointState<S>, limit: f64) {
    let a = st.active_state();
    let f = a.friction_si();
    for v in [
        f.viscous,
        f.coulomb,
        f.stribeck,
        f.stribeck_shape,
        a.integral_si(),
    ] {
        assert!(v.is_finite(), "{a:?}");
    }
    assert!(st.mode_state().bias_si().is_finite());
    let c = st.last_command_si();
    assert!(c.is_finite() && c.abs() <= limit, "{c}");
}

/// The most counts one tick may move under the joint's speed limit,
/// computed here from the settings: `⌊ω_max·T·M/(2π)⌋ + 1`.
fn max_counts_per_tick(p: &JointParams) -> u64 {
    let s = p.settings();
    let m = s.estimator.motor_counts_per_rev() as f64;
    (s.max_motor_speed * p.sample_period() * m / std::f64::consts::TAU) as u64 + 1
}

/// The joint from raw counts: invariants and truthful flags. With
/// `target[3]` as the target's whole turns when `turns` is set.
fn joint<S: Scalar>(
    p: &JointParams,
    readings: &[(u32, u32, u64, u8)],
    target: &[i32; 8],
    turns: bool,
) {
    let cfg = JointConfig::<S>::new(p);
    let limit = cfg.mode().torque_limit_si();
    let first = readings.first().map_or((0, 0), |r| (r.0, r.1));
    let mut st = cfg.state(first.0, first.1);
    let mut t = JointTarget::<S>::from_si(
        target[0] as f64 / 65536.0,
        target[1] as f64 / 65536.0,
        target[2] as f64 / 65536.0,
    );
    if turns {
        t.turns = target[3];
    }
    let max_counts = max_counts_per_tick(p);
    let mut last = first.1;
    for &(link, motor, tau, k) in readings {
        let motor_torque = match k & 3 {
            0 => None,
            1 => Some(f64::from_bits(tau)),
            _ => Some((tau >> 11) as f64 / (1u64 << 53) as f64 - 0.5),
        };
        let r = JointReadings::<S> {
            link_count: link,
            motor_counter: motor,
            motor_torque: motor_torque
                .map(|v| quantize_keep_non_finite::<S>(v, S::UNITS.motor_torque)),
        };
        let before = st.motor_position_counts();
        let o = cfg.update(&mut st, &r, &t);
        assert!(o.motor_torque_si().is_finite() && o.motor_torque_si().abs() <= limit);
        assert!(o.joint_torque_si().is_finite() && o.motor_velocity_si().is_finite());
        assert!(o.motor_position_si().is_finite());
        let bad_torque = motor_torque.is_some_and(|v| !v.is_finite());
        if S::NAME != "I16F16" && bad_torque {
            assert!(o.invalid_input, "{o:?}");
        }
        // A counter move beyond the speed limit is flagged and left out
        // of the position; one within it is counted.
        let moved = motor.wrapping_sub(last) as i32;
        last = motor;
        if moved.unsigned_abs() as u64 > max_counts {
            assert!(o.invalid_input && o.control.invalid_input, "{o:?}");
            assert_eq!(st.motor_position_counts(), before);
        } else {
            assert_eq!(st.motor_position_counts(), before + moved as i64);
        }
        // A flagged joint step took the mode manager's invalid path.
        assert!(!o.invalid_input || o.control.invalid_input, "{o:?}");
        readers_finite(&st, limit);
    }
}

/// The link count and the SI target of a joint whose motor is at `c`
/// counts with no torsion, turning `step` counts per tick: the link at
/// `c·L/(M·N)` counts, the target the link angle `2π·c/(M·N)` (whole turns
/// split off in `i64`, so `from_si` gets the angle to `f64` rounding).
fn consistent<S: Scalar>(p: &JointParams, c: i64, step: i64) -> (u32, JointTarget<S>) {
    let s = p.settings();
    let l = s.estimator.link_counts_per_rev() as i128;
    let mn = s.estimator.motor_counts_per_rev() as i64 * p.ratio() as i64;
    let link = (c as i128 * l).div_euclid(mn as i128).rem_euclid(l) as u32;
    let tau = std::f64::consts::TAU;
    let qd = (c.div_euclid(mn) as f64 + c.rem_euclid(mn) as f64 / mn as f64) * tau;
    let vd = step as f64 * tau / (mn as f64 * p.sample_period());
    (link, JointTarget::from_si(qd, vd, 0.0))
}

/// A joint turning continuously far from its start: the motor at
/// `start_turns` output revolutions (up to ±2²⁰) plus a fraction, moving
/// `step` counts per tick (within the speed limit), the link count and the
/// SI target consistent with it ([`consistent`]). The position is counted
/// exactly, the motor position in the target's frame stays within half an
/// output revolution at the motor, and with the table's estimator and
/// laws (`sane`) and a link encoder of at least 2¹⁴ counts no tick is
/// flagged. At the middle tick a whole-revolution
/// jump of `jump` output revolutions that stays: flagged when its wrapping
/// 32-bit move exceeds the limit, the position held, the next ticks
/// counted from the held position (and, `sane`, not flagged).
fn joint_multi_turn<S: Scalar>(
    p: &JointParams,
    start_turns: i32,
    step: i32,
    ticks: usize,
    jump: i32,
    sane: bool,
) {
    let cfg = JointConfig::<S>::new(p);
    let limit = cfg.mode().torque_limit_si();
    let s = p.settings();
    let m = s.estimator.motor_counts_per_rev() as i64;
    let n = p.ratio();
    let mn = m * n as i64;
    let max_counts = max_counts_per_tick(p) as i64;
    let step = step as i64 % (max_counts + 1);
    // A link encoder coarser than 2¹⁴ counts quantizes the torsion past
    // what the drive can twist (one count 3.8e-4 rad at 2¹⁴; 6.1e-3 rad at
    // 2¹⁰, beyond a torsion range of about 4.6e-3 rad): the estimator's
    // flag is then the truth, not a false one.
    let sane = sane && s.estimator.link_counts_per_rev() >= 1 << 14;
    let start_turns = (start_turns >> 11) as i64;
    let start = start_turns * mn + start_turns.rem_euclid(mn);
    let counter0 = start as u32 ^ 0x5a5a_5a5a;
    let mut st = cfg.state_at(start, counter0);
    let jump_at = ticks as i64 / 2;
    let offset = (jump as i64).wrapping_mul(mn) as u32;
    // `held` counts the ticks the joint rejected (none or the jump's).
    let mut held = 0i64;
    for k in 0..ticks as i64 {
        let jumped = jump != 0 && k >= jump_at;
        let counter = counter0
            .wrapping_add((k * step) as u32)
            .wrapping_add(if jumped { offset } else { 0 });
        // The joint's own count: what it should hold.
        let c = start + (k - held) * step;
        let (link, target) = consistent::<S>(p, c, step);
        let before = st.motor_position_counts();
        let o = cfg.update(&mut st, &JointReadings::counts(link, counter), &target);
        assert!(o.motor_torque_si().is_finite() && o.motor_torque_si().abs() <= limit);
        assert!(o.joint_torque_si().is_finite() && o.motor_velocity_si().is_finite());
        assert!(o.motor_position_si().is_finite());
        readers_finite(&st, limit);
        let seen = (offset.wrapping_add(step as u32) as i32).unsigned_abs() as i64;
        if jump != 0 && k == jump_at {
            if seen > max_counts {
                assert!(o.invalid_input && o.control.invalid_input, "{o:?}");
                assert_eq!(o.motor_torque_si(), 0.0);
                assert_eq!(st.motor_position_counts(), before);
                held = 1;
                continue;
            }
            // A jump the 32-bit difference cannot tell from motion.
            return;
        }
        assert_eq!(st.motor_position_counts(), c, "{o:?}");
        let half = 0.5 * std::f64::consts::TAU * n + 2.0 * std::f64::consts::TAU / m as f64;
        assert!(o.motor_position_si().abs() <= half, "{o:?}");
        if sane {
            assert!(!o.invalid_input, "{} tick {k}: {o:?}", S::NAME);
        }
    }
}

/// `update_radians` on backend `S`: finite and within the torque limit;
/// against `f64` within the widened `AgreementBound` when `compare`.
fn radians<S: Scalar>(p: &TorqueEstimatorParams, angles: &[(f64, f64, f64)], compare: bool) {
    let cfg = TorqueEstimatorConfig::<S>::new(p);
    let c64 = TorqueEstimatorConfig::<f64>::new(p);
    let max = p.max_torque();
    let q = if S::NAME == "I16F16" {
        2e-5
    } else {
        1e-6 * max
    };
    let n = p.drive().ratio();
    let ke = p.kinematic_error().map_or(0.0, |k| k.amplitude_bound());
    let u = S::UNITS;
    for &(la, ma, tw) in angles {
        let (ls, ms) = (S::from_f64(la * u.angle), S::from_f64(ma * u.angle));
        let ts = S::from_f64(tw * u.motor_torque);
        let e = cfg.update_radians(ls, ms, ts);
        assert!(
            e.torque_si().is_finite() && e.torque_si().abs() <= max + q,
            "{e:?}"
        );
        assert!(e.torsion_si().is_finite() && e.flexspline_torsion_si().is_finite());
        if !compare || ma.abs() >= 30_000.0 || tw.abs() > 30.0 {
            continue;
        }
        let (l64, m64) = (ls.to_f64() / u.angle, ms.to_f64() / u.angle);
        let a = c64.update_radians(l64, m64, ts.to_f64() / u.motor_torque);
        let mut b = p.agreement_bound::<S>();
        b.torsion += if S::NAME == "I16F16" {
            2f64.powi(-16) + ke * 2f64.powi(-10)
        } else {
            2f64.powi(-20) * (l64.abs() + m64.abs() / n)
                + ke * 2f64.powi(-19) * (l64.abs() + m64.abs() + 1.0)
        };
        let (lo, hi) = b.torque_interval(p, a.flexspline_torsion);
        assert!(
            lo <= e.torque_si() && e.torque_si() <= hi,
            "radians {}: {} not in [{lo}, {hi}] (f64 {a:?}) {p:?}",
            S::NAME,
            e.torque_si()
        );
    }
}

/// The admittance law: the reference stays in the workspace, moves at most
/// `max_rate·T` per step, and a non-finite torque is flagged and ignored.
fn admittance<S: Scalar>(p: &AdmittanceParams, max_rate: f64, torques: &[[f64; 2]]) {
    let cfg = AdmittanceConfig::<S>::new(p);
    let mut st = cfg.state_at([S::ZERO; 2]);
    let u = S::UNITS;
    let lim = p.limits();
    let step = max_rate * p.sample_period();
    for t in torques {
        let before = st;
        let o = cfg.update(
            &mut st,
            [
                S::from_f64(t[0] * u.link_torque),
                S::from_f64(t[1] * u.link_torque),
            ],
        );
        let bad = !(t[0].is_finite() && t[1].is_finite());
        if S::NAME != "I16F16" {
            assert_eq!(o.invalid_input, bad);
        }
        if o.invalid_input {
            assert_eq!(st, before);
        }
        for i in 0..2 {
            let r = o.reference[i].to_f64() / u.angle;
            let r0 = before.reference[i].to_f64() / u.angle;
            assert!(r.is_finite() && r.abs() <= lim[i] + 1e-4, "{o:?}");
            assert!((r - r0).abs() <= step * (1.0 + 1e-4) + 1e-4, "{o:?}");
        }
    }
}

fuzz_target!(|data: (
    u32,
    [u64; 12],
    (u16, u8, u8),
    [i32; 8],
    Vec<([i32; 8], u32, u8, u64)>
)| {
    let (mode_bits, raw, (debounce, ack, window), target, samples) = data;
    let flag = |k: u32| mode_bits & (1 << k) != 0;
    let samples = &samples[..samples.len().min(16)];
    let xs: Vec<ControlInput<f64>> = samples
        .iter()
        .map(|(v, scales, rawf, bits)| {
            // Raw fields in about one sample in eight.
            let r = if rawf & 0xe0 == 0 { *rawf } else { 0 };
            sample(v, *scales, r, *bits)
        })
        .collect();

    // The robust adaptive law: Table 4.1 with each field scaled or raw.
    let table = RobustAdaptiveDesign::table_4_1();
    let mut d = table;
    let spread = !flag(0);
    d.lambda = field(raw[0], flag(0), table.lambda);
    d.integral_gain = field(raw[1], flag(0), table.integral_gain);
    d.adaptation_gain = [field(raw[2], flag(0), 0.1); 4];
    d.eps_r = field(raw[3], flag(0), table.eps_r);
    d.rotor_inertia = field(raw[4], flag(1), table.rotor_inertia);
    d.ratio = if flag(2) {
        field(raw[5], true, 0.0)
    } else {
        [50.0, 80.0, 100.0, 120.0, 160.0][(raw[5] % 5) as usize]
    };
    d.torque_limit =
        field(raw[6], flag(3), table.torque_limit).min(if flag(3) { f64::INFINITY } else { 1.0 });
    d.integral_limit = field(raw[7], flag(3), table.integral_limit);
    d.sample_period = field(raw[8], flag(4), table.sample_period);
    d.uncertainty.torque_estimate = field(raw[9], flag(4), 1.0);
    d.initial_friction = FrictionParams {
        viscous: field(raw[10], flag(5), 5e-5).min(1e-4),
        coulomb: field(raw[10] >> 7, flag(5), 0.006).min(0.012),
        stribeck: field(raw[11], flag(5), 0.006).min(0.012),
        stribeck_shape: field(raw[11] >> 7, flag(5), 1.0).clamp(0.01, 10.0),
    };
    let spread = spread && !flag(1) && !flag(2) && !flag(3) && !flag(4) && !flag(5);
    let law_spread = spread;
    let active_params = match RobustAdaptiveParams::try_new(d) {
        Ok(p) => {
            active::<f64>(&p, &xs, false);
            active::<f32>(&p, &xs, spread);
            active::<I16F16>(&p, &xs, spread);
            Some(p)
        }
        Err(e) => {
            typed(e);
            None
        }
    };

    // The passive law, by name, from the (possibly rejected) design.
    let passive_spread = !flag(6) && !flag(1) && !flag(2) && !flag(3) && !flag(5);
    let passive_settings = PassiveSettings {
        rotor_inertia: d.rotor_inertia,
        gain: field(raw[9] >> 5, flag(6), 1.0 / table.rotor_inertia),
        ratio: d.ratio,
        eps_velocity: field(raw[3] >> 5, flag(6), table.eps_velocity),
        nominal_friction: d.initial_friction,
        torque_limit: d.torque_limit,
    };
    let passive_params = match PassiveParams::try_new(passive_settings) {
        Ok(p) => {
            assert_eq!(p.settings(), passive_settings);
            passive::<f64>(&p, &xs, false);
            passive::<f32>(&p, &xs, passive_spread);
            passive::<I16F16>(&p, &xs, passive_spread);
            Some(p)
        }
        Err(e) => {
            typed(e);
            None
        }
    };

    // Collision detection and the mode manager.
    let collision = if flag(7) {
        None
    } else {
        let s = CollisionSettings {
            threshold: field(raw[0] >> 3, flag(8), 2.0),
            release_threshold: field(raw[1] >> 3, flag(8), 1.0),
            debounce: debounce & 0xff,
            release: debounce >> 8,
            reaction: if flag(9) {
                CollisionReaction::Stop
            } else {
                CollisionReaction::Passive
            },
        };
        match CollisionParams::try_new(s) {
            Ok(c) => {
                assert_eq!(c.settings(), s);
                Some(c)
            }
            Err(e) => {
                typed(e);
                None
            }
        }
    };
    let (Some(a), Some(pp)) = (active_params, passive_params) else {
        return;
    };
    let ms = ModeSettings {
        active: a,
        passive: pp,
        enter_passive: field(raw[2] >> 3, flag(10), 2.0),
        exit_passive: field(raw[4] >> 3, flag(10), 1.0),
        debounce: (debounce >> 4) & 0xf,
        dwell: debounce & 0x3f,
        rejoin_bandwidth: field(raw[6] >> 3, flag(11), 10.0),
        bias_time_constant: field(raw[8] >> 3, flag(11), 0.1),
        collision,
    };
    let mode_params = match ModeParams::try_new(ms) {
        Ok(m) => {
            assert_eq!(ModeParams::try_new(m.settings()), Ok(m));
            mode::<f64>(&m, &xs, ack);
            mode::<f32>(&m, &xs, ack);
            mode::<I16F16>(&m, &xs, ack);
            Some(m)
        }
        Err(e) => {
            typed(e);
            None
        }
    };

    // The estimator (radian path) and the joint.
    let Ok(drive) = CatalogueData::SHD_17_100.identify() else {
        return;
    };
    let drive = if d.ratio != 100.0 {
        match mrr_control::harmonic_drive::HarmonicDriveParams::try_new(
            drive.flexspline(),
            drive.wave_generator(),
            d.ratio,
        ) {
            Ok(x) => x,
            Err(e) => return typed(e),
        }
    } else {
        drive
    };
    let est_spread = !flag(12) && !flag(2);
    let es = TorqueEstimatorSettings {
        drive,
        kinematic_error: flag(13).then(KinematicErrorModel::table_3_2),
        link_counts_per_rev: if flag(12) {
            raw[7] as u32
        } else {
            1 << (10 + raw[7] % 10)
        },
        motor_counts_per_rev: if flag(12) {
            (raw[7] >> 32) as u32
        } else {
            500 * (1 + (raw[7] >> 32) as u32 % 8)
        },
        max_torque: field(raw[9] >> 9, flag(12), 60.0),
    };
    let estimator = match TorqueEstimatorParams::try_new(es) {
        Ok(p) => {
            assert_eq!(p.settings(), es);
            p
        }
        Err(e) => return typed(e),
    };
    let n = estimator.drive().ratio();
    let angles: Vec<(f64, f64, f64)> = samples
        .iter()
        .map(|(v, _, rawf, bits)| {
            let link = v[0] as f64 / 2f64.powi(31) * std::f64::consts::PI;
            let torsion = v[1] as f64 / 2f64.powi(31) * 2e-3;
            let motor = if rawf & 0xf0 == 0x10 {
                f64::from_bits(*bits)
            } else {
                -n * (link - torsion)
            };
            (link, motor, v[2] as f64 / 2f64.powi(31) * 2.0)
        })
        .collect();
    radians::<f64>(&estimator, &angles, false);
    radians::<f32>(&estimator, &angles, est_spread);
    radians::<I16F16>(&estimator, &angles, est_spread);

    if let Some(m) = mode_params {
        match JointParams::try_new(JointSettings {
            estimator,
            mode: m,
            speed_window: window,
            max_motor_speed: field(
                raw[11] >> 3,
                flag(16),
                mrr_control::joint::TABLE_4_1_MAX_MOTOR_SPEED,
            ),
        }) {
            Ok(j) => {
                let readings: Vec<(u32, u32, u64, u8)> = samples
                    .iter()
                    .map(|(v, s, k, b)| (v[0] as u32, *s, *b, *k))
                    .collect();
                joint::<f64>(&j, &readings, &target, flag(17));
                joint::<f32>(&j, &readings, &target, flag(17));
                joint::<I16F16>(&j, &readings, &target, flag(17));
                // Multi-turn sequences: up to 32 ticks from `target[4]`
                // output revolutions, `target[5]` counts per tick, a
                // whole-revolution jump of `target[6]` revolutions.
                let ticks = 4 + (target[7] as u32 % 29) as usize;
                let jump = if flag(18) { target[6] } else { 0 };
                let sane =
                    est_spread && law_spread && !flag(8) && !flag(10) && !flag(11) && !flag(16);
                joint_multi_turn::<f64>(&j, target[4], target[5], ticks, jump, sane);
                joint_multi_turn::<f32>(&j, target[4], target[5], ticks, jump, sane);
                joint_multi_turn::<I16F16>(&j, target[4], target[5], ticks, jump, sane);
            }
            Err(e) => typed(e),
        }
    }

    // The wrist's admittance law, by name.
    let l = field(raw[10] >> 13, flag(14), 0.5).min(if flag(14) { f64::INFINITY } else { 1.5 });
    let adm = AdmittanceSettings {
        gain: [
            field(raw[11] >> 13, flag(14), 0.1),
            field(raw[11] >> 17, flag(14), 0.1),
        ],
        stiffness: field(raw[0] >> 13, flag(15), 200.0),
        sample_period: d.sample_period,
        lag_samples: window % 20,
        limits: [l, l],
        max_rate: field(raw[1] >> 13, flag(15), 1.0),
        deadband: field(raw[2] >> 13, flag(15), 0.05),
        desired_torque: [0.0, field(raw[3] >> 13, flag(15), 0.5)],
    };
    match AdmittanceParams::try_new(adm) {
        Ok(p) => {
            let torques: Vec<[f64; 2]> = xs
                .iter()
                .map(|x| [x.joint_torque, x.desired_joint_torque])
                .collect();
            admittance::<f64>(&p, adm.max_rate, &torques);
            admittance::<f32>(&p, adm.max_rate, &torques);
            admittance::<I16F16>(&p, adm.max_rate, &torques);
        }
        Err(e) => typed(e),
    }
});
