#!/usr/bin/env python3
"""Points sampled on the Stanford dragon, for the 3D boundary's scaling cliff (issue 17 item 9).

The full dragon scan (437,645 points) is not in ../shared/data; this samples N points uniformly by
area on the triangles of ../shared/data/meshes/dragon_vrip_res4.obj (seeded, no noise), which has
the same thin parts. Measured on 2026-12-04 (2 cores, main at fa19a6e):

    N        triangulate   boundary   ratio   points off   load
    100000   0.66 s        1.60 s     2.4x    0            ~1
    437645   3.24 s        33.5 s     10.3x   13           ~1   (another seed of the same sampler)
    437645   3.92 s        169 s      43x     8            ~4.7 (this script; peak RSS 1.97 GB)

At 437,645 points the Delaunay constriction locks, the local general engine (tetrahedra within 4
steps of the points off the boundary) does not free them, and the global general engine (3.3 M
live faces) runs for minutes without freeing them either (regions of depth 8 and 16 were tried:
24 s and 33 s, no point freed). Profile (perf, DWARF): ~80 % in the general engine, chiefly
push_all's per-face verdicts (best_plain, combinatorial, unchanged_lock, lock_box) and
gamma_decide; 8 % page faults.

After commit 417959f (insertion of the last vertices, bench/README.md "Dragon"): 437,645 points
all on a closed genus-0 surface, 55.6 s vs 5.77 s triangulate = 9.6x at load ~11.

usage: python3 bench/dragon_points.py N OUT.xyz
"""
import bisect
import math
import random
import sys
from pathlib import Path

def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    here = Path(__file__).resolve().parent
    rel = "shared/data/meshes/dragon_vrip_res4.obj"
    # the repository may be a worktree one or two levels below the folder holding shared/
    src = next((d / rel for d in here.parents if (d / rel).is_file()), here.parent.parent / rel)
    v, f = [], []
    for line in open(src):
        s = line.split()
        if not s:
            continue
        if s[0] == "v":
            v.append(tuple(map(float, s[1:4])))
        elif s[0] == "f":
            f.append(tuple(int(x.split("/")[0]) - 1 for x in s[1:4]))
    acc, total = [], 0.0
    for a, b, c in f:
        p, q, r = v[a], v[b], v[c]
        u = [q[i] - p[i] for i in range(3)]
        w = [r[i] - p[i] for i in range(3)]
        x = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        total += math.sqrt(sum(t * t for t in x)) / 2
        acc.append(total)
    rng = random.Random(7)
    rows = []
    for _ in range(n):
        t = min(bisect.bisect_left(acc, rng.random() * total), len(f) - 1)
        a, b, c = f[t]
        s1, s2 = rng.random(), rng.random()
        if s1 + s2 > 1:
            s1, s2 = 1 - s1, 1 - s2
        p = [v[a][i] + s1 * (v[b][i] - v[a][i]) + s2 * (v[c][i] - v[a][i]) for i in range(3)]
        rows.append("%.7f %.7f %.7f\n" % tuple(p))
    Path(out).write_text("".join(rows))

if __name__ == "__main__":
    main()
