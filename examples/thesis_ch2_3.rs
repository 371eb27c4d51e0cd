//! Thesis ch. 2–3 experiments reproduced in simulation.
fn main() {}
