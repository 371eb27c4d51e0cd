//! The compact DAUJ wrist of thesis ch. 5–6.
//!
//! * [`ft_sensor`] — the F/T sensor chain: gauge amplifier (eq. 6.34),
//!   decoupling matrix (eq. 6.35) and the interaction torques about the
//!   wrist axes (eq. 6.3).
//! * [`active`] — the robust adaptive law of both wrist motors (eq.
//!   6.12–6.15, Theorem 2), the arm-motion coupling (eq. 6.4, 6.9–6.10),
//!   Table 6.1 and the ultimate bound (eq. 6.24–6.27).
//! * [`admittance`] — the passive mode by the admittance law (eq.
//!   6.28–6.33) in task space, with its discrete-time stability range.
//! * [`modes`] — active ↔ passive switching of the wrist's task-space
//!   reference, bumpless.

pub mod active;
pub mod admittance;
pub mod ft_sensor;
pub mod modes;
