#!/usr/bin/env bash
# Runs a fixed list of CLI invocations with two `morpho` binaries and compares every output
# byte for byte (reports: all keys but timings/elapsed). For refactors that must not change
# behaviour:  tools/equivalence.sh OLD_BIN NEW_BIN [DATA_DIR]
# Exit 0 when every output is identical; prints the differing files otherwise.
set -u
old=$1; new=$2; data=${3:-}
# default: the nearest shared/data above the repository (worktrees live deeper than main)
if [ -z "$data" ]; then
  d=$(cd "$(dirname "$0")/.." && pwd)
  while [ "$d" != / ] && [ ! -d "$d/shared/data" ]; do d=$(dirname "$d"); done
  data=$d/shared/data
fi
[ -d "$data" ] || { echo "equivalence: no data directory $data" >&2; exit 2; }
work=$(mktemp -d); [ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT; echo "work: $work"
mkdir -p "$work/in"
# inputs
zcat "$data/meshes/horse.obj.gz" > "$work/in/horse.obj"
python3 - "$work/in" <<'PY'
import sys, random, math
d = sys.argv[1]
random.seed(7)
with open(f"{d}/pts2.csv", "w") as f:
    f.write("x,y\n")
    for i in range(3000):
        f.write(f"{random.random()},{random.random()}\n")
with open(f"{d}/pts3.csv", "w") as f:
    f.write("x,y,z\n")
    for i in range(2000):
        f.write(f"{random.random()},{random.random()},{random.random()}\n")
with open(f"{d}/grid2.csv", "w") as f:
    f.write("x,y\n")
    for i in range(30):
        for j in range(30):
            f.write(f"{i},{j}\n")
with open(f"{d}/sphere3.csv", "w") as f:
    f.write("x,y,z\n")
    for i in range(1500):
        z = 2 * random.random() - 1; t = 2 * math.pi * random.random(); r = math.sqrt(1 - z * z)
        f.write(f"{r*math.cos(t)},{r*math.sin(t)},{z}\n")
PY
P2=$data/polygons/benelux_mainland_ne50m.csv
cmds=(
 "triangulate $work/in/pts2.csv -o OUT/tri2.json"
 "triangulate $work/in/pts2.csv -o OUT/tri2.svg --voronoi"
 "triangulate $work/in/grid2.csv -o OUT/grid2.ply"
 "triangulate $work/in/pts3.csv -o OUT/tri3.ply"
 "triangulate $work/in/pts3.csv -o OUT/tets.ply --tets"
 "triangulate $work/in/pts3.csv -o OUT/tri3.json"
 "graph $work/in/pts2.csv --kind emst -o OUT/emst.json"
 "graph $work/in/pts2.csv --kind rng -o OUT/rng.svg"
 "graph $work/in/pts2.csv --kind gabriel -o OUT/gg.ply"
 "graph $work/in/pts2.csv --kind sig -o OUT/sig.json"
 "graph $work/in/pts2.csv --kind alpha --a 20 -o OUT/alpha.json"
 "graph $work/in/pts2.csv --kind beta-lune --b 0.5 -o OUT/bl.json"
 "graph $work/in/pts2.csv --kind beta-circle --b -0.3 -o OUT/bc.json"
 "graph $work/in/pts2.csv --kind gamma --c0 0.1 --c1 0.5 -o OUT/g.json"
 "graph $work/in/pts2.csv --kind gamma-range --range=-1,0.2,-0.2,1 -o OUT/gr.json"
 "graph $work/in/pts3.csv --kind rng -o OUT/rng3.json"
 "graph $work/in/pts3.csv --kind gamma --c0 0 --c1 0.3 -o OUT/g3.json"
 "graph $work/in/pts3.csv --kind emst -o OUT/emst3.ply"
 "boundary $P2 -o OUT/b2.csv --interior OUT/b2i.json"
 "boundary $P2 -o OUT/b2.geojson"
 "boundary $P2 -o OUT/b2.svg"
 "boundary $P2 -o OUT/b2ma.csv --method min-area-change"
 "boundary $P2 -o OUT/b2vs.csv --method voronoi-skeleton"
 "boundary $data/polygons/coast_ireland_ne10m.csv -o OUT/ire.csv --c auto"
 "boundary $data/meshes/bunny_npm.obj -o OUT/bunny.ply --interior OUT/bunnyi.ply"
 "boundary $work/in/sphere3.csv -o OUT/sph.obj"
 "boundary $data/meshes/spot.obj -o OUT/spotma.ply --method min-area-change"
 "isosurface $data/volumes/cthead_8bit_256x256x99.nhdr --level 80 -o OUT/head.ply"
 "isosurface $data/volumes/dipy_aniso_vox_58x58x24_i16.nhdr --level 300 -o OUT/dipy.obj --method tetra"
 "isosurface $data/volumes/dipy_aniso_vox_58x58x24_i16.nhdr --level 300 -o OUT/dipyl.ply --method lorensen --normals mesh"
 "contour $data/geostat/meuse.csv --value zinc --threshold 500 -o OUT/zinc.geojson"
 "contour $data/geostat/meuse.csv --value zinc --threshold 500 -o OUT/zinc.svg --holes"
 "contour $data/geostat/jura_pred.csv --value Cd --threshold 1 -o OUT/cd.json"
 "convert $work/in/horse.obj -o OUT/horse.stl"
 "convert $work/in/horse.obj -o OUT/horse.off"
 "convert $data/volumes/dipy_aniso_vox_58x58x24_i16.nhdr -o OUT/dipy.mhd"
 "info $work/in/horse.obj --check"
 "info $P2 --check"
 "render $work/in/horse.obj -o OUT/horse.png --width 200 --height 150"
 "render $P2 -o OUT/p2.svg"
 "render $data/volumes/dipy_aniso_vox_58x58x24_i16.nhdr -o OUT/vol.png --width 300"
)
fail=0
for bin in old new; do mkdir -p "$work/$bin"; done
i=0
for c in "${cmds[@]}"; do
  i=$((i+1))
  for bin in old new; do
    b=${!bin}; out=$work/$bin
    cc=${c//OUT/$out}
    (cd "$work" && $b $cc --report "$out/r$i.json" >"$out/stdout$i" 2>"$out/stderr$i"; echo $? >"$out/rc$i")
    sed -i "s|$out|OUT|g" "$out/stdout$i" "$out/stderr$i"
    python3 -c "
import json,sys
p=sys.argv[1]
try: d=json.load(open(p))
except Exception: sys.exit(0)
def strip(x):
    if isinstance(x,dict): return {k:strip(v) for k,v in x.items() if k not in ('timings','elapsed_s','version') and not k.endswith('_s')}
    if isinstance(x,list): return [strip(v) for v in x]
    if isinstance(x,str): return x.replace(sys.argv[2], 'OUT')
    return x
json.dump(strip(d),open(p,'w'),sort_keys=True,indent=1)" "$out/r$i.json" "$out"
  done
done
for f in $(cd "$work/old" && ls); do
  if ! cmp -s "$work/old/$f" "$work/new/$f"; then echo "DIFFERS: $f"; fail=1; fi
done
for f in $(cd "$work/new" && ls); do [ -e "$work/old/$f" ] || { echo "ONLY NEW: $f"; fail=1; }; done
n=$(ls "$work/old" | wc -l)
[ $fail = 0 ] && echo "equivalence: ${#cmds[@]} commands, $n files identical"
exit $fail
