//! Compliance models of a harmonic drive (thesis §2.2.2–2.2.3).
//!
//! * [`CataloguePiecewise`] — the manufacturer's piecewise-linear curve,
//!   eq. (2.11) (as the catalogue means it: see the errata).
//! * [`CubicStiffness`] — the cubic polynomial of eq. (2.10).
//! * [`FlexsplineParams`] — the proposed flexspline stiffness, eq. (2.24)–(2.26),
//!   and its inverse, eq. (3.10).
//! * [`WaveGeneratorParams`] — the wave-generator compliance, eq. (2.27)–(2.29).
//! * [`HarmonicDriveParams`] — the total torsion, eq. (2.30).
//!
//! Units: torques in N·m, torsion in rad (output side), stiffness in N·m/rad,
//! `c_f`, `c_w` in 1/(N·m). Torques are *flexspline* (link-side) torques
//! `τ_f` unless named wave-generator torques `τ_w` (motor side).
//!
//! The `…Params` types are `f64` designs; [`FlexsplineConfig`] and
//! [`WaveGeneratorConfig`] are the same models quantized for a backend `S`
//! (stored units `S::UNITS`), and the `f64` methods are those configs with
//! `S = f64`, so each formula exists once.

use crate::error::{combination, finite, gear_ratio, in_range, increasing, positive, ParamError};
use crate::scalar::{units::Units, Coef, Scalar};

/// The catalogue's piecewise-linear torsion curve, eq. (2.11), odd in the
/// torque: slopes `K1` up to `T1`, `K2` from `T1` to `T2`, `K3` above `T2`.
///
/// ```text
/// Δθ(τ) = τ/K1                                   0 ≤ τ ≤ T1
///         T1/K1 + (τ − T1)/K2                    T1 < τ ≤ T2
///         T1/K1 + (T2 − T1)/K2 + (τ − T2)/K3     τ > T2
/// Δθ(−τ) = −Δθ(τ)
/// ```
///
/// The printed eq. (2.11) divides the third piece by `K2` and writes `τ_1`,
/// `T_f` for `T_1`, `τ_f`; it also leaves the negative torques out. See
/// errata E2.2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CataloguePiecewise {
    k1: f64,
    k2: f64,
    k3: f64,
    t1: f64,
    t2: f64,
}

/// The five numbers of a catalogue curve by name, for
/// [`CataloguePiecewise::try_new`] (five `f64`s in a row could be swapped
/// silently).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogueCurve {
    /// Slope up to `T1`, N·m/rad.
    pub k1: f64,
    /// Slope from `T1` to `T2`, N·m/rad.
    pub k2: f64,
    /// Slope above `T2`, N·m/rad.
    pub k3: f64,
    /// First knee torque, N·m.
    pub t1: f64,
    /// Second knee torque, N·m.
    pub t2: f64,
}

impl CataloguePiecewise {
    /// Validates `K1, K2, K3 > 0` (N·m/rad) and `0 < T1 < T2` (N·m).
    pub fn try_new(curve: CatalogueCurve) -> Result<Self, ParamError> {
        let CatalogueCurve { k1, k2, k3, t1, t2 } = curve;
        let (k1, k2, k3) = (
            positive("k1", k1)?,
            positive("k2", k2)?,
            positive("k3", k3)?,
        );
        let (t1, t2) = (positive("t1", t1)?, positive("t2", t2)?);
        increasing(("t1", t1), ("t2", t2))?;
        Ok(CataloguePiecewise { k1, k2, k3, t1, t2 })
    }

    /// The validated curve.
    pub fn curve(&self) -> CatalogueCurve {
        CatalogueCurve {
            k1: self.k1,
            k2: self.k2,
            k3: self.k3,
            t1: self.t1,
            t2: self.t2,
        }
    }

    /// Torsion at the knee `T1`, rad.
    pub fn torsion_at_t1(&self) -> f64 {
        self.t1 / self.k1
    }

    /// Torsion at the knee `T2`, rad.
    pub fn torsion_at_t2(&self) -> f64 {
        self.torsion_at_t1() + (self.t2 - self.t1) / self.k2
    }

    /// Eq. (2.11): torsion (rad) for a flexspline torque (N·m).
    pub fn torsion(&self, torque: f64) -> f64 {
        let t = torque.abs();
        let d = if t <= self.t1 {
            t / self.k1
        } else if t <= self.t2 {
            self.torsion_at_t1() + (t - self.t1) / self.k2
        } else {
            self.torsion_at_t2() + (t - self.t2) / self.k3
        };
        d.copysign(torque)
    }

    /// The exact inverse of [`torsion`](Self::torsion): torque (N·m) for a
    /// torsion (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        let d = torsion.abs();
        let (d1, d2) = (self.torsion_at_t1(), self.torsion_at_t2());
        let t = if d <= d1 {
            d * self.k1
        } else if d <= d2 {
            self.t1 + (d - d1) * self.k2
        } else {
            self.t2 + (d - d2) * self.k3
        };
        t.copysign(torsion)
    }

    /// Local stiffness `dτ/dΔθ` at a torque (N·m/rad): `K1`, `K2` or `K3`.
    pub fn local_stiffness(&self, torque: f64) -> f64 {
        let t = torque.abs();
        if t <= self.t1 {
            self.k1
        } else if t <= self.t2 {
            self.k2
        } else {
            self.k3
        }
    }
}

/// The coefficients of eq. (2.10) by name, for [`CubicStiffness::try_new`] (two `f64` of different
/// units: named so that they cannot be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicStiffnessSettings {
    /// Linear coefficient `a1`, N·m/rad (> 0).
    pub a1: f64,
    /// Cubic coefficient `a3`, N·m/rad³ (≥ 0).
    pub a3: f64,
}

/// The cubic stiffness of eq. (2.10), `τ_f = a1 Δθ + a3 Δθ³`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicStiffness {
    a1: f64,
    a3: f64,
}

impl CubicStiffness {
    /// Validates `a1 > 0` (N·m/rad) and `a3 ≥ 0` (N·m/rad³), which make the
    /// curve strictly increasing and so invertible.
    pub fn try_new(settings: CubicStiffnessSettings) -> Result<Self, ParamError> {
        let CubicStiffnessSettings { a1, a3 } = settings;
        let a1 = positive("a1", a1)?;
        let a3 = finite("a3", a3)?;
        if a3 < 0.0 {
            return Err(ParamError::Negative {
                name: "a3",
                value: a3,
            });
        }
        Ok(CubicStiffness { a1, a3 })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> CubicStiffnessSettings {
        CubicStiffnessSettings {
            a1: self.a1,
            a3: self.a3,
        }
    }

    /// The cubic through the catalogue's two knee points `(Δθ(T1), T1)` and
    /// `(Δθ(T2), T2)` of a [`CataloguePiecewise`] curve — the identification
    /// used to compare the models (thesis Fig. 2.11–2.12). Fails with
    /// [`ParamError::NotRepresentable`] (`name = "a3"`) when the knees bend
    /// the wrong way (softening), which no admissible cubic fits.
    pub fn through_catalogue_knees(c: &CataloguePiecewise) -> Result<Self, ParamError> {
        let (x1, x2) = (c.torsion_at_t1(), c.torsion_at_t2());
        // [x1 x1³; x2 x2³] [a1; a3] = [T1; T2], solved by Cramer's rule.
        let det = x1 * x2 * x2 * x2 - x2 * x1 * x1 * x1;
        let a1 = (c.t1 * x2 * x2 * x2 - c.t2 * x1 * x1 * x1) / det;
        let a3 = (x1 * c.t2 - x2 * c.t1) / det;
        if a3 < 0.0 || a1 <= 0.0 || !a1.is_finite() || !a3.is_finite() {
            return Err(ParamError::NotRepresentable {
                name: "a3",
                value: a3,
            });
        }
        Self::try_new(CubicStiffnessSettings { a1, a3 })
    }

    /// The linear coefficient `a1`, N·m/rad.
    pub fn a1(&self) -> f64 {
        self.a1
    }

    /// The cubic coefficient `a3`, N·m/rad³.
    pub fn a3(&self) -> f64 {
        self.a3
    }

    /// Eq. (2.10): torque (N·m) for a torsion (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        torsion * (self.a1 + self.a3 * torsion * torsion)
    }

    /// Local stiffness `a1 + 3 a3 Δθ²` (N·m/rad) at a torsion (rad).
    pub fn local_stiffness(&self, torsion: f64) -> f64 {
        self.a1 + 3.0 * self.a3 * torsion * torsion
    }

    /// Torsion (rad) for a torque (N·m): the real root of the cubic
    /// (Remark 1: the inverse the controller needs), by Newton's method from
    /// the linear guess; the function is increasing and convex for
    /// `Δθ > 0`, so Newton from `τ/a1` (which over-estimates) decreases
    /// monotonically to the root.
    ///
    /// Both `τ/a1` and `∛(τ/a3)` over-estimate the root; Newton starts from
    /// the smaller, so the cubic never overflows for `|τ| ≤ 1e300` N·m
    /// (larger torques are taken as 1e300; a non-finite torque gives 0).
    pub fn torsion(&self, torque: f64) -> f64 {
        if !torque.is_finite() {
            return 0.0;
        }
        let t = torque.abs().min(1e300);
        let mut x = t / self.a1;
        if self.a3 > 0.0 {
            x = x.min(libm::cbrt(t / self.a3));
        }
        if !x.is_finite() {
            // Only for a1 and a3 so small that the torsion exceeds f64.
            return f64::MAX.copysign(torque);
        }
        for _ in 0..60 {
            let f = self.torque(x) - t;
            let step = f / self.local_stiffness(x);
            if !step.is_finite() {
                break;
            }
            x -= step;
            if step.abs() <= 1e-17 * x.abs() {
                break;
            }
        }
        x.copysign(torque)
    }
}

/// The flexspline stiffness of eq. (2.24)–(2.26) by name, for [`FlexsplineParams::try_new`] (two
/// `f64` of different units: named so that they cannot be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexsplineSettings {
    /// Stiffness at zero torque `K_f0`, N·m/rad (> 0).
    pub k_f0: f64,
    /// Stiffening coefficient `c_f`, 1/(N·m), in [`STIFFENING_RANGE`].
    pub c_f: f64,
}

/// Flexspline stiffness of the proposed model, eq. (2.24):
/// `K_fl = K_f0 (1 + (c_f τ_f)²)`.
///
/// Built only by [`try_new`](Self::try_new), so every value a
/// configuration sees has passed its checks.
///
/// ```compile_fail
/// // Fields are private: a NaN `c_f` cannot skip `try_new`.
/// let f = mrr_control::harmonic_drive::FlexsplineParams { k_f0: 8.3e3, c_f: f64::NAN };
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexsplineParams {
    k_f0: f64,
    c_f: f64,
}

/// Accepted range of the stiffening coefficients `c_f` and `c_w`,
/// 1/(N·m): wide around the thesis's identified values (0.045 and 83), and
/// narrow enough that every backend keeps the prepared coefficients
/// (`c`, `1/c`, in stored units) at full 31-bit precision.
pub const STIFFENING_RANGE: (f64, f64) = (1e-6, 1e6);

/// The largest argument of `tan_bounded` ([`kernels::i16f16::tan_bounded`](crate::scalar::kernels::i16f16::tan_bounded) on fixed point) the torque estimator
/// evaluates eq. (3.10) at, rad: `atan 8` (its torsion limit keeps the
/// argument within it; see
/// [`TorqueEstimatorParams::try_new`](crate::estimation::torque::TorqueEstimatorParams::try_new)).
pub(crate) const TAN_BOUNDED_ARGUMENT: f64 = 1.446_441_332_248_135;

/// Accepted range of the flexspline's largest torsion `π/(2 c_f K_f0)`,
/// rad. Harmonic drives twist by milliradians (4.2 mrad for the
/// SHD-17-100); the lower end is 65 steps of the fixed-point torsion unit,
/// so the inverse of eq. (3.10) keeps a usable domain on every backend.
pub const MAX_TORSION_RANGE: (f64, f64) = (1e-6, 1.0);

impl FlexsplineParams {
    /// Parameters whose validity is established elsewhere, as a constant:
    /// only for the verification harnesses' prepared configurations
    /// (`proofs/`), each of which is tested equal, bit for bit, to the
    /// result of [`FlexsplineParams::try_new`] on the same values.
    #[cfg(any(kani, test, feature = "proofs"))]
    pub(crate) const fn prevalidated(k_f0: f64, c_f: f64) -> Self {
        FlexsplineParams { k_f0, c_f }
    }

    /// Validates `K_f0 > 0` (N·m/rad) and `c_f` (1/(N·m)) in
    /// [`STIFFENING_RANGE`], both finite, and the composite: the largest
    /// torsion `π/(2 c_f K_f0)` (the edge of the inverse's domain) in
    /// [`MAX_TORSION_RANGE`]. Errors name the parameter (`k_f0`, `c_f`) or
    /// the combination (`π/(2·c_f·k_f0)`).
    pub fn try_new(settings: FlexsplineSettings) -> Result<Self, ParamError> {
        let FlexsplineSettings { k_f0, c_f } = settings;
        let k_f0 = positive("k_f0", k_f0)?;
        let c_f = in_range("c_f", c_f, STIFFENING_RANGE.0, STIFFENING_RANGE.1)?;
        let p = FlexsplineParams { k_f0, c_f };
        combination(
            "π/(2·c_f·k_f0)",
            p.max_torsion(),
            MAX_TORSION_RANGE.0,
            MAX_TORSION_RANGE.1,
        )?;
        Ok(p)
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> FlexsplineSettings {
        FlexsplineSettings {
            k_f0: self.k_f0,
            c_f: self.c_f,
        }
    }

    /// Stiffness at zero torque `K_f0`, N·m/rad.
    pub fn k_f0(&self) -> f64 {
        self.k_f0
    }

    /// Stiffening coefficient `c_f`, 1/(N·m).
    pub fn c_f(&self) -> f64 {
        self.c_f
    }

    /// Eq. (2.24): local stiffness (N·m/rad) at a flexspline torque (N·m).
    pub fn local_stiffness(&self, torque: f64) -> f64 {
        let u = self.c_f * torque;
        self.k_f0 * (1.0 + u * u)
    }

    /// Largest flexspline torsion the model can produce, `π / (2 c_f K_f0)`
    /// (rad): the torsion as `τ_f → ∞`, and the edge of the inverse's domain.
    pub fn max_torsion(&self) -> f64 {
        core::f64::consts::FRAC_PI_2 / (self.c_f * self.k_f0)
    }

    /// Eq. (2.26): flexspline torsion (rad) for a torque (N·m),
    /// `Δθ_f = atan(c_f τ_f) / (c_f K_f0)`.
    pub fn torsion(&self, torque: f64) -> f64 {
        FlexsplineConfig::<f64>::new(self).torsion(torque)
    }

    /// Eq. (3.10): torque (N·m) for a flexspline torsion (rad),
    /// `τ_f = tan(Δθ_f c_f K_f0) / c_f`, with the saturation of
    /// [`FlexsplineConfig::torque`].
    pub fn torque(&self, torsion: f64) -> FlexsplineTorque<f64> {
        FlexsplineConfig::<f64>::new(self).torque(torsion)
    }
}

/// The result of inverting the flexspline compliance (eq. 3.10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexsplineTorque<S> {
    /// The torque, in the backend's stored link-torque unit.
    pub torque: S,
    /// `true` when the torsion was at or beyond `±max_torsion` (the
    /// principal branch of `tan` ends there) and the torque was saturated.
    pub saturated: bool,
}

/// [`FlexsplineParams`] quantized for backend `S`: torques in
/// `S::UNITS.link_torque`, torsion in `S::UNITS.torsion`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexsplineConfig<S> {
    /// `c_f` per stored torque unit.
    c_f: Coef,
    /// Stored torsion per radian of `atan` (`1 / (c_f K_f0)` scaled).
    torsion_per_angle: Coef,
    /// Radian of `tan` argument per stored torsion (`c_f K_f0` scaled).
    angle_per_torsion: Coef,
    /// Stored torque per unit of `tan` (`1 / c_f` scaled).
    torque_per_tan: Coef,
    _backend: core::marker::PhantomData<S>,
}

impl<S: Scalar> FlexsplineConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &FlexsplineParams) -> Self {
        let u: Units = S::UNITS;
        let ck = p.c_f * p.k_f0;
        FlexsplineConfig {
            c_f: Coef::new(p.c_f / u.link_torque),
            torsion_per_angle: Coef::new(u.torsion / ck),
            angle_per_torsion: Coef::new(ck / u.torsion),
            torque_per_tan: Coef::new(u.link_torque / p.c_f),
            _backend: core::marker::PhantomData,
        }
    }

    /// Eq. (2.26) in stored units.
    #[inline]
    pub fn torsion(&self, torque: S) -> S {
        torque
            .mul_coef(&self.c_f)
            .atan()
            .mul_coef(&self.torsion_per_angle)
    }

    /// Eq. (3.10) in stored units. The argument `Δθ_f c_f K_f0` must stay
    /// inside the principal branch `(-π/2, π/2)`; at or beyond it the torque
    /// saturates at the backend's largest in-branch value (sign of the
    /// torsion) and `saturated` is set — a value from the wrong branch is
    /// never returned.
    #[inline]
    pub fn torque(&self, torsion: S) -> FlexsplineTorque<S> {
        let angle = torsion.mul_coef(&self.angle_per_torsion);
        FlexsplineTorque {
            torque: self.torque_of_angle(angle),
            saturated: angle.abs() >= S::FRAC_PI_2,
        }
    }

    /// Eq. (3.10) without the branch test, for a caller that has already
    /// bounded the torsion (see [`torsion_within`](Self::torsion_within)):
    /// the argument of `tan` is then at most `atan(c_f·max_torque) ≤
    /// atan 7.5` (the estimator's validated limit), inside the domain of
    /// `tan_bounded` ([`kernels::i16f16::tan_bounded`](crate::scalar::kernels::i16f16::tan_bounded) on fixed point) (`atan 8`), which it takes.
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    pub(crate) fn torque_in_branch(&self, torsion: S) -> S {
        self.angle_of(torsion)
            .tan_bounded()
            .mul_coef(&self.torque_per_tan)
    }

    /// The argument `Δθ_f c_f K_f0` of `tan` in eq. (3.10), stored units.
    #[inline(always)]
    pub(crate) fn angle_of(&self, torsion: S) -> S {
        torsion.mul_coef(&self.angle_per_torsion)
    }

    #[inline(always)]
    fn torque_of_angle(&self, angle: S) -> S {
        angle.tan().mul_coef(&self.torque_per_tan)
    }

    /// The largest stored torsion `a ≥ 0` such that, at `a` and at `−a`,
    /// the argument of `tan` is within `atan 8` (the domain of
    /// `tan_bounded` ([`kernels::i16f16::tan_bounded`](crate::scalar::kernels::i16f16::tan_bounded) on fixed point), inside the branch) and
    /// [`torque_in_branch`](Self::torque_in_branch) has a magnitude of at
    /// most `limit` (stored torque), while at the next representable
    /// torsion above `a` one of the two fails. Found once, at configuration
    /// time, by bisection on the backend's own arithmetic; `branch_edge` is
    /// the torsion (stored units, as `f64`) where the argument of `tan`
    /// reaches π/2, beyond the bracket's start.
    ///
    /// Every step of `torque_in_branch` is non-decreasing in the torsion
    /// (the products round monotonically; `tan_bounded` is monotone on
    /// `I16F16` at every input, and on f32 it is the proven-monotone `tan`
    /// bit for bit on its domain, clamped beyond), so the
    /// torsions that pass both tests are exactly those with `|Δθ_f| ≤ a`
    /// when the backend is also odd (f32, f64: the products and `tan` are
    /// exactly odd). On `I16F16` the rounding of the products is not
    /// exactly odd; `a` is then the smaller of the two sides, so
    /// `|Δθ_f| ≤ a` never admits a torsion that the direct test rejects.
    pub(crate) fn torsion_within(&self, limit: S, branch_edge: f64) -> S {
        let bound = S::from_f64(TAN_BOUNDED_ARGUMENT);
        let fits =
            |t: S| self.angle_of(t).abs() <= bound && self.torque_in_branch(t).abs() <= limit;
        let ok = |x: f64| {
            let t = S::from_f64(x);
            fits(t) && fits(t.neg())
        };
        // `ok(lo)` and `!ok(hi)` throughout; at the end `lo` and `hi` are
        // adjacent f64s, whose images in `S` are adjacent (or the loop
        // would have found them equal).
        let mut hi = 1.5 * branch_edge;
        if hi.is_nan() || hi >= S::MAX.to_f64() {
            hi = S::MAX.to_f64();
            if ok(hi) {
                return S::MAX;
            }
        }
        let mut lo = 0.0f64;
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if ok(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        S::from_f64(lo)
    }
}

/// The wave-generator compliance of eq. (2.27) by name, for [`WaveGeneratorParams::try_new`] (two
/// `f64` of different units: named so that they cannot be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorSettings {
    /// Stiffness at zero torque `K_w0`, N·m/rad, wave-generator side (> 0).
    pub k_w0: f64,
    /// Stiffening coefficient `c_w`, 1/(N·m), in [`STIFFENING_RANGE`].
    pub c_w: f64,
}

/// Wave-generator compliance of the proposed model, eq. (2.27):
/// `K_wl = K_w0 e^{c_w |τ_w|}`.
///
/// Built only by [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorParams {
    k_w0: f64,
    c_w: f64,
}

impl WaveGeneratorParams {
    /// Validates `K_w0 > 0` (N·m/rad, wave-generator side) and `c_w`
    /// (1/(N·m)) in [`STIFFENING_RANGE`], both finite; the largest
    /// wave-generator torsion `1/(c_w K_w0)` must be a finite number, that
    /// is `c_w·k_w0 ≥ 1/f64::MAX` (named `"c_w·k_w0"`).
    pub fn try_new(settings: WaveGeneratorSettings) -> Result<Self, ParamError> {
        let WaveGeneratorSettings { k_w0, c_w } = settings;
        let k_w0 = positive("k_w0", k_w0)?;
        let c_w = in_range("c_w", c_w, STIFFENING_RANGE.0, STIFFENING_RANGE.1)?;
        combination("c_w·k_w0", c_w * k_w0, 1.0 / f64::MAX, f64::INFINITY)?;
        Ok(WaveGeneratorParams { k_w0, c_w })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> WaveGeneratorSettings {
        WaveGeneratorSettings {
            k_w0: self.k_w0,
            c_w: self.c_w,
        }
    }

    /// Stiffness at zero torque `K_w0`, N·m/rad (wave-generator side).
    pub fn k_w0(&self) -> f64 {
        self.k_w0
    }

    /// Stiffening coefficient `c_w`, 1/(N·m).
    pub fn c_w(&self) -> f64 {
        self.c_w
    }

    /// Largest wave-generator torsion `1/(c_w K_w0)` (rad, input side), the
    /// limit of eq. (2.29) as `|τ_w| → ∞` (half the hysteresis width of
    /// eq. 2.36 times `N`).
    pub fn max_torsion(&self) -> f64 {
        1.0 / (self.c_w * self.k_w0)
    }

    /// Eq. (2.27): local stiffness (N·m/rad) at a wave-generator torque.
    pub fn local_stiffness(&self, torque: f64) -> f64 {
        self.k_w0 * libm::exp(self.c_w * torque.abs())
    }

    /// Eq. (2.29): wave-generator torsion `Δθ_w` (rad, input side) for a
    /// wave-generator torque `τ_w` (N·m):
    /// `Δθ_w = sgn(τ_w) (1 − e^{−c_w |τ_w|}) / (c_w K_w0)`.
    pub fn torsion(&self, torque: f64) -> f64 {
        // The output-side term of eq. (2.30) with N = 1 is Δθ_w itself.
        WaveGeneratorConfig::<f64>::new(self, 1.0).output_torsion(torque)
    }
}

/// The wave-generator term of eq. (2.30) quantized for backend `S`: the
/// output-side torsion `Δθ_w / N` for a motor-side torque in
/// `S::UNITS.motor_torque`, returned in `S::UNITS.torsion`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveGeneratorConfig<S> {
    /// `c_w` per stored motor-torque unit.
    c_w: Coef,
    /// `1 / (c_w N K_w0)` in stored torsion units (half the hysteresis
    /// width, eq. 2.36).
    amplitude: Coef,
    _backend: core::marker::PhantomData<S>,
}

impl<S: Scalar> WaveGeneratorConfig<S> {
    /// Quantize validated parameters for a drive of ratio `N`.
    pub fn new(p: &WaveGeneratorParams, ratio: f64) -> Self {
        let u = S::UNITS;
        WaveGeneratorConfig {
            c_w: Coef::new(p.c_w / u.motor_torque),
            amplitude: Coef::new(u.torsion / (p.c_w * ratio * p.k_w0)),
            _backend: core::marker::PhantomData,
        }
    }

    /// Output-side wave-generator torsion `Δθ_w / N` of eq. (2.29)/(2.30).
    #[inline]
    pub fn output_torsion(&self, motor_torque: S) -> S {
        // Floats round a product symmetrically, so `|τ_w|·c_w` and
        // `τ_w·c_w` have the same magnitude and `exp_neg_abs` (even) takes
        // it; fixed point rounds ties up and keeps the magnitude first
        // (folded at compile time).
        let t = if S::FLOAT {
            motor_torque
        } else {
            motor_torque.abs()
        };
        let e = t.mul_coef(&self.c_w).exp_neg_abs();
        // `sgn(τ_w)(1 − e)` as a sign transfer: `1 − e ≥ 0`, and it is 0
        // at `τ_w = 0` (and for a NaN torque, where `e = 1`), exactly where
        // `sgn` would give 0. Fixed point (no signed zero, no NaN) negates
        // on `τ_w < 0`: `copysign` of the non-negative `1 − e` without its
        // `abs` (folded at compile time).
        let v = S::ONE.sub(e);
        let v = if S::FLOAT {
            v.copysign(motor_torque)
        } else if motor_torque < S::ZERO {
            v.neg()
        } else {
            v
        };
        v.mul_coef(&self.amplitude)
    }
}

/// The proposed harmonic-drive compliance, eq. (2.30).
///
/// Built only by [`try_new`](Self::try_new) from validated parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HarmonicDriveParams {
    flexspline: FlexsplineParams,
    wave_generator: WaveGeneratorParams,
    ratio: f64,
}

/// Largest accepted output-side wave-generator torsion `1/(c_w N K_w0)`,
/// rad (0.145 mrad for the SHD-17-100): as for the flexspline, a harmonic
/// drive twists by milliradians.
pub const MAX_WAVE_GENERATOR_TORSION: f64 = 1.0;

impl HarmonicDriveParams {
    /// Validates the ratio (`N ≥ 1`, finite; `ratio`) and the composite:
    /// the output-side wave-generator torsion `1/(c_w N K_w0)` (rad) at most
    /// [`MAX_WAVE_GENERATOR_TORSION`] (named
    /// `1/(wave_generator.c_w·ratio·wave_generator.k_w0)`). The parts were validated by their
    /// own `try_new`.
    pub fn try_new(
        flexspline: FlexsplineParams,
        wave_generator: WaveGeneratorParams,
        ratio: f64,
    ) -> Result<Self, ParamError> {
        let ratio = gear_ratio(ratio)?;
        let p = HarmonicDriveParams {
            flexspline,
            wave_generator,
            ratio,
        };
        combination(
            "1/(wave_generator.c_w·ratio·wave_generator.k_w0)",
            p.output_wave_generator_torsion(),
            0.0,
            MAX_WAVE_GENERATOR_TORSION,
        )?;
        Ok(p)
    }

    /// Flexspline stiffness, eq. (2.24)–(2.26).
    pub fn flexspline(&self) -> FlexsplineParams {
        self.flexspline
    }

    /// Wave-generator compliance, eq. (2.27)–(2.29).
    pub fn wave_generator(&self) -> WaveGeneratorParams {
        self.wave_generator
    }

    /// Gear ratio `N` (≥ 1).
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    /// Largest output-side wave-generator torsion `1/(c_w N K_w0)`, rad:
    /// the wave-generator term of eq. (2.30) as `|τ_w| → ∞`.
    pub fn output_wave_generator_torsion(&self) -> f64 {
        1.0 / (self.wave_generator.c_w * self.ratio * self.wave_generator.k_w0)
    }

    /// Eq. (2.30): total output-side torsion (rad) for a flexspline torque
    /// `τ_f` and a wave-generator torque `τ_w` (both N·m):
    /// `Δθ = atan(c_f τ_f)/(c_f K_f0) − sgn(τ_w)(1 − e^{−c_w|τ_w|})/(c_w N K_w0)`.
    pub fn torsion(&self, flexspline_torque: f64, wave_generator_torque: f64) -> f64 {
        self.flexspline.torsion(flexspline_torque)
            - WaveGeneratorConfig::<f64>::new(&self.wave_generator, self.ratio)
                .output_torsion(wave_generator_torque)
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::{FlexsplineConfig, WaveGeneratorConfig};
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, I16F16};
    use core::marker::PhantomData;

    impl FlexsplineConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            FlexsplineConfig {
                c_f: Coef::take(r),
                torsion_per_angle: Coef::take(r),
                angle_per_torsion: Coef::take(r),
                torque_per_tan: Coef::take(r),
                _backend: PhantomData,
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            self.c_f.put(s);
            self.torsion_per_angle.put(s);
            self.angle_per_torsion.put(s);
            self.torque_per_tan.put(s);
        }
    }

    impl WaveGeneratorConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            WaveGeneratorConfig {
                c_w: Coef::take(r),
                amplitude: Coef::take(r),
                _backend: PhantomData,
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            self.c_w.put(s);
            self.amplitude.put(s);
        }
    }
}

#[cfg(test)]
mod tests;
