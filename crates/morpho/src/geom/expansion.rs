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

/// Stack-only expansion arithmetic, for the exact stage of
/// [`super::predicates::incircle_sign`] (an expansion is a slice of non-overlapping doubles in
/// increasing magnitude, zeros eliminated, whose exact sum is the value). Written for fixed
/// small sizes: nothing allocates and nothing is rounded. Products by Dekker's split (no
/// fused multiply-add needed, so no library call where the target lacks FMA).
pub(crate) mod stack {
    /// x = fl(a − b) and its exact rounding error y: a − b = x + y.
    #[inline(always)]
    pub fn two_diff(a: f64, b: f64) -> (f64, f64) {
        let x = a - b;
        let bv = a - x;
        let av = x + bv;
        (x, (a - av) + (bv - b))
    }

    /// x = fl(a + b), a + b = x + y exactly.
    #[inline(always)]
    fn two_sum(a: f64, b: f64) -> (f64, f64) {
        let x = a + b;
        let bv = x - a;
        let av = x - bv;
        (x, (a - av) + (b - bv))
    }

    /// x = fl(a + b), a + b = x + y exactly, valid when |a| ≥ |b| (or a = 0).
    #[inline(always)]
    fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
        let x = a + b;
        (x, b - (x - a))
    }

    /// Veltkamp's split of a into 26-bit halves.
    #[inline(always)]
    fn split(a: f64) -> (f64, f64) {
        const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
        let c = SPLITTER * a;
        let hi = c - (c - a);
        (hi, a - hi)
    }

    /// x = fl(a·b), a·b = x + y exactly (Dekker).
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let x = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        let err = x - ah * bh - al * bh - ah * bl;
        (x, al * bl - err)
    }

    /// The expansion e·b (|e| ≤ 16 components) into h; returns its length.
    fn scale(e: &[f64], b: f64, h: &mut [f64]) -> usize {
        let mut n = 0;
        let (mut q, lo) = two_prod(e[0], b);
        if lo != 0.0 {
            h[n] = lo;
            n += 1;
        }
        for &ei in &e[1..] {
            let (p1, p0) = two_prod(ei, b);
            let (s, lo) = two_sum(q, p0);
            if lo != 0.0 {
                h[n] = lo;
                n += 1;
            }
            let (q2, lo) = fast_two_sum(p1, s);
            q = q2;
            if lo != 0.0 {
                h[n] = lo;
                n += 1;
            }
        }
        if q != 0.0 || n == 0 {
            h[n] = q;
            n += 1;
        }
        n
    }

    /// The exact sum of two expansions into h (Shewchuk's fast expansion sum with zero
    /// elimination); returns its length (≥ 1).
    pub fn sum(e: &[f64], f: &[f64], h: &mut [f64]) -> usize {
        let (mut i, mut j) = (0, 0);
        let next = |i: &mut usize, j: &mut usize| -> f64 {
            let take_e = *j >= f.len() || (*i < e.len() && e[*i].abs() < f[*j].abs());
            if take_e {
                *i += 1;
                e[*i - 1]
            } else {
                *j += 1;
                f[*j - 1]
            }
        };
        let total = e.len() + f.len();
        let mut q = next(&mut i, &mut j);
        let mut n = 0;
        if total > 1 {
            let g = next(&mut i, &mut j);
            let (q2, lo) = fast_two_sum(g, q);
            q = q2;
            if lo != 0.0 {
                h[n] = lo;
                n += 1;
            }
            for _ in 2..total {
                let g = next(&mut i, &mut j);
                let (q2, lo) = two_sum(q, g);
                q = q2;
                if lo != 0.0 {
                    h[n] = lo;
                    n += 1;
                }
            }
        }
        if q != 0.0 || n == 0 {
            h[n] = q;
            n += 1;
        }
        n
    }

    /// (x² + y²)·(u × v) = (x² + y²)·(u.x·v.y − v.x·u.y) exactly, into h (≤ 32 components).
    pub fn lifted_cross(x: f64, y: f64, u: [f64; 2], v: [f64; 2], h: &mut [f64; 32]) -> usize {
        let (p1, p0) = two_prod(u[0], v[1]);
        let (q1, q0) = two_prod(v[0], u[1]);
        let cr = two_two_diff(p1, p0, q1, q0);
        let mut t1 = [0.0; 8];
        let mut t2 = [0.0; 16];
        let mut xx = [0.0; 16];
        let n1 = scale(&cr, x, &mut t1);
        let nx = scale(&t1[..n1], x, &mut xx);
        let n1 = scale(&cr, y, &mut t1);
        let ny = scale(&t1[..n1], y, &mut t2);
        sum(&xx[..nx], &t2[..ny], h)
    }

    /// (a1 + a0) − (b1 + b0) as the four-component expansion [x0, x1, x2, x3] (Shewchuk's
    /// Two-Two-Diff: two Two-One-Diffs, i.e. expansion growth by −b0, then by −b1).
    #[inline(always)]
    fn two_two_diff(a1: f64, a0: f64, b1: f64, b0: f64) -> [f64; 4] {
        let (i, x0) = two_diff(a0, b0);
        let (j, z) = two_sum(a1, i);
        let (k, x1) = two_diff(z, b1);
        let (x3, x2) = two_sum(j, k);
        [x0, x1, x2, x3]
    }

    /// The exact sign of an expansion: that of its largest (last) component.
    #[inline]
    pub fn sign(e: &[f64]) -> i32 {
        let top = e[e.len() - 1];
        (top > 0.0) as i32 - (top < 0.0) as i32
    }
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
