//! Pictures of every stage: SVG for 2D (the [`Svg`] builder and the pictures of the 2D results:
//! [`delaunay_svg`], [`boundary_svg`], [`contour_svg`], …), a software rasterizer (PNG) for meshes
//! ([`render_mesh`]) and volume views ([`slice_image`], [`orthogonal_slices`],
//! [`domain_subdivision_mesh`], colour bars by [`with_colorbar`]). Every picture is a value (an
//! SVG string or an [`Image`]); saving goes through [`crate::io`].

mod colormap;
mod error;
mod figures;
mod font;
mod formula;
mod legend;
mod raster;
mod slice;
mod subdivision;
mod svg;
mod views;

pub use colormap::{finite_range, luminance, normalize, Colormap, MISSING};
pub use error::RenderError;
pub use figures::{
    boundary_svg, cdt_svg, constriction_svg, contour_svg, cycle_svg, delaunay_svg, graph_svg,
    point_set_svg, PointLabel, PointsView, CONTOUR_SVG_MAX_TRIANGLES,
};
pub use formula::Formula;
pub use legend::with_colorbar;
pub use raster::{
    reflection_coordinate, render_mesh, render_mesh_stats, Projection, ReflectionLines,
    RenderOptions, RenderStats, Scalars, Shading, UpAxis,
};
pub use slice::{
    middle, orthogonal_slices, slice_height_mesh, slice_image, Axis, SliceOptions, Upsample,
};
pub use subdivision::{domain_subdivision_mesh, grid_planes_mesh, subbox_starts, trilinear};
pub use svg::{
    colored_triangulation_svg, points_svg, polygon_svg, triangulation_svg, Fill, Rgb, Stroke, Svg,
};
pub use views::{
    height_surface_mesh, heights_view_mesh, render_view, subdivision_view_mesh,
    transparency_rectangle_count, transparency_view_mesh, HeightStyle, Source, View, ViewOptions,
    ViewPicture,
};

use crate::{Error, Result};
use std::path::Path;

/// An RGBA image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

impl Image {
    /// An image filled with one colour.
    pub fn new(width: u32, height: u32, fill: [u8; 4]) -> Self {
        let n = width as usize * height as usize;
        let mut rgba = Vec::with_capacity(n * 4);
        for _ in 0..n {
            rgba.extend_from_slice(&fill);
        }
        Image {
            width,
            height,
            rgba,
        }
    }
    /// Pixel at (x, y).
    pub fn get(&self, x: u32, y: u32) -> [u8; 4] {
        let i = (y as usize * self.width as usize + x as usize) * 4;
        [
            self.rgba[i],
            self.rgba[i + 1],
            self.rgba[i + 2],
            self.rgba[i + 3],
        ]
    }
    /// Sets pixel (x, y).
    pub fn put(&mut self, x: u32, y: u32, c: [u8; 4]) {
        let i = (y as usize * self.width as usize + x as usize) * 4;
        self.rgba[i..i + 4].copy_from_slice(&c);
    }
    /// Encodes the image as PNG.
    ///
    /// ```
    /// use morpho::render::Image;
    /// let mut img = Image::new(2, 1, [0, 0, 0, 255]);
    /// img.put(1, 0, [255, 0, 0, 255]);
    /// assert_eq!(img.get(1, 0), [255, 0, 0, 255]);
    /// let mut png = Vec::new();
    /// img.write_png(&mut png).unwrap();
    /// assert_eq!(&png[1..4], b"PNG");
    /// ```
    pub fn write_png(&self, w: &mut dyn std::io::Write) -> Result<()> {
        let mut enc = png::Encoder::new(w, self.width, self.height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc.write_header().map_err(png_err)?;
        wr.write_image_data(&self.rgba).map_err(png_err)?;
        wr.finish().map_err(png_err)
    }
    /// Writes the image to a `.png` file atomically.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        crate::io::write_atomic(path, |w| self.write_png(w))
    }
}

/// A failing writer is [`Error::Io`] (as for every writer); anything else the encoder refuses
/// is invalid input.
fn png_err(e: png::EncodingError) -> Error {
    match e {
        png::EncodingError::IoError(e) => Error::Io {
            path: String::new(),
            source: e,
        },
        e => RenderError::Png {
            reason: e.to_string(),
        }
        .into(),
    }
}
