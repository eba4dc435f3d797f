"""The fixtures as the golden scripts and the Rust tests see them, prepared
once for every script here (run from the repository's root):

- `dektak_window()`: the Dektak profile's points whose printed x is in
  [468, 733] um, minus the least-squares line fitted against the printed x;
  spacing the least-squares grid of the whole scan (0.15625 um). Returns
  (heights in um, spacing in um).
- `nanovea_plane()`: the Nanovea map, 101 x 101 points (rows along x at
  fixed y), minus the least-squares plane. Returns (heights in m, spacing
  in m).
"""
import numpy as np

ROOT = "fixtures/roughness/"


def dektak_window():
    lines = open(ROOT + "dektak/dektak-1.csv", encoding="latin-1").read().splitlines()
    i = lines.index("Lateral um,Raw Micrometer,")
    d = np.array([[float(a) for a in l.split(",")[:2]] for l in lines[i + 1:] if l.strip()])
    x_um, z_um = d[:, 0], d[:, 1]
    dx_um = np.polyfit(np.arange(len(x_um)), x_um, 1)[0]
    m = (x_um >= 468.0) & (x_um <= 733.0)
    xw, zw = x_um[m], z_um[m]
    return zw - np.polyval(np.polyfit(xw, zw, 1), xw), dx_um


def nanovea_plane():
    rows = [l.split(",") for l in open(ROOT + "nanovea/test1.txt").read().splitlines() if l.strip()]
    a = np.array([[float(v) for v in r] for r in rows])
    nx = int(np.sum(a[:, 1] == a[0, 1]))
    ny = len(a) // nx
    z = a[:, 2].reshape(ny, nx) * 1e-6
    yy, xx = np.mgrid[0:ny, 0:nx]
    A = np.c_[np.ones(nx * ny), xx.ravel(), yy.ravel()]
    coef, *_ = np.linalg.lstsq(A, z.ravel(), rcond=None)
    return z - (A @ coef).reshape(ny, nx), 0.005e-3
