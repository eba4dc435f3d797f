#!/usr/bin/env bash
# Reading binary surface files, tribo against SurfaceTopography (#29):
# one generated 4096 × 4096 map per format (NPY f8, TMD f4, BCRF f4, WSxM
# double, NID i32, FRT u16), written by numpy, and Zygo DATX (f8 µm,
# contiguous and deflated), written by h5py; for each, the whole command
# `tribo inspect FILE` (read, decode the height channel into f64 metres,
# describe) against a fresh Python process running
# `read_topography(FILE).heights()` (SurfaceTopography), and the bytes of
# the file copied (`cat FILE > /dev/null`, a warm page cache) as the floor.
# Each time is the median of 3 runs after one warm-up; the ratios are
# SurfaceTopography / tribo in the same run: whole processes (ST_s, with
# Python's `import SurfaceTopography`, also timed alone), and the read
# alone in Python after the import (ST_read_s) against tribo's whole
# process.
#
#   [REPS=3] [FORMATS="npy datx"] benches/read_formats.sh [target/release/tribo] [PYTHON] [N]
#
# PYTHON is an interpreter with SurfaceTopography installed (the venv of
# scripts/python-tests.sh: $CARGO_TARGET_DIR/python-venv/bin/python).
set -euo pipefail
tribo=$(realpath "${1:-target/release/tribo}")
py="${2:-${CARGO_TARGET_DIR:-target}/python-venv/bin/python}"
n="${3:-4096}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$py" - "$work" "$n" <<'PY'
import os, struct, sys
import numpy as np
d, n = sys.argv[1], int(sys.argv[2])
rng = np.random.default_rng(1)
z = np.cumsum(rng.normal(size=(n, n)), axis=1) * 1e-9  # m, rows along y
nm = z * 1e9
np.save(f"{d}/map.npy", z)
with open(f"{d}/map.tmd", "wb") as f:
    f.write(b"Binary TrueMap Data File v2.0\r\n\0")
    f.write(b"Created by bench".ljust(21) + b"\r\n\0")
    f.write(struct.pack("<IIffff", n, n, n * 0.1, n * 0.1, 0, 0))
    f.write((z * 1e6).astype("<f4").tobytes())
head = (f"fileformat = bcrf\nheadersize = 2048\nxpixels = {n}\nypixels = {n}\n"
        f"xlength = {n * 100}\nylength = {n * 100}\nxunit = nm\nyunit = nm\nzunit = nm\n"
        "bit2nm = 1\nintelmode = 1\nvoidpixels = 3.402823E+38\n").encode()
with open(f"{d}/map.bcrf", "wb") as f:
    f.write(head.ljust(2048, b"\0"))
    f.write(nm.astype("<f4").tobytes())
lo, hi = float(nm.min()), float(nm.max())
body = ("\r\n[Control]\r\n    X Amplitude: %d nm\r\n    Y Amplitude: %d nm\r\n"
        "\r\n[General Info]\r\n    Image Data Type: double\r\n    Number of columns: %d\r\n"
        "    Number of rows: %d\r\n    Z Amplitude: %r nm\r\n    Acquisition time: 03/11/2011, 20:23:46\r\n"
        "\r\n[Miscellaneous]\r\n    Maximum: %r\r\n    Minimum: %r\r\n\r\n[Header end]\r\n"
        % (n * 100, n * 100, n, n, hi - lo, hi, lo))
pre = "WSxM file copyright UAM\r\nSxM Image file\r\nImage header size: "
size = len(pre) + 6 + len(body)
with open(f"{d}/map.top", "wb") as f:
    f.write(("%s%06d%s" % (pre, size, body)).encode())
    f.write(nm.astype("<f8").tobytes())
rng_nid = 2 * max(abs(lo), abs(hi)) * 1e-9 * 1.01
raw = np.round(z / (rng_nid / 2**32)).astype("<i4")
nid = ("[DataSet]\r\nVersion=2\r\nGroupCount=1\r\nGr0-Name=Scan forward\r\nGr0-ID=0\r\nGr0-Count=1\r\n"
       "Gr0-Ch0=DataSet-0:0\r\n\r\n[DataSet-Info]\r\nDate=03-11-2022\r\nTime=11:46:25\r\n\r\n"
       f"[DataSet-0:0]\r\nVersion=2\r\nPoints={n}\r\nLines={n}\r\nFrame=Scan forward\r\n"
       f"Dim0Name=X*\r\nDim0Unit=m\r\nDim0Range={n * 1e-7}\r\nDim0Min=0\r\nDim1Name=Y*\r\nDim1Unit=m\r\n"
       f"Dim1Range={n * 1e-7}\r\nDim1Min=0\r\nDim2Name=Z-Axis\r\nDim2Unit=m\r\nDim2Range={rng_nid}\r\n"
       f"Dim2Min={-rng_nid / 2}\r\nSaveMode=Binary\r\nSaveBits=32\r\nSaveSign=Signed\r\nSaveOrder=Intel\r\n#!")
with open(f"{d}/map.nid", "wb") as f:
    f.write(nid.encode())
    f.write(raw[::-1].tobytes())
step = (hi - lo) * 1e-9 / 60000
counts = (np.round((z - z.min()) / step) + 2).astype("<u2")
blocks = [(0x66, struct.pack("<III", n, n, 16)),
          (0x67, struct.pack("<dddddI", n * 1e-6, n * 1e-6, 0, 0, 1, 0)),
          (0x6c, struct.pack("<Id", 5, step)),
          (0x0b, counts.tobytes())]
with open(f"{d}/map.frt", "wb") as f:
    f.write(b"FRTM_GLIDERV1.01" + struct.pack("<H", len(blocks)))
    for i, c in blocks:
        f.write(struct.pack("<HQ", i, len(c)) + c)
# Zygo DATX (HDF5, by h5py) as the real files are laid out
# (scripts/write-datx-variants.py): heights in µm, contiguous and, as
# `map-gz.datx`, chunked by rows of 256 and deflated.
try:
    import h5py
except ImportError:
    h5py = None
if h5py is not None:
    s = h5py.string_dtype("ascii")
    conv = np.dtype([("Category", s), ("BaseUnit", s), ("Parameters", h5py.vlen_dtype(np.float64))])
    def c(cat, unit, p):
        return np.array([(cat, unit, np.array(p, dtype=np.float64))], dtype=conv)
    for name, kw in [("map.datx", {}), ("map-gz.datx", {"chunks": (256, n), "compression": "gzip"})]:
        with h5py.File(f"{d}/{name}", "w") as f:
            ds = f.create_dataset("Data/Surface/{00000000-0000-0000-0000-000000000001}", data=z * 1e6, **kw)
            ds.attrs["No Data"] = np.array([np.finfo(np.float64).max])
            ds.attrs.create("Unit", np.array(["MicroMeters"], dtype=object), dtype=s)
            ds.attrs["X Converter"] = c("LateralCat", "Pixels", [0, 1e-7, 0, 0])
            ds.attrs["Y Converter"] = c("LateralCat", "Pixels", [0, 1e-7, 0, 0])
            ds.attrs["Z Converter"] = c("HeightCat", "MicroMeters", [0, 1, 0, 0])
            rows = [("Root", "Measurement", "{M}"), ("{M}", "Surface", "{00000000-0000-0000-0000-000000000001}")]
            f.create_dataset("MetaData", data=np.array(rows, dtype=object), dtype=s)
PY

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
secs() { # secs CMD...: wall seconds of one run
    local s e
    s=$(date +%s.%N)
    "$@" >/dev/null 2>&1 || { echo "failed: $*" >&2; exit 1; }
    e=$(date +%s.%N)
    echo "$e - $s" | bc -l
}
run3() { "$@" >/dev/null 2>&1 || true; for _ in $(seq "${REPS:-3}"); do secs "$@"; done | median; }

# SurfaceTopography: NPY holds no size, and SurfaceTopography 1.x finds none in
# a DATX file (it reads no X/Y Converter), so one is given.
ST='import sys, time
t0 = time.perf_counter()
from SurfaceTopography import read_topography as r
t1 = time.perf_counter()
kw = {"physical_sizes": (1.0, 1.0)} if sys.argv[1].endswith((".npy", ".datx")) else {}
r(sys.argv[1], **kw).heights()
print(time.perf_counter() - t1)'
st_read() { "$py" -c "$ST" "$1"; }
# The read alone, after the import, in the same process.
st_inproc() { st_read "$1" >/dev/null; for _ in $(seq "${REPS:-3}"); do st_read "$1"; done | median; }
imp=$(run3 "$py" -c "import SurfaceTopography")
echo "map ${n} x ${n}; $("$tribo" --version 2>/dev/null | head -1); import SurfaceTopography alone: ${imp} s"
printf "%-5s %7s %8s %8s %10s %9s %11s %9s %9s\n" format MB copy_s tribo_s tribo/copy ST_s ST/tribo ST_read_s read/tribo
for f in ${FORMATS:-npy tmd bcrf top nid frt datx gz.datx}; do
    p="$work/map.$f"
    [ "$f" = gz.datx ] && p="$work/map-gz.datx"
    [ -e "$p" ] || { echo "$f: not written (no h5py)"; continue; }
    mb=$(echo "$(stat -c %s "$p") / 1000000" | bc -l)
    copy=$(run3 sh -c "cat '$p' > /dev/null")
    t=$(run3 "$tribo" inspect "$p")
    s=$(run3 st_read "$p")
    sr=$(st_inproc "$p")
    printf "%-5s %7.1f %8.3f %8.3f %10.2f %9.3f %11.2f %9.3f %9.2f\n" "$f" "$mb" "$copy" "$t" \
        "$(echo "$t / $copy" | bc -l)" "$s" "$(echo "$s / $t" | bc -l)" "$sr" "$(echo "$sr / $t" | bc -l)"
done
