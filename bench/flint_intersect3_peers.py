"""Mesh–mesh intersection: `morpho flint intersect A B` (two 3D flintstone trees, issue 18)
against VTK's vtkCollisionDetectionFilter (OBB trees, all contacts) and, once per data set,
vtkIntersectionPolyDataFilter, on a closed mesh and a shifted copy of it, in the same run,
taking turns.

    /tmp/benchenv/bin/python bench/flint_intersect3_peers.py --morpho target/release/morpho \
        --rounds 3 [--intersection-filter]

Reported: CPU seconds (user+sys) of the whole morpho process (read, both tree builds, the
descent, segments, CSV write) and its `intersect` phase from the report; for VTK the CPU seconds
of the filter's Update() (which builds both OBB trees) measured in-process; pair counts; the
load average. Minimum over rounds.
"""

import argparse
import gzip
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
import vtk
from vtk.util import numpy_support as ns

DATA = os.environ.get("MORPHO_DATA", "/work/shared/data")


def read_obj(path):
    opener = gzip.open if path.endswith(".gz") else open
    v, f = [], []
    with opener(path, "rt") as fh:
        for line in fh:
            if line.startswith("v "):
                v.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                f.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return np.array(v, dtype=np.float64), np.array(f, dtype=np.int64)


def write_ply(path, v, f):
    with open(path, "wb") as fh:
        fh.write(
            (
                "ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                "property double x\nproperty double y\nproperty double z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                % (len(v), len(f))
            ).encode()
        )
        fh.write(v.astype("<f8").tobytes())
        rec = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
        rec["n"] = 3
        rec["i"] = f
        fh.write(rec.tobytes())


def polydata(v, f):
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(np.ascontiguousarray(v), deep=True))
    cells = np.hstack([np.full((len(f), 1), 3, dtype=np.int64), f]).ravel()
    ca = vtk.vtkCellArray()
    ca.SetCells(len(f), ns.numpy_to_vtkIdTypeArray(cells, deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    pd.SetPolys(ca)
    return pd


def vtk_collision(pa, pb):
    f = vtk.vtkCollisionDetectionFilter()
    f.SetInputData(0, pa)
    f.SetTransform(0, vtk.vtkTransform())
    f.SetInputData(1, pb)
    f.SetMatrix(1, vtk.vtkMatrix4x4())
    f.SetCollisionModeToAllContacts()
    f.GenerateScalarsOff()
    t0 = time.process_time()
    f.Update()
    cpu = time.process_time() - t0
    return cpu, f.GetNumberOfContacts()


def vtk_intersection(pa, pb):
    f = vtk.vtkIntersectionPolyDataFilter()
    f.SetInputData(0, pa)
    f.SetInputData(1, pb)
    f.SplitFirstOutputOff()
    f.SplitSecondOutputOff()
    t0 = time.process_time()
    f.Update()
    cpu = time.process_time() - t0
    return cpu, f.GetOutput().GetNumberOfCells()


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_morpho(exe, a, b, out, rep, threads):
    env = dict(os.environ)
    if threads:
        env["RAYON_NUM_THREADS"] = str(threads)
    c0 = child_cpu()
    w0 = time.perf_counter()
    subprocess.run(
        [exe, "flint", "intersect", a, b, "-o", out, "--report", rep],
        check=True,
        env=env,
        stderr=subprocess.DEVNULL,
    )
    wall = time.perf_counter() - w0
    cpu = child_cpu() - c0
    r = json.load(open(rep))
    return cpu, wall, r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--morpho", default="target/release/morpho")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--intersection-filter", action="store_true")
    args = ap.parse_args()
    sets = [
        ("bunny_npm", "meshes/bunny_npm.obj"),
        ("horse", "meshes/horse.obj.gz"),
    ]
    tmp = tempfile.mkdtemp(prefix="flintx3_")
    for name, rel in sets:
        v, f = read_obj(os.path.join(DATA, rel))
        used = np.unique(f)
        ext = v[used].max(axis=0) - v[used].min(axis=0)
        d = np.array([0.23, 0.11, 0.05]) * ext
        a, b = os.path.join(tmp, name + "_a.ply"), os.path.join(tmp, name + "_b.ply")
        write_ply(a, v, f)
        write_ply(b, v + d, f)
        # a disjoint copy: the root pair is pruned, so that run is read + both builds + write
        far = os.path.join(tmp, name + "_far.ply")
        write_ply(far, v + 3.0 * ext, f)
        pa, pb = polydata(v, f), polydata(v + d, f)
        out, rep = os.path.join(tmp, "s.csv"), os.path.join(tmp, "r.json")
        best = {"morpho": 1e9, "morpho_fixed": 1e9, "vtk": 1e9}
        for rnd in range(args.rounds):
            cpu, wall, r = run_morpho(args.morpho, a, b, out, rep, args.threads)
            t = r.get("timings", r.get("time", {}))
            best["morpho"] = min(best["morpho"], cpu)
            pairs = r["pairs"]
            cfix, _, rf = run_morpho(args.morpho, a, far, out, rep, args.threads)
            assert rf["pairs"] == 0 and rf["visited"] == 1, rf
            best["morpho_fixed"] = min(best["morpho_fixed"], cfix)
            cv, nc = vtk_collision(pa, pb)
            best["vtk"] = min(best["vtk"], cv)
            print(
                f"{name} round {rnd}: morpho {cpu:.3f} s CPU ({wall:.3f} s wall) pairs {pairs} "
                f"visited {r['visited']} leaf_tests {r['leaf_tests']} timings {t}; disjoint copy "
                f"(read+build+write) {cfix:.3f} s CPU | "
                f"vtkCollisionDetectionFilter {cv:.3f} s CPU contacts {nc} | load {os.getloadavg()}",
                flush=True,
            )
        if args.intersection_filter:
            ci, nl = vtk_intersection(pa, pb)
            print(f"{name}: vtkIntersectionPolyDataFilter {ci:.3f} s CPU, {nl} lines", flush=True)
        print(
            f"{name}: triangles {len(f)}; min CPU morpho {best['morpho']:.3f} s "
            f"(disjoint copy {best['morpho_fixed']:.3f} s, difference = descent + segments "
            f"{best['morpho'] - best['morpho_fixed']:.3f} s), "
            f"vtk collision {best['vtk']:.3f} s, ratio vtk/morpho {best['vtk'] / best['morpho']:.2f}",
            flush=True,
        )


if __name__ == "__main__":
    sys.exit(main())
