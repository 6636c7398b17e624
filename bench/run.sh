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

base_u="$(awk '$1=="uniform" && $2=="delaunator" {print $3}' "$TMP/rust.txt")"
base_g="$(awk '$1=="grid" && $2=="delaunator" {print $3}' "$TMP/rust.txt")"

PY="${PYTHON:-python3}"
if [ -z "${NO_PIP:-}" ]; then
    "$PY" -c 'import scipy' 2>/dev/null || "$PY" -m pip install --quiet scipy >/dev/null 2>&1 || true
    "$PY" -c 'import CGAL' 2>/dev/null || "$PY" -m pip install --quiet cgal >/dev/null 2>&1 || true
fi

"$PY" - "$TMP/uniform.f64" "$N" "$base_u" "$base_g" <<'PYEOF'
import sys, time
path, n, base_u, base_g = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
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
        t = time.perf_counter()
        d = Delaunay(p)
        s = time.perf_counter() - t
        print(f"{name:8} scipy      {s:8.3f} s  ratio {s / base:.3f}  triangles {len(d.simplices)}")
except ImportError:
    print("# scipy not installable here: no Qhull comparison")
try:
    from CGAL.CGAL_Kernel import Point_2
    from CGAL.CGAL_Triangulation_2 import Delaunay_triangulation_2
    for name, p, base in inputs:
        pts = [Point_2(float(x), float(y)) for x, y in p]
        t = time.perf_counter()
        dt = Delaunay_triangulation_2()
        dt.insert(pts)
        s = time.perf_counter() - t
        print(f"{name:8} cgal       {s:8.3f} s  ratio {s / base:.3f}  triangles {dt.number_of_faces()}")
except ImportError:
    print("# CGAL Python bindings not installable here: no CGAL comparison")
PYEOF
