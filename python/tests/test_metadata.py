"""The tables explain themselves from pyarrow, polars and DuckDB, and a bad
file raises naming it."""

import json
from pathlib import Path

import polars as pl
import pytest

import tribo

SLED = "fixtures/lab/friction/sled_A1_100g.csv"


@pytest.fixture()
def friction_dir(root, tmp_path, monkeypatch) -> Path:
    monkeypatch.chdir(root)
    tribo.friction(SLED, samples="fixtures/lab/samples.csv", out=tmp_path)
    return tmp_path


def test_pyarrow_sees_provenance_and_units(friction_dir):
    pq = pytest.importorskip("pyarrow.parquet")
    schema = pq.read_schema(friction_dir / "friction.parquet")
    keys = {k.decode() for k in schema.metadata}
    assert any(k.startswith("tribo.") for k in keys), keys
    units = {f.name: f.metadata[b"unit"].decode() for f in schema if f.metadata and b"unit" in f.metadata}
    assert units.get("static_force_N") == "N", units
    assert all(f.metadata and f.metadata.get(b"description") for f in schema)
    assert tribo.schema(friction_dir / "friction.parquet")["static_force_N"]["unit"] == "N"


def test_polars_sees_provenance(friction_dir):
    meta = pl.read_parquet_metadata(friction_dir / "friction.parquet")
    assert any(k.startswith("tribo.") for k in meta), meta


def test_duckdb_sees_provenance_and_units(friction_dir):
    duckdb = pytest.importorskip("duckdb")
    path = str(friction_dir / "friction.parquet")
    kv = duckdb.sql(f"select key::varchar from parquet_kv_metadata('{path}')").fetchall()
    assert any(k[0].startswith("tribo.") for k in kv), kv
    # The Arrow schema (with the field metadata) is stored under ARROW:schema.
    assert any(k[0] == "ARROW:schema" for k in kv)


def test_bad_file_raises_naming_it(root, cli, monkeypatch):
    """The CLI's message (file, line, column), as a Python exception."""
    monkeypatch.chdir(root)
    for name in ("bad_cell.csv", "empty.csv"):
        path = f"fixtures/bad/{name}"
        r = cli("inspect", path)
        message = r.stderr.strip().removeprefix("error: ")
        assert name in message
        with pytest.raises(tribo.TriboError) as read_error:
            tribo.read(path)
        with pytest.raises(tribo.TriboError) as inspect_error:
            tribo.inspect(path)
        assert str(read_error.value) == str(inspect_error.value) == message
    # Inspect shows an unknown unit as such; reading into SI cannot.
    with pytest.raises(tribo.TriboError, match=r"unknown_unit\.csv.*furlong"):
        tribo.read("fixtures/bad/unknown_unit.csv")
    assert issubclass(tribo.TriboError, Exception)


def test_batch_never_raises_for_a_bad_file(root, monkeypatch):
    monkeypatch.chdir(root)
    out = tribo.friction(["fixtures/bad/bad_cell.csv", SLED])
    assert out["errors"].height >= 1
    assert "bad_cell.csv" in " ".join(out["errors"]["source"].to_list())
    assert out["friction"].height == 1


def test_inspect_is_the_cli_json(root, cli, monkeypatch):
    monkeypatch.chdir(root)
    r = cli("inspect", "--json", SLED)
    assert r.returncode == 0, r.stderr
    assert [tribo.inspect(SLED)] == json.loads(r.stdout)
