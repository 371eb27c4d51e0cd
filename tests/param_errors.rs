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
        row("JointSettings", "max_motor_speed", joint(|s| s.max_motor_speed = 0.0),
            "parameter `max_motor_speed` must be > 0, got 0"),
        // 1e9 rad/s · 4 ms · 2000/2π = 1.273e9 counts per tick > 2³⁰.
        row("JointSettings", "max_motor_speed·sample_period·motor_counts_per_rev",
            joint(|s| s.max_motor_speed = 1e9),
            "`max_motor_speed·mode.active.sample_period·estimator.motor_counts_per_rev/2π` \
             must lie in [0, 1.073741824e9], got 1.2732395447351627e9"),
        // M·N = 2²⁶·100 = 6.711e9 > 2³² (a 64-count link encoder keeps
        // L·M·N within the estimator's limit).
        row("JointSettings", "estimator.motor_counts_per_rev·drive.ratio",
            joint(|s| {
                s.estimator = estimator(|e| {
                    e.link_counts_per_rev = 64;
                    e.motor_counts_per_rev = 1 << 26;
                })
                .unwrap()
            }),
            "`estimator.motor_counts_per_rev·estimator.drive.ratio` must lie in [1, 4.294967296e9], \
             got 6.7108864e9"),
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
        row("FlexsplineSettings", "k_f0 (π/(2·c_f·k_f0))",
            FlexsplineParams::try_new(FlexsplineSettings { k_f0: 8.3e7, c_f: 1.0 }),
            "`π/(2·c_f·k_f0)` must lie in [1e-6, 1], got 1.8925256949336102e-8"),
        row("WaveGeneratorSettings", "k_w0 (c_w·k_w0)",
            WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 1e-303, c_w: 1e-6 }),
            "`c_w·k_w0` must lie in [5.562684646268003e-309, inf], got 1e-309"),
        row("HarmonicDriveParams", "wave_generator",
            HarmonicDriveParams::try_new(
                drive().flexspline(),
                WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 1e-3, c_w: 1.0 }).unwrap(),
                1.0,
            ),
            "`1/(wave_generator.c_w·ratio·wave_generator.k_w0)` must lie in [0, 1], got 1000"),
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
            Ok(()) => failures.push(format!(
                "{}.{}: accepted, wanted {:?}",
                r.ty, r.field, r.want
            )),
            Err(e) if e.to_string() != r.want => failures.push(format!(
                "{}.{}:\n   got  {}\n   want {}",
                r.ty, r.field, e, r.want
            )),
            Err(_) => {}
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} rows:\n{}",
        failures.len(),
        rows.len(),
        failures.join("\n")
    );
    // The table's reach, recorded here so that a lost row is noticed.
    let mut keys: Vec<_> = rows.iter().map(|r| (r.ty, r.field)).collect();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), rows.len(), "duplicate rows");
    assert_eq!(rows.len(), ROWS);
}

/// Number of (type, field) rows of the table.
const ROWS: usize = 154;

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

// ---- boundaries ----

/// The smallest positive `f64` (the smallest value a `> 0` rule accepts).
const TINY: f64 = 5e-324;

/// `f` accepts `lo` and `hi` and rejects the next representable values
/// outside, `lo.next_down()` and `hi.next_up()`, with an error naming
/// `name`. An infinite `hi` checks `f64::MAX` accepted and `∞` rejected.
#[track_caller]
fn edges<T: core::fmt::Debug>(
    name: &str,
    f: impl Fn(f64) -> Result<T, ParamError>,
    lo: f64,
    hi: f64,
) {
    let hi = if hi == INF { f64::MAX } else { hi };
    for v in [lo, hi] {
        if let Err(e) = f(v) {
            panic!("{name} = {v:e} should be accepted: {e}");
        }
    }
    for v in [lo.next_down(), hi.next_up()] {
        rejected_naming(name, f(v), &format!("{v:e}"));
    }
}

/// `got` is an error whose message names `name` (alone, or as one of an
/// ordered pair).
#[track_caller]
fn rejected_naming<T: core::fmt::Debug>(name: &str, got: Result<T, ParamError>, at: &str) {
    match got {
        Err(e) => assert!(
            e.to_string().contains(&format!("`{name}`")),
            "{name} = {at}: {e}"
        ),
        Ok(x) => panic!("{name} = {at} should be rejected, got {x:?}"),
    }
}

/// Only the upper end of a rule: `hi` accepted, `hi.next_up()` rejected
/// naming `name`.
#[track_caller]
fn upper_edge<T: core::fmt::Debug>(name: &str, f: impl Fn(f64) -> Result<T, ParamError>, hi: f64) {
    if let Err(e) = f(hi) {
        panic!("{hi:e} should be accepted: {e}");
    }
    rejected_naming(name, f(hi.next_up()), &format!("{:e}", hi.next_up()));
}

/// [`edges`] for an integer field: `lo` and `hi` accepted, `lo − 1` (if
/// representable) and `hi + 1` (if given) rejected by name.
#[track_caller]
fn integer_edges<T: core::fmt::Debug>(
    name: &str,
    f: impl Fn(u32) -> Result<T, ParamError>,
    lo: u32,
    hi: Option<u32>,
) {
    let mut accepted = vec![lo];
    let mut rejected = vec![];
    if lo > 0 {
        rejected.push(lo - 1);
    }
    if let Some(h) = hi {
        accepted.push(h);
        rejected.push(h + 1);
    }
    for v in accepted {
        if let Err(e) = f(v) {
            panic!("{name} = {v} should be accepted: {e}");
        }
    }
    for v in rejected {
        rejected_naming(name, f(v), &v.to_string());
    }
}

#[test]
fn boundaries_friction() {
    let p = |f: fn(&mut FrictionParams, f64)| {
        move |v: f64| {
            let mut x = friction();
            f(&mut x, v);
            x.validated()
        }
    };
    edges("viscous", p(|x, v| x.viscous = v), 0.0, INF);
    edges("coulomb", p(|x, v| x.coulomb = v), 0.0, INF);
    edges("stribeck", p(|x, v| x.stribeck = v), 0.0, INF);
    edges("stribeck_shape", p(|x, v| x.stribeck_shape = v), TINY, INF);
    // The box: f_τ,min ≥ 1e-3; min ≤ max per component; ρ_F ≥ 0.
    edges(
        "min.stribeck_shape",
        |v| {
            FrictionBounds::try_new(
                FrictionParams {
                    stribeck_shape: v,
                    ..box_min()
                },
                box_max(),
                VARIABLE,
            )
        },
        1e-3,
        10.0,
    );
    // The upper end of `min.stribeck_shape` is `max.stribeck_shape`: above
    // it the pair is out of order, named by its first member.
    edges(
        "min.coulomb",
        |v| {
            FrictionBounds::try_new(
                FrictionParams {
                    coulomb: v,
                    ..box_min()
                },
                box_max(),
                VARIABLE,
            )
        },
        0.0,
        0.012,
    );
    edges(
        "variable[3]",
        |v| FrictionBounds::try_new(box_min(), box_max(), [1e-3, 1e-2, 1e-2, v]),
        0.0,
        INF,
    );
}

#[test]
fn boundaries_robust_adaptive_design() {
    let d = |f: fn(&mut RobustAdaptiveDesign, f64)| {
        move |v: f64| {
            design(|d| {
                // No other term of K_r, so each bound of the robust gain is
                // reached alone.
                d.uncertainty.boundary_layer = 0.0;
                d.uncertainty.nonparametric_friction = 0.0;
                d.uncertainty.base_acceleration = 0.0;
                d.uncertainty.torque_estimate = 0.0;
                f(d, v)
            })
        }
    };
    edges("rotor_inertia", d(|d, v| d.rotor_inertia = v), TINY, 30.0);
    edges("ratio", d(|d, v| d.ratio = v), 1.0, INF);
    // λ alone, with an inertia small enough for λ² I_m ≤ 1e8 at λ = 1e11.
    edges(
        "lambda",
        d(|d, v| {
            d.rotor_inertia = 1e-20;
            d.lambda = v
        }),
        TINY,
        1e11,
    );
    // λ² I_m ≤ 1e8 N·m/rad: at I_m = 1, λ = 1e4 exactly.
    upper_edge(
        "lambda²·rotor_inertia",
        d(|d, v| {
            d.rotor_inertia = 1.0;
            d.lambda = v
        }),
        1e4,
    );
    // K_I ≥ 0, and K_I T ≤ 1e8: at T = 1 s, K_I = 1e8.
    let k_i = d(|d, v| {
        d.sample_period = 1.0;
        d.integral_gain = v
    });
    assert!(k_i(0.0).is_ok());
    rejected_naming("integral_gain", k_i((0.0f64).next_down()), "-0");
    upper_edge("integral_gain·sample_period", k_i, 1e8);
    for (j, hi) in [1e8, 1e8, 1e8, 1e14].into_iter().enumerate() {
        let name = [
            "adaptation_gain[0]",
            "adaptation_gain[1]",
            "adaptation_gain[2]",
            "adaptation_gain[3]",
        ][j];
        let at = move |v: f64| {
            design(|d| {
                d.sample_period = 1.0;
                d.adaptation_gain[j] = v
            })
        };
        // The lower end names the gain, the upper end the step μ_j T.
        assert!(at(0.0).is_ok() && at(hi).is_ok(), "{name}");
        assert_eq!(at((0.0f64).next_down()).unwrap_err().name(), name);
        let product = [
            "adaptation_gain[0]·sample_period",
            "adaptation_gain[1]·sample_period",
            "adaptation_gain[2]·sample_period",
            "adaptation_gain[3]·sample_period",
        ][j];
        assert_eq!(at(hi.next_up()).unwrap_err().name(), product);
    }
    let lsb = 1.0 / 65536.0;
    edges("eps_r", d(|d, v| d.eps_r = v), lsb, 30_000.0);
    edges("eps_velocity", d(|d, v| d.eps_velocity = v), lsb, 30_000.0);
    edges("eps_f[0]", d(|d, v| d.eps_f[0] = v), lsb, 30_000.0);
    edges("eps_f[1]", d(|d, v| d.eps_f[1] = v), lsb, 30_000.0);
    edges("eps_f[2]", d(|d, v| d.eps_f[2] = v), lsb, 30_000.0);
    // Y_4 is stored in mN·m·rad²/s²: the layer's range is 1e3 times lower.
    edges("eps_f[3]", d(|d, v| d.eps_f[3] = v), lsb / 1e3, 30.0);
    edges(
        "uncertainty.boundary_layer",
        d(|d, v| d.uncertainty.boundary_layer = v),
        0.0,
        30.0,
    );
    edges(
        "uncertainty.nonparametric_friction",
        d(|d, v| d.uncertainty.nonparametric_friction = v),
        0.0,
        30.0,
    );
    // ρ_base ≤ 30/I_m: at I_m = 1 kg·m², 30 rad/s².
    edges(
        "uncertainty.base_acceleration",
        d(|d, v| {
            d.rotor_inertia = 1.0;
            d.lambda = 1.0;
            d.uncertainty.base_acceleration = v
        }),
        0.0,
        30.0,
    );
    // ρ_τt ≤ 30 N: at N = 100, 3000 N·m.
    edges(
        "uncertainty.torque_estimate",
        d(|d, v| d.uncertainty.torque_estimate = v),
        0.0,
        3000.0,
    );
    // The sum K_r ≤ 30 N·m, reached as 28 + 2 (one ulp of 28 is one ulp
    // of 30, so the next value of the first term moves the sum).
    let sum = d(|d, v| {
        d.uncertainty.nonparametric_friction = 2.0;
        d.uncertainty.boundary_layer = v
    });
    assert!(sum(28.0).is_ok());
    assert!(matches!(
        sum(28f64.next_up()),
        Err(ParamError::CombinationOutOfRange { max, .. }) if max == 30.0
    ));
    edges("torque_limit", d(|d, v| d.torque_limit = v), TINY, 16.0);
    edges("integral_limit", d(|d, v| d.integral_limit = v), 0.0, 16.0);
    edges("sample_period", d(|d, v| d.sample_period = v), 1e-7, 1.0);
    // The initial estimate inside Table 4.1's box.
    edges(
        "initial_friction.viscous",
        d(|d, v| d.initial_friction.viscous = v),
        0.0,
        1e-4,
    );
    edges(
        "initial_friction.coulomb",
        d(|d, v| d.initial_friction.coulomb = v),
        0.0,
        0.012,
    );
    edges(
        "initial_friction.stribeck",
        d(|d, v| d.initial_friction.stribeck = v),
        0.0,
        0.012,
    );
    edges(
        "initial_friction.stribeck_shape",
        d(|d, v| d.initial_friction.stribeck_shape = v),
        0.01,
        10.0,
    );
    // ρ_F within the coefficient range: [1e8, 1e8, 1e8, 1e11].
    for (j, hi) in [1e8, 1e8, 1e8, 1e11].into_iter().enumerate() {
        let name = [
            "friction_bounds.variable[0]",
            "friction_bounds.variable[1]",
            "friction_bounds.variable[2]",
            "friction_bounds.variable[3]",
        ][j];
        let at = move |v: f64| {
            let mut rho = VARIABLE;
            rho[j] = v;
            let b = FrictionBounds::try_new(box_min(), box_max(), rho).unwrap();
            design(|d| d.friction_bounds = b)
        };
        assert!(at(0.0).is_ok() && at(hi).is_ok(), "{name}");
        assert_eq!(at(hi.next_up()).unwrap_err().name(), name);
    }
}

#[test]
fn boundaries_passive_mode_collision() {
    let p = |f: fn(&mut PassiveSettings, f64)| move |v: f64| passive(|s| f(s, v));
    // With no gain the inertia has no upper limit.
    edges(
        "rotor_inertia",
        p(|s, v| {
            s.gain = 0.0;
            s.rotor_inertia = v
        }),
        TINY,
        INF,
    );
    // I_m·gain/N ≤ 1e6: at I_m = N = 1, gain ≤ 1e6.
    edges(
        "gain",
        p(|s, v| {
            s.rotor_inertia = 1.0;
            s.ratio = 1.0;
            s.gain = v
        }),
        0.0,
        1e6,
    );
    edges("ratio", p(|s, v| s.ratio = v), 1.0, INF);
    edges(
        "eps_velocity",
        p(|s, v| s.eps_velocity = v),
        1.0 / 65536.0,
        INF,
    );
    edges("torque_limit", p(|s, v| s.torque_limit = v), TINY, 16.0);
    edges(
        "nominal_friction.viscous",
        p(|s, v| s.nominal_friction.viscous = v),
        0.0,
        INF,
    );

    let m = |f: fn(&mut ModeSettings, f64)| move |v: f64| mode(|s| f(s, v));
    // exit < enter ≤ 30 000 N·m (Table preset: exit 1, enter 2).
    edges(
        "enter_passive",
        m(|s, v| s.enter_passive = v),
        1f64.next_up(),
        30_000.0,
    );
    edges(
        "exit_passive",
        m(|s, v| s.exit_passive = v),
        TINY,
        2f64.next_down(),
    );
    integer_edges("debounce", |v| mode(|s| s.debounce = v as u16), 1, None);
    // ω T ≤ 0.5 at T = 4 ms: ω ≤ 125 rad/s.
    edges(
        "rejoin_bandwidth",
        m(|s, v| s.rejoin_bandwidth = v),
        TINY,
        125.0,
    );
    edges(
        "bias_time_constant",
        m(|s, v| s.bias_time_constant = v),
        0.004,
        INF,
    );
    let release = |speed: f64, samples: u16| {
        mode(|_| {}).and_then(|m| m.with_release(ReleaseRule { speed, samples }))
    };
    edges("rule.speed", |v| release(v, 5), TINY, 30_000.0);
    integer_edges("rule.samples", |v| release(0.1, v as u16), 3, None);

    let c = |f: fn(&mut CollisionSettings, f64)| move |v: f64| collision(|s| f(s, v));
    edges(
        "threshold",
        c(|s, v| {
            s.release_threshold = TINY;
            s.threshold = v
        }),
        TINY,
        30_000.0,
    );
    edges(
        "release_threshold",
        c(|s, v| s.release_threshold = v),
        TINY,
        5.0,
    );
    integer_edges(
        "debounce",
        |v| collision(|s| s.debounce = v as u16),
        1,
        None,
    );
    integer_edges("release", |v| collision(|s| s.release = v as u16), 1, None);
}

#[test]
fn boundaries_drive_and_estimator() {
    // A drive whose c_f (0.0625 = 2⁻⁴, exact) keeps c_f·max_torque exact.
    let soft = HarmonicDriveParams::try_new(
        FlexsplineParams::try_new(FlexsplineSettings {
            k_f0: 8000.0,
            c_f: 0.0625,
        })
        .unwrap(),
        drive().wave_generator(),
        100.0,
    )
    .unwrap();
    let e = |f: fn(&mut TorqueEstimatorSettings, f64)| {
        move |v: f64| {
            estimator(|s| {
                s.drive = soft;
                f(s, v)
            })
        }
    };
    // c_f·max_torque ≤ 7.5: max_torque ≤ 120 N·m for this drive.
    upper_edge("drive.c_f·max_torque", e(|s, v| s.max_torque = v), 120.0);
    // A drive stiff enough (c_f = 1e-6) for the full torque range.
    let stiff = HarmonicDriveParams::try_new(
        FlexsplineParams::try_new(FlexsplineSettings {
            k_f0: 1e7,
            c_f: 1e-6,
        })
        .unwrap(),
        drive().wave_generator(),
        100.0,
    )
    .unwrap();
    edges(
        "max_torque",
        |v| {
            estimator(|s| {
                s.drive = stiff;
                s.max_torque = v
            })
        },
        1e-3,
        30_000.0,
    );
    integer_edges(
        "link_counts_per_rev",
        |v| estimator(|s| s.link_counts_per_rev = v),
        1,
        None,
    );
    integer_edges(
        "motor_counts_per_rev",
        |v| estimator(|s| s.motor_counts_per_rev = v),
        1,
        None,
    );
    // N an integer in [1, 65535]; below 1 no drive is built.
    let with_ratio = |n: f64| {
        let d = HarmonicDriveParams::try_new(drive().flexspline(), drive().wave_generator(), n)?;
        estimator(|s| {
            s.drive = d;
            s.link_counts_per_rev = 1;
            s.motor_counts_per_rev = 1;
        })
    };
    assert!(with_ratio(1.0).is_ok());
    upper_edge("drive.ratio", with_ratio, 65535.0);
    rejected_naming("drive.ratio", with_ratio(65536.0), "65536");
    // max_motor_speed: > 0, and at most 2³⁰ counts per 4 ms tick at
    // 2000 counts per revolution, 2³⁰·(2π/2000)/0.004 rad/s (the largest
    // accepted float found by stepping down from it, checked to lie within
    // rounding of it).
    let speed = |v: f64| joint(|s| s.max_motor_speed = v);
    let top = (1u64 << 30) as f64 * (core::f64::consts::TAU / 2000.0) / 0.004;
    let mut hi = top.next_up().next_up();
    while speed(hi).is_err() {
        hi = hi.next_down();
    }
    assert!((hi / top - 1.0).abs() < 1e-15, "{hi} vs {top}");
    let tiny = f64::MIN_POSITIVE * f64::EPSILON;
    assert!(speed(tiny).is_ok());
    rejected_naming("max_motor_speed", speed(0.0), "0");
    rejected_naming("max_motor_speed", speed(f64::NAN), "NaN");
    match speed(hi.next_up()) {
        Err(e) => assert!(
            e.to_string()
                .starts_with("`max_motor_speed·mode.active.sample_period·"),
            "{e}"
        ),
        Ok(_) => panic!("{:e} should be rejected", hi.next_up()),
    }
    integer_edges(
        "speed_window",
        |v| joint(|s| s.speed_window = v as u8),
        1,
        Some(mrr_control::joint::MAX_SPEED_WINDOW as u32),
    );

    // Compliance parts.
    let curve_at = |f: fn(&mut CatalogueCurve, f64)| move |v: f64| curve(|c| f(c, v));
    edges("k1", curve_at(|c, v| c.k1 = v), TINY, INF);
    edges("k3", curve_at(|c, v| c.k3 = v), TINY, INF);
    edges("t2", curve_at(|c, v| c.t2 = v), 3.9f64.next_up(), INF);
    edges(
        "t1",
        curve_at(|c, v| {
            c.t2 = INF.next_down();
            c.t1 = v
        }),
        TINY,
        INF.next_down().next_down(),
    );
    edges(
        "a1",
        |v| CubicStiffness::try_new(CubicStiffnessSettings { a1: v, a3: 0.0 }),
        TINY,
        INF,
    );
    edges(
        "a3",
        |v| CubicStiffness::try_new(CubicStiffnessSettings { a1: 1.0, a3: v }),
        0.0,
        INF,
    );
    // c_f over its whole range, with a K_f0 that keeps π/(2 c_f K_f0) in
    // [1e-6, 1] rad at either end.
    edges(
        "c_f",
        |c_f| {
            let k_f0 = if c_f < 1.0 { 1e7 } else { 1.0 };
            FlexsplineParams::try_new(FlexsplineSettings { k_f0, c_f })
        },
        1e-6,
        1e6,
    );
    edges(
        "c_w",
        |c_w| WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0: 1.0, c_w }),
        1e-6,
        1e6,
    );
    // k_w0 > 0 alone; with c_w = 1 the torsion 1/(c_w k_w0) is finite
    // from k_w0 = 1/f64::MAX on.
    let wg = |k_w0: f64| WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0, c_w: 1.0 });
    assert!(wg(1.0 / f64::MAX).is_ok() && wg(f64::MAX).is_ok());
    rejected_naming("c_w·k_w0", wg((1.0 / f64::MAX).next_down()), "1/MAX-");
    rejected_naming("k_w0", wg(0.0), "0");
    rejected_naming("k_w0", wg(INF), "inf");
    edges(
        "k_a",
        |k_a| {
            TwoSpringParams::try_new(TwoSpringSettings {
                k_a,
                k_b: 1.0,
                friction: 0.0,
            })
        },
        TINY,
        INF,
    );
    edges(
        "friction",
        |friction| {
            TwoSpringParams::try_new(TwoSpringSettings {
                k_a: 1.0,
                k_b: 1.0,
                friction,
            })
        },
        0.0,
        INF,
    );
    edges(
        "ratio",
        |ratio| {
            WaveGeneratorTorqueParams::try_new(WaveGeneratorTorqueSettings {
                backdrive_friction: 1.0,
                ratio,
            })
        },
        1.0,
        INF,
    );
    for (i, name) in ["a0", "a_l1", "b_l1", "a_w1", "b_w1", "a_w2", "b_w2"]
        .into_iter()
        .enumerate()
    {
        edges(
            name,
            |v| {
                let mut c = [0.0; 7];
                c[i] = v;
                KinematicErrorModel::try_new(c)
            },
            -0.01,
            0.01,
        );
    }
}

/// The catalogue's own ranges guard the identification against overflow;
/// whether an edge value identifies also depends on the derived
/// constants, so at the edges the field's own rule is checked: the edge
/// passes it (accepted, or rejected by a combination), the next value out
/// is rejected naming the field.
#[test]
fn boundaries_catalogue() {
    // `at` passes the field's own range (accepted, or rejected naming
    // another rule), `out` is rejected by it.
    let own = |name: &str,
               at: Result<HarmonicDriveParams, ParamError>,
               out: Result<HarmonicDriveParams, ParamError>| {
        if let Err(e) = at {
            assert!(
                !e.to_string()
                    .starts_with(&format!("parameter `{name}` must lie in [")),
                "{name}: {e}"
            );
        }
        let e = out.unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("parameter `{name}` must lie in [")),
            "{name}: {e}"
        );
    };
    let (k_lo, k_hi, t_lo, t_hi) = (1e-6f64, 1e12f64, 1e-6f64, 1e6f64);
    own(
        "k1",
        catalogue(|c| {
            c.k2 = 2e-6;
            c.k1 = k_lo
        }),
        catalogue(|c| {
            c.k2 = 2e-6;
            c.k1 = k_lo.next_down()
        }),
    );
    own(
        "k2",
        catalogue(|c| {
            c.k1 = 1e11;
            c.k2 = k_hi
        }),
        catalogue(|c| {
            c.k1 = 1e11;
            c.k2 = k_hi.next_up()
        }),
    );
    own(
        "t1",
        catalogue(|c| {
            c.t2 = 1e-5;
            c.t1 = t_lo
        }),
        catalogue(|c| {
            c.t2 = 1e-5;
            c.t1 = t_lo.next_down()
        }),
    );
    own(
        "t2",
        catalogue(|c| {
            c.t1 = 5e5;
            c.t2 = t_hi
        }),
        catalogue(|c| {
            c.t1 = 5e5;
            c.t2 = t_hi.next_up()
        }),
    );
    // Edges that do identify: T1 = 1 µN·m with T2 = 2 µN·m and slopes
    // 1 and 2 N·m/rad (c_f ≈ 7.6e5 1/(N·m)); T2 = 1e6 N·m with T1 half of
    // it and slopes 1e7, 2e7.
    let small = catalogue(|c| {
        c.k1 = 1.0;
        c.k2 = 2.0;
        c.t1 = 1e-6;
        c.t2 = 2e-6
    });
    assert!(small.is_ok(), "{small:?}");
    let large = catalogue(|c| {
        c.k1 = 1e7;
        c.k2 = 2e7;
        c.t1 = 5e5;
        c.t2 = 1e6
    });
    assert!(large.is_ok(), "{large:?}");
    edges("ratio", |v| catalogue(|c| c.ratio = v), 1.0, INF);
}

#[test]
fn boundaries_wrist() {
    edges("gain", GaugeAmplifier::try_new, 1.0, 1e4);
    edges(
        "offset",
        |v| FtSensorParams::try_new(DecouplingMatrix::example(), v),
        0.0,
        1.0,
    );
    // κ₁ = 8 for the diagonal matrix: max_condition ≥ 1 is its own rule,
    // and 8 is the smallest that accepts this matrix.
    // The identity (κ₁ = 1) for `max_condition`'s own rule, `[1, ∞)`.
    let mut identity = [[0.0; 6]; 6];
    for (i, row) in identity.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    edges(
        "max_condition",
        |v| DecouplingMatrix::try_new(identity, v),
        1.0,
        INF,
    );
    // κ₁ = 8 for the diagonal matrix: 8 is the smallest limit that
    // accepts it.
    assert!(DecouplingMatrix::try_new(diagonal(), 8.0).is_ok());
    rejected_naming(
        "κ₁(matrix)",
        DecouplingMatrix::try_new(diagonal(), 8f64.next_down()),
        "8-",
    );
    edges(
        "phi",
        WristParams::try_new,
        1f64.to_radians(),
        30f64.to_radians(),
    );

    let a = |f: fn(&mut AdmittanceSettings, f64)| move |v: f64| admittance(|s| f(s, v));
    // K_c < a_max(1)/(T K_t) = 2 sin(π/6)/(0.004·1000): the open end.
    let kmax = 2.0 * (core::f64::consts::PI / 6.0).sin() / (0.004 * 1000.0);
    edges("gain[0]", a(|s, v| s.gain[0] = v), TINY, kmax.next_down());
    edges("gain[1]", a(|s, v| s.gain[1] = v), TINY, kmax.next_down());
    // Stiffness: K_c = 0.1 stays stable up to K_t < 2500 N·m/rad.
    edges(
        "stiffness",
        a(|s, v| {
            s.gain = [TINY; 2];
            s.stiffness = v
        }),
        TINY,
        INF,
    );
    edges(
        "sample_period",
        a(|s, v| {
            s.gain = [TINY; 2];
            s.sample_period = v
        }),
        1e-6,
        1.0,
    );
    integer_edges(
        "lag_samples",
        |v| {
            admittance(|s| {
                s.gain = [TINY; 2];
                s.lag_samples = v as u8
            })
        },
        0,
        Some(16),
    );
    let half_pi = core::f64::consts::FRAC_PI_2;
    edges("limits[0]", a(|s, v| s.limits[0] = v), TINY, half_pi);
    edges("limits[1]", a(|s, v| s.limits[1] = v), TINY, half_pi);
    edges("max_rate", a(|s, v| s.max_rate = v), TINY, 1e3);
    edges("deadband", a(|s, v| s.deadband = v), 0.0, 1e3);
    edges(
        "desired_torque[0]",
        a(|s, v| s.desired_torque[0] = v),
        -1e3,
        1e3,
    );
    edges(
        "desired_torque[1]",
        a(|s, v| s.desired_torque[1] = v),
        -1e3,
        1e3,
    );

    let w = |f: fn(&mut WristModeSettings, f64)| move |v: f64| wrist_modes(|s| f(s, v));
    edges(
        "enter_passive",
        w(|s, v| s.enter_passive = v),
        0.5f64.next_up(),
        1e3,
    );
    edges(
        "exit_passive",
        w(|s, v| s.exit_passive = v),
        TINY,
        1f64.next_down(),
    );
    edges("rest_speed", w(|s, v| s.rest_speed = v), TINY, INF);
    edges(
        "rejoin_bandwidth",
        w(|s, v| s.rejoin_bandwidth = v),
        TINY,
        125.0,
    );
    integer_edges(
        "debounce",
        |v| wrist_modes(|s| s.debounce = v as u16),
        1,
        None,
    );

    // The motors: I_mi N_i ≤ 30 kg·m² (N = 531).
    let im_max = 30.0 / 531.0;
    let m = |f: fn(&mut WristMotorDesign, f64)| {
        move |v: f64| {
            wrist_active(|d| {
                d[0].law.rotor_inertia = 0.0;
                d[0].law.uncertainty.base_acceleration = 0.0;
                // No other K_r term, so I_m ρ_base/N may reach 30 N·m.
                d[0].law.uncertainty.boundary_layer = 0.0;
                d[0].law.uncertainty.nonparametric_friction = 0.0;
                d[0].law.uncertainty.torque_estimate = 0.0;
                f(&mut d[0], v)
            })
        }
    };
    // I_mi > 0, and I_mi N_i ≤ 30 kg·m²: at N = 1, I_mi ≤ 30.
    let _ = im_max;
    let im = m(|d, v| {
        d.base_acceleration = 0.0;
        d.law.ratio = 1.0;
        d.rotor_inertia = v
    });
    assert!(im(TINY).is_ok());
    rejected_naming("designs[0].rotor_inertia", im(0.0), "0");
    upper_edge("designs[0].rotor_inertia·designs[0].law.ratio", im, 30.0);
    edges(
        "designs[0].law.ratio",
        m(|d, v| {
            d.rotor_inertia = TINY;
            d.law.ratio = v
        }),
        1.0,
        INF,
    );
    // ρ_base ≥ 0, and ρ_base/N ≤ 30/(I_mi N): at I_mi = 1 kg·m²,
    // ρ_base ≤ 30 rad/s² (N = 531).
    edges(
        "designs[0].base_acceleration",
        m(|d, v| {
            d.rotor_inertia = 1.0 / 531.0;
            d.base_acceleration = v
        }),
        0.0,
        30.0 * 531.0,
    );
}
