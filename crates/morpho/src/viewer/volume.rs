//! A volume in the viewer page (issue 22 part 2; Hamann 1991 §2.3, NOTES part F.3 "coloured
//! slices ... planes moved interactively"): the samples embedded compactly, drawn by
//! `slices.js` as three axis-aligned planes, each moved by its slider, coloured through a
//! colour map of the bilinearly interpolated value (the value at a pixel of a slice at grid
//! plane `i` is the bilinear interpolant of the four surrounding samples of that plane).
//!
//! **Encoding.** Samples are quantized linearly over the finite range `[lo, hi]`:
//! - `u8` when every sample is a finite integer and `hi − lo ≤ 255` (e.g. a CT in `u8`): the
//!   code is `v − lo`, exact;
//! - else `u16`: code `round((v − lo)/(hi − lo)·65534)`, decoded as `lo + code·step` with
//!   `step = (hi − lo)/65534`, so the error is at most `step/2`; the code 65535 marks a
//!   non-finite sample (drawn grey, picked as NaN).
//!
//! A constant volume has `step = 0` (every code 0). The page carries the grid planes' positions
//! per axis (`coords`, [`Volume::coord`], so uniform and per-index axes alike; spacing and
//! origin are in them) and the orientation (directions and the origin they turn about,
//! [`Orientation::to_world`]), so slices are drawn in the same world coordinates as the
//! volume's contour surface.
//!
//! **Size.** A volume with more than `max_samples` samples, or more than [`MAX_AXIS`] along an
//! axis (the texture size WebGL 2 guarantees), is subsampled with the smallest common stride
//! `s` (every `s`-th sample along each axis, from index 0; values are kept, not averaged) and
//! the page says so ([`VolumeLayer::notes`]). Cost: O(samples) time and `1` or `2` bytes per
//! embedded sample (× 4/3 in base64).

use crate::volume::{Orientation, Volume};

/// The largest number of samples along an axis of an embedded volume (WebGL 2 guarantees 2D
/// textures of 2048 texels).
pub const MAX_AXIS: usize = 2048;

/// The default cap on the samples of an embedded volume: 2²³ (about 203³; 16 MiB as `u16`).
pub const DEFAULT_MAX_SAMPLES: usize = 1 << 23;

/// The code of a non-finite sample in the `u16` encoding.
pub const NAN_CODE: u16 = 65535;

/// Samples quantized to `u8` or `u16` codes.
#[derive(Debug, Clone, PartialEq)]
pub struct Quantized {
    /// 8 or 16.
    pub bits: u32,
    /// The value of code 0 (the smallest finite sample).
    pub lo: f64,
    /// The value step between consecutive codes (0 for a constant volume).
    pub step: f64,
    /// The codes, one per sample (little-endian `u16` when `bits == 16`).
    pub bytes: Vec<u8>,
}

impl Quantized {
    /// Code `i` as stored.
    pub fn code(&self, i: usize) -> u16 {
        if self.bits == 8 {
            self.bytes[i] as u16
        } else {
            u16::from_le_bytes([self.bytes[2 * i], self.bytes[2 * i + 1]])
        }
    }
    /// The value sample `i` decodes to (NaN for a non-finite sample).
    pub fn value(&self, i: usize) -> f64 {
        let c = self.code(i);
        if self.bits == 16 && c == NAN_CODE {
            f64::NAN
        } else {
            self.lo + c as f64 * self.step
        }
    }
}

/// Quantizes samples (see the module doc); `None` when no sample is finite.
pub fn quantize_samples(data: &[f32]) -> Option<Quantized> {
    let (lo, hi) = crate::volume::finite_range(data, None)?;
    let (lo, hi) = (lo as f64, hi as f64);
    let integral = data.iter().all(|&v| v.is_finite() && v.fract() == 0.0);
    if integral && hi - lo <= 255.0 {
        let bytes = data.iter().map(|&v| (v as f64 - lo) as u8).collect();
        return Some(Quantized {
            bits: 8,
            lo,
            step: 1.0,
            bytes,
        });
    }
    let span = hi - lo;
    let step = span / 65534.0;
    let mut bytes = Vec::with_capacity(2 * data.len());
    for &v in data {
        let c = if !v.is_finite() {
            NAN_CODE
        } else if span > 0.0 {
            ((v as f64 - lo) / span * 65534.0)
                .round()
                .clamp(0.0, 65534.0) as u16
        } else {
            0
        };
        bytes.extend(c.to_le_bytes());
    }
    Some(Quantized {
        bits: 16,
        lo,
        step,
        bytes,
    })
}

/// A volume ready for the page: its (possibly subsampled) grid, codes and notes.
#[derive(Debug, Clone)]
pub struct VolumeLayer {
    /// Samples per axis of the embedded grid.
    pub dims: [usize; 3],
    /// The embedded grid planes' positions per axis, in the grid frame (before the orientation).
    pub coords: [Vec<f64>; 3],
    /// Unit directions of the grid axes (`None`: axis-aligned), turning about `pivot`.
    pub directions: Option<[[f64; 3]; 3]>,
    /// The point the directions turn about (the position of sample (0, 0, 0)).
    pub pivot: [f64; 3],
    /// The stride of the subsampling (1: every sample).
    pub stride: usize,
    /// The codes.
    pub quantized: Quantized,
    /// Smallest and largest finite sample of the embedded grid (data units).
    pub range: (f64, f64),
    /// Sentences shown in the page's panel (subsampling, a constant volume, a flat axis).
    pub notes: Vec<String>,
}

impl VolumeLayer {
    /// Prepares `v` for the page, subsampled to at most `max_samples` samples (at least 1).
    /// Fails (with a sentence naming the reason) when no sample is finite or the volume is empty.
    pub fn new(v: &Volume, max_samples: usize) -> Result<VolumeLayer, String> {
        let [nx, ny, nz] = v.dims;
        if v.is_empty() {
            return Err("the volume has no samples".into());
        }
        let max_samples = max_samples.max(1);
        let kept = |s: usize| v.dims.map(|n| n.div_ceil(s));
        let mut stride = 1;
        loop {
            let d = kept(stride);
            let fits = d.iter().all(|&n| n <= MAX_AXIS)
                && d[0]
                    .checked_mul(d[1])
                    .and_then(|x| x.checked_mul(d[2]))
                    .is_some_and(|n| n <= max_samples);
            if fits {
                break;
            }
            stride += 1;
        }
        let dims = kept(stride);
        let coords: [Vec<f64>; 3] =
            std::array::from_fn(|k| (0..dims[k]).map(|i| v.coord(k, i * stride)).collect());
        let data: Vec<f32> = if stride == 1 {
            v.data.clone()
        } else {
            let mut d = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
            for z in 0..dims[2] {
                for y in 0..dims[1] {
                    for x in 0..dims[0] {
                        d.push(v.at(x * stride, y * stride, z * stride));
                    }
                }
            }
            d
        };
        let quantized = quantize_samples(&data)
            .ok_or_else(|| "the volume has no finite sample; nothing to show".to_string())?;
        let (lo, hi) = crate::volume::finite_range(&data, None)
            .map_or((0.0, 0.0), |(a, b)| (a as f64, b as f64));
        let mut notes = Vec::new();
        if stride > 1 {
            notes.push(format!(
                "{nx}×{ny}×{nz} samples shown as {}×{}×{} (one sample in {stride} along each axis; \
                 the cap is {max_samples} samples)",
                dims[0], dims[1], dims[2]
            ));
        }
        if lo == hi {
            notes.push(format!(
                "the volume is constant ({lo}): the slices have one colour"
            ));
        }
        let flat: Vec<&str> = (0..3)
            .filter(|&k| v.dims[k] == 1)
            .map(|k| ["x", "y", "z"][k])
            .collect();
        match flat.len() {
            0 => {}
            1 => notes.push(format!(
                "one sample along {0}: the volume is flat, its {0} slice is the whole picture",
                flat[0]
            )),
            _ => notes.push(format!(
                "one sample along {}: no slice has an area (only the box is drawn)",
                flat.join(" and ")
            )),
        }
        let nan = data.iter().filter(|x| !x.is_finite()).count();
        if nan > 0 {
            notes.push(format!("{nan} non-finite samples (grey)"));
        }
        let pivot = [v.coord(0, 0), v.coord(1, 0), v.coord(2, 0)];
        let directions = if v.orientation.is_axis_aligned() {
            None
        } else {
            v.orientation.directions
        };
        Ok(VolumeLayer {
            dims,
            coords,
            directions,
            pivot,
            stride,
            quantized,
            range: (lo, hi),
            notes,
        })
    }

    /// The world position of the point with grid-frame position `p`.
    pub fn to_world(&self, p: [f64; 3]) -> [f64; 3] {
        Orientation {
            directions: self.directions,
            ..Default::default()
        }
        .to_world(self.pivot, p)
    }

    /// The four world corners of slice `index` along `axis` (the plane at the grid plane
    /// `coords[axis][index]`, spanning the grid along the two other axes), in the order
    /// (lo, lo), (hi, lo), (hi, hi), (lo, hi) of the other two axes in increasing order.
    pub fn slice_corners(&self, axis: usize, index: usize) -> [[f64; 3]; 4] {
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let (b, c) = (b.min(c), b.max(c));
        let end = |k: usize, hi: bool| {
            let v = &self.coords[k];
            if hi {
                v[v.len() - 1]
            } else {
                v[0]
            }
        };
        let corner = |hb: bool, hc: bool| {
            let mut p = [0.0; 3];
            p[axis] = self.coords[axis][index];
            p[b] = end(b, hb);
            p[c] = end(c, hc);
            self.to_world(p)
        };
        [
            corner(false, false),
            corner(true, false),
            corner(true, true),
            corner(false, true),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::volume::Axes;

    #[test]
    fn u16_round_trip_is_within_half_a_step() {
        let data: Vec<f32> = (0..5000)
            .map(|i| ((i as f32) * 0.37).sin() * 1234.5 + 17.0)
            .collect();
        let q = quantize_samples(&data).unwrap();
        assert_eq!(q.bits, 16);
        let (lo, hi) = crate::volume::finite_range(&data, None).unwrap();
        assert_eq!(q.step, (hi as f64 - lo as f64) / 65534.0);
        for (i, &v) in data.iter().enumerate() {
            let e = (q.value(i) - v as f64).abs();
            assert!(e <= 0.5 * q.step * (1.0 + 1e-9), "sample {i}: error {e}");
        }
        // the ends are exact
        let imin = data.iter().position(|&v| v == lo).unwrap();
        let imax = data.iter().position(|&v| v == hi).unwrap();
        assert_eq!(q.code(imin), 0);
        assert_eq!(q.code(imax), 65534);
    }

    #[test]
    fn integral_samples_in_a_byte_range_are_exact_u8() {
        let data: Vec<f32> = (0..300).map(|i| (i % 256) as f32 - 100.0).collect();
        let q = quantize_samples(&data).unwrap();
        assert_eq!(q.bits, 8);
        assert_eq!(q.bytes.len(), 300);
        for (i, &v) in data.iter().enumerate() {
            assert_eq!(q.value(i), v as f64);
        }
        // 257 levels do not fit a byte: u16
        let wide: Vec<f32> = (0..=256).map(|i| i as f32).collect();
        assert_eq!(quantize_samples(&wide).unwrap().bits, 16);
    }

    #[test]
    fn non_finite_samples_get_the_sentinel_and_all_nan_fails() {
        let q = quantize_samples(&[1.0, f32::NAN, 3.5, f32::INFINITY]).unwrap();
        assert_eq!(q.bits, 16);
        assert_eq!(q.code(1), NAN_CODE);
        assert_eq!(q.code(3), NAN_CODE);
        assert!(q.value(1).is_nan());
        assert_eq!(q.value(0), 1.0);
        assert_eq!(q.value(2), 3.5);
        assert!(quantize_samples(&[f32::NAN, f32::NAN]).is_none());
        let v = Volume::new([2, 1, 1], [0.0; 3], [1.0; 3], vec![f32::NAN; 2]).unwrap();
        assert!(VolumeLayer::new(&v, 100).is_err());
    }

    #[test]
    fn constant_volume_decodes_to_its_value_with_a_note() {
        let v = Volume::new([3, 2, 2], [0.0; 3], [1.0; 3], vec![2.25; 12]).unwrap();
        let l = VolumeLayer::new(&v, 100).unwrap();
        assert_eq!(l.quantized.step, 0.0);
        assert!((0..12).all(|i| l.quantized.value(i) == 2.25));
        assert!(
            l.notes.iter().any(|n| n.contains("constant")),
            "{:?}",
            l.notes
        );
    }

    #[test]
    fn slice_positions_follow_origin_spacing_and_coords() {
        let v = Volume::from_fn([5, 4, 3], [1.0, -2.0, 10.0], [3.0, 4.0, 14.0], |x, _, _| x);
        // spacing 0.5, 2, 2
        let l = VolumeLayer::new(&v, 1000).unwrap();
        assert_eq!(l.coords[0], vec![1.0, 1.5, 2.0, 2.5, 3.0]);
        assert_eq!(l.coords[2], vec![10.0, 12.0, 14.0]);
        let c = l.slice_corners(1, 2); // y = -2 + 2·2
        assert_eq!(c[0], [1.0, 2.0, 10.0]);
        assert_eq!(c[2], [3.0, 2.0, 14.0]);
        // per-index coordinates
        let mut w = v.clone();
        w.axes = Axes::Coords([
            vec![0.0, 1.0, 3.0, 7.0, 15.0],
            vec![0.0, 1.0, 2.0, 4.0],
            vec![-1.0, 0.0, 5.0],
        ]);
        let l = VolumeLayer::new(&w, 1000).unwrap();
        assert_eq!(l.slice_corners(0, 3)[0], [7.0, 0.0, -1.0]);
        assert_eq!(l.slice_corners(2, 2)[2], [15.0, 4.0, 5.0]);
        // a rotated grid: axis 0 along world y, axis 1 along −x, turning about sample (0, 0, 0)
        let mut r = v.clone();
        r.orientation.directions = Some([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
        let l = VolumeLayer::new(&r, 1000).unwrap();
        // sample (4, 0, 0) is 2 along axis 0 from (1, −2, 10): world (1, 0, 10)
        assert_eq!(l.slice_corners(0, 4)[0], [1.0, 0.0, 10.0]);
    }

    #[test]
    fn big_volumes_are_subsampled_with_a_note() {
        let v = Volume::from_fn([9, 9, 9], [0.0; 3], [8.0; 3], |x, y, z| {
            x + 10.0 * y + 100.0 * z
        });
        let l = VolumeLayer::new(&v, 200).unwrap();
        // stride 2 keeps 5³ = 125 ≤ 200 samples at indices 0, 2, 4, 6, 8
        assert_eq!(l.stride, 2);
        assert_eq!(l.dims, [5, 5, 5]);
        assert_eq!(l.coords[1], vec![0.0, 2.0, 4.0, 6.0, 8.0]);
        // kept samples keep their values (x + 10y + 100z at the kept grid points, exact in u16?
        // no: 889 levels; within half a step)
        let q = &l.quantized;
        let i = 1 + 5 * (2 + 5 * 3); // (x, y, z) = (2, 4, 6)
        assert!((q.value(i) - 642.0).abs() <= 0.5 * q.step + 1e-9);
        assert!(l.notes[0].contains("one sample in 2"), "{:?}", l.notes);
    }
}
