#!/usr/bin/env python3
"""Compare two PiRayDump outputs (before/after a change to the ray caster).

usage: compare_ray_dumps.py OLD NEW [TOL]
Per (model, setup, view): equal hit counts; per (pixel, hit index): equal depth within
TOL (default 1e-9 times the depth scale), equal Tangent, Singular and Factor flags.
Exits 1 on any difference."""
import sys
from collections import defaultdict


def load(path):
    hits = {}
    for line in open(path):
        m, s, v, i, j, k, d, t, sg, f = line.split()
        hits[(m, s, int(v), int(i), int(j), int(k))] = (float(d), int(t), int(sg), int(f))
    return hits


old, new = load(sys.argv[1]), load(sys.argv[2])
tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-9
bad = defaultdict(int)
worst = 0.0
for key in old.keys() | new.keys():
    group = key[:3]
    if key not in old or key not in new:
        bad[group + ("missing" if key not in new else "extra",)] += 1
        continue
    a, b = old[key], new[key]
    worst = max(worst, abs(a[0] - b[0]))
    if abs(a[0] - b[0]) > tol:
        bad[group + ("depth",)] += 1
    for name, x, y in (("tangent", a[1], b[1]), ("singular", a[2], b[2]), ("factor", a[3], b[3])):
        if x != y:
            bad[group + (name,)] += 1
print(f"{len(old)} hits before, {len(new)} after; largest depth difference {worst:.3g}")
for k, n in sorted(bad.items()):
    print("DIFF", *k, n)
sys.exit(1 if bad else 0)
