//! Polygons, polylines, triangle meshes, tetrahedral meshes, and their topology.
//!
//! Storage is flat (`Vec<[u32; 3]>` for triangles) as in meshoptimizer; typed ids
//! ([`VertexId`], [`TriId`]) are used where an index of one kind could be mistaken for another.

mod error;
// Generated test surfaces (`generate::torus(…)`, `generate::cube()`, …): a namespace of its own
// so that the shape names do not crowd the mesh types.
pub mod generate;
pub(crate) mod topology;

pub use error::MeshError;
mod normals;
pub(crate) use normals::{vertex_normal_from, weighted_crosses};
pub use normals::{vertex_normals, NormalWeighting};
pub use topology::{analyze_topology, orient_consistently, PartInfo, Topology};
// The polygon and mesh validators (a namespace of its own: `mesh::validity::check_polygon`, …).
pub mod validity;

use crate::geom::{Aabb3, Point2, Point3, Vector3};

macro_rules! id_type {
    ($(#[$m:meta])* $name:ident) => {
        $(#[$m])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name(pub u32);
        impl $name {
            /// The index as `usize`.
            #[inline]
            pub fn idx(self) -> usize {
                self.0 as usize
            }
        }
        impl From<$name> for usize {
            #[inline]
            fn from(v: $name) -> usize {
                v.0 as usize
            }
        }
    };
}

id_type!(
    /// Index of a vertex in a mesh's position array.
    VertexId
);
id_type!(
    /// Index of a triangle in a [`TriMesh`].
    TriId
);
id_type!(
    /// Index of a tetrahedron in a [`TetMesh`].
    TetId
);

/// Scalar type of a property as stored in a file (kept so a PLY round trip is faithful).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScalarKind {
    /// Signed 8-bit integer.
    I8,
    /// Unsigned 8-bit integer.
    U8,
    /// Signed 16-bit integer.
    I16,
    /// Unsigned 16-bit integer.
    U16,
    /// Signed 32-bit integer.
    I32,
    /// Unsigned 32-bit integer.
    U32,
    /// 32-bit float.
    F32,
    /// 64-bit float.
    F64,
}

/// A named per-vertex or per-face scalar column (PLY extra properties, curvatures, part labels…).
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// Property name as in the file (`k1`, `part`, `quality`, …).
    pub name: String,
    /// Type the values had (or will have) in the file.
    pub kind: ScalarKind,
    /// One value per vertex or per face.
    pub values: Vec<f64>,
}

/// A closed polygon with optional holes. Ring 0 is the outer ring; rings are not closed
/// explicitly (the last vertex connects back to the first).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Polygon {
    /// The rings: ring 0 is the outer ring, the others are holes.
    pub rings: Vec<Vec<Point2>>,
}

/// An open or closed sequence of points in the plane.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Polyline {
    /// The vertices in order.
    pub points: Vec<Point2>,
    /// If true, the last point connects back to the first.
    pub closed: bool,
}

/// What a 2D vector file (CSV polygon, GeoJSON) holds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Shapes2 {
    /// Closed polygons, with holes.
    pub polygons: Vec<Polygon>,
    /// Open or closed polylines.
    pub polylines: Vec<Polyline>,
}

/// A triangle mesh: positions and counter-clockwise (outward, by convention) triangles.
///
/// Invariant established by [`TriMesh::validate`]: every index is `< positions.len()`, every
/// coordinate is finite, every property column has the right length.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<Point3>,
    /// Triangles as indices into `positions`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Optional per-vertex normals (same length as `positions`).
    pub normals: Option<Vec<Vector3>>,
    /// Extra per-vertex scalar properties.
    pub vertex_props: Vec<Property>,
    /// Extra per-face scalar properties.
    pub face_props: Vec<Property>,
}

impl TriMesh {
    /// A mesh from positions and triangles, without properties.
    pub fn new(positions: Vec<Point3>, triangles: Vec<[u32; 3]>) -> Self {
        TriMesh {
            positions,
            triangles,
            ..Default::default()
        }
    }
    /// Number of vertices (including unreferenced ones).
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }
    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }
    /// Bounding box of all positions.
    pub fn bbox(&self) -> Aabb3 {
        crate::geom::bbox3(&self.positions)
    }
    /// Corner positions of triangle `t`.
    pub fn triangle_points(&self, t: TriId) -> [Point3; 3] {
        let [a, b, c] = self.triangles[t.idx()];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
    /// Checks the invariants: indices in range, finite coordinates, property lengths.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        if n > u32::MAX as usize {
            return Err(MeshError::TooManyVertices { vertices: n });
        }
        for (i, p) in self.positions.iter().enumerate() {
            if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
                return Err(MeshError::NonFiniteVertex { vertex: i });
            }
        }
        for (t, tri) in self.triangles.iter().enumerate() {
            for &v in tri {
                if v as usize >= n {
                    return Err(MeshError::VertexOutOfRange {
                        triangle: t,
                        vertex: v,
                        vertices: n,
                    });
                }
            }
        }
        if let Some(nr) = &self.normals {
            if nr.len() != n {
                return Err(MeshError::NormalCount {
                    normals: nr.len(),
                    vertices: n,
                });
            }
        }
        for p in &self.vertex_props {
            if p.values.len() != n {
                return Err(MeshError::PropertyLength {
                    per: "vertex",
                    name: p.name.clone(),
                });
            }
        }
        for p in &self.face_props {
            if p.values.len() != self.triangles.len() {
                return Err(MeshError::PropertyLength {
                    per: "face",
                    name: p.name.clone(),
                });
            }
        }
        Ok(())
    }
    /// The per-vertex property called `name`, if any.
    pub fn vertex_prop(&self, name: &str) -> Option<&Property> {
        self.vertex_props.iter().find(|p| p.name == name)
    }
    /// The per-face property called `name`, if any.
    pub fn face_prop(&self, name: &str) -> Option<&Property> {
        self.face_props.iter().find(|p| p.name == name)
    }
    /// Signed volume enclosed by the triangles (positive for a closed, outward-oriented mesh).
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| {
                let (a, b, c) = (
                    self.positions[a as usize].coords,
                    self.positions[b as usize].coords,
                    self.positions[c as usize].coords,
                );
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum()
    }
    /// Total surface area.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| {
                let (a, b, c) = (
                    self.positions[a as usize],
                    self.positions[b as usize],
                    self.positions[c as usize],
                );
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .sum()
    }
}

/// A tetrahedral mesh. Tetrahedra are positively oriented: `orient3d(a, b, c, d) > 0` in
/// Shewchuk's convention.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TetMesh {
    /// Vertex positions.
    pub positions: Vec<Point3>,
    /// Tetrahedra as indices into `positions`.
    pub tets: Vec<[u32; 4]>,
}

/// A set of points in 2 or 3 dimensions with optional named value columns (flat storage).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointSet {
    /// 2 or 3.
    pub dim: usize,
    /// `len() * dim` coordinates, point after point.
    pub coords: Vec<f64>,
    /// Extra columns (e.g. `value`, `zinc`), each with one value per point.
    pub columns: Vec<Column>,
}

/// A named column of values, one per point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Column {
    /// Column name (the CSV header).
    pub name: String,
    /// One value per point.
    pub values: Vec<f64>,
}

impl PointSet {
    /// Points from 2D positions.
    ///
    /// ```
    /// use morpho::geom::Point2;
    /// use morpho::mesh::{Column, PointSet};
    /// let mut ps = PointSet::from_points2(&[Point2::new(0.0, 1.0), Point2::new(2.0, 3.0)]);
    /// assert_eq!((ps.dim, ps.len()), (2, 2));
    /// assert_eq!(ps.point(1), &[2.0, 3.0]);
    /// ps.columns.push(Column { name: "v".into(), values: vec![1.0] });
    /// assert_eq!(ps.validate().unwrap_err().to_string(), "column v has the wrong length");
    /// ```
    pub fn from_points2(p: &[Point2]) -> Self {
        PointSet {
            dim: 2,
            coords: p.iter().flat_map(|p| [p.x, p.y]).collect(),
            columns: vec![],
        }
    }
    /// Points from 3D positions.
    pub fn from_points3(p: &[Point3]) -> Self {
        PointSet {
            dim: 3,
            coords: p.iter().flat_map(|p| [p.x, p.y, p.z]).collect(),
            columns: vec![],
        }
    }
    /// Number of points.
    pub fn len(&self) -> usize {
        self.coords.len().checked_div(self.dim).unwrap_or(0)
    }
    /// True when there is no point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Coordinates of point `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.coords[i * self.dim..(i + 1) * self.dim]
    }
    /// The points as 2D points (the first two coordinates).
    pub fn to_points2(&self) -> Vec<Point2> {
        (0..self.len())
            .map(|i| {
                let p = self.point(i);
                Point2::new(p[0], p[1])
            })
            .collect()
    }
    /// The points as 3D points (z = 0 for 2D sets).
    pub fn to_points3(&self) -> Vec<Point3> {
        (0..self.len())
            .map(|i| {
                let p = self.point(i);
                Point3::new(p[0], p[1], if self.dim > 2 { p[2] } else { 0.0 })
            })
            .collect()
    }
    /// The column called `name`.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|c| c.name == name)
    }
    /// Checks dim ∈ {2,3}, finite coordinates and column lengths.
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.dim != 2 && self.dim != 3 {
            return Err(MeshError::Dimension { dim: self.dim });
        }
        if self.coords.len() % self.dim != 0 {
            return Err(MeshError::CoordinateCount {
                coords: self.coords.len(),
                dim: self.dim,
            });
        }
        if let Some(i) = self.coords.iter().position(|c| !c.is_finite()) {
            return Err(MeshError::NonFinitePoint {
                point: i / self.dim,
            });
        }
        for c in &self.columns {
            if c.values.len() != self.len() {
                return Err(MeshError::ColumnLength {
                    name: c.name.clone(),
                });
            }
        }
        Ok(())
    }
}
