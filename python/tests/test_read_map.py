"""tribo.read on map files: the heights as a NumPy array with the spacing,
unit, mask and channels, equal to what the CLI's inspect says of them and
to the values the files were written with (tests/binary_keyence.rs writes
the fixtures: a 16 x 12 wave surface)."""

import json

import numpy as np
import pytest

import tribo


def waves(nx=16, ny=12, a=2e-7, b=5e-8):
    c = np.arange(nx)
    r = np.arange(ny)[:, None]
    return a * np.sin(2 * np.pi * c / 16) + b * np.cos(2 * np.pi * r / 8)


@pytest.mark.parametrize(
    "name, quantum, shift",
    [("waves-16x12.zon", 1e-9, 0.0), ("waves-16x12.vk4", 1e-11, 1e-6)],
)
def test_keyence_maps_read_back(root, name, quantum, shift):
    m = tribo.read(root / "fixtures/surface" / name)
    assert isinstance(m, tribo.Map)
    assert m.heights.shape == (12, 16) and m.unit == "m" and m.channel == "Height"
    assert m.dx_m == pytest.approx(1e-6, rel=1e-12) and m.dy_m == pytest.approx(1e-6, rel=1e-12)
    want = np.round((waves() + shift) / quantum) * quantum
    if name.endswith(".zon"):
        want.flat[5] = np.nan
    np.testing.assert_allclose(m.heights, want, rtol=0, atol=1e-18)
    assert m.n_invalid == int(np.isnan(want).sum()) == int(m.mask.sum())
    assert m.masked().count() == want.size - m.n_invalid
    assert m.metadata["instrument"].startswith("Keyence")


def test_channel_is_selectable_and_matches_inspect(root, cli):
    f = root / "fixtures/surface/waves-16x12.plux"
    m = tribo.read(f, channel="Layer 1")
    assert m.channel == "Layer 1" and [c for c, _ in m.channels] == ["Layer 0", "Layer 1"]
    want = 2 * waves()
    want.flat[5] = np.nan
    np.testing.assert_allclose(m.heights, want, rtol=0, atol=1e-12)
    assert m.n_invalid == 1
    out = json.loads(cli("inspect", "--json", f).stdout)
    grids = out[0]["grids"]
    assert (grids[0]["nx"], grids[0]["ny"], grids[0]["dx_m"]) == (16, 12, m.dx_m)
    assert grids[1]["decoded"] is False


def test_profile_is_one_row_and_text_exports_stay_tables(root):
    m = tribo.read(root / "fixtures/surface/sdf-1.sdf")
    assert isinstance(m, tribo.Map) and m.heights.shape == (4, 7)
    df = tribo.read(root / "fixtures/friction/hbm_catman_reibung.txt")
    assert not isinstance(df, tribo.Map) and df.height > 0


def test_datx_real_file(root):
    # Expected values from h5py + numpy on the same file (tests/binary_datx.rs).
    m = tribo.read(root / "fixtures/surface/zygo_test.datx")
    assert isinstance(m, tribo.Map) and m.heights.shape == (259, 33) and m.unit == "m"
    assert m.n_invalid == 776 == int(m.mask.sum())
    assert m.dx_m == pytest.approx(0.0010000000474974513, rel=1e-15)
    assert np.nanstd(m.heights) == pytest.approx(8.08176526396592e-08, rel=1e-12)
    assert m.heights[100, 10] == pytest.approx(1.4161572464506053e-07, rel=1e-14)
    assert m.metadata["instrument"] == "Zygo GPI (serial 651365)"
