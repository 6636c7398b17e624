//! Software rasterizer for triangle meshes: z-buffer, flat or smooth (Phong) shading, two-sided
//! lighting, scalar colour maps, wireframe overlay, supersampling — no GPU, no window.
//!
//! Size (over 800 lines): the rasterizer is one pipeline (camera, clipping, z-buffer, shading,
//! colour maps, wireframe, supersampling) over one private frame-buffer type.
//!
//! Method (standard scan conversion, e.g. Foley et al. 1990, ch. 15–16):
//! 1. triangles with an index out of range or a non-finite corner are skipped (counted);
//! 2. the used vertices are normalised by their bounding box (centre → origin, largest half
//!    extent → 1) so huge and tiny coordinates behave alike;
//! 3. a camera looks at the origin from azimuth/elevation around the chosen up axis;
//!    perspective or orthographic projection; the projected picture is fitted to the image with
//!    a margin;
//! 4. the supersampled image (`s × s` samples per pixel) is split into bands of rows processed
//!    in parallel (rayon); each band keeps its own depth buffer and draws the triangles binned to
//!    it in index order (strict depth test, so ties go to the lower index): the output does not
//!    depend on the thread count;
//! 5. per sample: perspective-correct interpolation of normals and scalars, Blinn–Phong
//!    lighting with a headlight and a key light, normals flipped on back faces (two-sided);
//!    optionally reflection lines (Veltkamp 1992, §8.4) from the same normals
//!    ([`ReflectionLines`]);
//! 6. the samples of each pixel are averaged (box filter).
//!
//! With [`RenderOptions::transparency`] the z-buffer is replaced by Hamann's alpha blending
//! (1991, §2.2): triangles sorted back to front, each sample `(1 − t) c_triangle + t c_old`.
//! The recurrence is evaluated front to back (same order, reversed; a transmittance per
//! sample, rounded to 8 bits once): a sample takes no more layers once the layers behind it
//! could change it by less than half a level, and triangles over saturated tiles are skipped,
//! so the cost follows the visible layers, not all of them. Per row a triangle takes one
//! interval of samples (found by the exact edge tests at its ends, the edge functions being
//! monotone along a row) and rows over saturated row tiles are skipped; inside the interval
//! the colour parameter is stepped (`Scene::composite_triangle`).
//!
//! Complexity: O(n log n + covered samples) time (alpha blending: O(n log n + samples ×
//! visible layers) plus a bounding-box test per triangle), O(W·H·s²) memory. Hamann (1991, §2.3) shades
//! slice surfaces with Gouraud shading; [`Shading::Smooth`] interpolates normals instead
//! (per-sample lighting), which keeps highlights round on coarse meshes.
//!
//! Orientation convention: triangles are counter-clockwise seen from outside; back faces get
//! [`RenderOptions::back_color`] if set, so inside-out parts show up.
//!
//! ```
//! use morpho::geom::Point3;
//! use morpho::mesh::TriMesh;
//! use morpho::render::{render_mesh, RenderOptions};
//!
//! let tet = TriMesh::new(
//!     vec![
//!         Point3::new(0.0, 0.0, 0.0),
//!         Point3::new(1.0, 0.0, 0.0),
//!         Point3::new(0.0, 1.0, 0.0),
//!         Point3::new(0.0, 0.0, 1.0),
//!     ],
//!     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
//! );
//! let opts = RenderOptions { width: 64, height: 48, ..Default::default() };
//! let img = render_mesh(&tet, &opts);
//! assert_eq!((img.width, img.height), (64, 48));
//! // img.save_png(std::path::Path::new("tet.png"))?;
//! ```

use super::colormap::{finite_range, normalize, Colormap};
use super::Image;
use crate::geom::Vector3;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Projection of the camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Pinhole camera.
    Perspective {
        /// Vertical field of view in degrees (clamped to 1°…120°).
        fov_deg: f64,
    },
    /// Parallel projection.
    Orthographic,
}

/// How normals are chosen for lighting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shading {
    /// One normal per triangle (facets visible).
    Flat,
    /// Vertex normals (the mesh's own if present, else area-weighted) interpolated per sample.
    Smooth,
}

/// Which coordinate axis points up on screen at elevation 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UpAxis {
    /// y up (OBJ/PLY convention; azimuth 0 looks from +z).
    Y,
    /// z up (volumes, terrain; azimuth 0 looks from −y).
    Z,
}

/// Scalar values shown through a colour map.
#[derive(Debug, Clone, PartialEq)]
pub struct Scalars {
    /// One value per vertex, or per triangle if `per_face`.
    pub values: Vec<f64>,
    /// The values are per triangle, not per vertex.
    pub per_face: bool,
    /// The colour map.
    pub colormap: Colormap,
    /// Values mapped to the ends of the map; `None`: min..max of the finite values used.
    pub range: Option<(f64, f64)>,
}

/// Everything that decides the picture. `Default` gives a 800×600 smooth-shaded perspective
/// view from azimuth 35°, elevation 25°, y up, 2×2 supersampling.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Image size in pixels (each clamped to 1…8192).
    pub width: u32,
    /// Image height in pixels (clamped to 1…8192).
    pub height: u32,
    /// Rotation of the viewpoint about the up axis, degrees.
    pub azimuth_deg: f64,
    /// Height of the viewpoint above the horizontal plane, degrees (clamped to ±90).
    pub elevation_deg: f64,
    /// Which axis points up on screen.
    pub up: UpAxis,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Flat or smooth normals.
    pub shading: Shading,
    /// Surface colour when no scalars are given.
    pub color: [u8; 3],
    /// Colour of back faces (`None`: same as the front).
    pub back_color: Option<[u8; 3]>,
    /// Values shown through a colour map instead of `color`.
    pub scalars: Option<Scalars>,
    /// Draw triangle edges (meant for small meshes).
    pub wireframe: bool,
    /// Colour of the wireframe.
    pub wire_color: [u8; 3],
    /// Background colour with alpha (alpha 0: transparent).
    pub background: [u8; 4],
    /// Samples per pixel along each axis (clamped to 1…4; lowered for very large images).
    pub supersample: u32,
    /// Empty border as a fraction of the smaller image side (clamped to 0…0.45).
    pub margin: f64,
    /// Alpha blending instead of the z-buffer (Hamann 1991, §2.2): triangles are sorted by
    /// depth (Hamann sorts polygons by their corner nearest to the screen; here the midpoint of
    /// the longest edge, which keeps both halves of a split rectangle together), drawn back to
    /// front, unlit, each sample becoming
    /// `(1 − t) c_triangle + t c_old`; `t` is clamped to [0, 1] (0: opaque painter's order).
    /// Evaluated front to back and rounded once, `Σ_i (1 − t) tⁱ c_i + tⁿ background` (layer
    /// 0 nearest), stopping once `tⁱ ≤ 1/512` (the rest moves a channel by < 0.5).
    /// Colour maps are read from a table of 4096 parameters.
    pub transparency: Option<f64>,
    /// Reflection lines (Veltkamp 1992, §8.4) over the shading: see [`ReflectionLines`].
    /// Ignored with `transparency`.
    pub reflection_lines: Option<ReflectionLines>,
}

/// Reflection lines, the visual continuity check of Veltkamp (1992, §8.4; NOTES B.8): a family
/// of parallel line lights, parallel to the screen's horizontal axis and far away around the
/// object (the limit of (8.11) for a distant light, so the reflection depends on the direction
/// of the reflected view ray only). Per sample, the view ray is reflected about the
/// interpolated unit normal, `r = d − 2(d·n)n`, and its angle about the lines' axis,
/// `θ = atan2(r_y, r_z)` in camera space ([`reflection_coordinate`]), decides: a sample whose
/// `θ·lines/π` lies within `width/2` of an integer sees a light line and is drawn dark.
/// The stripes are continuous where the normals are (G¹), and kink across patch edges unless
/// the surface is G² (Veltkamp 1992, §8.4); on a flat-shaded mesh they break at every edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReflectionLines {
    /// Light lines per π of the reflected ray's angle (clamped to 1…1000).
    pub lines: u32,
    /// Fraction of each period drawn dark (clamped to 0.02…0.98).
    pub width: f64,
    /// Colour of the stripes.
    pub color: [u8; 3],
}

impl Default for ReflectionLines {
    fn default() -> Self {
        ReflectionLines {
            lines: 4,
            width: 0.4,
            color: [20, 24, 36],
        }
    }
}

/// The stripe coordinate of [`ReflectionLines`]: for the unit view direction `d` (from the eye
/// to the surface) and the unit normal `n` (both in camera coordinates, x right, y up, z
/// towards the eye), the angle `atan2(r_y, r_z)` of the reflected ray `r = d − 2(d·n)n` about
/// the camera's x axis, in (−π, π]. A normal facing the eye gives 0.
pub fn reflection_coordinate(d: [f64; 3], n: [f64; 3]) -> f64 {
    let dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    let r = [d[1] - 2.0 * dn * n[1], d[2] - 2.0 * dn * n[2]];
    r[0].atan2(r[1])
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 600,
            azimuth_deg: 35.0,
            elevation_deg: 25.0,
            up: UpAxis::Y,
            projection: Projection::Perspective { fov_deg: 30.0 },
            shading: Shading::Smooth,
            color: [200, 205, 215],
            back_color: None,
            scalars: None,
            wireframe: false,
            wire_color: [30, 30, 30],
            background: [255, 255, 255, 255],
            supersample: 2,
            margin: 0.05,
            transparency: None,
            reflection_lines: None,
        }
    }
}

/// What [`render_mesh_stats`] drew.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderStats {
    /// Triangles sent to the rasterizer.
    pub drawn: usize,
    /// Triangles skipped for an index out of range or a non-finite corner.
    pub invalid: usize,
    /// Triangles with zero area on screen.
    pub degenerate: usize,
    /// Supersampling factor actually used.
    pub supersample: u32,
    /// Value range mapped to the colour map ends (when scalars were shown).
    pub range: Option<(f64, f64)>,
    /// Samples composited by alpha blending ([`RenderOptions::transparency`]): samples of a
    /// triangle that reached a pixel sample not yet saturated (0 with the z-buffer).
    pub composited: u64,
}

/// Renders `mesh` (see the module documentation). Never fails: invalid triangles are skipped,
/// an empty mesh gives a plain background.
pub fn render_mesh(mesh: &TriMesh, opts: &RenderOptions) -> Image {
    render_mesh_stats(mesh, opts).0
}

const BAND: usize = 16;
const MAX_SAMPLES: u64 = 1 << 26;
/// Width in samples of the tiles (of one band's height) whose saturation alpha blending tracks.
const TILE: usize = 8;
/// Transmittance at or below which a sample takes no more layers: the layers behind could add
/// at most `255 / 512 < 0.5` to a channel, so the rounded 8-bit result moves by at most one
/// rounding step.
const SATURATED: f32 = 1.0 / 512.0;
/// Entries of the colour table of alpha blending (parameter step 1/4095: neighbouring entries
/// of the 8-bit maps differ by at most one level).
const LUT: usize = 4096;

/// Per-vertex data after projection.
#[derive(Clone, Copy)]
struct Vert {
    px: f64,
    py: f64,
    /// Larger is nearer; linear in screen space.
    depth: f64,
    /// 1/w (1 for orthographic).
    invw: f64,
}

/// A triangle ready for scan conversion: corners ordered so that the edge functions are
/// positive inside, with everything that is constant over the triangle precomputed.
struct Tri {
    /// Vertex ids in edge-function order.
    ids: [u32; 3],
    p: [Vert; 3],
    /// Bounding box in sample coordinates (inclusive).
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
    /// 1 / (twice the screen area).
    inv_area: f64,
    /// Lengths of the edges opposite each corner (for the wireframe distance).
    lens: [f64; 3],
    /// True when the triangle shows its back (clockwise on screen).
    back: bool,
    /// Lighting normal of the face (flipped on back faces).
    face_n: Vector3,
    /// Base colour when it does not vary over the triangle.
    face_base: [u8; 3],
    /// Flat-shaded colour.
    flat_col: [u8; 4],
}

/// What triangle setup made of a triangle.
enum Setup {
    Degenerate,
    /// Drawn but covering no sample (off screen or thinner than a sample spacing).
    Empty,
    Tri(Box<Tri>),
}

/// Where a triangle lands on the sample grid: twice its signed screen area and its sample
/// box (inclusive).
#[derive(Clone, Copy)]
struct Cover {
    signed: f64,
    x0: u32,
    x1: u32,
    y0: u32,
    y1: u32,
}

/// A layer in a band's list: its mesh triangle and its sample box (inclusive; sample
/// coordinates fit in u16, at most 8192 · 4, `Frame::new`).
#[derive(Clone, Copy)]
struct BinEntry {
    tri: u32,
    x0: u16,
    x1: u16,
    y0: u16,
    y1: u16,
}

/// Edge function of the directed edge a→b at (x, y): twice the signed area of (a, b, p).
#[inline]
fn edge(a: &Vert, b: &Vert, x: f64, y: f64) -> f64 {
    (b.px - a.px) * (y - a.py) - (b.py - a.py) * (x - a.px)
}

/// Like [`render_mesh`], also returning counts. The steps of the module documentation, each a
/// function below.
pub fn render_mesh_stats(mesh: &TriMesh, opts: &RenderOptions) -> (Image, RenderStats) {
    let frame = Frame::new(opts);
    let mut stats = RenderStats {
        supersample: frame.ss as u32,
        ..Default::default()
    };

    // 1. Valid triangles.
    let (valid, used) = valid_triangles(mesh);
    stats.invalid = mesh.triangles.len() - valid.len();
    if valid.is_empty() {
        return (
            Image::new(frame.w as u32, frame.h as u32, opts.background),
            stats,
        );
    }

    // 2.–3. Normalisation, camera, projection fitted to the image; normals, scalars, lights.
    let camera = Camera::new(opts);
    let eye_dist = camera.persp;
    let cam = camera_space(mesh, &used, &camera);
    let verts = fit_to_image(&cam, &used, &camera, opts, &frame);
    let vnormals = if opts.shading == Shading::Smooth {
        vertex_normals(mesh, &valid, &cam, &camera)
    } else {
        Vec::new()
    };
    let (colours, range) = Colours::new(mesh, &valid, &used, opts);
    stats.range = range;
    let translucent = opts.transparency.map(|t| {
        if t.is_finite() {
            t.clamp(0.0, 1.0)
        } else {
            0.5
        }
    });
    let lut = match (translucent, colours.per_vertex()) {
        (Some(_), Some(m)) => (0..LUT)
            .map(|i| m.color(i as f64 / (LUT - 1) as f64).map(f32::from))
            .collect(),
        _ => Vec::new(),
    };
    let scene = Scene {
        mesh,
        opts,
        frame,
        cam,
        verts,
        vnormals,
        colours,
        lights: Lights::new(),
        eye_dist,
        translucent,
        lut,
    };

    if let Some(t) = scene.translucent {
        let (img, composited) = scene.blend(t, &valid, &mut stats);
        stats.composited = composited;
        return (img, stats);
    }

    // Triangle setup (parallel, order kept) and binning into bands.
    let setups: Vec<Setup> = valid.par_iter().map(|&t| scene.setup(t)).collect();
    let mut tris: Vec<Box<Tri>> = Vec::with_capacity(setups.len());
    for st in setups {
        match st {
            Setup::Degenerate => stats.degenerate += 1,
            Setup::Empty => stats.drawn += 1,
            Setup::Tri(t) => {
                stats.drawn += 1;
                tris.push(t);
            }
        }
    }
    let bins = bin_by_band(&tris, scene.frame.sh);

    // 4.–5. Bands in parallel.
    let (sw, sh) = (scene.frame.sw, scene.frame.sh);
    let mut samples = vec![0u8; sw * sh * 4];
    samples
        .par_chunks_mut(BAND * sw * 4)
        .enumerate()
        .for_each(|(bi, band)| scene.draw_band(bi * BAND, band, &bins[bi], &tris));

    // 6. Box filter down to the output size.
    (downsample(samples, &scene.frame), stats)
}

/// Image size and the supersampled grid.
struct Frame {
    w: usize,
    h: usize,
    /// Samples per pixel along each axis.
    ss: usize,
    /// Sample grid size.
    sw: usize,
    sh: usize,
}

impl Frame {
    fn new(opts: &RenderOptions) -> Self {
        let w = opts.width.clamp(1, 8192) as usize;
        let h = opts.height.clamp(1, 8192) as usize;
        let mut ss = opts.supersample.clamp(1, 4) as usize;
        while ss > 1 && (w * h * ss * ss) as u64 > MAX_SAMPLES {
            ss -= 1;
        }
        Frame {
            w,
            h,
            ss,
            sw: w * ss,
            sh: h * ss,
        }
    }
}

/// Step 1: the triangles with all corners present and finite, and the vertices they use.
fn valid_triangles(mesh: &TriMesh) -> (Vec<usize>, Vec<bool>) {
    let finite = |i: u32| {
        mesh.positions
            .get(i as usize)
            .is_some_and(|p| p.x.is_finite() && p.y.is_finite() && p.z.is_finite())
    };
    let valid: Vec<usize> = (0..mesh.triangles.len())
        .filter(|&t| mesh.triangles[t].iter().all(|&i| finite(i)))
        .collect();
    let mut used = vec![false; mesh.positions.len()];
    for &t in &valid {
        for &i in &mesh.triangles[t] {
            used[i as usize] = true;
        }
    }
    (valid, used)
}

/// The camera: basis (right, up, towards the eye) and the perspective distance.
struct Camera {
    right: Vector3,
    upv: Vector3,
    eye: Vector3,
    /// Distance of the eye from the origin (perspective), `None` for orthographic.
    persp: Option<f64>,
}

impl Camera {
    fn new(opts: &RenderOptions) -> Self {
        let (right, upv, eye) = camera_basis(opts);
        let persp = match opts.projection {
            Projection::Perspective { fov_deg } => {
                let f = fov_deg.clamp(1.0, 120.0).to_radians();
                Some(3f64.sqrt() / (0.5 * f).sin() + 1e-3)
            }
            Projection::Orthographic => None,
        };
        Camera {
            right,
            upv,
            eye,
            persp,
        }
    }
    /// A vector in camera coordinates.
    #[inline]
    fn to_cam(&self, v: &Vector3) -> Vector3 {
        Vector3::new(v.dot(&self.right), v.dot(&self.upv), v.dot(&self.eye))
    }
    /// Screen x, y, depth (larger is nearer) and 1/w of a camera-space point.
    #[inline]
    fn screen(&self, c: &Vector3) -> (f64, f64, f64, f64) {
        match self.persp {
            Some(d) => {
                let iw = 1.0 / (d - c.z);
                (c.x * iw, c.y * iw, iw, iw)
            }
            None => (c.x, c.y, c.z, 1.0),
        }
    }
}

/// Steps 2–3: the used vertices normalised without overflow (centre and half extent from
/// halved coordinates) and turned into camera space; unused vertices are 0.
fn camera_space(mesh: &TriMesh, used: &[bool], camera: &Camera) -> Vec<Vector3> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (i, p) in mesh.positions.iter().enumerate() {
        if used[i] {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let half: [f64; 3] = std::array::from_fn(|k| 0.5 * hi[k] - 0.5 * lo[k]);
    let centre_half: [f64; 3] = std::array::from_fn(|k| 0.25 * hi[k] + 0.25 * lo[k]);
    let rad_half = 0.5 * half.iter().fold(0.0f64, |a, &b| a.max(b));
    let norm_pos = |i: usize| -> Vector3 {
        let p = mesh.positions[i];
        if rad_half > 0.0 {
            Vector3::from_fn(|k, _| (0.5 * p[k] - centre_half[k]) / rad_half)
        } else {
            Vector3::zeros()
        }
    };
    (0..mesh.positions.len())
        .into_par_iter()
        .map(|i| {
            if used[i] {
                camera.to_cam(&norm_pos(i))
            } else {
                Vector3::zeros()
            }
        })
        .collect()
}

/// Step 3: the projected picture fitted into the sample grid with the margin.
fn fit_to_image(
    cam: &[Vector3],
    used: &[bool],
    camera: &Camera,
    opts: &RenderOptions,
    frame: &Frame,
) -> Vec<Vert> {
    let (mut sx0, mut sx1, mut sy0, mut sy1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (c, _) in cam.iter().zip(used).filter(|(_, &u)| u) {
        let (x, y, _, _) = camera.screen(c);
        sx0 = sx0.min(x);
        sx1 = sx1.max(x);
        sy0 = sy0.min(y);
        sy1 = sy1.max(y);
    }
    let (sw, sh) = (frame.sw, frame.sh);
    let margin = opts.margin.clamp(0.0, 0.45);
    let avail = (1.0 - 2.0 * margin) * sw.min(sh) as f64;
    let ext = (sx1 - sx0).max(sy1 - sy0);
    let k = if ext > 0.0 { avail / ext } else { 1.0 };
    let (cx, cy) = (0.5 * (sx0 + sx1), 0.5 * (sy0 + sy1));
    cam.iter()
        .map(|c| {
            let (x, y, depth, invw) = camera.screen(c);
            Vert {
                px: 0.5 * sw as f64 + (x - cx) * k,
                py: 0.5 * sh as f64 - (y - cy) * k,
                depth,
                invw,
            }
        })
        .collect()
}

/// The (unnormalised) normal of triangle `t` in camera space.
#[inline]
fn face_normal(mesh: &TriMesh, cam: &[Vector3], t: usize) -> Vector3 {
    let [a, b, c] = mesh.triangles[t];
    let (a, b, c) = (cam[a as usize], cam[b as usize], cam[c as usize]);
    (b - a).cross(&(c - a))
}

/// Unit vertex normals in camera space for smooth shading: the mesh's own if it has one per
/// vertex, else the sums of the adjacent face normals (area-weighted); 0 where undefined.
fn vertex_normals(
    mesh: &TriMesh,
    valid: &[usize],
    cam: &[Vector3],
    camera: &Camera,
) -> Vec<Vector3> {
    let n = mesh.positions.len();
    match &mesh.normals {
        Some(nr) if nr.len() == n => nr
            .iter()
            .map(|v| {
                let c = camera.to_cam(v);
                let l = c.norm();
                if l.is_finite() && l > 0.0 {
                    c / l
                } else {
                    Vector3::zeros()
                }
            })
            .collect(),
        _ => {
            let mut acc = vec![Vector3::zeros(); n];
            for &t in valid {
                let fnrm = face_normal(mesh, cam, t);
                if fnrm.iter().all(|v| v.is_finite()) {
                    for &i in &mesh.triangles[t] {
                        acc[i as usize] += fnrm;
                    }
                }
            }
            acc.iter()
                .map(|v| {
                    let l = v.norm();
                    if l > 0.0 && l.is_finite() {
                        v / l
                    } else {
                        Vector3::zeros()
                    }
                })
                .collect()
        }
    }
}

/// The scalars shown, as colour-map parameters.
struct Colours<'a> {
    /// The options' scalars when they have the right length.
    scalars: Option<&'a Scalars>,
    /// Parameter in [0, 1] per vertex or face (NaN = missing).
    tvals: Vec<f64>,
    cmap: Option<Colormap>,
}

impl<'a> Colours<'a> {
    /// The parameters and the value range mapped to the ends of the map.
    fn new(
        mesh: &TriMesh,
        valid: &[usize],
        used: &[bool],
        opts: &'a RenderOptions,
    ) -> (Self, Option<(f64, f64)>) {
        let n = mesh.positions.len();
        let scalars = opts
            .scalars
            .as_ref()
            .filter(|s| s.values.len() == if s.per_face { mesh.triangles.len() } else { n });
        let mut range = None;
        let tvals: Vec<f64> = match scalars {
            None => Vec::new(),
            Some(s) => {
                let r = s.range.or_else(|| {
                    if s.per_face {
                        finite_range(valid.iter().map(|&t| s.values[t]))
                    } else {
                        finite_range((0..n).filter(|&i| used[i]).map(|i| s.values[i]))
                    }
                });
                let (lo, hi) = r.unwrap_or((0.0, 1.0));
                range = Some((lo, hi));
                s.values.iter().map(|&v| normalize(v, lo, hi)).collect()
            }
        };
        let cmap = scalars.map(|s| s.colormap);
        (
            Colours {
                scalars,
                tvals,
                cmap,
            },
            range,
        )
    }
    fn per_face(&self) -> Option<Colormap> {
        match (self.cmap, self.scalars) {
            (Some(m), Some(s)) if s.per_face => Some(m),
            _ => None,
        }
    }
    fn per_vertex(&self) -> Option<Colormap> {
        match (self.cmap, self.scalars) {
            (Some(m), Some(s)) if !s.per_face => Some(m),
            _ => None,
        }
    }
}

/// A headlight and a key light (camera space, towards the light), Blinn–Phong.
struct Lights {
    head: Vector3,
    key: Vector3,
    half_key: Vector3,
}

impl Lights {
    fn new() -> Self {
        let head = Vector3::new(0.0, 0.0, 1.0);
        let key = Vector3::new(-0.45, 0.6, 0.66).normalize();
        Lights {
            head,
            key,
            half_key: (key + head).normalize(),
        }
    }
    /// The lit colour of a surface with unit normal `nrm` and colour `base`.
    #[inline]
    fn shade(&self, nrm: Vector3, base: [u8; 3]) -> [u8; 4] {
        let d1 = nrm.dot(&self.head).max(0.0);
        let d2 = nrm.dot(&self.key).max(0.0);
        let diff = 0.22 + 0.5 * d1 + 0.42 * d2;
        let spec = 0.22 * nrm.dot(&self.half_key).max(0.0).powi(40);
        let mut c = [0u8; 4];
        for k in 0..3 {
            c[k] = (base[k] as f64 * diff + 255.0 * spec)
                .round()
                .clamp(0.0, 255.0) as u8;
        }
        c[3] = 255;
        c
    }
}

/// Everything the triangle setup and the scan conversion read.
struct Scene<'a> {
    mesh: &'a TriMesh,
    opts: &'a RenderOptions,
    frame: Frame,
    /// Vertices in camera space.
    cam: Vec<Vector3>,
    /// Vertices on the sample grid.
    verts: Vec<Vert>,
    /// Unit vertex normals in camera space (smooth shading only).
    vnormals: Vec<Vector3>,
    colours: Colours<'a>,
    lights: Lights,
    /// Distance of the eye from the origin in camera space (perspective), `None`: orthographic.
    eye_dist: Option<f64>,
    /// Transparency t of alpha blending, `None` for the z-buffer.
    translucent: Option<f64>,
    /// Alpha blending with per-vertex scalars: the colour map at `i / (LUT − 1)`.
    lut: Vec<[f32; 3]>,
}

/// Triangle indices of the bands of `BAND` sample rows each triangle's box touches.
fn bin_by_band(tris: &[Box<Tri>], sh: usize) -> Vec<Vec<u32>> {
    let nbands = sh.div_ceil(BAND).max(1);
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); nbands];
    for (i, t) in tris.iter().enumerate() {
        for b in bins.iter_mut().take(t.y1 / BAND + 1).skip(t.y0 / BAND) {
            b.push(i as u32);
        }
    }
    bins
}

/// Alpha blending state of one band: per sample the colour composited so far (front to back)
/// and the transmittance left (`[r, g, b, T]`), and per tile the samples not yet saturated.
struct Composite {
    acc: Vec<[f32; 4]>,
    rows: usize,
    /// Unsaturated samples per tile (`TILE` columns of the band).
    open: Vec<u32>,
    /// Tiles with an unsaturated sample.
    open_tiles: usize,
    /// Unsaturated samples per row of each tile (`row · tiles + tile`): a triangle's row
    /// whose span lies in saturated row tiles is skipped before any edge test.
    row_open: Vec<u8>,
    /// Tiles per row.
    ntiles: usize,
    /// `1 − t` and `t`.
    opacity: f32,
    t: f32,
}

/// [`edge`] evaluated from the lexicographically smaller end, negated when that is `b`: the two
/// triangles of a shared edge get exactly opposite values at every sample (the plain edge
/// function rounds differently from each end, so a sample on the edge could be inside both or
/// neither), which [`owns_edge_samples`] needs. The ends are ordered once per triangle.
#[derive(Clone, Copy)]
struct SharedEdge {
    a: Vert,
    b: Vert,
    /// True when the ends were swapped (the value is negated).
    flip: bool,
}

impl SharedEdge {
    fn new(a: &Vert, b: &Vert) -> Self {
        if (a.px, a.py) <= (b.px, b.py) {
            SharedEdge {
                a: *a,
                b: *b,
                flip: false,
            }
        } else {
            SharedEdge {
                a: *b,
                b: *a,
                flip: true,
            }
        }
    }
    /// The edge function of the directed edge at (x, y).
    #[inline]
    fn at(&self, x: f64, y: f64) -> f64 {
        let e = edge(&self.a, &self.b, x, y);
        if self.flip {
            -e
        } else {
            e
        }
    }
    /// Its derivative in x.
    #[inline]
    fn dx(&self) -> f64 {
        let d = -(self.b.py - self.a.py);
        if self.flip {
            -d
        } else {
            d
        }
    }
}

/// The fill rule of alpha blending: a sample on an edge of `t` (`w`: its [`SharedEdge`]
/// functions, all ≥ 0) is `t`'s only if that edge is a left edge (the inside lies towards +x) or a horizontal
/// edge with the inside towards +y. Of two triangles sharing an edge exactly one owns the
/// samples on it, so a rectangle split along a diagonal through sample centres blends each
/// sample once (the inclusive test blended those twice). Opaque drawing does not need it: the
/// depth test keeps one of the two.
#[inline]
fn owns_edge_samples(t: &Tri, w: [f64; 3]) -> bool {
    let [p0, p1, p2] = &t.p;
    [(p1, p2), (p2, p0), (p0, p1)]
        .iter()
        .zip(w)
        .all(|((a, b), wi)| {
            if wi != 0.0 {
                return true;
            }
            // the gradient of edge(a, b, ·) is (−(b.py − a.py), b.px − a.px)
            let (gx, gy) = (a.py - b.py, b.px - a.px);
            gx > 0.0 || (gx == 0.0 && gy > 0.0)
        })
}

/// The span `xs..=xe` of sample row `fy` inside all three half-planes of `t` (one sample of
/// slack; the edge test per sample decides), clipped to the triangle's box.
#[inline]
fn row_span(t: &Tri, fy: f64) -> Option<(usize, usize)> {
    let [p0, p1, p2] = &t.p;
    let (mut xa, mut xb) = (t.x0 as f64, t.x1 as f64);
    for (a, b) in [(p1, p2), (p2, p0), (p0, p1)] {
        // edge(a, b, x, fy) = k * x + m
        let k = -(b.py - a.py);
        let m = edge(a, b, 0.0, fy);
        if k > 0.0 {
            xa = xa.max((-m / k - 0.5).floor() - 1.0);
        } else if k < 0.0 {
            xb = xb.min((-m / k - 0.5).ceil() + 1.0);
        }
    }
    if xa > xb {
        return None;
    }
    Some((xa.max(t.x0 as f64) as usize, xb.min(t.x1 as f64) as usize))
}

impl Scene<'_> {
    /// Triangle setup of triangle `t`: corner order, sample box, constant colours, depth key.
    fn setup(&self, t: usize) -> Setup {
        match self.cover(t) {
            Ok(c) => Setup::Tri(Box::new(self.make_tri(t, c))),
            Err(s) => s,
        }
    }

    /// Twice the signed screen area of triangle `t` (as [`Scene::cover`] computes it).
    fn signed_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.mesh.triangles[t];
        let (va, vb, vc) = (
            &self.verts[a as usize],
            &self.verts[b as usize],
            &self.verts[c as usize],
        );
        edge(va, vb, vc.px, vc.py)
    }

    /// The sample box of triangle `t`, or why it has none (degenerate, or covering no sample).
    fn cover(&self, t: usize) -> Result<Cover, Setup> {
        let (sw, sh) = (self.frame.sw, self.frame.sh);
        let [a, b, c] = self.mesh.triangles[t];
        let (va, vb, vc) = (
            self.verts[a as usize],
            self.verts[b as usize],
            self.verts[c as usize],
        );
        let signed = edge(&va, &vb, vc.px, vc.py);
        if signed == 0.0 || !signed.is_finite() {
            return Err(Setup::Degenerate);
        }
        let xmin = va.px.min(vb.px).min(vc.px);
        let xmax = va.px.max(vb.px).max(vc.px);
        let ymin = va.py.min(vb.py).min(vc.py);
        let ymax = va.py.max(vb.py).max(vc.py);
        // Samples at (i + 0.5); the covered range is ceil(min - 0.5) ..= floor(max - 0.5).
        let (fx0, fx1) = ((xmin - 0.5).ceil(), (xmax - 0.5).floor());
        let (fy0, fy1) = ((ymin - 0.5).ceil(), (ymax - 0.5).floor());
        if fx1 < 0.0
            || fy1 < 0.0
            || fx0 > (sw - 1) as f64
            || fy0 > (sh - 1) as f64
            || fx0 > fx1
            || fy0 > fy1
        {
            return Err(Setup::Empty);
        }
        // The sample grid is at most 8192 · 4 samples wide and high (`Frame::new`).
        Ok(Cover {
            signed,
            x0: fx0.max(0.0) as u32,
            x1: (fx1 as usize).min(sw - 1) as u32,
            y0: fy0.max(0.0) as u32,
            y1: (fy1 as usize).min(sh - 1) as u32,
        })
    }

    /// The setup of triangle `t` with sample box `cover`: corner order, constant colours and
    /// (with the z-buffer: alpha blending is unlit) the lighting and wireframe constants.
    fn make_tri(&self, t: usize, cover: Cover) -> Tri {
        let opts = self.opts;
        let [a, b, c] = self.mesh.triangles[t];
        let (va, vb, vc) = (
            self.verts[a as usize],
            self.verts[b as usize],
            self.verts[c as usize],
        );
        let signed = cover.signed;
        let lit = self.translucent.is_none();
        // Pixel y grows downwards, so a counter-clockwise (front) triangle has signed < 0.
        let back = signed > 0.0;
        let (p, ids) = if back {
            ([va, vb, vc], [a, b, c])
        } else {
            ([va, vc, vb], [a, c, b])
        };
        let lens = if lit {
            [
                (p[2].px - p[1].px).hypot(p[2].py - p[1].py),
                (p[0].px - p[2].px).hypot(p[0].py - p[2].py),
                (p[1].px - p[0].px).hypot(p[1].py - p[0].py),
            ]
        } else {
            [0.0; 3]
        };
        let face_n = if !lit {
            self.lights.head
        } else {
            let f = face_normal(self.mesh, &self.cam, t);
            let l = f.norm();
            let f = if l > 0.0 && l.is_finite() {
                f / l
            } else {
                self.lights.head
            };
            if back {
                -f
            } else {
                f
            }
        };
        let face_base = match self.colours.per_face() {
            Some(m) => m.color(self.colours.tvals[t]),
            None => {
                if back {
                    opts.back_color.unwrap_or(opts.color)
                } else {
                    opts.color
                }
            }
        };
        Tri {
            ids,
            p,
            x0: cover.x0 as usize,
            x1: cover.x1 as usize,
            y0: cover.y0 as usize,
            y1: cover.y1 as usize,
            inv_area: 1.0 / signed.abs(),
            lens,
            back,
            face_n,
            face_base,
            flat_col: if lit {
                self.lights.shade(face_n, face_base)
            } else {
                [0; 4]
            },
        }
    }

    /// Depth at the midpoint of the longest edge (in camera space): the two halves of a
    /// rectangle split along its diagonal get the same key, so the stable sort keeps them
    /// together.
    fn depth_key(&self, t: usize) -> f64 {
        let [a, b, c] = self.mesh.triangles[t];
        let (va, vb, vc) = (
            self.verts[a as usize],
            self.verts[b as usize],
            self.verts[c as usize],
        );
        let cam = &self.cam;
        let (ca, cb, cc) = (cam[a as usize], cam[b as usize], cam[c as usize]);
        let (lab, lbc, lca) = ((cb - ca).norm(), (cc - cb).norm(), (ca - cc).norm());
        if lab >= lbc && lab >= lca {
            0.5 * (va.depth + vb.depth)
        } else if lbc >= lca {
            0.5 * (vb.depth + vc.depth)
        } else {
            0.5 * (vc.depth + va.depth)
        }
    }

    /// Steps 4–5 for one band of sample rows starting at row `y_base`: the background, then
    /// the triangles binned to it in order.
    fn draw_band(&self, y_base: usize, band: &mut [u8], bin: &[u32], tris: &[Box<Tri>]) {
        let sw = self.frame.sw;
        let rows = band.len() / (sw * 4);
        for px in band.chunks_exact_mut(4) {
            px.copy_from_slice(&self.opts.background);
        }
        let mut zbuf = vec![f64::NEG_INFINITY; rows * sw];
        for &ti in bin {
            self.draw_triangle(&tris[ti as usize], y_base, rows, band, &mut zbuf);
        }
    }

    /// [`ReflectionLines`] over the lit colour `col` of a sample with unit normal `nn` at
    /// perspective-correct weights `b` of `t`.
    #[inline]
    fn stripe(
        &self,
        rl: &ReflectionLines,
        t: &Tri,
        b: [f64; 3],
        nn: Vector3,
        col: [u8; 4],
    ) -> [u8; 4] {
        let d = match self.eye_dist {
            None => Vector3::new(0.0, 0.0, -1.0),
            Some(e) => {
                let ids = t.ids;
                let p = b[0] * self.cam[ids[0] as usize]
                    + b[1] * self.cam[ids[1] as usize]
                    + b[2] * self.cam[ids[2] as usize];
                let v = p - Vector3::new(0.0, 0.0, e);
                let l = v.norm();
                if l > 0.0 && l.is_finite() {
                    v / l
                } else {
                    Vector3::new(0.0, 0.0, -1.0)
                }
            }
        };
        let theta = reflection_coordinate([d.x, d.y, d.z], [nn.x, nn.y, nn.z]);
        let u = theta * rl.lines.clamp(1, 1000) as f64 / std::f64::consts::PI;
        let frac = (u - u.round()).abs();
        if frac < 0.5 * rl.width.clamp(0.02, 0.98) {
            [rl.color[0], rl.color[1], rl.color[2], 255]
        } else {
            col
        }
    }

    /// Scan conversion of one triangle within a band.
    fn draw_triangle(
        &self,
        t: &Tri,
        y_base: usize,
        rows: usize,
        band: &mut [u8],
        zbuf: &mut [f64],
    ) {
        let sw = self.frame.sw;
        let [p0, p1, p2] = &t.p;
        let inv_area = t.inv_area;
        let ylo = t.y0.max(y_base);
        let yhi = t.y1.min(y_base + rows - 1);
        for y in ylo..=yhi {
            let fy = y as f64 + 0.5;
            let row = (y - y_base) * sw;
            let Some((xs, xe)) = row_span(t, fy) else {
                continue;
            };
            for x in xs..=xe {
                let fx = x as f64 + 0.5;
                // Edge functions: w0 opposite p0, etc. Positive inside (inclusive).
                let w = [
                    edge(p1, p2, fx, fy),
                    edge(p2, p0, fx, fy),
                    edge(p0, p1, fx, fy),
                ];
                if w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0 {
                    continue;
                }
                let l = [w[0] * inv_area, w[1] * inv_area, w[2] * inv_area];
                let depth = l[0] * p0.depth + l[1] * p1.depth + l[2] * p2.depth;
                let zi = row + x;
                if depth.partial_cmp(&zbuf[zi]) != Some(std::cmp::Ordering::Greater) {
                    continue;
                }
                zbuf[zi] = depth;
                let b = perspective_weights(t, w);
                let base = self.base_colour(t, b);
                let o = zi * 4;
                let col = self.lit_colour(t, b, base, w);
                band[o..o + 4].copy_from_slice(&col);
            }
        }
    }

    /// Steps 4–6 with alpha blending (transparency `t`): the covering triangles' sample boxes
    /// and depth keys, sorted back to front (ties in mesh order: the order of a stable sort;
    /// a total order, so the parallel sort gives it for any thread count), binned to bands
    /// and composited band by band ([`Scene::composite_band`]; a triangle's full setup is made
    /// only where it is not hidden). Returns the picture and the samples composited.
    fn blend(&self, t: f64, valid: &[usize], stats: &mut RenderStats) -> (Image, u64) {
        // Depth key, mesh index and sample box of each covering triangle, in one small array
        // sorted in place (collected with its exact size: no per-thread pieces to join); the
        // bins carry the box, so the hidden layers are skipped without another lookup.
        let mut order: Vec<(f64, u32, [u16; 4])> = valid
            .par_iter()
            .map(|&ti| match self.cover(ti) {
                Ok(c) => (
                    self.depth_key(ti),
                    ti as u32,
                    [c.x0, c.x1, c.y0, c.y1].map(|v| v as u16),
                ),
                // covers no sample: dropped below
                Err(_) => (0.0, u32::MAX, [0; 4]),
            })
            .collect();
        order.retain(|e| e.1 != u32::MAX);
        stats.degenerate = valid
            .par_iter()
            .filter(|&&ti| {
                let s = self.signed_area(ti);
                s == 0.0 || !s.is_finite()
            })
            .count();
        stats.drawn = valid.len() - stats.degenerate;
        // ties in mesh order (`valid` is increasing): a total order
        order.par_sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let (sw, sh) = (self.frame.sw, self.frame.sh);
        let nbands = sh.div_ceil(BAND).max(1);
        let mut counts = vec![0usize; nbands];
        for &(_, _, [_, _, y0, y1]) in &order {
            for c in &mut counts[y0 as usize / BAND..=y1 as usize / BAND] {
                *c += 1;
            }
        }
        let mut bins: Vec<Vec<BinEntry>> = counts.iter().map(|&n| Vec::with_capacity(n)).collect();
        for &(_, tri, [x0, x1, y0, y1]) in &order {
            let e = BinEntry {
                tri,
                x0,
                x1,
                y0,
                y1,
            };
            for b in &mut bins[y0 as usize / BAND..=y1 as usize / BAND] {
                b.push(e);
            }
        }
        drop(order);
        let mut samples = vec![0u8; sw * sh * 4];
        let composited = samples
            .par_chunks_mut(BAND * sw * 4)
            .enumerate()
            .map(|(bi, band)| self.composite_band(t, bi * BAND, band, &bins[bi]))
            .sum();
        (downsample(samples, &self.frame), composited)
    }

    /// Alpha blending of one band starting at sample row `y_base` (Hamann 1991, §2.2):
    /// the band's triangles are taken front to back (the reverse of the back-to-front order
    /// in `bin`), each sample keeping the colour composited so far `C` and the transmittance
    /// `T` of the layers in front; a layer of colour `c` makes `C += T (1 − t) c`,
    /// `T *= t`, and the background ends it: `C + T · background`. This is the back-to-front
    /// recurrence `c_new = (1 − t) c + t c_old` unrolled, `Σ_i (1 − t) tⁱ c_i + tⁿ bg`, rounded
    /// to 8 bits once instead of after every layer. A sample stops taking layers once
    /// `T ≤ 1/512` (`SATURATED`), a triangle is skipped when every tile it touches is
    /// saturated, and the band stops when all are. Returns the samples composited.
    fn composite_band(&self, t: f64, y_base: usize, band: &mut [u8], bin: &[BinEntry]) -> u64 {
        let sw = self.frame.sw;
        let rows = band.len() / (sw * 4);
        let ntiles = sw.div_ceil(TILE);
        let mut buf = Composite {
            acc: vec![[0.0, 0.0, 0.0, 1.0]; rows * sw],
            rows,
            open: (0..ntiles)
                .map(|k| (rows * (sw.min((k + 1) * TILE) - k * TILE)) as u32)
                .collect(),
            open_tiles: ntiles,
            row_open: (0..rows * ntiles)
                .map(|i| (sw.min((i % ntiles + 1) * TILE) - (i % ntiles) * TILE) as u8)
                .collect(),
            ntiles,
            opacity: (1.0 - t) as f32,
            t: t as f32,
        };
        let mut composited = 0;
        // t = 1: every layer is invisible.
        if t < 1.0 {
            for e in bin.iter().rev() {
                if buf.open_tiles == 0 {
                    break;
                }
                let (x0, x1) = (e.x0 as usize, e.x1 as usize);
                if (x0 / TILE..=x1 / TILE).all(|k| buf.open[k] == 0) {
                    continue;
                }
                let ti = e.tri as usize;
                let cover = Cover {
                    signed: self.signed_area(ti),
                    x0: e.x0 as u32,
                    x1: e.x1 as u32,
                    y0: e.y0 as u32,
                    y1: e.y1 as u32,
                };
                let tri = self.make_tri(ti, cover);
                composited += self.composite_triangle(&tri, y_base, &mut buf);
            }
        }
        let bg = self.opts.background.map(f32::from);
        for (px, a) in band.chunks_exact_mut(4).zip(&buf.acc) {
            let tr = a[3];
            // Non-negative sums: adding 0.5 and truncating rounds half away from zero, as
            // `f64::round` does; `as u8` saturates at 255.
            for k in 0..3 {
                px[k] = (a[k] + tr * bg[k] + 0.5) as u8;
            }
            px[3] = (255.0 * (1.0 - tr) + tr * bg[3] + 0.5) as u8;
        }
        composited
    }

    /// One triangle of [`Scene::composite_band`] over the unsaturated samples it covers.
    ///
    /// Which samples: per row, the samples whose [`SharedEdge`] functions are all ≥ 0 and
    /// that [`owns_edge_samples`] gives the triangle. Each edge function, computed in floating
    /// point, is monotone in x along a row (`C − D·(x − a)`: every operation rounds
    /// monotonically), so these samples form one interval: its ends are found by testing from
    /// the ends of [`row_span`] inwards, and the samples between them take no edge test (the
    /// same samples as testing each one).
    ///
    /// Their colour: the colour-map parameter is the perspective-correct interpolation
    /// `Σ wᵢ qᵢ τᵢ / Σ wᵢ qᵢ` (`wᵢ` the edge functions, `qᵢ` the corners' `1/w` over the area,
    /// `τᵢ` the corners' parameters), whose numerator and denominator are linear along a row:
    /// both are evaluated at the interval's first sample from its edge functions and stepped
    /// by their x-derivatives (`N₀ + k·dN`, no running sum). This is [`Scene::blend_colour`]'s
    /// value up to rounding (relative 1e-14), so a colour-table index (step 1/4095) differs
    /// only for a parameter within that of a half step; a corner without a value (NaN) takes
    /// [`Scene::blend_colour`] per sample.
    fn composite_triangle(&self, t: &Tri, y_base: usize, buf: &mut Composite) -> u64 {
        let sw = self.frame.sw;
        let [p0, p1, p2] = &t.p;
        let edges = [(p1, p2), (p2, p0), (p0, p1)].map(|(a, b)| SharedEdge::new(a, b));
        let w_at = |fx: f64, fy: f64| -> [f64; 3] { edges.map(|e| e.at(fx, fy)) };
        let takes =
            |w: [f64; 3]| !(w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0) && owns_edge_samples(t, w);
        // the colour-map parameter along a row: corners' parameters and weights per unit w
        let tvals = &self.colours.tvals;
        let tv = t.ids.map(|i| tvals.get(i as usize).copied().unwrap_or(0.0));
        let stepped = !self.lut.is_empty() && tv.iter().all(|v| v.is_finite());
        let q = [
            t.inv_area * p0.invw,
            t.inv_area * p1.invw,
            t.inv_area * p2.invw,
        ];
        let dw = edges.map(|e| e.dx());
        let d_s = dw[0] * q[0] + dw[1] * q[1] + dw[2] * q[2];
        let d_n = dw[0] * q[0] * tv[0] + dw[1] * q[1] * tv[1] + dw[2] * q[2] * tv[2];
        let ylo = t.y0.max(y_base);
        let yhi = t.y1.min(y_base + buf.rows - 1);
        let mut n = 0;
        for y in ylo..=yhi {
            let fy = y as f64 + 0.5;
            let row = (y - y_base) * sw;
            let Some((xa, xb)) = row_span(t, fy) else {
                continue;
            };
            let rt = (y - y_base) * buf.ntiles;
            if xa > xb
                || buf.row_open[rt + xa / TILE..=rt + xb / TILE]
                    .iter()
                    .all(|&o| o == 0)
            {
                continue;
            }
            // the interval of samples the triangle takes on this row
            let Some(xs) = (xa..=xb).find(|&x| takes(w_at(x as f64 + 0.5, fy))) else {
                continue;
            };
            let xe = (xs..=xb)
                .rev()
                .find(|&x| takes(w_at(x as f64 + 0.5, fy)))
                .unwrap_or(xs);
            let w0 = w_at(xs as f64 + 0.5, fy);
            let s0 = w0[0] * q[0] + w0[1] * q[1] + w0[2] * q[2];
            let n0 = w0[0] * q[0] * tv[0] + w0[1] * q[1] * tv[1] + w0[2] * q[2] * tv[2];
            for x in xs..=xe {
                let zi = row + x;
                let tr = buf.acc[zi][3];
                if tr <= SATURATED {
                    continue;
                }
                let c = if self.lut.is_empty() {
                    t.face_base.map(f32::from)
                } else {
                    let k = (x - xs) as f64;
                    let tt = (n0 + k * d_n) / (s0 + k * d_s);
                    if stepped && tt.is_finite() {
                        self.lut_colour(tt)
                    } else {
                        let w = w_at(x as f64 + 0.5, fy);
                        self.blend_colour(t, perspective_weights(t, w))
                    }
                };
                let k = tr * buf.opacity;
                let nt = tr * buf.t;
                let a = &mut buf.acc[zi];
                a[0] += k * c[0];
                a[1] += k * c[1];
                a[2] += k * c[2];
                a[3] = nt;
                n += 1;
                if nt <= SATURATED {
                    let tile = x / TILE;
                    buf.row_open[rt + tile] -= 1;
                    buf.open[tile] -= 1;
                    if buf.open[tile] == 0 {
                        buf.open_tiles -= 1;
                    }
                }
            }
        }
        n
    }

    /// The unlit colour of alpha blending at weights `b`: [`Scene::base_colour`] with the
    /// colour map read from the table `lut` (nearest of 4096 parameters).
    #[inline]
    fn blend_colour(&self, t: &Tri, b: [f64; 3]) -> [f32; 3] {
        if self.lut.is_empty() {
            return t.face_base.map(f32::from);
        }
        let tt = self.corner_param(t, b);
        if tt.is_nan() {
            return super::colormap::MISSING.map(f32::from);
        }
        self.lut_colour(tt)
    }

    /// The colour-map parameter `tt` read from the table `lut` (nearest of its entries).
    #[inline]
    fn lut_colour(&self, tt: f64) -> [f32; 3] {
        let i = (tt.clamp(0.0, 1.0) * (LUT - 1) as f64 + 0.5) as usize;
        self.lut[i.min(LUT - 1)]
    }

    /// The per-vertex colour parameter at barycentric weights `b` (corner order of `t`),
    /// interpolated; where a corner has no value (NaN), the nearest corner's (itself NaN when
    /// that corner has none).
    #[inline]
    fn corner_param(&self, t: &Tri, b: [f64; 3]) -> f64 {
        let tvals = &self.colours.tvals;
        let tv = t.ids.map(|i| tvals[i as usize]);
        let tt = b[0] * tv[0] + b[1] * tv[1] + b[2] * tv[2];
        if !tt.is_nan() {
            return tt;
        }
        let j = if b[0] >= b[1] && b[0] >= b[2] {
            0
        } else if b[1] >= b[2] {
            1
        } else {
            2
        };
        tv[j]
    }

    /// The unlit colour at barycentric weights `b` (corner order of `t`): per-vertex scalars
    /// interpolated (a missing corner value: the nearest corner decides), else the face's.
    #[inline]
    fn base_colour(&self, t: &Tri, b: [f64; 3]) -> [u8; 3] {
        let Some(m) = self.colours.per_vertex() else {
            return t.face_base;
        };
        m.color(self.corner_param(t, b))
    }

    /// The lit colour of a sample (z-buffer mode), with the wireframe where the sample is
    /// within half a wire width of an edge (`w`: the edge functions).
    #[inline]
    fn lit_colour(&self, t: &Tri, b: [f64; 3], base: [u8; 3], w: [f64; 3]) -> [u8; 4] {
        let opts = self.opts;
        let smooth_n = (opts.shading == Shading::Smooth).then(|| {
            let (vn, ids) = (&self.vnormals, t.ids);
            let nn = b[0] * vn[ids[0] as usize]
                + b[1] * vn[ids[1] as usize]
                + b[2] * vn[ids[2] as usize];
            let l = nn.norm();
            if l > 1e-12 {
                let nn = nn / l;
                if t.back {
                    -nn
                } else {
                    nn
                }
            } else {
                t.face_n
            }
        });
        let mut col = if let Some(nn) = smooth_n {
            self.lights.shade(nn, base)
        } else if self.colours.per_vertex().is_some() {
            self.lights.shade(t.face_n, base)
        } else {
            t.flat_col
        };
        if let Some(rl) = &opts.reflection_lines {
            col = self.stripe(rl, t, b, smooth_n.unwrap_or(t.face_n), col);
        }
        if opts.wireframe {
            let wire_half = 0.55 * self.frame.ss as f64;
            let lens = t.lens;
            let dist = (w[0] / lens[0]).min(w[1] / lens[1]).min(w[2] / lens[2]);
            if dist < wire_half {
                col = [
                    opts.wire_color[0],
                    opts.wire_color[1],
                    opts.wire_color[2],
                    255,
                ];
            }
        }
        col
    }
}

/// Perspective-correct barycentric weights of a sample with edge functions `w` in `t`.
#[inline]
fn perspective_weights(t: &Tri, w: [f64; 3]) -> [f64; 3] {
    let [p0, p1, p2] = &t.p;
    let inv_area = t.inv_area;
    let pw = [
        w[0] * inv_area * p0.invw,
        w[1] * inv_area * p1.invw,
        w[2] * inv_area * p2.invw,
    ];
    let s = pw[0] + pw[1] + pw[2];
    [pw[0] / s, pw[1] / s, pw[2] / s]
}

/// Step 6: each pixel the average of its `ss × ss` samples (rounded).
fn downsample(samples: Vec<u8>, frame: &Frame) -> Image {
    let (w, h, ss, sw) = (frame.w, frame.h, frame.ss, frame.sw);
    if ss == 1 {
        return Image {
            width: w as u32,
            height: h as u32,
            rgba: samples,
        };
    }
    let mut rgba = vec![0u8; w * h * 4];
    let n2 = (ss * ss) as u32;
    rgba.par_chunks_mut(w * 4).enumerate().for_each(|(y, out)| {
        for x in 0..w {
            let mut acc = [0u32; 4];
            for dy in 0..ss {
                let row = (y * ss + dy) * sw;
                for dx in 0..ss {
                    let o = (row + x * ss + dx) * 4;
                    for k in 0..4 {
                        acc[k] += samples[o + k] as u32;
                    }
                }
            }
            for k in 0..4 {
                out[x * 4 + k] = ((acc[k] + n2 / 2) / n2) as u8;
            }
        }
    });
    Image {
        width: w as u32,
        height: h as u32,
        rgba,
    }
}

/// Camera basis (right, up, towards-eye) for the options' azimuth, elevation and up axis:
/// screen x = p·right, screen y = p·up, depth towards the viewer = p·eye (orthographic view).
pub fn camera_basis(opts: &RenderOptions) -> (Vector3, Vector3, Vector3) {
    let (up, front0, right0) = match opts.up {
        UpAxis::Y => (Vector3::y(), Vector3::z(), Vector3::x()),
        UpAxis::Z => (Vector3::z(), -Vector3::y(), Vector3::x()),
    };
    let az = if opts.azimuth_deg.is_finite() {
        opts.azimuth_deg.to_radians()
    } else {
        0.0
    };
    let el = if opts.elevation_deg.is_finite() {
        opts.elevation_deg.clamp(-90.0, 90.0).to_radians()
    } else {
        0.0
    };
    let horiz = az.cos() * front0 + az.sin() * right0;
    let eye = (el.cos() * horiz + el.sin() * up).normalize();
    // Right: horizontal, perpendicular to the viewing direction (well defined even at ±90°).
    let right = (az.cos() * right0 - az.sin() * front0).normalize();
    let upv = eye.cross(&right).normalize();
    (right, upv, eye)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;

    fn quad(z: f64, s: f64) -> TriMesh {
        TriMesh::new(
            vec![
                Point3::new(-s, -s, z),
                Point3::new(s, -s, z),
                Point3::new(s, s, z),
                Point3::new(-s, s, z),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
    }

    fn front_ortho() -> RenderOptions {
        RenderOptions {
            width: 40,
            height: 40,
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
            projection: Projection::Orthographic,
            shading: Shading::Flat,
            supersample: 1,
            margin: 0.0,
            ..Default::default()
        }
    }

    #[test]
    fn camera_basis_is_orthonormal_and_right_handed() {
        for up in [UpAxis::Y, UpAxis::Z] {
            for (az, el) in [(0.0, 0.0), (35.0, 25.0), (-120.0, 90.0), (10.0, -90.0)] {
                let o = RenderOptions {
                    azimuth_deg: az,
                    elevation_deg: el,
                    up,
                    ..Default::default()
                };
                let (r, u, e) = camera_basis(&o);
                assert!((r.norm() - 1.0).abs() < 1e-12 && (u.norm() - 1.0).abs() < 1e-12);
                assert!(r.dot(&u).abs() < 1e-12 && r.dot(&e).abs() < 1e-12);
                assert!((r.cross(&u) - e).norm() < 1e-12);
            }
        }
        // Y up, az 0: looking from +z, x to the right.
        let (r, u, e) = camera_basis(&front_ortho());
        assert!((r - Vector3::x()).norm() < 1e-12);
        assert!((u - Vector3::y()).norm() < 1e-12);
        assert!((e - Vector3::z()).norm() < 1e-12);
    }

    #[test]
    fn front_facing_quad_fills_image() {
        let img = render_mesh(&quad(0.0, 1.0), &front_ortho());
        let bg = [255, 255, 255, 255];
        let covered = img.rgba.chunks(4).filter(|p| *p != bg).count();
        assert_eq!(covered, 40 * 40);
        // Facing the headlight: bright but not white.
        let c = img.get(20, 20);
        assert!(c[0] > 150 && c[0] < 255, "{c:?}");
    }

    #[test]
    fn back_color_marks_flipped_faces() {
        let mut m = quad(0.0, 1.0);
        m.triangles[1] = [0, 3, 2];
        let o = RenderOptions {
            back_color: Some([255, 0, 0]),
            color: [0, 0, 255],
            ..front_ortho()
        };
        let img = render_mesh(&m, &o);
        // Triangle 0 (front) covers the lower right, triangle 1 (back) the upper left.
        let lr = img.get(35, 35);
        let ul = img.get(4, 4);
        assert!(lr[2] > lr[0], "{lr:?}");
        assert!(ul[0] > ul[2], "{ul:?}");
    }

    #[test]
    fn invalid_triangles_are_skipped() {
        let mut m = quad(0.0, 1.0);
        m.triangles.push([0, 1, 99]);
        m.positions.push(Point3::new(f64::NAN, 0.0, 0.0));
        m.triangles.push([0, 1, 4]);
        m.triangles.push([0, 0, 1]);
        let (img, st) = render_mesh_stats(&m, &front_ortho());
        assert_eq!(st.invalid, 2);
        assert_eq!(st.degenerate, 1);
        assert_eq!(st.drawn, 2);
        assert_eq!(img.width, 40);
    }
}
