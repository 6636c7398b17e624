//! The mutable triangulation of the reduction (Hamann 1991, §5.2, Alg. 5.1 input: "table of
//! triangles including neighbourhood information"): flat arrays of triangles with half-edge
//! opposites, a free list of slots, and one outgoing half-edge per vertex.
//!
//! Half-edge `h = 3t + i` runs from `tri[t][i]` to `tri[t][(i+1)%3]`; `opp[h]` is the reverse
//! half-edge in the neighbour across it, or [`NONE`] on the mesh boundary. Built by
//! [`State::build`], which refuses non-manifold edges and vertices, inconsistent orientation and
//! degenerate triangles (typed [`ReduceError`]s). O(n log n) to build, O(valence) per fan.

use super::error::ReduceError;
use crate::geom::intersect::degenerate_triangle;
use crate::util::NONE;

/// The triangulation being reduced.
pub(crate) struct State {
    pub pos: Vec<[f64; 3]>,
    pub tri: Vec<[u32; 3]>,
    pub opp: Vec<u32>,
    pub alive: Vec<bool>,
    /// One outgoing half-edge of each live vertex ([`NONE`] for dead or unused vertices).
    pub vhe: Vec<u32>,
    free: Vec<u32>,
    pub live_tris: usize,
}

#[inline]
pub(crate) fn next(h: u32) -> u32 {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}
#[inline]
pub(crate) fn prev(h: u32) -> u32 {
    if h % 3 == 0 {
        h + 2
    } else {
        h - 1
    }
}

impl State {
    /// Builds the half-edge structure of `tris` over `pos`, refusing what the method cannot
    /// take.
    pub fn build(pos: Vec<[f64; 3]>, tris: &[[u32; 3]]) -> Result<State, ReduceError> {
        if tris.is_empty() {
            return Err(ReduceError::Empty);
        }
        let nt = tris.len();
        for (t, &[a, b, c]) in tris.iter().enumerate() {
            let p = |v: u32| pos[v as usize];
            if a == b || b == c || a == c || degenerate_triangle(p(a), p(b), p(c)) {
                return Err(ReduceError::DegenerateTriangle { triangle: t });
            }
        }
        // directed edges sorted by (min, max, half-edge)
        let mut e: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * nt);
        for (t, tr) in tris.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (tr[i], tr[(i + 1) % 3]);
                e.push((a.min(b), a.max(b), (3 * t + i) as u32));
            }
        }
        e.sort_unstable();
        let mut opp = vec![NONE; 3 * nt];
        let mut i = 0;
        while i < e.len() {
            let mut j = i + 1;
            while j < e.len() && e[j].0 == e[i].0 && e[j].1 == e[i].1 {
                j += 1;
            }
            match j - i {
                1 => {}
                2 => {
                    let (h, g) = (e[i].2, e[i + 1].2);
                    let from = |h: u32| tris[h as usize / 3][h as usize % 3];
                    if from(h) == from(g) {
                        return Err(ReduceError::InconsistentOrientation {
                            a: e[i].0,
                            b: e[i].1,
                        });
                    }
                    opp[h as usize] = g;
                    opp[g as usize] = h;
                }
                _ => {
                    return Err(ReduceError::NonManifoldEdge {
                        a: e[i].0,
                        b: e[i].1,
                    })
                }
            }
            i = j;
        }
        let mut s = State {
            vhe: vec![NONE; pos.len()],
            pos,
            tri: tris.to_vec(),
            opp,
            alive: vec![true; nt],
            free: Vec::new(),
            live_tris: nt,
        };
        let mut count = vec![0u32; s.pos.len()];
        for (t, tr) in tris.iter().enumerate() {
            for i in 0..3 {
                count[tr[i] as usize] += 1;
                s.vhe[tr[i] as usize] = (3 * t + i) as u32;
            }
        }
        // one fan per vertex: the fan walk must reach every triangle of the vertex
        let mut fan = Vec::new();
        for v in 0..s.pos.len() {
            if s.vhe[v] == NONE {
                continue;
            }
            s.fan(v as u32, &mut fan);
            if fan.len() != count[v] as usize {
                return Err(ReduceError::NonManifoldVertex { vertex: v as u32 });
            }
        }
        Ok(s)
    }

    #[inline]
    pub fn from(&self, h: u32) -> u32 {
        self.tri[h as usize / 3][h as usize % 3]
    }
    #[inline]
    pub fn to(&self, h: u32) -> u32 {
        self.from(next(h))
    }
    #[inline]
    pub fn p(&self, v: u32) -> [f64; 3] {
        self.pos[v as usize]
    }

    /// The outgoing half-edges of `v`, one per triangle, counter-clockwise; for a boundary
    /// vertex starting at the clockwise-most one. Returns whether `v` is on the boundary.
    pub fn fan(&self, v: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        let h0 = self.vhe[v as usize];
        if h0 == NONE {
            return false;
        }
        // counter-clockwise from h0: all the way round for an interior vertex (the answer);
        // a boundary ends the walk, and the fan is collected again from the clockwise-most
        let mut h = h0;
        loop {
            out.push(h);
            let o = self.opp[prev(h) as usize];
            if o == h0 {
                return false;
            }
            if o == NONE || out.len() > self.tri.len() {
                break;
            }
            h = o;
        }
        out.clear();
        // rotate clockwise to the boundary (or all the way round)
        let mut h = h0;
        let mut boundary = false;
        let mut guard = 0usize;
        loop {
            let o = self.opp[h as usize];
            if o == NONE {
                boundary = true;
                break;
            }
            let g = next(o);
            if g == h0 {
                break;
            }
            h = g;
            guard += 1;
            if guard > self.tri.len() {
                break;
            }
        }
        let start = if boundary { h } else { h0 };
        let mut h = start;
        loop {
            out.push(h);
            let o = self.opp[prev(h) as usize];
            if o == NONE || o == start || out.len() > self.tri.len() {
                break;
            }
            h = o;
        }
        boundary
    }

    /// Is `a–b` an edge of a live triangle?
    pub fn has_edge(&self, a: u32, b: u32, scratch: &mut Vec<u32>) -> bool {
        self.fan(a, scratch);
        scratch
            .iter()
            .any(|&h| self.to(h) == b || self.from(prev(h)) == b)
    }

    /// Stores a new triangle (reusing a freed slot) and returns its index.
    pub fn add_triangle(&mut self, t: [u32; 3]) -> u32 {
        self.live_tris += 1;
        if let Some(s) = self.free.pop() {
            self.tri[s as usize] = t;
            self.alive[s as usize] = true;
            for i in 0..3 {
                self.opp[3 * s as usize + i] = NONE;
            }
            s
        } else {
            self.tri.push(t);
            self.alive.push(true);
            self.opp.extend([NONE; 3]);
            (self.tri.len() - 1) as u32
        }
    }

    /// Frees a triangle's slot (its opposites are left to the caller).
    pub fn kill_triangle(&mut self, t: u32) {
        debug_assert!(self.alive[t as usize]);
        self.alive[t as usize] = false;
        self.live_tris -= 1;
        self.free.push(t);
    }

    /// The live triangles, compacted, with the map old vertex → new vertex index.
    pub fn compact(&self) -> (Vec<[f64; 3]>, Vec<[u32; 3]>, Vec<u32>) {
        let mut map = vec![NONE; self.pos.len()];
        let mut pos = Vec::new();
        let mut tris = Vec::with_capacity(self.live_tris);
        for (t, tr) in self.tri.iter().enumerate() {
            if !self.alive[t] {
                continue;
            }
            tris.push(tr.map(|v| {
                if map[v as usize] == NONE {
                    map[v as usize] = pos.len() as u32;
                    pos.push(self.pos[v as usize]);
                }
                map[v as usize]
            }));
        }
        (pos, tris, map)
    }
}
