#!/usr/bin/env bash
# The spring-block comparison study (thesis Fig. 4.10; docs/spring_block.md
# "Comparison study"), one pattern at a time so that each pattern's wall and
# CPU time are measured, then the docs' tables:
#
#   scripts/spring-block-study.sh [STUDY.toml] [OUT]
#
# STUDY defaults to pipelines/spring_block_compare.toml (6 patterns × 8
# pressures × 10 repetitions at 85 × 85, about 12 min of CPU), OUT to
# out/spring_block_study. Every scene of the study is run, in release, with
# `--threads ${THREADS:-2}`, as a one-scene study with the same [measured]
# and [groups] (the measured and AF predictions come from the measured fits
# only, so each pattern's rows are those of the whole study). Per pattern,
# /usr/bin/time gives wall and user + sys time; then the script prints the
# timing table and the static-friction table (simulated / measured = ratio
# per pattern and pressure) from OUT/<pattern>/spring_block_compare.parquet,
# and writes both to OUT/tables.md. Needs python3 >= 3.11 with pyarrow.
# TRIBO=path uses an already built binary instead of building one.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
study="$(realpath "${1:-$root/pipelines/spring_block_compare.toml}")"
out="$(realpath -m "${2:-$root/out/spring_block_study}")"
threads="${THREADS:-2}"
python="${PYTHON:-python3}"

if ! "$python" -c 'import sys, tomllib, pyarrow' 2>/dev/null; then
  echo "error: $python with tomllib (3.11+) and pyarrow is needed to split the study and read its tables" >&2
  exit 2
fi
if [[ ! -x /usr/bin/time ]]; then
  echo "error: /usr/bin/time (GNU time) is needed to measure CPU time" >&2
  exit 2
fi
if [[ -z "${TRIBO:-}" ]]; then
  (cd "$root" && nice cargo build --release --quiet --bin tribo)
  TRIBO="${CARGO_TARGET_DIR:-$root/target}/release/tribo"
fi
mkdir -p "$out"

# One study file per scene, scene and coulomb paths made absolute.
"$python" - "$study" "$out" <<'EOF'
import json, os, sys, tomllib
study, out = sys.argv[1], sys.argv[2]
base = os.path.dirname(study)
spec = tomllib.load(open(study, "rb"))
if "scenes" not in spec:
    sys.exit(f"error: {study}: not a comparison study (no `scenes = [...]`)")
def q(s):
    return json.dumps(s)  # a TOML basic string
names = []
for scene in spec["scenes"]:
    path = os.path.normpath(os.path.join(base, scene))
    name = tomllib.load(open(path, "rb")).get("name") or os.path.splitext(os.path.basename(path))[0]
    lines = [f"scenes = [{q(path)}]", "", "[measured]"]
    m = spec.get("measured", {})
    if "coulomb" in m:
        lines.append(f"coulomb = {q(os.path.normpath(os.path.join(base, m['coulomb'])))}")
    lines.append(f"flat_group = {q(m.get('flat_group', 'F'))}")
    for f in m.get("fit", []):
        lines += ["", "[[measured.fit]]"] + [f"{k} = {q(v) if isinstance(v, str) else repr(v)}" for k, v in f.items()]
    lines += ["", "[groups]"] + [f"{q(k)} = {q(v)}" for k, v in spec.get("groups", {}).items()]
    os.makedirs(os.path.join(out, name), exist_ok=True)
    open(os.path.join(out, name, "study.toml"), "w").write("\n".join(lines) + "\n")
    names.append(name)
open(os.path.join(out, "patterns.txt"), "w").write("\n".join(names) + "\n")
EOF

: > "$out/times.tsv"
status=0
while read -r name; do
  dir="$out/$name"
  echo "== $name: $TRIBO simulate spring-block $dir/study.toml --threads $threads" >&2
  rc=0
  /usr/bin/time -f "%e %U %S" -o "$dir/time.txt" \
    "$TRIBO" simulate spring-block "$dir/study.toml" --out "$dir" --threads "$threads" \
    > "$dir/stdout.txt" 2> "$dir/stderr.txt" || rc=$?
  # GNU time puts "Command exited with non-zero status N" before its line.
  read -r wall user sys < <(tail -n 1 "$dir/time.txt")
  # Exit 1: some runs diverged or reached max_time (their rows say why);
  # anything else is a failure of the tool.
  if (( rc > 1 )); then
    echo "error: $name exited $rc; see $dir/stderr.txt" >&2
    tail -5 "$dir/stderr.txt" >&2
    exit "$rc"
  fi
  (( rc == 1 )) && status=1
  printf '%s\t%s\t%s\t%s\t%s\n' "$name" "$wall" "$user" "$sys" "$rc" >> "$out/times.tsv"
  echo "   wall ${wall} s, CPU $(awk "BEGIN{print $user + $sys}") s, exit $rc" >&2
done < "$out/patterns.txt"

"$python" - "$out" "$threads" <<'EOF' | tee "$out/tables.md"
import os, sys
import pyarrow.parquet as pq
out, threads = sys.argv[1], sys.argv[2]
times = [l.split("\t") for l in open(os.path.join(out, "times.tsv")).read().splitlines()]
print(f"Per pattern, release build, --threads {threads} (wall and user + sys CPU from /usr/bin/time):\n")
print("| pattern | runs | failed | wall [s] | CPU [s] | CPU per run [s] |")
print("|---|---|---|---|---|---|")
tw = tc = 0.0
rows = {}
for name, wall, user, sys_, rc in times:
    s = pq.read_table(os.path.join(out, name, "spring_block_summary.parquet")).to_pylist()
    runs, failed = sum(r["n"] for r in s), sum(r["n_failed"] for r in s)
    cpu = float(user) + float(sys_)
    tw, tc = tw + float(wall), tc + cpu
    print(f"| {name} | {runs} | {failed} | {float(wall):.1f} | {cpu:.1f} | {cpu / max(runs, 1):.2f} |")
    rows[name] = [r for r in pq.read_table(os.path.join(out, name, "spring_block_compare.parquet")).to_pylist()
                  if r["regime"] == "static"]
print(f"| total | | | {tw:.1f} ({tw / 60:.1f} min) | {tc:.1f} ({tc / 60:.1f} min) | |")
pressures = sorted({r["pressure_Pa"] for rs in rows.values() for r in rs})
def kpa(p):
    return f"{p / 1e3:g} kPa"
def fmt(v, d=2):
    return "–" if v is None else f"{v:.{d}f}"
print("\nSimulated / measured static friction (spring_block_compare, regime static):\n")
print("| pattern | " + " | ".join(kpa(p) for p in pressures) + " |")
print("|---|" + "---|" * len(pressures))
for name, rs in rows.items():
    by = {r["pressure_Pa"]: r for r in rs}
    cells = []
    for p in pressures:
        r = by.get(p)
        cells.append("–" if r is None else
                     f"{fmt(r['mu_simulated_mean'])} / {fmt(r['mu_measured'])} = {fmt(r['ratio_simulated_to_measured'])}")
    print(f"| {name} | " + " | ".join(cells) + " |")
print("\nRun-to-run sd of the simulated static friction:\n")
print("| pattern | n | " + " | ".join(kpa(p) for p in pressures) + " |")
print("|---|---|" + "---|" * len(pressures))
for name, rs in rows.items():
    by = {r["pressure_Pa"]: r for r in rs}
    n = sorted({r["n"] for r in rs})
    print(f"| {name} | {'/'.join(map(str, n))} | " + " | ".join(fmt(by[p]["mu_simulated_sd"], 3) if p in by else "–" for p in pressures) + " |")
EOF
exit "$status"
