#!/usr/bin/env python3
"""Times CGAL's Delaunay_triangulation_3 (Python bindings, package `cgal`) on the points written by
`cargo run --release -p morpho --example bench_delaunay3d -- N --write points.f64`, single thread.

The points are inserted as one list (CGAL sorts them spatially itself); the time excludes the
construction of the Point_3 list. usage: python3 bench/delaunay3d_cgal.py points.f64
"""
import sys
import time

import numpy as np

try:
    from CGAL.CGAL_Kernel import Point_3
    from CGAL.CGAL_Triangulation_3 import Delaunay_triangulation_3
except ImportError:
    print("CGAL bindings are not installed: pip install cgal")
    sys.exit(1)


def main():
    pts = np.fromfile(sys.argv[1], dtype="<f8").reshape(-1, 3)
    plist = [Point_3(float(x), float(y), float(z)) for x, y, z in pts]
    t = time.perf_counter()
    c = time.process_time()
    dt = Delaunay_triangulation_3()
    dt.insert(plist)
    secs = time.perf_counter() - t
    cpu = time.process_time() - c
    print(f"cgal: points {len(pts)}  tets {dt.number_of_finite_cells()}  wall {secs:.3f} s  "
          f"{len(pts) / secs:.0f} points/s  cpu {cpu:.2f} s")


if __name__ == "__main__":
    main()
