//! A volume's samples read slice by slice (z fastest-varying last), for volumes larger than
//! memory (issue 24: the CLI's streaming contour surface).
//!
//! The three volume formats ([`super::nrrd`], [`super::mhd`], [`super::rawjson`]) parse their
//! header as for a whole read and hand over the data stream (raw, gzip or zlib; NRRD text data
//! is not streamed). The stream decodes `k` slices of `n_x·n_y` samples at a time into `f32`,
//! so the memory used is that of the slices asked for, whatever the volume's size. Sizes are
//! checked as for a whole read: raw data must have exactly the header's size before the first
//! slice is read, compressed data must end where the header says (checked by [`VolumeStream::finish`]).
//! The whole-volume memory limit ([`super::memory`]) does not apply; each call checks the
//! memory of the slices it decodes instead.

use super::rawjson::{decode, sample_reader, Codec, Sample};
use crate::volume::{Axes, DType, Orientation, VolumeGrid};
use crate::{Error, Result};
use std::io::Read;
use std::path::{Path, PathBuf};

/// What a header says about the samples, apart from where they are.
pub(crate) struct Head {
    pub dims: [usize; 3],
    pub axes: Axes,
    pub orientation: Orientation,
    pub ty: Sample,
    pub big: bool,
}

/// Where the samples are: `available` bytes of `reader` (the data file, or the rest of the
/// header file), of which `skip` (after decompression for `codec` ≠ Raw) precede the samples.
pub(crate) struct Data {
    pub reader: Box<dyn Read>,
    pub available: u64,
    pub codec: Codec,
    pub skip: u64,
    /// The file the data is in (named in errors).
    pub path: PathBuf,
}

/// The samples of a volume file, decoded a few z-slices at a time ([`super::open_volume_stream`]).
pub struct VolumeStream {
    dims: [usize; 3],
    axes: Axes,
    orientation: Orientation,
    ty: Sample,
    big: bool,
    reader: Box<dyn Read>,
    compressed: bool,
    /// Slices not read yet.
    left: usize,
    path: PathBuf,
    bytes: Vec<u8>,
}

impl VolumeStream {
    /// Checks the data's size and skips the bytes before the samples.
    pub(crate) fn new(head: Head, data: Data) -> Result<VolumeStream> {
        let slice_bytes = head.dims[0]
            .checked_mul(head.dims[1])
            .and_then(|v| v.checked_mul(head.ty.size()))
            .ok_or_else(|| Error::invalid(format!("volume sizes {:?} overflow", head.dims)))?;
        let expected = (slice_bytes as u64)
            .checked_mul(head.dims[2] as u64)
            .ok_or_else(|| Error::invalid(format!("volume sizes {:?} overflow", head.dims)))?;
        let path = data.path.clone();
        let compressed = data.codec != Codec::Raw;
        let reader = sample_reader(data.reader, data.available, data.codec, data.skip, expected)
            .map_err(|e| e.with_path(&path))?;
        Ok(VolumeStream {
            dims: head.dims,
            axes: head.axes,
            orientation: head.orientation,
            ty: head.ty,
            big: head.big,
            reader,
            compressed,
            left: head.dims[2],
            path,
            bytes: Vec::new(),
        })
    }

    /// Samples along x, y, z.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The grid the samples lie on (dims, axes, orientation).
    pub fn grid(&self) -> VolumeGrid {
        VolumeGrid {
            dims: self.dims,
            axes: self.axes.clone(),
            orientation: self.orientation.clone(),
        }
    }

    /// The file's sample type.
    pub fn source_dtype(&self) -> DType {
        self.ty.source_dtype()
    }

    /// Slices not read yet.
    pub fn slices_left(&self) -> usize {
        self.left
    }

    /// Appends the next `k` slices (`k·n_x·n_y` samples, x fastest) to `out` as `f32`; fewer
    /// when fewer are left. Errors: the data ends early or cannot be decompressed, or the
    /// slices' memory passes the limit.
    pub fn read_slices(&mut self, k: usize, out: &mut Vec<f32>) -> Result<usize> {
        let k = k.min(self.left);
        let per = self.dims[0] * self.dims[1];
        let nbytes = per * k * self.ty.size();
        super::memory::check(
            (per * k * 4 + nbytes) as u64,
            &format!("{k} slices of {}×{} samples", self.dims[0], self.dims[1]),
        )?;
        // decode in pieces of about 16 MiB: the byte buffer stays small
        let piece = (16usize << 20) / (per * self.ty.size()).max(1);
        let piece = piece.max(1);
        out.reserve(per * k);
        let mut done = 0;
        while done < k {
            let m = piece.min(k - done);
            self.bytes.resize(per * m * self.ty.size(), 0);
            self.reader.read_exact(&mut self.bytes).map_err(|e| {
                let what = if e.kind() == std::io::ErrorKind::UnexpectedEof {
                    "the data ends before the header's last slice".to_string()
                } else {
                    format!("cannot read data: {e}")
                };
                Error::format(what).with_path(&self.path)
            })?;
            out.extend(decode(&self.bytes, self.ty, self.big));
            done += m;
        }
        self.left -= k;
        Ok(k)
    }

    /// After the last slice: compressed data must end there (as a whole read checks).
    pub fn finish(mut self) -> Result<()> {
        if self.compressed {
            let mut one = [0u8; 1];
            let n = self.reader.read(&mut one).map_err(|e| {
                Error::format(format!("bad compressed data: {e}")).with_path(&self.path)
            })?;
            if n > 0 {
                return Err(Error::format(
                    "the decompressed data is longer than dims × sample size",
                )
                .with_path(&self.path));
            }
        }
        Ok(())
    }

    /// The file the samples are read from.
    pub fn data_path(&self) -> &Path {
        &self.path
    }
}
