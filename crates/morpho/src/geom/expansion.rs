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
