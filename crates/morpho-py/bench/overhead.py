"""Python call overhead and skimage comparison (issue 24 numbers).

    target/pyenv/bin/python crates/morpho-py/bench/overhead.py target/release/morpho [REPS]

1. 256³ gyroid contour surface (level 0, decider, Zucker–Hummel normals, topology): the
   Python call `morpho.isosurface(..., return_report=True)` (the same work as the command) against
   the command's `timings.compute`, for a Fortran-ordered array (as `read` returns) and a
   C-ordered one.
2. 1M random 2D points: `morpho.triangulate` against `morpho triangulate`'s `timings.compute`.
3. `morpho.isosurface` with normals against `skimage.measure.marching_cubes` (Lewiner, normals
   always computed) on the same C-ordered array in the same process.

Prints one JSON line per measurement (wall seconds, minimum of REPS) and the load averages.
"""

import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import morpho


def best(f, reps):
    t = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def cli_compute(cli, args, reps):
    out = []
    with tempfile.TemporaryDirectory() as d:
        for _ in range(reps):
            rep = os.path.join(d, "r.json")
            subprocess.run([cli, *args, "--report", rep], check=True, capture_output=True)
            out.append(json.load(open(rep))["timings"]["compute"])
    return min(out)


def main():
    cli = sys.argv[1]
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    print(json.dumps({"load_before": os.getloadavg()}))
    n = 256
    t = np.linspace(0, 4 * np.pi, n)
    x, y, z = np.meshgrid(t, t, t, indexing="ij")
    g = (np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)).astype(np.float32)
    del x, y, z
    gf = np.asfortranarray(g)
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "g.nrrd")
        morpho.write(src, volume=gf)
        c = cli_compute(cli, ["isosurface", src, "--level", "0", "-o", os.path.join(d, "g.ply")], reps)
    for name, arr in [("fortran", gf), ("c", g)]:
        p = best(lambda: morpho.isosurface(arr, 0.0, return_report=True), reps)
        print(json.dumps({"case": f"isosurface 256^3 gyroid ({name} order)", "cli_compute_s": c,
                          "python_s": p, "overhead": (p - c) / c}))
    v, f, _ = morpho.isosurface(g, 0.0)
    print(json.dumps({"triangles": len(f), "vertices": len(v)}))

    pts = np.random.default_rng(0).random((1_000_000, 2))
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "p.ply")
        morpho.write(src, points=pts)
        c = cli_compute(cli, ["triangulate", src, "-o", os.path.join(d, "t.ply")], reps)
    p = best(lambda: morpho.triangulate(pts), reps)
    print(json.dumps({"case": "triangulate 1M 2D points", "cli_compute_s": c, "python_s": p,
                      "overhead": (p - c) / c}))

    try:
        from skimage import measure
    except ImportError:
        return
    m = best(lambda: morpho.isosurface(g, 0.0), reps)
    s = best(lambda: measure.marching_cubes(g, 0.0), reps)
    print(json.dumps({"case": "isosurface vs skimage marching_cubes, 256^3 gyroid, with normals",
                      "morpho_s": m, "skimage_s": s, "skimage_over_morpho": s / m}))
    print(json.dumps({"load_after": os.getloadavg()}))


if __name__ == "__main__":
    main()
