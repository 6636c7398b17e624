//! The least-squares core shared by the surface and the trivariate fits (H §4.2 step (iv),
//! H §4.3): normal equations `UᵀU c = Uᵀd` (H (4.29)) solved by Cholesky, refused when the
//! condition number of `UᵀU` (from its symmetric eigenvalues, by Jacobi rotations on the
//! stack: no allocation per vertex) exceeds a bound. (Solving through eigenvectors instead lost
//! up to 10 % on nearly repeated eigenvalues — the 5-valent vertices of an icosphere.)
//!
//! The condition number `λ_max/λ_min` of `UᵀU` does not change when the platelet is scaled
//! (all entries scale like h⁴), so the "undetermined" rule is scale-free (notes C.2, C.3);
//! an absolute determinant threshold would not be.

use nalgebra::{SMatrix, SVector};
use std::ops::{AddAssign, Mul, SubAssign};

mod jet_solve;

/// Accumulated normal equations of an N-coefficient linear least-squares fit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Normal<const N: usize> {
    /// `UᵀU`, upper triangle: `ata[i][j]` for `i ≤ j` (plain arrays: the accumulation
    /// unrolls and vectorises; the sums are the same as with a matrix type)
    ata: [[f64; N]; N],
    atd: [f64; N],
    rows: usize,
}

impl<const N: usize> Normal<N> {
    pub(crate) fn new() -> Self {
        Normal {
            ata: [[0.0; N]; N],
            atd: [0.0; N],
            rows: 0,
        }
    }
    /// Adds the equation `row · c = d`.
    #[inline(always)]
    pub(crate) fn add(&mut self, row: [f64; N], d: f64) {
        for i in 0..N {
            for j in i..N {
                self.ata[i][j] += row[i] * row[j];
            }
            self.atd[i] += row[i] * d;
        }
        self.rows += 1;
    }
    /// The least-squares solution, or `None` when fewer than N rows were added or
    /// `cond(UᵀU) > max_cond` (also when it is not finite).
    pub(crate) fn solve(&self, max_cond: f64) -> Option<SVector<f64, N>> {
        if self.rows < N {
            return None;
        }
        let m = SMatrix::<f64, N, N>::from_fn(|i, j| self.ata[i.min(j)][i.max(j)]);
        // cond ≤ trace^N / det (λ_max ≤ trace, λ_min ≥ det / λ_max^{N−1}): when that bound
        // already passes, the eigenvalues are not needed (the decision is the same; the
        // eigenvalues were a third of the whole computation)
        if let Some((c, det)) = self.ldl(f64::INFINITY) {
            let tr: f64 = (0..N).map(|i| m[(i, i)]).sum();
            if det > 0.0 && tr.powi(N as i32) <= max_cond * det {
                return Some(SVector::from(c));
            }
        }
        let a: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]));
        let eig = sym_eigenvalues(a);
        let lmax = eig.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let lmin = eig.iter().copied().fold(f64::INFINITY, f64::min);
        // written so that NaN refuses too
        if !(lmax.is_finite() && lmin > 0.0 && lmin * max_cond >= lmax) {
            return None;
        }
        // the solution by LDLᵀ (the eigenvectors of nearly repeated eigenvalues are not
        // accurate enough to solve with)
        self.solve_ldl(f64::INFINITY).map(SVector::from)
    }
}

impl<const N: usize> Normal<N> {
    /// The least-squares solution by an LDLᵀ factorisation on the stack, or `None` when fewer
    /// than N rows were added or a pivot is at most `max_ratio⁻¹` times the largest (the pivot
    /// ratio is a cheap lower bound of `cond(UᵀU)`, also scale-free); for fits whose refusal
    /// only selects a fallback (the jet normals).
    pub(crate) fn solve_ldl(&self, max_ratio: f64) -> Option<[f64; N]> {
        self.ldl(max_ratio).map(|(c, _)| c)
    }

    /// [`Normal::solve_ldl`] and the determinant of `UᵀU` (the product of the pivots).
    fn ldl(&self, max_ratio: f64) -> Option<([f64; N], f64)> {
        if self.rows < N {
            return None;
        }
        let mut l = [[0.0f64; N]; N];
        let mut d = [0.0f64; N];
        // the pivots' reciprocals: one division per pivot instead of one per entry of L and
        // of the solution
        let mut rd = [0.0f64; N];
        let dmax = (0..N).map(|i| self.ata[i][i]).fold(0.0, f64::max);
        for j in 0..N {
            let mut dj = self.ata[j][j];
            for k in 0..j {
                dj -= l[j][k] * l[j][k] * d[k];
            }
            // written so that NaN refuses too
            if !(dj > 0.0 && dj * max_ratio >= dmax) {
                return None;
            }
            d[j] = dj;
            rd[j] = 1.0 / dj;
            for i in j + 1..N {
                let mut x = self.ata[j][i];
                for k in 0..j {
                    x -= l[i][k] * l[j][k] * d[k];
                }
                l[i][j] = x * rd[j];
            }
        }
        // L y = b, D z = y, Lᵀ c = z
        let mut c = [0.0f64; N];
        for i in 0..N {
            let mut x = self.atd[i];
            for k in 0..i {
                x -= l[i][k] * c[k];
            }
            c[i] = x;
        }
        for i in 0..N {
            c[i] *= rd[i];
        }
        for i in (0..N).rev() {
            let mut x = c[i];
            for k in i + 1..N {
                x -= l[k][i] * c[k];
            }
            c[i] = x;
        }
        let det = d.iter().product::<f64>();
        c.iter().all(|x| x.is_finite()).then_some((c, det))
    }
}

/// The jets' unknowns: the exponents `(a, b)` of `uᵃtᵇ` and their factors, in the order of the
/// fit; the cubic jet ([`CubicJet`]) has the first 9, the quartic ([`QuarticJet`]) all 14.
const JET_TERMS: [(usize, usize, f64); 14] = [
    (1, 0, 1.0),
    (0, 1, 1.0),
    (2, 0, 0.5),
    (1, 1, 1.0),
    (0, 2, 0.5),
    (3, 0, 1.0),
    (2, 1, 1.0),
    (1, 2, 1.0),
    (0, 3, 1.0),
    (4, 0, 1.0),
    (3, 1, 1.0),
    (2, 2, 1.0),
    (1, 3, 1.0),
    (0, 4, 1.0),
];

/// For each entry `(i, j)`, `i ≤ j`, of `UᵀU` of the first `N` jet terms in row order
/// (`E = N(N+1)/2` entries): the index of its moment ([`CubicJet::at`]) and its factor
/// `cᵢcⱼ` (evaluated at compile time).
const fn jet_entries<const N: usize, const E: usize>() -> [(u8, f64); E] {
    let mut e = [(0u8, 0.0f64); E];
    let (mut i, mut k) = (0, 0);
    while i < N {
        let mut j = i;
        while j < N {
            let (ai, bi, ci) = JET_TERMS[i];
            let (aj, bj, cj) = JET_TERMS[j];
            e[k] = (CubicJet::at(ai + aj, bi + bj) as u8, ci * cj);
            k += 1;
            j += 1;
        }
        i += 1;
    }
    e
}

/// The normal equations `UᵀU c = Uᵀd` of a jet with the first `N` terms from its moments `m`
/// (`Σ uᵃtᵇ` laid out by [`CubicJet::at`]) and `r` (`Σ d uᵃtᵇ` in the order of the unknowns).
#[inline]
fn jet_normal<const N: usize, const E: usize>(
    entries: &[(u8, f64); E],
    m: &[f64],
    r: &[f64],
    rows: usize,
) -> Normal<N> {
    let mut ne = Normal::<N>::new();
    let mut k = 0;
    for i in 0..N {
        for j in i..N {
            let (at, f) = entries[k];
            ne.ata[i][j] = f * m[at as usize];
            k += 1;
        }
        ne.atd[i] = JET_TERMS[i].2 * r[i];
    }
    ne.rows = rows;
    ne
}

/// The monomials of degree 2, 3, 4, 5, 6 ([`monomials_2_6`]).
type Monomials2to6<T> = ([T; 3], [T; 4], [T; 5], [T; 6], [T; 7]);

/// The arithmetic of the moments: `f64` (one vertex) and [`F4`] (four vertices, one per lane,
/// each lane the same operations as `f64`).
pub(crate) trait Lane: Copy + Mul<Output = Self> + AddAssign {
    /// `x` (in every lane).
    fn splat(x: f64) -> Self;
    /// `1 / self` (in every lane).
    fn recip(self) -> Self;
}
impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }
}
impl Lane for F4 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        F4::splat(x)
    }
    #[inline(always)]
    fn recip(self) -> Self {
        F4::recip(self)
    }
}

/// The offset of the jets' distance weight ([`jet_weight`]).
pub(crate) const JET_WEIGHT_EPS: f64 = 0.1;

/// The least-squares weight `w = 1/(ε + u² + t² + d²)⁴` (ε = [`JET_WEIGHT_EPS`]) of a jet's
/// point `(u, t, d)` in coordinates divided by the ring's RMS radius (so the mean of
/// `u² + t² + d²` over the ring is 1 and the weight is scale-free). The far points of a
/// 2-ring carry the jet's truncation error (the surface's terms beyond degree 4, ∝ r⁵, r⁶):
/// weighting them down takes it out of the Hessian (on the 40×120 torus grid 3.4× less RMS
/// of H, `bench/README.md`); ε bounds the weight of a point at the vertex (a zero-length edge)
/// by ε⁻⁴ = 10⁴, so the weights span at most that range times the ring's own. The same
/// operations for `f64` and [`F4`] (the scalar and the four-lane paths agree bit for bit).
#[inline(always)]
pub(crate) fn jet_weight<T: Lane>(u: T, t: T, d: T) -> T {
    let mut q = T::splat(JET_WEIGHT_EPS);
    q += u * u;
    q += t * t;
    q += d * d;
    let q2 = q * q;
    (q2 * q2).recip()
}

/// The monomials `w uᵃtᵇ` of degree 2–6 from `wu = w u` and `wt = w t` (`w` a point's weight,
/// 1 for the unweighted fits: then the same bits as without it), each block by increasing
/// `b`, each monomial one product from degree k − 1 (the first times `u`, every other the one
/// before it times `t`): the jets' moment layout. Written out, not looped: a loop kept the
/// monomials in memory and took twice as long.
#[inline(always)]
fn monomials_2_6<T: Lane>(u: T, t: T, wu: T, wt: T) -> Monomials2to6<T> {
    let d2 = [wu * u, wu * t, wt * t];
    let d3 = [d2[0] * u, d2[0] * t, d2[1] * t, d2[2] * t];
    let d4 = [d3[0] * u, d3[0] * t, d3[1] * t, d3[2] * t, d3[3] * t];
    let d5 = [
        d4[0] * u,
        d4[0] * t,
        d4[1] * t,
        d4[2] * t,
        d4[3] * t,
        d4[4] * t,
    ];
    let d6 = [
        d5[0] * u,
        d5[0] * t,
        d5[1] * t,
        d5[2] * t,
        d5[3] * t,
        d5[4] * t,
        d5[5] * t,
    ];
    (d2, d3, d4, d5, d6)
}

/// Adds the monomials of [`monomials_2_6`] to the first 25 moments.
#[inline(always)]
fn add_moments_2_6<T: Lane>(m: &mut [T], d: &Monomials2to6<T>) {
    for (acc, x) in m[0..3].iter_mut().zip(d.0) {
        *acc += x;
    }
    for (acc, x) in m[3..7].iter_mut().zip(d.1) {
        *acc += x;
    }
    for (acc, x) in m[7..12].iter_mut().zip(d.2) {
        *acc += x;
    }
    for (acc, x) in m[12..18].iter_mut().zip(d.3) {
        *acc += x;
    }
    for (acc, x) in m[18..25].iter_mut().zip(d.4) {
        *acc += x;
    }
}

/// Adds the point `(u, t)` with height `d` and weight `w` to the quartic jet's moments `m`
/// (`Σ w uᵃtᵇ`, degree 2–8) and `r` (`Σ w d uᵃtᵇ`, degree 1–4): [`QuarticJet::add_weighted`]
/// for one vertex, [`QuarticJet4::add`] for four — the same code, so each lane's sums are the
/// one vertex's, bit for bit.
#[inline(always)]
fn quartic_add<T: Lane>(m: &mut [T; 42], r: &mut [T; 14], u: T, t: T, d: T, w: T) {
    // degree by degree, as in `CubicJet::add`, two degrees further
    let (wu, wt) = (w * u, w * t);
    let mo = monomials_2_6(u, t, wu, wt);
    add_moments_2_6(m, &mo);
    let (d2, d3, d4, d6) = (mo.0, mo.1, mo.2, mo.4);
    let d7 = [
        d6[0] * u,
        d6[0] * t,
        d6[1] * t,
        d6[2] * t,
        d6[3] * t,
        d6[4] * t,
        d6[5] * t,
        d6[6] * t,
    ];
    let d8 = [
        d7[0] * u,
        d7[0] * t,
        d7[1] * t,
        d7[2] * t,
        d7[3] * t,
        d7[4] * t,
        d7[5] * t,
        d7[6] * t,
        d7[7] * t,
    ];
    for (acc, x) in m[25..33].iter_mut().zip(d7) {
        *acc += x;
    }
    for (acc, x) in m[33..42].iter_mut().zip(d8) {
        *acc += x;
    }
    let low = [
        wu, wt, d2[0], d2[1], d2[2], d3[0], d3[1], d3[2], d3[3], d4[0], d4[1], d4[2], d4[3], d4[4],
    ];
    for (acc, x) in r.iter_mut().zip(low) {
        *acc += d * x;
    }
}

/// The normal equations of the cubic jet `a u + b t + ½(c20 u² + 2 c11 ut + c02 t²) + c30 u³ +
/// c21 u²t + c12 ut² + c03 t³ = d` (the unknowns in that order), accumulated as moments: the
/// 45 entries of `UᵀU` are `cᵢcⱼ Σ uᵃtᵇ` over only 25 distinct monomials of degree 2–6, and
/// `Uᵀd` is `cᵢ Σ d uᵃtᵇ` over the 9 monomials of degree 1–3 (`cᵢ` is 1 or ½, so the
/// scaling is exact). Each monomial of degree k is one product from degree k − 1, so a point
/// costs 34 products and 34 sums instead of the 54 products and sums of its row's outer
/// product. The sums are those of [`Normal::add`] up to the rounding of the monomials.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CubicJet {
    /// `Σ uᵃtᵇ` for `a + b = k`, k = 2…6, in blocks of k + 1 by increasing b
    /// ([`CubicJet::at`]).
    m: [f64; 25],
    /// `Σ d u, Σ d t, Σ d u², Σ d ut, Σ d t², Σ d u³, Σ d u²t, Σ d ut², Σ d t³`.
    r: [f64; 9],
    rows: usize,
}

impl CubicJet {
    pub(crate) fn new() -> Self {
        CubicJet {
            m: [0.0; 25],
            r: [0.0; 9],
            rows: 0,
        }
    }

    /// The index of `Σ uᵃtᵇ` (`2 ≤ a + b ≤ 6`) in `m`.
    const fn at(a: usize, b: usize) -> usize {
        let k = a + b;
        k * (k + 1) / 2 - 3 + b
    }

    /// Adds the point `(u, t)` with height `d` (weight 1).
    #[cfg_attr(not(test), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn add(&mut self, u: f64, t: f64, d: f64) {
        self.add_weighted(u, t, d, 1.0);
    }

    /// Adds the point `(u, t)` with height `d` and least-squares weight `w > 0` (the normal
    /// equations `UᵀWU c = UᵀW d`; `w = 1` gives the bits of [`CubicJet::add`]).
    #[inline(always)]
    pub(crate) fn add_weighted(&mut self, u: f64, t: f64, d: f64, w: f64) {
        let (wu, wt) = (w * u, w * t);
        let mo = monomials_2_6(u, t, wu, wt);
        add_moments_2_6(&mut self.m, &mo);
        let (d2, d3) = (mo.0, mo.1);
        let low = [wu, wt, d2[0], d2[1], d2[2], d3[0], d3[1], d3[2], d3[3]];
        for (acc, x) in self.r.iter_mut().zip(low) {
            *acc += d * x;
        }
        self.rows += 1;
    }

    const ENTRIES: [(u8, f64); 45] = jet_entries::<9, 45>();

    /// The normal equations `UᵀU c = Uᵀd` of the points added so far.
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) fn normal(&self) -> Normal<9> {
        jet_normal(&Self::ENTRIES, &self.m, &self.r, self.rows)
    }

    /// `self.normal().solve_ldl(max_ratio)` up to rounding (the same rule of refusal), from the
    /// moments without forming the matrix, in straight-line code ([`jet_solve`]); the
    /// lockstep test `jet_solves_are_normal_solve_ldl` compares the two.
    pub(crate) fn solve(&self, max_ratio: f64) -> Option<[f64; 9]> {
        if self.rows < 9 {
            return None;
        }
        jet_solve::cubic_solve(&self.m, &self.r, max_ratio)
    }
}

/// The normal equations of the quartic jet: the 14 unknowns of [`CubicJet`] followed by the
/// quartic terms `c40 u⁴ + c31 u³t + c22 u²t² + c13 ut³ + c04 t⁴`, accumulated as the 42
/// moments `Σ uᵃtᵇ` of degree 2–8 and the 14 right-hand moments `Σ d uᵃtᵇ` of degree 1–4 (the
/// same construction as [`CubicJet`], one degree higher: 56 products per point instead of the
/// rows' 119).
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuarticJet {
    m: [f64; 42],
    r: [f64; 14],
    rows: usize,
}

impl QuarticJet {
    pub(crate) fn new() -> Self {
        QuarticJet {
            m: [0.0; 42],
            r: [0.0; 14],
            rows: 0,
        }
    }

    /// Adds the point `(u, t)` with height `d` (weight 1).
    #[cfg_attr(not(test), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn add(&mut self, u: f64, t: f64, d: f64) {
        self.add_weighted(u, t, d, 1.0);
    }

    /// Adds the point `(u, t)` with height `d` and least-squares weight `w > 0`
    /// ([`CubicJet::add_weighted`]).
    #[inline(always)]
    pub(crate) fn add_weighted(&mut self, u: f64, t: f64, d: f64, w: f64) {
        quartic_add(&mut self.m, &mut self.r, u, t, d, w);
        self.rows += 1;
    }

    const ENTRIES: [(u8, f64); 105] = jet_entries::<14, 105>();

    /// `self.normal().solve_ldl(max_ratio)` up to rounding (the same rule of refusal), as
    /// [`CubicJet::solve`].
    pub(crate) fn solve(&self, max_ratio: f64) -> Option<[f64; 14]> {
        if self.rows < 14 {
            return None;
        }
        jet_solve::quartic_solve(&self.m, &self.r, max_ratio)
    }

    /// The cubic jet of the same points: its moments are the prefixes (degree 2–6 and 1–3).
    pub(crate) fn cubic(&self) -> CubicJet {
        CubicJet {
            m: std::array::from_fn(|i| self.m[i]),
            r: std::array::from_fn(|i| self.r[i]),
            rows: self.rows,
        }
    }

    /// The normal equations `UᵀU c = Uᵀd` of the points added so far.
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) fn normal(&self) -> Normal<14> {
        jet_normal(&Self::ENTRIES, &self.m, &self.r, self.rows)
    }
}

/// Four `f64` lanes, one vertex each: every operation is the `f64` operation in each lane
/// (so a lane's results are bit for bit those of the scalar code doing the same operations);
/// written as loops over the lanes that the compiler turns into vector instructions (two SSE2
/// or one AVX2 instruction per operation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(align(32))]
pub(crate) struct F4(pub(crate) [f64; 4]);

impl F4 {
    pub(crate) const ZERO: F4 = F4([0.0; 4]);

    #[inline(always)]
    pub(crate) fn splat(x: f64) -> F4 {
        F4([x; 4])
    }

    #[inline(always)]
    fn zip(self, o: F4, f: impl Fn(f64, f64) -> f64) -> F4 {
        F4(std::array::from_fn(|l| f(self.0[l], o.0[l])))
    }

    /// `f64::max` in each lane.
    #[inline(always)]
    fn max(self, o: F4) -> F4 {
        self.zip(o, f64::max)
    }

    /// `1.0 / x` in each lane.
    #[inline(always)]
    fn recip(self) -> F4 {
        F4::splat(1.0).zip(self, |a, b| a / b)
    }

    /// Clears `ok` in the lanes where the pivot `self` fails the test of [`Normal::solve_ldl`]
    /// (not positive, or at most `max_ratio⁻¹` times `dmax`; NaN fails). Both comparisons are
    /// made in every lane and combined by `&` (no short circuit, no side effects: the same
    /// answer as `&&`), so that the test has no branch (the solve is one basic block).
    #[inline(always)]
    fn pivot_ok(self, max_ratio: f64, dmax: F4, ok: &mut [bool; 4]) {
        for l in 0..4 {
            let p = self.0[l];
            ok[l] &= (p > 0.0) & (p * max_ratio >= dmax.0[l]);
        }
    }

    /// The solution of each lane where `ok` holds and every entry is finite.
    #[inline(always)]
    fn solutions<const N: usize>(c: &[F4; N], ok: [bool; 4]) -> [Option<[f64; N]>; 4] {
        std::array::from_fn(|l| {
            let x: [f64; N] = std::array::from_fn(|i| c[i].0[l]);
            (ok[l] && x.iter().all(|v| v.is_finite())).then_some(x)
        })
    }
}

impl Mul for F4 {
    type Output = F4;
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        self.zip(o, |a, b| a * b)
    }
}

impl AddAssign for F4 {
    #[inline(always)]
    fn add_assign(&mut self, o: F4) {
        *self = self.zip(o, |a, b| a + b);
    }
}

impl SubAssign for F4 {
    #[inline(always)]
    fn sub_assign(&mut self, o: F4) {
        *self = self.zip(o, |a, b| a - b);
    }
}

/// The quartic jets of four vertices at once, one per lane ([`F4`]): lane `l` holds the moments
/// of [`QuarticJet`] of the points added in lane `l`. A lane with fewer points is padded with
/// the point `(0, 0, 0)`, which adds exactly nothing (every monomial is +0, and `x + 0 = x` for
/// every sum that starts at +0: such a sum is never −0), so its moments are its own vertex's
/// bit for bit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuarticJet4 {
    m: [F4; 42],
    r: [F4; 14],
}

impl QuarticJet4 {
    pub(crate) fn new() -> Self {
        QuarticJet4 {
            m: [F4::ZERO; 42],
            r: [F4::ZERO; 14],
        }
    }

    /// Adds one point per lane with its weight ([`QuarticJet::add_weighted`] in each lane).
    #[inline(always)]
    pub(crate) fn add(&mut self, u: F4, t: F4, d: F4, w: F4) {
        quartic_add(&mut self.m, &mut self.r, u, t, d, w);
    }

    /// [`QuarticJet::solve`] of each lane, for lanes of at least 14 points (the caller's
    /// condition: the row count is not kept).
    #[inline(always)]
    pub(crate) fn solve(&self, max_ratio: f64) -> [Option<[f64; 14]>; 4] {
        jet_solve::quartic_solve4(&self.m, &self.r, max_ratio)
    }
}

/// Eigenvalues of a small symmetric matrix by cyclic Jacobi rotations, on the stack (no
/// allocation per vertex; accurate to rounding also for the small eigenvalues the condition
/// test needs). NaN entries give NaN eigenvalues.
fn sym_eigenvalues<const N: usize>(mut a: [[f64; N]; N]) -> [f64; N] {
    for _ in 0..32 {
        let mut off = 0.0;
        let mut diag = 0.0;
        for i in 0..N {
            diag += a[i][i] * a[i][i];
            for j in i + 1..N {
                off += a[i][j] * a[i][j];
            }
        }
        if off.is_nan() || diag.is_nan() || off <= 1e-34 * diag {
            break;
        }
        for p in 0..N {
            for q in p + 1..N {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                // (θ² may overflow to ∞: then t = 0, no rotation; libm's hypot was a fifth of
                // the whole computation)
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (kp, kq) = (row[p], row[q]);
                    row[p] = c * kp - s * kq;
                    row[q] = s * kp + c * kq;
                }
                for k in 0..N {
                    let (pk, qk) = (a[p][k], a[q][k]);
                    a[p][k] = c * pk - s * qk;
                    a[q][k] = s * pk + c * qk;
                }
                a[p][q] = 0.0;
                a[q][p] = 0.0;
            }
        }
    }
    std::array::from_fn(|i| a[i][i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_fit_and_rank_deficiency() {
        let mut n = Normal::<3>::new();
        for (u, v) in [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (-1.0, 2.0)] {
            let row = [u * u, u * v, v * v];
            n.add(row, 3.0 * u * u - 2.0 * u * v + 0.5 * v * v);
        }
        let c = n.solve(1e10).unwrap();
        assert!((c - SVector::<f64, 3>::new(3.0, -2.0, 0.5)).norm() < 1e-12);
        let mut d = Normal::<3>::new();
        for u in [1.0, 2.0, 3.0] {
            d.add([u * u, 0.0, 0.0], 1.0);
        }
        assert!(d.solve(1e10).is_none());
        assert!(d.solve_ldl(1e10).is_none());
        let e = n.solve_ldl(1e10).unwrap();
        assert!((SVector::<f64, 3>::from(e) - c).norm() < 1e-12);
    }

    #[test]
    fn jet_moments_are_the_rows_normal_equations() {
        // the 25 moments must give the outer products' sums of the 9-term rows up to rounding
        // (a wrong index or factor is off by O(1))
        let mut rows = Normal::<9>::new();
        let mut jet = CubicJet::new();
        let mut x = 0.37f64;
        for k in 0..23 {
            let mut next = || {
                x = (x * 3.7 + 0.11 * k as f64).fract() - 0.5;
                2.0 * x
            };
            let (u, t) = (next(), next());
            let d = next() + 0.3 * u * t;
            let (uu, ut, tt) = (u * u, u * t, t * t);
            rows.add(
                [u, t, 0.5 * uu, ut, 0.5 * tt, uu * u, uu * t, u * tt, tt * t],
                d,
            );
            jet.add(u, t, d);
        }
        let ne = jet.normal();
        assert_eq!(ne.rows, rows.rows);
        for i in 0..9 {
            let (a, b) = (ne.atd[i], rows.atd[i]);
            assert!((a - b).abs() <= 1e-14 * b.abs().max(1.0), "atd {i} {a} {b}");
            for j in i..9 {
                let (a, b) = (ne.ata[i][j], rows.ata[i][j]);
                assert!(
                    (a - b).abs() <= 1e-14 * b.abs().max(1.0),
                    "({i},{j}) {a} {b}"
                );
            }
        }
        let (c1, c2) = (ne.solve_ldl(1e10).unwrap(), rows.solve_ldl(1e10).unwrap());
        for i in 0..9 {
            assert!(
                (c1[i] - c2[i]).abs() < 1e-9 * (1.0 + c2[i].abs()),
                "{c1:?} {c2:?}"
            );
        }
    }

    /// The quartic jet's 14-term row at (u, t), written out from the monomials (the oracle of
    /// the moment tests: independent of the moment code's own monomial table).
    fn quartic_row(u: f64, t: f64) -> [f64; 14] {
        let (uu, ut, tt) = (u * u, u * t, t * t);
        [
            u,
            t,
            0.5 * uu,
            ut,
            0.5 * tt,
            uu * u,
            uu * t,
            u * tt,
            tt * t,
            uu * uu,
            uu * ut,
            uu * tt,
            ut * tt,
            tt * tt,
        ]
    }

    #[test]
    fn quartic_moments_are_the_rows_normal_equations() {
        // the 42 moments must give the outer products' sums of the 14-term rows up to rounding,
        // and their prefix the cubic's (a wrong index, factor or monomial is off by O(1))
        let mut rows = Normal::<14>::new();
        let mut cubic = CubicJet::new();
        let mut jet = QuarticJet::new();
        let mut x = 0.41f64;
        for k in 0..31 {
            let mut next = || {
                x = (x * 3.7 + 0.13 * k as f64).fract() - 0.5;
                2.0 * x
            };
            let (u, t) = (next(), next());
            let d = next() + 0.3 * u * t;
            rows.add(quartic_row(u, t), d);
            jet.add(u, t, d);
            cubic.add(u, t, d);
        }
        let ne = jet.normal();
        assert_eq!(ne.rows, rows.rows);
        for i in 0..14 {
            let (a, b) = (ne.atd[i], rows.atd[i]);
            assert!((a - b).abs() <= 1e-14 * b.abs().max(1.0), "atd {i} {a} {b}");
            for j in i..14 {
                let (a, b) = (ne.ata[i][j], rows.ata[i][j]);
                assert!(
                    (a - b).abs() <= 1e-14 * b.abs().max(1.0),
                    "({i},{j}) {a} {b}"
                );
            }
        }
        let (c1, c2) = (ne.solve_ldl(1e12).unwrap(), rows.solve_ldl(1e12).unwrap());
        for i in 0..14 {
            assert!(
                (c1[i] - c2[i]).abs() < 1e-8 * (1.0 + c2[i].abs()),
                "{c1:?} {c2:?}"
            );
        }
        let (p, q) = (jet.cubic().normal(), cubic.normal());
        assert_eq!(p.ata, q.ata);
        assert_eq!(p.atd, q.atd);
        assert_eq!(p.rows, q.rows);
    }

    #[test]
    fn weighted_moments_are_the_weighted_rows_normal_equations() {
        // `add_weighted(u, t, d, w)` must give the normal equations `UᵀWU c = UᵀW d`: those of
        // the rows and heights scaled by √w, up to rounding (a weight missing from a moment,
        // or applied twice, is off by O(1)); weight 1 must give the bits of `add`
        let mut rows = Normal::<14>::new();
        let mut jet = QuarticJet::new();
        let mut cubic = CubicJet::new();
        let (mut plain, mut one) = (QuarticJet::new(), QuarticJet::new());
        let mut x = 0.43f64;
        for k in 0..29 {
            let mut next = || {
                x = (x * 3.7 + 0.13 * k as f64).fract() - 0.5;
                2.0 * x
            };
            let (u, t) = (next(), next());
            let d = next() + 0.3 * u * t;
            let w = jet_weight(u, t, d);
            assert!(w > 0.0 && w <= 1e4 * (1.0 + 1e-12));
            let s = w.sqrt();
            rows.add(quartic_row(u, t).map(|r| s * r), s * d);
            jet.add_weighted(u, t, d, w);
            cubic.add_weighted(u, t, d, w);
            plain.add(u, t, d);
            one.add_weighted(u, t, d, 1.0);
        }
        let ne = jet.normal();
        for i in 0..14 {
            let (a, b) = (ne.atd[i], rows.atd[i]);
            assert!((a - b).abs() <= 1e-13 * b.abs().max(1.0), "atd {i} {a} {b}");
            for j in i..14 {
                let (a, b) = (ne.ata[i][j], rows.ata[i][j]);
                assert!(
                    (a - b).abs() <= 1e-13 * b.abs().max(1.0),
                    "({i},{j}) {a} {b}"
                );
            }
        }
        let (p, q) = (jet.cubic().normal(), cubic.normal());
        assert_eq!(p.ata, q.ata);
        assert_eq!(p.atd, q.atd);
        assert_eq!(plain.m.map(f64::to_bits), one.m.map(f64::to_bits));
        assert_eq!(plain.r.map(f64::to_bits), one.r.map(f64::to_bits));
        // the weight: 1/(ε + |p|²)⁴, largest (ε⁻⁴) at the origin
        let w0 = jet_weight(0.0, 0.0, 0.0);
        assert!((w0 * JET_WEIGHT_EPS.powi(4) - 1.0).abs() < 1e-12, "{w0}");
        let w = jet_weight(0.3, -0.4, 0.5);
        assert!((w - 1.0 / (JET_WEIGHT_EPS + 0.5f64).powi(4)).abs() < 1e-12 * w);
    }

    /// The points of a jittered 2-ring of a valence-6 vertex (19 points: the origin's 18
    /// neighbours within two edges, in units of the edge), heights of a smooth surface; `k`
    /// varies the jitter.
    fn ring_points(k: usize) -> Vec<(f64, f64, f64)> {
        let mut x = 0.29 + 0.01 * k as f64;
        let mut next = || {
            x = (x * 3.7 + 0.17).fract();
            x - 0.5
        };
        let mut p = Vec::new();
        for (ring, count) in [(1.0f64, 6), (2.0, 12)] {
            for j in 0..count {
                let a = std::f64::consts::TAU * j as f64 / count as f64 + 0.2 * next();
                let rad = ring * (1.0 + 0.2 * next());
                let (u, t) = (rad * a.cos(), rad * a.sin());
                let d = 0.07 * u - 0.03 * t + 0.3 * u * u - 0.2 * u * t
                    + 0.1 * t * t
                    + 0.05 * u * u * t
                    - 0.01 * t.powi(4)
                    + 1e-3 * next();
                p.push((u, t, d));
            }
        }
        p
    }

    #[test]
    fn jet_solves_are_normal_solve_ldl() {
        // the straight-line solves (`jet_solve.rs`) must give `Normal::solve_ldl` of the same
        // normal equations up to rounding: a wrong factor, moment, update or substitution in
        // the generated code is off by far more than 1e-9
        for k in 0..40 {
            let mut q = QuarticJet::new();
            for (u, t, d) in ring_points(k) {
                q.add(u, t, d);
            }
            let a = q.solve(1e10).expect("a determined quartic");
            let b = q.normal().solve_ldl(1e10).expect("a determined quartic");
            for i in 0..14 {
                assert!(
                    (a[i] - b[i]).abs() <= 1e-9 * b[i].abs().max(1e-3),
                    "{k} {a:?} {b:?}"
                );
            }
            let c = q.cubic();
            let a = c.solve(1e10).expect("a determined cubic");
            let b = c.normal().solve_ldl(1e10).expect("a determined cubic");
            for i in 0..9 {
                assert!(
                    (a[i] - b[i]).abs() <= 1e-9 * b[i].abs().max(1e-3),
                    "{k} {a:?} {b:?}"
                );
            }
        }
        // the same refusals: rank deficiency (points on a line; on two lines for the
        // quartic), too few points, a pivot ratio above the bound, NaN
        let mut line = QuarticJet::new();
        for j in 0..20 {
            let u = j as f64 * 0.1 - 1.0;
            line.add(u, 0.5 * u, u * u);
        }
        assert!(line.solve(1e10).is_none() && line.normal().solve_ldl(1e10).is_none());
        assert!(line.cubic().solve(1e10).is_none());
        let mut cross = QuarticJet::new();
        for j in 0..20 {
            let s = j as f64 * 0.1 - 1.0;
            let (u, t) = if j % 2 == 0 { (s, 0.0) } else { (0.0, s) };
            cross.add(u, t, s * s);
        }
        assert!(cross.solve(1e10).is_none() && cross.normal().solve_ldl(1e10).is_none());
        let mut few = QuarticJet::new();
        for &(u, t, d) in &ring_points(0)[..13] {
            few.add(u, t, d);
        }
        assert!(few.solve(1e10).is_none());
        assert!(few.cubic().solve(1e10).is_some());
        let mut q = QuarticJet::new();
        for (u, t, d) in ring_points(1) {
            q.add(u, t, d);
        }
        assert!(q.solve(1.0).is_none() && q.normal().solve_ldl(1.0).is_none());
        q.add(0.5, 0.5, f64::NAN);
        assert!(q.solve(1e10).is_none() && q.cubic().solve(1e10).is_none());
    }

    #[test]
    fn quartic_solve4_lanes_are_quartic_solve() {
        // each lane of `QuarticJet4` (moments and solution) must be `QuarticJet` of that lane's
        // points bit for bit, whatever the other lanes hold and however many points they have
        // (shorter lanes padded with zeros), refusals included: a wrong padding, a lane mix-up,
        // a different order of operations or a refusal rule that differs changes some bits
        let lanes_of = |k: usize| -> [Vec<(f64, f64, f64)>; 4] {
            let mut line = Vec::new();
            for j in 0..17 {
                let u = j as f64 * 0.1 - 1.0;
                line.push((u, 0.5 * u, u * u));
            }
            let mut nan = ring_points(k + 3);
            nan[7].2 = f64::NAN;
            let mut long = ring_points(k + 1);
            long.extend(
                ring_points(k + 2)
                    .iter()
                    .map(|&(u, t, d)| (0.5 * u, 0.7 * t, d)),
            );
            let short: Vec<_> = ring_points(k)[..14 + k % 5].to_vec();
            match k % 4 {
                0 => [ring_points(k), long, short, line],
                1 => [short, ring_points(k), nan, long],
                2 => [line, nan, ring_points(k), short],
                _ => [long, short, line, ring_points(k)],
            }
        };
        let mut refused = 0;
        for k in 0..24 {
            let lanes = lanes_of(k);
            let longest = lanes.iter().map(Vec::len).max().unwrap();
            let mut q4 = QuarticJet4::new();
            for p in 0..longest {
                let at = |c: usize| {
                    F4(std::array::from_fn(|l| {
                        lanes[l].get(p).map_or(0.0, |&(u, t, d)| [u, t, d][c])
                    }))
                };
                let (u, t, d) = (at(0), at(1), at(2));
                q4.add(u, t, d, jet_weight(u, t, d));
            }
            let sol = q4.solve(1e10);
            for (l, pts) in lanes.iter().enumerate() {
                let mut q = QuarticJet::new();
                for &(u, t, d) in pts {
                    q.add_weighted(u, t, d, jet_weight(u, t, d));
                }
                for i in 0..42 {
                    assert_eq!(q.m[i].to_bits(), q4.m[i].0[l].to_bits(), "{k} {l} m{i}");
                }
                for i in 0..14 {
                    assert_eq!(q.r[i].to_bits(), q4.r[i].0[l].to_bits(), "{k} {l} r{i}");
                }
                let one = q.solve(1e10);
                refused += usize::from(one.is_none());
                assert_eq!(
                    one.map(|c| c.map(f64::to_bits)),
                    sol[l].map(|c| c.map(f64::to_bits)),
                    "{k} {l}"
                );
            }
        }
        assert!(refused >= 24, "the line and NaN lanes are refused");
    }

    #[test]
    fn quartic_solve4_is_quartic_solve_on_random_and_ill_conditioned_rings() {
        // `quartic_solve4` finishes its rows one by one (up-looking) where `quartic_solve`
        // eliminates right-looking: each entry must still get the same terms in the same
        // order, so every lane is the scalar solve bit for bit, and refuses where it refuses,
        // for every pivot bound. Lanes of 14–40 random points, a third of them squeezed
        // towards a line (pivot ratios from 1e2 to past 1e10, where a term taken in another
        // order, or a quotient `u_ki / d_k` for the product `u_ki · (1/d_k)`, shows in the last
        // bits, and the pivot test is near its bound)
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut same, mut refused) = (0, 0);
        for case in 0..300 {
            let lanes: [Vec<(f64, f64, f64)>; 4] = std::array::from_fn(|l| {
                let n = 14 + ((rnd() * 27.0) as usize);
                let squeeze = if (case + l) % 3 == 0 {
                    10f64.powf(-1.0 - 4.0 * rnd())
                } else {
                    1.0
                };
                let c: [f64; 6] = std::array::from_fn(|_| rnd() - 0.5);
                (0..n)
                    .map(|_| {
                        let (a, b) = (2.0 * rnd() - 1.0, squeeze * (2.0 * rnd() - 1.0));
                        let (u, t) = (0.8 * a - 0.6 * b, 0.6 * a + 0.8 * b);
                        let d = c[0] * u
                            + c[1] * t
                            + c[2] * u * u
                            + c[3] * u * t
                            + c[4] * t * t * t
                            + c[5] * u.powi(4)
                            + 1e-4 * (rnd() - 0.5);
                        (u, t, d)
                    })
                    .collect()
            });
            let longest = lanes.iter().map(Vec::len).max().unwrap();
            let mut q4 = QuarticJet4::new();
            for p in 0..longest {
                let at = |c: usize| {
                    F4(std::array::from_fn(|l| {
                        lanes[l].get(p).map_or(0.0, |&(u, t, d)| [u, t, d][c])
                    }))
                };
                let (u, t, d) = (at(0), at(1), at(2));
                q4.add(u, t, d, jet_weight(u, t, d));
            }
            for max_ratio in [1e10, 1e6, 1e3] {
                let sol = q4.solve(max_ratio);
                for (l, pts) in lanes.iter().enumerate() {
                    let mut q = QuarticJet::new();
                    for &(u, t, d) in pts {
                        q.add_weighted(u, t, d, jet_weight(u, t, d));
                    }
                    let one = q.solve(max_ratio);
                    refused += usize::from(one.is_none());
                    same += usize::from(one.is_some());
                    assert_eq!(
                        one.map(|c| c.map(f64::to_bits)),
                        sol[l].map(|c| c.map(f64::to_bits)),
                        "case {case} lane {l} max_ratio {max_ratio}"
                    );
                }
            }
        }
        // both outcomes occur often (the bounds and the squeezed lanes are not vacuous)
        assert!(
            same > 1000 && refused > 300,
            "{same} solved, {refused} refused"
        );
    }

    #[test]
    fn jacobi_eigenvalues() {
        let a = [[4.0, 1.0, -2.0], [1.0, 2.0, 0.5], [-2.0, 0.5, 3.0]];
        let mut e = sym_eigenvalues(a);
        e.sort_by(f64::total_cmp);
        let m = nalgebra::Matrix3::from_fn(|i, j| a[i][j]);
        let mut r: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
        r.sort_by(f64::total_cmp);
        for i in 0..3 {
            assert!((e[i] - r[i]).abs() < 1e-13, "{e:?} {r:?}");
        }
        // a tiny eigenvalue is kept to relative accuracy (the condition test needs it)
        let d = [[1.0, 1.0], [1.0, 1.0 + 1e-9]];
        let e = sym_eigenvalues(d);
        let small = e[0].min(e[1]);
        assert!((small - 0.5e-9).abs() < 1e-15, "{e:?}");
        assert!(sym_eigenvalues([[f64::NAN, 0.0], [0.0, 1.0]])[0].is_nan());
    }
}
