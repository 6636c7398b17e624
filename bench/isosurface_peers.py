#!/usr/bin/env python3
"""Peer timings for `morpho::volume::isosurface` on the same volume.

Usage:
    cargo run --release -p morpho --example bench_isosurface -- 256 /tmp/gyroid256.f32 > morpho.jsonl
    python3 bench/isosurface_peers.py /tmp/gyroid256.f32 256,256,256 0.0 [morpho.jsonl]

Reads a raw little-endian float32 volume (x fastest, as morpho writes it), runs
scikit-image's `marching_cubes` (Lewiner) and VTK's `vtkFlyingEdges3D` (with and without
normals) once each, single process as the libraries run by default, and prints one JSON line
per run (wall and process CPU seconds; on a loaded machine compare CPU seconds). With morpho's JSON lines it also prints the time ratios (peer / morpho) for the
single-thread variants that compute comparable outputs.
"""
import json
import os
import sys
import time

import numpy as np

REPS = int(os.environ.get("REPS", "1"))  # repeat each run, report the minimum times


def main():
    path, dims, level = sys.argv[1], [int(s) for s in sys.argv[2].split(",")], float(sys.argv[3])
    nx, ny, nz = dims
    vol = np.fromfile(path, dtype="<f4").reshape(nz, ny, nx)  # [z, y, x]
    results = []
    try:
        from skimage.measure import marching_cubes

        dt = dc = float("inf")
        for _ in range(REPS):
            t, c = time.perf_counter(), time.process_time()
            verts, faces, normals, values = marching_cubes(vol, level=level, method="lewiner")
            dt, dc = min(dt, time.perf_counter() - t), min(dc, time.process_time() - c)
        results.append({"peer": "skimage.marching_cubes(lewiner)", "seconds": round(dt, 4),
                        "cpu_seconds": round(dc, 4),
                        "vertices": len(verts), "triangles": len(faces),
                        "tri_per_s": round(len(faces) / dt)})
    except ImportError as e:
        results.append({"peer": "skimage", "error": str(e)})
    try:
        import vtk
        from vtk.util import numpy_support

        img = vtk.vtkImageData()
        img.SetDimensions(nx, ny, nz)
        arr = numpy_support.numpy_to_vtk(vol.ravel(order="C"), deep=True)
        img.GetPointData().SetScalars(arr)
        for normals in (False, True):
            fe = vtk.vtkFlyingEdges3D()
            fe.SetInputData(img)
            fe.SetValue(0, level)
            fe.SetComputeNormals(normals)
            fe.SetComputeGradients(False)
            fe.SetComputeScalars(False)
            dt = dc = float("inf")
            for _ in range(REPS):
                fe.Modified()
                t, c = time.perf_counter(), time.process_time()
                fe.Update()
                dt, dc = min(dt, time.perf_counter() - t), min(dc, time.process_time() - c)
            out = fe.GetOutput()
            results.append({"peer": f"vtkFlyingEdges3D(normals={normals})",
                            "seconds": round(dt, 4), "cpu_seconds": round(dc, 4),
                            "vertices": out.GetNumberOfPoints(),
                            "triangles": out.GetNumberOfCells(),
                            "tri_per_s": round(out.GetNumberOfCells() / dt),
                            "vtk_threads": vtk.vtkSMPTools.GetEstimatedNumberOfThreads()})
    except ImportError as e:
        results.append({"peer": "vtk", "error": str(e)})
    for r in results:
        print(json.dumps(r))
    if len(sys.argv) > 4:
        morpho = [json.loads(l) for l in open(sys.argv[4]) if l.startswith("{")]
        single = {m["variant"]: m for m in morpho if m["threads"] == 1}
        allc = {m["variant"]: m for m in morpho if m["threads"] > 1}
        pairs = [("skimage.marching_cubes(lewiner)", "decider_central_notopo"),
                 ("vtkFlyingEdges3D(normals=False)", "decider_nonormals_notopo"),
                 ("vtkFlyingEdges3D(normals=True)", "decider_central_notopo")]
        for peer, var in pairs:
            p = next((r for r in results if r.get("peer") == peer and "seconds" in r), None)
            if p and var in single:
                print(json.dumps({"ratio": f"{peer} / morpho {var}",
                                  "single_thread_wall": round(p["seconds"] / single[var]["seconds"], 2),
                                  "single_thread_cpu": round(p["cpu_seconds"] / single[var]["cpu_seconds"], 2),
                                  "all_cores_wall": round(p["seconds"] / allc[var]["seconds"], 2)
                                  if var in allc else None}))


if __name__ == "__main__":
    main()
