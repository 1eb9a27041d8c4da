#!/bin/bash
# fixed cost of the render phase vs threads and spp (device check, session 13)
#   on the lent machine, with the bundle of device_bundle.sh (made with a second build: pathtracer-old=OLD_EXE) in /tmp/b:
#   bash tools/bench/threads/device_fixed_cost.sh > fixed.txt
cd /tmp/b
r() { ./$1 $2 --threads $3 --spp $4 -o /tmp/f.ppm 2>&1 | grep -o "render [0-9.]* s" | awk -v e=$1 -v s=$2 -v t=$3 -v p=$4 '{print e, s, "threads", t, "spp", p, $2}'; }
for rep in 1 2 3; do for t in 16 1 8; do for e in pathtracer pathtracer-old; do r $e cornell-box.json $t 1; r $e sponza-sky-sun.json $t 1; done; done; done
for rep in 1 2; do for e in pathtracer pathtracer-old; do for p in 16 64 256 1024; do r $e cornell-box.json 16 $p; done; for p in 4 16 64 256; do r $e sponza-sky-sun.json 16 $p; done; done; done
r pathtracer cornell-box.json 1 64; r pathtracer sponza-sky-sun.json 1 16
cat /proc/loadavg
