#!/bin/sh
# Issue 23 item 3: 2D Delaunay on one vs two threads (crates/morpho/src/delaunay/par2.rs).
# Each (input, thread count) is its own process; the rounds alternate 1 and 2 threads so both
# see the same machine load. Usage: bench/par2d.sh [ROUNDS] [N]
set -e
ROUNDS=${1:-3}
N=${2:-1000000}
cd "$(dirname "$0")/.."
cargo build --release --example bench_delaunay2d_par -p morpho >/dev/null 2>&1
BIN=target/release/examples/bench_delaunay2d_par
echo "# $(date -u '+%F %T') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$ROUNDS"); do
  for dist in uniform curve grid; do
    RAYON_NUM_THREADS=1 $BIN $dist "$N"
    RAYON_NUM_THREADS=2 $BIN $dist "$N"
    RAYON_NUM_THREADS=1 $BIN $dist "$N" --split always
    RAYON_NUM_THREADS=1 $BIN $dist "$N" --split merge
    RAYON_NUM_THREADS=2 $BIN $dist "$N" --split merge
  done
done
