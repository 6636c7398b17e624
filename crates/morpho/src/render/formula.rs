//! The trivariate functions of Hamann's figures (1991, §2.2), given by formula, so the views
//! can be drawn from the exact function instead of samples (notes part F.1):
//!
//! - [`Formula::HamannExp`]: `f = 15 (e^{−0.005 |x − (10,10,10)|²} + e^{−0.0025 |x − (15,20,20)|²}
//!   + e^{−0.005 |x − (25,25,25)|²})` on `[0, 39]³` (Figs 2.2, 2.3 and 2.9);
//! - [`Formula::HamannCos`]: `f = cos(2 |x|)` over the partial unit ball
//!   `(u cos v, u sin v cos w, u sin v sin w)`, `u ∈ [0, 1]`, `v ∈ [0, π]`, `w ∈ [0, 3π/2]`
//!   (Fig. 2.4: a curvilinear volume; the sub-boxes are laid out in uvw-space and mapped).
//!
//! Cost: O(1) per evaluation; [`Formula::sample`] is O(n³).

use super::RenderError;
use crate::volume::Volume;
use std::f64::consts::PI;

/// A function given by formula, with its parameter box and its map to xyz-space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Formula {
    /// The sum of three Gaussians of Figs 2.2, 2.3 and 2.9 on `[0, 39]³`.
    HamannExp,
    /// `cos(2 sqrt(x² + y² + z²))` over the partial unit ball of Fig. 2.4.
    HamannCos,
}

impl Formula {
    /// Every formula, for listings.
    pub const ALL: [Formula; 2] = [Formula::HamannExp, Formula::HamannCos];

    /// The name accepted by [`std::str::FromStr`].
    pub fn name(self) -> &'static str {
        match self {
            Formula::HamannExp => "hamann-exp",
            Formula::HamannCos => "hamann-cos",
        }
    }

    /// The function value at the point `p` of xyz-space.
    ///
    /// ```
    /// use morpho::render::Formula;
    /// let f = Formula::HamannCos.eval([0.0, 0.0, 0.0]);
    /// assert_eq!(f, 1.0);
    /// ```
    pub fn eval(self, p: [f64; 3]) -> f64 {
        match self {
            Formula::HamannExp => {
                let g = |c: [f64; 3], a: f64| {
                    let d2 = (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2);
                    (-a * d2).exp()
                };
                15.0 * (g([10.0; 3], 0.005) + g([15.0, 20.0, 20.0], 0.0025) + g([25.0; 3], 0.005))
            }
            Formula::HamannCos => (2.0 * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).cos(),
        }
    }

    /// The parameter box (uvw-space) of the domain: `[0, 39]³` for the exponential function,
    /// `[0, 1] × [0, π] × [0, 3π/2]` for the partial ball.
    pub fn param_box(self) -> ([f64; 3], [f64; 3]) {
        match self {
            Formula::HamannExp => ([0.0; 3], [39.0; 3]),
            Formula::HamannCos => ([0.0; 3], [1.0, PI, 1.5 * PI]),
        }
    }

    /// The map from uvw-space to xyz-space (the identity for box domains).
    pub fn map(self, uvw: [f64; 3]) -> [f64; 3] {
        match self {
            Formula::HamannExp => uvw,
            Formula::HamannCos => {
                let [u, v, w] = uvw;
                [u * v.cos(), u * v.sin() * w.cos(), u * v.sin() * w.sin()]
            }
        }
    }

    /// The bounding box of the domain in xyz-space.
    pub fn bounds(self) -> ([f64; 3], [f64; 3]) {
        match self {
            Formula::HamannExp => self.param_box(),
            Formula::HamannCos => ([-1.0; 3], [1.0; 3]),
        }
    }

    /// True when `p` lies in the domain (the partial ball: `|p| ≤ 1` and the angle `w` of
    /// `(y, z)` in `[0, 3π/2]`).
    pub fn contains(self, p: [f64; 3]) -> bool {
        match self {
            Formula::HamannExp => p.iter().all(|&c| (0.0..=39.0).contains(&c)),
            Formula::HamannCos => {
                let r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
                let w = p[2].atan2(p[1]);
                let w = if w < 0.0 { w + 2.0 * PI } else { w };
                r2 <= 1.0 + 1e-12 && (w <= 1.5 * PI + 1e-12 || p[1].hypot(p[2]) < 1e-12)
            }
        }
    }

    /// The function sampled on `(n+1)³` points of its xyz bounding box (NaN outside the
    /// domain), as a rectilinear volume (Hamann's rectilinear data, Def. 2.1). `n ≥ 1`.
    ///
    /// ```
    /// use morpho::render::Formula;
    /// let v = Formula::HamannExp.sample(8).unwrap();
    /// assert_eq!(v.dims, [9, 9, 9]);
    /// ```
    pub fn sample(self, n: usize) -> Result<Volume, RenderError> {
        if n == 0 || n > 1024 {
            return Err(RenderError::GridSize { n });
        }
        let (lo, hi) = self.bounds();
        Ok(Volume::from_fn([n + 1; 3], lo, hi, |x, y, z| {
            if self.contains([x, y, z]) {
                self.eval([x, y, z])
            } else {
                f64::NAN
            }
        }))
    }
}

impl std::str::FromStr for Formula {
    type Err = RenderError;
    fn from_str(s: &str) -> Result<Formula, RenderError> {
        Formula::ALL
            .into_iter()
            .find(|f| f.name() == s.trim().to_ascii_lowercase())
            .ok_or_else(|| RenderError::UnknownFunction {
                name: s.to_string(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ball_map_stays_in_domain() {
        let f = Formula::HamannCos;
        for u in [0.0, 0.5, 1.0] {
            for v in [0.0, 1.0, 3.0] {
                for w in [0.0, 2.0, 4.7] {
                    let p = f.map([u, v, w]);
                    assert!(f.contains(p), "{p:?}");
                }
            }
        }
        assert!(!f.contains([0.0, 0.5, -0.5]));
        assert!(f.contains([0.0, -0.5, -0.1]));
        assert_eq!("hamann-exp".parse::<Formula>().unwrap(), Formula::HamannExp);
        assert!("nope".parse::<Formula>().is_err());
    }
}
