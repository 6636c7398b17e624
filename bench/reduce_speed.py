#!/usr/bin/env python3
"""One-thread CPU time of `morpho reduce` against pymeshlab and meshoptimizer, taking turns
(issue 21, "faster than pymeshlab on one core, and within 4x of meshoptimizer").

Usage (from the repository root; peers from PyPI as in bench/reduce_peers.py):
    cargo build --release -p morpho-cli
    /tmp/benchenv/bin/python bench/reduce_speed.py [--meshes horse,bunny] [--keep 50,10]
                                                   [--rounds 3] [--morpho BIN[,BIN2...]]

Each round runs, for every mesh and every kept percentage K, every morpho binary given
(`morpho reduce IN --keep K`, default options, and with `--hamann` also `--order hamann`, RAYON_NUM_THREADS=1, its own process under
/usr/bin/time: CPU = user + sys of the whole process, peak RSS, and the report's stage
timings), then pymeshlab (`meshing_decimation_quadric_edge_collapse(targetfacenum=T)`,
defaults, and with `preservetopology=True`) and meshoptimizer (`simplify` to 3T indices,
error bound lifted) with T = floor(K/100 · n), morpho's own target. Peers' CPU is the call
alone (`time.process_time`, OMP/MKL threads 1). The minimum over rounds is printed with the
load average at the start and end of the run; a SHA-256 of each morpho output tells whether
two binaries produced the same mesh.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")
import numpy as np  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
DATA = os.environ.get("MORPHO_SHARED_DATA", os.path.join(ROOT, "..", "shared", "data"))
FILES = {
    "horse": "horse.obj.gz",
    "bunny": "stanford-bunny.obj.gz",
    "fandisk": "fandisk.obj",
    "spot": "spot.obj",
    "rocker": "rocker-arm.obj",
}


def load():
    return open("/proc/loadavg").read().split()[:3]


def run_morpho(binary, inp, keep, tmp, extra=()):
    out = os.path.join(tmp, "m.ply")
    rep = os.path.join(tmp, "m.json")
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    cmd = ["/usr/bin/time", "-f", "%e %U %S %M", binary, "reduce", inp, "--keep", str(keep),
           "-o", out, "--report", rep, *extra]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-300:])
    wall, user, sys_, rss = r.stderr.strip().splitlines()[-1].split()
    report = json.load(open(rep))
    return {
        "cpu": float(user) + float(sys_),
        "wall": float(wall),
        "rss_mib": int(rss) / 1024,
        "timings": report["timings"],
        "triangles": report["triangles_out"],
        "rms": report["rms"],
        "hausdorff": report["hausdorff"],
        "sha": hashlib.sha256(open(out, "rb").read()).hexdigest()[:12],
    }


def run_pymeshlab(v, f, target, preserve):
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f))
    kw = {"targetfacenum": int(target)}
    if preserve:
        kw.update(preservetopology=True, qualitythr=0.3)
    c = time.process_time()
    ms.meshing_decimation_quadric_edge_collapse(**kw)
    return {"cpu": time.process_time() - c, "triangles": ms.current_mesh().face_number()}


def run_meshopt(v, f, target):
    import meshoptimizer

    idx = np.ascontiguousarray(f.ravel(), dtype=np.uint32)
    pos = np.ascontiguousarray(v, dtype=np.float32)
    dest = np.zeros_like(idx)
    c = time.process_time()
    n = meshoptimizer.simplify(dest, idx, pos, target_index_count=3 * int(target),
                               target_error=1.0)
    return {"cpu": time.process_time() - c, "triangles": n // 3}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshes", default="horse,bunny")
    ap.add_argument("--keep", default="50,10")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--morpho", default=os.path.join(ROOT, "target", "release", "morpho"))
    ap.add_argument("--hamann", action="store_true",
                    help="also time the first binary with --order hamann")
    a = ap.parse_args()
    import trimesh

    bins = a.morpho.split(",")
    keeps = [float(k) for k in a.keep.split(",")]
    best = {}
    print("load at start:", " ".join(load()), flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        inputs = {}
        for name in a.meshes.split(","):
            inp = os.path.join(tmp, f"{name}.ply")
            subprocess.run([bins[0], "convert", os.path.join(DATA, "meshes", FILES[name]),
                            "-o", inp], check=True, capture_output=True)
            m = trimesh.load(inp, process=False, force="mesh")
            inputs[name] = (inp, np.asarray(m.vertices, dtype=np.float64),
                            np.asarray(m.faces, dtype=np.int64))
        for rnd in range(a.rounds):
            for name, (inp, v, f) in inputs.items():
                for keep in keeps:
                    target = int(keep / 100.0 * len(f))
                    runs = [(f"morpho[{i}]", lambda b=b: run_morpho(b, inp, keep, tmp))
                            for i, b in enumerate(bins)]
                    if a.hamann:
                        runs.append(("morpho-hamann", lambda: run_morpho(
                            bins[0], inp, keep, tmp, ("--order", "hamann"))))
                    runs += [("pymeshlab", lambda: run_pymeshlab(v, f, target, False)),
                             ("pymeshlab-topo", lambda: run_pymeshlab(v, f, target, True)),
                             ("meshopt", lambda: run_meshopt(v, f, target))]
                    for tool, go in runs:
                        res = go()
                        res.update(round=rnd, mesh=name, keep=keep, tool=tool,
                                   load=load()[0])
                        print(json.dumps(res), flush=True)
                        key = (name, keep, tool)
                        if key not in best or res["cpu"] < best[key]["cpu"]:
                            best[key] = res
    print("load at end:", " ".join(load()))
    print()
    print("| mesh | kept | tool | triangles | CPU s (min of rounds) | × pymeshlab | × meshopt |"
          " morpho compute / measure s | peak RSS MiB |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (name, keep, tool), r in best.items():
        pm = best[(name, keep, "pymeshlab")]["cpu"]
        mo = best[(name, keep, "meshopt")]["cpu"]
        extra = ""
        if tool.startswith("morpho"):
            t = r["timings"]
            extra = f"{t.get('compute', 0):.2f} / {t.get('measure', 0):.2f} | {r['rss_mib']:.0f}"
        else:
            extra = " | "
        print(f"| {name} | {keep:g} % | {tool} | {r['triangles']} | {r['cpu']:.3f} | "
              f"{r['cpu'] / pm:.2f} | {r['cpu'] / max(mo, 1e-9):.1f} | {extra} |")


if __name__ == "__main__":
    sys.exit(main())
