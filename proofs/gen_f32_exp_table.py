#!/usr/bin/env python3
"""Print the table of kernels::f32::exp_neg_abs (EXP_NEG_ABS_TABLE in
src/scalar/kernels/f32.rs): for j = 0..64 the encoding of 2^(-j/64)
correctly rounded to f32 (computed at 200 bits), plus j*2^17, which the
kernel's subtraction of k*2^17 = m*2^23 + j*2^17 cancels. The test
`exp_neg_abs_edges` checks every entry against the f64 power.

Usage: python3 proofs/gen_f32_exp_table.py   (needs `pip install mpmath`)
"""
import struct

import mpmath as mp

mp.mp.prec = 200


def f32_bits(v):
    return struct.unpack("I", struct.pack("f", v))[0]


def f32_correct(v):
    """The f32 nearest to the high-precision v (float(v) rounds to f64
    first; the neighbours are compared in case the double rounding went
    wrong)."""
    c = struct.unpack("f", struct.pack("f", float(v)))[0]
    b = f32_bits(c)
    cands = [c] + [struct.unpack("f", struct.pack("I", b + d))[0] for d in (-1, 1)]
    return min(cands, key=lambda x: abs(mp.mpf(x) - v))


rows = []
for j in range(64):
    bits = f32_bits(f32_correct(mp.power(2, -mp.mpf(j) / 64))) + (j << 17)
    rows.append("0x%04x_%04x" % divmod(bits, 0x10000))
for i in range(0, 64, 4):
    print("    " + ", ".join(rows[i : i + 4]) + ",")
