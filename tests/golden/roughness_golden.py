"""Golden numbers for tests/roughness_golden.rs, computed once with
established libraries: SurfaceTopography (Rq, Rdq, Sq, Sdq) and surfalize
(Ra, Rsk, Rku, Sa, Ssk, Sku). CI does not run this script; the numbers it
prints are kept in the Rust test.

    python -m venv env && env/bin/pip install SurfaceTopography surfalize
    env/bin/python tests/golden/roughness_golden.py

Versions used: SurfaceTopography 1.27.1, surfalize 0.19.2, numpy (as
installed with them). Inputs are the fixtures in fixtures/roughness/, with
the same window and form removal as the Rust side:
- Dektak profile: points whose printed x is in [468, 733] um, minus the
  least-squares line fitted against the printed x; spacing 0.15625 um (the
  least-squares grid of the whole scan).
- Nanovea map: 101 x 101 points, 5 um spacing, minus the least-squares
  plane.
"""
import numpy as np
import SurfaceTopography as st
from SurfaceTopography.Uniform.ScalarParameters import Rq, Rdq, Sq, rms_gradient
from surfalize import Profile, Surface

from prepared import dektak_window, nanovea_plane

# --- Dektak profile -------------------------------------------------------
h_um, dx_um = dektak_window()
h = h_um * 1e-6
dx = dx_um * 1e-6
print("dektak n", len(h), "dx_m", repr(dx))
t = st.UniformLineScan(h, physical_sizes=dx * len(h), periodic=False)
print("ST Rq_m", repr(Rq(t)))
print("ST Rdq (forward differences, slope)", repr(Rdq(t)))
p = Profile(h_um, dx_um, dx_um * len(h_um))
print("surfalize Ra_m", repr(p.Ra() * 1e-6))
print("surfalize Rsk", repr(p.Rsk()))
print("surfalize Rku", repr(p.Rku()))

# --- Nanovea map ----------------------------------------------------------
zl, step = nanovea_plane()
ny, nx = zl.shape
print("nanovea", nx, "x", ny)
topo = st.Topography(zl.T.copy(), physical_sizes=(step * nx, step * ny), periodic=False)
print("ST Sq_m", repr(Sq(topo)))
print("ST Sdq (forward differences, gradient)", repr(rms_gradient(topo)))
s = Surface(zl * 1e6, step * 1e6, step * 1e6)
print("surfalize Sa_m", repr(s.Sa() * 1e-6))
print("surfalize Ssk", repr(s.Ssk()))
print("surfalize Sku", repr(s.Sku()))
