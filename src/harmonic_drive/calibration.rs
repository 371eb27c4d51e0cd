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
/// `cw[i]` and `ccw[i]` must be the link readings (rad) at the *same* motor
/// index, as in the printed sum, which pairs `θ_cw_i` with `θ_ccw_i`: store
/// one of the two runs in reverse order of encounter. The first pair may be
/// any index (the numbering need not start at link angle 0) and the readings
/// may wrap through 0/2π anywhere.
///
/// The thesis averages `θ_cw_i + θ_ccw_i − 2 i·360/N` over the `N` indexes:
/// the two directions carry opposite torsion and backlash (the *lag*), so
/// the midpoint of a pair is the unloaded index position. As printed it
/// fails when a reading wraps through 0/360° or when the readings are not
/// numbered from the index nearest link angle 0 (errata E2.7). This
/// implementation
/// 1. takes the midpoint `m_i` of each pair along the shorter arc,
///    `m_i = ccw_i + wrap(cw_i − ccw_i)/2` with `wrap` into `(−π, π]`,
///    and requires `|wrap(cw_i − ccw_i)| < P` (the lag below half a pitch
///    `P = 2π/N`; at or beyond it a pair is indistinguishable from one
///    whose midpoint is half a pitch away);
/// 2. takes the circular mean `m̄` of the `m_i` modulo `P` as a reference;
/// 3. returns `m̄` plus the arithmetic mean of the deviations
///    `m_i − m̄`, each reduced into `[−P/2, P/2)`, reduced into `[0, P)`.
///
/// Step 3 makes the result the least-squares offset of the midpoints
/// (the minimiser of `Σ d(m_i, x)²` with `d` the distance modulo `P`, for
/// scatter well below a pitch) and, when no reading wraps and the numbering
/// starts at link angle 0, equal to the printed formula up to rounding
/// (≈ 1e-16 rad), where a circular mean alone would differ from it on
/// scattered readings. Neither form depends on the sign of the lag.
///
/// Errors: `ratio = 0`; `cw` or `ccw` empty, of different lengths
/// (`name = "ccw.len()"`), or containing a non-finite reading
/// ([`ParamError::ElementOutOfRange`] named `"cw"` or `"ccw"` with the
/// reading's index); a pair at least a pitch apart
/// (`ElementOutOfRange { name: "cw[i] - ccw[i] (wrapped)", index: i, min:
/// −P, max: P }`, the value being the wrapped difference); midpoints so spread that their circular
/// mean is undefined (`NotRepresentable { name: "readings" }`).
pub fn encoder_offset(cw: &[f64], ccw: &[f64], ratio: u32) -> Result<f64, ParamError> {
    use core::f64::consts::PI;
    let p = pitch(ratio)?;
    if cw.is_empty() || cw.len() != ccw.len() {
        return Err(ParamError::OutOfRange {
            name: "ccw.len()",
            value: ccw.len() as f64,
            min: cw.len().max(1) as f64,
            max: cw.len().max(1) as f64,
        });
    }
    // Into [-h, h) for a half-width h.
    let wrap = |x: f64, h: f64| x - 2.0 * h * libm::floor((x + h) / (2.0 * h));
    // Pass 1: validate, and the circular mean of the midpoints modulo P.
    let (mut s, mut c) = (0.0, 0.0);
    for (i, (&a, &b)) in cw.iter().zip(ccw).enumerate() {
        let a = reading("cw", i, a)?;
        let b = reading("ccw", i, b)?;
        let d = wrap(a - b, PI);
        if d.abs() >= p {
            return Err(ParamError::ElementOutOfRange {
                name: "cw[i] - ccw[i] (wrapped)",
                index: i,
                value: d,
                min: -p,
                max: p,
            });
        }
        let phase = TAU * ((b + 0.5 * d) / p);
        let (sp, cp) = libm::sincos(phase);
        s += sp;
        c += cp;
    }
    let n = cw.len() as f64;
    let resultant = libm::hypot(s, c);
    if resultant <= 1e-9 * n {
        return Err(ParamError::NotRepresentable {
            name: "readings",
            value: resultant / n,
        });
    }
    let reference = libm::atan2(s, c) / TAU * p; // (−P/2, P/2]
                                                 // Pass 2: the arithmetic mean of the deviations from the reference.
    let mut sum = 0.0;
    for (&a, &b) in cw.iter().zip(ccw) {
        let m = b + 0.5 * wrap(a - b, PI);
        sum += wrap(m - reference, 0.5 * p);
    }
    let offset = wrap(reference + sum / n, 0.5 * p);
    let offset = if offset < 0.0 { offset + p } else { offset };
    // `offset + p` rounds to `p` for offsets within an ulp below zero.
    Ok(if offset >= p { 0.0 } else { offset })
}

/// Eq. (2.39): absolute motor position (link-equivalent rad) after power-on.
///
/// `link_at_first_index` is the link reading `θ_fo0` at the first index met
/// after power-on, `incremental_since_index` the incremental encoder's travel
/// since that index, in link-equivalent radians (`θ_IE`). The index met is
/// the one nearest to `θ_fo0`:
/// `θ = offset + P · round((θ_fo0 − offset)/P) + θ_IE`, with `round` to
/// nearest (`floor(x + ½)`). The printed `int(x + 0.5)` truncates toward zero
/// and is one index off for negative angles (errata E2.6).
///
/// Errors: `ratio = 0`; an argument that is not finite (named by the
/// argument); finite arguments whose result overflows (e.g. `offset =
/// 1e308`, `link_at_first_index = −1e308`):
/// [`ParamError::ResultNotFinite`].
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
    let theta = offset + p * k + inc;
    if !theta.is_finite() {
        return Err(ParamError::ResultNotFinite {
            name: "offset + P·round((link_at_first_index − offset)/P) + incremental_since_index",
            value: theta,
        });
    }
    Ok(theta)
}

/// Reading `i` of the run `name`: finite, or the error naming it.
fn reading(name: &'static str, i: usize, value: f64) -> Result<f64, ParamError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ParamError::ElementOutOfRange {
            name,
            index: i,
            value,
            min: f64::MIN,
            max: f64::MAX,
        })
    }
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

    /// Wraps into `(−π, π]`, as a link encoder reporting signed angles does.
    fn signed(x: f64) -> f64 {
        let y = x - TAU * libm::floor((x + core::f64::consts::PI) / TAU);
        if y == -core::f64::consts::PI {
            core::f64::consts::PI
        } else {
            y
        }
    }

    /// Readings of a drive whose indexes sit at `offset + k P`: the cw run
    /// reads `lag` (in pitches) ahead, the ccw run `lag` behind, plus the
    /// given noise (in pitches); numbered from index `first`, each reading
    /// reported in `(−π, π]`.
    fn readings(
        n: u32,
        offset: f64,
        lag: f64,
        first: usize,
        noise: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let p = TAU / n as f64;
        let idx = |i: usize| ((i + first) % n as usize) as f64;
        let cw = (0..n as usize)
            .map(|i| signed(offset + idx(i) * p + (lag + noise[i]) * p))
            .collect();
        let ccw = (0..n as usize)
            .map(|i| signed(offset + idx(i) * p - (lag - noise[n as usize + i]) * p))
            .collect();
        (cw, ccw)
    }

    /// An independent least-squares criterion: for a trial offset `x`, each
    /// pair is charged the squared sum of its two residuals against the
    /// index `x + kP` that fits it best, `k` searched over all `N` indexes
    /// and residuals taken on the circle (no midpoint formula involved).
    fn brute_force_cost(cw: &[f64], ccw: &[f64], x: f64) -> f64 {
        let n = cw.len();
        let p = TAU / n as f64;
        cw.iter()
            .zip(ccw)
            .map(|(&a, &b)| {
                (0..n)
                    .map(|k| {
                        let index = x + k as f64 * p;
                        let r = signed(a - index) + signed(b - index);
                        r * r
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .sum()
    }

    /// The issue as reported: a lag of 0.26 pitch. Averaging all readings
    /// on the pitch circle (the former implementation) puts the offset half
    /// a pitch away, at 0.8 P; pairing the runs gives 0.3 P, as the printed
    /// formula does.
    #[test]
    fn lag_beyond_a_quarter_pitch_keeps_the_offset() {
        let n = 100;
        let p = TAU / n as f64;
        let (cw, ccw) = readings(n, 0.3 * p, 0.26, 0, &[0.0; 200]);
        let (s, c) = cw.iter().chain(&ccw).fold((0.0, 0.0), |(s, c), &t| {
            let (sp, cp) = libm::sincos(TAU * t / p);
            (s + sp, c + cp)
        });
        let unpaired = (libm::atan2(s, c) / TAU).rem_euclid(1.0);
        assert!((unpaired - 0.8).abs() < 1e-9, "unpaired mean {unpaired}");
        let got = encoder_offset(&cw, &ccw, n).unwrap() / p;
        assert!((got - 0.3).abs() < 1e-12, "{got}");
        // The printed sum (no reading wraps for this offset in [0, 2π)).
        let unsigned = |v: &[f64]| -> Vec<f64> { v.iter().map(|&t| t.rem_euclid(TAU)).collect() };
        let printed = printed_offset(&unsigned(&cw), &unsigned(&ccw)) / p;
        assert!((printed - 0.3).abs() < 1e-12, "{printed}");
    }

    /// Every lag strictly below half a pitch, both signs, in steps of
    /// 0.001 P: the offset is recovered exactly (noise-free readings).
    #[test]
    fn every_lag_below_half_a_pitch() {
        let n = 100;
        let p = TAU / n as f64;
        for step in -499..=499 {
            let lag = step as f64 * 1e-3;
            for &frac in &[0.0, 0.3, 0.74, 0.999] {
                let (cw, ccw) = readings(n, frac * p, lag, 17, &[0.0; 200]);
                let got = encoder_offset(&cw, &ccw, n).unwrap();
                let d = (got - frac * p).rem_euclid(p);
                assert!(
                    d.min(p - d) < 1e-12,
                    "lag {lag}, offset {frac}: {}",
                    got / p
                );
            }
        }
    }

    /// At or beyond half a pitch a pair cannot be told from one with the
    /// opposite lag around the index half a pitch away: rejected, naming
    /// the pair's wrapped difference.
    #[test]
    fn lag_of_half_a_pitch_is_rejected() {
        let n = 100;
        let p = TAU / n as f64;
        for lag in [0.5, 0.6, -0.5, -0.7] {
            let (cw, ccw) = readings(n, 0.3 * p, lag, 0, &[0.0; 200]);
            match encoder_offset(&cw, &ccw, n) {
                Err(ParamError::ElementOutOfRange {
                    name: "cw[i] - ccw[i] (wrapped)",
                    index: 0,
                    value,
                    min,
                    max,
                }) => {
                    assert!((value.abs() - 2.0 * lag.abs() * p).abs() < 1e-9);
                    assert_eq!((min, max), (-p, p));
                }
                other => panic!("lag {lag}: {other:?}"),
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// Noisy readings over the whole lag range, any numbering, wrapped
        /// into (−π, π]: the result is within the noise of the true offset
        /// and minimises the brute-force criterion over a grid of 4000
        /// trial offsets (to the grid's resolution).
        #[test]
        fn minimises_the_circular_residual_over_the_lag_range(
            n in 2u32..40, frac in 0.0f64..1.0, lag in -0.49f64..0.49, first in 0usize..40,
            noise in proptest::collection::vec(-0.002f64..0.002, 80),
        ) {
            let p = TAU / n as f64;
            let (cw, ccw) = readings(n, frac * p, lag, first, &noise);
            let got = encoder_offset(&cw, &ccw, n).unwrap();
            prop_assert!((0.0..p).contains(&got));
            // Each midpoint lies within ±0.002 P of the truth, so does
            // their mean.
            let d = (got - frac * p).rem_euclid(p);
            prop_assert!(d.min(p - d) <= 0.0021 * p, "{} vs {frac}", got / p);
            let at_got = brute_force_cost(&cw, &ccw, got);
            let grid = (0..4000)
                .map(|j| brute_force_cost(&cw, &ccw, j as f64 * p / 4000.0))
                .fold(f64::INFINITY, f64::min);
            prop_assert!(at_got <= grid * (1.0 + 1e-9) + 1e-24, "{at_got} > {grid}");
            // And no trial offset half a grid step away does better: `got`
            // is the minimiser, not merely close to the grid's best.
            for dx in [-0.5e-4 * p, 0.5e-4 * p, -1e-7 * p, 1e-7 * p] {
                prop_assert!(at_got <= brute_force_cost(&cw, &ccw, got + dx) * (1.0 + 1e-9) + 1e-24);
            }
        }

        /// Midpoints spread over ±0.1 P (far more than encoder noise): the
        /// deviations are averaged around a reference that must sit within
        /// a few tenths of a pitch of their mean, or some of them wrap to
        /// the wrong side. The result still minimises the brute-force
        /// criterion (each deviation is below half a pitch, so the
        /// criterion's minimiser is their mean).
        #[test]
        fn spread_midpoints_give_the_least_squares_offset(
            n in 2u32..40, frac in 0.0f64..1.0, lag in -0.3f64..0.3, first in 0usize..40,
            noise in proptest::collection::vec(-0.1f64..0.1, 80),
        ) {
            let p = TAU / n as f64;
            let (cw, ccw) = readings(n, frac * p, lag, first, &noise);
            let got = encoder_offset(&cw, &ccw, n).unwrap();
            prop_assert!((0.0..p).contains(&got));
            // The mean of the midpoints' deviations, from the readings'
            // construction: (noise_i + noise_{n+i})/2 pitches each.
            let k = n as usize;
            let mean = (0..k).map(|i| 0.5 * (noise[i] + noise[k + i])).sum::<f64>() / k as f64;
            let d = (got - (frac + mean) * p).rem_euclid(p);
            prop_assert!(d.min(p - d) <= 1e-9 * p, "{} vs {}", got / p, frac + mean);
            let at_got = brute_force_cost(&cw, &ccw, got);
            for dx in [-1e-3 * p, 1e-3 * p, -1e-6 * p, 1e-6 * p] {
                prop_assert!(at_got <= brute_force_cost(&cw, &ccw, got + dx) * (1.0 + 1e-9) + 1e-24);
            }
        }

        /// Where nothing wraps (readings in [0, 2π), numbered from the index
        /// nearest 0) the result equals the printed eq. (2.38) to rounding,
        /// for noisy readings too.
        #[test]
        fn equals_the_printed_formula_without_wrap(
            n in 20u32..160, frac in 0.05f64..0.95, lag in -0.45f64..0.45,
            noise in proptest::collection::vec(-0.01f64..0.01, 320),
        ) {
            let p = TAU / n as f64;
            let margin = 0.02 + lag.abs();
            prop_assume!(frac - margin > 0.0 && frac + margin < 1.0);
            let (cw, ccw) = readings(n, frac * p, lag, 0, &noise);
            let unsigned = |v: &[f64]| -> Vec<f64> { v.iter().map(|&t| t.rem_euclid(TAU)).collect() };
            let (cw, ccw) = (unsigned(&cw), unsigned(&ccw));
            let got = encoder_offset(&cw, &ccw, n).unwrap();
            let printed = printed_offset(&cw, &ccw);
            prop_assert!((got - printed).abs() <= 1e-12 * p, "{got} vs printed {printed}");
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

    /// Midpoints at `offset + {−0.3, 0, +0.3} P` (a symmetric spread, so
    /// the least-squares offset is `offset` itself): the reference the
    /// deviations are taken from must be the circular mean; a reference a
    /// quarter pitch off wraps the outer deviation to the other side.
    #[test]
    fn widely_spread_midpoints_keep_their_mean() {
        let n = 50;
        let p = TAU / n as f64;
        for frac in [0.1, 0.25, 0.5, 0.6, 0.75, 0.95] {
            let mids = [frac - 0.3, frac, frac + 0.3];
            let cw: Vec<f64> = mids.iter().map(|m| signed((m + 0.1) * p)).collect();
            let ccw: Vec<f64> = mids.iter().map(|m| signed((m - 0.1) * p)).collect();
            let got = encoder_offset(&cw, &ccw, n).unwrap() / p;
            let d = (got - frac).rem_euclid(1.0);
            assert!(d.min(1.0 - d) < 1e-9, "offset {frac}: {got}");
        }
    }

    /// The circular mean is undefined when the mean resultant length of
    /// the midpoints' phases is at most 1e-9: two midpoints half a pitch
    /// (phase π) apart, moved by a phase `ε`, have a resultant of about
    /// `ε` over two readings; rejected at `ε = 1.5e-9`, accepted at `3e-9`,
    /// and the error reports that length.
    #[test]
    fn undefined_circular_mean_at_its_threshold() {
        let pi = core::f64::consts::PI;
        match encoder_offset(&[0.0, pi + 1.5e-9], &[0.0, pi + 1.5e-9], 1) {
            Err(ParamError::NotRepresentable {
                name: "readings",
                value,
            }) => {
                let (s, c) = (libm::sin(pi + 1.5e-9), 1.0 + libm::cos(pi + 1.5e-9));
                let want = libm::hypot(s, c) / 2.0;
                assert!((value - want).abs() <= 1e-6 * want, "{value} vs {want}");
            }
            other => panic!("{other:?}"),
        }
        assert!(encoder_offset(&[0.0, pi + 3e-9], &[0.0, pi + 3e-9], 1).is_ok());
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
            Err(ParamError::ElementOutOfRange {
                name: "cw",
                index: 0,
                ..
            })
        ));
        assert!(matches!(
            encoder_offset(&[0.0, 0.1], &[0.0, f64::INFINITY], 1),
            Err(ParamError::ElementOutOfRange {
                name: "ccw",
                index: 1,
                ..
            })
        ));
        // Two pairs whose midpoints lie half a pitch apart have no circular
        // mean.
        let pi = core::f64::consts::PI;
        assert!(matches!(
            encoder_offset(&[0.0, pi], &[0.0, pi], 1),
            Err(ParamError::NotRepresentable { .. })
        ));
        assert!(matches!(
            absolute_motor_position(f64::INFINITY, 0.0, 0.0, 100),
            Err(ParamError::NotFinite { name: "offset", .. })
        ));
    }
}
