//! SI conversions of the control types: each stored value to and from
//! its SI unit with the scale of `S::UNITS` ([`crate::scalar::units`]).

use super::{
    ActiveOutput, ControlInput, ModeConfig, ModeOutput, PassiveConfig, PassiveOutput,
    RobustAdaptiveConfig,
};
use crate::scalar::units::{dequantize, quantize_keep_non_finite};
use crate::scalar::Scalar;

impl<S: Scalar> ControlInput<S> {
    /// The sample for backend `S` from SI values: positions in rad, speeds
    /// in rad/s, accelerations in rad/s², joint torques in N·m (link side).
    /// Each field is quantized with its scale of `S::UNITS`
    /// (angle, speed, speed, link torque) by [`quantize_keep_non_finite`]:
    /// within half a stored step
    /// ([`half_step_si`](crate::scalar::units::half_step_si)) on fixed
    /// point, rounded to nearest on floats; finite out-of-range values saturate. A NaN or
    /// infinite value stays one on floats, and the step flags it
    /// (`invalid_input`); fixed point cannot hold it (NaN becomes 0, ±∞
    /// saturates), so firmware on fixed point should test
    /// `si.is_finite()` before converting.
    pub fn from_si(si: &ControlInput<f64>) -> Self {
        let u = S::UNITS;
        let quantize = quantize_keep_non_finite::<S>;
        ControlInput {
            desired_position: quantize(si.desired_position, u.angle),
            desired_velocity: quantize(si.desired_velocity, u.speed),
            desired_acceleration: quantize(si.desired_acceleration, u.speed),
            motor_position: quantize(si.motor_position, u.angle),
            motor_velocity: quantize(si.motor_velocity, u.speed),
            joint_torque: quantize(si.joint_torque, u.link_torque),
            desired_joint_torque: quantize(si.desired_joint_torque, u.link_torque),
            expected_joint_torque: quantize(si.expected_joint_torque, u.link_torque),
        }
    }

    /// The SI values this sample stands for (the inverse of
    /// [`from_si`](Self::from_si), exact).
    pub fn to_si(&self) -> ControlInput<f64> {
        let u = S::UNITS;
        ControlInput {
            desired_position: dequantize(self.desired_position, u.angle),
            desired_velocity: dequantize(self.desired_velocity, u.speed),
            desired_acceleration: dequantize(self.desired_acceleration, u.speed),
            motor_position: dequantize(self.motor_position, u.angle),
            motor_velocity: dequantize(self.motor_velocity, u.speed),
            joint_torque: dequantize(self.joint_torque, u.link_torque),
            desired_joint_torque: dequantize(self.desired_joint_torque, u.link_torque),
            expected_joint_torque: dequantize(self.expected_joint_torque, u.link_torque),
        }
    }
}

impl<S: Scalar> ModeOutput<S> {
    /// [`torque`](Self::torque), the motor torque command, in N·m.
    pub fn torque_si(&self) -> f64 {
        dequantize(self.torque, S::UNITS.motor_torque)
    }
    /// [`interaction`](Self::interaction), link side, in N·m.
    pub fn interaction_si(&self) -> f64 {
        dequantize(self.interaction, S::UNITS.link_torque)
    }
    /// [`reference_position`](Self::reference_position) in rad.
    pub fn reference_position_si(&self) -> f64 {
        dequantize(self.reference_position, S::UNITS.angle)
    }
}

impl<S: Scalar> ActiveOutput<S> {
    /// [`torque`](Self::torque), the motor torque command, in N·m.
    pub fn torque_si(&self) -> f64 {
        dequantize(self.torque, S::UNITS.motor_torque)
    }
    /// [`law_torque`](Self::law_torque) in N·m.
    pub fn law_torque_si(&self) -> f64 {
        dequantize(self.law_torque, S::UNITS.motor_torque)
    }
    /// [`tracking_error`](Self::tracking_error) in rad.
    pub fn tracking_error_si(&self) -> f64 {
        dequantize(self.tracking_error, S::UNITS.angle)
    }
}

impl<S: Scalar> PassiveOutput<S> {
    /// [`torque`](Self::torque), the motor torque command, in N·m.
    pub fn torque_si(&self) -> f64 {
        dequantize(self.torque, S::UNITS.motor_torque)
    }
    /// [`law_torque`](Self::law_torque) in N·m.
    pub fn law_torque_si(&self) -> f64 {
        dequantize(self.law_torque, S::UNITS.motor_torque)
    }
}

impl<S: Scalar> ModeConfig<S> {
    /// The motor torque limit `L` in N·m.
    pub fn torque_limit_si(&self) -> f64 {
        dequantize(self.torque_limit(), S::UNITS.motor_torque)
    }
}

impl<S: Scalar> RobustAdaptiveConfig<S> {
    /// The motor torque limit in N·m.
    pub fn torque_limit_si(&self) -> f64 {
        dequantize(self.torque_limit(), S::UNITS.motor_torque)
    }
}

impl<S: Scalar> PassiveConfig<S> {
    /// The motor torque limit in N·m.
    pub fn torque_limit_si(&self) -> f64 {
        dequantize(self.torque_limit(), S::UNITS.motor_torque)
    }
}
