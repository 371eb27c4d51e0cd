//! Motor-encoder offset calibration and absolute motor position after
//! power-on (thesis §2.4, eq. 2.38–2.39).
//!
//! The motor carries an incremental encoder with one index per motor turn;
//! the link carries an absolute encoder. Over one link revolution the motor
//! passes `N` indexes (`N` = gear ratio, an integer here), one every
//! `P = 2π/N` of link angle. Calibration finds where, modulo `P`, the indexes
//! sit in link coordinates; after power-on the first index seen then pins the
//! incremental count to an absolute position.
//!
//! Angles are link-side radians. A motor position is expressed as its
//! *link equivalent* (the link angle the rigid drive would show); by
//! eq. (2.4) the motor angle is `θ_w = −N ·` that.

use crate::error::{finite, ParamError};
use core::f64::consts::TAU;

/// Index pitch in link radians, `2π/N`; validates `N ≥ 1`.
fn pitch(ratio: u32) -> Result<f64, ParamError> {
    if ratio == 0 {
        return Err(ParamError::NotPositive {
            name: "ratio",
            value: 0.0,
        });
    }
    Ok(TAU / ratio as f64)
}

/// Eq. (2.38): the offset of the motor indexes in link coordinates, in
/// `[0, 2π/N)`, from the link readings at every index met during one
/// clockwise (`cw`) and one counter-clockwise (`ccw`) link revolution.
///
/// The thesis averages `θ_cw_i + θ_ccw_i − 2 i·360/N` over the `N` indexes:
/// the two directions carry opposite torsion and backlash, so their mean is
/// the unloaded index position. As printed it fails when a reading wraps
/// through 0/360° or when the readings are not numbered from the index at
/// link angle 0. This implementation uses the circular mean of all `2N`
/// readings modulo the pitch `P` — identical to the printed formula when
/// nothing wraps, and independent of numbering and wrap-around.
///
/// Errors: `ratio = 0`; `cw` or `ccw` empty, of different lengths, or
/// containing a non-finite reading; readings so spread that their circular
/// mean is undefined (`name = "readings"`).
pub fn encoder_offset(cw: &[f64], ccw: &[f64], ratio: u32) -> Result<f64, ParamError> {
    let p = pitch(ratio)?;
    if cw.is_empty() || cw.len() != ccw.len() {
        return Err(ParamError::OutOfRange {
            name: "ccw.len()",
            value: ccw.len() as f64,
            min: cw.len().max(1) as f64,
            max: cw.len().max(1) as f64,
        });
    }
    let (mut s, mut c) = (0.0, 0.0);
    for &theta in cw.iter().chain(ccw) {
        let theta = finite("reading", theta)?;
        let phase = TAU * (theta / p);
        let (sp, cp) = libm::sincos(phase);
        s += sp;
        c += cp;
    }
    let n = (2 * cw.len()) as f64;
    if libm::hypot(s, c) <= 1e-9 * n {
        return Err(ParamError::NotRepresentable {
            name: "readings",
            value: libm::hypot(s, c) / n,
        });
    }
    let mean_phase = libm::atan2(s, c); // (-π, π]
    let offset = mean_phase / TAU * p;
    Ok(if offset < 0.0 { offset + p } else { offset })
}

/// Eq. (2.39): absolute motor position (link-equivalent rad) after power-on.
///
/// `link_at_first_index` is the link reading `θ_fo0` at the first index met
/// after power-on, `incremental_since_index` the incremental encoder's travel
/// since that index, in link-equivalent radians (`θ_IE`). The index met is
/// the one nearest to `θ_fo0`:
/// `θ = offset + P · round((θ_fo0 − offset)/P) + θ_IE`, with `round` to
/// nearest (`floor(x + ½)`). The printed `int(x + 0.5)` truncates toward zero
/// and is one index off for negative angles (errata E6).
pub fn absolute_motor_position(
    offset: f64,
    link_at_first_index: f64,
    incremental_since_index: f64,
    ratio: u32,
) -> Result<f64, ParamError> {
    let p = pitch(ratio)?;
    let offset = finite("offset", offset)?;
    let theta0 = finite("link_at_first_index", link_at_first_index)?;
    let inc = finite("incremental_since_index", incremental_since_index)?;
    let k = libm::floor((theta0 - offset) / p + 0.5);
    Ok(offset + p * k + inc)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The printed eq. (2.38), in radians, for readings numbered from the
    /// index nearest link angle 0 and not wrapping.
    fn printed_offset(cw: &[f64], ccw: &[f64]) -> f64 {
        let n = cw.len() as f64;
        let p = TAU / n;
        (0..cw.len())
            .map(|i| (cw[i] + ccw[i] - 2.0 * i as f64 * p) / (2.0 * n))
            .sum()
    }

    proptest! {
        /// Readings generated from a known offset, ± a direction-dependent
        /// lag and small noise: the offset is recovered, and it equals the
        /// printed formula when nothing wraps.
        #[test]
        fn recovers_offset_and_agrees_with_print_without_wrap(
            n in 20u32..160, frac in 0.05f64..0.95, lag in 0.0f64..0.2, noise in proptest::collection::vec(-0.01f64..0.01, 320),
        ) {
            let p = TAU / n as f64;
            let offset = frac * p;
            let cw: Vec<f64> = (0..n as usize).map(|i| offset + i as f64 * p + lag * p + noise[i] * p).collect();
            let ccw: Vec<f64> = (0..n as usize).map(|i| offset + i as f64 * p - lag * p + noise[160 + i] * p).collect();
            let got = encoder_offset(&cw, &ccw, n).unwrap();
            // Each cw/ccw pair of unit phasors sums to a vector at the mean
            // of their phases, offset + (n₁ + n₂)/2 (the lags cancel), so
            // every pair's resultant lies within ±0.01 p of the offset and so
            // does their sum's direction; 1e-3 p covers rounding.
            prop_assert!((got - offset).abs() <= 0.011 * p, "{got} vs {offset}");
            let printed = printed_offset(&cw, &ccw);
            prop_assert!((got - printed).abs() <= 1e-3 * p, "{got} vs printed {printed}");
        }

        /// Wrapping every reading into (−π, π] and shuffling the numbering
        /// does not change the result (the printed formula breaks here).
        #[test]
        fn independent_of_wrap_and_numbering(n in 20u32..160, frac in 0.0f64..1.0, shift in 0usize..160) {
            let p = TAU / n as f64;
            let offset = frac * p;
            let wrap = |x: f64| x - TAU * libm::floor((x + core::f64::consts::PI) / TAU);
            let cw: Vec<f64> = (0..n as usize).map(|i| wrap(offset + ((i + shift) % n as usize) as f64 * p)).collect();
            let ccw: Vec<f64> = cw.iter().rev().copied().collect();
            let got = encoder_offset(&cw, &ccw, n).unwrap();
            let d = (got - offset).rem_euclid(p);
            prop_assert!(d.min(p - d) <= 1e-9 * p);
        }

        /// Eq. (2.39) finds the true index for positive and negative link
        /// angles, as long as the link reading is within half a pitch.
        #[test]
        fn absolute_position_picks_the_true_index(
            n in 20u32..160, frac in 0.0f64..1.0, k in -500i64..500, err in -0.49f64..0.49, inc in -1.0f64..1.0,
        ) {
            let p = TAU / n as f64;
            let offset = frac * p;
            let true_index = offset + k as f64 * p;
            let got = absolute_motor_position(offset, true_index + err * p, inc, n).unwrap();
            prop_assert!((got - (true_index + inc)).abs() <= 1e-9 * (1.0 + true_index.abs()));
        }
    }

    /// The printed `int(x + 0.5)` truncates toward zero: for a link angle
    /// just below −½ pitch from the offset it picks index 0 instead of −1.
    #[test]
    fn printed_rounding_is_one_index_off_for_negative_angles() {
        let n = 100;
        let p = TAU / n as f64;
        let theta0 = -1.2 * p; // nearest index: −1 (at −p)
        let printed_index = ((theta0 / p) + 0.5) as i64; // int() truncation
        assert_eq!(printed_index, 0);
        let got = absolute_motor_position(0.0, theta0, 0.0, n).unwrap();
        assert!((got + p).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_named() {
        assert!(matches!(
            encoder_offset(&[0.1], &[0.1], 0),
            Err(ParamError::NotPositive { name: "ratio", .. })
        ));
        assert!(matches!(
            encoder_offset(&[0.1, 0.2], &[0.1], 2),
            Err(ParamError::OutOfRange {
                name: "ccw.len()",
                ..
            })
        ));
        assert!(matches!(
            encoder_offset(&[], &[], 2),
            Err(ParamError::OutOfRange { .. })
        ));
        assert!(matches!(
            encoder_offset(&[f64::NAN], &[0.0], 1),
            Err(ParamError::NotFinite {
                name: "reading",
                ..
            })
        ));
        // Two readings half a pitch apart have no circular mean.
        assert!(matches!(
            encoder_offset(&[0.0], &[core::f64::consts::PI], 1),
            Err(ParamError::NotRepresentable { .. })
        ));
        assert!(matches!(
            absolute_motor_position(f64::INFINITY, 0.0, 0.0, 100),
            Err(ParamError::NotFinite { name: "offset", .. })
        ));
    }
}
