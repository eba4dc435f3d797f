#!/usr/bin/env bash
# Regenerates the report screenshots in docs/img/ from the demo pipeline:
# the first page, and one figure per stage kind. Needs headless Chromium
# (scripts/install-chromium.sh) and a built tribo.
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(mktemp -d /tmp/tribo-shots.XXXXXX)"
trap 'rm -rf "$out"' EXIT
cargo run --quiet -- run pipelines/demo.toml --out "$out/demo" 2>/dev/null || true
shot() { # page, png, width, height
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
    --window-size="$3,$4" --screenshot="$2" "file://$1" >/dev/null 2>&1
}
mkdir -p docs/img
shot "$out/demo/.tribo/current/report.html" docs/img/report-overview.png 1100 900
cargo run --quiet -- plot \
  fixtures/lab/friction/HT-2n-6-4_2_001.csv fixtures/lab/fibres/t150_knotted.txt \
  fixtures/lab/profiles/dektak-1.csv --out "$out/figs" >/dev/null 2>&1
python3 - "$out" <<'PY'
import sys, pyarrow.parquet as pq
out = sys.argv[1]
for table, figure, part, name in [
    ("coulomb_figures", "fit", "pattern, static", "fits"),
    ("spring_block_figures", "static", "", "simulations"),
]:
    for r in pq.read_table(f"{out}/demo/{table}.parquet").to_pylist():
        if r["figure"] == figure and r["part"] == part:
            open(f"{out}/figs/{name}.svg", "w").write(r["svg"])
            break
PY
shot "$out/figs/HT-2n-6-4_2_001-Step_1-force.svg" docs/img/report-friction.png 720 360
shot "$out/figs/t150_knotted-curve.svg" docs/img/report-tensile.png 720 360
shot "$out/figs/dektak-1-surface.svg" docs/img/report-roughness.png 720 360
shot "$out/figs/fits.svg" docs/img/report-fits.png 720 360
shot "$out/figs/simulations.svg" docs/img/report-simulations.png 720 360
ls -l docs/img/report-*.png
