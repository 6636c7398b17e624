//! Triangle reduction by iterative triangle removal (Hamann 1991, §5.2, Algorithm 5.1,
//! Rems 5.7–5.11; notes D.3).
//!
//! Each step pops the removable triangle of smallest weight ω = σρ ([`super::weight`]) from a
//! lazy heap, replaces it and the corona triangles at its corners by a fan from one new point
//! ([`super::point`]), improves the fan by max-min angle-weight swaps ([`super::retri`]) and
//! pushes the new triangles. Removable (Rem. 5.2 plus the guarantees below):
//! 1. the corona is continuous and acyclic, and the link of the triangle is one simple
//!    path/cycle ([`super::corona`]): χ, parts and boundary loops stay (Thm 5.4);
//! 2. the half-plane test (5.18) passes, and every new triangle is counter-clockwise in the
//!    projection onto the removed triangle's plane (exact `orient2d`), is not degenerate (exact)
//!    and has angle weight > 1e-6;
//! 3. no new triangle meets a nearby triangle beyond their shared vertices/edge (the exact
//!    triangle–triangle test of [`crate::geom::intersect`], candidates from a [`BoxGrid`]), so no
//!    self-intersection is created;
//! 4. [`Domain::HeightField`]: every new triangle is counter-clockwise over xy (exact), the
//!    new point of an open corona keeps the origin's (x, y) with its height from the fit in the
//!    vertical frame, and the boundary polyline through the removed corners is replaced by one
//!    that is the same point set over xy (exact on-segment tests both ways), so the domain stays
//!    covered, fold-free. (Collinearity with the new segments' *lines* is not enough: it let
//!    domain corners be cut off, 465 of the 2601 Table 5.1 knots uncovered in one run.)
//!
//! **"New" triangles (Rem. 5.9, notes D.3.1).** Every re-triangulation's triangles are "new"
//! and wait in a second heap; only when no old triangle is removable do all new triangles
//! become old at once ([`NewTriangles::Generations`], the default). The removals thus sweep
//! the whole surface in weight order before a re-triangulated region is reduced again. The
//! narrow reading, only the last step's triangles deferred ([`NewTriangles::LastStep`]), lets
//! the skinny fan triangles (low σ, so low ω) be removed two steps later: the removals
//! snowball into a few regions emptied to huge fans, and Table 5.1 comes out 18–157× the
//! thesis's RMS; with generations every cell is 0.85–1.13× (`tests/reduce.rs`). A triangle
//! found not removable is parked and re-queued (in the heap of its age) when a removal
//! touches its platelet (a corner on the new ring). **Curvature of the old vertices is kept**
//! (D.3.7); the new point gets its curvature from its fit. Undetermined vertex curvatures of
//! the input (H ch. 4 fit) are replaced by the mean of their determined neighbours (0 if none).
//!
//! **Order (an extension; [`Order`]).** Algorithm 5.1 orders removals by ω = σρ alone
//! ([`Order::Hamann`], the default of the library and of Table 5.1). ω does not see how far a
//! removal moves the surface: a flat triangle beside a crease goes early and its fitted point
//! rounds the crease, and regions re-triangulated several times drift. [`Order::ErrorLevels`]
//! (the CLI's default) keeps the weight order but admits a removal only when the input's
//! vertices it re-assigns ([`super::track`], the one-sided error of (5.41)) stay within a bound
//! ε, measured as the root of their summed squared errors (their local L2 error, ≥ the largest
//! of them); a removal over ε waits, keyed by that error, and when nothing removable is left ε
//! grows to max(1.25 ε, the smallest waiting error) (first level: 1e-6 of the mean edge
//! length). The new point is the one of three candidates that moves the input's vertices
//! least: the fitted one; the **QEM point** ([`super::qem`], Garland–Heckbert's quadric error
//! memory: the minimiser of the summed squared distances to the planes of the input triangles
//! around the three merged corners — not Hamann's); and — when both exceed ε — the corners of
//! the removed triangle (creases and corners then stay where the quadratic fit would round
//! them). Every candidate passes the same tests (removability, fold, degeneracy, reach,
//! self-intersection, height-field domain). A waiting triangle whose platelet changes is
//! planned again only when ε reaches its recorded error. Measured (bench/README.md, "Triangle
//! reduction", "QEM candidate"): at 90 % removed the RMS distance is 0.97–1.01× pymeshlab's on
//! the bunny and the horse (the fit and corners alone with doubling levels: 1.5–2.1×), at
//! 1.2–1.75× the time of the doubling levels. `--order hamann` is untouched. Every
//! removability and embedding guarantee below holds in both.
//!
//! **The fit's reach.** A fitted point farther from the origin than every platelet point is
//! not determined by them (a platelet folded over a crease projects to a sliver of its plane
//! and the quadratic extrapolates): the triangle is not removable then (in both orders).
//!
//! Stops: [`Stop::Keep`] (% of triangles kept, "while #triangles > p/100·N0"),
//! [`Stop::Triangles`], and (Rem. 5.10) [`Stop::Rms`] / [`Stop::MaxError`]: the removal that
//! would exceed the tolerance is not made, so the output satisfies it ([`super::track`]).
//!
//! Cost: O(n log n) time, O(n) memory (flat arrays, freed slots reused).

use super::corona::{centroid, half_plane_2d, origin_of, ring_of, Frame, Origin, Ring, Scratch};
use super::error::ReduceError;
use super::heap::WeightHeap;
use super::point::{bivariate_point, implicit_point, Fitted, NewPoint};
use super::qem::QemQuadric;
use super::retri::{fan, improve, Flips};
use super::state::State;
use super::track::Tracker;
use super::weight::triangle_weight;
use crate::curvature::{surface_curvature, NormalSource, SurfaceOptions};
use crate::geom::grid::BoxGrid;
use crate::geom::intersect::{degenerate_triangle, triangles_meet_beyond_shared};
use crate::geom::predicates::raw::orient2d;
use crate::geom::vec::{bounds, dist, midpoint};
use crate::geom::Point3;
use crate::mesh::TriMesh;
use crate::util::NONE;

/// When the reduction stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stop {
    /// Keep this percentage of the input's triangles, in (0, 100] (Alg. 5.1).
    Keep(f64),
    /// Stop at this many triangles or fewer (at most the input's count).
    Triangles(usize),
    /// Stop before the RMS error (5.41) at the input's vertices would exceed this (Rem. 5.10).
    Rms(f64),
    /// Stop before the largest error at the input's vertices would exceed this.
    MaxError(f64),
}

/// What kind of surface is reduced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Domain {
    /// Any manifold, consistently oriented triangulation; errors are Euclidean distances.
    #[default]
    Surface,
    /// The graph of a function over xy (every triangle counter-clockwise over xy): the domain
    /// stays covered, the projection fold-free, errors are vertical (5.41).
    HeightField,
}

/// Which triangles count as "new" (H Rem. 5.9: new triangles "can not be removed at once in
/// the next iteration step. Only if no triangle among the 'old' ones can be removed, all new
/// triangles can be considered for removal").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NewTriangles {
    /// Generations (the default): a triangle stays new until no old triangle is removable;
    /// then every triangle becomes old at once ("all new triangles can be considered"). The
    /// removals sweep the whole surface in weight order before any re-triangulated region is
    /// reduced again.
    #[default]
    Generations,
    /// Only the triangles of the last step are new (the narrowest reading of "in the next
    /// iteration step"). Skinny fan triangles are then removed two steps later, so removals
    /// snowball into a few regions: on Table 5.1 this gives 18–157× the thesis's RMS.
    LastStep,
}

/// In which order removable triangles go (see the module documentation, "Order").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Order {
    /// Algorithm 5.1 as written: the removable triangle of least weight ω = σρ first.
    #[default]
    Hamann,
    /// Error levels: the same weight order, restricted to removals whose error at the input's
    /// vertices stays within a bound ε that doubles whenever nothing removable is left
    /// (an extension, not in the thesis; see the module documentation).
    ErrorLevels,
}

/// Options of [`reduce`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReduceOptions {
    /// When to stop.
    pub stop: Stop,
    /// How the new point is computed.
    pub point: NewPoint,
    /// Never remove a triangle with a corner on the boundary (Rem. 5.8).
    pub freeze_boundary: bool,
    /// Surface or height field.
    pub domain: Domain,
    /// The normals of the H ch. 4 curvature fit at the input's vertices.
    pub normals: NormalSource,
    /// Test each re-triangulation against nearby triangles (exact); off only for inputs known
    /// to stay embedded (height fields are fold-free anyway).
    pub check_intersections: bool,
    /// Which triangles are deferred as "new" (Rem. 5.9).
    pub new_triangles: NewTriangles,
    /// Weight order alone (the thesis) or within doubling error levels.
    pub order: Order,
}

impl Default for ReduceOptions {
    fn default() -> Self {
        ReduceOptions {
            stop: Stop::Keep(50.0),
            point: NewPoint::Bivariate,
            freeze_boundary: false,
            domain: Domain::Surface,
            normals: NormalSource::default(),
            check_intersections: true,
            new_triangles: NewTriangles::default(),
            order: Order::default(),
        }
    }
}

/// Why the reduction ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The triangle target was reached.
    Target,
    /// One more removal would exceed the tolerance.
    Tolerance,
    /// No triangle is removable any more (Rem. 5.11).
    NoRemovable,
}

/// The result of [`reduce`].
#[derive(Debug, Clone, PartialEq)]
pub struct Reduced {
    /// The reduced mesh (unreferenced vertices dropped).
    pub mesh: TriMesh,
    /// For each output vertex, the input vertex whose index it inherits (H (5.40): the new
    /// point takes the index of the removed triangle's first corner).
    pub source: Vec<u32>,
    /// Triangles of the input.
    pub triangles_in: usize,
    /// Triangles removed (one step replaces one triangle and its neighbours).
    pub removals: usize,
    /// Why it stopped.
    pub stop: StopReason,
    /// The RMS error at the input's vertices, when tracked (tolerance stops, height fields).
    pub rms: Option<f64>,
    /// The largest error at the input's vertices (an upper bound), when tracked.
    pub max_error: Option<f64>,
}

/// What every plan of one triangle's removal shares, whatever the new point: the ring, the
/// frame, the origin and the fit (computed once per triangle and reused for the corner
/// alternatives of [`Order::ErrorLevels`]).
struct Prep {
    /// The triangle removed.
    t: u32,
    ring: Ring,
    ap: [[f64; 3]; 3],
    f0: Frame,
    /// The ring in the frame's plane coordinates.
    ring2: Vec<[f64; 2]>,
    fit: Fitted,
    origin: [f64; 3],
    /// The farthest platelet point from the origin (the fit's reach).
    reach: f64,
}

/// Where a plan puts the new point.
#[derive(Debug, Clone, Copy)]
enum Cand {
    /// The fitted point (H (5.29) or (5.33)).
    Fit,
    /// Corner `k` of the removed triangle ([`Order::ErrorLevels`]).
    Corner(usize),
    /// A given point ([`Order::ErrorLevels`]: the QEM point, [`super::qem`]).
    At([f64; 3]),
}

/// [`Order::ErrorLevels`]: the factor by which ε grows when nothing is removable within it.
/// 2 before; 1.25 keeps the removals closer to the order of their errors (with the local L2
/// error and the QEM candidate, horse 90 % removed: RMS 2.09× → 1.01× pymeshlab's;
/// bench/README.md, "The QEM candidate and finer error levels").
const LEVEL_GROWTH: f64 = 1.25;

/// A removal ready to apply (with the [`Prep`] it was made from).
struct Plan {
    p: [f64; 3],
    abs_curv: f64,
    /// New triangles in local indices (0 = p, 1 + j = ring vertex j).
    tris: Vec<[usize; 3]>,
}

struct Engine<'o> {
    s: State,
    curv: Vec<f64>,
    w: Vec<f64>,
    gen: Vec<u32>,
    parked: Vec<bool>,
    heap: WeightHeap,
    /// The "new" triangles (generation > `epoch`), considered only when `heap` has no
    /// removable one.
    young: WeightHeap,
    /// Triangles of generation ≤ epoch are old.
    epoch: u32,
    grid: Option<BoxGrid<3>>,
    sc: Scratch,
    opts: &'o ReduceOptions,
    removals: u32,
    buf: Vec<u32>,
    /// Scratch of [`Engine::finish`] and [`Engine::embedded`] (reused: no allocation per plan).
    flips: Flips,
    p2s: Vec<[f64; 2]>,
    p3s: Vec<[f64; 3]>,
    xys: Vec<[f64; 2]>,
    cand: Vec<u32>,
    /// [`Order::ErrorLevels`]: the current error bound ε.
    eps: f64,
    /// Triangles whose removal would exceed ε, keyed by that error.
    over: WeightHeap,
    /// Waits in `over` (a change of its platelet does not re-queue it: it is planned again
    /// when ε reaches the error it had).
    waiting: Vec<bool>,
    /// [`Order::ErrorLevels`]: the quadric error memory of every vertex ([`super::qem`]).
    quad: Vec<QemQuadric>,
}

/// Reduces `mesh` by Hamann's triangle removal (Alg. 5.1); see the module documentation.
///
/// ```
/// use morpho::mesh::{analyze_topology, generate};
/// use morpho::reduce::{reduce, ReduceOptions, Stop};
/// let torus = generate::torus(2.0, 0.7, 40, 20);
/// let opts = ReduceOptions { stop: Stop::Keep(30.0), ..Default::default() };
/// let r = reduce(&torus, &opts).unwrap();
/// assert!(r.mesh.triangles.len() <= 480);
/// let t = analyze_topology(&r.mesh);
/// assert!(t.manifold && t.consistently_oriented && t.genus() == Some(1));
/// ```
pub fn reduce(mesh: &TriMesh, opts: &ReduceOptions) -> Result<Reduced, ReduceError> {
    mesh.validate()?;
    let n0 = mesh.triangles.len();
    let target = match opts.stop {
        Stop::Keep(p) => {
            if !(p > 0.0 && p <= 100.0) {
                return Err(ReduceError::BadPercentage { percent: p });
            }
            (p / 100.0 * n0 as f64).floor() as usize
        }
        Stop::Triangles(t) => {
            if t > n0 {
                return Err(ReduceError::CountAboveInput {
                    target: t,
                    input: n0,
                });
            }
            t
        }
        Stop::Rms(e) | Stop::MaxError(e) => {
            if !(e >= 0.0 && e.is_finite()) {
                return Err(ReduceError::BadTolerance { tolerance: e });
            }
            0
        }
    };
    let pos: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.coords.into()).collect();
    let s = State::build(pos.clone(), &mesh.triangles)?;
    let height = opts.domain == Domain::HeightField;
    if height {
        for (t, tr) in mesh.triangles.iter().enumerate() {
            let q = |v: u32| [pos[v as usize][0], pos[v as usize][1]];
            if orient2d(q(tr[0]), q(tr[1]), q(tr[2])) <= 0.0 {
                return Err(ReduceError::NotAHeightField { triangle: t });
            }
        }
    }
    let curv = vertex_curvature(mesh, &s, opts)?;
    let tolerance = matches!(opts.stop, Stop::Rms(_) | Stop::MaxError(_));
    let levels = opts.order == Order::ErrorLevels;
    let mut tracker =
        (tolerance || height || levels).then(|| Tracker::new(pos, &mesh.triangles, height));
    let mut e = Engine::new(s, curv, opts);
    let mut corners: Vec<[[f64; 3]; 3]> = Vec::new();
    let stop = loop {
        if !tolerance && e.s.live_tris <= target {
            break StopReason::Target;
        }
        let Some((prep, mut plan)) = e.next_plan() else {
            if levels && e.next_level() {
                continue;
            }
            break StopReason::NoRemovable;
        };
        let t = prep.t;
        // the tracker's last evaluation, while it is that of `plan` (then not repeated)
        let mut evaluated = None;
        if let (true, Some(tr)) = (levels, tracker.as_mut()) {
            // the fitted point, the QEM point, or a corner of the triangle, whichever moves
            // the input's vertices least (root of their summed squared errors); creases and
            // corners stay where the fit would round them
            e.new_corners(&prep, &plan, &mut corners);
            evaluated = Some(tr.evaluate(&prep.ring.removed, &corners));
            let mut best = tr.last_local_l2();
            // the QEM point (an extension, not Hamann's: `super::qem`), judged the same way
            if let Some(alt) = e
                .qem_point(&prep)
                .and_then(|q| e.finish(&prep, Cand::At(q)))
            {
                e.new_corners(&prep, &alt, &mut corners);
                let ev = tr.evaluate_within(&prep.ring.removed, &corners, best);
                if ev.is_some() && tr.last_local_l2() < best {
                    best = tr.last_local_l2();
                    plan = alt;
                    evaluated = ev;
                } else {
                    evaluated = None;
                }
            }
            if best > e.eps {
                for k in 0..3 {
                    if let Some(alt) = e.finish(&prep, Cand::Corner(k)) {
                        // (a corner worse than the best so far is abandoned early)
                        e.new_corners(&prep, &alt, &mut corners);
                        let ev = tr.evaluate_within(&prep.ring.removed, &corners, best);
                        evaluated = None;
                        if ev.is_some() && tr.last_local_l2() < best {
                            best = tr.last_local_l2();
                            plan = alt;
                            evaluated = ev;
                        }
                    }
                }
            }
            if best > e.eps {
                e.park_over(t, best);
                continue;
            }
        }
        let eval = tracker.as_mut().map(|tr| {
            let ev = evaluated.unwrap_or_else(|| {
                e.new_corners(&prep, &plan, &mut corners);
                tr.evaluate(&prep.ring.removed, &corners)
            });
            (ev, tr)
        });
        // the costliest test last: no self-intersection (exact, against nearby triangles)
        if !e.embedded(&prep, &plan, e.s.tri[t as usize][0]) {
            e.parked[t as usize] = true;
            continue;
        }
        let over = match (opts.stop, &eval) {
            (Stop::Rms(eps), Some(((sse, _), _))) => (sse / n_knots(mesh)).sqrt() > eps,
            (Stop::MaxError(eps), Some(((_, mx), _))) => *mx > eps,
            _ => false,
        };
        if over {
            break StopReason::Tolerance;
        }
        let slots = e.apply(&prep, &plan);
        if let Some(((sse, mx), tr)) = eval {
            tr.commit(&prep.ring.removed, &slots, sse, mx);
        }
    };
    let (p, tris, map) = e.s.compact();
    let mut source = vec![0u32; p.len()];
    for (old, &m) in map.iter().enumerate() {
        if m != NONE {
            source[m as usize] = old as u32;
        }
    }
    Ok(Reduced {
        mesh: TriMesh::new(p.into_iter().map(Point3::from).collect(), tris),
        source,
        triangles_in: n0,
        removals: e.removals as usize,
        stop,
        rms: tracker.as_ref().map(|t| t.rms()),
        max_error: tracker.as_ref().map(|t| t.max),
    })
}

fn n_knots(mesh: &TriMesh) -> f64 {
    mesh.positions.len().max(1) as f64
}

/// Absolute curvature per vertex by the H ch. 4 fit, undetermined ones from their neighbours.
fn vertex_curvature(
    mesh: &TriMesh,
    s: &State,
    opts: &ReduceOptions,
) -> Result<Vec<f64>, ReduceError> {
    if let NormalSource::Given(n) = &opts.normals {
        if n.len() != mesh.positions.len() {
            return Err(ReduceError::NormalCount {
                given: n.len(),
                vertices: mesh.positions.len(),
            });
        }
    }
    let so = SurfaceOptions {
        normals: opts.normals.clone(),
        ring: 1,
        ..Default::default()
    };
    let c = surface_curvature(mesh, &so)?;
    let mut a = c.a;
    let mut fanb = Vec::new();
    let fixed: Vec<(usize, f64)> = (0..a.len())
        .filter(|&v| !a[v].is_finite())
        .map(|v| {
            s.fan(v as u32, &mut fanb);
            let (mut sum, mut k) = (0.0, 0);
            for &h in &fanb {
                for u in [s.to(h), s.from(super::state::prev(h))] {
                    if a[u as usize].is_finite() {
                        sum += a[u as usize];
                        k += 1;
                    }
                }
            }
            (v, if k > 0 { sum / k as f64 } else { 0.0 })
        })
        .collect();
    for (v, x) in fixed {
        a[v] = x;
    }
    Ok(a)
}

impl<'o> Engine<'o> {
    fn new(s: State, curv: Vec<f64>, opts: &'o ReduceOptions) -> Self {
        let nt = s.tri.len();
        let mut e = Engine {
            curv,
            w: vec![0.0; nt],
            gen: vec![0; nt],
            parked: vec![false; nt],
            heap: WeightHeap::default(),
            young: WeightHeap::default(),
            epoch: 0,
            grid: None,
            sc: Scratch::default(),
            opts,
            removals: 0,
            buf: Vec::new(),
            flips: Flips::default(),
            p2s: Vec::new(),
            p3s: Vec::new(),
            xys: Vec::new(),
            cand: Vec::new(),
            eps: 0.0,
            over: WeightHeap::default(),
            waiting: vec![false; nt],
            quad: Vec::new(),
            s,
        };
        // the mean length of one edge per triangle sizes the grid's cells and the first error
        // level of [`Order::ErrorLevels`]: 1e-6 of it (planar regions, whose fits are exact to
        // rounding, go first)
        let mut len = 0.0;
        for tr in &e.s.tri {
            len += dist(e.s.p(tr[0]), e.s.p(tr[1]));
        }
        if opts.order == Order::ErrorLevels {
            e.quad = vec![QemQuadric::default(); e.s.pos.len()];
            for tr in &e.s.tri {
                let q = QemQuadric::of_triangle(tr.map(|v| e.s.p(v)));
                for &v in tr {
                    e.quad[v as usize].add(&q);
                }
            }
            let mean = if nt > 0 { len / nt as f64 } else { 1.0 };
            e.eps = (1e-6 * mean).max(f64::MIN_POSITIVE);
        }
        if opts.check_intersections {
            let cell = 2.0 * len / nt as f64;
            let mut g = BoxGrid::new([0.0; 3], cell, true);
            for t in 0..nt as u32 {
                let (lo, hi) = e.bbox(t);
                g.insert(t, lo, hi);
            }
            e.grid = Some(g);
        }
        for t in 0..nt as u32 {
            let w = e.weight(t);
            e.w[t as usize] = w;
            e.heap.push(t, w);
        }
        e
    }

    fn bbox(&self, t: u32) -> ([f64; 3], [f64; 3]) {
        bounds(&self.s.tri[t as usize].map(|v| self.s.p(v)))
    }

    fn weight(&self, t: u32) -> f64 {
        let tr = self.s.tri[t as usize];
        triangle_weight(tr.map(|v| self.s.p(v)), tr.map(|v| self.curv[v as usize]))
    }

    fn local_pos(&self, prep: &Prep, plan: &Plan, i: usize) -> [f64; 3] {
        if i == 0 {
            plan.p
        } else {
            self.s.p(prep.ring.verts[i - 1])
        }
    }

    /// The next removal of Alg. 5.1: the removable old triangle of least weight; when there
    /// is none, every new triangle becomes old (Rem. 5.9) and the search repeats.
    fn next_plan(&mut self) -> Option<(Prep, Plan)> {
        loop {
            while let Some((t, _)) = self.heap.pop() {
                if !self.s.alive[t as usize] {
                    continue;
                }
                match self
                    .prepare(t)
                    .and_then(|prep| Some((self.finish(&prep, Cand::Fit)?, prep)))
                {
                    Some((plan, prep)) => return Some((prep, plan)),
                    None => self.parked[t as usize] = true,
                }
            }
            if !self.promote() {
                return None;
            }
        }
    }

    /// [`Order::ErrorLevels`]: `t` is removable but its removal would move an input vertex
    /// by `err` > ε; it waits in `over` until ε reaches `err` (a change of its platelet does
    /// not re-queue it, unlike a triangle parked as not removable; it is planned anew then).
    fn park_over(&mut self, t: u32, err: f64) {
        self.waiting[t as usize] = true;
        self.over.push(t, err);
    }

    /// [`Order::ErrorLevels`], nothing removable within ε: ε grows to at least twice itself
    /// and the smallest waiting error, and the waiting triangles within it are queued again.
    /// `false` when none waits (then nothing is removable at any level).
    fn next_level(&mut self) -> bool {
        let mut any = false;
        while !any {
            let Some((t, err)) = self.over.pop() else {
                return false;
            };
            if !self.s.alive[t as usize] || !self.waiting[t as usize] {
                continue;
            }
            self.eps = (LEVEL_GROWTH * self.eps).max(err);
            self.waiting[t as usize] = false;
            self.queue(t);
            any = true;
        }
        while let Some((t, err)) = self.over.pop() {
            if err > self.eps {
                self.over.push(t, err);
                break;
            }
            if self.s.alive[t as usize] && self.waiting[t as usize] {
                self.waiting[t as usize] = false;
                self.queue(t);
            }
        }
        true
    }

    /// Makes every new triangle old; `false` if there was none.
    fn promote(&mut self) -> bool {
        self.epoch = self.removals;
        let mut any = false;
        while let Some((t, w)) = self.young.pop() {
            self.heap.push(t, w);
            any = true;
        }
        any
    }

    /// Queues triangle `t` in the heap of its age.
    fn queue(&mut self, t: u32) {
        let w = self.w[t as usize];
        if self.gen[t as usize] > self.epoch {
            self.young.push(t, w);
        } else {
            self.heap.push(t, w);
        }
    }

    /// [`Order::ErrorLevels`]: the QEM candidate of a prepared removal, the minimiser of the
    /// removed corners' summed quadrics closest to the fitted point ([`super::qem`]).
    fn qem_point(&self, prep: &Prep) -> Option<[f64; 3]> {
        let tr = self.s.tri[prep.t as usize];
        let mut q = *self.quad.get(tr[0] as usize)?;
        q.add(&self.quad[tr[1] as usize]);
        q.add(&self.quad[tr[2] as usize]);
        q.minimizer(prep.fit.p)
    }

    /// The corners of a plan's new triangles, into `out`.
    fn new_corners(&self, prep: &Prep, plan: &Plan, out: &mut Vec<[[f64; 3]; 3]>) {
        out.clear();
        out.extend(
            plan.tris
                .iter()
                .map(|t| t.map(|i| self.local_pos(prep, plan, i))),
        );
    }

    /// The part of a plan that does not depend on the new point: the ring and its
    /// removability (corona, frozen boundary, half-plane test), the origin and the fit.
    fn prepare(&mut self, t: u32) -> Option<Prep> {
        let mut ring = Ring::default();
        let class = ring_of(&self.s, t, &mut self.sc, &mut ring)?;
        if !class.admits_removal() || (self.opts.freeze_boundary && ring.any_boundary) {
            return None;
        }
        let a = self.s.tri[t as usize];
        let ap = a.map(|v| self.s.p(v));
        let cen = centroid(ap);
        let f0 = Frame::of(ap, cen)?;
        let ring2: Vec<[f64; 2]> = ring.verts.iter().map(|&v| f0.uv(self.s.p(v))).collect();
        if !half_plane_2d(&ring2, [0.0, 0.0], ring.closed) {
            return None;
        }
        let height = self.opts.domain == Domain::HeightField;
        let origin = match origin_of(&ring, |v| {
            self.s.fan(v, &mut self.buf);
            self.buf.len()
        }) {
            Origin::Centroid => cen,
            Origin::Vertex(v) => self.s.p(v),
            Origin::Midpoint(u, v) => midpoint(self.s.p(u), self.s.p(v)),
        };
        let mut pts = std::mem::take(&mut self.p3s);
        pts.clear();
        pts.extend_from_slice(&ap);
        pts.extend(ring.verts.iter().map(|&v| self.s.p(v)));
        let fallback = a.iter().map(|&v| self.curv[v as usize]).sum::<f64>() / 3.0;
        let fit = if height && !ring.closed {
            let vf = Frame {
                c: origin,
                n: [0.0, 0.0, 1.0],
                b1: [1.0, 0.0, 0.0],
                b2: [0.0, 1.0, 0.0],
            };
            bivariate_point(&vf, &pts, fallback)
        } else {
            let f = Frame { c: origin, ..f0 };
            match self.opts.point {
                NewPoint::Implicit => {
                    implicit_point(&f, &pts).unwrap_or_else(|| bivariate_point(&f, &pts, fallback))
                }
                NewPoint::Bivariate => bivariate_point(&f, &pts, fallback),
            }
        };
        let reach = pts.iter().map(|&q| dist(q, origin)).fold(0.0f64, f64::max);
        self.p3s = pts;
        Some(Prep {
            t,
            ring,
            ap,
            f0,
            ring2,
            fit,
            origin,
            reach,
        })
    }

    /// The plan of a prepared removal with the new point fitted (`corner` `None`) or put at
    /// a corner of the triangle ([`Order::ErrorLevels`] compares them): the fan, its swaps
    /// and the tests of the new triangles.
    fn finish(&mut self, prep: &Prep, cand: Cand) -> Option<Plan> {
        let ring = &prep.ring;
        let t = prep.t;
        let (p, abs_curv) = match cand {
            Cand::Corner(k) => (prep.ap[k], self.curv[self.s.tri[t as usize][k] as usize]),
            Cand::Fit => (prep.fit.p, prep.fit.abs_curv),
            // (the fit's curvature: the QEM point lies near the fitted one, and the quadric
            // carries no curvature of its own)
            Cand::At(q) => (q, prep.fit.abs_curv),
        };
        // an ill-conditioned fit (a platelet folded over a crease projects to a sliver of
        // its plane) can extrapolate far beyond the data: a point farther from the origin
        // than every platelet point is not determined by them, and the triangle waits
        if !p.iter().all(|x| x.is_finite()) || dist(p, prep.origin) > prep.reach {
            return None;
        }
        let height = self.opts.domain == Domain::HeightField;
        let m = ring.verts.len();
        let mut p2 = std::mem::take(&mut self.p2s);
        p2.clear();
        p2.push(prep.f0.uv(p));
        p2.extend_from_slice(&prep.ring2);
        let mut xy = std::mem::take(&mut self.xys);
        xy.clear();
        if height {
            xy.push([p[0], p[1]]);
            xy.extend(ring.verts.iter().map(|&v| {
                let q = self.s.p(v);
                [q[0], q[1]]
            }));
        }
        let mut p3 = std::mem::take(&mut self.p3s);
        p3.clear();
        p3.push(p);
        p3.extend(ring.verts.iter().map(|&v| self.s.p(v)));
        let mut tris = Vec::new();
        let ok = (!height || ring.closed || self.domain_kept(ring, p)) && {
            fan(m, ring.closed, &mut tris);
            let xyo = height.then_some(xy.as_slice());
            let (s, verts, buf, flips) = (&self.s, &ring.verts, &mut self.buf, &mut self.flips);
            improve(
                &mut tris,
                &p3,
                &p2,
                xyo,
                |i, j| s.has_edge(verts[i - 1], verts[j - 1], buf),
                flips,
            );
            // (the angle weights of the final triangles are improve's, same corners in the
            // same order)
            tris.iter().zip(flips.weights()).all(|(&[x, y, z], &w)| {
                !(orient2d(p2[x], p2[y], p2[z]) <= 0.0
                    || xyo.is_some_and(|c| orient2d(c[x], c[y], c[z]) <= 0.0)
                    || degenerate_triangle(p3[x], p3[y], p3[z])
                    || w <= 1e-6)
            })
        };
        self.p2s = p2;
        self.xys = xy;
        self.p3s = p3;
        ok.then_some(Plan { p, abs_curv, tris })
    }

    /// Height fields, open corona: the boundary polyline `e → chain… → s` through the removed
    /// corners is replaced by `e → p → s`, which must be the same point set over xy, so the
    /// covered domain does not change: every chain corner lies on one of the two new segments
    /// and `p` lies on one of the old segments (closed segments, exact `orient2d` and
    /// coordinate comparisons). Collinearity with the segments' *lines* is not enough: a domain
    /// corner `(1, 1)` between `(1, .96)` and `(.96, 1)` is collinear with the line `p → s` of
    /// `p = (.98, 1)` and would be cut off.
    fn domain_kept(&self, ring: &Ring, p: [f64; 3]) -> bool {
        let xy = |q: [f64; 3]| [q[0], q[1]];
        let e = xy(self.s.p(*ring.verts.last().unwrap()));
        let s0 = xy(self.s.p(ring.verts[0]));
        let pp = xy(p);
        let mut old = vec![e];
        old.extend(ring.chain.iter().map(|&c| xy(self.s.p(c))));
        old.push(s0);
        let corners_on_new = old[1..old.len() - 1]
            .iter()
            .all(|&c| on_segment(e, pp, c) || on_segment(pp, s0, c));
        corners_on_new && old.windows(2).any(|w| on_segment(w[0], w[1], pp))
    }

    /// No new triangle meets a triangle outside the platelet beyond shared vertices/edges.
    fn embedded(&mut self, prep: &Prep, plan: &Plan, pid: u32) -> bool {
        let Some(grid) = &self.grid else {
            return true;
        };
        let ring = &prep.ring;
        let ids = |i: usize| if i == 0 { pid } else { ring.verts[i - 1] };
        let mut cand = std::mem::take(&mut self.cand);
        let mut ok = true;
        'tris: for tr in &plan.tris {
            let ti = tr.map(ids);
            let tp = tr.map(|i| self.local_pos(prep, plan, i));
            let (lo, hi) = bounds(&tp);
            grid.query(lo, hi, &mut cand);
            for &u in &cand {
                if (u as usize) >= self.s.tri.len()
                    || !self.s.alive[u as usize]
                    || ring.removed.contains(&u)
                {
                    continue;
                }
                let ut = self.s.tri[u as usize];
                if triangles_meet_beyond_shared(ti, tp, ut, ut.map(|v| self.s.p(v))) {
                    ok = false;
                    break 'tris;
                }
            }
        }
        self.cand = cand;
        ok
    }

    /// Applies a plan; returns the slots of the new triangles (in plan order).
    fn apply(&mut self, prep: &Prep, plan: &Plan) -> Vec<u32> {
        let t0 = prep.ring.removed[0];
        let a = self.s.tri[t0 as usize];
        for &u in &prep.ring.removed {
            self.heap.invalidate(u);
            self.young.invalidate(u);
            self.over.invalidate(u);
            self.s.kill_triangle(u);
        }
        let pid = a[0];
        if !self.quad.is_empty() {
            // the new point absorbs the three corners: their quadrics add up
            let (q1, q2) = (self.quad[a[1] as usize], self.quad[a[2] as usize]);
            self.quad[pid as usize].add(&q1);
            self.quad[pid as usize].add(&q2);
        }
        self.s.pos[pid as usize] = plan.p;
        self.curv[pid as usize] = plan.abs_curv;
        self.s.vhe[a[1] as usize] = NONE;
        self.s.vhe[a[2] as usize] = NONE;
        let verts = &prep.ring.verts;
        let m = verts.len();
        let gid = |i: usize| if i == 0 { pid } else { verts[i - 1] };
        let slots: Vec<u32> = plan
            .tris
            .iter()
            .map(|tr| self.s.add_triangle(tr.map(gid)))
            .collect();
        if self.opts.new_triangles == NewTriangles::LastStep {
            // the previous step's triangles are old now
            self.promote();
        }
        self.removals += 1;
        let nt = self.s.tri.len();
        self.w.resize(nt, 0.0);
        self.gen.resize(nt, 0);
        self.parked.resize(nt, false);
        self.waiting.resize(nt, false);
        // opposites: ring edges to the outside, the rest among the new triangles
        for (k, tr) in plan.tris.iter().enumerate() {
            for i in 0..3 {
                let (x, y) = (tr[i], tr[(i + 1) % 3]);
                let h = 3 * slots[k] + i as u32;
                let ring_edge = x >= 1 && y >= 1 && (y == x % m + 1) && (prep.ring.closed || x < m);
                let o = if ring_edge {
                    prep.ring.outer[x - 1]
                } else {
                    plan.tris
                        .iter()
                        .enumerate()
                        .find_map(|(l, u)| {
                            (0..3)
                                .find(|&j| u[j] == y && u[(j + 1) % 3] == x)
                                .map(|j| 3 * slots[l] + j as u32)
                        })
                        .unwrap_or(NONE)
                };
                self.s.opp[h as usize] = o;
                if o != NONE {
                    self.s.opp[o as usize] = h;
                }
                self.s.vhe[gid(x) as usize] = h;
            }
        }
        for &sl in &slots {
            let w = self.weight(sl);
            self.w[sl as usize] = w;
            self.gen[sl as usize] = self.removals;
            self.parked[sl as usize] = false;
            self.waiting[sl as usize] = false;
            self.queue(sl);
            if self.grid.is_some() {
                let (lo, hi) = self.bbox(sl);
                if let Some(g) = self.grid.as_mut() {
                    g.insert(sl, lo, hi);
                }
            }
        }
        // re-queue parked triangles whose platelet changed
        let mut fanb = std::mem::take(&mut self.buf);
        for &v in verts {
            self.s.fan(v, &mut fanb);
            for &h in &fanb {
                let u = h / 3;
                if self.parked[u as usize] {
                    self.parked[u as usize] = false;
                    self.queue(u);
                }
            }
        }
        self.buf = fanb;
        slots
    }
}

/// Is `c` on the closed segment `a–b` (exact)?
fn on_segment(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    orient2d(a, b, c) == 0.0
        && c[0] >= a[0].min(b[0])
        && c[0] <= a[0].max(b[0])
        && c[1] >= a[1].min(b[1])
        && c[1] <= a[1].max(b[1])
}
