//! Floating-point values with a proven absolute error bound (running error analysis, Wilkinson;
//! Higham 2002, §3.3): each [`Bounded`] carries the computed `f64` and a bound `e` with
//! |exact − value| ≤ e, where "exact" is the same expression evaluated in real arithmetic on
//! the exact inputs. Each operation adds the propagated input errors and its own rounding error
//! (at most ε·|result|, ε = 2⁻⁵² twice the unit roundoff, plus the smallest subnormal for
//! products and quotients, which may underflow). The bounds themselves are computed in floating
//! point, rounded to nearest: [`Bounded::certified`] inflates the final bound by 1 + 2⁻⁴⁰, more
//! than the relative rounding of any chain of fewer than 4000 operations on nonnegative terms.
//! A bound that overflows is infinite, and nothing is certified.
//!
//! Sharper than a priori (first-order, condition-number) bounds: the error terms use the actual
//! magnitudes met, so a well-conditioned evaluation is certified to a few ε even when the
//! input is nearly degenerate in some other respect. Used as the floating-point stage of the
//! γ-value offsets (`graphs::gamma`) before their exact fallbacks (`geom::exact`).

/// ε = 2⁻⁵²: bounds the relative rounding error of every basic operation (twice the unit
/// roundoff, so that it may be taken of the rounded result).
const EPS: f64 = f64::EPSILON;
/// The smallest positive subnormal: bounds the absolute error of an underflowing product.
const ETA: f64 = 5e-324;

/// A computed value `v` and a bound `e` of its distance to the exact value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounded {
    /// The floating-point value.
    pub v: f64,
    /// |exact − v| ≤ e (before the final inflation of [`Bounded::certified`]).
    pub e: f64,
}

impl Bounded {
    /// An exact input.
    #[inline]
    pub fn exact(v: f64) -> Self {
        Bounded { v, e: 0.0 }
    }
    /// a − b of exact inputs.
    #[inline]
    pub fn diff(a: f64, b: f64) -> Self {
        let v = a - b;
        Bounded {
            v,
            e: EPS * v.abs(),
        }
    }
    /// self + o.
    #[inline]
    pub fn plus(self, o: Bounded) -> Self {
        let v = self.v + o.v;
        Bounded {
            v,
            e: self.e + o.e + EPS * v.abs(),
        }
    }
    /// self − o.
    #[inline]
    pub fn minus(self, o: Bounded) -> Self {
        let v = self.v - o.v;
        Bounded {
            v,
            e: self.e + o.e + EPS * v.abs(),
        }
    }
    /// self · o.
    #[inline]
    pub fn times(self, o: Bounded) -> Self {
        let v = self.v * o.v;
        Bounded {
            v,
            e: self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + EPS * v.abs() + 2.0 * ETA,
        }
    }
    /// self · 2ᵏ for a power of two `p` (exact but for over- and underflow).
    #[inline]
    pub fn scale2(self, p: f64) -> Self {
        let v = self.v * p;
        Bounded {
            v,
            e: self.e * p + ETA,
        }
    }
    /// self / o; `None` unless |o| is certainly nonzero (|o.v| > o.e).
    #[inline]
    pub fn over(self, o: Bounded) -> Option<Self> {
        let d = o.v.abs() - o.e;
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        let v = self.v / o.v;
        // |X/Y − x/y| ≤ (e_x + |x/y| e_y) / (|y| − e_y), computed rounding towards safety
        let prop = (self.e + v.abs() * (1.0 + EPS) * o.e) / (d * (1.0 - 2.0 * EPS));
        Some(Bounded {
            v,
            e: prop + EPS * v.abs() + 2.0 * ETA,
        })
    }
    /// The dot product of 3-vectors.
    #[inline]
    pub fn dot3(x: [Bounded; 3], y: [Bounded; 3]) -> Self {
        x[0].times(y[0])
            .plus(x[1].times(y[1]))
            .plus(x[2].times(y[2]))
    }
    /// The cross product of 3-vectors.
    #[inline]
    pub fn cross3(x: [Bounded; 3], y: [Bounded; 3]) -> [Self; 3] {
        [
            x[1].times(y[2]).minus(x[2].times(y[1])),
            x[2].times(y[0]).minus(x[0].times(y[2])),
            x[0].times(y[1]).minus(x[1].times(y[0])),
        ]
    }
    /// The final bound, inflated for the rounding of the bound computations; infinite (nothing
    /// certified) when the value or the bound is not finite.
    #[inline]
    pub fn certified(self) -> f64 {
        if self.v.is_finite() && self.e.is_finite() {
            self.e * (1.0 + 1.0 / (1u64 << 40) as f64) + 2.0 * ETA
        } else {
            f64::INFINITY
        }
    }
    /// The sign of the exact value when the bound decides it (`Some(0)` never: a value within
    /// its bound of zero is undecided).
    #[inline]
    pub fn sign(self) -> Option<i32> {
        let e = self.certified();
        if self.v > e {
            Some(1)
        } else if self.v < -e {
            Some(-1)
        } else {
            None
        }
    }
}

/// x = fl(a + b) and its exact rounding error y: a + b = x + y (Knuth's TWO-SUM; exact for any
/// finite a, b whose sum does not overflow, subnormals included).
#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    (x, (a - av) + (b - bv))
}

/// x = fl(a·b) and y with a·b = x + y (Dekker's product through Veltkamp's split; no fused
/// multiply-add, so no library call on targets without one). Exact while |a|, |b| < 2⁹⁹⁵ (the
/// split does not overflow) and no partial product underflows; with underflow, each of its
/// four partial products is off by at most η/2 (η the smallest subnormal), so |a·b − x − y| ≤ 2η.
#[inline(always)]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let split = |a: f64| {
        let c = SPLITTER * a;
        let hi = c - (c - a);
        (hi, a - hi)
    };
    let x = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let err = x - ah * bh - al * bh - ah * bl;
    (x, al * bl - err)
}

/// A double-double value `hi + lo` with a proven bound `e` of its distance to the exact value of
/// the same expression on the exact inputs: the second floating-point stage of the γ offsets
/// (`graphs::gamma::TriFrame`), for the points where the [`Bounded`] stage's cancellation
/// (rounding errors of ε times the magnitudes, on skinny triangles and points nearly in their
/// plane) misses its tolerance. About 2⁻¹⁰⁶ instead of 2⁻⁵³ times the magnitudes, with no
/// allocation (the exact fallback is heap expansion arithmetic).
///
/// The bound is a running error bound as in [`Bounded`], argued per operation:
/// - [`BoundedDd::diff`]: a − b = hi + lo exactly (TWO-SUM), e = 0.
/// - [`BoundedDd::plus`]: (s, t₁) = TWO-SUM(x.hi, y.hi) exactly; t₂ = fl(x.lo + y.lo);
///   c = fl(t₁ + t₂); (hi, lo) = TWO-SUM(s, c) exactly. So hi + lo = x + y but for the two
///   roundings of t₂ and c, each at most ε/2 times the rounded result (a sum that is subnormal
///   is exact): e = e_x + e_y + ε(|t₂| + |c|).
/// - [`BoundedDd::times`]: (p, e₀) = Dekker(x.hi, y.hi) (exact up to 2η); the three cross
///   products a₁ = x.hi·y.lo, a₂ = x.lo·y.hi, a₃ = x.lo·y.lo and the sums s₁ = a₁ + a₂,
///   s₂ = s₁ + a₃, t = s₂ + e₀ rounded (each off by at most ε/2 of its rounded result, and a
///   product by η/2 more when it underflows); (hi, lo) = TWO-SUM(p, t) exactly. The exact
///   product of the exact values X = x + δx, Y = y + δy differs from x·y by at most
///   |x| e_y + |y| e_x + e_x e_y with |x| ≤ |x.hi| + |x.lo|: e = that + ε(|a₁| + |a₂| + |a₃| +
///   |s₁| + |s₂| + |t|) + 8η.
/// - [`BoundedDd::to_bounded`]: the value hi (rounded away: the bound grows by |lo|).
///
/// The bounds are computed in floating point, on nonnegative terms only: the final
/// [`Bounded::certified`] (inflation by 1 + 2⁻⁴⁰) covers their rounding, as for [`Bounded`].
/// Nothing is certified when a value or bound is not finite (overflow, or a split that
/// overflows: NaN).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundedDd {
    /// The leading part.
    pub hi: f64,
    /// The trailing part (|lo| ≤ ulp(hi)/2 after each operation).
    pub lo: f64,
    /// |exact − (hi + lo)| ≤ e (before the final inflation).
    pub e: f64,
}

impl BoundedDd {
    /// a − b of exact inputs, exactly.
    #[inline]
    pub fn diff(a: f64, b: f64) -> Self {
        let (hi, lo) = two_sum(a, -b);
        BoundedDd { hi, lo, e: 0.0 }
    }
    /// self + o.
    #[inline]
    pub fn plus(self, o: BoundedDd) -> Self {
        let (s, t1) = two_sum(self.hi, o.hi);
        let t2 = self.lo + o.lo;
        let c = t1 + t2;
        let (hi, lo) = two_sum(s, c);
        BoundedDd {
            hi,
            lo,
            e: self.e + o.e + EPS * (t2.abs() + c.abs()),
        }
    }
    /// self − o.
    #[inline]
    pub fn minus(self, o: BoundedDd) -> Self {
        self.plus(BoundedDd {
            hi: -o.hi,
            lo: -o.lo,
            e: o.e,
        })
    }
    /// self · o.
    #[inline]
    pub fn times(self, o: BoundedDd) -> Self {
        let (p, e0) = two_prod(self.hi, o.hi);
        let a1 = self.hi * o.lo;
        let a2 = self.lo * o.hi;
        let a3 = self.lo * o.lo;
        let s1 = a1 + a2;
        let s2 = s1 + a3;
        let t = s2 + e0;
        let (hi, lo) = two_sum(p, t);
        let (xm, ym) = (self.hi.abs() + self.lo.abs(), o.hi.abs() + o.lo.abs());
        let op = EPS * (a1.abs() + a2.abs() + a3.abs() + s1.abs() + s2.abs() + t.abs()) + 8.0 * ETA;
        BoundedDd {
            hi,
            lo,
            e: xm * o.e + ym * self.e + self.e * o.e + op,
        }
    }
    /// self · 2ᵏ for a power of two `p` (exact but for over- and underflow: η per part).
    #[inline]
    pub fn scale2(self, p: f64) -> Self {
        BoundedDd {
            hi: self.hi * p,
            lo: self.lo * p,
            e: self.e * p + 2.0 * ETA,
        }
    }
    /// The dot product of 3-vectors.
    #[inline]
    pub fn dot3(x: [BoundedDd; 3], y: [BoundedDd; 3]) -> Self {
        x[0].times(y[0])
            .plus(x[1].times(y[1]))
            .plus(x[2].times(y[2]))
    }
    /// The cross product of 3-vectors.
    #[inline]
    pub fn cross3(x: [BoundedDd; 3], y: [BoundedDd; 3]) -> [Self; 3] {
        [
            x[1].times(y[2]).minus(x[2].times(y[1])),
            x[2].times(y[0]).minus(x[0].times(y[2])),
            x[0].times(y[1]).minus(x[1].times(y[0])),
        ]
    }
    /// The value rounded to `hi`, as a [`Bounded`]: |exact − hi| ≤ e + |lo| (NaN, so never
    /// certified, when `lo` is not finite).
    #[inline]
    pub fn to_bounded(self) -> Bounded {
        Bounded {
            v: self.hi,
            e: self.e + self.lo.abs(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound holds on cancellations where the float result is pure rounding, and it is
    /// sharp (a few ε) on a well-conditioned expression.
    #[test]
    fn bounds_hold_and_are_sharp() {
        // (0.1 + 0.2) − 0.3 in reals is 0; the float inputs are exact binary numbers, so the
        // exact value of the expression on them is the sum of the inputs as given.
        let (a, b, c) = (0.1f64, 0.2f64, 0.3f64);
        let r = Bounded::exact(a)
            .plus(Bounded::exact(b))
            .minus(Bounded::exact(c));
        // exact value on the binary inputs: computed with an expansion
        let mut e = Vec::new();
        for x in [a, b, -c] {
            super::super::expansion::grow(&mut e, x);
        }
        let exact: f64 = e.iter().sum();
        assert!((r.v - exact).abs() <= r.certified());
        if let Some(s) = r.sign() {
            assert_eq!(s as f64, exact.signum());
        }
        // well conditioned: 3·7 + 1/3 to a few ε
        let w = Bounded::exact(3.0)
            .times(Bounded::exact(7.0))
            .plus(Bounded::exact(1.0).over(Bounded::exact(3.0)).unwrap());
        assert!(w.certified() < 8.0 * EPS * w.v);
        assert_eq!(w.sign(), Some(1));
        // a divisor within its bound of zero is refused
        let z = Bounded { v: 1e-20, e: 1e-19 };
        assert!(Bounded::exact(1.0).over(z).is_none());
    }
}
