//! Theorem 2 (thesis ch. 6, eq. 6.15–6.27) on wrist-motor plants the law's
//! model, eq. (6.4), does not describe: each of the two wrist motors drives
//! a plant built from the elements of `sim::plants` (a rotor with
//! asymmetric Maxwell-slip friction and pre-sliding, an elastic gear with
//! Maxwell-slip hysteresis, a kinematic error, a distal body with its own
//! bearing friction, a quantizing motor encoder), the arm's motion adding
//! its coupling torque (eq. 6.4, 6.9–6.10), the law sampled at the
//! thesis's 4 ms with its uncertainty bounds derived from this family
//! below.
//!
//! # Which law: the step's preset cannot be checked at 4 ms
//! The wrist step's preset ([`WristStepParams::table_6_1`]) runs both motors
//! on [`WristActiveParams::table_6_1`] at `T = 4 ms`. Its E4.4 step ratio is
//! 39.5 (errata E6.3): the premise of the sampled bound (ratio below 1, so
//! that the law stays a boundary-layer law) fails before any plant is
//! chosen (`the_step_preset_fails_the_sampling_premise`). The check runs
//! the 4 ms retuning the door, bench and engine runs use,
//! [`door_wrist_design`]`(0.004)`: Table 6.1's rotor `I_m = 1.05e-6 kg·m²`,
//! `N = 531`, friction box (`b ≤ 2e-3 N·m·s/rad` of `q̇`, `f_c, f_s ≤ 0.01
//! N·m`), `ρ_F`, `ρ_base = 50 rad/s²`, with `λ = 20`, `ε_r = 0.5`, the
//! Stribeck shape known (`f_τ = 1`), `K_I = 1`, limits 0.6 N·m and 0.02
//! N·m; its `ρ_f`, `ρ_fq`, `ρ_τt` are replaced by the derived values.
//!
//! # The plant (per motor; joint coordinate `q = θ_m/N`)
//! Rotor angle `θ_m` (motor rad), output angle `θ_o` (rad of the joint),
//! arm acceleration along the (parallel) rotor and output axes `a_b(t)`
//! ([`base_acceleration`], eq. 6.9), gear twist
//! `y = θ_m/N − θ_o + e_k(θ_m, θ_o)`, gear torque `T_g = k_g y + H(y)`:
//!
//! ```text
//! I_m (θ̈_m + a_b) = τ_m − F_m − T_g (1/N + ∂e_k/∂θ_m)
//! I_o (θ̈_o + a_b) = T_g (1 − ∂e_k/∂θ_o) − F_o − τ_t(t)
//! ```
//!
//! by virtual work, `τ_t(t) = E sin(w t)` the interaction torque the joint
//! applies to its environment (eq. 6.4's sign). Eq. (6.4) in motor torque
//! is `I_m N q̈ + f + I_m a_b + τ_t/N = τ_m`: the rotor equation above is
//! it with `f = F_m` and `τ_t` replaced by the drive's load
//! `L = T_g (1 + N ∂e_k/∂θ_m)`. The law is fed what the F/T sensor gives,
//! `τ_t(t_k) + n_k` (`|n_k| ≤ 0.2 N·m`, held over the tick); its error
//! against `L` is what eq. (6.11) bounds.
//!
//! Numbers and their sources:
//! * `N = 531` (thesis §6.4, Table 6.1; the GP 32 A gear head), `I_m =
//!   1.05e-6 kg·m²` (Table 6.1 read as g·m², see `wrist::active`);
//! * motor encoder 2000 counts per motor turn (the HEDL-5540's 500 lines,
//!   quadrature; §6.4), 0.1 count of noise (the family's);
//! * motor friction: the family's asymmetric Maxwell-slip
//!   ([`AsymmetricSlip`]) with its shares, pre-sliding displacements
//!   ([`MOTOR_PRESLIDING`], motor rad, one third to two and a half counts
//!   of the same 2000-count encoder) and asymmetry `a = 0.15`
//!   ([`MOTOR_ASYMMETRY`]), damping ratio 0.3, break-away `F` swept over
//!   half and all of the box's `f_c` limit, 0.005 and 0.01 N·m (the thesis
//!   gives no friction data for the wrist motor; the design's box is the
//!   only number), plus viscous `b_m = 2e-6 N·m·s/rad` at the motor
//!   (assumed; `b_m N = 1.06e-3` of `q̇`, inside the box);
//! * gear stiffness `k_g` 50 or 500 N·m/rad at the joint (assumed and
//!   swept: the thesis gives none), hysteresis `H` a Maxwell-slip of
//!   0.05 N·m over `[1, 2, 4, 8]e-4` rad (assumed);
//! * kinematic error: the family's draw ([`KinematicErrorPlant::draw`],
//!   Table 3.2 magnitudes, harmonics 1–4 of the input shaft) with the
//!   wrist's ratio (ripple order `2(N + 1) = 1064` per motor turn) and the
//!   family's smaller ripple, 5e-6 rad (its larger 4e-5 rad at this order
//!   gives `N ∂e_k/∂θ_m` up to 22.8, outside what the 4 ms design can
//!   cover: see "Left out");
//! * distal body `I_o` 5e-4 or 2e-3 kg·m² (assumed: a 0.5 kg gripper at
//!   2–6 cm), bearing friction `F_o` a Maxwell-slip of 0.05 N·m over the
//!   family's link pre-sliding ([`LINK_PRESLIDING`]);
//! * arm motion and axes as in `tests/wrist_ch6.rs` (three joints
//!   `A_j sin(w_j t)`, `A_j ≤ 0.3 rad`, `w_j ≤ 6 rad/s`, random unit
//!   axes), interaction `|E| ≤ 2 N·m` at `w ≤ 3 rad/s` (the step's passive
//!   switch is at 1 N·m), joint trajectory [`raised_cosine`] of amplitude
//!   0.02–0.2 rad over 1.5–3 s (peak joint speed 0.84 rad/s, 445 rad/s at
//!   the motor).
//!
//! # Derived bounds (Assumptions 7–10, Property 2)
//! * **Friction, `ρ_f + ρ_fq`.** As for Theorem 1 (`tests/theorem_family.rs`):
//!   `F_m = F_ms + b_m θ̇_m` with the Maxwell-slip part
//!   `F_ms ∈ [−F(1 − a), F(1 + a)]` held at any value with `θ̇_m` near 0
//!   after a reversal, where every eq. (6.5) form is 0; the form
//!   `F* = (b_m N, 0, 0, 1)` (in the box) leaves exactly `F_ms`. So
//!   `ρ_fq = F_max (1 + a) = 0.01·1.15 = 0.0115 N·m`, `ρ_f = 0`.
//! * **Arm coupling, `ρ_base`.** [`base_acceleration_bound`] of the arm
//!   motion's ranges: `3·(0.3·36) + 3·(0.3·6)² = 42.1 ≤ 50 rad/s²`, the
//!   design's value (kept).
//! * **Torque feedback, `ρ_τt`.** `|τ_t + n − L| ≤ |n| + |T_g − τ_t| +
//!   N |T_g| |∂e_k/∂θ_m|`, and from the output equation
//!   `T_g − τ_t = I_o (θ̈_o + a_b) + F_o + T_g ∂e_k/∂θ_o`. With an
//!   allowance `α` on `|θ̈_o + a_b|` (the trajectory needs 5.3 rad/s², the
//!   arm 42; the rest is for the distal body ringing on the gear at
//!   `√(k_g/I_o)` = 158–1000 rad/s, which the 4 ms law cannot damp),
//!   `|∂e_k/∂θ_o| ≤ o = 7.5e-5` (the output term) and
//!   `|∂e_k/∂θ_m| ≤ g = Σ h a_h + 1064·5e-6 = 3.695e-4 + 5.32e-3 =
//!   5.6895e-3`: `|T_g| ≤ T̄ = (2 + 2e-3·α + 0.05)/(1 − o)` and
//!   `ρ_τt = 0.2 + 2e-3·α + 0.05 + T̄ (o + N g)`.
//!
//!   *As first written (before the first run):* `α = 250 rad/s²`,
//!   `T̄ = 2.5502 N·m`, `ρ_τt = 8.455 N·m` (`ρ_τt/N = 0.0159 N·m` at the
//!   motor), `K_r = 0 + 0.0115 + 5.25e-5 + 0.0159 = 0.0275 N·m`, step
//!   ratio `T (K_r/ε_r + I_m N λ)/(I_m N) = 0.47`.
//!
//!   *Revised after the first run:* 64 cases saw `|θ̈_o + a_b|` up to
//!   330 rad/s² (the stiff gear with the light body ringing), above the
//!   250 allowed. Eq. (6.11), checked directly, still held (error at most
//!   6.2 N·m against 8.455), but an input of the derivation did not, so
//!   `α` is now 500 rad/s² and `|θ̈_o + a_b| ≤ α` is checked in every run
//!   with the other premises: `T̄ = (2 + 1.0 + 0.05)/(1 − o) = 3.0502 N·m`,
//!   `ρ_τt = 0.2 + 1.0 + 0.05 + 3.0502·(7.5e-5 + 531·5.6895e-3) =
//!   10.4653 N·m` (`ρ_τt/N = 0.01971 N·m`).
//!
//! The resulting robust gain is `K_r = 0 + 0.0115 + 5.25e-5 + 0.01971 =
//! 0.03126 N·m` and the step ratio
//! `T (K_r/ε_r + I_m N λ)/(I_m N) = 0.004 (0.06252 + 0.011151)/5.5755e-4 =
//! 0.53`.
//!
//! # Criteria (written before the first run)
//! Per case, both motors, over one trajectory period: the premises hold —
//! the step ratio at the peak speed below 1, no sample at the torque
//! limit, `|F_ms| ≤ ρ_fq`, `|a_b| ≤ ρ_base` (after the first run also
//! `|θ̈_o + a_b| ≤ α`, see above), and eq. (6.11) itself,
//! `|τ_t(t) + n_k − L(t)| ≤ ρ_τt` at every sample and integration step
//! (the `α` allowance is how `ρ_τt` was sized, not a premise: the error
//! it bounds is checked directly) — and after the reaching time of
//! eq. (6.27) (from `V(0)` of the true initial state and `F̃ = F* − F̂(0)`,
//! required below half the period) the true `|r_i|` stays within
//! `r̄(δ_i)`, the set of eq. (6.25)–(6.26) widened by the sampling
//! disturbance `δ_i` measured on the run as in ch. 4
//! ([`sampled_sliding_radius`]). 24 cases in the default test. The case
//! outside the assumptions: the same plant with its motor friction levels
//! ×25 must leave `r̄(δ)` (the stuck rotor lets `|e|` reach `2A` at the
//! turning point, `|r| ≈ 2λA`), and the unscaled plant on that case stay
//! inside.
//!
//! # Left out
//! The gravity of the distal body, the universal joints' coupling of the
//! two motors (each motor drives its own output here), backlash in the
//! gear head, and the family's larger kinematic-error ripple (see above).
#![cfg(feature = "sim")]

use core::f64::consts::TAU;
use mrr_control::control::{RobustAdaptiveDesign, UltimateBound};
use mrr_control::sim::closed_loop::{raised_cosine, sampled_sliding_radius};
use mrr_control::sim::door::door_wrist_design;
use mrr_control::sim::plants::drive::SLIP_SHARES;
use mrr_control::sim::plants::elements::{
    KinematicErrorPlant, MaxwellSlip, MaxwellSlipState, QuantizingEncoder,
};
use mrr_control::sim::plants::joint::{
    AsymmetricSlip, LINK_PRESLIDING, MOTOR_ASYMMETRY, MOTOR_PRESLIDING, STEP,
};
use mrr_control::sim::SplitMix64;
use mrr_control::wrist::active::{
    base_acceleration, base_acceleration_bound, WristActiveConfig, WristActiveParams,
    WristJointSample, WristMotorDesign,
};
use mrr_control::wrist::step::WristStepParams;
use proptest::prelude::*;

/// The thesis's controller period, s.
const PERIOD: f64 = 0.004;
/// Gear ratio `N` (Table 6.1).
const RATIO: f64 = 531.0;
/// Rotor inertia `I_m`, kg·m² (Table 6.1).
const ROTOR_INERTIA: f64 = 1.05e-6;
/// Motor encoder counts per motor turn (HEDL-5540, quadrature).
const MOTOR_COUNTS: f64 = 2000.0;
/// Motor break-away levels `F` swept, N·m.
const MOTOR_BREAKAWAYS: [f64; 2] = [0.005, 0.01];
/// Motor viscous friction `b_m`, N·m·s/rad (motor speed).
const MOTOR_VISCOUS: f64 = 2e-6;
/// Gear stiffness swept, N·m/rad (joint side).
const GEAR_STIFFNESS: [f64; 2] = [50.0, 500.0];
/// Gear hysteresis break-away, N·m.
const GEAR_HYSTERESIS: f64 = 0.05;
/// Gear hysteresis pre-sliding displacements, rad.
const GEAR_PRESLIDING: [f64; 4] = [1e-4, 2e-4, 4e-4, 8e-4];
/// Distal-body inertias swept, kg·m².
const OUTPUT_INERTIAS: [f64; 2] = [5e-4, 2e-3];
/// Distal-body bearing break-away, N·m.
const OUTPUT_FRICTION: f64 = 0.05;
/// Kinematic-error ripple amplitude, rad.
const RIPPLE: f64 = 5e-6;
/// Largest interaction torque `|E|`, N·m.
const INTERACTION_MAX: f64 = 2.0;
/// Largest F/T noise on the fed-back torque, N·m.
const NOISE: f64 = 0.2;
/// Allowance on `|θ̈_o + a_b|` in the derivation of `ρ_τt`, rad/s².
const OUTPUT_ACCELERATION: f64 = 500.0;
/// `ρ_base` of the design, rad/s².
const RHO_BASE: f64 = 50.0;

/// Largest `|∂e_k/∂θ_m|`, rad/rad: `Σ h a_h` of the draw's largest
/// harmonics plus the ripple's `2(N + 1) a_r`.
fn kinematic_gradient_max() -> f64 {
    let harmonics = [4.3e-5 * 1.5, 6.0e-5 * 1.5, 1.5e-5, 2.0e-5];
    let h: f64 = harmonics
        .iter()
        .enumerate()
        .map(|(i, a)| (i as f64 + 1.0) * a)
        .sum();
    h + 2.0 * (RATIO + 1.0) * RIPPLE
}

/// Largest `|∂e_k/∂θ_o|`: the output term's amplitude, rad/rad.
const OUTPUT_GRADIENT_MAX: f64 = 7.5e-5;

/// `ρ_fq = F_max (1 + a)`, N·m (motor).
fn friction_gap() -> f64 {
    MOTOR_BREAKAWAYS.iter().fold(0.0f64, |m, &f| m.max(f)) * (1.0 + MOTOR_ASYMMETRY)
}

/// `T̄`, the `|T_g|` of the derivation, N·m.
fn gear_torque_max() -> f64 {
    let io = OUTPUT_INERTIAS.iter().fold(0.0f64, |m, &i| m.max(i));
    (INTERACTION_MAX + io * OUTPUT_ACCELERATION + OUTPUT_FRICTION) / (1.0 - OUTPUT_GRADIENT_MAX)
}

/// `ρ_τt` (module docs), N·m (joint side).
fn torque_error_bound() -> f64 {
    let io = OUTPUT_INERTIAS.iter().fold(0.0f64, |m, &i| m.max(i));
    NOISE
        + io * OUTPUT_ACCELERATION
        + OUTPUT_FRICTION
        + gear_torque_max() * (OUTPUT_GRADIENT_MAX + RATIO * kinematic_gradient_max())
}

/// The 4 ms wrist design with the family's derived bounds.
fn wrist_design() -> WristMotorDesign {
    let mut d = door_wrist_design(PERIOD);
    d.law.uncertainty.boundary_layer = 0.0;
    d.law.uncertainty.nonparametric_friction = friction_gap();
    d.law.uncertainty.torque_estimate = torque_error_bound();
    d
}

/// One wrist motor's plant.
#[derive(Debug, Clone)]
struct WristMotorPlant {
    motor_friction: AsymmetricSlip,
    stiffness: f64,
    hysteresis: MaxwellSlip,
    output_inertia: f64,
    output_friction: MaxwellSlip,
}

#[derive(Debug, Clone)]
struct WristMotorState {
    /// `[θ_m, θ̇_m, θ_o, θ̇_o]`: motor rad, rad/s; joint rad, rad/s.
    x: [f64; 4],
    motor: Vec<f64>,
    hysteresis: MaxwellSlipState,
    output: MaxwellSlipState,
    kinematic_error: KinematicErrorPlant,
}

/// The 8 plants: motor break-away × gear stiffness × distal inertia.
fn wrist_family() -> Vec<WristMotorPlant> {
    let mut v = Vec::new();
    for f in MOTOR_BREAKAWAYS {
        for k in GEAR_STIFFNESS {
            for io in OUTPUT_INERTIAS {
                v.push(WristMotorPlant {
                    motor_friction: AsymmetricSlip::new(
                        f,
                        MOTOR_ASYMMETRY,
                        &MOTOR_PRESLIDING,
                        ROTOR_INERTIA,
                        0.3,
                    ),
                    stiffness: k,
                    hysteresis: MaxwellSlip::from_shares(
                        GEAR_HYSTERESIS,
                        &SLIP_SHARES,
                        &GEAR_PRESLIDING,
                    ),
                    output_inertia: io,
                    output_friction: MaxwellSlip::from_shares(
                        OUTPUT_FRICTION,
                        &SLIP_SHARES,
                        &LINK_PRESLIDING,
                    ),
                });
            }
        }
    }
    v
}

impl WristMotorPlant {
    /// `e_k`, `∂e_k/∂θ_m`, `∂e_k/∂θ_o` of the draw `k`.
    fn kinematic(k: &KinematicErrorPlant, motor: f64, output: f64) -> (f64, f64, f64) {
        let mut de_m = 0.0;
        for (h, &(a, p)) in k.wave_generator.iter().enumerate() {
            let n = h as f64 + 1.0;
            de_m += a * n * (n * motor + p).cos();
        }
        de_m += k.ripple.0 * k.ripple_order * (k.ripple_order * motor + k.ripple.1).cos();
        let de_o = k.output.0 * (output + k.output.1).cos();
        (k.error(motor, output), de_m, de_o)
    }

    /// Gear twist `y` (rad) and torque `T_g` (N·m) at `x`.
    fn gear(&self, st: &WristMotorState, x: &[f64; 4]) -> (f64, f64, f64, f64) {
        let (e, de_m, de_o) = Self::kinematic(&st.kinematic_error, x[0], x[2]);
        let y = x[0] / RATIO - x[2] + e;
        let t = self.stiffness * y + self.hysteresis.torque(&st.hysteresis, y);
        (y, t, de_m, de_o)
    }

    /// The drive's load on the rotor at the joint, `L = T_g (1 + N ∂e_k/∂θ_m)`, N·m.
    fn load(&self, st: &WristMotorState, x: &[f64; 4]) -> f64 {
        let (_, t, de_m, _) = self.gear(st, x);
        t * (1.0 + RATIO * de_m)
    }

    /// The Maxwell-slip part of the motor friction, N·m.
    fn slip_friction(&self, st: &WristMotorState, x: &[f64; 4]) -> f64 {
        self.motor_friction.torque(&st.motor, x[0], x[1])
    }

    fn derivative(
        &self,
        st: &WristMotorState,
        x: &[f64; 4],
        motor_torque: f64,
        arm: f64,
        interaction: f64,
    ) -> [f64; 4] {
        let (_, t, de_m, de_o) = self.gear(st, x);
        let f_m = self.slip_friction(st, x) + MOTOR_VISCOUS * x[1];
        let f_o = self.output_friction.torque(&st.output, x[2]);
        [
            x[1],
            (motor_torque - f_m - t * (1.0 / RATIO + de_m)) / ROTOR_INERTIA - arm,
            x[3],
            (t * (1.0 - de_o) - f_o - interaction) / self.output_inertia - arm,
        ]
    }

    /// At rest with the output at 0 and no twist (`θ_m = −N e_k`, by
    /// fixed-point iteration), the kinematic error drawn from `seed`.
    fn rest(&self, seed: u64) -> WristMotorState {
        let mut rng = SplitMix64::new(seed ^ 0x005E_ED0F_2A11);
        let kinematic_error = KinematicErrorPlant::draw(&mut rng, RIPPLE, RATIO);
        let mut m = 0.0;
        for _ in 0..60 {
            m = 0.5 * m - 0.5 * RATIO * kinematic_error.error(m, 0.0);
        }
        WristMotorState {
            x: [m, 0.0, 0.0, 0.0],
            motor: vec![m; self.motor_friction.elements.len()],
            hysteresis: self.hysteresis.relaxed(0.0),
            output: self.output_friction.relaxed(0.0),
            kinematic_error,
        }
    }

    /// One RK4 step of `h` s with the inputs held, then the friction
    /// anchors committed.
    fn step(
        &self,
        st: &mut WristMotorState,
        motor_torque: f64,
        arm: f64,
        interaction: f64,
        h: f64,
    ) {
        let x = st.x;
        let add = |a: [f64; 4], b: [f64; 4], s: f64| [0, 1, 2, 3].map(|j| a[j] + s * b[j]);
        let k1 = self.derivative(st, &x, motor_torque, arm, interaction);
        let k2 = self.derivative(st, &add(x, k1, h / 2.0), motor_torque, arm, interaction);
        let k3 = self.derivative(st, &add(x, k2, h / 2.0), motor_torque, arm, interaction);
        let k4 = self.derivative(st, &add(x, k3, h), motor_torque, arm, interaction);
        st.x = [0, 1, 2, 3].map(|j| x[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
        let (y, ..) = self.gear(st, &st.x);
        self.hysteresis.commit(&mut st.hysteresis, y);
        self.motor_friction.commit(&mut st.motor, st.x[0]);
        self.output_friction.commit(&mut st.output, st.x[2]);
    }
}

fn family() -> &'static [WristMotorPlant] {
    static F: std::sync::OnceLock<Vec<WristMotorPlant>> = std::sync::OnceLock::new();
    F.get_or_init(wrist_family)
}

/// One closed-loop case of both motors.
#[derive(Debug, Clone)]
struct Case {
    /// Plant of each motor (index into the family).
    plants: [usize; 2],
    seed: u64,
    /// Joint trajectory `[A, P]` per motor (rad, s); the run lasts the
    /// longer period.
    trajectory: [[f64; 2]; 2],
    /// Interaction `[E, w]` per motor (N·m, rad/s).
    interaction: [[f64; 2]; 2],
    /// Arm joints `[A_j, w_j]` (rad, rad/s).
    arm: [[f64; 2]; 3],
    /// Rotor axis, then the three arm axes (unit vectors).
    axes: [[f64; 3]; 4],
    /// Fraction of [`NOISE`] used by the F/T noise.
    noise: f64,
    /// Factor on the motor friction's levels (1: the family's plant).
    friction_scale: f64,
}

#[derive(Debug, Clone)]
struct Run {
    bound: [UltimateBound; 2],
    delta: [f64; 2],
    radius: [f64; 2],
    reaching_time: [f64; 2],
    max_sliding: [f64; 2],
    max_feedback_error: f64,
    max_slip_friction: f64,
    max_arm: f64,
    max_output_acceleration: f64,
    max_gear_torque: f64,
    saturated: usize,
    step_ratio: f64,
    duration: f64,
}

fn run(case: &Case) -> Run {
    let design = wrist_design();
    let params = WristActiveParams::try_new([design; 2]).expect("valid derived design");
    let law = WristActiveConfig::<f64>::new(&params);
    let d: RobustAdaptiveDesign = *params.laws()[0].design();
    let lambda = d.lambda;
    let bound = [params.ultimate_bound(0), params.ultimate_bound(1)];
    let plants = case.plants.map(|i| {
        let mut p = family()[i].clone();
        if case.friction_scale != 1.0 {
            let s = case.friction_scale;
            for e in p.motor_friction.elements.iter_mut() {
                *e = (e.0 * s, e.1 * s, e.2 * s, e.3 * s.sqrt());
            }
        }
        p
    });
    let mut st = [0, 1].map(|i| plants[i].rest(case.seed.wrapping_add(i as u64)));
    let mut rng = SplitMix64::new(case.seed ^ 0x7E57_0002);
    let encoder = QuantizingEncoder {
        counts_per_rev: MOTOR_COUNTS,
        noise_counts: 0.1,
    };
    let arm = |t: f64| {
        let mut qd = [0.0; 3];
        let mut qdd = [0.0; 3];
        for j in 0..3 {
            let [a, w] = case.arm[j];
            qd[j] = a * w * (w * t).cos();
            qdd[j] = -a * w * w * (w * t).sin();
        }
        base_acceleration(
            case.axes[0],
            &[case.axes[1], case.axes[2], case.axes[3]],
            &qd,
            &qdd,
        )
    };
    let tau_t = |i: usize, t: f64| case.interaction[i][0] * (case.interaction[i][1] * t).sin();
    let sliding =
        |x: &[f64; 4], qd: f64, vd: f64| (x[1] / RATIO - vd) + lambda * (x[0] / RATIO - qd);
    // V(0) of eq. (6.16) for F* = (b_m N, 0, 0, 1): r(0) of the true state,
    // no integral, F̃ = F* − F̂(0).
    let f0 = d.initial_friction.to_array();
    let f_tilde = [MOTOR_VISCOUS * RATIO - f0[0], -f0[1], -f0[2], 0.0];
    let reaching_time = [0, 1].map(|i| {
        let v0 = UltimateBound::lyapunov(&d, sliding(&st[i].x, 0.0, 0.0), 0.0, &f_tilde);
        bound[i].reaching_time(v0, 0.0)
    });
    let peak = case
        .trajectory
        .iter()
        .fold(0.0f64, |m, [a, p]| m.max(a * TAU / p));
    let step_ratio = UltimateBound::step_ratio_at_speed(&d, peak);
    let duration = case.trajectory[0][1].max(case.trajectory[1][1]);
    let ticks = (duration / PERIOD).round() as usize;
    let steps = (PERIOD / STEP).round() as usize;
    let h = PERIOD / steps as f64;
    let mut ls = law.initial_state();
    let mut last = [0, 1].map(|i| encoder.read(st[i].x[0], &mut rng) / RATIO);
    let mut out = Run {
        bound,
        delta: [0.0; 2],
        radius: [0.0; 2],
        reaching_time,
        max_sliding: [0.0; 2],
        max_feedback_error: 0.0,
        max_slip_friction: 0.0,
        max_arm: 0.0,
        max_output_acceleration: 0.0,
        max_gear_torque: 0.0,
        saturated: 0,
        step_ratio,
        duration,
    };
    for k in 0..ticks {
        let t = k as f64 * PERIOD;
        let mut x = [WristJointSample::<f64>::default(); 2];
        let mut noise = [0.0; 2];
        for i in 0..2 {
            let q = encoder.read(st[i].x[0], &mut rng) / RATIO;
            let v = if k == 0 { 0.0 } else { (q - last[i]) / PERIOD };
            last[i] = q;
            noise[i] = case.noise * NOISE * (2.0 * rng.uniform() - 1.0);
            let [a, p] = case.trajectory[i];
            let (qd, vd, ad) = raised_cosine(a, p, t);
            x[i] = WristJointSample {
                desired_position: qd,
                desired_velocity: vd,
                desired_acceleration: ad,
                position: q,
                velocity: v,
                interaction_torque: tau_t(i, t) + noise[i],
            };
        }
        let held = ls;
        let o = law.update(&mut ls, &x);
        out.saturated += o.iter().filter(|m| m.saturated).count();
        // The hold interval: the sample instant, then the end of every
        // integration step.
        for s in 0..=steps {
            let tt = t + s as f64 * h;
            let ab = arm(tt);
            if s > 0 {
                // Inputs held over the step at their value at its start.
                let t0 = tt - h;
                let a0 = arm(t0);
                for i in 0..2 {
                    plants[i].step(&mut st[i], o[i].torque, a0, tau_t(i, t0), h);
                }
            }
            out.max_arm = out.max_arm.max(ab.abs());
            for i in 0..2 {
                let p = &plants[i];
                let [a, per] = case.trajectory[i];
                let (qd, vd, ad) = raised_cosine(a, per, tt);
                // The continuous law of `sampled_sliding_radius`: the true
                // state and the interaction torque now plus the held
                // noise, with the held integral and estimates.
                let fbc = tau_t(i, tt) + noise[i];
                let xc = WristJointSample {
                    desired_position: qd,
                    desired_velocity: vd,
                    desired_acceleration: ad,
                    position: st[i].x[0] / RATIO,
                    velocity: st[i].x[1] / RATIO,
                    interaction_torque: fbc,
                };
                let mut scratch = held.motors()[i];
                let tc = law
                    .law(i)
                    .update(&mut scratch, &xc.to_control_input())
                    .law_torque;
                out.delta[i] = out.delta[i].max((o[i].law_torque - tc).abs());
                let xs = st[i].x;
                out.max_feedback_error = out
                    .max_feedback_error
                    .max((fbc - p.load(&st[i], &xs)).abs());
                out.max_slip_friction = out
                    .max_slip_friction
                    .max(p.slip_friction(&st[i], &xs).abs());
                let dx = p.derivative(&st[i], &xs, o[i].torque, ab, tau_t(i, tt));
                out.max_output_acceleration = out.max_output_acceleration.max((dx[3] + ab).abs());
                out.max_gear_torque = out.max_gear_torque.max(p.gear(&st[i], &xs).1.abs());
                if tt >= reaching_time[i] {
                    out.max_sliding[i] = out.max_sliding[i].max(sliding(&xs, qd, vd).abs());
                }
            }
        }
    }
    out.radius = [0, 1]
        .map(|i| sampled_sliding_radius(bound[i].damping, bound[i].dissipation, out.delta[i]));
    out
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
    [v[0] / n, v[1] / n, v[2] / n]
}

fn case() -> impl Strategy<Value = Case> {
    let axis =
        || (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(a, b, c)| unit([a, b, c + 1e-3]));
    (
        ([0..8usize, 0..8usize], any::<u64>(), 0.0..1.0f64),
        [(0.02..0.2f64, 1.5..3.0f64), (-0.2..-0.02f64, 1.5..3.0f64)],
        [
            (-INTERACTION_MAX..INTERACTION_MAX, 0.0..3.0f64),
            (-INTERACTION_MAX..INTERACTION_MAX, 0.0..3.0f64),
        ],
        [
            (0.0..0.3f64, 1.0..6.0f64),
            (0.0..0.3f64, 1.0..6.0f64),
            (0.0..0.3f64, 1.0..6.0f64),
        ],
        [axis(), axis(), axis(), axis()],
    )
        .prop_map(|((plants, seed, noise), tr, it, arm, axes)| Case {
            plants,
            seed,
            trajectory: tr.map(|(a, p)| [a, p]),
            interaction: it.map(|(e, w)| [e, w]),
            arm: arm.map(|(a, w)| [a, w]),
            axes,
            noise,
            friction_scale: 1.0,
        })
}

/// The derivation's numbers and the design they make: `ρ_fq`, `g`, `T̄`,
/// `ρ_τt` recomputed by hand (module docs), every plant's motor friction
/// within `ρ_fq`, the kinematic-error draws of 64 seeds with gradients
/// within `g` and `o` (evaluated on a grid), the arm ranges within
/// `ρ_base`, the design valid with `K_r` below the torque limit and its
/// boundary-layer step ratio below 1.
#[test]
fn derived_bounds_cover_the_family() {
    assert!((friction_gap() - 0.0115).abs() < 1e-12);
    let g = kinematic_gradient_max();
    assert!((g - 5.6895e-3).abs() < 1e-9, "{g}");
    let tbar = (2.0 + 2e-3 * 500.0 + 0.05) / (1.0 - 7.5e-5);
    assert!((gear_torque_max() - tbar).abs() < 1e-12);
    let rho = 0.2 + 1.0 + 0.05 + tbar * (7.5e-5 + 531.0 * 5.6895e-3);
    assert!(
        (torque_error_bound() - rho).abs() < 1e-9,
        "{}",
        torque_error_bound()
    );
    assert!((rho - 10.4653).abs() < 1e-4, "{rho}");
    for p in family() {
        assert!(p.motor_friction.breakaway_forward() <= friction_gap() + 1e-15);
        assert!(p.motor_friction.breakaway_backward() <= friction_gap());
    }
    let p = &family()[0];
    for seed in 0..64u64 {
        let st = p.rest(seed);
        let dm = 1e-7;
        for j in 0..20000 {
            let m = j as f64 * TAU / 20000.0;
            let k = &st.kinematic_error;
            let d = (k.error(m + dm, 0.3) - k.error(m - dm, 0.3)) / (2.0 * dm);
            assert!(d.abs() <= g * (1.0 + 1e-5), "seed {seed} at {m}: {d} > {g}");
            let o = m / 531.0 * 1000.0;
            let d = (k.error(0.1, o + dm) - k.error(0.1, o - dm)) / (2.0 * dm);
            assert!(d.abs() <= OUTPUT_GRADIENT_MAX * (1.0 + 1e-5));
        }
    }
    let rb = base_acceleration_bound(&[0.3 * 6.0; 3], &[0.3 * 36.0; 3]);
    assert!((rb - 42.12).abs() < 1e-9 && rb <= RHO_BASE, "{rb}");
    let w = wrist_design();
    assert_eq!(w.base_acceleration, RHO_BASE);
    let params = WristActiveParams::try_new([w; 2]).expect("valid");
    let d = params.laws()[0].design();
    let kr = d.robust_gain();
    assert!(
        (kr - (0.0115 + 1.05e-6 * 50.0 + rho / 531.0)).abs() < 1e-12,
        "{kr}"
    );
    assert!(kr < d.torque_limit);
    let ratio = params.ultimate_bound(0).boundary_layer_step_ratio;
    let hand = 0.004 * (kr / 0.5 + 1.05e-6 * 531.0 * 20.0) / (1.05e-6 * 531.0);
    assert!((ratio - hand).abs() < 1e-9 && ratio < 1.0, "{ratio}");
}

/// The wrist step's own preset (Table 6.1 at 4 ms) fails the premise of
/// the sampled bound before any plant is chosen (errata E6.3): its step
/// ratio is `0.004 (0.5419357/0.1 + 0.089208)/5.5755e-4 = 39.52`.
#[test]
fn the_step_preset_fails_the_sampling_premise() {
    let p = WristStepParams::table_6_1().expect("preset");
    let active = p.settings().active;
    for i in 0..2 {
        let r = active.ultimate_bound(i).boundary_layer_step_ratio;
        assert!((r - 39.52).abs() < 0.01, "{r}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Theorem 2 on the wrist family at 4 ms, both motors (criteria in
    /// the module docs). Cases: any two of the 8 plants, any seed
    /// (kinematic-error draws, encoder and F/T noise), trajectories of
    /// 0.02–0.2 rad over 1.5–3 s, arm motion and interaction as above.
    ///
    /// 24 cases, about 6 s of the file's 8 s under the test profile. Seen
    /// on one run of 256 cases (`PROPTEST_CASES=256`): `|r|` 0.09–0.22
    /// rad/s against `r̄(δ)` 1.18–1.61 rad/s (at most 0.14 of it; `r_S` =
    /// 0.91 rad/s), `δ` 0.005–0.012 N·m, the feedback error 0.6–6.1 N·m
    /// against `ρ_τt` = 10.47 N·m, `|θ̈_o + a_b|` up to 315 rad/s², `|T_g|`
    /// up to 2.15 N·m. The bound is loose at 4 ms, as Theorem 1's is: the
    /// same check with the applied motor torque scaled by 0.8 (a 20 %
    /// torque-constant error, outside the law's model) still passed.
    #[test]
    fn wrist_sliding_variables_stay_within_theorem_2_bound_on_family_plants(c in case()) {
        let r = run(&c);
        prop_assert!(r.step_ratio < 1.0, "{c:?} {r:?}");
        prop_assert_eq!(r.saturated, 0, "{:?} {:?}", c, r);
        prop_assert!(r.max_slip_friction <= friction_gap() + 1e-12, "{c:?} {r:?}");
        prop_assert!(r.max_arm <= RHO_BASE, "{c:?} {r:?}");
        prop_assert!(r.max_output_acceleration <= OUTPUT_ACCELERATION, "{c:?} {r:?}");
        prop_assert!(r.max_feedback_error <= torque_error_bound(), "{c:?} {r:?}");
        for i in 0..2 {
            prop_assert!(r.reaching_time[i] < 0.5 * r.duration, "{c:?} {r:?}");
            prop_assert!(r.max_sliding[i] <= r.radius[i], "motor {i}: {c:?} {r:?}");
        }
    }
}

/// The check can fail: both motors' friction levels ×25 (break-away
/// `25·0.01·0.85 = 0.2125` N·m backward, 0.2875 forward, 25 times
/// `ρ_fq`). Stuck in pre-sliding, the rotor stays within twice the largest
/// pre-sliding displacement (8e-3 motor rad, 1.5e-5 rad of joint) of its
/// start, within `N·2.2e-4` motor rad of 0 (the kinematic error). The law
/// cannot push through: at the turning point `t = P/2` its linear part
/// `I_m N λ² e = 5.5755e-4·400·0.4 = 0.089 N·m` plus the robust gain
/// 0.0313 N·m, the integral's 0.02 N·m, the friction estimate's at most
/// 0.02 + 0.01·2 and `τ_t/N ≤ 4e-3` stay below the 0.2125 N·m break-away.
/// There `q_d = 2A`, `q̇_d = 0`, so `|r| ≥ λ (2A − 1e-4) − |q̇|`: with
/// `A = 0.2` rad, `λ = 20`, about 8 rad/s; the test asks for 0.9 of
/// `2λA` = 7.2 rad/s and that to be more than twice `r̄`. The unscaled
/// plant on the same case stays inside.
#[test]
fn friction_outside_the_bound_exceeds_the_ultimate_bound() {
    let mut c = Case {
        plants: [7, 3],
        seed: 5,
        trajectory: [[0.2, 2.0], [0.2, 2.0]],
        interaction: [[1.0, 1.0], [-1.5, 2.0]],
        arm: [[0.2, 2.0], [0.1, 3.0], [0.1, 1.0]],
        axes: [
            unit([0.0, 0.3, 1.0]),
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        noise: 0.5,
        friction_scale: 1.0,
    };
    let ok = run(&c);
    assert_eq!(ok.saturated, 0, "{ok:?}");
    for i in 0..2 {
        assert!(ok.max_sliding[i] <= ok.radius[i], "{ok:?}");
    }
    c.friction_scale = 25.0;
    let bad = run(&c);
    assert!(bad.max_slip_friction > 10.0 * friction_gap(), "{bad:?}");
    let expected = 0.9 * 2.0 * 20.0 * 0.2;
    for i in 0..2 {
        assert!(bad.radius[i] >= bad.bound[i].sliding_radius, "{bad:?}");
        assert!(expected > 2.0 * bad.radius[i], "{expected} vs {bad:?}");
        assert!(bad.max_sliding[i] >= expected, "{expected} vs {bad:?}");
    }
}
