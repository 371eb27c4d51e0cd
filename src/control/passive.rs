//! Interactive-force compensation in passive mode, thesis §4.3, eq. (4.32):
//!
//! ```text
//! τ_m = f̂^c(q̇_m) + τ̂_t/N
//!       + Î_m K_p (τ_td − τ̂_t)/N
//! ```
//!
//! Friction is compensated by the nominal model of eq. (4.17) (the
//! estimates passed in, e.g. the adapted ones of the active law, or the
//! configured nominal ones), the joint torque is fed forward, and the
//! proportional term drives the joint torque toward `τ_td` (0 for a free
//! joint).
//!
//! **Eq. (4.33), corrected (errata E4.1).** Substituted into eq. (4.2) with
//! exact friction compensation, `Î_m = I_m` and `τ̂_t = τ_t`:
//! `I_m q̈_m = I_m K_p (τ_td − τ̂_t)/N`, i.e. with `τ_td = 0`
//! `(N/K_p) q̈_m + τ̂_t = 0` — a free body of inertia `N/K_p` at the motor,
//! `N²/K_p` seen from the link. Checked by
//! `closed_loop_is_a_free_body_of_inertia_n_over_kp`.
//!
//! Units: `K_p` in 1/(kg·m²) (so that `Î_m K_p` is a dimensionless torque
//! gain), `Î_m` in kg·m².

use super::ControlInput;
use crate::error::{gear_ratio, positive, ParamError};
use crate::friction::{FrictionConfig, FrictionParams};
use crate::scalar::{Coef, Scalar};

/// The parameters of eq. (4.32) by name, SI, for [`PassiveParams::try_new`]
/// (six values, five of them `f64`: named so that none can be swapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveSettings {
    /// Rotor inertia estimate `Î_m`, kg·m² (> 0).
    pub rotor_inertia: f64,
    /// Torque-feedback gain `K_p`, 1/(kg·m²) (≥ 0).
    pub gain: f64,
    /// Gear ratio `N` (≥ 1).
    pub ratio: f64,
    /// Boundary layer `ε_q̇` of the friction model's sign, rad/s
    /// (≥ 2⁻¹⁶).
    pub eps_velocity: f64,
    /// Nominal friction `f̂^c` compensated by the law (eq. 4.17).
    pub nominal_friction: FrictionParams,
    /// Motor torque limit, N·m, in `(0, 16]`.
    pub torque_limit: f64,
}

/// Parameters of eq. (4.32), SI; built only by [`try_new`](Self::try_new).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveParams {
    rotor_inertia: f64,
    gain: f64,
    ratio: f64,
    eps_velocity: f64,
    nominal_friction: FrictionParams,
    torque_limit: f64,
}

impl PassiveParams {
    /// Validate: `Î_m > 0` (kg·m²), `K_p ≥ 0` (1/(kg·m²)), `N ≥ 1`,
    /// `ε_q̇ ≥ 2⁻¹⁶` rad/s, valid nominal friction, torque limit in
    /// `(0, 16]` N·m, `Î_m K_p / N ≤ 10⁶`.
    pub fn try_new(settings: PassiveSettings) -> Result<Self, ParamError> {
        let PassiveSettings {
            rotor_inertia,
            gain,
            ratio,
            eps_velocity,
            nominal_friction,
            torque_limit,
        } = settings;
        positive("rotor_inertia", rotor_inertia)?;
        let gain = crate::error::finite("gain", gain)?;
        if gain < 0.0 {
            return Err(ParamError::Negative {
                name: "gain",
                value: gain,
            });
        }
        gear_ratio(ratio)?;
        positive("eps_velocity", eps_velocity)?;
        if eps_velocity < 1.0 / 65536.0 {
            return Err(ParamError::OutOfRange {
                name: "eps_velocity",
                value: eps_velocity,
                min: 1.0 / 65536.0,
                max: f64::INFINITY,
            });
        }
        let f = nominal_friction;
        FrictionParams {
            viscous: f.viscous,
            coulomb: f.coulomb,
            stribeck: f.stribeck,
            stribeck_shape: f.stribeck_shape,
        }
        .validated()
        .map_err(|e| e.map_names(crate::friction::nominal_friction_path))?;
        positive("torque_limit", torque_limit)?;
        if torque_limit > 16.0 {
            return Err(ParamError::OutOfRange {
                name: "torque_limit",
                value: torque_limit,
                min: 0.0,
                max: 16.0,
            });
        }
        if rotor_inertia * gain / ratio > 1e6 {
            return Err(ParamError::OutOfRange {
                name: "gain",
                value: gain,
                min: 0.0,
                max: 1e6 * ratio / rotor_inertia,
            });
        }
        Ok(PassiveParams {
            rotor_inertia,
            gain,
            ratio,
            eps_velocity,
            nominal_friction,
            torque_limit,
        })
    }

    /// The settings, by name (`try_new(p.settings()) == Ok(p)`).
    pub fn settings(&self) -> PassiveSettings {
        PassiveSettings {
            rotor_inertia: self.rotor_inertia,
            gain: self.gain,
            ratio: self.ratio,
            eps_velocity: self.eps_velocity,
            nominal_friction: self.nominal_friction,
            torque_limit: self.torque_limit,
        }
    }

    /// Rotor inertia estimate `Î_m`, kg·m².
    pub fn rotor_inertia(&self) -> f64 {
        self.rotor_inertia
    }

    /// Gear ratio `N`.
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    /// Boundary layer `ε_q̇` of the friction sign, rad/s.
    pub fn eps_velocity(&self) -> f64 {
        self.eps_velocity
    }

    /// Nominal friction compensated by the law.
    pub fn nominal_friction(&self) -> FrictionParams {
        self.nominal_friction
    }

    /// Motor torque limit, N·m.
    pub fn torque_limit(&self) -> f64 {
        self.torque_limit
    }

    /// The passive mode for the Table 4.1 joint: `Î_m = 1.14e-5 kg·m²`,
    /// `N = 100`, `ε_q̇ = 0.01 rad/s`, the nominal friction at the centre of
    /// the Table 4.1 example box
    /// ([`RobustAdaptiveDesign::table_4_1`](super::RobustAdaptiveDesign::table_4_1)),
    /// limit 0.188 N·m, and `K_p` given (the thesis prints no value for
    /// ch. 4).
    pub fn table_4_1(gain: f64) -> Result<Self, ParamError> {
        let d = super::RobustAdaptiveDesign::table_4_1();
        Self::try_new(PassiveSettings {
            rotor_inertia: d.rotor_inertia,
            gain,
            ratio: d.ratio,
            eps_velocity: d.eps_velocity,
            nominal_friction: d.initial_friction,
            torque_limit: d.torque_limit,
        })
    }

    /// The Table 4.1 passive mode with a default gain the thesis does not
    /// give: `K_p = 1/Î_m` (`Î_m K_p = 1`, i.e. `K_p ≈ 87 719` 1/(kg·m²)
    /// for `Î_m = 1.14e-5 kg·m²`).
    ///
    /// With `Î_m K_p = 1` the two joint-torque terms of eq. (4.32) cancel,
    /// `τ_m = f̂^c(q̇_m) + τ_td/N`: the law compensates friction and adds
    /// the desired joint torque, and the estimate's noise and sampling
    /// delay do not enter a torque-feedback loop, so the choice is stable
    /// at any sample period (below the sampled limit
    /// `Î_m K_p > 1 + J₀/I_l` of errata E4.12 for every link). By eq. (4.33) as corrected (errata E4.1) the
    /// joint then moves as a free body of link-side inertia
    /// `N²/K_p = N² Î_m` (0.114 kg·m² here): the rotor's reflected inertia
    /// without its friction. A larger `K_p` makes the joint feel lighter
    /// (eq. 4.33) but closes a loop on the sampled estimate; check it in
    /// simulation before raising it ([`table_4_1`](Self::table_4_1) takes
    /// any gain).
    pub fn table_4_1_default() -> Result<Self, ParamError> {
        let d = super::RobustAdaptiveDesign::table_4_1();
        Self::table_4_1(1.0 / d.rotor_inertia)
    }

    /// `K_p`, 1/(kg·m²).
    pub fn gain(&self) -> f64 {
        self.gain
    }

    /// `N/K_p`: the apparent motor-side inertia of eq. (4.33) as corrected
    /// (errata E4.1), kg·m²; `∞` for `K_p = 0`.
    pub fn apparent_motor_inertia(&self) -> f64 {
        self.ratio / self.gain
    }
}

/// A hand (or any spring–damper environment) holding the link of a
/// passive joint, link side: `τ_h = −K_h (q_l − q_h) − B_h (q̇_l − q̇_h)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandContact {
    /// Stiffness `K_h ≥ 0`, N·m/rad.
    pub stiffness: f64,
    /// Damping `B_h ≥ 0`, N·m·s/rad.
    pub damping: f64,
    /// Link inertia `I_l ≥ 0` about the joint axis, kg·m².
    pub link_inertia: f64,
}

/// A complex number `re + i·im` (a pole).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pole {
    /// Real part (1/s for a continuous pole; dimensionless for a discrete
    /// one).
    pub re: f64,
    /// Imaginary part, same unit.
    pub im: f64,
}

impl Pole {
    /// `|p|`.
    pub fn magnitude(&self) -> f64 {
        libm::hypot(self.re, self.im)
    }
}

/// The passive joint of eq. (4.32)–(4.33) under a [`HandContact`]: what a
/// user tuning `K_p` feels. From [`PassiveParams::characteristics`].
///
/// **Continuous model** (exact friction compensation, `τ̂_t = τ_t`, rigid
/// transmission, the rotor inertia equal to its estimate `Î_m`):
/// eq. (4.2) with (4.32) gives `τ_t = −(N/K_p) q̈_m` (errata E4.1), the
/// link `I_l q̈_l = τ_t + τ_h` and `q_m = N q_l`, so
///
/// ```text
/// J q̈_l + B_h q̇_l + K_h q_l = K_h q_h + B_h q̇_h,    J = I_l + N²/K_p,
/// ```
///
/// with `ω_n = √(K_h/J)`, `ζ = B_h/(2√(K_h J))` and poles
/// `s = (−B_h ± √(B_h² − 4 J K_h))/(2J)`.
///
/// **Sampled model** (period `T`): the law is evaluated at `t_k` on the
/// joint torque measured just before the new command is applied, and held
/// (zero-order hold). With `J₀ = I_l + N² I_m` and the link-side motor
/// torque `u = N τ_m`, the plant between samples is
/// `J₀ q̈_l = u_{k} − K_h q_l − B_h q̇_l`, the measured torque
/// `τ_t,k = (I_l u_{k−1} + N² I_m (K_h q_k + B_h q̇_k))/J₀` (eliminating
/// `q̈` from the motor and link equations) and the law
/// `u_k = (1 − Î_m K_p) τ_t,k`. On the state `(q_k, q̇_k, u_{k−1})` this is
/// `z_{k+1} = M z_k` with the `3×3` matrix `M` built from the exact
/// discretization `(Φ, Γ)` of the plant; the discrete poles are the
/// eigenvalues of `M`. As `T → 0` two of them tend to `e^{sT}` of the
/// continuous poles and the third (the torque loop) to
/// `(1 − Î_m K_p) I_l/J₀`; the loop is unstable when a pole leaves the unit
/// circle, which happens for large `K_p` (`|1 − Î_m K_p| I_l/J₀ > 1`, at
/// any period: on the thesis joint with its bare link, `Î_m K_p > 4.64`,
/// test `sampled_torque_loop_limits_the_gain`) or for a stiff hand at a
/// long period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveCharacteristics {
    /// Apparent link-side inertia `J = I_l + N²/K_p`, kg·m².
    pub apparent_inertia: f64,
    /// `ω_n = √(K_h/J)`, rad/s (0 without stiffness).
    pub natural_frequency: f64,
    /// `ζ = B_h/(2√(K_h J))` (`∞` without stiffness and with damping,
    /// 0 with neither).
    pub damping_ratio: f64,
    /// `−max Re s` over the continuous poles, 1/s: the slowest mode decays
    /// as `e^{−σ t}` (0 for a free joint, `K_h = 0`).
    pub decay_rate: f64,
    /// The continuous poles `s₁, s₂`, 1/s.
    pub continuous_poles: [Pole; 2],
    /// The discrete poles of the sampled loop (eigenvalues of `M`).
    pub discrete_poles: [Pole; 3],
    /// `max |z|` over the discrete poles: the slowest mode shrinks by this
    /// factor per sample (stable below 1).
    pub spectral_radius: f64,
    /// `−ln(max |z|)/T`, 1/s: the sampled loop's decay rate (negative when
    /// unstable).
    pub discrete_decay_rate: f64,
}

impl PassiveParams {
    /// The closed-loop characteristics of the passive joint (eq.
    /// 4.32–4.33) held by `hand`, continuous and sampled at
    /// `sample_period` (see [`PassiveCharacteristics`] for the models).
    /// Errors: `K_p = 0` (no finite apparent inertia), a negative or
    /// non-finite hand parameter, or `T` outside `(0, 1]` s.
    pub fn characteristics(
        &self,
        hand: &HandContact,
        sample_period: f64,
    ) -> Result<PassiveCharacteristics, ParamError> {
        positive("gain", self.gain)?;
        let kh = crate::error::non_negative("stiffness", hand.stiffness)?;
        let bh = crate::error::non_negative("damping", hand.damping)?;
        let il = crate::error::non_negative("link_inertia", hand.link_inertia)?;
        let t = positive("sample_period", sample_period)?;
        if t > 1.0 {
            return Err(ParamError::OutOfRange {
                name: "sample_period",
                value: t,
                min: 0.0,
                max: 1.0,
            });
        }
        let n = self.ratio;
        let c = self.rotor_inertia * self.gain;
        let j = il + n * n / self.gain;
        let (wn, zeta) = if kh > 0.0 {
            (libm::sqrt(kh / j), bh / (2.0 * libm::sqrt(kh * j)))
        } else if bh > 0.0 {
            (0.0, f64::INFINITY)
        } else {
            (0.0, 0.0)
        };
        let disc = bh * bh - 4.0 * j * kh;
        let continuous_poles = if disc >= 0.0 {
            let r = libm::sqrt(disc);
            [
                Pole {
                    re: (-bh + r) / (2.0 * j),
                    im: 0.0,
                },
                Pole {
                    re: (-bh - r) / (2.0 * j),
                    im: 0.0,
                },
            ]
        } else {
            let w = libm::sqrt(-disc) / (2.0 * j);
            [
                Pole {
                    re: -bh / (2.0 * j),
                    im: w,
                },
                Pole {
                    re: -bh / (2.0 * j),
                    im: -w,
                },
            ]
        };
        let decay_rate = -f64::max(continuous_poles[0].re, continuous_poles[1].re);
        // Sampled loop.
        let j0 = il + n * n * self.rotor_inertia;
        // exp([[A, B], [0, 0]] T) = [[Φ, Γ], [0, 1]].
        let aug = [
            [0.0, t, 0.0],
            [-kh / j0 * t, -bh / j0 * t, t / j0],
            [0.0, 0.0, 0.0],
        ];
        let e = expm3(aug);
        let g = [
            (1.0 - c) * n * n * self.rotor_inertia * kh / j0,
            (1.0 - c) * n * n * self.rotor_inertia * bh / j0,
            (1.0 - c) * il / j0,
        ];
        let mut m = [[0.0; 3]; 3];
        for r in 0..2 {
            for col in 0..3 {
                let phi = if col < 2 { e[r][col] } else { 0.0 };
                m[r][col] = phi + e[r][2] * g[col];
            }
        }
        m[2] = g;
        let discrete_poles = eigenvalues3(&m);
        let spectral_radius = discrete_poles
            .iter()
            .map(Pole::magnitude)
            .fold(0.0, f64::max);
        Ok(PassiveCharacteristics {
            apparent_inertia: j,
            natural_frequency: wn,
            damping_ratio: zeta,
            decay_rate,
            continuous_poles,
            discrete_poles,
            spectral_radius,
            discrete_decay_rate: -libm::log(spectral_radius) / t,
        })
    }
}

/// `e^A` of a 3×3 matrix: scaling (to a norm below ½), a 20-term Taylor
/// series, and squaring back (relative error near `f64` roundoff for the
/// norms met here).
fn expm3(a: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let norm = a
        .iter()
        .map(|r| r.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut squarings = 0;
    let mut scale = 1.0;
    while norm * scale > 0.5 && squarings < 60 {
        scale *= 0.5;
        squarings += 1;
    }
    let mut x = [[0.0; 3]; 3];
    for (xr, ar) in x.iter_mut().zip(a.iter()) {
        for (xv, av) in xr.iter_mut().zip(ar.iter()) {
            *xv = av * scale;
        }
    }
    let mut sum = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut term = sum;
    for k in 1..=20 {
        term = mul3(&term, &x);
        for row in term.iter_mut() {
            for v in row.iter_mut() {
                *v /= k as f64;
            }
        }
        for (sr, tr) in sum.iter_mut().zip(term.iter()) {
            for (sv, tv) in sr.iter_mut().zip(tr.iter()) {
                *sv += tv;
            }
        }
    }
    for _ in 0..squarings {
        sum = mul3(&sum, &sum);
    }
    sum
}

fn mul3(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// Eigenvalues of a 3×3 real matrix: its characteristic polynomial
/// `λ³ + a λ² + b λ + c`, one real root by bisection on a bracket that
/// contains every root (Cauchy's bound), polished by Newton steps, then
/// the remaining quadratic of the deflation.
fn eigenvalues3(m: &[[f64; 3]; 3]) -> [Pole; 3] {
    let tr = m[0][0] + m[1][1] + m[2][2];
    let minors = m[0][0] * m[1][1] - m[0][1] * m[1][0] + m[0][0] * m[2][2] - m[0][2] * m[2][0]
        + m[1][1] * m[2][2]
        - m[1][2] * m[2][1];
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    let (a, b, c) = (-tr, minors, -det);
    let p = |x: f64| ((x + a) * x + b) * x + c;
    let bound = 1.0 + a.abs().max(b.abs()).max(c.abs());
    let (mut lo, mut hi) = (-bound, bound);
    // p(−bound) < 0 < p(bound): a monic cubic.
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if p(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let mut r = 0.5 * (lo + hi);
    for _ in 0..3 {
        let d = (3.0 * r + 2.0 * a) * r + b;
        if d != 0.0 {
            let next = r - p(r) / d;
            if next.is_finite() && p(next).abs() < p(r).abs() {
                r = next;
            }
        }
    }
    // λ³ + aλ² + bλ + c = (λ − r)(λ² + (a + r)λ + (b + r(a + r))).
    let qb = a + r;
    let qc = b + r * qb;
    let disc = qb * qb - 4.0 * qc;
    let (p1, p2) = if disc >= 0.0 {
        let s = libm::sqrt(disc);
        // The larger root without cancellation, the other from the product.
        let big = if qb >= 0.0 {
            -(qb + s) / 2.0
        } else {
            (-qb + s) / 2.0
        };
        let small = if big != 0.0 { qc / big } else { 0.0 };
        (Pole { re: big, im: 0.0 }, Pole { re: small, im: 0.0 })
    } else {
        let w = libm::sqrt(-disc) / 2.0;
        (
            Pole {
                re: -qb / 2.0,
                im: w,
            },
            Pole {
                re: -qb / 2.0,
                im: -w,
            },
        )
    };
    [Pole { re: r, im: 0.0 }, p1, p2]
}

/// Eq. (4.32) quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveConfig<S> {
    friction: FrictionConfig<S>,
    nominal: [S; 4],
    /// `1/N` from stored link torque to stored motor torque.
    feedback: Coef,
    /// `Î_m K_p / N` from stored link torque to stored motor torque.
    torque_gain: Coef,
    torque_limit: S,
}

/// One step of the passive law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveOutput<S> {
    /// Motor torque, stored motor-torque units, `|τ| ≤ limit`.
    pub torque: S,
    /// The law's value before the limit.
    pub law_torque: S,
    /// The torque is not the law's value: it was limited, or the input
    /// was invalid (then also `invalid_input`); the limit alone is
    /// `saturated && !invalid_input` ([status
    /// flags](crate::joint#status-flags)).
    pub saturated: bool,
    /// An input (or a friction estimate given to
    /// [`update_with_friction`](PassiveConfig::update_with_friction)) was
    /// NaN or infinite, or the law overflowed: torque 0.
    pub invalid_input: bool,
}

impl<S: Scalar> PassiveConfig<S> {
    /// Quantize validated parameters once.
    pub fn new(p: &PassiveParams) -> Self {
        let u = S::UNITS;
        let mt = u.motor_torque;
        PassiveConfig {
            friction: FrictionConfig::new(p.eps_velocity),
            nominal: FrictionConfig::<S>::quantize(&p.nominal_friction),
            feedback: Coef::new(mt / (p.ratio * u.link_torque)),
            torque_gain: Coef::new(p.rotor_inertia * p.gain * mt / (p.ratio * u.link_torque)),
            torque_limit: S::from_f64(p.torque_limit * mt),
        }
    }

    /// The configured nominal friction estimates, stored units.
    pub fn nominal_friction(&self) -> [S; 4] {
        self.nominal
    }

    /// The motor torque limit, stored units.
    pub fn torque_limit(&self) -> S {
        self.torque_limit
    }

    /// Eq. (4.32) with the configured nominal friction.
    ///
    /// ```
    /// use mrr_control::control::{ControlInput, PassiveConfig, PassiveParams};
    /// use mrr_control::I16F16;
    /// let p = PassiveParams::table_4_1(2000.0)?;
    /// let cfg = PassiveConfig::<I16F16>::new(&p);
    /// // At rest with τ̂_t = 1 N·m: τ_m = 1/100 − 1.14e-5·2000·1/100
    /// // = 0.01 − 0.000228 = 0.009772 N·m = 9.772 mN·m.
    /// let x = ControlInput { joint_torque: I16F16::from_num(1), ..Default::default() };
    /// let tau = cfg.update(&x).torque.to_num::<f64>();
    /// assert!((tau - 9.772).abs() < 1e-3);
    /// # Ok::<(), mrr_control::ParamError>(())
    /// ```
    pub fn update(&self, x: &ControlInput<S>) -> PassiveOutput<S> {
        self.update_with_friction(x, &self.nominal)
    }

    /// Eq. (4.32) with given friction estimates (stored units, e.g. the
    /// adapted `F̂^c` of the active law). Uses `motor_velocity`,
    /// `joint_torque` and `desired_joint_torque` of the sample.
    #[inline]
    pub fn update_with_friction(&self, x: &ControlInput<S>, friction: &[S; 4]) -> PassiveOutput<S> {
        let law = self.law(x, friction);
        if !x.is_finite() || law.is_nan() {
            return PassiveOutput {
                torque: S::ZERO,
                law_torque: S::ZERO,
                saturated: true,
                invalid_input: true,
            };
        }
        let l = self.torque_limit;
        let torque = law.clamp(l.neg(), l);
        PassiveOutput {
            torque,
            law_torque: law,
            saturated: torque != law,
            invalid_input: false,
        }
    }

    /// The unlimited law value.
    #[inline]
    pub(crate) fn law(&self, x: &ControlInput<S>, friction: &[S; 4]) -> S {
        let f = self.friction.evaluate(friction, x.motor_velocity).torque;
        f.add(x.joint_torque.mul_coef(&self.feedback)).add(
            x.desired_joint_torque
                .sub(x.joint_torque)
                .mul_coef(&self.torque_gain),
        )
    }
}

#[cfg(any(kani, test))]
mod words {
    use super::PassiveConfig;
    use crate::friction::FrictionConfig;
    #[cfg(test)]
    use crate::scalar::words::Sink;
    use crate::scalar::{words::Words, Coef, I16F16};

    impl PassiveConfig<I16F16> {
        pub(crate) const fn take(r: &mut Words) -> Self {
            PassiveConfig {
                friction: FrictionConfig::<I16F16>::take(r),
                nominal: r.fixed4(),
                feedback: Coef::take(r),
                torque_gain: Coef::take(r),
                torque_limit: r.fixed(),
            }
        }

        #[cfg(test)]
        pub(crate) fn put(&self, s: &mut Sink) {
            self.friction.put(s);
            s.fixeds(&self.nominal);
            self.feedback.put(s);
            self.torque_gain.put(s);
            s.fixed(self.torque_limit);
        }
    }
}

#[cfg(test)]
mod tests;
