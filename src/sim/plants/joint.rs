//! A dynamic joint plant for the chapter 3 and 4 claims: a rotor, a
//! compliant harmonic drive with hysteresis and kinematic error, and a link
//! with its own friction and a payload, integrated finely (RK4, 50 µs)
//! between the controller's 4 ms ticks (thesis §6.3).
//!
//! # Structure and signs (chapter-4 convention, eq. 4.1–4.2)
//! Motor angle `θ_m` (rad, motor side), link angle `θ_l` (rad), input
//! `a = θ_m/N`. The drive is the one of [`super::drive`], calibrated to the
//! catalogue: the wave-generator bearing `W` carries `T_w = W(a − x)` to a
//! massless node `x`, where the mesh friction `M(x)` (Maxwell-slip to the
//! housing) and the flexspline take it, `T_w = T_f + M(x)`; the flexspline
//! carries `T_f = B(y) + H(y)` (backbone `B`, Maxwell-slip hysteresis `H`)
//! over its twist `y = x − θ_l + e_k(θ_m, θ_l)`, with `e_k` the kinematic
//! error of [`KinematicErrorPlant`] (the output is off its ideal position
//! by `−e_k` at zero load; the wave-generator angle is `θ_m`). The node is
//! solved at each evaluation. `τ_t = T_f`; by virtual work:
//!
//! ```text
//! I_m θ̈_m = τ_m − F_m − T_w/N − T_f ∂e_k/∂θ_m
//! I_l θ̈_l = T_f (1 − ∂e_k/∂θ_l) + τ_load − F_l
//! ```
//!
//! * `F_m`: motor friction — asymmetric Maxwell-slip (pre-sliding, levels
//!   `F(1 ± a)` by direction) with damping of the sticking elements, plus
//!   viscous `b_m θ̇_m`. It is **not** eq. (4.8)'s form (no `sgn`, no
//!   Stribeck exponential, rate-independent memory) but its level lies in
//!   Table 4.1's friction box (`f_c + f_s ≤ 0.024` N·m) and its
//!   direction asymmetry `a F ≤ 1.8e-3` N·m is inside `ρ_fq = 2e-3` N·m
//!   (Assumption 3); the pre-sliding part is inside `ρ_F` (Property 1).
//! * `F_l`: link-bearing friction, Maxwell-slip plus viscous.
//! * `τ_load = −G sin θ_l + τ_ext(t)`: a payload of moment `G` (N·m) and
//!   an external torque (a hand, a cut wire) given per step.
//!
//! # Sensors
//! Motor encoder 2000 counts/rev and link encoder 2¹⁷ counts/rev (Table
//! 4.1's joint), each with 0.1 count of Gaussian noise; torque sensor of
//! 1/376 N·m resolution (ATI Mini45, §3.2) with half a step of noise.
//!
//! Left out: any temperature or rate dependence of the friction, and the
//! motor's torque-constant error.

use core::f64::consts::TAU;

use super::drive::{
    self, BearingShape, DrivePlant, PlantChoice, CATALOGUE, RATIO, TORQUE_SENSOR_RESOLUTION,
};
use super::elements::{
    illinois, FlexsplineBackbone, KinematicErrorPlant, MaxwellSlip, MaxwellSlipState,
    WaveGeneratorCompliance,
};
use crate::sim::sensors::SplitMix64;

/// Rotor inertia `I_m`, kg·m² (Table 4.1).
pub const ROTOR_INERTIA: f64 = 1.14e-5;
/// Motor encoder counts per motor revolution (Table 4.1's joint).
pub const MOTOR_COUNTS: u32 = 2000;
/// Link encoder counts per revolution (`2¹⁷`).
pub const LINK_COUNTS: u32 = 1 << 17;
/// Standard deviation of both encoders' reading noise, counts (Gaussian,
/// added before rounding to a whole count; [`JointPlant::read`]).
pub const ENCODER_NOISE_COUNTS: f64 = 0.1;
/// Integration step, s (80 steps per 4 ms tick).
pub const STEP: f64 = 50e-6;
/// Motor-friction pre-sliding displacements, motor rad (an assumption:
/// one third to two and a half counts of the 2000-count encoder).
pub const MOTOR_PRESLIDING: [f64; 4] = [1e-3, 2e-3, 4e-3, 8e-3];
/// Link-bearing friction pre-sliding displacements, rad (an assumption).
pub const LINK_PRESLIDING: [f64; 4] = [5e-5, 1e-4, 2e-4, 4e-4];
/// Direction asymmetry `a` of the motor friction levels `F(1 ± a)`.
pub const MOTOR_ASYMMETRY: f64 = 0.15;
/// Motor break-away levels swept, N·m: half and all of the catalogue's
/// starting torque `τ_fs = 1.2` N·cm (§2.4).
pub const MOTOR_BREAKAWAYS: [f64; 2] = [0.006, 0.012];
/// Link inertias swept, kg·m² (the 4 ms preset's design range).
pub const LINK_INERTIAS: [f64; 2] = [0.03, 0.1];
/// Link-bearing break-away, N·m (an assumption).
pub const LINK_BREAKAWAY: f64 = 0.3;
/// Link viscous friction, N·m·s/rad (an assumption).
pub const LINK_VISCOUS: f64 = 0.05;
/// Motor viscous friction `b_m`, N·m·s/rad (Table 4.1's nominal `b̂_m`).
pub const MOTOR_VISCOUS: f64 = 5e-5;
/// Payload moment `G`, N·m (an assumption: about a 1 kg module at
/// 0.4 m, the size of Fig. 3.5's payload).
pub const PAYLOAD: f64 = 4.0;
/// Tooth-pass ripples of the kinematic error, rad; seed `s` draws
/// `RIPPLES[s % 2]`.
pub const RIPPLES: [f64; 2] = [5e-6, 4e-5];

/// Root of an increasing function near `y0` to `1e-13` (rad): bracket by
/// doubling steps, then Illinois regula falsi.
fn solve_increasing(f: impl Fn(f64) -> f64, y0: f64) -> f64 {
    let f0 = f(y0);
    if f0 == 0.0 {
        return y0;
    }
    // Secant steps from the last solution first (the node moves little
    // between evaluations); the bracketing search if they do not settle.
    let (mut y1, mut f1) = (y0, f0);
    let mut y2 = y0 - 1e-9 * f0.signum();
    let mut f2 = f(y2);
    for _ in 0..8 {
        if f2 == 0.0 {
            return y2;
        }
        if f2 == f1 {
            break;
        }
        let y3 = y2 - f2 * (y2 - y1) / (f2 - f1);
        if !y3.is_finite() {
            break;
        }
        if (y3 - y2).abs() <= 1e-13 {
            return y3;
        }
        (y1, f1) = (y2, f2);
        y2 = y3;
        f2 = f(y3);
    }
    let dir = if f0 < 0.0 { 1.0 } else { -1.0 };
    let (mut a, mut fa) = (y0, f0);
    let mut h = 1e-8;
    let (mut b, mut fb) = (y0 + dir * h, f(y0 + dir * h));
    let mut n = 0;
    while fa.signum() == fb.signum() && n < 100 {
        a = b;
        fa = fb;
        h *= 4.0;
        b = y0 + dir * h;
        fb = f(b);
        n += 1;
    }
    illinois(&f, (a, fa), (b, fb), 100, |a, b, _| (b - a).abs() <= 1e-13)
}

/// Asymmetric Maxwell-slip friction with damping of the sticking elements.
#[derive(Debug, Clone, PartialEq)]
pub struct AsymmetricSlip {
    /// `(k_i, F_i⁺, F_i⁻, c_i)`: stiffness N·m/rad, break-away forward and
    /// backward N·m, sticking damping N·m·s/rad.
    pub elements: Vec<(f64, f64, f64, f64)>,
}

impl AsymmetricSlip {
    /// Break-away `F` shared by [`drive::SLIP_SHARES`] over `presliding`,
    /// levels `F(1 + a)` forward and `F(1 − a)` backward, each element's
    /// damping giving a damping ratio `zeta` against `inertia`.
    pub fn new(
        breakaway: f64,
        asymmetry: f64,
        presliding: &[f64],
        inertia: f64,
        zeta: f64,
    ) -> Self {
        AsymmetricSlip {
            elements: drive::SLIP_SHARES
                .iter()
                .zip(presliding)
                .map(|(s, d)| {
                    let k = s * breakaway / d;
                    (
                        k,
                        s * breakaway * (1.0 + asymmetry),
                        s * breakaway * (1.0 - asymmetry),
                        2.0 * zeta * (k * inertia).sqrt(),
                    )
                })
                .collect(),
        }
    }

    /// Friction (N·m, opposing motion) at `position` and `speed` with the
    /// anchors `z`: each element's spring plus damper, limited to its
    /// break-away.
    pub fn torque(&self, z: &[f64], position: f64, speed: f64) -> f64 {
        self.elements
            .iter()
            .zip(z)
            .map(|(&(k, fp, fm, c), &z)| {
                // A sticking element's spring and damper together never
                // exceed its break-away (then it slides).
                (k * (position - z) + c * speed).clamp(-fm, fp)
            })
            .sum()
    }

    /// Accept `position`: elements past break-away slide.
    pub fn commit(&self, z: &mut [f64], position: f64) {
        for (&(k, fp, fm, _), z) in self.elements.iter().zip(z.iter_mut()) {
            let s = k * (position - *z);
            if s > fp {
                *z = position - fp / k;
            } else if s < -fm {
                *z = position + fm / k;
            }
        }
    }

    /// Largest break-away, forward, N·m.
    pub fn breakaway_forward(&self) -> f64 {
        self.elements.iter().map(|e| e.1).sum()
    }

    /// Largest break-away, backward, N·m.
    pub fn breakaway_backward(&self) -> f64 {
        self.elements.iter().map(|e| e.2).sum()
    }
}

/// One member of the joint family.
#[derive(Debug, Clone, PartialEq)]
pub struct JointPlant {
    /// Flexspline backbone.
    pub backbone: FlexsplineBackbone,
    /// Flexspline hysteresis (empty when the drive's loss sits at its node).
    pub hysteresis: MaxwellSlip,
    /// Wave-generator bearing compliance between the input and the node.
    pub bearing: WaveGeneratorCompliance,
    /// Mesh friction tying the node to the housing.
    pub mesh_friction: MaxwellSlip,
    /// Share of the catalogue loss `Ψ` made at the node (the rest in the
    /// flexspline).
    pub node_share: f64,
    /// Motor friction.
    pub motor_friction: AsymmetricSlip,
    /// Motor break-away level `F`, N·m (before the asymmetry).
    pub motor_breakaway: f64,
    /// Link inertia, kg·m².
    pub link_inertia: f64,
    /// Link-bearing friction.
    pub link_friction: MaxwellSlip,
    /// Payload moment `G`, N·m.
    pub payload: f64,
}

/// The plant's state: `[θ_m, θ̇_m, θ_l, θ̇_l]` and the friction anchors.
#[derive(Debug, Clone, PartialEq)]
pub struct JointPlantState {
    /// `[θ_m, θ̇_m, θ_l, θ̇_l]`, rad and rad/s.
    pub x: [f64; 4],
    /// Flexspline hysteresis anchors.
    pub hysteresis: MaxwellSlipState,
    /// Flexspline twist `y` of the last solve, rad.
    pub flexspline_twist: f64,
    /// Mesh friction anchors.
    pub mesh: MaxwellSlipState,
    /// Motor friction anchors.
    pub motor: Vec<f64>,
    /// Link friction anchors.
    pub link: MaxwellSlipState,
    /// The kinematic error of this run.
    pub kinematic_error: KinematicErrorPlant,
}

/// The drive's and the frictions' share of the joint's equations at one
/// state (module docs): what [`JointPlant::forces`] returns. Torques in
/// N·m, slopes of `e_k` dimensionless (rad/rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointForces {
    /// Flexspline torque `T_f = B(y) + H(y)` (the transmitted `τ_t`).
    pub flexspline_torque: f64,
    /// Wave-generator bearing torque `T_w` at the input `a = θ_m/N`.
    pub bearing_torque: f64,
    /// `∂e_k/∂θ_m` of the kinematic error.
    pub kinematic_error_slope_motor: f64,
    /// `∂e_k/∂θ_l` of the kinematic error.
    pub kinematic_error_slope_link: f64,
    /// Motor friction `F_m` (Maxwell-slip plus viscous), opposing `θ̇_m`.
    pub motor_friction: f64,
    /// Link-bearing friction `F_l` (Maxwell-slip plus viscous), opposing
    /// `θ̇_l`.
    pub link_friction: f64,
}

impl JointForces {
    /// Generalized force of the drive and the motor friction on `θ_m`:
    /// `−T_w/N − T_f ∂e_k/∂θ_m − F_m` (the rotor equation of the module
    /// docs without `τ_m`).
    pub fn on_motor(&self) -> f64 {
        -self.bearing_torque / RATIO
            - self.flexspline_torque * self.kinematic_error_slope_motor
            - self.motor_friction
    }

    /// Generalized force of the drive and the link friction on `θ_l`:
    /// `T_f (1 − ∂e_k/∂θ_l) − F_l` (the link equation of the module docs
    /// without `τ_load`).
    pub fn on_link(&self) -> f64 {
        self.flexspline_torque * (1.0 - self.kinematic_error_slope_link) - self.link_friction
    }
}

/// What the sensors read at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSensors {
    /// Link encoder count in `[0, 2¹⁷)`.
    pub link_count: u32,
    /// Free-running motor counter.
    pub motor_counter: u32,
    /// Torque sensor reading of `τ_t`, N·m.
    pub torque: f64,
}

impl JointPlant {
    /// Kinematic error `e_k` and its partial derivatives by `θ_m`, `θ_l`.
    fn kinematic(&self, k: &KinematicErrorPlant, motor: f64, link: f64) -> (f64, f64, f64) {
        let mut e = 0.0;
        let mut de_m = 0.0;
        for (h, &(a, p)) in k.wave_generator.iter().enumerate() {
            let n = h as f64 + 1.0;
            let (s, c) = (n * motor + p).sin_cos();
            e += a * s;
            de_m += a * n * c;
        }
        let (s, c) = (k.ripple_order * motor + k.ripple.1).sin_cos();
        e += k.ripple.0 * s;
        de_m += k.ripple.0 * k.ripple_order * c;
        let (s, c) = (link + k.output.1).sin_cos();
        (e + k.output.0 * s, de_m, k.output.0 * c)
    }

    /// The node balance at the state `x`: the flexspline twist `y` (rad)
    /// with `W(a − o + e_k − y) = B(y) + H(y) + M(o − e_k + y)` (`a = θ_m/N`,
    /// `o = θ_l`), started from the last solve. Returns `y`, the flexspline
    /// torque `T_f = B(y) + H(y)`, the bearing torque `T_w` and the partials
    /// of `e_k`.
    fn node(&self, st: &JointPlantState, x: &[f64; 4]) -> (f64, f64, f64, f64, f64) {
        let (e, de_m, de_l) = self.kinematic(&st.kinematic_error, x[0], x[2]);
        let total = x[0] / RATIO - x[2] + e;
        let base = x[2] - e;
        let balance = |y: f64| {
            self.backbone.torque(y)
                + self.hysteresis.torque(&st.hysteresis, y)
                + self.mesh_friction.torque(&st.mesh, base + y)
                - self.bearing.torque(total - y)
        };
        let y = solve_increasing(balance, st.flexspline_twist);
        let t_f = self.backbone.torque(y) + self.hysteresis.torque(&st.hysteresis, y);
        (y, t_f, self.bearing.torque(total - y), de_m, de_l)
    }

    /// Transmitted (flexspline) torque `τ_t`, N·m, at the state `x` with
    /// the anchors of `st`.
    pub fn transmitted(&self, st: &JointPlantState, x: &[f64; 4]) -> f64 {
        self.node(st, x).1
    }

    /// The load the drive puts on the rotor, expressed at the link as
    /// `N` times its motor-side torque (N·m): `T_w + N T_f ∂e_k/∂θ_m`, the
    /// wave-generator bearing torque plus the kinematic error's share of
    /// the flexspline torque (the rotor equation of the module docs is
    /// `I_m θ̈_m = τ_m − F_m − motor_load/N`). It differs from
    /// [`transmitted`](Self::transmitted) by the mesh friction at the node
    /// and the kinematic-error term; eq. (4.1) has one `τ_t` for both.
    pub fn motor_load(&self, st: &JointPlantState, x: &[f64; 4]) -> f64 {
        let (_, t_f, t_w, de_m, _) = self.node(st, x);
        t_w + RATIO * t_f * de_m
    }

    /// The drive's and the frictions' torques at the state `x`
    /// (`[θ_m, θ̇_m, θ_l, θ̇_l]`, rad and rad/s) with the anchors of `st`:
    /// the node solved as [`transmitted`](Self::transmitted) does, the
    /// frictions at their anchors. No payload and no external torque.
    pub fn forces(&self, st: &JointPlantState, x: &[f64; 4]) -> JointForces {
        let (_, t_f, t_w, de_m, de_l) = self.node(st, x);
        JointForces {
            flexspline_torque: t_f,
            bearing_torque: t_w,
            kinematic_error_slope_motor: de_m,
            kinematic_error_slope_link: de_l,
            motor_friction: self.motor_friction.torque(&st.motor, x[0], x[1])
                + MOTOR_VISCOUS * x[1],
            link_friction: self.link_friction.torque(&st.link, x[2]) + LINK_VISCOUS * x[3],
        }
    }

    /// Accept the state `st.x` at the end of a step: solve the node there
    /// and let every friction and hysteresis element past its break-away
    /// slide (what [`advance`](Self::advance) does after each step).
    pub fn commit(&self, st: &mut JointPlantState) {
        let x = st.x;
        let (y, ..) = self.node(st, &x);
        let e = self.kinematic_error(st, x[0], x[2]);
        self.hysteresis.commit(&mut st.hysteresis, y);
        self.mesh_friction.commit(&mut st.mesh, x[2] - e + y);
        st.flexspline_twist = y;
        self.motor_friction.commit(&mut st.motor, x[0]);
        self.link_friction.commit(&mut st.link, x[2]);
    }

    fn derivative(
        &self,
        st: &JointPlantState,
        x: &[f64; 4],
        motor_torque: f64,
        external: f64,
    ) -> [f64; 4] {
        let JointForces {
            flexspline_torque: t_f,
            bearing_torque: t_w,
            kinematic_error_slope_motor: de_m,
            kinematic_error_slope_link: de_l,
            motor_friction: f_m,
            link_friction: f_l,
        } = self.forces(st, x);
        let load = -self.payload * x[2].sin() + external;
        // By virtual work: the bearing takes `T_w` through `a = θ_m/N`; the
        // kinematic error moves the flexspline's end by `e_k(θ_m, θ_l)`.
        [
            x[1],
            (motor_torque - f_m - t_w / RATIO - t_f * de_m) / ROTOR_INERTIA,
            x[3],
            (t_f * (1.0 - de_l) + load - f_l) / self.link_inertia,
        ]
    }

    /// A state at rest at link angle `link` (rad) with no load on the
    /// spring, the kinematic error drawn from `seed`.
    pub fn rest(&self, link: f64, seed: u64) -> JointPlantState {
        let mut rng = SplitMix64::new(seed ^ 0x6A09_E667_F3BC_C908);
        let ripple = RIPPLES[(seed % 2) as usize];
        let kinematic_error = KinematicErrorPlant::draw(&mut rng, ripple, RATIO);
        let mut st = JointPlantState {
            x: [RATIO * link, 0.0, link, 0.0],
            hysteresis: self.hysteresis.relaxed(0.0),
            flexspline_twist: 0.0,
            mesh: self.mesh_friction.relaxed(0.0),
            motor: vec![RATIO * link; self.motor_friction.elements.len()],
            link: self.link_friction.relaxed(link),
            kinematic_error,
        };
        st.x[0] = self.zero_load_motor_angle(&st, link);
        let e = self.kinematic_error(&st, st.x[0], link);
        st.mesh = self.mesh_friction.relaxed(link - e);
        st.motor.iter_mut().for_each(|z| *z = st.x[0]);
        st
    }

    /// Advance by `duration` s (a whole number of [`STEP`]s, at least one)
    /// under the motor torque `motor_torque` (N·m) and an external link
    /// torque `external(t_offset, x)` (N·m), RK4 with the friction anchors
    /// committed after each step.
    pub fn advance(
        &self,
        st: &mut JointPlantState,
        motor_torque: f64,
        duration: f64,
        mut external: impl FnMut(f64, &[f64; 4]) -> f64,
    ) {
        let n = ((duration / STEP).round() as usize).max(1);
        let h = duration / n as f64;
        for i in 0..n {
            let x = st.x;
            let ext = external(i as f64 * h, &x);
            let add = |a: [f64; 4], b: [f64; 4], s: f64| [0, 1, 2, 3].map(|j| a[j] + s * b[j]);
            let k1 = self.derivative(st, &x, motor_torque, ext);
            let k2 = self.derivative(st, &add(x, k1, h / 2.0), motor_torque, ext);
            let k3 = self.derivative(st, &add(x, k2, h / 2.0), motor_torque, ext);
            let k4 = self.derivative(st, &add(x, k3, h), motor_torque, ext);
            st.x =
                [0, 1, 2, 3].map(|j| x[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
            self.commit(st);
        }
    }

    /// The sensors at the current state (noise from `rng`).
    pub fn read(&self, st: &JointPlantState, rng: &mut SplitMix64) -> JointSensors {
        let count = |angle: f64, per_rev: u32, rng: &mut SplitMix64| {
            (angle / TAU * per_rev as f64 + ENCODER_NOISE_COUNTS * rng.gaussian()).round() as i64
        };
        let link = count(st.x[2], LINK_COUNTS, rng).rem_euclid(LINK_COUNTS as i64) as u32;
        let motor = count(st.x[0], MOTOR_COUNTS, rng) as u32;
        let q = TORQUE_SENSOR_RESOLUTION;
        let torque = ((self.transmitted(st, &st.x) / q + 0.5 * rng.gaussian()).round()) * q;
        JointSensors {
            link_count: link,
            motor_counter: motor,
            torque,
        }
    }

    /// The kinematic error `e_k` (rad) of the run `st` at motor angle
    /// `motor` and link angle `link`.
    pub fn kinematic_error(&self, st: &JointPlantState, motor: f64, link: f64) -> f64 {
        self.kinematic(&st.kinematic_error, motor, link).0
    }

    /// The motor angle (rad) at which the drive carries no torque with the
    /// link at `link` (zero twist: `θ_m = N (θ_l − e_k)`), by damped
    /// fixed-point iteration from `N θ_l`.
    pub fn zero_load_motor_angle(&self, st: &JointPlantState, link: f64) -> f64 {
        let mut m = RATIO * link;
        for _ in 0..60 {
            let (e, _, _) = self.kinematic(&st.kinematic_error, m, link);
            m = 0.5 * m + 0.5 * RATIO * (link - e);
        }
        m
    }

    /// The sensors with the shafts at `motor` and `link` (rad), the torque
    /// sensor reading the transmitted torque of `st`.
    pub fn read_at(
        &self,
        st: &JointPlantState,
        motor: f64,
        link: f64,
        rng: &mut SplitMix64,
    ) -> JointSensors {
        let mut s = st.clone();
        s.x[0] = motor;
        s.x[2] = link;
        self.read(&s, rng)
    }

    /// Name of the swept choices.
    pub fn label(&self) -> String {
        format!(
            "{} / node share {:.1} / motor F {:.3} N·m / I_l {:.2} kg·m²",
            self.backbone.name(),
            self.node_share,
            self.motor_breakaway,
            self.link_inertia
        )
    }
}

fn build(drive: &DrivePlant, motor_breakaway: f64, link_inertia: f64) -> JointPlant {
    JointPlant {
        backbone: drive.backbone,
        hysteresis: drive.flexspline_hysteresis.clone(),
        bearing: drive.wave_generator,
        mesh_friction: drive.mesh_friction.clone(),
        node_share: drive.node_share,
        motor_friction: AsymmetricSlip::new(
            motor_breakaway,
            MOTOR_ASYMMETRY,
            &MOTOR_PRESLIDING,
            ROTOR_INERTIA,
            0.3,
        ),
        motor_breakaway,
        link_inertia,
        link_friction: MaxwellSlip::from_shares(
            LINK_BREAKAWAY,
            &drive::SLIP_SHARES,
            &LINK_PRESLIDING,
        ),
        payload: PAYLOAD,
    }
}

/// The drive plant calibrated to the catalogue (hyperbolic bearing, mesh
/// break-away `τ_fb = 2.0` N·m) with the share `node_share` of the loss
/// `Ψ` at the node.
fn drive_of(backbone: FlexsplineBackbone, node_share: f64) -> DrivePlant {
    drive::calibrate(&PlantChoice {
        backbone,
        bearing: BearingShape::Hyperbolic,
        mesh_breakaway: drive::BACKDRIVE_TORQUE,
        node_share,
    })
}

fn backbones() -> [FlexsplineBackbone; 3] {
    [
        FlexsplineBackbone::rounded_knees(&CATALOGUE, 0.3),
        FlexsplineBackbone::monotone_spline(&CATALOGUE, 0.8),
        FlexsplineBackbone::quadratic_stiffening(&CATALOGUE),
    ]
}

/// The full joint family: 3 backbones × the loss `Ψ` all at the node or
/// 30 % there × 2 motor friction levels × 2 link inertias = 24 plants (the
/// kinematic-error draw and its ripple vary with the seed).
pub fn joint_family() -> Vec<JointPlant> {
    let mut v = Vec::new();
    for b in backbones() {
        for node_share in [1.0, 0.3] {
            let d = drive_of(b, node_share);
            for f in MOTOR_BREAKAWAYS {
                for i in LINK_INERTIAS {
                    v.push(build(&d, f, i));
                }
            }
        }
    }
    v
}

/// The quick joint family: two corners of the full one (spline backbone,
/// 30 % of `Ψ` at the node, full friction, light link; quadratic backbone,
/// all of `Ψ` at the node, half friction, heavy link).
pub fn quick_joint_family() -> Vec<JointPlant> {
    let [_, spline, quadratic] = backbones();
    vec![
        build(&drive_of(spline, 0.3), 0.012, 0.03),
        build(&drive_of(quadratic, 1.0), 0.006, 0.1),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Released from rest with no motor torque and no payload, the plant
    /// stays at rest (the rest state is an equilibrium: zero twist).
    #[test]
    fn rest_is_an_equilibrium() {
        let mut p = quick_joint_family().remove(0);
        p.payload = 0.0;
        let mut st = p.rest(0.3, 5);
        let x0 = st.x;
        p.advance(&mut st, 0.0, 0.1, |_, _| 0.0);
        assert!((st.x[2] - x0[2]).abs() < 1e-7, "{:?} {:?}", st.x, x0);
        assert!(p.transmitted(&st, &st.x).abs() < 1e-3);
    }

    /// Back-driving: with no motor torque, a link torque of 5 N·m (above
    /// the mesh friction's 2 N·m plus the motor's `N F (1 + a)` = 1.38 N·m
    /// plus the link bearing's 0.3 N·m) turns the link by more than 0.1 rad
    /// in 0.5 s; a
    /// torque of 0.2 N·m (below the link bearing's break-away and the
    /// drive's back-driving torque) moves it by less than twice the link
    /// bearing's largest pre-sliding displacement (a step load overshoots
    /// its static deflection by at most a factor of two, and the friction
    /// keeps what it overshoots).
    #[test]
    fn back_driving_needs_the_breakaway() {
        let mut p = quick_joint_family().remove(0);
        p.payload = 0.0;
        let mut st = p.rest(0.0, 1);
        p.advance(&mut st, 0.0, 0.5, |_, _| 5.0);
        assert!(st.x[2] > 0.1, "{:?}", st.x);
        let mut st = p.rest(0.0, 1);
        p.advance(&mut st, 0.0, 0.5, |_, _| 0.2);
        assert!(st.x[2].abs() < 2.0 * LINK_PRESLIDING[3], "{:?}", st.x);
    }

    /// `motor_load` is the load the rotor feels: over one integration step
    /// of 1 µs from a twisted drive (motor turned 0.05 rad past the link's
    /// zero-load angle, link at 0.2 rad), the rotor's speed changes by
    /// `h (τ_m − F_m − L/N)/I_m` to within 0.1 %, with `F_m` the motor
    /// friction and `L` [`JointPlant::motor_load`] at the start; the
    /// flexspline torque alone in place of `L` misses by the mesh friction
    /// and the kinematic-error term.
    #[test]
    fn motor_load_is_the_rotor_load() {
        for p in quick_joint_family() {
            let mut st = p.rest(0.2, 3);
            st.x[0] += 0.05;
            let x0 = st.x;
            let tau = 0.05;
            let f_m = p.motor_friction.torque(&st.motor, x0[0], x0[1]) + MOTOR_VISCOUS * x0[1];
            let load = p.motor_load(&st, &x0);
            let flex = p.transmitted(&st, &x0);
            let h = 1e-6;
            p.advance(&mut st, tau, h, |_, _| 0.0);
            let accel = (st.x[1] - x0[1]) / h;
            let expected = (tau - f_m - load / RATIO) / ROTOR_INERTIA;
            assert!(
                (accel - expected).abs() <= 1e-3 * expected.abs(),
                "{accel} vs {expected} (L {load}, T_f {flex})"
            );
            let with_flex = (tau - f_m - flex / RATIO) / ROTOR_INERTIA;
            assert!((accel - with_flex).abs() > 1e-2 * expected.abs());
        }
    }

    /// The motor friction's levels are asymmetric as stated, and inside
    /// Table 4.1's box.
    #[test]
    fn motor_friction_levels() {
        let f = AsymmetricSlip::new(0.012, 0.15, &MOTOR_PRESLIDING, ROTOR_INERTIA, 0.3);
        assert!((f.breakaway_forward() - 0.0138).abs() < 1e-12);
        assert!((f.breakaway_backward() - 0.0102).abs() < 1e-12);
        let mut z = vec![0.0; 4];
        f.commit(&mut z, 1.0);
        assert!((f.torque(&z, 1.0, 0.0) - 0.0138).abs() < 1e-12);
        f.commit(&mut z, -1.0);
        assert!((f.torque(&z, -1.0, 0.0) + 0.0102).abs() < 1e-12);
    }
}
