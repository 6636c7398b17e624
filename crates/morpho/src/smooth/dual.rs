//! Forward-mode differentiation with two partials (issue 19 item 5/6: the side-vertex surface's
//! exact first derivatives). A [`Dual`] carries a value and its derivatives along two fixed
//! directions; every operation applies the chain rule, so a function written over `Dual`
//! returns its value and both directional derivatives at once, exact up to rounding (no step
//! size). The value part of every operation rounds exactly like the `f64` expression, so a
//! computation mirrored operation for operation gives the same value as its `f64` original
//! (checked in lockstep by the side-vertex tests).
//!
//! Kinks (`abs`, `max`, branches on values) take the derivative of the branch the value
//! selects: callers use them only where the function is C¹ or where a one-sided derivative is
//! what they want (documented at the use).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value with its partial derivatives along two directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dual {
    /// The value.
    pub v: f64,
    /// `∂/∂a`, `∂/∂b`.
    pub d: [f64; 2],
}

/// A point or vector with its two partials.
pub(crate) type D3 = [Dual; 3];

impl Dual {
    /// A constant (zero derivatives).
    #[inline(always)]
    pub fn c(v: f64) -> Dual {
        Dual { v, d: [0.0; 2] }
    }

    #[inline(always)]
    fn chain(self, v: f64, f: f64) -> Dual {
        Dual {
            v,
            d: [f * self.d[0], f * self.d[1]],
        }
    }

    pub fn sqrt(self) -> Dual {
        let v = self.v.sqrt();
        // d sqrt = 1/(2 sqrt): infinite at 0, where callers have branched away
        self.chain(v, 0.5 / v)
    }

    pub fn sin(self) -> Dual {
        self.chain(self.v.sin(), self.v.cos())
    }

    pub fn cos(self) -> Dual {
        self.chain(self.v.cos(), -self.v.sin())
    }

    /// `|x|`: the derivative of the branch `x ≥ 0` or `x < 0`.
    pub fn abs(self) -> Dual {
        if self.v < 0.0 {
            -self
        } else {
            self
        }
    }

    /// `atan2(self, x)`.
    pub fn atan2(self, x: Dual) -> Dual {
        let y = self;
        let r2 = x.v * x.v + y.v * y.v;
        let v = y.v.atan2(x.v);
        if r2 > 0.0 {
            Dual {
                v,
                d: [
                    (x.v * y.d[0] - y.v * x.d[0]) / r2,
                    (x.v * y.d[1] - y.v * x.d[1]) / r2,
                ],
            }
        } else {
            Dual::c(v)
        }
    }

    /// The larger of the two values (with its derivatives; `other` on a tie).
    pub fn max(self, other: Dual) -> Dual {
        if self.v > other.v {
            self
        } else {
            other
        }
    }
}

impl Add for Dual {
    type Output = Dual;
    #[inline(always)]
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            d: [self.d[0] + o.d[0], self.d[1] + o.d[1]],
        }
    }
}

impl Sub for Dual {
    type Output = Dual;
    #[inline(always)]
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            d: [self.d[0] - o.d[0], self.d[1] - o.d[1]],
        }
    }
}

impl Mul for Dual {
    type Output = Dual;
    #[inline(always)]
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self.v * o.v,
            d: [
                self.d[0] * o.v + self.v * o.d[0],
                self.d[1] * o.v + self.v * o.d[1],
            ],
        }
    }
}

impl Div for Dual {
    type Output = Dual;
    #[inline(always)]
    fn div(self, o: Dual) -> Dual {
        let v = self.v / o.v;
        Dual {
            v,
            d: [
                (self.d[0] - v * o.d[0]) / o.v,
                (self.d[1] - v * o.d[1]) / o.v,
            ],
        }
    }
}

impl Neg for Dual {
    type Output = Dual;
    #[inline(always)]
    fn neg(self) -> Dual {
        Dual {
            v: -self.v,
            d: [-self.d[0], -self.d[1]],
        }
    }
}

impl Mul<Dual> for f64 {
    type Output = Dual;
    #[inline(always)]
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self * o.v,
            d: [self * o.d[0], self * o.d[1]],
        }
    }
}

/// Vector helpers over [`D3`], rounding like `geom::vec` (same operation order).
pub(crate) mod v3 {
    use super::{Dual, D3};

    pub fn c(p: [f64; 3]) -> D3 {
        p.map(Dual::c)
    }
    pub fn val(p: D3) -> [f64; 3] {
        p.map(|x| x.v)
    }
    /// The partial along direction `k` (0 or 1).
    pub fn part(p: D3, k: usize) -> [f64; 3] {
        p.map(|x| x.d[k])
    }
    pub fn sub(a: D3, b: D3) -> D3 {
        std::array::from_fn(|k| a[k] - b[k])
    }
    pub fn add(a: D3, b: D3) -> D3 {
        std::array::from_fn(|k| a[k] + b[k])
    }
    pub fn scale(a: D3, s: Dual) -> D3 {
        std::array::from_fn(|k| s * a[k])
    }
    pub fn scale_f(a: D3, s: f64) -> D3 {
        std::array::from_fn(|k| s * a[k])
    }
    pub fn add_scaled(a: D3, s: Dual, b: D3) -> D3 {
        std::array::from_fn(|k| a[k] + s * b[k])
    }
    pub fn dot(a: D3, b: D3) -> Dual {
        let mut s = a[0] * b[0];
        for k in 1..3 {
            s = s + a[k] * b[k];
        }
        s
    }
    pub fn norm(a: D3) -> Dual {
        dot(a, a).sqrt()
    }
    pub fn cross(a: D3, b: D3) -> D3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chain_rule_against_closed_forms() {
        // f(a, b) = atan2(sin(a)·b, sqrt(a² + b)) / (a − b) at (0.7, 0.3)
        let f = |a: Dual, b: Dual| (a.sin() * b).atan2((a * a + b).sqrt()) / (a - b);
        let (a, b) = (0.7, 0.3);
        let r = f(
            Dual {
                v: a,
                d: [1.0, 0.0],
            },
            Dual {
                v: b,
                d: [0.0, 1.0],
            },
        );
        let g = |a: f64, b: f64| (a.sin() * b).atan2((a * a + b).sqrt()) / (a - b);
        assert_eq!(r.v, g(a, b));
        let h = 1e-6;
        let da = (g(a + h, b) - g(a - h, b)) / (2.0 * h);
        let db = (g(a, b + h) - g(a, b - h)) / (2.0 * h);
        assert!(
            (r.d[0] - da).abs() < 1e-8 && (r.d[1] - db).abs() < 1e-8,
            "{r:?} {da} {db}"
        );
    }
}
