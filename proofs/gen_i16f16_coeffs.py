#!/usr/bin/env python3
"""Generator of the I16F16 kernel constants in src/scalar/kernels/i16f16.rs.

Run: python3 proofs/gen_i16f16_coeffs.py   (needs mpmath; prints Rust items)

Polynomials are near-minimax Chebyshev fits (mpmath.chebyfit) computed at
80-digit precision, then rounded to the fixed-point format used by the
kernel. The rounding of each constant is part of what the exhaustive proofs
in proofs/kernels_i16f16.rs check.
"""
from mpmath import mp, mpf, pi, sin, cos, atan, log, e, sqrt, chebyfit, floor, nint, tan, exp

mp.dps = 80
Q32 = mpf(2) ** 32


def q(v, bits):
    return int(nint(v * mpf(2) ** bits))


def emit(name, ty, v):
    print(f"const {name}: {ty} = {v};")


# --- sin / cos on rho in [0, pi/4 + margin], z = rho^2 -------------------
zmax = (pi / 4 + mpf(2) ** -10) ** 2


def g_sin(z):
    if z == 0:
        return mpf(1) / 6
    r = sqrt(z)
    return (1 - sin(r) / r) / z


def g_cos(z):
    if z == 0:
        return mpf(1) / 2
    r = sqrt(z)
    return (1 - cos(r)) / z


for name, g in (("SIN", g_sin), ("COS", g_cos)):
    # g(z) = k1 + k2 z + k3 z^2 ; kernel uses k1 - z (k2' - z k3') with k2' = -k2
    poly, err = chebyfit(g, [0, zmax], 3, error=True)
    k3, k2, k1 = poly  # highest degree first
    print(f"// {name}: g(z) fit error {float(err):.3e} (times z*rho <= 0.5 in the kernel)")
    emit(f"{name}_K1", "u32", q(k1, 32))
    emit(f"{name}_K2", "u32", q(-k2, 32))
    emit(f"{name}_K3", "u32", q(k3, 32))


def cubic_table(g, pieces=32, bits=32):
    """`pieces` cubic pieces of g(k, H), H in [0, 1): rows (b0, b1, b2, b3)
    with `bits` fraction bits and g ~ b0 + H(b1 + H(b2 + H b3)), and the
    worst fit error."""
    rows, worst = [], 0
    for k in range(pieces):
        poly, err = chebyfit(lambda h, k=k: g(k, h), [0, 1], 4, error=True)
        worst = max(worst, err)
        b3, b2, b1, b0 = poly
        rows.append((q(b0, bits), q(b1, bits), q(b2, bits), q(b3, bits)))
    print(f"// worst piece fit error {float(worst):.3e}")
    return rows


# --- atan: 32 cubic pieces on [k/32, (k+1)/32), H = 32 (t - k/32) in [0,1) --
print("// ATAN_TABLE[k] = [b0, b1, b2, b3]: atan(k/32 + H/32) ~ b0 + H(b1 + H(b2 + H b3)), Q0.32")
rows = cubic_table(lambda k, h: atan((k + h) / 32))
print("const ATAN_TABLE: [[i32; 4]; 32] = [")
for r in rows:
    # b0 < pi/4 * 2^32 does not fit i32: store b0 as u32 bit pattern
    print(f"    [{r[0] - (1 << 32) if r[0] >= 1 << 31 else r[0]}, {r[1]}, {r[2]}, {r[3]}],")
print("];")

# --- atan_small on [1, 2): atan(1 + (k + H)/32) - pi/4, the same cubic form ---
print("// ATAN_TABLE_HI[k]: atan(1 + k/32 + H/32) - pi/4 ~ b0 + H(b1 + H(b2 + H b3)), Q0.32")
rows = cubic_table(lambda k, h: atan(1 + (k + h) / 32) - pi / 4)
print("const ATAN_TABLE_HI: [[i32; 4]; 32] = [")
for r in rows:
    print(f"    [{r[0]}, {r[1]}, {r[2]}, {r[3]}],")
print("];")

# --- rsqrt on [1/4, 1): 24 cubic pieces on [1/4 + k/32, 1/4 + (k+1)/32) ----
print("// RSQRT_TABLE[k]: 1/sqrt(1/4 + k/32 + H/32) ~ b0 + H(b1 + H(b2 + H b3)), Q2.30")
rows = cubic_table(lambda k, h: 1 / sqrt(mpf(1) / 4 + (k + h) / 32), pieces=24, bits=30)
print("const RSQRT_TABLE: [[i32; 4]; 24] = [")
for r in rows:
    print(f"    [{r[0]}, {r[1]}, {r[2]}, {r[3]}],")
print("];")

# --- tan: 20 cubic pieces in z = x^2 on [k/32, (k+1)/32), z < (pi/4)^2 ------
# TAN_TABLE[k]: tan(sqrt z)/sqrt z - 1 (for |x| <= pi/4, tan x = x (1 + .)),
# COT_TABLE[k]: 1 - sqrt z cot(sqrt z) (for delta = pi/2 - |x|,
# tan x = cot delta = (1 - .)/delta); both Q0.32.
def g_tan(k, h):
    z = (k + h) / 32
    if z == 0:
        return mpf(0)
    r = sqrt(z)
    return tan(r) / r - 1


def g_cot(k, h):
    z = (k + h) / 32
    if z == 0:
        return mpf(0)
    r = sqrt(z)
    return 1 - r * cos(r) / sin(r)


for name, g in (("TAN_TABLE", g_tan), ("COT_TABLE", g_cot)):
    print(f"// {name}[k] = [b0, b1, b2, b3], Q0.32")
    rows = cubic_table(g, pieces=20)
    print(f"const {name}: [[i32; 4]; 20] = [")
    for r in rows:
        print(f"    [{r[0]}, {r[1]}, {r[2]}, {r[3]}],")
    print("];")

# --- tan_bounded: G = tan(sqrt z)/sqrt z - 1 on z in [0, 67/32), |x| up to
# atan(8) (z = 2.0922); 67 cubic pieces, Q3.29 (G < 4.6).
print("// TAN_BOUNDED_TABLE[k] = [b0, b1, b2, b3], Q3.29")
rows = cubic_table(g_tan, pieces=67, bits=29)
print("const TAN_BOUNDED_TABLE: [[i32; 4]; 67] = [")
for r in rows:
    print(f"    [{r[0]}, {r[1]}, {r[2]}, {r[3]}],")
print("];")
print(f"const TAN_BOUNDED_MAX_BITS: u32 = {int(floor(atan(8) * 65536))};")

# --- exp: 2^(j/64) in Q1.31 and 2^(R/64) - 1 = R (c1 + R (c2 + R c3)) -----
print("const EXP2_TABLE: [u32; 64] = [")
print("    " + ", ".join(str(q(mpf(2) ** (mpf(j) / 64), 31)) for j in range(64)) + ",")
print("];")


def g_exp(r):
    if r == 0:
        return log(2) / 64
    return (mpf(2) ** (r / 64) - 1) / r


poly, err = chebyfit(g_exp, [0, 1], 3, error=True)
c3, c2, c1 = poly
print(f"// EXP fit error {float(err):.3e}")
emit("EXP_C1", "u32", q(c1, 32))
emit("EXP_C2", "u32", q(c2, 32))
emit("EXP_C3", "u32", q(c3, 32))


# --- exp_neg_abs: e^(-i/16) in Q0.31, i = 0 .. while it can round to 1 LSB --
# exp_neg_abs is 0 from the smallest raw |x| whose e^(-|x|) < 2^-17.
zero = int(floor(17 * log(2) * 65536)) + 1
print(f"// e^(-i/16) in Q0.31, i = 0..={(zero - 1) >> 12}.")
print(f"const EXP_NEG_TABLE: [u32; {((zero - 1) >> 12) + 1}] = [")
vals = [str(q(exp(-mpf(i) / 16), 31)) for i in range(((zero - 1) >> 12) + 1)]
for k in range(0, len(vals), 8):
    print("    " + ", ".join(vals[k:k + 8]) + ",")
print("];")
emit("EXP_NEG_ZERO_BITS", "u32", zero)

# --- constants ---------------------------------------------------------------
log2e = 1 / log(2)
hi = int(floor(log2e * mpf(2) ** 31))
emit("LOG2E_Q31", "u32", hi)
emit("LOG2E_LO_Q43", "u32", q(log2e * mpf(2) ** 31 - hi, 12))
emit("TWO_OVER_PI_Q32", "u32", q(2 / pi, 32))
p1 = int(floor(pi / 2 * mpf(2) ** 30))
emit("PIO2_Q30_HI", "u32", p1)
emit("PIO2_Q30_LO_Q17", "u32", q(pi / 2 * mpf(2) ** 30 - p1, 17))
emit("PIO2_Q30", "u32", q(pi / 2, 30))
emit("PIO4_Q30", "u32", q(pi / 4, 30))
emit("PI_Q30", "u32", q(pi, 30))
emit("PIO2_Q48", "u64", q(pi / 2, 48))
# exp saturates where the reference rounds to MAX: exp(x) >= 32768 - 2^-17
xs = log(mpf(32768) - mpf(2) ** -17) * 65536
emit("EXP_SAT_BITS", "i32", int(floor(xs)) + 1)
# tan saturates where the reference exceeds MAX: tan(x) >= 32768 - 2^-17
ts = atan(mpf(32768) - mpf(2) ** -17) * 65536
emit("TAN_SAT_BITS", "u32", int(floor(ts)) + 1)
emit("PIO4_BITS", "u32", int(floor(pi / 4 * 65536)))
emit("FRAC_PI_2_BITS", "u32", int(floor(pi / 2 * 65536)) + 1)
