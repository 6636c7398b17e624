#!/bin/sh
# One thread against two for the 3D Delaunay tetrahedralization (issue 23 item 3), taking turns:
# each round runs the one-thread engine (RAYON_NUM_THREADS=1, the facade then stays sequential)
# and the facade with two threads (split and merge, par3.rs) on the same points, for 1M uniform
# points and 100k points on a sphere. Prints wall, CPU (user+sys), peak RSS and the load average
# of every run; take the minimum of the rounds. Build first:
#   cargo build --release -p morpho --example bench_delaunay3d
# Usage: bench/delaunay3d_threads.sh [ROUNDS]
set -e
B=${CARGO_TARGET_DIR:-target}/release/examples/bench_delaunay3d
ROUNDS=${1:-3}
for r in $(seq 1 "$ROUNDS"); do
  for args in "1000000" "100000 --sphere"; do
    for t in 1 2; do
      echo "== round $r  threads $t  $args"
      # shellcheck disable=SC2086
      RAYON_NUM_THREADS=$t $B $args --engine auto | grep -E "^points|^engine|^split|^peak"
    done
  done
done
