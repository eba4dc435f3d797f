#!/usr/bin/env bash
# The cycle tables' cost (#31): a generated 1e7-row reciprocating trace of
# 10^4 strokes (1 000 samples each; position a triangle of 10 mm, friction
# force ±μN with a break-away at each reversal and a running-in decay, noise
# σ 0.02 N), run through `tribo friction --no-traces` by two builds side by
# side, interleaved: BEFORE (a build without friction_cycles and
# friction_tests, e.g. of commit c933377^1) and AFTER (this one). Prints each
# run's wall and user seconds and the ratio of the medians, AFTER / BEFORE.
#
#   [REPS=5] benches/cycles.sh BEFORE_TRIBO AFTER_TRIBO
set -euo pipefail
before=$(realpath "$1")
after=$(realpath "$2")
reps="${REPS:-5}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work/recip.csv" <<'PY'
import sys
import numpy as np
n, strokes = 10_000_000, 10_000
per = n // strokes
rng = np.random.default_rng(1)
i = np.arange(n)
k, s = i % per, i // per
t = i * 1e-3
pos = np.where(s % 2 == 0, k / per * 10.0, (1 - k / per) * 10.0)
sign = np.where(s % 2 == 0, 1.0, -1.0)
mu = 0.3 + 0.2 * np.exp(-s / 500)
force = sign * mu * 10.0 * (1 + 0.5 * np.exp(-k / 20.0)) + rng.normal(0, 0.02, n)
with open(sys.argv[1], "w") as f:
    f.write("Time [s],Position [mm],Friction force [N],Normal force [N]\n")
    for a in range(0, n, 1_000_000):
        b = a + 1_000_000
        cols = np.column_stack([t[a:b], pos[a:b], force[a:b], np.full(b - a, 10.0)])
        np.savetxt(f, cols, fmt=["%.3f", "%.5f", "%.5f", "%.1f"], delimiter=",")
PY

times="$work/times"
for _ in $(seq "$reps"); do
  for which in before after; do
    bin=$before; [ "$which" = after ] && bin=$after
    rm -rf "$work/out"
    /usr/bin/time -f "$which %e %U" -a -o "$times" \
      "$bin" friction "$work/recip.csv" --out "$work/out" --no-traces >/dev/null 2>&1
  done
done
cat "$times"
python3 - "$times" <<'PY'
import statistics, sys
runs = {"before": [], "after": []}
for line in open(sys.argv[1]):
    which, wall, _ = line.split()
    runs[which].append(float(wall))
b, a = statistics.median(runs["before"]), statistics.median(runs["after"])
print(f"median wall: before {b:.2f} s, after {a:.2f} s, after/before {a / b:.2f}")
PY
