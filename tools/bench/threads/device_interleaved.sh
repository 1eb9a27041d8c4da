#!/bin/bash
# interleaved 1-thread / 16-thread throughput (device check, session 13): samples/s ratio per round
#   on the lent machine, with the bundle of device_bundle.sh (made with a second build: pathtracer-old=OLD_EXE) in /tmp/b:
#   bash tools/bench/threads/device_interleaved.sh > interleaved.txt
cd /tmp/b
r() { ./$1 $2 --threads $3 --spp $4 -o /tmp/f.ppm 2>&1 | grep -o "render [0-9.]* s ([0-9]* samples/s" | tr -d '(' | awk -v e=$1 -v s=$2 -v t=$3 -v p=$4 -v k=$5 '{print k, e, s, "threads", t, "spp", p, $2, $4}'; }
for k in 1 2 3 4 5; do
  r pathtracer cornell-box.json 1 64 $k; r pathtracer cornell-box.json 16 256 $k; r pathtracer-old cornell-box.json 16 256 $k
  r pathtracer sponza-sky-sun.json 1 16 $k; r pathtracer sponza-sky-sun.json 16 64 $k; r pathtracer-old sponza-sky-sun.json 16 64 $k
done
cat /proc/loadavg
