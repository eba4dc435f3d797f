"""Each function returns the numbers of the CLI's Parquet on the same inputs:
the CLI is the independent reference here (its own tests check the science)."""

from pathlib import Path

import polars as pl
import pytest
from polars.testing import assert_frame_equal

import tribo

LAB = "fixtures/lab"
SLEDS = [f"{LAB}/friction/sled_{p}_{m}g.csv" for p in ("A1", "F1") for m in (50, 100, 200)]


def cli_tables(out: Path) -> dict[str, pl.DataFrame]:
    tables = {p.stem: pl.read_parquet(p) for p in sorted(out.glob("*.parquet"))}
    # A dataset (out/traces: one file per input) as one table
    # (test_dataset.py checks this reading against DuckDB, polars, pyarrow).
    for m in out.glob("*.dataset.json"):
        name = m.name.removesuffix(".dataset.json")
        tables[name] = tribo.read_table(out / name)
    return tables


def same_tables(py: dict, ref: dict) -> None:
    assert set(py) == set(ref), (sorted(py), sorted(ref))
    for name, df in ref.items():
        assert_frame_equal(py[name], df, check_exact=True)


def test_friction(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    r = cli("friction", *SLEDS, "--samples", f"{LAB}/samples.csv", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    ref = cli_tables(tmp_path)
    py = tribo.friction(SLEDS, samples=f"{LAB}/samples.csv")
    same_tables(py, ref)
    assert py["friction"].height == len(SLEDS)
    assert py["friction"]["static_force_N"].null_count() < py["friction"].height


def test_friction_params(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    (tmp_path / "p.toml").write_text("median_window = 5\nplateau_tolerance = 0.05\n")
    out = tmp_path / "out"
    r = cli("friction", SLEDS[0], "--params", tmp_path / "p.toml", "--out", out, "--no-traces")
    assert r.returncode in (0, 1), r.stderr
    py = tribo.friction(SLEDS[0], traces=False, median_window=5, plateau_tolerance=0.05)
    same_tables(py, cli_tables(out))
    assert "traces" not in py


def test_tensile(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    files = sorted(str(p.relative_to(root)) for p in (root / LAB / "fibres").iterdir())
    r = cli("tensile", *files, "--out", tmp_path)
    assert r.returncode in (0, 1), r.stderr
    same_tables(tribo.tensile(files), cli_tables(tmp_path))


def test_roughness(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    files = sorted(str(p.relative_to(root)) for p in (root / LAB / "profiles").iterdir())
    r = cli("roughness", *files, "--out", tmp_path)
    assert r.returncode in (0, 1), r.stderr
    py = tribo.roughness(files)
    same_tables(py, cli_tables(tmp_path))
    assert py["roughness"].height >= len(files)


def test_fit_coulomb(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    fr = tmp_path / "fr"
    assert cli("friction", *SLEDS, "--samples", f"{LAB}/samples.csv", "--out", fr).returncode == 0
    out = tmp_path / "co"
    r = cli("fit", "coulomb", fr / "friction.parquet", "--out", out, "--by", "sample_id")
    assert r.returncode in (0, 1), r.stderr
    friction = tribo.friction(SLEDS, samples=f"{LAB}/samples.csv", traces=False)["friction"]
    same_tables(tribo.fit_coulomb(friction, by=["sample_id"]), cli_tables(out))


def test_fit_ice(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    fr, ro, ice = tmp_path / "fr", tmp_path / "ro", tmp_path / "ice"
    pin = f"{LAB}/friction/pod_pin1_-10C.tsv"
    assert cli("friction", pin, "--samples", f"{LAB}/samples.csv", "--out", fr).returncode == 0
    # The pin's profile with its manifest row (`tribo roughness` takes none).
    spec = tmp_path / "ro.toml"
    spec.write_text(
        f'stages = ["roughness"]\n[input]\nfiles = ["{root}/{LAB}/profiles/pin1_profile.csv"]\n'
        f'samples = "{root}/{LAB}/samples.csv"\n[output]\ndir = "{ro}"\n'
    )
    assert cli("run", spec).returncode == 0
    r = cli("fit", "ice", fr / "friction_steps.parquet", "--roughness", ro / "roughness.parquet", "--out", ice)
    assert r.returncode in (0, 1), r.stderr
    steps = tribo.friction(pin, samples=f"{LAB}/samples.csv")["friction_steps"]
    assert_frame_equal(steps, pl.read_parquet(fr / "friction_steps.parquet"))
    py = tribo.fit_ice(steps, roughness=pl.read_parquet(ro / "roughness.parquet"))
    same_tables(py, cli_tables(ice))
    assert py["ice_fit"].height >= 1
    same_tables(tribo.run(spec, out=tmp_path / "ro-py"), cli_tables(ro))


def test_run_demo(root, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(root)
    r = cli("run", "pipelines/demo.toml", "--out", tmp_path / "cli")
    assert r.returncode in (0, 1), r.stderr
    py = tribo.run("pipelines/demo.toml", out=tmp_path / "py")
    same_tables(py, cli_tables(tmp_path / "cli"))
    for table in ("friction", "coulomb", "ice_fit", "tensile", "roughness", "errors"):
        assert table in py


def test_read_is_the_si_trace(root, cli, tmp_path, monkeypatch):
    """`read` against the friction stage's `traces` table of the same file:
    the same SI samples reached by another path through the library."""
    monkeypatch.chdir(root)
    f = "fixtures/friction/sled_mN.csv"
    df = tribo.read(f)
    assert df.columns[0] == "section"
    traces = tribo.friction(f)["traces"]
    assert df.height == traces.height
    force = [c for c in df.columns if c.endswith("_N")]
    assert any(df[c].to_list() == traces["friction_force_N"].to_list() for c in force), force


def test_quickstart_reproduces_the_demo(root):
    """examples/quickstart.py checks its fits against the generating values
    (thesis Table 4.2, a = 5 mm) and exits non-zero when off."""
    import subprocess
    import sys

    r = subprocess.run([sys.executable, "examples/quickstart.py"], cwd=root, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "a = 5.0" in r.stdout
