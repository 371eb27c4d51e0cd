//! Properties of the sign function (thesis eq. 2.17) and of the
//! boundary-layer saturation `sat(x, y)` (thesis eq. 4.18), generic over the
//! [`Scalar`] backends.
//!
//! | property | I16F16 | f32 | f64 |
//! |---|---|---|---|
//! | `sgn_exact` | Kani; exhaustive (all 2³² inputs) | Kani; exhaustive (all 2³² bit patterns) | random |
//! | `sat_in_range`, `sat_matches_definition` | Kani; exhaustive over all 2³² pairs of a 16-bit lattice (`k·2⁻⁸`) | Kani; exhaustive over all 2³² pairs of bfloat16-valued inputs | random |
//! | `sat_odd` | same | same | random |
//! | `sat_monotone_step` (continuity + monotonicity in `x`) | same | same | random |
//!
//! The 16-bit lattices: for `I16F16`, every pair `(x, y)` whose bit patterns
//! are `a << 8`, `b << 8` for 16-bit `a, b` (the `I8F8` values, range ±128,
//! step 2⁻⁸); for `f32`, every pair whose bit patterns are `a << 16`,
//! `b << 16` (the bfloat16 values: every sign, every exponent, including
//! zeros, subnormals, infinities and NaNs).

use super::engine::Verdict;
pub use super::kernels_f32::next_up;
use crate::scalar::{Scalar, I16F16};

/// `sgn` returns exactly `1`, `0` or `-1` according to the sign of `x`,
/// with `sgn(±0) = 0` and `sgn(NaN) = 0` (eq. 2.17).
pub fn sgn_exact<S: Scalar>(x: S) -> Verdict {
    let expected = if x > S::ZERO {
        S::ONE
    } else if x < S::ZERO {
        S::ONE.neg()
    } else {
        S::ZERO
    };
    let got = x.sgn();
    Verdict::logical(got == expected && !got.is_nan())
}

/// `sat(x, y)` is never NaN and lies in `[-1, 1]`.
pub fn sat_in_range<S: Scalar>(x: S, y: S) -> Verdict {
    let s = x.sat(y);
    Verdict::logical(!s.is_nan() && s >= S::ONE.neg() && s <= S::ONE)
}

/// `sat(x, y)` equals the thesis definition evaluated exactly (in `f64` on
/// the exact input values) to within half a unit of the backend's
/// resolution at 1 (rounding of the quotient `x/|y|`), plus `1e-12` for the
/// `f64` evaluation of the reference. The error is reported in units of
/// [`Scalar::RESOLUTION`].
pub fn sat_matches_definition<S: Scalar>(x: S, y: S) -> Verdict {
    sat_value_matches_definition(x.sat(y).to_f64(), x, y)
}

/// The check behind [`sat_matches_definition`], for a given result `got`.
pub fn sat_value_matches_definition<S: Scalar>(got: f64, x: S, y: S) -> Verdict {
    let (xf, yf) = (x.to_f64(), y.to_f64());
    let expected = if x.is_nan() {
        0.0
    } else if y.is_nan() || xf.abs() > yf {
        // Outside the boundary layer: x / |x| (and 0 for x = 0).
        if xf > 0.0 {
            1.0
        } else if xf < 0.0 {
            -1.0
        } else {
            0.0
        }
    } else if yf == 0.0 {
        0.0
    } else if xf.is_infinite() {
        // |x| = y = +inf: the limit of x/|y| along |x| = y.
        xf.signum()
    } else {
        xf / yf.abs()
    };
    let res = S::RESOLUTION.to_f64();
    Verdict::bounded((got - expected).abs() / res, 0.5 + 1e-12 / res)
}

/// [`sat_matches_definition`] for `I16F16`, decided in exact integer
/// arithmetic on the bit patterns (no `f64` on the way, so Kani decides it
/// bit-precisely): with `X`, `Y` the bits of `x`, `y` and `Q` those of
/// `sat(x, y)`,
/// * `Y ≤ 0` or `|X| > Y` (outside the boundary layer, eq. 4.18):
///   `Q = 2¹⁶·sgn(X)` exactly;
/// * otherwise `|Q/2¹⁶ − X/Y| ≤ ½ LSB`, i.e. `2·|Q·Y − 2¹⁶·X| ≤ Y` (all
///   products below 2⁴⁸ in magnitude, so `i64` holds them exactly).
///
/// The same bound as [`sat_matches_definition`] (half an LSB), without its
/// `1e-12` slack for the `f64` reference.
pub fn sat_matches_definition_i16f16(x: I16F16, y: I16F16) -> Verdict {
    sat_bits_match_definition(x.sat(y).to_bits(), x.to_bits(), y.to_bits())
}

/// The check behind [`sat_matches_definition_i16f16`] for a computed result
/// `q` (bits), inputs `x`, `y` (bits).
pub fn sat_bits_match_definition(q: i32, x: i32, y: i32) -> Verdict {
    const ONE: i64 = 1 << 16;
    let (q, x, y) = (q as i64, x as i64, y as i64);
    let holds = if y <= 0 || x.abs() > y {
        q == ONE * x.signum()
    } else {
        2 * (q * y - ONE * x).abs() <= y
    };
    Verdict::logical(holds)
}

/// The contract of the `I16F16` quotient `div_bits(a, b)` on the operands
/// `sat` gives it (`0 < b`, `|a| ≤ b`, bits): `q` is the quotient
/// `2¹⁶·a/b` rounded to nearest with ties away from zero, i.e. with the
/// error `e = q·b − 2¹⁶·a` (below 2⁴⁸ in magnitude, exact in `i64`),
/// `2·|e| < b`, or `2·|e| = b` with `e` of the sign of `a`; and `|q| ≤ 2¹⁶`,
/// with `q = ±2¹⁶` exactly at `a = ±b`.
/// This is the whole of the division that the `sat` Kani harnesses use
/// (they replace `div_bits` by a value satisfying it); that `div_bits`
/// meets it is [`div_bits_meets_layer_contract`].
pub fn div_bits_layer_contract(a: i32, b: i32, q: i32) -> bool {
    const ONE: i64 = 1 << 16;
    let (q, a, b) = (q as i64, a as i64, b as i64);
    if q.abs() > ONE {
        return false;
    }
    let e = q * b - ONE * a;
    let nearest = 2 * e.abs() < b || (2 * e.abs() == b && (e > 0) == (a > 0));
    // Exact at the ends of the layer (implied by `nearest`, stated for the
    // solver, which does not factor `(q ∓ 2¹⁶)·b`).
    nearest && (a != b || q == ONE) && (a != -b || q == -ONE)
}

/// `div_bits(a, b)` satisfies [`div_bits_layer_contract`] for every
/// `0 < b`, `|a| ≤ b` (the other operands are outside the contract and
/// pass).
pub fn div_bits_meets_layer_contract(a: i32, b: i32) -> Verdict {
    if b <= 0 || a < -b || a > b {
        // Precondition of the contract: the boundary layer of `sat`.
        return Verdict::logical(true);
    }
    Verdict::logical(div_bits_layer_contract(
        a,
        b,
        crate::scalar::fixed::div_bits(a, b),
    ))
}

/// Two quotients of `div_bits` by the same `b` (bits), as the `sat`
/// harnesses for oddness and monotonicity use them: `q0 = div_bits(a0, b)`,
/// `q = div_bits(a, b)` satisfy: `a = a0 ⇒ q = q0` (a function), `a = −a0 ⇒
/// q = −q0` (odd), `a = a0 + 1 ⇒ q0 ≤ q` and `(q − q0 − 1)·b ≤ 2¹⁶`
/// (monotone, steps at most one LSB beyond the slope `2¹⁶/b`). All three
/// follow from [`div_bits_layer_contract`] (which fixes the quotient
/// uniquely and is symmetric in the sign of `a`); the solver cannot derive
/// them from two instances of it in 300 s (that needs distributivity of the
/// products), so they are stated here and checked on the real `div_bits`
/// by `exhaustive_div_bits_layer_contract` and at random.
pub fn div_bits_pair_lemma(a0: i32, q0: i32, a: i32, q: i32, b: i32) -> bool {
    let (a0, q0, a, q, b) = (a0 as i64, q0 as i64, a as i64, q as i64, b as i64);
    (a != a0 || q == q0)
        && (a != -a0 || q == -q0)
        && (a != a0 + 1 || (q0 <= q && (q - q0 - 1) * b <= 1 << 16))
}

/// [`sat_monotone_step`] for `I16F16` at consecutive bit patterns `x`,
/// `x + 1` (bits), in exact integer arithmetic (no `f64` on the way, so
/// Kani decides it bit-precisely): with `Q₀`, `Q₁` the bits of `sat(x, y)`,
/// `sat(x + 2⁻¹⁶, y)` and `Y` those of `y`, `Q₀ ≤ Q₁` and, for `Y > 0`,
/// `Q₁ − Q₀ ≤ 2¹⁶/Y + 1` (one LSB beyond the slope `1/y` of eq. 4.18), i.e.
/// `(Q₁ − Q₀ − 1)·Y ≤ 2¹⁶`.
pub fn sat_monotone_step_i16f16(x: i32, y: i32) -> Verdict {
    if x == i32::MAX {
        // Precondition: the successor of x exists.
        return Verdict::logical(true);
    }
    let (xs, ys) = (I16F16::from_bits(x), I16F16::from_bits(y));
    let q0 = xs.sat(ys).to_bits();
    let q1 = I16F16::from_bits(x + 1).sat(ys).to_bits();
    sat_step_bits_ok(q0, q1, y)
}

/// The check behind [`sat_monotone_step_i16f16`] for computed results
/// `q0`, `q1` (bits) and `y` (bits).
pub fn sat_step_bits_ok(q0: i32, q1: i32, y: i32) -> Verdict {
    let (q0, q1, y) = (q0 as i64, q1 as i64, y as i64);
    Verdict::logical(q0 <= q1 && (y <= 0 || (q1 - q0 - 1) * y <= 1 << 16))
}

/// Odd symmetry: `sat(-x, y) = -sat(x, y)` whenever `-x` is representable.
pub fn sat_odd<S: Scalar>(x: S, y: S) -> Verdict {
    if x == S::MIN {
        // Precondition: -MIN is not representable in fixed point.
        return Verdict::logical(true);
    }
    Verdict::logical(x.neg().sat(y) == x.sat(y).neg())
}

/// Monotone and continuous in `x`: for the next representable value `x'`
/// after `x` (`x' > x`), `sat(x, y) <= sat(x', y)` and, for `y > 0`, the
/// step is at most `(x' - x)/y` plus one resolution unit — so there is no
/// jump at `|x| = y` or anywhere else. The error is the step in excess of
/// `(x' - x)/y`, in resolution units.
pub fn sat_monotone_step<S: Scalar>(x: S, x_next: S, y: S) -> Verdict {
    if x.is_nan() || x_next.is_nan() || x >= x_next {
        // Precondition: x_next is strictly above x.
        return Verdict::logical(true);
    }
    sat_step_verdict(x, x_next, y, x.sat(y), x_next.sat(y))
}

/// The check of [`sat_monotone_step`] for results `a = sat(x, y)` and
/// `b = sat(x', y)` (`x' > x`, neither NaN).
pub fn sat_step_verdict<S: Scalar>(x: S, x_next: S, y: S, a: S, b: S) -> Verdict {
    let monotone = a <= b;
    if y.is_nan() || y <= S::ZERO {
        return Verdict::logical(monotone);
    }
    let res = S::RESOLUTION.to_f64();
    let allowed = (x_next.to_f64() - x.to_f64()) / y.to_f64();
    let excess = ((b.to_f64() - a.to_f64()) - allowed).max(0.0) / res;
    Verdict::logical(monotone).and(Verdict::bounded(excess, 1.0))
}

/// [`sat_step_verdict`] on `f32` without a division: for `y > 0`,
/// `(b − a) − (x' − x)/y ≤ ε` is `(b − a − ε)·y ≤ x' − x` (`ε` the `f32`
/// resolution), written with `f64` products. The same property in exact
/// arithmetic; the `f64` roundings of the two forms differ by a few units
/// of `2⁻⁵³` relative, far inside the one-unit (`2⁻²³`) allowance, and
/// `sat_step_product_form_agrees_with_the_quotient_form` compares them on
/// random and constructed results, failing ones included. For the Kani
/// harness, whose solver does not finish an `f64` division in 600 s.
pub fn sat_step_f32_products(x: f32, x_next: f32, y: f32, a: f32, b: f32) -> bool {
    let monotone = a <= b;
    if y.is_nan() || y <= 0.0 {
        return monotone;
    }
    let over = (b as f64 - a as f64) - f32::EPSILON as f64;
    monotone && (over <= 0.0 || over * y as f64 <= x_next as f64 - x as f64)
}

/// The body of `<f32 as Scalar>::div` (`src/scalar/float.rs`), for the
/// Kani stub of `kani_sat_odd_f32`, which cannot call the function it
/// replaces; `f32_div_body_is_scalar_div` tests the two equal bit for bit.
pub fn f32_div_body(a: f32, b: f32) -> f32 {
    if b == 0.0 {
        if a > 0.0 {
            f32::MAX
        } else if a < 0.0 {
            f32::MIN
        } else {
            0.0
        }
    } else {
        a / b
    }
}

/// The lemma that stub assumes: the division of `−a` is the negated
/// division of `a` (IEEE 754: the sign of a quotient is the exclusive or of
/// the operands' signs and its magnitude is `|a|/|b|` rounded, by a
/// rounding that is symmetric in the sign; the saturating `x/0` is odd by
/// its branches), compared with `==` (so `±0` agree) or both NaN.
pub fn f32_div_sign_symmetric(div: fn(f32, f32) -> f32, a: f32, b: f32) -> bool {
    let (p, m) = (div(a, b), div(-a, b));
    (p.is_nan() && m.is_nan()) || m == -p
}

/// The largest `f32` below `x` (for `x` not NaN and not `−∞`; `−0` and `+0`
/// both give `−2⁻¹⁴⁹`).
pub fn next_down(x: f32) -> f32 {
    let b = x.to_bits();
    if b == 0 {
        f32::from_bits(0x8000_0001)
    } else if b >> 31 == 0 {
        f32::from_bits(b - 1)
    } else {
        f32::from_bits(b + 1)
    }
}

/// The contract of `sat`'s division inside the boundary layer on `f32`:
/// for `0 < b < ∞` and `|a| ≤ b`, the quotient `q` is the `f32` nearest
/// `a/b` (IEEE 754 division rounds to nearest), written without a
/// division: `a/b` lies between the midpoints of `q` and its neighbours,
///
/// ```text
/// (q⁻ + q)/2 · b ≤ a ≤ (q + q⁺)/2 · b,      q⁻ = next_down(q), q⁺ = next_up(q),
/// ```
///
/// with both products exact in `f64` (a midpoint of neighbouring `f32`
/// values has at most 26 significant bits, `b` 24, and no product leaves
/// `f64`'s normal range). At a tie both neighbours satisfy it (the real
/// division picks the even one), so the contract allows a superset of the
/// real quotient. `q` must also be finite with `|q| ≤ 1`, which the
/// interval implies for the real division (1 is representable).
pub fn f32_div_rounding_contract(a: f32, b: f32, q: f32) -> bool {
    if !(q.is_finite() && q.abs() <= 1.0) {
        return false;
    }
    let (lo, hi) = (next_down(q) as f64, next_up(q) as f64);
    let (a, b, q) = (a as f64, b as f64, q as f64);
    (lo + q) * 0.5 * b <= a && a <= (q + hi) * 0.5 * b
}

/// What `sat`'s logic needs of its division inside the boundary layer on
/// `f32` (`0 < b < ∞`, `|a| ≤ b`), as comparisons only: `|q| ≤ 1`, the
/// quotient takes the sign of `a` (0 for ±0), and it is exactly `±1` at
/// `a = ±b`. IEEE 754 division guarantees each (the real quotient is in
/// `[−1, 1]` and both ends are representable; `b/b = 1` exactly), and
/// `f32_division_meets_layer_lemma` tests it on edge values and random
/// pairs. Weaker than [`f32_div_rounding_contract`]: it leaves the
/// quotient's value inside `(−1, 1)` free, so a harness that assumes it
/// decides the branch logic around the division, not the rounding.
pub fn f32_div_layer_lemma(a: f32, b: f32, q: f32) -> bool {
    let sign = if a > 0.0 {
        q >= 0.0
    } else if a < 0.0 {
        q <= 0.0
    } else {
        q == 0.0
    };
    q.abs() <= 1.0 && sign && (a != b || q == 1.0) && (a != -b || q == -1.0)
}

/// Two quotients by one divisor are in the order of their dividends
/// (IEEE 754: the exact quotient `a/b` is increasing in `a` for `b > 0`,
/// and rounding to nearest is non-decreasing), as comparisons only:
/// `a₀ ≤ a₁ ⇒ q₀ ≤ q₁` and `a₁ ≤ a₀ ⇒ q₁ ≤ q₀`. Tested on the real
/// division by `f32_division_is_monotone_in_the_dividend`.
pub fn f32_div_pair_lemma(a0: f32, q0: f32, a1: f32, q1: f32) -> bool {
    let (up, down) = (a0 <= a1, a1 <= a0);
    (!up || q0 <= q1) && (!down || q1 <= q0)
}

#[cfg(kani)]
pub(crate) mod kani_entries {
    //! One property per harness (a conjunction is as slow as its hardest
    //! part, and a split result says which part is decided). Every input is
    //! `kani::any()` over the whole type; no assumption cuts the domain
    //! except the stated preconditions.
    use super::*;

    #[kani::proof]
    fn kani_sgn_exact_i16f16() {
        assert!(sgn_exact(I16F16::from_bits(kani::any())).holds);
    }

    #[kani::proof]
    fn kani_sgn_exact_f32() {
        assert!(sgn_exact::<f32>(kani::any()).holds);
    }

    /// `div_bits` as its contract ([`div_bits_layer_contract`]): the
    /// `I16F16` `sat` harnesses check the logic of eq. (4.18) around the
    /// quotient, not the 64-bit division circuit again (which the solver
    /// does not finish in 600 s). The precondition is asserted at every
    /// call, so a `sat` that divided outside the boundary layer fails; the
    /// value is any one the contract allows, so the result holds for the
    /// real quotient once `kani_div_bits_layer_contract` (and the
    /// exhaustive `exhaustive_div_bits_layer_contract`) show `div_bits`
    /// meets the contract.
    ///
    /// A second call by the same `b` (the odd and monotone harnesses call
    /// `sat` twice) also assumes [`div_bits_pair_lemma`] relating the two
    /// quotients, which the contract implies but the solver does not derive.
    pub(crate) fn div_bits_as_contract(a: i32, b: i32) -> i32 {
        assert!(
            b > 0 && a >= -b && a <= b,
            "div_bits called outside the boundary layer"
        );
        let q: i32 = kani::any();
        // Postcondition of the stubbed function (proven separately).
        kani::assume(div_bits_layer_contract(a, b, q));
        if FIRST_CALL.load(Relaxed) {
            FIRST_CALL.store(false, Relaxed);
            A0.store(a, Relaxed);
            B0.store(b, Relaxed);
            Q0.store(q, Relaxed);
        } else if B0.load(Relaxed) == b {
            // Lemma on two quotients of the stubbed function (checked on
            // the real one by exhaustive_div_bits_layer_contract).
            kani::assume(div_bits_pair_lemma(
                A0.load(Relaxed),
                Q0.load(Relaxed),
                a,
                q,
                b,
            ));
        }
        q
    }

    use core::sync::atomic::Ordering::Relaxed;
    use core::sync::atomic::{AtomicBool, AtomicI32};
    /// The operands and quotient of the first stubbed `div_bits` call.
    static FIRST_CALL: AtomicBool = AtomicBool::new(true);
    static A0: AtomicI32 = AtomicI32::new(0);
    static B0: AtomicI32 = AtomicI32::new(0);
    static Q0: AtomicI32 = AtomicI32::new(0);

    /// The contract `div_bits_as_contract` stands for: `div_bits` meets it
    /// on every operand pair in the boundary layer.
    #[kani::proof]
    fn kani_div_bits_layer_contract() {
        assert!(div_bits_meets_layer_contract(kani::any(), kani::any()).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::fixed::div_bits, div_bits_as_contract)]
    fn kani_sat_in_range_i16f16() {
        let x = I16F16::from_bits(kani::any());
        let y = I16F16::from_bits(kani::any());
        assert!(sat_in_range(x, y).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::fixed::div_bits, div_bits_as_contract)]
    fn kani_sat_definition_i16f16() {
        let x = I16F16::from_bits(kani::any());
        let y = I16F16::from_bits(kani::any());
        assert!(sat_matches_definition_i16f16(x, y).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::fixed::div_bits, div_bits_as_contract)]
    fn kani_sat_odd_i16f16() {
        let x = I16F16::from_bits(kani::any());
        let y = I16F16::from_bits(kani::any());
        assert!(sat_odd(x, y).holds);
    }

    #[kani::proof]
    #[kani::stub(crate::scalar::fixed::div_bits, div_bits_as_contract)]
    fn kani_sat_monotone_i16f16() {
        assert!(sat_monotone_step_i16f16(kani::any(), kani::any()).holds);
    }

    /// `x`, `y` for the f32 harnesses. Checker limit, not a property
    /// precondition: for `y = +∞`, `sat` divides `x/∞` (`±0`, or `±∞/∞`,
    /// whose NaN it replaces by `sgn(x)`), and CBMC 6.6.0's `--nan-check`,
    /// which Kani turns on with its overflow checks, reports "NaN on
    /// division" for `0/∞` as well, although the quotient is 0 (a
    /// three-line C program shows it with `cbmc --nan-check` alone). The
    /// pairs with `y = +∞` are left to the exhaustive engine
    /// (`exhaustive_sat_f32`: every pair of bfloat16 values, `y = +∞` with
    /// every `x` among them) and to `sat_of_infinities_is_the_limit`.
    fn any_f32_pair() -> (f32, f32) {
        let (x, y): (f32, f32) = (kani::any(), kani::any());
        kani::assume(y != f32::INFINITY);
        (x, y)
    }

    #[kani::proof]
    fn kani_sat_in_range_f32() {
        let (x, y) = any_f32_pair();
        assert!(sat_in_range(x, y).holds);
    }

    use core::sync::atomic::AtomicU32;
    /// The operands and quotient (bits) of the first stubbed f32 division.
    static FD_FIRST: AtomicBool = AtomicBool::new(true);
    static FD_A0: AtomicU32 = AtomicU32::new(0);
    static FD_B0: AtomicU32 = AtomicU32::new(0);
    static FD_Q0: AtomicU32 = AtomicU32::new(0);

    /// `<f32 as Scalar>::div` for `kani_sat_odd_f32`: the real quotient
    /// ([`f32_div_body`]), except that a second division whose numerator is
    /// the first one's negated (same divisor) returns the first quotient
    /// negated instead of dividing again. That is the lemma
    /// [`f32_div_sign_symmetric`] of IEEE division, checked on the real
    /// division by `f32_division_is_sign_symmetric` (edge values and random
    /// bit patterns) and, inside the boundary layer, by `exhaustive_sat_f32`
    /// (every pair of bfloat16 values). Two symbolic IEEE divisions cost
    /// the solver two dividers with fresh quotient variables whose equality
    /// it does not find in 600 s; the logic of `sat` around the division is
    /// what this harness decides.
    fn f32_div_sign_symmetric_stub(a: f32, b: f32) -> f32 {
        if FD_FIRST.load(Relaxed) {
            FD_FIRST.store(false, Relaxed);
            let q = f32_div_body(a, b);
            FD_A0.store(a.to_bits(), Relaxed);
            FD_B0.store(b.to_bits(), Relaxed);
            FD_Q0.store(q.to_bits(), Relaxed);
            return q;
        }
        if b.to_bits() == FD_B0.load(Relaxed) && a.to_bits() == FD_A0.load(Relaxed) ^ (1 << 31) {
            // Lemma f32_div_sign_symmetric (IEEE 754 division is odd in
            // the numerator).
            return -f32::from_bits(FD_Q0.load(Relaxed));
        }
        f32_div_body(a, b)
    }

    #[kani::proof]
    #[kani::stub(<f32 as crate::scalar::Scalar>::div, f32_div_sign_symmetric_stub)]
    fn kani_sat_odd_f32() {
        let (x, y) = any_f32_pair();
        assert!(sat_odd(x, y).holds);
    }

    /// `<f32 as Scalar>::div` as its rounding contract
    /// ([`f32_div_rounding_contract`]: the nearest `f32` to `a/b`, written
    /// with exact `f64` products instead of a division). The two IEEE
    /// divisions of the monotone harness (`x/y` and `next_up(x)/y`) are two
    /// division circuits with related operands, which the solver does not
    /// relate in 600 s; the contract states what IEEE 754 guarantees of
    /// each, and the harness decides the rest. The precondition (the
    /// boundary layer of a finite positive `y`) is asserted at every call,
    /// so a `sat` that divided elsewhere fails the harness; the contract
    /// holds for the real division by IEEE 754, tested on edge values and
    /// random pairs by `f32_division_meets_rounding_contract`.
    fn f32_div_as_rounding_contract(a: f32, b: f32) -> f32 {
        assert!(
            b > 0.0 && b.is_finite() && a.abs() <= b,
            "f32 division called outside the boundary layer"
        );
        let q: f32 = kani::any();
        // Postcondition of the stubbed function (IEEE 754 rounding to
        // nearest; f32_division_meets_rounding_contract).
        kani::assume(f32_div_rounding_contract(a, b, q));
        q
    }

    /// `<f32 as Scalar>::div` as [`f32_div_layer_lemma`], its precondition
    /// asserted at every call (as for the rounding contract above).
    fn f32_div_as_layer_lemma(a: f32, b: f32) -> f32 {
        assert!(
            b > 0.0 && b.is_finite() && a.abs() <= b,
            "f32 division called outside the boundary layer"
        );
        let q: f32 = kani::any();
        kani::assume(f32_div_layer_lemma(a, b, q));
        q
    }

    /// `sat_monotone_step` wherever `x` or its successor `x'` is outside
    /// the boundary layer, or the layer is empty (`y ≤ 0`, NaN): the
    /// branch logic of eq. (4.18), the joins at `|x| = y` included (there
    /// `x = y < x'` or `x < −y = x'`, and the division meets `±1`
    /// exactly). Split domain: both points inside the layer is
    /// `kani_sat_monotone_inside_f32`, where the step is the monotonicity
    /// and rounding of IEEE division itself (and
    /// `exhaustive_sat_properties_f32` checks every pair of bfloat16
    /// values).
    #[kani::proof]
    #[kani::stub(<f32 as crate::scalar::Scalar>::div, f32_div_as_layer_lemma)]
    fn kani_sat_monotone_f32() {
        let (x, y) = any_f32_pair();
        // Precondition: a finite successor exists.
        kani::assume(x.is_finite() && x < f32::MAX);
        let xn = next_up(x);
        // Split domain (the complement is the next harness).
        kani::assume(!(y > 0.0 && x.abs() <= y && xn.abs() <= y));
        // The check in its division-free form (`sat_step_f32_products`).
        assert!(sat_step_f32_products(x, xn, y, x.sat(y), xn.sat(y)));
    }

    /// `sat_monotone_step` with both points inside the layer, the division
    /// by its rounding contract ([`f32_div_as_rounding_contract`]).
    #[kani::proof]
    #[kani::stub(<f32 as crate::scalar::Scalar>::div, f32_div_as_rounding_contract)]
    fn kani_sat_monotone_inside_f32() {
        let (x, xn, y) = any_pair_inside_layer();
        assert!(sat_step_f32_products(x, xn, y, x.sat(y), xn.sat(y)));
    }

    /// `(x, x' = next_up(x), y)` with both points inside the boundary
    /// layer: the split domain of the two harnesses with both points
    /// inside, the complement of `kani_sat_monotone_f32`'s.
    fn any_pair_inside_layer() -> (f32, f32, f32) {
        let (x, y) = any_f32_pair();
        // Precondition: a finite successor exists.
        kani::assume(x.is_finite() && x < f32::MAX);
        let xn = next_up(x);
        kani::assume(y > 0.0 && x.abs() <= y && xn.abs() <= y);
        (x, xn, y)
    }

    /// The operands and quotient (bits) of the first division of
    /// [`f32_div_as_layer_and_pair_lemma`].
    static PAIR_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `<f32 as Scalar>::div` inside the boundary layer as comparisons
    /// only: any quotient that [`f32_div_layer_lemma`] allows
    /// ([`f32_div_as_layer_lemma`]), and a second
    /// division by the same divisor in the order of the dividends
    /// ([`f32_div_pair_lemma`]). The precondition is asserted at every call.
    fn f32_div_as_layer_and_pair_lemma(a: f32, b: f32) -> f32 {
        let q = f32_div_as_layer_lemma(a, b);
        if let Some((a0, b0, q0)) =
            PAIR_FIRST.first_or_record(a.to_bits(), b.to_bits(), q.to_bits())
        {
            if b0 == b.to_bits() {
                let (a0, q0) = (f32::from_bits(a0), f32::from_bits(q0));
                kani::assume(f32_div_pair_lemma(a0, q0, a, q));
            }
        }
        q
    }

    /// The order part of `sat_monotone_step` with both points inside the
    /// layer: `sat(x, y) ≤ sat(x', y)` for `x' = next_up(x)`, every such
    /// pair, the division by comparison-only lemmas of IEEE division
    /// ([`f32_div_as_layer_and_pair_lemma`]). The step bound (at most one
    /// unit beyond the slope) is `kani_sat_monotone_inside_f32`'s, which
    /// needs the rounding itself.
    #[kani::proof]
    #[kani::stub(<f32 as crate::scalar::Scalar>::div, f32_div_as_layer_and_pair_lemma)]
    fn kani_sat_order_inside_f32() {
        let (x, xn, y) = any_pair_inside_layer();
        assert!(x.sat(y) <= xn.sat(y));
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::exhaustive_u32;
    use super::*;
    use crate::scalar::I16F16;
    use proptest::prelude::*;
    use std::println;

    fn i8f8_pair(code: u32) -> (I16F16, I16F16) {
        let x = I16F16::from_bits(((code >> 16) as u16 as i16 as i32) << 8);
        let y = I16F16::from_bits(((code & 0xffff) as u16 as i16 as i32) << 8);
        (x, y)
    }

    fn bf16_pair(code: u32) -> (f32, f32) {
        (
            f32::from_bits(code & 0xffff_0000),
            f32::from_bits(code << 16),
        )
    }

    fn all_sat_properties<S: Scalar>(x: S, y: S, x_next: Option<S>) -> Verdict {
        let mut v = sat_in_range(x, y)
            .and(sat_matches_definition(x, y))
            .and(sat_odd(x, y));
        if let Some(xn) = x_next {
            // The step check has its own bound (1 unit beyond (x'−x)/y); it
            // counts as pass/fail so the reported error is the value's.
            v = v.and(Verdict::logical(sat_monotone_step(x, xn, y).holds));
        }
        v
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sgn_i16f16() {
        let r = exhaustive_u32(0, u32::MAX, |c| sgn_exact(I16F16::from_bits(c as i32)));
        println!(
            "PROOF kernel=sgn backend=I16F16 domain=all bound=exact max_err={} LSB at={} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sgn_f32() {
        let r = exhaustive_u32(0, u32::MAX, |c| sgn_exact(f32::from_bits(c)));
        println!(
            "PROOF kernel=sgn backend=f32 domain=all(incl. NaN, inf) bound=exact max_err={} ulp at={:#x} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sat_i16f16() {
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let (x, y) = i8f8_pair(c);
            let xn = (x.to_bits() < i32::MAX).then(|| I16F16::from_bits(x.to_bits() + 1));
            all_sat_properties(x, y, xn).and(sat_matches_definition_i16f16(x, y))
        });
        println!(
            "PROOF kernel=sat backend=I16F16 domain=all pairs of I8F8 lattice bound=0.5 LSB (value; steps <= (x'-x)/y + 1 LSB, monotone, odd) max_err={} LSB at={:#x} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(
            r.failures,
            0,
            "first failure at code {:?}",
            r.first_failure.map(i8f8_pair)
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sat_f32() {
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let (x, y) = bf16_pair(c);
            let xn = (x.is_finite() && x < f32::MAX).then(|| next_up(x));
            all_sat_properties(x, y, xn)
        });
        println!(
            "PROOF kernel=sat backend=f32 domain=all pairs of bfloat16 values bound=0.5 ulp(1) (value; steps <= (x'-x)/y + 1 ulp(1), monotone, odd) max_err={} at={:#x} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(
            r.failures,
            0,
            "first failure at code {:?}",
            r.first_failure.map(bf16_pair)
        );
    }

    /// The `div_bits` contract of the `I16F16` `sat` harnesses, on every
    /// operand pair `0 < b < 2¹⁶`, `|a| ≤ b` (both signs of `a`), and on
    /// the same pairs scaled by 2¹⁵ (operands up to 2³¹, numerators up to
    /// 2⁴⁷; the scaled quotient is exact, so this checks the wide
    /// division path without rounding). Beyond: `Kani` (`kani_div_bits_layer_contract`)
    /// and the random test below.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_div_bits_layer_contract() {
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let (a, b) = ((c >> 16) as i32, (c & 0xffff) as i32);
            let (sa, sb) = (a << 15, b << 15);
            let pairs = b == 0
                || a > b
                || div_bits_pair_holds(a, -a, b)
                    && div_bits_pair_holds(-a, a, b)
                    && (a == b
                        || div_bits_pair_holds(a, a + 1, b) && div_bits_pair_holds(-a - 1, -a, b));
            div_bits_meets_layer_contract(a, b)
                .and(div_bits_meets_layer_contract(-a, b))
                .and(div_bits_meets_layer_contract(sa, sb))
                .and(div_bits_meets_layer_contract(-sa, sb))
                .and(Verdict::logical(pairs))
        });
        println!(
            "PROOF kernel=div_bits(layer contract) backend=I16F16 domain=0<b<2^16,|a|<=b and the same scaled by 2^15 bound=nearest, ties away from 0 max_err={} at={:#x} checked={} engine=exhaustive",
            r.max_error, r.argmax, r.checked
        );
        assert_eq!(r.failures, 0, "first failure at code {:?}", r.first_failure);
    }

    /// [`div_bits_pair_lemma`] on the real quotients of `a0` and `a` by `b`.
    fn div_bits_pair_holds(a0: i32, a: i32, b: i32) -> bool {
        use crate::scalar::fixed::div_bits;
        div_bits_pair_lemma(a0, div_bits(a0, b), a, div_bits(a, b), b)
    }

    /// The division-free check of `kani_sat_monotone_f32` agrees with the
    /// quotient form of `sat_monotone_step` on results near the allowance
    /// (both sides of it) and on arbitrary ones, and it can fail.
    #[test]
    fn sat_step_product_form_agrees_with_the_quotient_form() {
        let mut next = super::super::engine::xorshift64(0x9e37_79b9_7f4a_7c15u64);
        let (mut pass, mut fail) = (0, 0);
        for i in 0..400_000 {
            let r = next();
            let (x, y) = match i % 4 {
                // Arbitrary bit patterns.
                0 => (f32::from_bits(r as u32), f32::from_bits((r >> 32) as u32)),
                // Inside and around the boundary layer of a moderate y.
                _ => {
                    let y = f32::from_bits(0x3000_0000 + (r as u32 % 0x1800_0000));
                    let k = ((r >> 32) as u32 as f32 / u32::MAX as f32) * 2.4 - 1.2;
                    (k * y, y)
                }
            };
            if !x.is_finite() || x >= f32::MAX {
                continue;
            }
            let xn = next_up(x);
            let a = x.sat(y);
            // b: the real result, or one moved to the edge of the
            // allowance (a + (x' − x)/y + ε, a few units either side).
            let b = match (r >> 60) & 3 {
                0 => xn.sat(y),
                1 => f32::from_bits(next() as u32),
                _ => {
                    let edge = a as f64 + (xn as f64 - x as f64) / y as f64 + f32::EPSILON as f64;
                    let mut b = edge as f32;
                    for _ in 0..((r >> 56) & 7) {
                        b = if r & 1 == 0 { next_up(b) } else { next_down(b) };
                    }
                    b
                }
            };
            if b.is_nan() {
                continue;
            }
            let quotient = sat_step_verdict(x, xn, y, a, b).holds;
            assert_eq!(
                sat_step_f32_products(x, xn, y, a, b),
                quotient,
                "x {x:e} y {y:e} a {a:e} b {b:e}"
            );
            if quotient {
                pass += 1;
            } else {
                fail += 1;
            }
        }
        // Both verdicts occur, so the comparison covers failing results.
        assert!(pass > 10_000 && fail > 10_000, "{pass} pass, {fail} fail");
    }

    /// The copy of `<f32 as Scalar>::div` in the Kani stub is the function,
    /// bit for bit, on edge values and random bit patterns.
    #[test]
    fn f32_div_body_is_scalar_div() {
        for (a, b) in f32_division_operands() {
            let (got, want) = (f32_div_body(a, b), Scalar::div(a, b));
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{a:e} / {b:e}"
            );
        }
    }

    /// The lemma of the `kani_sat_odd_f32` stub holds for the real
    /// division on edge values and random bit patterns, and the check can
    /// fail (a division that rounds towards +∞ is not odd).
    #[test]
    fn f32_division_is_sign_symmetric() {
        for (a, b) in f32_division_operands() {
            assert!(f32_div_sign_symmetric(Scalar::div, a, b), "{a:e} / {b:e}");
        }
        fn upward(a: f32, b: f32) -> f32 {
            let q = a / b;
            if (q as f64) < a as f64 / b as f64 {
                next_up(q)
            } else {
                q
            }
        }
        assert!(!f32_div_sign_symmetric(upward, 1.0, 3.0));
    }

    /// The lemma of the `kani_sat_monotone_f32` stub holds for the real
    /// division on every operand pair of the boundary layer among the edge
    /// values and random bit patterns, and the check can fail.
    #[test]
    fn f32_division_meets_layer_lemma() {
        let mut pairs = f32_division_operands();
        pairs.extend([(f32::MAX, f32::MAX), (-f32::MAX, f32::MAX), (-0.0, 1.0)]);
        let mut checked = 0;
        for (a, b) in pairs {
            if !(b > 0.0 && b.is_finite() && a.abs() <= b) {
                continue;
            }
            assert!(
                f32_div_layer_lemma(a, b, Scalar::div(a, b)),
                "{a:e} / {b:e}"
            );
            checked += 1;
        }
        assert!(checked > 100_000, "{checked}");
        // And it can fail: a quotient off the end, or of the wrong sign.
        assert!(!f32_div_layer_lemma(2.0, 2.0, next_down(1.0)));
        assert!(!f32_div_layer_lemma(-1.0, 2.0, 0.5));
        assert!(!f32_div_layer_lemma(0.0, 2.0, f32::from_bits(1)));
    }

    /// The order lemma of `kani_sat_order_inside_f32` holds for the real
    /// division: each dividend against its successor and predecessor and
    /// against every other dividend of the edge and random pairs with the
    /// same divisor; and it can fail.
    #[test]
    fn f32_division_is_monotone_in_the_dividend() {
        let pairs = f32_division_operands();
        let mut checked = 0;
        for &(a, b) in &pairs {
            if !(b > 0.0 && b.is_finite()) || a.is_nan() {
                continue;
            }
            let q = Scalar::div(a, b);
            for a1 in [next_up(a), next_down(a), -a, 0.0, b, -b] {
                if a1.is_nan() {
                    continue;
                }
                let q1 = Scalar::div(a1, b);
                assert!(f32_div_pair_lemma(a, q, a1, q1), "{a:e}, {a1:e} / {b:e}");
                checked += 1;
            }
        }
        assert!(checked > 100_000, "{checked}");
        assert!(!f32_div_pair_lemma(1.0, 0.5, 2.0, 0.25));
        assert!(!f32_div_pair_lemma(2.0, 0.5, 1.0, 0.75));
    }

    /// The contract of the `kani_sat_monotone_inside_f32` stub holds for
    /// the real division on every operand pair of the boundary layer among
    /// the edge values and random bit patterns (and on the ties and
    /// subnormal quotients below), and the check can fail: the quotient's
    /// neighbours are rejected.
    #[test]
    fn f32_division_meets_rounding_contract() {
        let mut checked = 0;
        let mut pairs = f32_division_operands();
        // Ties of the rounding (1 + 2⁻²⁴ is halfway between 1 and its
        // successor), subnormal and zero quotients, |a| = b.
        pairs.extend([
            (1.0 + f32::EPSILON, 2.0),
            (f32::from_bits(1), 1.0),
            (f32::from_bits(1), 2.0),
            (f32::from_bits(3), 2.0),
            (f32::from_bits(1), f32::MAX),
            (-f32::MAX, f32::MAX),
            (f32::MIN_POSITIVE, 3.0),
            (0.0, 7.0),
            (-0.0, 7.0),
        ]);
        for (a, b) in pairs {
            if !(b > 0.0 && b.is_finite() && a.abs() <= b) {
                continue;
            }
            let q = Scalar::div(a, b);
            assert!(f32_div_rounding_contract(a, b, q), "{a:e} / {b:e} = {q:e}");
            let exact = a as f64 / b as f64;
            for wrong in [next_up(q), next_down(q)] {
                // A neighbour is allowed only at an exact tie.
                let tie = ((wrong as f64 + q as f64) * 0.5 - exact) == 0.0;
                if !tie {
                    assert!(
                        !f32_div_rounding_contract(a, b, wrong),
                        "{a:e} / {b:e}: {wrong:e}"
                    );
                }
            }
            checked += 1;
        }
        assert!(checked > 100_000, "only {checked} layer pairs");
    }

    proptest! {
        /// The rounding contract on random layer pairs of every magnitude.
        #[test]
        fn f32_division_meets_rounding_contract_random(b in 1e-40f32..1e38, t in -1.0f32..=1.0) {
            let a = (t * b).clamp(-b, b);
            let q = Scalar::div(a, b);
            prop_assert!(f32_div_rounding_contract(a, b, q), "{a:e} / {b:e} = {q:e}");
        }
    }

    /// Edge values (zeros, subnormals, ±1, extremes, infinities, NaN) in
    /// every pairing, and 10⁶ pairs of random bit patterns.
    fn f32_division_operands() -> std::vec::Vec<(f32, f32)> {
        let edges = [
            0.0f32,
            -0.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            1.0,
            3.0,
            0.1,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        let mut v: std::vec::Vec<(f32, f32)> = std::vec::Vec::new();
        for &a in &edges {
            for &b in &edges {
                for (sa, sb) in [(1.0f32, 1.0f32), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                    v.push((sa * a, sb * b));
                }
            }
        }
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..1_000_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            v.push((
                f32::from_bits((state >> 32) as u32),
                f32::from_bits(state as u32),
            ));
        }
        v
    }

    /// The contract check can fail: the quotient one LSB off, a tie
    /// rounded towards zero, and a value beyond ±1 are rejected.
    #[test]
    fn div_bits_layer_contract_can_fail() {
        let (one, three) = (1i32 << 16, 3i32 << 16);
        // 1/3 = 21845.33 LSB.
        assert!(div_bits_layer_contract(one, three, 21845));
        assert!(!div_bits_layer_contract(one, three, 21846));
        assert!(!div_bits_layer_contract(one, three, 21844));
        // a/b = 0.5 LSB exactly: ties away from zero give ±1, not 0.
        assert!(div_bits_layer_contract(1, 1 << 17, 1));
        assert!(!div_bits_layer_contract(1, 1 << 17, 0));
        assert!(div_bits_layer_contract(-1, 1 << 17, -1));
        assert!(!div_bits_layer_contract(-1, 1 << 17, 0));
        // |q| ≤ 1 (2¹⁶ bits), even where the quotient would say otherwise.
        assert!(div_bits_layer_contract(three, three, one));
        assert!(!div_bits_layer_contract(three, three, one + 1));
        // The pair lemma rejects a non-odd pair and a jump of two slopes.
        assert!(!div_bits_pair_lemma(5, 3, -5, -2, 7));
        assert!(div_bits_pair_lemma(5, 3, -5, -3, 7));
        // b = 2 bits: slope 2¹⁵ per step, so 2¹⁵ + 1 passes, 2¹⁵ + 2 not.
        assert!(!div_bits_pair_lemma(0, 0, 1, (1 << 15) + 2, 2));
        assert!(div_bits_pair_lemma(0, 0, 1, (1 << 15) + 1, 2));
        assert!(!div_bits_pair_lemma(1, 9, 2, 8, 2));
        // The shipped division meets it, e.g. at a tie and at ±1.
        assert!(div_bits_meets_layer_contract(1, 1 << 17).holds);
        assert!(div_bits_meets_layer_contract(-three, three).holds);
    }

    /// The integer monotone-step check agrees with the generic one at
    /// random points and rejects a step of two slopes.
    #[test]
    fn monotone_step_i16f16_matches_generic_and_can_fail() {
        for (x, y) in [
            (0, 7),
            (-65536, 65536),
            (12_345, 98_765),
            (5, -3),
            (i32::MIN, 1),
        ] {
            let (xs, ys) = (I16F16::from_bits(x), I16F16::from_bits(y));
            let generic = sat_monotone_step(xs, I16F16::from_bits(x + 1), ys).holds;
            assert_eq!(sat_monotone_step_i16f16(x, y).holds, generic, "{x} {y}");
        }
        // y = 2 LSB: the slope is 2¹⁵ LSB per LSB of x; a step of 2¹⁵ + 1 is
        // allowed, 2¹⁵ + 2 is not; a decrease is not.
        assert!(sat_step_bits_ok(0, (1 << 15) + 1, 2).holds);
        assert!(!sat_step_bits_ok(0, (1 << 15) + 2, 2).holds);
        assert!(!sat_step_bits_ok(1, 0, 2).holds);
        // y = 3 LSB: slope 21845.3; 21846 allowed, 21847 not.
        assert!(sat_step_bits_ok(-10, 21836, 3).holds);
        assert!(!sat_step_bits_ok(-10, 21837, 3).holds);
        // y ≤ 0: only monotonicity.
        assert!(sat_step_bits_ok(-65536, 65536, 0).holds);
    }

    #[test]
    fn sat_is_continuous_exactly_at_the_boundary() {
        // At |x| = y both branches of eq. (4.18) give ±1.
        for y in [1e-4f64, 0.01, 0.1, 3.0] {
            assert_eq!(y.sat(y), 1.0);
            assert_eq!((-y).sat(y), -1.0);
            let yf = I16F16::from_num(y);
            assert_eq!(yf.sat(yf), I16F16::ONE);
            assert_eq!(yf.neg().sat(yf), I16F16::ONE.neg());
        }
    }

    /// The pairs the f32 Kani harnesses leave out (`y = +∞`):
    /// `sat(±∞, +∞) = ±1` (the `∞/∞` NaN replaced by its limit), `sat(x, +∞)
    /// = ±0` for finite `x`; in range, odd, as defined.
    #[test]
    fn sat_of_infinities_is_the_limit() {
        let inf = f32::INFINITY;
        assert_eq!(inf.sat(inf), 1.0);
        assert_eq!((-inf).sat(inf), -1.0);
        assert_eq!(0.0f32.sat(inf), 0.0);
        assert_eq!(f32::MAX.sat(inf), 0.0);
        for x in [inf, -inf, 0.0, -0.0, 1.0, -f32::MAX, f32::MIN_POSITIVE] {
            assert!(sat_in_range(x, inf).holds);
            assert!(sat_odd(x, inf).holds);
            assert!(sat_matches_definition(x, inf).holds);
        }
    }

    /// The definition check can fail: a saturation that compares `|x|`
    /// with `|y|` instead of `y` (misreading the `|y|` of eq. 4.18) is
    /// rejected for a negative `y`, where the thesis saturates every `x != 0`.
    #[test]
    fn definition_check_rejects_a_misread_boundary() {
        fn misread_sat(x: f64, y: f64) -> f64 {
            if x.abs() > y.abs() {
                x.signum()
            } else {
                x / y.abs()
            }
        }
        let (x, y) = (-0.5f64, -1.0f64);
        assert!(!sat_value_matches_definition(misread_sat(x, y), x, y).holds);
        assert!(sat_value_matches_definition(x.sat(y), x, y).holds);
        assert_eq!(x.sat(y), -1.0);
    }

    /// The integer definition check rejects one LSB off inside the layer,
    /// an off-by-one at the layer's edge, and a wrong saturation value; it
    /// accepts both roundings of an exact tie.
    #[test]
    fn exact_definition_check_can_fail() {
        let (one, three) = (1i32 << 16, 3i32 << 16);
        // 1/3 = 21845.33 LSB: 21845 is the nearest, 21846 is not.
        assert!(sat_bits_match_definition(21845, one, three).holds);
        assert!(!sat_bits_match_definition(21846, one, three).holds);
        // |x| = y: exactly ±1; one LSB short fails.
        assert!(sat_bits_match_definition(-one, -three, three).holds);
        assert!(!sat_bits_match_definition(-one + 1, -three, three).holds);
        // Outside the layer and for y ≤ 0: sgn(x) exactly.
        assert!(sat_bits_match_definition(one, three + 1, three).holds);
        assert!(!sat_bits_match_definition(one - 1, three + 1, three).holds);
        assert!(sat_bits_match_definition(0, 0, -5).holds);
        assert!(!sat_bits_match_definition(one, 0, -5).holds);
        // x/y = 0.5 LSB exactly (x = 1 bit, y = 2^17 bits): 0 and 1 are
        // both within half an LSB.
        assert!(sat_bits_match_definition(0, 1, 1 << 17).holds);
        assert!(sat_bits_match_definition(1, 1, 1 << 17).holds);
        assert!(!sat_bits_match_definition(2, 1, 1 << 17).holds);
        // The shipped sat passes where the f64 check does.
        let (x, y) = (I16F16::from_bits(12_345), I16F16::from_bits(98_765));
        assert!(sat_matches_definition_i16f16(x, y).holds);
        assert!(sat_matches_definition(x, y).holds);
    }

    proptest! {
        #[test]
        fn sat_properties_f64(x in -10.0f64..10.0, y in -1.0f64..2.0, dx in 1e-9f64..1e-3) {
            prop_assert!(sgn_exact(x).holds);
            prop_assert!(all_sat_properties(x, y, Some(x + dx)).holds);
        }

        #[test]
        fn sat_properties_f32(x in -10.0f32..10.0, y in -1.0f32..2.0) {
            prop_assert!(sgn_exact(x).holds);
            prop_assert!(all_sat_properties(x, y, Some(next_up(x))).holds);
        }

        #[test]
        fn div_bits_contract_random(a in i32::MIN..i32::MAX, b in 1i32..i32::MAX) {
            let a = a % b;
            prop_assert!(div_bits_meets_layer_contract(a, b).holds);
            prop_assert!(div_bits_meets_layer_contract(b, b).holds);
            prop_assert!(sat_monotone_step_i16f16(a, b).holds);
            prop_assert!(div_bits_pair_holds(a, -a, b) && div_bits_pair_holds(a, a, b));
            prop_assert!(div_bits_pair_holds(a, a + 1, b));
        }

        #[test]
        fn sat_properties_i16f16(x in i32::MIN..i32::MAX, y in -(1i32 << 20)..(1i32 << 22)) {
            let (x, y) = (I16F16::from_bits(x), I16F16::from_bits(y));
            prop_assert!(sgn_exact(x).holds);
            prop_assert!(all_sat_properties(x, y, Some(I16F16::from_bits(x.to_bits() + 1))).holds);
            prop_assert!(sat_matches_definition_i16f16(x, y).holds);
        }
    }
}
