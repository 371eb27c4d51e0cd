//! Boundary layers and gains of the robust adaptive law (eq. 4.19) that the
//! **sampled** law holds at a given controller period, with the ultimate
//! bound of Theorem 1 (eq. 4.28–4.31) they give.
//!
//! Theorem 1 treats eq. (4.19) in continuous time. Run every `T` seconds
//! with a zero-order hold, the law inside its boundary layers is a linear
//! feedback on the motor, and that feedback must be stable *as a sampled
//! loop*, or the robust terms jump from `+K_r` to `−K_r` from tick to tick
//! (errata E4.4). Table 4.1's layers need `T < 13.4 µs`; at the 4 ms of
//! §6.3 (TMS320F2812) the forward-Euler factor across the `ε_r` layer is
//! 597 where a held layer needs less than 2, and on a joint with the SHD-17-100's spring the
//! motor speed changes by `K_r T/I_m = 60 rad/s` per tick, the torsion
//! estimate swings by ±20 N·m and the mode manager leaves Active within
//! six ticks (`tests/preset_4ms.rs`).
//!
//! [`design_for_period`] chooses `λ`, `ε_r`, `ε_F`, `ε_q̇` and `K_I` for a
//! joint and period so that the criterion below holds, and reports the
//! bound with the library's calculator ([`UltimateBound::new`]).
//!
//! # The sampled model (motor side, SI)
//! The link is reflected to the motor: `J_m = I_m`, `J_l = I_l/N²`,
//! `k = K/N²` for a drive stiffness `K` (N·m/rad, link side). The drive
//! spring carries `τ_t/N = k δ` with the torsion `δ = x_m − x_l` (both
//! motor-side angles). The centre of mass `c = (J_m x_m + J_l x_l)/J`,
//! `J = J_m + J_l`, and `δ` decouple:
//!
//! ```text
//! J c̈ = u,    δ̈ = u/J_m − ω² δ,    ω² = k (1/J_m + 1/J_l),
//! ```
//!
//! and a torque `u` held over `[kT, (k+1)T)` advances them exactly:
//!
//! ```text
//! c⁺ = c + T ċ + T²/(2J) u,                ċ⁺ = ċ + T/J u,
//! δ⁺ = cos(ωT) δ + sin(ωT)/ω δ̇ + (1 − cos ωT)/(ω² J_m) u,
//! δ̇⁺ = −ω sin(ωT) δ + cos(ωT) δ̇ + sin(ωT)/(ω J_m) u,
//! ```
//!
//! with `x_m = c + (J_l/J) δ`. The joint measures the speed as the count
//! difference over one tick, `ė_k = (x_k − x_{k−1})/T`, and feeds back the
//! joint torque estimated from the torsion at the sample, `τ̂_t/N = k δ_k`.
//! Inside every boundary layer eq. (4.19) is then, on the error
//! (reference and bounded disturbances dropped),
//!
//! ```text
//! u_k = −λ I_m (ė_k + r_k) − S r_k + ν ė_k − z_k + k δ_k,
//! r_k = ė_k + λ x_k,        z_{k+1} = z_k + K_I T r_k,
//! ```
//!
//! where `S = K_r/ε_r + Σ_j ρ_Fj Y_j²/ε_Fj` is the slope of the robust
//! terms in `r` (the parametric ones at the regressor `Y`, bounded as in
//! [`UltimateBound::step_ratio_at_speed`], with `|q̇_m| ≤` the design's
//! maximum speed) and `ν = b_max + (f_c,max + f_s,max)/ε_q̇` bounds the
//! slope of the nominal friction `f̂^c(q̇)` (eq. 4.17), which pushes along
//! the motion. The closed loop is linear in `s = [c, ċ, δ, δ̇, x_{k−1}, z]`,
//! `s_{k+1} = A s_k` (6 × 6).
//!
//! # The criterion
//! 1. **Sampled stability with margin**: every eigenvalue of `A` lies in
//!    the disc `|z| ≤ ρ_max` (e.g. 0.9: every mode decays at least by 0.9
//!    per tick, a time constant under 10 ticks), for `S` anywhere between
//!    `K_r/ε_r` (all regressors 0) and its value at the maximum speed, `ν`
//!    between 0 and its bound, and `K` and `I_l` at both ends of their
//!    ranges. Checked on the corners of
//!    that box by the Schur–Cohn test on `det(zI − A)` scaled to the disc
//!    (the polynomial from Faddeev–LeVerrier).
//! 2. **The ultimate set lies in the layer**: `r_S ≤ ε_r`. After the
//!    reaching time of eq. (4.31) `|r| ≤ r_S`, so the robust term stays on
//!    its linear part, the one whose sampled loop item 1 checked: the
//!    sampled law does not chatter across the layer there.
//! 3. **Quantisation inside the layer**: the quantum of the measured `r`,
//!    `2π/(M T) + λ 2π/M` (one count of speed and of position), is at most
//!    `ε_r/2`, so count noise alone cannot carry `r` across the layer.
//!
//! # The choice
//! Eq. (4.28)'s constant is `c = K_r ε_r/4 + Σ_j ρ_Fj ε_Fj/4`. For a given
//! total slope `S` (what item 1 allows), writing `g_0 = K_r`,
//! `g_j = ρ_Fj Y_j,max` and the slopes `s_0 = K_r/ε_r`,
//! `s_j = ρ_Fj Y_j,max²/ε_Fj`, `c = Σ_i g_i²/(4 s_i)` is smallest under
//! `Σ s_i = S` when `s_i ∝ g_i` (Lagrange): `c = G²/(4S)` with
//! `G = Σ_i g_i`, i.e. **every layer saturates at the same sliding value
//! `|r| = G/S`**: `ε_r = G/S`, `ε_Fj = Y_j,max G/S`. Then
//! `r_S = G/√(2 S I_m λ)` and the motor tracking bound is
//! `r_S/λ = G/(λ^{3/2} √(2 S I_m))`, and item 2 reads `S ≤ 2 I_m λ`.
//! [`design_for_period`] searches `λ ∈ [10⁻³/T, 0.5/T]` and
//! `S ∈ [10⁻⁴ I_m/T, 4 I_m/T]` (log grids of 64 points), keeps the pairs that meet items 1–3 (layers capped at what
//! every backend represents, the slope recomputed from the capped layer),
//! and returns the one with the smallest bound; `ε_q̇` is set so that `ν`
//! is a quarter of the damping `2λI_m + S`, and `K_I` is the largest of
//! `K_I,base·10^{−n/2}` (n = 0…12) or 0 that keeps item 1.
//!
//! *Not covered* by the model: the friction of the link (its Coulomb part
//! a bounded disturbance outside the linear check, its viscous part a
//! damping the model leaves out — conservative: on the test plant designs
//! up to a radius of 1.14 still held, those from 1.18 fell, test
//! `pole_radius_separates_designs_that_hold_from_those_that_fall`), the drive's hysteresis, the
//! estimator's kinematic-error model (its error enters as `ρ_τt`), and
//! speeds above the design's maximum. The test `tests/preset_4ms.rs` runs
//! the result on a plant with them.

use super::adaptive::{RobustAdaptiveDesign, RobustAdaptiveParams};
use super::bound::UltimateBound;
use crate::error::{in_range, positive, ParamError};
use crate::scalar::units;
use core::f64::consts::TAU;
use core::fmt;

/// The joint and the requirements a sampled design is made for (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledJoint {
    /// Controller period `T`, s, in `[1e-6, 0.1]`.
    pub sample_period: f64,
    /// Reduction ratio `N ≥ 1`.
    pub ratio: f64,
    /// Drive stiffness range `[K_min, K_max]`, N·m/rad (link side), e.g.
    /// the catalogue's `K1` and `K2`; `0 < K_min ≤ K_max`.
    pub stiffness: [f64; 2],
    /// Rotor inertia `I_m` (motor, coupling, wave generator), kg·m², `> 0`.
    pub rotor_inertia: f64,
    /// Link inertia range `[I_l,min, I_l,max]` about the joint axis,
    /// kg·m², `0 < I_l,min ≤ I_l,max` (the loads the design must hold
    /// with; the sampled joint-torque feedback `τ̂_t/N` makes the pole
    /// radius depend on it).
    pub link_inertia: [f64; 2],
    /// Motor encoder counts per motor revolution `M`, `≥ 1`.
    pub motor_counts_per_rev: u32,
    /// Largest motor speed the design must hold at, rad/s, `> 0` (the
    /// parametric robust terms' slopes grow with it).
    pub max_motor_speed: f64,
    /// Largest admissible eigenvalue magnitude `ρ_max` of the sampled
    /// closed loop, in `(0, 1)`.
    pub max_pole_radius: f64,
}

/// What [`design_for_period`] chose and what it gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeriodDesign {
    /// The validated law.
    pub params: RobustAdaptiveParams,
    /// Theorem 1's bound of the law ([`UltimateBound::new`]).
    pub bound: UltimateBound,
    /// The largest eigenvalue magnitude of the sampled closed loop over
    /// the checked corners ([`sampled_pole_radius`]).
    pub pole_radius: f64,
    /// The total slope `S` of the robust terms in `r` at the maximum
    /// speed, N·m·s/rad.
    pub robust_slope: f64,
}

/// Why no sampled design was returned.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum DesignError {
    /// An input (named as the field of [`SampledJoint`] or of the base
    /// [`RobustAdaptiveDesign`]) was rejected, or the chosen law failed
    /// [`RobustAdaptiveParams::try_new`].
    Param(ParamError),
    /// No `λ` and `S` on the search grid meets the criterion at this
    /// period (module docs): the joint cannot be held by eq. (4.19) at
    /// `sample_period` with these bounds. `smallest_radius` is the
    /// smallest pole radius found (with `K_I = 0`), `max_pole_radius` the
    /// one asked for.
    NoSampledDesign {
        /// The period, s.
        sample_period: f64,
        /// Smallest pole radius on the grid.
        smallest_radius: f64,
        /// The requirement.
        max_pole_radius: f64,
    },
}

impl From<ParamError> for DesignError {
    fn from(e: ParamError) -> Self {
        DesignError::Param(e)
    }
}

impl fmt::Display for DesignError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            DesignError::Param(e) => write!(f, "{e}"),
            DesignError::NoSampledDesign {
                sample_period,
                smallest_radius,
                max_pole_radius,
            } => write!(
                f,
                "no boundary-layer design holds at sample_period = {sample_period} s: \
                 the smallest sampled pole radius found is {smallest_radius}, \
                 the rule asks for at most {max_pole_radius}"
            ),
        }
    }
}

/// Largest layer (SI, in the unit of `r Y_j`) every backend represents:
/// [`RobustAdaptiveParams::try_new`] accepts a stored layer up to 30 000.
fn layer_cap(j: Option<usize>) -> f64 {
    let u = units::FIXED;
    // Regressor scales of the fixed-point backend (crate::friction).
    let ys = [u.speed, 1.0, 1.0, u.motor_torque * u.speed * u.speed];
    match j {
        None => 30_000.0 / u.speed,
        Some(j) => 30_000.0 / (u.speed * ys[j]),
    }
}

/// Bounds of the regressor magnitudes `|Y_j|` over the friction box at
/// motor speeds up to `qd` (rad/s), as in
/// [`UltimateBound::step_ratio_at_speed`]: `|Y_1| = |q̇|`,
/// `|Y_2|, |Y_3| ≤ 1`, `|Y_4| ≤ f_s,max q̇² e^{−f_τ,min q̇²}` maximised
/// over `|q̇| ≤ qd`.
fn regressor_bounds(d: &RobustAdaptiveDesign, qd: f64) -> [f64; 4] {
    let fs = d.friction_bounds.max()[2];
    let ft = d.friction_bounds.min()[3];
    // q̇² e^{−f_τ q̇²} peaks at q̇² = 1/f_τ.
    let q2 = f64::min(qd * qd, 1.0 / ft);
    [qd, 1.0, 1.0, fs * q2 * libm::exp(-ft * q2)]
}

/// The slope `S` of the robust terms in `r` inside their layers at the
/// regressor bounds of speed `qd`, N·m·s/rad.
fn robust_slope_at(d: &RobustAdaptiveDesign, qd: f64) -> f64 {
    let y = regressor_bounds(d, qd);
    let rho = d.friction_bounds.variable();
    let mut s = d.robust_gain() / d.eps_r;
    for j in 0..4 {
        s += rho[j] * y[j] * y[j] / d.eps_f[j];
    }
    s
}

/// The closed-loop matrix `A` of the module docs.
#[allow(clippy::too_many_arguments)]
fn closed_loop(
    t: f64,
    jm: f64,
    jl: f64,
    k: f64,
    lambda: f64,
    slope: f64,
    nu: f64,
    ki: f64,
) -> [[f64; 6]; 6] {
    let j = jm + jl;
    let alpha = jl / j;
    let w = libm::sqrt(k * (1.0 / jm + 1.0 / jl));
    let (sn, cs) = (libm::sin(w * t), libm::cos(w * t));
    let damping = 2.0 * lambda * jm + slope - nu;
    let ax = -damping / t - lambda * lambda * jm - lambda * slope;
    let ap = damping / t;
    // u = U·s over s = [c, ċ, δ, δ̇, x_prev, z].
    let u = [ax, 0.0, ax * alpha + k, 0.0, ap, -1.0];
    let mut a = [[0.0; 6]; 6];
    let input = [
        t * t / (2.0 * j),
        t / j,
        (1.0 - cs) / (w * w * jm),
        sn / (w * jm),
        0.0,
        0.0,
    ];
    a[0][0] = 1.0;
    a[0][1] = t;
    a[1][1] = 1.0;
    a[2][2] = cs;
    a[2][3] = sn / w;
    a[3][2] = -w * sn;
    a[3][3] = cs;
    for (row, b) in a.iter_mut().zip(input.iter()) {
        for (x, ui) in row.iter_mut().zip(u.iter()) {
            *x += b * ui;
        }
    }
    // x_prev⁺ = x = c + α δ.
    a[4][0] = 1.0;
    a[4][2] = alpha;
    // z⁺ = z + K_I T ((1/T + λ) x − x_prev/T).
    let g = ki * t * (1.0 / t + lambda);
    a[5][0] = g;
    a[5][2] = g * alpha;
    a[5][4] = -ki;
    // Without integral action `z` stays at its initial 0: the state is
    // dropped (its eigenvalue set to 0 instead of the unexcited 1).
    a[5][5] = if ki > 0.0 { 1.0 } else { 0.0 };
    a
}

/// `det(zI − A)` as coefficients `p[i]` of `z^i` (`p[6] = 1`), by
/// Faddeev–LeVerrier.
fn characteristic(a: &[[f64; 6]; 6]) -> [f64; 7] {
    let mut p = [0.0; 7];
    p[6] = 1.0;
    let mut m = [[0.0; 6]; 6];
    for k in 1..=6 {
        // M_k = A M_{k−1} + p_{7−k} I; p_{6−k} = −tr(A M_k)/k.
        let mut next = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let mut s = 0.0;
                for l in 0..6 {
                    s += a[i][l] * m[l][j];
                }
                next[i][j] = s;
            }
            next[i][i] += p[7 - k];
        }
        m = next;
        let mut tr = 0.0;
        for i in 0..6 {
            for l in 0..6 {
                tr += a[i][l] * m[l][i];
            }
        }
        p[6 - k] = -tr / k as f64;
    }
    p
}

/// `true` when every root of `p` (`p[i]` the coefficient of `z^i`, degree
/// 6) lies strictly inside `|z| < radius`: the Schur–Cohn recursion on
/// `p(radius·z)`, which is Schur stable iff `|a_0| < |a_n|` and
/// `(a_n p − a_0 p*)/z` is.
fn roots_inside(p: &[f64; 7], radius: f64) -> bool {
    let mut a = [0.0; 7];
    let mut scale = 1.0;
    for i in 0..7 {
        a[i] = p[i] * scale;
        scale *= radius;
    }
    let mut n = 6;
    while n > 0 {
        let (lead, tail) = (a[n], a[0]);
        // (A NaN fails the comparison: not stable.)
        if tail.abs() >= lead.abs() || tail.is_nan() || lead.is_nan() {
            return false;
        }
        let mut b = [0.0; 7];
        for i in 0..n {
            b[i] = lead * a[i + 1] - tail * a[n - 1 - i];
        }
        // Normalise against overflow and underflow.
        let top = b[n - 1].abs();
        if top.is_nan() || top <= 0.0 || top.is_infinite() {
            return false;
        }
        for x in b.iter_mut().take(n) {
            *x /= top;
        }
        a = b;
        n -= 1;
    }
    true
}

/// The spectral radius `ρ` of `A` by bisection on [`roots_inside`], within
/// `2·10⁻¹² · max(1, ρ)`; `∞` when it exceeds 2³⁹ (5.5e11) or `A` is not
/// finite. Both loops are bounded: the bracket is the first power of two
/// `2^k ≥ ρ` (`k < 40`, so `2^k < 2 max(1, ρ)`), then 40 halvings of
/// `[0, 2^k]` leave it `2^{k−40} < 10⁻¹² · 2^k` wide.
fn pole_radius(a: &[[f64; 6]; 6]) -> f64 {
    let p = characteristic(a);
    let Some(mut hi) = (0..40)
        .map(|k| libm::ldexp(1.0, k))
        .find(|&r| roots_inside(&p, r))
    else {
        return f64::INFINITY;
    };
    let mut lo = 0.0;
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if roots_inside(&p, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The closed-loop matrices of the corners of the module docs' item 1.
fn corners(d: &RobustAdaptiveDesign, joint: &SampledJoint) -> [[[f64; 6]; 6]; 16] {
    let t = joint.sample_period;
    let n2 = joint.ratio * joint.ratio;
    let nu_max = d.friction_bounds.max()[0]
        + (d.friction_bounds.max()[1] + d.friction_bounds.max()[2]) / d.eps_velocity;
    let slopes = [
        d.robust_gain() / d.eps_r,
        robust_slope_at(d, joint.max_motor_speed),
    ];
    let mut out = [[[0.0; 6]; 6]; 16];
    let mut i = 0;
    for &il in &joint.link_inertia {
        for &k in &joint.stiffness {
            for &s in &slopes {
                for nu in [0.0, nu_max] {
                    out[i] = closed_loop(
                        t,
                        joint.rotor_inertia,
                        il / n2,
                        k / n2,
                        d.lambda,
                        s,
                        nu,
                        d.integral_gain,
                    );
                    i += 1;
                }
            }
        }
    }
    out
}

/// The worst pole radius of the sampled law `d` on `joint` over the
/// corners of the module docs' item 1 (slope at rest and at the maximum
/// speed, friction slope 0 and its bound, both ends of the stiffness and
/// of the link inertia ranges); the period is `joint.sample_period` (the
/// design's own is not used).
///
/// For Table 4.1 on its joint at 4 ms it is far above 1 (the law cannot
/// hold its layers); see `table_4_1_is_unstable_when_sampled` in the
/// tests of this module.
///
/// The joint is validated as by [`design_for_period`] (a `ParamError`
/// names the bad field), so the radius is never computed from a
/// non-finite or non-physical joint.
pub fn sampled_pole_radius(
    d: &RobustAdaptiveDesign,
    joint: &SampledJoint,
) -> Result<f64, ParamError> {
    check_joint(joint)?;
    Ok(worst_pole_radius(d, joint))
}

/// [`sampled_pole_radius`] of a joint already validated.
fn worst_pole_radius(d: &RobustAdaptiveDesign, joint: &SampledJoint) -> f64 {
    corners(d, joint)
        .iter()
        .map(pole_radius)
        .fold(0.0f64, f64::max)
}

/// `true` when every corner's poles lie strictly inside `radius`.
fn holds_within(d: &RobustAdaptiveDesign, joint: &SampledJoint, radius: f64) -> bool {
    corners(d, joint)
        .iter()
        .all(|a| roots_inside(&characteristic(a), radius))
}

fn check_joint(j: &SampledJoint) -> Result<(), ParamError> {
    in_range("sample_period", j.sample_period, 1e-6, 0.1)?;
    crate::error::gear_ratio(j.ratio)?;
    positive("stiffness[0]", j.stiffness[0])?;
    positive("stiffness[1]", j.stiffness[1])?;
    if j.stiffness[1] < j.stiffness[0] {
        return Err(ParamError::NotIncreasing {
            lower: "stiffness[0]",
            lower_value: j.stiffness[0],
            upper: "stiffness[1]",
            upper_value: j.stiffness[1],
        });
    }
    positive("rotor_inertia", j.rotor_inertia)?;
    positive("link_inertia[0]", j.link_inertia[0])?;
    positive("link_inertia[1]", j.link_inertia[1])?;
    if j.link_inertia[1] < j.link_inertia[0] {
        return Err(ParamError::NotIncreasing {
            lower: "link_inertia[0]",
            lower_value: j.link_inertia[0],
            upper: "link_inertia[1]",
            upper_value: j.link_inertia[1],
        });
    }
    if j.motor_counts_per_rev == 0 {
        return Err(ParamError::NotPositive {
            name: "motor_counts_per_rev",
            value: 0.0,
        });
    }
    positive("max_motor_speed", j.max_motor_speed)?;
    let r = positive("max_pole_radius", j.max_pole_radius)?;
    if r >= 1.0 {
        return Err(ParamError::OutOfRange {
            name: "max_pole_radius",
            value: r,
            min: 0.0,
            max: 1.0,
        });
    }
    Ok(())
}

/// Table 4.1's law ([`RobustAdaptiveDesign::table_4_1`]) with the
/// Stribeck shape taken as known, the base of the sampled preset: the box
/// of `f_τ` shrunk to its initial estimate 1 s²/rad² (`min = max`), its
/// variable bound `ρ_F4 = 0` and its adaptation gain `μ_4 = 0`; every
/// other number as in Table 4.1.
///
/// Why: with `f_τ ∈ [0.01, 10]` the regressor `|Y_4|` reaches
/// `f_s,max/(e f_τ,min) = 0.44 N·m·s²/rad²`-scaled, and the layer
/// `ε_F4` that would keep `ρ_F4 Y_4²/ε_F4` inside the sampled gain budget
/// at 4 ms (about `Y_4 G/S ≈ 10³`) is beyond what the fixed-point backend
/// represents (30 in its stored unit), so [`design_for_period`] finds no
/// design from Table 4.1 itself (test
/// `table_4_1_base_has_no_sampled_design`). With `f_τ` known the friction
/// is linear in the adapted parameters (eq. 4.16–4.17) and the term
/// vanishes; the simulator's designs at 4 ms and 50 µs make the same
/// choice.
pub fn table_4_1_known_stribeck_shape() -> RobustAdaptiveDesign {
    let mut d = RobustAdaptiveDesign::table_4_1();
    let (mut lo, mut hi, mut rho) = (
        d.friction_bounds.min(),
        d.friction_bounds.max(),
        d.friction_bounds.variable(),
    );
    lo[3] = 1.0;
    hi[3] = 1.0;
    rho[3] = 0.0;
    d.friction_bounds = crate::friction::FrictionBounds::from_checked(lo, hi, rho);
    d.adaptation_gain[3] = 0.0;
    d
}

/// Points of the log grids of `λ` and `S`.
const GRID: usize = 64;

/// Boundary layers and gains of eq. (4.19) that the law sampled at
/// `joint.sample_period` holds, by the criterion of the module docs, with
/// the smallest ultimate bound on the search grid.
///
/// From `base` the design keeps the rotor inertia, ratio, uncertainty
/// bounds (Assumptions 3–6), friction box and `ρ_F`, initial estimate,
/// adaptation gains, torque and integral limits; it sets `λ`, `ε_r`,
/// `ε_F`, `ε_q̇`, `K_I` (at most `base`'s) and `T`. `base.rotor_inertia`
/// and `base.ratio` must equal `joint`'s (`OutOfRange` naming
/// `rotor_inertia` or `ratio`, with `joint`'s value as both bounds).
///
/// Errors: a `joint` field out of range ([`DesignError::Param`] naming
/// it: `sample_period ∈ [1e-6, 0.1]` s, `ratio ≥ 1`, stiffnesses
/// positive and ordered, inertias and `max_motor_speed` positive,
/// `motor_counts_per_rev ≥ 1`, `max_pole_radius ∈ (0, 1)`); no grid point
/// meeting the criterion ([`DesignError::NoSampledDesign`]); the chosen
/// law rejected by [`RobustAdaptiveParams::try_new`].
///
/// ```
/// use mrr_control::control::design::{
///     design_for_period, table_4_1_known_stribeck_shape, SampledJoint,
/// };
/// let joint = SampledJoint {
///     sample_period: 0.004,
///     ratio: 100.0,
///     stiffness: [8.4e3, 9.4e3],
///     rotor_inertia: 1.14e-5,
///     link_inertia: [0.03, 0.1],
///     motor_counts_per_rev: 2000,
///     max_motor_speed: 100.0,
///     max_pole_radius: 0.9,
/// };
/// let mut base = table_4_1_known_stribeck_shape();
/// let p = design_for_period(&base, &joint).unwrap();
/// assert!(p.pole_radius <= 0.9);
/// // The ultimate set lies inside the layer (criterion item 2).
/// assert!(p.bound.sliding_radius <= p.params.design().eps_r);
/// // A base law for another drive is rejected, naming the field.
/// base.ratio = 50.0;
/// assert!(design_for_period(&base, &joint).is_err());
/// ```
pub fn design_for_period(
    base: &RobustAdaptiveDesign,
    joint: &SampledJoint,
) -> Result<PeriodDesign, DesignError> {
    check_joint(joint)?;
    if base.rotor_inertia != joint.rotor_inertia {
        return Err(ParamError::OutOfRange {
            name: "rotor_inertia",
            value: base.rotor_inertia,
            min: joint.rotor_inertia,
            max: joint.rotor_inertia,
        }
        .into());
    }
    if base.ratio != joint.ratio {
        return Err(ParamError::OutOfRange {
            name: "ratio",
            value: base.ratio,
            min: joint.ratio,
            max: joint.ratio,
        }
        .into());
    }
    // The base must itself be a valid law (names its own bad field).
    RobustAdaptiveParams::try_new(*base)?;
    let t = joint.sample_period;
    let im = joint.rotor_inertia;
    let y = regressor_bounds(base, joint.max_motor_speed);
    let rho = base.friction_bounds.variable();
    let kr = base.robust_gain();
    let g_total = kr + (0..4).map(|j| rho[j] * y[j]).sum::<f64>();
    let fmax = base.friction_bounds.max();
    let quantum_angle = TAU / joint.motor_counts_per_rev as f64;
    let quantum_speed = quantum_angle / t;
    // The law for (λ, S, K_I), layers by the equal-saturation rule, capped
    // at what every backend represents.
    let law = |lambda: f64, s: f64, ki: f64| {
        let mut d = *base;
        d.sample_period = t;
        d.lambda = lambda;
        d.integral_gain = ki;
        let width = g_total / s;
        d.eps_r = width.min(layer_cap(None));
        for j in 0..4 {
            if rho[j] > 0.0 && y[j] > 0.0 {
                d.eps_f[j] = (y[j] * width).min(layer_cap(Some(j)));
            }
        }
        let nu_budget = (2.0 * lambda * im + s) / 4.0;
        let friction = fmax[1] + fmax[2];
        d.eps_velocity = if nu_budget > fmax[0] && friction > 0.0 {
            (friction / (nu_budget - fmax[0])).min(layer_cap(None))
        } else {
            layer_cap(None)
        };
        d
    };
    let lam_lo = 1e-3 / t;
    let lam_hi = 0.5 / t;
    let s_lo = 1e-4 * im / t;
    let s_hi = 4.0 * im / t;
    let geo = |lo: f64, hi: f64, i: usize| lo * libm::pow(hi / lo, i as f64 / (GRID - 1) as f64);
    let mut best: Option<(f64, RobustAdaptiveDesign)> = None;
    let mut smallest = f64::INFINITY;
    for il in 0..GRID {
        let lambda = geo(lam_lo, lam_hi, il);
        let quantum_r = quantum_speed + lambda * quantum_angle;
        for is in 0..GRID {
            let s = geo(s_lo, s_hi, is);
            let d = law(lambda, s, 0.0);
            if RobustAdaptiveParams::try_new(d).is_err() {
                continue;
            }
            let b = UltimateBound::new(&d);
            // Items 2 and 3, then 1.
            if b.sliding_radius > d.eps_r || quantum_r > d.eps_r / 2.0 {
                continue;
            }
            if !holds_within(&d, joint, joint.max_pole_radius) {
                continue;
            }
            if best.as_ref().is_none_or(|(e, _)| b.tracking_error < *e) {
                best = Some((b.tracking_error, d));
            }
        }
    }
    let Some((_, mut d)) = best else {
        // The smallest radius on the grid, for the error.
        for il in 0..GRID {
            for is in 0..GRID {
                let d = law(geo(lam_lo, lam_hi, il), geo(s_lo, s_hi, is), 0.0);
                if RobustAdaptiveParams::try_new(d).is_ok() {
                    smallest = smallest.min(worst_pole_radius(&d, joint));
                }
            }
        }
        return Err(DesignError::NoSampledDesign {
            sample_period: t,
            smallest_radius: smallest,
            max_pole_radius: joint.max_pole_radius,
        });
    };
    // The largest integral gain (a half-decade ladder below the base's)
    // that keeps item 1; the bound does not depend on it.
    for n in 0..=12 {
        let ki = base.integral_gain * libm::pow(10.0, -(n as f64) / 2.0);
        let mut trial = d;
        trial.integral_gain = ki;
        if RobustAdaptiveParams::try_new(trial).is_ok()
            && holds_within(&trial, joint, joint.max_pole_radius)
        {
            d = trial;
            break;
        }
    }
    let params = RobustAdaptiveParams::try_new(d)?;
    Ok(PeriodDesign {
        params,
        bound: UltimateBound::new(&d),
        pole_radius: worst_pole_radius(&d, joint),
        robust_slope: robust_slope_at(&d, joint.max_motor_speed),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::{FrictionBounds, FrictionParams};

    fn joint() -> SampledJoint {
        SampledJoint {
            sample_period: 0.004,
            ratio: 100.0,
            stiffness: [8.4e3, 9.4e3],
            rotor_inertia: 1.14e-5,
            link_inertia: [0.03, 0.1],
            motor_counts_per_rev: 2000,
            max_motor_speed: 100.0,
            max_pole_radius: 0.9,
        }
    }

    /// The Schur–Cohn test against roots placed by hand: `(z − a)(z − b)…`
    /// expanded, inside a radius iff the largest `|root|` is below it.
    #[test]
    fn pole_radius_of_an_invalid_joint_is_an_error_naming_the_field() {
        let d = table_4_1_known_stribeck_shape();
        let mut j = joint();
        j.link_inertia[1] = f64::NAN;
        let e = sampled_pole_radius(&d, &j).unwrap_err();
        assert_eq!(e.name(), "link_inertia[1]", "{e}");
        j = joint();
        j.sample_period = 0.0;
        assert_eq!(
            sampled_pole_radius(&d, &j).unwrap_err().name(),
            "sample_period"
        );
        assert!(sampled_pole_radius(&d, &joint()).unwrap().is_finite());
    }

    #[test]
    fn roots_inside_matches_placed_roots() {
        let expand = |roots: [(f64, f64); 3]| {
            // Three conjugate pairs (re, im): z² − 2re z + re² + im².
            let mut p = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            let mut deg = 0;
            for (re, im) in roots {
                let q = [re * re + im * im, -2.0 * re, 1.0];
                let mut out = [0.0; 7];
                for i in 0..=deg {
                    for (j, qj) in q.iter().enumerate() {
                        out[i + j] += p[i] * qj;
                    }
                }
                p = out;
                deg += 2;
            }
            p
        };
        // Distinct roots (a double root moves by √ε under rounding).
        let p = expand([(0.5, 0.3), (-0.2, 0.7), (0.85, 0.2)]);
        let largest = (0.85f64 * 0.85 + 0.04).sqrt();
        assert!(roots_inside(&p, largest + 1e-9));
        assert!(!roots_inside(&p, largest - 1e-9));
        // A pair on the unit circle is not strictly inside it.
        let q = expand([(0.6, 0.8), (0.1, 0.0), (0.0, 0.2)]);
        assert!(!roots_inside(&q, 1.0));
        assert!(roots_inside(&q, 1.0 + 1e-9));
    }

    /// A NaN anywhere in the polynomial is never called stable: at the
    /// constant or leading coefficient (the first comparison) or inside
    /// (it reaches the recursion's next leading coefficient).
    #[test]
    fn roots_inside_rejects_nan() {
        let stable = [0.001, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        assert!(roots_inside(&stable, 1.0));
        for i in [0, 3, 5, 6] {
            let mut p = stable;
            p[i] = f64::NAN;
            assert!(!roots_inside(&p, 1.0), "NaN at {i}");
        }
    }

    /// The radius of a diagonal matrix is its largest entry's magnitude
    /// (to the bisection's 1e-9); beyond 1e12 it is reported as infinite.
    #[test]
    fn pole_radius_of_diagonal_matrices() {
        for (big, want) in [(0.3, 0.3), (-0.95, 0.95), (5.0, 5.0), (3e5, 3e5)] {
            let mut a = [[0.0; 6]; 6];
            a[0][0] = 0.1;
            a[2][2] = big;
            a[4][4] = -0.2;
            let r = pole_radius(&a);
            assert!((r - want).abs() <= 2e-9 * want, "{big}: {r}");
        }
        let mut a = [[0.0; 6]; 6];
        a[1][1] = 1e13;
        assert_eq!(pole_radius(&a), f64::INFINITY);
    }

    /// Faddeev–LeVerrier against the rigid case solved by hand: with the
    /// spring made stiff and the link light the loop is the rigid motor
    /// under `u = −D ė − P x` and `K_I = 0`, whose non-trivial poles with
    /// `P = 0` are the roots of `z² + (d − 1) z + d` (`d = D T/(2 I_m)`),
    /// magnitude `√d` when complex (derivation: `(z−1)²z + (T²/2I)(z+1)
    /// D(z−1)/T = (z−1)(z² + (d−1)z + d)`).
    #[test]
    fn rigid_loop_poles_are_root_d() {
        let (t, im) = (0.004, 1e-5);
        let d = 0.5;
        // D = 2λI_m + S with λ → 0: all from S.
        let s = 2.0 * d * im / t;
        let a = closed_loop(t, im, 1e-12, 1e-3, 0.0, s, 0.0, 0.0);
        let r = pole_radius(&a);
        // The link's own oscillator (undamped, |z| = 1) and the rigid
        // integrator dominate: remove them by comparing the roots directly.
        let p = characteristic(&a);
        // z = √d·e^{±iθ} must be roots: p evaluated there is ~0.
        let theta = ((1.0 - d) / (2.0 * d.sqrt())).acos();
        let (re, im_) = (d.sqrt() * theta.cos(), d.sqrt() * theta.sin());
        let (mut vr, mut vi) = (0.0, 0.0);
        let (mut zr, mut zi) = (1.0, 0.0);
        for c in p {
            vr += c * zr;
            vi += c * zi;
            let nr = zr * re - zi * im_;
            zi = zr * im_ + zi * re;
            zr = nr;
        }
        assert!(vr.abs() < 1e-6 && vi.abs() < 1e-6, "{vr} {vi} {p:?}");
        assert!(r >= 1.0 - 1e-6, "{r}");
    }

    /// `closed_loop` against the sampled law simulated from its physical
    /// description: the two masses `J_m ẍ_m = u − k(x_m − x_l)`,
    /// `J_l ẍ_l = k(x_m − x_l)` integrated by RK4 (4000 steps per period,
    /// `ωh < 10⁻³`) under the held torque of the law as the module docs
    /// write it (`ė = (x − x_prev)/T`, `r = ė + λx`,
    /// `u = −λI_m(ė + r) − S r + ν ė − z + k δ`, `z⁺ = z + K_I T r`). The
    /// map of one period on `s = [c, ċ, δ, δ̇, x_prev, z]` (linear: columns
    /// from unit states) must be `A`, with integral action so that every
    /// row and column takes part.
    #[test]
    fn closed_loop_is_the_simulated_period_map() {
        let (t, jm, jl, k) = (0.004, 1.14e-5, 1e-5, 0.9);
        let (lambda, slope, nu, ki) = (50.0, 0.01, 0.002, 5.0);
        let a = closed_loop(t, jm, jl, k, lambda, slope, nu, ki);
        let j = jm + jl;
        let alpha = jl / j;
        let period = |s: [f64; 6]| -> [f64; 6] {
            let [c, cd, d, dd, x_prev, z] = s;
            let (mut xm, mut vm) = (c + alpha * d, cd + alpha * dd);
            let (mut xl, mut vl) = (c - (jm / j) * d, cd - (jm / j) * dd);
            let ed = (xm - x_prev) / t;
            let r = ed + lambda * xm;
            let u = -lambda * jm * (ed + r) - slope * r + nu * ed - z + k * (xm - xl);
            let f = |x: [f64; 4]| {
                let spring = k * (x[0] - x[2]);
                [x[1], (u - spring) / jm, x[3], spring / jl]
            };
            let steps = 4000;
            let h = t / steps as f64;
            let mut x = [xm, vm, xl, vl];
            for _ in 0..steps {
                let add = |x: [f64; 4], k: [f64; 4], w: f64| {
                    [
                        x[0] + w * k[0],
                        x[1] + w * k[1],
                        x[2] + w * k[2],
                        x[3] + w * k[3],
                    ]
                };
                let k1 = f(x);
                let k2 = f(add(x, k1, 0.5 * h));
                let k3 = f(add(x, k2, 0.5 * h));
                let k4 = f(add(x, k3, h));
                for i in 0..4 {
                    x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
            }
            [xm, vm, xl, vl] = x;
            let xm_sample = c + alpha * d;
            [
                (jm * xm + jl * xl) / j,
                (jm * vm + jl * vl) / j,
                xm - xl,
                vm - vl,
                xm_sample,
                z + ki * t * r,
            ]
        };
        for col in 0..6 {
            let mut e = [0.0; 6];
            e[col] = 1.0;
            let got = period(e);
            let size = (0..6).map(|i| a[i][col].abs()).fold(0.0f64, f64::max);
            for row in 0..6 {
                let want = a[row][col];
                assert!(
                    (got[row] - want).abs() <= 1e-7 * want.abs() + 1e-9 * size,
                    "A[{row}][{col}] = {want}, simulated {}",
                    got[row]
                );
            }
        }
    }

    /// Errata E4.4 on the joint: Table 4.1's law sampled at 4 ms is
    /// unstable by a wide margin (its loop gain across the ε_r layer alone
    /// is `T K_r/(ε_r I_m) = 596`).
    #[test]
    fn table_4_1_is_unstable_when_sampled() {
        let d = RobustAdaptiveDesign::table_4_1();
        let r = sampled_pole_radius(&d, &joint()).unwrap();
        std::println!("Table 4.1 sampled pole radius at 4 ms: {r}");
        assert!(r > 100.0, "{r}");
    }

    #[test]
    fn design_at_4ms_meets_its_criterion() {
        let p = design_for_period(&table_4_1_known_stribeck_shape(), &joint()).unwrap();
        let d = p.params.design();
        std::println!(
            "{d:?}\n{:?}\nradius {} slope {}",
            p.bound,
            p.pole_radius,
            p.robust_slope
        );
        assert!(p.pole_radius <= 0.9);
        assert!(p.bound.sliding_radius <= d.eps_r);
        assert!(TAU / 2000.0 / 0.004 + d.lambda * TAU / 2000.0 <= d.eps_r / 2.0);
        assert_eq!(d.sample_period, 0.004);
        // The numbers `JointParams::table_4_1_at` documents.
        assert!((d.lambda - 56.78).abs() < 0.01, "{}", d.lambda);
        assert!((d.eps_r - 525.25).abs() < 0.01, "{}", d.eps_r);
        assert!((d.eps_velocity - 66.36).abs() < 0.01, "{}", d.eps_velocity);
        assert_eq!(d.eps_f[0], 30_000.0);
        assert_eq!(d.eps_f[1], d.eps_r);
        assert_eq!(d.eps_f[3], 0.1);
        assert_eq!(d.integral_gain, 0.0);
        assert!((p.pole_radius - 0.899).abs() < 1e-3, "{}", p.pole_radius);
        // Eq. (4.28)'s constant by hand: K_r = 0.044 + 0.002 + 0.114 + 0.01
        // = 0.170 N·m; c = (K_r ε_r + ρ_F1 ε_F1 + ρ_F2 ε_F2 + ρ_F3 ε_F3)/4.
        let c = (0.170 * d.eps_r + 1e-3 * 3e4 + 0.01 * d.eps_r * 2.0) / 4.0;
        assert!((p.bound.dissipation - c).abs() < 1e-9 * c);
        let rs = (2.0 * c / (1.14e-5 * d.lambda)).sqrt();
        assert!((p.bound.sliding_radius - rs).abs() < 1e-9 * rs);
        assert!((rs - 316.6).abs() < 0.1 && (rs / d.lambda - 5.577).abs() < 1e-3);
        // S is the slope with ε_F1 capped: K_r/ε_r + ρ_F1 q̇²/ε_F1 + 2ρ/ε.
        let s_capped = 0.170 / d.eps_r + 1e-3 * 1e4 / 3e4 + 0.02 / d.eps_r;
        assert!((p.robust_slope - s_capped).abs() < 1e-12);
    }

    /// The worst radius is the largest over the sixteen corners the module
    /// docs list, each built here from the documented quantities: `S` at
    /// rest (`K_r/ε_r`) and at the maximum speed, the friction slope 0 and
    /// `ν = b_max + (f_c,max + f_s,max)/ε_q̇`, both stiffnesses and both
    /// link inertias (link side, reflected by `N²`).
    #[test]
    fn worst_radius_is_the_worst_documented_corner() {
        let mut d = table_4_1_known_stribeck_shape();
        // A narrow friction layer, so that ν is large enough to matter.
        d.eps_velocity = 0.05;
        d.lambda = 40.0;
        d.eps_r = 300.0;
        let j = joint();
        let fmax = d.friction_bounds.max();
        let nu = fmax[0] + (fmax[1] + fmax[2]) / 0.05;
        let rest = d.robust_gain() / 300.0;
        let moving = robust_slope_at(&d, j.max_motor_speed);
        let mut worst = 0.0f64;
        let mut radii = std::vec::Vec::new();
        let built = corners(&d, &j);
        for il in j.link_inertia {
            for k in j.stiffness {
                for s in [rest, moving] {
                    for n in [0.0, nu] {
                        let a = closed_loop(
                            0.004,
                            1.14e-5,
                            il / 1e4,
                            k / 1e4,
                            40.0,
                            s,
                            n,
                            d.integral_gain,
                        );
                        assert!(built.contains(&a), "corner I_l {il}, K {k}, S {s}, ν {n}");
                        let r = pole_radius(&a);
                        radii.push(r);
                        worst = worst.max(r);
                    }
                }
            }
        }
        assert_eq!(sampled_pole_radius(&d, &j).unwrap(), worst);
        // Every corner counts: the radii differ, and ν moves them.
        assert!(radii.windows(2).any(|w| w[0] != w[1]));
        assert!(
            (0..16).step_by(2).all(|i| radii[i] != radii[i + 1]),
            "{radii:?}"
        );
    }

    /// Criterion item 3 (a count of speed and position moves `r` by at
    /// most half the layer) holds for every encoder resolution, and binds
    /// on a coarse encoder: with 4 counts per revolution the layer is
    /// wider than with 2000.
    #[test]
    fn quantisation_item_holds_for_coarse_encoders() {
        let base = table_4_1_known_stribeck_shape();
        let mut widths = std::vec::Vec::new();
        for m in [4u32, 6, 2000] {
            let j = SampledJoint {
                motor_counts_per_rev: m,
                ..joint()
            };
            let p = design_for_period(&base, &j).unwrap();
            let d = p.params.design();
            let q = TAU / m as f64;
            assert!(q / 0.004 + d.lambda * q <= d.eps_r / 2.0, "{m}: {d:?}");
            widths.push(d.eps_r);
        }
        assert!(widths[0] > widths[2], "{widths:?}");
    }

    /// A box with no Coulomb or Stribeck friction (`f_c = f_s = 0`, viscous
    /// only, `ρ_F4 > 0`): the Stribeck regressor bound is 0, so `ε_F4` keeps
    /// the base's value (a layer of `0 · G/S` would be rejected), and with
    /// nothing for the velocity layer to smooth `ε_q̇` is the largest one,
    /// the cap.
    #[test]
    fn viscous_only_box_keeps_its_layers() {
        let mut base = table_4_1_known_stribeck_shape();
        let (mut lo, mut hi, mut rho) = (
            base.friction_bounds.min(),
            base.friction_bounds.max(),
            base.friction_bounds.variable(),
        );
        for j in [1, 2] {
            lo[j] = 0.0;
            hi[j] = 0.0;
            rho[j] = 0.0;
        }
        rho[3] = 1e-3;
        base.friction_bounds = FrictionBounds::try_new(
            FrictionParams::from_array(lo),
            FrictionParams::from_array(hi),
            rho,
        )
        .unwrap();
        base.initial_friction.coulomb = 0.0;
        base.initial_friction.stribeck = 0.0;
        RobustAdaptiveParams::try_new(base).unwrap();
        assert_eq!(regressor_bounds(&base, 100.0)[3], 0.0);
        let p = design_for_period(&base, &joint()).unwrap();
        let d = p.params.design();
        assert_eq!(d.eps_f[3], base.eps_f[3]);
        assert_eq!(d.eps_velocity, layer_cap(None));
        assert!(p.pole_radius <= 0.9);
    }

    /// `K_I` is the largest rung of the half-decade ladder below the
    /// base's (`K_I,base·10^{−n/2}`, `n = 0…12`) that keeps item 1: the
    /// rung is found here by walking the ladder with
    /// [`sampled_pole_radius`] (not the design's own test), and on these
    /// two joints it is above 0, so the ladder is exercised.
    #[test]
    fn integral_gain_is_the_largest_rung_that_holds() {
        let base = table_4_1_known_stribeck_shape();
        for (t, k, il) in [(1e-3, 1e5, 0.01), (4e-3, 8e3, 0.03)] {
            let j = SampledJoint {
                sample_period: t,
                stiffness: [k, k],
                link_inertia: [il, il],
                max_pole_radius: 0.95,
                ..joint()
            };
            let p = design_for_period(&base, &j).unwrap();
            let d = *p.params.design();
            let rung = |n: i32| base.integral_gain * 10f64.powf(-n as f64 / 2.0);
            let holds = |ki: f64| {
                let mut trial = d;
                trial.integral_gain = ki;
                sampled_pole_radius(&trial, &j).unwrap() < 0.95
            };
            let n = (0..=12).find(|&n| holds(rung(n))).expect("a rung holds");
            assert!(n > 0 && d.integral_gain > 0.0, "{d:?}");
            assert!(
                (d.integral_gain - rung(n)).abs() <= 1e-12 * rung(n),
                "{n}: {d:?}"
            );
            assert!(p.pole_radius <= 0.95);
        }
    }

    /// Table 4.1's own base (Stribeck shape adapted over `[0.01, 10]`)
    /// has no sampled design at 4 ms, and says so with a typed error.
    #[test]
    fn table_4_1_base_has_no_sampled_design() {
        let e = design_for_period(&RobustAdaptiveDesign::table_4_1(), &joint()).unwrap_err();
        std::println!("{e}");
        assert!(
            matches!(e, DesignError::NoSampledDesign { smallest_radius, .. } if smallest_radius > 0.9)
        );
        // The known-shape base validates (it is a law the joint accepts).
        RobustAdaptiveParams::try_new(table_4_1_known_stribeck_shape()).unwrap();
    }

    /// Every range of the joint at its documented edge: the edge accepted,
    /// the next `f64` (or count) beyond it rejected by name.
    #[test]
    fn joint_ranges_at_their_edges() {
        let d = table_4_1_known_stribeck_shape();
        let accepts = |j: SampledJoint| sampled_pole_radius(&d, &j).is_ok();
        let rejects = |j: SampledJoint| sampled_pole_radius(&d, &j).unwrap_err();
        let j = joint();
        for t in [1e-6, 0.1] {
            assert!(accepts(SampledJoint {
                sample_period: t,
                ..j
            }));
        }
        for t in [1e-6f64.next_down(), 0.1f64.next_up()] {
            let e = rejects(SampledJoint {
                sample_period: t,
                ..j
            });
            assert!(
                matches!(e, ParamError::OutOfRange { name: "sample_period", min, max, .. }
                    if min == 1e-6 && max == 0.1),
                "{e}"
            );
        }
        assert!(accepts(SampledJoint { ratio: 1.0, ..j }));
        assert_eq!(
            rejects(SampledJoint {
                ratio: 1.0f64.next_down(),
                ..j
            })
            .name(),
            "ratio"
        );
        // Ordered ranges: equal ends accepted, reversed ones rejected.
        let k = 9e3;
        assert!(accepts(SampledJoint {
            stiffness: [k, k],
            ..j
        }));
        assert!(matches!(
            rejects(SampledJoint {
                stiffness: [k, k.next_down()],
                ..j
            }),
            ParamError::NotIncreasing {
                lower: "stiffness[0]",
                upper: "stiffness[1]",
                ..
            }
        ));
        assert_eq!(
            rejects(SampledJoint {
                stiffness: [0.0, k],
                ..j
            })
            .name(),
            "stiffness[0]"
        );
        assert_eq!(
            rejects(SampledJoint {
                stiffness: [k, 0.0],
                ..j
            })
            .name(),
            "stiffness[1]"
        );
        let il = 0.05;
        assert!(accepts(SampledJoint {
            link_inertia: [il, il],
            ..j
        }));
        assert!(matches!(
            rejects(SampledJoint {
                link_inertia: [il, il.next_down()],
                ..j
            }),
            ParamError::NotIncreasing {
                lower: "link_inertia[0]",
                upper: "link_inertia[1]",
                ..
            }
        ));
        assert_eq!(
            rejects(SampledJoint {
                link_inertia: [0.0, il],
                ..j
            })
            .name(),
            "link_inertia[0]"
        );
        assert_eq!(
            rejects(SampledJoint {
                link_inertia: [il, 0.0],
                ..j
            })
            .name(),
            "link_inertia[1]"
        );
        assert_eq!(
            rejects(SampledJoint {
                rotor_inertia: 0.0,
                ..j
            })
            .name(),
            "rotor_inertia"
        );
        assert!(accepts(SampledJoint {
            motor_counts_per_rev: 1,
            ..j
        }));
        assert!(matches!(
            rejects(SampledJoint {
                motor_counts_per_rev: 0,
                ..j
            }),
            ParamError::NotPositive {
                name: "motor_counts_per_rev",
                ..
            }
        ));
        assert_eq!(
            rejects(SampledJoint {
                max_motor_speed: 0.0,
                ..j
            })
            .name(),
            "max_motor_speed"
        );
        // ρ_max in (0, 1).
        assert!(accepts(SampledJoint {
            max_pole_radius: 1.0f64.next_down(),
            ..j
        }));
        assert!(matches!(
            rejects(SampledJoint { max_pole_radius: 1.0, ..j }),
            ParamError::OutOfRange { name: "max_pole_radius", min, max, .. } if min == 0.0 && max == 1.0
        ));
        assert!(matches!(
            rejects(SampledJoint {
                max_pole_radius: 0.0,
                ..j
            }),
            ParamError::NotPositive {
                name: "max_pole_radius",
                ..
            }
        ));
    }

    /// A base for another drive is rejected with the joint's value as the
    /// only accepted one; an invalid base names its own field; the
    /// messages carry the numbers.
    #[test]
    fn mismatched_or_invalid_base_is_named() {
        let mut base = table_4_1_known_stribeck_shape();
        base.rotor_inertia = 2e-5;
        let e = design_for_period(&base, &joint()).unwrap_err();
        assert_eq!(
            e,
            DesignError::Param(ParamError::OutOfRange {
                name: "rotor_inertia",
                value: 2e-5,
                min: 1.14e-5,
                max: 1.14e-5
            })
        );
        assert_eq!(
            std::format!("{e}"),
            std::format!(
                "{}",
                ParamError::OutOfRange {
                    name: "rotor_inertia",
                    value: 2e-5,
                    min: 1.14e-5,
                    max: 1.14e-5
                }
            )
        );
        let mut base = table_4_1_known_stribeck_shape();
        base.ratio = 50.0;
        assert_eq!(
            design_for_period(&base, &joint()).unwrap_err(),
            DesignError::Param(ParamError::OutOfRange {
                name: "ratio",
                value: 50.0,
                min: 100.0,
                max: 100.0
            })
        );
        let mut base = table_4_1_known_stribeck_shape();
        base.lambda = -1.0;
        assert!(matches!(
            design_for_period(&base, &joint()),
            Err(DesignError::Param(e)) if e.name() == "lambda"
        ));
        let e = DesignError::NoSampledDesign {
            sample_period: 0.004,
            smallest_radius: 1.5,
            max_pole_radius: 0.9,
        };
        let text = std::format!("{e}");
        assert!(
            text.contains("sample_period = 0.004 s")
                && text.contains("1.5")
                && text.contains("0.9"),
            "{text}"
        );
    }

    /// The caps are the largest layers the law accepts: each cap passes
    /// [`RobustAdaptiveParams::try_new`] and the next `f64` above it is
    /// rejected, naming the layer.
    #[test]
    fn layer_caps_are_the_largest_accepted_layers() {
        let base = table_4_1_known_stribeck_shape();
        let check = |set: &dyn Fn(&mut RobustAdaptiveDesign, f64), cap: f64, name: &str| {
            let mut d = base;
            set(&mut d, cap);
            assert!(RobustAdaptiveParams::try_new(d).is_ok(), "{name} = {cap}");
            set(&mut d, cap.next_up());
            assert_eq!(RobustAdaptiveParams::try_new(d).unwrap_err().name(), name);
        };
        check(&|d, v| d.eps_r = v, layer_cap(None), "eps_r");
        check(&|d, v| d.eps_velocity = v, layer_cap(None), "eps_velocity");
        let names = ["eps_f[0]", "eps_f[1]", "eps_f[2]", "eps_f[3]"];
        for (j, name) in names.iter().enumerate() {
            check(&|d, v| d.eps_f[j] = v, layer_cap(Some(j)), name);
        }
    }

    /// The regressor bounds against a dense search over `|q̇| ≤ q̇_max`:
    /// `|Y_4| = f_s q̇² e^{−f_τ q̇²}` peaks at `q̇² = 1/f_τ` when that speed
    /// is reached, and at `q̇_max` otherwise; the slope adds
    /// `ρ_Fj Y_j²/ε_Fj` to `K_r/ε_r`.
    #[test]
    fn regressor_bounds_match_a_search_over_speed() {
        let d = RobustAdaptiveDesign::table_4_1();
        let fs = d.friction_bounds.max()[2];
        let ft = d.friction_bounds.min()[3];
        for qd in [0.5, 3.0, 100.0] {
            let y = regressor_bounds(&d, qd);
            let n = 200_000;
            let search = (0..=n)
                .map(|i| {
                    let v = qd * i as f64 / n as f64;
                    fs * v * v * (-ft * v * v).exp()
                })
                .fold(0.0f64, f64::max);
            assert_eq!(&y[..3], &[qd, 1.0, 1.0]);
            assert!(
                y[3] >= search * (1.0 - 1e-12) && y[3] - search <= 1e-6 * search,
                "{qd}: {y:?} vs {search}"
            );
            let rho = d.friction_bounds.variable();
            let mut s = d.robust_gain() / d.eps_r;
            for j in 0..4 {
                s += rho[j] * y[j] * y[j] / d.eps_f[j];
            }
            assert!((robust_slope_at(&d, qd) - s).abs() <= 1e-12 * s);
            assert!(rho[3] > 0.0 && y[3] > 0.0);
        }
    }

    #[test]
    fn bad_inputs_name_their_field() {
        let base = RobustAdaptiveDesign::table_4_1();
        let mut j = joint();
        j.sample_period = 0.0;
        assert!(matches!(
            design_for_period(&base, &j),
            Err(DesignError::Param(ParamError::OutOfRange {
                name: "sample_period",
                ..
            }))
        ));
        let mut j = joint();
        j.stiffness = [9e3, 8e3];
        assert!(matches!(
            design_for_period(&base, &j),
            Err(DesignError::Param(ParamError::NotIncreasing {
                lower: "stiffness[0]",
                ..
            }))
        ));
        let mut j = joint();
        j.max_pole_radius = 1.0;
        assert!(matches!(
            design_for_period(&base, &j),
            Err(DesignError::Param(ParamError::OutOfRange {
                name: "max_pole_radius",
                ..
            }))
        ));
        let mut j = joint();
        j.link_inertia[1] = f64::NAN;
        assert!(matches!(
            design_for_period(&base, &j),
            Err(DesignError::Param(ParamError::NotFinite {
                name: "link_inertia[1]",
                ..
            }))
        ));
    }
}
