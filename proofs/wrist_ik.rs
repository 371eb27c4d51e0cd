//! The wrist's inverse-kinematics branch selection (thesis eq. 5.13–5.15),
//! for the thesis's wrist (`φ = 16°`), written once and run by every
//! engine.
//!
//! | property | I16F16 | f32 | f64 |
//! |---|---|---|---|
//! | `branch_and_round_trip` — at a reachable `(δ, γ)`, for both roots of eq. (5.13): not flagged, no NaN, on its root (`θ4 ≥ 0`, `θ1 + θ3 ∈ [−π − ε, ε]`; `θ4 ≤ 0`, `θ1 + θ3 ∈ [−ε, π + ε]`) and `FK(IK(δ, γ)) = (δ, γ)` within [`round_trip_bound`] | Kani entry (not run here); exhaustive (256 × 256 grid, and every code within 64 LSB of the straight pose) | exhaustive (same grid); random | random |
//! | `continuity_step` — `update` from either root of one reachable pose to another `Δ = |Δδ| + |Δγ|` away (bends `≥ β_min`): it takes the root whose `θ1` is nearest ([`nearest_root_of`]), and each motor angle moves (mod 2π) by at most [`continuity_modulus`] | Kani entry (not run here); exhaustive (grid neighbours) | exhaustive; random | random |
//! | `branch_logic_of`, `other_branch_logic_of` — both roots' ranges (`θ4`, `θ1`, `θ1 + θ3`), zero motors at the straight pose, the flag, for every target, kernels by contracts | Kani entry (not run here); random targets | — | — |
//!
//! Both roots are checked because [`WristConfig::update`] and the wrist
//! step take either (the one whose `θ1` is nearer the previous one, module
//! docs of [`crate::wrist::kinematics`]); [`WristConfig::inverse`] alone
//! keeps `θ4 ≥ 0`.
//!
//! **The grid.** Code `c = 256 i + j` (16 bits) is the pose
//! `δ = −2φ + i·h`, `γ = −2φ + j·h`, `h = 4φ/255`: the bounding square of
//! the workspace, of which 79 % (51,756 of 65,536 points in f32) is
//! reachable. Measured (release, `cargo test --release --lib -- --ignored
//! exhaustive_wrist --nocapture`): round trip ≤ 0.25 of the bound on
//! I16F16 (24 LSB = 3.7e-4 rad), 0.016 on f32 (1.5 units = 3.6e-7 rad);
//! continuity ≤ 0.57 (I16F16) and 0.64 (f32) of the modulus. (Measured
//! on the root `θ4 ≥ 0` alone, before both roots and `update`'s choice
//! were part of the properties; not yet rerun.)
//!
//! **The round-trip bound** is a first-order error budget in units `q` of
//! the backend's absolute angle resolution (`I16F16`: `2⁻¹⁶`; `f32`:
//! `2⁻²²`, the ulp at π; `f64`: `2⁻⁵¹`), not an interval proof: the
//! forward map evaluates about 40 rounded products and 7 kernels (each
//! ≤ 2 q, their proven bounds) on terms of magnitude ≤ 1, and its `atan2`
//! arguments have unit norm, so the angles it returns are within ~30 q;
//! the inverse's errors reach the pose through `J` (`‖J‖ ≤ 1.4`), where
//! the direction errors (`∝ q / sin β`) meet the self-motion column
//! difference `J·(1, −1)ᵀ ∝ sin β`. Allowing a factor two over the sum:
//! [`ROUND_TRIP_UNITS`]` = 96` units. Near the boundary the check excludes
//! poses within [`BOUNDARY_MARGIN_UNITS`] units of bend of the edge, where
//! the backend's workspace test may flag a reachable pose (its
//! `sin(β/2) > sin φ` comparison is rounded).
//!
//! **The continuity modulus** (derived in [`continuity_modulus`]): the
//! motor angles are `θ1 = π + az(z_h) − ψ`, `θ3 = −π + az(r_h) − ψ` with
//! `z_h = (Sδ Cγ, −Sγ)` and `r_h = (Sδ, Cδ Sγ)`, both of length `sin β`
//! and 1-Lipschitz in each of `δ, γ`; the angle between two vectors is at
//! most `(π/√2)·|a − b| / min(|a|, |b|)`; and `ψ = atan2(Cφ s, √(1−s²))`
//! with `s = sin(β/2)/Sφ` moves by at most `Δ(asin s)/Cφ`, where
//! `Δs ≤ Δ/(2Sφ)` and `Δ asin s ≤ min(Δs/√(1 − s_max²), π√(Δs/2))`.

use super::engine::Verdict;
use crate::scalar::Scalar;
use crate::wrist::{IkState, Inverse, MotorAngles, PitchYaw, WristConfig, WristParams};
use core::f64::consts::PI;

/// Grid points per axis (the code is 16 bits: 256 × 256).
pub const GRID: u32 = 256;
/// The round-trip bound in units of [`angle_unit`].
pub const ROUND_TRIP_UNITS: f64 = 96.0;
/// Poses within this many units of bend from the workspace edge are
/// outside the property (the rounded workspace test may flag them).
pub const BOUNDARY_MARGIN_UNITS: f64 = 64.0;
/// The smallest bend (rad) at which continuity is checked: the direction
/// of the bend is undefined at the straight pose.
pub const CONTINUITY_MIN_BEND: f64 = 0.05;

/// The backend's absolute angle resolution `q` (rad).
pub fn angle_unit<S: Scalar>() -> f64 {
    match S::NAME {
        "I16F16" => 1.0 / 65536.0,
        "f32" => libm::exp2(-22.0),
        _ => libm::exp2(-51.0),
    }
}

/// The thesis's wrist.
pub fn wrist() -> WristParams {
    WristParams::thesis()
}

/// The grid pose of code `c` (only its low 16 bits are used), in rad.
pub fn grid_pose(p: &WristParams, code: u32) -> (f64, f64) {
    let (i, j) = ((code >> 8) & 0xff, code & 0xff);
    let lim = p.max_bend();
    let h = 2.0 * lim / (GRID - 1) as f64;
    (-lim + i as f64 * h, -lim + j as f64 * h)
}

/// Bend `acos(cos δ cos γ)` (rad), in f64 by the half-angle form.
pub fn bend(d: f64, g: f64) -> f64 {
    let s = libm::sqrt(libm::sin(d / 2.0).powi(2) + libm::cos(d) * libm::sin(g / 2.0).powi(2));
    2.0 * libm::asin(s.min(1.0))
}

/// Whether the pose (as the backend holds it) is inside the property's
/// domain: `|δ|, |γ| ≤ π/2` and bend `≤ 2φ − margin`.
pub fn in_domain<S: Scalar>(p: &WristParams, d: S, g: S) -> bool {
    let (df, gf) = (d.to_f64(), g.to_f64());
    !df.is_nan()
        && !gf.is_nan()
        && df.abs() <= PI / 2.0
        && gf.abs() <= PI / 2.0
        && bend(df, gf) <= p.max_bend() - BOUNDARY_MARGIN_UNITS * angle_unit::<S>()
}

/// The round-trip bound for backend `S` (rad).
pub fn round_trip_bound<S: Scalar>() -> f64 {
    ROUND_TRIP_UNITS * angle_unit::<S>()
}

/// `ε = atan(sin²φ / cos 2φ)`: how far `θ1 + θ3` may leave `[−π, 0]`.
pub fn branch_slack(p: &WristParams) -> f64 {
    let s = libm::sin(p.phi());
    libm::atan(s * s / libm::cos(2.0 * p.phi()))
}

/// The property at one pose, for the computed inverse `r` on the root
/// `θ4 ≥ 0` ([`WristConfig::inverse`]).
pub fn branch_and_round_trip_of<S: Scalar>(
    cfg: &WristConfig<S>,
    p: &WristParams,
    d: S,
    g: S,
    r: &Inverse<S>,
) -> Verdict {
    root_and_round_trip_of(cfg, p, d, g, r, false)
}

/// The property at one pose for the other root, `θ4 ≤ 0`
/// ([`WristConfig::inverse_other_branch`]): `θ4 ≤ 0` (by the forward map),
/// `θ1 ∈ (−π, π]`, `θ1 + θ3 ∈ [−ε, π + ε]` and the same round trip.
pub fn other_branch_and_round_trip_of<S: Scalar>(
    cfg: &WristConfig<S>,
    p: &WristParams,
    d: S,
    g: S,
    r: &Inverse<S>,
) -> Verdict {
    root_and_round_trip_of(cfg, p, d, g, r, true)
}

/// The root property: `negative` selects the root `θ4 ≤ 0`.
fn root_and_round_trip_of<S: Scalar>(
    cfg: &WristConfig<S>,
    p: &WristParams,
    d: S,
    g: S,
    r: &Inverse<S>,
    negative: bool,
) -> Verdict {
    if !in_domain(p, d, g) {
        // Outside: only no NaN.
        return Verdict::logical(!r.motors.theta1.is_nan() && !r.motors.theta3.is_nan());
    }
    let q = angle_unit::<S>();
    let (t1, t3) = (r.motors.theta1.to_f64(), r.motors.theta3.to_f64());
    let no_nan = !t1.is_nan() && !t3.is_nan();
    let not_flagged = !r.saturated;
    // The root (its θ4 re-evaluated by the forward map), and the
    // continuous representative of θ1 + θ3 on it: [−π − ε, ε] for
    // θ4 ≥ 0, mirrored to [−ε, π + ε] for θ4 ≤ 0.
    let f = cfg.forward(r.motors);
    let eps = branch_slack(p);
    let u = t1 + t3;
    let (theta4, lo, hi) = if negative {
        (-f.theta4.to_f64(), -eps, PI + eps)
    } else {
        (f.theta4.to_f64(), -PI - eps, eps)
    };
    let branch = theta4 >= -ROUND_TRIP_UNITS * q
        && u >= lo - 8.0 * q
        && u <= hi + 8.0 * q
        && t1.abs() <= PI + 2.0 * q;
    let err = (f.pose.delta.to_f64() - d.to_f64())
        .abs()
        .max((f.pose.gamma.to_f64() - g.to_f64()).abs());
    Verdict::bounded(err / round_trip_bound::<S>(), 1.0)
        .and(Verdict::logical(no_nan && not_flagged && branch))
}

/// [`branch_and_round_trip_of`] and [`other_branch_and_round_trip_of`]
/// with both roots computed here: each motor position of the pose is on
/// its root and reaches the pose.
pub fn branch_and_round_trip<S: Scalar>(
    cfg: &WristConfig<S>,
    p: &WristParams,
    d: S,
    g: S,
) -> Verdict {
    let (plus, minus) = cfg.inverse_branches(PitchYaw { delta: d, gamma: g });
    branch_and_round_trip_of(cfg, p, d, g, &plus)
        .and(other_branch_and_round_trip_of(cfg, p, d, g, &minus))
}

/// The derived bound on the motion of each motor angle (rad, mod 2π)
/// between two poses `delta_sum = |Δδ| + |Δγ|` apart whose bends are at
/// least `min_bend` and whose `sin(β/2)/sin φ` is at most `s_max`; see
/// the module docs.
pub fn continuity_modulus(p: &WristParams, delta_sum: f64, min_bend: f64, s_max: f64) -> f64 {
    let (sp, cp) = (libm::sin(p.phi()), libm::cos(p.phi()));
    let direction = PI / core::f64::consts::SQRT_2 * delta_sum / libm::sin(min_bend);
    let ds = delta_sum / (2.0 * sp);
    let s_max = s_max.min(1.0);
    let lip = if s_max < 1.0 {
        ds / libm::sqrt(1.0 - s_max * s_max)
    } else {
        f64::INFINITY
    };
    let holder = PI * libm::sqrt(ds / 2.0);
    direction + lip.min(holder) / cp
}

/// Wrapped distance of two angles (rad).
fn ang_dist(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// Continuity between two poses `a`, `b` and their computed inverses.
pub fn continuity_step_of<S: Scalar>(
    p: &WristParams,
    a: (S, S),
    ra: &Inverse<S>,
    b: (S, S),
    rb: &Inverse<S>,
) -> Verdict {
    if !in_domain(p, a.0, a.1) || !in_domain(p, b.0, b.1) {
        return Verdict::logical(true);
    }
    let (ad, ag, bd, bg) = (a.0.to_f64(), a.1.to_f64(), b.0.to_f64(), b.1.to_f64());
    let (ba, bb) = (bend(ad, ag), bend(bd, bg));
    let min_bend = ba.min(bb);
    if min_bend < CONTINUITY_MIN_BEND {
        return Verdict::logical(true);
    }
    let sp = libm::sin(p.phi());
    let s_max = (libm::sin(ba.max(bb) / 2.0) / sp).min(1.0);
    let delta_sum = (ad - bd).abs() + (ag - bg).abs();
    // Each endpoint's own rounding (round-trip units through ‖J⁻¹‖, which
    // the direction term dominates; 4× the budget is ample).
    let slack = 4.0 * round_trip_bound::<S>() / libm::sin(min_bend);
    let bound = continuity_modulus(p, delta_sum, min_bend, s_max) + slack;
    let m1 = ang_dist(ra.motors.theta1.to_f64(), rb.motors.theta1.to_f64());
    let m3 = ang_dist(ra.motors.theta3.to_f64(), rb.motors.theta3.to_f64());
    Verdict::bounded(m1.max(m3) / bound, 1.0)
}

/// The root [`WristConfig::update`] took (`taken`) from the previous
/// motors `prev`, given both roots of the target (`plus`, `minus`): its
/// motors are one root's (mod 2π), and its `θ1` is no farther from
/// `prev.θ1` than either root's (within `8 q`).
pub fn nearest_root_of<S: Scalar>(
    prev: &MotorAngles<S>,
    plus: &Inverse<S>,
    minus: &Inverse<S>,
    taken: &Inverse<S>,
) -> Verdict {
    let q = angle_unit::<S>();
    let p1 = prev.theta1.to_f64();
    let t = taken.motors;
    let on = |r: &Inverse<S>| {
        ang_dist(t.theta1.to_f64(), r.motors.theta1.to_f64()) <= 8.0 * q
            && ang_dist(t.theta3.to_f64(), r.motors.theta3.to_f64()) <= 8.0 * q
    };
    let nearest = ang_dist(t.theta1.to_f64(), p1)
        <= ang_dist(plus.motors.theta1.to_f64(), p1)
            .min(ang_dist(minus.motors.theta1.to_f64(), p1))
            + 8.0 * q;
    Verdict::logical((on(plus) || on(minus)) && nearest)
}

/// Continuity of [`WristConfig::update`] from `a` to `b`, started at each
/// root of `a` in turn: it takes the root nearest in `θ1`
/// ([`nearest_root_of`]) and moves each motor by at most the modulus
/// ([`continuity_step_of`]; never more than staying on the root it
/// started on would).
pub fn continuity_step<S: Scalar>(
    cfg: &WristConfig<S>,
    p: &WristParams,
    a: (S, S),
    b: (S, S),
) -> Verdict {
    let (plus, minus) = cfg.inverse_branches(PitchYaw {
        delta: a.0,
        gamma: a.1,
    });
    let tb = PitchYaw {
        delta: b.0,
        gamma: b.1,
    };
    let (plus_b, minus_b) = cfg.inverse_branches(tb);
    let mut v = Verdict::logical(true);
    for start in [plus, minus] {
        let mut st = IkState::new(start.motors);
        let rb = cfg.update(&mut st, tb);
        v = v
            .and(nearest_root_of(&start.motors, &plus_b, &minus_b, &rb))
            .and(continuity_step_of(p, a, &start, b, &rb));
    }
    v
}

/// The branch selection of the inverse (eq. 5.13–5.15) as logic, for
/// any pose and any kernel values within the kernels' contracts: the
/// result's `θ4 ∈ [0, π]` (the non-negative root: `sin(θ4/2) ≥ 0`,
/// `cos(θ4/2) ≥ 0`), `θ1 ∈ (−π, π]`, `θ1 + θ3 = u ∈ [−3π/2, π/2]` (`u = ε − 2ψ`
/// with `ψ ∈ [0, π/2]`, `ε ∈ [−π/2, π/2]`; the tight `[−π − ε, ε]` of
/// [`branch_and_round_trip`] needs the kernels' accuracy and is the
/// exhaustive engine's), motors zero exactly at the straight pose, and the
/// flag set for a clamped target. Values in `2⁻¹⁶` (I16F16 bits).
pub fn branch_logic_of(d: i32, g: i32, r: &Inverse<crate::scalar::I16F16>) -> Verdict {
    const HALF_PI: i32 = 102_944; // I16F16::FRAC_PI_2 (bits)
    const PI_B: i32 = 205_887; // I16F16::PI (bits)
    let (t1, t3, t4) = (
        r.motors.theta1.to_bits() as i64,
        r.motors.theta3.to_bits() as i64,
        r.theta4.to_bits() as i64,
    );
    let pi = PI_B as i64;
    let u = t1 + t3;
    let clamped = d.unsigned_abs() > HALF_PI as u32 || g.unsigned_abs() > HALF_PI as u32;
    let straight_ok = !r.straight || (t1 == 0 && t3 == 0 && t4 == 0);
    Verdict::logical(
        (0..=pi + 1).contains(&t4)
            && t1 > -pi - 1
            && t1 <= pi + 1
            && (r.straight || (-3 * pi / 2 - 4..=pi / 2 + 4).contains(&u))
            && straight_ok
            && (!clamped || r.saturated),
    )
}

/// [`branch_logic_of`] for the other root (`inverse_branches(..).1`):
/// `θ4 ∈ [−π, 0]`, `θ1 ∈ (−π, π]`, `θ1 + θ3 = ε + 2ψ ∈ [−π/2, 3π/2]`, motors
/// zero exactly at the straight pose, and the flag set for a clamped
/// target. Values in `2⁻¹⁶` (I16F16 bits).
pub fn other_branch_logic_of(d: i32, g: i32, r: &Inverse<crate::scalar::I16F16>) -> Verdict {
    const HALF_PI: i32 = 102_944; // I16F16::FRAC_PI_2 (bits)
    const PI_B: i32 = 205_887; // I16F16::PI (bits)
    let (t1, t3, t4) = (
        r.motors.theta1.to_bits() as i64,
        r.motors.theta3.to_bits() as i64,
        r.theta4.to_bits() as i64,
    );
    let pi = PI_B as i64;
    let u = t1 + t3;
    let clamped = d.unsigned_abs() > HALF_PI as u32 || g.unsigned_abs() > HALF_PI as u32;
    let straight_ok = !r.straight || (t1 == 0 && t3 == 0 && t4 == 0);
    Verdict::logical(
        (-pi - 1..=0).contains(&t4)
            && t1 > -pi - 1
            && t1 <= pi + 1
            && (r.straight || (-pi / 2 - 4..=3 * pi / 2 + 4).contains(&u))
            && straight_ok
            && (!clamped || r.saturated),
    )
}

/// The part of the `I16F16` product's contract that
/// `kani_wrist_ik_branch_logic_i16f16` assumes, for operands `a`, `b` and
/// result `r` (bits): `a, b ≥ 0 ⇒ r ≥ 0`; `a ≥ 0, b ≥ 2¹⁶ ⇒ r ≥ a`;
/// `a ≤ 0, b ≥ 0 ⇒ r ≤ 0`; `a ≥ 0, b ≤ 0 ⇒ r ≤ 0`; `a, b ≤ 0 ⇒ r ≥ 0`;
/// `|b| ≤ 2¹⁶ ⇒ |r| ≤ |a|`.
pub fn mul_bits_contract(a: i32, b: i32, r: i32) -> bool {
    (!(a >= 0 && b >= 0) || r >= 0)
        && (!(a >= 0 && b >= 1 << 16) || r >= a)
        && (!(a <= 0 && b >= 0) || r <= 0)
        && (!(a >= 0 && b <= 0) || r <= 0)
        && (!(a <= 0 && b <= 0) || r >= 0)
        && ((b as i64).abs() > 1 << 16 || (r as i64).abs() <= (a as i64).abs())
}

/// The part of the `I16F16` quotient's contract that
/// `kani_wrist_ik_branch_logic_i16f16` assumes, for a numerator `a` and
/// the result `q` (bits) of a division by `b` with `0 < b`, `|a| ≤ b`: `q ∈ [−2¹⁶, 2¹⁶]` (`[−1, 1]`),
/// `q ≥ 0` for `a > 0`, `q ≤ 0` for `a < 0`, and `q = 0` for `a = 0`.
/// (A form that allowed any `q ∈ [−1, 1]` at `a = 0` let the harness pick
/// `sin(θ4/2) < 0` at the straight pose and fail, although the real
/// `div_bits(0, b)` is 0.)
pub fn div_bits_range_contract(a: i32, q: i32) -> bool {
    (-(1 << 16)..=1 << 16).contains(&q) && (a < 0 || q >= 0) && (a > 0 || q <= 0)
}

#[cfg(kani)]
mod kani_entries {
    use super::*;
    use crate::scalar::I16F16;

    fn any_bits_in(lo: i32, hi: i32) -> i32 {
        let v: i32 = kani::any();
        kani::assume(lo <= v && v <= hi);
        v
    }

    const ONE: i32 = 1 << 16;
    const HALF_PI: i32 = 102_944;
    const PI_B: i32 = 205_887;

    // Kernel contracts (each proven for the real kernel where noted).
    /// `sin ∈ [−1, 1]` (`outputs_in_range`, Kani and exhaustive).
    fn sin_as_contract(_x: I16F16) -> I16F16 {
        // Postcondition of the stubbed kernel.
        I16F16::from_bits(any_bits_in(-ONE, ONE))
    }
    /// `sin, cos ∈ [−1, 1]`, `cos ≥ 0` for `|x| ≤ π/2` (`outputs_in_range`;
    /// `cos_is_non_negative_on_the_half_circle`, every input).
    fn sin_cos_as_contract(x: I16F16) -> (I16F16, I16F16) {
        // Postcondition of the stubbed kernel.
        let lo = if x.to_bits().unsigned_abs() <= HALF_PI as u32 {
            0
        } else {
            -ONE
        };
        (
            I16F16::from_bits(any_bits_in(-ONE, ONE)),
            I16F16::from_bits(any_bits_in(lo, ONE)),
        )
    }
    /// `sqrt ≥ 0`, and `≥ 1` from `1` on (`sqrt_contract_holds`, every
    /// input; monotone by `exhaustive_sqrt_i16f16`).
    fn sqrt_as_contract(x: I16F16) -> I16F16 {
        // Postcondition of the stubbed kernel.
        let lo = if x.to_bits() >= ONE { ONE } else { 0 };
        I16F16::from_bits(any_bits_in(lo, i32::MAX))
    }
    /// `atan2 ∈ [−π, π]`, in `[0, π/2]` for `y, x ≥ 0`, in `[−π/2, π/2]`
    /// for `x ≥ 0` (`atan2_contract_holds`, random and on a lattice).
    fn atan2_as_contract(y: I16F16, x: I16F16) -> I16F16 {
        // Postcondition of the stubbed kernel.
        let (y, x) = (y.to_bits(), x.to_bits());
        let (lo, hi) = if x >= 0 && y >= 0 {
            (0, HALF_PI)
        } else if x >= 0 {
            (-HALF_PI, HALF_PI)
        } else {
            (-PI_B, PI_B)
        };
        I16F16::from_bits(any_bits_in(lo, hi))
    }

    /// `mul_bits` (the I16F16 product) as the part of its contract the
    /// branch logic uses: the sign rules, at most `|a|` for `|b| ≤ 1`, at
    /// least `a` for `a ≥ 0`, `b ≥ 1`, and exactly the saturated `2b` for
    /// `a = 2` (`mul_contract_holds`: the real product at random and on
    /// edge classes; it equals the correctly rounded `mul_bits_reference`,
    /// tested in `src/scalar/fixed.rs`).
    fn mul_bits_as_contract(a: i32, b: i32) -> i32 {
        if a == 2 * ONE {
            return b.saturating_mul(2);
        }
        let r: i32 = kani::any();
        // Postcondition of the stubbed function.
        kani::assume(mul_bits_contract(a, b, r));
        r
    }

    /// `div_bits_unit` (the inverse's divisions, all of ratios
    /// `|a| ≤ b`) as its range contract: the precondition `0 < b`,
    /// `|a| ≤ b` asserted at each call; [`div_bits_range_contract`] for the
    /// quotient, which `kani_div_unit_range_contract` verifies on the real
    /// `div_bits_unit`.
    fn div_bits_unit_as_range_contract(a: i32, b: i32) -> i32 {
        assert!(
            b > 0 && a >= -b && a <= b,
            "div_bits_unit called outside the boundary layer"
        );
        let q: i32 = kani::any();
        // Postcondition of the stubbed function.
        kani::assume(div_bits_range_contract(a, q));
        q
    }

    /// Any magnitude quotient: the range contract of `div_bits_unit` holds
    /// by its structure, whatever the division circuit returns, so the
    /// circuit is left out (a sound over-approximation, no contract).
    fn div_magnitude_any(_ua: u32, _ub: u32) -> u32 {
        kani::any()
    }

    /// The contract `div_bits_unit_as_range_contract` stands for: the real
    /// `div_bits_unit` meets [`div_bits_range_contract`] for every divisor
    /// `b > 0` and every `a` (inside the ratio domain and beyond it, where
    /// it clamps), with the magnitude quotient any `u32`.
    #[kani::proof]
    #[kani::stub(crate::scalar::fixed::div_magnitude, div_magnitude_any)]
    fn kani_div_unit_range_contract() {
        let (a, b): (i32, i32) = (kani::any(), kani::any());
        kani::assume(b > 0); // precondition of the contract
        assert!(div_bits_range_contract(
            a,
            crate::scalar::fixed::div_bits_unit(a, b)
        ));
    }

    /// The branch logic of both roots of the inverse (`θ4 ≥ 0` and
    /// `θ4 ≤ 0`) for every I16F16 target (all 2⁶⁴
    /// pairs), the kernels and the division replaced by their contracts
    /// (above; the division's precondition, a boundary-layer quotient, is
    /// asserted at each of the inverse's divisions). The sums, clamps,
    /// `wrap` and the branch choice itself are the real code.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::sin, sin_as_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::sin_cos, sin_cos_as_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::sqrt, sqrt_as_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::atan2, atan2_as_contract)]
    #[kani::stub(crate::scalar::fixed::mul_bits, mul_bits_as_contract)]
    #[kani::stub(crate::scalar::fixed::div_bits_unit, div_bits_unit_as_range_contract)]
    fn kani_wrist_ik_branch_logic_i16f16() {
        let cfg = WristConfig::<I16F16>::new(&wrist());
        let (d, g): (i32, i32) = (kani::any(), kani::any());
        let (r, other) = cfg.inverse_branches(PitchYaw {
            delta: I16F16::from_bits(d),
            gamma: I16F16::from_bits(g),
        });
        let (t1, t3, t4) = (
            r.motors.theta1.to_bits() as i64,
            r.motors.theta3.to_bits() as i64,
            r.theta4.to_bits() as i64,
        );
        assert!(t4 >= 0, "theta4 >= 0");
        assert!(t4 <= PI_B as i64 + 1, "theta4 <= pi");
        assert!(
            t1 > -(PI_B as i64) - 1 && t1 <= PI_B as i64 + 1,
            "theta1 in (-pi, pi]"
        );
        assert!(r.straight || t1 + t3 >= -3 * PI_B as i64 / 2 - 4, "u low");
        assert!(r.straight || t1 + t3 <= PI_B as i64 / 2 + 4, "u high");
        assert!(branch_logic_of(d, g, &r).holds);
        // The other root, θ4 ≤ 0, which `update` and the wrist step may
        // take.
        let (o1, o3, o4) = (
            other.motors.theta1.to_bits() as i64,
            other.motors.theta3.to_bits() as i64,
            other.theta4.to_bits() as i64,
        );
        assert!(
            o4 <= 0 && o4 >= -(PI_B as i64) - 1,
            "other theta4 in [-pi, 0]"
        );
        assert!(
            o1 > -(PI_B as i64) - 1 && o1 <= PI_B as i64 + 1,
            "other theta1 in (-pi, pi]"
        );
        assert!(
            other.straight || o1 + o3 >= -(PI_B as i64) / 2 - 4,
            "other u low"
        );
        assert!(
            other.straight || o1 + o3 <= 3 * PI_B as i64 / 2 + 4,
            "other u high"
        );
        assert!(other_branch_logic_of(d, g, &other).holds);
    }

    /// The branch property of both roots at every point of the 16-bit
    /// grid, I16F16.
    #[kani::proof]
    fn kani_wrist_ik_branch_i16f16() {
        let p = wrist();
        // Configuration built outside the solver's choices.
        let cfg = WristConfig::<I16F16>::new(&p);
        let code: u16 = kani::any();
        let (d, g) = grid_pose(&p, code as u32);
        let (d, g) = (I16F16::from_f64(d), I16F16::from_f64(g));
        assert!(branch_and_round_trip(&cfg, &p, d, g).holds);
    }

    /// Continuity of `update` between a grid point and its `γ` neighbour,
    /// started at each root of the first, I16F16: the nearest root in
    /// `θ1` is taken and each motor moves by at most the modulus.
    #[kani::proof]
    fn kani_wrist_ik_continuity_i16f16() {
        let p = wrist();
        let cfg = WristConfig::<I16F16>::new(&p);
        let code: u16 = kani::any();
        // Precondition: the neighbour is on the same grid row.
        kani::assume(code & 0xff != 0xff);
        let a = grid_pose(&p, code as u32);
        let b = grid_pose(&p, code as u32 + 1);
        let q = |x: f64| I16F16::from_f64(x);
        assert!(continuity_step(&cfg, &p, (q(a.0), q(a.1)), (q(b.0), q(b.1))).holds);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::exhaustive_u32;
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;
    use std::println;
    use std::vec::Vec;

    fn exhaustive_grid<S: Scalar>(name: &str) {
        let p = wrist();
        let cfg = WristConfig::<S>::new(&p);
        let pose = |c: u32| {
            let (d, g) = grid_pose(&p, c);
            (S::from_f64(d), S::from_f64(g))
        };
        // Engine 2 on the per-point property.
        let r = exhaustive_u32(0, GRID * GRID - 1, |c| {
            let (d, g) = pose(c);
            branch_and_round_trip(&cfg, &p, d, g)
        });
        let reachable = (0..GRID * GRID)
            .filter(|&c| {
                let (d, g) = pose(c);
                in_domain(&p, d, g)
            })
            .count();
        println!(
            "PROOF property=wrist-ik-branch+round-trip backend={name} domain=256x256 grid of [-2phi,2phi]^2 ({reachable} in the workspace) bound={ROUND_TRIP_UNITS} units max_err={:.3} of bound at={} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
        // Continuity of `update` between grid neighbours along δ and γ,
        // started at each root of the first.
        let mut worst = Verdict::logical(true);
        let mut pairs = 0u32;
        for c in 0..GRID * GRID {
            for n in [c + 1, c + GRID] {
                if n >= GRID * GRID || (n == c + 1 && c % GRID == GRID - 1) {
                    continue;
                }
                let v = continuity_step(&cfg, &p, pose(c), pose(n));
                assert!(
                    v.holds,
                    "continuity fails between codes {c} and {n}: {}",
                    v.error
                );
                worst = worst.and(v);
                pairs += 1;
            }
        }
        println!(
            "PROOF property=wrist-ik-continuity backend={name} domain=grid neighbours with bend >= {CONTINUITY_MIN_BEND} rad max_err={:.3} of modulus checked={pairs} engine=exhaustive",
            worst.error
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_wrist_ik_i16f16() {
        exhaustive_grid::<I16F16>("I16F16");
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_wrist_ik_f32() {
        exhaustive_grid::<f32>("f32");
    }

    /// Every I16F16 pose within 64 LSB of the straight pose (129 × 129
    /// codes, the 0/0 point of the printed formulas and its neighbours).
    #[test]
    fn wrist_ik_near_the_straight_pose_i16f16() {
        let p = wrist();
        let cfg = WristConfig::<I16F16>::new(&p);
        let mut worst: f64 = 0.0;
        for i in -64i32..=64 {
            for j in -64i32..=64 {
                let (d, g) = (I16F16::from_bits(i), I16F16::from_bits(j));
                let v = branch_and_round_trip(&cfg, &p, d, g);
                assert!(v.holds, "({i}, {j}) LSB: {}", v.error);
                worst = worst.max(v.error);
            }
        }
        println!("near straight, I16F16: max {worst:.3} of the round-trip bound");
    }

    /// The property can fail: a wrong branch (θ4 < 0, the motors of the
    /// other preimage) is caught, and so is a motor jump.
    #[test]
    fn the_property_rejects_the_other_branch_and_a_jump() {
        let p = wrist();
        let cfg = WristConfig::<f64>::new(&p);
        let (d, g) = (0.2, -0.1);
        let mut r = cfg.inverse(PitchYaw { delta: d, gamma: g });
        assert!(branch_and_round_trip_of(&cfg, &p, d, g, &r).holds);
        // The other preimage: found by searching the motor torus for the
        // pose with θ4 < 0.
        let mut best = (f64::MAX, 0.0, 0.0);
        for i in 0..400 {
            for j in 0..400 {
                let t1 = -PI + 2.0 * PI * i as f64 / 400.0;
                let t3 = -PI + 2.0 * PI * j as f64 / 400.0;
                let f = cfg.forward(crate::wrist::MotorAngles {
                    theta1: t1,
                    theta3: t3,
                });
                let e = (f.pose.delta - d).abs() + (f.pose.gamma - g).abs();
                if f.theta4 < 0.0 && e < best.0 {
                    best = (e, t1, t3);
                }
            }
        }
        assert!(best.0 < 0.05);
        // It is the library's other root (to the search's resolution),
        // which passes its own check and fails the first root's, and
        // conversely.
        let other = cfg.inverse_other_branch(PitchYaw { delta: d, gamma: g });
        assert!(ang_dist(other.motors.theta1, best.1) < 0.05);
        assert!(ang_dist(other.motors.theta3, best.2) < 0.05);
        assert!(other_branch_and_round_trip_of(&cfg, &p, d, g, &other).holds);
        assert!(!other_branch_and_round_trip_of(&cfg, &p, d, g, &r).holds);
        assert!(!branch_and_round_trip_of(&cfg, &p, d, g, &other).holds);
        r.motors = crate::wrist::MotorAngles {
            theta1: best.1,
            theta3: best.2,
        };
        assert!(!branch_and_round_trip_of(&cfg, &p, d, g, &r).holds);
        // The root farther from the previous θ1 is rejected.
        let plus = cfg.inverse(PitchYaw { delta: d, gamma: g });
        assert!(nearest_root_of(&plus.motors, &plus, &other, &plus).holds);
        assert!(!nearest_root_of(&plus.motors, &plus, &other, &other).holds);
        assert!(nearest_root_of(&other.motors, &plus, &other, &other).holds);
        // A jump of 0.5 rad in θ1 between neighbours is caught.
        let a = (0.2, 0.1);
        let b = (0.2, 0.1 + 2.0 * p.max_bend() / 255.0);
        let ra = cfg.inverse(PitchYaw {
            delta: a.0,
            gamma: a.1,
        });
        let mut rb = cfg.inverse(PitchYaw {
            delta: b.0,
            gamma: b.1,
        });
        assert!(continuity_step_of(&p, a, &ra, b, &rb).holds);
        rb.motors.theta1 += 0.5;
        assert!(!continuity_step_of(&p, a, &ra, b, &rb).holds);
    }

    /// The kernel contracts `kani_wrist_ik_branch_logic_i16f16` stubs:
    /// `sin`, `sin_cos` in `[−1, 1]` and `cos ≥ 0` on `|x| ≤ π/2` (every
    /// input of the half circle; the whole type in steps of 2¹¹ and every
    /// input of `|x| ≤ 8`), `sqrt ≥ 0` and `≥ 1` from 1 on (`sqrt(1) = 1`
    /// and the exhaustive monotonicity of `exhaustive_sqrt_i16f16`, spot
    /// checked here), `atan2` ranges by quadrant (axes, and a lattice).
    #[test]
    fn kernel_contracts_of_the_branch_logic_harness() {
        use crate::scalar::kernels::i16f16 as k;
        const ONE: i32 = 1 << 16;
        const HALF_PI: i32 = 102_944;
        const PI_B: i32 = 205_887;
        let near = (-(8 * ONE)..=8 * ONE).map(I16F16::from_bits);
        let coarse = (i32::MIN..=i32::MAX)
            .step_by(1 << 11)
            .map(I16F16::from_bits);
        for x in near.chain(coarse) {
            let (s, c) = k::sin_cos(x);
            let one = I16F16::ONE;
            assert!(
                s.abs() <= one && c.abs() <= one && k::sin(x).abs() <= one,
                "{x}"
            );
            if x.to_bits().unsigned_abs() <= HALF_PI as u32 {
                assert!(c >= I16F16::ZERO, "cos({x}) = {c}");
            }
            let r = k::sqrt(x);
            assert!(
                r >= I16F16::ZERO && (x < one || r >= one),
                "sqrt({x}) = {r}"
            );
        }
        assert_eq!(k::sqrt(I16F16::ONE), I16F16::ONE);
        let vals: Vec<i32> = [
            0,
            1,
            2,
            3,
            100,
            ONE - 1,
            ONE,
            3 * ONE,
            i32::MAX - 1,
            i32::MAX,
        ]
        .iter()
        .flat_map(|&v| [v, -v, v / 7, -(v / 7)])
        .chain([i32::MIN, i32::MIN + 1])
        .collect();
        for &y in &vals {
            for &x in &vals {
                let a = k::atan2(I16F16::from_bits(y), I16F16::from_bits(x)).to_bits();
                let ok = if x >= 0 && y >= 0 {
                    (0..=HALF_PI).contains(&a)
                } else if x >= 0 {
                    (-HALF_PI..=HALF_PI).contains(&a)
                } else {
                    (-PI_B..=PI_B).contains(&a)
                };
                assert!(ok, "atan2({y}, {x}) = {a} bits");
            }
        }
    }

    /// The product contract of the branch-logic harness holds for the
    /// real `mul_bits` (random pairs, edge classes, and `2·b` exact), and
    /// can fail.
    #[test]
    fn mul_contract_holds() {
        use crate::scalar::fixed::mul_bits;
        let edges = [
            0,
            1,
            2,
            0x7fff,
            0x8000,
            0xffff,
            1 << 16,
            (1 << 16) + 1,
            3 << 16,
            i32::MAX,
            i32::MAX - 1,
        ];
        let mut vals: Vec<i32> = edges.iter().flat_map(|&v| [v, -v]).collect();
        vals.push(i32::MIN);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..2000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            vals.push((state >> 32) as i32 >> (state % 24));
        }
        for &a in &vals {
            for &b in &vals {
                assert!(mul_bits_contract(a, b, mul_bits(a, b)), "{a} * {b}");
            }
            assert_eq!(mul_bits(2 << 16, a), a.saturating_mul(2));
        }
        assert!(!mul_bits_contract(5, 7, -1));
        assert!(!mul_bits_contract(5 << 16, 1 << 16, (5 << 16) - 1));
        assert!(!mul_bits_contract(-5, 7, 1));
        assert!(!mul_bits_contract(5 << 16, 1 << 16, (5 << 16) + 1));
    }

    /// The quotient contract of the branch-logic harness holds for the
    /// real `div_bits` and `div_bits_unit` (every numerator of a few divisors, including the
    /// configured `sin φ`, and random pairs), and can fail: it rejects a
    /// nonzero quotient of `a = 0` (the counterexample Kani found for the
    /// earlier, weaker form: `div_bits(0, sin φ) = −1` bit, which made
    /// `sin(θ4/2) < 0` at the straight pose), a wrong sign and `|q| > 1`.
    #[test]
    fn div_range_contract_holds() {
        use crate::scalar::fixed::{div_bits, div_bits_unit};
        // Both divisions, which agree on every ratio |a| ≤ b.
        let div_bits = |a: i32, b: i32| {
            let q = div_bits(a, b);
            assert_eq!(div_bits_unit(a, b), q, "{a} / {b}");
            q
        };
        let sin_phi = WristConfig::<I16F16>::new(&wrist()).sin_phi.to_bits();
        for b in [1, 2, 3, 255, 1 << 16, sin_phi, (1 << 20) + 7] {
            for a in -b.min(1 << 16)..=b.min(1 << 16) {
                assert!(div_bits_range_contract(a, div_bits(a, b)), "{a} / {b}");
                assert!(div_bits_range_contract(
                    -b + a.abs(),
                    div_bits(-b + a.abs(), b)
                ));
            }
            assert_eq!(div_bits(0, b), 0);
        }
        for b in [i32::MAX, i32::MAX - 1] {
            for a in [-b, -1, 0, 1, b, b / 3] {
                assert!(div_bits_range_contract(a, div_bits(a, b)), "{a} / {b}");
            }
        }
        let mut state = 0x0123_4567_89ab_cdefu64;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let b = ((state >> 33) as i32).max(1);
            let a = ((state as i32 as i64) % (b as i64 + 1)) as i32;
            assert!(div_bits_range_contract(a, div_bits(a, b)), "{a} / {b}");
        }
        assert!(!div_bits_range_contract(0, -1));
        assert!(!div_bits_range_contract(0, 1));
        assert!(!div_bits_range_contract(5, -1));
        assert!(!div_bits_range_contract(-5, 1));
        assert!(!div_bits_range_contract(5, (1 << 16) + 1));
        assert!(div_bits_range_contract(0, 0) && div_bits_range_contract(-5, -(1 << 16)));
    }

    /// The branch-logic check can fail: a negative `θ4` (the other root),
    /// a `θ1` beyond `π`, nonzero motors at the straight pose, and a
    /// clamped target without the flag are rejected.
    #[test]
    fn branch_logic_check_can_fail() {
        use crate::wrist::MotorAngles;
        let f = |b: i32| I16F16::from_bits(b);
        let good = Inverse {
            motors: MotorAngles {
                theta1: f(100_000),
                theta3: f(-150_000),
            },
            theta4: f(30_000),
            pose: PitchYaw {
                delta: f(1000),
                gamma: f(2000),
            },
            saturated: false,
            straight: false,
        };
        assert!(branch_logic_of(1000, 2000, &good).holds);
        let mut bad = good;
        bad.theta4 = f(-1);
        assert!(!branch_logic_of(1000, 2000, &bad).holds);
        let mut bad = good;
        bad.motors.theta1 = f(205_889);
        assert!(!branch_logic_of(1000, 2000, &bad).holds);
        let mut bad = good;
        bad.straight = true;
        assert!(!branch_logic_of(1000, 2000, &bad).holds);
        assert!(!branch_logic_of(200_000, 2000, &good).holds);
        let mut bad = good;
        bad.motors.theta3 = f(100_000);
        assert!(!branch_logic_of(1000, 2000, &bad).holds);
        // The other root: θ4 ≤ 0 and θ1 + θ3 ∈ [−π/2, 3π/2].
        let mut other = good;
        other.theta4 = f(-30_000);
        other.motors.theta3 = f(150_000);
        assert!(other_branch_logic_of(1000, 2000, &other).holds);
        assert!(!other_branch_logic_of(1000, 2000, &good).holds);
        let mut bad = other;
        bad.motors.theta3 = f(-250_000); // u = −150,000 bits < −π/2
        assert!(!other_branch_logic_of(1000, 2000, &bad).holds);
        let mut bad = other;
        bad.motors.theta1 = f(-205_889);
        assert!(!other_branch_logic_of(1000, 2000, &bad).holds);
        assert!(!other_branch_logic_of(200_000, 2000, &other).holds);
    }

    /// The shipped inverse meets the branch logic with its real kernels,
    /// at random targets over the whole I16F16 range.
    #[test]
    fn branch_logic_holds_at_random_targets() {
        let cfg = WristConfig::<I16F16>::new(&wrist());
        let mut state = 0x1234_5678_9abc_def0u64;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (d, g) = ((state >> 32) as i32, state as i32);
            // Half of the targets inside the clamp range.
            let (d, g) = if state & 1 == 0 {
                (d >> 14, g >> 14)
            } else {
                (d, g)
            };
            let (r, o) = cfg.inverse_branches(PitchYaw {
                delta: I16F16::from_bits(d),
                gamma: I16F16::from_bits(g),
            });
            assert!(branch_logic_of(d, g, &r).holds, "{d} {g}: {r:?}");
            assert!(other_branch_logic_of(d, g, &o).holds, "{d} {g}: {o:?}");
        }
    }

    proptest! {
        #[test]
        fn wrist_ik_branch_f64(bend in 0.0f64..0.56, tau in -PI..PI, step in 1e-6f64..0.02, dir in -PI..PI) {
            let p = wrist();
            let cfg = WristConfig::<f64>::new(&p);
            // A pose of the given bend and direction of the output axis.
            let z = [libm::sin(bend) * libm::cos(tau), libm::sin(bend) * libm::sin(tau), libm::cos(bend)];
            let d = libm::atan2(z[0], z[2]);
            let g = libm::atan2(-z[1], libm::hypot(z[0], z[2]));
            let v = branch_and_round_trip(&cfg, &p, d, g);
            prop_assert!(v.holds, "{} at {} {}", v.error, d, g);
            let b = (d + step * libm::cos(dir), g + step * libm::sin(dir));
            prop_assert!(continuity_step(&cfg, &p, (d, g), b).holds);
        }

        #[test]
        fn wrist_ik_branch_f32(bend in 0.0f64..0.55, tau in -PI..PI, step in 1e-4f64..0.02, dir in -PI..PI) {
            let p = wrist();
            let cfg = WristConfig::<f32>::new(&p);
            let z = [libm::sin(bend) * libm::cos(tau), libm::sin(bend) * libm::sin(tau), libm::cos(bend)];
            let d = libm::atan2(z[0], z[2]) as f32;
            let g = libm::atan2(-z[1], libm::hypot(z[0], z[2])) as f32;
            prop_assert!(branch_and_round_trip(&cfg, &p, d, g).holds);
            let b = ((d as f64 + step * libm::cos(dir)) as f32, (g as f64 + step * libm::sin(dir)) as f32);
            prop_assert!(continuity_step(&cfg, &p, (d, g), b).holds);
        }
    }
}
