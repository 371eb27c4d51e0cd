//! Thesis ch. 2–3 experiments reproduced in simulation.
#![cfg(feature = "sim")]
