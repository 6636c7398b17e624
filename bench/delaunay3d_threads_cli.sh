#!/bin/sh
# `morpho triangulate` on 3D points as users run it, one rayon thread against two, taking turns
# (issue 23 item 3): whole-process CPU (user, sys), wall, peak RSS (/usr/bin/time), the compute
# stage's wall time from --report, and the load average before each run. The points: 1M uniform
# in the unit cube and 100k on the unit sphere from the bench example (seed 1), as binary PLY:
#   cargo build --release -p morpho-cli -p morpho --example bench_delaunay3d
#   target/release/examples/bench_delaunay3d 1000000 --engine seq --write /tmp/p3u1m.f64
#   target/release/examples/bench_delaunay3d 100000 --sphere --engine seq --write /tmp/p3s100k.f64
#   (then write each .f64 as a PLY with one `double x, y, z` vertex element, e.g. with numpy)
# Usage: bench/delaunay3d_threads_cli.sh [ROUNDS]
M=${CARGO_TARGET_DIR:-target}/release/morpho
for r in $(seq 1 "${1:-3}"); do
  for f in p3u1m p3s100k; do
    for t in 1 2; do
      L=$(cut -d' ' -f1-3 /proc/loadavg)
      R=$(RAYON_NUM_THREADS=$t /usr/bin/time -f "cpu %U %S wall %e rss %M" "$M" triangulate /tmp/$f.ply \
        -o /tmp/o_$t.ply --tets --report /tmp/r_$t.json 2>&1 | tail -1)
      C=$(python3 -c "import json;r=json.load(open('/tmp/r_$t.json'));print(r['timings']['compute'], r['tetrahedra'])")
      echo "round $r $f threads $t load $L | $R | compute_wall tets $C"
    done
  done
done
