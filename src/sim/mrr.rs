//! Dynamics of a modular and reconfigurable robot of `n` modules with
//! harmonic-drive joints (thesis §4.1, eq. 4.1–4.8), a sampled controller
//! hook, and the module's sensors.
//!
//! **Model.** Module `i` has a rotor (inertia `I_mi` about its axis
//! `z_mi`, mounted in the housing carried by link `i−1`, the base for
//! `i = 1`) and a link rotating about `z_li`, coupled by the simulated
//! harmonic drive ([`DrivePlantParams`]). The generalized coordinates are
//! the link angles `q_l` and motor angles `q_m`. The kinetic energy is that
//! of the links as rigid bodies plus the rotors' spin,
//! `½ I_mi (q̇_mi + z_miᵀ ω_{i−1})²` (the rotor mass is part of the carrying
//! link, Assumption 1 of §4.1), so the motor equations contain exactly the
//! coupling terms `I_mi z_miᵀ z_lj q̈_lj` and
//! `I_mi z_miᵀ (z_lk × z_lj) q̇_lk q̇_lj` of eq. (4.4)/(4.6), and the link
//! equations those of eq. (4.3)/(4.5) — together with the reactions of the
//! upper modules on the lower ones and the full gravity `g_li`, which the
//! per-module form of eq. (4.1)–(4.6) leaves in `τ_ext`. The inertia
//! matrix and the bias forces come from the recursive Newton–Euler
//! algorithm (the matrix column by column), so the equations are those of
//! Lagrange and the plant conserves energy without friction and control.
//!
//! Per module the applied generalized forces are, in eq. (4.1)/(4.2) form,
//! link: `τ_ti (1 − ∂θ_err/∂θ_fo) + τ_exti − f_li(q_li, q̇_li)`,
//! motor: `τ_mi − f_mi(q_mi, q̇_mi) − τ_ti (1/N_i − ∂θ_err/∂θ_wi)`,
//! with the friction of eq. (4.7)/(4.8) ([`FrictionParams`]).
//!
//! **Axis misalignment.** Each module's axis is a unit vector in the frame
//! of the link that carries it; reconfiguration (or a mounting error) is a
//! different vector, e.g. [`misaligned`].
//!
//! **Sampling.** The controller runs every `control_period` (4 ms or
//! faster) on quantized, noisy encoder counts and holds its torques (zero
//! order) while the plant is integrated by RK4 with `steps_per_period`
//! steps; friction anchors and slip states are updated after every step.

use super::friction::FrictionParams;
use super::integrator::Rk4;
use super::sensors::{Encoder, SplitMix64, TorqueSensor};
use super::transmission::DrivePlantParams;
use crate::error::{finite, gear_ratio, positive, ParamError};

pub(crate) type V3 = [f64; 3];
pub(crate) type M3 = [[f64; 3]; 3];

pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn mat_vec(m: &M3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
pub(crate) fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}
pub(crate) fn transpose(a: &M3) -> M3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = a[j][i];
        }
    }
    r
}
const I3: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// Rotation by `angle` (rad) about the unit vector `axis` (Rodrigues).
pub fn rotation(axis: V3, angle: f64) -> M3 {
    let (s, c) = libm::sincos(angle);
    let [x, y, z] = axis;
    let t = 1.0 - c;
    [
        [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
        [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
        [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
    ]
}

/// `axis` tilted by `angle` (rad) about the unit vector `about`
/// (normalized): the axis of a module mounted with a misalignment.
pub fn misaligned(axis: V3, about: V3, angle: f64) -> V3 {
    let n = libm::sqrt(dot(about, about));
    let v = mat_vec(&rotation(scale(about, 1.0 / n), angle), axis);
    let m = libm::sqrt(dot(v, v));
    scale(v, 1.0 / m)
}

/// One module of the robot.
#[derive(Debug, Clone, PartialEq)]
pub struct ModuleParams {
    /// Joint axis `z_i` (unit vector) in the frame of the carrying link.
    pub axis: V3,
    /// Joint origin in the frame of the carrying link, m.
    pub origin: V3,
    /// Link mass (including the rotors and housings it carries), kg.
    pub link_mass: f64,
    /// Link centre of mass in the link frame, m.
    pub link_com: V3,
    /// Link inertia tensor about its centre of mass, link frame, kg·m².
    pub link_inertia: M3,
    /// Rotor inertia `I_m` about its axis (rotor + wave generator), kg·m².
    pub rotor_inertia: f64,
    /// The harmonic drive.
    pub drive: DrivePlantParams,
    /// Motor-side friction, eq. (4.8).
    pub motor_friction: FrictionParams,
    /// Link-side friction, eq. (4.7).
    pub link_friction: FrictionParams,
    /// Motor-side incremental encoder.
    pub motor_encoder: Encoder,
    /// Link-side absolute encoder.
    pub link_encoder: Encoder,
    /// Link-side torque sensor (reads `τ_t`).
    pub torque_sensor: TorqueSensor,
    /// Largest motor torque magnitude, N·m (commands saturate here).
    pub max_motor_torque: f64,
    /// The link is rotationally locked (`q_l` fixed, as in the thesis's
    /// locked-output experiment).
    pub link_locked: bool,
}

impl ModuleParams {
    /// A module of the thesis's test joint (SHD-17-100 drive, Maxon 218014
    /// motor): rotor inertia `1.14e-5 kg·m²` (Table 4.1); motor friction
    /// with breakaway equal to the measured starting torque
    /// `τ_fs = 1.2 N·cm` (§2.4; Coulomb 1.0 N·cm + static 0.2 N·cm,
    /// Stribeck 1 s²/rad², viscous 1e-5 N·m·s/rad, presliding 1e-3 rad);
    /// link friction with breakaway `τ_fb − N τ_fs = 0.8 N·m` (the measured
    /// back-driving torque minus what the motor side explains; Coulomb 0.6 +
    /// static 0.2 N·m, viscous 0.05 N·m·s/rad, presliding 1e-4 rad);
    /// encoders of 2000 motor counts (500-line quadrature) and 2¹⁷ link
    /// counts with 0.3 count jitter; a torque sensor with 0.01 N·m noise
    /// and 1/376 N·m resolution (ATI Mini45); the motor limited to its
    /// rated 18.8 N·cm. `link_mass`, `link_com` and `link_inertia` describe
    /// the link (uniform rod of 0.64 kg and 0.45 m along x by default, the
    /// link of Table 4.1).
    pub fn thesis_joint() -> Self {
        let (m, l) = (0.64, 0.45);
        let i_rod = m * l * l / 12.0;
        ModuleParams {
            axis: [0.0, 0.0, 1.0],
            origin: [0.0; 3],
            link_mass: m,
            link_com: [l / 2.0, 0.0, 0.0],
            link_inertia: [[1e-4, 0.0, 0.0], [0.0, i_rod, 0.0], [0.0, 0.0, i_rod]],
            rotor_inertia: 1.14e-5,
            drive: DrivePlantParams::shd_17_100(),
            motor_friction: FrictionParams {
                coulomb: 0.010,
                static_excess: 0.002,
                stribeck: 1.0,
                viscous: 1e-5,
                presliding: 1e-3,
                presliding_damping: 2e-4,
            },
            link_friction: FrictionParams {
                coulomb: 0.6,
                static_excess: 0.2,
                stribeck: 1.0,
                viscous: 0.05,
                presliding: 1e-4,
                presliding_damping: 1.0,
            },
            motor_encoder: Encoder {
                counts_per_rev: 2000,
                noise_counts: 0.0,
            },
            link_encoder: Encoder {
                counts_per_rev: 1 << 17,
                noise_counts: 0.3,
            },
            torque_sensor: TorqueSensor {
                noise: 0.01,
                resolution: 1.0 / 376.0,
            },
            max_motor_torque: 0.188,
            link_locked: false,
        }
    }
}

impl ModuleParams {
    /// The module with a point payload of `mass` (kg) fixed at `point` (m,
    /// link frame) added to its link: total mass, combined centre of mass,
    /// and the inertia about the new centre by the parallel-axis theorem
    /// (`I + m (|r|² 1 − r rᵀ)` for each part's offset `r`).
    pub fn with_payload(&self, mass: f64, point: V3) -> Self {
        let m0 = self.link_mass;
        let total = m0 + mass;
        let com = scale(
            add(scale(self.link_com, m0), scale(point, mass)),
            1.0 / total,
        );
        let shift = |m: f64, r: V3| -> M3 {
            let rr = dot(r, r);
            let mut out = [[0.0; 3]; 3];
            for (i, row) in out.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = m * (if i == j { rr } else { 0.0 } - r[i] * r[j]);
                }
            }
            out
        };
        let a = shift(m0, sub(self.link_com, com));
        let b = shift(mass, sub(point, com));
        let mut inertia = self.link_inertia;
        for i in 0..3 {
            for j in 0..3 {
                inertia[i][j] += a[i][j] + b[i][j];
            }
        }
        ModuleParams {
            link_mass: total,
            link_com: com,
            link_inertia: inertia,
            ..self.clone()
        }
    }
}

/// The sensor readings of one sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensors {
    /// Sample time, s.
    pub time: f64,
    /// Link encoder counts (unwrapped; `q_l ≈ counts · 2π/L`).
    pub link_counts: Vec<i64>,
    /// Motor encoder counts (unwrapped; `q_m ≈ counts · 2π/M`).
    pub motor_counts: Vec<i64>,
    /// Link-side torque sensor readings (`τ_t`, N·m).
    pub link_torque: Vec<f64>,
}

/// A sampled controller: given the readings at a sample, write the motor
/// torques (N·m, chapter-4 sign) held until the next sample.
pub trait Controller {
    /// Compute the motor torques for this sample.
    fn update(&mut self, sensors: &Sensors, motor_torque: &mut [f64]);
}

impl<F: FnMut(&Sensors, &mut [f64])> Controller for F {
    fn update(&mut self, sensors: &Sensors, motor_torque: &mut [f64]) {
        self(sensors, motor_torque)
    }
}

/// The simulated robot.
///
/// A controller plugs in through [`Controller`] (a closure works): it sees
/// only [`Sensors`] and returns motor torques, held for one period.
///
/// ```
/// use mrr_control::sim::{ModuleParams, Mrr, Sensors};
/// // One thesis joint, vertical axis; hold the link at 0.2 rad with a PD
/// // law on the motor counts, sampled every 4 ms.
/// let joint = ModuleParams::thesis_joint();
/// let rad = joint.motor_encoder.rad_per_count();
/// let mut robot = Mrr::try_new(vec![joint], [0.0, 0.0, -9.81], 4e-3, 40, 1).unwrap();
/// let target = 0.2 * 100.0; // motor angle, rad
/// let mut last: Option<i64> = None;
/// let mut pd = |s: &Sensors, tau: &mut [f64]| {
///     let c = s.motor_counts[0];
///     let v = last.map_or(0.0, |p| (c - p) as f64 * rad / 4e-3);
///     last = Some(c);
///     tau[0] = 0.02 * (target - c as f64 * rad) - 5e-4 * v;
/// };
/// while robot.time() < 3.0 {
///     robot.sample(&mut pd, &mut |_, _| {});
/// }
/// // It stops where the P term no longer overcomes the breakaway of the
/// // motor (0.012 N·m) plus the link's seen at the motor (0.8 N·m / N):
/// // |e_m| ≤ 0.02 N·m / 0.02 N·m/rad = 1 rad, i.e. 0.01 rad at the link,
/// // plus the drive's torsion under ≤ 0.8 N·m (< 1e-4 rad).
/// let bound = (0.012 + 0.8 / 100.0) / 0.02 / 100.0 + 1e-4;
/// assert!((robot.link_angles()[0] - 0.2).abs() <= bound);
/// ```
#[derive(Debug, Clone)]
pub struct Mrr {
    modules: Vec<ModuleParams>,
    /// Gravity vector in the base frame, m/s² (e.g. `[0, 0, −9.81]`).
    pub gravity: V3,
    /// Controller sample period, s.
    pub control_period: f64,
    /// RK4 steps per sample.
    pub steps_per_period: usize,
    /// State `[q_l, q_m, q̇_l, q̇_m]` (each `n` long).
    x: Vec<f64>,
    time: f64,
    motor_anchor: Vec<f64>,
    link_anchor: Vec<f64>,
    slip_anchor: Vec<Vec<f64>>,
    /// Motor torques applied now (after saturation), N·m.
    motor_torque: Vec<f64>,
    /// External link torques applied now, N·m.
    pub external_torque: Vec<f64>,
    rng: SplitMix64,
    rk: Rk4,
}

/// Kinematic quantities of one configuration (world frame).
struct Kin {
    rot: Vec<M3>,
    origin: Vec<V3>,
    axis: Vec<V3>,
    com: Vec<V3>,
    inertia: Vec<M3>,
}

impl Mrr {
    /// A robot of the given modules at rest at `q_l = 0`, `q_m = 0`; the
    /// integration step is `control_period / steps_per_period`.
    ///
    /// Validated, each error naming the value: `control_period` positive
    /// and at most 4 ms (the servo tick the thesis targets);
    /// `steps_per_period ≥ 1`; gravity finite; per module a unit axis
    /// (within 1e-9), positive rotor inertia and link mass, finite origin
    /// and centre of mass, non-zero encoder resolutions, a positive motor
    /// torque limit and a gear ratio ≥ 1.
    pub fn try_new(
        modules: Vec<ModuleParams>,
        gravity: V3,
        control_period: f64,
        steps_per_period: usize,
        seed: u64,
    ) -> Result<Self, ParamError> {
        let period = positive("control_period", control_period)?;
        if period > 4e-3 {
            return Err(ParamError::OutOfRange {
                name: "control_period",
                value: period,
                min: 0.0,
                max: 4e-3,
            });
        }
        if steps_per_period == 0 {
            return Err(ParamError::NotPositive {
                name: "steps_per_period",
                value: 0.0,
            });
        }
        for g in gravity {
            finite("gravity", g)?;
        }
        for m in &modules {
            let norm = libm::sqrt(dot(m.axis, m.axis));
            if (norm - 1.0).abs() > 1e-9 || norm.is_nan() {
                return Err(ParamError::OutOfRange {
                    name: "axis",
                    value: norm,
                    min: 1.0 - 1e-9,
                    max: 1.0 + 1e-9,
                });
            }
            positive("rotor_inertia", m.rotor_inertia)?;
            positive("link_mass", m.link_mass)?;
            positive("max_motor_torque", m.max_motor_torque)?;
            gear_ratio(m.drive.ratio)?;
            for v in m.origin.iter().chain(&m.link_com) {
                finite("origin", *v)?;
            }
            for (name, c) in [
                ("motor_encoder", m.motor_encoder.counts_per_rev),
                ("link_encoder", m.link_encoder.counts_per_rev),
            ] {
                if c == 0 {
                    return Err(ParamError::NotPositive { name, value: 0.0 });
                }
            }
        }
        Ok(Self::build(
            modules,
            gravity,
            period,
            steps_per_period,
            seed,
        ))
    }

    fn build(
        modules: Vec<ModuleParams>,
        gravity: V3,
        control_period: f64,
        steps_per_period: usize,
        seed: u64,
    ) -> Self {
        let n = modules.len();
        let slip_anchor = modules
            .iter()
            .map(|m| vec![0.0; m.drive.slip_elements.len()])
            .collect();
        Mrr {
            modules,
            gravity,
            control_period,
            steps_per_period: steps_per_period.max(1),
            x: vec![0.0; 4 * n],
            time: 0.0,
            motor_anchor: vec![0.0; n],
            link_anchor: vec![0.0; n],
            slip_anchor,
            motor_torque: vec![0.0; n],
            external_torque: vec![0.0; n],
            rng: SplitMix64::new(seed),
            rk: Rk4::new(4 * n),
        }
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.modules.len()
    }

    /// `true` for a robot without modules.
    pub fn is_empty(&self) -> bool {
        self.modules.is_empty()
    }

    /// The modules.
    pub fn modules(&self) -> &[ModuleParams] {
        &self.modules
    }

    /// Simulation time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Integration step, s.
    pub fn step_size(&self) -> f64 {
        self.control_period / self.steps_per_period as f64
    }

    /// Link angles `q_l`, rad.
    pub fn link_angles(&self) -> &[f64] {
        &self.x[..self.len()]
    }
    /// Motor angles `q_m`, rad.
    pub fn motor_angles(&self) -> &[f64] {
        let n = self.len();
        &self.x[n..2 * n]
    }
    /// Link speeds, rad/s.
    pub fn link_speeds(&self) -> &[f64] {
        let n = self.len();
        &self.x[2 * n..3 * n]
    }
    /// Motor speeds, rad/s.
    pub fn motor_speeds(&self) -> &[f64] {
        let n = self.len();
        &self.x[3 * n..]
    }
    /// Motor torques applied now (after saturation), N·m.
    pub fn applied_motor_torque(&self) -> &[f64] {
        &self.motor_torque
    }

    /// Set positions and speeds; friction and slip elements are reset to
    /// rest at the new positions (no stored presliding deflection).
    pub fn set_state(&mut self, q_l: &[f64], q_m: &[f64], v_l: &[f64], v_m: &[f64]) {
        let n = self.len();
        self.x[..n].copy_from_slice(q_l);
        self.x[n..2 * n].copy_from_slice(q_m);
        self.x[2 * n..3 * n].copy_from_slice(v_l);
        self.x[3 * n..].copy_from_slice(v_m);
        self.motor_anchor.copy_from_slice(q_m);
        self.link_anchor.copy_from_slice(q_l);
        for i in 0..n {
            let (d, _, _) = self.modules[i].drive.compliance_torsion(q_l[i], q_m[i]);
            for z in self.slip_anchor[i].iter_mut() {
                *z = d;
            }
        }
    }

    /// Motor angles that make every transmission carry `torque[i]` (N·m) at
    /// the link angles `q_l` with fresh slip elements (solved by bisection
    /// on the monotone transmission curve).
    pub fn motor_angles_for_torque(&self, q_l: &[f64], torque: &[f64]) -> Vec<f64> {
        (0..self.len())
            .map(|i| {
                let d = &self.modules[i].drive;
                let n = d.ratio;
                let (mut lo, mut hi) = (-0.05, 0.05);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    let qm = n * (q_l[i] + mid);
                    let (dc, _, _) = d.compliance_torsion(q_l[i], qm);
                    let z = vec![dc; d.slip_elements.len()];
                    if d.torque(dc, &z) < torque[i] {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                n * (q_l[i] + 0.5 * (lo + hi))
            })
            .collect()
    }

    fn kinematics(&self, q_l: &[f64]) -> Kin {
        let n = self.len();
        let mut k = Kin {
            rot: Vec::with_capacity(n),
            origin: Vec::with_capacity(n),
            axis: Vec::with_capacity(n),
            com: Vec::with_capacity(n),
            inertia: Vec::with_capacity(n),
        };
        let (mut r_p, mut o_p) = (I3, [0.0; 3]);
        for (i, m) in self.modules.iter().enumerate() {
            let z = mat_vec(&r_p, m.axis);
            let o = add(o_p, mat_vec(&r_p, m.origin));
            let r = mat_mul(&r_p, &rotation(m.axis, q_l[i]));
            let c = add(o, mat_vec(&r, m.link_com));
            let iw = mat_mul(&mat_mul(&r, &m.link_inertia), &transpose(&r));
            k.rot.push(r);
            k.origin.push(o);
            k.axis.push(z);
            k.com.push(c);
            k.inertia.push(iw);
            r_p = r;
            o_p = o;
        }
        k
    }

    /// Recursive Newton–Euler: the inertial generalized forces
    /// `M(q) a + c(q, v) + g(q)` (links then motors) for speeds `(v_l, v_m)`
    /// and accelerations `(a_l, a_m)`; gravity included when `gravity`.
    /// These are the left-hand sides of eq. (4.1)–(4.6) without friction
    /// (the motor rows are `I_mi (q̈_mi + z_miᵀ ω̇_{i−1})`, whose
    /// `z_miᵀ ω̇_{i−1}` expands into the `z_miᵀ z_lj q̈_lj` and
    /// `z_miᵀ (z_lk × z_lj) q̇_lk q̇_lj` terms of eq. 4.4/4.6), plus the
    /// reactions of the upper modules that eq. (4.1)–(4.5) leave in `τ_ext`.
    #[allow(clippy::too_many_arguments)]
    fn inverse_dynamics(
        &self,
        k: &Kin,
        v_l: &[f64],
        v_m: &[f64],
        a_l: &[f64],
        a_m: &[f64],
        gravity: bool,
        out: &mut [f64],
    ) {
        let n = self.len();
        let mut w_p = [0.0; 3];
        let mut dw_p = [0.0; 3];
        let mut a_p = if gravity {
            scale(self.gravity, -1.0)
        } else {
            [0.0; 3]
        };
        let mut o_p = [0.0; 3];
        let mut force = vec![[0.0; 3]; n];
        let mut moment = vec![[0.0; 3]; n];
        let mut h_dot = vec![[0.0; 3]; n];
        for i in 0..n {
            let z = k.axis[i];
            let r = sub(k.origin[i], o_p);
            let a_o = add(add(a_p, cross(dw_p, r)), cross(w_p, cross(w_p, r)));
            // Rotor i on the carrying body: spin s = zᵀω_p + q̇_m.
            let jm = self.modules[i].rotor_inertia;
            let s = dot(z, w_p) + v_m[i];
            let s_dot = dot(z, dw_p) + a_m[i];
            h_dot[i] = add(scale(z, jm * s_dot), scale(cross(w_p, z), jm * s));
            out[n + i] = jm * s_dot;
            let w = add(w_p, scale(z, v_l[i]));
            let dw = add(add(dw_p, scale(z, a_l[i])), scale(cross(w_p, z), v_l[i]));
            let c = sub(k.com[i], k.origin[i]);
            let a_c = add(add(a_o, cross(dw, c)), cross(w, cross(w, c)));
            let mass = self.modules[i].link_mass;
            force[i] = scale(a_c, mass);
            let iw = &k.inertia[i];
            moment[i] = add(
                add(mat_vec(iw, dw), cross(w, mat_vec(iw, w))),
                cross(c, force[i]),
            );
            w_p = w;
            dw_p = dw;
            a_p = a_o;
            o_p = k.origin[i];
        }
        let (mut f_c, mut n_c) = ([0.0; 3], [0.0; 3]);
        for i in (0..n).rev() {
            let mut nn = add(moment[i], n_c);
            if i + 1 < n {
                nn = add(nn, cross(sub(k.origin[i + 1], k.origin[i]), f_c));
                nn = add(nn, h_dot[i + 1]);
            }
            f_c = add(force[i], f_c);
            n_c = nn;
            out[i] = dot(k.axis[i], nn);
        }
    }

    /// Applied generalized forces (links then motors) and transmission
    /// torques at state `x`: the right-hand sides of eq. (4.1)/(4.2),
    /// `τ_t + τ_ext − f_l` and `τ_m − f_m − τ_t/N`, with the kinematic
    /// error's gradient terms (see the module docs).
    fn applied_forces(&self, x: &[f64], q: &mut [f64], tau_t: &mut [f64]) {
        let n = self.len();
        for i in 0..n {
            let m = &self.modules[i];
            let (ql, qm, vl, vm) = (x[i], x[n + i], x[2 * n + i], x[3 * n + i]);
            let (dc, dl, dm) = m.drive.compliance_torsion(ql, qm);
            let tt = m.drive.torque(dc, &self.slip_anchor[i]);
            tau_t[i] = tt;
            let fl = m.link_friction.torque(ql, vl, self.link_anchor[i]);
            let fm = m.motor_friction.torque(qm, vm, self.motor_anchor[i]);
            // Q = −∂V/∂q with V(δ_c): −τ_t ∂δ_c/∂q.
            q[i] = -tt * dl + self.external_torque[i] - fl;
            q[n + i] = self.motor_torque[i] - fm - tt * dm;
        }
    }

    /// The state derivative `ẋ` at `x` (the current torques held): solves
    /// eq. (4.1)–(4.6) in matrix form, `M(q) q̈ = Q − c − g`, with the
    /// applied forces `Q` of eq. (4.1)/(4.2) (friction eq. 4.7/4.8).
    fn derivative(&self, x: &[f64], dx: &mut [f64]) {
        let n = self.len();
        let (ql, rest) = x.split_at(n);
        let (_qm, rest) = rest.split_at(n);
        let (vl, vm) = rest.split_at(n);
        let k = self.kinematics(ql);
        let dim = 2 * n;
        let zero = vec![0.0; n];
        let mut bias = vec![0.0; dim];
        self.inverse_dynamics(&k, vl, vm, &zero, &zero, true, &mut bias);
        let mut mass = vec![0.0; dim * dim];
        let mut col = vec![0.0; dim];
        let mut e_l = vec![0.0; n];
        let mut e_m = vec![0.0; n];
        for j in 0..dim {
            e_l.iter_mut().for_each(|v| *v = 0.0);
            e_m.iter_mut().for_each(|v| *v = 0.0);
            if j < n {
                e_l[j] = 1.0;
            } else {
                e_m[j - n] = 1.0;
            }
            self.inverse_dynamics(&k, &zero, &zero, &e_l, &e_m, false, &mut col);
            for i in 0..dim {
                mass[i * dim + j] = col[i];
            }
        }
        let mut rhs = vec![0.0; dim];
        let mut tt = vec![0.0; n];
        self.applied_forces(x, &mut rhs, &mut tt);
        for i in 0..dim {
            rhs[i] -= bias[i];
        }
        // Locked links: q̈_l = 0 (row and column replaced by identity).
        for (i, m) in self.modules.iter().enumerate() {
            if m.link_locked {
                for j in 0..dim {
                    mass[i * dim + j] = 0.0;
                    mass[j * dim + i] = 0.0;
                }
                mass[i * dim + i] = 1.0;
                rhs[i] = 0.0;
            }
        }
        solve_spd(&mut mass, &mut rhs, dim);
        dx[..2 * n].copy_from_slice(&x[2 * n..]);
        for (i, m) in self.modules.iter().enumerate() {
            if m.link_locked {
                dx[i] = 0.0;
            }
        }
        dx[2 * n..].copy_from_slice(&rhs);
    }

    /// Inertia matrix `M(q_l)` (2n × 2n, row-major; links then motors).
    pub fn inertia_matrix(&self) -> Vec<f64> {
        let n = self.len();
        let dim = 2 * n;
        let k = self.kinematics(self.link_angles());
        let zero = vec![0.0; n];
        let mut mass = vec![0.0; dim * dim];
        let mut col = vec![0.0; dim];
        for j in 0..dim {
            let mut e_l = vec![0.0; n];
            let mut e_m = vec![0.0; n];
            if j < n {
                e_l[j] = 1.0;
            } else {
                e_m[j - n] = 1.0;
            }
            self.inverse_dynamics(&k, &zero, &zero, &e_l, &e_m, false, &mut col);
            for i in 0..dim {
                mass[i * dim + j] = col[i];
            }
        }
        mass
    }

    /// Gravity generalized forces `g(q_l)` of the links (N·m): the torques
    /// the joints must supply to hold the current configuration.
    pub fn gravity_torques(&self) -> Vec<f64> {
        let n = self.len();
        let k = self.kinematics(self.link_angles());
        let zero = vec![0.0; n];
        let mut out = vec![0.0; 2 * n];
        self.inverse_dynamics(&k, &zero, &zero, &zero, &zero, true, &mut out);
        out.truncate(n);
        out
    }

    /// Transmission torques `τ_t` (N·m) at the current state.
    pub fn transmission_torques(&self) -> Vec<f64> {
        let n = self.len();
        let mut q = vec![0.0; 2 * n];
        let mut tt = vec![0.0; n];
        self.applied_forces(&self.x, &mut q, &mut tt);
        tt
    }

    /// Total mechanical energy (J): kinetic energy of links and rotors,
    /// gravity potential, and the elastic energy of the drives.
    pub fn energy(&self) -> f64 {
        let n = self.len();
        let k = self.kinematics(self.link_angles());
        let (vl, vm) = (self.link_speeds(), self.motor_speeds());
        let (mut w_p, mut v_p, mut o_p) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        let mut e = 0.0;
        for i in 0..n {
            let m = &self.modules[i];
            let z = k.axis[i];
            let v_o = add(v_p, cross(w_p, sub(k.origin[i], o_p)));
            let s = dot(z, w_p) + vm[i];
            e += 0.5 * m.rotor_inertia * s * s;
            let w = add(w_p, scale(z, vl[i]));
            let v_c = add(v_o, cross(w, sub(k.com[i], k.origin[i])));
            e += 0.5 * m.link_mass * dot(v_c, v_c) + 0.5 * dot(w, mat_vec(&k.inertia[i], w));
            e -= m.link_mass * dot(self.gravity, k.com[i]);
            let (dc, _, _) = m
                .drive
                .compliance_torsion(self.link_angles()[i], self.motor_angles()[i]);
            e += m.drive.elastic_energy(dc, &self.slip_anchor[i]);
            w_p = w;
            v_p = v_o;
            o_p = k.origin[i];
        }
        e
    }

    /// Energy stored in the drive of module `i` (backbone and slip
    /// elements), J.
    pub fn drive_energy(&self, i: usize) -> f64 {
        let m = &self.modules[i];
        let (dc, _, _) = m
            .drive
            .compliance_torsion(self.link_angles()[i], self.motor_angles()[i]);
        m.drive.elastic_energy(dc, &self.slip_anchor[i])
    }

    /// Read the sensors now (encoders quantize and add their noise).
    pub fn read_sensors(&mut self) -> Sensors {
        let n = self.len();
        let tt = self.transmission_torques();
        let mut s = Sensors {
            time: self.time,
            link_counts: Vec::with_capacity(n),
            motor_counts: Vec::with_capacity(n),
            link_torque: Vec::with_capacity(n),
        };
        for (i, tau) in tt.iter().enumerate() {
            let m = &self.modules[i];
            s.link_counts
                .push(m.link_encoder.read(self.x[i], &mut self.rng));
            s.motor_counts
                .push(m.motor_encoder.read(self.x[n + i], &mut self.rng));
            s.link_torque
                .push(m.torque_sensor.read(*tau, &mut self.rng));
        }
        s
    }

    /// Advance by one integration step with the held torques.
    pub fn step(&mut self) {
        let h = self.step_size();
        let mut x = core::mem::take(&mut self.x);
        let mut rk = core::mem::replace(&mut self.rk, Rk4::new(0));
        rk.step(|_, x, dx| self.derivative(x, dx), self.time, &mut x, h);
        self.x = x;
        self.rk = rk;
        self.time += h;
        let n = self.len();
        for i in 0..n {
            let m = &self.modules[i];
            let (ql, qm, vl, vm) = (
                self.x[i],
                self.x[n + i],
                self.x[2 * n + i],
                self.x[3 * n + i],
            );
            m.motor_friction
                .update_anchor(qm, vm, &mut self.motor_anchor[i]);
            m.link_friction
                .update_anchor(ql, vl, &mut self.link_anchor[i]);
            let (dc, _, _) = m.drive.compliance_torsion(ql, qm);
            m.drive.update_anchors(dc, &mut self.slip_anchor[i]);
        }
    }

    /// Set the motor torques (N·m), saturated at each module's limit.
    pub fn set_motor_torque(&mut self, torque: &[f64]) {
        for (i, t) in torque.iter().enumerate() {
            let lim = self.modules[i].max_motor_torque;
            self.motor_torque[i] = if t.is_finite() {
                t.clamp(-lim, lim)
            } else {
                0.0
            };
        }
    }

    /// Run one controller sample: read the sensors, ask the controller for
    /// torques, hold them over `steps_per_period` integration steps; the
    /// external torques are set by `external(t, self)` before every step.
    /// Returns the readings the controller saw.
    pub fn sample<C: Controller + ?Sized, E: FnMut(f64, &mut Mrr)>(
        &mut self,
        controller: &mut C,
        external: &mut E,
    ) -> Sensors {
        let s = self.read_sensors();
        let mut tau = vec![0.0; self.len()];
        controller.update(&s, &mut tau);
        self.set_motor_torque(&tau);
        for _ in 0..self.steps_per_period {
            let t = self.time;
            external(t, self);
            self.step();
        }
        s
    }
}

/// Solve `A x = b` in place for a symmetric positive-definite `A`
/// (row-major `dim × dim`) by Cholesky; `b` becomes `x`.
fn solve_spd(a: &mut [f64], b: &mut [f64], dim: usize) {
    for j in 0..dim {
        let mut d = a[j * dim + j];
        for k in 0..j {
            d -= a[j * dim + k] * a[j * dim + k];
        }
        let d = libm::sqrt(d.max(1e-300));
        a[j * dim + j] = d;
        for i in j + 1..dim {
            let mut s = a[i * dim + j];
            for k in 0..j {
                s -= a[i * dim + k] * a[j * dim + k];
            }
            a[i * dim + j] = s / d;
        }
    }
    for i in 0..dim {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * dim + k] * b[k];
        }
        b[i] = s / a[i * dim + i];
    }
    for i in (0..dim).rev() {
        let mut s = b[i];
        for k in i + 1..dim {
            s -= a[k * dim + i] * b[k];
        }
        b[i] = s / a[i * dim + i];
    }
}

#[cfg(test)]
mod tests;
