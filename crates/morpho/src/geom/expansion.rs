//! Error-free floating-point transformations and Shewchuk's expansion arithmetic (Shewchuk 1997,
//! "Adaptive precision floating-point arithmetic and fast robust geometric predicates"): the
//! building blocks of the exact signs computed outside the `robust` crate's four predicates
//! (dot-product signs, shoelace sums, the enclosing-ball tests).
//!
//! Exact as long as no intermediate value overflows or underflows.

/// `a + b = s + t` exactly (Knuth's TWO-SUM).
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let t = (a - (s - bb)) + (b - bb);
    (s, t)
}

/// `a · b = p + t` exactly (with a fused multiply-add).
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Adds `b` to the nonoverlapping expansion `e` (components in increasing magnitude), dropping
/// zero components (GROW-EXPANSION with zero elimination). The exact value of `e` afterwards is
/// the old value plus `b`; its sign is the sign of its last component.
pub fn grow(e: &mut Vec<f64>, b: f64) {
    let mut q = b;
    let mut k = 0;
    for i in 0..e.len() {
        let (s, h) = two_sum(q, e[i]);
        q = s;
        if h != 0.0 {
            e[k] = h;
            k += 1;
        }
    }
    e.truncate(k);
    if q != 0.0 {
        e.push(q);
    }
}

/// A nonoverlapping floating-point expansion (Shewchuk 1997): the exact value is the sum of the
/// components, stored in increasing magnitude, zeros removed.
#[derive(Debug, Clone, Default)]
pub struct Expansion(pub Vec<f64>);

impl Expansion {
    pub fn zero() -> Self {
        Expansion(Vec::new())
    }
    /// a − b, exactly.
    pub fn diff(a: f64, b: f64) -> Self {
        let (x, y) = two_sum(a, -b);
        Expansion([y, x].into_iter().filter(|&c| c != 0.0).collect())
    }
    /// Grow-Expansion: self + b.
    pub fn grow(&self, b: f64) -> Self {
        let mut out = Vec::with_capacity(self.0.len() + 1);
        let mut q = b;
        for &e in &self.0 {
            let (s, h) = two_sum(q, e);
            if h != 0.0 {
                out.push(h);
            }
            q = s;
        }
        if q != 0.0 {
            out.push(q);
        }
        Expansion(out)
    }
    pub fn add(&self, o: &Expansion) -> Self {
        o.0.iter().fold(self.clone(), |acc, &c| acc.grow(c))
    }
    pub fn neg(&self) -> Self {
        Expansion(self.0.iter().map(|c| -c).collect())
    }
    pub fn sub(&self, o: &Expansion) -> Self {
        self.add(&o.neg())
    }
    /// Sum of all pairwise exact products.
    pub fn mul(&self, o: &Expansion) -> Self {
        let mut acc = Expansion::zero();
        for &x in &self.0 {
            for &y in &o.0 {
                let (p, e) = two_prod(x, y);
                acc = acc.grow(e).grow(p);
            }
        }
        acc
    }
    /// The exact value `x` (one component, or none for zero).
    #[allow(dead_code)] // kernel API without a caller yet
    pub fn from(x: f64) -> Self {
        Expansion(if x == 0.0 { vec![] } else { vec![x] })
    }
    /// self · b, exactly (SCALE-EXPANSION through exact products).
    pub fn scale(&self, b: f64) -> Self {
        let mut acc = Expansion::zero();
        for &x in &self.0 {
            let (p, e) = two_prod(x, b);
            acc = acc.grow(e).grow(p);
        }
        acc
    }
    /// Sign of the exact value: that of the largest component.
    pub fn sign(&self) -> i32 {
        match self.0.last() {
            Some(&c) if c > 0.0 => 1,
            Some(&c) if c < 0.0 => -1,
            _ => 0,
        }
    }
}

/// x × y of 3-vectors of expansions, exactly.
pub fn cross(x: &[Expansion; 3], y: &[Expansion; 3]) -> [Expansion; 3] {
    [
        x[1].mul(&y[2]).sub(&x[2].mul(&y[1])),
        x[2].mul(&y[0]).sub(&x[0].mul(&y[2])),
        x[0].mul(&y[1]).sub(&x[1].mul(&y[0])),
    ]
}

/// x · y of 3-vectors of expansions, exactly.
pub fn dot(x: &[Expansion; 3], y: &[Expansion; 3]) -> Expansion {
    x[0].mul(&y[0]).add(&x[1].mul(&y[1])).add(&x[2].mul(&y[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transformations_are_exact() {
        let (s, t) = two_sum(1.0, 1e-30);
        assert_eq!((s, t), (1.0, 1e-30));
        let (p, t) = two_prod(1.0 + f64::EPSILON, 1.0 + f64::EPSILON);
        assert_eq!(p, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(t, f64::EPSILON * f64::EPSILON);
        // 1e16 + 1 − 1e16 = 1, exactly, through an expansion
        let mut e = Vec::new();
        for x in [1e16, 1.0, -1e16] {
            grow(&mut e, x);
        }
        assert_eq!(e, vec![1.0]);
        let mut z = Vec::new();
        for x in [0.1, -0.1] {
            grow(&mut z, x);
        }
        assert!(z.is_empty(), "exact cancellation leaves no component");
    }
}
