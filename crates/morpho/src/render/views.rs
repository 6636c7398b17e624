//! Hamann's volume views (1991, ch. 2; notes part F) as pictures, for rectilinear volumes and
//! for functions given by formula ([`Formula`]):
//!
//! - [`View::Subdivision`] (§2.2, Figs 2.2–2.4): `q_x × q_y × q_z` sub-boxes separated by gaps
//!   of ratio α ([`subbox_starts`]), faces evaluated on `(k+1)²` points (trilinear interpolation
//!   of a volume, or the formula), Gouraud-coloured; optional centroid links to the six
//!   neighbours drawn as thin grey tubes. Curvilinear domains (Fig. 2.4): the sub-boxes are laid
//!   out in uvw-space and mapped by [`Formula::map`].
//! - [`View::Transparency`] (§2.2, Figs 2.5–2.6): the three families of grid rectangles
//!   (count [`transparency_rectangle_count`], the corrected closed form of notes F.2), sorted
//!   back to front and alpha-blended `c_new = (1 − t) c_poly + t c_old` by the rasterizer
//!   ([`super::RenderOptions::transparency`]; the sort key is the rectangle's centre, which for
//!   the axis-parallel rectangles of one family orders them as Hamann's nearest corner does).
//!   The rasterizer evaluates that recurrence front to back in the same order (one rounding
//!   to 8 bits, a sample stops once the layers behind it cannot move it by half a level), so
//!   the hidden layers cost a bounding-box test, not a blend. There is no empty space to skip:
//!   every rectangle has opacity 1 − t whatever its value (t = 1 draws the background only).
//! - [`View::Slices`] (§2.3, first possibility): [`super::orthogonal_slices`].
//! - [`View::Heights`] (§2.3, second possibility, Fig. 2.9): the three middle slices sampled on
//!   `(k+1)²` points, their graphs triangulated by I₁/I₂ ([`height_surface_mesh`], `2k²`
//!   triangles each) or drawn as curve networks, each in its own unit sub-box over a base plane
//!   parallel to its slice (so the graphs cannot intersect — the notes' choice), beside the
//!   domain box with the three slice rectangles for orientation.
//!
//! Bad input: a volume without a finite value or with one sample along an axis (3D views) is a
//! [`RenderError`]; a constant volume gives a picture with a note written on it.
//!
//! Cost: linear in the primitives drawn plus the rasterizer's O(covered samples) (for the
//! transparency view: O(n log n) for the sort plus samples × layers in front of saturation).

/// A map of domain points (the identity for volumes, a formula's parameter map otherwise).
type PointMap = Box<dyn Fn([f64; 3]) -> [f64; 3]>;

use super::colormap::{finite_range, Colormap};
use super::font::draw_text;
use super::legend::{label_num, with_colorbar};
use super::raster::{render_mesh_stats, RenderOptions, Scalars, Shading, UpAxis};
use super::slice::{middle, orthogonal_slices, Axis, SliceOptions};
use super::subdivision::{grid_planes_mesh, subdivision_mesh_with, trilinear};
use super::{Formula, Image, RenderError};
use crate::geom::{Point3, Vector3};
use crate::mesh::{Property, ScalarKind, TriMesh};
use crate::volume::Volume;

/// What is drawn: a sampled volume or a function given by formula.
#[derive(Debug, Clone, Copy)]
pub enum Source<'a> {
    /// Rectilinear samples (values between samples by trilinear interpolation).
    Volume(&'a Volume),
    /// A formula with its domain; `grid` cells per axis where samples are needed
    /// (transparency, slices).
    Formula {
        /// The function.
        formula: Formula,
        /// Cells per axis of the sampling grid.
        grid: usize,
    },
}

/// Curve network or shaded surface for [`View::Heights`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum HeightStyle {
    /// I₁/I₂ triangles, smooth-shaded.
    #[default]
    Surface,
    /// The grid lines of the graph (both directions) as thin tubes.
    Network,
}

/// One of Hamann's views with its parameters.
#[derive(Debug, Clone, PartialEq)]
pub enum View {
    /// Sub-boxes with gaps (§2.2).
    Subdivision {
        /// Boxes per axis (each ≥ 1).
        q: [usize; 3],
        /// Gap ratios (gap / box edge, each ≥ 0).
        alpha: [f64; 3],
        /// Samples per box edge minus one (≥ 1; 1 = corners only).
        k: usize,
        /// Draw links between the centroids of neighbouring boxes.
        links: bool,
    },
    /// Alpha-blended grid rectangles (§2.2).
    Transparency {
        /// Resample on `(n+1)³` points; `None`: the volume's own grid (a formula uses its grid).
        n: Option<usize>,
        /// Transparency t in [0, 1] (0 opaque).
        t: f64,
    },
    /// Three orthogonal coloured slices through the middle (§2.3).
    Slices,
    /// Height surfaces of the three middle slices (§2.3, Fig. 2.9).
    Heights {
        /// Grid cells per slice side (k = l, ≥ 1).
        k: usize,
        /// Surface or curve network.
        style: HeightStyle,
    },
}

/// Camera, size and colours of a view.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewOptions {
    /// Camera and image (its `scalars`, `shading` and `transparency` are set by the view).
    pub render: RenderOptions,
    /// The colour map.
    pub colormap: Colormap,
    /// Values mapped to the ends of the map (`None`: the range of the values drawn).
    pub range: Option<(f64, f64)>,
    /// Append a colour bar.
    pub legend: bool,
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            render: RenderOptions {
                up: UpAxis::Z,
                ..Default::default()
            },
            colormap: Colormap::Viridis,
            range: None,
            legend: true,
        }
    }
}

/// A view's picture and what it drew.
#[derive(Debug, Clone)]
pub struct ViewPicture {
    /// The picture (with its colour bar when asked).
    pub image: Image,
    /// Primitives: boxes, rectangles, slices or graph triangles.
    pub primitives: usize,
    /// Triangles sent to the rasterizer.
    pub triangles: usize,
    /// Value range mapped to the colour map.
    pub range: (f64, f64),
    /// Remarks written on the picture (e.g. a constant volume).
    pub notes: Vec<String>,
}

/// Hamann's rectangle count of the transparency view on an `n_x × n_y × n_z`-cell grid
/// (notes F.2, the printed formula corrected):
/// `n_x n_y (n_z+1) + n_x (n_y+1) n_z + (n_x+1) n_y n_z = 3 n_x n_y n_z + n_x n_y + n_x n_z + n_y n_z`.
///
/// ```
/// assert_eq!(morpho::render::transparency_rectangle_count([8, 8, 8]), 3 * 512 + 3 * 64);
/// ```
pub fn transparency_rectangle_count(n: [usize; 3]) -> usize {
    let [a, b, c] = n;
    3 * a * b * c + a * b + a * c + b * c
}

/// The value of the source at a point of xyz-space.
fn value_at(src: &Source, p: [f64; 3]) -> f64 {
    match src {
        Source::Volume(v) => trilinear(v, p),
        Source::Formula { formula, .. } => formula.eval(p),
    }
}

/// The xyz bounding box of the source.
fn bounds(src: &Source) -> ([f64; 3], [f64; 3]) {
    match src {
        Source::Volume(v) => (
            std::array::from_fn(|a| v.coord(a, 0)),
            std::array::from_fn(|a| v.coord(a, v.dims[a] - 1)),
        ),
        Source::Formula { formula, .. } => formula.bounds(),
    }
}

/// The volume checks shared by the views: not empty, some finite value, and (for 3D views)
/// an extent along every axis.
fn check_volume(v: &Volume, need_extent: bool) -> Result<(), RenderError> {
    v.validate()?;
    if v.dims.contains(&0) {
        return Err(RenderError::EmptyVolume { dims: v.dims });
    }
    if !v.data.iter().any(|x| x.is_finite()) {
        return Err(RenderError::NoFiniteValues {
            samples: v.data.len(),
        });
    }
    if need_extent {
        for a in 0..3 {
            let ext = v.coord(a, v.dims[a] - 1) - v.coord(a, 0);
            if v.dims[a] < 2 || !(ext > 0.0 && ext.is_finite()) {
                return Err(RenderError::FlatVolume {
                    axis: ["x", "y", "z"][a],
                });
            }
        }
    }
    Ok(())
}

fn param(ok: bool, what: &str) -> Result<(), RenderError> {
    if ok {
        Ok(())
    } else {
        Err(RenderError::ViewParameter { what: what.into() })
    }
}

/// The sub-box mesh of [`View::Subdivision`] (vertex property `value`; links have NaN).
pub fn subdivision_view_mesh(
    src: &Source,
    q: [usize; 3],
    alpha: [f64; 3],
    k: usize,
    links: bool,
) -> Result<TriMesh, RenderError> {
    if let Source::Volume(v) = src {
        check_volume(v, true)?;
    }
    if q.contains(&0) || k == 0 {
        return Err(RenderError::SubBoxes { boxes: q, k });
    }
    if alpha.iter().any(|a| !a.is_finite() || *a < 0.0) {
        return Err(RenderError::GapRatios { ratios: alpha });
    }
    let cap = q
        .iter()
        .try_fold(12 * k * k, |acc, &x| acc.checked_mul(x))
        .filter(|&t| t <= super::subdivision::MAX_TRIANGLES)
        .ok_or(RenderError::TooManyBoxTriangles {
            max: super::subdivision::MAX_TRIANGLES,
        })?;
    let (lo, hi, map): ([f64; 3], [f64; 3], PointMap) = match src {
        Source::Volume(_) => {
            let (lo, hi) = bounds(src);
            (lo, hi, Box::new(|p| p))
        }
        Source::Formula { formula, .. } => {
            let (lo, hi) = formula.param_box();
            let f = *formula;
            (lo, hi, Box::new(move |p| f.map(p)))
        }
    };
    let mut m = subdivision_mesh_with(lo, hi, q, alpha, k, cap, |uvw| {
        let p = map(uvw);
        (Point3::new(p[0], p[1], p[2]), value_at(src, p))
    });
    if links {
        let starts: [(Vec<f64>, f64); 3] = std::array::from_fn(|a| {
            super::subdivision::subbox_starts(lo[a], hi[a], q[a], alpha[a])
        });
        let centre = |r: [usize; 3]| -> Point3 {
            let c: [f64; 3] = std::array::from_fn(|a| starts[a].0[r[a]] + 0.5 * starts[a].1);
            let p = map(c);
            Point3::new(p[0], p[1], p[2])
        };
        let diag = (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt();
        let width = 0.004 * diag.max(f64::MIN_POSITIVE);
        let mut tubes = Tubes::default();
        for t in 0..q[2] {
            for s in 0..q[1] {
                for r in 0..q[0] {
                    let here = [r, s, t];
                    for a in 0..3 {
                        if here[a] + 1 < q[a] {
                            let mut next = here;
                            next[a] += 1;
                            tubes.add(centre(here), centre(next), width, f64::NAN);
                        }
                    }
                }
            }
        }
        tubes.append_to(&mut m);
    }
    Ok(m)
}

/// Thin square tubes for lines (links, box edges, curve networks) in a z-buffered picture.
#[derive(Default)]
struct Tubes {
    positions: Vec<Point3>,
    values: Vec<f64>,
    triangles: Vec<[u32; 3]>,
}

impl Tubes {
    /// A tube of half-width `w` from `a` to `b` with value `f` (four sides, eight triangles).
    fn add(&mut self, a: Point3, b: Point3, w: f64, f: f64) {
        let d = b - a;
        let len = d.norm();
        if !(len > 0.0 && len.is_finite()) {
            return;
        }
        let d = d / len;
        let helper = if d.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let u = d.cross(&helper).normalize() * w;
        let v = d.cross(&u).normalize() * w;
        let base = self.positions.len() as u32;
        for end in [a, b] {
            for off in [u + v, u - v, -u - v, -u + v] {
                self.positions.push(end + off);
                self.values.push(f);
            }
        }
        for i in 0..4u32 {
            let j = (i + 1) % 4;
            let (a0, a1, b0, b1) = (base + i, base + j, base + 4 + i, base + 4 + j);
            self.triangles.push([a0, a1, b1]);
            self.triangles.push([a0, b1, b0]);
        }
    }
    /// Appends the tubes to a mesh with one vertex property (`value`).
    fn append_to(self, m: &mut TriMesh) {
        let off = m.positions.len() as u32;
        m.positions.extend(self.positions);
        m.triangles.extend(
            self.triangles
                .into_iter()
                .map(|t| [t[0] + off, t[1] + off, t[2] + off]),
        );
        if let Some(p) = m.vertex_props.first_mut() {
            p.values.extend(self.values);
        }
    }
}

/// The grid rectangles of [`View::Transparency`] as a mesh (two triangles per rectangle,
/// vertex property `value`), and the grid's cells per axis.
pub fn transparency_view_mesh(
    src: &Source,
    n: Option<usize>,
) -> Result<(TriMesh, [usize; 3]), RenderError> {
    let resampled;
    let vol = match (src, n) {
        (Source::Volume(v), None) => {
            check_volume(v, true)?;
            *v
        }
        (Source::Volume(v), Some(n)) => {
            check_volume(v, true)?;
            param(
                (1..=1024).contains(&n),
                "transparency grid n must be 1..=1024",
            )?;
            let (lo, hi) = bounds(src);
            resampled = Volume::from_fn([n + 1; 3], lo, hi, |x, y, z| trilinear(v, [x, y, z]));
            &resampled
        }
        (Source::Formula { formula, grid }, n) => {
            resampled = formula.sample(n.unwrap_or(*grid))?;
            &resampled
        }
    };
    let cells = vol.dims.map(|d| d - 1);
    Ok((grid_planes_mesh(vol, [1, 1, 1])?, cells))
}

/// The graph of the slice of `src` normal to `axis` at coordinate `c`, sampled on a
/// `(k+1) × (l+1)` grid of the slice rectangle, as a mesh in the unit square
/// (in-plane coordinates → [0, 1]², value → height in [0, 1] by `range`), triangulated by
/// Hamann's I₁ = ((i,j),(i+1,j),(i+1,j+1)) and I₂ = ((i,j),(i+1,j+1),(i,j+1)): `2 k l`
/// triangles (those with a NaN corner left out). Vertex property `value`. Height is along z.
///
/// ```
/// use morpho::render::{height_surface_mesh, Axis, Formula, Source};
/// let src = Source::Formula { formula: Formula::HamannExp, grid: 16 };
/// let m = height_surface_mesh(&src, Axis::Z, 19.5, 30, 30, None).unwrap();
/// assert_eq!(m.triangles.len(), 2 * 30 * 30);
/// ```
pub fn height_surface_mesh(
    src: &Source,
    axis: Axis,
    c: f64,
    k: usize,
    l: usize,
    range: Option<(f64, f64)>,
) -> Result<TriMesh, RenderError> {
    if let Source::Volume(v) = src {
        check_volume(v, false)?;
    }
    param(
        (1..=2048).contains(&k) && (1..=2048).contains(&l),
        "height surface grid k, l must be 1..=2048",
    )?;
    let (lo, hi) = bounds(src);
    let (ku, kv) = axis.in_plane();
    let mut values = Vec::with_capacity((k + 1) * (l + 1));
    let mut uv = Vec::with_capacity((k + 1) * (l + 1));
    for j in 0..=l {
        for i in 0..=k {
            let (s, t) = (i as f64 / k as f64, j as f64 / l as f64);
            let mut p = [0.0; 3];
            p[axis.index()] = c;
            p[ku] = lo[ku] + s * (hi[ku] - lo[ku]);
            p[kv] = lo[kv] + t * (hi[kv] - lo[kv]);
            let f = match src {
                Source::Formula { formula, .. } if !formula.contains(p) => f64::NAN,
                _ => value_at(src, p),
            };
            values.push(f);
            uv.push((s, t));
        }
    }
    let (flo, fhi) = range
        .or_else(|| finite_range(values.iter().copied()))
        .unwrap_or((0.0, 1.0));
    let positions = uv
        .iter()
        .zip(&values)
        .map(|(&(s, t), &f)| {
            let h = super::colormap::normalize(f, flo, fhi);
            Point3::new(s, t, if h.is_nan() { 0.0 } else { h })
        })
        .collect();
    let id = |i: usize, j: usize| (j * (k + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * k * l);
    for j in 0..l {
        for i in 0..k {
            for t in [
                [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
            ] {
                if t.iter().all(|&v| !values[v as usize].is_nan()) {
                    triangles.push(t);
                }
            }
        }
    }
    let mut m = TriMesh::new(positions, triangles);
    m.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values,
    });
    Ok(m)
}

/// The scene of [`View::Heights`]: the domain box with the three slice rectangles and the
/// three graphs in their own sub-boxes. Returns the mesh and the number of graph triangles.
pub fn heights_view_mesh(
    src: &Source,
    k: usize,
    style: HeightStyle,
    range: Option<(f64, f64)>,
) -> Result<(TriMesh, usize), RenderError> {
    let (lo, hi) = bounds(src);
    let mid: [f64; 3] = match src {
        Source::Volume(v) => {
            check_volume(v, true)?;
            let m = middle(v);
            std::array::from_fn(|a| v.coord(a, m[a]))
        }
        Source::Formula { .. } => std::array::from_fn(|a| 0.5 * (lo[a] + hi[a])),
    };
    let graphs: Vec<TriMesh> = (0..3)
        .map(|a| {
            let axis = Axis::from_index(a).unwrap_or(Axis::Z);
            height_surface_mesh(src, axis, mid[a], k, k, range)
        })
        .collect::<Result<_, _>>()?;
    let all: Vec<f64> = graphs
        .iter()
        .flat_map(|g| g.vertex_props[0].values.iter().copied())
        .collect();
    let flo = range
        .or_else(|| finite_range(all.iter().copied()))
        .map_or(0.0, |r| r.0);
    let graph_triangles = graphs.iter().map(|g| g.triangles.len()).sum();
    let mut scene = TriMesh::new(Vec::new(), Vec::new());
    scene.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values: Vec::new(),
    });
    let gap = 1.45;
    let mut edges = Tubes::default();
    let w = 0.006;
    // The domain box (unit cube at the origin) with its three slice rectangles.
    let rel: [f64; 3] = std::array::from_fn(|a| {
        let e = hi[a] - lo[a];
        if e > 0.0 {
            (mid[a] - lo[a]) / e
        } else {
            0.5
        }
    });
    let mut rects = TriMesh::new(Vec::new(), Vec::new());
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        let base = rects.positions.len() as u32;
        for (s, t) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            let mut p = [0.0; 3];
            p[a] = rel[a];
            p[u] = s;
            p[v] = t;
            rects.positions.push(Point3::new(p[0], p[1], p[2]));
        }
        rects.triangles.push([base, base + 1, base + 2]);
        rects.triangles.push([base, base + 2, base + 3]);
    }
    rects.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values: vec![f64::NAN; rects.positions.len()],
    });
    append(&mut scene, &rects, [0.0; 3]);
    cube_edges(&mut edges, [0.0; 3], w, flo);
    // Graph of slice a in the sub-box at offsets[a], its base plane normal to axis a.
    let offsets = [[gap, 0.0, 0.0], [0.0, gap, 0.0], [gap, gap, 0.0]];
    for (a, g) in graphs.iter().enumerate() {
        let (ku, kv) = Axis::from_index(a).unwrap_or(Axis::Z).in_plane();
        let mut placed = g.clone();
        for p in placed.positions.iter_mut() {
            let mut q = [0.0; 3];
            q[ku] = p.x;
            q[kv] = p.y;
            q[a] = p.z;
            *p = Point3::new(q[0], q[1], q[2]);
        }
        cube_edges(&mut edges, offsets[a], w, flo);
        match style {
            HeightStyle::Surface => append(&mut scene, &placed, offsets[a]),
            HeightStyle::Network => {
                let o = Vector3::from(offsets[a]);
                let vals = &placed.vertex_props[0].values;
                let id = |i: usize, j: usize| j * (k + 1) + i;
                for j in 0..=k {
                    for i in 0..=k {
                        for (ni, nj) in [(i + 1, j), (i, j + 1)] {
                            if ni > k || nj > k {
                                continue;
                            }
                            let (x, y) = (id(i, j), id(ni, nj));
                            let f = 0.5 * (vals[x] + vals[y]);
                            if f.is_finite() {
                                let pa = placed.positions[x] + o;
                                let pb = placed.positions[y] + o;
                                edges.add(pa, pb, 0.5 * w, f);
                            }
                        }
                    }
                }
            }
        }
    }
    edges.append_to(&mut scene);
    Ok((scene, graph_triangles))
}

/// The twelve edges of the unit cube at `o` as tubes with value `f`.
fn cube_edges(t: &mut Tubes, o: [f64; 3], w: f64, f: f64) {
    let o = Vector3::from(o);
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        for (s, r) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            let mut p = Vector3::zeros();
            p[u] = s;
            p[v] = r;
            let mut q = p;
            q[a] = 1.0;
            t.add(Point3::from(p + o), Point3::from(q + o), w, f);
        }
    }
}

/// Appends `m` (one vertex property) shifted by `o` to `scene`.
fn append(scene: &mut TriMesh, m: &TriMesh, o: [f64; 3]) {
    let off = scene.positions.len() as u32;
    let o = Vector3::from(o);
    scene.positions.extend(m.positions.iter().map(|p| p + o));
    scene.triangles.extend(
        m.triangles
            .iter()
            .map(|t| [t[0] + off, t[1] + off, t[2] + off]),
    );
    scene.vertex_props[0]
        .values
        .extend_from_slice(&m.vertex_props[0].values);
}

/// Draws `view` of `src` (see the module documentation).
///
/// ```
/// use morpho::render::{render_view, Formula, Source, View, ViewOptions};
/// let src = Source::Formula { formula: Formula::HamannExp, grid: 8 };
/// let view = View::Subdivision { q: [5; 3], alpha: [1.0; 3], k: 2, links: false };
/// let mut opts = ViewOptions::default();
/// opts.render.width = 120;
/// opts.render.height = 90;
/// let pic = render_view(&src, &view, &opts).unwrap();
/// assert_eq!(pic.primitives, 125);
/// ```
pub fn render_view(
    src: &Source,
    view: &View,
    opts: &ViewOptions,
) -> Result<ViewPicture, RenderError> {
    let (mesh, primitives, shading, transparency) = match view {
        View::Slices => return slices_picture(src, opts),
        View::Subdivision { q, alpha, k, links } => {
            let m = subdivision_view_mesh(src, *q, *alpha, *k, *links)?;
            (m, q.iter().product(), Shading::Flat, None)
        }
        View::Transparency { n, t } => {
            param(
                t.is_finite() && (0.0..=1.0).contains(t),
                "transparency t must be in [0, 1]",
            )?;
            let (m, cells) = transparency_view_mesh(src, *n)?;
            let rects = m.triangles.len() / 2;
            debug_assert_eq!(rects, transparency_rectangle_count(cells));
            (m, rects, Shading::Flat, Some(*t))
        }
        View::Heights { k, style } => {
            let (m, tris) = heights_view_mesh(src, *k, *style, opts.range)?;
            (m, tris, Shading::Smooth, None)
        }
    };
    let values = mesh.vertex_props[0].values.clone();
    let range = opts
        .range
        .or_else(|| finite_range(values.iter().copied()))
        .ok_or(RenderError::NoFiniteValues {
            samples: values.len(),
        })?;
    let ropts = RenderOptions {
        shading,
        transparency,
        scalars: Some(Scalars {
            values,
            per_face: false,
            colormap: opts.colormap,
            range: Some(range),
        }),
        ..opts.render.clone()
    };
    let (image, stats) = render_mesh_stats(&mesh, &ropts);
    let mut pic = ViewPicture {
        image,
        primitives,
        triangles: stats.drawn,
        range,
        notes: Vec::new(),
    };
    finish(&mut pic, opts);
    Ok(pic)
}

/// [`View::Slices`]: the three middle slices of the volume or of the sampled formula.
fn slices_picture(src: &Source, opts: &ViewOptions) -> Result<ViewPicture, RenderError> {
    let sampled;
    let vol = match src {
        Source::Volume(v) => {
            check_volume(v, false)?;
            *v
        }
        Source::Formula { formula, grid } => {
            sampled = formula.sample(*grid)?;
            &sampled
        }
    };
    let sopts = SliceOptions {
        colormap: opts.colormap,
        range: opts.range,
        labels: opts.legend,
        ..Default::default()
    };
    let image = orthogonal_slices(vol, middle(vol), &sopts)?;
    let range = opts
        .range
        .or_else(|| finite_range(vol.data.iter().map(|&x| x as f64)))
        .unwrap_or((0.0, 1.0));
    let mut pic = ViewPicture {
        image,
        primitives: 3,
        triangles: 0,
        range,
        notes: Vec::new(),
    };
    if range.0 == range.1 {
        note(&mut pic, format!("constant value {}", label_num(range.0)));
    }
    Ok(pic)
}

/// Writes a note on the top-left of the picture.
fn note(pic: &mut ViewPicture, text: String) {
    let y = 4 + 16 * pic.notes.len() as i64;
    draw_text(&mut pic.image, 4, y, &text, 2, [200, 0, 0, 255]);
    pic.notes.push(text);
}

/// The note on constant values, and the colour bar.
fn finish(pic: &mut ViewPicture, opts: &ViewOptions) {
    let (lo, hi) = pic.range;
    if opts.legend {
        pic.image = with_colorbar(&pic.image, opts.colormap, lo, hi, Some("value"));
    }
    if lo == hi {
        note(pic, format!("constant value {}: one colour", label_num(lo)));
    }
}
