#!/bin/sh
# Side by side in one run: our kernel (1 and 2 threads), an earlier binary of ours (BEFORE, if
# given) and CGAL 5.5 Delaunay_triangulation_3 (Epick, range insertion), interleaved, R repeats per
# point file; prints the medians of the kernels' own timings (input parsing excluded) and ratios.
#   benches/kernel_vs_cgal.sh [R] POINTS.xyz ...
# Env: S2S (default target/release/slice2solid), BEFORE (e.g. /tmp/s2s-kernel-before),
#      CGAL_DT (default /tmp/cgal_dt, built from benches/cgal/cgal_dt.cpp if missing).
set -e
R=${1:-5}; shift
S2S=${S2S:-target/release/slice2solid}
CGAL_DT=${CGAL_DT:-/tmp/cgal_dt}
[ -x "$CGAL_DT" ] || g++ -O3 -DNDEBUG -o "$CGAL_DT" "$(dirname "$0")/cgal/cgal_dt.cpp" -lgmp
sec() { sed -n 's/.*"seconds":\([0-9.e-]*\).*/\1/p'; }
med() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
for f in "$@"; do
  o1=""; o2=""; b=""; c=""
  for i in $(seq "$R"); do
    o1="$o1 $("$S2S" delaunay "$f" --json --threads 1 | sec)"
    o2="$o2 $("$S2S" delaunay "$f" --json --threads 2 | sec)"
    [ -n "$BEFORE" ] && b="$b $("$BEFORE" delaunay "$f" --json | sec)"
    c="$c $("$CGAL_DT" "$f" | sec)"
  done
  m1=$(echo $o1 | med); m2=$(echo $o2 | med); mc=$(echo $c | med)
  line="$(basename "$f"): ours1 $m1 s, ours2 $m2 s, cgal $mc s; ours1/cgal $(echo "$m1 / $mc" | bc -l | cut -c1-5), ours2/cgal $(echo "$m2 / $mc" | bc -l | cut -c1-5)"
  if [ -n "$BEFORE" ]; then
    mb=$(echo $b | med)
    line="$line; before $mb s, ours1/before $(echo "$m1 / $mb" | bc -l | cut -c1-5), ours2/before $(echo "$m2 / $mb" | bc -l | cut -c1-5), before/cgal $(echo "$mb / $mc" | bc -l | cut -c1-5)"
  fi
  echo "$line"
done
