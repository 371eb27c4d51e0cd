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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::{
        JointMode, ModeParams, ModeSettings, PassiveParams, RobustAdaptiveParams,
    };
    use crate::scalar::I16F16;

    /// Each SI reader of the control outputs is its own field in the units
    /// the backend stores (`scalar::units`: on `I16F16` motor torque in
    /// mN·m, link torque in N·m, angles in rad; SI on floats). The fields
    /// hold different values (all exact in every backend), so a reader of
    /// another field, a constant or a wrong scale fails; `motor` is the
    /// backend's motor-torque scale, written here from the units table.
    fn outputs_read_their_own_field<S: Scalar>(motor: f64) {
        let v = S::from_f64;
        let m = ModeOutput {
            torque: v(0.125 * motor),
            mode: JointMode::Active,
            switched: false,
            saturated: false,
            invalid_input: false,
            interaction: v(2.5),
            collision: false,
            reference_position: v(0.75),
        };
        assert_eq!(
            (m.torque_si(), m.interaction_si(), m.reference_position_si()),
            (0.125, 2.5, 0.75)
        );
        let a = ActiveOutput {
            torque: v(-0.0625 * motor),
            law_torque: v(0.1875 * motor),
            saturated: false,
            invalid_input: false,
            tracking_error: v(-0.375),
            sliding: v(3.0),
        };
        assert_eq!(
            (a.torque_si(), a.law_torque_si(), a.tracking_error_si()),
            (-0.0625, 0.1875, -0.375)
        );
        let p = PassiveOutput {
            torque: v(0.03125 * motor),
            law_torque: v(-0.15625 * motor),
            saturated: false,
            invalid_input: false,
        };
        assert_eq!((p.torque_si(), p.law_torque_si()), (0.03125, -0.15625));
    }

    #[test]
    fn outputs_read_their_own_field_on_every_backend() {
        outputs_read_their_own_field::<f32>(1.0);
        outputs_read_their_own_field::<f64>(1.0);
        outputs_read_their_own_field::<I16F16>(1e3);
    }

    /// The configurations' torque limits read back the SI limit they were
    /// built from (Table 4.1's 0.188 N·m), within half a stored step of
    /// motor torque (`I16F16`: 2⁻¹⁷ mN·m) or the float's rounding.
    #[test]
    fn torque_limits_read_back_the_si_limit() {
        fn check<S: Scalar>(tol: f64) {
            let active = RobustAdaptiveParams::table_4_1().unwrap();
            let want = active.design().torque_limit;
            let passive = PassiveParams::table_4_1(1e4).unwrap();
            let mode = ModeParams::try_new(ModeSettings::table_4_1(1e4).unwrap()).unwrap();
            for got in [
                RobustAdaptiveConfig::<S>::new(&active).torque_limit_si(),
                PassiveConfig::<S>::new(&passive).torque_limit_si(),
                ModeConfig::<S>::new(&mode).torque_limit_si(),
            ] {
                assert!((got - want).abs() <= tol, "{got} vs {want}");
            }
        }
        check::<f64>(0.0);
        check::<f32>(0.188 * f32::EPSILON as f64);
        check::<I16F16>(0.5 / 65_536.0 / 1e3);
    }
}
