//! Joint friction of thesis §4.1–4.2: the Coulomb + static (Stribeck) +
//! viscous model of eq. (4.7)/(4.8) (and its ch. 6 form, eq. 6.5), the
//! split of its parameters into a constant and a variable part, eq.
//! (4.9)–(4.10), and the boundary-layer nominal model with its regressor,
//! eq. (4.16)–(4.17), that the robust adaptive law of eq. (4.19) adapts.
//!
//! The parameter vector is ordered as in the thesis,
//! `F = [b, f_c, f_s, f_τ]ᵀ`:
//!
//! | index | symbol | meaning | SI unit | stored unit (`S::UNITS`) |
//! |---|---|---|---|---|
//! | 0 | `b` | viscous coefficient | N·m·s/rad | motor torque per speed |
//! | 1 | `f_c` | Coulomb level | N·m | motor torque |
//! | 2 | `f_s` | static (Stribeck) excess | N·m | motor torque |
//! | 3 | `f_τ` | Stribeck shape, `> 0` | s²/rad² | 1/speed² |
//!
//! Sign convention: the friction torque has the sign of the velocity it
//! opposes (it enters eq. 4.2 on the left, `I_m q̈_m + f_m + τ_t/N = τ_m`),
//! so the nominal model is *added* to the motor command to compensate it.
//!
//! The nonparametric term `f_q(q, q̇)` of eq. (4.8) is not modelled; it is
//! covered by its bound `ρ_fq` (Assumption 3) in the robust law.

use crate::error::{non_negative, positive, ParamError};
use crate::scalar::{slope_within, Coef, Scalar};

/// Friction parameters `F = [b, f_c, f_s, f_τ]` of eq. (4.8), SI units
/// (see the module table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionParams {
    /// Viscous coefficient `b`, N·m·s/rad (≥ 0).
    pub viscous: f64,
    /// Coulomb level `f_c`, N·m (≥ 0).
    pub coulomb: f64,
    /// Static excess `f_s`, N·m (≥ 0): the breakaway torque is `f_c + f_s`.
    pub stribeck: f64,
    /// Stribeck shape `f_τ`, s²/rad² (> 0): the static excess decays as
    /// `exp(−f_τ q̇²)`.
    pub stribeck_shape: f64,
}

/// Names of the four parameters, in vector order (for errors and reports).
pub const PARAMETER_NAMES: [&str; 4] = ["viscous", "coulomb", "stribeck", "stribeck_shape"];

/// Smallest accepted lower bound of the Stribeck shape `f_τ` in a
/// [`FrictionBounds`] box, s²/rad².
pub const STRIBECK_SHAPE_MIN: f64 = 1e-3;

/// Field paths of the variable-part bounds in [`FrictionBounds::try_new`].
const VARIABLE_PATHS: [&str; 4] = ["variable[0]", "variable[1]", "variable[2]", "variable[3]"];

/// A [`FrictionParams`] field name under `prefix`: the field paths of a
/// composite's errors. Names that are not fields pass unchanged.
fn prefixed(name: &'static str, paths: [&'static str; 4]) -> &'static str {
    PARAMETER_NAMES
        .iter()
        .position(|n| *n == name)
        .map_or(name, |j| paths[j])
}

/// `min.<field>` of [`FrictionBounds::try_new`].
fn min_path(name: &'static str) -> &'static str {
    prefixed(
        name,
        [
            "min.viscous",
            "min.coulomb",
            "min.stribeck",
            "min.stribeck_shape",
        ],
    )
}

/// `max.<field>` of [`FrictionBounds::try_new`].
fn max_path(name: &'static str) -> &'static str {
    prefixed(
        name,
        [
            "max.viscous",
            "max.coulomb",
            "max.stribeck",
            "max.stribeck_shape",
        ],
    )
}

/// `nominal_friction.<field>` of the passive law's settings.
pub(crate) fn nominal_friction_path(name: &'static str) -> &'static str {
    prefixed(
        name,
        [
            "nominal_friction.viscous",
            "nominal_friction.coulomb",
            "nominal_friction.stribeck",
            "nominal_friction.stribeck_shape",
        ],
    )
}

/// `initial_friction.<field>` of a robust adaptive design.
pub(crate) fn initial_friction_path(name: &'static str) -> &'static str {
    prefixed(
        name,
        [
            "initial_friction.viscous",
            "initial_friction.coulomb",
            "initial_friction.stribeck",
            "initial_friction.stribeck_shape",
        ],
    )
}

impl FrictionParams {
    /// Validate the named fields: `b, f_c, f_s ≥ 0`, `f_τ > 0`, all finite
    /// (errors name the field). The fields are named, so none can be
    /// swapped: `FrictionParams { viscous, coulomb, stribeck,
    /// stribeck_shape }.validated()?`.
    pub fn validated(self) -> Result<Self, ParamError> {
        let p = FrictionParams {
            viscous: non_negative("viscous", self.viscous)?,
            coulomb: non_negative("coulomb", self.coulomb)?,
            stribeck: non_negative("stribeck", self.stribeck)?,
            stribeck_shape: positive("stribeck_shape", self.stribeck_shape)?,
        };
        Ok(p)
    }

    /// The vector `F = [b, f_c, f_s, f_τ]`.
    pub fn to_array(&self) -> [f64; 4] {
        [
            self.viscous,
            self.coulomb,
            self.stribeck,
            self.stribeck_shape,
        ]
    }

    /// The parameters of a vector `[b, f_c, f_s, f_τ]` (unvalidated).
    pub fn from_array(f: [f64; 4]) -> Self {
        FrictionParams {
            viscous: f[0],
            coulomb: f[1],
            stribeck: f[2],
            stribeck_shape: f[3],
        }
    }

    /// Eq. (4.8) without the nonparametric term: friction torque (N·m) at
    /// motor speed `qd` (rad/s),
    /// `f = (f_c + f_s e^{−f_τ q̇²}) sgn(q̇) + b q̇`, with `sgn(0) = 0`
    /// (eq. 2.17).
    ///
    /// ```
    /// use mrr_control::friction::FrictionParams;
    /// let f = FrictionParams { viscous: 1e-4, coulomb: 0.01, stribeck: 0.005, stribeck_shape: 4.0 }.validated()?;
    /// // At 0.5 rad/s: 0.01 + 0.005·e^{−1} + 1e-4·0.5 = 0.0118894 N·m.
    /// assert!((f.torque(0.5) - 0.0118894).abs() < 1e-7);
    /// // Inside the boundary layer ε = 0.01 the nominal model ramps:
    /// // (0.01 + 0.005·e^{−1e-4})·0.5 + 1e-4·0.005 = 0.00750025 N·m.
    /// assert!((f.nominal(0.005, 0.01) - 0.00750025).abs() < 1e-8);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn torque(&self, qd: f64) -> f64 {
        self.sliding_level(qd) * qd.sgn() + self.viscous * qd
    }

    /// The Coulomb + Stribeck level of eq. (4.8), `f_c + f_s e^{−f_τ q̇²}`
    /// (N·m, ≥ 0): the friction magnitude while sliding at speed `q̇`
    /// (rad/s), before the viscous term.
    pub fn sliding_level(&self, qd: f64) -> f64 {
        self.coulomb + self.stribeck * libm::exp(-self.stribeck_shape * qd * qd)
    }

    /// Eq. (4.17), first line: the nominal model with the boundary layer
    /// `ε_q̇` (rad/s),
    /// `f̂ = (f_c + f_s e^{−f_τ q̇²}) sat(q̇, ε_q̇) + b q̇` (N·m).
    pub fn nominal(&self, qd: f64, eps: f64) -> f64 {
        self.sliding_level(qd) * qd.sat(eps) + self.viscous * qd
    }

    /// Eq. (4.17), third line: the regressor `Y = ∂f̂/∂F` at these
    /// parameters,
    /// `Y = [q̇, s, e^{−f_τ q̇²} s, −f_s q̇² e^{−f_τ q̇²} s]` with
    /// `s = sat(q̇, ε_q̇)`; units `[rad/s, 1, 1, N·m·rad²/s²]`.
    pub fn regressor(&self, qd: f64, eps: f64) -> [f64; 4] {
        let s = qd.sat(eps);
        let e = libm::exp(-self.stribeck_shape * qd * qd);
        [qd, s, e * s, -self.stribeck * qd * qd * e * s]
    }

    /// Eq. (4.17), second line: the boundary-layer residual
    /// `f̌ = (f_c + f_s e^{−f_τ q̇²}) (sgn(q̇) − sat(q̇, ε_q̇))` (N·m), the part
    /// of eq. (4.8) the smooth nominal model leaves out. It vanishes for
    /// `|q̇| > ε_q̇` and is bounded by `f_c + f_s` (Assumption 6).
    pub fn boundary_layer_residual(&self, qd: f64, eps: f64) -> f64 {
        (self.coulomb + self.stribeck * libm::exp(-self.stribeck_shape * qd * qd))
            * (qd.sgn() - qd.sat(eps))
    }
}

/// What is known about a joint's friction: the box `[min, max]` that the
/// constant part `F^c` lies in (the projection bounds of the adaptation
/// law), and the bound `ρ_F` on the variable part, eq. (4.9)–(4.10):
/// `F = F^c + F^v`, `|F^v_j| < ρ_Fj`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionBounds {
    min: [f64; 4],
    max: [f64; 4],
    variable: [f64; 4],
}

impl FrictionBounds {
    /// Validate: `min` and `max` are valid [`FrictionParams`] with
    /// `min_j ≤ max_j` (a component may be fixed, `min_j = max_j`),
    /// `ρ_Fj ≥ 0`, and `f_τ,min ≥ 1e-3 s²/rad²` — below it the Stribeck
    /// term of a fixed-point backend could not be evaluated beyond
    /// `|q̇| = 181 rad/s`, where `q̇²` leaves the `I16F16` range while
    /// `e^{−f_τ q̇²}` is still above one LSB (with `f_τ ≥ 1e-3` it is
    /// below `e^{−32}`). Errors name the argument's field as
    /// `min.viscous`, `max.stribeck_shape`, `variable[2]`, … (a box
    /// corner out of order is [`ParamError::Exceeds`] naming both
    /// corners' fields).
    pub fn try_new(
        min: FrictionParams,
        max: FrictionParams,
        variable: [f64; 4],
    ) -> Result<Self, ParamError> {
        let min = min.validated().map_err(|e| e.map_names(min_path))?;
        let max = max.validated().map_err(|e| e.map_names(max_path))?;
        let (lo, hi) = (min.to_array(), max.to_array());
        for j in 0..4 {
            non_negative(VARIABLE_PATHS[j], variable[j])?;
        }
        if lo[3] < STRIBECK_SHAPE_MIN {
            return Err(ParamError::OutOfRange {
                name: "min.stribeck_shape",
                value: lo[3],
                min: STRIBECK_SHAPE_MIN,
                max: f64::INFINITY,
            });
        }
        for j in 0..4 {
            if lo[j] > hi[j] {
                return Err(ParamError::Exceeds {
                    lower: min_path(PARAMETER_NAMES[j]),
                    lower_value: lo[j],
                    upper: max_path(PARAMETER_NAMES[j]),
                    upper_value: hi[j],
                });
            }
        }
        Ok(FrictionBounds {
            min: lo,
            max: hi,
            variable,
        })
    }

    /// Bounds from constants already known to be valid (the shipped
    /// example configurations; their validity is tested).
    pub(crate) const fn from_checked(min: [f64; 4], max: [f64; 4], variable: [f64; 4]) -> Self {
        FrictionBounds { min, max, variable }
    }

    /// Lower corner of the box of `F^c`.
    pub fn min(&self) -> [f64; 4] {
        self.min
    }

    /// Upper corner of the box of `F^c`.
    pub fn max(&self) -> [f64; 4] {
        self.max
    }

    /// Bounds `ρ_F` of the variable part, eq. (4.10), in the units of `F`.
    pub fn variable(&self) -> [f64; 4] {
        self.variable
    }

    /// `true` when `f` lies in the box of `F^c`.
    pub fn contains(&self, f: &FrictionParams) -> bool {
        let a = f.to_array();
        (0..4).all(|j| a[j] >= self.min[j] && a[j] <= self.max[j])
    }

    /// Eq. (4.9): split an actual parameter vector into its constant part
    /// `F^c` (the nearest point of the box) and its variable part
    /// `F^v = F − F^c`, and report whether Property 1, `|F^v_j| < ρ_Fj`
    /// (eq. 4.10), holds for it.
    pub fn split(&self, f: &FrictionParams) -> ([f64; 4], [f64; 4], bool) {
        let a = f.to_array();
        let mut c = [0.0; 4];
        let mut v = [0.0; 4];
        let mut ok = true;
        for j in 0..4 {
            c[j] = a[j].clamp(self.min[j], self.max[j]);
            v[j] = a[j] - c[j];
            ok &= v[j].abs() < self.variable[j] || v[j] == 0.0;
        }
        (c, v, ok)
    }

    /// A bound `ρ_f` for Assumption 6, derived: `|sgn − sat| ≤ 1` and
    /// `e^{−f_τ q̇²} ≤ 1`, so `|f̌| ≤ f_c + f_s ≤ (f_c,max + ρ_F2) +
    /// (f_s,max + ρ_F3)` (N·m) for every actual parameter vector allowed by
    /// the box and eq. (4.10). The supremum is approached as `q̇ → 0⁺` with
    /// `f_τ`'s factor → 1, so it cannot be lowered in general.
    pub fn boundary_layer_bound(&self) -> f64 {
        self.max[1] + self.variable[1] + self.max[2] + self.variable[2]
    }
}

/// Stored units of `F = [b, f_c, f_s, f_τ]` for backend `S`: the factor
/// from SI to stored value of each component.
pub(crate) fn parameter_scales<S: Scalar>() -> [f64; 4] {
    let u = S::UNITS;
    [
        u.motor_torque / u.speed,
        u.motor_torque,
        u.motor_torque,
        1.0 / (u.speed * u.speed),
    ]
}

/// Stored units of the regressor `Y` of eq. (4.17) for backend `S`.
pub(crate) fn regressor_scales<S: Scalar>() -> [f64; 4] {
    let u = S::UNITS;
    [u.speed, 1.0, 1.0, u.motor_torque * u.speed * u.speed]
}

/// `sat(x, ε)` of eq. (4.18) with a prepared reciprocal `inv_eps = 1/ε`:
/// no division in the hot path. For `ε > 0` equals [`Scalar::sat`] up to
/// the rounding of the product (in `[−1, 1]`, non-decreasing; odd on
/// floats, on fixed point odd but for one LSB at a product tie); `ε ≤ 0`
/// is an empty layer, the sign function (0 at 0); NaN gives 0.
#[inline]
pub fn sat_with_reciprocal<S: Scalar>(x: S, eps: S, inv_eps: &Coef) -> S {
    sat_scaled(x, eps, |x| x.mul_coef(inv_eps))
}

/// `±1` outside the layer `|x| ≤ ε`, 0 for NaN, and `scale(x)` (`x/ε`
/// by some product) clamped to `[−1, 1]` inside it.
///
/// The inside of the layer is tested first, by one magnitude comparison
/// (false for NaN; on fixed point `|MIN|` saturates to `MAX`, outside any
/// layer, and `MIN` then takes the `−1` branch as it should).
#[inline(always)]
fn sat_scaled<S: Scalar>(x: S, eps: S, scale: impl Fn(S) -> S) -> S {
    sat_in_layer(x, eps, |x| scale(x).clamp(S::ONE.neg(), S::ONE))
}

/// [`sat_scaled`] for a `scale` that already keeps `[−ε, ε]` within
/// `[−1, 1]` (a slope prepared by `slope_within`): no clamp.
#[inline(always)]
fn sat_in_layer<S: Scalar>(x: S, eps: S, scale: impl Fn(S) -> S) -> S {
    if x.abs() <= eps {
        scale(x)
    } else if x > S::ZERO {
        S::ONE
    } else if x < S::ZERO {
        S::ONE.neg()
    } else {
        // NaN.
        S::ZERO
    }
}

/// [`sat_in_layer`] for an `x` known not to be NaN: the same value for
/// every other `x` without the NaN test (outside the layer `x` is
/// positive or negative, and `±1` is `1` with the sign of `x`: on floats
/// its sign bit, without a comparison; on fixed point `MIN` takes the `−1`
/// branch).
#[inline(always)]
fn sat_in_layer_number<S: Scalar>(x: S, eps: S, scale: impl Fn(S) -> S) -> S {
    if x.abs() <= eps {
        scale(x)
    } else {
        S::ONE.copysign(x)
    }
}

/// `x · s` for a factor `s ∈ [−1, 1]` (a `sat` value, often exactly `±1`):
/// [`Scalar::mul_unit_range`], bit-identical to `x.mul(s)` on every
/// backend (on `I16F16` a short product for every such `s`, `±1`
/// included; floats multiply).
#[inline]
pub(crate) fn mul_unit<S: Scalar>(x: S, s: S) -> S {
    x.mul_unit_range(s)
}

/// The nominal friction model of eq. (4.17) and its boundary layer,
/// quantized for backend `S`; the parameters themselves are passed per
/// call (they are adapted at run time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionConfig<S> {
    eps: S,
    inv_eps: Coef,
    /// `1/ε_q̇` as a stored value when it is at most 2¹⁴ (every layer above
    /// 6.1e-5 rad/s): inside the layer `|q̇| ≤ ε_q̇`, so on `I16F16` the
    /// product `q̇ · (1/ε_q̇)` has an operand below 0.5 and takes the
    /// two-multiply path of the `I16F16` product; `None` falls back to the
    /// coefficient product.
    inv_eps_value: Option<S>,
}

/// The nominal friction torque and regressor at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionEval<S> {
    /// `f̂^c(q̇)` of eq. (4.17), stored motor-torque units.
    pub torque: S,
    /// `Y(q̇)` of eq. (4.17), stored regressor units
    /// (`[speed, 1, 1, motor torque · speed²]`).
    pub regressor: [S; 4],
}

impl<S: Scalar> FrictionConfig<S> {
    /// Quantize the velocity boundary layer `ε_q̇` (rad/s, > 0; validated by
    /// the owning component).
    pub fn new(eps_velocity: f64) -> Self {
        let eps = S::from_f64(eps_velocity * S::UNITS.speed);
        let inv = 1.0 / eps.to_f64();
        let (one, minus_one) = (S::ONE, S::ONE.neg());
        // `1/ε` at most rounded down so that `±ε·(1/ε)` stays in `[−1, 1]`:
        // `sat` then needs no clamp inside the layer.
        FrictionConfig {
            eps,
            inv_eps: slope_within(inv, Coef::new, |c| {
                eps.mul_coef(c) <= one && eps.neg().mul_coef(c) >= minus_one
            }),
            inv_eps_value: (inv <= 16384.0).then(|| {
                slope_within(inv, S::from_f64, |&v| {
                    eps.mul(v) <= one && eps.neg().mul(v) >= minus_one
                })
            }),
        }
    }

    /// The quantized boundary layer, stored speed units.
    pub fn eps_velocity(&self) -> S {
        self.eps
    }

    /// Parameters `F` (SI) as stored values for this backend.
    pub fn quantize(f: &FrictionParams) -> [S; 4] {
        let sc = parameter_scales::<S>();
        let a = f.to_array();
        [
            S::from_f64(a[0] * sc[0]),
            S::from_f64(a[1] * sc[1]),
            S::from_f64(a[2] * sc[2]),
            S::from_f64(a[3] * sc[3]),
        ]
    }

    /// Stored parameters back to SI.
    pub fn dequantize(theta: &[S; 4]) -> FrictionParams {
        let sc = parameter_scales::<S>();
        FrictionParams::from_array([
            theta[0].to_f64() / sc[0],
            theta[1].to_f64() / sc[1],
            theta[2].to_f64() / sc[2],
            theta[3].to_f64() / sc[3],
        ])
    }

    /// `sat(q̇, ε_q̇)` of eq. (4.18), the regressor's `Y_2`, at motor speed
    /// `qd` (stored speed units, rad/s on floats; dimensionless result): in
    /// `[−1, 1]`, non-decreasing, 0 for NaN; within the rounding of the
    /// prepared `1/ε_q̇` and of one product of `q̇/ε_q̇` inside the layer.
    /// Odd on floats; on fixed point the product rounds ties up, so where
    /// `q̇/ε_q̇` falls exactly halfway between two steps `sat(−q̇)` is
    /// `−sat(q̇)` plus one LSB (never more).
    #[inline]
    pub fn sat(&self, qd: S) -> S {
        // Fixed point only (folded at compile time): a float product by the
        // coefficient is already one multiply.
        let fixed = S::RESOLUTION.to_f64() >= 1e-6;
        // Both slopes are prepared so that the layer's value stays in
        // [−1, 1] (`new`): no clamp.
        match self.inv_eps_value {
            Some(inv) if fixed => sat_in_layer(qd, self.eps, |x| x.mul(inv)),
            _ => sat_in_layer(qd, self.eps, |x| x.mul_coef(&self.inv_eps)),
        }
    }

    /// [`sat`](Self::sat) for a speed that is not NaN: the same value for
    /// every such `qd`, without the NaN test.
    #[inline(always)]
    fn sat_number(&self, qd: S) -> S {
        let fixed = S::RESOLUTION.to_f64() >= 1e-6;
        match self.inv_eps_value {
            Some(inv) if fixed => sat_in_layer_number(qd, self.eps, |x| x.mul(inv)),
            _ => sat_in_layer_number(qd, self.eps, |x| x.mul_coef(&self.inv_eps)),
        }
    }

    /// Eq. (4.17): nominal torque `f̂^c(q̇)` and regressor `Y(q̇)` at motor
    /// speed `qd` (stored speed units) for stored parameters `theta`.
    /// One exponential per call. In fixed point, `q̇²` saturates above
    /// 181 rad/s; there `e^{−f_τ q̇²}` is 0 for every admissible `f_τ`
    /// (see [`FrictionBounds::try_new`]), so the Stribeck terms vanish as
    /// they should.
    #[inline]
    pub fn evaluate(&self, theta: &[S; 4], qd: S) -> FrictionEval<S> {
        self.evaluate_with_sat(theta, qd, self.sat(qd))
    }

    /// [`evaluate`](Self::evaluate) for a speed that is not NaN (the active
    /// law's checked sample): the same value for every such `qd`; a NaN
    /// `qd` gives a NaN torque either way, with `Y_2 = ±1` (the NaN's sign
    /// bit) here instead of 0.
    #[inline(always)]
    pub(crate) fn evaluate_number(&self, theta: &[S; 4], qd: S) -> FrictionEval<S> {
        // Floats only (folded at compile time): fixed point has no NaN and
        // keeps `evaluate` (the smaller Armv6-M code).
        if S::RESOLUTION.to_f64() >= 1e-6 {
            self.evaluate(theta, qd)
        } else {
            self.evaluate_with_sat(theta, qd, self.sat_number(qd))
        }
    }

    /// Eq. (4.17) given `s = sat(q̇, ε_q̇)`.
    #[inline(always)]
    fn evaluate_with_sat(&self, theta: &[S; 4], qd: S, s: S) -> FrictionEval<S> {
        let q2 = qd.mul(qd);
        // f̂_τ q̇² ≥ 0 (f̂_τ is projected into a box of positive shapes):
        // e^{−|f̂_τ q̇²|} is e^{−f̂_τ q̇²}.
        let e = theta[3].mul(q2).exp_neg_abs();
        // Outside the velocity layer s = ±1 and its products are free.
        let es = mul_unit(e, s);
        // f̂_s e s, shared by the torque and Y_4 = −f̂_s q̇² e s.
        // |es| ≤ 1: the unit-range product.
        let stribeck = theta[2].mul_unit_range(es);
        let y4 = q2.mul(stribeck).neg();
        let torque = theta[0].mul(qd).add(mul_unit(theta[1], s)).add(stribeck);
        FrictionEval {
            torque,
            regressor: [qd, s, es, y4],
        }
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::{FrictionBounds, FrictionConfig, FrictionParams};
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, I16F16};

    const fn f64x4(r: &mut Words) -> [f64; 4] {
        [r.f64(), r.f64(), r.f64(), r.f64()]
    }

    /// `take`/`put` of a backend's configuration, with that backend's
    /// value readers and writers.
    macro_rules! stored {
        ($t:ty, $val:ident, $opt:ident) => {
            impl FrictionConfig<$t> {
                pub(crate) const fn take(r: &mut Words) -> Self {
                    FrictionConfig {
                        eps: r.$val(),
                        inv_eps: Coef::take(r),
                        inv_eps_value: r.$opt(),
                    }
                }

                #[cfg(test)]
                pub(crate) fn put(&self, s: &mut Sink) {
                    s.$val(self.eps);
                    self.inv_eps.put(s);
                    s.$opt(self.inv_eps_value);
                }
            }
        };
    }
    stored!(I16F16, fixed, option_fixed);
    stored!(f32, f32, option_f32);

    impl FrictionBounds {
        pub(crate) const fn take(r: &mut Words) -> Self {
            FrictionBounds {
                min: f64x4(r),
                max: f64x4(r),
                variable: f64x4(r),
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            for v in self.min.iter().chain(&self.max).chain(&self.variable) {
                s.f64(*v);
            }
        }
    }

    impl FrictionParams {
        pub(crate) const fn take(r: &mut Words) -> Self {
            FrictionParams {
                viscous: r.f64(),
                coulomb: r.f64(),
                stribeck: r.f64(),
                stribeck_shape: r.f64(),
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            for v in [
                self.viscous,
                self.coulomb,
                self.stribeck,
                self.stribeck_shape,
            ] {
                s.f64(v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;

    /// `contains`: the box is closed (both corners inside) and a point one
    /// `f64` step outside any face, on either side, is not.
    #[test]
    fn contains_is_the_closed_box() {
        let lo = [1e-5, 0.002, 0.004, 0.5];
        let hi = [1e-4, 0.005, 0.01, 2.0];
        let params = |a: [f64; 4]| FrictionParams {
            viscous: a[0],
            coulomb: a[1],
            stribeck: a[2],
            stribeck_shape: a[3],
        };
        let b = FrictionBounds::try_new(
            params(lo).validated().unwrap(),
            params(hi).validated().unwrap(),
            [0.0; 4],
        )
        .unwrap();
        assert!(b.contains(&params(lo)) && b.contains(&params(hi)));
        let mid = [0, 1, 2, 3].map(|j| 0.5 * (lo[j] + hi[j]));
        assert!(b.contains(&params(mid)));
        for j in 0..4 {
            let mut below = mid;
            below[j] = f64::from_bits(lo[j].to_bits() - 1);
            let mut above = mid;
            above[j] = f64::from_bits(hi[j].to_bits() + 1);
            assert!(!b.contains(&params(below)), "{j} below");
            assert!(!b.contains(&params(above)), "{j} above");
        }
    }

    /// The field paths that composite settings report for a friction
    /// field: `<composite>.<field>` for each of the four fields (written
    /// out here as the users' settings spell them), and any other name
    /// unchanged.
    #[test]
    fn composite_paths_name_the_users_field() {
        let fields = ["viscous", "coulomb", "stribeck", "stribeck_shape"];
        type Path = fn(&'static str) -> &'static str;
        let cases: [(Path, &str); 4] = [
            (min_path, "min"),
            (max_path, "max"),
            (nominal_friction_path, "nominal_friction"),
            (initial_friction_path, "initial_friction"),
        ];
        for (path, prefix) in cases {
            for f in fields {
                assert_eq!(path(f), std::format!("{prefix}.{f}"), "{prefix} {f}");
            }
            assert_eq!(path("sample_period"), "sample_period", "{prefix}");
        }
    }

    /// `validated` keeps the named fields as they are and names the field
    /// that breaks its rule.
    #[test]
    fn validated_keeps_the_fields_and_names_the_bad_one() {
        let f = FrictionParams {
            viscous: 1e-4,
            coulomb: 2e-3,
            stribeck: 3e-3,
            stribeck_shape: 4.0,
        };
        assert_eq!(f.validated(), Ok(f));
        let bad = FrictionParams {
            stribeck: -1.0,
            ..f
        };
        assert_eq!(
            bad.validated(),
            Err(ParamError::Negative {
                name: "stribeck",
                value: -1.0
            })
        );
        let bad = FrictionParams {
            stribeck_shape: 0.0,
            ..f
        };
        assert!(matches!(
            bad.validated(),
            Err(ParamError::NotPositive {
                name: "stribeck_shape",
                ..
            })
        ));
    }

    fn example() -> FrictionParams {
        FrictionParams {
            viscous: 2e-5,
            coulomb: 0.006,
            stribeck: 0.006,
            stribeck_shape: 1.0,
        }
        .validated()
        .unwrap()
    }

    #[test]
    fn try_new_names_the_bad_value() {
        assert_eq!(
            FrictionParams {
                viscous: -1.0,
                coulomb: 0.0,
                stribeck: 0.0,
                stribeck_shape: 1.0
            }
            .validated(),
            Err(ParamError::Negative {
                name: "viscous",
                value: -1.0
            })
        );
        assert!(matches!(
            FrictionParams {
                viscous: 0.0,
                coulomb: 0.0,
                stribeck: 0.0,
                stribeck_shape: 0.0
            }
            .validated(),
            Err(ParamError::NotPositive {
                name: "stribeck_shape",
                ..
            })
        ));
        assert!(matches!(
            FrictionParams {
                viscous: 0.0,
                coulomb: f64::NAN,
                stribeck: 0.0,
                stribeck_shape: 1.0
            }
            .validated(),
            Err(ParamError::NotFinite {
                name: "coulomb",
                ..
            })
        ));
        let lo = FrictionParams {
            viscous: 0.0,
            coulomb: 0.01,
            stribeck: 0.0,
            stribeck_shape: 1.0,
        }
        .validated()
        .unwrap();
        let hi = FrictionParams {
            viscous: 1e-4,
            coulomb: 0.005,
            stribeck: 0.01,
            stribeck_shape: 2.0,
        }
        .validated()
        .unwrap();
        assert!(matches!(
            FrictionBounds::try_new(lo, hi, [0.0; 4]),
            Err(ParamError::Exceeds {
                lower: "min.coulomb",
                upper: "max.coulomb",
                ..
            })
        ));
        let lo = FrictionParams {
            viscous: 0.0,
            coulomb: 0.0,
            stribeck: 0.0,
            stribeck_shape: 1e-4,
        }
        .validated()
        .unwrap();
        assert!(matches!(
            FrictionBounds::try_new(lo, hi, [0.0; 4]),
            Err(ParamError::OutOfRange {
                name: "min.stribeck_shape",
                ..
            })
        ));
        // The smallest accepted `min.stribeck_shape` is 1e-3 itself; the
        // next `f64` below it is rejected by name.
        let shape = |f_tau: f64| {
            let lo = FrictionParams {
                viscous: 0.0,
                coulomb: 0.0,
                stribeck: 0.0,
                stribeck_shape: f_tau,
            }
            .validated()
            .unwrap();
            FrictionBounds::try_new(lo, hi, [0.0; 4])
        };
        assert!(shape(1e-3).is_ok());
        assert!(matches!(
            shape(f64::from_bits(1e-3f64.to_bits() - 1)),
            Err(ParamError::OutOfRange {
                name: "min.stribeck_shape",
                ..
            })
        ));
    }

    /// Hand values: at q̇ = 0.5 rad/s with ε = 0.01 the layer is left,
    /// f = (0.006 + 0.006·e^{−0.25}) + 2e-5·0.5.
    #[test]
    fn torque_matches_hand_value_and_nominal_outside_layer() {
        let f = example();
        let want = 0.006 + 0.006 * (-0.25f64).exp() + 1e-5;
        assert!((f.torque(0.5) - want).abs() < 1e-15);
        assert!((f.nominal(0.5, 0.01) - want).abs() < 1e-15);
        assert_eq!(f.boundary_layer_residual(0.5, 0.01), 0.0);
        assert!((f.torque(-0.5) + want).abs() < 1e-15);
        assert_eq!(f.torque(0.0), 0.0);
        // Inside the layer the nominal model is the linear ramp.
        let inside = f.nominal(0.004, 0.01);
        let ramp = (0.006 + 0.006 * (-1.6e-5f64).exp()) * 0.4 + 2e-5 * 0.004;
        assert!((inside - ramp).abs() < 1e-15);
    }

    proptest! {
        /// Eq. (4.16) without parameter error: f = f̂ + f̌ exactly, and the
        /// residual obeys the bound of Assumption 6.
        #[test]
        fn model_splits_into_nominal_and_residual(
            qd in -50.0f64..50.0, eps in 1e-4f64..0.5,
            b in 0.0f64..1e-3, fc in 0.0f64..0.05, fs in 0.0f64..0.05, ft in 1e-3f64..100.0,
        ) {
            let f = FrictionParams { viscous: b, coulomb: fc, stribeck: fs, stribeck_shape: ft }.validated().unwrap();
            let sum = f.nominal(qd, eps) + f.boundary_layer_residual(qd, eps);
            prop_assert!((sum - f.torque(qd)).abs() <= 1e-15 * (1.0 + f.torque(qd).abs()));
            prop_assert!(f.boundary_layer_residual(qd, eps).abs() <= fc + fs);
        }

        /// The regressor is the gradient of the nominal model (central
        /// finite differences in each parameter).
        #[test]
        fn regressor_is_the_parameter_gradient(
            qd in -5.0f64..5.0, eps in 1e-3f64..0.1,
            b in 0.0f64..1e-3, fc in 0.0f64..0.05, fs in 1e-3f64..0.05, ft in 0.01f64..10.0,
        ) {
            let f = FrictionParams { viscous: b, coulomb: fc, stribeck: fs, stribeck_shape: ft }.validated().unwrap();
            let y = f.regressor(qd, eps);
            let a = f.to_array();
            for j in 0..4 {
                let h = 1e-6 * (1.0 + a[j].abs());
                let (mut p, mut m) = (a, a);
                p[j] += h;
                m[j] -= h;
                let fd = (FrictionParams::from_array(p).nominal(qd, eps)
                    - FrictionParams::from_array(m).nominal(qd, eps)) / (2.0 * h);
                prop_assert!((fd - y[j]).abs() <= 1e-6 * (1.0 + y[j].abs()), "j={} fd={} y={}", j, fd, y[j]);
            }
        }

        /// The backend evaluation agrees with the f64 reference evaluated
        /// on the same (quantized) speed and parameters, within a
        /// derived budget. I16F16, in stored LSB `q` of mN·m: `δs ≤ 0.6q`
        /// (product with the prepared `1/ε`), `δq̇² ≤ ½q`,
        /// `δu ≤ ½q + θ₄·½q` (`u = f_τ q̇²`), `δe ≤ q + δu` (exp kernel
        /// ≤ 1 LSB for `e^x ≤ 1`, slope ≤ 1), `δ(e s) ≤ ½q + δe + δs`, and
        /// the three products of the sum ½q each, weighted by `θ₂`, `θ₃`;
        /// plus 1 LSB for the reference. f32: ≤ 10 unit roundoffs of
        /// the sum of term magnitudes, plus `f_s`·u for the exp argument.
        #[test]
        fn backends_agree_with_reference(
            qd in -200.0f64..200.0,
            b in 0.0f64..1e-3, fc in 0.0f64..0.05, fs in 0.0f64..0.05, ft in 1e-3f64..10.0,
        ) {
            let f = FrictionParams { viscous: b, coulomb: fc, stribeck: fs, stribeck_shape: ft }.validated().unwrap();
            let eps = 0.01;
            // I16F16
            let cx = FrictionConfig::<I16F16>::new(eps);
            let thx = FrictionConfig::<I16F16>::quantize(&f);
            let qx = I16F16::from_f64(qd);
            let gx = cx.evaluate(&thx, qx).torque.to_f64();
            let fq = FrictionConfig::<I16F16>::dequantize(&thx);
            let want = fq.nominal(qx.to_f64(), cx.eps_velocity().to_f64()) * 1e3;
            let q = 1.0 / 65536.0;
            let th: [f64; 4] = [thx[0].to_f64(), thx[1].to_f64(), thx[2].to_f64(), thx[3].to_f64()];
            let ds = 0.6 * q;
            let du = 0.5 * q + th[3] * 0.5 * q;
            let de = q + du;
            let des = 0.5 * q + de + ds;
            let tol = 1.5 * q + th[1].abs() * ds + th[2].abs() * des + q;
            prop_assert!((gx - want).abs() <= tol, "{gx} vs {want} tol {tol}");
            // f32
            let c32 = FrictionConfig::<f32>::new(eps);
            let th32 = FrictionConfig::<f32>::quantize(&f);
            let g32 = c32.evaluate(&th32, qd as f32).torque as f64;
            let f32p = FrictionConfig::<f32>::dequantize(&th32);
            let want32 = f32p.nominal(qd as f32 as f64, c32.eps_velocity() as f64);
            let u = f32::EPSILON as f64 / 2.0;
            let mag = (f32p.viscous * qd).abs() + f32p.coulomb + f32p.stribeck;
            prop_assert!((g32 - want32).abs() <= 10.0 * u * mag + u * f32p.stribeck, "{g32} vs {want32}");
        }

        /// `sat_with_reciprocal` matches the division form of eq. (4.18)
        /// to one rounding, stays in [−1, 1] and is odd.
        #[test]
        fn reciprocal_sat_matches_eq_4_18(x in -1.0f64..1.0, eps in 1e-4f64..0.5) {
            let inv = Coef::new(1.0 / eps);
            let a = sat_with_reciprocal(x, eps, &inv);
            prop_assert!((a - x.sat(eps)).abs() <= 2.0 * f64::EPSILON);
            prop_assert!((-1.0..=1.0).contains(&a));
            prop_assert_eq!(sat_with_reciprocal(-x, eps, &inv), -a);
            let xf = x as f32;
            let ef = eps as f32;
            let invf = Coef::new(1.0 / ef as f64);
            let af = sat_with_reciprocal(xf, ef, &invf);
            prop_assert!((af - xf.sat(ef)).abs() <= 2.0 * f32::EPSILON);
        }

        /// The friction layer's `sat` on I16F16 (both prepared slopes: the
        /// stored `1/ε` up to ε ≈ 6.1e-5 and the coefficient beyond)
        /// matches the division form of eq. (4.18) within the rounding of
        /// `1/ε` (≤ |x|·2⁻¹⁷ ≤ ε·2⁻¹⁷), of the product (½ LSB) and of
        /// the preparation (≤ 64·2⁻²³ relative), stays in [−1, 1], is odd
        /// up to the product's tie rounding (`sat(−x) − (−sat(x)) ∈ {0, 1
        /// LSB}`, one LSB exactly at a tie: the saved regression case) and
        /// non-decreasing.
        #[test]
        fn layer_sat_matches_eq_4_18_on_i16f16(x in -1.0f64..1.0, dx in 1i32..64, eps in 2e-5f64..0.5) {
            let c = FrictionConfig::<I16F16>::new(eps);
            let e = c.eps_velocity();
            let xq = I16F16::from_f64(x);
            let a = c.sat(xq);
            let want = xq.to_f64().sat(e.to_f64());
            let q = 1.0 / 65536.0;
            let tol = 0.5 * q + e.to_f64() * q / 2.0 + 64.0 / 8_388_608.0 + 1e-12;
            prop_assert!((a.to_f64() - want).abs() <= tol, "{} vs {want}", a.to_f64());
            prop_assert!(a >= -I16F16::ONE && a <= I16F16::ONE);
            let odd = c.sat(xq.neg()).to_bits() - a.neg().to_bits();
            prop_assert!(odd == 0 || odd == 1, "sat(−x) + sat(x) = {odd} LSB");
            let up = I16F16::from_bits(xq.to_bits().saturating_add(dx));
            prop_assert!(c.sat(up) >= a);
        }
    }

    /// The prepared slopes keep the layer's value in [−1, 1] without a
    /// clamp: at every I16F16 layer width from 1 LSB to 0.5 rad/s (the
    /// edge `±ε` is the extreme, the product being monotone) and at 20,000
    /// f32 and f64 widths.
    #[test]
    fn prepared_layer_slope_never_exceeds_one() {
        for bits in 1..=32768i32 {
            let eps = I16F16::from_bits(bits).to_f64();
            let c = FrictionConfig::<I16F16>::new(eps);
            let e = c.eps_velocity();
            assert_eq!(e.to_bits(), bits);
            for x in [e, e.neg()] {
                let s = c.sat(x);
                assert!(s.abs() <= I16F16::ONE, "ε bits {bits}: sat = {s}");
            }
            // Just inside and outside the layer.
            assert_eq!(c.sat(I16F16::from_bits(bits + 1)), I16F16::ONE);
            assert!(c.sat(I16F16::from_bits(bits - 1)) <= I16F16::ONE);
        }
        let mut w = 1e-5f64;
        for _ in 0..20_000 {
            w *= 1.0004;
            let c = FrictionConfig::<f32>::new(w);
            let e = c.eps_velocity();
            assert!(c.sat(e) <= 1.0 && c.sat(-e) >= -1.0, "f32 ε {e}");
            let c = FrictionConfig::<f64>::new(w);
            let e = c.eps_velocity();
            assert!(c.sat(e) <= 1.0 && c.sat(-e) >= -1.0, "f64 ε {e}");
        }
    }

    #[test]
    fn split_and_boundary_layer_bound() {
        let lo = FrictionParams {
            viscous: 0.0,
            coulomb: 0.0,
            stribeck: 0.0,
            stribeck_shape: 0.01,
        }
        .validated()
        .unwrap();
        let hi = FrictionParams {
            viscous: 1e-4,
            coulomb: 0.012,
            stribeck: 0.012,
            stribeck_shape: 10.0,
        }
        .validated()
        .unwrap();
        let bx = FrictionBounds::try_new(lo, hi, [1e-3, 1e-2, 1e-2, 1.0]).unwrap();
        let inside = FrictionParams {
            viscous: 5e-5,
            coulomb: 0.006,
            stribeck: 0.006,
            stribeck_shape: 1.0,
        }
        .validated()
        .unwrap();
        let (c, v, ok) = bx.split(&inside);
        assert!(ok && v == [0.0; 4] && c == inside.to_array());
        let outside = FrictionParams {
            viscous: 5e-5,
            coulomb: 0.015,
            stribeck: 0.006,
            stribeck_shape: 1.0,
        }
        .validated()
        .unwrap();
        let (c, v, ok) = bx.split(&outside);
        assert!(ok && (c[1] - 0.012).abs() < 1e-15 && (v[1] - 0.003).abs() < 1e-15);
        let far = FrictionParams {
            viscous: 5e-5,
            coulomb: 0.03,
            stribeck: 0.006,
            stribeck_shape: 1.0,
        }
        .validated()
        .unwrap();
        assert!(!bx.split(&far).2);
        // ρ_f = (0.012 + 0.01) + (0.012 + 0.01), and it bounds f̌ for the
        // extreme admissible parameters just inside the layer.
        assert!((bx.boundary_layer_bound() - 0.044).abs() < 1e-15);
        let extreme = FrictionParams {
            viscous: 1e-4,
            coulomb: 0.0219,
            stribeck: 0.0219,
            stribeck_shape: 0.01,
        }
        .validated()
        .unwrap();
        let r = extreme.boundary_layer_residual(1e-9, 0.01);
        assert!(r < bx.boundary_layer_bound() && r > 0.0438 * 0.99);
    }

    /// Property 1 (eq. 4.10) is strict: a variable part of exactly `ρ_F`
    /// (here 0.25, every value exact in `f64`) breaks it, half of it does
    /// not, on either side of the box.
    #[test]
    fn split_rejects_a_variable_part_of_exactly_rho() {
        let p = |a: [f64; 4]| FrictionParams::from_array(a).validated().unwrap();
        let bx = FrictionBounds::try_new(p([0.5; 4]), p([1.0; 4]), [0.25; 4]).unwrap();
        for j in 0..4 {
            for (x, holds) in [(1.25, false), (1.125, true), (0.25, false), (0.375, true)] {
                let mut a = [0.75; 4];
                a[j] = x;
                let (c, v, ok) = bx.split(&FrictionParams::from_array(a));
                assert_eq!(ok, holds, "component {j} at {x}");
                assert_eq!(c[j] + v[j], x);
            }
        }
    }

    /// The stored parameters are in the documented units (the table of
    /// `scalar::units`): on `I16F16` `b` in mN·m·s/rad, `f_c` and `f_s`
    /// in mN·m, `f_τ` in s²/rad² (speeds are stored in rad/s); floats
    /// store SI. Each stored value is the SI value times that scale to
    /// half an LSB, and back to SI to the same, and the `I16F16` torque
    /// read in N·m agrees with the `f64` torque.
    #[test]
    fn quantize_stores_the_documented_units() {
        let f = FrictionParams {
            viscous: 1e-3,
            coulomb: 0.012,
            stribeck: 0.006,
            stribeck_shape: 0.25,
        };
        let scale = [1e3, 1e3, 1e3, 1.0];
        let q = I16F16::RESOLUTION.to_f64();
        let stored = FrictionConfig::<I16F16>::quantize(&f);
        let back = FrictionConfig::<I16F16>::dequantize(&stored).to_array();
        for j in 0..4 {
            let want = f.to_array()[j] * scale[j];
            assert!(
                (stored[j].to_f64() - want).abs() <= q / 2.0,
                "component {j}"
            );
            let si = f.to_array()[j];
            assert!((back[j] - si).abs() <= q / 2.0 / scale[j], "component {j}");
        }
        assert_eq!(FrictionConfig::<f64>::quantize(&f), f.to_array());
        assert_eq!(FrictionConfig::<f64>::dequantize(&f.to_array()), f);
        let s32 = FrictionConfig::<f32>::quantize(&f);
        assert_eq!(s32, f.to_array().map(|x| x as f32));
        // The torque at 2 rad/s (outside the layer), read in N·m.
        let c = FrictionConfig::<I16F16>::new(0.01);
        let t = c.evaluate(&stored, I16F16::from_f64(2.0)).torque.to_f64() / 1e3;
        let want = FrictionConfig::<f64>::new(0.01)
            .evaluate(&f.to_array(), 2.0)
            .torque;
        assert!((t - want).abs() < 1e-6, "{t} vs {want}");
    }

    /// On `I16F16` the layer's value is the `I16F16` product of `q̇` and
    /// the stored slope `1/ε` when the slope is stored (the fast path the
    /// field's docs promise), and the coefficient product otherwise; the
    /// widths below include values where the two products differ by an
    /// LSB, so taking the other path fails. `sat_number` and
    /// `evaluate_number` give the same values. On floats the stored slope
    /// and the coefficient are the same float, so the two paths are one
    /// product there.
    #[test]
    fn layer_products_take_the_documented_path() {
        let theta = FrictionConfig::<I16F16>::quantize(&example());
        for eps in [2e-5, 0.0123, 0.3] {
            let c = FrictionConfig::<I16F16>::new(eps);
            let e = c.eps.to_bits();
            let mut differ = 0;
            for bits in -e - 3..=e + 3 {
                let x = I16F16::from_bits(bits);
                let by_coef = x.mul_coef(&c.inv_eps);
                let inside = match c.inv_eps_value {
                    Some(v) => {
                        differ += usize::from(x.mul(v) != by_coef);
                        x.mul(v)
                    }
                    None => by_coef,
                };
                let want = if bits.abs() <= e {
                    inside
                } else if bits > 0 {
                    I16F16::ONE
                } else {
                    I16F16::ONE.neg()
                };
                assert_eq!(c.sat(x), want, "ε {eps}, q̇ bits {bits}");
                assert_eq!(c.sat_number(x), want, "ε {eps}, q̇ bits {bits}");
                assert_eq!(c.evaluate_number(&theta, x), c.evaluate(&theta, x));
            }
            assert_eq!(c.inv_eps_value.is_some(), eps > 1e-4, "ε {eps}");
            if eps > 0.01 {
                assert!(differ > 0, "ε {eps}: the two products never differ");
            }
        }
        for eps in [1e-4, 0.0123, 0.3] {
            let c = FrictionConfig::<f32>::new(eps);
            assert_eq!(c.inv_eps_value, Some(1.0f32.mul_coef(&c.inv_eps)));
            let c = FrictionConfig::<f64>::new(eps);
            assert_eq!(c.inv_eps_value, Some(1.0f64.mul_coef(&c.inv_eps)));
            let theta = example().to_array();
            for k in -40..=40 {
                let x = k as f64 * eps / 16.0;
                assert_eq!(c.evaluate_number(&theta, x), c.evaluate(&theta, x));
            }
        }
    }

    /// `sat_with_reciprocal` with `ε ≤ 0` (an empty layer) is the sign
    /// function, 0 at 0, on every backend.
    #[test]
    fn reciprocal_sat_with_an_empty_layer_is_the_sign() {
        fn check<S: Scalar>() {
            for eps in [0.0, -0.1] {
                let inv = Coef::new(1.0 / eps);
                let sat = |x: f64| sat_with_reciprocal(S::from_f64(x), S::from_f64(eps), &inv);
                assert_eq!(sat(0.0), S::ZERO, "ε {eps}");
                for x in [0.05, 2.0] {
                    assert_eq!(sat(x), S::ONE, "ε {eps}, x {x}");
                    assert_eq!(sat(-x), S::ONE.neg(), "ε {eps}, x {x}");
                }
            }
        }
        check::<f32>();
        check::<f64>();
        check::<I16F16>();
    }
}
