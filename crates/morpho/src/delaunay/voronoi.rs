//! Voronoi diagram of a planar point set as the dual of its Delaunay triangulation
//! (Veltkamp 1992, §2.2.9: each j-simplex of the k-D Delaunay triangulation corresponds to a
//! (k−j)-face of the Voronoi diagram — in 2D triangle ↔ Voronoi vertex, Delaunay edge ↔ Voronoi
//! edge, site ↔ cell; Dorgerloh et al. §2, Definition 1: the cell V(p) is the intersection of the
//! half-planes H(p, q) bounded by the bisectors).
//!
//! [`voronoi`] returns one Voronoi vertex per Delaunay triangle (its circumcentre), one Voronoi
//! edge per Delaunay edge: a segment between the circumcentres of the two triangles of an
//! interior edge, a ray from the circumcentre of the hull triangle in the outward normal
//! direction of a hull edge, or — when all points are collinear — the full bisector line of two
//! consecutive points. [`Voronoi2::cell`] lists the cell of a vertex in order.
//!
//! Complexity O(n) after the triangulation. Circumcentres are floating-point constructions; with
//! cocircular input several Voronoi vertices coincide (zero-length segments), as the dual of the
//! perturbed triangulation. For collinear input there are no Voronoi vertices, the edges are
//! [`VoronoiEdge::Line`]s and [`Voronoi2::cell`] returns an empty vertex list.

use super::d2::Delaunay2;
use crate::geom::{Point2, Vector2};
use crate::util::NONE;

/// One edge of the Voronoi diagram, dual to the Delaunay edge `dual = [a, b]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VoronoiEdge {
    /// The segment between Voronoi vertices `vertices[0]` (the triangle left of `a → b`) and
    /// `vertices[1]` (the triangle right of it).
    Segment {
        /// The dual Delaunay edge `[a, b]` (vertex indices).
        dual: [u32; 2],
        /// The two Voronoi vertices (triangle indices).
        vertices: [u32; 2],
    },
    /// The ray from Voronoi vertex `from` in direction `direction` (outward normal of the hull
    /// edge `a → b`, which runs counter-clockwise around the hull).
    Ray {
        /// The dual hull edge `[a, b]` (vertex indices).
        dual: [u32; 2],
        /// The Voronoi vertex the ray starts at (a triangle index).
        from: u32,
        /// Its direction (not normalised).
        direction: Vector2,
    },
    /// Collinear input only: the bisector line of `a` and `b` through `point` with `direction`.
    Line {
        /// The dual Delaunay edge `[a, b]` (consecutive points of the line).
        dual: [u32; 2],
        /// The midpoint of `a` and `b`.
        point: Point2,
        /// The line's direction (not normalised).
        direction: Vector2,
    },
}

impl VoronoiEdge {
    /// The dual Delaunay edge.
    pub fn dual(&self) -> [u32; 2] {
        match *self {
            VoronoiEdge::Segment { dual, .. }
            | VoronoiEdge::Ray { dual, .. }
            | VoronoiEdge::Line { dual, .. } => dual,
        }
    }
}

/// The Voronoi diagram (dual of a [`Delaunay2`]).
#[derive(Debug, Clone)]
pub struct Voronoi2 {
    /// Circumcentres, one per Delaunay triangle (same index).
    pub vertices: Vec<Point2>,
    /// One edge per Delaunay edge.
    pub edges: Vec<VoronoiEdge>,
}

/// The Voronoi cell of one site.
#[derive(Debug, Clone, PartialEq)]
pub struct VoronoiCell {
    /// Voronoi vertices (triangle indices) around the site, counter-clockwise.
    pub vertices: Vec<u32>,
    /// For a site on the convex hull the cell is unbounded: the ray leaving `vertices[0]`
    /// (dual to the hull edge leaving the site) and the ray leaving the last vertex (dual to the
    /// hull edge entering the site), both as outward directions. `None` for a bounded cell.
    pub rays: Option<[Vector2; 2]>,
}

/// Outward normal of the counter-clockwise hull edge a → b.
fn outward(d: &Delaunay2, a: u32, b: u32) -> Vector2 {
    let e = d.points[b as usize] - d.points[a as usize];
    Vector2::new(e.y, -e.x)
}

/// Builds the Voronoi diagram dual to `d` (facade name
/// [`voronoi_2d`](crate::delaunay::voronoi_2d)): one vertex per triangle (its circumcentre,
/// same index), one edge per Delaunay edge (segment, ray on the hull, or a bisector line for
/// collinear input). O(n) after the triangulation; circumcentres are floating-point
/// constructions.
///
/// ```rust
/// use morpho::delaunay::{triangulate_2d, voronoi_2d, VoronoiEdge};
/// use morpho::geom::Point2;
/// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.], [1., 1.]].map(|[x, y]| Point2::new(x, y));
/// let d = triangulate_2d(&p).unwrap();
/// let v = voronoi_2d(&d);
/// assert_eq!(v.vertices.len(), d.triangles.len());
/// assert_eq!(v.edges.len(), d.edges().len());
/// // four hull edges, four rays
/// let rays = v.edges.iter().filter(|e| matches!(e, VoronoiEdge::Ray { .. })).count();
/// assert_eq!(rays, 4);
/// ```
pub fn voronoi(d: &Delaunay2) -> Voronoi2 {
    let vertices: Vec<Point2> = (0..d.triangles.len() as u32)
        .map(|t| d.circumcenter(t))
        .collect();
    let mut edges = Vec::new();
    if d.collinear {
        for w in d.hull.windows(2) {
            let (p, q) = (d.points[w[0] as usize], d.points[w[1] as usize]);
            let e = q - p;
            edges.push(VoronoiEdge::Line {
                dual: [w[0], w[1]],
                point: p + e * 0.5,
                direction: Vector2::new(-e.y, e.x),
            });
        }
        return Voronoi2 { vertices, edges };
    }
    for (t, tri) in d.triangles.iter().enumerate() {
        for i in 0..3 {
            let nb = d.neighbors[t][i];
            let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            if nb == NONE {
                edges.push(VoronoiEdge::Ray {
                    dual: [a, b],
                    from: t as u32,
                    direction: outward(d, a, b),
                });
            } else if nb as usize > t {
                edges.push(VoronoiEdge::Segment {
                    dual: [a, b],
                    vertices: [t as u32, nb],
                });
            }
        }
    }
    Voronoi2 { vertices, edges }
}

impl Voronoi2 {
    /// The cell of vertex `v` of `d` (the triangulation this diagram was built from).
    /// O(degree of `v`).
    ///
    /// ```rust
    /// use morpho::delaunay::{triangulate_2d, voronoi_2d};
    /// use morpho::geom::Point2;
    /// // a square with its centre: the centre's cell is bounded (4 Voronoi vertices),
    /// // a corner's cell is unbounded (two rays)
    /// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.], [1., 1.]].map(|[x, y]| Point2::new(x, y));
    /// let d = triangulate_2d(&p).unwrap();
    /// let v = voronoi_2d(&d);
    /// let centre = v.cell(&d, d.vertex_of_input[4]);
    /// assert_eq!((centre.vertices.len(), centre.rays), (4, None));
    /// assert!(v.cell(&d, d.vertex_of_input[0]).rays.is_some());
    /// ```
    pub fn cell(&self, d: &Delaunay2, v: u32) -> VoronoiCell {
        let vertices: Vec<u32> = d.triangles_around(v).collect();
        let first = match vertices.first() {
            Some(&t) => t,
            None => {
                return VoronoiCell {
                    vertices,
                    rays: None,
                }
            }
        };
        let last = vertices[vertices.len() - 1];
        let tri = d.triangles[first as usize];
        let i = tri.iter().position(|&w| w == v).unwrap_or(0);
        // open fan: the first triangle has its outgoing hull edge v -> tri[i+1] on the boundary
        if d.neighbors[first as usize][(i + 2) % 3] == NONE {
            let out_next = tri[(i + 1) % 3];
            let lt = d.triangles[last as usize];
            let j = lt.iter().position(|&w| w == v).unwrap_or(0);
            let in_prev = lt[(j + 2) % 3];
            return VoronoiCell {
                vertices,
                rays: Some([outward(d, v, out_next), outward(d, in_prev, v)]),
            };
        }
        VoronoiCell {
            vertices,
            rays: None,
        }
    }

    /// The edges as finite segments, in the order of [`Self::edges`]: a segment as it is, a
    /// ray cut at distance `reach` from its Voronoi vertex, a line (collinear input) cut at
    /// `reach` on both sides of its point. Choosing `reach` (for a picture: the diagonal of the
    /// drawn box, so that every cut lies outside it) is the caller's business.
    ///
    /// ```
    /// use morpho::delaunay::{triangulate_2d, voronoi_2d};
    /// use morpho::geom::Point2;
    /// let p = [Point2::new(0.0, 0.0), Point2::new(4.0, 0.0), Point2::new(0.0, 4.0)];
    /// let v = voronoi_2d(&triangulate_2d(&p).unwrap());
    /// let segs = v.segments(10.0);
    /// assert_eq!(segs.len(), 3); // three rays from the circumcentre (2, 2)
    /// assert!(segs.iter().all(|(a, b)| *a == Point2::new(2.0, 2.0) && ((b - a).norm() - 10.0).abs() < 1e-12));
    /// ```
    pub fn segments(&self, reach: f64) -> Vec<(Point2, Point2)> {
        self.edges
            .iter()
            .map(|e| match *e {
                VoronoiEdge::Segment { vertices, .. } => (
                    self.vertices[vertices[0] as usize],
                    self.vertices[vertices[1] as usize],
                ),
                VoronoiEdge::Ray {
                    from, direction, ..
                } => {
                    let p = self.vertices[from as usize];
                    (p, p + direction.normalize() * reach)
                }
                VoronoiEdge::Line {
                    point, direction, ..
                } => {
                    let u = direction.normalize() * reach;
                    (point - u, point + u)
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::delaunay::d2::triangulate;

    #[test]
    fn square_with_centre() {
        let p: Vec<Point2> = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 1.1]]
            .iter()
            .map(|q| Point2::new(q[0], q[1]))
            .collect();
        let d = triangulate(&p).unwrap();
        let v = voronoi(&d);
        assert_eq!(v.vertices.len(), 4);
        let rays = v
            .edges
            .iter()
            .filter(|e| matches!(e, VoronoiEdge::Ray { .. }))
            .count();
        assert_eq!(rays, 4);
        assert_eq!(v.edges.len(), 8);
        let centre = d.vertex_of_input[4];
        let c = v.cell(&d, centre);
        assert_eq!(c.vertices.len(), 4);
        assert!(c.rays.is_none());
        let corner = d.vertex_of_input[0];
        let c0 = v.cell(&d, corner);
        assert!(c0.rays.is_some());
        // the outward rays of corner (0,0) point down and left
        let [r0, r1] = c0.rays.unwrap();
        assert!(r0.y < 0.0 || r0.x < 0.0);
        assert!(r1.y < 0.0 || r1.x < 0.0);
    }
}
