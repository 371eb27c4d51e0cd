//! The simulated harmonic drive: a "true" transmission that is *not* the
//! estimator's model of eq. (2.30).
//!
//! Sign convention (thesis ch. 4, eq. 4.1–4.2): the motor angle `q_m` turns
//! `N` times the link angle `q_l` when rigid; the transmission torque `τ_t`
//! acts on the link (`+τ_t`) and on the rotor (`−τ_t/N`). The rigid torsion
//! is `δ = q_m/N − q_l` (positive when the motor leads). In the chapter-2
//! convention used by the estimator the link angle is `θ_fo = q_l`, the
//! motor angle `θ_wi = −q_m` (so that `θ_wi = −N θ_fo` when rigid,
//! eq. 2.4), the measured torsion is `Δθ = θ_fo + θ_wi/N = −δ`
//! (eq. 2.13) and the flexspline torque is `τ_f = −τ_t`.
//!
//! Elements, all derived from the SHD-17-100 numbers of thesis §2.4:
//!
//! 1. **Kinematic error** `θ_err(θ_fo, θ_wi)` of eq. (3.7) (Table 3.2): the
//!    measured torsion is the compliance torsion plus `θ_err` (eq. 3.8), so
//!    the torsion that loads the elastic parts is `δ_c = δ + θ_err`.
//! 2. **Elastic backbone** ([`Backbone`], chosen by [`BackboneShape`]),
//!    torque as a function of `δ_c`. The default is the catalogue's
//!    piecewise-linear curve, eq. (2.11) (library [`CataloguePiecewise`],
//!    slopes `K1, K2, K3`, knees `T1, T2`). `K3` is not in the thesis; the
//!    plant assumes `K3 = 1.3e4 N·m/rad` ([`SHD_17_100_K3`], our reading
//!    of the Harmonic Drive catalogue for size 17, ratio 100 — not checked
//!    against a catalogue copy here); the experiments stay below
//!    `T2 = 12 N·m`, where it plays no part. The other shapes (the cubic
//!    of eq. 2.10, a tanh curve fitted to the catalogue, the flexspline
//!    curve of eq. 2.26) test whether a comparison of the compliance
//!    models depends on which of them the plant happens to be built on.
//! 3. **Maxwell-slip hysteresis** in parallel with the backbone: `M`
//!    elasto-plastic elements `τ_i = clamp(k_i (δ_c − z_i), ±F_i)`. Their
//!    total slip torque is set by the catalogue's hysteresis loss: after
//!    loading to either side, the slipped elements hold `∓ΣF` and the
//!    backbone `±ΣF`, so the loop's width at zero torque is
//!    `2 τ_b⁻¹(ΣF) = Ψ` for backbone torque `τ_b`, i.e. `ΣF = τ_b(Ψ/2)`
//!    (on the catalogue curve `K1 Ψ/2` = 1.218 N·m). The elements share
//!    it equally and their presliding displacements `F_i/k_i` are spread
//!    uniformly over `(0, Ψ/2]` — the thesis's bound on the wave generator's
//!    one-sided deformation (eq. 2.36).
//!
//! The generalized forces follow from the potential of the elastic parts as
//! functions of `δ_c(q_l, q_m)`, including the kinematic error's gradient,
//! so the plant is conservative when the hysteresis is switched off.

use crate::error::{increasing, positive, ParamError};
use crate::harmonic_drive::{
    kinematic_error::KinematicErrorModel, CatalogueCurve, CatalogueData, CataloguePiecewise,
    CubicStiffness, FlexsplineParams,
};

/// `K3` of the SHD-17-100 (N·m/rad) assumed by the plant (see the module
/// docs); the thesis gives only `K1`, `K2`, `T1`, `T2`.
pub const SHD_17_100_K3: f64 = 1.3e4;

/// Which elastic backbone the simulated drive is built on (see
/// [`Backbone::from_catalogue`] for how each is fitted to the catalogue).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BackboneShape {
    /// The catalogue's piecewise-linear curve, eq. (2.11).
    CataloguePiecewise,
    /// The cubic of eq. (2.10) through the catalogue's two knees.
    CubicThroughKnees,
    /// A smooth curve that is none of the compared models: slope `K1` at
    /// zero, `K2` asymptotically, through the catalogue's `T2` knee.
    TanhThroughT2,
    /// The proposed model's flexspline curve, eq. (2.26), with `K_f0`,
    /// `c_f` identified by eq. (2.33)–(2.34).
    IdentifiedFlexspline,
}

impl BackboneShape {
    /// Every shape, the catalogue curve first.
    pub const ALL: [BackboneShape; 4] = [
        BackboneShape::CataloguePiecewise,
        BackboneShape::CubicThroughKnees,
        BackboneShape::TanhThroughT2,
        BackboneShape::IdentifiedFlexspline,
    ];

    /// A short label for tables.
    pub fn name(self) -> &'static str {
        match self {
            BackboneShape::CataloguePiecewise => "piecewise (2.11)",
            BackboneShape::CubicThroughKnees => "cubic (2.10)",
            BackboneShape::TanhThroughT2 => "tanh, fitted",
            BackboneShape::IdentifiedFlexspline => "flexspline atan (2.26)",
        }
    }
}

/// A smooth stiffening curve, torque (N·m) from torsion `δ` (rad):
///
/// ```text
/// τ(δ) = K_∞ δ − (K_∞ − K_0) w tanh(δ/w)
/// ```
///
/// local stiffness `K_∞ − (K_∞ − K_0) sech²(δ/w)`, from `K_0` at zero to
/// `K_∞` for `|δ| ≫ w`. Not a model of the thesis: a plant shape that
/// favours none of the compared models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TanhStiffness {
    /// Stiffness at zero torsion `K_0`, N·m/rad.
    pub k0: f64,
    /// Asymptotic stiffness `K_∞`, N·m/rad (`> K_0`).
    pub k_inf: f64,
    /// Transition width `w`, rad.
    pub width: f64,
}

impl TanhStiffness {
    /// The tanh curve fitted to a catalogue curve: `K_0 = K1`,
    /// `K_∞ = K2`, and `w` such that the curve passes through the `T2`
    /// knee `(δ2, T2)`, i.e. `w tanh(δ2/w) = (K2 δ2 − T2)/(K2 − K1)`,
    /// which on the catalogue curve equals `δ1 = T1/K1` (the asymptote is
    /// then that of the catalogue's second piece, shifted by `w − δ1`).
    /// `w tanh(δ2/w)` increases from 0 to `δ2` with `w`, and
    /// `0 < δ1 < δ2`, so bisection finds the unique `w`. Fails with
    /// [`ParamError::NotIncreasing`] unless `K1 < K2`.
    pub fn through_t2_knee(c: &CataloguePiecewise) -> Result<Self, ParamError> {
        let (d1, d2) = (c.torsion_at_t1(), c.torsion_at_t2());
        let (k0, t1) = (c.local_stiffness(0.0), c.torque(d1));
        let k_inf = c.local_stiffness(0.5 * (t1 + c.torque(d2)));
        increasing(("k1", k0), ("k2", k_inf))?;
        let target = d1;
        let g = |w: f64| w * libm::tanh(d2 / w);
        let (mut lo, mut hi) = (0.0, d2);
        while g(hi) <= target {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let width = positive("width", 0.5 * (lo + hi))?;
        Ok(TanhStiffness { k0, k_inf, width })
    }

    /// Torque (N·m) at torsion `δ` (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        self.k_inf * torsion
            - (self.k_inf - self.k0) * self.width * libm::tanh(torsion / self.width)
    }

    /// Local stiffness `dτ/dδ` (N·m/rad).
    pub fn local_stiffness(&self, torsion: f64) -> f64 {
        let c = libm::cosh(torsion / self.width);
        self.k_inf - (self.k_inf - self.k0) / (c * c)
    }

    /// Stored energy `∫₀^δ τ dx = K_∞ δ²/2 − (K_∞ − K_0) w² ln cosh(δ/w)`
    /// (J), with `ln cosh x = |x| + ln((1 + e^{−2|x|})/2)` so that large
    /// arguments do not overflow.
    pub fn energy(&self, torsion: f64) -> f64 {
        let x = (torsion / self.width).abs();
        let ln_cosh = x + libm::log1p(libm::exp(-2.0 * x)) - core::f64::consts::LN_2;
        0.5 * self.k_inf * torsion * torsion
            - (self.k_inf - self.k0) * self.width * self.width * ln_cosh
    }
}

/// The flexspline curve of eq. (2.26) used as a plant backbone: the
/// torque of eq. (3.10), `τ = tan(c_f K_f0 δ)/c_f`, up to the torsion
/// `δ_L = 0.8 π/(2 c_f K_f0)` (68 N·m on the SHD-17-100, far beyond the
/// experiments), continued linearly with the slope there so that the
/// plant never meets the pole of `tan`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexsplineBackbone {
    /// The flexspline parameters, eq. (2.24).
    pub flexspline: FlexsplineParams,
}

impl FlexsplineBackbone {
    /// Share of the largest flexspline torsion where the linear
    /// continuation starts.
    const LIMIT_SHARE: f64 = 0.8;

    fn limit(&self) -> f64 {
        Self::LIMIT_SHARE * self.flexspline.max_torsion()
    }

    fn ck(&self) -> f64 {
        self.flexspline.c_f() * self.flexspline.k_f0()
    }

    /// Torque (N·m) at torsion `δ` (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        let (d, l) = (torsion.abs(), self.limit());
        let t = if d <= l {
            self.flexspline.torque(d).torque
        } else {
            self.flexspline.torque(l).torque + self.stiffness_abs(l) * (d - l)
        };
        t.copysign(torsion)
    }

    fn stiffness_abs(&self, d: f64) -> f64 {
        let tan = libm::tan(self.ck() * d.min(self.limit()));
        self.flexspline.k_f0() * (1.0 + tan * tan)
    }

    /// Local stiffness `K_f0 (1 + tan²(c_f K_f0 δ))` (N·m/rad), eq. (2.24)
    /// written in the torsion; constant beyond `δ_L`.
    pub fn local_stiffness(&self, torsion: f64) -> f64 {
        self.stiffness_abs(torsion.abs())
    }

    /// Stored energy (J): `∫₀^δ tan(c K x)/c dx = −ln cos(c K δ)/(c² K)`
    /// up to `δ_L`, plus `τ_L x + K_L x²/2` for the linear part
    /// (`x = |δ| − δ_L`).
    pub fn energy(&self, torsion: f64) -> f64 {
        let (d, l) = (torsion.abs(), self.limit());
        let c = self.flexspline.c_f();
        let v = |x: f64| -libm::log(libm::cos(self.ck() * x)) / (c * c * self.flexspline.k_f0());
        if d <= l {
            v(d)
        } else {
            let x = d - l;
            v(l) + self.flexspline.torque(l).torque * x + 0.5 * self.stiffness_abs(l) * x * x
        }
    }
}

/// The elastic backbone of the simulated drive: an odd, increasing torque
/// (N·m, on the link) of the compliance torsion `δ_c` (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Backbone {
    /// Eq. (2.11), inverted exactly.
    CataloguePiecewise(CataloguePiecewise),
    /// Eq. (2.10).
    Cubic(CubicStiffness),
    /// [`TanhStiffness`].
    Tanh(TanhStiffness),
    /// Eq. (2.26) inverted, eq. (3.10) ([`FlexsplineBackbone`]).
    Flexspline(FlexsplineBackbone),
}

impl Backbone {
    /// Torsion (rad) at `torque` (N·m) by bisection on the increasing
    /// torque curve over ±10 mrad (100 halvings: exact to the last bit of
    /// the bracket), independent of every model's own closed-form inverse;
    /// the experiments and their tests use it as the ground-truth curve.
    pub fn torsion_by_bisection(&self, torque: f64) -> f64 {
        let (mut lo, mut hi) = (-1e-2, 1e-2);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.torque(mid) < torque {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The backbone of `shape` fitted to catalogue data (`k3` completes
    /// the piecewise curve): the catalogue curve itself; the cubic through
    /// its knees ([`CubicStiffness::through_catalogue_knees`]); the tanh
    /// curve through its `T2` knee ([`TanhStiffness::through_t2_knee`]);
    /// the flexspline curve identified by eq. (2.33)–(2.34)
    /// ([`CatalogueData::identify`]). Errors are those of the fits.
    pub fn from_catalogue(
        shape: BackboneShape,
        data: &CatalogueData,
        k3: f64,
    ) -> Result<Self, ParamError> {
        let piecewise = CataloguePiecewise::try_new(CatalogueCurve {
            k1: data.k1,
            k2: data.k2,
            k3,
            t1: data.t1,
            t2: data.t2,
        })?;
        Ok(match shape {
            BackboneShape::CataloguePiecewise => Backbone::CataloguePiecewise(piecewise),
            BackboneShape::CubicThroughKnees => {
                Backbone::Cubic(CubicStiffness::through_catalogue_knees(&piecewise)?)
            }
            BackboneShape::TanhThroughT2 => {
                Backbone::Tanh(TanhStiffness::through_t2_knee(&piecewise)?)
            }
            BackboneShape::IdentifiedFlexspline => Backbone::Flexspline(FlexsplineBackbone {
                flexspline: data.identify()?.flexspline(),
            }),
        })
    }

    /// Torque (N·m) at compliance torsion `δ_c` (rad).
    pub fn torque(&self, torsion: f64) -> f64 {
        match self {
            Backbone::CataloguePiecewise(b) => b.torque(torsion),
            Backbone::Cubic(b) => b.torque(torsion),
            Backbone::Tanh(b) => b.torque(torsion),
            Backbone::Flexspline(b) => b.torque(torsion),
        }
    }

    /// Local stiffness `dτ/dδ_c` (N·m/rad) at torsion `δ_c` (rad).
    pub fn local_stiffness(&self, torsion: f64) -> f64 {
        match self {
            Backbone::CataloguePiecewise(b) => b.local_stiffness(b.torque(torsion)),
            Backbone::Cubic(b) => b.local_stiffness(torsion),
            Backbone::Tanh(b) => b.local_stiffness(torsion),
            Backbone::Flexspline(b) => b.local_stiffness(torsion),
        }
    }

    /// Stored energy `∫₀^δ τ(x) dx` (J) at torsion `δ_c` (rad), in closed
    /// form per shape: piecewise `K1 δ²/2`, then `T1 x + K2 x²/2` past
    /// `δ1` and `T2 x + K3 x²/2` past `δ2`; cubic `a1 δ²/2 + a3 δ⁴/4`;
    /// [`TanhStiffness::energy`]; [`FlexsplineBackbone::energy`].
    pub fn energy(&self, torsion: f64) -> f64 {
        match self {
            Backbone::CataloguePiecewise(b) => {
                let d = torsion.abs();
                let (d1, d2) = (b.torsion_at_t1(), b.torsion_at_t2());
                let (t1, t2) = (b.torque(d1), b.torque(d2));
                let k1 = b.local_stiffness(0.0);
                let k2 = b.local_stiffness(0.5 * (t1 + t2));
                let k3 = b.local_stiffness(2.0 * t2);
                let mut v = 0.5 * k1 * d.min(d1).powi(2);
                if d > d1 {
                    let x = d.min(d2) - d1;
                    v += t1 * x + 0.5 * k2 * x * x;
                }
                if d > d2 {
                    let x = d - d2;
                    v += t2 * x + 0.5 * k3 * x * x;
                }
                v
            }
            Backbone::Cubic(b) => {
                let d2 = torsion * torsion;
                0.5 * b.a1() * d2 + 0.25 * b.a3() * d2 * d2
            }
            Backbone::Tanh(b) => b.energy(torsion),
            Backbone::Flexspline(b) => b.energy(torsion),
        }
    }
}

/// One Maxwell-slip element: stiffness (N·m/rad) and slip torque (N·m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipElement {
    /// Presliding stiffness `k_i`, N·m/rad.
    pub stiffness: f64,
    /// Slip torque `F_i`, N·m.
    pub slip_torque: f64,
}

/// Parameters of the simulated transmission.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivePlantParams {
    /// Gear ratio `N`.
    pub ratio: f64,
    /// Elastic backbone.
    pub backbone: Backbone,
    /// Maxwell-slip elements (empty: purely elastic).
    pub slip_elements: Vec<SlipElement>,
    /// True kinematic error, eq. (3.7), or `None`.
    pub kinematic_error: Option<KinematicErrorModel>,
}

impl DrivePlantParams {
    /// The plant derived from catalogue data (see the module docs) on a
    /// backbone of `shape` with `elements` Maxwell-slip elements of total
    /// slip torque `τ_b(Ψ/2)` and an optional kinematic error.
    pub fn from_catalogue(
        data: &CatalogueData,
        k3: f64,
        shape: BackboneShape,
        elements: usize,
        kinematic_error: Option<KinematicErrorModel>,
    ) -> Result<Self, ParamError> {
        let backbone = Backbone::from_catalogue(shape, data, k3)?;
        let total = backbone.torque(data.hysteresis_loss / 2.0);
        let slip_elements = (1..=elements)
            .map(|i| {
                let f = total / elements as f64;
                let x = i as f64 / elements as f64 * data.hysteresis_loss / 2.0;
                SlipElement {
                    stiffness: f / x,
                    slip_torque: f,
                }
            })
            .collect();
        Ok(DrivePlantParams {
            ratio: data.ratio,
            backbone,
            slip_elements,
            kinematic_error,
        })
    }

    /// The SHD-17-100 of thesis §2.4 on the catalogue backbone, with 8
    /// slip elements and the Table 3.2 kinematic error.
    pub fn shd_17_100() -> Self {
        Self::shd_17_100_on(BackboneShape::CataloguePiecewise)
    }

    /// The same on a backbone of another shape.
    pub fn shd_17_100_on(shape: BackboneShape) -> Self {
        Self::from_catalogue(
            &CatalogueData::SHD_17_100,
            SHD_17_100_K3,
            shape,
            8,
            Some(KinematicErrorModel::table_3_2()),
        )
        .expect("catalogue constants are valid")
    }

    /// The same without hysteresis and kinematic error (elastic backbone
    /// only).
    pub fn elastic(&self) -> Self {
        DrivePlantParams {
            slip_elements: Vec::new(),
            kinematic_error: None,
            ..self.clone()
        }
    }

    /// Total slip torque `ΣF_i`, N·m.
    pub fn total_slip_torque(&self) -> f64 {
        self.slip_elements.iter().map(|e| e.slip_torque).sum()
    }

    /// Small-amplitude stiffness at zero torque (the backbone's slope at
    /// zero, `K1` on the catalogue curve, plus every element's `k_i`),
    /// N·m/rad.
    pub fn micro_stiffness(&self) -> f64 {
        self.backbone.local_stiffness(0.0)
            + self.slip_elements.iter().map(|e| e.stiffness).sum::<f64>()
    }

    /// Kinematic error `θ_err` (rad) and its partial derivatives with
    /// respect to `θ_fo` and `θ_wi`, eq. (3.7), at link angle `q_l` and
    /// motor angle `q_m` (chapter-4 angles).
    pub fn kinematic_error(&self, q_l: f64, q_m: f64) -> (f64, f64, f64) {
        match &self.kinematic_error {
            None => (0.0, 0.0, 0.0),
            Some(k) => {
                let c = &k.coefficients();
                let (sl, cl) = libm::sincos(q_l);
                let (s1, c1) = libm::sincos(-q_m);
                let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
                let value = k.evaluate(q_l, -q_m);
                let d_link = -c[1] * sl + c[2] * cl;
                let d_motor = -c[3] * s1 + c[4] * c1 - 2.0 * c[5] * s2 + 2.0 * c[6] * c2;
                (value, d_link, d_motor)
            }
        }
    }

    /// Compliance torsion `δ_c = q_m/N − q_l + θ_err` (rad) and its partial
    /// derivatives `(∂δ_c/∂q_l, ∂δ_c/∂q_m)`: eq. (3.8) read backwards — the
    /// encoder torsion of eq. (2.13), `Δθ = q_l − q_m/N`, is the compliance
    /// torsion `−δ_c` plus the kinematic error of eq. (3.7).
    pub fn compliance_torsion(&self, q_l: f64, q_m: f64) -> (f64, f64, f64) {
        let (e, d_l, d_w) = self.kinematic_error(q_l, q_m);
        (
            q_m / self.ratio - q_l + e,
            -1.0 + d_l,
            1.0 / self.ratio - d_w,
        )
    }

    /// Transmission torque `τ_t` (N·m, on the link) at compliance torsion
    /// `δ_c` with slip anchors `z` (one per element): the inverse of the
    /// backbone plus the Maxwell-slip elements.
    pub fn torque(&self, delta_c: f64, anchors: &[f64]) -> f64 {
        let mut t = self.backbone.torque(delta_c);
        for (e, z) in self.slip_elements.iter().zip(anchors) {
            t += (e.stiffness * (delta_c - z)).clamp(-e.slip_torque, e.slip_torque);
        }
        t
    }

    /// Move the slip anchors after a step (plastic part of each element).
    pub fn update_anchors(&self, delta_c: f64, anchors: &mut [f64]) {
        for (e, z) in self.slip_elements.iter().zip(anchors.iter_mut()) {
            let x = e.slip_torque / e.stiffness;
            if delta_c - *z > x {
                *z = delta_c - x;
            } else if delta_c - *z < -x {
                *z = delta_c + x;
            }
        }
    }

    /// Elastic energy (J) of the backbone at torsion `δ_c`
    /// ([`Backbone::energy`]) plus that stored in the slip elements,
    /// `τ_i²/(2k_i)`.
    pub fn elastic_energy(&self, delta_c: f64, anchors: &[f64]) -> f64 {
        let mut v = self.backbone.energy(delta_c);
        for (e, z) in self.slip_elements.iter().zip(anchors) {
            let t = (e.stiffness * (delta_c - z)).clamp(-e.slip_torque, e.slip_torque);
            v += t * t / (2.0 * e.stiffness);
        }
        v
    }
}

/// A drive with the structure of thesis Fig. 2.7 / Fig. 2.9: two
/// compliances in series with the mesh friction acting on the node between
/// them, all torques and torsions link-side (chapter-4 signs: positive
/// motor torque, positive torsion `δ`).
///
/// * The **wave-generator compliance** carries the motor torque: with the
///   link-equivalent torque `T = N τ_m` it twists by
///   `g_w(T) = sgn(T) (Ψ_s/2)(1 − e^{−|T|/T_w})`, the shape of eq. (2.29),
///   with `T_w = N τ_fs` (eq. 2.37's `c_w = 1/τ_fs` after errata E2.4).
/// * The **mesh friction** holds the node between the two compliances:
///   the flexspline torque `τ` follows `T` as a play operator of half
///   width `F`, `τ ← clamp(τ, T − F, T + F)` (the clamp of errata E2.5).
/// * The **flexspline compliance** is whatever makes the catalogue-style
///   test match the catalogue: with the input held and a torque `τ`
///   cycled on the output, the wave generator carries `τ ∓ F` on the
///   slipping branches, so the loop's centreline is
///   `f(τ) + [g_w(τ + F) + g_w(τ − F)]/2` and its width at zero torque
///   `2 g_w(F)`. Choosing `Ψ_s` so that `2 g_w(F) = Ψ` and
///   `f(τ) = cat(τ) − [g_w(τ + F) + g_w(τ − F)]/2` (with `cat` the
///   catalogue curve, eq. 2.11) makes that loop the catalogue's: centred
///   on eq. (2.11), `Ψ` wide at zero torque, narrowing as the wave
///   generator stiffens, as Fig. 2.10 draws it.
///
/// This is the plant eq. (2.30) is built for (its wave-generator term is
/// the plant's `g_w` up to `Ψ_s`); it has no rotor, kinematic error or
/// sensor noise, and is evaluated quasi-statically (see
/// [`locked_output_mesh_friction`](super::experiments::locked_output_mesh_friction)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshFrictionPlant {
    /// Gear ratio `N`.
    pub ratio: f64,
    /// The catalogue curve the catalogue-style test reproduces.
    pub catalogue: CataloguePiecewise,
    /// Mesh friction `F`, link-side N·m.
    pub mesh_friction: f64,
    /// Wave-generator torque scale `T_w`, link-side N·m.
    pub wave_generator_scale: f64,
    /// Wave-generator saturation torsion `Ψ_s/2`, rad.
    pub wave_generator_saturation: f64,
}

impl MeshFrictionPlant {
    /// The plant for catalogue `data` (with `k3`) and mesh friction `F`
    /// (N·m, link side); `T_w = N τ_fs`, `Ψ_s/2 = (Ψ/2)/(1 − e^{−F/T_w})`.
    ///
    /// Errors: invalid catalogue numbers; `F ≤ 0`; a flexspline curve that
    /// would not increase (checked on a grid of 0.01 N·m up to `2 T2 + F`).
    pub fn from_catalogue(
        data: &CatalogueData,
        k3: f64,
        mesh_friction: f64,
    ) -> Result<Self, ParamError> {
        let catalogue = CataloguePiecewise::try_new(CatalogueCurve {
            k1: data.k1,
            k2: data.k2,
            k3,
            t1: data.t1,
            t2: data.t2,
        })?;
        let mesh_friction = positive("mesh_friction", mesh_friction)?;
        let scale = positive("starting_torque", data.ratio * data.starting_torque)?;
        let plant = MeshFrictionPlant {
            ratio: data.ratio,
            catalogue,
            mesh_friction,
            wave_generator_scale: scale,
            wave_generator_saturation: 0.5 * data.hysteresis_loss
                / (1.0 - libm::exp(-mesh_friction / scale)),
        };
        let top = 2.0 * data.t2 + mesh_friction;
        let mut prev = plant.flexspline_torsion(0.0);
        for k in 1..=(top / 0.01) as usize {
            let next = plant.flexspline_torsion(k as f64 * 0.01);
            if next <= prev {
                return Err(ParamError::NotRepresentable {
                    name: "mesh_friction",
                    value: mesh_friction,
                });
            }
            prev = next;
        }
        Ok(plant)
    }

    /// The SHD-17-100 of §2.4 with the mesh friction equal to the measured
    /// back-driving torque `τ_fb = 2.0 N·m`.
    pub fn shd_17_100() -> Self {
        Self::from_catalogue(&CatalogueData::SHD_17_100, SHD_17_100_K3, 2.0)
            .expect("catalogue constants are valid")
    }

    /// Wave-generator torsion `g_w(T)` (rad) at link-equivalent torque `T`.
    pub fn wave_generator_torsion(&self, torque: f64) -> f64 {
        let m = self.wave_generator_saturation
            * (1.0 - libm::exp(-torque.abs() / self.wave_generator_scale));
        if torque < 0.0 {
            -m
        } else {
            m
        }
    }

    /// Flexspline torsion `f(τ)` (rad) at flexspline torque `τ` (N·m).
    pub fn flexspline_torsion(&self, torque: f64) -> f64 {
        let f = self.mesh_friction;
        self.catalogue.torsion(torque)
            - 0.5
                * (self.wave_generator_torsion(torque + f)
                    + self.wave_generator_torsion(torque - f))
    }

    /// The flexspline torque after the wave generator's torque moves to
    /// `wave_generator_torque` (link-equivalent, N·m) from a flexspline
    /// torque `previous`: the mesh friction's play operator.
    pub fn flexspline_torque(&self, previous: f64, wave_generator_torque: f64) -> f64 {
        previous.clamp(
            wave_generator_torque - self.mesh_friction,
            wave_generator_torque + self.mesh_friction,
        )
    }

    /// Total torsion `δ = f(τ) + g_w(T)` (rad).
    pub fn torsion(&self, flexspline_torque: f64, wave_generator_torque: f64) -> f64 {
        self.flexspline_torsion(flexspline_torque)
            + self.wave_generator_torsion(wave_generator_torque)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The catalogue-style test of the Fig. 2.7 plant, run as an
    /// experiment (input held, output torque cycled ±15 N·m through the
    /// mesh-friction play, torsion read on the two branches), reproduces
    /// the catalogue: branch midpoint = eq. (2.11), width at zero = Ψ.
    #[test]
    fn mesh_friction_plant_catalogue_test_matches_the_catalogue() {
        let p = MeshFrictionPlant::shd_17_100();
        let data = CatalogueData::SHD_17_100;
        // Output torque cycled 0 → 15 → −15 → 15 in 0.01 N·m steps; the
        // wave generator torque is the play of the output torque.
        let mut wg = 0.0;
        let mut up = Vec::new();
        let mut down = Vec::new();
        let steps = 1500;
        let path = (0..=steps)
            .map(|k| k as f64 * 0.01)
            .chain((0..=2 * steps).map(|k| 15.0 - k as f64 * 0.01))
            .chain((0..=2 * steps).map(|k| -15.0 + k as f64 * 0.01));
        for (j, tau) in path.enumerate() {
            wg = p.flexspline_torque(wg, tau); // same play, roles swapped
            let torsion = p.flexspline_torsion(tau) + p.wave_generator_torsion(wg);
            if j > steps && j <= 3 * steps + 1 {
                down.push((tau, torsion));
            } else if j > 3 * steps + 1 {
                up.push((tau, torsion));
            }
        }
        // Both branches slip everywhere 2F = 4 N·m or more from the turns.
        for t in [-10.0, -5.0, -1.0, 0.0, 2.0, 3.9, 8.0, 10.0] {
            let at = |v: &[(f64, f64)]| {
                v.iter()
                    .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
                    .unwrap()
                    .1
            };
            let (lo, hi) = (at(&up), at(&down));
            let mid = 0.5 * (lo + hi);
            assert!((mid - p.catalogue.torsion(t)).abs() < 1e-12, "{t}: {mid}");
            if t == 0.0 {
                assert!(
                    (hi - lo - data.hysteresis_loss).abs() < 1e-12,
                    "{}",
                    hi - lo
                );
            }
            assert!(hi - lo > 0.0 && hi - lo <= data.hysteresis_loss * (1.0 + 1e-12));
        }
    }

    /// The loop of the plant's compliance, driven quasi-statically by the
    /// torsion, has width Ψ at zero torque on every backbone: once every
    /// element has slipped, the elements hold `∓ΣF` at zero torque and the
    /// backbone `±ΣF = ±τ_b(Ψ/2)`, so the torsion there is `±Ψ/2`.
    #[test]
    fn loop_width_at_zero_torque_is_psi() {
        for shape in BackboneShape::ALL {
            loop_width_on(shape);
        }
    }

    fn loop_width_on(shape: BackboneShape) {
        let p = DrivePlantParams::shd_17_100_on(shape);
        let psi = CatalogueData::SHD_17_100.hysteresis_loss;
        let mut z = vec![0.0; p.slip_elements.len()];
        // Load to +8 N·m worth of torsion, then sweep down and find where
        // the torque crosses zero.
        let amp = 1.0e-3;
        let steps = 20_000;
        let mut crossing_down = f64::NAN;
        let mut crossing_up = f64::NAN;
        let mut prev = (0.0, p.torque(0.0, &z));
        for k in 0..=4 * steps {
            let phase = k as f64 / steps as f64; // 0..4 quarter cycles
            let d = amp * (phase * core::f64::consts::FRAC_PI_2).sin();
            p.update_anchors(d, &mut z);
            let t = p.torque(d, &z);
            if k > steps && prev.1 > 0.0 && t <= 0.0 {
                crossing_down = prev.0 + (d - prev.0) * prev.1 / (prev.1 - t);
            }
            prev = (d, t);
        }
        for k in 0..=2 * steps {
            let phase = k as f64 / steps as f64;
            let d = -amp * (phase * core::f64::consts::FRAC_PI_2).cos();
            p.update_anchors(d, &mut z);
            let t = p.torque(d, &z);
            if prev.1 < 0.0 && t >= 0.0 {
                crossing_up = prev.0 + (d - prev.0) * (-prev.1) / (t - prev.1);
            }
            prev = (d, t);
        }
        let width = crossing_down - crossing_up;
        assert!((width - psi).abs() < 1e-3 * psi, "{shape:?}: width {width}");
    }

    /// While every slip element sticks, the torque is the derivative of
    /// the stored energy (finite differences), so the generalized forces
    /// derived from it are conservative.
    #[test]
    fn torque_is_energy_gradient() {
        for shape in BackboneShape::ALL {
            torque_is_energy_gradient_on(shape);
        }
    }

    fn torque_is_energy_gradient_on(shape: BackboneShape) {
        let p = DrivePlantParams::shd_17_100_on(shape);
        for d in [-2e-3, -1e-4, 3e-5, 4e-4, 1.2e-3, 2.5e-3, -3.6e-3, 5e-3] {
            // Each element half-way to its slip torque.
            let z: Vec<f64> = p
                .slip_elements
                .iter()
                .map(|e| d - 0.5 * e.slip_torque / e.stiffness)
                .collect();
            let h = 1e-9;
            let fd = (p.elastic_energy(d + h, &z) - p.elastic_energy(d - h, &z)) / (2.0 * h);
            let t = p.torque(d, &z);
            assert!(
                (fd - t).abs() < 1e-5 * (1.0 + t.abs()),
                "{shape:?} {d}: {fd} vs {t}"
            );
        }
    }

    /// Composite Simpson rule of `f` over `[0, x]` with `n` (even)
    /// intervals.
    fn simpson(f: impl Fn(f64) -> f64, x: f64, n: usize) -> f64 {
        let h = x / n as f64;
        let mut s = f(0.0) + f(x);
        for i in 1..n {
            s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    /// The closed-form energy of each backbone equals the quadrature of its
    /// torque, across the catalogue knees (δ1 = 4.64e-4, δ2 = 1.33e-3 rad)
    /// and the flexspline curve's linear continuation (from 3.35e-3 rad),
    /// and is even. Simpson's error at a slope kink is of order
    /// `ΔK h²` ≈ 4e3 · (6e-3/2e5)² ≈ 4e-12 J, and 1e-9 of the energy
    /// (≥ 2e-9 J at the smallest torsion here) covers it and the rounding.
    #[test]
    fn backbone_energy_is_the_integral_of_its_torque() {
        for shape in BackboneShape::ALL {
            let b =
                Backbone::from_catalogue(shape, &CatalogueData::SHD_17_100, SHD_17_100_K3).unwrap();
            for d in [2e-5, 3e-4, 4.64e-4, 9e-4, 1.6e-3, 3.0e-3, 3.5e-3, 6e-3] {
                let q = simpson(|x| b.torque(x), d, 200_000);
                let v = b.energy(d);
                assert!(
                    (v - q).abs() <= 1e-9 * q + 1e-15,
                    "{shape:?} at {d}: {v} vs {q}"
                );
                assert_eq!(b.energy(-d), v);
                assert_eq!(b.torque(-d), -b.torque(d));
            }
        }
    }

    /// Each backbone's local stiffness is the slope of its torque (central
    /// differences, step 1e-8 rad; the curvature error `τ‴ h²/6` is below
    /// 1e-6 of the stiffness) away from the piecewise curve's kinks.
    #[test]
    fn backbone_stiffness_is_the_slope_of_its_torque() {
        for shape in BackboneShape::ALL {
            let b =
                Backbone::from_catalogue(shape, &CatalogueData::SHD_17_100, SHD_17_100_K3).unwrap();
            for d in [0.0, 2e-4, -7e-4, 1.1e-3, 2.0e-3, -3.0e-3, 4.5e-3] {
                let h = 1e-8;
                let fd = (b.torque(d + h) - b.torque(d - h)) / (2.0 * h);
                let k = b.local_stiffness(d);
                assert!((fd - k).abs() < 1e-6 * k, "{shape:?} at {d}: {fd} vs {k}");
            }
        }
    }

    /// The fitted shapes reproduce what they were fitted to: the tanh curve
    /// has slope `K1` at zero and passes through the `T2` knee; the cubic
    /// passes through both knees; the flexspline backbone is the inverse
    /// of eq. (2.26).
    #[test]
    fn fitted_backbones_meet_their_catalogue_conditions() {
        let c = CatalogueData::SHD_17_100;
        let pw = CataloguePiecewise::try_new(CatalogueCurve {
            k1: c.k1,
            k2: c.k2,
            k3: SHD_17_100_K3,
            t1: c.t1,
            t2: c.t2,
        })
        .unwrap();
        let (d1, d2) = (pw.torsion_at_t1(), pw.torsion_at_t2());
        let get = |s| Backbone::from_catalogue(s, &c, SHD_17_100_K3).unwrap();
        let tanh = get(BackboneShape::TanhThroughT2);
        assert!((tanh.local_stiffness(0.0) - c.k1).abs() < 1e-9 * c.k1);
        assert!((tanh.torque(d2) - c.t2).abs() < 1e-9 * c.t2);
        let cubic = get(BackboneShape::CubicThroughKnees);
        assert!((cubic.torque(d1) - c.t1).abs() < 1e-9 * c.t2);
        assert!((cubic.torque(d2) - c.t2).abs() < 1e-9 * c.t2);
        let flex = get(BackboneShape::IdentifiedFlexspline);
        let fs = c.identify().unwrap().flexspline();
        for t in [-12.0, 0.5, 7.0] {
            assert!((flex.torque(fs.torsion(t)) - t).abs() < 1e-9 * 12.0);
        }
    }

    /// The analytic gradient of θ_err matches finite differences.
    #[test]
    fn kinematic_error_gradient() {
        let p = DrivePlantParams::shd_17_100();
        for (l, m) in [(0.3, 17.0), (-2.0, -150.0), (5.0, 2.0)] {
            let h = 1e-6;
            let (_, dl, dw) = p.kinematic_error(l, m);
            let fl = (p.kinematic_error(l + h, m).0 - p.kinematic_error(l - h, m).0) / (2.0 * h);
            // θ_wi = −q_m
            let fw = (p.kinematic_error(l, m - h).0 - p.kinematic_error(l, m + h).0) / (2.0 * h);
            assert!((dl - fl).abs() < 1e-9 && (dw - fw).abs() < 1e-9);
        }
    }
}
