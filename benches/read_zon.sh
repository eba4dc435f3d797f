#!/usr/bin/env bash
# Reading a Keyence ZON file (zstd-compressed entries), tribo against
# surfalize's reader (#29): the whole command `tribo inspect FILE` (read,
# decompress, decode the heights into f64 metres with the mask, describe)
# against a fresh Python process running surfalize's `read_zon` (zstandard,
# numpy), and surfalize's read alone after its imports. Medians of REPS
# runs after one warm-up (warm page cache).
#
#   [REPS=5] benches/read_zon.sh FILE [target/release/tribo] [PYTHON] [SURFALIZE_SRC]
#
# FILE: surfalize's tests/test_files/test_1.zon (scripts/format-examples.sh
# extracts it); SURFALIZE_SRC: a surfalize source tree at commit f558db5 or
# later (its surfalize/file/zon.py), importable with PYTHON (numpy,
# zstandard, python-dateutil and surfalize's own imports installed).
set -euo pipefail
file=$(realpath "${1:?usage: benches/read_zon.sh FILE [tribo] [PYTHON] [SURFALIZE_SRC]}")
tribo=$(realpath "${2:-target/release/tribo}")
py="${3:-python3}"
src=$(realpath "${4:-.}")
reps="${REPS:-5}"

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}'; }
timed() { local s e; s=$(date +%s.%N); "$@" > /dev/null; e=$(date +%s.%N); echo "$e - $s" | bc -l; }

read_py="import sys, time; sys.path.insert(0, '$src'); from surfalize.file.zon import read_zon
t = time.perf_counter(); f = open('$file', 'rb'); read_zon(f); print(time.perf_counter() - t)"
"$tribo" inspect "$file" > /dev/null
"$py" -c "$read_py" > /dev/null
t_tribo=$(for _ in $(seq "$reps"); do timed "$tribo" inspect "$file"; done | median)
t_proc=$(for _ in $(seq "$reps"); do timed "$py" -c "$read_py"; done | median)
t_read=$(for _ in $(seq "$reps"); do "$py" -c "$read_py"; done | median)
printf 'tribo inspect: %.3f s\nsurfalize process: %.3f s (%.1fx)\nsurfalize read alone: %.3f s (%.2fx)\n' \
  "$t_tribo" "$t_proc" "$(echo "$t_proc / $t_tribo" | bc -l)" "$t_read" "$(echo "$t_read / $t_tribo" | bc -l)"
