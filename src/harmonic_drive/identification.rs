//! Identification of the proposed compliance model from catalogue numbers
//! (thesis §2.3, eq. 2.31–2.37).
//!
//! The flexspline stiffness of eq. (2.24) is matched to the catalogue's
//! piecewise slopes at the middle of the first two pieces: `K_fl(T1/2) = K1`
//! (2.31) and `K_fl((T1+T2)/2) = K2` (2.32). Solving the pair gives
//!
//! ```text
//! K_f0 = (K1 S² − K2 T1²) / (S² − T1²)
//!      = K1 + (K1 − K2) T1² / (S² − T1²)
//! c_f  = 2 √( (K2 − K1) / (K1 S² − K2 T1²) ),     S = T1 + T2
//! ```
//!
//! (eq. 2.33, 2.34). The wave generator is matched to the hysteresis loss
//! `Ψ` and the starting torque `τ_fs`: `K_w0 = 2 τ_fs / (N Ψ)` (2.35) and
//! `c_w = 2 / (N K_w0 Ψ)` (2.37), which simplifies to `c_w = 1/τ_fs`.
//!
//! The thesis's printed SHD-17-100 results (`K_f0 = 8.2e3`, `c_f = 0.012`)
//! do not follow from its own equations and inputs; the equations give
//! `K_f0 = 8335.98 N·m/rad`, `c_f = 0.044940 1/(N·m)` (errata E2.3).
//!
//! # Example
//! Identify the SHD-17-100 from its catalogue sheet and check the model
//! against the sheet: the flexspline's stiffness, measured by a central
//! difference of its torsion curve, is `K1` and `K2` at the middles of the
//! first two pieces (the conditions 2.31–2.32 the identification
//! imposes), and the hysteresis width `2/(N c_w K_w0)` is the catalogue's
//! loss `Ψ`.
//!
//! ```
//! use mrr_control::harmonic_drive::CatalogueData;
//! let sheet = CatalogueData::SHD_17_100;
//! let drive = sheet.identify()?;
//! let f = drive.flexspline();
//! let stiffness = |tau: f64| {
//!     let h = 1e-3;
//!     2.0 * h / (f.torsion(tau + h) - f.torsion(tau - h))
//! };
//! assert!((stiffness(sheet.t1 / 2.0) - sheet.k1).abs() < 1e-3 * sheet.k1);
//! assert!((stiffness((sheet.t1 + sheet.t2) / 2.0) - sheet.k2).abs() < 1e-3 * sheet.k2);
//! let width = 2.0 * drive.wave_generator().max_torsion() / drive.ratio();
//! assert!((width - sheet.hysteresis_loss).abs() < 1e-12);
//! # Ok::<(), mrr_control::ParamError>(())
//! ```

use super::compliance::{
    FlexsplineParams, FlexsplineSettings, HarmonicDriveParams, WaveGeneratorParams,
    WaveGeneratorSettings,
};
use crate::error::{gear_ratio, in_range, increasing, positive, ParamError};

/// Catalogue data of a harmonic drive and two measured friction torques.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogueData {
    /// Slope of the first piece `K1`, N·m/rad.
    pub k1: f64,
    /// Slope of the second piece `K2`, N·m/rad (must exceed `K1`).
    pub k2: f64,
    /// End of the first piece `T1`, N·m.
    pub t1: f64,
    /// End of the second piece `T2`, N·m (must exceed `T1`).
    pub t2: f64,
    /// Hysteresis loss `Ψ`, rad (output side).
    pub hysteresis_loss: f64,
    /// Starting torque on the wave generator `τ_fs`, N·m.
    pub starting_torque: f64,
    /// Gear ratio `N`.
    pub ratio: f64,
}

impl CatalogueData {
    /// The SHD-17-100-2SH data used in thesis §2.4: `K1 = 8.4e3`,
    /// `K2 = 9.4e3` N·m/rad, `T1 = 3.9`, `T2 = 12` N·m, `Ψ = 2.9e-4` rad,
    /// `τ_fs = 1.2` N·cm, `N = 100`.
    pub const SHD_17_100: CatalogueData = CatalogueData {
        k1: 8.4e3,
        k2: 9.4e3,
        t1: 3.9,
        t2: 12.0,
        hysteresis_loss: 2.9e-4,
        starting_torque: 0.012,
        ratio: 100.0,
    };

    /// Catalogue data for another SHD size, scaled from the shape of
    /// [`SHD_17_100`](Self::SHD_17_100) — for drives where only the rated
    /// torque, `K2` and the ratio are known (Table 3.1 gives just those).
    ///
    /// **Assumption, not thesis data.** The shape of the SHD-17-100
    /// catalogue is kept: `K1/K2 = 8.4/9.4`, `T1/T_rated = 3.9/16`,
    /// `T2/T_rated = 12/16`, the same hysteresis loss `Ψ = 2.9e-4` rad, and a
    /// starting torque that is the same share of the rated torque seen from
    /// the motor side, `τ_fs = 0.012 · (T_rated/16) · (100/N)` N·m. Because
    /// the ratios `K2/K1` and `T2/T1` are those of the SHD-17-100, every
    /// scaled catalogue is admissible for [`identify`](Self::identify);
    /// identification then gives `K_f0 ∝ K2` and `c_f ∝ 1/T_rated`.
    ///
    /// Errors: a rated torque or `K2` that is not finite and positive, or a
    /// ratio below 1, named by field; and extreme values whose scaled
    /// catalogue does not identify (e.g. a starting torque that underflows
    /// to a zero `K_w0`), with the error [`identify`](Self::identify) gives.
    pub fn scaled_from_shd17(rated_torque: f64, k2: f64, ratio: f64) -> Result<Self, ParamError> {
        let rated = positive("rated_torque", rated_torque)?;
        let k2 = positive("k2", k2)?;
        let n = gear_ratio(ratio)?;
        let base = Self::SHD_17_100;
        let rated_base = 16.0;
        let scale = rated / rated_base;
        let c = CatalogueData {
            k1: k2 * (base.k1 / base.k2),
            k2,
            t1: base.t1 * scale,
            t2: base.t2 * scale,
            hysteresis_loss: base.hysteresis_loss,
            starting_torque: base.starting_torque * scale * (base.ratio / n),
            ratio: n,
        };
        // Extreme inputs can overflow or underflow a derived value; the
        // identification's check names it, spelled in this function's
        // arguments.
        c.identify().map_err(|e| {
            e.map_names(|name| match name {
                "k1" => "k1 = (8.4/9.4)·k2",
                "t1" => "t1 = 3.9·rated_torque/16",
                "t2" => "t2 = 12·rated_torque/16",
                "starting_torque" => "starting_torque = 0.012·(rated_torque/16)·(100/ratio)",
                other => other,
            })
        })?;
        Ok(c)
    }

    /// Eq. (2.31)–(2.37): the parameters of the proposed model.
    ///
    /// Errors name the offending value: any input not finite or not
    /// positive; `T2 ≤ T1` or `K2 ≤ K1` ([`ParamError::NotIncreasing`]: the
    /// model stiffens with torque, so a flat or softening catalogue has no
    /// real `c_f`); `K2/K1 ≥ ((T1+T2)/T1)²` ([`ParamError::OutOfRange`] on
    /// `k2`: the stiffening would be faster than eq. 2.24 can produce); a
    /// ratio below 1; slopes outside [`CATALOGUE_STIFFNESS_RANGE`] and
    /// knee torques outside [`CATALOGUE_TORQUE_RANGE`]. Every field is
    /// checked before anything is derived from it; a derived constant out
    /// of its model's range (e.g. `c_w` for an extreme starting torque) is
    /// a [`ParamError::CombinationOutOfRange`] spelled in the catalogue's
    /// fields.
    pub fn identify(&self) -> Result<HarmonicDriveParams, ParamError> {
        let (k_lo, k_hi) = CATALOGUE_STIFFNESS_RANGE;
        let (t_lo, t_hi) = CATALOGUE_TORQUE_RANGE;
        let k1 = in_range("k1", positive("k1", self.k1)?, k_lo, k_hi)?;
        let k2 = in_range("k2", positive("k2", self.k2)?, k_lo, k_hi)?;
        let t1 = in_range("t1", positive("t1", self.t1)?, t_lo, t_hi)?;
        let t2 = in_range("t2", positive("t2", self.t2)?, t_lo, t_hi)?;
        let psi = positive("hysteresis_loss", self.hysteresis_loss)?;
        let tau_fs = positive("starting_torque", self.starting_torque)?;
        let n = gear_ratio(self.ratio)?;
        increasing(("t1", t1), ("t2", t2))?;
        increasing(("k1", k1), ("k2", k2))?;
        // Eq. (2.33)–(2.34) divided through by T1², in terms of
        // r² = ((T1 + T2)/T1)², so that no product of torques can underflow
        // or overflow: K_f0 = (K1 r² − K2)/(r² − 1) and
        // c_f = 2 √((K2 − K1)/(K1 r² − K2)) / T1. With the ranges above
        // r² ≤ (1 + 1e12)² and K1 r² ≤ 1e36: every step is finite.
        let r = (t1 + t2) / t1;
        let r2 = r * r;
        let denom = k1 * r2 - k2;
        if denom <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "k2",
                value: k2,
                min: k1,
                max: k1 * r2,
            });
        }
        let k_f0 = denom / (r2 - 1.0); // eq. (2.33)
        let c_f = 2.0 * libm::sqrt((k2 - k1) / denom) / t1; // eq. (2.34)
        let k_w0 = 2.0 * tau_fs / (n * psi); // eq. (2.35)
        let c_w = 2.0 / (n * k_w0 * psi); // eq. (2.37)
        let flexspline = FlexsplineParams::try_new(FlexsplineSettings { k_f0, c_f })
            .map_err(|e| as_combination(e, flexspline_name))?;
        let wave_generator = WaveGeneratorParams::try_new(WaveGeneratorSettings { k_w0, c_w })
            .map_err(|e| as_combination(e, wave_generator_name))?;
        HarmonicDriveParams::try_new(flexspline, wave_generator, n)
            .map_err(|e| as_combination(e, wave_generator_name))
    }
}

/// Accepted catalogue slopes `K1`, `K2`, N·m/rad: wide enough for every
/// drive, narrow enough that no step of eq. (2.33)–(2.34) overflows.
pub const CATALOGUE_STIFFNESS_RANGE: (f64, f64) = (1e-6, 1e12);

/// Accepted catalogue knee torques `T1`, `T2`, N·m (the reciprocal of
/// the stiffening range [`super::compliance::STIFFENING_RANGE`] that
/// `c_f ≈ 1/T` must land in).
pub const CATALOGUE_TORQUE_RANGE: (f64, f64) = (1e-6, 1e6);

/// The flexspline constants of eq. (2.33)–(2.34), spelled in the
/// catalogue's fields.
fn flexspline_name(name: &'static str) -> &'static str {
    match name {
        "k_f0" => "k_f0 = (k1·r² − k2)/(r² − 1), r = (t1 + t2)/t1",
        "c_f" => "c_f = 2·√((k2 − k1)/(k1·r² − k2))/t1, r = (t1 + t2)/t1",
        "π/(2·c_f·k_f0)" => "π/(2·c_f·k_f0) from k1, k2, t1, t2",
        other => other,
    }
}

/// The wave-generator constants of eq. (2.35)–(2.37), spelled in the
/// catalogue's fields.
fn wave_generator_name(name: &'static str) -> &'static str {
    match name {
        "k_w0" => "k_w0 = 2·starting_torque/(ratio·hysteresis_loss)",
        "c_w" => "c_w = 2/(ratio·k_w0·hysteresis_loss) = 1/starting_torque",
        "c_w·k_w0" => "c_w·k_w0 = 2/(ratio·hysteresis_loss)",
        "1/(wave_generator.c_w·ratio·wave_generator.k_w0)" => {
            "1/(c_w·ratio·k_w0) = hysteresis_loss/2"
        }
        other => other,
    }
}

/// A derived constant's error as the combination of catalogue fields it
/// comes from, so that no error names a quantity the user did not write.
fn as_combination(e: ParamError, spell: fn(&'static str) -> &'static str) -> ParamError {
    let (value, min, max) = match e {
        ParamError::NotFinite { value, .. } => (value, f64::MIN, f64::MAX),
        ParamError::NotPositive { value, .. } => (value, f64::MIN_POSITIVE, f64::MAX),
        ParamError::OutOfRange {
            value, min, max, ..
        }
        | ParamError::CombinationOutOfRange {
            value, min, max, ..
        } => (value, min, max),
        // The ratio was validated above; other variants are not produced.
        other => return other,
    };
    ParamError::CombinationOutOfRange {
        name: spell(e.name()),
        value,
        min,
        max,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The SHD-17-100 example recomputed by hand from eq. (2.33)–(2.37):
    /// S² = 15.9² = 252.81, K1 S² − K2 T1² = 2 123 604 − 142 974 = 1 980 630,
    /// K_f0 = 1 980 630 / 237.6 = 8335.98…, c_f = 2 √(1000 / 1 980 630),
    /// K_w0 = 0.024 / 0.029, c_w = 1 / 0.012 (eq. 2.37, which solves the
    /// condition 0.5 Ψ = 1/(c_w N K_w0) of eq. 2.36; errata E2.11, E2.12).
    #[test]
    fn shd17_example_follows_the_equations() {
        let p = CatalogueData::SHD_17_100.identify().unwrap();
        assert!((p.flexspline().k_f0() - 1_980_630.0 / 237.6).abs() < 1e-6);
        assert!((p.flexspline().c_f() - 2.0 * (1000.0f64 / 1_980_630.0).sqrt()).abs() < 1e-12);
        assert!((p.wave_generator().k_w0() - 0.024 / 0.029).abs() < 1e-12);
        assert!((p.wave_generator().c_w() - 1.0 / 0.012).abs() < 1e-9);
        let w = p.wave_generator();
        assert!((0.5 * 2.9e-4 - 1.0 / (w.c_w() * 100.0 * w.k_w0())).abs() < 1e-15);
        // To the two decimals the errata print.
        assert_eq!(format!("{:.2}", p.flexspline().k_f0()), "8335.98");
        // The thesis prints K_f0 = 8.2e3 and c_f = 0.012 (errata E2.3): the
        // equations do not give those numbers.
        assert!((p.flexspline().k_f0() - 8.2e3).abs() > 100.0);
        assert!((p.flexspline().c_f() - 0.012).abs() > 0.03);
    }

    /// The scaled catalogue by hand: a drive rated 32 N·m (scale 2), `K2 =
    /// 2e4`, `N = 50` has `K1 = 2e4·8.4/9.4`, knees at 7.8 and 24 N·m, the
    /// loss of the SHD-17-100 and a starting torque of `0.012·2·(100/50)
    /// = 0.048` N·m.
    #[test]
    fn scaled_catalogue_by_hand() {
        let c = CatalogueData::scaled_from_shd17(32.0, 2e4, 50.0).unwrap();
        assert!((c.k1 - 2e4 * 8.4 / 9.4).abs() <= 1e-12 * c.k1);
        assert_eq!((c.k2, c.t1, c.t2, c.ratio), (2e4, 7.8, 24.0, 50.0));
        assert_eq!(c.hysteresis_loss, 2.9e-4);
        assert!(
            (c.starting_torque - 0.048).abs() <= 1e-15,
            "{}",
            c.starting_torque
        );
    }

    /// `K2/K1 ≥ ((T1+T2)/T1)²` is rejected on `k2` with the range it had:
    /// `(K1, K1 r²)`, here `r = (1 + 3)/1 = 4`, so at most `16 K1`.
    #[test]
    fn too_fast_stiffening_names_its_range() {
        let c = CatalogueData {
            k1: 1e3,
            k2: 1.6e4,
            t1: 1.0,
            t2: 3.0,
            ..CatalogueData::SHD_17_100
        };
        assert_eq!(
            c.identify().unwrap_err(),
            ParamError::OutOfRange {
                name: "k2",
                value: 1.6e4,
                min: 1e3,
                max: 1.6e4
            }
        );
        assert!(CatalogueData { k2: 1.59e4, ..c }.identify().is_ok());
    }

    /// A derived constant out of its model's range is named as the
    /// combination of catalogue fields it comes from: a soft catalogue
    /// (`K1 = 1`, `K2 = 1.5` N·m/rad, knees 1 and 2 N·m: `K_f0 = 0.9375`,
    /// `c_f = 2√(0.5/7.5)`, a largest torsion `π/(2 c_f K_f0) = 3.2` rad
    /// beyond 1 rad), and a starting torque of 1e-7 N·m (`c_w = 1e7`
    /// beyond 1e6).
    #[test]
    fn derived_constants_are_named_by_their_fields() {
        let soft = CatalogueData {
            k1: 1.0,
            k2: 1.5,
            t1: 1.0,
            t2: 2.0,
            ..CatalogueData::SHD_17_100
        };
        match soft.identify().unwrap_err() {
            ParamError::CombinationOutOfRange { name, value, .. } => {
                assert_eq!(name, "π/(2·c_f·k_f0) from k1, k2, t1, t2");
                let c_f = 2.0 * (0.5f64 / 7.5).sqrt();
                let want = core::f64::consts::PI / (2.0 * c_f * 0.9375);
                assert!((value - want).abs() <= 1e-12 * want, "{value} vs {want}");
            }
            other => panic!("{other:?}"),
        }
        let weak = CatalogueData {
            starting_torque: 1e-7,
            ..CatalogueData::SHD_17_100
        };
        match weak.identify().unwrap_err() {
            ParamError::CombinationOutOfRange { name, value, .. } => {
                assert_eq!(
                    name,
                    "c_w = 2/(ratio·k_w0·hysteresis_loss) = 1/starting_torque"
                );
                assert!((value - 1e7).abs() <= 1e-6, "{value}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn nonsense_inputs_are_rejected_by_name() {
        let ok = CatalogueData::SHD_17_100;
        let e = CatalogueData { k2: ok.k1, ..ok }.identify().unwrap_err();
        assert!(matches!(
            e,
            ParamError::NotIncreasing {
                lower: "k1",
                upper: "k2",
                ..
            }
        ));
        let e = CatalogueData { t2: 1.0, ..ok }.identify().unwrap_err();
        assert!(matches!(
            e,
            ParamError::NotIncreasing {
                lower: "t1",
                upper: "t2",
                ..
            }
        ));
        let e = CatalogueData {
            hysteresis_loss: 0.0,
            ..ok
        }
        .identify()
        .unwrap_err();
        assert!(matches!(
            e,
            ParamError::NotPositive {
                name: "hysteresis_loss",
                ..
            }
        ));
        let e = CatalogueData {
            starting_torque: f64::NAN,
            ..ok
        }
        .identify()
        .unwrap_err();
        assert!(matches!(
            e,
            ParamError::NotFinite {
                name: "starting_torque",
                ..
            }
        ));
        let e = CatalogueData { ratio: 0.5, ..ok }.identify().unwrap_err();
        assert!(matches!(e, ParamError::OutOfRange { name: "ratio", .. }));
        // K2/K1 = 300 > (15.9/3.9)² ≈ 16.6: too steep for eq. (2.24).
        let e = CatalogueData {
            k2: 300.0 * ok.k1,
            ..ok
        }
        .identify()
        .unwrap_err();
        assert!(matches!(e, ParamError::OutOfRange { name: "k2", .. }));
    }

    /// The scaled catalogue of the SHD-17-100's own row reproduces its
    /// catalogue; other sizes keep the shape, so `K_f0/K2` and `c_f·T_rated`
    /// are the same for every size (by eq. 2.33–2.34, `K_f0` is linear in
    /// the slopes and `c_f` scales as 1/torque).
    #[test]
    fn scaled_catalogues_keep_the_shd17_shape() {
        let base = CatalogueData::SHD_17_100;
        let same = CatalogueData::scaled_from_shd17(16.0, 9.4e3, 100.0).unwrap();
        for (a, b) in [
            (same.k1, base.k1),
            (same.t1, base.t1),
            (same.t2, base.t2),
            (same.starting_torque, base.starting_torque),
        ] {
            assert!((a - b).abs() <= 1e-12 * b, "{a} vs {b}");
        }
        let p0 = base.identify().unwrap().flexspline();
        for row in crate::harmonic_drive::kinematic_error::TABLE_3_1 {
            let c = CatalogueData::scaled_from_shd17(row.rated_torque, row.k2, row.ratio as f64)
                .unwrap();
            let p = c.identify().unwrap();
            let f = p.flexspline();
            assert!((f.k_f0() / row.k2 - p0.k_f0() / 9.4e3).abs() < 1e-12);
            assert!((f.c_f() * row.rated_torque - p0.c_f() * 16.0).abs() < 1e-12);
            // Eq. (2.35): K_w0 N Ψ / 2 is the starting torque.
            let w = p.wave_generator();
            assert!(
                (w.k_w0() * p.ratio() * c.hysteresis_loss / 2.0 - c.starting_torque).abs() < 1e-15
            );
        }
        assert!(matches!(
            CatalogueData::scaled_from_shd17(0.0, 9.4e3, 100.0),
            Err(ParamError::NotPositive {
                name: "rated_torque",
                ..
            })
        ));
        assert!(matches!(
            CatalogueData::scaled_from_shd17(16.0, f64::INFINITY, 100.0),
            Err(ParamError::NotFinite { name: "k2", .. })
        ));
        // A rated torque so small that c_f overflows: an error, not a model.
        assert!(CatalogueData::scaled_from_shd17(1e-310, 9.4e3, 1e10).is_err());
    }

    proptest! {
        /// Round trip: the identified model reproduces the catalogue slopes
        /// at the piece centres (eq. 2.31, 2.32) and the hysteresis half
        /// width Ψ/2 of eq. (2.36).
        #[test]
        fn identified_model_matches_its_defining_equations(
            k1 in 1e3f64..1e5, ratio_k in 1.01f64..3.0, t1 in 0.5f64..50.0, ratio_t in 1.2f64..5.0,
            psi in 1e-5f64..1e-3, tau_fs in 1e-3f64..0.1, n in 30.0f64..200.0,
        ) {
            let data = CatalogueData {
                k1, k2: k1 * ratio_k, t1, t2: t1 * ratio_t,
                hysteresis_loss: psi, starting_torque: tau_fs, ratio: n,
            };
            // Only admissible catalogues (K2/K1 below the limit) identify.
            let limit = ((data.t1 + data.t2) / data.t1).powi(2);
            prop_assume!(ratio_k < limit);
            let p = data.identify().unwrap();
            let f = p.flexspline();
            prop_assert!((f.local_stiffness(t1 / 2.0) - k1).abs() <= 1e-9 * k1);
            prop_assert!((f.local_stiffness((t1 + data.t2) / 2.0) - data.k2).abs() <= 1e-9 * data.k2);
            let w = p.wave_generator();
            prop_assert!((1.0 / (w.c_w() * n * w.k_w0()) - psi / 2.0).abs() <= 1e-12 * psi);
            // Eq. (2.35): slope of the WG torsion at zero torque.
            prop_assert!((w.k_w0() * n * psi / 2.0 - tau_fs).abs() <= 1e-12 * tau_fs);
        }
    }
}
