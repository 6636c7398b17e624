//! Colour maps for scalar values: perceptual sequential (viridis), diverging (coolwarm), greys.
//!
//! Hamann (1991, §2.2) maps a value `f` linearly to a colour index
//! `c = ((f_max - f) c_min + (f - f_min) c_max) / (f_max - f_min)`; here the index is the
//! parameter `t = (f - f_min) / (f_max - f_min)` in `[0, 1]` ([`normalize`]) and the map is a
//! small table of anchor colours with linear interpolation in sRGB between them.
//!
//! Tables (written from the published anchor values):
//! - viridis (van der Walt & Smith, matplotlib 1.5): the 9 evenly spaced samples
//!   `#440154 #472D7B #3B528B #2C728E #21908C #27AD81 #5DC863 #AADC32 #FDE725`;
//! - coolwarm (Moreland, "Diverging Color Maps for Scientific Visualization", 2009): 9 evenly
//!   spaced samples from blue (59, 76, 192) through grey (221, 221, 221) to red (180, 4, 38);
//! - greys: black to white.
//!
//! Cost: O(1) per lookup. `t` is clamped to `[0, 1]`; NaN gives [`MISSING`].

use super::RenderError;
use std::str::FromStr;

/// Colour used for missing values (NaN): a neutral mid grey.
pub const MISSING: [u8; 3] = [128, 128, 128];

/// A colour map from `[0, 1]` to sRGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Colormap {
    /// Perceptually uniform, dark purple → blue → green → yellow; luminance increases.
    #[default]
    Viridis,
    /// Diverging blue → light grey → red (for signed values such as curvature).
    Coolwarm,
    /// Black → white.
    Greys,
}

const VIRIDIS: [[u8; 3]; 9] = [
    [0x44, 0x01, 0x54],
    [0x47, 0x2D, 0x7B],
    [0x3B, 0x52, 0x8B],
    [0x2C, 0x72, 0x8E],
    [0x21, 0x90, 0x8C],
    [0x27, 0xAD, 0x81],
    [0x5D, 0xC8, 0x63],
    [0xAA, 0xDC, 0x32],
    [0xFD, 0xE7, 0x25],
];

const COOLWARM: [[u8; 3]; 9] = [
    [59, 76, 192],
    [98, 130, 234],
    [141, 176, 254],
    [184, 208, 249],
    [221, 221, 221],
    [245, 196, 173],
    [244, 154, 123],
    [222, 96, 77],
    [180, 4, 38],
];

const GREYS: [[u8; 3]; 2] = [[0, 0, 0], [255, 255, 255]];

impl Colormap {
    /// All maps, for listings.
    pub const ALL: [Colormap; 3] = [Colormap::Viridis, Colormap::Coolwarm, Colormap::Greys];

    /// The map's name as accepted by [`FromStr`].
    pub fn name(self) -> &'static str {
        match self {
            Colormap::Viridis => "viridis",
            Colormap::Coolwarm => "coolwarm",
            Colormap::Greys => "grey",
        }
    }

    fn table(self) -> &'static [[u8; 3]] {
        match self {
            Colormap::Viridis => &VIRIDIS,
            Colormap::Coolwarm => &COOLWARM,
            Colormap::Greys => &GREYS,
        }
    }

    /// Colour at parameter `t` (clamped to `[0, 1]`; NaN gives [`MISSING`]).
    pub fn color(&self, t: f64) -> [u8; 3] {
        if t.is_nan() {
            return MISSING;
        }
        let tab = self.table();
        let t = t.clamp(0.0, 1.0);
        let x = t * (tab.len() - 1) as f64;
        let i = (x.floor() as usize).min(tab.len() - 2);
        let f = x - i as f64;
        let (a, b) = (tab[i], tab[i + 1]);
        let mut c = [0u8; 3];
        for k in 0..3 {
            let v = a[k] as f64 + f * (b[k] as f64 - a[k] as f64);
            c[k] = v.round().clamp(0.0, 255.0) as u8;
        }
        c
    }

    /// Colour of value `v` in the range `[lo, hi]` (see [`normalize`]).
    pub fn color_of(&self, v: f64, lo: f64, hi: f64) -> [u8; 3] {
        self.color(normalize(v, lo, hi))
    }
}

/// Hamann's linear map of a value to `[0, 1]`: `(v - lo) / (hi - lo)`, clamped. A degenerate
/// range (`hi <= lo`) maps every finite value to 0.5; NaN stays NaN (→ missing colour).
pub fn normalize(v: f64, lo: f64, hi: f64) -> f64 {
    if v.is_nan() {
        return f64::NAN;
    }
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) || !(hi - lo).is_finite() {
        return 0.5;
    }
    ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
}

/// Smallest and largest finite value, or `None` when there is none.
///
/// ```
/// use morpho::render::{finite_range, normalize};
/// assert_eq!(finite_range([3.0, f64::NAN, -1.0, f64::INFINITY]), Some((-1.0, 3.0)));
/// assert_eq!(finite_range([f64::NAN]), None);
/// assert_eq!(normalize(5.0, 0.0, 10.0), 0.5);
/// ```
pub fn finite_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let mut r: Option<(f64, f64)> = None;
    for v in values {
        if v.is_finite() {
            r = Some(match r {
                None => (v, v),
                Some((a, b)) => (a.min(v), b.max(v)),
            });
        }
    }
    r
}

impl FromStr for Colormap {
    type Err = RenderError;
    fn from_str(s: &str) -> Result<Self, RenderError> {
        match s.to_ascii_lowercase().as_str() {
            "viridis" => Ok(Colormap::Viridis),
            "coolwarm" => Ok(Colormap::Coolwarm),
            "grey" | "gray" | "greys" | "grays" => Ok(Colormap::Greys),
            _ => Err(RenderError::UnknownColormap {
                name: s.to_string(),
            }),
        }
    }
}

/// Relative luminance (Rec. 709 / sRGB) of an sRGB colour, in `[0, 1]`.
pub fn luminance(c: [u8; 3]) -> f64 {
    let lin = |u: u8| {
        let s = u as f64 / 255.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endpoints() {
        assert_eq!(Colormap::Viridis.color(0.0), [68, 1, 84]);
        assert_eq!(Colormap::Viridis.color(1.0), [253, 231, 37]);
        assert_eq!(Colormap::Viridis.color(-3.0), [68, 1, 84]);
        assert_eq!(Colormap::Viridis.color(7.0), [253, 231, 37]);
        assert_eq!(Colormap::Coolwarm.color(0.0), [59, 76, 192]);
        assert_eq!(Colormap::Coolwarm.color(0.5), [221, 221, 221]);
        assert_eq!(Colormap::Coolwarm.color(1.0), [180, 4, 38]);
        assert_eq!(Colormap::Greys.color(0.0), [0, 0, 0]);
        assert_eq!(Colormap::Greys.color(1.0), [255, 255, 255]);
        assert_eq!(Colormap::Greys.color(0.5), [128, 128, 128]);
        for m in Colormap::ALL {
            assert_eq!(m.color(f64::NAN), MISSING);
            assert_eq!(m.name().parse::<Colormap>().unwrap(), m);
        }
        assert!("jet".parse::<Colormap>().is_err());
    }

    #[test]
    fn viridis_luminance_increases() {
        let mut prev = -1.0;
        for i in 0..=1000 {
            let l = luminance(Colormap::Viridis.color(i as f64 / 1000.0));
            assert!(l >= prev - 1e-3, "luminance drops at {i}: {l} < {prev}");
            prev = prev.max(l);
        }
        let lo = luminance(Colormap::Viridis.color(0.0));
        let hi = luminance(Colormap::Viridis.color(1.0));
        assert!(hi - lo > 0.6);
        // Greys strictly increasing in steps.
        let g: Vec<f64> = (0..=10)
            .map(|i| luminance(Colormap::Greys.color(i as f64 / 10.0)))
            .collect();
        assert!(g.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn coolwarm_diverges() {
        // Luminance rises to the middle and falls after it.
        let l = |t: f64| luminance(Colormap::Coolwarm.color(t));
        assert!(l(0.0) < l(0.25) && l(0.25) < l(0.5));
        assert!(l(1.0) < l(0.75) && l(0.75) < l(0.5));
        // Blue end is blue, red end is red.
        let (b, r) = (Colormap::Coolwarm.color(0.0), Colormap::Coolwarm.color(1.0));
        assert!(b[2] > b[0] && r[0] > r[2]);
    }

    #[test]
    fn normalize_cases() {
        assert_eq!(normalize(5.0, 0.0, 10.0), 0.5);
        assert_eq!(normalize(-5.0, 0.0, 10.0), 0.0);
        assert_eq!(normalize(3.0, 3.0, 3.0), 0.5);
        assert!(normalize(f64::NAN, 0.0, 1.0).is_nan());
        assert_eq!(
            finite_range([f64::NAN, 2.0, -1.0, f64::INFINITY]),
            Some((-1.0, 2.0))
        );
        assert_eq!(finite_range([f64::NAN]), None);
    }

    #[test]
    fn interpolation_is_continuous() {
        for m in Colormap::ALL {
            for i in 0..1000 {
                let a = m.color(i as f64 / 1000.0);
                let b = m.color((i + 1) as f64 / 1000.0);
                for k in 0..3 {
                    assert!((a[k] as i32 - b[k] as i32).abs() <= 3);
                }
            }
        }
    }
}
