//! The wrist's maps (thesis ch. 5–6) on `f64`, `f32` and `I16F16` with
//! arbitrary inputs and arbitrary parameters: forward and inverse
//! kinematics (eq. 5.8–5.15) with the tracking inverse, the polar (α, β)
//! description (eq. 5.16–5.21), the exact Jacobian and the thesis's chain
//! `J_2 J_c` (eq. 5.22–5.27), the force mapping both ways (eq. 5.28–5.29),
//! the F/T chain (eq. 6.34, 6.35, 6.3), the admittance law (eq. 6.32) and
//! its discrete-time gain limit, the wrist mode manager and the whole
//! wrist step.
//!
//! Parameters come from raw `f64` bits (any value: the constructor must
//! answer with a typed error naming the parameter, or accept a value that
//! obeys every documented rule) or near the thesis's values (each field
//! scaled by a factor, so that most are accepted and the maps run).
//!
//! Asserted, for every input: no panic; every output finite and within
//! its documented range; the flags exactly as documented (`saturated`,
//! `singular`, `straight`, `invalid_input`); a flagged step leaves the
//! state alone; no state ever holds a NaN or an infinity (checked through
//! `Debug`, which prints the private fields). The only comparison with a
//! documented error bound is the inverse kinematics' round trip
//! (`proofs::wrist_ik::round_trip_bound`, derived for `φ = 16°`): for the
//! thesis's wrist, `FK(IK(δ, γ)) = (δ, γ)` within it at every reachable
//! pose away from the edge. Every other tolerance below is the rounding
//! allowance of the backend on a stated range, derived where it is used.
//!
//! At most 16 samples per input keep one execution cheap.
#![no_main]
// Two-element arrays (axes) indexed in parallel: index loops read better
// than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use libfuzzer_sys::fuzz_target;
use mrr_control::proofs::wrist_ik::{
    angle_unit, bend, branch_and_round_trip_of, branch_slack, in_domain, round_trip_bound,
};
use mrr_control::scalar::units::quantize_keep_non_finite;
use mrr_control::scalar::{Scalar, I16F16};
use mrr_control::wrist::active::WristActiveParams;
use mrr_control::wrist::admittance::{AdmittanceConfig, AdmittanceParams, AdmittanceSettings};
use mrr_control::wrist::alpha_beta::AlphaBeta;
use mrr_control::wrist::ft_sensor::{
    DecouplingMatrix, FtSensorConfig, FtSensorParams, GaugeAmplifier, DEFAULT_MAX_CONDITION,
};
use mrr_control::wrist::jacobian::{DET_MIN, MAX_TORQUE};
use mrr_control::wrist::modes::{
    WristModeConfig, WristModeInput, WristModeParams, WristModeSettings,
};
use mrr_control::wrist::step::{
    WristReadings, WristStepConfig, WristStepParams, WristStepSettings, WristTarget,
};
use mrr_control::wrist::{
    ForceMapping, IkState, JacobianKind, MotorAngles, PitchYaw, WristConfig, WristMode, WristParams,
};
use mrr_control::ParamError;
use std::f64::consts::{FRAC_PI_2, PI};

/// A rejected parameter: its message names something in backticks.
fn typed(e: ParamError) {
    let s = e.to_string();
    assert!(s.contains('`') && s.len() > 10, "{s}");
}

/// A field: the raw bits as an `f64` when `raw`, else `base` times a
/// factor log-uniform in `[lo, hi]`.
fn field(bits: u64, raw: bool, base: f64, lo: f64, hi: f64) -> f64 {
    if raw {
        return f64::from_bits(bits);
    }
    let frac = (bits >> 11) as f64 / (1u64 << 53) as f64;
    base * lo * (hi / lo).powf(frac)
}

/// A sample value from one fuzz word: by its low three bits, raw `f64`
/// bits (NaN, ±∞, huge, tiny), a magnitude near the `f32` range, exactly
/// 0, or uniform in `[−scale, scale]`.
fn value(w: u64, scale: f64) -> f64 {
    let u = (w >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
    match w & 7 {
        0 => f64::from_bits(w),
        1 => u * f32::MAX as f64,
        2 => 0.0,
        _ => u * scale,
    }
}

/// Stored value of backend `S` (a non-finite value stays one on floats).
fn q<S: Scalar>(v: f64) -> S {
    quantize_keep_non_finite(v, 1.0)
}

fn finite<S: Scalar>(x: S) -> bool {
    x.to_f64().is_finite()
}

fn is_fixed<S: Scalar>() -> bool {
    S::NAME == "I16F16"
}

/// One rounding unit of `S` at magnitude `m` (the ulp on floats, the LSB
/// on fixed point).
fn unit<S: Scalar>(m: f64) -> f64 {
    match S::NAME {
        "I16F16" => 1.0 / 65536.0,
        "f32" => m.abs().max(f32::MIN_POSITIVE as f64) * f32::EPSILON as f64,
        _ => m.abs().max(f64::MIN_POSITIVE) * f64::EPSILON,
    }
}

/// A magnitude bound as the backend can reach it: fixed point saturates
/// at `MAX` (or `MIN`, one LSB further, `2¹⁵`).
fn sat_bound<S: Scalar>(b: f64) -> f64 {
    if is_fixed::<S>() && b >= S::MAX.to_f64() {
        32768.0
    } else {
        b
    }
}

/// Wrapped distance of two angles (rad).
fn ang_dist(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// No NaN and no infinity anywhere in a state, private fields included.
fn clean_state<T: core::fmt::Debug>(st: &T) {
    let s = format!("{st:?}");
    assert!(!s.contains("NaN") && !s.contains("inf"), "{s}");
}

/// The exact Jacobian's entry bounds for bend `≤ 2φ` (module docs of
/// `wrist::jacobian`): with `D = Sδ Sφ S1 + Cδ Cφ ≥ d_min`,
/// `|J00| ≤ Sφ/D`, `|J01| ≤ Sφ/D + S2φ`, `|J10| ≤ Sφ/D`,
/// `|J11| ≤ (S2φ Cφ + Sφ)/D`.
fn exact_jacobian_bound(phi: f64, d_min: f64) -> [[f64; 2]; 2] {
    let (sp, cp, s2) = (phi.sin(), phi.cos(), (2.0 * phi).sin());
    [
        [sp / d_min, sp / d_min + s2],
        [sp / d_min, (s2 * cp + sp) / d_min],
    ]
}

/// Kinematics, polar description, Jacobians and force mapping on `S`.
fn kinematics<S: Scalar>(p: &WristParams, samples: &[[u64; 6]], thesis: bool) {
    let cfg = WristConfig::<S>::new(p);
    let phi = p.phi();
    let qa = angle_unit::<S>();
    // Range allowance: the forward map's angles are within ~30 units of
    // the backend's angle resolution (`proofs::wrist_ik` module docs: 40
    // rounded products and 7 kernels on terms ≤ 1, unit-norm `atan2`
    // arguments); the documented round-trip budget, 96 units, covers it.
    let tol = round_trip_bound::<S>();
    let eps = branch_slack(p);
    let mut ik_state: Option<IkState<S>> = None;
    for (k, w) in samples.iter().enumerate() {
        let m = MotorAngles {
            theta1: q::<S>(value(w[0], 8.0)),
            theta3: q::<S>(if w[5] & 0x30 == 0x30 {
                // The straight pose: θ3 = −θ1 exactly.
                -value(w[0], 8.0)
            } else {
                value(w[1], 8.0)
            }),
        };
        // Poses: mostly in and around the workspace, some raw.
        let pose = PitchYaw {
            delta: q::<S>(value(w[2], 2.5 * phi)),
            gamma: q::<S>(value(w[3], 2.5 * phi)),
        };
        let (d, g) = (pose.delta.to_f64(), pose.gamma.to_f64());

        // Forward kinematics: every motor position is a pose.
        let f = cfg.forward(m);
        for x in [f.pose.delta, f.pose.gamma, f.theta4] {
            assert!(finite(x), "forward {m:?} -> {f:?}");
        }
        let (fd, fg) = (f.pose.delta.to_f64(), f.pose.gamma.to_f64());
        assert!(
            fd.abs() <= 2.0 * phi + tol && fg.abs() <= 2.0 * phi + tol,
            "{f:?}"
        );
        assert!(
            bend(fd, fg) <= 2.0 * phi + tol,
            "{f:?} bend {}",
            bend(fd, fg)
        );
        assert!(f.theta4.to_f64().abs() <= PI + tol, "{f:?}");

        // Inverse kinematics, saturating.
        let r = cfg.inverse(pose);
        let (t1, t3) = (r.motors.theta1.to_f64(), r.motors.theta3.to_f64());
        assert!(
            finite(r.motors.theta1) && finite(r.motors.theta3),
            "{pose:?} {r:?}"
        );
        assert!(finite(r.pose.delta) && finite(r.pose.gamma) && finite(r.theta4));
        assert!(t1.abs() <= PI + tol, "{r:?}");
        assert!(t1 + t3 >= -PI - eps - tol && t1 + t3 <= eps + tol, "{r:?}");
        assert!(
            r.theta4.to_f64() >= -tol && r.theta4.to_f64() <= PI + tol,
            "{r:?}"
        );
        let (rd, rg) = (r.pose.delta.to_f64(), r.pose.gamma.to_f64());
        assert!(
            rd.abs() <= FRAC_PI_2 + tol && rg.abs() <= FRAC_PI_2 + tol,
            "{r:?}"
        );
        assert!(bend(rd, rg) <= 2.0 * phi + tol, "{r:?}");
        if r.straight {
            assert!(
                r.motors.theta1 == S::ZERO && r.motors.theta3 == S::ZERO,
                "{r:?}"
            );
        }
        let nan = d.is_nan() || g.is_nan();
        // Outside by more than the rounding of the workspace test (64
        // units of bend, `BOUNDARY_MARGIN_UNITS`): saturated, onto the edge.
        let outside = nan
            || !(d.abs() <= FRAC_PI_2 && g.abs() <= FRAC_PI_2)
            || bend(d, g) > 2.0 * phi + 64.0 * qa;
        if outside {
            assert!(r.saturated, "{pose:?} {r:?}");
        }
        if r.saturated && !nan && d.abs() <= FRAC_PI_2 && g.abs() <= FRAC_PI_2 {
            assert!(bend(rd, rg) >= 2.0 * phi - tol, "{pose:?} {r:?}");
        }
        if in_domain(&p.clone(), pose.delta, pose.gamma) {
            assert!(!r.saturated && r.pose == pose, "{pose:?} {r:?}");
        }
        if thesis {
            // The documented round trip and branch (φ = 16° only).
            let v = branch_and_round_trip_of(&cfg, p, pose.delta, pose.gamma, &r);
            assert!(v.holds, "round trip {} at {pose:?}: {r:?}", v.error);
        }

        // Inverse kinematics with a typed error.
        match cfg.try_inverse(pose) {
            Ok(t) => {
                assert!(!outside, "accepted {pose:?}");
                assert!(!t.saturated && t.pose == pose);
                assert_eq!(t.motors, r.motors);
            }
            Err(e) => {
                assert!(
                    !in_domain(p, pose.delta, pose.gamma),
                    "rejected {pose:?}: {e}"
                );
                assert_eq!(e.max_bend, 2.0 * phi);
                assert!(e.to_string().contains("unreachable"));
            }
        }

        // The tracking inverse: each motor within π of its previous value,
        // equal modulo 2π to one root of eq. (5.13) — the inverse (θ4 ≥ 0)
        // or the other preimage (θ4 ≤ 0), both motors from the same root;
        // at the straight pose θ1 stays.
        let mut st = ik_state.unwrap_or_else(|| IkState::new(m));
        let prev = st.motors;
        let u = cfg.update(&mut st, pose);
        assert!(finite(u.motors.theta1) && finite(u.motors.theta3), "{u:?}");
        assert_eq!(st.motors, u.motors);
        let other = cfg.inverse_other_branch(pose);
        let mut off = [0.0f64; 2];
        let mut tracked = true;
        for (now, before, roots) in [
            (
                u.motors.theta1,
                prev.theta1,
                [r.motors.theta1, other.motors.theta1],
            ),
            (
                u.motors.theta3,
                prev.theta3,
                [r.motors.theta3, other.motors.theta3],
            ),
        ] {
            let b = before.to_f64();
            if b.is_nan() || b.abs() >= 1e3 {
                tracked = false;
                continue;
            }
            // `p + atan2(sin Δ, cos Δ)`: |atan2| ≤ π, and the sum and the
            // removal of whole turns round at the magnitude of `p` (4
            // units), plus the kernels' angle error (`tol`).
            let slack = tol + 4.0 * unit::<S>(b.abs() + 2.0 * PI);
            assert!(
                (now.to_f64() - b).abs() <= PI + slack,
                "{now:?} from {before:?}"
            );
            for (k, root) in roots.iter().enumerate() {
                off[k] = off[k].max(ang_dist(now.to_f64(), root.to_f64()) - slack);
            }
        }
        if tracked && !r.straight {
            assert!(off[0] <= 0.0 || off[1] <= 0.0, "{u:?} {r:?} {other:?}");
        }
        if r.straight && prev.theta1.to_f64().abs() < 1e3 {
            assert_eq!(u.motors.theta1, prev.theta1);
        }
        ik_state = Some(st);

        // The polar description, eq. (5.16)–(5.21).
        let ab = cfg.alpha_beta(m);
        let ap = cfg.alpha_beta_approx(m);
        for x in [ab, ap] {
            assert!(finite(x.alpha) && finite(x.beta), "{x:?}");
            assert!(x.alpha.to_f64().abs() <= PI + tol, "{x:?}");
            let b = x.beta.to_f64();
            assert!(b >= -tol && b <= 2.0 * phi + tol, "{x:?}");
        }
        let abp = cfg.alpha_beta_of_pose(pose);
        assert!(finite(abp.alpha) && finite(abp.beta), "{abp:?}");
        assert!(abp.alpha.to_f64().abs() <= PI + tol && abp.beta.to_f64() >= -tol);
        assert!(abp.beta.to_f64() <= PI + tol, "{abp:?}");
        let any_ab = AlphaBeta {
            alpha: q::<S>(value(w[4], 4.0)),
            // Around the workspace's bends, or anywhere up to past ±π/2.
            beta: q::<S>(value(w[5], if w[4] & 8 == 0 { 2.5 * phi } else { 1.7 })),
        };
        let pp = cfg.pose_of_alpha_beta(any_ab);
        assert!(finite(pp.delta) && finite(pp.gamma), "{any_ab:?} -> {pp:?}");
        assert!(pp.delta.to_f64().abs() <= FRAC_PI_2 + tol, "{pp:?}");
        assert!(pp.gamma.to_f64().abs() <= PI + tol, "{pp:?}");

        // J_c and J_2 (eq. 5.24, 5.27 corrected): J_c = [[−½, ½], [−Ω, −Ω]],
        // |Ω| ≤ tan φ; J_2 at any (α, β), β limited to ±2φ: each entry
        // ≤ 1/cos²(2φ) (`cos δ ≥ cos β`, `q ≥ cos² β`).
        let jc = cfg.jc_approx(m);
        assert!(
            jc[0][0].to_f64() == -0.5 && jc[0][1].to_f64() == 0.5,
            "{jc:?}"
        );
        assert!(jc[1][0] == jc[1][1] && jc[1][0].to_f64().abs() <= phi.tan() + tol);
        let j2 = cfg.j2(any_ab);
        let j2_max = 1.0 / (2.0 * phi).cos().powi(2);
        for row in j2 {
            for x in row {
                assert!(finite(x), "J2 at {any_ab:?}: {j2:?}");
                // Relative rounding of a few products and one division
                // (8 units) on top of the bound.
                let t = j2_max * (1.0 + 8.0 * unit::<S>(1.0)) + 8.0 * unit::<S>(j2_max);
                assert!(x.to_f64().abs() <= t, "J2 at {any_ab:?}: {j2:?}");
            }
        }

        // Both Jacobians and the force mapping.
        let torques = [q::<S>(value(w[4], 50.0)), q::<S>(value(w[5], 50.0))];
        for kind in [JacobianKind::Exact, JacobianKind::Thesis] {
            let fm = ForceMapping::<S>::new(p, kind);
            let j = fm.jacobian(m);
            let lsb = unit::<S>(1.0);
            // Entry bounds (derived above and in `exact_jacobian_bound`),
            // with the rounding of the FK angles (≤ tol, so D is lowered by
            // at most 2·tol) and of the entries (8 units relative).
            let bound = match kind {
                JacobianKind::Exact => {
                    let d_min = (3.0 * phi).cos() - 2.0 * tol;
                    if d_min < 1e-3 {
                        None
                    } else {
                        Some(exact_jacobian_bound(phi, d_min))
                    }
                }
                JacobianKind::Thesis => {
                    // Entry i,j = J2[i][0]·J_c[0][j] + J2[i][1]·J_c[1][j],
                    // |J_c| ≤ ½, tan φ, |J2| ≤ 1/cos²(2φ).
                    let b = (0.5 + phi.tan()) * j2_max;
                    Some([[b; 2]; 2])
                }
            };
            for (i, row) in j.m.iter().enumerate() {
                for (l, x) in row.iter().enumerate() {
                    assert!(finite(*x), "{kind:?} {m:?} {j:?}");
                    if let Some(b) = bound {
                        let t = b[i][l] * (1.0 + 8.0 * lsb.min(1e-3)) + 8.0 * unit::<S>(b[i][l]);
                        assert!(x.to_f64().abs() <= t, "{kind:?} {m:?} {j:?} > {b:?}");
                    }
                }
            }
            if kind == JacobianKind::Exact && thesis {
                // Documented for φ = 16°: |J_ij| ≤ 1.4.
                for x in j.m.iter().flatten() {
                    assert!(x.to_f64().abs() <= 1.4, "{j:?}");
                }
            }
            let det_min = S::from_f64(DET_MIN);
            assert!(finite(j.det));
            assert_eq!(j.singular, j.det.abs() < det_min, "{j:?}");
            if w[5] & 0x30 == 0x30 && finite(m.theta1) && m.theta1.to_f64().abs() < 1e3 {
                assert!(j.singular, "straight pose {kind:?} {m:?}: {j:?}");
            }

            // Eq. (5.28): Jᵀ τ, inputs clamped to ±MAX_TORQUE and flagged.
            let lim = S::from_f64(MAX_TORQUE).to_f64();
            let clipped = |t: S| t.to_f64().is_nan() || t.to_f64().abs() > lim;
            let tm = fm.motor_torques(m, torques);
            assert_eq!(
                tm.saturated,
                clipped(torques[0]) || clipped(torques[1]),
                "{tm:?}"
            );
            assert_eq!(tm.singular, j.singular);
            let tin = |t: S| {
                let v = t.to_f64();
                if v.is_nan() || v.is_infinite() {
                    0.0
                } else {
                    v.abs().min(lim)
                }
            };
            let (a0, a1) = (tin(torques[0]), tin(torques[1]));
            for c in 0..2 {
                let x = tm.torque[c];
                assert!(finite(x), "{tm:?}");
                // Two products and a sum: 2 units at the sum of the terms.
                let s = j.m[0][c].to_f64().abs() * a0 + j.m[1][c].to_f64().abs() * a1;
                let b = s + 2.0 * unit::<S>(s) + 2.0 * unit::<S>(1.0) * s;
                assert!(
                    x.to_f64().abs() <= sat_bound::<S>(b),
                    "{kind:?} {tm:?} > {s}"
                );
            }
            // Eq. (5.29): bounded by ‖adj J‖ |τ| / DET_MIN, flagged singular.
            let tt = fm.task_torques(m, torques);
            assert_eq!(tt.singular, j.singular);
            assert_eq!(tt.saturated, tm.saturated);
            let [[ja, jb], [jc_, jd]] = j.m.map(|r| r.map(|x| x.to_f64().abs()));
            let adj = [jd * a0 + jc_ * a1, jb * a0 + ja * a1];
            for c in 0..2 {
                let x = tt.torque[c];
                assert!(finite(x), "{tt:?}");
                // |factor| ≤ 1/det_min (1/det above it, det/det_min²
                // below); the adjugate product rounds by 2 units and the
                // factor by 1 unit relative (floats) or ½ LSB (fixed
                // point, times the product); the result by 1 unit.
                let f = 1.0 / det_min.to_f64();
                let pa = adj[c] + 2.0 * unit::<S>(adj[c]);
                let b = pa * (f + unit::<S>(f)) + unit::<S>(pa * f);
                let b = sat_bound::<S>(b * (1.0 + 1e-12));
                assert!(x.to_f64().abs() <= b, "{kind:?} {tt:?} > {b}");
            }
        }
        let _ = k;
    }
}

/// The F/T chain: amplifier and decoupling matrix validation, then
/// eq. (6.35) and (6.3) on `S`.
fn ft<S: Scalar>(p: &FtSensorParams, samples: &[[u64; 6]]) {
    let cfg = FtSensorConfig::<S>::new(p);
    let mat = p.decoupling().matrix();
    for (k, w) in samples.iter().enumerate() {
        let sg: [S; 6] =
            core::array::from_fn(|i| q::<S>(value(w[i].rotate_left(7 * k as u32), 10.0)));
        let gamma = q::<S>(value(w[(k + 3) % 6], 1.0));
        let r = cfg.update(&sg, gamma);
        let bad_in = !is_fixed::<S>() && (sg.iter().any(|v| !finite(*v)) || !finite(gamma));
        if bad_in {
            assert!(r.invalid_input, "{sg:?} {gamma:?} {r:?}");
        }
        if r.invalid_input {
            assert!(r
                .wrench
                .iter()
                .chain(r.interaction.iter())
                .all(|v| *v == S::ZERO));
            // Documented: an input was NaN or infinite, or the wrench
            // overflowed. Every intermediate (products, partial sums,
            // `m_x = τ_x − l F_y`, `c m_x − s τ_z`) is at most
            // `(2 + l)·B`, `B = max_i Σ_j |M_ij||SG_j|`, up to a relative
            // rounding far below 1 %: below `S::MAX` nothing overflows.
            if !bad_in {
                let b = largest_row_sum(&mat, &sg);
                let reach = (2.0 + p.offset()) * b * 1.01;
                assert!(
                    reach >= S::MAX.to_f64(),
                    "flagged with finite inputs {sg:?} {gamma:?} (reach {reach})"
                );
            }
        } else {
            for v in r.wrench.iter().chain(r.interaction.iter()) {
                assert!(finite(*v), "{r:?}");
            }
        }
    }
}

/// The admittance law's rules (`AdmittanceParams::try_new` docs):
/// `Some(accepted)`, or `None` within rounding of the gain limit.
fn admittance_rules(s: &AdmittanceSettings) -> Option<bool> {
    let pos = |x: f64| x.is_finite() && x > 0.0;
    let k = s.stiffness;
    let t = s.sample_period;
    let mut ok = pos(k)
        && pos(t)
        && (1e-6..=1.0).contains(&t)
        && s.lag_samples <= 16
        && s.limits.iter().all(|&l| pos(l) && l <= FRAC_PI_2)
        && pos(s.max_rate)
        && s.max_rate <= 1e3
        && s.deadband.is_finite()
        && (0.0..=1e3).contains(&s.deadband)
        && s.desired_torque
            .iter()
            .all(|d| d.is_finite() && d.abs() <= 1e3)
        && s.gain.iter().all(|g| g.is_finite() && *g > 0.0);
    if !ok {
        return Some(false);
    }
    // a_max(d) = 2 sin(π/(2(2d+1))) (module docs), computed here with std.
    let a = 2.0 * (PI / (2.0 * (2.0 * s.lag_samples as f64 + 1.0))).sin();
    let kmax = a / (t * k);
    for g in s.gain {
        let r = g / kmax;
        if (r - 1.0).abs() < 1e-9 {
            return None;
        }
        ok &= r < 1.0;
    }
    Some(ok)
}

/// The admittance law on `S`: reference in the workspace, moving at most
/// `max_rate·T` per sample, `saturated` and `invalid_input` exactly as
/// documented.
fn admittance<S: Scalar>(p: &AdmittanceParams, s: &AdmittanceSettings, samples: &[[u64; 6]]) {
    let cfg = AdmittanceConfig::<S>::new(p);
    let lim = [S::from_f64(s.limits[0]), S::from_f64(s.limits[1])];
    let m = S::from_f64(s.max_rate * s.sample_period);
    let seed = samples.first().map_or([0, 0], |w| [w[0], w[1]]);
    let mut st = cfg.state_at([q::<S>(value(seed[0], 1.0)), q::<S>(value(seed[1], 1.0))]);
    for i in 0..2 {
        assert!(st.reference[i].abs() <= lim[i], "{st:?}");
    }
    for w in samples {
        let tau = [q::<S>(value(w[2], 20.0)), q::<S>(value(w[3], 20.0))];
        let before = st;
        let o = cfg.update(&mut st, tau);
        let bad = !is_fixed::<S>() && tau.iter().any(|v| !finite(*v));
        assert_eq!(o.invalid_input, bad, "{tau:?} {o:?}");
        if o.invalid_input {
            assert!(
                st == before && o.rate == [S::ZERO; 2] && !o.saturated,
                "{o:?}"
            );
            continue;
        }
        assert_eq!(o.reference, st.reference);
        let mut limited = false;
        for i in 0..2 {
            let (x, x0) = (o.reference[i], before.reference[i]);
            assert!(finite(x) && x.abs() <= lim[i], "{o:?}");
            let dx = (x.to_f64() - x0.to_f64()).abs();
            // `old + dx` rounds once at the magnitude of the reference.
            assert!(dx <= m.to_f64() + unit::<S>(FRAC_PI_2), "{o:?} step {dx}");
            limited |= x.abs() == lim[i] || dx >= m.to_f64() - unit::<S>(FRAC_PI_2);
            // rate = Δx/T through a prepared coefficient: ½ LSB + 2⁻³⁰
            // relative on fixed point (`mul_coef_is_rounded_product`), one
            // rounding on floats.
            let want = (x.to_f64() - x0.to_f64()) / s.sample_period;
            let got = o.rate[i].to_f64();
            assert!(got.is_finite());
            let t = if is_fixed::<S>() {
                0.5 / 65536.0 + want.abs() * 2f64.powi(-30)
            } else {
                2.0 * unit::<S>(want)
            };
            assert!((got - want).abs() <= t, "rate {got} vs {want}");
        }
        if o.saturated {
            assert!(limited, "{o:?} from {before:?}");
        }
        clean_state(&st);
    }
}

/// The wrist mode manager on `S`.
fn modes<S: Scalar>(p: &WristModeParams, limits: [f64; 2], samples: &[[u64; 6]]) {
    let cfg = WristModeConfig::<S>::new(p);
    let lim = [S::from_f64(limits[0]), S::from_f64(limits[1])];
    let first = samples.first().copied().unwrap_or_default();
    let mode = if first[5] & 1 == 0 {
        WristMode::Active
    } else {
        WristMode::Passive
    };
    let mut st = cfg.initial_state(
        mode,
        [q::<S>(value(first[0], 0.5)), q::<S>(value(first[1], 0.5))],
    );
    clean_state(&st);
    for w in samples {
        let x = WristModeInput {
            desired: [q::<S>(value(w[0], 1.0)), q::<S>(value(w[1], 1.0))],
            desired_rate: [q::<S>(value(w[2], 5.0)), q::<S>(value(w[3], 5.0))],
            interaction: [
                q::<S>(value(w[4], 3.0)),
                q::<S>(value(w[5].rotate_left(17), 3.0)),
            ],
            request: match (w[5] >> 8) & 7 {
                0 => Some(WristMode::Active),
                1 => Some(WristMode::Passive),
                _ => None,
            },
        };
        let before = st;
        let o = cfg.update(&mut st, &x);
        let bad = !is_fixed::<S>()
            && x.desired
                .iter()
                .chain(x.desired_rate.iter())
                .chain(x.interaction.iter())
                .any(|v| !finite(*v));
        assert_eq!(o.invalid_input, bad, "{x:?} {o:?}");
        if o.invalid_input {
            assert!(st == before && o.reference == before.reference() && !o.switched);
        }
        assert_eq!(o.mode, st.mode());
        assert_eq!(o.switched, o.mode != before.mode(), "{o:?}");
        assert_eq!(o.reference, st.reference());
        for i in 0..2 {
            assert!(
                finite(o.reference[i]) && o.reference[i].abs() <= lim[i],
                "{o:?}"
            );
            assert!(finite(o.reference_rate[i]), "{x:?} {o:?}");
        }
        clean_state(&st);
    }
}

/// The whole wrist on `S`.
fn step<S: Scalar>(p: &WristStepParams, samples: &[[u64; 6]]) {
    let cfg = WristStepConfig::<S>::new(p);
    let s = p.settings();
    let phi = s.kinematics.phi();
    let limits = s.modes.admittance().limits();
    let tol = round_trip_bound::<S>();
    let first = samples.first().copied().unwrap_or_default();
    let motors0 = MotorAngles {
        theta1: q::<S>(value(first[4], 4.0)),
        theta3: q::<S>(value(first[5], 4.0)),
    };
    let mut st = cfg.state(motors0);
    clean_state(&st);
    let torque_limit = [
        cfg.active().law(0).torque_limit(),
        cfg.active().law(1).torque_limit(),
    ];
    for (k, w) in samples.iter().enumerate() {
        let sg: [S; 6] = core::array::from_fn(|i| {
            // Gauge signals mostly small (a push of a few N·m), some raw.
            q::<S>(value(w[i].rotate_left(11 * k as u32 + 5), 0.05))
        });
        let readings = WristReadings {
            gauges: sg,
            motors: MotorAngles {
                theta1: q::<S>(value(w[0].rotate_left(23), 4.0)),
                theta3: q::<S>(value(w[1].rotate_left(23), 4.0)),
            },
            motor_velocity: [
                q::<S>(value(w[2].rotate_left(29), 20.0)),
                q::<S>(value(w[3].rotate_left(29), 20.0)),
            ],
        };
        let target = WristTarget {
            pose: PitchYaw {
                delta: q::<S>(value(w[4].rotate_left(31), 0.7)),
                gamma: q::<S>(value(w[5].rotate_left(31), 0.7)),
            },
            rate: [
                q::<S>(value(w[0].rotate_left(41), 2.0)),
                q::<S>(value(w[1].rotate_left(41), 2.0)),
            ],
            request: match (w[2] >> 5) & 15 {
                0 => Some(WristMode::Active),
                1 => Some(WristMode::Passive),
                _ => None,
            },
        };
        let o = cfg.update(&mut st, &readings, &target);
        let inputs = sg
            .iter()
            .chain([readings.motors.theta1, readings.motors.theta3].iter())
            .chain(readings.motor_velocity.iter())
            .chain([target.pose.delta, target.pose.gamma].iter())
            .chain(target.rate.iter())
            .copied()
            .collect::<Vec<S>>();
        let bad = !is_fixed::<S>() && inputs.iter().any(|v| !finite(*v));
        // Every field finite on every backend (`WristOutput` docs).
        let fields = [
            o.motor_torque[0],
            o.motor_torque[1],
            o.interaction[0],
            o.interaction[1],
            o.joint_torque[0],
            o.joint_torque[1],
            o.reference.delta,
            o.reference.gamma,
            o.motor_reference.theta1,
            o.motor_reference.theta3,
            o.motor_reference_rate[0],
            o.motor_reference_rate[1],
        ];
        assert!(
            fields.iter().all(|v| finite(*v)),
            "{readings:?} {target:?} {o:?}"
        );
        for i in 0..2 {
            assert!(o.motor_torque[i].abs() <= torque_limit[i], "{o:?}");
            assert_eq!(o.motor_torque[i], o.laws[i].torque);
        }
        if bad {
            assert!(o.invalid_input, "{readings:?} {target:?}: {o:?}");
        }
        if o.invalid_input && !bad {
            // Documented: finite inputs so large that a product overflows
            // are flagged like non-finite ones. Below `big` nothing can:
            // with every input and the start position at most `X` in
            // magnitude, the tracking error is at most `2X + 16π`, `r` at
            // most `λ(2X + 16π) + X + 2π/T` (λ = 160, T = 4 ms), the
            // friction regressor at most `X²` (`q̇²`, and `e^{−f_τ q̇²}`
            // vanishes before it can meet an infinity), so the largest
            // product `r·q̇` is below `400 X²`, and the interaction below
            // `(2 + l)·B` (see `ft`) times `‖J‖ ≤ 2`. `X = 1e15` on `f32`
            // (`400 X² = 4e32`), `1e150` on `f64`.
            let x = if S::NAME == "f32" { 1e15 } else { 1e150 };
            let largest = inputs
                .iter()
                .chain([motors0.theta1, motors0.theta3].iter())
                .map(|v| v.to_f64().abs())
                .fold(0.0, f64::max);
            let mat = s.sensor.decoupling().matrix();
            let b = largest_row_sum(&mat, &sg);
            let reach = 2.0 * (2.0 + s.sensor.offset()) * b;
            assert!(
                largest > x || reach > x,
                "{} flagged with finite inputs {readings:?} {target:?}: {o:?}",
                S::NAME
            );
        }
        if !is_fixed::<S>() && sg.iter().any(|v| !finite(*v)) {
            assert!(o.interaction == [S::ZERO; 2], "{o:?}");
        }
        assert_eq!(o.saturated, o.reference_saturated || o.torque_saturated);
        assert_eq!(o.mode, st.mode());
        // The reference: in the mode manager's box and the reachable cone.
        let (rd, rg) = (o.reference.delta.to_f64(), o.reference.gamma.to_f64());
        assert!(
            rd.abs() <= limits[0] + tol && rg.abs() <= limits[1] + tol,
            "{o:?}"
        );
        assert!(bend(rd, rg) <= 2.0 * phi + tol, "{o:?}");
        // |det J| ≤ Sφ sin β / D with D ≥ cos 3φ (module docs of
        // `wrist::jacobian`): a reference bent so little that this is
        // below DET_MIN/2 must be flagged singular.
        let b = bend(rd, rg) + tol;
        let d_min = (3.0 * phi).cos() - 2.0 * tol;
        if d_min > 0.0 && phi.sin() * b.sin() / d_min < DET_MIN / 2.0 {
            assert!(o.singular, "straight reference {o:?}");
        }
        if o.torque_saturated {
            assert!(
                (0..2).any(|i| o.motor_torque[i].abs() == torque_limit[i]),
                "{o:?}"
            );
        }
        clean_state(&st);
    }
}

/// `B = max_i Σ_j |M_ij| |SG_j|`: the largest decoupled wrench component
/// the gauge signals can reach through the matrix (eq. 6.35).
fn largest_row_sum<S: Scalar>(mat: &[[f64; 6]; 6], sg: &[S; 6]) -> f64 {
    mat.iter()
        .map(|row| {
            row.iter()
                .zip(sg.iter())
                .map(|(m, g)| m.abs() * g.to_f64().abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

fuzz_target!(|data: (u32, [u64; 16], Vec<[u64; 6]>)| {
    let (flags, raw, samples) = data;
    let flag = |k: u32| flags & (1 << k) != 0;
    // Raw parameter fields in half of the inputs only, so that the other
    // half reaches the maps with accepted parameters.
    let raw_ok = flag(31);
    let rflag = |k: u32| raw_ok && flag(k);
    let samples = &samples[..samples.len().min(16)];

    // The kinematics: φ raw, or 16° times a factor in [1/20, 2.5]
    // (0.8°–40°, a quarter of it outside the accepted [1°, 30°]).
    let phi_in = field(raw[0], rflag(0), 16f64.to_radians(), 0.05, 2.5);
    // The thesis's wrist, and both edges of the accepted range exactly.
    let phi_in = match (flag(1), flag(18), flag(19)) {
        (true, _, _) => 16f64.to_radians(),
        (_, true, false) => 30f64.to_radians(),
        (_, false, true) => 1f64.to_radians(),
        _ => phi_in,
    };
    let params = match WristParams::try_new(phi_in) {
        Ok(p) => {
            assert!(phi_in >= 1f64.to_radians() && phi_in <= 30f64.to_radians());
            p
        }
        Err(e) => {
            assert!(
                !(phi_in >= 1f64.to_radians() && phi_in <= 30f64.to_radians()),
                "{phi_in}"
            );
            typed(e);
            WristParams::thesis()
        }
    };
    let thesis = params == WristParams::thesis();
    kinematics::<f64>(&params, samples, thesis);
    kinematics::<f32>(&params, samples, thesis);
    kinematics::<I16F16>(&params, samples, thesis);

    // The gauge amplifier: G ∈ [1, 10⁴].
    let gain = field(raw[1], rflag(2), 100.0, 1e-3, 1e3);
    match GaugeAmplifier::try_new(gain) {
        Ok(a) => {
            assert!((1.0..=1e4).contains(&gain));
            let (vr, vin) = (value(raw[2], 2.5), value(raw[3], 1e-2));
            if vr.is_finite() && vin.is_finite() && vr.abs() <= 1e3 && vin.abs() <= 1e3 {
                // Three roundings: V_out, SG and SG/G, each ½ ulp of its
                // magnitude (≤ |V_ref| + G|v_in|), relative to v_in's scale.
                let back = a.bridge_voltage(GaugeAmplifier::gauge_signal(a.output(vr, vin), vr));
                let t = 2.0 * f64::EPSILON * (vr.abs() + gain * vin.abs()) / gain
                    + f64::EPSILON * vin.abs();
                assert!((back - vin).abs() <= t, "{back} vs {vin}");
            }
        }
        Err(e) => {
            assert!(!(1.0..=1e4).contains(&gain), "{gain}");
            typed(e);
        }
    }

    // The decoupling matrix: the example's entries each scaled, or raw.
    let ex = *DecouplingMatrix::example().matrix();
    let mut mat = ex;
    for (i, row) in mat.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let b = raw[(i * 6 + j) % 16].rotate_left((i * 6 + j) as u32);
            *v = if rflag(3) && b & 0x3f == 0 {
                f64::from_bits(b)
            } else if flag(4) {
                field(b, false, *v, 0.25, 4.0)
            } else {
                *v
            };
        }
    }
    let maxc = if rflag(5) {
        f64::from_bits(raw[4])
    } else {
        DEFAULT_MAX_CONDITION
    };
    let dm = match DecouplingMatrix::try_new(mat, maxc) {
        Ok(d) => {
            assert!(mat.iter().flatten().all(|v| v.is_finite()));
            assert!(maxc >= 1.0 && d.condition() <= maxc && d.condition() >= 1.0 - 1e-9);
            d
        }
        Err(e) => {
            typed(e);
            DecouplingMatrix::example()
        }
    };
    let offset = field(raw[5], rflag(6), 0.05, 0.01, 40.0);
    let sensor = match FtSensorParams::try_new(dm, offset) {
        Ok(s) => {
            assert!((0.0..=1.0).contains(&offset));
            s
        }
        Err(e) => {
            assert!(!(0.0..=1.0).contains(&offset));
            typed(e);
            FtSensorParams::try_new(dm, 0.05).unwrap()
        }
    };
    ft::<f64>(&sensor, samples);
    ft::<f32>(&sensor, samples);
    ft::<I16F16>(&sensor, samples);

    // The admittance law: the gain drawn around its discrete-time limit.
    let lag = if rflag(7) {
        (raw[6] & 0xff) as u8
    } else {
        (raw[6] % 4) as u8
    };
    let stiffness = field(raw[7], rflag(8), 200.0, 0.01, 100.0);
    let period = if rflag(9) {
        f64::from_bits(raw[8])
    } else {
        0.004
    };
    let a = 2.0 * (PI / (2.0 * (2.0 * lag as f64 + 1.0))).sin();
    let kmax = a / (period * stiffness);
    let lim = field(raw[9], rflag(10), 0.5, 0.25, 4.0);
    let adm = AdmittanceSettings {
        gain: [
            field(raw[10], rflag(11), kmax, 0.25, 2.0),
            field(raw[10].rotate_left(32), rflag(11), kmax, 0.1, 1.5),
        ],
        stiffness,
        sample_period: period,
        lag_samples: lag,
        limits: [
            lim,
            field(raw[9].rotate_left(32), rflag(10), 0.5, 0.25, 4.0),
        ],
        max_rate: field(raw[11], rflag(12), 1.0, 0.01, 100.0),
        deadband: field(raw[12], rflag(12), 0.05, 0.01, 100.0) - if flag(13) { 0.1 } else { 0.0 },
        desired_torque: [
            0.0,
            field(raw[13], rflag(12), 0.5, 0.1, 1e4) * if flag(14) { -1.0 } else { 1.0 },
        ],
    };
    let rule = admittance_rules(&adm);
    let adm_params = match AdmittanceParams::try_new(adm) {
        Ok(p) => {
            assert_ne!(rule, Some(false), "accepted {adm:?}");
            admittance::<f64>(&p, &adm, samples);
            admittance::<f32>(&p, &adm, samples);
            admittance::<I16F16>(&p, &adm, samples);
            Some(p)
        }
        Err(e) => {
            assert_ne!(rule, Some(true), "rejected {adm:?}: {e}");
            typed(e);
            None
        }
    };

    // The mode manager (its own admittance law, or the thesis's).
    let adm_p = adm_params.unwrap_or_else(|| AdmittanceParams::thesis(200.0).unwrap());
    let t = adm_p.sample_period();
    let ms = WristModeSettings {
        admittance: adm_p,
        enter_passive: field(raw[14], rflag(15), 1.0, 0.25, 4.0),
        exit_passive: field(raw[14].rotate_left(32), rflag(15), 0.5, 0.25, 4.0),
        rest_speed: field(raw[15], rflag(16), 0.01, 0.1, 10.0),
        debounce: (raw[15] & 0xf) as u16,
        dwell: ((raw[15] >> 4) & 0x3f) as u16,
        rejoin_bandwidth: field(raw[15].rotate_left(32), rflag(16), 0.1 / t, 0.1, 8.0),
    };
    let mode_rules = ms.exit_passive.is_finite()
        && ms.exit_passive > 0.0
        && ms.enter_passive.is_finite()
        && ms.exit_passive < ms.enter_passive
        && ms.enter_passive <= 1e3
        && ms.rest_speed.is_finite()
        && ms.rest_speed > 0.0
        && ms.debounce >= 1
        && ms.rejoin_bandwidth.is_finite()
        && ms.rejoin_bandwidth > 0.0
        && ms.rejoin_bandwidth <= 0.5 / t;
    let mode_params = match WristModeParams::try_new(ms) {
        Ok(m) => {
            assert!(mode_rules, "accepted {ms:?}");
            assert_eq!(m.settings(), ms);
            modes::<f64>(&m, adm_p.limits(), samples);
            modes::<f32>(&m, adm_p.limits(), samples);
            modes::<I16F16>(&m, adm_p.limits(), samples);
            Some(m)
        }
        Err(e) => {
            assert!(!mode_rules, "rejected {ms:?}: {e}");
            typed(e);
            None
        }
    };

    // The whole wrist.
    let Some(mp) = mode_params else { return };
    let Ok(active) = WristActiveParams::table_6_1() else {
        panic!("Table 6.1 preset rejected");
    };
    let ss = WristStepSettings {
        kinematics: params,
        sensor,
        active,
        modes: mp,
        initial_mode: if flag(17) {
            WristMode::Passive
        } else {
            WristMode::Active
        },
    };
    match WristStepParams::try_new(ss) {
        Ok(p) => {
            assert_eq!(t, 0.004);
            step::<f64>(&p, samples);
            step::<f32>(&p, samples);
            step::<I16F16>(&p, samples);
        }
        Err(e) => {
            assert_ne!(t, 0.004);
            typed(e);
        }
    }
});
