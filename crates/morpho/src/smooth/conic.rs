//! Hamann's conic curve scheme (Hamann 1991, §6.2, (6.5)–(6.12), Thm 6.3, Def. 6.3; NOTES E.2)
//! and the boundary normal field along it (§6.3 (6.13)–(6.16); NOTES E.3.2): the building
//! block of the side-vertex surface (`side_vertex.rs`).
//!
//! **The curve.** Given end points `b0, b3` with outward unit normals `n0, n3`: the plane P
//! through `b0, b3` containing `(n0+n3)/2` has the normal `m = (b3−b0)×(n0+n3)`; the end
//! tangents `t0 = m×n0`, `t3 = m×n3` (unit) are oriented so that `t0·(b3−b0) > 0` and
//! `t3·(b0−b3) > 0`. With α the angle between `t0` and the chord, β between `t3` and the
//! reversed chord and `γ = π−α−β`, the conic `(b0, q, b3; 1, ω, 1)` (q = intersection of the
//! tangent lines) is written degree-elevated as the rational cubic (6.5)
//! `c(t) = Σ ωᵢ bᵢ B³ᵢ(t) / Σ ωᵢ B³ᵢ(t)` with `b1 = b0 + L01 t0`, `b2 = b3 + L32 t3`, (6.9)
//! `L01 = 2ω/(1+2ω) · sin β/sin γ · |b3−b0|` (L32 with α), and the **elevated weights
//! `ω1 = ω2 = (1+2ω)/3`** (NOTES E.2.5: the printed `ω1 = ω2 = ω` contradicts (6.8) and leaves
//! circles; only the elevated weights reproduce them). The automatic weight (Thm 6.3) is
//! `ω = sin(γ/2)`; the **tension** τ scales it, `ω = τ sin(γ/2)` (τ = 1: Thm 6.3; τ ≪ 1 pulls
//! the curve to its chord, §6.3 end). With `sin γ = 2 sin(γ/2) cos(γ/2)` the handle length is
//! evaluated as `L01 = τ sin β / ((1+2ω) cos(γ/2)) · |b3−b0|`, finite for γ → 0 ((6.12)).
//!
//! **Generalized conics** (Def. 6.3, Ball's rational cubics with an inflection). In P the
//! configuration is *convex* when `t0` and `t3` (both pointing to the other end) lie on the same
//! side of the chord line (then the tangent lines meet, on that side; the curve's own
//! direction at `b3` is `−t3`, so the text's "opposite half-planes" is this case); otherwise
//! the text reflects the tangents in the chord and carries the construction out "in both
//! half-planes" without giving the recipe (Fig. 6.6 is lost). **Deviation (NOTES E.2.6
//! proposal):** the lengths `L01, L32` and the weight are those of the reflected, convex
//! configuration (the unsigned angles α, β), applied along the original `t0, t3`; the result
//! is a rational cubic with one inflection, and it equals the conic where α or β passes 0.
//!
//! **Degenerate data (documented choices, never a panic).** `n0+n3` parallel to the chord or
//! zero (`n0 = −n3`): P is the plane containing the chord and `n0` (NOTES E.2.1), else `n3`,
//! else any plane through the chord. A tangent that cannot be formed (normal perpendicular to
//! P) is the chord direction; a tangent perpendicular to the chord takes the sense that makes
//! the configuration convex (a semicircle from a diameter's end normals). Angles with `α + β ≤ 1e-9` (both tangents along the chord,
//! e.g. flat data) are taken as `α = β`: the uniformly parametrised segment (the limit of the
//! text's formula depends on how α, β → 0, so rounding would otherwise pick the handles).
//! `b0 = b3`: the constant curve.
//!
//! **Collapsing handles (deviation, optional).** The handle at `b0` is `∝ sin β`: when the
//! tangent at `b3` lies along the chord (β → 0, α not) the conic degenerates to its chord
//! with a zero handle at `b0`, whose tangent is then no longer honoured in the limit, and
//! where β changes side (convex ↔ generalized conic) the unsigned angle makes the handle,
//! and every surface built from it, only C⁰ (a fold on real meshes). With a **handle floor**
//! κ > 0 the shape ratios `r = sin β / cos(γ/2)` (1 for an isosceles configuration) below
//! `2κ` are replaced by `κ + r²/(4κ)` (C¹, even in β, never below κ): circles (r = 1) and
//! every configuration with `r ≥ 2κ` keep the text's conic exactly. κ = 0 is the text.
//! The floor alone leaves a kink: the *other* handle `∝ sin α / cos(γ/2)` and the weight
//! depend on the unsigned β, and change slope by O(1/α) where β changes side. So with κ > 0
//! an angle x below `c = 0.25` times the larger angle M is also softened to
//! `(x² + c²M²)/(2cM)` (C¹, even, at least cM/2): isosceles configurations (circles, sphere
//! data) and every configuration with both angles within a factor 4 are untouched.
//!
//! **The boundary normal.** Along a curve the surface normal `n^S(t)` must be perpendicular to
//! `ċ(t)` (6.13) and make a prescribed angle with the conic's in-plane normal `n^C(t)`; the text
//! interpolates the cosine linearly (6.16). Because P contains `n0+n3`, the out-of-plane parts of
//! `n0` and `n3` are equal and opposite, so a linear cosine forces a sign jump of `n^S`
//! (NOTES E.3.2). **Deviation (NOTES E.3.2 fix):** the *signed rotation angle* of `n^S` about
//! the unit tangent `T`, measured from `n^C`, is interpolated: `φ(t) = (1−t)φ0 + tφ1`,
//! `n^S = cos φ n^C + sin φ (T × n^C)`, with `φ0`, `φ1` the angles of `n0`, `n3`. It equals
//! the text's whenever the normals lie in P (spheres, circles). `n^C = σ T×m` with the sign σ
//! fixed once per curve so that `n^C` leans towards the end normals.
//!
//! O(1) per construction and per evaluation.

use super::dual::{v3, Dual, D3};
use super::SmoothError;
use crate::geom::vec;

type P3 = [f64; 3];

/// Below this `|x|`, a cross product counts as zero (inputs are unit vectors).
const TINY: f64 = 1e-12;
/// With a handle floor, angles below this fraction of the larger one are softened.
const SOFT_ANGLE: f64 = 0.25;
/// `α + β` at or below this: both tangents along the chord (module doc).
const STRAIGHT: f64 = 1e-9;

/// A degree-elevated conic or generalized conic: a planar rational cubic Bézier curve.
///
/// ```
/// use morpho::smooth::Conic;
/// // a quarter of the unit circle from its points and outward normals
/// let (a, b) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
/// let c = Conic::new(a, a, b, b, 1.0).unwrap();
/// for k in 0..=10 {
///     let p = c.eval(k as f64 / 10.0);
///     assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-14);
/// }
/// assert!(c.convex);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conic {
    /// `b0, b1, b2, b3`.
    pub control: [P3; 4],
    /// `1, (1+2ω)/3, (1+2ω)/3, 1` (the degree-elevated weights).
    pub weights: [f64; 4],
    /// The weight ω of the quadratic conic: `τ sin(γ/2)` (Thm 6.3 times the tension).
    pub omega: f64,
    /// Unit normal `m` of the curve's plane P.
    pub plane_normal: P3,
    /// Unit end tangents: `t0` at `b0` pointing along the chord, `t3` at `b3` pointing back.
    pub tangents: [P3; 2],
    /// The angles α (at `b0`) and β (at `b3`) between the tangents and the chord, in [0, π/2].
    pub angles: [f64; 2],
    /// `false` for a non-convex configuration (Def. 6.3): a generalized conic with an
    /// inflection.
    pub convex: bool,
}

fn unit(v: P3) -> Option<P3> {
    let l = vec::norm(v);
    (l > TINY && l.is_finite()).then(|| vec::scale(v, 1.0 / l))
}

/// Any unit vector perpendicular to the unit vector `d`.
fn perpendicular(d: P3) -> P3 {
    let k = (0..3)
        .min_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    unit(vec::cross(d, e)).unwrap_or([0.0, 0.0, 1.0])
}

impl Conic {
    /// The conic from `b0` (normal `n0`) to `b3` (normal `n3`) with tension `tension` (1 = the
    /// automatic weight of Thm 6.3). Normals need not be unit; they are normalised.
    ///
    /// Errors: a non-finite coordinate ([`SmoothError::NonFinite`], index 0 or 1 for `b0`,
    /// `b3`), a zero or non-finite normal ([`SmoothError::BadNormal`], vertex 0 or 1), a tension
    /// that is not positive and finite ([`SmoothError::Parameter`]).
    pub fn new(b0: P3, n0: P3, b3: P3, n3: P3, tension: f64) -> Result<Conic, SmoothError> {
        for (index, p) in [b0, b3].iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(SmoothError::NonFinite { index });
            }
        }
        let mut n = [[0.0; 3]; 2];
        for (vertex, v) in [n0, n3].iter().enumerate() {
            let l = vec::norm(*v);
            if !(l > 0.0 && l.is_finite()) {
                return Err(SmoothError::BadNormal { vertex });
            }
            n[vertex] = vec::scale(*v, 1.0 / l);
        }
        check_tension(tension)?;
        Ok(Conic::build(b0, n[0], b3, n[1], tension, 0.0))
    }

    /// [`Conic::new`] with the handle floor κ of the module doc ("collapsing handles"):
    /// shape ratios below `2κ` are replaced by `κ + r²/(4κ)`; `floor = 0` is the text's conic.
    /// Errors as [`Conic::new`], and a floor outside [0, 0.5] ([`SmoothError::Parameter`]).
    pub fn with_floor(
        b0: P3,
        n0: P3,
        b3: P3,
        n3: P3,
        tension: f64,
        floor: f64,
    ) -> Result<Conic, SmoothError> {
        check_floor(floor)?;
        let c = Conic::new(b0, n0, b3, n3, tension)?;
        let [n0, n3] = [n0, n3].map(|v| vec::scale(v, 1.0 / vec::norm(v)));
        Ok(Conic::build(
            c.control[0],
            n0,
            c.control[3],
            n3,
            tension,
            floor,
        ))
    }

    /// The construction of the module doc for unit normals and a valid tension.
    pub(crate) fn build(b0: P3, n0: P3, b3: P3, n3: P3, tension: f64, floor: f64) -> Conic {
        let chord = vec::sub(b3, b0);
        let len = vec::norm(chord);
        let Some(d) = unit(chord).filter(|_| len > 0.0) else {
            let m = perpendicular(unit(n0).unwrap_or([1.0, 0.0, 0.0]));
            return Conic {
                control: [b0; 4],
                weights: [1.0; 4],
                omega: tension,
                plane_normal: m,
                tangents: [[0.0; 3]; 2],
                angles: [0.0; 2],
                convex: true,
            };
        };
        let m = unit(vec::cross(d, vec::add(n0, n3)))
            .or_else(|| unit(vec::cross(d, n0)))
            .or_else(|| unit(vec::cross(d, n3)))
            .unwrap_or_else(|| perpendicular(d));
        let mut t0 = unit(vec::cross(m, n0)).unwrap_or(d);
        if vec::dot(t0, d) < 0.0 {
            t0 = vec::scale(t0, -1.0);
        }
        let mut t3 = unit(vec::cross(m, n3)).unwrap_or(vec::scale(d, -1.0));
        if vec::dot(t3, d) > 0.0 {
            t3 = vec::scale(t3, -1.0);
        }
        // in-plane frame (d, y): t0 = (cos α, ±sin α), t3 = (−cos β, ±sin β)
        let y = vec::cross(m, d);
        let (mut s0, mut s3) = (vec::dot(t0, y), vec::dot(t3, y));
        // a tangent perpendicular to the chord has no preferred sense: take the convex one
        if s0 * s3 < 0.0 {
            if vec::dot(t0, d).abs() <= TINY {
                (t0, s0) = (vec::scale(t0, -1.0), -s0);
            } else if vec::dot(t3, d).abs() <= TINY {
                (t3, s3) = (vec::scale(t3, -1.0), -s3);
            }
        }
        let mut alpha = s0.abs().atan2(vec::dot(t0, d));
        let mut beta = s3.abs().atan2(-vec::dot(t3, d));
        if alpha + beta <= STRAIGHT {
            (alpha, beta) = (0.0, 0.0);
        } else if floor > 0.0 {
            // the unsigned angle has a kink where a tangent crosses the chord (module doc)
            let m = alpha.max(beta) * SOFT_ANGLE;
            let soft = |x: f64| {
                if x >= m {
                    x
                } else {
                    (x * x + m * m) / (2.0 * m)
                }
            };
            (alpha, beta) = (soft(alpha), soft(beta));
        }
        let half = 0.5 * (alpha + beta); // (π − γ)/2: cos(γ/2) = sin(half)
        let omega = tension * half.cos();
        let (ra, rb) = if half == 0.0 {
            (1.0, 1.0)
        } else {
            (alpha.sin() / half.sin(), beta.sin() / half.sin())
        };
        let soft = |r: f64| {
            if floor > 0.0 && r < 2.0 * floor {
                floor + r * r / (4.0 * floor)
            } else {
                r
            }
        };
        let (ra, rb) = (soft(ra), soft(rb));
        let l01 = tension * rb / (1.0 + 2.0 * omega) * len;
        let l32 = tension * ra / (1.0 + 2.0 * omega) * len;
        let w = (1.0 + 2.0 * omega) / 3.0;
        Conic {
            control: [
                b0,
                vec::add_scaled(b0, l01, t0),
                vec::add_scaled(b3, l32, t3),
                b3,
            ],
            weights: [1.0, w, w, 1.0],
            omega,
            plane_normal: m,
            tangents: [t0, t3],
            angles: [alpha, beta],
            convex: s0 * s3 >= 0.0,
        }
    }

    /// `(P(t), w(t), P'(t), w'(t))` of the homogeneous curve `P = Σ ωᵢ bᵢ B³ᵢ`, `w = Σ ωᵢ B³ᵢ`.
    fn homogeneous(&self, t: f64) -> (P3, f64, P3, f64) {
        let s = 1.0 - t;
        let b = [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t];
        let db = [s * s, 2.0 * t * s, t * t];
        let (mut p, mut w) = ([0.0; 3], 0.0);
        for i in 0..4 {
            p = vec::add_scaled(p, b[i] * self.weights[i], self.control[i]);
            w += b[i] * self.weights[i];
        }
        let (mut dp, mut dw) = ([0.0; 3], 0.0);
        for i in 0..3 {
            let a = vec::sub(
                vec::scale(self.control[i + 1], self.weights[i + 1]),
                vec::scale(self.control[i], self.weights[i]),
            );
            dp = vec::add_scaled(dp, 3.0 * db[i], a);
            dw += 3.0 * db[i] * (self.weights[i + 1] - self.weights[i]);
        }
        (p, w, dp, dw)
    }

    /// `c(t)`, `t ∈ [0, 1]` (6.5); exactly `b0` at 0 and `b3` at 1.
    pub fn eval(&self, t: f64) -> P3 {
        if t <= 0.0 {
            return self.control[0];
        }
        if t >= 1.0 {
            return self.control[3];
        }
        let (p, w, _, _) = self.homogeneous(t);
        vec::scale(p, 1.0 / w)
    }

    /// `ċ(t) = (P' − c w')/w`.
    pub fn derivative(&self, t: f64) -> P3 {
        let (p, w, dp, dw) = self.homogeneous(t.clamp(0.0, 1.0));
        let c = vec::scale(p, 1.0 / w);
        vec::scale(vec::add_scaled(dp, -dw, c), 1.0 / w)
    }

    /// The unit tangent in the curve's direction; at the ends with a non-zero handle the
    /// construction's `t0`, `−t3` (the direction of `ċ`, free of the rounding of short
    /// handles stored as absolute coordinates); where `ċ` vanishes (a zero handle) the end
    /// tangent of the nearer end.
    pub fn unit_tangent(&self, t: f64) -> P3 {
        if t <= 0.0 && self.control[1] != self.control[0] {
            return self.tangents[0];
        }
        if t >= 1.0 && self.control[2] != self.control[3] {
            return vec::scale(self.tangents[1], -1.0);
        }
        let scale = vec::dist(self.control[0], self.control[3]);
        let d = self.derivative(t);
        let l = vec::norm(d);
        if l > 1e-12 * scale && l.is_finite() {
            vec::scale(d, 1.0 / l)
        } else if t < 0.5 {
            self.tangents[0]
        } else {
            vec::scale(self.tangents[1], -1.0)
        }
    }
}

/// A [`Conic`] over [`Dual`] numbers: control points and weights with their partials along two
/// directions (the side-vertex surface's radial conics, whose ends move with the surface
/// point). Built by [`Conic::build_dual`], which mirrors [`Conic::build`] operation for
/// operation, so the value parts equal the `f64` construction's.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DualConic {
    pub control: [D3; 4],
    pub weights: [Dual; 4],
    pub tangents: [D3; 2],
}

fn unit_dual(v: D3) -> Option<D3> {
    let l = v3::norm(v);
    (l.v > TINY && l.v.is_finite()).then(|| v3::scale(v, Dual::c(1.0) / l))
}

impl Conic {
    /// [`Conic::build`] over dual numbers (value parts identical, derivatives by the chain
    /// rule). The branches are taken on the values; where the construction has a kink (the
    /// unsigned angles where a tangent crosses the chord, the fallbacks of degenerate data)
    /// the derivative is that of the branch the value selects.
    pub(crate) fn build_dual(
        b0: D3,
        n0: D3,
        b3: D3,
        n3: D3,
        tension: f64,
        floor: f64,
    ) -> DualConic {
        let chord = v3::sub(b3, b0);
        let len = v3::norm(chord);
        let Some(d) = unit_dual(chord).filter(|_| len.v > 0.0) else {
            return DualConic {
                control: [b0; 4],
                weights: [Dual::c(1.0); 4],
                tangents: [v3::c([0.0; 3]); 2],
            };
        };
        let m = unit_dual(v3::cross(d, v3::add(n0, n3)))
            .or_else(|| unit_dual(v3::cross(d, n0)))
            .or_else(|| unit_dual(v3::cross(d, n3)))
            .unwrap_or_else(|| v3::c(perpendicular(v3::val(d))));
        let mut t0 = unit_dual(v3::cross(m, n0)).unwrap_or(d);
        if v3::dot(t0, d).v < 0.0 {
            t0 = v3::scale_f(t0, -1.0);
        }
        let mut t3 = unit_dual(v3::cross(m, n3)).unwrap_or(v3::scale_f(d, -1.0));
        if v3::dot(t3, d).v > 0.0 {
            t3 = v3::scale_f(t3, -1.0);
        }
        let y = v3::cross(m, d);
        let (mut s0, mut s3) = (v3::dot(t0, y), v3::dot(t3, y));
        if s0.v * s3.v < 0.0 {
            if v3::dot(t0, d).v.abs() <= TINY {
                (t0, s0) = (v3::scale_f(t0, -1.0), -s0);
            } else if v3::dot(t3, d).v.abs() <= TINY {
                (t3, s3) = (v3::scale_f(t3, -1.0), -s3);
            }
        }
        let mut alpha = s0.abs().atan2(v3::dot(t0, d));
        let mut beta = s3.abs().atan2(-v3::dot(t3, d));
        if alpha.v + beta.v <= STRAIGHT {
            (alpha, beta) = (Dual::c(0.0), Dual::c(0.0));
        } else if floor > 0.0 {
            let m = SOFT_ANGLE * alpha.max(beta);
            let soft = |x: Dual| {
                if x.v >= m.v {
                    x
                } else {
                    (x * x + m * m) / (2.0 * m)
                }
            };
            (alpha, beta) = (soft(alpha), soft(beta));
        }
        let half = 0.5 * (alpha + beta);
        let omega = tension * half.cos();
        let (ra, rb) = if half.v == 0.0 {
            (Dual::c(1.0), Dual::c(1.0))
        } else {
            (alpha.sin() / half.sin(), beta.sin() / half.sin())
        };
        let soft = |r: Dual| {
            if floor > 0.0 && r.v < 2.0 * floor {
                Dual::c(floor) + r * r / Dual::c(4.0 * floor)
            } else {
                r
            }
        };
        let (ra, rb) = (soft(ra), soft(rb));
        let e = Dual::c(1.0) + 2.0 * omega;
        let l01 = tension * rb / e * len;
        let l32 = tension * ra / e * len;
        let w = e / Dual::c(3.0);
        DualConic {
            control: [
                b0,
                v3::add_scaled(b0, l01, t0),
                v3::add_scaled(b3, l32, t3),
                b3,
            ],
            weights: [Dual::c(1.0), w, w, Dual::c(1.0)],
            tangents: [t0, t3],
        }
    }
}

impl DualConic {
    /// The constant lift of `c` (zero partials).
    pub fn lift(c: &Conic) -> DualConic {
        DualConic {
            control: c.control.map(v3::c),
            weights: c.weights.map(Dual::c),
            tangents: c.tangents.map(v3::c),
        }
    }

    /// [`Conic::homogeneous`] at a dual parameter.
    fn homogeneous(&self, t: Dual) -> (D3, Dual, D3, Dual) {
        let s = Dual::c(1.0) - t;
        let b = [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t];
        let db = [s * s, 2.0 * t * s, t * t];
        let (mut p, mut w) = (v3::c([0.0; 3]), Dual::c(0.0));
        for i in 0..4 {
            p = v3::add_scaled(p, b[i] * self.weights[i], self.control[i]);
            w = w + b[i] * self.weights[i];
        }
        let (mut dp, mut dw) = (v3::c([0.0; 3]), Dual::c(0.0));
        for i in 0..3 {
            let a = v3::sub(
                v3::scale(self.control[i + 1], self.weights[i + 1]),
                v3::scale(self.control[i], self.weights[i]),
            );
            dp = v3::add_scaled(dp, 3.0 * db[i], a);
            dw = dw + 3.0 * db[i] * (self.weights[i + 1] - self.weights[i]);
        }
        (p, w, dp, dw)
    }

    /// `c(t)` for `t ∈ [0, 1]` with its partials; no shortcut at the ends (the partials there
    /// include the end tangent times `∂t`), the value there is exactly `b0` or `b3`.
    pub fn eval(&self, t: Dual) -> D3 {
        let (p, w, _, _) = self.homogeneous(t);
        v3::scale(p, Dual::c(1.0) / w)
    }

    /// [`Conic::unit_tangent`] at a dual parameter inside (0, 1) (at the ends and where `ċ`
    /// vanishes: the constant end tangent).
    pub fn unit_tangent(&self, t: Dual, scale: f64) -> D3 {
        let (p, w, dp, dw) = self.homogeneous(t);
        let c = v3::scale(p, Dual::c(1.0) / w);
        let d = v3::scale(v3::add_scaled(dp, -dw, c), Dual::c(1.0) / w);
        let l = v3::norm(d);
        if t.v > 0.0 && t.v < 1.0 && l.v > 1e-12 * scale && l.v.is_finite() {
            v3::scale(d, Dual::c(1.0) / l)
        } else if t.v < 0.5 {
            self.tangents[0]
        } else {
            v3::scale_f(self.tangents[1], -1.0)
        }
    }
}

impl ConicEdge {
    /// The point `c(t)` and the boundary normal `n^S(t)` ([`ConicEdge::normal`]) at a dual
    /// parameter, with their partials; at `t ≤ 0` or `t ≥ 1` the normal is the constant end
    /// normal (its partials are not needed there: the side-vertex weights of such a block
    /// vanish to first order).
    pub(crate) fn eval_dual(&self, t: Dual) -> (D3, D3) {
        let c = DualConic::lift(&self.conic);
        let p = c.eval(t);
        if t.v <= 0.0 {
            return (p, v3::c(self.end_normals[0]));
        }
        if t.v >= 1.0 {
            return (p, v3::c(self.end_normals[1]));
        }
        let scale = vec::dist(self.conic.control[0], self.conic.control[3]);
        let tan = c.unit_tangent(t, scale);
        let m = v3::c(self.conic.plane_normal);
        let nc = v3::scale_f(v3::cross(tan, m), self.sigma);
        let phi = (Dual::c(1.0) - t) * Dual::c(self.phi[0]) + t * Dual::c(self.phi[1]);
        let n = v3::add(
            v3::scale(nc, phi.cos()),
            v3::scale(v3::cross(tan, nc), phi.sin()),
        );
        (p, n)
    }
}

/// `Err(Parameter)` unless `0 ≤ floor ≤ 0.5`.
pub(crate) fn check_floor(floor: f64) -> Result<(), SmoothError> {
    if (0.0..=0.5).contains(&floor) {
        Ok(())
    } else {
        Err(SmoothError::Parameter {
            what: format!("handle floor {floor} is not in [0, 0.5]"),
        })
    }
}

/// `Err(Parameter)` unless `0 < tension ≤ 1e6` (and finite).
pub(crate) fn check_tension(tension: f64) -> Result<(), SmoothError> {
    if tension > 0.0 && tension <= 1e6 {
        Ok(())
    } else {
        Err(SmoothError::Parameter {
            what: format!("tension {tension} is not in (0, 1e6]"),
        })
    }
}

/// A boundary curve of the side-vertex surface: the conic between two vertices and the
/// surface normal `n^S(t)` along it (module doc, "the boundary normal").
///
/// ```
/// use morpho::smooth::ConicEdge;
/// let s = 0.5f64.sqrt();
/// let (a, b) = ([1.0, 0.0, 0.0], [0.0, s, s]);
/// let e = ConicEdge::new(a, a, b, b, 1.0).unwrap();
/// // sphere data: the boundary normal is the radial direction
/// let (p, n) = (e.conic.eval(0.3), e.normal(0.3));
/// let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
/// assert!((r - 1.0).abs() < 1e-14);
/// assert!((0..3).all(|k| (n[k] - p[k]).abs() < 1e-14));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConicEdge {
    /// The curve.
    pub conic: Conic,
    /// `+1` or `−1`: the sign of `n^C = σ T × m`.
    pub sigma: f64,
    /// The rotation angles `φ0`, `φ1` of the end normals about the tangent, from `n^C`.
    pub phi: [f64; 2],
    /// The unit end normals (interpolated exactly at `t = 0, 1`).
    pub end_normals: [P3; 2],
}

impl ConicEdge {
    /// The boundary curve from `b0` (normal `n0`) to `b3` (normal `n3`); errors as
    /// [`Conic::new`].
    pub fn new(b0: P3, n0: P3, b3: P3, n3: P3, tension: f64) -> Result<ConicEdge, SmoothError> {
        let c = Conic::new(b0, n0, b3, n3, tension)?;
        let n = [n0, n3].map(|v| vec::scale(v, 1.0 / vec::norm(v)));
        Ok(ConicEdge::from_conic(c, n[0], n[1]))
    }

    pub(crate) fn from_conic(conic: Conic, n0: P3, n3: P3) -> ConicEdge {
        let m = conic.plane_normal;
        let (ta, tb) = (conic.unit_tangent(0.0), conic.unit_tangent(1.0));
        let lean = vec::dot(vec::cross(ta, m), n0) + vec::dot(vec::cross(tb, m), n3);
        let sigma = if lean < 0.0 { -1.0 } else { 1.0 };
        let angle = |t: P3, n: P3| {
            let nc = vec::scale(vec::cross(t, m), sigma);
            vec::dot(n, vec::cross(t, nc)).atan2(vec::dot(n, nc))
        };
        ConicEdge {
            conic,
            sigma,
            phi: [angle(ta, n0), angle(tb, n3)],
            end_normals: [n0, n3],
        }
    }

    /// The in-plane unit normal `n^C(t) = σ T(t) × m`.
    pub fn curve_normal(&self, t: f64) -> P3 {
        vec::scale(
            vec::cross(self.conic.unit_tangent(t), self.conic.plane_normal),
            self.sigma,
        )
    }

    /// The surface normal `n^S(t)`: perpendicular to `ċ(t)` (6.13), rotated from `n^C(t)` about
    /// the tangent by the interpolated angle; exactly the end normals at `t = 0, 1`.
    pub fn normal(&self, t: f64) -> P3 {
        if t <= 0.0 {
            return self.end_normals[0];
        }
        if t >= 1.0 {
            return self.end_normals[1];
        }
        let tan = self.conic.unit_tangent(t);
        let nc = vec::scale(vec::cross(tan, self.conic.plane_normal), self.sigma);
        let phi = (1.0 - t) * self.phi[0] + t * self.phi[1];
        vec::add(
            vec::scale(nc, phi.cos()),
            vec::scale(vec::cross(tan, nc), phi.sin()),
        )
    }
}

/// The side-vertex blending weights (Thm 6.1 with the squares of NOTES E.1):
/// `wᵢ(u) = (u_j u_k)² / ((u1u2)² + (u2u3)² + (u3u1)²)`; at a vertex (where they are 0/0) the
/// vertex's own weight is 1. They satisfy (i) `Σ wᵢ = 1`, (ii) `wᵢ = δᵢₖ` on edge `e_k` and
/// (iii) a zero derivative of `wᵢ` across `eᵢ`. The printed (6.2) without the squares violates
/// (iii) (its derivative across `e₁` is `−1/(u2u3)`).
///
/// ```
/// use morpho::smooth::side_vertex_weights;
/// assert_eq!(side_vertex_weights([0.0, 0.3, 0.7]), [1.0, 0.0, 0.0]);
/// let w = side_vertex_weights([0.2, 0.3, 0.5]);
/// assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
/// ```
pub fn side_vertex_weights(u: [f64; 3]) -> [f64; 3] {
    let q = [
        (u[1] * u[2]).powi(2),
        (u[2] * u[0]).powi(2),
        (u[0] * u[1]).powi(2),
    ];
    let s = q[0] + q[1] + q[2];
    if s > 0.0 && s.is_finite() {
        q.map(|x| x / s)
    } else {
        let k = (0..3).max_by(|&a, &b| u[a].total_cmp(&u[b])).unwrap_or(0);
        let mut w = [0.0; 3];
        w[k] = 1.0;
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_data_gives_the_uniform_segment() {
        let n = [0.0, 0.0, 1.0];
        let c = Conic::build([0.0; 3], n, [3.0, 0.0, 0.0], n, 1.0, 0.0);
        assert_eq!(c.weights, [1.0; 4]);
        for k in 0..=6 {
            let t = k as f64 / 6.0;
            let p = c.eval(t);
            assert!((p[0] - 3.0 * t).abs() < 1e-14 && p[1].abs() < 1e-14 && p[2].abs() < 1e-14);
        }
    }

    #[test]
    fn opposite_normals_and_coincident_ends_do_not_panic() {
        let c = Conic::build(
            [0.0; 3],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, -1.0],
            1.0,
            0.0,
        );
        assert!(c.eval(0.5).iter().all(|x| x.is_finite()));
        let c = Conic::build(
            [1.0; 3],
            [0.0, 0.0, 1.0],
            [1.0; 3],
            [0.0, 1.0, 0.0],
            1.0,
            0.0,
        );
        assert_eq!(c.eval(0.5), [1.0; 3]);
        let c = Conic::build(
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            1.0,
            0.0,
        );
        assert!(c.eval(0.5).iter().all(|x| x.is_finite()));
    }

    #[test]
    fn semicircle_from_parallel_tangents() {
        let c = Conic::build(
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            1.0,
            0.0,
        );
        for k in 1..10 {
            let p = c.eval(k as f64 / 10.0);
            assert!((vec::norm(p) - 1.0).abs() < 1e-14, "{p:?}");
        }
    }

    #[test]
    fn inflection_when_the_tangents_point_to_different_sides() {
        let s = 0.5f64.sqrt();
        let c = Conic::build(
            [0.0; 3],
            [-s, s, 0.0],
            [1.0, 0.0, 0.0],
            [-s, s, 0.0],
            1.0,
            0.0,
        );
        assert!(!c.convex);
        // the curve crosses its chord: an S
        let (a, b) = (c.eval(0.25)[1], c.eval(0.75)[1]);
        assert!(a * b < 0.0, "{a} {b}");
    }
}
