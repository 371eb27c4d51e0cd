//! Q15 normalized fixed point (placeholder; filled in by the Q15 kernels).
