"""Reference rows of the `psd` and `acf` tables for
tests/roughness_spectra_golden.rs, computed here with numpy (and scipy's
window and direct 2-D correlation) from the definitions in schemas/psd.toml,
schemas/acf.toml and MODELS.md §10, written afresh rather than translated
from src/extract/roughness/psd.rs and acf.rs. CI does not run this script;
the numbers it prints are kept in the Rust test.

    python3 tests/golden/roughness_spectra_golden.py

Versions used: numpy 2.4, scipy 1.17. The fixtures are prepared exactly as
tests/golden/roughness_golden.py prepares them:
- Dektak profile: points whose printed x is in [468, 733] um, minus the
  least-squares line fitted against the printed x; spacing the
  least-squares grid of the whole scan (0.15625 um).
- Nanovea map: 101 x 101 points, 5 um spacing, minus the least-squares
  plane.

PSD of the profile (schemas/psd.toml): C1D(q_k) = (dx^2 / L) |sum_i w_i h_i
exp(-i q_k x_i)|^2 with x_i = i dx, L = n dx, q_k = 2 pi k / L for k = 1 ..
n//2 - 1 (SurfaceTopography's grid, np.arange(n // 2) without q = 0), w the
periodic Hann window (scipy.signal.get_window("hann", n)) scaled to
mean(w^2) = 1. The sum is evaluated directly (a matrix of exponentials), not
by FFT. Bins: edges 10^linspace(log10 q_min - 0.01, log10 q_max + 0.01, m),
m = ceil((log10 q_max - log10 q_min + 1) * 10), q_min = 2 pi / L, q_max =
pi / dx; each bin's mean q and mean C (np.histogram with weights), empty
bins dropped.

ACF of the map (schemas/acf.toml): the heights minus their mean, R(t) =
sum h(r) h(r + t) / N(t) over the N(t) = (nx - |tx|)(ny - |ty|) pairs
(scipy.signal.correlate2d, direct sums), f = R / R(0). Radial rows: rings of
width w = max(min(dx, dy), r_max / 1000) about the origin, ring k holding
the lags of radius in [(k - 1/2) w, (k + 1/2) w) and at most r_max = min(lx
dx, ly dy) / 2 with lx = nx - 1, ly = ny - 1 (half the largest lag); each
ring's mean radius and mean f. Here dx = dy = w, so a lag (i, j) belongs to
ring k when (2k - 1)^2 <= 4 (i^2 + j^2) < (2k + 1)^2 and i^2 + j^2 <= 50^2:
integer arithmetic, no rounding at the ring edges (20 lags lie exactly at
r_max, e.g. (30, 40)). x and y rows: f at lags 0 .. lx/2 along each axis.
"""
import numpy as np
from scipy.signal import correlate2d, get_window

from prepared import dektak_window, nanovea_plane


def rust_rows(name, rows):
    """A Rust constant `const NAME: [[f64; k]; n]` holding `rows`."""
    rows = [list(r) for r in rows]
    print(f"const {name}: [[f64; {len(rows[0])}]; {len(rows)}] = [")
    for r in rows:
        print("    [" + ", ".join(repr(float(v)) for v in r) + "],")
    print("];")


def rust_list(name, values):
    print(f"const {name}: [f64; {len(values)}] = [")
    for v in values:
        print(f"    {float(v)!r},")
    print("];")


# --- Dektak profile: PSD --------------------------------------------------
h_um, dx_um = dektak_window()
h = h_um * 1e-6
dx = dx_um * 1e-6
n = len(h)
L = n * dx
w = get_window("hann", n)  # periodic (fftbins=True)
w = w / np.sqrt(np.mean(w**2))
k = np.arange(1, n // 2)
q = 2 * np.pi * k / L
# q_k x_i = 2 pi k i / n; the integer k i reduced modulo n keeps the phase
# exact to rounding however large k i grows.
F = np.exp(-2j * np.pi * (np.outer(k, np.arange(n)) % n) / n) @ (w * h)
C = dx**2 / L * np.abs(F) ** 2
# The same sum by FFT: a check of the direct sum, not used below.
C_fft = dx**2 / L * np.abs(np.fft.rfft(w * h)[1 : n // 2]) ** 2
print("# profile n", n, "dx", repr(dx), "direct vs FFT max rel", np.max(np.abs(C / C_fft - 1)))

q_min, q_max = 2 * np.pi / L, np.pi / dx
nb = int(np.ceil((np.log10(q_max) - np.log10(q_min) + 1) * 10))
edges = 10 ** np.linspace(np.log10(q_min) - 0.01, np.log10(q_max) + 0.01, nb)
count, _ = np.histogram(q, edges)
sum_q, _ = np.histogram(q, edges, weights=q)
sum_c, _ = np.histogram(q, edges, weights=C)
keep = count > 0
qb, cb = sum_q[keep] / count[keep], sum_c[keep] / count[keep]
# No q within rounding of a bin edge, so the side an edge falls on cannot
# differ between implementations.
print("# psd bins", nb - 1, "non-empty", keep.sum(), "closest q to an edge (rel)",
      np.min(np.abs(q[:, None] / edges[None, :] - 1)))
# The normalisation: with no window, (1/pi) sum C dq over k = 1 .. (n-1)/2
# is Rq^2 exactly (Parseval, h of zero mean); the grid's k stops at
# n//2 - 1, one short of (n-1)/2 for odd n (as SurfaceTopography's).
C0 = dx**2 / L * np.abs(np.fft.fft(h)) ** 2
dq = 2 * np.pi / L
print("# Rq^2", np.mean(h**2), "(1/pi) sum C dq, k<=(n-1)/2:", np.sum(C0[1 : (n - 1) // 2 + 1]) * dq / np.pi,
      "k<=n//2-1:", np.sum(C0[1 : n // 2]) * dq / np.pi)
rust_rows("PSD", np.c_[qb, 2 * np.pi / qb, cb])

# --- Nanovea map: ACF -----------------------------------------------------
hm, step = nanovea_plane()
ny, nx = hm.shape
hm = hm - hm.mean()
S = correlate2d(hm, hm, mode="full", boundary="fill")  # S[ny-1+j, nx-1+i] = sum h[r, c] h[r+j, c+i]
j = np.arange(-(ny - 1), ny)[:, None]
i = np.arange(-(nx - 1), nx)[None, :]
f = S / ((ny - np.abs(j)) * (nx - np.abs(i)))
f = f / f[ny - 1, nx - 1]
lx, ly = nx - 1, ny - 1
assert lx == ly == 100
r_max = min(lx, ly) * step / 2  # 50 steps
ring = max(step, r_max / 1000)
assert ring == step
K = 50
m2 = i**2 + j**2
radial = []
for kk in range(K + 1):
    lo = 0 if kk == 0 else (2 * kk - 1) ** 2
    sel = (4 * m2 >= lo) & (4 * m2 < (2 * kk + 1) ** 2) & (m2 <= K * K)
    radial.append((step * np.mean(np.sqrt(m2[sel])), np.mean(f[sel])))
print("# map", nx, "x", ny, "rings", len(radial))
rust_rows("ACF_RADIAL", radial)
rust_list("ACF_X", f[ny - 1, nx - 1 : nx - 1 + lx // 2 + 1])
rust_list("ACF_Y", f[ny - 1 : ny - 1 + ly // 2 + 1, nx - 1])
