#!/usr/bin/env bash
# Copies the example files of SurfaceTopography (MIT licence,
# test/file_format_examples at a pinned commit) into a folder, for the
# real-file tests of the binary readers (tests/binary_real.rs):
#
#   scripts/format-examples.sh DIR [SOURCE [SURFALIZE]]
#   TRIBO_FORMAT_EXAMPLES=DIR cargo test binary_real
#
# SOURCE is a clone of https://github.com/ContactEngineering/SurfaceTopography
# (a work tree or a bare git directory); without it the repository is
# cloned (network). Files missing from SOURCE are skipped.
#
# SURFALIZE, a clone of https://github.com/fredericjs/surfalize (GPL-3),
# gives its Keyence ZON example (tests/test_files/test_1.zon, blob
# b93a72ce at commit f558db5) as DIR/surfalize-test_1.zon: read by the
# tests only, never committed. Without SURFALIZE it is skipped.
set -euo pipefail
DIR="${1:?usage: scripts/format-examples.sh DIR [SOURCE [SURFALIZE]]}"
SOURCE="${2:-}"
SURFALIZE="${3:-}"
COMMIT=119cb66a
FILES="x3p-1.x3p x3p-2.x3p x3p-3.x3p x3p-4.x3p sur-1.sur sur-2.sur sur-3.sur sur-4.sur sur-5.sur
metropro-1.dat datx-1.datx datx-2.datx plu-1.plu opd-1.opd opd-2.opd opd-3.opd opdx-1.opdx
opdx-2.opdx opdx-2.txt opdx-3.opdx opdx-3.txt nc-1.nc example-2d.npy wrongnpyfile.npy sdf-1.sdf sdf-2.sdf
gwy-1.gwy gwy-2.gwy spot_1-1000nm.ibw 10x10-one_channel_without_name.ibw nid-1.nid mi-1.mi bcrf-1.bcrf
stp-1.stp top-1.top frt-1.frt frt-2.frt di-1.di di-2.di di-3.di di-4.di di-5.di di-6.di di_corrupted.di tmd-1.tmd al3d-1.al3d
zon-1.zon vk3-1.vk3 vk4-1.vk4 vk6-1.vk6 plux-1.plux"
mkdir -p "$DIR"
if [ -z "$SOURCE" ]; then
  SOURCE="$DIR/.SurfaceTopography"
  [ -d "$SOURCE" ] || git clone --quiet --filter=blob:none --no-checkout \
    https://github.com/ContactEngineering/SurfaceTopography "$SOURCE"
fi
GIT=(git -C "$SOURCE")
[ -d "$SOURCE/.git" ] || GIT=(git --git-dir="$SOURCE")
REV=$("${GIT[@]}" rev-parse --verify --quiet "$COMMIT^{commit}" || "${GIT[@]}" rev-parse HEAD)
n=0
for f in $FILES; do
  if "${GIT[@]}" cat-file -e "$REV:test/file_format_examples/$f" 2>/dev/null; then
    "${GIT[@]}" show "$REV:test/file_format_examples/$f" > "$DIR/$f"
    n=$((n + 1))
  else
    echo "absent from $SOURCE: $f"
  fi
done
"${GIT[@]}" show "$REV:LICENSE.md" > "$DIR/LICENSE-SurfaceTopography.md" 2>/dev/null || true
if [ -n "$SURFALIZE" ]; then
  SG=(git -C "$SURFALIZE")
  [ -d "$SURFALIZE/.git" ] || SG=(git --git-dir="$SURFALIZE")
  if "${SG[@]}" cat-file -e b93a72ce2b31fd000618f1d6812ca22c9ed01721 2>/dev/null; then
    "${SG[@]}" cat-file blob b93a72ce2b31fd000618f1d6812ca22c9ed01721 > "$DIR/surfalize-test_1.zon"
    n=$((n + 1))
  else
    echo "absent from $SURFALIZE: test_1.zon (blob b93a72ce)"
  fi
fi
echo "$n files in $DIR; run the tests with TRIBO_FORMAT_EXAMPLES=$DIR"
