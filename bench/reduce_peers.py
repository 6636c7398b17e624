#!/usr/bin/env python3
"""Triangle reduction against quadric-error (QEM) decimation, same inputs, same run (issue 21).

Usage (from the repository root; the peers come from PyPI):
    python3 -m venv /tmp/benchenv
    /tmp/benchenv/bin/pip install pymeshlab fast-simplification meshoptimizer numpy trimesh
    cargo build --release -p morpho-cli --example mesh_compare -p morpho
    /tmp/benchenv/bin/python bench/reduce_peers.py [--rates 50,90,99] [--meshes skull,horse,...]
        [--tools morpho,pymeshlab,...] [--morpho-old /path/to/another/morpho]

For each mesh and each reduction rate R (% of the triangles removed) the target is
T = round(n · (1 − R/100)) triangles, and every tool is asked for exactly T:
  * morpho      `morpho reduce IN --triangles T` (Hamann ch. 5, bivariate point, error levels;
                `morpho-hamann`: `--order hamann`, the thesis's order alone; one thread:
                the reduction is sequential, RAYON_NUM_THREADS=1 also for its measuring pass),
                run as its own process under /usr/bin/time for wall, CPU and peak RSS — this
                includes reading and writing the files and the report's distance measurement,
                so morpho's time is an upper bound of its reduction time; the report's
                `timings.compute` is printed too;
  * pymeshlab   `meshing_decimation_quadric_edge_collapse(targetfacenum=T)` with MeshLab's
                defaults, and again with `preservetopology=True, qualitythr=0.3` (the option a
                user who needs a manifold turns on);
  * fast-simplification `simplify(points, faces, target_reduction=R/100)`;
  * meshoptimizer `simplify(..., target_index_count=3T, target_error=1.0)` (error bound
                lifted so that it reaches the count, as a user asking for a count does).
Peers run in this process; their time is the call alone (CPU and wall), no I/O.
Every output is written as PLY and measured by the same code (`examples/mesh_compare.rs`):
triangles, χ, genus, parts, boundary loops, non-manifold edges/vertices, orientation conflicts,
degenerate triangles, RMS of the input's vertices to the output, sampled symmetric Hausdorff.
Prints one JSON line per run and a Markdown table (distances relative to the bbox diagonal).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
DATA = os.environ.get("MORPHO_SHARED_DATA", os.path.join(ROOT, "..", "shared", "data"))
# MORPHO_BIN: a folder holding copies of both binaries (so a rebuild cannot change them mid-run)
BIN = os.environ.get("MORPHO_BIN")
MORPHO = os.path.join(BIN, "morpho") if BIN else os.path.join(ROOT, "target", "release", "morpho")
COMPARE = (os.path.join(BIN, "mesh_compare") if BIN
           else os.path.join(ROOT, "target", "release", "examples", "mesh_compare"))


def read_mesh(path):
    """Vertices and triangles through morpho itself (any format it reads), via binary PLY."""
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    return np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.int64)


def write_ply(path, v, f):
    v = np.ascontiguousarray(v, dtype="<f8")
    f = np.ascontiguousarray(f, dtype="<i4")
    with open(path, "wb") as out:
        out.write(
            (
                "ply\nformat binary_little_endian 1.0\n"
                f"element vertex {len(v)}\nproperty double x\nproperty double y\nproperty double z\n"
                f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n"
            ).encode()
        )
        rows = np.empty(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
        rows["n"] = 3
        rows["i"] = f
        out.write(v.tobytes())
        out.write(rows.tobytes())


def compare(inp, out):
    r = subprocess.run([COMPARE, inp, out], capture_output=True, text=True)
    if r.returncode != 0:
        return {"compare_error": r.stderr.strip()}
    return json.loads(r.stdout)


def timed(fn):
    t, c = time.perf_counter(), time.process_time()
    res = fn()
    return res, time.perf_counter() - t, time.process_time() - c


def run_morpho(inp, target, tmp, extra=(), binary=None):
    out = os.path.join(tmp, "morpho.ply")
    rep = os.path.join(tmp, "morpho.json")
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    cmd = ["/usr/bin/time", "-f", "%e %U %S %M", binary or MORPHO, "reduce", inp, "--triangles",
           str(target), "-o", out, "--report", rep, *extra]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        return {"error": r.stderr.strip()[-300:]}, None
    wall, user, sys_, rss = r.stderr.strip().splitlines()[-1].split()
    report = json.load(open(rep))
    return {
        "seconds": float(wall),
        "cpu_seconds": float(user) + float(sys_),
        "compute_seconds": report["timings"]["compute"],
        "peak_rss_mib": int(rss) / 1024,
        "stop": report["stop"],
    }, out


def run_pymeshlab(v, f, target, tmp, preserve):
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f))
    kw = {"targetfacenum": int(target)}
    if preserve:
        kw.update(preservetopology=True, qualitythr=0.3)
    _, wall, cpu = timed(lambda: ms.meshing_decimation_quadric_edge_collapse(**kw))
    m = ms.current_mesh()
    out = os.path.join(tmp, "pymeshlab.ply")
    write_ply(out, m.vertex_matrix(), m.face_matrix())
    return {"seconds": wall, "cpu_seconds": cpu}, out


def run_fast(v, f, rate, tmp):
    import fast_simplification

    (v2, f2), wall, cpu = timed(
        lambda: fast_simplification.simplify(v, f, target_reduction=rate / 100.0)
    )
    out = os.path.join(tmp, "fast.ply")
    write_ply(out, v2, f2)
    return {"seconds": wall, "cpu_seconds": cpu}, out


def run_meshopt(v, f, target, tmp):
    import meshoptimizer

    idx = np.ascontiguousarray(f.ravel(), dtype=np.uint32)
    pos = np.ascontiguousarray(v, dtype=np.float32)
    dest = np.zeros_like(idx)

    def go():
        return meshoptimizer.simplify(dest, idx, pos, target_index_count=3 * int(target),
                                      target_error=1.0)

    n, wall, cpu = timed(go)
    f2 = dest[:n].reshape(-1, 3).astype(np.int64)
    out = os.path.join(tmp, "meshopt.ply")
    write_ply(out, v, f2)
    return {"seconds": wall, "cpu_seconds": cpu}, out


def skull(tmp):
    """The CT head's bone surface (level 120), as `morpho isosurface` makes it."""
    vol = os.path.join(DATA, "volumes", "cthead_8bit_256x256x99.json")
    out = os.path.join(tmp, "skull_iso.ply")
    subprocess.run([MORPHO, "isosurface", vol, "--level", "120", "-o", out], check=True,
                   capture_output=True)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rates", default="50,90,99")
    ap.add_argument("--meshes", default="skull,horse,bunny,fandisk")
    ap.add_argument("--tools", default="morpho,morpho-hamann,pymeshlab,pymeshlab-topo,fast,meshopt")
    # another morpho binary (e.g. main's) run right after `morpho` as tool `morpho-old`
    ap.add_argument("--morpho-old", default=None)
    a = ap.parse_args()
    rates = [float(r) for r in a.rates.split(",")]
    tools = a.tools.split(",")
    if a.morpho_old and "morpho" in tools:
        tools.insert(tools.index("morpho") + 1, "morpho-old")
    files = {
        "horse": os.path.join(DATA, "meshes", "horse.obj.gz"),
        "bunny": os.path.join(DATA, "meshes", "stanford-bunny.obj.gz"),
        "fandisk": os.path.join(DATA, "meshes", "fandisk.obj"),
        "spot": os.path.join(DATA, "meshes", "spot.obj"),
        "rocker": os.path.join(DATA, "meshes", "rocker-arm.obj"),
    }
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.meshes.split(","):
            src = skull(tmp) if name == "skull" else files[name]
            # every tool reads the same triangles: one binary PLY written from morpho's reader
            inp = os.path.join(tmp, f"{name}.ply")
            subprocess.run([MORPHO, "convert", src, "-o", inp], check=True, capture_output=True)
            v, f = read_mesh(inp)
            n = len(f)
            for rate in rates:
                target = max(4, round(n * (1 - rate / 100.0)))
                for tool in tools:
                    try:
                        if tool == "morpho":
                            res, out = run_morpho(inp, target, tmp)
                        elif tool == "morpho-old":
                            res, out = run_morpho(inp, target, tmp, binary=a.morpho_old)
                        elif tool == "morpho-hamann":
                            res, out = run_morpho(inp, target, tmp, ("--order", "hamann"))
                        elif tool == "pymeshlab":
                            res, out = run_pymeshlab(v, f, target, tmp, False)
                        elif tool == "pymeshlab-topo":
                            res, out = run_pymeshlab(v, f, target, tmp, True)
                        elif tool == "fast":
                            res, out = run_fast(v, f, rate, tmp)
                        elif tool == "meshopt":
                            res, out = run_meshopt(v, f, target, tmp)
                        else:
                            continue
                    except Exception as e:  # a peer that fails is reported, not fatal
                        res, out = {"error": repr(e)[:300]}, None
                    if out:
                        res.update(compare(inp, out))
                    res.update(mesh=name, triangles_in=n, rate=rate, target=target, tool=tool)
                    print(json.dumps(res), flush=True)
                    rows.append(res)
    print()
    print("| mesh | removed | tool | triangles | time s (CPU) | χ / genus | loops | non-manifold e/v | "
          "RMS / diag | Hausdorff / diag |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if "error" in r or "compare_error" in r:
            print(f"| {r['mesh']} | {r['rate']:g} % | {r['tool']} | error: "
                  f"{r.get('error', r.get('compare_error'))[:80]} |||||||")
            continue
        t = f"{r['cpu_seconds']:.3f}"
        if r["tool"].startswith("morpho"):
            t += f" (compute {r['compute_seconds']:.3f}, {r['peak_rss_mib']:.0f} MiB)"
        print(f"| {r['mesh']} ({r['triangles_in']}) | {r['rate']:g} % | {r['tool']} | "
              f"{r['triangles']} | {t} | {r['euler_characteristic']} / {r['genus']} | "
              f"{r['boundary_loops']} | {r['non_manifold_edges']}/{r['non_manifold_vertices']} | "
              f"{r['rms_rel']:.2e} | {r['hausdorff_rel']:.2e} |")


if __name__ == "__main__":
    sys.exit(main())
