//! The rating phase (Dorgerloh et al., §1): one number per triangle (tetrahedron) from the values
//! at its corners, and the black/white colouring by a threshold.
//!
//! Ratings: the mean (the paper's example), the minimum, the maximum, the median, and an
//! *area-weighted mean* in which each corner's value is weighted by the area of the sample's
//! region of influence — one third of the total area of its incident triangles (in 3D: one quarter
//! of the volume of its incident tetrahedra), so that an isolated sample counts more than one in
//! a dense cluster. O(n) time.

use super::dual::Valid;
use super::ContourError;
use crate::geom::{Point2, Point3};
use crate::Result;

/// How a triangle (tetrahedron) is rated from its corner values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Rating {
    /// Arithmetic mean of the corner values.
    #[default]
    Mean,
    /// Smallest corner value.
    Min,
    /// Largest corner value.
    Max,
    /// Median corner value (mean of the two middle values for a tetrahedron).
    Median,
    /// Mean weighted by each corner's share of the area (volume) of its incident simplices.
    AreaMean,
}

impl std::str::FromStr for Rating {
    type Err = ContourError;
    fn from_str(s: &str) -> Result<Self, ContourError> {
        Ok(match s.to_ascii_lowercase().as_str() {
            "mean" => Rating::Mean,
            "min" => Rating::Min,
            "max" => Rating::Max,
            "median" => Rating::Median,
            "area-mean" | "area_mean" | "areamean" => Rating::AreaMean,
            _ => {
                return Err(ContourError::UnknownRating {
                    name: s.to_string(),
                })
            }
        })
    }
}

fn check_values(values: &[f64], n: usize) -> Result<(), ContourError> {
    if values.len() != n {
        return Err(ContourError::ValueCount {
            values: values.len(),
            vertices: n,
        });
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(ContourError::NonFiniteValue { index: i });
    }
    Ok(())
}

fn rate<const K: usize>(corners: [f64; K], weights: Option<[f64; K]>, rating: Rating) -> f64 {
    match rating {
        Rating::Mean => corners.iter().sum::<f64>() / K as f64,
        Rating::Min => corners.iter().copied().fold(f64::INFINITY, f64::min),
        Rating::Max => corners.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        Rating::Median => {
            let mut c = corners;
            c.sort_by(|a, b| a.total_cmp(b));
            if K % 2 == 1 {
                c[K / 2]
            } else {
                0.5 * (c[K / 2 - 1] + c[K / 2])
            }
        }
        Rating::AreaMean => {
            let w = weights.unwrap_or([1.0; K]);
            let sw: f64 = w.iter().sum();
            if sw > 0.0 {
                corners
                    .iter()
                    .zip(w.iter())
                    .map(|(c, w)| c * w)
                    .sum::<f64>()
                    / sw
            } else {
                corners.iter().sum::<f64>() / K as f64
            }
        }
    }
}

/// Ratings of the triangles `tri` of `points` from the per-vertex `values`.
///
/// ```
/// use morpho::contour::{classify, rate_triangles, Rating};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0), Point2::new(1.0, 1.0)];
/// let r = rate_triangles(&[[0, 1, 2], [1, 3, 2]], &p, &[0.0, 3.0, 6.0, 9.0], Rating::Mean).unwrap();
/// assert_eq!(r, vec![3.0, 6.0]);
/// assert_eq!(classify(&r, 4.0, false), vec![false, true]); // black above 4
/// assert_eq!(classify(&r, 4.0, true), vec![true, false]); // black below 4
/// ```
pub fn rate_triangles(
    tri: &[[u32; 3]],
    points: &[Point2],
    values: &[f64],
    rating: Rating,
) -> Result<Vec<f64>, ContourError> {
    crate::contour::dual::check_indices(tri, points.len())?;
    rate_triangles_in_range(tri, points, values, rating)
}

/// [`rate_triangles`] on a triangulation `valid` vouches for (indices not re-checked).
pub(crate) fn rate_triangles_valid(
    tri: &[[u32; 3]],
    points: &[Point2],
    values: &[f64],
    rating: Rating,
    _valid: Valid,
) -> Result<Vec<f64>, ContourError> {
    rate_triangles_in_range(tri, points, values, rating)
}

/// [`rate_triangles`] once the indices are known to be in range.
fn rate_triangles_in_range(
    tri: &[[u32; 3]],
    points: &[Point2],
    values: &[f64],
    rating: Rating,
) -> Result<Vec<f64>, ContourError> {
    check_values(values, points.len())?;
    Ok(rate_simplices(tri, points.len(), values, rating, |t| {
        let [a, b, c] = t.map(|v| points[v as usize]);
        0.5 * ((b - a).perp(&(c - a))).abs()
    }))
}

/// Ratings of the tetrahedra `tets` of `points` from the per-vertex `values`.
pub fn rate_tetrahedra(
    tets: &[[u32; 4]],
    points: &[Point3],
    values: &[f64],
    rating: Rating,
) -> Result<Vec<f64>, ContourError> {
    crate::contour::dual::check_indices(tets, points.len())?;
    rate_tetrahedra_in_range(tets, points, values, rating)
}

/// [`rate_tetrahedra`] on a triangulation `valid` vouches for (indices not re-checked).
pub(crate) fn rate_tetrahedra_valid(
    tets: &[[u32; 4]],
    points: &[Point3],
    values: &[f64],
    rating: Rating,
    _valid: Valid,
) -> Result<Vec<f64>, ContourError> {
    rate_tetrahedra_in_range(tets, points, values, rating)
}

/// [`rate_tetrahedra`] once the indices are known to be in range.
fn rate_tetrahedra_in_range(
    tets: &[[u32; 4]],
    points: &[Point3],
    values: &[f64],
    rating: Rating,
) -> Result<Vec<f64>, ContourError> {
    check_values(values, points.len())?;
    Ok(rate_simplices(tets, points.len(), values, rating, |t| {
        let [a, b, c, d] = t.map(|v| points[v as usize]);
        ((b - a).cross(&(c - a)).dot(&(d - a)) / 6.0).abs()
    }))
}

/// Rates every simplex (indices already checked). For the area-weighted mean each corner is
/// weighted by 1/K of the `measure` (area or volume) of its incident simplices.
fn rate_simplices<const K: usize>(
    simplices: &[[u32; K]],
    n: usize,
    values: &[f64],
    rating: Rating,
    measure: impl Fn(&[u32; K]) -> f64,
) -> Vec<f64> {
    let weights = (rating == Rating::AreaMean).then(|| {
        let mut w = vec![0.0; n];
        for t in simplices {
            let m = measure(t) / K as f64;
            for &v in t {
                w[v as usize] += m;
            }
        }
        w
    });
    simplices
        .iter()
        .map(|t| {
            let c = t.map(|v| values[v as usize]);
            let wt = weights.as_ref().map(|w| t.map(|v| w[v as usize]));
            rate(c, wt, rating)
        })
        .collect()
}

/// Black (`true`) where the rating is strictly above `threshold`, or strictly below it when
/// `below` is set.
pub fn classify(ratings: &[f64], threshold: f64, below: bool) -> Vec<bool> {
    ratings
        .iter()
        .map(|&r| if below { r < threshold } else { r > threshold })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratings_of_one_triangle() {
        let p = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
        ];
        let t = [[0, 1, 2]];
        let v = [1.0, 5.0, 3.0];
        let r = |k| rate_triangles(&t, &p, &v, k).unwrap()[0];
        assert_eq!(r(Rating::Mean), 3.0);
        assert_eq!(r(Rating::Min), 1.0);
        assert_eq!(r(Rating::Max), 5.0);
        assert_eq!(r(Rating::Median), 3.0);
        assert!((r(Rating::AreaMean) - 3.0).abs() < 1e-12);
        assert_eq!(classify(&[1.0, 2.0, 3.0], 2.0, false), [false, false, true]);
        assert_eq!(classify(&[1.0, 2.0, 3.0], 2.0, true), [true, false, false]);
    }

    #[test]
    fn area_mean_weights_sparse_samples() {
        // Weights are one third of the incident areas: w0 = a0/3, w1 = w2 = (a0+a1)/3, w3 = a1/3.
        let p = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
            Point2::new(10.0, 10.0),
        ];
        let t = [[0, 1, 2], [1, 3, 2]];
        let v = [0.0, 0.0, 0.0, 1.0];
        let r = rate_triangles(&t, &p, &v, Rating::AreaMean).unwrap();
        let (a0, a1) = (0.5, 9.5);
        let expect = a1 / (a1 + 2.0 * (a0 + a1));
        assert!((r[1] - expect).abs() < 1e-12, "{r:?}");
        assert_eq!(r[0], 0.0);
    }

    #[test]
    fn tetra_median_and_errors() {
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ];
        let t = [[0, 1, 2, 3]];
        let r = rate_tetrahedra(&t, &p, &[4.0, 1.0, 3.0, 2.0], Rating::Median).unwrap();
        assert_eq!(r[0], 2.5);
        assert!(rate_tetrahedra(&t, &p, &[1.0, f64::NAN, 0.0, 0.0], Rating::Mean).is_err());
        assert!(rate_tetrahedra(&t, &p, &[1.0], Rating::Mean).is_err());
        assert!(rate_tetrahedra(&[[0, 1, 2, 9]], &p, &[0.0; 4], Rating::Mean).is_err());
        assert!("area-mean".parse::<Rating>().is_ok());
        assert!("mode".parse::<Rating>().is_err());
    }
}
