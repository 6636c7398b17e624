#!/usr/bin/env python3
"""Issue 24 scale figures: a contour surface of a 1024³ float32 volume (4 GiB) by the CLI's
streaming mode under a 2 GiB address-space limit, and by ``morpho.dask.isosurface`` on a
``LocalCluster(n_workers=2, memory_limit="1.5GB")``; throughput against the in-memory CLI on a
512³ volume of the same function.

    python bench/stream_scale.py --dir /big/tmp [--n 1024] [--skip-dask] [--morpho target/release/morpho]

The volume is a gyroid with two periods per axis, written slab by slab as raw float32 with a
JSON sidecar (nothing here holds it in memory). Prints one line per run: wall seconds, CPU
seconds, peak RSS (of the CLI; of each worker for Dask), triangles, samples per second.
"""

import argparse
import json
import os
import resource
import subprocess
import sys
import time

import numpy as np


def make_volume(folder, n, periods=2.0):
    raw = os.path.join(folder, f"gyroid{n}.raw")
    side = os.path.join(folder, f"gyroid{n}.json")
    if os.path.exists(side) and os.path.getsize(raw) == 4 * n**3:
        return side, raw
    t = 2 * np.pi * periods * np.arange(n, dtype=np.float64) / n
    sx, cx = np.sin(t), np.cos(t)
    with open(raw, "wb") as f:
        for z in range(n):
            # f(x, y, z) = sin x cos y + sin y cos z + sin z cos x, x fastest
            a = sx[None, :] * cx[:, None] + sx[:, None] * cx[z] + sx[z] * cx[None, :]
            f.write(a.astype("<f4").tobytes())
    with open(side, "w") as f:
        json.dump({"data": os.path.basename(raw), "dims": [n, n, n], "dtype": "f32"}, f)
    return side, raw


def timed(cmd, limit=None):
    """Runs cmd (under an address-space limit in bytes); wall, CPU s, peak RSS MiB, report."""
    pre = ["prlimit", f"--as={limit}"] if limit else []
    t = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(pre + ["/usr/bin/time", "-f", "%M"] + cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    rss = int(p.stderr.strip().splitlines()[-1]) / 1024
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, rss


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--morpho", default="target/release/morpho")
    ap.add_argument("--skip-dask", action="store_true")
    ap.add_argument("--skip-cli", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    print(f"load average {os.getloadavg()[0]:.1f}, {os.cpu_count()} cores")
    t = time.perf_counter()
    big, big_raw = make_volume(a.dir, a.n)
    print(f"volume {a.n}³ f32 ready ({time.perf_counter() - t:.1f} s)")
    small, _ = make_volume(a.dir, a.n // 2)
    out = os.path.join(a.dir, "out.ply")
    rep = os.path.join(a.dir, "rep.json")

    def line(name, n, wall, cpu, rss):
        r = json.load(open(rep))
        print(f"{name:34s} wall {wall:7.1f} s  cpu {cpu:7.1f} s  peak RSS {rss:7.0f} MiB  "
              f"triangles {r['triangles']:>10,}  {n**3 / wall / 1e6:6.1f} M samples/s")

    if not a.skip_cli:
        w, c, m = timed([a.morpho, "isosurface", small, "--level", "0", "-o", out, "--report", rep])
        line(f"CLI in memory {a.n // 2}³", a.n // 2, w, c, m)
        w, c, m = timed([a.morpho, "isosurface", small, "--level", "0", "-o", out, "--report", rep,
                         "--stream"])
        line(f"CLI --stream {a.n // 2}³", a.n // 2, w, c, m)
        w, c, m = timed([a.morpho, "isosurface", big, "--level", "0", "-o", out, "--report", rep,
                         "--stream"], limit=2 << 30)
        line(f"CLI --stream {a.n}³ (2 GiB AS limit)", a.n, w, c, m)
        os.remove(out)
    if not a.skip_dask:
        from dask.distributed import Client, LocalCluster

        import morpho.dask as md

        with LocalCluster(n_workers=2, threads_per_worker=1, memory_limit="1.5GB",
                          processes=True, dashboard_address=None) as cluster, Client(cluster) as cl:
            darr = md.from_raw(big_raw, (a.n, a.n, a.n), "float32", chunks=(128, 256, 256))
            index = os.path.join(a.dir, "chunked.json")
            t = time.perf_counter()
            md.isosurface(darr, 0.0, out=index)
            wall = time.perf_counter() - t
            peaks = cl.run(lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
            idx = json.load(open(index))
            tris = idx.get("faces", "?")
            print(f"Dask LocalCluster(2, 1.5GB) {a.n}³  wall {wall:7.1f} s  worker peak RSS "
                  f"{', '.join(f'{v:.0f}' for v in peaks.values())} MiB  triangles {tris}  "
                  f"{a.n**3 / wall / 1e6:6.1f} M samples/s")


if __name__ == "__main__":
    main()
