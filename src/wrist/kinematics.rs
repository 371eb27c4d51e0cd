//! Forward and inverse kinematics of the DAUJ wrist, thesis §5.2–5.3,
//! eq. (5.4)–(5.15).
//!
//! # Frames and conventions
//!
//! Motor 1 turns the lower semi-sphere by `θ1` about the base `z` axis; the
//! upper semi-sphere turns by `θ3` about the output `z` axis; the internal
//! oblique joint (axis inclined by `φ`) turns by `θ4`. The output
//! orientation is, eq. (5.4) in the product order of the matrices printed
//! in eq. (5.5) (errata E5.1):
//!
//! ```text
//! R(θ1, θ4, θ3) = R_z(θ1) R_x(φ) R_z(θ4) R_x(−φ) R_z(θ3)
//! ```
//!
//! The outer universal joint makes it `R = R_y(δ)R_x(γ)`, eq. (5.6)–(5.7):
//! pitch `δ` about the base `y` axis, then yaw `γ` about the new `x` axis,
//! both in rad. The straight pose is `δ = γ = 0`; it is reached for every
//! `θ1 = −θ3` (a circle of motor positions), e.g. the thesis's
//! `θ1 = θ3 = 0` and `θ1 = 1, θ3 = −1`.
//!
//! # The inclination `φ`
//!
//! The thesis never states `φ`. The only number that depends on it is the
//! branch test of §5.2: at `θ1 = 1, θ3 = −1` the other root of eq. (5.10)
//! gives `δ = −2.6681`, `γ = 2.8342`. Solving each of these for `φ` (the
//! root is monotone in `φ`) gives the intervals `[15.9973°, 16.0006°]` and
//! `[15.9964°, 16.0014°]` (the 4-digit rounding of the print); both contain
//! exactly one round value, `φ = 16°` ([`WristParams::THESIS_PHI_DEG`];
//! test `tests::phi_is_recovered_from_the_printed_branch_test`). The
//! product order of the first line of eq. (5.4) gives the same numbers with
//! both signs flipped. The rejected root is public,
//! [`WristConfig::forward_plus_root`], so that the search can be rerun
//! from the API (its example does).
//!
//! # Forward kinematics, eq. (5.8)–(5.12)
//!
//! `R = R_y(δ)R_x(γ)` holds exactly when `t21 = 0` (the first column of
//! `R_y R_x` has no `y` component, and any rotation whose first column has
//! none is such a product), which is the constraint eq. (5.8). Written as
//! `A cos θ4 + B sin θ4 = C`, eq. (5.9), it has the two roots of
//! eq. (5.10), `θ4 = a ± acos(C/b)`. The physical one is
//! `θ4 = a − acos(C/b)`, eq. (5.12), **for every motor position**, not only
//! at the test point:
//!
//! * `|C/b| ≤ tan²φ < 1` for `φ < 45°` (`C = −C1 S3 Sφ²`, `b ≥ Cφ²`;
//!   `tests::constraint_roots_never_merge`), so the two roots never merge
//!   and each is a continuous function on the motor torus;
//! * on either root `t11 = cos δ` and `t33 = cos δ cos γ ≥ cos 2φ > 0`, so
//!   `cos δ` never changes sign along a root: it has the sign it has at the
//!   test point, where the `−` root is the straight pose (`cos δ = 1`) and
//!   the `+` root has `cos δ < 0` (a universal joint turned past 90°, not a
//!   pose of the wrist).
//!
//! Then `δ = atan2(−t31, t11)`, `γ = atan2(−t23, t22)`, eq. (5.11).
//!
//! # Inverse kinematics, eq. (5.13)–(5.15)
//!
//! With `β` the bend of the output axis (`cos β = cos δ cos γ`), eq. (5.13)
//! reads `sin(θ4/2) = sin(β/2)/sin φ`: the workspace is `β ≤ 2φ`. The
//! library evaluates it in that half-angle form, with
//! `sin²(β/2) = sin²(δ/2) + cos δ sin²(γ/2)`, which has no cancellation
//! near the straight pose (the printed `acos((CδCγ − Cφ²)/Sφ²)` loses half
//! the digits there). [`WristConfig::inverse`] takes the root `θ4 ≥ 0` of
//! eq. (5.14) (see "Two roots" below for the other). From the
//! third column and row of `R` (derivation in
//! `docs/derivations/wrist_fk.py`), with `ψ = atan2(Cφ sin(θ4/2), cos(θ4/2))`:
//!
//! ```text
//! θ1 =  π + atan2(−Sγ, Cγ Sδ) − ψ,
//! θ3 = −π + atan2(Cδ Sγ, Sδ) − ψ,
//! ```
//!
//! which is eq. (5.14) divided by `2 sin(θ4/2) sin φ` (the printed
//! `C_1` has `C_δ` for `S_δ`, errata E5.4). It divides nothing by zero:
//! at the straight pose the direction of the bend is undefined — the
//! mechanism is singular there (see [`super::jacobian`]) — and
//! [`WristConfig::inverse`] returns the representative `θ1 = θ3 = 0`;
//! [`IkState`] keeps the previous motor positions instead.
//!
//! The continuity fix, eq. (5.15): on the selected branch
//! `u = θ1 + θ3 ∈ [−π − ε, ε]`, `ε = atan(sin²φ/cos 2φ)`. The library returns `θ1 ∈ (−π, π]` and
//! `θ3 = u − θ1` with `u` evaluated as the continuous
//! `atan2(−2 S_δ S_γ sin²(β/2), C_γ S_δ² + C_δ S_γ²) − 2ψ`, which is the
//! printed rule `θ3 ← θ3 + 2μπ` with the threshold moved to where the
//! branch lives (errata E5.5). `θ1` itself must jump by `2π` somewhere: it
//! winds once around the straight pose. [`IkState`] unwraps both motors
//! to the nearest multiple of `2π` of their previous value.
//!
//! # Two roots, and the one taken in time
//!
//! Eq. (5.13) fixes `sin(θ4/2) = sin(β/2)/sin φ ≥ 0` only; `cos(θ4/2)` is
//! either square root. The axis of the output before `R_z(θ1)` has the
//! horizontal part `−2 sin φ sin(θ4/2) · P` with `P = (cos(θ4/2),
//! cos φ sin(θ4/2))` (as a complex number, `ψ = arg P`), which `R_z(θ1)`
//! must turn onto `A = (Cγ Sδ, −Sγ)`. The root `cos(θ4/2) ≥ 0` (`θ4 ≥ 0`)
//! gives the formulas above; the root `cos(θ4/2) ≤ 0` (`θ4 ≤ 0`, the same
//! joint as `2π − θ4`) replaces `P` by `(−cos(θ4/2), cos φ sin(θ4/2))`,
//! i.e. `ψ` by `π − ψ`:
//!
//! ```text
//! θ1' = atan2(−Sγ, Cγ Sδ) + ψ = θ1 + 2ψ + π,
//! θ3' = atan2(Cδ Sγ, Sδ) + ψ  = θ3 + 2ψ + π   (mod 2π),
//! ```
//!
//! with `θ1' + θ3' = ε(δ, γ) + 2ψ ∈ [−ε, π + ε]`, the mirror image of
//! eq. (5.15)'s interval ([`WristConfig::inverse_other_branch`]; checked
//! against the rotation matrices in `tests::both_branches_reach_the_pose`).
//! The two roots are the two motor positions of each pose; they are
//! `π − 2ψ` apart on both motors: about `π` near the straight pose and `0`
//! on the boundary `β = 2φ`, where they meet (`θ4 = ±π`).
//!
//! A path through the straight pose reverses `A`: on one root the motors
//! turn by `π` there in no time, while on the path `θ1 = arg A + π − ψ`
//! passes continuously into `θ1' = arg A' + ψ` of the other root (`A' = −A`,
//! `ψ → 0`). [`WristConfig::update`] (and the wrist step,
//! [`super::step`]) therefore takes, on every sample, **the root whose `θ1`
//! is nearer the previous `θ1`**; `θ4 ≥ 0` on a tie. The two candidates
//! `arg A + ψ` and `arg A + π − ψ` are mirror images about
//! `arg A ± π/2`, so the nearer one is `θ4 ≤ 0` exactly when
//! `A·(cos θ1_prev, sin θ1_prev) > 0`: two products, no root and no
//! `atan2` more. `θ1` alone decides because the roots are the same angle
//! `π − 2ψ` apart on both motors: a sample that moves the motors by less
//! than half of it picks the same root for both; and where the roots
//! are `π` apart, near the straight pose (held there at `θ3 = −θ1`),
//! `B = (Sδ, Cδ Sγ)` is nearly `(A_x, −A_y)` and `θ3` nearly `−θ1`, so
//! `θ3`'s own test, `B·(cos θ3_prev, sin θ3_prev) > 0`, agrees. Away
//! from the straight pose and the boundary this is the root already in
//! use; on the boundary the choice is void (the roots coincide). The
//! motors then cross the straight pose with speeds bounded by the path's
//! (`tests::tracker_crosses_the_straight_pose_continuously`).
//! [`WristConfig::inverse`], which has no previous sample, keeps `θ4 ≥ 0`.

use crate::error::{finite, ParamError};
use crate::scalar::Scalar;

/// Parameters of the DAUJ wrist: the inclination `φ` of the internal
/// oblique joint (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristParams {
    phi: f64,
}

impl WristParams {
    /// The inclination that reproduces the thesis's own numbers of §5.2,
    /// in degrees (see the module docs).
    pub const THESIS_PHI_DEG: f64 = 16.0;

    /// Validate `φ` (rad): finite and in `[1°, 30°]`. Below 45° the two
    /// roots of eq. (5.10) never merge (`|C/b| ≤ tan²φ < 1`); below 30° the
    /// Jacobian's denominator `D = Sδ Sφ S1 + Cδ Cφ ≥ cos 3φ` stays positive
    /// (see [`super::jacobian`]). Above 1° the workspace is wider than the
    /// `I16F16` resolution by four orders of magnitude.
    pub fn try_new(phi: f64) -> Result<Self, ParamError> {
        let phi = finite("phi", phi)?;
        let (min, max) = (1f64.to_radians(), 30f64.to_radians());
        if !(min..=max).contains(&phi) {
            return Err(ParamError::OutOfRange {
                name: "phi",
                value: phi,
                min,
                max,
            });
        }
        Ok(WristParams { phi })
    }

    /// The thesis's wrist, `φ = 16°`.
    pub fn thesis() -> Self {
        WristParams {
            phi: Self::THESIS_PHI_DEG.to_radians(),
        }
    }

    /// The inclination `φ` (rad).
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// The largest bend of the output axis, `2φ` (rad): the workspace is
    /// `acos(cos δ cos γ) ≤ 2φ`.
    pub fn max_bend(&self) -> f64 {
        2.0 * self.phi
    }

    /// Whether `(δ, γ)` (rad) is reachable: `|δ|, |γ| ≤ π/2` and
    /// `cos δ cos γ ≥ cos 2φ`.
    pub fn is_reachable(&self, delta: f64, gamma: f64) -> bool {
        let h = core::f64::consts::FRAC_PI_2;
        delta.abs() <= h
            && gamma.abs() <= h
            && libm::cos(delta) * libm::cos(gamma) >= libm::cos(2.0 * self.phi)
    }
}

impl Default for WristParams {
    fn default() -> Self {
        Self::thesis()
    }
}

/// Motor-side angles (rad): `θ1` of motor 1 (lower semi-sphere) and `θ3`
/// of the upper semi-sphere driven by motor 2 (eq. 5.1 relates it to the
/// motor-2 shaft angle `θ2`). Zero at the thesis's initial status.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotorAngles<S> {
    /// `θ1` (rad), positive about the base `z` axis.
    pub theta1: S,
    /// `θ3` (rad), positive about the output `z` axis.
    pub theta3: S,
}

/// Output angles of the outer universal joint (rad), eq. (5.6).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PitchYaw<S> {
    /// Pitch `δ` (rad) about the base `y` axis.
    pub delta: S,
    /// Yaw `γ` (rad) about the `x` axis after the pitch.
    pub gamma: S,
}

/// Result of [`WristConfig::forward`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Forward<S> {
    /// The output angles, `|δ|, |γ| ≤ 2φ` (up to the backend's rounding).
    pub pose: PitchYaw<S>,
    /// The oblique joint angle `θ4 ∈ (−π, π]` (rad) of the root evaluated:
    /// the physical one, eq. (5.12), for [`WristConfig::forward`].
    pub theta4: S,
}

/// Result of [`WristConfig::inverse`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inverse<S> {
    /// The motor angles: `θ1 ∈ (−π, π]`, `θ1 + θ3 ∈ [−π − ε, ε]` with
    /// `ε = atan(sin²φ/cos 2φ)`, 0.09 for `φ = 16°` (rad, up to
    /// rounding) on the root `θ4 ≥ 0`, `[−ε, π + ε]` on the other;
    /// continuous (turns accumulated) from [`WristConfig::update`].
    pub motors: MotorAngles<S>,
    /// The oblique joint angle (rad), eq. (5.13): `θ4 ∈ [0, π]` from
    /// [`WristConfig::inverse`], `[−π, 0]` from
    /// [`WristConfig::inverse_other_branch`]; [`WristConfig::update`]
    /// returns the root it took.
    pub theta4: S,
    /// The pose the motors reach: the input, or its projection onto the
    /// workspace boundary when `saturated`.
    pub pose: PitchYaw<S>,
    /// The input was outside the workspace (`|δ|` or `|γ| > π/2`, a bend
    /// above `2φ`, or NaN or infinite, which is read as 0): `pose` is the
    /// nearest reachable pose in the same bend direction.
    pub saturated: bool,
    /// The pose is the straight pose (bend below the backend's
    /// resolution): the motor angles are the representative
    /// `θ1 = θ3 = 0` of the circle `θ1 + θ3 = 0` that reaches it.
    pub straight: bool,
}

/// A pose outside the workspace, as rejected by
/// [`WristConfig::try_inverse`]. Angles in rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unreachable {
    /// The requested pitch (rad).
    pub delta: f64,
    /// The requested yaw (rad).
    pub gamma: f64,
    /// Its bend `acos(cos δ cos γ)` (rad).
    pub bend: f64,
    /// The largest bend, `2φ` (rad).
    pub max_bend: f64,
}

impl core::fmt::Display for Unreachable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "wrist pose (delta = {}, gamma = {}) rad is unreachable: bend {} rad exceeds 2 phi = {} rad (or |delta|, |gamma| > pi/2)",
            self.delta, self.gamma, self.bend, self.max_bend
        )
    }
}

#[cfg(feature = "std")]
impl std::error::Error for Unreachable {}

/// The wrist kinematics quantized for backend `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristConfig<S> {
    pub(crate) sin_phi: S,
    pub(crate) cos_phi: S,
    pub(crate) sin_phi_sq: S,
    pub(crate) cos_phi_sq: S,
    pub(crate) tan_phi: S,
    pub(crate) sin_max_bend: S,
    pub(crate) cos_max_bend: S,
    /// `2φ` (rad).
    pub(crate) max_bend: S,
    phi: f64,
}

/// `2π` on backend `S` as `PI + PI` (exact on floats; on `I16F16` 0.81 LSB
/// below 2π, which [`wrap`] keeps: one wrap, and its result stays within
/// `(−PI, PI]`).
#[inline]
pub(crate) fn two_pi<S: Scalar>() -> S {
    S::PI.add(S::PI)
}

/// `x` wrapped to `(−π, π]`, for `|x| < 3π`.
#[inline]
pub(crate) fn wrap<S: Scalar>(x: S) -> S {
    if x > S::PI {
        x.sub(two_pi())
    } else if x <= S::PI.neg() {
        x.add(two_pi())
    } else {
        x
    }
}

/// NaN and infinities read as 0 (floats; a no-op on fixed point).
#[inline]
pub(crate) fn denan<S: Scalar>(x: S) -> S {
    if x.is_nan() || x.abs() > S::MAX {
        S::ZERO
    } else {
        x
    }
}

#[inline]
pub(crate) fn sq<S: Scalar>(x: S) -> S {
    x.mul(x)
}

pub(crate) use crate::scalar::hypot;

impl<S: Scalar> WristConfig<S> {
    /// Quantize validated parameters.
    pub fn new(p: &WristParams) -> Self {
        let phi = p.phi;
        WristConfig {
            sin_phi: S::from_f64(libm::sin(phi)),
            cos_phi: S::from_f64(libm::cos(phi)),
            sin_phi_sq: S::from_f64(libm::sin(phi) * libm::sin(phi)),
            cos_phi_sq: S::from_f64(libm::cos(phi) * libm::cos(phi)),
            tan_phi: S::from_f64(libm::tan(phi)),
            sin_max_bend: S::from_f64(libm::sin(2.0 * phi)),
            cos_max_bend: S::from_f64(libm::cos(2.0 * phi)),
            max_bend: S::from_f64(2.0 * phi),
            phi,
        }
    }

    /// The inclination `φ` (rad) this configuration was built from.
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// Forward kinematics, eq. (5.8)–(5.12): motor angles (rad, any value;
    /// NaN and infinities are read as 0) to the pose and the oblique joint angle. Every
    /// motor position is a pose of the wrist: there is no error case.
    pub fn forward(&self, m: MotorAngles<S>) -> Forward<S> {
        self.forward_on_root(m, false)
    }

    /// The forward kinematics on the other root of eq. (5.10),
    /// `θ4 = a + acos(C/b)`: the root the thesis rejects in §5.2. It is a
    /// solution of the closure eq. (5.7)–(5.8) but not a pose of the wrist
    /// (`cos δ < 0` everywhere on it: the outer universal joint turned
    /// past 90°; module docs), so controllers use [`forward`](Self::forward).
    /// It is exposed so that the branch test of §5.2, and the search for
    /// the unstated `φ` that it permits (errata E5.3), can be rerun from
    /// the public API. Motor angles in rad (NaN and infinities read as 0);
    /// `δ = atan2(−t31, t11)`, `γ = atan2(−t23, t22)` of eq. (5.11) on
    /// that root, so `|δ| > π/2` is expected.
    ///
    /// ```
    /// use mrr_control::wrist::{MotorAngles, WristConfig, WristParams};
    /// // §5.2: at θ1 = 1, θ3 = −1 the `+` root gives δ = −2.6681, γ = 2.8342.
    /// let m = MotorAngles { theta1: 1.0f64, theta3: -1.0 };
    /// let other = |phi: f64| {
    ///     WristConfig::<f64>::new(&WristParams::try_new(phi).unwrap()).forward_plus_root(m)
    /// };
    /// let p = other(16f64.to_radians()).pose;
    /// assert!((p.delta + 2.6681).abs() < 5e-5 && (p.gamma - 2.8342).abs() < 5e-5);
    /// // The physical root is the straight pose there.
    /// let cfg = WristConfig::<f64>::new(&WristParams::thesis());
    /// assert!(cfg.forward(m).pose.delta.abs() < 1e-12);
    /// // The φ search: bisect the printed γ = 2.8342 for φ on [10°, 25°]
    /// // (γ on the `+` root falls as φ grows).
    /// let (mut lo, mut hi) = (10f64.to_radians(), 25f64.to_radians());
    /// for _ in 0..50 {
    ///     let mid = 0.5 * (lo + hi);
    ///     if other(mid).pose.gamma > 2.8342 { lo = mid } else { hi = mid }
    /// }
    /// assert!((lo.to_degrees() - 16.0).abs() < 2e-3, "{}", lo.to_degrees());
    /// ```
    pub fn forward_plus_root(&self, m: MotorAngles<S>) -> Forward<S> {
        self.forward_on_root(m, true)
    }

    /// Eq. (5.8)–(5.11) on the root `θ4 = a ∓ acos(C/b)` of eq. (5.10):
    /// `−` (eq. 5.12, the physical one) for `plus = false`.
    fn forward_on_root(&self, m: MotorAngles<S>, plus: bool) -> Forward<S> {
        let (s1, c1) = denan(m.theta1).sin_cos();
        let (s3, c3) = denan(m.theta3).sin_cos();
        let (cp, sp, cp2, sp2) = (self.cos_phi, self.sin_phi, self.cos_phi_sq, self.sin_phi_sq);
        // Eq. (5.9): A cos θ4 + B sin θ4 = C.
        let a_coef = s1.mul(c3).add(c1.mul(s3).mul(cp2));
        let c13 = c1.mul(c3).sub(s1.mul(s3));
        let b_coef = cp.mul(c13);
        let c_coef = c1.mul(s3).mul(sp2).neg();
        // Eq. (5.10) and the physical root, eq. (5.12), repeated as (5.18).
        let b = hypot(a_coef, b_coef);
        let a = b_coef.atan2(a_coef);
        let half_width = c_coef.div(b).acos();
        let theta4 = wrap(if plus {
            a.add(half_width)
        } else {
            a.sub(half_width)
        });
        let (s4, c4) = theta4.sin_cos();
        let v = S::ONE.sub(c4);
        // Entries of eq. (5.5) (t11 with the term the print drops, E5.2).
        let t11 = c1
            .mul(c4)
            .mul(c3)
            .sub(s1.mul(s4).mul(c3).mul(cp))
            .sub(c1.mul(s4).mul(s3).mul(cp))
            .sub(s1.mul(c4).mul(s3).mul(cp2))
            .sub(s1.mul(s3).mul(sp2));
        let t31 = sp.mul(s4.mul(c3).sub(v.mul(cp).mul(s3)));
        let t22 = c1
            .mul(c4)
            .mul(c3)
            .mul(cp2)
            .add(c1.mul(c3).mul(sp2))
            .sub(s1.mul(c4).mul(s3))
            .sub(c1.mul(s4).mul(s3).mul(cp))
            .sub(s1.mul(s4).mul(c3).mul(cp));
        let t23 = sp.mul(c1.mul(v).mul(cp).add(s1.mul(s4))).neg();
        // Eq. (5.11).
        Forward {
            pose: PitchYaw {
                delta: t31.neg().atan2(t11),
                gamma: t23.neg().atan2(t22),
            },
            theta4,
        }
    }

    /// Inverse kinematics, eq. (5.13)–(5.15), saturating: a pose outside
    /// the workspace is replaced by the reachable pose of the same bend
    /// direction on its boundary, and flagged. Never NaN. The root
    /// `θ4 ≥ 0` (`cos(θ4/2) ≥ 0`); [`inverse_other_branch`](Self::inverse_other_branch)
    /// gives the other preimage and [`update`](Self::update) chooses
    /// between them (module docs).
    pub fn inverse(&self, target: PitchYaw<S>) -> Inverse<S> {
        self.inverse_branches(target).0
    }

    /// The other preimage of [`inverse`](Self::inverse): the same pose
    /// (and the same projection and flags) reached with the oblique joint
    /// at `−θ4 ∈ [−π, 0]`, i.e. `cos(θ4/2) ≤ 0` in eq. (5.13). Its motor
    /// angles are `θ1' = θ1 + 2ψ + π`, `θ3' = θ3 + 2ψ + π` (mod `2π`),
    /// returned as `θ1' ∈ (−π, π]` and `θ1' + θ3' ∈ [−ε, π + ε]` (module
    /// docs). At the straight pose it is [`inverse`](Self::inverse)'s
    /// representative; on the workspace boundary (`θ4 = π`) the two
    /// preimages are the same motor angles (`θ3'` may differ by `2π`).
    ///
    /// ```
    /// use mrr_control::wrist::{PitchYaw, WristConfig, WristParams};
    /// let cfg = WristConfig::<f64>::new(&WristParams::thesis());
    /// let pose = PitchYaw { delta: 0.2, gamma: -0.1 };
    /// let other = cfg.inverse_other_branch(pose);
    /// assert!(other.theta4 < 0.0);
    /// let back = cfg.forward(other.motors);
    /// assert!((back.pose.delta - 0.2).abs() < 1e-12 && (back.pose.gamma + 0.1).abs() < 1e-12);
    /// assert!((back.theta4 - other.theta4).abs() < 1e-12);
    /// ```
    pub fn inverse_other_branch(&self, target: PitchYaw<S>) -> Inverse<S> {
        self.inverse_branches(target).1
    }

    /// Both preimages of `target`: `(θ4 ≥ 0, θ4 ≤ 0)`.
    pub(crate) fn inverse_branches(&self, target: PitchYaw<S>) -> (Inverse<S>, Inverse<S>) {
        let half_pi = S::FRAC_PI_2;
        let d0 = denan(target.delta);
        let g0 = denan(target.gamma);
        // NaN and ±∞ (read as 0 above) are outside the workspace.
        let nan = d0 != target.delta || g0 != target.gamma;
        let mut d = d0.clamp(half_pi.neg(), half_pi);
        let mut g = g0.clamp(half_pi.neg(), half_pi);
        let mut saturated = nan || d != d0 || g != g0;
        let (mut sd, mut cd) = d.sin_cos();
        let (mut sg, mut cg) = g.sin_cos();
        let two = S::ONE.add(S::ONE);
        let half = S::ONE.div_unit_range(two);
        // sin(β/2) = |(sin(δ/2), √cos δ · sin(γ/2))|, eq. (5.13) in half
        // angles (a norm, not a difference of cosines: exact near the
        // straight pose on every backend).
        let mut half_bend = hypot(d.mul(half).sin(), cd.sqrt().mul(g.mul(half).sin()));
        if half_bend > self.sin_phi {
            // Outside: the boundary pose with the same output-axis
            // azimuth, z = (sin 2φ·n, cos 2φ).
            saturated = true;
            let (zx, zy) = (sd.mul(cg), sg.neg());
            let n = hypot(zx, zy);
            let (ux, uy) = if n > S::ZERO {
                // n ≥ max(|zx|, |zy|): the root of 1 + r² is at least 1.
                (zx.div_unit_range(n), zy.div_unit_range(n))
            } else {
                (S::ONE, S::ZERO)
            };
            let (bx, by, bz) = (
                ux.mul(self.sin_max_bend),
                uy.mul(self.sin_max_bend),
                self.cos_max_bend,
            );
            d = bx.atan2(bz);
            g = by.neg().atan2(hypot(bx, bz));
            (sd, cd) = d.sin_cos();
            (sg, cg) = g.sin_cos();
            half_bend = self.sin_phi;
        }
        let half_bend_sq = sq(half_bend);
        let pose = PitchYaw { delta: d, gamma: g };
        // sin(θ4/2) ∈ [0, 1], cos(θ4/2) ≥ 0.
        let sh = half_bend.div_unit_range(self.sin_phi).min(S::ONE);
        let ch = S::ONE.sub(sq(sh)).sqrt();
        let theta4 = two.mul(sh.atan2(ch));
        if sh == S::ZERO {
            let r = Inverse {
                motors: MotorAngles::default(),
                theta4: S::ZERO,
                pose,
                saturated,
                straight: true,
            };
            return (r, r);
        }
        let psi = self.cos_phi.mul(sh).atan2(ch);
        // Eq. (5.14), divided by 2 sin(θ4/2) sin φ.
        let az_z = sg.neg().atan2(cg.mul(sd));
        let theta1 = wrap(S::PI.add(az_z).sub(psi));
        // Eq. (5.15): u = θ1 + θ3 continuous on the branch, in [−π − ε, ε].
        let eps = two
            .mul(sd)
            .mul(sg)
            .mul(half_bend_sq)
            .neg()
            .atan2(cg.mul(sq(sd)).add(cd.mul(sq(sg))));
        let u = eps.sub(two.mul(psi));
        let plus = Inverse {
            motors: MotorAngles {
                theta1,
                theta3: u.sub(theta1),
            },
            theta4,
            pose,
            saturated,
            straight: false,
        };
        // The root cos(θ4/2) ≤ 0 of eq. (5.13): ψ → π − ψ, so θ1 = az + ψ
        // and u = ε + 2ψ (module docs).
        let theta1 = wrap(az_z.add(psi));
        let minus = Inverse {
            motors: MotorAngles {
                theta1,
                theta3: eps.add(two.mul(psi)).sub(theta1),
            },
            theta4: theta4.neg(),
            ..plus
        };
        (plus, minus)
    }

    /// Inverse kinematics that rejects an unreachable pose with a typed
    /// error instead of saturating. The test is in `f64` on the stored
    /// pose, against the exact `sin²φ`, with a tolerance of 4 resolution
    /// steps of the backend on the bend at the edge (`2 q sin 2φ` on
    /// `sin²(β/2)`, whose derivative is `½ sin β`), so that the boundary
    /// as the backend rounds it is accepted.
    pub fn try_inverse(&self, target: PitchYaw<S>) -> Result<Inverse<S>, Unreachable> {
        let (d, g) = (target.delta.to_f64(), target.gamma.to_f64());
        let h = core::f64::consts::FRAC_PI_2;
        let (sdh, sgh) = (libm::sin(d / 2.0), libm::sin(g / 2.0));
        let hb = sdh * sdh + libm::cos(d) * sgh * sgh;
        let sp = libm::sin(self.phi);
        let tol = 2.0 * S::RESOLUTION.to_f64() * libm::sin(2.0 * self.phi);
        if d.is_nan() || g.is_nan() || d.abs() > h || g.abs() > h || hb > sp * sp + tol {
            return Err(Unreachable {
                delta: d,
                gamma: g,
                bend: libm::acos((libm::cos(d) * libm::cos(g)).clamp(-1.0, 1.0)),
                max_bend: 2.0 * self.phi,
            });
        }
        let mut r = self.inverse(target);
        r.saturated = false;
        r.pose = target;
        Ok(r)
    }
}

/// The motor positions of the previous sample, for an inverse kinematics
/// that is continuous in time (eq. 5.15 generalized): the root of eq.
/// (5.13) whose `θ1` is nearer the previous one (module docs), each motor
/// unwrapped to the multiple of `2π` nearest its previous value, and at
/// the straight pose the motors stay where they are on the circle
/// `θ1 + θ3 = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IkState<S> {
    /// The last motor angles returned (rad); start from the measured ones.
    pub motors: MotorAngles<S>,
}

impl<S: Scalar> IkState<S> {
    /// Start from measured motor angles (rad).
    pub fn new(motors: MotorAngles<S>) -> Self {
        IkState { motors }
    }
}

impl<S: Scalar> WristConfig<S> {
    /// Inverse kinematics continuous in time: of the two roots
    /// ([`WristConfig::inverse`], `θ4 ≥ 0`, and
    /// [`WristConfig::inverse_other_branch`], `θ4 ≤ 0`) the one whose `θ1`
    /// is nearer the previous sample's (`state`; `θ4 ≥ 0` on a tie; module
    /// docs), then each motor angle moved by a multiple of `2π` to the
    /// nearest of the previous sample's, which it updates. At the straight
    /// pose `θ1` keeps its previous value and `θ3 = −θ1` (mod `2π`). A
    /// state started at measured motors picks their root on the first
    /// sample.
    /// Motor angles accumulate turns; on `I16F16` they saturate after
    /// about 5,000 turns.
    pub fn update(&self, state: &mut IkState<S>, target: PitchYaw<S>) -> Inverse<S> {
        let (plus, minus) = self.inverse_branches(target);
        let prev = state.motors;
        let (p1, p3) = (denan(prev.theta1), denan(prev.theta3));
        // The branch whose θ1 is nearer the previous θ1 (`θ4 ≥ 0` on a
        // tie); module docs.
        let off = |n: S| {
            let d = n.to_f64() - p1.to_f64();
            libm::fabs(d - libm::round(d / core::f64::consts::TAU) * core::f64::consts::TAU)
        };
        let mut r = if off(minus.motors.theta1) < off(plus.motors.theta1) {
            minus
        } else {
            plus
        };
        let (n1, n3) = if r.straight {
            (p1, p1.neg())
        } else {
            (r.motors.theta1, r.motors.theta3)
        };
        // Nearest representative: p + (n − p reduced to [−π, π]). The
        // difference and its reduction are formed in `f64`, where both
        // backends' values are exact and `2π` is accurate to 2.4e-16: the
        // result stays congruent to `n` (within the two roundings to `S`)
        // however many turns `p` holds. The former reduction by the
        // backend's own `2π` (`PI + PI`, 0.81 LSB short on `I16F16`) drifted
        // by that error per turn: 1.6e-3 rad after 127 turns. The clamp
        // only acts where `f64` cannot resolve the reduction (`f32`
        // angles beyond 2⁵⁰ rad), keeping each step within ±π.
        let near = |p: S, n: S| {
            let d = n.to_f64() - p.to_f64();
            let d = d - libm::round(d / core::f64::consts::TAU) * core::f64::consts::TAU;
            let d = d.clamp(-core::f64::consts::PI, core::f64::consts::PI);
            p.add(S::from_f64(d))
        };
        r.motors = MotorAngles {
            theta1: near(p1, n1),
            theta3: near(p3, n3),
        };
        state.motors = r.motors;
        r
    }
}

#[cfg(test)]
pub(crate) mod tests {
    extern crate std;
    use super::*;
    use crate::scalar::I16F16;
    use core::f64::consts::PI;
    use proptest::prelude::*;

    /// Rotation matrices built from their definitions (the reference).
    pub(crate) type Mat = [[f64; 3]; 3];
    pub(crate) fn mul(a: &Mat, b: &Mat) -> Mat {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    }
    pub(crate) fn rz(a: f64) -> Mat {
        let (s, c) = a.sin_cos();
        [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
    }
    pub(crate) fn rx(a: f64) -> Mat {
        let (s, c) = a.sin_cos();
        [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
    }
    pub(crate) fn ry(a: f64) -> Mat {
        let (s, c) = a.sin_cos();
        [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    }
    /// Eq. (5.4) in the order of the matrices of eq. (5.5).
    pub(crate) fn chain(phi: f64, t1: f64, t4: f64, t3: f64) -> Mat {
        mul(
            &mul(&mul(&mul(&rz(t1), &rx(phi)), &rz(t4)), &rx(-phi)),
            &rz(t3),
        )
    }
    /// Eq. (5.6).
    pub(crate) fn pitch_yaw(d: f64, g: f64) -> Mat {
        mul(&ry(d), &rx(g))
    }
    pub(crate) fn dist(a: &Mat, b: &Mat) -> f64 {
        let mut m: f64 = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                m = m.max((a[i][j] - b[i][j]).abs());
            }
        }
        m
    }

    /// Both roots of eq. (5.10) by an independent route: a dense scan of
    /// `t21(θ4)` for sign changes, refined by bisection.
    fn roots_by_scan(phi: f64, t1: f64, t3: f64) -> std::vec::Vec<f64> {
        let f = |t4: f64| chain(phi, t1, t4, t3)[1][0];
        let n = 2000;
        let mut out = std::vec::Vec::new();
        for k in 0..n {
            let (mut lo, mut hi) = (
                -PI + 2.0 * PI * k as f64 / n as f64,
                -PI + 2.0 * PI * (k + 1) as f64 / n as f64,
            );
            if f(lo) == 0.0 {
                out.push(lo);
                continue;
            }
            if f(lo) * f(hi) < 0.0 {
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    if f(lo) * f(m) <= 0.0 {
                        hi = m
                    } else {
                        lo = m
                    }
                }
                out.push(0.5 * (lo + hi));
            }
        }
        out
    }

    fn ang_dist(a: f64, b: f64) -> f64 {
        let d = (a - b).rem_euclid(2.0 * PI);
        d.min(2.0 * PI - d)
    }

    /// The other root of eq. (5.10) at the branch-test point, by scan.
    fn other_root_pose(phi: f64) -> (f64, f64) {
        let roots = roots_by_scan(phi, 1.0, -1.0);
        let r = roots
            .iter()
            .copied()
            .find(|&t| ang_dist(t, 0.0) > 1e-6)
            .unwrap();
        let m = chain(phi, 1.0, r, -1.0);
        ((-m[2][0]).atan2(m[0][0]), (-m[1][2]).atan2(m[1][1]))
    }

    #[test]
    fn phi_is_recovered_from_the_printed_branch_test() {
        // Solve δ(φ) = −2.6681 ± 5e-5 and γ(φ) = 2.8342 ± 5e-5 for φ by
        // bisection on [10°, 25°] (both monotone there), independent of
        // the library's FK: the root comes from a scan of t21.
        let solve = |idx: usize, target: f64| {
            let (mut lo, mut hi) = (10f64.to_radians(), 25f64.to_radians());
            let val = |p: f64| {
                let (d, g) = other_root_pose(p);
                if idx == 0 {
                    d
                } else {
                    g
                }
            };
            let s = (val(lo) - target).signum();
            for _ in 0..50 {
                let m = 0.5 * (lo + hi);
                if (val(m) - target).signum() == s {
                    lo = m
                } else {
                    hi = m
                }
            }
            0.5 * (lo + hi)
        };
        let mut lo_all = f64::MIN;
        let mut hi_all = f64::MAX;
        for (idx, t) in [(0usize, -2.6681), (1, 2.8342)] {
            let a = solve(idx, t - 5e-5).to_degrees();
            let b = solve(idx, t + 5e-5).to_degrees();
            let (l, h) = (a.min(b), a.max(b));
            std::println!("printed value {t}: phi in [{l:.4}°, {h:.4}°]");
            lo_all = lo_all.max(l);
            hi_all = hi_all.min(h);
        }
        assert!(lo_all < hi_all, "the two printed numbers disagree on phi");
        assert!(lo_all <= 16.0 && 16.0 <= hi_all, "[{lo_all}, {hi_all}]");
        assert!(hi_all - lo_all < 0.01);
        // And the library's φ = 16° reproduces both numbers to 4 digits.
        let (d, g) = other_root_pose(WristParams::thesis().phi());
        assert_eq!(libm::round(d * 1e4) / 1e4, -2.6681);
        assert_eq!(libm::round(g * 1e4) / 1e4, 2.8342);
    }

    #[test]
    fn product_order_of_the_printed_matrices_matches_the_printed_entries() {
        // Entries of eq. (5.5) that print correctly (t21, t31, t22, t32,
        // t13, t23), against both product orders of eq. (5.4).
        let phi = 0.3;
        let (cp, sp) = (phi.cos(), phi.sin());
        let mut worst = [0.0f64; 2];
        for &(t1, t4, t3) in &[(0.3, 1.1, -0.7), (2.0, -0.4, 1.3), (-1.2, 2.5, 0.2)] {
            let (s1, c1, s3, c3, s4, c4) = (
                f64::sin(t1),
                f64::cos(t1),
                f64::sin(t3),
                f64::cos(t3),
                f64::sin(t4),
                f64::cos(t4),
            );
            let printed = [
                (
                    (1, 0),
                    s1 * c4 * c3 + c1 * s4 * c3 * cp - s1 * s4 * s3 * cp
                        + c1 * c4 * s3 * cp * cp
                        + c1 * s3 * sp * sp,
                ),
                ((2, 0), -s3 * cp * sp + s4 * c3 * sp + c4 * s3 * sp * cp),
                (
                    (1, 1),
                    c1 * c4 * c3 * cp * cp + c1 * c3 * sp * sp
                        - s1 * c4 * s3
                        - c1 * s4 * s3 * cp
                        - s1 * s4 * c3 * cp,
                ),
                ((2, 1), -s4 * s3 * sp - c3 * cp * sp + c4 * c3 * sp * cp),
                ((0, 2), s1 * cp * sp - c1 * s4 * sp - s1 * c4 * cp * sp),
                ((1, 2), c1 * c4 * cp * sp - s1 * s4 * sp - c1 * cp * sp),
            ];
            let as_printed = chain(phi, t1, t4, t3);
            let first_line = mul(
                &mul(&mul(&mul(&rz(t1), &rx(-phi)), &rz(t4)), &rx(phi)),
                &rz(t3),
            );
            for ((i, j), v) in printed {
                worst[0] = worst[0].max((as_printed[i][j] - v).abs());
                worst[1] = worst[1].max((first_line[i][j] - v).abs());
            }
            // t11 as printed lacks −S1 S3 Sφ² (E5.2); eq. (5.11) has it.
            let t11_511 = c1 * c4 * c3
                - s1 * s4 * c3 * cp
                - c1 * s4 * s3 * cp
                - s1 * c4 * s3 * cp * cp
                - s1 * s3 * sp * sp;
            assert!((as_printed[0][0] - t11_511).abs() < 1e-14);
            assert!((as_printed[0][0] - (t11_511 + s1 * s3 * sp * sp)).abs() > 1e-3);
        }
        assert!(worst[0] < 1e-14, "{worst:?}");
        assert!(worst[1] > 0.1, "{worst:?}");
    }

    #[test]
    fn constraint_roots_never_merge() {
        // |C/b| ≤ tan²φ and b ≥ cos²φ over a dense motor grid, for
        // several φ; and the physical root is the `−` one and the only
        // one with cos δ > 0 (roots found by scan, not by eq. 5.10).
        for deg in [1.0f64, 10.0, 16.0, 30.0, 40.0] {
            let phi = deg.to_radians();
            let (cp, sp) = (phi.cos(), phi.sin());
            let n = 90;
            for i in 0..n {
                for j in 0..n {
                    let t1 = -PI + 2.0 * PI * i as f64 / n as f64 + 1e-3;
                    let t3 = -PI + 2.0 * PI * j as f64 / n as f64 + 2e-3;
                    let a = t1.sin() * t3.cos() + t1.cos() * t3.sin() * cp * cp;
                    let bb = cp * (t1 + t3).cos();
                    let c = -t1.cos() * t3.sin() * sp * sp;
                    let b = a.hypot(bb);
                    assert!(b >= cp * cp * (1.0 - 1e-12), "b {b} at {t1} {t3}");
                    assert!((c / b).abs() <= (sp / cp).powi(2) + 1e-12);
                    if i % 9 == 0 && j % 9 == 0 {
                        let roots = roots_by_scan(phi, t1, t3);
                        assert_eq!(roots.len(), 2, "{deg}° {t1} {t3}");
                        let phys: std::vec::Vec<_> = roots
                            .iter()
                            .filter(|&&r| chain(phi, t1, r, t3)[0][0] > 0.0)
                            .collect();
                        assert_eq!(phys.len(), 1);
                        let minus = bb.atan2(a) - (c / b).acos();
                        assert!(ang_dist(*phys[0], minus) < 1e-9, "{deg}° {t1} {t3}");
                    }
                }
            }
        }
    }

    /// `forward_plus_root` is the other root of eq. (5.10), found here by
    /// a scan of `t21(θ4)`: its `θ4` is the scanned root that is not the
    /// physical one, its pose is that root's `R_y(δ)R_x(γ)`, and `cos δ < 0`
    /// on it.
    #[test]
    fn plus_root_is_the_other_solution_of_the_constraint() {
        let phi = WristParams::thesis().phi();
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        for i in 0..12 {
            for j in 0..12 {
                let t1 = -PI + 2.0 * PI * i as f64 / 12.0 + 0.01;
                let t3 = -PI + 2.0 * PI * j as f64 / 12.0 + 0.02;
                let m = MotorAngles {
                    theta1: t1,
                    theta3: t3,
                };
                let (phys, plus) = (cfg.forward(m), cfg.forward_plus_root(m));
                let roots = roots_by_scan(phi, t1, t3);
                assert_eq!(roots.len(), 2);
                let other = if ang_dist(roots[0], phys.theta4) < 1e-9 {
                    roots[1]
                } else {
                    roots[0]
                };
                assert!(ang_dist(plus.theta4, other) < 1e-9, "{t1} {t3}");
                let r = chain(phi, t1, other, t3);
                let pose = pitch_yaw(plus.pose.delta, plus.pose.gamma);
                assert!(dist(&r, &pose) < 1e-9, "{t1} {t3}");
                assert!(plus.pose.delta.cos() < 0.0, "{t1} {t3}");
            }
        }
    }

    /// Errata E5.11: eq. (5.5)'s `t12` ends in `−S1 S3 Sφ²`; the chain has
    /// `−S1 C3 Sφ²`. The printed entry misses by `S1 Sφ² (C3 − S3)`, at
    /// most `√2 sin²φ` = 0.1074 (`φ = 16°`), at `θ1 = ±π/2`,
    /// `θ3 = −π/4` or `3π/4`, for any `θ4`.
    #[test]
    fn printed_t12_has_s3_for_c3_in_its_last_term() {
        let phi = WristParams::thesis().phi();
        let (cp, sp) = (phi.cos(), phi.sin());
        let n = 72; // 5° steps: the grid holds the worst point
        let (mut worst_printed, mut worst_fixed, mut at) = (0.0f64, 0.0f64, (0.0, 0.0));
        for i in 0..n {
            for j in 0..n {
                let t1 = -PI + 2.0 * PI * i as f64 / n as f64;
                let t3 = -PI + 2.0 * PI * j as f64 / n as f64;
                for t4 in [-2.0, 0.0, 0.7, PI] {
                    let (s1, c1, s3, c3, s4, c4) = (
                        t1.sin(),
                        t1.cos(),
                        t3.sin(),
                        t3.cos(),
                        f64::sin(t4),
                        f64::cos(t4),
                    );
                    let head = s1 * s4 * s3 * cp
                        - c1 * c4 * s3
                        - c1 * s4 * c3 * cp
                        - s1 * c4 * c3 * cp * cp;
                    let printed = head - s1 * s3 * sp * sp;
                    let fixed = head - s1 * c3 * sp * sp;
                    let t12 = chain(phi, t1, t4, t3)[0][1];
                    worst_fixed = worst_fixed.max((fixed - t12).abs());
                    if (printed - t12).abs() > worst_printed {
                        worst_printed = (printed - t12).abs();
                        at = (t1, t3);
                    }
                }
            }
        }
        std::println!(
            "printed t12 off by {worst_printed:.5} at theta1 = {:.4}, theta3 = {:.4}",
            at.0,
            at.1
        );
        assert!(worst_fixed < 1e-14, "{worst_fixed}");
        let sup = 2f64.sqrt() * sp * sp;
        assert!(
            (worst_printed - sup).abs() < 1e-12,
            "{worst_printed} vs {sup}"
        );
        assert!((at.0.abs() - PI / 2.0).abs() < 1e-12, "{at:?}");
        assert!(((at.1 + PI / 4.0).rem_euclid(PI)).abs() < 1e-12, "{at:?}");
    }

    /// Errata E5.12: §5.3 repeats `t31` and `t32` of eq. (5.5) with sign
    /// errors: `t31 = S3CφSφ + S4C3Sφ − C4S3SφCφ` (the `(1 − C4) S3 CφSφ`
    /// part negated) and `t32 = S4S3Sφ − C3CφSφ + C4C3SφCφ` (the `S4S3Sφ`
    /// term negated). On the wrist (physical root of eq. 5.10) they miss
    /// the chain by up to `2 sin 2φ` = 1.0598 (at `θ1 = θ3 = −π/2`,
    /// `θ4 = π`) and nearly `2 sin φ` = 0.5513. The `C3`, `S3` that §5.3
    /// derives from them (with `S4` for the printed `S2`, E5.4) hold with
    /// the corrected entries, to 1e-12: the slip is in the transcription.
    #[test]
    fn section_5_3_prints_t31_and_t32_with_sign_errors() {
        let phi = WristParams::thesis().phi();
        let (cp, sp) = (phi.cos(), phi.sin());
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        let n = 72;
        let mut worst = [0.0f64; 2];
        let mut at = [(0.0, 0.0); 2];
        let mut worst_fixed = 0.0f64;
        let mut worst_c3s3 = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let t1 = -PI + 2.0 * PI * i as f64 / n as f64;
                let t3 = -PI + 2.0 * PI * j as f64 / n as f64;
                let f = cfg.forward(MotorAngles {
                    theta1: t1,
                    theta3: t3,
                });
                let t4 = f.theta4;
                let (s3, c3, s4, c4) = (t3.sin(), t3.cos(), t4.sin(), t4.cos());
                let r = chain(phi, t1, t4, t3);
                let p31 = s3 * cp * sp + s4 * c3 * sp - c4 * s3 * sp * cp;
                let p32 = s4 * s3 * sp - c3 * cp * sp + c4 * c3 * sp * cp;
                let f31 = -s3 * cp * sp + s4 * c3 * sp + c4 * s3 * sp * cp;
                let f32 = -s4 * s3 * sp - c3 * cp * sp + c4 * c3 * sp * cp;
                worst_fixed = worst_fixed.max((f31 - r[2][0]).abs().max((f32 - r[2][1]).abs()));
                for (k, e) in [(p31 - r[2][0]).abs(), (p32 - r[2][1]).abs()]
                    .into_iter()
                    .enumerate()
                {
                    if e > worst[k] {
                        worst[k] = e;
                        at[k] = (t1, t3);
                    }
                }
                // §5.3's C3, S3 against the true θ3, away from θ4 = 0.
                let (sd, cd) = f.pose.delta.sin_cos();
                let (sg, _) = f.pose.gamma.sin_cos();
                let den = s4 * s4 * sp * sp + (c4 - 1.0).powi(2) * cp * cp * sp * sp;
                if den > 1e-3 {
                    let c3p = -((1.0 - c4) * cp * sp * sg * cd + s4 * sp * sd) / den;
                    let s3p = ((1.0 - c4) * cp * sp * sd - cd * sg * s4 * sp) / den;
                    worst_c3s3 = worst_c3s3.max((c3p - c3).abs().max((s3p - s3).abs()));
                }
            }
        }
        std::println!(
            "printed t31 off by {:.4} at {:?}, t32 by {:.4} at {:?}",
            worst[0],
            at[0],
            worst[1],
            at[1]
        );
        assert!(worst_fixed < 1e-12, "{worst_fixed}");
        assert!(worst_c3s3 < 1e-12, "{worst_c3s3}");
        let sup31 = 2.0 * (2.0 * phi).sin();
        assert!((worst[0] - sup31).abs() < 1e-9, "{} vs {sup31}", worst[0]);
        assert!(
            worst[1] > 0.55 && worst[1] <= 2.0 * sp + 1e-12,
            "{}",
            worst[1]
        );
    }

    /// FK against the rotation-matrix identity: the chain with the
    /// returned θ4 equals R_y(δ)R_x(γ), and t33 = cos δ cos γ.
    #[test]
    fn forward_satisfies_the_closure_identity() {
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        let phi = cfg.phi();
        let mut worst: f64 = 0.0;
        let n = 64;
        for i in 0..n {
            for j in 0..n {
                let t1 = -4.0 + 8.0 * i as f64 / n as f64;
                let t3 = -4.0 + 8.0 * j as f64 / n as f64;
                let f = cfg.forward(MotorAngles {
                    theta1: t1,
                    theta3: t3,
                });
                let r = chain(phi, t1, f.theta4, t3);
                let p = pitch_yaw(f.pose.delta, f.pose.gamma);
                worst = worst.max(dist(&r, &p));
                // Orthogonality of the reference product.
                let rt = [
                    [r[0][0], r[1][0], r[2][0]],
                    [r[0][1], r[1][1], r[2][1]],
                    [r[0][2], r[1][2], r[2][2]],
                ];
                let id = mul(&r, &rt);
                for (k, row) in id.iter().enumerate() {
                    for (l, v) in row.iter().enumerate() {
                        assert!((v - if k == l { 1.0 } else { 0.0 }).abs() < 1e-14);
                    }
                }
                assert!(f.pose.delta.abs() <= 2.0 * phi + 1e-12);
                assert!(f.pose.gamma.abs() <= 2.0 * phi + 1e-12);
            }
        }
        assert!(worst < 1e-14, "{worst}");
    }

    /// `φ ∈ [1°, 30°]`, closed: both ends accepted and read back, the next
    /// `f64` past each rejected by name with the range; `2φ` is the
    /// largest bend.
    #[test]
    fn phi_bounds_are_inclusive_and_max_bend_is_twice_phi() {
        let (lo, hi) = (1f64.to_radians(), 30f64.to_radians());
        for phi in [lo, hi, 0.3] {
            let p = WristParams::try_new(phi).unwrap();
            assert_eq!(p.phi(), phi);
            assert_eq!(p.max_bend(), phi + phi);
            assert_eq!(WristConfig::<f64>::new(&p).phi(), phi);
        }
        for bad in [
            f64::from_bits(lo.to_bits() - 1),
            f64::from_bits(hi.to_bits() + 1),
        ] {
            assert_eq!(
                WristParams::try_new(bad),
                Err(ParamError::OutOfRange {
                    name: "phi",
                    value: bad,
                    min: lo,
                    max: hi
                })
            );
        }
        assert_eq!(WristParams::thesis().phi(), 16f64.to_radians());
    }

    /// The workspace test against hand values at `φ = 16°`
    /// (`cos 32° = 0.8480`): `cos 0.3 · cos 0.3 = 0.9127` inside,
    /// `cos 0.5 · cos 0.3 = 0.8384` and `cos²0.8 = 0.4854` outside; a pure
    /// pitch or yaw of exactly `2φ` is on the edge (inside), one part in
    /// 10⁹ more is outside; `(π, π)` has `cos δ cos γ = 1` but
    /// `|δ|, |γ| > π/2`: outside.
    #[test]
    fn is_reachable_against_hand_values() {
        let p = WristParams::thesis();
        let b = p.max_bend();
        for (d, g, inside) in [
            (0.0, 0.0, true),
            (0.3, -0.3, true),
            (0.5, -0.3, false),
            (-0.3, 0.5, false),
            (0.8, 0.8, false),
            (b, 0.0, true),
            (0.0, -b, true),
            (b * (1.0 + 1e-9), 0.0, false),
            (0.0, -b * (1.0 + 1e-9), false),
            (PI, PI, false),
            (-PI, PI, false),
        ] {
            assert_eq!(p.is_reachable(d, g), inside, "({d}, {g})");
        }
    }

    /// `wrap` maps to `(−π, π]`: `π` stays, `−π` becomes `π`, `π + 0.5`
    /// becomes `0.5 − π`; `denan` keeps every finite value, the largest
    /// ones included, and reads NaN and ±∞ as 0 — on `f64` and `f32`.
    #[test]
    fn wrap_is_half_open_and_denan_keeps_every_finite_value() {
        fn check<S: Scalar>(max: S, inf: S, nan: S) {
            let pi = S::PI;
            assert_eq!(wrap(pi), pi, "{}", S::NAME);
            assert_eq!(wrap(pi.neg()), pi, "{}", S::NAME);
            let half = S::from_f64(0.5);
            let w = wrap(pi.add(half)).to_f64();
            assert!((w - (0.5 - PI)).abs() < 1e-6, "{} {w}", S::NAME);
            let w = wrap(pi.neg().sub(half)).to_f64();
            assert!((w - (PI - 0.5)).abs() < 1e-6, "{} {w}", S::NAME);
            assert_eq!(wrap(half), half);
            for x in [max, max.neg(), half, S::ZERO] {
                assert_eq!(denan(x), x, "{}", S::NAME);
            }
            for x in [inf, inf.neg(), nan] {
                assert_eq!(denan(x), S::ZERO, "{}", S::NAME);
            }
        }
        check::<f64>(f64::MAX, f64::INFINITY, f64::NAN);
        check::<f32>(f32::MAX, f32::INFINITY, f32::NAN);
        assert_eq!(wrap(I16F16::PI), I16F16::PI);
    }

    /// `try_inverse`'s error carries the request, its bend (here from the
    /// output axis `z = (sin δ cos γ, −sin γ, cos δ cos γ)`, not from the
    /// library's formula) and `2φ`, and its message names them. NaN on
    /// either axis is rejected, and so is `(3, π)`, whose half-angle
    /// measure `sin²(δ/2) + cos δ sin²(γ/2) = 0.005` is below `sin²φ` but
    /// whose `|δ|, |γ|` exceed `π/2`.
    #[test]
    fn unreachable_error_names_the_pose_its_bend_and_the_limit() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        for (d, g) in [(0.5, 0.6), (-0.2, 1.2), (3.0, 0.0), (-2.0, 0.5)] {
            let e = cfg
                .try_inverse(PitchYaw { delta: d, gamma: g })
                .unwrap_err();
            let z = [d.sin() * g.cos(), -g.sin(), d.cos() * g.cos()];
            let bend = z[0].hypot(z[1]).atan2(z[2]);
            assert_eq!((e.delta, e.gamma), (d, g));
            assert!(
                (e.bend - bend).abs() < 1e-12,
                "{d} {g}: {} vs {bend}",
                e.bend
            );
            assert!((e.max_bend - 32f64.to_radians()).abs() < 1e-15);
            let text = std::format!("{e}");
            for part in [d, g, e.bend, e.max_bend] {
                assert!(text.contains(&std::format!("{part}")), "{text}");
            }
        }
        for (d, g) in [(f64::NAN, 0.1), (0.1, f64::NAN), (3.0, PI), (-3.0, -PI)] {
            assert!(
                cfg.try_inverse(PitchYaw { delta: d, gamma: g }).is_err(),
                "({d}, {g})"
            );
        }
    }

    /// On `I16F16` the edge tolerance is `2 q sin 2φ` on `sin²(β/2)`
    /// (`q = 2⁻¹⁶`): a pure pitch 5 resolution steps beyond `2φ` exceeds
    /// `sin²φ` by about 1.25 tolerances (`Δ ≈ ½ sin 2φ · 5 q`) and is
    /// rejected (a tolerance with `sin(2 + φ)` or `1/sin 2φ` for
    /// `sin 2φ`, 1.4 and 3.6 times larger, would accept it); the edge
    /// rounded to the backend is accepted.
    #[test]
    fn try_inverse_tolerance_is_a_few_steps_on_i16f16() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<I16F16>::new(&p);
        let q = I16F16::RESOLUTION.to_f64();
        let tol = 2.0 * q * (2.0 * p.phi()).sin();
        let at = |d: f64| PitchYaw {
            delta: I16F16::from_f64(d),
            gamma: I16F16::ZERO,
        };
        let beyond = at(p.max_bend() + 5.0 * q);
        let d = beyond.delta.to_f64();
        let excess = (d / 2.0).sin().powi(2) - p.phi().sin().powi(2);
        assert!(
            excess > 1.05 * tol && excess < 1.4 * tol,
            "{}",
            excess / tol
        );
        assert!(cfg.try_inverse(beyond).is_err());
        assert!(cfg.try_inverse(at(p.max_bend())).is_ok());
    }

    /// A pure pitch of exactly `2φ` lies on the edge: the saturating
    /// inverse does not flag it, and one part in 10⁶ more is flagged.
    #[test]
    fn inverse_does_not_flag_the_edge_itself() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        let r = cfg.inverse(PitchYaw {
            delta: p.max_bend(),
            gamma: 0.0,
        });
        assert!(!r.saturated, "{r:?}");
        let r = cfg.inverse(PitchYaw {
            delta: p.max_bend() * (1.0 + 1e-6),
            gamma: 0.0,
        });
        assert!(r.saturated, "{r:?}");
    }

    #[test]
    fn params_reject_bad_inclinations_naming_them() {
        assert!(WristParams::try_new(16f64.to_radians()).is_ok());
        for bad in [0.0, -0.1, 35f64.to_radians(), 1.0] {
            assert!(matches!(
                WristParams::try_new(bad),
                Err(ParamError::OutOfRange { name: "phi", .. })
            ));
        }
        assert!(matches!(
            WristParams::try_new(f64::NAN),
            Err(ParamError::NotFinite { name: "phi", .. })
        ));
    }

    #[test]
    fn forward_reproduces_the_straight_poses_of_the_thesis() {
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        for (t1, t3) in [(0.0, 0.0), (1.0, -1.0), (-2.5, 2.5)] {
            let f = cfg.forward(MotorAngles {
                theta1: t1,
                theta3: t3,
            });
            assert!(f.pose.delta.abs() < 1e-15 && f.pose.gamma.abs() < 1e-15);
            assert!(f.theta4.abs() < 1e-15);
        }
    }

    /// Round trip FK(IK(x)) = x over the workspace (a polar grid reaching
    /// the boundary and the straight pose), on f64.
    #[test]
    fn inverse_round_trips_over_the_workspace_f64() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        let mut worst: f64 = 0.0;
        for i in 0..=60 {
            for j in 0..=60 {
                let d = -0.6 + 1.2 * i as f64 / 60.0;
                let g = -0.6 + 1.2 * j as f64 / 60.0;
                if !p.is_reachable(d, g) {
                    let r = cfg.inverse(PitchYaw { delta: d, gamma: g });
                    assert!(r.saturated);
                    assert!(cfg.try_inverse(PitchYaw { delta: d, gamma: g }).is_err());
                    continue;
                }
                let r = cfg.try_inverse(PitchYaw { delta: d, gamma: g }).unwrap();
                assert!(!r.saturated);
                let u = r.motors.theta1 + r.motors.theta3;
                assert!((-PI - 0.1..=0.1).contains(&u), "{u}");
                let f = cfg.forward(r.motors);
                worst = worst.max((f.pose.delta - d).abs().max((f.pose.gamma - g).abs()));
                assert!((f.theta4 - r.theta4).abs() < 1e-7, "{d} {g}");
            }
        }
        assert!(worst < 1e-12, "{worst}");
    }

    #[test]
    fn inverse_is_exact_and_smooth_at_and_near_the_straight_pose() {
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        let r = cfg.inverse(PitchYaw::default());
        assert!(r.straight && !r.saturated);
        assert_eq!(r.motors, MotorAngles::default());
        // Near it: for bends from 1e-12 to 1e-3 rad in 16 directions the
        // round trip error is below 1e-15 rad + 1e-12 of the bend, and
        // the motor angles converge to (π − τ, τ − π) (bend direction τ)
        // — the circle of straight-pose solutions.
        for k in 0..16 {
            let tau = 2.0 * PI * k as f64 / 16.0 + 0.1;
            for e in [1e-12, 1e-9, 1e-6, 1e-3] {
                let (d, g) = (e * tau.cos(), e * tau.sin());
                let r = cfg.inverse(PitchYaw { delta: d, gamma: g });
                assert!(!r.straight);
                let f = cfg.forward(r.motors);
                let err = (f.pose.delta - d).abs().max((f.pose.gamma - g).abs());
                assert!(err <= 1e-15 + 1e-9 * e, "{e} {tau} {err}");
                assert!(ang_dist(r.motors.theta1, PI - tau) < 10.0 * e + 1e-9);
                assert!(ang_dist(r.motors.theta3, tau - PI) < 10.0 * e + 1e-9);
            }
        }
    }

    #[test]
    fn printed_inverse_has_a_typo_and_its_continuity_threshold_is_misplaced() {
        // Eq. (5.14) as printed (C_δ in the cosine of θ1) misses the
        // target; with S_δ it round-trips; eq. (5.15)'s μ rule as printed
        // cuts the branch in its middle (u = −π/2), the library's does not.
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        let (cp, sp) = (p.phi().cos(), p.phi().sin());
        let printed = |d: f64, g: f64, typo: bool| {
            let (sd, cd, sg, cg) = (d.sin(), d.cos(), g.sin(), g.cos());
            let c4 = ((cd * cg - cp * cp) / (sp * sp)).clamp(-1.0, 1.0);
            let t4 = c4.acos();
            let (s4, c4) = t4.sin_cos();
            let t1 = ((1.0 - c4) * cp * sp * cg * sd + s4 * sp * sg)
                .atan2((1.0 - c4) * cp * sp * sg - cg * if typo { cd } else { sd } * s4 * sp);
            let t3 = ((1.0 - c4) * cp * sp * sd - cd * sg * s4 * sp)
                .atan2(-(1.0 - c4) * cp * sp * sg * cd - s4 * sd * sp);
            (t1, t3)
        };
        let mut worst_typo: f64 = 0.0;
        let mut worst_fixed: f64 = 0.0;
        let mut u_printed_rule = std::vec::Vec::new();
        for i in 0..=40 {
            for j in 0..=40 {
                let d = -0.55 + 1.1 * i as f64 / 40.0;
                let g = -0.55 + 1.1 * j as f64 / 40.0;
                if !p.is_reachable(d, g) || (d == 0.0 && g == 0.0) {
                    continue;
                }
                for typo in [true, false] {
                    let (t1, t3) = printed(d, g, typo);
                    let f = cfg.forward(MotorAngles {
                        theta1: t1,
                        theta3: t3,
                    });
                    let e = (f.pose.delta - d).abs().max((f.pose.gamma - g).abs());
                    if typo {
                        worst_typo = worst_typo.max(e)
                    } else {
                        worst_fixed = worst_fixed.max(e);
                        let mut t3m = t3;
                        if t1 + t3 < -PI / 2.0 {
                            t3m += 2.0 * PI;
                        }
                        u_printed_rule.push(t1 + t3m);
                        // Same motors as the library, mod 2π.
                        let r = cfg.inverse(PitchYaw { delta: d, gamma: g });
                        assert!(ang_dist(r.motors.theta1, t1) < 1e-9);
                        assert!(ang_dist(r.motors.theta3, t3) < 1e-9);
                    }
                }
            }
        }
        std::println!(
            "printed (5.14) round trip: {worst_typo:.3} rad; with S_delta: {worst_fixed:.1e}"
        );
        assert!(worst_typo > 0.1);
        assert!(worst_fixed < 1e-12);
        // The printed rule leaves u on both sides of a 2π gap.
        let lo = u_printed_rule.iter().any(|&u| u < 0.1);
        let hi = u_printed_rule.iter().any(|&u| u > PI);
        assert!(lo && hi);
    }

    #[test]
    fn saturation_projects_onto_the_boundary_and_nan_is_flagged() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        for (d, g) in [
            (0.8, 0.0),
            (0.5, 0.5),
            (-3.0, 0.2),
            (0.0, -1.4),
            (f64::NAN, 0.1),
            (1e300, -1e300),
        ] {
            let r = cfg.inverse(PitchYaw { delta: d, gamma: g });
            assert!(r.saturated, "{d} {g}");
            let f = cfg.forward(r.motors);
            assert!((f.pose.delta - r.pose.delta).abs() < 1e-12);
            assert!((f.pose.gamma - r.pose.gamma).abs() < 1e-12);
            let bend = (r.pose.delta.cos() * r.pose.gamma.cos()).acos();
            assert!(bend <= p.max_bend() + 1e-9, "{bend}");
            assert!(r.motors.theta1.is_finite() && r.motors.theta3.is_finite());
        }
        // Same azimuth of the output axis for an in-range direction.
        let r = cfg.inverse(PitchYaw {
            delta: 0.5,
            gamma: 0.5,
        });
        let az = |d: f64, g: f64| (-g.sin()).atan2(d.sin() * g.cos());
        assert!((az(0.5, 0.5) - az(r.pose.delta, r.pose.gamma)).abs() < 1e-12);
        let e = cfg
            .try_inverse(PitchYaw {
                delta: 0.5,
                gamma: 0.5,
            })
            .unwrap_err();
        assert!(e.bend > e.max_bend);
    }

    /// An infinite pitch or yaw is outside the workspace (`|δ| > π/2`):
    /// it is read as 0, like NaN, and flagged. Before, the infinity was
    /// replaced by 0 ahead of the workspace test, and `(−∞, −3.6e−132)`
    /// came back unflagged (found by the `wrist_maps` fuzz target).
    #[test]
    fn infinite_pose_is_flagged() {
        fn check<S: Scalar>(inf: S) {
            let cfg = WristConfig::<S>::new(&WristParams::thesis());
            for (d, g) in [
                (inf.neg(), S::ZERO),
                (inf, S::from_f64(0.1)),
                (S::ZERO, inf.neg()),
                (inf, inf),
            ] {
                let r = cfg.inverse(PitchYaw { delta: d, gamma: g });
                assert!(r.saturated, "{} ({d:?}, {g:?}): {r:?}", S::NAME);
                assert!(r.motors.theta1.to_f64().is_finite());
                assert!(cfg.try_inverse(PitchYaw { delta: d, gamma: g }).is_err());
            }
        }
        check::<f64>(f64::INFINITY);
        check::<f32>(f32::INFINITY);
    }

    /// `try_inverse` accepts the workspace boundary as the backend rounds
    /// it and rejects a pose 1 % of `2φ` (plus 8 resolution steps)
    /// beyond it, for every backend and the whole range of `φ`. Before,
    /// its tolerance was 4 resolution steps on `sin²(β/2)` compared with
    /// the backend's rounded `sin²φ`: on `I16F16` with `φ = 1°` it accepted
    /// the pose `(0, −0.0378)`, 8 % beyond the edge (found by the
    /// `wrist_maps` fuzz target), as exact.
    #[test]
    fn try_inverse_rejects_just_beyond_the_edge_on_every_backend() {
        fn check<S: Scalar>() {
            for deg in [1.0f64, 4.0, 16.0, 30.0] {
                let p = WristParams::try_new(deg.to_radians()).unwrap();
                let cfg = WristConfig::<S>::new(&p);
                let res = S::RESOLUTION.to_f64();
                for k in 0..16 {
                    let tau = 2.0 * PI * k as f64 / 16.0;
                    let at = |b: f64| {
                        let z = [b.sin() * tau.cos(), b.sin() * tau.sin(), b.cos()];
                        PitchYaw {
                            delta: S::from_f64(z[0].atan2(z[2])),
                            gamma: S::from_f64((-z[1]).atan2(z[0].hypot(z[2]))),
                        }
                    };
                    let edge = at(p.max_bend());
                    assert!(cfg.try_inverse(edge).is_ok(), "{} {deg}° {edge:?}", S::NAME);
                    let beyond = at(p.max_bend() * 1.01 + 8.0 * res);
                    assert!(
                        cfg.try_inverse(beyond).is_err(),
                        "{} {deg}° {beyond:?}",
                        S::NAME
                    );
                }
            }
        }
        check::<f64>();
        check::<f32>();
        check::<I16F16>();
    }

    /// `dψ/dβ` at bend `beta` (rad), with `ψ = atan(cos φ tan(θ4/2))` and
    /// `sin(θ4/2) = sin(β/2)/sin φ` (eq. 5.13): the product of
    /// `dψ/dθ4 = (cos φ/2)/(cos²(θ4/2) + cos²φ sin²(θ4/2))` and
    /// `dθ4/dβ = cos(β/2)/(sin φ cos(θ4/2))`, both increasing in `β` on
    /// `[0, 2φ)`.
    pub(crate) fn psi_rate(phi: f64, beta: f64) -> f64 {
        let (sp, cp) = libm::sincos(phi);
        let sh = libm::sin(beta / 2.0) / sp;
        let ch = libm::sqrt(1.0 - sh * sh);
        let dpsi_dt4 = 0.5 * cp / (ch * ch + cp * cp * sh * sh);
        let dt4_db = libm::cos(beta / 2.0) / (sp * ch);
        dpsi_dt4 * dt4_db
    }

    /// Both roots of eq. (5.13) reach the pose, checked against the
    /// rotation matrices built from their definitions (eq. 5.4 = eq. 5.6),
    /// with opposite `θ4`; their motor angles differ by `2ψ + π` on both
    /// motors, `ψ = atan2(cos φ sin(θ4/2), cos(θ4/2))` (module docs).
    #[test]
    fn both_branches_reach_the_pose() {
        let p = WristParams::thesis();
        let phi = p.phi();
        let cfg = WristConfig::<f64>::new(&p);
        let mut worst: f64 = 0.0;
        let n = 41;
        for i in 0..n {
            for j in 0..n {
                let d = -0.6 + 1.2 * i as f64 / (n - 1) as f64;
                let g = -0.6 + 1.2 * j as f64 / (n - 1) as f64 + 1e-3;
                let target = PitchYaw { delta: d, gamma: g };
                let plus = cfg.inverse(target);
                let minus = cfg.inverse_other_branch(target);
                assert_eq!(
                    (plus.pose, plus.saturated, plus.straight),
                    (minus.pose, minus.saturated, minus.straight)
                );
                let want = pitch_yaw(plus.pose.delta, plus.pose.gamma);
                for r in [plus, minus] {
                    let m = chain(phi, r.motors.theta1, r.theta4, r.motors.theta3);
                    worst = worst.max(dist(&m, &want));
                    let f = cfg.forward(r.motors);
                    worst = worst
                        .max((f.pose.delta - r.pose.delta).abs())
                        .max((f.pose.gamma - r.pose.gamma).abs());
                    if !r.saturated {
                        worst = worst.max((f.theta4 - r.theta4).abs());
                    }
                }
                assert!(plus.theta4 >= 0.0 && minus.theta4 == -plus.theta4);
                let h = plus.theta4 / 2.0;
                let psi = (phi.cos() * h.sin()).atan2(h.cos());
                for (a, b) in [
                    (plus.motors.theta1, minus.motors.theta1),
                    (plus.motors.theta3, minus.motors.theta3),
                ] {
                    worst = worst.max(ang_dist(b, a + 2.0 * psi + PI));
                }
                // The other branch's continuity interval, mirrored.
                let (u, eps) = (
                    minus.motors.theta1 + minus.motors.theta3,
                    (phi.sin().powi(2) / (2.0 * phi).cos()).atan(),
                );
                assert!(minus.motors.theta1.abs() <= PI);
                assert!((-eps - 1e-12..=PI + eps + 1e-12).contains(&u), "{u}");
            }
        }
        assert!(worst < 1e-12, "{worst}");
    }

    /// [`IkState`] along the line `(δ, γ) = s (cos a, sin a)`, `s` from
    /// −10° to +10° in steps `Δs = 2 mrad` (0.5 rad/s at 4 ms), through
    /// the straight pose, on every backend: each motor moves by at most
    /// `(psi_rate(φ, 10°) + s_max/2)·Δs` a sample (derivation at the step's
    /// test `crossing`) plus both ends' rounding (`tol` away from the
    /// straight pose, and the bend direction `A` rounded, `4√2 q/s_min` at
    /// the smallest bend `s_min` of the path, `q` the resolution); the
    /// forward kinematics of the motors reaches the pose within the
    /// round-trip bound of `proofs::wrist_ik`. On the branch `θ4 ≥ 0`
    /// alone the motors turn by about π at the crossing.
    #[test]
    fn tracker_crosses_the_straight_pose_continuously() {
        fn run<S: Scalar>(a_deg: f64, tol: f64) -> (f64, f64) {
            let p = WristParams::thesis();
            let cfg = WristConfig::<S>::new(&p);
            let c64 = WristConfig::<f64>::new(&p);
            let (sa, ca) = libm::sincos(a_deg.to_radians());
            let (ds, s_max) = (0.002, 10f64.to_radians());
            let n = libm::ceil(2.0 * s_max / ds) as usize;
            let s = |k: usize| -s_max + k as f64 * ds;
            let s_min = (0..=n).map(|k| s(k).abs()).fold(f64::MAX, f64::min);
            let q = S::RESOLUTION.to_f64();
            let bound = (psi_rate(p.phi(), s_max) + s_max / 2.0) * ds
                + 2.0 * (tol + 4.0 * core::f64::consts::SQRT_2 * q / s_min);
            let pose_bound = crate::proofs::wrist_ik::round_trip_bound::<S>();
            let at = |k: usize| PitchYaw {
                delta: S::from_f64(s(k) * ca),
                gamma: S::from_f64(s(k) * sa),
            };
            let m0 = c64
                .inverse(PitchYaw {
                    delta: s(0) * ca,
                    gamma: s(0) * sa,
                })
                .motors;
            let mut st = IkState::new(MotorAngles {
                theta1: S::from_f64(m0.theta1),
                theta3: S::from_f64(m0.theta3),
            });
            let (mut worst_step, mut worst_pose) = (0.0f64, 0.0f64);
            for k in 1..=n {
                let before = st.motors;
                let r = cfg.update(&mut st, at(k));
                for (now, was) in [
                    (r.motors.theta1, before.theta1),
                    (r.motors.theta3, before.theta3),
                ] {
                    worst_step = worst_step.max((now.to_f64() - was.to_f64()).abs() / bound);
                }
                let f = c64.forward(MotorAngles {
                    theta1: r.motors.theta1.to_f64(),
                    theta3: r.motors.theta3.to_f64(),
                });
                let e = (f.pose.delta - at(k).delta.to_f64())
                    .abs()
                    .max((f.pose.gamma - at(k).gamma.to_f64()).abs());
                worst_pose = worst_pose.max(e / pose_bound);
            }
            (worst_step, worst_pose)
        }
        for a in [0.0, 35.0, 90.0, 200.0] {
            for (name, (step, pose)) in [
                ("f64", run::<f64>(a, 1e-12)),
                ("f32", run::<f32>(a, 2e-5)),
                ("I16F16", run::<I16F16>(a, 5e-3)),
            ] {
                std::eprintln!("{name} a = {a}°: step {step:.3}, pose {pose:.3} of the bounds");
                assert!(
                    step <= 1.0,
                    "{name} a = {a}°: motor step {step} of the bound"
                );
                assert!(
                    pose <= 1.0,
                    "{name} a = {a}°: pose error {pose} of the bound"
                );
            }
        }
    }

    #[test]
    fn tracker_is_continuous_through_the_cut_and_the_straight_pose() {
        let cfg = WristConfig::<f64>::new(&WristParams::thesis());
        let mut st = IkState::new(MotorAngles::default());
        // A circle of radius 0.3 around the straight pose, twice, then a
        // line through the straight pose: motor steps stay small.
        let mut prev = st.motors;
        let mut max_step: f64 = 0.0;
        for k in 0..=2000 {
            let t = 4.0 * PI * k as f64 / 2000.0;
            let r = cfg.update(
                &mut st,
                PitchYaw {
                    delta: 0.3 * t.cos(),
                    gamma: 0.3 * t.sin(),
                },
            );
            if k > 0 {
                max_step = max_step.max((r.motors.theta1 - prev.theta1).abs());
                max_step = max_step.max((r.motors.theta3 - prev.theta3).abs());
            }
            prev = r.motors;
        }
        assert!(max_step < 0.05, "{max_step}");
        // Two loops around the straight pose: θ1 wound by ∓4π.
        assert!(
            (prev.theta1
                - cfg
                    .inverse(PitchYaw {
                        delta: 0.3,
                        gamma: 0.0
                    })
                    .motors
                    .theta1)
                .abs()
                > 12.0
        );
        let before = st.motors;
        let r = cfg.update(&mut st, PitchYaw::default());
        assert!(r.straight);
        assert_eq!(r.motors.theta1, before.theta1);
        let sum = r.motors.theta1 + r.motors.theta3;
        let turns = (sum / (2.0 * PI)).round();
        assert!((sum - turns * 2.0 * PI).abs() < 1e-9, "{sum}");
        assert!((r.motors.theta3 - before.theta3).abs() <= PI + 0.1);
    }

    #[test]
    fn tracker_stays_congruent_after_many_turns() {
        // Previous motor angles up to thousands of turns out (as a wound-up
        // tracker has them): the result is the backend's one-shot inverse
        // plus a whole number of turns, within two roundings at the
        // magnitude of the previous angle, however many turns it holds.
        fn check<S: Scalar>() {
            let cfg = WristConfig::<S>::new(&WristParams::thesis());
            let mut worst: f64 = 0.0;
            for (i, turns) in [-4000.0, -127.0, -1.0, 0.0, 3.0, 127.0, 1000.0, 4000.0]
                .into_iter()
                .enumerate()
            {
                for j in 0..24 {
                    let t = j as f64 * 0.26 + i as f64;
                    let pose = PitchYaw {
                        delta: S::from_f64(0.45 * t.cos()),
                        gamma: S::from_f64(0.4 * (1.3 * t).sin()),
                    };
                    let one_shot = cfg.inverse(pose);
                    assert!(!one_shot.straight);
                    let m = one_shot.motors;
                    // Previous angles `turns` turns away, off by < π.
                    let prev = MotorAngles {
                        theta1: S::from_f64(m.theta1.to_f64() + 2.0 * PI * turns + 0.7),
                        theta3: S::from_f64(m.theta3.to_f64() - 2.0 * PI * turns - 2.9),
                    };
                    let mut st = IkState::new(prev);
                    let r = cfg.update(&mut st, pose);
                    assert_eq!(st.motors, r.motors);
                    for (now, before, want) in [
                        (r.motors.theta1, prev.theta1, m.theta1),
                        (r.motors.theta3, prev.theta3, m.theta3),
                    ] {
                        let (now, before) = (now.to_f64(), before.to_f64());
                        assert!((now - before).abs() <= PI, "{now} {before}");
                        let d = now - want.to_f64();
                        let d = d - (d / (2.0 * PI)).round() * 2.0 * PI;
                        // One unit: an LSB on fixed point, an ulp at the
                        // previous angle's magnitude on floats.
                        let res = S::RESOLUTION.to_f64();
                        let unit = if res < 1e-6 {
                            res * (before.abs() + 2.0 * PI)
                        } else {
                            res
                        };
                        assert!(
                            d.abs() <= 2.0 * unit,
                            "{} turns {turns}: {d:e} vs unit {unit:e}",
                            S::NAME
                        );
                        worst = worst.max(d.abs() / unit);
                    }
                }
            }
            std::eprintln!("{}: worst congruence error {worst:.2} units", S::NAME);
        }
        check::<f64>();
        check::<f32>();
        check::<I16F16>();
    }

    #[test]
    fn backends_agree_with_f64() {
        let p = WristParams::thesis();
        let c64 = WristConfig::<f64>::new(&p);
        let c32 = WristConfig::<f32>::new(&p);
        let cfx = WristConfig::<I16F16>::new(&p);
        let mut worst = [0.0f64; 2];
        for i in 0..=24 {
            for j in 0..=24 {
                let d = -0.55 + 1.1 * i as f64 / 24.0;
                let g = -0.55 + 1.1 * j as f64 / 24.0;
                if !p.is_reachable(d, g) {
                    continue;
                }
                let r32 = c32.inverse(PitchYaw {
                    delta: d as f32,
                    gamma: g as f32,
                });
                let f32_ = c32.forward(r32.motors);
                let rfx = cfx.inverse(PitchYaw {
                    delta: I16F16::from_f64(d),
                    gamma: I16F16::from_f64(g),
                });
                let ffx = cfx.forward(rfx.motors);
                let e32 = (f32_.pose.delta as f64 - d)
                    .abs()
                    .max((f32_.pose.gamma as f64 - g).abs());
                let efx = (ffx.pose.delta.to_f64() - d)
                    .abs()
                    .max((ffx.pose.gamma.to_f64() - g).abs());
                worst[0] = worst[0].max(e32);
                worst[1] = worst[1].max(efx);
                let r64 = c64.inverse(PitchYaw { delta: d, gamma: g });
                if d.hypot(g) > 0.05 {
                    assert!(ang_dist(r64.motors.theta1, r32.motors.theta1 as f64) < 1e-4);
                }
            }
        }
        std::println!(
            "round trip f32 {:.2e} rad, I16F16 {:.2e} rad",
            worst[0],
            worst[1]
        );
        assert!(worst[0] < 2e-5 && worst[1] < 1e-3, "{worst:?}");
    }

    proptest! {
        #[test]
        fn forward_inverse_forward_is_the_identity(t1 in -10.0f64..10.0, t3 in -10.0f64..10.0) {
            // FK then IK returns the same motor angles mod 2π (up to the
            // straight-pose circle).
            let cfg = WristConfig::<f64>::new(&WristParams::thesis());
            let f = cfg.forward(MotorAngles { theta1: t1, theta3: t3 });
            prop_assume!(f.theta4 > 0.0);
            let r = cfg.inverse(f.pose);
            let bend = (f.pose.delta.cos() * f.pose.gamma.cos()).clamp(-1.0, 1.0).acos();
            prop_assume!(bend > 1e-6 && bend < cfg.phi() * 2.0 - 1e-6);
            // Near the straight pose the direction is conditioned by 1/bend.
            let tol = 1e-12 / bend + 1e-12;
            prop_assert!(ang_dist(r.motors.theta1, t1) < tol, "{} {}", r.motors.theta1, t1);
            prop_assert!(ang_dist(r.motors.theta3, t3) < tol);
        }
    }

    /// `update`'s tie rule, `θ4 ≥ 0` when both roots' `θ1` are equally far
    /// from the previous `θ1` (module docs). On `f32` a previous `θ1`
    /// exactly half-way between the two roots' `θ1` exists whenever their
    /// mean, formed exactly in `f64`, is an `f32`: the distances `update`
    /// forms in `f64` are then equal bit for bit. (On `I16F16` the two
    /// `θ1` are `π − 2ψ` apart, `2·arg A + π` in sum, an odd number of
    /// steps: no grid value is half-way.)
    #[test]
    fn update_takes_the_plus_root_on_an_exact_tie() {
        let cfg = WristConfig::<f32>::new(&WristParams::thesis());
        let mut ties = 0;
        for k in 0..64 {
            let pose = PitchYaw {
                delta: 0.12f32,
                gamma: 0.05 + 0.003 * k as f32,
            };
            let (a, b) = (cfg.inverse(pose), cfg.inverse_other_branch(pose));
            assert!(a.theta4 > 0.0 && b.theta4 < 0.0);
            let (a1, b1) = (f64::from(a.motors.theta1), f64::from(b.motors.theta1));
            let mean = 0.5 * (a1 + b1);
            let mid = mean as f32;
            if f64::from(mid) != mean {
                continue;
            }
            let (da, db) = ((a1 - mean).abs(), (b1 - mean).abs());
            assert!(da == db && da < PI, "{da} {db}");
            let mut st = IkState::new(MotorAngles {
                theta1: mid,
                theta3: -mid,
            });
            let r = cfg.update(&mut st, pose);
            assert!(r.theta4 >= 0.0, "pose {pose:?}: {r:?}");
            // Off the tie by one `f32` step towards the θ4 ≤ 0 root, that
            // root.
            let toward = if b1 > mean {
                f32::from_bits(
                    mid.to_bits()
                        .wrapping_add(if mid > 0.0 { 1 } else { u32::MAX }),
                )
            } else {
                f32::from_bits(
                    mid.to_bits()
                        .wrapping_add(if mid > 0.0 { u32::MAX } else { 1 }),
                )
            };
            assert!((f64::from(toward) - b1).abs() < db, "{toward} {mid}");
            let mut st = IkState::new(MotorAngles {
                theta1: toward,
                theta3: -toward,
            });
            assert!(cfg.update(&mut st, pose).theta4 < 0.0);
            ties += 1;
        }
        assert!(ties >= 8, "{ties} exact ties");
    }

    /// `try_inverse` accepts a pose whose `sin²(β/2)` equals its limit
    /// `sin²φ + 2 q sin 2φ` exactly, and rejects the next `f64` above it:
    /// the comparison is strict. The pose is found by bisection on `δ` (at
    /// `γ = 0`, where the tested quantity is `sin²(δ/2)`, computed here as
    /// the method documents it) and a walk over neighbouring `f64` values
    /// to the one that hits the limit bit for bit.
    #[test]
    fn try_inverse_accepts_its_limit_exactly() {
        let p = WristParams::thesis();
        let cfg = WristConfig::<f64>::new(&p);
        let sp = libm::sin(p.phi());
        let limit = sp * sp + 2.0 * f64::EPSILON * libm::sin(2.0 * p.phi());
        let hb = |d: f64| {
            let s = libm::sin(d / 2.0);
            s * s + libm::cos(d) * 0.0 * 0.0
        };
        let (mut lo, mut hi) = (0.0, 2.0 * p.phi() + 0.1);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if hb(mid) > limit {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let mut d = lo;
        for _ in 0..64 {
            if hb(d) == limit {
                break;
            }
            d = f64::from_bits(d.to_bits() - 1);
        }
        assert!(hb(d) == limit, "no pose on the limit near {lo}");
        let at = |delta| cfg.try_inverse(PitchYaw { delta, gamma: 0.0 });
        assert!(at(d).is_ok(), "{d}");
        let mut above = f64::from_bits(d.to_bits() + 1);
        while hb(above) == limit {
            above = f64::from_bits(above.to_bits() + 1);
        }
        assert!(at(above).is_err(), "{above}");
    }
}
