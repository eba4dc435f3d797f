"""The areal parameters and the PSD of `tribo roughness` against the peers a
user would otherwise use: surfalize (parameters) and SurfaceTopography
(PSD), on a seeded random surface with a lay. Skips without them (they are
never dependencies): pip install surfalize SurfaceTopography.

Measured (surfalize 0.19.2, SurfaceTopography 1.27.1): amplitude, heights
and Sdr agree to 1e-13; Sk, Smr1, Smr2, Sxp, Vvc, Vvv, Str to 1e-4; Spk,
Svk, Vmp, Vmc, Sal, Sdq to 2e-3 (the material-ratio curve's interpolation,
the ACF's ray search and the slope stencil differ); the PSD to 3e-10."""

import math

import polars as pl
import pytest

np = pytest.importorskip("numpy")

N, DX_UM = 256, 0.5


def surface():
    """Gaussian-correlated heights (correlation ~5 µm, Sq 0.2 µm) plus a
    sine lay along y of 16 µm, mean zero; rows are y, columns x (µm)."""
    rng = np.random.default_rng(7)
    k = np.fft.fftfreq(N, DX_UM)
    kx, ky = np.meshgrid(k, k)
    f = np.exp(-(kx**2 + ky**2) * (np.pi * 5.0) ** 2 / 4)
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((N, N))) * f))
    z = z / z.std() * 0.2
    z += 0.1 * np.sin(2 * np.pi * np.arange(N) * DX_UM / 16.0)[None, :]
    return z - z.mean()


def run(cli, tmp_path, z):
    path = tmp_path / "surface.txt"
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(f"# Width: {N * DX_UM} µm\n# Height: {N * DX_UM} µm\n# Value units: µm\n")
        for row in z:
            fh.write("\t".join(f"{v:.15e}" for v in row) + "\n")
    out = tmp_path / "out"
    r = cli("roughness", path, "--out", out, "--detrend", "mean")
    assert r.returncode == 0, r.stderr
    return out


def test_areal_parameters_agree_with_surfalize(cli, tmp_path):
    surfalize = pytest.importorskip("surfalize")
    z = surface()
    row = pl.read_parquet(run(cli, tmp_path, z) / "roughness.parquet").row(0, named=True)
    s = surfalize.Surface(z.copy(), DX_UM, DX_UM)
    um = 1e-6
    # (surfalize's name, ours, factor from our SI to surfalize's unit)
    pairs = [
        ("Sa", "Sa_m", 1 / um), ("Sq", "Sq_m", 1 / um), ("Ssk", "Ssk", 1),
        ("Sku", "Sku", 1), ("Sp", "Sp_m", 1 / um), ("Sv", "Sv_m", 1 / um),
        ("Sz", "Sz_m", 1 / um), ("Sdr", "Sdr", 100), ("Sal", "Sal_m", 1 / um),
        ("Str", "Str", 1), ("Sk", "Sk_m", 1 / um), ("Spk", "Spk_m", 1 / um),
        ("Svk", "Svk_m", 1 / um), ("Smr1", "Smr1", 100), ("Smr2", "Smr2", 100),
        ("Sxp", "Sxp_m", 1 / um), ("Vmp", "Vmp_m3_per_m2", 1 / um),
        ("Vmc", "Vmc_m3_per_m2", 1 / um), ("Vvc", "Vvc_m3_per_m2", 1 / um),
        ("Vvv", "Vvv_m3_per_m2", 1 / um),
    ]
    off = {}
    for theirs, ours, factor in pairs:
        ref = float(getattr(s, theirs)())
        got = row[ours] * factor
        if abs(got - ref) > 0.01 * abs(ref):
            off[theirs] = (got, ref)
    # Sdq: ours is an angle; the 7-point stencil against numpy's gradient.
    sdq = math.tan(math.radians(row["Sdq_deg"]))
    if abs(sdq - float(s.Sdq())) > 0.01 * float(s.Sdq()):
        off["Sdq"] = (sdq, float(s.Sdq()))
    # Std: the lay is along y, the dominant wavevector along x: 0°.
    std = row["Std_deg"]
    if min(std, 180 - std) > 0.5 or abs(float(s.Std()) % 180) > 0.5:
        off["Std"] = (std, float(s.Std()))
    assert not off, off


def test_psd_agrees_with_surfacetopography(cli, tmp_path):
    st = pytest.importorskip("SurfaceTopography")
    z = surface()
    psd = pl.read_parquet(run(cli, tmp_path, z) / "psd" / "*.parquet")
    t = st.Topography(z.T * 1e-6, (N * DX_UM * 1e-6, N * DX_UM * 1e-6), periodic=False)
    q, c = t.power_spectrum_from_area()
    q, c = np.ma.filled(q, np.nan), np.ma.filled(c, np.nan)
    keep = np.isfinite(q) & np.isfinite(c)
    q, c = q[keep], c[keep]
    assert psd.height == len(q)
    np.testing.assert_allclose(psd["q_rad_per_m"].to_numpy(), q, rtol=1e-9)
    np.testing.assert_allclose(psd["psd_m4"].to_numpy(), c, rtol=1e-6)
