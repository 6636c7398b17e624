//! Adaptive augmentation in 3D (Veltkamp 1992, §5.4): the triangles of γ(\[-1,1\],\[c,1\]),
//! c < 0, at the vertices off the boundary ([`General3::local_gamma`]), their certified
//! insertion ([`General3::augment`]), and the schedule c = −0.1, …, −1 of [`super::boundary_3d`]
//! (local first, then the whole object).
//!
//! [`General3::augment`] adds triangles (of γ(\[-1,1\],\[c,1\]), c < 0) that are certified to lie in
//! the region: they meet no boundary triangle except in common vertices/edges (exact), and have
//! a vertex not on the boundary, or a boundary edge from which they go inward (m strictly inside
//! the interior dihedral wedge of the two boundary faces there; exact `orient3d`). Such a
//! triangle is connected, starts inside and never crosses the surface, so it lies in the closed
//! region.

use super::constrict::Constriction3;
use super::engine::{Engine3, Outcome3};
use super::general::*;
use crate::delaunay::d3::Delaunay3;
use crate::geom::intersect::degenerate_triangle;
use crate::geom::predicates::raw::orient3d;
use crate::util::sorted3;

impl General3<'_> {
    /// Does the triangle a b m leave the boundary edge ab into the region? (exact: m strictly
    /// inside the interior dihedral wedge of the two boundary faces at ab)
    pub(super) fn inward_at_edge(&self, a: u32, b: u32, m: u32) -> bool {
        let (Some(y), Some(w)) = (self.bnext_of(a, b), self.bnext_of(b, a)) else {
            return false;
        };
        let (pa, pb, py, pw, pm) = (self.pt(a), self.pt(b), self.pt(y), self.pt(w), self.pt(m));
        let convex = orient3d(pa, pb, py, pw);
        let o1 = orient3d(pa, pb, py, pm) > 0.0;
        let o2 = orient3d(pb, pa, pw, pm) > 0.0;
        if convex > 0.0 {
            o1 && o2
        } else if convex < 0.0 {
            o1 || o2
        } else {
            o1 && o2
        }
    }

    /// Inserts triangle t when it is new, non-degenerate, certified to start inside the region
    /// (a vertex off the boundary, or a boundary edge it leaves inward) and meets no boundary
    /// triangle beyond common vertices/edges.
    pub(super) fn try_insert(&mut self, t: [u32; 3]) -> bool {
        !self.has(t[0], t[1], t[2]) && self.insertable_at_boundary(t) && self.add_tri(t)
    }

    /// The conditions of `try_insert` that depend on the boundary only (not on the
    /// live triangles, which adding changes): distinct corners, started inside, not
    /// degenerate, meeting no boundary triangle.
    pub(super) fn insertable_at_boundary(&self, t: [u32; 3]) -> bool {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return false;
        }
        if t.iter().all(|&v| self.on_boundary(v))
            && !(0..3).any(|k| {
                let (a, b, m) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                self.bedge(a, b) && self.inward_at_edge(a, b, m)
            })
        {
            return false;
        }
        let pt = t.map(|v| self.pt(v));
        !(degenerate_triangle(pt[0], pt[1], pt[2]) || self.hits_boundary(t, &[]))
    }

    /// The triangles of γ(\[-1,1\],\[c,1\]) (Def. 3.1 by the exact centre intervals of
    /// `TriFrame` of the γ-graph module) on the vertices not on the boundary and pairs of
    /// their `k` nearest vertices or edges of the `k` boundary faces nearest to them — the part
    /// of the γ-graph needed to free a locked vertex (V §5.4 "adaptive augmentation": only where
    /// needed). Each triangle is decided against every point that can change the decision
    /// (the diametral ball, then the balls that certify an empty neighbourhood; for c = −1 the
    /// points in the closed triangle); see `gamma_decide`. Triangles found at an
    /// earlier (larger) c are not returned again, and triangles rejected earlier with an upper
    /// bound of c₁′ below c are not tested again. The nearest vertices of a vertex are computed
    /// once (positions do not change); the candidates are decided in parallel (rayon).
    /// O(L·k²·m) for L locked vertices and m points in the balls scanned.
    pub fn local_gamma(&mut self, c: f64, k: usize) -> Vec<[u32; 3]> {
        use rayon::prelude::*;
        let locked: Vec<u32> = (0..self.p.len() as u32)
            .filter(|&v| !self.on_boundary(v))
            .collect();
        // the nearest vertices of the vertices met for the first time (in parallel)
        let missing: Vec<u32> = locked
            .iter()
            .copied()
            .filter(|l| !self.near_cache.contains_key(l))
            .collect();
        let this = &*self;
        let found: Vec<(Vec<u32>, f64)> = missing.par_iter().map(|&l| this.nearest(l, k)).collect();
        self.near_cache.extend(missing.into_iter().zip(found));
        // candidates of every locked vertex (read-only, in parallel; in the order of `locked`)
        let this = &*self;
        let mut cand: Vec<([u32; 3], u32)> = locked
            .par_iter()
            .map_init(Vec::new, |tb, &l| this.gamma_candidates(l, k, c, tb))
            .flatten_iter()
            .collect();
        // each triangle once (with the first locked vertex that proposed it)
        cand.sort_unstable();
        cand.dedup_by_key(|e| e.0);
        let this = &*self;
        let verdicts: Vec<Option<f64>> = cand
            .par_iter()
            .map(|&(t, l)| this.gamma_decide(t, c, &this.near_cache[&l].0))
            .collect();
        let mut out = Vec::new();
        for (&(t, _), v) in cand.iter().zip(verdicts) {
            match v {
                None => {
                    self.in_gamma.insert(t);
                    out.push(t);
                }
                Some(ub) => {
                    self.gamma_ub.insert(t, ub);
                }
            }
        }
        out
    }

    /// The candidate triangles of [`Self::local_gamma`] for the locked vertex `l` (its nearest
    /// vertices cached): `l` with pairs of its `k` nearest vertices and with the edges of the
    /// `k` boundary faces nearest to it, minus live triangles, triangles already found and
    /// triangles whose cached bound of c₁′ is below `c`. `tb` is scratch space.
    pub(super) fn gamma_candidates(
        &self,
        l: u32,
        k: usize,
        c: f64,
        tb: &mut Vec<u32>,
    ) -> Vec<([u32; 3], u32)> {
        let (near, rad) = &self.near_cache[&l];
        let mut cand = Vec::new();
        let pl = self.pt(l);
        // pairs of near vertices, and the edges of the k boundary faces nearest to l (by
        // centroid; the faces a removal w.r.t. l starts from)
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, &x) in near.iter().enumerate() {
            for &y in &near[i + 1..] {
                pairs.push((x, y));
            }
        }
        // the k faces nearest by centroid among those meeting the box of half-width 2·rad:
        // a face missing from the box of half-width rad has its centroid farther than rad,
        // so when that smaller box already holds k faces with centroids within rad, they
        // are the same k (and the same order)
        let mut faces: Vec<(f64, [u32; 3])> = Vec::new();
        for reach_l in [*rad, 2.0 * rad] {
            self.bgrid.query(
                std::array::from_fn(|i| pl[i] - reach_l),
                std::array::from_fn(|i| pl[i] + reach_l),
                tb,
            );
            faces = tb
                .iter()
                .filter(|&&i| self.live[i as usize] && self.bflag[i as usize])
                .map(|&i| self.tris[i as usize])
                .map(|u| {
                    let q = u.map(|v| self.pt(v));
                    let d2 = (0..3)
                        .map(|i| ((q[0][i] + q[1][i] + q[2][i]) / 3.0 - pl[i]).powi(2))
                        .sum::<f64>();
                    (d2, u)
                })
                .collect();
            if faces.iter().filter(|f| f.0 <= rad * rad).count() >= k {
                // at least k faces have d² ≤ rad² and every other face comes after them in
                // the order (distance, face): the first k are among those, so the rest are
                // dropped before the selection (the same k, fewer to select from)
                faces.retain(|f| f.0 <= rad * rad);
                break;
            }
        }
        // the first k in the order (distance, face): selected, then only they sorted (the
        // order is total, so the same k in the same order as sorting all)
        let order =
            |a: &(f64, [u32; 3]), b: &(f64, [u32; 3])| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
        if k < faces.len() {
            faces.select_nth_unstable_by(k, order);
            faces.truncate(k);
        }
        faces.sort_unstable_by(order);
        for (_, u) in faces.into_iter().take(k) {
            for e in 0..3 {
                pairs.push((u[e], u[(e + 1) % 3]));
            }
        }
        // whether l x y is live: y in the list of edge x–l ([`General3::live_thirds`], which
        // lists exactly the live triangles on an edge with a warm end; `has` when both ends
        // are cold), looked up once per run of pairs with the same x (the pairs of the
        // nearest vertices come in such runs) instead of a lookup of `id` per pair
        let mut last: Option<(u32, Option<&[u32]>)> = None;
        for (x, y) in pairs {
            let t = sorted3([l, x, y]);
            if x == l || y == l {
                continue;
            }
            let thirds = match last {
                Some((lx, s)) if lx == x => s,
                _ => {
                    let s = self.live_thirds(x, l);
                    last = Some((x, s));
                    s
                }
            };
            let live = match thirds {
                Some(s) => s.contains(&y),
                None => self.has(t[0], t[1], t[2]),
            };
            if live || self.in_gamma.contains(&t) {
                continue;
            }
            if self.gamma_ub.get(&t).is_some_and(|&ub| ub < c) {
                continue;
            }
            cand.push((t, l));
        }
        cand
    }

    /// The `k` nearest vertices of `l` (by growing boxes of the vertex grid; ties by index) and
    /// the box half-width that certified them.
    pub(super) fn nearest(&self, l: u32, k: usize) -> (Vec<u32>, f64) {
        let pl = self.pt(l);
        let n = self.p.len();
        let mut buf = Vec::new();
        let mut rad = self.vgrid.cell();
        loop {
            self.vgrid.query(
                std::array::from_fn(|i| pl[i] - rad),
                std::array::from_fn(|i| pl[i] + rad),
                &mut buf,
            );
            if buf.len() > k || buf.len() >= n {
                let mut v: Vec<(f64, u32)> = buf
                    .iter()
                    .filter(|&&x| x != l)
                    .map(|&x| {
                        let q = self.pt(x);
                        let d2 = (0..3).map(|i| (q[i] - pl[i]).powi(2)).sum::<f64>();
                        (d2, x)
                    })
                    .collect();
                v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                // only points within rad are certainly among the nearest (unless the box holds
                // every point)
                if buf.len() < n {
                    v.retain(|e| e.0 <= rad * rad);
                }
                if v.len() >= k || buf.len() >= n {
                    return (v.into_iter().take(k).map(|e| e.1).collect(), rad);
                }
            }
            rad *= 2.0;
        }
    }

    /// Decides whether triangle `t` is in γ(\[-1,1\],\[c,1\]): `None` when it is, `Some(ub)` with an
    /// upper bound ub < c of its c₁′ when it is not. Points only narrow the centre interval
    /// (c₁′ never grows), so a decision needs only the points that could still change it:
    /// 1. the points `first` (near the triangle; blocking points are often among them);
    /// 2. the points of the diametral ball B(m, r). If then no ball is empty (c₁′ < 0, the gap
    ///    regime of `gamma_values`), c₁′ is final: a point outside B(m, r) has τ of the sign
    ///    of its side (q > 0) and never moves the gap's farther end;
    /// 3. otherwise the points of the witness ball B(s) of
    ///    [`crate::graphs::gamma::CenterInterval::witness_offset`], again and again while s moves: once every point
    ///    of B(s) has been added and s stays, an empty neighbourhood of γ(\[-1,1\],\[c,1\]) lies in
    ///    a ball no further point enters. No fixed radius in terms of c suffices: while some
    ///    ball is empty (c₁′ ≥ 0) a far point inside the largest empty balls can still open a
    ///    gap whose far end passes c.
    ///
    /// A rejection scans on until ub < c − [`UB_LOOKAHEAD`] (not below [`UB_FLOOR`], nor above c;
    /// or until the ball's points run out) so that the cached bound also settles the next
    /// smaller c. Each ball's points are added nearest to its centre first, cells wholly
    /// outside the ball skipped.
    ///
    /// The offsets τ go through the double-double stage of
    /// [`crate::graphs::gamma::TriFrame::with_dd_stage`] before exact expansions (no
    /// allocation for most of the points the floating-point stage does not certify); the
    /// verdicts are those without it (`gamma_decide_with(.., false)`; a lockstep test).
    pub(super) fn gamma_decide(&self, t: [u32; 3], c: f64, first: &[u32]) -> Option<f64> {
        self.gamma_decide_with(t, c, first, true)
    }

    /// [`Self::gamma_decide`], with the offsets' double-double stage when `dd`.
    pub(super) fn gamma_decide_with(
        &self,
        t: [u32; 3],
        c: f64,
        first: &[u32],
        dd: bool,
    ) -> Option<f64> {
        self.gamma_decide_batched(t, c, first, dd, SCAN_BATCH)
    }

    /// [`Self::gamma_decide_with`], the points gathered `batch` at a time (≥ 1) before they
    /// are added (see [`SCAN_BATCH`]; any `batch` gives the same result, bit for bit: the
    /// points are added in the same order and the early checks fall at the same positions).
    pub(super) fn gamma_decide_batched(
        &self,
        t: [u32; 3],
        c: f64,
        first: &[u32],
        dd: bool,
        batch: usize,
    ) -> Option<f64> {
        use crate::graphs::gamma::{
            in_closed_triangle_3d, triangle_circle, CenterInterval, TriFrame,
        };
        let [pa, pb, pc] = t.map(|v| self.pt(v));
        let frame = TriFrame::new(pa, pb, pc).map(|f| if dd { f.with_dd_stage() } else { f });
        let (Some(f), Some((m, r2, n))) = (frame, triangle_circle(pa, pb, pc)) else {
            // degenerate (collinear corners): never a γ-triangle
            return Some(f64::NEG_INFINITY);
        };
        let mut buf = Vec::new();
        let pts = self.p;
        if c <= -1.0 {
            // c = −1: every triangle is in γ([-1,1],[-1,1]) unless a point lies in the closed
            // triangle (then no neighbourhood is empty); such points lie in its bounding box.
            // Only the points in the plane can block (`TriFrame::add` sets `all_blocked` for
            // them alone, by the same exact tests; the binding points and offsets it computes
            // for the others do not enter this decision), so the rest are not added.
            let (lo, hi) = bbox(&[pa, pb, pc]);
            self.vgrid.query(lo, hi, &mut buf);
            let blocked = buf.iter().any(|&z| {
                let x = pts[z as usize];
                !t.contains(&z)
                    && orient3d(pa, pb, pc, x) == 0.0
                    && in_closed_triangle_3d(pa, pb, pc, x, n)
            });
            return blocked.then_some(f64::NEG_INFINITY);
        }
        let mut iv = f.start();
        // the float c₁′ (accurate to 1e-9: the offsets are certified to `TAU_TOL`) raised by
        // `UB_MARGIN`: a proven upper bound of c₁′, the bound returned and cached
        let c1_float = |iv: &CenterInterval| iv.gamma_values().map_or(f64::NEG_INFINITY, |g| g.1);
        let ub_of = |iv: &CenterInterval| c1_float(iv) + UB_MARGIN;
        let stop = (c - UB_LOOKAHEAD).max(UB_FLOOR).min(c);
        // c₁′ < c, exactly (the float bound when it is below c, else the exact decision)
        let below_c = |iv: &CenterInterval| ub_of(iv) < c || !f.c1_at_least(iv, c);
        // `feed` adds one gathered batch of points, `j` the position of its first point in the
        // whole sequence; true when rejected early (ub below stop at a check every 32 points).
        // (`skip`: the points of `first` once they have all been added — adding a point again
        // changes nothing, as a binding end only ever moves to a strictly better point; the
        // positions `j` of the early checks stay those of the full sequence, so the bound
        // returned is the same too.) The points of a batch are gathered first (their
        // coordinate loads independent of each other, so their cache misses overlap), then
        // added: the same points in the same order as one at a time.
        let batch = batch.max(1);
        let feed =
            |iv: &mut CenterInterval, got: &[(u32, P)], j: &mut usize, skip: &[u32]| -> bool {
                for &(z, x) in got {
                    if !t.contains(&z) && !skip.contains(&z) {
                        f.add(iv, x);
                    }
                    let at = *j;
                    *j += 1;
                    if at % 32 == 31 && c1_float(iv) < stop && below_c(iv) {
                        return true;
                    }
                }
                false
            };
        // adds the points; true when rejected (ub below stop on the way, or c₁′ < c at the end)
        let scan =
            |iv: &mut CenterInterval, ids: &mut dyn Iterator<Item = u32>, skip: &[u32]| -> bool {
                let mut j = 0usize;
                let mut got: Vec<(u32, P)> = Vec::with_capacity(batch.min(64));
                for z in ids {
                    got.push((z, pts[z as usize]));
                    if got.len() == batch {
                        if feed(iv, &got, &mut j, skip) {
                            return true;
                        }
                        got.clear();
                    }
                }
                feed(iv, &got, &mut j, skip) || below_c(iv)
            };
        if scan(&mut iv, &mut first.iter().copied(), &[]) {
            return Some(ub_of(&iv));
        }
        let nlen = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let (plo, phi) = self.pbox;
        // every point of the ball B(s) (touching the triangle, offset s), by cells of the point
        // grid (the coarse one for wide boxes) whose centres lie deepest in the ball first —
        // by the power q − 2·s·h (< 0 inside; divided by |s| when |s| > 1: the same order
        // without overflow). When the ball's box holds every point, or is not finite: all
        // points in that order.
        let mut cells: Vec<(f64, &[u32])> = Vec::new();
        let mut got: Vec<(u32, P)> = vec![(0, [0.0; 3]); batch];
        let mut scan_ball = |iv: &mut CenterInterval, s: f64| -> bool {
            let depth = |x: P| {
                let d: P = std::array::from_fn(|i| x[i] - m[i]);
                let q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - r2;
                let h = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
                if s.abs() > 1.0 {
                    q / s.abs() - 2.0 * s.signum() * h
                } else {
                    q - 2.0 * s * h
                }
            };
            let centre: P = std::array::from_fn(|i| m[i] + s * n[i]);
            let radius = nlen * (iv.r_over_n * iv.r_over_n + s * s).sqrt() * (1.0 + 1e-9);
            let finite = radius.is_finite() && centre.iter().all(|x| x.is_finite());
            let all = !finite
                || (0..3).all(|i| centre[i] - radius <= plo[i] && centre[i] + radius >= phi[i]);
            let (lo, hi): (P, P) = if all {
                (plo, phi)
            } else {
                (
                    std::array::from_fn(|i| centre[i] - radius),
                    std::array::from_fn(|i| centre[i] + radius),
                )
            };
            let g = self.point_grid_for(lo, hi);
            if !g.is_single_level() {
                // (points are never wide boxes; kept for safety) every point, in index order
                return scan(iv, &mut (0..pts.len() as u32), first);
            }
            cells.clear();
            let (origin, cell) = (g.origin(), g.cell());
            let r2s = radius * radius;
            g.for_cells(lo, hi, |k, ids| {
                let mid: P = std::array::from_fn(|i| origin[i] + (k[i] as f64 + 0.5) * cell);
                // a cell wholly outside the ball holds no point that `inside` admits: skip it
                // (the points scanned, and their order, stay the same). The cell's box is
                // widened for the rounding of the points' cell coordinates, the distance
                // compared with room for its own rounding.
                if !all {
                    let d2: f64 = (0..3)
                        .map(|i| {
                            let half = 0.5 * cell * (1.0 + 1e-6) + 1e-12 * mid[i].abs();
                            ((mid[i] - centre[i]).abs() - half).max(0.0).powi(2)
                        })
                        .sum();
                    if d2 > r2s * (1.0 + 1e-6) {
                        return;
                    }
                }
                cells.push((depth(mid), ids));
            });
            cells.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
            // the points of the cells in that order that lie in the ball, gathered `batch` at a
            // time (a point outside is written and dropped: no branch on its test) and fed
            let inside =
                |x: &P| all || (0..3).map(|i| (x[i] - centre[i]).powi(2)).sum::<f64>() <= r2s;
            let mut j = 0usize;
            let mut len = 0usize;
            for &(_, ids) in cells.iter() {
                for &z in ids {
                    let x = pts[z as usize];
                    got[len] = (z, x);
                    len += usize::from(inside(&x));
                    if len == batch {
                        if feed(iv, &got, &mut j, first) {
                            return true;
                        }
                        len = 0;
                    }
                }
            }
            feed(iv, &got[..len], &mut j, first) || below_c(iv)
        };
        if scan_ball(&mut iv, 0.0) {
            return Some(ub_of(&iv));
        }
        let mut scanned = 0.0; // B(0) = B(m, r)
                               // s moves only when a point of B(s) changed the interval, i.e. became a binding point
                               // strictly better than the last one on its side (exact): at most 2n + 2 moves. The cap
                               // makes that explicit; beyond it (never reached) every point decides.
        let mut moves = 0usize;
        loop {
            if !iv.finite_blocked && iv.lo > iv.hi {
                return None; // the gap regime with B(m, r) added: c₁′ ≥ c is final
            }
            moves += 1;
            if moves > 2 * pts.len() + 4 {
                let all = scan(&mut iv, &mut (0..pts.len() as u32), first);
                return all.then(|| ub_of(&iv));
            }
            let Some(s) = iv.witness_offset(c) else {
                // only half-spaces can be empty (`finite_blocked`): every point decides
                return if scan(&mut iv, &mut (0..pts.len() as u32), first) {
                    Some(ub_of(&iv))
                } else {
                    None
                };
            };
            if s == scanned {
                return None;
            }
            if scan_ball(&mut iv, s) {
                return Some(ub_of(&iv));
            }
            scanned = s;
        }
    }

    /// Adds the given triangles where they are certified inside (as for the rewiring; see
    /// the module documentation) and pushes the boundary faces on their edges; returns how
    /// many were added.
    ///
    /// The same as `try_insert` one after the other, in order: adding a triangle
    /// changes the live triangles but not the boundary, so the boundary conditions
    /// (`insertable_at_boundary`) are decided for all triangles first, in parallel —
    /// unless a triangle comes back that was a boundary face (its flag would count again):
    /// from then on one by one. The boundary faces on the new triangles' edges are then
    /// evaluated (in parallel without keep triangles) and pushed or locked again.
    pub fn augment(&mut self, tris: &[[u32; 3]]) -> usize {
        use rayon::prelude::*;
        let this = &*self;
        let at_boundary: Vec<bool> = tris
            .par_iter()
            .map(|&t| this.insertable_at_boundary(t))
            .collect();
        let mut one_by_one = false;
        let mut added = 0;
        let mut faces = Vec::new();
        // No change stamps for the added triangles: a live triangle enters the removability
        // of exactly the boundary faces on its edges (as a candidate tetrahedron's face, all
        // of which contain an edge of the face), and those are evaluated and locked again
        // below — other locked faces stay valid.
        let track = std::mem::replace(&mut self.track, false);
        for (&t, ok) in tris.iter().zip(at_boundary) {
            let inserted = if one_by_one {
                self.try_insert(t)
            } else if ok && !self.has(t[0], t[1], t[2]) {
                one_by_one = self
                    .id_of(sorted3(t))
                    .is_some_and(|i| self.bflag[i as usize]);
                self.add_tri(t)
            } else {
                false
            };
            if inserted {
                added += 1;
                // the boundary faces on its edges may have gained a tetrahedron
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    for (x, y) in [(a, b), (b, a)] {
                        if let Some(z) = self.bnext_of(x, y) {
                            faces.push([x, y, z]);
                        }
                    }
                }
            }
        }
        self.track = track;
        self.added += added;
        if self.keep.is_empty() && !self.sequential_sweeps {
            // without keep triangles an evaluation changes nothing: all in parallel, then the
            // verdicts in order (as one after the other)
            let this = &*self;
            let verdicts: Vec<Result<(f64, u32), (P, P)>> = faces
                .par_iter()
                .map_init(Vec::new, |buf, &f| {
                    this.best_plain(f, buf).ok_or_else(|| this.lock_box(f))
                })
                .collect();
            let e = self.epoch;
            for (f, v) in faces.into_iter().zip(verdicts) {
                match v {
                    Ok((key, l)) => {
                        self.heap.push(Entry { key, item: (f, l) });
                        self.locked_at.remove(&f);
                    }
                    Err((lo, hi)) => {
                        if track {
                            self.locked_at.insert(f, (e, lo, hi));
                        }
                    }
                }
            }
            return added;
        }
        for f in faces {
            let e = self.epoch;
            if self.push(f) {
                self.locked_at.remove(&f);
            } else if track {
                let (lo, hi) = self.lock_box(f);
                self.locked_at.insert(f, (e, lo, hi));
            }
        }
        added
    }
}

impl Engine3 {
    /// V §5.4 after a locked Delaunay constriction `st`: augment only where needed. First the
    /// live tetrahedra within [`LOCAL_DEPTH`] neighbour steps of the vertices off the boundary
    /// (the rest of the object is locked for the Delaunay constriction and far from the added
    /// triangles; without keep triangles only); the whole object when that does not free every
    /// vertex.
    pub(super) fn augment_after_lock(&self, st: &Constriction3) -> Outcome3 {
        if self.keep_v.is_empty() {
            let region = near_locked(&self.d, &st.alive, &st.triangles, LOCAL_DEPTH);
            let live = self.faces_of(&region);
            let mut g = General3::new(&self.pos, &st.triangles, &live, &self.keep_v);
            // (the boundary and live triangles are faces of Delaunay tetrahedra)
            g.trust_initial_as_delaunay();
            let c = augment_until_done_3d(&mut g, 0.0);
            if g.done() {
                return Outcome3::general(&g, c, st.iterations);
            }
        }
        let live = self.faces_of(&st.alive);
        let mut g = General3::new(&self.pos, &st.triangles, &live, &self.keep_v);
        // (keep triangles too: this path has only Delaunay faces among them)
        g.trust_initial_as_delaunay();
        let c = augment_until_done_3d(&mut g, 0.0);
        Outcome3::general(&g, c, st.iterations)
    }
}

/// How many points of a ball scan [`General3::gamma_decide`] gathers (coordinates loaded,
/// ball test) before adding them to the centre interval. The scans are bound by cache misses
/// on the points' coordinates (ids in grid cells, coordinates in input order); gathered in a
/// tight loop whose loads do not wait for each other, the misses overlap instead of each
/// waiting behind the previous point's in-sphere work. Larger batches gather points past an
/// early rejection for nothing.
pub(super) const SCAN_BATCH: usize = 32;

/// Up to this many vertices [`crate::boundary::CParam::Fixed`]`(c < 0)` constricts all of
/// γ(\[-1,1\],\[c,1\]) ([`crate::graphs::beyond3::beyond_dt_3d`], which tries every triple: O(N³));
/// above, the Delaunay triangles plus the γ-triangles at every interior vertex and pairs of its
/// 16 nearest vertices ([`General3::local_gamma`]).
pub(super) const BEYOND_ALL_MAX: usize = 400;

/// Runs `g` and, while locked, augments it with the γ(\[-1,1\],\[c,1\]) triangles at the vertices
/// off the boundary ([`General3::local_gamma`], their 16 nearest vertices) for
/// c = from − 0.1, … −1; vertices still off the boundary then are put on it through the nearest
/// boundary face that sees them ([`General3::insert_left_out`], c = −1 with a wider search).
/// Returns the last c used.
pub(super) fn augment_until_done_3d(g: &mut General3<'_>, from: f64) -> f64 {
    g.run();
    let mut c = from;
    let mut step = 1;
    while !g.done() && step <= 10 {
        c = (from - step as f64 / 10.0).max(-1.0);
        let extra = g.local_gamma(c, 16);
        if g.augment(&extra) > 0 {
            g.run();
        }
        step += 1;
    }
    if !g.done() && c <= -1.0 && g.insert_left_out() > 0 {
        g.run();
    }
    c
}

/// Tetrahedron steps from the vertices off the boundary that the local general engine sees.
const LOCAL_DEPTH: usize = 4;

/// The live tetrahedra within `depth` neighbour steps of a tetrahedron at a vertex that is
/// not on the boundary `tris` (O(T) for T tetrahedra).
fn near_locked(d: &Delaunay3, alive: &[bool], tris: &[[u32; 3]], depth: usize) -> Vec<bool> {
    let mut on = vec![false; d.points.len()];
    for t in tris {
        for &v in t {
            on[v as usize] = true;
        }
    }
    let mut region = vec![false; d.tets.len()];
    let mut front: Vec<u32> = Vec::new();
    for (t, tet) in d.tets.iter().enumerate() {
        if alive[t] && tet.iter().any(|&v| !on[v as usize]) {
            region[t] = true;
            front.push(t as u32);
        }
    }
    for _ in 0..depth {
        let mut next = Vec::new();
        for &t in &front {
            for &n in &d.neighbors[t as usize] {
                if n != crate::util::NONE && alive[n as usize] && !region[n as usize] {
                    region[n as usize] = true;
                    next.push(n);
                }
            }
        }
        front = next;
    }
    region
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The former code, kept as the references of `gamma_decide_equals_the_former_code` and
    /// `gamma_candidates_equal_the_former_code`.
    impl General3<'_> {
        /// `gamma_candidates` sorting every face met (before the selection of the nearest k).
        fn gamma_candidates_reference(
            &self,
            l: u32,
            k: usize,
            c: f64,
            tb: &mut Vec<u32>,
        ) -> Vec<([u32; 3], u32)> {
            let (near, rad) = &self.near_cache[&l];
            let mut cand = Vec::new();
            let pl = self.pt(l);
            // pairs of near vertices, and the edges of the k boundary faces nearest to l (by
            // centroid; the faces a removal w.r.t. l starts from)
            let mut pairs: Vec<(u32, u32)> = Vec::new();
            for (i, &x) in near.iter().enumerate() {
                for &y in &near[i + 1..] {
                    pairs.push((x, y));
                }
            }
            // the k faces nearest by centroid among those meeting the box of half-width 2·rad:
            // a face missing from the box of half-width rad has its centroid farther than rad,
            // so when that smaller box already holds k faces with centroids within rad, they
            // are the same k (and the same order)
            let mut faces: Vec<(f64, [u32; 3])> = Vec::new();
            for reach_l in [*rad, 2.0 * rad] {
                self.bgrid.query(
                    std::array::from_fn(|i| pl[i] - reach_l),
                    std::array::from_fn(|i| pl[i] + reach_l),
                    tb,
                );
                faces = tb
                    .iter()
                    .filter(|&&i| self.live[i as usize] && self.bflag[i as usize])
                    .map(|&i| self.tris[i as usize])
                    .map(|u| {
                        let q = u.map(|v| self.pt(v));
                        let d2 = (0..3)
                            .map(|i| ((q[0][i] + q[1][i] + q[2][i]) / 3.0 - pl[i]).powi(2))
                            .sum::<f64>();
                        (d2, u)
                    })
                    .collect();
                faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                if faces.iter().filter(|f| f.0 <= rad * rad).count() >= k {
                    break;
                }
            }
            for (_, u) in faces.into_iter().take(k) {
                for e in 0..3 {
                    pairs.push((u[e], u[(e + 1) % 3]));
                }
            }
            for (x, y) in pairs {
                let t = sorted3([l, x, y]);
                if x == l || y == l || self.has(t[0], t[1], t[2]) || self.in_gamma.contains(&t) {
                    continue;
                }
                if self.gamma_ub.get(&t).is_some_and(|&ub| ub < c) {
                    continue;
                }
                cand.push((t, l));
            }
            cand
        }

        /// `gamma_decide` before the c = −1 shortcut (every point of the triangle's box added)
        /// and before the points of `first` were skipped in the ball scans.
        fn gamma_decide_reference(&self, t: [u32; 3], c: f64, first: &[u32]) -> Option<f64> {
            use crate::graphs::gamma::{triangle_circle, CenterInterval, TriFrame};
            let [pa, pb, pc] = t.map(|v| self.pt(v));
            // (with the offsets' double-double stage, as `gamma_decide`: this reference is of
            // the c = −1 shortcut and the skipped points; the stage has its own lockstep test)
            let (Some(f), Some((m, r2, n))) = (
                TriFrame::new(pa, pb, pc).map(TriFrame::with_dd_stage),
                triangle_circle(pa, pb, pc),
            ) else {
                // degenerate (collinear corners): never a γ-triangle
                return Some(f64::NEG_INFINITY);
            };
            let mut iv = f.start();
            let mut buf = Vec::new();
            let pts = self.p;
            if c <= -1.0 {
                // c = −1: every triangle is in γ([-1,1],[-1,1]) unless a point lies in the closed
                // triangle (then no neighbourhood is empty); such points lie in its bounding box
                let (lo, hi) = bbox(&[pa, pb, pc]);
                self.vgrid.query(lo, hi, &mut buf);
                for &z in &buf {
                    if !t.contains(&z) {
                        f.add(&mut iv, pts[z as usize]);
                    }
                }
                return if iv.all_blocked {
                    Some(f64::NEG_INFINITY)
                } else {
                    None
                };
            }
            // the float c₁′ (accurate to 1e-9: the offsets are certified to `TAU_TOL`) raised by
            // `UB_MARGIN`: a proven upper bound of c₁′, the bound returned and cached
            let c1_float =
                |iv: &CenterInterval| iv.gamma_values().map_or(f64::NEG_INFINITY, |g| g.1);
            let ub_of = |iv: &CenterInterval| c1_float(iv) + UB_MARGIN;
            let stop = (c - UB_LOOKAHEAD).max(UB_FLOOR).min(c);
            // c₁′ < c, exactly (the float bound when it is below c, else the exact decision)
            let below_c = |iv: &CenterInterval| ub_of(iv) < c || !f.c1_at_least(iv, c);
            // adds the points; true when rejected (ub below stop on the way, or c₁′ < c at the end)
            let scan = |iv: &mut CenterInterval, ids: &mut dyn Iterator<Item = u32>| -> bool {
                for (j, z) in ids.enumerate() {
                    if !t.contains(&z) {
                        f.add(iv, pts[z as usize]);
                    }
                    if j % 32 == 31 && c1_float(iv) < stop && below_c(iv) {
                        return true;
                    }
                }
                below_c(iv)
            };
            if scan(&mut iv, &mut first.iter().copied()) {
                return Some(ub_of(&iv));
            }
            let nlen = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let (plo, phi) = self.pbox;
            // every point of the ball B(s) (touching the triangle, offset s), by cells of the point
            // grid (the coarse one for wide boxes) whose centres lie deepest in the ball first —
            // by the power q − 2·s·h (< 0 inside; divided by |s| when |s| > 1: the same order
            // without overflow). When the ball's box holds every point, or is not finite: all
            // points in that order.
            let mut cells: Vec<(f64, &[u32])> = Vec::new();
            let mut scan_ball = |iv: &mut CenterInterval, s: f64| -> bool {
                let depth = |x: P| {
                    let d: P = std::array::from_fn(|i| x[i] - m[i]);
                    let q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - r2;
                    let h = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
                    if s.abs() > 1.0 {
                        q / s.abs() - 2.0 * s.signum() * h
                    } else {
                        q - 2.0 * s * h
                    }
                };
                let centre: P = std::array::from_fn(|i| m[i] + s * n[i]);
                let radius = nlen * (iv.r_over_n * iv.r_over_n + s * s).sqrt() * (1.0 + 1e-9);
                let finite = radius.is_finite() && centre.iter().all(|x| x.is_finite());
                let all = !finite
                    || (0..3).all(|i| centre[i] - radius <= plo[i] && centre[i] + radius >= phi[i]);
                let (lo, hi): (P, P) = if all {
                    (plo, phi)
                } else {
                    (
                        std::array::from_fn(|i| centre[i] - radius),
                        std::array::from_fn(|i| centre[i] + radius),
                    )
                };
                let g = self.point_grid_for(lo, hi);
                if !g.is_single_level() {
                    // (points are never wide boxes; kept for safety) every point, in index order
                    return scan(iv, &mut (0..pts.len() as u32));
                }
                cells.clear();
                let (origin, cell) = (g.origin(), g.cell());
                let r2s = radius * radius;
                g.for_cells(lo, hi, |k, ids| {
                    let mid: P = std::array::from_fn(|i| origin[i] + (k[i] as f64 + 0.5) * cell);
                    // a cell wholly outside the ball holds no point that `inside` admits: skip it
                    // (the points scanned, and their order, stay the same). The cell's box is
                    // widened for the rounding of the points' cell coordinates, the distance
                    // compared with room for its own rounding.
                    if !all {
                        let d2: f64 = (0..3)
                            .map(|i| {
                                let half = 0.5 * cell * (1.0 + 1e-6) + 1e-12 * mid[i].abs();
                                ((mid[i] - centre[i]).abs() - half).max(0.0).powi(2)
                            })
                            .sum();
                        if d2 > r2s * (1.0 + 1e-6) {
                            return;
                        }
                    }
                    cells.push((depth(mid), ids));
                });
                cells.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
                let inside = |z: &u32| {
                    all || {
                        let x = pts[*z as usize];
                        (0..3).map(|i| (x[i] - centre[i]).powi(2)).sum::<f64>() <= r2s
                    }
                };
                scan(
                    iv,
                    &mut cells
                        .iter()
                        .flat_map(|e| e.1.iter().copied())
                        .filter(inside),
                )
            };
            if scan_ball(&mut iv, 0.0) {
                return Some(ub_of(&iv));
            }
            let mut scanned = 0.0; // B(0) = B(m, r)
                                   // s moves only when a point of B(s) changed the interval, i.e. became a binding point
                                   // strictly better than the last one on its side (exact): at most 2n + 2 moves. The cap
                                   // makes that explicit; beyond it (never reached) every point decides.
            let mut moves = 0usize;
            loop {
                if !iv.finite_blocked && iv.lo > iv.hi {
                    return None; // the gap regime with B(m, r) added: c₁′ ≥ c is final
                }
                moves += 1;
                if moves > 2 * pts.len() + 4 {
                    let all = scan(&mut iv, &mut (0..pts.len() as u32));
                    return all.then(|| ub_of(&iv));
                }
                let Some(s) = iv.witness_offset(c) else {
                    // only half-spaces can be empty (`finite_blocked`): every point decides
                    return if scan(&mut iv, &mut (0..pts.len() as u32)) {
                        Some(ub_of(&iv))
                    } else {
                        None
                    };
                };
                if s == scanned {
                    return None;
                }
                if scan_ball(&mut iv, s) {
                    return Some(ub_of(&iv));
                }
                scanned = s;
            }
        }
    }
    use rand::{Rng, SeedableRng};
    /// local_gamma with k ≥ n tries every triangle at a vertex off the boundary: its results
    /// over decreasing c must be exactly the triangles of γ(\[-1,1\],\[c,1\]) there (Def. 3.1 by
    /// the full center interval over all points), without the live ones.
    #[test]
    fn local_gamma_matches_the_full_definition() {
        use crate::graphs::gamma::center_interval_3d;
        for seed in 0..4u64 {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let n = 24;
            let pts: Vec<crate::geom::Point3> = (0..n)
                .map(|i| {
                    if seed == 3 && i % 4 == 0 {
                        // far points: they decide for balls far beyond the diametral ones
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                        crate::geom::Point3::new(4.0 * v[0] / r, 4.0 * v[1] / r, 4.0 * v[2] / r)
                    } else if i % 2 == 0 || seed == 2 {
                        // on a sphere (rounded), and inside
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                        let s = if i % 4 == 0 { 1.0 } else { 0.6 };
                        crate::geom::Point3::new(v[0] / r * s, v[1] / r * s, v[2] / r * s)
                    } else {
                        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-0.5..0.5));
                        crate::geom::Point3::new(v[0], v[1], v[2])
                    }
                })
                .collect();
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let nv = pos.len();
            let mut g = General3::new(&pos, &d.hull, &[], &[]);
            let locked: Vec<u32> = (0..nv as u32).filter(|&v| !g.on_boundary(v)).collect();
            assert!(locked.len() >= 5, "{}", locked.len());
            let mut found: std::collections::BTreeSet<[u32; 3]> = Default::default();
            for c in [-0.1, -0.3, -0.5, -0.7, -0.9, -1.0] {
                for t in g.local_gamma(c, nv) {
                    assert!(found.insert(t), "returned twice: {t:?}");
                }
                let mut expect: std::collections::BTreeSet<[u32; 3]> = Default::default();
                for a in 0..nv as u32 {
                    for b in a + 1..nv as u32 {
                        for e in b + 1..nv as u32 {
                            let t = [a, b, e];
                            if !t.iter().any(|v| locked.contains(v)) || g.has(a, b, e) {
                                continue;
                            }
                            let Some(iv) =
                                center_interval_3d(&pos, a as usize, b as usize, e as usize)
                            else {
                                continue;
                            };
                            if iv.gamma_values().is_some_and(|v| v.1 >= c) {
                                expect.insert(t);
                            }
                        }
                    }
                }
                let missing: Vec<_> = expect.difference(&found).collect();
                let extra: Vec<_> = found.difference(&expect).collect();
                for t in missing.iter().chain(&extra) {
                    let iv = center_interval_3d(&pos, t[0] as usize, t[1] as usize, t[2] as usize);
                    eprintln!("{t:?}: {:?}", iv.and_then(|iv| iv.gamma_values()));
                }
                assert!(
                    missing.is_empty() && extra.is_empty(),
                    "seed {seed}, c {c}: missing {missing:?}, extra {extra:?}"
                );
            }
        }
    }

    /// n points on a bumpy ellipsoid (radius 1 ± 0.15 waves, ±0.01 noise, z stretched by 1.3).
    fn bumpy_sphere(n: usize, seed: u64) -> Vec<crate::geom::Point3> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                let s = 1.0
                    + 0.15 * (5.0 * v[0] / n).sin() * (4.0 * v[1] / n).cos()
                    + rng.gen_range(-0.01..0.01);
                crate::geom::Point3::new(v[0] / n * s, v[1] / n * s, 1.3 * v[2] / n * s)
            })
            .collect()
    }

    /// gamma_decide on a dense bumpy sphere (3000 points, grid cells far smaller than the
    /// set): for triangles among the 16 nearest vertices of many vertices, at several c, it
    /// accepts exactly the triangles whose c₁′ over *all* points (the full center interval)
    /// is ≥ c, and a rejection's bound is ≥ that c₁′. Includes triangles whose largest empty
    /// balls reach far beyond the balls of parameter c (a far point inside them opens the gap
    /// that rejects them), which a scan bounded by those balls gets wrong.
    #[test]
    fn gamma_decide_matches_the_full_center_interval() {
        use crate::graphs::gamma::center_interval_3d;
        let pts = bumpy_sphere(3000, 9);
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let g = General3::new(&pos, &d.hull, &[], &[]);
        let (mut accepted, mut rejected, mut far_gap) = (0, 0, 0);
        for l in (0..pos.len() as u32).step_by(97) {
            let near = g.nearest(l, 16).0;
            for (i, &x) in near.iter().enumerate() {
                for &y in &near[i + 1..] {
                    let t = sorted3([l, x, y]);
                    let Some(full) =
                        center_interval_3d(&pos, t[0] as usize, t[1] as usize, t[2] as usize)
                    else {
                        continue;
                    };
                    let c1 = full.gamma_values().map_or(f64::NEG_INFINITY, |v| v.1);
                    for c in [-0.1, -0.3, -0.6, -0.9] {
                        match g.gamma_decide(t, c, &near) {
                            None => {
                                assert!(c1 >= c, "{t:?} c {c}: accepted, c1' = {c1}");
                                accepted += 1;
                            }
                            Some(ub) => {
                                assert!(c1 < c && ub >= c1, "{t:?} c {c}: {ub} vs c1' {c1}");
                                rejected += 1;
                                // a gap on one side beyond the balls of parameter c
                                far_gap +=
                                    usize::from(full.lo > full.hi && full.lo * full.hi > 0.0);
                            }
                        }
                    }
                }
            }
        }
        assert!(
            accepted > 500 && rejected > 500 && far_gap > 100,
            "{accepted} {rejected} {far_gap}"
        );
    }

    /// augment (boundary conditions decided in parallel first) adds exactly the triangles that
    /// try_insert one after the other adds, in the same order: same ids, live flags and edge
    /// lists — with repeated triangles, boundary faces and degenerate ones among them.
    #[test]
    fn augment_equals_inserting_one_by_one() {
        let pts = bumpy_sphere(1500, 4);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let mut a = General3::new(&pos, &d.hull, &[], &[]);
        let mut b = General3::new(&pos, &d.hull, &[], &[]);
        let mut extra = a.local_gamma(-0.6, 16);
        extra.extend(b.local_gamma(-0.6, 16).into_iter().take(40));
        extra.extend(d.hull.iter().take(30).map(|&f| sorted3(f)));
        extra.push([5, 5, 9]);
        // triples of hull vertices: outside the region unless along an inward hull edge
        let hv: Vec<u32> = d.hull.iter().flatten().copied().collect();
        for _ in 0..200 {
            let t = [0; 3].map(|_: u32| hv[rng.gen_range(0..hv.len())]);
            extra.push(t);
        }
        let added = a.augment(&extra);
        let mut one = 0;
        for &t in &extra {
            one += usize::from(b.try_insert(t));
        }
        assert_eq!(added, one);
        let fails = extra
            .iter()
            .filter(|&&t| !b.insertable_at_boundary(t))
            .count();
        assert!(
            added > 100 && fails > 100,
            "{added} of {}, {fails}",
            extra.len()
        );
        assert_eq!(a.tris, b.tris);
        assert_eq!(a.live, b.live);
        assert_eq!(a.eadj, b.eadj);
    }

    /// Points on the surface of a cube on an integer lattice (exactly coplanar quadruples,
    /// collinear triples, lattice points inside lattice triangles) and random points inside
    /// it: the degenerate cases of `gamma_decide` (points in the plane, in the closed
    /// triangle, on the circumcircle).
    fn cube_lattice(m: i32, inner: usize, seed: u64) -> Vec<crate::geom::Point3> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut v = Vec::new();
        for x in 0..=m {
            for y in 0..=m {
                for z in 0..=m {
                    if [x, y, z].iter().any(|&c| c == 0 || c == m) {
                        v.push(crate::geom::Point3::new(x as f64, y as f64, z as f64));
                    }
                }
            }
        }
        for _ in 0..inner {
            let q: [f64; 3] = std::array::from_fn(|_| rng.gen_range(0.5..m as f64 - 0.5));
            v.push(crate::geom::Point3::new(q[0], q[1], q[2]));
        }
        v
    }

    /// The Delaunay tetrahedralization of [`cube_lattice`]`(m, inner, seed)`, its points, and
    /// the faces of its tetrahedra with a corner among the first three points off the hull:
    /// a constriction from the hull (`d.hull`) with a small region to work on.
    fn lattice_from_hull(
        m: i32,
        inner: usize,
        seed: u64,
    ) -> (crate::delaunay::d3::Delaunay3, Vec<P>, Vec<[u32; 3]>) {
        let d = crate::delaunay::d3::triangulate(&cube_lattice(m, inner, seed)).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let mut on = vec![false; pos.len()];
        for &v in d.hull.iter().flatten() {
            on[v as usize] = true;
        }
        let inner_v: Vec<u32> = (0..pos.len() as u32)
            .filter(|&v| !on[v as usize])
            .take(3)
            .collect();
        let region: Vec<bool> = d
            .tets
            .iter()
            .map(|t| t.iter().any(|v| inner_v.contains(v)))
            .collect();
        let live = super::super::test_sets::live_faces(&d, &region);
        (d, pos, live)
    }

    /// The supporting planes proposed only by the boundary faces among the live triangles'
    /// corners (`general::support_faces`) leave the general engine exactly as with the planes
    /// of the whole boundary (the former construction, kept here through
    /// `blank_with_support`): same surface, removals, added triangles, vertices on the
    /// boundary and last c after the whole schedule of `augment_until_done_3d` — (1) as
    /// `augment_after_lock` starts it, on clustered points on which the Delaunay constriction
    /// locks; (2) from the convex hull of cube lattices with points inside (six facets: six
    /// supporting planes of the whole boundary) with only the tetrahedra at a few inner
    /// vertices live (none of the facets' planes is proposed then: the case is exercised, the
    /// planes differ).
    #[test]
    fn support_from_the_region_changes_nothing() {
        use super::super::support::Support;
        let go = |pos: &[P], bnd: &[[u32; 3]], live: &[[u32; 3]], whole: bool| {
            let mut g = if whole {
                let s = Support::new(pos, bnd);
                let mut g = General3::blank_with_support(pos, bnd, live, &[], s);
                g.build(bnd, live, &[]);
                g.track = true;
                g.push_all();
                g
            } else {
                General3::new(pos, bnd, live, &[])
            };
            let planes = g.support.len();
            let c = augment_until_done_3d(&mut g, 0.0);
            let counts = (g.iterations, g.added, g.boundary_vertices, c);
            (g.boundary(), counts, planes)
        };
        let mut locked = 0;
        for seed in [1647u64, 1755] {
            let Some((d, pos, st)) = super::super::test_sets::locked_clustered_cube(seed) else {
                continue;
            };
            locked += 1;
            let region = near_locked(&d, &st.alive, &st.triangles, LOCAL_DEPTH);
            let live = super::super::test_sets::live_faces(&d, &region);
            let (a, b) = (
                go(&pos, &st.triangles, &live, true),
                go(&pos, &st.triangles, &live, false),
            );
            assert_eq!((&a.0, a.1), (&b.0, b.1), "seed {seed}");
        }
        assert!(locked >= 1);
        for (m, inner, seed) in [(5, 30, 1u64), (6, 60, 2), (7, 90, 3)] {
            let (d, pos, live) = lattice_from_hull(m, inner, seed);
            let (a, b) = (
                go(&pos, &d.hull, &live, true),
                go(&pos, &d.hull, &live, false),
            );
            assert_eq!((&a.0, a.1), (&b.0, b.1), "lattice {m}");
            assert_eq!(a.2, 6, "lattice {m}");
            assert!(b.2 < a.2, "lattice {m}: {} planes", b.2);
        }
    }

    /// gamma_decide equals the former code (`gamma_decide_reference`: every point of the
    /// box added for c = −1, the points of `first` added again in the ball scans) — the same
    /// verdicts and bit-identical bounds — on a bumpy sphere and on a cube lattice with points
    /// inside, for the triangles of every vertex with pairs of its 16 nearest, at c from −0.1
    /// to −1; with enough triangles blocked at c = −1 by a point in the plane (and, on the
    /// lattice, with points off the plane in the triangle's box).
    #[test]
    fn gamma_decide_equals_the_former_code() {
        let sets = [(bumpy_sphere(2000, 5), 37), (cube_lattice(7, 120, 6), 3)];
        for (set, (pts, step)) in sets.into_iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let g = General3::new(&pos, &d.hull, &[], &[]);
            let (mut same, mut blocked_at_minus_one, mut rejected) = (0, 0, 0);
            for l in (0..pos.len() as u32).step_by(step) {
                let near = g.nearest(l, 16).0;
                for (i, &x) in near.iter().enumerate() {
                    for &y in &near[i + 1..] {
                        let t = sorted3([l, x, y]);
                        for c in [-0.1, -0.3, -0.5, -0.8, -0.9, -1.0] {
                            let new = g.gamma_decide(t, c, &near);
                            let old = g.gamma_decide_reference(t, c, &near);
                            assert_eq!(
                                new.map(f64::to_bits),
                                old.map(f64::to_bits),
                                "{t:?} c {c}: {new:?} against {old:?}"
                            );
                            same += 1;
                            rejected += usize::from(new.is_some());
                            blocked_at_minus_one += usize::from(c <= -1.0 && new.is_some());
                        }
                    }
                }
            }
            // (on the lattice: triangles with a lattice point in them)
            let need_blocked = if set == 1 { 20 } else { 0 };
            assert!(
                same > 5000 && rejected > 1000 && blocked_at_minus_one >= need_blocked,
                "set {set}: {same} {rejected} {blocked_at_minus_one}"
            );
        }
    }

    /// The ball scans' batches (`gamma_decide_batched`, points gathered `batch` at a time
    /// before they are added) change nothing: for batches of 1, 2, 3, 5, 32 (the default) and
    /// 1000 the verdicts and bounds are bit-identical to the former code's
    /// (`gamma_decide_reference`, one point at a time, the early checks every 32 points of each
    /// scan), with and without the double-double stage, on a bumpy sphere and on a cube lattice
    /// with points inside, for the triangles of some vertices with pairs of their 16 nearest.
    #[test]
    fn gamma_decide_batches_equal_the_former_code() {
        let sets = [(bumpy_sphere(2000, 7), 53), (cube_lattice(7, 120, 6), 7)];
        for (set, (pts, step)) in sets.into_iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let g = General3::new(&pos, &d.hull, &[], &[]);
            let (mut same, mut rejected, mut accepted) = (0, 0, 0);
            for l in (0..pos.len() as u32).step_by(step) {
                let near = g.nearest(l, 16).0;
                for (i, &x) in near.iter().enumerate() {
                    for &y in near[i + 1..].iter().step_by(2) {
                        let t = sorted3([l, x, y]);
                        for c in [-0.1, -0.4, -0.8, -0.9] {
                            let old = g.gamma_decide_reference(t, c, &near);
                            for batch in [1, 2, 3, 5, SCAN_BATCH, 1000] {
                                let new = g.gamma_decide_batched(t, c, &near, true, batch);
                                assert_eq!(
                                    new.map(f64::to_bits),
                                    old.map(f64::to_bits),
                                    "{t:?} c {c} batch {batch}: {new:?} against {old:?}"
                                );
                                let plain = g.gamma_decide_batched(t, c, &near, false, batch);
                                let plain_ref = g.gamma_decide_batched(t, c, &near, false, 1);
                                assert_eq!(plain.map(f64::to_bits), plain_ref.map(f64::to_bits));
                                same += 1;
                            }
                            rejected += usize::from(old.is_some());
                            accepted += usize::from(old.is_none());
                        }
                    }
                }
            }
            assert!(
                same > 5000 && rejected > 300 && accepted > 100,
                "set {set}: {same} {rejected} {accepted}"
            );
        }
    }

    /// The offsets' double-double stage (`TriFrame::with_dd_stage`) changes no verdict of
    /// gamma_decide: with and without it, the same triangles are in γ(\[-1,1\],\[c,1\]), on
    /// a dense bumpy sphere (skinny triangles of near vertices, points nearly in their planes)
    /// and on the cube lattice, for the triangles of every vertex with pairs of its 16 nearest.
    #[test]
    fn gamma_decide_verdicts_do_not_depend_on_the_dd_stage() {
        let sets = [(bumpy_sphere(4000, 12), 23), (cube_lattice(7, 120, 6), 5)];
        for (set, (pts, step)) in sets.into_iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let g = General3::new(&pos, &d.hull, &[], &[]);
            let (mut decided, mut accepted) = (0, 0);
            for l in (0..pos.len() as u32).step_by(step) {
                let near = g.nearest(l, 16).0;
                for (i, &x) in near.iter().enumerate() {
                    for &y in &near[i + 1..] {
                        let t = sorted3([l, x, y]);
                        for c in [-0.1, -0.4, -0.8, -0.9] {
                            let with = g.gamma_decide_with(t, c, &near, true);
                            let without = g.gamma_decide_with(t, c, &near, false);
                            assert_eq!(with.is_none(), without.is_none(), "{t:?} c {c}");
                            decided += 1;
                            accepted += usize::from(with.is_none());
                        }
                    }
                }
            }
            assert!(
                decided > 5000 && accepted > 500 && decided - accepted > 500,
                "set {set}: {decided} {accepted}"
            );
        }
    }

    /// Asserts `gamma_candidates` = `gamma_candidates_reference` for every vertex of `locked`
    /// and every k of `ks` and c of `cs` (`at` names the case); returns the candidates compared.
    fn compare_candidates(
        g: &General3<'_>,
        locked: &[u32],
        ks: &[usize],
        cs: &[f64],
        at: &str,
    ) -> usize {
        let (mut tb, mut compared) = (Vec::new(), 0);
        for &l in locked {
            for &k in ks {
                for &c in cs {
                    let new = g.gamma_candidates(l, k, c, &mut tb);
                    let old = g.gamma_candidates_reference(l, k, c, &mut tb);
                    assert_eq!(new, old, "{at}: l {l} k {k} c {c}");
                    compared += new.len();
                }
            }
        }
        compared
    }

    /// gamma_candidates (the k nearest faces selected, then sorted) equals the former code
    /// (every face met sorted) for every locked vertex, for k = 1, 4, 16, 40 and several c —
    /// on the hull of a bumpy sphere and of a cube lattice with points inside, before and after
    /// a round of augmentation and removals changed the boundary and the cached bounds.
    #[test]
    fn gamma_candidates_equal_the_former_code() {
        // a bumpy sphere with a smaller one inside (its points off the hull), and the lattice
        let mut two = bumpy_sphere(1500, 8);
        two.extend(
            bumpy_sphere(300, 9)
                .into_iter()
                .map(|q| crate::geom::Point3::new(0.5 * q.x, 0.5 * q.y, 0.5 * q.z)),
        );
        for (set, pts) in [two, cube_lattice(6, 80, 7)].into_iter().enumerate() {
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let mut g = General3::new(&pos, &d.hull, &[], &[]);
            let mut compared = 0;
            for round in 0..2 {
                let extra = g.local_gamma(-0.4, 16);
                let locked: Vec<u32> = (0..pos.len() as u32)
                    .filter(|&v| !g.on_boundary(v))
                    .collect();
                // (the round of removals may free them all)
                assert!(
                    round > 0 || locked.len() > 20,
                    "set {set}: {}",
                    locked.len()
                );
                compared += compare_candidates(
                    &g,
                    &locked,
                    &[1, 4, 16, 40],
                    &[-0.1, -0.5, -1.0],
                    &format!("set {set} round {round}"),
                );
                if g.augment(&extra) > 0 {
                    g.run();
                }
            }
            assert!(compared > 10_000, "set {set}: {compared}");
        }
    }

    /// gamma_candidates against the former code where live triangles do meet the locked
    /// vertices: engines on the live triangles of locked Delaunay constrictions (lazy
    /// construction: cold boundary faces, and the list of edge x–l answering `has`), before
    /// and after a local γ round, every locked vertex, k = 4, 16, c = −0.5, −1.
    #[test]
    fn gamma_candidates_equal_the_former_code_among_live_triangles() {
        let (mut locked_sets, mut compared) = (0, 0);
        for seed in (1..=40u64).chain([1647, 1755]) {
            let Some((d, pos, st)) = super::super::test_sets::locked_clustered_cube(seed) else {
                continue;
            };
            locked_sets += 1;
            let live = super::super::test_sets::live_faces(&d, &st.alive);
            let mut g = General3::new(&pos, &st.triangles, &live, &[]);
            for _round in 0..2 {
                // (fills the nearest-vertex cache of the locked vertices)
                let extra = g.local_gamma(-0.5, 16);
                let locked: Vec<u32> = (0..pos.len() as u32)
                    .filter(|&v| !g.on_boundary(v))
                    .collect();
                compared += compare_candidates(
                    &g,
                    &locked,
                    &[4, 16],
                    &[-0.5, -1.0],
                    &format!("seed {seed}"),
                );
                if g.augment(&extra) > 0 {
                    g.run();
                }
            }
        }
        assert!(
            locked_sets >= 3 && compared > 300,
            "{locked_sets} {compared}"
        );
    }

    /// The engine of [`General3::new`], whose hash maps hold only the initial boundary faces
    /// at warm vertices ([`General3::build_lazy`]), in lockstep with the engine built over
    /// the whole boundary ([`General3::build`], the construction before): through the whole
    /// schedule of `augment_until_done_3d` (runs, local γ rounds c = −0.1 … −1,
    /// augmentations, `insert_left_out`), the same γ candidates found, the same surface,
    /// removals, additions and Delaunay-face flags after every step, and the same answers of
    /// `has`, `id_of`, `is_bface`, `bedge`, `bnext_of` on every triangle and edge the eager
    /// engine knows; the lazy maps agree with the eager ones on every key they hold and hold
    /// every key with a warm end. Sets: clustered cube points on which the Delaunay
    /// constriction locks (regions of depth 0, 1 and `LOCAL_DEPTH`), cube lattices from
    /// their hull with the tetrahedra at three inner vertices live, and a sphere with
    /// clusters just inside whose engine has no live triangle (every vertex cold at the
    /// start; `insert_left_out` does all the work).
    #[test]
    fn lazy_engine_equals_the_eager_one() {
        use rand::{Rng, SeedableRng};
        fn eager<'a>(pos: &'a [P], bnd: &[[u32; 3]], live: &[[u32; 3]]) -> General3<'a> {
            let mut g = General3::blank(pos, bnd, live, &[]);
            g.build(bnd, live, &[]);
            g.track = true;
            g.push_all();
            g
        }
        fn same(a: &General3<'_>, b: &General3<'_>, what: &str) -> usize {
            assert_eq!(a.boundary(), b.boundary(), "{what}");
            assert_eq!(
                a.boundary_with_delaunay_flags(),
                b.boundary_with_delaunay_flags(),
                "{what}"
            );
            let counts = |g: &General3<'_>| (g.iterations, g.added, g.boundary_vertices);
            assert_eq!(counts(a), counts(b), "{what}");
            assert!(a.cold.cold.is_empty());
            let warm = |t: &[u32]| !b.cold.all_cold(t);
            for (i, &t) in a.tris.iter().enumerate() {
                let [x, y, z] = t;
                assert_eq!(a.has(x, y, z), b.has(x, y, z), "{what} {t:?}");
                assert_eq!(a.id_of(t), b.id_of(t), "{what} {t:?}");
                assert_eq!(Some(i as u32), b.id_of(t), "{what} {t:?}");
                for f in [[x, y, z], [x, z, y], [y, z, x], [z, y, x]] {
                    assert_eq!(a.is_bface(f), b.is_bface(f), "{what} {f:?}");
                    assert_eq!(a.bnext_of(f[0], f[1]), b.bnext_of(f[0], f[1]), "{what}");
                    assert_eq!(a.bedge(f[0], f[1]), b.bedge(f[0], f[1]), "{what}");
                }
            }
            // the maps: equal where the lazy one has a key, and it has every warm key
            for (k, v) in &b.eadj {
                assert_eq!(a.eadj.get(k), Some(v), "{what} eadj");
            }
            for (k, v) in &a.eadj {
                if warm(&[(k >> 32) as u32, *k as u32]) {
                    assert_eq!(b.eadj.get(k), Some(v), "{what} eadj {k}");
                }
            }
            for (k, v) in &b.bnext {
                assert_eq!(a.bnext.get(k), Some(v), "{what} bnext");
            }
            for (k, v) in &a.bnext {
                if warm(&[(k >> 32) as u32, *k as u32, *v]) {
                    assert_eq!(b.bnext.get(k), Some(v), "{what} bnext {k}");
                }
            }
            for (k, v) in &b.id {
                assert_eq!(a.id.get(k), Some(v), "{what} id");
            }
            assert!(b.id.len() <= a.id.len() && b.bnext.len() <= a.bnext.len());
            b.cold.cold.iter().filter(|&&c| c).count()
        }
        let lockstep = |pos: &[P], bnd: &[[u32; 3]], live: &[[u32; 3]], what: &str| {
            let mut a = eager(pos, bnd, live);
            let mut b = General3::new(pos, bnd, live, &[]);
            a.trust_initial_as_delaunay();
            b.trust_initial_as_delaunay();
            let cold_at_start = same(&a, &b, what);
            a.run();
            b.run();
            same(&a, &b, what);
            for step in 1..=10 {
                if a.done() {
                    break;
                }
                let c = -(step as f64) / 10.0;
                let (xa, xb) = (a.local_gamma(c, 16), b.local_gamma(c, 16));
                assert_eq!(xa, xb, "{what} c {c}");
                assert_eq!(a.augment(&xa), b.augment(&xb), "{what} c {c}");
                a.run();
                b.run();
                same(&a, &b, &format!("{what} c {c}"));
            }
            if !a.done() {
                assert_eq!(a.insert_left_out(), b.insert_left_out(), "{what}");
                a.run();
                b.run();
            }
            let cold_at_end = same(&a, &b, what);
            assert!(a.iterations > 0, "{what}: nothing removed");
            (cold_at_start, cold_at_end)
        };
        let mut cold_kept = 0;
        let mut locked = 0;
        for seed in [1647u64, 1755, 1, 2, 3, 4] {
            let Some((d, pos, st)) = super::super::test_sets::locked_clustered_cube(seed) else {
                continue;
            };
            locked += 1;
            for depth in [0, 1, LOCAL_DEPTH] {
                let region = near_locked(&d, &st.alive, &st.triangles, depth);
                let live = super::super::test_sets::live_faces(&d, &region);
                let (c0, c1) = lockstep(&pos, &st.triangles, &live, &format!("{seed}/{depth}"));
                assert!(c0 > 0, "seed {seed} depth {depth}: no cold vertex");
                cold_kept += c1;
            }
        }
        assert!(locked >= 2, "{locked}");
        for (m, inner, seed) in [(5, 30, 1u64), (6, 60, 2), (7, 90, 3)] {
            let (d, pos, live) = lattice_from_hull(m, inner, seed);
            let (c0, c1) = lockstep(&pos, &d.hull, &live, &format!("lattice {m}"));
            assert!(c0 > 0, "lattice {m}");
            cold_kept += c1;
        }
        // a sphere with clusters just inside, no live triangle: all cold at the start
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let r = 2e-4 * (3000.0f64 / (4.0 * std::f64::consts::PI)).sqrt();
        let mut dir = || {
            let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
            (v.map(|x| x / n), rng.gen_range(-1e-5..1e-5))
        };
        let mut pts: Vec<crate::geom::Point3> = Vec::new();
        for i in 0..3030 {
            let (u, e) = dir();
            let s = if i < 3000 { r } else { r - 3e-5 + e };
            pts.push(crate::geom::Point3::new(s * u[0], s * u[1], s * u[2]));
        }
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let (c0, c1) = lockstep(&pos, &d.hull, &[], "sphere");
        assert_eq!(c0, pos.len(), "sphere: every vertex cold at the start");
        cold_kept += c1;
        assert!(cold_kept > 100, "{cold_kept} vertices never warmed");
    }
}
