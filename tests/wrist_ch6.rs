//! Thesis ch. 6 in closed loop: Theorem 2's ultimate bound (eq.
//! 6.24–6.27) on the sampled wrist with arm motion and F/T noise inside
//! Assumptions 7–10, the sampled Table 6.1 law (errata E6.3), and the door
//! opening of §6.4.4.
//!
//! Thresholds are derived in each test's comment; none is tuned to the
//! measured value.
#![cfg(feature = "sim")]

use core::f64::consts::TAU;
use mrr_control::control::UltimateBound;
use mrr_control::sim::closed_loop::sampled_sliding_radius;
use mrr_control::sim::door::{
    door_opening, door_wrist_design, DoorConfig, DoorControl, DoorRun, FrictionAxis,
};
use mrr_control::sim::SplitMix64;
use mrr_control::wrist::active::{
    base_acceleration, base_acceleration_bound, WristActiveConfig, WristActiveParams,
    WristJointSample, WristMotorDesign,
};
use proptest::prelude::*;
use std::sync::OnceLock;

/// One random case of Theorem 2's check, for both wrist motors.
#[derive(Debug, Clone)]
struct WristCase {
    /// Plant friction per motor `[b, f_c, f_s]` (motor torque vs joint
    /// speed), inside the design's box; `f_τ = 1` (the box fixes it).
    friction: [[f64; 3]; 2],
    /// Position ripple `f_q = A sin(5 q)` amplitude, N·m (Assumption 7).
    ripple: f64,
    /// Arm joint motion `A_j sin(w_j t)`: amplitudes (rad) and rates
    /// (rad/s), and the rotor axis and arm axes (unit vectors).
    arm: [[f64; 2]; 3],
    axes: [[f64; 3]; 4],
    /// Joint trajectory `A (1 − cos 2πt/P)` per motor.
    trajectory: [[f64; 2]; 2],
    /// Interaction torque on each joint `E sin(w_e t)`, N·m joint side.
    interaction: [[f64; 2]; 2],
    /// F/T error: uniform in `±fraction · ρ_τt`, or a constant bias of
    /// `fraction · ρ_τt` when `bias`.
    error_fraction: f64,
    bias: bool,
    seed: u64,
}

#[derive(Debug, Clone)]
struct WristBoundRun {
    bound: [UltimateBound; 2],
    radius: [f64; 2],
    max_sliding: [f64; 2],
    reaching_time: [f64; 2],
    max_feedback_error: f64,
    max_base_acceleration: f64,
    rho_base: f64,
    saturated: usize,
    step_ratio: f64,
    samples: usize,
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
    [v[0] / n, v[1] / n, v[2] / n]
}

/// The bound check's design: [`door_wrist_design`] (the 4 ms-capable
/// retuning of Table 6.1, errata E6.3) with `ρ_f` and `ρ_fq` covering the
/// Karnopp plant: its friction is within `±(f_c + f_s)` while sticking,
/// so `|f − b q̇ − F(q̇) sat(q̇, ε_q̇)| ≤ 2(f_c + f_s) ≤ 2·0.011 = 0.022`
/// (box max + ρ_F), which `ρ_f = 0.022` (the box's
/// `boundary_layer_bound`) plus `ρ_fq = 0.022 + 0.005` (the ripple) cover,
/// as in ch. 4's `bound_design`.
fn bound_design() -> WristMotorDesign {
    let mut d = door_wrist_design(0.004);
    d.law.uncertainty.boundary_layer = d.law.friction_bounds.boundary_layer_bound();
    d.law.uncertainty.nonparametric_friction = 0.027;
    d
}

/// Eq. (6.4) per motor in motor torque: `I_m N q̈ + f(q̇) + f_q(q) +
/// I_m a_base + τ_t/N = τ_m`, Karnopp friction at a 0.25 ms step, the
/// law at 4 ms on the encoder (2000·531 counts per joint turn) and the
/// one-sample speed. The sampling disturbance `δ_i` is measured as in
/// ch. 4: the law evaluated on the true state after every substep with
/// the held state and feedback, against the applied law value.
fn wrist_bound_run(case: &WristCase, design: &WristMotorDesign, duration: f64) -> WristBoundRun {
    let params = WristActiveParams::try_new([*design; 2]).expect("valid design");
    let law = WristActiveConfig::<f64>::new(&params);
    let d = params.laws()[0].design();
    let (m, n, lam, t) = (d.rotor_inertia, d.ratio, d.lambda, d.sample_period);
    let im = design.rotor_inertia;
    let sub = 16;
    let dt = t / sub as f64;
    let mut rng = SplitMix64::new(case.seed);
    let mut plant = [0, 1].map(|i| FrictionAxis {
        inertia: m,
        coulomb: case.friction[i][1],
        static_excess: case.friction[i][2],
        stribeck: 1.0,
        viscous: case.friction[i][0],
        position: 0.0,
        velocity: 0.0,
        acceleration: 0.0,
    });
    let traj = |i: usize, tt: f64| {
        let [a, p] = case.trajectory[i];
        let w = TAU / p;
        (
            a * (1.0 - (w * tt).cos()),
            a * w * (w * tt).sin(),
            a * w * w * (w * tt).cos(),
        )
    };
    let arm = |tt: f64| {
        let mut q = [0.0; 3];
        let mut qd = [0.0; 3];
        let mut qdd = [0.0; 3];
        for j in 0..3 {
            let [a, w] = case.arm[j];
            q[j] = a * (w * tt).sin();
            qd[j] = a * w * (w * tt).cos();
            qdd[j] = -a * w * w * (w * tt).sin();
        }
        let _ = q;
        let axes = [case.axes[1], case.axes[2], case.axes[3]];
        (base_acceleration(case.axes[0], &axes, &qd, &qdd), qd, qdd)
    };
    let rho_base = base_acceleration_bound(
        &case.arm.map(|[a, w]| a * w),
        &case.arm.map(|[a, w]| a * w * w),
    );
    let tau_t = |i: usize, tt: f64| {
        let [e, w] = case.interaction[i];
        e * (w * tt).sin()
    };
    let bound = [params.ultimate_bound(0), params.ultimate_bound(1)];
    // V(0): on the trajectory at rest (r = 0), ∫r = 0, F̃ = F − F̂(0).
    let f0 = d.initial_friction.to_array();
    let reaching_time = [0, 1].map(|i| {
        let ft = [
            case.friction[i][0] - f0[0],
            case.friction[i][1] - f0[1],
            case.friction[i][2] - f0[2],
            0.0,
        ];
        bound[i].reaching_time(UltimateBound::lyapunov(d, 0.0, 0.0, &ft), 0.0)
    });
    let mut st = law.initial_state();
    let rad = TAU / (2000.0 * n);
    let mut last = [0.0f64; 2];
    let (mut delta, mut max_r, mut max_fe, mut max_ab) = ([0.0f64; 2], [0.0f64; 2], 0.0f64, 0.0f64);
    let mut sat = 0usize;
    let total = (duration / t).round() as usize;
    let amp = case.error_fraction * d.uncertainty.torque_estimate;
    for k in 0..total {
        let time = k as f64 * t;
        let mut x = [WristJointSample::<f64>::default(); 2];
        let mut fb = [0.0; 2];
        for i in 0..2 {
            let q = (plant[i].position / rad).round() * rad;
            let v = (q - last[i]) / t;
            last[i] = q;
            let err = if case.bias {
                amp
            } else {
                amp * (2.0 * rng.uniform() - 1.0)
            };
            fb[i] = tau_t(i, time) + err;
            let (qd, vd, ad) = traj(i, time);
            x[i] = WristJointSample {
                desired_position: qd,
                desired_velocity: vd,
                desired_acceleration: ad,
                position: q,
                velocity: v,
                interaction_torque: fb[i],
            };
        }
        let held = st;
        let o = law.update(&mut st, &x);
        sat += o.iter().filter(|m| m.saturated).count();
        for s in 0..sub {
            let tt = time + s as f64 * dt;
            let (ab, _, _) = arm(tt);
            max_ab = max_ab.max(ab.abs());
            for i in 0..2 {
                let p = &mut plant[i];
                let fq = case.ripple * (5.0 * p.position).sin();
                let drive = o[i].torque - fq - im * ab - tau_t(i, tt) / n;
                p.step(dt, drive);
            }
            let te = time + (s + 1) as f64 * dt;
            for i in 0..2 {
                let (qd, vd, ad) = traj(i, te);
                let (q, v) = (plant[i].position, plant[i].velocity);
                let xc = WristJointSample {
                    desired_position: qd,
                    desired_velocity: vd,
                    desired_acceleration: ad,
                    position: q,
                    velocity: v,
                    interaction_torque: fb[i],
                };
                let mut scratch = held.motors()[i];
                let tc = law
                    .law(i)
                    .update(&mut scratch, &xc.to_control_input())
                    .law_torque;
                delta[i] = delta[i].max((o[i].law_torque - tc).abs());
                max_fe = max_fe.max((fb[i] - tau_t(i, te)).abs());
                if te >= reaching_time[i] {
                    max_r[i] = max_r[i].max(((v - vd) + lam * (q - qd)).abs());
                }
            }
        }
    }
    WristBoundRun {
        bound,
        radius: [0, 1]
            .map(|i| sampled_sliding_radius(bound[i].damping, bound[i].dissipation, delta[i])),
        max_sliding: max_r,
        reaching_time,
        max_feedback_error: max_fe,
        max_base_acceleration: max_ab,
        rho_base,
        saturated: sat,
        step_ratio: bound[0].boundary_layer_step_ratio,
        samples: 2 * total,
    }
}

/// A case inside Assumptions 7–10 and Property 2: friction inside the
/// box (`b ≤ 2e-3`, `f_c, f_s ≤ 0.01`), ripple ≤ 0.005 N·m, arm motion
/// whose bound of eq. (6.9) is ≤ 3·10.8 + 3·1.8² = 42 ≤ ρ_base = 50, an
/// interaction torque up to 20 N·m at ≤ 3 rad/s (its change over a 4 ms
/// hold ≤ 0.24 N·m) and F/T noise within 0.7 ρ_τt: the held feedback
/// error stays below ρ_τt = 1 N·m (checked).
fn wrist_case() -> impl Strategy<Value = WristCase> {
    let axis =
        || (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(a, b, c)| unit([a, b, c + 1e-3]));
    (
        (
            [
                (0.0..2e-3f64, 0.0..0.01f64, 0.0..0.01f64),
                (0.0..2e-3f64, 0.0..0.01f64, 0.0..0.01f64),
            ],
            0.0..0.005f64,
        ),
        (
            [
                (0.0..0.3f64, 1.0..6.0f64),
                (0.0..0.3f64, 1.0..6.0f64),
                (0.0..0.3f64, 1.0..6.0f64),
            ],
            [axis(), axis(), axis(), axis()],
        ),
        (
            [(0.0..0.3f64, 1.5..4.0f64), (0.0..0.3f64, 1.5..4.0f64)],
            [(0.0..20.0f64, 0.0..3.0f64), (0.0..20.0f64, 0.0..3.0f64)],
            0.0..0.7f64,
            any::<u64>(),
        ),
    )
        .prop_map(
            |((fr, ripple), (arm, axes), (tr, it, ef, seed))| WristCase {
                friction: fr.map(|(b, c, s)| [b, c, s]),
                ripple,
                arm: arm.map(|(a, w)| [a, w]),
                axes,
                trajectory: tr.map(|(a, p)| [a, p]),
                interaction: it.map(|(e, w)| [e, w]),
                error_fraction: ef,
                bias: false,
                seed,
            },
        )
}

const DURATION: f64 = 3.0;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Theorem 2 on the sampled wrist (both motors): after the reaching
    /// time of eq. (6.27), the true `|r_i|` stays within `r̄(δ_i)`, the set
    /// of eq. (6.25)–(6.26) widened by the sampling disturbance measured on
    /// the same run (ch. 4's `sampled_sliding_radius`, derived there from
    /// eq. 4.28, whose ch. 6 form is eq. 6.24 with `I_m → I_m N`). The
    /// premises are checked, not assumed: the step ratio below 1 (errata
    /// E6.3), no sample at the torque limit, the arm acceleration of eq.
    /// (6.9) within `ρ_base`, the held F/T error within `ρ_τt` (eq. 6.11).
    #[test]
    fn wrist_sliding_variable_stays_within_theorem_2_bound(case in wrist_case()) {
        let run = wrist_bound_run(&case, &bound_design(), DURATION);
        prop_assert!(run.step_ratio < 1.0, "{run:?}");
        prop_assert_eq!(run.saturated, 0, "{:?}", run);
        prop_assert!(run.rho_base <= 50.0 && run.max_base_acceleration <= run.rho_base + 1e-9, "{run:?}");
        prop_assert!(run.max_feedback_error <= 1.0, "{run:?}");
        for i in 0..2 {
            prop_assert!(run.reaching_time[i] < 0.5 * DURATION, "{run:?}");
            prop_assert!(run.radius[i] >= run.bound[i].sliding_radius);
            prop_assert!(run.max_sliding[i] <= run.radius[i], "motor {i}: {case:?} {run:?}");
        }
    }
}

/// The check can fail: an F/T bias of 150 ρ_τt = 150 N·m on both joints
/// (violating eq. 6.11). Steady state of the r dynamics with the bias:
/// `I_m N λ r ≈ E/N − z_max − K_r − ρ_F2 − ρ_F3` with `E/N = 0.2825`,
/// `z_max = 0.02`, `K_r = 0.022 + 0.027 + 5.3e-5 + 0.0019 = 0.051`,
/// `ρ_F2 + ρ_F3 = 0.002`: `r ≈ 0.2095/0.01115 ≈ 18.8 rad/s`. The widened
/// radius grows with the disturbance the bias also causes (through the
/// speed measurement's lag at that `r`), but only like `δ/(I_m N λ)`: it
/// stays well below (about 8 rad/s here; 60 ρ_τt would give `r ≈ 4` and
/// stay inside it, which is why the bias is larger than ch. 4's). The
/// same case with a bias of 0.9 ρ_τt stays inside.
#[test]
fn violated_sensor_bound_exceeds_the_ultimate_bound() {
    let mut case = WristCase {
        friction: [[1e-3, 0.006, 0.003]; 2],
        ripple: 0.003,
        arm: [[0.2, 2.0], [0.1, 3.0], [0.1, 1.0]],
        axes: [
            unit([0.0, 0.3, 1.0]),
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        trajectory: [[0.2, 2.0], [-0.1, 3.0]],
        interaction: [[5.0, 1.0], [-3.0, 2.0]],
        error_fraction: 0.9,
        bias: true,
        seed: 3,
    };
    let ok = wrist_bound_run(&case, &bound_design(), DURATION);
    for i in 0..2 {
        assert!(ok.max_sliding[i] <= ok.radius[i], "{ok:?}");
    }
    case.error_fraction = 150.0;
    let bad = wrist_bound_run(&case, &bound_design(), DURATION);
    assert!(bad.max_feedback_error > 140.0);
    assert!(
        bad.max_sliding[0] > bad.radius[0] && bad.max_sliding[1] > bad.radius[1],
        "a violated assumption should exceed the bound: {bad:?}"
    );
}

/// Errata E6.3: Table 6.1 sampled at the thesis's 4 ms. The E4.4 step
/// ratio of the law (ch. 4's calculator on the ch. 6 design) is
/// `T (K_r/ε_r + I_m N λ)/(I_m N) = 0.004 (0.5419357/0.1 + 0.089208)/
/// 5.5755e-4 = 39.52` by hand: far above 2, so the sampled robust term
/// cannot settle in its layer (it needs `T < 2/(K_r/(ε_r I_m N) + λ) =
/// 0.20 ms`). In closed loop (a bound case, Table 6.1's law) a sample
/// inside the layer is thrown out of it (`r ← (1 − 39.5) r`), and outside
/// the robust term alone is `K_r = 0.542 N·m`, which with the `λ² I_m N e`
/// and feedback terms reaches the 0.6 N·m limit: expected, the command
/// at its limit in more than half the samples and `|r|` an order of
/// magnitude above the retuned design's, which never saturates and stays
/// inside its own bound.
#[test]
fn table_6_1_chatters_at_4ms() {
    let p = WristActiveParams::table_6_1().unwrap();
    let ratio = p.ultimate_bound(0).boundary_layer_step_ratio;
    let hand = 0.004 * (0.5419357 / 0.1 + 0.089208) / 5.5755e-4;
    assert!((ratio - hand).abs() < 1e-3 * hand, "{ratio} vs {hand}");
    assert!((hand - 39.52).abs() < 0.01);
    let case = WristCase {
        friction: [[1e-3, 0.006, 0.003]; 2],
        ripple: 0.0,
        arm: [[0.0, 1.0]; 3],
        axes: [[0.0, 0.0, 1.0]; 4],
        trajectory: [[0.2, 2.0], [-0.1, 3.0]],
        interaction: [[0.0, 1.0]; 2],
        error_fraction: 0.0,
        bias: false,
        seed: 1,
    };
    let mut t61 = WristMotorDesign::table_6_1();
    // The plant's Stribeck shape is 1; Table 6.1's box allows it.
    t61.law.initial_friction.stribeck_shape = 1.0;
    let chatter = wrist_bound_run(&case, &t61, 1.0);
    let smooth = wrist_bound_run(&case, &bound_design(), 1.0);
    let sat = |r: &WristBoundRun| r.saturated as f64 / r.samples as f64;
    assert!(sat(&chatter) > 0.5, "{}", sat(&chatter));
    assert_eq!(smooth.saturated, 0);
    for i in 0..2 {
        assert!(
            chatter.max_sliding[i] > 10.0 * smooth.max_sliding[i],
            "{chatter:?} {smooth:?}"
        );
        assert!(smooth.max_sliding[i] <= smooth.radius[i]);
    }
}

/// Seeds of the door runs (slip and jerk sequences).
const DOOR_SEEDS: [u64; 3] = [3, 6, 7];

fn door_runs() -> &'static Vec<[DoorRun; 3]> {
    static R: OnceLock<Vec<[DoorRun; 3]>> = OnceLock::new();
    R.get_or_init(|| {
        DOOR_SEEDS
            .iter()
            .map(|&seed| {
                [
                    door_opening(&DoorConfig::thesis(DoorControl::Passive, 0.0, seed)),
                    door_opening(&DoorConfig::thesis(
                        DoorControl::Passive,
                        3f64.to_radians(),
                        seed,
                    )),
                    door_opening(&DoorConfig::thesis(DoorControl::ActiveHold, 0.0, seed)),
                ]
            })
            .collect()
    })
}

/// §6.4.4 qualitatively, for three slip/jerk sequences. In every run the
/// door opens (the base carries the grasp round; at least 80° of the
/// planned 90°), the passive wrist stays inside its ±30° workspace and its
/// motors are never at their limit.
///
/// *Passive against held.* The held wrist must absorb every deviation of
/// the base from the door's circle through the grasp's yaw stiffness; the
/// passive one yields to it. "Well below" is asserted as at most half the
/// held wrist's yaw peak (a qualitative margin, not a derived constant).
///
/// *Heading error.* A 3° error displaces the base's circle by
/// `2 ρ_b sin(1.5°) = 5.6 cm` (`ρ_b = 1.06 m`), which the passive joints
/// take up over the 12 s opening: a rate of about
/// `0.056 m / 0.75 m / 12 s ≈ 6e-3 rad/s`, i.e. `6e-3/K_c ≈ 0.06 N·m` of
/// admittance torque — small against the jerk-driven peaks. Expected: its
/// yaw peak of the same magnitude as without the error (within a factor 2
/// either way, the thesis's "comparable magnitude") and below the held
/// wrist's.
///
/// *Measured against true.* The library's F/T chain reads the true torques
/// within the gauge noise: ±0.5 mV through the torque rows of the example
/// matrix (`Σ_j |M_ij| ≤ 5.8 N·m/V`: 2.9e-3 N·m) plus `l` times the force
/// rows (`≤ 140 N/V`: 0.07 N · 0.05 m = 3.5e-3 N·m): 0.01 N·m.
#[test]
fn door_opening_passive_wrist_limits_the_interaction_torque() {
    for [nominal, heading, hold] in door_runs() {
        for r in [nominal, heading, hold] {
            assert!(
                r.door_angle > 80f64.to_radians(),
                "{}",
                r.door_angle.to_degrees()
            );
            for i in 0..2 {
                let d = (r.peak_measured[i] - r.peak_interaction[i]).abs();
                assert!(d < 0.01, "{:?} {:?}", r.peak_measured, r.peak_interaction);
            }
        }
        for r in [nominal, heading] {
            assert!(r.wrist_range[0] < 30f64.to_radians());
            assert!(r.wrist_range[1] < 30f64.to_radians());
            assert_eq!(r.saturated_samples, 0);
        }
        assert!(
            2.0 * nominal.peak_measured[1] < hold.peak_measured[1],
            "{:?} {:?}",
            nominal.peak_measured,
            hold.peak_measured
        );
        assert!(heading.peak_measured[1] < hold.peak_measured[1]);
        let ratio = heading.peak_measured[1] / nominal.peak_measured[1];
        assert!((0.5..=2.0).contains(&ratio), "{ratio}");
    }
}

/// Bumpless in motor space: the mode manager's task reference (active on a
/// trajectory, a torque pulse into Passive, guidance, release, rejoin),
/// mapped every sample through the ch. 5 inverse kinematics kept
/// continuous in time (`WristConfig::update`), gives motor references that
/// (a) reach the reference (forward kinematics back within 1e-9 rad) and
/// (b) move per sample — switching samples included — by no more than the
/// local inverse Jacobian allows: `|Δθ| ≤ 1.5 ‖J⁻¹‖∞ |Δx|∞ + 1e-9`, with
/// `J` from central differences of the forward kinematics (independent of
/// the library's Jacobians) and 1.5 covering its variation over one step.
/// The path stays away from the straight pose, where `J` is singular.
#[test]
fn mode_switching_is_bumpless_through_the_inverse_kinematics() {
    use mrr_control::wrist::admittance::AdmittanceParams;
    use mrr_control::wrist::modes::{
        WristMode, WristModeConfig, WristModeInput, WristModeParams, WristModeSettings,
    };
    use mrr_control::wrist::{IkState, MotorAngles, PitchYaw, WristConfig, WristParams};
    let kin = WristConfig::<f64>::new(&WristParams::thesis());
    let fk = |m: MotorAngles<f64>| {
        let p = kin.forward(m).pose;
        [p.delta, p.gamma]
    };
    let a = AdmittanceParams::thesis(200.0).unwrap();
    let modes = WristModeConfig::<f64>::new(
        &WristModeParams::try_new(WristModeSettings {
            admittance: a,
            enter_passive: 1.5,
            exit_passive: 0.5,
            rest_speed: 0.01,
            debounce: 5,
            dwell: 50,
            rejoin_bandwidth: 10.0,
        })
        .unwrap(),
    );
    let x0 = [0.2, 0.1];
    let mut st = modes.initial_state(WristMode::Active, x0);
    let mut ik = IkState::new(
        kin.inverse(PitchYaw {
            delta: x0[0],
            gamma: x0[1],
        })
        .motors,
    );
    let (mut last_x, mut last_m) = (x0, ik.motors);
    let mut switches = 0;
    for k in 0..2500 {
        let t = k as f64 * 0.004;
        let desired = [0.2 + 0.05 * t.sin(), 0.1 + 0.03 * (0.5 * t).sin()];
        let desired_rate = [0.05 * t.cos(), 0.015 * (0.5 * t).cos()];
        let tau = if (1.0..1.2).contains(&t) {
            [2.0, -2.0]
        } else if (1.2..5.0).contains(&t) {
            [0.3 + 0.1 * (3.0 * t).sin(), -0.3]
        } else {
            [0.0, 0.0]
        };
        let o = modes.update(
            &mut st,
            &WristModeInput {
                desired,
                desired_rate,
                interaction: tau,
                request: None,
            },
        );
        switches += o.switched as usize;
        let inv = kin.update(
            &mut ik,
            PitchYaw {
                delta: o.reference[0],
                gamma: o.reference[1],
            },
        );
        assert!(!inv.saturated && !inv.straight, "k={k}");
        let back = fk(inv.motors);
        assert!((back[0] - o.reference[0]).abs() < 1e-9 && (back[1] - o.reference[1]).abs() < 1e-9);
        // ‖J⁻¹‖∞ at the previous motors by central differences of FK.
        let h = 1e-6;
        let m = last_m;
        let col = |d1: f64, d3: f64| {
            let p = fk(MotorAngles {
                theta1: m.theta1 + d1,
                theta3: m.theta3 + d3,
            });
            let q = fk(MotorAngles {
                theta1: m.theta1 - d1,
                theta3: m.theta3 - d3,
            });
            [(p[0] - q[0]) / (2.0 * h), (p[1] - q[1]) / (2.0 * h)]
        };
        let (c1, c3) = (col(h, 0.0), col(0.0, h));
        let det = c1[0] * c3[1] - c3[0] * c1[1];
        let inv_norm = ((c3[1].abs() + c3[0].abs()).max(c1[1].abs() + c1[0].abs())) / det.abs();
        let dx = (o.reference[0] - last_x[0])
            .abs()
            .max((o.reference[1] - last_x[1]).abs());
        let dm = (inv.motors.theta1 - m.theta1)
            .abs()
            .max((inv.motors.theta3 - m.theta3).abs());
        assert!(
            dm <= 1.5 * inv_norm * dx + 1e-9,
            "k={k}: {dm} vs {}",
            inv_norm * dx
        );
        last_x = o.reference;
        last_m = inv.motors;
    }
    assert_eq!(
        switches, 2,
        "into Passive at the pulse, back after the release"
    );
}
