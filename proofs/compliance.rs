//! Properties of the flexspline compliance and its inverse (thesis eq. 2.26
//! and 3.10) as configured for a backend: the map the torque estimator
//! inverts on every sample.
//!
//! | property | I16F16 | f32 |
//! |---|---|---|
//! | `inverse_sign_and_saturation` — never a value from the wrong branch of `tan`: the torque has the sign of the torsion; `saturated` exactly outside the branch (to the angle's rounding); never NaN | Kani; exhaustive (all 2³² torsions) | Kani; exhaustive (all 2³² bit patterns) |
//! | `inverse_monotone_step`, `forward_monotone_step` — both maps non-decreasing | same | same |
//! | `round_trip` — `torsion(torque(δ))` within the derived bound of δ wherever the torque is not saturated | exhaustive | exhaustive |
//!
//! The configuration is the SHD-17-100 drive identified from its catalogue
//! (eq. 2.33–2.34).

use super::engine::Verdict;
use crate::harmonic_drive::{CatalogueData, FlexsplineConfig, FlexsplineParams, FlexsplineTorque};
use crate::scalar::{Scalar, I16F16};

/// The drive the properties are stated for.
pub fn shd17() -> FlexsplineParams {
    // The catalogue constants are valid (tested); the error is unreachable.
    match CatalogueData::SHD_17_100.identify() {
        Ok(p) => p.flexspline(),
        Err(e) => panic!("SHD-17-100 catalogue data rejected: {e}"),
    }
}

/// Sign and saturation of the inverse at torsion `d` (stored units).
pub fn inverse_sign_and_saturation<S: Scalar>(
    cfg: &FlexsplineConfig<S>,
    p: &FlexsplineParams,
    d: S,
) -> Verdict {
    sign_and_saturation_of(p, d, cfg.torque(d))
}

/// The check behind [`inverse_sign_and_saturation`] for a computed `r`.
pub fn sign_and_saturation_of<S: Scalar>(
    p: &FlexsplineParams,
    d: S,
    r: FlexsplineTorque<S>,
) -> Verdict {
    let no_nan = !r.torque.is_nan();
    let sign_ok = if d > S::ZERO {
        r.torque >= S::ZERO
    } else if d < S::ZERO {
        r.torque <= S::ZERO
    } else {
        r.torque == S::ZERO || d.is_nan()
    };
    // The flag is computed from the rounded angle: exact angle within one
    // resolution step (relative for floats) of π/2 may go either way.
    let angle = d.to_f64() * (p.c_f() * p.k_f0()) / S::UNITS.torsion;
    let slack = S::RESOLUTION.to_f64() * (1.0 + angle.abs());
    let half_pi = core::f64::consts::FRAC_PI_2;
    let flag_ok = d.is_nan()
        || (angle.abs() >= half_pi + slack && r.saturated)
        || (angle.abs() < half_pi - slack && !r.saturated)
        || (angle.abs() - half_pi).abs() <= slack;
    Verdict::logical(no_nan && sign_ok && flag_ok)
}

/// The torsions (stored `I16F16` bits) where [`sign_and_saturation_of`]
/// pins the `saturated` flag, computed once in `f64` from the parameters
/// (outside the solver: under Kani these are constants), so the check on a
/// symbolic torsion is two integer comparisons.
///
/// With `q = 2⁻¹⁶` and the angle `θ = Δθ_f c_f K_f0`, the flag must be clear
/// where `|θ| < π/2 − q(1 + |θ|)`, i.e. `|θ| < (π/2 − q)/(1 + q)`, and set
/// where `|θ| ≥ π/2 + q(1 + |θ|)`, i.e. `|θ| ≥ (π/2 + q)/(1 − q)`; in
/// stored bits (`2¹⁶` per stored unit) each edge is moved inward by a
/// margin of `10⁻⁶` bit for the `f64` rounding of this computation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SaturationEdges {
    /// `|D| ≤ clear_up_to` ⟹ the flag must be clear.
    pub clear_up_to: i64,
    /// `|D| ≥ set_from` ⟹ the flag must be set.
    pub set_from: i64,
}

impl SaturationEdges {
    /// The edges for the `I16F16` torsion of `p`.
    pub fn i16f16(p: &FlexsplineParams) -> Self {
        let q = I16F16::RESOLUTION.to_f64();
        let half_pi = core::f64::consts::FRAC_PI_2;
        let bits_per_rad = I16F16::UNITS.torsion / (p.c_f() * p.k_f0()) * 65536.0;
        let lo = (half_pi - q) / (1.0 + q) * bits_per_rad;
        let hi = (half_pi + q) / (1.0 - q) * bits_per_rad;
        SaturationEdges {
            clear_up_to: libm::floor(lo - 1e-6) as i64,
            set_from: libm::ceil(hi + 1e-6) as i64,
        }
    }
}

/// [`inverse_sign_and_saturation`] on `I16F16`, decided on integers (no
/// `f64` of the symbolic torsion): the torque has the sign of the torsion
/// (zero at zero), and the flag is clear up to and set from the
/// [`SaturationEdges`]. Implies [`sign_and_saturation_of`] (fixed point is
/// never NaN).
pub fn inverse_sign_and_saturation_i16f16(
    cfg: &FlexsplineConfig<I16F16>,
    edges: &SaturationEdges,
    d: I16F16,
) -> Verdict {
    sign_and_saturation_bits(edges, d, cfg.torque(d))
}

/// The check behind [`inverse_sign_and_saturation_i16f16`] for a computed
/// `r`.
pub fn sign_and_saturation_bits(
    edges: &SaturationEdges,
    d: I16F16,
    r: FlexsplineTorque<I16F16>,
) -> Verdict {
    let (d, t) = (d.to_bits(), r.torque.to_bits());
    let sign_ok = (d > 0 && t >= 0) || (d < 0 && t <= 0) || (d == 0 && t == 0);
    let mag = (d as i64).abs();
    let flag_ok = (mag <= edges.clear_up_to && !r.saturated)
        || (mag >= edges.set_from && r.saturated)
        || (mag > edges.clear_up_to && mag < edges.set_from);
    Verdict::logical(sign_ok && flag_ok)
}

/// Monotone inverse: `torque(d) ≤ torque(d_next)` for `d < d_next`.
pub fn inverse_monotone_step<S: Scalar>(cfg: &FlexsplineConfig<S>, d: S, d_next: S) -> Verdict {
    Verdict::logical(
        d.is_nan()
            || d_next.is_nan()
            || d >= d_next
            || cfg.torque(d).torque <= cfg.torque(d_next).torque,
    )
}

/// Monotone forward map: `torsion(t) ≤ torsion(t_next)` for `t < t_next`.
pub fn forward_monotone_step<S: Scalar>(cfg: &FlexsplineConfig<S>, t: S, t_next: S) -> Verdict {
    Verdict::logical(
        t.is_nan() || t_next.is_nan() || t >= t_next || cfg.torsion(t) <= cfg.torsion(t_next),
    )
}

/// Round trip `torsion(torque(d))` against `d`, where the torque is neither
/// flagged nor clipped at the backend's range. The error is reported in
/// units of the derived bound (so `≤ 1` holds).
///
/// The bound, derived in the backend's arithmetic (see the module docs of
/// `FlexsplineConfig`): with `θ = d·c_f K_f0` the `tan` argument,
/// `t = tan θ`, `g = 1/(c_f K_f0)` in stored units and `q` the resolution
/// (`2⁻¹⁶` for I16F16; for f32, `2⁻²³·|x|` of each value `x`):
///
/// * fixed: `g·[(½q + |θ|2⁻³⁰) + (|t|2⁻²⁵ + (1.5 + ½c_f)q)/(1 + m²) + 2q] + |d|2⁻³⁰ + ½q`,
///   `m = |t| − (|t|2⁻²⁵ + (1.5 + ½c_f)q)` (`m ≥ 0`): the rounded
///   angle, the tan kernel (≤ 1 LSB + 2⁻²⁶|t|), the rounded torque and
///   argument of `atan` and the quantized coefficients (each 2⁻³⁰
///   relative), `atan` (≤ 2 LSB), the final rounding;
/// * f32: `10·2⁻²³·|d| + 4·2⁻¹²⁶`: angle (2 ulp-relative terms), tan (3 ulp),
///   torque and `atan` argument (1 each), their product's deviation from 1
///   (1), `atan` (2 ulp), final product (1): 9 relative units on `|θ|`
///   because `|t|/(1+t²) ≤ |θ|`, and one more on the last rounding.
pub fn round_trip<S: Scalar>(cfg: &FlexsplineConfig<S>, p: &FlexsplineParams, d: S) -> Verdict {
    round_trip_of(cfg, p, d, cfg.torque(d))
}

/// The check behind [`round_trip`] for a computed inverse `r`.
pub fn round_trip_of<S: Scalar>(
    cfg: &FlexsplineConfig<S>,
    p: &FlexsplineParams,
    d: S,
    r: FlexsplineTorque<S>,
) -> Verdict {
    if d.is_nan() || r.saturated || r.torque.abs() >= S::MAX {
        return Verdict::logical(true);
    }
    let back = cfg.torsion(r.torque).to_f64();
    let df = d.to_f64();
    let g = S::UNITS.torsion / (p.c_f() * p.k_f0());
    let theta = df / g;
    let bound = if S::RESOLUTION.to_f64() < 1e-6 {
        // f32 and f64: relative.
        let u = S::RESOLUTION.to_f64(); // 2^-23 for f32
        10.0 * u * df.abs() + 4.0 * f64::from(f32::MIN_POSITIVE)
    } else {
        let q = S::RESOLUTION.to_f64();
        // |tan θ| from the computed torque: t̂ = |T|·c_f within the tan
        // kernel's bound (1 LSB + 2⁻²⁶|t|) and the roundings (½ LSB + 2⁻³⁰),
        // so t ≤ (t̂ + 2q)(1 + 2⁻²⁵) bounds it from above.
        let t_hat = r.torque.to_f64().abs() * p.c_f() / S::UNITS.link_torque;
        let t = (t_hat + 2.0 * q) * (1.0 + 2f64.powi(-25));
        let e_u = t * 2f64.powi(-25) + (1.5 + 0.5 * p.c_f()) * q;
        let m = (t_hat - 2.0 * q - e_u).max(0.0);
        g * ((0.5 * q + theta.abs() * 2f64.powi(-30)) + e_u / (1.0 + m * m) + 2.0 * q)
            + df.abs() * 2f64.powi(-30)
            + 0.5 * q
    };
    Verdict::bounded((back - df).abs() / bound, 1.0)
}

/// [`shd17`] as constants: the identified parameters written out bit for
/// bit, so a Kani harness starts from a prepared configuration instead of
/// running the catalogue identification inside the solver (the test
/// `shd17_constants_match_identification` keeps the two equal).
pub const SHD17: FlexsplineParams = FlexsplineParams::prevalidated(
    f64::from_bits(SHD17_K_F0_BITS),
    f64::from_bits(SHD17_C_F_BITS),
);
const SHD17_K_F0_BITS: u64 = 0x40c0_47fe_0f83_e0f9;
const SHD17_C_F_BITS: u64 = 0x3fa7_024f_af76_0983;

#[cfg(kani)]
mod kani_entries {
    //! The configuration is [`SHD17`] quantized by the library's own
    //! constructor (concrete values, folded by the solver's front end); the
    //! torsion is `kani::any()` over every `I16F16` or `f32` value.
    //!
    //! The `I16F16` harnesses replace the `tan` and `atan` kernels by their
    //! contract (`kernel_as_contract`): a value with the sign of the
    //! argument (zero at zero), and, for a second call, ordered like the
    //! arguments (non-decreasing). Both facts are proven for the real
    //! kernels at all 2³² inputs by `exhaustive_tan_i16f16` and
    //! `exhaustive_atan_i16f16` (monotone and odd at every input; odd gives
    //! `f(0) = 0`, and with monotone the sign), and monotonicity also by
    //! `kani_tan_monotone_pair_i16f16` / `kani_atan_monotone_pair_i16f16`.
    //! The harnesses then decide the rest of eq. (3.10) and its inverse —
    //! the quantized coefficients, the rounding products, the saturation
    //! flag — bit-precisely; the kernels' accuracy (1 LSB) is the
    //! exhaustive engine's.
    use super::*;
    use core::sync::atomic::Ordering::Relaxed;
    use core::sync::atomic::{AtomicBool, AtomicI32, AtomicUsize};

    /// The argument and result of a kernel's first call in a harness.
    struct FirstCall {
        seen: AtomicBool,
        x: AtomicI32,
        y: AtomicI32,
    }

    impl FirstCall {
        const fn new() -> Self {
            FirstCall {
                seen: AtomicBool::new(false),
                x: AtomicI32::new(0),
                y: AtomicI32::new(0),
            }
        }
    }

    /// A value the contract of an odd, non-decreasing kernel allows at `x`.
    fn kernel_as_contract(first: &FirstCall, x: I16F16) -> I16F16 {
        let (x, y) = (x.to_bits(), kani::any::<i32>());
        // Postcondition of the stubbed kernel (sign of the argument).
        kani::assume(if x > 0 {
            y >= 0
        } else if x < 0 {
            y <= 0
        } else {
            y == 0
        });
        if first.seen.load(Relaxed) {
            let (x0, y0) = (first.x.load(Relaxed), first.y.load(Relaxed));
            // Postcondition relating two calls (a function, non-decreasing).
            kani::assume((x != x0 || y == y0) && (x <= x0 || y >= y0) && (x >= x0 || y <= y0));
        } else {
            first.seen.store(true, Relaxed);
            first.x.store(x, Relaxed);
            first.y.store(y, Relaxed);
        }
        I16F16::from_bits(y)
    }

    /// Up to two coefficients' first products, keyed by the coefficient's
    /// address (each harness uses one configuration).
    static COEF_KEY: [AtomicUsize; 2] = [AtomicUsize::new(0), AtomicUsize::new(0)];
    static COEF_CALL: [FirstCall; 2] = [FirstCall::new(), FirstCall::new()];

    /// `mul_coef` by a positive coefficient as its contract: the sign of
    /// `x` (zero at zero), and non-decreasing between two products by the
    /// same coefficient. Proven for the real product by the four
    /// coefficients of the configuration at all 2³² inputs
    /// (`exhaustive_coefficient_products_monotone_i16f16`).
    fn scale_i32_as_contract(c: &crate::scalar::Coef, x: i32) -> i32 {
        let key = c as *const crate::scalar::Coef as usize;
        let slot = if COEF_KEY[0].load(Relaxed) == key || COEF_KEY[0].load(Relaxed) == 0 {
            0
        } else {
            // Precondition of the stub: at most two coefficients.
            assert!(COEF_KEY[1].load(Relaxed) == key || COEF_KEY[1].load(Relaxed) == 0);
            1
        };
        COEF_KEY[slot].store(key, Relaxed);
        kernel_as_contract(&COEF_CALL[slot], I16F16::from_bits(x)).to_bits()
    }

    static TAN_CALL: FirstCall = FirstCall::new();
    static ATAN_CALL: FirstCall = FirstCall::new();

    fn tan_as_contract(x: I16F16) -> I16F16 {
        kernel_as_contract(&TAN_CALL, x)
    }

    fn atan_as_contract(x: I16F16) -> I16F16 {
        kernel_as_contract(&ATAN_CALL, x)
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::tan, tan_as_contract)]
    fn kani_inverse_sign_and_saturation_i16f16() {
        let cfg = FlexsplineConfig::<I16F16>::new(&SHD17);
        let edges = SaturationEdges::i16f16(&SHD17);
        let d = I16F16::from_bits(kani::any());
        assert!(inverse_sign_and_saturation_i16f16(&cfg, &edges, d).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::tan, tan_as_contract)]
    #[kani::stub(crate::scalar::Coef::scale_i32, scale_i32_as_contract)]
    fn kani_inverse_monotone_i16f16() {
        let cfg = FlexsplineConfig::<I16F16>::new(&SHD17);
        let b: i32 = kani::any();
        // Precondition: the successor exists.
        kani::assume(b < i32::MAX);
        assert!(inverse_monotone_step(&cfg, I16F16::from_bits(b), I16F16::from_bits(b + 1)).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::atan, atan_as_contract)]
    #[kani::stub(crate::scalar::Coef::scale_i32, scale_i32_as_contract)]
    fn kani_forward_monotone_i16f16() {
        let cfg = FlexsplineConfig::<I16F16>::new(&SHD17);
        let b: i32 = kani::any();
        // Precondition: the successor exists.
        kani::assume(b < i32::MAX);
        assert!(forward_monotone_step(&cfg, I16F16::from_bits(b), I16F16::from_bits(b + 1)).holds);
    }

    #[kani::proof]
    fn kani_inverse_sign_and_saturation_f32() {
        let cfg = FlexsplineConfig::<f32>::new(&SHD17);
        assert!(inverse_sign_and_saturation(&cfg, &SHD17, kani::any::<f32>()).holds);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::exhaustive_u32_chained;
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;
    use std::println;

    /// One pass per input: the inverse, the forward map, and the checks
    /// against the predecessor's values.
    fn chained<S: Scalar>(
        cfg: &FlexsplineConfig<S>,
        p: &FlexsplineParams,
        d: S,
        cur: &(FlexsplineTorque<S>, S),
        prev: Option<&(FlexsplineTorque<S>, S)>,
    ) -> Verdict {
        let mut v = sign_and_saturation_of(p, d, cur.0).and(round_trip_of(cfg, p, d, cur.0));
        if let Some(pr) = prev {
            // Predecessor in the input order; both maps non-decreasing.
            v = v.and(Verdict::logical(
                pr.0.torque <= cur.0.torque && pr.1 <= cur.1,
            ));
        }
        v
    }

    /// The `mul_coef` contract of the monotone Kani harnesses: for each of
    /// the four coefficients `FlexsplineConfig::<I16F16>::new(&SHD17)`
    /// prepares (recomputed here from their definitions), the product has
    /// the sign of `x` and is non-decreasing over all 2³² inputs.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_coefficient_products_monotone_i16f16() {
        use crate::scalar::Coef;
        let u = I16F16::UNITS;
        let ck = SHD17.c_f() * SHD17.k_f0();
        let coefs = [
            SHD17.c_f() / u.link_torque,
            u.torsion / ck,
            ck / u.torsion,
            u.link_torque / SHD17.c_f(),
        ];
        let bits = |c: u32| (c ^ 0x8000_0000) as i32;
        for v in coefs {
            let c = Coef::new(v);
            let r = exhaustive_u32_chained(
                0,
                u32::MAX,
                |code| I16F16::from_bits(bits(code)).mul_coef(&c).to_bits(),
                |code, &y, prev| {
                    let x = bits(code);
                    let sign = if x > 0 {
                        y >= 0
                    } else if x < 0 {
                        y <= 0
                    } else {
                        y == 0
                    };
                    Verdict::logical(sign && prev.is_none_or(|&p| p <= y))
                },
            );
            println!(
                "PROOF kernel=mul_coef({v:e}) backend=I16F16 domain=all bound=sign of x, non-decreasing max_err={} at={:#x} checked={} engine=exhaustive",
                r.max_error, r.argmax, r.checked
            );
            assert_eq!(
                r.failures, 0,
                "coefficient {v}: first failure at code {:?}",
                r.first_failure
            );
        }
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_compliance_inverse_i16f16() {
        let p = shd17();
        let cfg = FlexsplineConfig::<I16F16>::new(&p);
        let edges = SaturationEdges::i16f16(&p);
        // Codes in signed order: code c stands for bits c − 2³¹.
        let bits = |c: u32| I16F16::from_bits((c ^ 0x8000_0000) as i32);
        let r = exhaustive_u32_chained(
            0,
            u32::MAX,
            |c| (cfg.torque(bits(c)), cfg.torsion(bits(c))),
            |c, cur, prev| {
                chained(&cfg, &p, bits(c), cur, prev).and(sign_and_saturation_bits(
                    &edges,
                    bits(c),
                    cur.0,
                ))
            },
        );
        println!(
            "PROOF kernel=compliance-inverse(SHD-17) backend=I16F16 domain=all torsions bound=derived round trip, monotone, branch-safe max_err={:.3} of bound at={} checked={} engine=exhaustive",
            r.max_error, bits(r.argmax).to_bits(), r.checked
        );
        assert_eq!(
            r.failures,
            0,
            "first failure at bits {:?}",
            r.first_failure.map(|c| bits(c).to_bits())
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_compliance_inverse_f32() {
        let p = shd17();
        let cfg = FlexsplineConfig::<f32>::new(&p);
        // Codes in numeric order: negative floats (descending bit patterns)
        // first, then positive ones; NaN codes have no predecessor check.
        let val = |c: u32| {
            let b = if c < 0x8000_0000 { !c } else { c & 0x7fff_ffff };
            f32::from_bits(b)
        };
        let r = exhaustive_u32_chained(
            0,
            u32::MAX,
            |c| (cfg.torque(val(c)), cfg.torsion(val(c))),
            |c, cur, prev| {
                let d = val(c);
                let prev = prev.filter(|_| c > 0 && !val(c - 1).is_nan() && !d.is_nan());
                chained(&cfg, &p, d, cur, prev)
            },
        );
        println!(
            "PROOF kernel=compliance-inverse(SHD-17) backend=f32 domain=all bit patterns bound=derived round trip, monotone, branch-safe max_err={:.3} of bound at={:e} checked={} engine=exhaustive",
            r.max_error, val(r.argmax), r.checked
        );
        assert_eq!(
            r.failures,
            0,
            "first failure at {:?}",
            r.first_failure.map(val)
        );
    }

    proptest! {
        #[test]
        fn compliance_properties_f64(d in -0.01f64..0.01, dd in 1e-12f64..1e-6) {
            let p = shd17();
            let cfg = FlexsplineConfig::<f64>::new(&p);
            prop_assert!(inverse_sign_and_saturation(&cfg, &p, d).holds);
            prop_assert!(inverse_monotone_step(&cfg, d, d + dd).holds);
            prop_assert!(forward_monotone_step(&cfg, d * 1e4, d * 1e4 + dd).holds);
            prop_assert!(round_trip(&cfg, &p, d).holds);
        }

        #[test]
        fn compliance_properties_i16f16(bits in -(1i32 << 20)..(1i32 << 20)) {
            let p = shd17();
            let cfg = FlexsplineConfig::<I16F16>::new(&p);
            let d = I16F16::from_bits(bits);
            prop_assert!(inverse_sign_and_saturation(&cfg, &p, d).holds);
            prop_assert!(inverse_sign_and_saturation_i16f16(&cfg, &SaturationEdges::i16f16(&p), d).holds);
            prop_assert!(round_trip(&cfg, &p, d).holds);
        }
    }

    #[test]
    fn shd17_constants_match_identification() {
        let p = shd17();
        assert_eq!(SHD17.k_f0().to_bits(), p.k_f0().to_bits());
        assert_eq!(SHD17.c_f().to_bits(), p.c_f().to_bits());
        let checked = FlexsplineParams::try_new(crate::harmonic_drive::FlexsplineSettings {
            k_f0: SHD17.k_f0(),
            c_f: SHD17.c_f(),
        });
        assert_eq!(checked, Ok(SHD17));
    }

    /// The integer sign/saturation check accepts the shipped inverse on
    /// both sides of each edge and rejects a flag or a sign flipped there.
    #[test]
    fn integer_saturation_check_can_fail() {
        let cfg = FlexsplineConfig::<I16F16>::new(&SHD17);
        let e = SaturationEdges::i16f16(&SHD17);
        assert!(e.clear_up_to > 0 && e.set_from > e.clear_up_to);
        for bits in [
            e.clear_up_to,
            -e.clear_up_to,
            e.set_from,
            -e.set_from,
            1,
            -1,
            0,
        ] {
            let d = I16F16::from_bits(bits as i32);
            let r = cfg.torque(d);
            assert!(sign_and_saturation_bits(&e, d, r).holds, "{bits}");
            assert!(sign_and_saturation_of(&SHD17, d, r).holds, "{bits}");
            if bits != 0 {
                let flipped = FlexsplineTorque {
                    saturated: !r.saturated,
                    ..r
                };
                assert!(!sign_and_saturation_bits(&e, d, flipped).holds, "{bits}");
                if r.torque != I16F16::ZERO {
                    let negated = FlexsplineTorque {
                        torque: r.torque.neg(),
                        ..r
                    };
                    assert!(!sign_and_saturation_bits(&e, d, negated).holds, "{bits}");
                }
            }
        }
    }

    /// The round-trip check fails for a configuration whose forward and
    /// inverse disagree (a 1e-4 relative error in c_f on one side only).
    #[test]
    fn round_trip_check_detects_inconsistent_coefficients() {
        let p = shd17();
        let skewed = FlexsplineParams::try_new(crate::harmonic_drive::FlexsplineSettings {
            k_f0: p.k_f0(),
            c_f: p.c_f() * (1.0 + 1e-4),
        })
        .unwrap();
        let inv = FlexsplineConfig::<f32>::new(&skewed);
        let fwd = FlexsplineConfig::<f32>::new(&p);
        let d = 0.9 * p.max_torsion() as f32;
        let back = fwd.torsion(inv.torque(d).torque);
        let bound = 10.0 * 2f64.powi(-23) * d as f64;
        assert!(((back - d) as f64).abs() > bound);
        assert!(round_trip(&fwd, &p, d).holds);
    }
}
