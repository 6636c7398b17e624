//! Delaunay triangulations in 2D, 3D and d dimensions, convex hulls and Voronoi duals
//! (Veltkamp 1992 §2.2.8–2.2.9; Dorgerloh et al. §2). TODO(helper): issue 3.
