#!/usr/bin/env python3
"""Surface curvature against libigl and VTK, same meshes, same run (issue 20).

Usage (from the repository root; the peers come from PyPI):
    python3 -m venv /tmp/benchenv
    /tmp/benchenv/bin/pip install libigl vtk scipy numpy
    cargo build --release -p morpho-cli
    /tmp/benchenv/bin/python bench/curvature_peers.py accuracy [--variants default,thesis]
    /tmp/benchenv/bin/python bench/curvature_peers.py slopes
    /tmp/benchenv/bin/python bench/curvature_peers.py speed [--rounds 3]

accuracy — every mesh has *estimated* normals only (positions and triangles, nothing else) and
exact analytic curvature at its vertices (they lie on the surface):
  * torus (R 2, r 1) on a regular 40×120 parameter grid (40 around the tube); the same torus tessellated irregularly
    (parameter points jittered by ±0.35 cell, each quad split along a random diagonal);
  * an ellipsoid (1.5, 1, 0.6) from 4000 Fibonacci points on the sphere (convex hull), scaled;
  * a sphere (R 1) tessellated irregularly: 4000 uniform random points and their convex hull
    (no minimum spacing: slivers included);
  * the 8 curved surfaces of H Table 4.1 on the 51×51 grid over [-1,1]² (the thesis's grid,
    but *estimated* normals here; the table itself used exact ones).
Truth from the implicit form F = 0 (graphs: F = z − f): K = ∇Fᵀ adj(∇²F) ∇F / |∇F|⁴,
H = (∇Fᵀ ∇²F ∇F − |∇F|² tr ∇²F) / (2|∇F|³) (Goldman 2005), along the normal ∇F/|∇F|: an
outward sphere has H = −1/R, as in morpho. Each tool's H is multiplied by the sign that makes
Σ H·H_exact ≥ 0 (the conventions differ; K has no sign ambiguity); the sign used is printed.
Errors over the interior vertices (open meshes: more than 2 edges from the boundary) where every
tool returned a finite value; also RMS over all its finite vertices. The relative error of a
vertex is |x − x_ex| / max(|x_ex|, 0.1·rms(x_ex)) (the floor keeps saddles' zero crossings from
dominating); median over the vertices.
Tools: morpho `morpho curvature IN.ply -o OUT.csv` (variants below), libigl
`igl.principal_curvature(V, F)` (its defaults: radius 5, k-ring), VTK `vtkCurvatures` mean and
Gaussian (the discrete operators). Variants: `default` (the CLI default, `--fit jet`: the jet of
degree 4 (else 3) over the 2-ring in the frame of the area normal, its points weighted by
1/(0.1 + r²/ρ²)⁴ since branch `tor`, curvature of the jet at the vertex),
`jetparab` (`--fit paraboloid`: the previous default, area normals corrected by the cubic jet,
then the thesis's 1-ring paraboloid), `thesis` (`--normals area`: the 1-ring paraboloid with
area-weighted normals, H §4.2), `quadric` (`--normals area --fit quadric`: linear terms over
the 2-ring), `jetquadric` (`--fit quadric`), `jet3` (`--fit jet --ring 3`).

slopes — morpho's default on refined meshes (regular torus, jittered torus, Table 4.1 row 8,
random sphere): interior RMS of H and K against the mean edge length h, and the least-squares
slope of log error against log h (2 = O(h²)).

speed — the CT head's bone surface (`morpho isosurface cthead level 120`, ~500k vertices),
alternately: morpho 1 thread (RAYON_NUM_THREADS=1), morpho 2 threads, VTK mean + Gaussian (one
process each under /usr/bin/time: wall, CPU, peak RSS; plus the compute time alone: morpho's
report `timings.compute`, VTK's two Update() calls), the 1-minute load average before each.
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
MORPHO = os.environ.get("MORPHO", os.path.join(ROOT, "target", "release", "morpho"))

VARIANTS = {
    "default": [],
    "jetparab": ["--fit", "paraboloid"],
    "jet3": ["--fit", "jet", "--ring", "3"],
    "thesis": ["--normals", "area"],
    "quadric": ["--normals", "area", "--fit", "quadric"],
    "jetquadric": ["--fit", "quadric"],
}


def loadavg():
    return os.getloadavg()[0]


# ---------------------------------------------------------------- meshes and exact curvature


def implicit_curvature(grad, hess):
    """H (along ∇F/|∇F|) and K of the implicit surface F = 0 from ∇F (n×3) and ∇²F (n×3×3)."""
    g2 = np.einsum("ni,ni->n", grad, grad)
    gn = np.sqrt(g2)
    ghg = np.einsum("ni,nij,nj->n", grad, hess, grad)
    tr = np.trace(hess, axis1=1, axis2=2)
    h = (ghg - g2 * tr) / (2 * gn**3)
    adj = np.empty_like(hess)
    for i in range(3):
        for j in range(3):
            r = [k for k in range(3) if k != j]
            c = [k for k in range(3) if k != i]
            minor = hess[:, r][:, :, c]
            adj[:, i, j] = (-1) ** (i + j) * (minor[:, 0, 0] * minor[:, 1, 1] - minor[:, 0, 1] * minor[:, 1, 0])
    k = np.einsum("ni,nij,nj->n", grad, adj, grad) / g2**2
    return h, k


def torus_exact(v, R=2.0, r=1.0):
    s = np.einsum("ni,ni->n", v, v) + R * R - r * r
    grad = 4 * s[:, None] * v
    grad[:, :2] -= 8 * R * R * v[:, :2]
    hess = 8 * np.einsum("ni,nj->nij", v, v) + 4 * s[:, None, None] * np.eye(3)[None]
    hess[:, 0, 0] -= 8 * R * R
    hess[:, 1, 1] -= 8 * R * R
    return implicit_curvature(grad, hess)


def torus_mesh(nu, nv, R=2.0, r=1.0, jitter=0.0, seed=0):
    """(u around the tube, v around the axis); outward; jittered parameters, random diagonals."""
    rng = np.random.default_rng(seed)
    iu, iv = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    u = (iu + jitter * rng.uniform(-1, 1, iu.shape)) * 2 * np.pi / nu
    w = (iv + jitter * rng.uniform(-1, 1, iv.shape)) * 2 * np.pi / nv
    x = np.stack([(R + r * np.cos(u)) * np.cos(w), (R + r * np.cos(u)) * np.sin(w), r * np.sin(u)], -1)
    idx = lambda a, b: (a % nu) * nv + (b % nv)
    faces = []
    flip = rng.integers(0, 2, (nu, nv)) if jitter > 0 else np.zeros((nu, nv), int)
    for a in range(nu):
        for b in range(nv):
            p, q, s_, t = idx(a, b), idx(a + 1, b), idx(a + 1, b + 1), idx(a, b + 1)
            if flip[a, b]:
                faces += [[p, t, q], [q, t, s_]]
            else:
                faces += [[p, s_, q], [p, t, s_]]
    v = x.reshape(-1, 3)
    f = np.array(faces, dtype=np.int64)
    return orient_outward(v, f)


def orient_outward(v, f):
    """Flip every triangle if the signed volume is negative (closed meshes)."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol = np.einsum("ni,ni->n", a, np.cross(b, c)).sum()
    return (v, f[:, ::-1].copy()) if vol < 0 else (v, f)


def hull_mesh(p):
    """Convex hull of points on a sphere around the origin, every triangle turned outward
    (Qhull's simplices are not consistently oriented)."""
    from scipy.spatial import ConvexHull

    f = ConvexHull(p).simplices.astype(np.int64)
    a, b, c = p[f[:, 0]], p[f[:, 1]], p[f[:, 2]]
    inward = np.einsum("ni,ni->n", np.cross(b - a, c - a), a + b + c) < 0
    f[inward] = f[inward][:, ::-1]
    return p, f


def fibonacci_sphere(n):
    i = np.arange(n) + 0.5
    phi = np.arccos(1 - 2 * i / n)
    th = np.pi * (1 + 5**0.5) * i
    return np.stack([np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)], -1)


def random_sphere(n, seed=1):
    p = np.random.default_rng(seed).normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None]


def ellipsoid_exact(v, ax):
    a2 = np.array(ax) ** 2
    grad = 2 * v / a2
    hess = np.repeat(np.diag(2 / a2)[None], len(v), 0)
    return implicit_curvature(grad, hess)


def sphere_exact(v):
    return ellipsoid_exact(v, (1.0, 1.0, 1.0))


# H Table 4.1 rows 2-9: (name, f, fx, fy, fxx, fxy, fyy)
PI = np.pi
T41 = [
    ("cylinder", lambda x, y: np.sqrt(2 - x * x), lambda x, y: -x / np.sqrt(2 - x * x), lambda x, y: 0 * x,
     lambda x, y: -2 / (2 - x * x) ** 1.5, lambda x, y: 0 * x, lambda x, y: 0 * x),
    ("sphere4", lambda x, y: np.sqrt(4 - x * x - y * y), lambda x, y: -x / np.sqrt(4 - x * x - y * y),
     lambda x, y: -y / np.sqrt(4 - x * x - y * y), lambda x, y: -(4 - y * y) / (4 - x * x - y * y) ** 1.5,
     lambda x, y: -x * y / (4 - x * x - y * y) ** 1.5, lambda x, y: -(4 - x * x) / (4 - x * x - y * y) ** 1.5),
    ("paraboloid", lambda x, y: .4 * (x * x + y * y), lambda x, y: .8 * x, lambda x, y: .8 * y,
     lambda x, y: .8 + 0 * x, lambda x, y: 0 * x, lambda x, y: .8 + 0 * x),
    ("hyperboloid", lambda x, y: .4 * (x * x - y * y), lambda x, y: .8 * x, lambda x, y: -.8 * y,
     lambda x, y: .8 + 0 * x, lambda x, y: 0 * x, lambda x, y: -.8 + 0 * x),
    ("monkey", lambda x, y: .2 * (x**3 - 3 * x * y * y), lambda x, y: .6 * (x * x - y * y), lambda x, y: -1.2 * x * y,
     lambda x, y: 1.2 * x, lambda x, y: -1.2 * y, lambda x, y: -1.2 * x),
    ("cubic", lambda x, y: .15 * (x**3 + 2 * x * x * y - x * y + 2 * y * y),
     lambda x, y: .15 * (3 * x * x + 4 * x * y - y), lambda x, y: .15 * (2 * x * x - x + 4 * y),
     lambda x, y: .15 * (6 * x + 4 * y), lambda x, y: .15 * (4 * x - 1), lambda x, y: .6 + 0 * x),
    ("exponential", lambda x, y: np.exp(-(x * x + y * y) / 2), lambda x, y: -x * np.exp(-(x * x + y * y) / 2),
     lambda x, y: -y * np.exp(-(x * x + y * y) / 2), lambda x, y: (x * x - 1) * np.exp(-(x * x + y * y) / 2),
     lambda x, y: x * y * np.exp(-(x * x + y * y) / 2), lambda x, y: (y * y - 1) * np.exp(-(x * x + y * y) / 2)),
    ("trig", lambda x, y: .1 * (np.cos(PI * x) + np.cos(PI * y)), lambda x, y: -.1 * PI * np.sin(PI * x),
     lambda x, y: -.1 * PI * np.sin(PI * y), lambda x, y: -.1 * PI * PI * np.cos(PI * x), lambda x, y: 0 * x,
     lambda x, y: -.1 * PI * PI * np.cos(PI * y)),
]


def graph_mesh(fn, m):
    """H Table 4.1's grid: m×m over [-1,1]², quads split along (i,j)–(i+1,j+1), upward."""
    t = np.linspace(-1, 1, m)
    x, y = np.meshgrid(t, t, indexing="xy")
    x, y = x.ravel(), y.ravel()
    v = np.stack([x, y, fn[1](x, y)], -1)
    faces = []
    for j in range(m - 1):
        for i in range(m - 1):
            a, b, c, d = i + m * j, i + 1 + m * j, i + 1 + m * (j + 1), i + m * (j + 1)
            faces += [[a, b, c], [a, c, d]]
    return v, np.array(faces, dtype=np.int64)


def graph_exact(fn, v):
    x, y = v[:, 0], v[:, 1]
    fx, fy, fxx, fxy, fyy = (g(x, y) for g in fn[2:])
    grad = np.stack([-fx, -fy, np.ones_like(x)], -1)
    hess = np.zeros((len(x), 3, 3))
    hess[:, 0, 0], hess[:, 0, 1], hess[:, 1, 0], hess[:, 1, 1] = -fxx, -fxy, -fxy, -fyy
    return implicit_curvature(grad, hess)


def accuracy_meshes():
    out = []
    v, f = torus_mesh(40, 120)
    out.append(("torus 40x120", v, f, torus_exact(v)))
    v, f = torus_mesh(40, 120, jitter=0.35, seed=7)
    out.append(("torus jittered", v, f, torus_exact(v)))
    ax = (1.5, 1.0, 0.6)
    v, f = hull_mesh(fibonacci_sphere(4000))
    v = v * np.array(ax)
    out.append(("ellipsoid", v, f, ellipsoid_exact(v, ax)))
    v, f = hull_mesh(random_sphere(4000))
    out.append(("sphere random", v, f, sphere_exact(v)))
    for fn in T41:
        v, f = graph_mesh(fn, 51)
        out.append((f"T4.1 {fn[0]}", v, f, graph_exact(fn, v)))
    return out


# ---------------------------------------------------------------- tools


def write_ply(path, v, f):
    v = np.ascontiguousarray(v, dtype="<f8")
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


def read_csv_columns(path, names):
    with open(path) as fh:
        head = fh.readline().strip().split(",")
        idx = [head.index(n) for n in names]
        rows = [line.rstrip("\n").split(",") for line in fh]
    return [np.array([float(r[i]) if r[i] != "" else np.nan for r in rows]) for i in idx]


def run_morpho(tmp, v, f, extra, threads=None):
    inp, out, rep = (os.path.join(tmp, n) for n in ("in.ply", "out.csv", "r.json"))
    write_ply(inp, v, f)
    env = dict(os.environ)
    if threads:
        env["RAYON_NUM_THREADS"] = str(threads)
    t = time.perf_counter()
    r = subprocess.run([MORPHO, "curvature", inp, "-o", out, "--report", rep] + extra,
                       capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    h, k = read_csv_columns(out, ["H", "K"])
    compute = json.load(open(rep)).get("timings", {}).get("compute")
    return h, k, compute or wall


def run_igl(v, f):
    import igl

    t = time.perf_counter()
    res = igl.principal_curvature(np.ascontiguousarray(v), np.ascontiguousarray(f))
    dt = time.perf_counter() - t
    pv1, pv2 = res[2], res[3]
    h, k = 0.5 * (pv1 + pv2), pv1 * pv2
    if len(res) > 4 and len(res[4]):
        h[np.asarray(res[4])] = np.nan
        k[np.asarray(res[4])] = np.nan
    return h, k, dt


def vtk_polydata(v, f):
    import vtk
    from vtk.util import numpy_support as ns

    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(np.ascontiguousarray(v, dtype=np.float64), deep=True))
    cells = vtk.vtkCellArray()
    off = np.arange(0, 3 * len(f) + 1, 3, dtype=np.int64)
    cells.SetData(ns.numpy_to_vtkIdTypeArray(off, deep=True),
                  ns.numpy_to_vtkIdTypeArray(np.ascontiguousarray(f.ravel(), dtype=np.int64), deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    pd.SetPolys(cells)
    return pd


def run_vtk(v, f):
    import vtk
    from vtk.util import numpy_support as ns

    pd = vtk_polydata(v, f)
    out = []
    t = time.perf_counter()
    for kind in ("mean", "gauss"):
        c = vtk.vtkCurvatures()
        c.SetInputData(pd)
        if kind == "mean":
            c.SetCurvatureTypeToMean()
        else:
            c.SetCurvatureTypeToGaussian()
        c.Update()
        name = "Mean_Curvature" if kind == "mean" else "Gauss_Curvature"
        out.append(ns.vtk_to_numpy(c.GetOutput().GetPointData().GetArray(name)).astype(np.float64))
    dt = time.perf_counter() - t
    return out[0], out[1], dt


# ---------------------------------------------------------------- errors


def interior_mask(nv, f, rings=2):
    """Vertices more than `rings` edges from a boundary edge (all of them on closed meshes)."""
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    u, cnt = np.unique(e, axis=0, return_counts=True)
    near = np.zeros(nv, bool)
    near[u[cnt == 1].ravel()] = True
    for _ in range(rings):
        hit = near[u[:, 0]] | near[u[:, 1]]
        near[u[hit].ravel()] = True
    return ~near


def errors(app, ex, mask):
    d = app[mask] - ex[mask]
    e = ex[mask]
    scale = 0.1 * np.sqrt(np.mean(e * e))
    rel = np.abs(d) / np.maximum(np.abs(e), scale) if scale > 0 else np.abs(d)
    return float(np.sqrt(np.mean(d * d))), float(np.median(rel))


def accuracy(args):
    variants = args.variants.split(",")
    tools = [f"morpho:{x}" for x in variants] + ["libigl", "vtk"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, v, f, (hx, kx) in accuracy_meshes():
            res = {}
            for t in tools:
                if t.startswith("morpho"):
                    res[t] = run_morpho(tmp, v, f, VARIANTS[t.split(":")[1]])
                elif t == "libigl":
                    res[t] = run_igl(v, f)
                else:
                    res[t] = run_vtk(v, f)
            inner = interior_mask(len(v), f)
            ok = inner.copy()
            for h, k, _ in res.values():
                ok &= np.isfinite(h) & np.isfinite(k)
            row = {"mesh": name, "vertices": len(v), "evaluated": int(ok.sum()), "load": loadavg()}
            for t, (h, k, dt) in res.items():
                fin = np.isfinite(h) & np.isfinite(k)
                s = 1.0 if np.nansum(h[fin] * hx[fin]) >= 0 else -1.0
                h = s * h
                rh, mh = errors(h, hx, ok)
                rk, mk = errors(k, kx, ok)
                rha, _ = errors(h, hx, fin)
                rka, _ = errors(k, kx, fin)
                row[t] = {"sign": s, "rmsH": rh, "medH": mh, "rmsK": rk, "medK": mk, "rmsH_all": rha,
                          "rmsK_all": rka, "seconds": dt, "nonfinite": int((~fin).sum())}
            rows.append(row)
            print(json.dumps(row), flush=True)
    print_accuracy(rows, tools)


def print_accuracy(rows, tools):
    m = [t for t in tools if t.startswith("morpho")]
    print("\nInterior vertices, estimated normals. RMS and median relative error; ratios morpho/peer "
          "(< 1: morpho more accurate).\n")
    for mt in m:
        print(f"### {mt}\n")
        print("| mesh | V | quantity | morpho RMS | libigl RMS | VTK RMS | morpho/libigl | morpho/VTK "
              "| morpho med rel | libigl med rel | VTK med rel | morpho/libigl | morpho/VTK |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            for q in ("H", "K"):
                a, b, c = r[mt], r["libigl"], r["vtk"]
                rm, rb, rc = a["rms" + q], b["rms" + q], c["rms" + q]
                mm, mb, mc = a["med" + q], b["med" + q], c["med" + q]
                print(f"| {r['mesh']} | {r['vertices']} | {q} | {rm:.2e} | {rb:.2e} | {rc:.2e} | "
                      f"**{rm / rb:.2f}** | **{rm / rc:.2f}** | {mm:.2e} | {mb:.2e} | {mc:.2e} | "
                      f"**{mm / mb:.2f}** | **{mm / mc:.2f}** |")
        print()
    wins = {mt: [0, 0] for mt in m}
    for mt in m:
        for r in rows:
            for q in ("H", "K"):
                for peer in ("libigl", "vtk"):
                    for kind in ("rms", "med"):
                        wins[mt][1] += 1
                        wins[mt][0] += r[mt][kind + q] <= r[peer][kind + q]
        print(f"{mt}: ≤ peer in {wins[mt][0]} of {wins[mt][1]} comparisons")
    print("\nAll finite vertices (boundary included), RMS of H / K:\n")
    print("| mesh | " + " | ".join(tools) + " |")
    print("|---|" + "---|" * len(tools))
    for r in rows:
        print(f"| {r['mesh']} | " + " | ".join(f"{r[t]['rmsH_all']:.2e} / {r[t]['rmsK_all']:.2e}"
                                                 for t in tools) + " |")
    print("\nSeconds per call (this run, load average %.1f):" % loadavg())
    for r in rows:
        print(f"  {r['mesh']}: " + ", ".join(f"{t} {r[t]['seconds']:.3f}" for t in tools))


# ---------------------------------------------------------------- slopes


def slopes(args):
    extra = VARIANTS[args.slope_variant]
    series = {
        "torus regular": [torus_mesh(n, 3 * n) for n in (10, 20, 40, 80)],
        "torus jittered": [torus_mesh(n, 3 * n, jitter=0.35, seed=7) for n in (10, 20, 40, 80)],
        "T4.1 exponential": [graph_mesh(T41[6], m) for m in (26, 51, 101, 201)],
        "sphere random": [hull_mesh(random_sphere(n)) for n in (1000, 4000, 16000, 64000)],
    }
    exact = {
        "torus regular": torus_exact,
        "torus jittered": torus_exact,
        "T4.1 exponential": lambda v: graph_exact(T41[6], v),
        "sphere random": sphere_exact,
    }
    print(f"morpho {args.slope_variant} ({' '.join(extra) or 'CLI default'}), interior RMS vs mean edge length h")
    with tempfile.TemporaryDirectory() as tmp:
        for name, meshes in series.items():
            hs, eh, ek = [], [], []
            for v, f in meshes:
                hx, kx = exact[name](v)
                h, k, _ = run_morpho(tmp, v, f, extra)
                e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
                hmean = float(np.mean(np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)))
                ok = interior_mask(len(v), f) & np.isfinite(h)
                hs.append(hmean)
                eh.append(errors(h, hx, ok)[0])
                ek.append(errors(k, kx, ok)[0])
                print(f"  {name}: V {len(v)}, h {hmean:.4f}: RMS H {eh[-1]:.3e}, K {ek[-1]:.3e}")
            sh = np.polyfit(np.log(hs), np.log(eh), 1)[0]
            sk = np.polyfit(np.log(hs), np.log(ek), 1)[0]
            print(f"{name}: slope H {sh:.2f}, K {sk:.2f}")


# ---------------------------------------------------------------- speed

VTK_CHILD = r"""
import sys, time, numpy as np
sys.path.insert(0, sys.argv[2])
from curvature_peers import vtk_polydata, read_ply_numpy
import vtk
v, f = read_ply_numpy(sys.argv[1])
pd = vtk_polydata(v, f)
t = time.perf_counter(); c0 = time.process_time()
for kind in ("mean", "gauss"):
    c = vtk.vtkCurvatures(); c.SetInputData(pd)
    (c.SetCurvatureTypeToMean if kind == "mean" else c.SetCurvatureTypeToGaussian)()
    c.Update()
print(time.perf_counter() - t, time.process_time() - c0)
"""


def read_ply_numpy(path):
    """The binary PLY written by `morpho isosurface` (double xyz, normals, triangles as uchar/int
    lists, a `part` face property); enough for this benchmark's inputs."""
    with open(path, "rb") as fh:
        head = b""
        while not head.endswith(b"end_header\n"):
            head += fh.readline()
        lines = head.decode().splitlines()
        nv = nf = 0
        vprops, fprops, cur = [], [], None
        for ln in lines:
            p = ln.split()
            if p[:2] == ["element", "vertex"]:
                nv, cur = int(p[2]), "v"
            elif p[:2] == ["element", "face"]:
                nf, cur = int(p[2]), "f"
            elif p and p[0] == "property" and cur == "v":
                vprops.append((p[2], {"double": "<f8", "float": "<f4", "float32": "<f4", "float64": "<f8",
                                      "uchar": "u1", "int": "<i4", "uint": "<u4"}[p[1]]))
            elif p[:3] == ["property", "list", "uchar"] and cur == "f":
                idx_t = {"int": "<i4", "uint": "<u4", "int32": "<i4", "uint32": "<u4"}[p[3]]
                fprops += [("n", "u1"), ("i", idx_t, (3,))]
            elif p and p[0] == "property" and cur == "f":
                fprops.append((p[2], {"uint": "<u4", "int": "<i4", "uchar": "u1", "float": "<f4",
                                      "double": "<f8"}[p[1]]))
        vd = np.frombuffer(fh.read(nv * np.dtype(vprops).itemsize), dtype=vprops)
        fd = np.frombuffer(fh.read(nf * np.dtype(fprops).itemsize), dtype=fprops)
    v = np.stack([vd["x"], vd["y"], vd["z"]], -1).astype(np.float64)
    return v, fd["i"].astype(np.int64)


def timed_process(cmd, env=None):
    r = subprocess.run(["/usr/bin/time", "-f", "%e %U %S %M"] + cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    wall, user, sys_, rss = r.stderr.strip().splitlines()[-1].split()
    return float(wall), float(user) + float(sys_), int(rss) / 1024.0, r.stdout


def speed(args):
    with tempfile.TemporaryDirectory() as tmp:
        skull = os.path.join(tmp, "skull.ply")
        vol = os.path.join(DATA, "volumes", "cthead_8bit_256x256x99.json")
        subprocess.run([MORPHO, "isosurface", vol, "--level", "120", "--method", args.iso_method,
                        "-o", skull], check=True, capture_output=True)
        v, f = read_ply_numpy(skull)
        print(f"skull: {len(v)} vertices, {len(f)} triangles (morpho isosurface level 120, "
              f"--method {args.iso_method})")
        child = os.path.join(tmp, "vtk_child.py")
        open(child, "w").write(VTK_CHILD)
        out = os.path.join(tmp, "c.ply")
        rep = os.path.join(tmp, "r.json")
        results = {}
        for rnd in range(args.rounds):
            for tool in ("morpho-1", "vtk", "morpho-2"):
                load = loadavg()
                if tool.startswith("morpho"):
                    env = dict(os.environ, RAYON_NUM_THREADS=tool[-1])
                    wall, cpu, rss, _ = timed_process([MORPHO, "curvature", skull, "-o", out, "--report", rep]
                                                      + VARIANTS[args.variant], env)
                    comp = json.load(open(rep))["timings"]["compute"]
                else:
                    env = dict(os.environ, OMP_NUM_THREADS="1")
                    wall, cpu, rss, so = timed_process([sys.executable, child, skull,
                                                        os.path.dirname(os.path.abspath(__file__))], env)
                    comp, comp_cpu = (float(x) for x in so.split()[:2])
                rec = {"round": rnd, "tool": tool, "compute_s": comp, "wall_s": wall, "cpu_s": cpu,
                       "rss_mb": rss, "load1": load}
                if tool == "vtk":
                    rec["compute_cpu_s"] = comp_cpu
                results.setdefault(tool, []).append(rec)
                print(json.dumps(rec), flush=True)
        print("\n| tool | compute s (best / median) | process wall s | process CPU s | peak RSS MB | load avg |")
        print("|---|---|---|---|---|---|")
        for tool, recs in results.items():
            c = sorted(r["compute_s"] for r in recs)
            b = min(recs, key=lambda r: r["compute_s"])
            loads = ", ".join("%.1f" % r["load1"] for r in recs)
            print(f"| {tool} | {c[0]:.3f} / {c[len(c) // 2]:.3f} | {b['wall_s']:.2f} | {b['cpu_s']:.2f} | "
                  f"{b['rss_mb']:.0f} | {loads} |")
        m1 = sorted(r["compute_s"] for r in results["morpho-1"])
        m2 = sorted(r["compute_s"] for r in results["morpho-2"])
        vt = sorted(r["compute_s"] for r in results["vtk"])
        print(f"\nbest compute: morpho 1 thread / VTK = {m1[0] / vt[0]:.2f}; "
              f"1 thread / 2 threads = {m1[0] / m2[0]:.2f}× (medians {m1[len(m1) // 2] / m2[len(m2) // 2]:.2f}×)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["accuracy", "slopes", "speed"])
    ap.add_argument("--variants", default="default,thesis")
    ap.add_argument("--slope-variant", default="default")
    ap.add_argument("--variant", default="default", help="morpho variant timed in `speed`")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--iso-method", default="decider", choices=["decider", "tetra"],
                    help="`morpho isosurface --method` of the skull timed in `speed`")
    args = ap.parse_args()
    {"accuracy": accuracy, "slopes": slopes, "speed": speed}[args.mode](args)


if __name__ == "__main__":
    main()
