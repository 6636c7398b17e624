#!/usr/bin/env python3
"""Times scipy.spatial.Delaunay (Qhull) on the points written by
`cargo run --release -p morpho --example bench_delaunay3d -- N --write points.f64 [--tets tets.u32]`
and, when the tetrahedra file is given, checks that morpho's tetrahedron set equals Qhull's
(true for random points, which are in general position with probability 1).

usage: python3 bench/delaunay3d_qhull.py points.f64 [tets.u32] [morpho_seconds]
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
    c = time.process_time()
    d = Delaunay(pts)
    secs = time.perf_counter() - t
    cpu = time.process_time() - c
    print(f"qhull: points {len(pts)}  tets {len(d.simplices)}  wall {secs:.3f} s  "
          f"{len(pts) / secs:.0f} points/s  cpu {cpu:.2f} s")
    rest = sys.argv[2:]
    if rest and not rest[0].replace(".", "", 1).isdigit():
        ours = np.fromfile(rest[0], dtype="<u4").reshape(-1, 4)
        a = {tuple(sorted(t)) for t in ours.tolist()}
        b = {tuple(sorted(t)) for t in d.simplices.tolist()}
        print(f"tetrahedron sets equal: {a == b}  (morpho {len(a)}, qhull {len(b)}, "
              f"only morpho {len(a - b)}, only qhull {len(b - a)})")
        rest = rest[1:]
    if rest:
        print(f"ratio morpho/qhull (wall) = {float(rest[0]) / secs:.3f}")


if __name__ == "__main__":
    main()
