//! Every parameter error names the field the user wrote, the value the user
//! gave and the rule, word for word.
//!
//! `every_settings_field_names_itself` is a table: one row per (public
//! parameter type, settings field), each a valid preset with that one field
//! made bad, and the exact `Display` message expected. The expected texts
//! are written from the documented rules (ranges recomputed by hand where
//! they depend on other fields, e.g. `30/I_m`), not read back from the
//! library. The `boundaries_*` tests take every validated range at its
//! largest and smallest accepted values and at the next representable ones
//! (`f64::next_up`/`next_down`, or the next integer), which must be
//! rejected by name.

use mrr_control::control::{
    ModeParams, ModeSettings, PassiveParams, PassiveSettings, ReleaseRule, RobustAdaptiveDesign,
    RobustAdaptiveParams,
};
use mrr_control::estimation::{
    CollisionParams, CollisionReaction, CollisionSettings, TorqueEstimatorParams,
    TorqueEstimatorSettings,
};
use mrr_control::friction::{FrictionBounds, FrictionParams};
use mrr_control::harmonic_drive::calibration::{absolute_motor_position, encoder_offset};
use mrr_control::harmonic_drive::kinematic_error::{KinematicErrorFit, KinematicErrorModel};
use mrr_control::harmonic_drive::two_spring::{TwoSpringParams, TwoSpringSettings};
use mrr_control::harmonic_drive::{
    CatalogueCurve, CatalogueData, CataloguePiecewise, CubicStiffness, CubicStiffnessSettings,
    FlexsplineParams, FlexsplineSettings, HarmonicDriveParams, WaveGeneratorParams,
    WaveGeneratorSettings, WaveGeneratorTorqueParams, WaveGeneratorTorqueSettings,
};
use mrr_control::joint::{JointParams, JointSettings};
use mrr_control::wrist::active::{WristActiveParams, WristMotorDesign};
use mrr_control::wrist::admittance::{AdmittanceParams, AdmittanceSettings};
use mrr_control::wrist::ft_sensor::{DecouplingMatrix, FtSensorParams, GaugeAmplifier};
use mrr_control::wrist::modes::{WristModeParams, WristModeSettings};
use mrr_control::wrist::{WristParams, WristStepParams};
use mrr_control::ParamError;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

/// One row: the type and field it covers, the outcome, the message wanted.
struct Row {
    ty: &'static str,
    field: &'static str,
    got: Result<(), ParamError>,
    want: String,
}

fn row<T>(
    ty: &'static str,
    field: &'static str,
    got: Result<T, ParamError>,
    want: impl Into<String>,
) -> Row {
    Row {
        ty,
        field,
        got: got.map(|_| ()),
        want: want.into(),
    }
}

// ---- valid presets, each then spoiled one field at a time ----

fn friction() -> FrictionParams {
    FrictionParams {
        viscous: 1e-4,
        coulomb: 0.01,
        stribeck: 0.005,
        stribeck_shape: 4.0,
    }
}

/// Table 4.1's box (see `RobustAdaptiveDesign::table_4_1`).
fn box_min() -> FrictionParams {
    FrictionParams {
        viscous: 0.0,
        coulomb: 0.0,
        stribeck: 0.0,
        stribeck_shape: 0.01,
    }
}

fn box_max() -> FrictionParams {
    FrictionParams {
        viscous: 1e-4,
        coulomb: 0.012,
        stribeck: 0.012,
        stribeck_shape: 10.0,
    }
}

const VARIABLE: [f64; 4] = [1e-3, 1e-2, 1e-2, 1.0];

fn design(f: impl FnOnce(&mut RobustAdaptiveDesign)) -> Result<RobustAdaptiveParams, ParamError> {
    let mut d = RobustAdaptiveDesign::table_4_1();
    f(&mut d);
    RobustAdaptiveParams::try_new(d)
}

fn passive_settings() -> PassiveSettings {
    PassiveParams::table_4_1_default().unwrap().settings()
}

fn passive(f: impl FnOnce(&mut PassiveSettings)) -> Result<PassiveParams, ParamError> {
    let mut s = passive_settings();
    f(&mut s);
    PassiveParams::try_new(s)
}

fn mode(f: impl FnOnce(&mut ModeSettings)) -> Result<ModeParams, ParamError> {
    let mut s = ModeSettings::table_4_1(1.0 / 1.14e-5).unwrap();
    f(&mut s);
    ModeParams::try_new(s)
}

fn collision(f: impl FnOnce(&mut CollisionSettings)) -> Result<CollisionParams, ParamError> {
    let mut s = CollisionSettings {
        threshold: 5.0,
        release_threshold: 2.0,
        debounce: 3,
        release: 10,
        reaction: CollisionReaction::Stop,
    };
    f(&mut s);
    CollisionParams::try_new(s)
}

fn drive() -> HarmonicDriveParams {
    CatalogueData::SHD_17_100.identify().unwrap()
}

fn estimator_settings() -> TorqueEstimatorSettings {
    TorqueEstimatorSettings {
        drive: drive(),
        kinematic_error: Some(KinematicErrorModel::table_3_2()),
        link_counts_per_rev: 1 << 17,
        motor_counts_per_rev: 2000,
        max_torque: 60.0,
    }
}

fn estimator(
    f: impl FnOnce(&mut TorqueEstimatorSettings),
) -> Result<TorqueEstimatorParams, ParamError> {
    let mut s = estimator_settings();
    f(&mut s);
    TorqueEstimatorParams::try_new(s)
}

fn joint(f: impl FnOnce(&mut JointSettings)) -> Result<JointParams, ParamError> {
    let mut s = JointParams::table_4_1().unwrap().settings();
    f(&mut s);
    JointParams::try_new(s)
}

fn curve(f: impl FnOnce(&mut CatalogueCurve)) -> Result<CataloguePiecewise, ParamError> {
    let mut c = CatalogueCurve {
        k1: 8.4e3,
        k2: 9.4e3,
        k3: 1.1e4,
        t1: 3.9,
        t2: 12.0,
    };
    f(&mut c);
    CataloguePiecewise::try_new(c)
}

fn catalogue(f: impl FnOnce(&mut CatalogueData)) -> Result<HarmonicDriveParams, ParamError> {
    let mut c = CatalogueData::SHD_17_100;
    f(&mut c);
    c.identify()
}

fn wrist_active(
    f: impl FnOnce(&mut [WristMotorDesign; 2]),
) -> Result<WristActiveParams, ParamError> {
    let mut d = [WristMotorDesign::table_6_1(); 2];
    f(&mut d);
    WristActiveParams::try_new(d)
}

fn admittance_settings() -> AdmittanceSettings {
    let l = 30f64.to_radians();
    AdmittanceSettings {
        gain: [0.1, 0.1],
        stiffness: 1000.0,
        sample_period: 0.004,
        lag_samples: 1,
        limits: [l, l],
        max_rate: 1.0,
        deadband: 0.0,
        desired_torque: [0.0; 2],
    }
}

fn admittance(f: impl FnOnce(&mut AdmittanceSettings)) -> Result<AdmittanceParams, ParamError> {
    let mut s = admittance_settings();
    f(&mut s);
    AdmittanceParams::try_new(s)
}

fn wrist_modes(f: impl FnOnce(&mut WristModeSettings)) -> Result<WristModeParams, ParamError> {
    let mut s = WristModeSettings {
        admittance: AdmittanceParams::try_new(admittance_settings()).unwrap(),
        enter_passive: 1.0,
        exit_passive: 0.5,
        rest_speed: 0.01,
        debounce: 5,
        dwell: 50,
        rejoin_bandwidth: 5.0,
    };
    f(&mut s);
    WristModeParams::try_new(s)
}

/// A diagonal matrix of condition number 8 (‖M‖₁ = 4, ‖M⁻¹‖₁ = 2).
fn diagonal() -> [[f64; 6]; 6] {
    let mut m = [[0.0; 6]; 6];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = [1.0, 2.0, 4.0, 0.5, 1.0, 1.0][i];
    }
    m
}

fn kinematic(i: usize, v: f64) -> Result<KinematicErrorModel, ParamError> {
    let mut c = KinematicErrorModel::table_3_2().coefficients();
    c[i] = v;
    KinematicErrorModel::try_new(c)
}

fn all_rows() -> Vec<Row> {
    let robust_gain = "uncertainty.boundary_layer + uncertainty.nonparametric_friction \
                       + rotor_inertia·uncertainty.base_acceleration + uncertainty.torque_estimate/ratio";
    let c_f = drive().flexspline().c_f();
    vec![
        // FrictionParams::validated
        row("FrictionParams", "viscous", FrictionParams { viscous: NAN, ..friction() }.validated(),
            "parameter `viscous` must be finite, got NaN"),
        row("FrictionParams", "coulomb", FrictionParams { coulomb: -1.0, ..friction() }.validated(),
            "parameter `coulomb` must be >= 0, got -1"),
        row("FrictionParams", "stribeck", FrictionParams { stribeck: INF, ..friction() }.validated(),
            "parameter `stribeck` must be finite, got inf"),
        row("FrictionParams", "stribeck_shape", FrictionParams { stribeck_shape: 0.0, ..friction() }.validated(),
            "parameter `stribeck_shape` must be > 0, got 0"),
        // FrictionBounds::try_new(min, max, variable)
        row("FrictionBounds", "min.viscous",
            FrictionBounds::try_new(FrictionParams { viscous: 2e-4, ..box_min() }, box_max(), VARIABLE),
            "parameter `min.viscous` (0.0002) must be <= `max.viscous` (0.0001)"),
        row("FrictionBounds", "min.coulomb",
            FrictionBounds::try_new(FrictionParams { coulomb: -1.0, ..box_min() }, box_max(), VARIABLE),
            "parameter `min.coulomb` must be >= 0, got -1"),
        row("FrictionBounds", "min.stribeck",
            FrictionBounds::try_new(FrictionParams { stribeck: NAN, ..box_min() }, box_max(), VARIABLE),
            "parameter `min.stribeck` must be finite, got NaN"),
        row("FrictionBounds", "min.stribeck_shape",
            FrictionBounds::try_new(FrictionParams { stribeck_shape: 1e-4, ..box_min() }, box_max(), VARIABLE),
            "parameter `min.stribeck_shape` must lie in [0.001, inf], got 0.0001"),
        row("FrictionBounds", "max.viscous",
            FrictionBounds::try_new(box_min(), FrictionParams { viscous: -1e-4, ..box_max() }, VARIABLE),
            "parameter `max.viscous` must be >= 0, got -0.0001"),
        row("FrictionBounds", "max.coulomb",
            FrictionBounds::try_new(FrictionParams { coulomb: 0.02, ..box_min() }, box_max(), VARIABLE),
            "parameter `min.coulomb` (0.02) must be <= `max.coulomb` (0.012)"),
        row("FrictionBounds", "max.stribeck",
            FrictionBounds::try_new(box_min(), FrictionParams { stribeck: INF, ..box_max() }, VARIABLE),
            "parameter `max.stribeck` must be finite, got inf"),
        row("FrictionBounds", "max.stribeck_shape",
            FrictionBounds::try_new(box_min(), FrictionParams { stribeck_shape: 0.0, ..box_max() }, VARIABLE),
            "parameter `max.stribeck_shape` must be > 0, got 0"),
        row("FrictionBounds", "variable[0]",
            FrictionBounds::try_new(box_min(), box_max(), [-1.0, 1e-2, 1e-2, 1.0]),
            "parameter `variable[0]` must be >= 0, got -1"),
        row("FrictionBounds", "variable[1]",
            FrictionBounds::try_new(box_min(), box_max(), [1e-3, NAN, 1e-2, 1.0]),
            "parameter `variable[1]` must be finite, got NaN"),
        row("FrictionBounds", "variable[2]",
            FrictionBounds::try_new(box_min(), box_max(), [1e-3, 1e-2, -2.0, 1.0]),
            "parameter `variable[2]` must be >= 0, got -2"),
        row("FrictionBounds", "variable[3]",
            FrictionBounds::try_new(box_min(), box_max(), [1e-3, 1e-2, 1e-2, INF]),
            "parameter `variable[3]` must be finite, got inf"),
        // RobustAdaptiveParams::try_new(RobustAdaptiveDesign)
        row("RobustAdaptiveDesign", "rotor_inertia", design(|d| d.rotor_inertia = 31.0),
            "parameter `rotor_inertia` must lie in [0, 30], got 31"),
        row("RobustAdaptiveDesign", "ratio", design(|d| d.ratio = 0.5),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        row("RobustAdaptiveDesign", "lambda", design(|d| d.lambda = 1e300),
            "parameter `lambda` must lie in [0, 1e11], got 1e300"),
        row("RobustAdaptiveDesign", "integral_gain", design(|d| d.integral_gain = -1.0),
            "parameter `integral_gain` must be >= 0, got -1"),
        row("RobustAdaptiveDesign", "adaptation_gain[0]", design(|d| d.adaptation_gain[0] = -0.1),
            "parameter `adaptation_gain[0]` must be >= 0, got -0.1"),
        row("RobustAdaptiveDesign", "adaptation_gain[1]", design(|d| d.adaptation_gain[1] = 1e11),
            "`adaptation_gain[1]·sample_period` must lie in [0, 1e8], got 4e8"),
        row("RobustAdaptiveDesign", "adaptation_gain[2]", design(|d| d.adaptation_gain[2] = NAN),
            "parameter `adaptation_gain[2]` must be finite, got NaN"),
        row("RobustAdaptiveDesign", "adaptation_gain[3]", design(|d| d.adaptation_gain[3] = INF),
            "parameter `adaptation_gain[3]` must be finite, got inf"),
        row("RobustAdaptiveDesign", "eps_r", design(|d| d.eps_r = 1e-6),
            "parameter `eps_r` must lie in [1.52587890625e-5, 30000], got 1e-6"),
        row("RobustAdaptiveDesign", "eps_velocity", design(|d| d.eps_velocity = 0.0),
            "parameter `eps_velocity` must be > 0, got 0"),
        row("RobustAdaptiveDesign", "eps_f[0]", design(|d| d.eps_f[0] = 1e-6),
            "parameter `eps_f[0]` must lie in [1.52587890625e-5, 30000], got 1e-6"),
        row("RobustAdaptiveDesign", "eps_f[1]", design(|d| d.eps_f[1] = 4e4),
            "parameter `eps_f[1]` must lie in [1.52587890625e-5, 30000], got 40000"),
        row("RobustAdaptiveDesign", "eps_f[2]", design(|d| d.eps_f[2] = -1.0),
            "parameter `eps_f[2]` must be > 0, got -1"),
        row("RobustAdaptiveDesign", "eps_f[3]", design(|d| d.eps_f[3] = 1e-9),
            "parameter `eps_f[3]` must lie in [1.52587890625e-8, 30], got 1e-9"),
        row("RobustAdaptiveDesign", "uncertainty.boundary_layer", design(|d| d.uncertainty.boundary_layer = 1e300),
            "parameter `uncertainty.boundary_layer` must lie in [0, 30], got 1e300"),
        row("RobustAdaptiveDesign", "uncertainty.nonparametric_friction",
            design(|d| d.uncertainty.nonparametric_friction = -1.0),
            "parameter `uncertainty.nonparametric_friction` must lie in [0, 30], got -1"),
        row("RobustAdaptiveDesign", "uncertainty.base_acceleration",
            design(|d| d.uncertainty.base_acceleration = 1e7),
            // 30 N·m / 1.14e-5 kg·m² = 2 631 578.947… rad/s².
            "parameter `uncertainty.base_acceleration` must lie in [0, 2.631578947368421e6], got 1e7"),
        row("RobustAdaptiveDesign", "uncertainty.torque_estimate",
            design(|d| d.uncertainty.torque_estimate = 1e4),
            // 30 N·m at the motor is 3000 N·m at the link for N = 100.
            "parameter `uncertainty.torque_estimate` must lie in [0, 3000], got 10000"),
        row("RobustAdaptiveDesign", "uncertainty (sum K_r)",
            design(|d| d.uncertainty.nonparametric_friction = 29.9),
            // 0.044 + 29.9 + 1.14e-5·1e4 + 1/100 = 30.068 N·m.
            format!("`{robust_gain}` must lie in [0, 30], got 30.068")),
        row("RobustAdaptiveDesign", "friction_bounds",
            design(|d| {
                d.friction_bounds = FrictionBounds::try_new(box_min(), box_max(), [1e9, 1e-2, 1e-2, 1.0]).unwrap()
            }),
            "parameter `friction_bounds.variable[0]` must lie in [0, 1e8], got 1e9"),
        row("RobustAdaptiveDesign", "initial_friction.viscous", design(|d| d.initial_friction.viscous = -1.0),
            "parameter `initial_friction.viscous` must be >= 0, got -1"),
        row("RobustAdaptiveDesign", "initial_friction.coulomb", design(|d| d.initial_friction.coulomb = 0.02),
            "parameter `initial_friction.coulomb` must lie in [0, 0.012], got 0.02"),
        row("RobustAdaptiveDesign", "initial_friction.stribeck", design(|d| d.initial_friction.stribeck = NAN),
            "parameter `initial_friction.stribeck` must be finite, got NaN"),
        row("RobustAdaptiveDesign", "initial_friction.stribeck_shape",
            design(|d| d.initial_friction.stribeck_shape = 20.0),
            "parameter `initial_friction.stribeck_shape` must lie in [0.01, 10], got 20"),
        row("RobustAdaptiveDesign", "integral_limit", design(|d| d.integral_limit = -0.1),
            "parameter `integral_limit` must be >= 0, got -0.1"),
        row("RobustAdaptiveDesign", "torque_limit", design(|d| d.torque_limit = 20.0),
            "parameter `torque_limit` must lie in [0, 16], got 20"),
        row("RobustAdaptiveDesign", "sample_period", design(|d| d.sample_period = 2.0),
            "parameter `sample_period` must lie in [1e-7, 1], got 2"),
        row("RobustAdaptiveDesign", "lambda (λ²·I_m)", design(|d| d.lambda = 1e7),
            // 1e14 · 1.14e-5 = 1.14e9 > 1e8 N·m/rad.
            "`lambda²·rotor_inertia` must lie in [0, 1e8], got 1.14e9"),
        row("RobustAdaptiveDesign", "integral_gain (K_I·T)", design(|d| d.integral_gain = 1e11),
            "`integral_gain·sample_period` must lie in [0, 1e8], got 4e8"),
        // PassiveParams::try_new(PassiveSettings)
        row("PassiveSettings", "rotor_inertia", passive(|s| s.rotor_inertia = 0.0),
            "parameter `rotor_inertia` must be > 0, got 0"),
        row("PassiveSettings", "gain", passive(|s| s.gain = -1.0),
            "parameter `gain` must be >= 0, got -1"),
        row("PassiveSettings", "gain (I_m·gain/N)", passive(|s| s.gain = 1e14),
            // 1e6 · 100 / 1.14e-5 = 8.77e12.
            "parameter `gain` must lie in [0, 8.771929824561404e12], got 1e14"),
        row("PassiveSettings", "ratio", passive(|s| s.ratio = 0.5),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        row("PassiveSettings", "eps_velocity", passive(|s| s.eps_velocity = 1e-6),
            "parameter `eps_velocity` must lie in [1.52587890625e-5, inf], got 1e-6"),
        row("PassiveSettings", "nominal_friction", passive(|s| s.nominal_friction.coulomb = -1.0),
            "parameter `nominal_friction.coulomb` must be >= 0, got -1"),
        row("PassiveSettings", "torque_limit", passive(|s| s.torque_limit = 17.0),
            "parameter `torque_limit` must lie in [0, 16], got 17"),
        // ModeParams::try_new(ModeSettings), ModeParams::with_release
        row("ModeSettings", "enter_passive", mode(|s| s.enter_passive = 4e4),
            "parameter `enter_passive` must lie in [0, 30000], got 40000"),
        row("ModeSettings", "exit_passive", mode(|s| s.exit_passive = 3.0),
            "parameter `exit_passive` (3) must be smaller than `enter_passive` (2)"),
        row("ModeSettings", "debounce", mode(|s| s.debounce = 0),
            "parameter `debounce` must be > 0, got 0"),
        row("ModeSettings", "passive",
            mode(|s| {
                s.passive = PassiveParams::try_new(PassiveSettings { torque_limit: 0.1, ..passive_settings() }).unwrap()
            }),
            "parameter `passive.torque_limit` must lie in [0.188, 0.188], got 0.1"),
        row("ModeSettings", "rejoin_bandwidth", mode(|s| s.rejoin_bandwidth = 200.0),
            "parameter `rejoin_bandwidth` must lie in [0, 125], got 200"),
        row("ModeSettings", "bias_time_constant", mode(|s| s.bias_time_constant = 0.001),
            "parameter `bias_time_constant` must lie in [0.004, inf], got 0.001"),
        row("ReleaseRule", "speed",
            mode(|_| {}).and_then(|m| m.with_release(ReleaseRule { speed: 0.0, samples: 5 })),
            "parameter `rule.speed` must be > 0, got 0"),
        row("ReleaseRule", "samples",
            mode(|_| {}).and_then(|m| m.with_release(ReleaseRule { speed: 0.1, samples: 1 })),
            "parameter `rule.samples` must lie in [3, 65535], got 1"),
        // CollisionParams::try_new(CollisionSettings)
        row("CollisionSettings", "threshold", collision(|s| s.threshold = 4e4),
            "parameter `threshold` must lie in [0, 30000], got 40000"),
        row("CollisionSettings", "release_threshold", collision(|s| s.release_threshold = 6.0),
            "parameter `release_threshold` (6) must be <= `threshold` (5)"),
        row("CollisionSettings", "debounce", collision(|s| s.debounce = 0),
            "parameter `debounce` must be > 0, got 0"),
        row("CollisionSettings", "release", collision(|s| s.release = 0),
            "parameter `release` must be > 0, got 0"),
        // TorqueEstimatorParams::try_new(TorqueEstimatorSettings)
        row("TorqueEstimatorSettings", "drive",
            estimator(|s| {
                s.drive = HarmonicDriveParams::try_new(drive().flexspline(), drive().wave_generator(), 100.5).unwrap()
            }),
            "parameter `drive.ratio` must be an integer in [1, 65535], got 100.5"),
        row("TorqueEstimatorSettings", "link_counts_per_rev", estimator(|s| s.link_counts_per_rev = 0),
            "parameter `link_counts_per_rev` must be > 0, got 0"),
        row("TorqueEstimatorSettings", "motor_counts_per_rev", estimator(|s| s.motor_counts_per_rev = 0),
            "parameter `motor_counts_per_rev` must be > 0, got 0"),
        row("TorqueEstimatorSettings", "max_torque", estimator(|s| s.max_torque = 1e-4),
            "parameter `max_torque` must lie in [0.001, 30000], got 0.0001"),
        row("TorqueEstimatorSettings", "max_torque (c_f·max_torque)", estimator(|s| s.max_torque = 200.0),
            format!("`drive.c_f·max_torque` must lie in [0, 7.5], got {}", c_f * 200.0)),
        // JointParams::try_new(JointSettings)
        row("JointSettings", "mode",
            joint(|s| {
                let active = design(|d| d.ratio = 50.0).unwrap();
                s.mode = mode(|m| m.active = active).unwrap();
            }),
            "parameter `mode.active.ratio` must lie in [100, 100], got 50"),
        row("JointSettings", "speed_window", joint(|s| s.speed_window = 65),
            "parameter `speed_window` must lie in [1, 64], got 65"),
        // CataloguePiecewise::try_new(CatalogueCurve)
        row("CatalogueCurve", "k1", curve(|c| c.k1 = 0.0), "parameter `k1` must be > 0, got 0"),
        row("CatalogueCurve", "k2", curve(|c| c.k2 = -1.0), "parameter `k2` must be > 0, got -1"),
        row("CatalogueCurve", "k3", curve(|c| c.k3 = NAN), "parameter `k3` must be finite, got NaN"),
        row("CatalogueCurve", "t1", curve(|c| c.t1 = 0.0), "parameter `t1` must be > 0, got 0"),
        row("CatalogueCurve", "t2", curve(|c| c.t2 = 3.0),
            "parameter `t1` (3.9) must be smaller than `t2` (3)"),
        // CubicStiffness::try_new(CubicStiffnessSettings)
        row("CubicStiffnessSettings", "a1", CubicStiffness::try_new(CubicStiffnessSettings { a1: 0.0, a3: 1.0 }),
            "parameter `a1` must be > 0, got 0"),
        row("CubicStiffnessSettings", "a3", CubicStiffness::try_new(CubicStiffnessSettings { a1: 1.0, a3: -1.5 }),
            "parameter `a3` must be >= 0, got -1.5"),
        // FlexsplineParams, WaveGeneratorParams, HarmonicDriveParams
        row("FlexsplineSettings", "k_f0", FlexsplineParams::try_new(FlexsplineSettings { k_f0: -1.0, c_f: 0.045 }),
            "parameter `k_f0` must be > 0, got -1"),
        row("FlexsplineSettings", "c_f", FlexsplineParams::try_new(FlexsplineSettings { k_f0: 8336.0, c_f: 2e6 }),
            "parameter `c_f` must lie in [1e-6, 1e6], got 2e6"),
        row("WaveGeneratorSettings", "k_w0", WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 0.0, c_w: 83.0 }),
            "parameter `k_w0` must be > 0, got 0"),
        row("WaveGeneratorSettings", "c_w", WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 0.83, c_w: 0.0 }),
            "parameter `c_w` must lie in [1e-6, 1e6], got 0"),
        row("HarmonicDriveParams", "ratio",
            HarmonicDriveParams::try_new(drive().flexspline(), drive().wave_generator(), 0.5),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        // TwoSpringParams, WaveGeneratorTorqueParams
        row("TwoSpringSettings", "k_a", TwoSpringParams::try_new(TwoSpringSettings { k_a: 0.0, k_b: 1.0, friction: 0.0 }),
            "parameter `k_a` must be > 0, got 0"),
        row("TwoSpringSettings", "k_b", TwoSpringParams::try_new(TwoSpringSettings { k_a: 1.0, k_b: INF, friction: 0.0 }),
            "parameter `k_b` must be finite, got inf"),
        row("TwoSpringSettings", "friction", TwoSpringParams::try_new(TwoSpringSettings { k_a: 1.0, k_b: 1.0, friction: -1.0 }),
            "parameter `friction` must be >= 0, got -1"),
        row("WaveGeneratorTorqueSettings", "backdrive_friction",
            WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings { backdrive_friction: 0.0, ratio: 100.0 }),
            "parameter `backdrive_friction` must be > 0, got 0"),
        row("WaveGeneratorTorqueSettings", "ratio",
            WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings { backdrive_friction: 1.0, ratio: 0.5 }),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        // KinematicErrorModel::try_new(coefficients) (element names of eq. 3.7)
        row("KinematicErrorModel", "coefficients[0]", kinematic(0, NAN), "parameter `a0` must be finite, got NaN"),
        row("KinematicErrorModel", "coefficients[1]", kinematic(1, 0.03), "parameter `a_l1` must lie in [-0.01, 0.01], got 0.03"),
        row("KinematicErrorModel", "coefficients[2]", kinematic(2, -0.03), "parameter `b_l1` must lie in [-0.01, 0.01], got -0.03"),
        row("KinematicErrorModel", "coefficients[3]", kinematic(3, INF), "parameter `a_w1` must be finite, got inf"),
        row("KinematicErrorModel", "coefficients[4]", kinematic(4, 1.0), "parameter `b_w1` must lie in [-0.01, 0.01], got 1"),
        row("KinematicErrorModel", "coefficients[5]", kinematic(5, 1e300), "parameter `a_w2` must lie in [-0.01, 0.01], got 1e300"),
        row("KinematicErrorModel", "coefficients[6]", kinematic(6, -INF), "parameter `b_w2` must be finite, got -inf"),
        // KinematicErrorFit::add_sample
        row("KinematicErrorFit::add_sample", "link_angle", KinematicErrorFit::new().add_sample(NAN, 0.0, 0.0),
            "parameter `link_angle` must be finite, got NaN"),
        row("KinematicErrorFit::add_sample", "motor_angle", KinematicErrorFit::new().add_sample(0.0, INF, 0.0),
            "parameter `motor_angle` must be finite, got inf"),
        row("KinematicErrorFit::add_sample", "kinematic_error", KinematicErrorFit::new().add_sample(0.0, 0.0, NAN),
            "parameter `kinematic_error` must be finite, got NaN"),
        // CatalogueData::identify
        row("CatalogueData", "k1", catalogue(|c| c.k1 = 0.0), "parameter `k1` must be > 0, got 0"),
        row("CatalogueData", "k2", catalogue(|c| c.k2 = 1e13),
            "parameter `k2` must lie in [1e-6, 1e12], got 1e13"),
        row("CatalogueData", "t1", catalogue(|c| c.t1 = 5e-324),
            "parameter `t1` must lie in [1e-6, 1e6], got 5e-324"),
        row("CatalogueData", "t2", catalogue(|c| c.t2 = 1e300),
            "parameter `t2` must lie in [1e-6, 1e6], got 1e300"),
        row("CatalogueData", "hysteresis_loss", catalogue(|c| c.hysteresis_loss = 0.0),
            "parameter `hysteresis_loss` must be > 0, got 0"),
        row("CatalogueData", "starting_torque", catalogue(|c| c.starting_torque = NAN),
            "parameter `starting_torque` must be finite, got NaN"),
        row("CatalogueData", "starting_torque (c_w)", catalogue(|c| c.starting_torque = 1e-7),
            "`c_w = 2/(ratio·k_w0·hysteresis_loss) = 1/starting_torque` must lie in [1e-6, 1e6], got 1e7"),
        row("CatalogueData", "ratio", catalogue(|c| c.ratio = 0.5),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        // CatalogueData::scaled_from_shd17
        row("CatalogueData::scaled_from_shd17", "rated_torque", CatalogueData::scaled_from_shd17(0.0, 9.4e3, 100.0),
            "parameter `rated_torque` must be > 0, got 0"),
        row("CatalogueData::scaled_from_shd17", "k2", CatalogueData::scaled_from_shd17(16.0, INF, 100.0),
            "parameter `k2` must be finite, got inf"),
        row("CatalogueData::scaled_from_shd17", "ratio", CatalogueData::scaled_from_shd17(16.0, 9.4e3, 0.5),
            "parameter `ratio` must lie in [1, inf], got 0.5"),
        // calibration
        row("encoder_offset", "cw", encoder_offset(&[0.0, NAN], &[0.0, 0.0], 2),
            "parameter `cw` (i = 1) must be finite, got NaN"),
        row("encoder_offset", "ccw", encoder_offset(&[0.0, 0.0], &[0.0], 2),
            "parameter `ccw.len()` must lie in [2, 2], got 1"),
        row("encoder_offset", "ratio", encoder_offset(&[0.0], &[0.0], 0),
            "parameter `ratio` must be > 0, got 0"),
        row("absolute_motor_position", "offset", absolute_motor_position(NAN, 0.0, 0.0, 100),
            "parameter `offset` must be finite, got NaN"),
        row("absolute_motor_position", "link_at_first_index", absolute_motor_position(0.0, INF, 0.0, 100),
            "parameter `link_at_first_index` must be finite, got inf"),
        row("absolute_motor_position", "incremental_since_index", absolute_motor_position(0.0, 0.0, -INF, 100),
            "parameter `incremental_since_index` must be finite, got -inf"),
        row("absolute_motor_position", "ratio", absolute_motor_position(0.0, 0.0, 0.0, 0),
            "parameter `ratio` must be > 0, got 0"),
        row("absolute_motor_position", "(result)", absolute_motor_position(1e308, -1e308, 0.0, 100),
            "result `offset + P·round((link_at_first_index − offset)/P) + incremental_since_index` \
             of finite arguments is not finite (-inf): the arguments are too large"),
        // F/T sensor chain
        row("GaugeAmplifier", "gain", GaugeAmplifier::try_new(0.5),
            "parameter `gain` must lie in [1, 10000], got 0.5"),
        row("DecouplingMatrix", "max_condition", DecouplingMatrix::try_new(diagonal(), 1e-30),
            "parameter `max_condition` must lie in [1, inf], got 1e-30"),
        row("DecouplingMatrix", "matrix",
            DecouplingMatrix::try_new({ let mut m = diagonal(); m[2][3] = NAN; m }, 1e4),
            "parameter `matrix[2][3]` must be finite, got NaN"),
        row("DecouplingMatrix", "matrix (κ₁)", DecouplingMatrix::try_new(diagonal(), 7.9),
            "`κ₁(matrix)` must lie in [1, 7.9], got 8"),
        row("FtSensorParams", "offset", FtSensorParams::try_new(DecouplingMatrix::example(), 2.0),
            "parameter `offset` must lie in [0, 1], got 2"),
        // WristParams
        row("WristParams", "phi", WristParams::try_new(0.0),
            "parameter `phi` must lie in [0.017453292519943295, 0.5235987755982988], got 0"),
        // AdmittanceParams::try_new(AdmittanceSettings)
        row("AdmittanceSettings", "gain", admittance(|s| s.gain[1] = 0.3),
            // a_max(1)/(T K_t) = 2 sin(π/6)/(0.004·1000), rounded.
            "parameter `gain[1]` must lie in [0, 0.24999999999999997], got 0.3"),
        row("AdmittanceSettings", "stiffness", admittance(|s| s.stiffness = 0.0),
            "parameter `stiffness` must be > 0, got 0"),
        row("AdmittanceSettings", "sample_period", admittance(|s| s.sample_period = 2.0),
            "parameter `sample_period` must lie in [1e-6, 1], got 2"),
        row("AdmittanceSettings", "lag_samples", admittance(|s| s.lag_samples = 17),
            "parameter `lag_samples` must lie in [0, 16], got 17"),
        row("AdmittanceSettings", "limits", admittance(|s| s.limits[0] = 2.0),
            "parameter `limits[0]` must lie in [0, 1.5707963267948966], got 2"),
        row("AdmittanceSettings", "max_rate", admittance(|s| s.max_rate = 2e3),
            "parameter `max_rate` must lie in [0, 1000], got 2000"),
        row("AdmittanceSettings", "deadband", admittance(|s| s.deadband = -1.0),
            "parameter `deadband` must be >= 0, got -1"),
        row("AdmittanceSettings", "desired_torque", admittance(|s| s.desired_torque[1] = 2e3),
            "parameter `desired_torque[1]` must lie in [-1000, 1000], got 2000"),
        // WristModeParams::try_new(WristModeSettings)
        row("WristModeSettings", "enter_passive", wrist_modes(|s| s.enter_passive = 2e3),
            "parameter `enter_passive` must lie in [0, 1000], got 2000"),
        row("WristModeSettings", "exit_passive", wrist_modes(|s| s.exit_passive = 2.0),
            "parameter `exit_passive` (2) must be smaller than `enter_passive` (1)"),
        row("WristModeSettings", "rest_speed", wrist_modes(|s| s.rest_speed = 0.0),
            "parameter `rest_speed` must be > 0, got 0"),
        row("WristModeSettings", "debounce", wrist_modes(|s| s.debounce = 0),
            "parameter `debounce` must be > 0, got 0"),
        row("WristModeSettings", "rejoin_bandwidth", wrist_modes(|s| s.rejoin_bandwidth = 200.0),
            "parameter `rejoin_bandwidth` must lie in [0, 125], got 200"),
        // WristActiveParams::try_new([WristMotorDesign; 2])
        row("WristMotorDesign", "rotor_inertia", wrist_active(|d| d[0].rotor_inertia = 0.0),
            "parameter `designs[0].rotor_inertia` must be > 0, got 0"),
        row("WristMotorDesign", "rotor_inertia (·law.ratio)", wrist_active(|d| d[0].rotor_inertia = 0.1),
            "`designs[0].rotor_inertia·designs[0].law.ratio` must lie in [0, 30], got 53.1"),
        row("WristMotorDesign", "base_acceleration", wrist_active(|d| d[1].base_acceleration = -1.0),
            "parameter `designs[1].base_acceleration` must be >= 0, got -1"),
        row("WristMotorDesign", "law.ratio", wrist_active(|d| d[0].law.ratio = 0.0),
            "parameter `designs[0].law.ratio` must lie in [1, inf], got 0"),
        row("WristMotorDesign", "law.rotor_inertia", wrist_active(|d| d[0].law.rotor_inertia = NAN),
            // 1.05e-6 kg·m² · 531.
            "parameter `designs[0].law.rotor_inertia` is set from other fields: leave it 0 or give 0.00055755, got NaN"),
        row("WristMotorDesign", "law.uncertainty.base_acceleration",
            wrist_active(|d| d[1].law.uncertainty.base_acceleration = 1.0),
            // 50 rad/s² / 531.
            "parameter `designs[1].law.uncertainty.base_acceleration` is set from other fields: \
             leave it 0 or give 0.09416195856873823, got 1"),
        row("WristMotorDesign", "law.lambda", wrist_active(|d| d[1].law.lambda = -1.0),
            "parameter `designs[1].law.lambda` must be > 0, got -1"),
        row("WristMotorDesign", "law.uncertainty.boundary_layer",
            wrist_active(|d| d[0].law.uncertainty.boundary_layer = 1e300),
            "parameter `designs[0].law.uncertainty.boundary_layer` must lie in [0, 30], got 1e300"),
        row("WristMotorDesign", "law.eps_f", wrist_active(|d| d[1].law.eps_f[2] = 0.0),
            "parameter `designs[1].law.eps_f[2]` must be > 0, got 0"),
        row("WristMotorDesign", "law.initial_friction", wrist_active(|d| d[0].law.initial_friction.coulomb = 1.0),
            "parameter `designs[0].law.initial_friction.coulomb` must lie in [0, 0.01], got 1"),
        row("WristMotorDesign", "law.sample_period", wrist_active(|d| d[1].law.sample_period = 0.002),
            "parameter `designs[1].law.sample_period` must lie in [0.004, 0.004], got 0.002"),
        // WristStepParams::try_new(WristStepSettings)
        row("WristStepSettings", "modes",
            {
                let mut s = WristStepParams::table_6_1().unwrap().settings();
                s.modes = wrist_modes(|m| {
                    m.admittance = admittance(|a| a.sample_period = 0.002).unwrap();
                    m.rejoin_bandwidth = 5.0;
                })
                .unwrap();
                WristStepParams::try_new(s)
            },
            "parameter `modes.admittance.sample_period` must lie in [0.004, 0.004], got 0.002"),
    ]
}

#[test]
fn every_settings_field_names_itself() {
    let rows = all_rows();
    let mut failures = Vec::new();
    for r in &rows {
        match &r.got {
            Ok(()) => failures.push(format!("{}.{}: accepted, wanted {:?}", r.ty, r.field, r.want)),
            Err(e) if e.to_string() != r.want => failures.push(format!(
                "{}.{}:\n   got  {}\n   want {}",
                r.ty, r.field, e, r.want
            )),
            Err(_) => {}
        }
    }
    assert!(failures.is_empty(), "{} of {} rows:\n{}", failures.len(), rows.len(), failures.join("\n"));
    // The table's reach, recorded here so that a lost row is noticed.
    let mut keys: Vec<_> = rows.iter().map(|r| (r.ty, r.field)).collect();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), rows.len(), "duplicate rows");
    assert_eq!(rows.len(), ROWS);
}

/// Number of (type, field) rows of the table.
const ROWS: usize = 148;

/// No message carries a value in long decimal form: every number has at
/// most 17 significant digits and no run of zeros.
#[test]
fn messages_print_readable_numbers() {
    for r in all_rows() {
        if let Err(e) = r.got {
            let s = e.to_string();
            assert!(!s.contains("00000"), "{s}");
            assert!(s.len() < 200, "{s}");
        }
    }
}
