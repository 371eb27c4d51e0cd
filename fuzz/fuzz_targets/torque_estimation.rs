//! Fuzz identification (eq. 2.31–2.37) and the torque estimator
//! (eq. 3.8–3.10) with arbitrary inputs: no panic, and no NaN or
//! out-of-limit torque on any backend.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mrr_control::estimation::{
    TorqueEstimatorConfig, TorqueEstimatorParams, TorqueEstimatorSettings,
};
use mrr_control::harmonic_drive::kinematic_error::KinematicErrorModel;
use mrr_control::harmonic_drive::CatalogueData;
use mrr_control::scalar::{Scalar, I16F16};

fn run<S: Scalar>(p: &TorqueEstimatorParams, start: i64, readings: &[(u32, u32, f32)]) {
    let cfg = TorqueEstimatorConfig::<S>::new(p);
    let mut st = cfg.state(start, readings.first().map_or(0, |r| r.1));
    let limit = S::from_f64(p.max_torque() * S::UNITS.link_torque);
    for &(link, motor, tau_w) in readings {
        let e = cfg.update(&mut st, link, motor, S::from_f64(tau_w as f64));
        assert!(!e.torque.is_nan() && !e.torsion.is_nan() && !e.flexspline_torsion.is_nan());
        assert!(e.torque.abs() <= limit, "{:?} beyond {:?}", e.torque, limit);
        let r = cfg.update_radians(
            S::from_f64(link as f64 * 1e-6),
            S::from_f64(motor as f64 * 1e-4),
            S::from_f64(tau_w as f64),
        );
        assert!(!r.torque.is_nan() && r.torque.abs() <= limit);
    }
}

fuzz_target!(
    |data: ([f64; 7], [u32; 2], u64, i64, bool, Vec<(u32, u32, f32)>)| {
        let (cat, [l, m], max_t, start, with_ke, readings) = data;
        let catalogue = CatalogueData {
            k1: cat[0],
            k2: cat[1],
            t1: cat[2],
            t2: cat[3],
            hysteresis_loss: cat[4],
            starting_torque: cat[5],
            ratio: libm_round(cat[6]),
        };
        // Identification never panics; arbitrary input mostly fails cleanly.
        let drive = match catalogue.identify() {
            Ok(d) => {
                // An accepted catalogue gives a physical model.
                let (f, w) = (d.flexspline(), d.wave_generator());
                for v in [f.k_f0(), f.c_f(), w.k_w0(), w.c_w(), d.ratio()] {
                    assert!(v.is_finite() && v > 0.0, "{d:?} from {catalogue:?}");
                }
                d
            }
            Err(_) => CatalogueData::SHD_17_100.identify().unwrap(),
        };
        // Scaled catalogues either fail by name or identify.
        if let Ok(c) = CatalogueData::scaled_from_shd17(cat[0], cat[1], cat[6]) {
            let d = c
                .identify()
                .expect("a scaled SHD-17 catalogue always identifies");
            assert!(d.flexspline().k_f0().is_finite() && d.flexspline().c_f().is_finite());
        }
        let ke = with_ke.then(KinematicErrorModel::table_3_2);
        let max_torque = (max_t % 30_000) as f64 + 0.5;
        let Ok(p) = TorqueEstimatorParams::try_new(TorqueEstimatorSettings {
            drive,
            kinematic_error: ke,
            link_counts_per_rev: l,
            motor_counts_per_rev: m,
            max_torque,
        }) else {
            return;
        };
        let readings = &readings[..readings.len().min(64)];
        run::<f32>(&p, start, readings);
        run::<f64>(&p, start, readings);
        run::<I16F16>(&p, start, readings);
    }
);

fn libm_round(x: f64) -> f64 {
    if x.is_finite() {
        x.round()
    } else {
        x
    }
}
