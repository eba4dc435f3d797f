"""Golden numbers for the fractal fit in tests/roughness_golden.rs,
computed with numpy alone from MODELS.md section 4 and the method stated in
src/extract/roughness/fractal.rs (not from its code): the structure
function V(tau) = mean over pairs of (h(x + tau) - h(x))^2 at about 24 lags
spaced geometrically from 1 sample to floor(0.1 (n - 1)) samples (each
rounded to a whole sample, repeats dropped), an ordinary least-squares line
of ln V on ln tau, H = slope / 2, D = 2 - H, and that line's r^2. CI does
not run this script; the numbers it prints are kept in the Rust test.

    python3 tests/golden/fractal_golden.py

Input: the Dektak window of tests/golden/roughness_golden.py (points whose
printed x is in [468, 733] um, minus the least-squares line fitted against
the printed x; spacing 0.15625 um, the least-squares grid of the scan).
"""
import numpy as np

from prepared import dektak_window

h_um, dx_um = dektak_window()
h, dx = h_um * 1e-6, dx_um * 1e-6
n = len(h)
hi = int(np.floor(0.1 * (n - 1)))
lags = sorted(set(int(round(1 * (hi / 1) ** (k / 24))) for k in range(25)))
v = np.array([np.mean((h[l:] - h[:-l]) ** 2) for l in lags])
tau = np.array(lags) * dx
slope, icept = np.polyfit(np.log(tau), np.log(v), 1)
fit = icept + slope * np.log(tau)
r2 = 1 - np.sum((np.log(v) - fit) ** 2) / np.sum((np.log(v) - np.log(v).mean()) ** 2)
print("n", n, "lags", len(lags), lags[0], lags[-1])
print("hurst", repr(slope / 2), "dimension", repr(2 - slope / 2), "r2", repr(r2))
print("scales_m", repr(tau[0]), repr(tau[-1]))
