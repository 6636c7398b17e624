#!/usr/bin/env bash
# Side-by-side 2D Delaunay timings on the same inputs: morpho vs the delaunator and spade crates
# (Rust, same process), and scipy.spatial.Delaunay (Qhull) / CGAL's Python bindings when
# installable. Prints seconds and ratios to delaunator. Single thread.
#
#   bench/run.sh [N]        (default N = 1000000; uniform random points and a √N×√N grid)
#
# Set NO_PIP=1 to skip the pip installs.
set -euo pipefail
N="${1:-1000000}"
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
export RAYON_NUM_THREADS=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

cd "$ROOT"
cargo run --quiet --release --example bench_delaunay2d -p morpho -- "$N" \
    --write-points "$TMP/uniform.f64" | tee "$TMP/rust.txt"

base_u="$(awk '$1=="uniform" && $2=="delaunator" {print $3 "," $8}' "$TMP/rust.txt")"
base_g="$(awk '$1=="grid" && $2=="delaunator" {print $3 "," $8}' "$TMP/rust.txt")"

PY="${PYTHON:-python3}"
if [ -z "${NO_PIP:-}" ]; then
    "$PY" -c 'import scipy' 2>/dev/null || "$PY" -m pip install --quiet scipy >/dev/null 2>&1 || true
    "$PY" -c 'import CGAL' 2>/dev/null || "$PY" -m pip install --quiet cgal >/dev/null 2>&1 || true
fi

"$PY" - "$TMP/uniform.f64" "$N" "$base_u" "$base_g" <<'PYEOF'
import sys, time
path, n = sys.argv[1], int(sys.argv[2])
base_u = [float(v) for v in sys.argv[3].split(",")]  # delaunator wall, cpu
base_g = [float(v) for v in sys.argv[4].split(",")]

def ratio(a, b):
    return a / b if b > 0 else float("nan")

def report(name, lib, wall, cpu, base, tris):
    print(f"{name:8} {lib:10} {wall:8.3f} s  ratio {ratio(wall, base[0]):.3f}  cpu {cpu:7.2f} s"
          f"  cpu-ratio {ratio(cpu, base[1]):.3f}  triangles {tris}")

try:
    import numpy as np
except ImportError:
    print("# numpy not available: skipping the Python peers")
    sys.exit(0)
uni = np.fromfile(path, dtype="<f8").reshape(-1, 2)
side = int(round(n ** 0.5))
k = np.arange(side * side)
grid = np.stack([(k % side).astype(float), (k // side).astype(float)], axis=1)
inputs = [("uniform", uni, base_u), ("grid", grid, base_g)]
try:
    from scipy.spatial import Delaunay
    for name, p, base in inputs:
        t, c = time.perf_counter(), time.process_time()
        d = Delaunay(p)
        report(name, "scipy", time.perf_counter() - t, time.process_time() - c, base,
               len(d.simplices))
except ImportError:
    print("# scipy not installable here: no Qhull comparison")
try:
    from CGAL.CGAL_Kernel import Point_2
    from CGAL.CGAL_Triangulation_2 import Delaunay_triangulation_2
    for name, p, base in inputs:
        pts = [Point_2(float(x), float(y)) for x, y in p]
        t, c = time.perf_counter(), time.process_time()
        dt = Delaunay_triangulation_2()
        dt.insert(pts)
        report(name, "cgal", time.perf_counter() - t, time.process_time() - c, base,
               dt.number_of_faces())
except ImportError:
    print("# CGAL Python bindings not installable here: no CGAL comparison")
PYEOF
