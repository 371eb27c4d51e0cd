#!/usr/bin/env python3
"""Regenerate the polynomial coefficients of src/scalar/kernels/f32.rs.

Each polynomial approximates the remainder after the exactly known leading
terms on the kernel's reduced interval, at 50 digits, then rounded to f32.
Two kinds of fit:

* "cheb": mpmath's Chebyshev approximation (near-minimax in absolute error
  of the remainder).
* "remez": the minimax polynomial of the remainder for the *relative* error
  of the kernel's result (Remez exchange, weighted), accurate far below the
  f32 rounding with one coefficient fewer than the earlier "cheb" fits:
  EXP_E (relative error of e^r, 3.1e-9 at the minimax level) and TAN_T
  (relative error of tan d, which is also that of the reflected 1/tan d,
  1.3e-9); the printed errors are those of the f32-rounded coefficients.
  An optional nudge then moves single coefficients by whole f32 ulps; it is
  chosen by the exhaustive proof's measured maximum error, not by the fit.

The error bounds of the kernels are not taken from these fits: they are
proven by the exhaustive tests in proofs/kernels_f32.rs.

Usage: python3 proofs/kernels_f32_coefficients.py   (needs `pip install mpmath`)
"""
import struct

import mpmath as mp

mp.mp.dps = 50


def f32(v):
    return struct.unpack("f", struct.pack("f", float(v)))[0]


def f32_nudge(v, ulps):
    """Move the f32 `v` by `ulps` codes (same sign, no zero crossing)."""
    b = struct.unpack("I", struct.pack("f", v))[0]
    return struct.unpack("f", struct.pack("I", b + ulps))[0]


def remez(g, w, a, b, n, grid=4001, iters=30):
    """Coefficients (ascending) of the degree n-1 polynomial P minimising
    max |w(x)·(P(x) − g(x))| on [a, b] (Remez exchange on a grid, each
    extremum refined by golden-section search)."""
    m = n + 1
    # Chebyshev-like start, kept off the midpoint (w may vanish there).
    xs = [(a + b) / 2 - (b - a) / 2 * mp.cos(mp.pi * (i + mp.mpf("0.1")) / (m - 1 + mp.mpf("0.5")))
          for i in range(m)]
    pts = [a + (b - a) * mp.mpf(i) / grid for i in range(grid + 1)]
    for _ in range(iters):
        A = mp.matrix(m, m)
        rhs = mp.matrix(m, 1)
        for i, x in enumerate(xs):
            for j in range(n):
                A[i, j] = x ** j
            A[i, n] = (-1) ** i / w(x)
            rhs[i] = g(x)
        sol = mp.lu_solve(A, rhs)
        c = [sol[j] for j in range(n)]
        level = abs(sol[n])

        def err(x):
            return w(x) * (mp.polyval(c[::-1], x) - g(x))

        vals = [err(x) for x in pts]
        # One extremum per run of equal sign.
        runs, cur = [], [0]
        for i in range(1, len(pts)):
            if (vals[i] >= 0) == (vals[cur[0]] >= 0):
                cur.append(i)
            else:
                runs.append(cur)
                cur = [i]
        runs.append(cur)
        ext = []
        for run in runs:
            i = max(run, key=lambda i: abs(vals[i]))
            lo, hi = pts[max(i - 1, 0)], pts[min(i + 1, grid)]
            for _ in range(60):
                m1, m2 = lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618
                if abs(err(m1)) > abs(err(m2)):
                    hi = m2
                else:
                    lo = m1
            x = (lo + hi) / 2
            ext.append(x if abs(err(x)) > abs(vals[i]) else pts[i])
        while len(ext) > m:
            if abs(err(ext[0])) < abs(err(ext[-1])):
                ext.pop(0)
            else:
                ext.pop()
        assert len(ext) == m, "Remez: too few alternation points"
        xs = ext
        top = max(abs(v) for v in vals)
        if (top - level) / level < mp.mpf("1e-12"):
            break
    return c


def sq(z):
    return mp.sqrt(z)


FITS = [
    # name, g, interval, number of coefficients, form, method
    # (method: ("cheb",) or ("remez", weight, {index: ulps nudged}))
    ("ATAN_Q", lambda z: (mp.atan(sq(z)) - sq(z)) / sq(z) ** 3,
     mp.mpf("1e-30"), mp.mpf("0.36"), 7, "atan u = u + u^3 Q(u^2), u in [0, 0.6]", ("cheb",)),
    # Weight d^3/tan d: the error of T times it is the relative error of
    # tan d, and so (to first order) of the reflected 1/tan d as well.
    # Nudge: T[1] one ulp up (exhaustive maximum 1.612 instead of 1.633 ulp).
    ("TAN_T", lambda z: (mp.tan(sq(z)) - sq(z)) / sq(z) ** 3,
     mp.mpf("1e-20"), (mp.pi / 4) ** 2, 7, "tan d = d + d^3 T(d^2), d in [0, pi/4]",
     ("remez", lambda z: sq(z) ** 3 / mp.tan(sq(z)), {1: +1})),
    # Weight r^2/e^r: the error of E times it is the relative error of e^r.
    # Nudge: E[2] one ulp down (exhaustive maximum 0.976 instead of 0.989 ulp).
    ("EXP_E", lambda r: (mp.exp(r) - 1 - r) / r ** 2 if r != 0 else mp.mpf(1) / 2,
     -mp.log(2) / 2, mp.log(2) / 2, 5, "e^r = 1 + r + r^2 E(r), |r| <= ln2/2",
     ("remez", lambda r: r ** 2 / mp.exp(r), {2: -1})),
    ("SIN_S", lambda z: (mp.sin(sq(z)) - sq(z)) / sq(z) ** 3,
     mp.mpf("1e-30"), (mp.pi / 4) ** 2, 4, "sin r = r + r^3 S(r^2), |r| <= pi/4", ("cheb",)),
    ("COS_C", lambda z: (mp.cos(sq(z)) - 1 + z / 2) / z ** 2,
     mp.mpf("1e-30"), (mp.pi / 4) ** 2, 3, "cos r = 1 - r^2/2 + r^4 C(r^2), |r| <= pi/4", ("cheb",)),
    ("ASIN_A", lambda z: (mp.asin(sq(z)) - sq(z)) / sq(z) ** 3,
     mp.mpf("1e-30"), mp.mpf("0.25"), 7, "asin s = s + s^3 A(s^2), s in [0, 1/2]", ("cheb",)),
]

if __name__ == "__main__":
    for name, g, a, b, n, form, method in FITS:
        pts = [a + (b - a) * (i + 0.5) / 997 for i in range(997)]
        if method[0] == "cheb":
            poly = mp.chebyfit(g, [a, b], n)
            coeffs = [f32(c) for c in poly[::-1]]  # ascending powers
            # Error of the f32-rounded remainder polynomial, sampled.
            err = max(abs(g(t) - mp.polyval(coeffs[::-1], t)) for t in pts)
            what = "max |remainder error|"
        else:
            _, w, nudges = method
            coeffs = [f32(c) for c in remez(g, w, a, b, n)]
            for i, ulps in nudges.items():
                coeffs[i] = f32_nudge(coeffs[i], ulps)
            err = max(abs(w(t) * (g(t) - mp.polyval(coeffs[::-1], t))) for t in pts)
            what = "max relative error of the result"
        print(f"// {form}; {what} (f32 coefficients): {mp.nstr(err, 3)}")
        print(f"const {name}: [f32; {n}] = [")
        for c in coeffs:
            print(f"    {c!r},")
        print("];")
