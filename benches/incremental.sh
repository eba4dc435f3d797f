#!/usr/bin/env bash
# What a nightly rerun costs against a full run (#32): generated friction
# traces of 5 000 rows (a static peak, then a noisy plateau), friction
# stage only; for each folder size, a full run (--force), an unchanged
# rerun, the same with --verify (every input read and hashed again), and a
# rerun after one file was added. Each time is the median of 3; ratios are
# against the full run of the same folder, in this run. "out MB" is the
# output folder with its cache (a hard-linked file counted once), "tables
# MB" the published tables alone.
#
#   cargo build --release && benches/incremental.sh [target/release/tribo] [200 2000 ...]
set -euo pipefail
tribo=$(realpath "${1:-target/release/tribo}")
shift || true
sizes=("${@:-200 2000}")
sizes=(${sizes[@]})
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

gen() { # gen DIR FROM TO: traces FROM..TO-1
    python3 - "$@" <<'PY'
import os, random, sys
d, a, b = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
os.makedirs(d, exist_ok=True)
for i in range(a, b):
    r = random.Random(i)
    lines = ["t (s),Fx [mN],Fz [mN]"]
    for k in range(5000):
        t = k * 1e-3
        f = 1200.0 * t if t < 1.0 else 1000.0
        e = r.gauss(0.0, 0.01)
        lines.append(f"{t:.3f},{f + 100.0 * e:.3f},{2000.0 + e:.3f}")
    with open(os.path.join(d, f"trace_{i:05d}.csv"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
PY
}

# Seconds of one `tribo run` with extra flags.
timed() {
    local s e
    s=$(date +%s.%N)
    "$tribo" run p.toml "$@" >/dev/null 2>&1 || { echo "tribo run $* failed" >&2; exit 1; }
    e=$(date +%s.%N)
    echo "$e - $s" | bc -l
}
median() { printf '%s\n' "$@" | sort -g | sed -n 2p; }

echo "| files | MB | full | unchanged | unchanged --verify | one file added | out MB | tables MB |"
echo "|---|---|---|---|---|---|---|---|"
for n in "${sizes[@]}"; do
    dir="$work/$n"
    gen "$dir/traces" 0 "$n"
    # Written long before the runs (as an archive is): a file modified
    # within 2 s of a run is hashed again by the next.
    find "$dir/traces" -type f -exec touch -d '-1 hour' {} +
    printf 'stages = ["friction"]\n[input]\nfiles = ["traces/*.csv"]\n[output]\ndir = "out"\nreport = false\n' >"$dir/p.toml"
    cd "$dir"
    full=(); same=(); verify=(); added=()
    for k in 1 2 3; do
        rm -rf out
        full+=("$(timed --force)")
        same+=("$(timed)")
        verify+=("$(timed --verify)")
        gen "$dir/traces" $((n + k - 1)) $((n + k))
        touch -d '-1 hour' "$dir/traces/trace_$(printf %05d $((n + k - 1))).csv"
        added+=("$(timed)")
    done
    f=$(median "${full[@]}"); u=$(median "${same[@]}"); v=$(median "${verify[@]}"); a=$(median "${added[@]}")
    mb=$(du -sm traces | cut -f1); omb=$(du -sm out | cut -f1)
    # The published tables alone (links followed; a file once): output
    # and cache together against them.
    tmb=$(du -smL out/*.parquet out/traces | awk '{s += $1} END {print s}')
    pct() { printf '%.3f s (%.1f %%)' "$1" "$(echo "100 * $1 / $f" | bc -l)"; }
    printf '| %s | %s | %.3f s | %s | %s | %s | %s | %s |\n' "$n" "$mb" "$f" "$(pct "$u")" "$(pct "$v")" "$(pct "$a")" "$omb" "$tmb"
    cd - >/dev/null
done
