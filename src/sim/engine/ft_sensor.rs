//! The wrist's six-axis force/torque sensor as measured (thesis §6.1,
//! §6.3, eq. 6.34–6.35): the wrench comes from the engine, the gauge
//! voltages from a sensor that is not the library's model of it.
//!
//! # The wrench: the tool as its own body
//! [`SensedWrist`] is the DAUJ mechanism of [`super::DaujMechanism`] with
//! the tool split off the output link `L2`: a body of its own, held to `L2`
//! by a fixed joint at the sensor origin, `l` along the output axis from the
//! wrist centre (Fig. 6.1). The load on the tool acts on the tool body only,
//! so everything `L2` and the motors feel of it passes through that joint —
//! the sensor.
//!
//! The engine does not report the joint's force directly; it is read by
//! momentum balance on the tool over each step. The engine advances the
//! tool's velocities by `m Δv = (F + F_j) dt` and `I_w Δω = (M + M_j) dt`
//! (the engine's rigid bodies carry no gyroscopic term), with `F`, `M` the
//! known load and `F_j`, `M_j` the joint's force and moment on the tool
//! (about its centre of mass `c`). So
//!
//! `F_j = m Δv / dt − F`,  `M_j = I_w Δω / dt − M − (p − c) × F`,
//!
//! with `p` the tool point where `F` acts, all at the start of the step.
//! The wrench the tool transmits to `L2` through the sensor is the opposite,
//! `F_s = −F_j` and, about the sensor origin `o`,
//! `M_s = −(M_j + (c − o) × F_j)`. At rest it is the load moved to `o`; in
//! motion the tool's own inertia is in it, as in a real sensor.
//!
//! # The sensor frame
//! The sensor frame is fixed to `L2` at `o`, its `z` along the output axis
//! and turned +90° about it from `L2`'s frame: `x_s = y_L2`, `y_s = −x_L2`.
//! With it, the yaw axis (`L2`'s `x`, the cross's yaw joint) reads `−ŷ_s`
//! and the pitch axis (base `y`) reads `(cos γ, 0, −sin γ)`: the mounting
//! the library's eq. (6.3) assumes ([`crate::wrist::ft_sensor`]). Wrenches
//! are `[F_x, F_y, F_z, τ_x, τ_y, τ_z]` (N, N·m) in this frame.
//!
//! # The gauges: [`StrainGaugeSensor`]
//! The strain gauges answer the wrench through a "true" sensitivity matrix
//! `C` (V per N and per N·m, amplifier gain folded in), which is not the
//! inverse of the certificate matrix `M` the library is given: each element
//! of the certificate's inverse `M⁻¹` (inverted here with nalgebra, not by
//! the library) is off by a stated calibration error,
//! `C_jk = (M⁻¹)_jk (1 + x u_jk)` with `u_jk` uniform in `[−1, 1)` (seeded).
//! Each amplifier adds a constant offset `o_j` uniform in `[−o_max, o_max]`
//! (seeded) and white Gaussian noise of standard deviation `σ` per reading:
//! the outputs are `V_out,j = V_REF + (C w)_j + o_j + σ n_j` (eq. 6.34 with
//! the bridge and gain lumped into `C`).
//!
//! The library reads `SG = V_out − V_REF` and `ŵ = M SG` (eq. 6.35), so
//! `ŵ − w = (M C − I) w + M o + σ M n`, and elementwise
//!
//! `|ŵ_i − w_i| ≤ x (|M| |M⁻¹| |w|)_i + o_max Σ_j |M_ij| + |σ (M n)_i|`,
//!
//! where `(M n)_i` is Gaussian with standard deviation `σ ‖M_i·‖₂`.

use rapier3d_f64::na::{Matrix6, UnitQuaternion};
use rapier3d_f64::prelude::*;

use super::world::EngineSettings;
use super::wrist::DaujMechanism;
use crate::error::{in_range, ParamError};
use crate::sim::SplitMix64;
use crate::wrist::WristParams;

/// The amplifiers' reference voltage `V_ref` of eq. (6.34), V.
pub const V_REF: f64 = 2.5;

/// A wrench `[F_x, F_y, F_z, τ_x, τ_y, τ_z]`, N and N·m.
pub type Wrench = [f64; 6];

/// The errors of the gauge chain, relative to the certificate (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaugeErrors {
    calibration: f64,
    offset: f64,
    noise: f64,
    seed: u64,
}

impl GaugeErrors {
    /// `calibration`: the largest relative error `x` of each element of the
    /// sensitivity matrix (dimensionless, in `[0, 0.5]`; 0.01 is ±1 %);
    /// `offset`: the largest amplifier offset `o_max` (V, in `[0, 1]`);
    /// `noise`: the standard deviation `σ` of the output noise (V, in
    /// `[0, 1]`); `seed` draws the errors and the noise.
    pub fn try_new(
        calibration: f64,
        offset: f64,
        noise: f64,
        seed: u64,
    ) -> Result<Self, ParamError> {
        Ok(Self {
            calibration: in_range("calibration", calibration, 0.0, 0.5)?,
            offset: in_range("offset", offset, 0.0, 1.0)?,
            noise: in_range("noise", noise, 0.0, 1.0)?,
            seed,
        })
    }

    /// No error: the gauges answer through exactly `M⁻¹`.
    pub fn none() -> Self {
        Self {
            calibration: 0.0,
            offset: 0.0,
            noise: 0.0,
            seed: 0,
        }
    }

    /// `x` (dimensionless).
    pub fn calibration(&self) -> f64 {
        self.calibration
    }

    /// `o_max`, V.
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// `σ`, V.
    pub fn noise(&self) -> f64 {
        self.noise
    }
}

/// The six strain-gauge channels and their amplifiers (module docs).
#[derive(Debug, Clone)]
pub struct StrainGaugeSensor {
    sensitivity: [[f64; 6]; 6],
    offsets: [f64; 6],
    noise: f64,
    rng: SplitMix64,
}

impl StrainGaugeSensor {
    /// The sensor whose certificate is `certificate` (the decoupling matrix
    /// `M` of eq. 6.35: rows 0–2 in N/V, 3–5 in N·m/V), off from it by
    /// `errors`. A certificate nalgebra cannot invert gives
    /// [`ParamError::NotFinite`] named `"certificate⁻¹"`.
    pub fn try_new(certificate: &[[f64; 6]; 6], errors: GaugeErrors) -> Result<Self, ParamError> {
        let m = Matrix6::from_fn(|r, c| certificate[r][c]);
        let inv = m
            .try_inverse()
            .filter(|i| i.iter().all(|v| v.is_finite()))
            .ok_or(ParamError::NotFinite {
                name: "certificate⁻¹",
                value: f64::INFINITY,
            })?;
        let mut rng = SplitMix64::new(errors.seed);
        let mut sensitivity = [[0.0; 6]; 6];
        for (j, row) in sensitivity.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                let u = 2.0 * rng.uniform() - 1.0;
                *v = inv[(j, k)] * (1.0 + errors.calibration * u);
            }
        }
        let mut offsets = [0.0; 6];
        for o in offsets.iter_mut() {
            *o = errors.offset * (2.0 * rng.uniform() - 1.0);
        }
        Ok(Self {
            sensitivity,
            offsets,
            noise: errors.noise,
            rng,
        })
    }

    /// The true sensitivity `C` (V per N, rows of forces; V per N·m).
    pub fn sensitivity(&self) -> &[[f64; 6]; 6] {
        &self.sensitivity
    }

    /// The amplifier offsets `o_j`, V.
    pub fn offsets(&self) -> &[f64; 6] {
        &self.offsets
    }

    /// The six amplifier outputs `V_out,j` (V) for the wrench `w` on the
    /// sensor (N, N·m, sensor frame), one noise draw per channel. The
    /// amplifiers do not saturate; a non-finite wrench gives non-finite
    /// outputs, which the library's chain flags as invalid input.
    pub fn read(&mut self, w: &Wrench) -> [f64; 6] {
        let mut out = [0.0; 6];
        for (j, o) in out.iter_mut().enumerate() {
            let signal: f64 = (0..6).map(|k| self.sensitivity[j][k] * w[k]).sum();
            let noise = if self.noise > 0.0 {
                self.noise * self.rng.gaussian()
            } else {
                0.0
            };
            *o = V_REF + signal + self.offsets[j] + noise;
        }
        out
    }
}

/// The mass of the tool of [`SensedWrist`], kg; its centre of mass is
/// halfway between the sensor origin and the tool point.
pub const TOOL_MASS: f64 = 0.1;
/// The tool's moment of inertia about every axis through its centre of
/// mass, kg·m² (isotropic, so its gyroscopic moment `ω × I ω` is zero).
pub const TOOL_INERTIA: f64 = 1e-4;

/// A body's motion, base frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    /// Centre of mass, m.
    pub com: [f64; 3],
    /// Velocity of the centre of mass, m/s.
    pub linvel: [f64; 3],
    /// Angular velocity, rad/s.
    pub angvel: [f64; 3],
}

/// The DAUJ wrist with the tool on its own body behind the F/T sensor
/// (module docs), and the wrench the engine puts through the sensor.
pub struct SensedWrist {
    mechanism: DaujMechanism,
    tool: RigidBodyHandle,
    sensor_offset: f64,
    wrench: Wrench,
}

impl SensedWrist {
    /// The wrist of `params` with its sensor origin `sensor_offset` (m, the
    /// `l` of eq. 6.3: finite, `0 < l < tool_length`) and its tool point
    /// `tool_length` (m, in `(0, 1]`) along the output axis.
    pub fn try_new(
        params: &WristParams,
        sensor_offset: f64,
        tool_length: f64,
        settings: EngineSettings,
    ) -> Result<Self, ParamError> {
        let mut mechanism = DaujMechanism::try_new(params, tool_length, settings)?;
        let l = in_range("sensor_offset", sensor_offset, 0.0, tool_length)?;
        if l == 0.0 || l == tool_length {
            return Err(ParamError::OutOfRange {
                name: "sensor_offset",
                value: l,
                min: f64::MIN_POSITIVE,
                max: tool_length,
            });
        }
        let com = Vector::new(0.0, 0.0, 0.5 * (l + tool_length));
        let tool = mechanism
            .attach_tool(l, TOOL_MASS, com, Vector::repeat(TOOL_INERTIA))
            .ok_or(ParamError::NotFinite {
                name: "tool",
                value: f64::NAN,
            })?;
        Ok(Self {
            mechanism,
            tool,
            sensor_offset: l,
            wrench: [0.0; 6],
        })
    }

    /// The mechanism (poses, angles, motor torques).
    pub fn mechanism(&self) -> &DaujMechanism {
        &self.mechanism
    }

    /// `l`, m.
    pub fn sensor_offset(&self) -> f64 {
        self.sensor_offset
    }

    /// See [`DaujMechanism::set_targets`].
    pub fn set_targets(&mut self, theta1: f64, theta3: f64) {
        self.mechanism.set_targets(theta1, theta3);
    }

    /// See [`DaujMechanism::set_tool_wrench`]: `force` (N) at the tool
    /// point and `couple` (N·m), base frame, on the tool body.
    pub fn set_tool_wrench(&mut self, force: [f64; 3], couple: [f64; 3]) {
        self.mechanism.set_tool_wrench(force, couple);
    }

    /// The sensor frame: origin (m) and orientation, base frame.
    pub fn sensor_frame(&self) -> (Point<Real>, UnitQuaternion<Real>) {
        let out = self.mechanism.body(self.mechanism.output_handle());
        let origin = out.position() * Point::new(0.0, 0.0, self.sensor_offset);
        let mount =
            UnitQuaternion::from_axis_angle(&Vector::z_axis(), core::f64::consts::FRAC_PI_2);
        (origin, out.rotation() * mount)
    }

    /// The motion of the output link `L2` (the sensor's mounting side).
    pub fn output_motion(&self) -> BodyMotion {
        let b = self.mechanism.body(self.mechanism.output_handle());
        let c = b.center_of_mass();
        BodyMotion {
            com: [c.x, c.y, c.z],
            linvel: (*b.linvel()).into(),
            angvel: (*b.angvel()).into(),
        }
    }

    /// The wrench the tool put through the sensor over the last step
    /// (N, N·m, sensor frame, about the sensor origin; module docs); zero
    /// before the first step.
    pub fn sensor_wrench(&self) -> Wrench {
        self.wrench
    }

    /// One engine step, and the sensor's wrench over it.
    pub fn step(&mut self) {
        let dt = self.mechanism.settings().dt();
        let (force, couple) = self.mechanism.tool_wrench();
        let p = Vector::from(self.mechanism.tool_point());
        let (origin, frame) = self.sensor_frame();
        let (v0, w0, c, rot) = {
            let t = self.mechanism.body(self.tool);
            (
                *t.linvel(),
                *t.angvel(),
                t.center_of_mass().coords,
                *t.rotation(),
            )
        };
        self.mechanism.step();
        let (v1, w1) = {
            let t = self.mechanism.body(self.tool);
            (*t.linvel(), *t.angvel())
        };
        // I_w α with I_w = R diag(I) Rᵀ = I·1 (equal principal moments; the
        // rotation is kept for the general form).
        let alpha = (w1 - w0) / dt;
        let i_alpha = rot * (TOOL_INERTIA * (rot.inverse() * alpha));
        let f_joint = TOOL_MASS * (v1 - v0) / dt - force;
        let m_joint = i_alpha - couple - (p - c).cross(&force);
        let f_sensor = -f_joint;
        let m_sensor = -(m_joint + (c - origin.coords).cross(&f_joint));
        let f = frame.inverse() * f_sensor;
        let m = frame.inverse() * m_sensor;
        self.wrench = [f.x, f.y, f.z, m.x, m.y, m.z];
    }

    /// Runs for `seconds` (s) of simulated time.
    pub fn run(&mut self, seconds: f64) {
        let n = (seconds / self.mechanism.settings().dt())
            .ceil()
            .clamp(0.0, 1e9) as u64;
        for _ in 0..n {
            self.step();
        }
    }

    /// See [`DaujMechanism::move_to`].
    pub fn move_to(&mut self, theta1: f64, theta3: f64, ramp: f64) {
        let [a1, a3] = self.mechanism.targets();
        let n = (ramp / self.mechanism.settings().dt())
            .ceil()
            .clamp(1.0, 1e9) as u64;
        for i in 1..=n {
            let s = i as f64 / n as f64;
            self.set_targets(a1 + s * (theta1 - a1), a3 + s * (theta3 - a3));
            self.step();
        }
    }

    /// See [`DaujMechanism::settle`]; returns the largest body angular
    /// speed at the end (rad/s).
    pub fn settle(&mut self, speed_tol: f64, min_seconds: f64, max_seconds: f64) -> f64 {
        let start = self.mechanism.time();
        self.run(min_seconds);
        let dt = self.mechanism.settings().dt();
        while self.mechanism.time() - start < max_seconds
            && self.mechanism.max_angular_speed() > speed_tol
        {
            self.run(10.0 * dt);
        }
        self.mechanism.max_angular_speed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wrist::ft_sensor::DecouplingMatrix;

    #[test]
    fn settings_are_validated_by_name() {
        assert!(matches!(
            GaugeErrors::try_new(0.6, 0.0, 0.0, 1),
            Err(ParamError::OutOfRange {
                name: "calibration",
                ..
            })
        ));
        assert!(matches!(
            GaugeErrors::try_new(0.01, f64::NAN, 0.0, 1),
            Err(ParamError::NotFinite { name: "offset", .. })
        ));
        assert!(matches!(
            GaugeErrors::try_new(0.01, 0.0, -1e-3, 1),
            Err(ParamError::OutOfRange { name: "noise", .. })
        ));
        let p = WristParams::thesis();
        let s = EngineSettings::default();
        for l in [0.0, 0.06, 0.07, f64::NAN] {
            assert!(
                matches!(
                    SensedWrist::try_new(&p, l, 0.06, s),
                    Err(ParamError::OutOfRange {
                        name: "sensor_offset",
                        ..
                    }) | Err(ParamError::NotFinite {
                        name: "sensor_offset",
                        ..
                    })
                ),
                "{l}"
            );
        }
        assert!(SensedWrist::try_new(&p, 0.03, 0.06, s).is_ok());
        let mut singular = *DecouplingMatrix::example().matrix();
        singular[5] = singular[4];
        assert!(matches!(
            StrainGaugeSensor::try_new(&singular, GaugeErrors::none()),
            Err(ParamError::NotFinite {
                name: "certificate⁻¹",
                ..
            })
        ));
    }

    /// The drawn errors stay within the stated sizes and are not all zero;
    /// with no errors the outputs are `V_REF + M⁻¹ w` (checked by `M`).
    #[test]
    fn drawn_errors_are_within_their_sizes() {
        let cert = *DecouplingMatrix::example().matrix();
        let e = GaugeErrors::try_new(0.02, 1e-3, 0.0, 9).unwrap();
        let s = StrainGaugeSensor::try_new(&cert, e).unwrap();
        let ideal = StrainGaugeSensor::try_new(&cert, GaugeErrors::none()).unwrap();
        let mut largest = 0.0f64;
        for j in 0..6 {
            for k in 0..6 {
                let (c, c0) = (s.sensitivity()[j][k], ideal.sensitivity()[j][k]);
                let rel = (c - c0).abs() / c0.abs();
                assert!(rel <= 0.02 + 1e-12, "{j} {k} {rel}");
                largest = largest.max(rel);
            }
            assert!(s.offsets()[j].abs() <= 1e-3);
        }
        assert!(largest > 0.01, "{largest}");
        let w = [3.0, -2.0, 10.0, 0.2, -0.1, 0.3];
        let out = StrainGaugeSensor::try_new(&cert, GaugeErrors::none())
            .unwrap()
            .read(&w);
        for (i, row) in cert.iter().enumerate() {
            let back: f64 = (0..6).map(|j| row[j] * (out[j] - V_REF)).sum();
            assert!((back - w[i]).abs() < 1e-9, "{i} {back}");
        }
    }
}
