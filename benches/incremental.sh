#!/usr/bin/env bash
# What a nightly rerun costs against a full run (#32): generated friction
# traces of 5 000 rows (a static peak, then a noisy plateau), friction
# stage only; for each folder size, a full run (--force), an unchanged
# rerun, the same with --verify (every input read and hashed again), and a
# rerun after one file was added. Each time is the median of REPS (3);
# an added file is timed ADDS (3) times after each full run, one more file
# each time, since its time scatters most (fresh memory, the disk): the
# median of REPS x ADDS. Ratios are against the full run of the same
# folder, in this run.
#
# The report is timed apart, on the same folder with `report = true` (once
# its figures are made): a file added, which renders the report again
# ("added, with report": its first page and the page of the added file's
# section; the other pages are linked unread), and an unchanged rerun,
# which keeps it ("report kept").
#
# "list + stat" is the least any rerun does per input: the inputs' folder
# listed and every file in it stat'ed, on all cores (benches/floor/
# list_stat.rs, built here with rustc alone; median of 5): between two
# folder sizes, an added file's time cannot grow by less than it does.
#
# After the table: an added file's time by phase, as the run itself
# measures it (`tribo run --json`, phases_s), for each folder size; then,
# for each size against the one before, #32's test: the added file's
# ratio, the growth 1.5x allows and what listing and stat'ing grew by.
#
# "out / tables" is the output folder with its cache (`du`, in file system
# blocks, a hard-linked file counted once) against the published tables
# alone (`du -L` of OUT/*.parquet and the dataset folder OUT/traces).
#
#   cargo build --release && benches/incremental.sh [target/release/tribo] [200 2000 20000 ...]
set -euo pipefail
tribo=$(realpath "${1:-target/release/tribo}")
shift || true
sizes=("${@:-200 2000}")
sizes=(${sizes[@]})
reps=${REPS:-3}
adds=${ADDS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
floor="$work/list_stat"
rustc -O "$(dirname "$0")/floor/list_stat.rs" -o "$floor"

gen() { # gen DIR FROM TO: traces FROM..TO-1, on two processes
    python3 - "$@" <<'PY'
import os, random, sys
from multiprocessing import Pool
d, a, b = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
os.makedirs(d, exist_ok=True)
def one(i):
    r = random.Random(i)
    lines = ["t (s),Fx [mN],Fz [mN]"]
    for k in range(5000):
        t = k * 1e-3
        f = 1200.0 * t if t < 1.0 else 1000.0
        e = r.gauss(0.0, 0.01)
        lines.append(f"{t:.3f},{f + 100.0 * e:.3f},{2000.0 + e:.3f}")
    with open(os.path.join(d, f"trace_{i:05d}.csv"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
with Pool(2) as p:
    p.map(one, range(a, b), chunksize=64)
PY
}

# Seconds of one `tribo run` of pipeline $1 with extra flags. The writes
# of what ran before are put on disk first, as they are long before a
# nightly run: a full run over 20 000 files leaves 1.5 GB to write back,
# and the next run's sync (its state, its set) waited for it in the file
# system's journal.
timed() {
    local p=$1 s e
    shift
    sync
    s=$(date +%s.%N)
    "$tribo" run "$p" "$@" >/dev/null 2>&1 || { echo "tribo run $p $* failed" >&2; exit 1; }
    e=$(date +%s.%N)
    echo "$e - $s" | bc -l
}
median() { printf '%s\n' "$@" | sort -g | sed -n "$((($# + 1) / 2))p"; }

echo "| files | MB | full | unchanged | unchanged --verify | one file added | list + stat | added, with report | report kept | out / tables MB |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for n in "${sizes[@]}"; do
    dir="$work/$n"
    gen "$dir/traces" 0 "$n"
    # Written long before the runs (as an archive is): a file modified
    # within 2 s of a run is hashed again by the next.
    find "$dir/traces" -type f -exec touch -d '-1 hour' {} +
    for report in false true; do
        printf 'stages = ["friction"]\n[input]\nfiles = ["traces/*.csv"]\n[output]\ndir = "out"\nreport = %s\n' \
            "$report" >"$dir/report-$report.toml"
    done
    cd "$dir"
    sync
    least_ms=$("$floor" traces | awk '{printf "%.1f", $1 + $2}')
    least="$least_ms ms"
    p=report-false.toml
    full=(); same=(); verify=(); added=()
    for k in $(seq 1 "$reps"); do
        rm -rf out
        full+=("$(timed $p --force)")
        same+=("$(timed $p)")
        verify+=("$(timed $p --verify)")
        for a in $(seq 1 "$adds"); do
            i=$((n + (k - 1) * adds + a - 1))
            gen "$dir/traces" "$i" $((i + 1))
            touch -d '-1 hour' "$dir/traces/trace_$(printf %05d "$i").csv"
            added+=("$(timed $p)")
        done
    done
    okb=$(du -sk out | cut -f1)
    tkb=$(du -skL out/*.parquet out/traces | awk '{s += $1} END {print s}')
    # Where an added file's time goes: the run's own phase times
    # (`--json`'s phases_s), medians over ADDS more added files. Apart from
    # the timed runs above: the summary lists every input, and printing it
    # is no part of a scheduled run.
    for a in $(seq 1 "$adds"); do
        i=$((n + reps * adds + a - 1))
        gen "$dir/traces" "$i" $((i + 1))
        touch -d '-1 hour' "$dir/traces/trace_$(printf %05d "$i").csv"
        sync
        "$tribo" run $p --json >"$work/phases-$a.json" 2>/dev/null
    done
    python3 - "$n" "$work"/phases-*.json >>"$work/phases.md" <<'PY'
import json, statistics, sys
runs = [json.load(open(f))["phases_s"] for f in sys.argv[2:]]
names = [p["phase"] for p in runs[0]]
ms = [statistics.median(next(p["seconds"] for p in r if p["phase"] == k) for r in runs) * 1e3 for k in names]
print("| " + sys.argv[1] + " | " + " | ".join(f"{m:.1f}" for m in ms) + f" | {sum(ms):.1f} |")
PY
    rm -f "$work"/phases-*.json
    # The report: a first run with it computes what it draws (each file's
    # figures: the friction stage's parameters change); then a file is
    # added before each timed run, which renders the report again, and the
    # run after keeps it.
    timed report-true.toml >/dev/null
    drawn=(); shown=()
    for k in $(seq 1 "$reps"); do
        i=$((n + (reps + 1) * adds + k - 1))
        gen "$dir/traces" "$i" $((i + 1))
        touch -d '-1 hour' "$dir/traces/trace_$(printf %05d "$i").csv"
        drawn+=("$(timed report-true.toml)")
        shown+=("$(timed report-true.toml)")
    done
    f=$(median "${full[@]}"); u=$(median "${same[@]}"); v=$(median "${verify[@]}")
    a=$(median "${added[@]}"); d=$(median "${drawn[@]}"); r=$(median "${shown[@]}")
    mb=$(du -sm traces | cut -f1)
    echo "$n $a $least_ms" >>"$work/added.txt"
    pct() { printf '%.3f s (%.1f %%)' "$1" "$(echo "100 * $1 / $f" | bc -l)"; }
    printf '| %s | %s | %.3f s | %s | %s | %s | %s | %s | %s | %d / %d (%.2fx) |\n' "$n" "$mb" "$f" \
        "$(pct "$u")" "$(pct "$v")" "$(pct "$a")" "$least" "$(pct "$d")" "$(pct "$r")" $((okb / 1024)) $((tkb / 1024)) \
        "$(echo "$okb / $tkb" | bc -l)"
    cd - >/dev/null
    rm -rf "$dir"
done
echo
echo "An added file's phases (ms, medians of $adds; \`tribo run --json\`'s phases_s):"
echo
echo "| files | plan | state | files | join | table stages | tables | report | commit | in all |"
echo "|---|---|---|---|---|---|---|---|---|---|"
cat "$work/phases.md"
# #32's test, from the figures above: an added file's time against the
# size before, and the room 1.5x of it leaves against what listing and
# stat'ing the inputs alone grew by.
echo
python3 - "$work/added.txt" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1])]
for (n0, a0, l0), (n1, a1, l1) in zip(rows, rows[1:]):
    a0, a1, l0, l1 = float(a0), float(a1), float(l0), float(l1)
    print(f"An added file at {n1} files: {a1:.3f} s, {a1 / a0:.1f}x its {a0:.3f} s at {n0} "
          f"(#32 asks at most 1.5x: {500 * a0:.1f} ms of growth); listing and stat'ing "
          f"the inputs alone grew by {l1 - l0:.1f} ms.")
PY
