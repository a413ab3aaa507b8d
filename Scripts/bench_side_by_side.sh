#!/usr/bin/env bash
# The mesher, ray-casting and molecule benchmarks of `./run bench` for two builds, taking
# turns (before, after, before, after): a change's effect on speed, measured in one run
# on one machine, where the load of a shared machine slows both sides alike.
#
#   Scripts/bench_side_by_side.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [N]
#
# Each build needs its Python package (BUILD/lib/python) and bin/PiRayBenchmark. The
# outputs go to out/side-by-side/{before,after}-ROUND-*.txt; compare their tables.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
before="$1" after="$2" rounds="${3:-2}" n="${4:-256}"
out="$ROOT/out/side-by-side"
mkdir -p "$out"
for round in $(seq 1 "$rounds"); do
  for side in before after; do
    build="$before"
    [ "$side" = after ] && build="$after"
    echo "round $round: $side ($build)" >&2
    PYTHONPATH="$build/lib/python" pvpython "$ROOT/Scripts/benchmark.py" \
      "$ROOT/Testing/Data/Models" "$n" > "$out/$side-$round-mesh.txt"
    "$build/bin/PiRayBenchmark" "$ROOT/Testing/Data/Models" 1024 > "$out/$side-$round-rays.txt"
    PYTHONPATH="$build/lib/python" pvpython "$ROOT/Scripts/molecule_benchmark.py" --quick \
      > "$out/$side-$round-molecule.txt"
  done
done
echo "results in $out" >&2
