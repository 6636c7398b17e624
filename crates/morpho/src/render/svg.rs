//! SVG pictures of 2D points, polylines, polygons, graphs and triangulations. TODO(helper).
