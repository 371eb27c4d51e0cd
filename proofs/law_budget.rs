//! The first-order error budget of the robust adaptive law (eq. 4.19) on a
//! backend against exact arithmetic on the same stored inputs, parameters
//! and state: the bound the backend-agreement tests
//! (`control::adaptive::tests::backends_agree_within_the_derived_budget`)
//! and the `api_laws` fuzz target compare `f32` and `I16F16` with `f64`
//! within.

use crate::control::{ControlInput, RobustAdaptiveConfig, RobustAdaptiveState};
use crate::scalar::Scalar;

/// The regressor part of [`law_error_budget`]: `r`, `Y` and the bounds of
/// their errors (stored units), and the friction torque with its error.
pub struct RegressorBudget {
    pub e: f64,
    pub ed: f64,
    pub de: f64,
    pub ded: f64,
    pub r: f64,
    pub dr: f64,
    pub y: [f64; 4],
    pub dy: [f64; 4],
    pub f: f64,
    pub df: f64,
}

/// Rounding of one operation of stored magnitude `m` (see
/// [`law_error_budget`]).
pub fn rounding<S: Scalar>(m: f64) -> f64 {
    let q = S::RESOLUTION.to_f64();
    if q >= 1.0 / 65536.0 {
        0.5 * q + 2.0 * m.abs() * 2f64.powi(-30)
    } else {
        0.5 * q * m.abs()
    }
}

/// Rounding of one addition of stored magnitude `m` (exact in fixed point).
pub fn addition<S: Scalar>(m: f64) -> f64 {
    let q = S::RESOLUTION.to_f64();
    if q >= 1.0 / 65536.0 {
        0.0
    } else {
        0.5 * q * m.abs()
    }
}

pub fn regressor_budget<S: Scalar>(
    cfg: &RobustAdaptiveConfig<S>,
    st: &RobustAdaptiveState<S>,
    x: &ControlInput<S>,
) -> RegressorBudget {
    let fixed = S::RESOLUTION.to_f64() >= 1.0 / 65536.0;
    let q = S::RESOLUTION.to_f64();
    let u = q / 2.0;
    let rnd = rounding::<S>;
    let add = addition::<S>;
    let d = cfg.quantized_design();
    let un = S::UNITS;
    let g = |v: S| v.to_f64();
    let e = g(x.motor_position) - g(x.desired_position);
    let ed = g(x.motor_velocity) - g(x.desired_velocity);
    let (de, ded) = (add(e), add(ed));
    let lam = d.lambda * un.speed / un.angle;
    let r = ed + lam * e;
    let dr = ded + lam * de + rnd(lam * e) + add(r);
    // Friction.
    let th: [f64; 4] = [
        g(st.friction[0]),
        g(st.friction[1]),
        g(st.friction[2]),
        g(st.friction[3]),
    ];
    let v = g(x.motor_velocity);
    let eps_v = d.eps_velocity * un.speed;
    let s = v.sat(eps_v);
    let ds = rnd(1.0);
    let q2 = v * v;
    let dq2 = rnd(q2);
    let arg = th[3] * q2;
    let darg = th[3] * dq2 + rnd(arg);
    let ex = (-arg).exp();
    let dex = ex * darg + if fixed { q } else { 4.0 * u * ex };
    let es = ex * s;
    let des = dex * s.abs() + ex * ds + rnd(es);
    let q2e = q2 * ex;
    let dq2e = dq2 * ex + q2 * dex + rnd(q2e);
    let y4 = -th[2] * q2e * s;
    let dy4 = th[2].abs() * (dq2e * s.abs() + q2e * ds) + rnd(th[2] * q2e) + rnd(y4);
    let f = th[0] * v + th[1] * s + th[2] * es;
    let df = rnd(th[0] * v)
        + th[1].abs() * ds
        + rnd(th[1] * s)
        + th[2].abs() * des
        + rnd(th[2] * es)
        + 2.0 * add(f);
    RegressorBudget {
        e,
        ed,
        de,
        ded,
        r,
        dr,
        y: [v, s, es, y4],
        dy: [0.0, ds, des, dy4],
        f,
        df,
    }
}

/// First-order error budget of the stored-unit law on backend `S`
/// against exact arithmetic on the same (stored) inputs and parameters,
/// in SI N·m. It follows the implementation's operations one by one:
/// each rounding of a value of stored magnitude `m` costs
/// `½ LSB + 2·2⁻³⁰ m` in fixed point (product, prepared coefficient) and
/// `u·m` in floats (`u = RESOLUTION/2`); fixed additions are exact, float
/// additions cost `u·|sum|`; `exp` costs 1 LSB (fixed, `e^x ≤ 1`) or 2 ulp
/// (f32); `sat(x, ε)` is `1/ε`-Lipschitz, its error capped at 2.
pub fn law_error_budget<S: Scalar>(
    cfg: &RobustAdaptiveConfig<S>,
    st: &RobustAdaptiveState<S>,
    x: &ControlInput<S>,
) -> f64 {
    let q = S::RESOLUTION.to_f64();
    let rnd = rounding::<S>;
    let add = addition::<S>;
    let d = cfg.quantized_design();
    let un = S::UNITS;
    let mt = un.motor_torque;
    let g = |v: S| v.to_f64();
    let RegressorBudget {
        e,
        ed,
        de,
        ded,
        r,
        dr,
        y,
        dy,
        f,
        df,
    } = regressor_budget(cfg, st, x);
    let c_acc = d.rotor_inertia * mt / un.speed;
    let c_ed = 2.0 * d.lambda * d.rotor_inertia * mt / un.speed;
    let c_e = d.lambda * d.lambda * d.rotor_inertia * mt / un.angle;
    let ia = [g(x.desired_acceleration) * c_acc, ed * c_ed, e * c_e];
    let dia = rnd(ia[0])
        + c_ed * ded
        + rnd(ia[1])
        + c_e * de
        + rnd(ia[2])
        + 2.0 * add(ia.iter().map(|v| v.abs()).sum());
    // Robust terms.
    let eps_r = d.eps_r * un.speed;
    let kr = d.robust_gain() * mt;
    let drob = kr * (dr / eps_r + rnd(1.0)).min(2.0) + rnd(kr);
    let ys = crate::friction::regressor_scales::<S>();
    let rho = d.friction_bounds.variable();
    let mut dparam = 0.0;
    let mut mag = 0.0;
    for j in 0..4 {
        let ry = r * y[j];
        let dry = r.abs() * dy[j] + y[j].abs() * dr + rnd(ry);
        let eps_j = d.eps_f[j] * un.speed * ys[j];
        let dss = (dry / eps_j + rnd(1.0)).min(2.0);
        let rj = rho[j] * mt / ys[j];
        let ry_term = rj * y[j];
        let term = ry_term * ry.sat(eps_j);
        dparam +=
            (rj * dy[j] + rnd(ry_term)) + ry_term.abs() * dss + rnd(term) + add(mag + term.abs());
        mag += term.abs();
    }
    let fb = g(x.joint_torque) * mt / (d.ratio * un.link_torque);
    let total = ia.iter().map(|v| v.abs()).sum::<f64>()
        + fb.abs()
        + f.abs()
        + g(st.integral).abs()
        + kr
        + mag;
    let budget = dia + rnd(fb) + df + drob + dparam + 5.0 * add(total);
    (budget * 1.01 + q) / mt
}
