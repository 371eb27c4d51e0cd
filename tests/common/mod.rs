//! Helpers shared by the engine tests.

use std::f64::consts::PI;

/// The `n × n` grid of the motor torus `(θ1, θ3)` at cell centres, in
/// serpentine order (neighbours one step apart, so a mechanism driven
/// from one point to the next moves by one cell), rad.
pub fn motor_grid(n: usize) -> Vec<(f64, f64)> {
    let step = 2.0 * PI / n as f64;
    let mut v = Vec::new();
    for i in 0..n {
        let t1 = -PI + (i as f64 + 0.5) * step;
        for j in 0..n {
            let jj = if i % 2 == 0 { j } else { n - 1 - j };
            v.push((t1, -PI + (jj as f64 + 0.5) * step));
        }
    }
    v
}
