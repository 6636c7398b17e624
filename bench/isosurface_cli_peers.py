#!/usr/bin/env python3
"""`morpho isosurface` as users run it against VTK Flying Edges, taking turns (issue 23 item 4).

Usage:
    python bench/isosurface_cli_peers.py MORPHO_BIN[,LABEL=BIN...] DIR [ROUNDS]

DIR holds the volumes (`bench/isosurface_cli_peers.py` writes them when missing, see
`make_volumes`): the 256³ gyroid and bumpy sphere as raw float32 + NRRD header, and the CT head
(`/work/shared/data/volumes/cthead_8bit_256x256x99.raw.gz`, gunzipped, uint8 + NRRD header).
Each round runs, for each volume, one after the other:
* the morpho process `morpho isosurface VOL --level L -o out.ply --serial` (default options:
  decider, Zucker–Hummel normals, topology, binary PLY) under `/usr/bin/time` and `perf stat`:
  CPU time (perf's task-clock, user + sys), page faults, wall, peak RSS, and the `--report`
  stage times (read / compute / write);
* a Python process that loads the same samples with numpy and runs `vtkFlyingEdges3D` with and
  without normals on one thread (`vtkSMPTools.Initialize(1)`), timing `Update()` by process CPU
  time (the peer's compute alone: interpreter start and numpy read are not counted);
* a second Python process running VTK's whole pipeline as a user would: read the raw file
  (numpy), build the image, `vtkFlyingEdges3D` with normals (one thread), write a binary PLY
  with `vtkPLYWriter` (`vtk_pipeline`: process CPU from the read to the closed file, without
  the interpreter's start and imports, which `vtk_pipeline_process` — the whole process's
  task-clock — includes). VTK does not fsync its file; morpho's write stage does (see
  bench/README "Where the write stage goes").
Prints one JSON line per run and, at the end, the minimum over rounds per (volume, tool), the
machine's load average before and after, and the memory-bandwidth floor of reading the volume
file and writing the PLY (bytes / a measured numpy copy rate).
"""
import gzip
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

VOLS = [  # name, header, level, dims, numpy dtype
    ("gyroid256", "gyroid256.nhdr", 0.0, (256, 256, 256), "<f4"),
    ("bumpy256", "bumpy256.nhdr", 0.0, (256, 256, 256), "<f4"),
    ("cthead", "cthead.nhdr", 120.0, (256, 256, 99), "u1"),
]

VTK = r"""
import sys, time, json, numpy as np, vtk
from vtk.util import numpy_support
vtk.vtkSMPTools.Initialize(1)
path, nx, ny, nz, dt, level = sys.argv[1], *map(int, sys.argv[2:5]), sys.argv[5], float(sys.argv[6])
vol = np.fromfile(path, dtype=dt).reshape(nz, ny, nx).astype(np.float32)
img = vtk.vtkImageData(); img.SetDimensions(nx, ny, nz)
img.GetPointData().SetScalars(numpy_support.numpy_to_vtk(vol.ravel(), deep=True))
for normals in (False, True):
    fe = vtk.vtkFlyingEdges3D(); fe.SetInputData(img); fe.SetValue(0, level)
    fe.SetComputeNormals(normals); fe.SetComputeGradients(False); fe.SetComputeScalars(False)
    t, c = time.perf_counter(), time.process_time()
    fe.Update()
    print(json.dumps({"normals": normals, "wall": time.perf_counter() - t,
                      "cpu": time.process_time() - c,
                      "triangles": fe.GetOutput().GetNumberOfCells()}))
"""


VTK_PIPELINE = r"""
import sys, time, json, numpy as np, vtk
from vtk.util import numpy_support
vtk.vtkSMPTools.Initialize(1)
path, nx, ny, nz, dt, level, out = sys.argv[1], *map(int, sys.argv[2:5]), sys.argv[5], float(sys.argv[6]), sys.argv[7]
t, c = time.perf_counter(), time.process_time()
vol = np.fromfile(path, dtype=dt).reshape(nz, ny, nx).astype(np.float32)
img = vtk.vtkImageData(); img.SetDimensions(nx, ny, nz)
img.GetPointData().SetScalars(numpy_support.numpy_to_vtk(vol.ravel(), deep=True))
fe = vtk.vtkFlyingEdges3D(); fe.SetInputData(img); fe.SetValue(0, level)
fe.SetComputeNormals(True); fe.SetComputeGradients(False); fe.SetComputeScalars(False)
w = vtk.vtkPLYWriter(); w.SetInputConnection(fe.GetOutputPort()); w.SetFileName(out)
w.SetFileTypeToBinary(); w.Write()
print(json.dumps({"wall": time.perf_counter() - t, "cpu": time.process_time() - c,
                  "triangles": fe.GetOutput().GetNumberOfCells()}))
"""


def make_volumes(d):
    n = 256
    hdr = "NRRD0004\ntype: {t}\ndimension: 3\nsizes: {s}\nspacings: {sp}\nencoding: raw\n{e}data file: {f}\n"
    if not os.path.exists(os.path.join(d, "gyroid256.raw")):
        t = np.linspace(0, 6 * np.pi, n)
        z, y, x = np.meshgrid(t, t, t, indexing="ij")
        g = np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)
        g.astype("<f4").tofile(os.path.join(d, "gyroid256.raw"))
        s = np.linspace(-1, 1, n)
        z, y, x = np.meshgrid(s, s, s, indexing="ij")
        r = np.sqrt(x * x + y * y + z * z)
        b = r - 0.7 - 0.06 * np.sin(9 * x) * np.sin(9 * y) * np.sin(9 * z)
        b.astype("<f4").tofile(os.path.join(d, "bumpy256.raw"))
        for name in ("gyroid256", "bumpy256"):
            open(os.path.join(d, name + ".nhdr"), "w").write(hdr.format(
                t="float", s="256 256 256", sp="1 1 1", e="endian: little\n", f=name + ".raw"))
    if not os.path.exists(os.path.join(d, "cthead.raw")):
        src = "/work/shared/data/volumes/cthead_8bit_256x256x99.raw.gz"
        open(os.path.join(d, "cthead.raw"), "wb").write(gzip.open(src).read())
        open(os.path.join(d, "cthead.nhdr"), "w").write(hdr.format(
            t="uint8", s="256 256 99", sp="1 1 2", e="", f="cthead.raw"))


def run_morpho(label, binary, d, name, hdr, level, tmp):
    out, rep = os.path.join(tmp, name + ".ply"), os.path.join(tmp, name + ".json")
    cmd = ["/usr/bin/time", "-f", "time %U %S %e %M", "perf", "stat", "-x,", "-e",
           "task-clock,page-faults", "--", binary, "--report", rep, "isosurface",
           os.path.join(d, hdr), "--level", str(level), "-o", out, "--serial"]
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    lines = p.stderr.strip().splitlines()
    u, s, e, m = next(l for l in lines if l.startswith("time ")).split()[1:]
    stat = {l.split(",")[2]: float(l.split(",")[0]) for l in lines if l.count(",") >= 3}
    r = json.load(open(rep))
    return {"tool": label, "vol": name, "cpu": stat["task-clock"] / 1e3,
            "cpu_time_10ms": float(u) + float(s), "page_faults": int(stat["page-faults"]),
            "wall": float(e), "rss_mb": int(m) / 1024, "stages": r.get("timings"),
            "triangles": r.get("triangles"), "ply_bytes": os.path.getsize(out),
            "io": r.get("io")}


def run_vtk(d, name, dims, dt, level):
    raw = os.path.join(d, name + ".raw")
    p = subprocess.run([sys.executable, "-c", VTK, raw, *map(str, dims), dt, str(level)],
                       capture_output=True, text=True, check=True)
    rows = [json.loads(l) for l in p.stdout.splitlines()]
    return [{"tool": f"vtk_fe_normals={r['normals']}", "vol": name, "cpu": r["cpu"],
             "wall": r["wall"], "triangles": r["triangles"]} for r in rows]


def run_vtk_pipeline(d, name, dims, dt, level, tmp):
    raw, out = os.path.join(d, name + ".raw"), os.path.join(tmp, name + "_vtk.ply")
    cmd = ["perf", "stat", "-x,", "-e", "task-clock", "--", sys.executable, "-c", VTK_PIPELINE,
           raw, *map(str, dims), dt, str(level), out]
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    r = json.loads(p.stdout.splitlines()[-1])
    stat = {l.split(",")[2]: float(l.split(",")[0])
            for l in p.stderr.strip().splitlines() if l.count(",") >= 3}
    row = {"tool": "vtk_pipeline", "vol": name, "cpu": r["cpu"], "wall": r["wall"],
           "process_cpu": stat["task-clock"] / 1e3, "triangles": r["triangles"],
           "ply_bytes": os.path.getsize(out)}
    os.remove(out)
    return [row]


def bandwidth():
    a = np.ones(64 << 20, dtype=np.uint8)
    b = np.empty_like(a)
    best = float("inf")
    for _ in range(5):
        t = time.perf_counter()
        np.copyto(b, a)
        best = min(best, time.perf_counter() - t)
    return a.nbytes / best  # bytes copied per second (read + write of each byte)


def main():
    bins = [b.split("=", 1) if "=" in b else ("morpho", b) for b in sys.argv[1].split(",")]
    d = sys.argv[2]
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    make_volumes(d)
    load0 = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(rounds):
            for name, hdr, level, dims, dt in VOLS:
                runs = [run_morpho(lb, b, d, name, hdr, level, tmp) for lb, b in bins]
                vtk_rows = run_vtk(d, name, dims, dt, level)
                vtk_rows += run_vtk_pipeline(d, name, dims, dt, level, tmp)
                for r in runs + vtk_rows:
                    r["round"] = k
                    print(json.dumps(r), flush=True)
                    rows.append(r)
    load1 = os.getloadavg()
    bw = bandwidth()
    print(json.dumps({"load_before": load0, "load_after": load1, "copy_GB_s": bw / 1e9}))
    for name, hdr, level, dims, dt in VOLS:
        v = [r for r in rows if r["vol"] == name and r["tool"] == "vtk_fe_normals=True"]
        vn = [r for r in rows if r["vol"] == name and r["tool"] == "vtk_fe_normals=False"]
        vcpu = min(r["cpu"] for r in v)
        vp = [r for r in rows if r["vol"] == name and r["tool"] == "vtk_pipeline"]
        pcpu = min(r["cpu"] for r in vp)
        print(json.dumps({"vol": name, "tool": "vtk_pipeline", "cpu_min": pcpu,
                          "process_cpu_min": min(r["process_cpu"] for r in vp),
                          "ply_mb": vp[0]["ply_bytes"] / 1e6}))
        vol_bytes = os.path.getsize(os.path.join(d, name + ".raw"))
        for label, _ in bins:
            m = [r for r in rows if r["vol"] == name and r["tool"] == label]
            cpu = min(r["cpu"] for r in m)
            floor = (vol_bytes + m[0]["ply_bytes"]) / bw
            stage = {k: min(r["stages"][k] for r in m) for k in m[0]["stages"]}
            print(json.dumps({
                "vol": name, "tool": label, "triangles": m[0]["triangles"],
                "cpu_min": cpu, "wall_min": min(r["wall"] for r in m),
                "stage_wall_min": stage, "rss_mb_max": max(r["rss_mb"] for r in m),
                "page_faults": m[0]["page_faults"],
                "vtk_normals_cpu_min": vcpu, "vtk_nonormals_cpu_min": min(r["cpu"] for r in vn),
                "ratio_cpu_vs_vtk_normals": cpu / vcpu, "vtk_pipeline_cpu_min": pcpu,
                "ratio_cpu_vs_vtk_pipeline": cpu / pcpu, "rw_floor_s": floor,
                "cpu_over_rw_floor": cpu / floor,
                "volume_f32_mb": float(np.prod(dims)) * 4 / 1e6, "ply_mb": m[0]["ply_bytes"] / 1e6}))


if __name__ == "__main__":
    main()
