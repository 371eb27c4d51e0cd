//! Every public parameter type of the drive and estimator family built from
//! raw fields, then the estimator fed arbitrary readings. Asserts: a typed
//! error whose message names something, or finite outputs within their
//! stated range with the flags telling the truth; and, for accepted
//! parameters, the f32 and I16F16 count-path estimates within the
//! documented `AgreementBound` of the f64 one (a silent 0 fails it).
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::control::{ModeParams, ModeSettings};
use mrr_control::estimation::{
    CollisionParams, CollisionReaction, CollisionSettings, TorqueEstimate, TorqueEstimatorConfig,
    TorqueEstimatorParams, TorqueEstimatorSettings,
};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::two_spring::{TwoSpringParams, TwoSpringSettings, TwoSpringState};
use mrr_control::harmonic_drive::{
    CatalogueCurve, CataloguePiecewise, CubicStiffness, CubicStiffnessSettings, FlexsplineParams,
    FlexsplineSettings, HarmonicDriveParams, WaveGeneratorParams, WaveGeneratorSettings,
    WaveGeneratorTorqueConfig, WaveGeneratorTorqueParams, WaveGeneratorTorqueSettings,
    WaveGeneratorTorqueState,
};
use mrr_control::scalar::units::quantize_keep_non_finite;
use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::ParamError;
use std::f64::consts::TAU;

/// A raw `f64`: the bits themselves when `raw`, else a value spread
/// log-uniformly over `[lo, hi]` (with a sign bit when `signed`), so that
/// both sides of every range check are reached often.
fn value(bits: u64, raw: bool, lo: f64, hi: f64, signed: bool) -> f64 {
    if raw {
        return f64::from_bits(bits);
    }
    let frac = (bits >> 11) as f64 / (1u64 << 53) as f64;
    let v = lo * (hi / lo).powf(frac);
    if signed && bits & 1 == 1 {
        -v
    } else {
        v
    }
}

/// A rejected parameter: its message names a parameter or combination in
/// backticks and is not empty.
fn typed(e: ParamError) {
    let s = e.to_string();
    assert!(s.contains('`') && s.len() > 10, "{s}");
}

fn finite<S: Scalar>(e: &TorqueEstimate<S>) -> bool {
    [e.torque_si(), e.torsion_si(), e.flexspline_torsion_si()]
        .iter()
        .all(|v| v.is_finite())
}

/// One count-path reading: link count, motor counter, motor torque (SI).
type Reading = (u32, u32, f64);

fn run<S: Scalar>(p: &TorqueEstimatorParams, start: i64, r: &[Reading]) -> Vec<TorqueEstimate<S>> {
    let cfg = TorqueEstimatorConfig::<S>::new(p);
    let mut st = cfg.state(start, r.first().map_or(0, |x| x.1));
    let max = p.max_torque();
    r.iter()
        .map(|&(link, motor, tau_w)| {
            let e = cfg.update(
                &mut st,
                link,
                motor,
                quantize_keep_non_finite::<S>(tau_w, S::UNITS.motor_torque),
            );
            assert!(finite(&e), "{e:?}");
            // Stated ranges: |torque| ≤ max_torque (its quantization),
            // |torsion| ≤ torsion_range.
            let q = if S::NAME == "I16F16" {
                2e-5
            } else {
                1e-6 * max
            };
            assert!(e.torque_si().abs() <= max + q, "{e:?}");
            assert!(e.torsion_si().abs() <= p.torsion_range() * (1.0 + 1e-6) + 2e-8);
            assert_eq!(e.link_count_invalid, link >= p.link_counts_per_rev());
            if e.saturated {
                assert!((e.torque_si().abs() - max).abs() <= q, "{e:?}");
            }
            // The radian path: finite, in range, flagged on non-finite input.
            let la = link as f64 / p.link_counts_per_rev() as f64 * TAU;
            let ra = cfg.update_radians(
                S::from_f64(la),
                S::from_f64(-la * p.drive().ratio() + (motor % 7) as f64 * 1e-4),
                quantize_keep_non_finite::<S>(tau_w, S::UNITS.motor_torque),
            );
            assert!(finite(&ra) && ra.torque_si().abs() <= max + q, "{ra:?}");
            if S::NAME != "I16F16" && !tau_w.is_finite() {
                assert!(e.invalid_input && ra.invalid_input);
            }
            e
        })
        .collect()
}

/// The exact torsion (rad) of the readings from integer arithmetic:
/// eq. (2.13) with the motor position followed through the counter.
fn exact_torsions(p: &TorqueEstimatorParams, start: i64, r: &[Reading]) -> Vec<f64> {
    let (l, m, n) = (
        p.link_counts_per_rev() as i128,
        p.motor_counts_per_rev() as i128,
        p.drive().ratio() as i128,
    );
    let (mn, lmn) = (m * n, l * m * n);
    let mut pos = start as i128;
    let mut last = r.first().map_or(0, |x| x.1);
    r.iter()
        .map(|&(link, motor, _)| {
            pos += motor.wrapping_sub(last) as i32 as i128;
            last = motor;
            let c_l = link as i128 % l;
            // Reduced to [−LMN + ⌊LMN/2⌋, ⌊LMN/2⌋), the estimator's
            // convention (symmetric for even LMN).
            let mut d = (c_l * mn + pos.rem_euclid(mn) * l).rem_euclid(lmn);
            if d >= lmn / 2 {
                d -= lmn;
            }
            TAU * d as f64 / lmn as f64
        })
        .collect()
}

fn check_estimator(p: &TorqueEstimatorParams, start: i64, r: &[Reading]) {
    let e64 = run::<f64>(p, start, r);
    let e32 = run::<f32>(p, start, r);
    let ex = run::<I16F16>(p, start, r);
    let exact = exact_torsions(p, start, r);
    let range = p.torsion_range();
    for (i, a) in e64.iter().enumerate() {
        let (_, _, tau_w) = r[i];
        // `invalid_input` tells the truth (away from the range's edge,
        // where the torsion's own rounding decides).
        let t = exact[i];
        if (t.abs() - range).abs() > 1e-9 * range {
            let want = t.abs() > range || !tau_w.is_finite();
            assert_eq!(a.invalid_input, want, "f64 {a:?}, exact torsion {t}");
            if t.abs() <= range {
                assert!((a.torsion - t).abs() <= 1e-12 * range.max(t.abs()));
            } else {
                assert_eq!(a.torsion, range.copysign(t));
                assert!(a.saturated);
            }
        }
        // `saturated` tells the truth on f64: the torque is eq. (3.10) of
        // the flexspline torsion unless it is flagged.
        if !a.saturated {
            let f = p.drive().flexspline().torque(a.flexspline_torsion);
            assert!(!f.saturated && f.torque.abs() <= p.max_torque() * (1.0 + 1e-12));
            assert!((a.torque - f.torque).abs() <= 1e-9 * (1.0 + f.torque.abs()));
        }
        // Backends against f64, within the documented bound; only where
        // the backends see the same finite motor torque.
        // (|τ_w| < 32.7 N·m: the fixed-point motor-torque range, mN·m.)
        if !tau_w.is_finite() || tau_w.abs() > 32.0 {
            continue;
        }
        for (name, b, bound) in [
            ("f32", e32[i].torque_si(), p.agreement_bound::<f32>()),
            ("I16F16", ex[i].torque_si(), p.agreement_bound::<I16F16>()),
        ] {
            let (lo, hi) = bound.torque_interval(p, a.flexspline_torsion);
            assert!(
                lo <= b && b <= hi,
                "{name}: {b} not in [{lo}, {hi}] (f64 {a:?}, bound {bound:?}, params {p:?})"
            );
        }
        for (name, b, bound) in [
            (
                "f32",
                e32[i].flexspline_torsion_si(),
                p.agreement_bound::<f32>(),
            ),
            (
                "I16F16",
                ex[i].flexspline_torsion_si(),
                p.agreement_bound::<I16F16>(),
            ),
        ] {
            assert!(
                (b - a.flexspline_torsion).abs() <= bound.torsion,
                "{name}: Δθ_f {b} vs {} (bound {bound:?}, params {p:?})",
                a.flexspline_torsion
            );
        }
    }
}

/// The other parameter types of the family: typed error or a finite step.
fn check_others(raw: &[u64; 8], mode: u8, readings: &[Reading]) {
    let flag = |k: u8| mode & (1 << k) != 0;
    match CataloguePiecewise::try_new(CatalogueCurve {
        k1: value(raw[0], flag(0), 1e2, 1e6, true),
        k2: value(raw[1], flag(0), 1e2, 1e6, true),
        k3: value(raw[2], flag(0), 1e2, 1e6, true),
        t1: value(raw[3], flag(0), 1e-1, 1e3, true),
        t2: value(raw[4], flag(0), 1e-1, 1e3, true),
    }) {
        Ok(c) => {
            for &(_, _, t) in readings {
                let d = c.torsion(t);
                // Eq. (2.11) in f64: never NaN for a number; the inverse
                // round-trips while nothing overflows.
                assert!(t.is_nan() || !d.is_nan());
                // (Checked for the spread values; raw bits reach subnormal
                // knees where the round trip has no precision to keep.)
                if !flag(0) && t.abs() < 1e100 {
                    let back = c.torque(d);
                    assert!(
                        (back - t).abs() <= 1e-9 * (1.0 + t.abs()),
                        "{c:?} {t} {back}"
                    );
                }
            }
            match CubicStiffness::through_catalogue_knees(&c) {
                Ok(q) => {
                    for &(_, _, t) in readings {
                        assert!(!q.torsion(t).is_nan());
                    }
                }
                Err(e) => typed(e),
            }
        }
        Err(e) => typed(e),
    }
    // Eq. (2.10) from raw coefficients: a typed error, or a torsion that is
    // never NaN, has the torque's sign, and round-trips where the cubic is
    // well inside f64 (relative 1e-9).
    match CubicStiffness::try_new(CubicStiffnessSettings {
        a1: value(raw[6], flag(6), 1e2, 1e6, true),
        a3: value(raw[7], flag(6), 1e2, 1e9, false),
    }) {
        Ok(q) => {
            assert_eq!(CubicStiffness::try_new(q.settings()), Ok(q));
            for &(_, _, t) in readings {
                let d = q.torsion(t);
                assert!(!d.is_nan(), "{q:?} {t}");
                assert!(
                    !t.is_finite() || d == 0.0 || (d > 0.0) == (t > 0.0),
                    "{q:?} {t} {d}"
                );
                if !flag(6) && t.is_finite() && t.abs() < 1e6 {
                    let back = q.torque(d);
                    assert!(
                        (back - t).abs() <= 1e-9 * (1.0 + t.abs()),
                        "{q:?} {t} {back}"
                    );
                }
            }
        }
        Err(e) => typed(e),
    }
    match TwoSpringParams::try_new(TwoSpringSettings {
        k_a: value(raw[5], flag(1), 1e-3, 1e6, true),
        k_b: value(raw[6], flag(1), 1e-3, 1e6, true),
        friction: value(raw[7], flag(1), 1e-3, 1e3, true),
    }) {
        Ok(p) => {
            let mut st = TwoSpringState::default();
            for &(_, _, t) in readings {
                let x = st.apply(&p, t);
                // Eq. (2.14) in f64: finite unless F/K itself overflows.
                let k = p.k_a().min(p.k_b());
                assert!(!t.is_finite() || (t.abs() + p.friction()) / k > 1e300 || x.is_finite());
                assert!(st.spring_b_force.is_finite());
            }
        }
        Err(e) => typed(e),
    }
    match WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
        backdrive_friction: value(raw[0], flag(2), 1e-3, 1e3, true),
        ratio: value(raw[1], flag(2), 0.5, 200.0, false),
    }) {
        Ok(p) => {
            let c32 = WaveGeneratorTorqueConfig::<f32>::new(&p);
            let cx = WaveGeneratorTorqueConfig::<I16F16>::new(&p);
            let (mut s32, mut sx) = (
                WaveGeneratorTorqueState::default(),
                WaveGeneratorTorqueState::default(),
            );
            for &(_, _, t) in readings {
                let a = c32.update(&mut s32, t as f32);
                let b = cx.update(&mut sx, I16F16::from_f64(t));
                // The play stays within `τ_fb/N` of `−τ_f/N` and finite.
                assert!(a.is_finite() && s32.torque.is_finite());
                let _ = b;
            }
        }
        Err(e) => typed(e),
    }
    if let Ok(s) = ModeSettings::table_4_1(2000.0) {
        let collision = CollisionParams::try_new(CollisionSettings {
            threshold: value(raw[2], flag(3), 1e-2, 1e2, true),
            release_threshold: value(raw[3], flag(3), 1e-2, 1e2, true),
            debounce: raw[4] as u16,
            release: (raw[4] >> 16) as u16,
            reaction: CollisionReaction::Stop,
        });
        let collision = match collision {
            Ok(c) => Some(c),
            Err(e) => {
                typed(e);
                None
            }
        };
        let settings = ModeSettings {
            enter_passive: value(raw[5], flag(4), 1e-2, 1e5, true),
            exit_passive: value(raw[6], flag(4), 1e-2, 1e5, true),
            debounce: raw[7] as u16,
            dwell: (raw[7] >> 16) as u16,
            rejoin_bandwidth: value(raw[0] >> 3, flag(5), 1e-2, 1e6, true),
            bias_time_constant: value(raw[1] >> 3, flag(5), 1e-5, 1e2, true),
            collision,
            ..s
        };
        match ModeParams::try_new(settings) {
            Ok(p) => assert_eq!(ModeParams::try_new(p.settings()), Ok(p)),
            Err(e) => typed(e),
        }
    }
}

fuzz_target!(|data: (
    u8,
    [u64; 8],
    [u64; 7],
    (u32, u32, u32),
    i64,
    Vec<(u32, u32, i32, u64, u8)>
)| {
    let (mode, raw, ke_raw, (l, m, n_raw), start, rs) = data;
    let flag = |k: u8| mode & (1 << k) != 0;
    // The readings: a raw counter, or one near the rigid position of the
    // link count (a torsion within about ±1.5 torsion ranges), so that both
    // the in-range and the impossible readings are reached; the motor
    // torque from raw bits (NaN, ±∞ included) or within ±1 N·m.
    let rs = &rs[..rs.len().min(32)];
    let others: Vec<Reading> = rs
        .iter()
        .map(|&(link, motor, _, tau, k)| {
            let t = value(tau, k & 1 == 1, 1e-6, 1.0, true);
            (link, motor, t)
        })
        .collect();
    check_others(&raw, mode, &others);

    // The drive and estimator from raw fields.
    let fl = FlexsplineParams::try_new(FlexsplineSettings {
        k_f0: value(raw[0], flag(0), 1.0, 1e8, true),
        c_f: value(raw[1], flag(0), 1e-8, 1e8, true),
    });
    let wg = WaveGeneratorParams::try_new(WaveGeneratorSettings {
        k_w0: value(raw[2], flag(1), 1e-4, 1e4, true),
        c_w: value(raw[3], flag(1), 1e-8, 1e8, true),
    });
    let ratio = if flag(2) {
        f64::from_bits(raw[4])
    } else if n_raw & 1 == 0 {
        (n_raw >> 1) as f64 % 70_000.0
    } else {
        (n_raw >> 1) as f64 / 8.0
    };
    let drive = match (fl, wg) {
        (Ok(f), Ok(w)) => HarmonicDriveParams::try_new(f, w, ratio),
        (Err(e), _) | (_, Err(e)) => Err(e),
    };
    let drive = match drive {
        Ok(d) => d,
        Err(e) => return typed(e),
    };
    let ke = if flag(3) {
        let c = if flag(4) {
            ke_raw.map(f64::from_bits)
        } else {
            ke_raw.map(|b| value(b, false, 1e-7, 2e-2, true))
        };
        match KinematicErrorModel::try_new(c) {
            Ok(k) => Some(k),
            Err(e) => return typed(e),
        }
    } else {
        None
    };
    let (l, m) = if flag(5) {
        (l, m)
    } else {
        (1 + (l >> (l % 32)), 1 + (m >> (m % 32)))
    };
    let max_torque = value(raw[5], flag(6), 1e-3, 1e5, true);
    let p = match TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
        drive,
        kinematic_error: ke,
        link_counts_per_rev: l,
        motor_counts_per_rev: m,
        max_torque,
    }) {
        Ok(p) => p,
        Err(e) => return typed(e),
    };
    let (lc, mn) = (
        p.link_counts_per_rev() as i128,
        (m as i128) * (p.drive().ratio() as i128),
    );
    let counts_per_range = p.torsion_range() / TAU * (lc * mn) as f64;
    let mut readings = Vec::with_capacity(rs.len());
    let mut pos = start as i128;
    let mut counter = rs.first().map_or(0, |x| x.1);
    for (i, &(link, motor, delta, _, k)) in rs.iter().enumerate() {
        let motor = if k & 2 == 0 || i == 0 {
            motor
        } else {
            // Torsion D = c_l·MN + p·L: choose p so that D is near
            // `delta / 2³¹ · 1.5 · range` in counts.
            let c_l = link as i128 % lc;
            let want_d = (delta as f64 / 2_147_483_648.0 * 1.5 * counts_per_range) as i128;
            let target_p = (want_d - c_l * mn).div_euclid(lc);
            let step = (target_p - pos.rem_euclid(mn)).rem_euclid(mn);
            let step = if step > mn / 2 { step - mn } else { step };
            if step.abs() >= 1 << 31 {
                motor
            } else {
                counter.wrapping_add(step as i32 as u32)
            }
        };
        pos += motor.wrapping_sub(counter) as i32 as i128;
        counter = motor;
        readings.push((link, motor, others[i].2));
    }
    check_estimator(&p, start, &readings);
});
