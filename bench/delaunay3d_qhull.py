#!/usr/bin/env python3
"""Times scipy.spatial.Delaunay (Qhull) on the points written by
`cargo run --release -p morpho --example bench_delaunay3d -- N --write points.f64`.

usage: python3 bench/delaunay3d_qhull.py points.f64 [morpho_seconds]
Prints Qhull's time, points/second, and the ratio morpho/Qhull when morpho's time is given.
"""
import sys
import time

import numpy as np

try:
    from scipy.spatial import Delaunay
except ImportError:
    print("scipy is not installed: pip install scipy")
    sys.exit(1)


def main():
    pts = np.fromfile(sys.argv[1], dtype="<f8").reshape(-1, 3)
    t = time.perf_counter()
    d = Delaunay(pts)
    secs = time.perf_counter() - t
    print(f"qhull: points {len(pts)}  tets {len(d.simplices)}  time {secs:.3f} s  "
          f"{len(pts) / secs:.0f} points/s")
    if len(sys.argv) > 2:
        ours = float(sys.argv[2])
        print(f"ratio morpho/qhull = {ours / secs:.3f}")


if __name__ == "__main__":
    main()
