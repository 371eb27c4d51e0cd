#!/usr/bin/env python3
"""Regenerate the polynomial coefficients of src/scalar/kernels/f32.rs.

Each polynomial approximates the remainder after the exactly known leading
terms on the kernel's reduced interval; the fit is mpmath's Chebyshev
approximation (near-minimax) at 50 digits, then rounded to f32. The error
bounds of the kernels are not taken from these fits: they are proven by the
exhaustive tests in proofs/kernels_f32.rs.

Usage: python3 proofs/kernels_f32_coefficients.py   (needs `pip install mpmath`)
"""
import struct

import mpmath as mp

mp.mp.dps = 50


def f32(v):
    return struct.unpack("f", struct.pack("f", float(v)))[0]



FITS = [
    # name, g(z), interval, number of coefficients, form
    ("ATAN_Q", lambda z: (mp.atan(mp.sqrt(z)) - mp.sqrt(z)) / mp.sqrt(z) ** 3,
     mp.mpf("1e-30"), mp.mpf("0.36"), 7, "atan u = u + u^3 Q(u^2), u in [0, 0.6]"),
    ("TAN_T", lambda z: (mp.tan(mp.sqrt(z)) - mp.sqrt(z)) / mp.sqrt(z) ** 3,
     mp.mpf("1e-30"), (mp.pi / 4) ** 2, 8, "tan d = d + d^3 T(d^2), d in [0, pi/4]"),
    ("EXP_E", lambda r: (mp.exp(r) - 1 - r) / r ** 2 if r != 0 else mp.mpf(1) / 2,
     -mp.log(2) / 2, mp.log(2) / 2, 6, "e^r = 1 + r + r^2 E(r), |r| <= ln2/2"),
    ("SIN_S", lambda z: (mp.sin(mp.sqrt(z)) - mp.sqrt(z)) / mp.sqrt(z) ** 3,
     mp.mpf("1e-30"), (mp.pi / 4) ** 2, 4, "sin r = r + r^3 S(r^2), |r| <= pi/4"),
    ("COS_C", lambda z: (mp.cos(mp.sqrt(z)) - 1 + z / 2) / z ** 2,
     mp.mpf("1e-30"), (mp.pi / 4) ** 2, 3, "cos r = 1 - r^2/2 + r^4 C(r^2), |r| <= pi/4"),
    ("ASIN_A", lambda z: (mp.asin(mp.sqrt(z)) - mp.sqrt(z)) / mp.sqrt(z) ** 3,
     mp.mpf("1e-30"), mp.mpf("0.25"), 7, "asin s = s + s^3 A(s^2), s in [0, 1/2]"),
]

if __name__ == "__main__":
    for name, g, a, b, n, form in FITS:
        poly = mp.chebyfit(g, [a, b], n)
        coeffs = [f32(c) for c in poly[::-1]]  # ascending powers
        # Error of the f32-rounded remainder polynomial, sampled.
        pts = [a + (b - a) * (i + 0.5) / 997 for i in range(997)]
        err = max(abs(g(t) - mp.polyval(coeffs[::-1], t)) for t in pts)
        print(f"// {form}; max |remainder error| (f32 coefficients): {mp.nstr(err, 3)}")
        print(f"const {name}: [f32; {n}] = [")
        for c in coeffs:
            print(f"    {c!r},")
        print("];")
