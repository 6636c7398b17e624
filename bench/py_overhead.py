#!/usr/bin/env python3
"""Issue 24 numbers: the Python call overhead against the CLI's ``timings.compute`` (256³
contour surface; 1M-point 2D Delaunay), and ``morpho.isosurface`` against
``skimage.measure.marching_cubes`` with normals on the same array in the same process.

    python bench/py_overhead.py [--morpho target/release/morpho] [--rounds 3]

Run with the venv that has the extension (``target/pyenv``). Minimum of the rounds; the CLI's
figure is its own ``compute`` timing (reading and writing excluded), the Python figure is the
whole call (argument conversion, GIL release, result arrays).
"""

import argparse
import json
import os
import subprocess
import tempfile
import time

import numpy as np

import morpho


def best(f, rounds):
    t = []
    for _ in range(rounds):
        s = time.perf_counter()
        f()
        t.append(time.perf_counter() - s)
    return min(t)


def cli_compute(cmd, rep, rounds):
    t = []
    for _ in range(rounds):
        subprocess.run(cmd + ["--report", rep], check=True, capture_output=True)
        t.append(json.load(open(rep))["timings"]["compute"])
    return min(t)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--morpho", default="target/release/morpho")
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}")
    d = tempfile.mkdtemp()
    rep = os.path.join(d, "r.json")
    # 256³ gyroid, stored x fastest; the Python array is indexed [x, y, z] (F order) so both
    # see the same grid
    n = 256
    t = 2 * np.pi * 4 * np.arange(n) / n
    x, y, z = np.meshgrid(t, t, t, indexing="ij")
    vol = (np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)).astype(np.float32)
    vol.ravel(order="F").tofile(os.path.join(d, "g.raw"))
    json.dump({"data": "g.raw", "dims": [n, n, n], "dtype": "f32"}, open(os.path.join(d, "g.json"), "w"))
    volc = np.ascontiguousarray(vol)
    for normals in ["zucker", "central"]:
        cli = cli_compute([a.morpho, "isosurface", os.path.join(d, "g.json"), "--level", "0.1",
                           "--normals", normals, "-o", os.path.join(d, "o.ply")], rep, a.rounds)
        py = best(lambda: morpho.isosurface(volc, 0.1, normals=normals), a.rounds)
        print(f"isosurface 256³ {normals:8s} CLI compute {cli:.3f} s  Python call {py:.3f} s  "
              f"overhead {100 * (py - cli) / cli:+.1f} %")
    from skimage.measure import marching_cubes
    sk = best(lambda: marching_cubes(volc, 0.1), a.rounds)
    mo = best(lambda: morpho.isosurface(volc, 0.1, normals="central"), a.rounds)
    print(f"same array, with normals: skimage marching_cubes {sk:.3f} s  morpho.isosurface {mo:.3f} s"
          f"  ({sk / mo:.2f}× faster)")
    rng = np.random.default_rng(1)
    pts = rng.random((1_000_000, 2))
    np.savetxt(os.path.join(d, "p.csv"), pts, delimiter=",", header="x,y", comments="")
    cli = cli_compute([a.morpho, "triangulate", os.path.join(d, "p.csv"), "-o",
                       os.path.join(d, "t.json")], rep, a.rounds)
    py = best(lambda: morpho.triangulate(pts), a.rounds)
    print(f"triangulate 1M 2D  CLI compute {cli:.3f} s  Python call {py:.3f} s  "
          f"overhead {100 * (py - cli) / cli:+.1f} %")


if __name__ == "__main__":
    main()
