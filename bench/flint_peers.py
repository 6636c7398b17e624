#!/usr/bin/env python3
"""Issue 18 numbers: point-in-polygon and point-in-mesh queries, morpho's flintstone tree
against shapely (GEOS, prepared ``contains_xy``) and trimesh (``contains``, ray tests) on the
same inputs in the same run.

    python bench/flint_peers.py [--morpho target/release/morpho] [--vertices 1000000] [--queries 1000000]

2D: the Great Britain coast (``../shared/data/polygons``) upsampled to about ``--vertices``
vertices (points inserted along each edge: the same shape), ``--queries`` uniform points in its
bounding box. 3D: the horse (97k triangles), queries uniform in its bounding box. morpho's
figures are the CLI's own ``timings.build`` and ``timings.query`` (reading and writing the CSVs
excluded), with ``RAYON_NUM_THREADS`` 1 and 2, plus the whole process's CPU time; the answers are compared
with the peer's (points exactly on the boundary excepted). Minimum of ``--rounds``.
"""

import argparse
import gzip
import json
import os
import resource
import subprocess
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data")


def best(f, rounds):
    """Minimum wall time of `rounds` calls, the CPU time of that call, the last result."""
    out, t = None, []
    for _ in range(rounds):
        s, c = time.perf_counter(), time.process_time()
        out = f()
        t.append((time.perf_counter() - s, time.process_time() - c))
    w, c = min(t)
    best.cpu = c
    return w, out


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def morpho_contains(exe, shape, queries, out, rep, threads, rounds):
    env = dict(os.environ)
    if threads:
        env["RAYON_NUM_THREADS"] = str(threads)
    b, q, cpu = [], [], []
    for _ in range(rounds):
        c = child_cpu()
        subprocess.run([exe, "flint", "contains", shape, queries, "-o", out, "--report", rep],
                       check=True, capture_output=True, env=env)
        cpu.append(child_cpu() - c)
        r = json.load(open(rep))
        b.append(r["timings"]["build"])
        q.append(r["timings"]["query"])
    inside = np.loadtxt(out, delimiter=",", skiprows=1, usecols=-1).astype(int)
    morpho_contains.cpu = min(cpu)
    return min(b), min(q), inside


def build_only(a, up, poly_csv, d):
    """Tree build against Douglas–Peucker on the same polygon, taking turns, `a.rounds` rounds:
    morpho's `timings.build` and process CPU (`flint contains` with one query: read + build),
    shapely's `simplify` wall and CPU at tolerance 1e-3 and 0 (0 recurses to every vertex, the
    whole hierarchy as the tree does). Minimum over the rounds."""
    import shapely

    q_csv = os.path.join(d, "q1.csv")
    np.savetxt(q_csv, up[:1] * 0 + up.mean(axis=0), delimiter=",", header="x,y", comments="",
               fmt="%.17g")
    poly = shapely.Polygon(up)
    rep, out = os.path.join(d, "r.json"), os.path.join(d, "o.csv")
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    rows = {"morpho build": [], "morpho process cpu": [], "dp 1e-3": [], "dp 1e-3 cpu": [],
            "dp 0": [], "dp 0 cpu": []}
    depth = None
    for _ in range(a.rounds):
        c = child_cpu()
        subprocess.run([a.morpho, "flint", "contains", poly_csv, q_csv, "-o", out, "--report", rep],
                       check=True, capture_output=True, env=env)
        rows["morpho process cpu"].append(child_cpu() - c)
        r = json.load(open(rep))
        rows["morpho build"].append(r["timings"]["build"])
        for tol in ["1e-3", "0"]:
            w, _ = best(lambda: shapely.simplify(poly, float(tol), preserve_topology=False), 1)
            rows[f"dp {tol}"].append(w)
            rows[f"dp {tol} cpu"].append(best.cpu)
    subprocess.run([a.morpho, "flint", "build", poly_csv, "-o", os.path.join(d, "t.json"),
                    "--report", rep], check=True, capture_output=True, env=env)
    depth = json.load(open(rep)).get("depth")
    m = {k: min(v) for k, v in rows.items()}
    print(f"build only: {len(up):,} vertices, tree depth {depth}, min of {a.rounds} rounds")
    for k, v in m.items():
        print(f"  {k:20s} {v:.3f} s")
    print(f"  ratio build / DP 1e-3 {m['morpho build'] / m['dp 1e-3']:.2f}× (wall), "
          f"build / DP 0 {m['morpho build'] / m['dp 0']:.2f}× (wall), "
          f"process cpu / DP 0 cpu {m['morpho process cpu'] / max(m['dp 0 cpu'], 1e-9):.2f}×")
    print(f"load average {os.getloadavg()}")


def intersect_only(a, up, poly_csv, d):
    """Intersection of two polygons' boundaries (issue 18: "faster than shapely `intersection`
    of their boundaries"): B is A turned by 0.5° about its centroid and moved by 0.2 % of its
    box, so the two coasts cross many times. morpho: `flint intersect A B` (the CLI's
    `timings.build` of both trees and `timings.intersect`, and the whole process's CPU);
    shapely: `intersection(A.exterior, B.exterior)` of the two rings (GEOS overlay), wall and
    CPU. Taking turns, minimum of `a.rounds`. The crossing counts are compared."""
    import shapely

    c = up.mean(axis=0)
    th = np.radians(0.5)
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    span = up.max(axis=0) - up.min(axis=0)
    vb = (up - c) @ rot.T + c + 0.002 * span
    b_csv = os.path.join(d, "polyb.csv")
    np.savetxt(b_csv, vb, delimiter=",", header="x,y", comments="", fmt="%.17g")
    ra, rb = shapely.LinearRing(up), shapely.LinearRing(vb)
    rep, out = os.path.join(d, "ri.json"), os.path.join(d, "oi.csv")
    rows = {"shapely wall": [], "shapely cpu": []}
    for threads in [1, 2]:
        for k in ["build", "intersect", "process cpu"]:
            rows[f"morpho {threads}t {k}"] = []
    pairs = None
    for _ in range(a.rounds):
        for threads in [1, 2]:
            env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
            c0 = child_cpu()
            subprocess.run([a.morpho, "flint", "intersect", poly_csv, b_csv, "-o", out,
                            "--report", rep], check=True, capture_output=True, env=env)
            rows[f"morpho {threads}t process cpu"].append(child_cpu() - c0)
            r = json.load(open(rep))
            rows[f"morpho {threads}t build"].append(r["timings"]["build"])
            rows[f"morpho {threads}t intersect"].append(r["timings"]["intersect"])
            pairs = r["pairs"]
        w, g = best(lambda: shapely.intersection(ra, rb), 1)
        rows["shapely wall"].append(w)
        rows["shapely cpu"].append(best.cpu)
    n_sh = len(shapely.get_parts(shapely.get_parts(g)))
    m = {k: min(v) for k, v in rows.items()}
    print(f"intersection: {len(up):,} + {len(vb):,} vertices, morpho {pairs} meeting edge pairs, "
          f"shapely {n_sh} parts ({g.geom_type}), min of {a.rounds} rounds")
    for k, v in m.items():
        print(f"  {k:26s} {v:.3f} s")
    for threads in [1, 2]:
        t = m[f"morpho {threads}t build"] + m[f"morpho {threads}t intersect"]
        print(f"  {threads} thread(s): build + intersect {t:.3f} s = "
              f"{m['shapely wall'] / t:.2f}× faster than shapely (wall)")
    print(f"load average {os.getloadavg()}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--morpho", default=os.path.join(HERE, "..", "target", "release", "morpho"))
    ap.add_argument("--vertices", type=int, default=1_000_000)
    ap.add_argument("--queries", type=int, default=1_000_000)
    ap.add_argument("--mesh-queries", type=int, default=200_000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--polygon", help="a polygon CSV (x,y in order) instead of the upsampled GB coast")
    ap.add_argument("--star", type=int, metavar="N",
                    help="instead of the coast: a rough star of N vertices (radius 1 + 600 "
                         "harmonics with amplitudes 0.05·g/h, g standard normal, + a closed 2e-5 "
                         "random walk; seed 7), the dense smooth-and-rough case of bench/README")
    ap.add_argument("--circle", type=int, metavar="N",
                    help="instead of the coast: the exact circle (cos, sin of k·2π/N)")
    ap.add_argument("--build-only", action="store_true",
                    help="tree build (one query) against Douglas–Peucker at tolerance 1e-3 and 0 "
                         "(the whole hierarchy), process CPU, taking turns; no point queries")
    ap.add_argument("--intersect", action="store_true",
                    help="intersection of the polygon's boundary with a turned, moved copy "
                         "against shapely's intersection of the two rings; no point queries")
    a = ap.parse_args()
    import shapely
    import rtree  # noqa: F401  trimesh's ray tests need it to stay fast

    d = tempfile.mkdtemp()
    rep, out = os.path.join(d, "r.json"), os.path.join(d, "o.csv")
    print(f"load average {os.getloadavg()}, {os.cpu_count()} cores")
    # 2D
    if a.polygon:
        up = np.loadtxt(a.polygon, delimiter=",", skiprows=1)
        poly_csv = a.polygon
    elif a.star or a.circle:
        n = a.star or a.circle
        th = np.arange(n) * 2 * np.pi / n
        r = np.ones(n)
        if a.star:
            rng = np.random.default_rng(7)
            for h in range(1, 601):
                amp = rng.normal() * 0.05 / h
                r += amp * np.cos(h * th + rng.random() * 2 * np.pi)
            w = np.cumsum(rng.normal(size=n)) * 2e-5
            r += w - np.arange(n) / n * w[-1]
        up = np.c_[r * np.cos(th), r * np.sin(th)]
        poly_csv = os.path.join(d, "poly.csv")
        np.savetxt(poly_csv, up, delimiter=",", header="x,y", comments="", fmt="%.17g")
    else:
        xy = np.loadtxt(os.path.join(DATA, "polygons", "coast_great_britain_ne10m.csv"),
                        delimiter=",", skiprows=1)
        if np.all(xy[0] == xy[-1]):
            xy = xy[:-1]
        k = max(1, a.vertices // len(xy))
        nxt = np.roll(xy, -1, axis=0)
        t = np.arange(k)[None, :, None] / k
        up = (xy[:, None, :] * (1 - t) + nxt[:, None, :] * t).reshape(-1, 2)
        poly_csv = os.path.join(d, "poly.csv")
        np.savetxt(poly_csv, up, delimiter=",", header="x,y", comments="", fmt="%.17g")
    if a.build_only:
        build_only(a, up, poly_csv, d)
        return
    if a.intersect:
        intersect_only(a, up, poly_csv, d)
        return
    rng = np.random.default_rng(18)
    lo, hi = up.min(axis=0), up.max(axis=0)
    q = lo + rng.random((a.queries, 2)) * (hi - lo)
    q_csv = os.path.join(d, "q.csv")
    np.savetxt(q_csv, q, delimiter=",", header="x,y", comments="", fmt="%.17g")
    poly = shapely.Polygon(up)
    t_prep, _ = best(lambda: shapely.prepare(shapely.Polygon(up)), a.rounds)
    shapely.prepare(poly)
    t_sh, sh = best(lambda: shapely.contains_xy(poly, q[:, 0], q[:, 1]), a.rounds)
    c_sh = best.cpu
    t_dp, _ = best(lambda: shapely.simplify(poly, 1e-3, preserve_topology=False), a.rounds)
    print(f"2D: GB coast upsampled to {len(up):,} vertices, {len(q):,} queries")
    print(f"  shapely prepare {t_prep:.3f} s, contains_xy {t_sh:.3f} s (cpu {c_sh:.3f} s) = "
          f"{len(q) / t_sh / 1e6:.2f} M/s; Douglas–Peucker (simplify) {t_dp:.3f} s")
    for threads in [1, 2]:
        b, qt, ins = morpho_contains(a.morpho, poly_csv, q_csv, out, rep, threads, a.rounds)
        agree = np.mean((ins == 1) == sh)
        print(f"  morpho {threads} thread(s) build {b:.3f} s ({b / t_dp:.2f}× DP), queries {qt:.3f} s = "
              f"{len(q) / qt / 1e6:.2f} M/s ({t_sh / qt:.2f}× shapely); whole process cpu "
              f"{morpho_contains.cpu:.3f} s (with reading/writing); answers agree {100 * agree:.4f} %")
    print(f"load average {os.getloadavg()}")
    if a.mesh_queries <= 0:
        return
    # 3D
    import trimesh

    with gzip.open(os.path.join(DATA, "meshes", "horse.obj.gz"), "rt") as f:
        m = trimesh.load(trimesh.util.wrap_as_stream(f.read()), file_type="obj", process=False)
    mesh_ply = os.path.join(d, "horse.ply")
    m.export(mesh_ply)
    lo, hi = m.bounds
    q3 = lo + rng.random((a.mesh_queries, 3)) * (hi - lo)
    q3_csv = os.path.join(d, "q3.csv")
    np.savetxt(q3_csv, q3, delimiter=",", header="x,y,z", comments="", fmt="%.17g")
    # trimesh's ray tests hold arrays per query × candidate triangle: batches keep it in memory
    # (one call on 20k points took 22 GB here)
    t_tm, tm = best(lambda: np.concatenate([m.contains(q3[i:i + 200])
                                            for i in range(0, len(q3), 200)]), 1)
    print(f"3D: horse {len(m.faces):,} triangles, {len(q3):,} queries")
    print(f"  trimesh contains {t_tm:.3f} s = {len(q3) / t_tm / 1e6:.3f} M/s")
    for threads in [1, 2]:
        b, qt, ins = morpho_contains(a.morpho, mesh_ply, q3_csv, out, rep, threads, a.rounds)
        agree = np.mean((ins == 1) == tm)
        name = f"{threads} thread(s)"
        print(f"  morpho {name:9s} build {b:.3f} s, queries {qt:.3f} s = {len(q3) / qt / 1e6:.2f} M/s "
              f"({t_tm / qt:.1f}× trimesh); answers agree {100 * agree:.3f} %")


if __name__ == "__main__":
    main()
