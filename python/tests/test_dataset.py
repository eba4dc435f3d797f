"""The tables with many rows per input are Parquet datasets (out/traces/,
out/psd/, ...: one file per input): DuckDB, polars and pyarrow each read the
folder as one table, dictionary columns included, and the package reads it
as one DataFrame with the same rows."""

import json
from pathlib import Path

import polars as pl
import pytest
from polars.testing import assert_frame_equal

import tribo

LAB = "fixtures/lab"
SLEDS = [f"{LAB}/friction/sled_{p}_{m}g.csv" for p in ("A1", "F1") for m in (50, 100, 200)]
PROFILES = [f"{LAB}/profiles/{p}" for p in ("dektak-1.csv", "pin1_profile.csv", "test1.txt")]
KEY = ["source", "section", "time_s"]
# The roughness stage's dataset tables, each with the columns that order
# its rows.
CURVES = {
    "psd": ["source", "kind", "q_rad_per_m"],
    "acf": ["source", "kind", "direction", "lag_m"],
    "bearing_curve": ["source", "material_ratio"],
    "roughness_figures": ["source", "part", "figure"],
}


@pytest.fixture(scope="module")
def out(root, cli, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("dataset")
    r = cli("friction", *SLEDS, "--samples", f"{LAB}/samples.csv", "--out", out)
    assert r.returncode == 0, r.stderr
    return out


@pytest.fixture(scope="module")
def rough(root, cli, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("curves")
    r = cli("roughness", *PROFILES, "--out", out)
    assert r.returncode == 0, r.stderr
    return out


def canonical(df: pl.DataFrame, key=KEY) -> pl.DataFrame:
    """Dictionary columns as strings, rows in one order: a glob reader's
    file order is its own."""
    strings = [c for c, t in df.schema.items() if t in (pl.Categorical, pl.String) or isinstance(t, pl.Enum)]
    return df.with_columns(pl.col(strings).cast(pl.String)).sort(key)


def test_one_file_per_input_listed_by_the_manifest(out):
    files = sorted(p.name for p in (out / "traces").iterdir())
    manifest = json.loads((out / "traces.dataset.json").read_text())
    assert manifest["table"] == "traces"
    assert sorted(manifest["files"]) == files
    assert len(files) == len(SLEDS)
    # Nothing but Parquet in the folder: polars reads the folder itself.
    assert all(f.endswith(".parquet") for f in files)


def test_the_package_reads_one_table_in_input_order(out):
    df = tribo.read_table(out / "traces")
    assert isinstance(df.schema["source"], pl.Enum)
    sources = df["source"].cast(pl.String).unique(maintain_order=True).to_list()
    assert sources == sorted(SLEDS)  # the run's input order: by path
    per_file = [pl.read_parquet(out / "traces" / f).height for f in
                json.loads((out / "traces.dataset.json").read_text())["files"]]
    assert df.height == sum(per_file)
    assert df.height > 0


READERS = ["polars_glob", "polars_folder", "pyarrow", "duckdb"]


@pytest.mark.parametrize("reader", READERS)
def test_every_reader_sees_the_same_table(out, reader):
    ref = canonical(tribo.read_table(out / "traces"))
    df = read_with(reader, out / "traces")
    if reader == "polars_glob":
        assert df.schema["source"] == pl.Categorical
    if reader == "pyarrow":
        import pyarrow as pa
        import pyarrow.dataset as ds

        field = ds.dataset(str(out / "traces"), format="parquet").schema.field("source")
        assert pa.types.is_dictionary(field.type)
    assert df.columns == ref.columns
    assert_frame_equal(canonical(df), ref, check_dtypes=False, check_exact=True)


@pytest.mark.parametrize("table", sorted(CURVES))
@pytest.mark.parametrize("reader", READERS)
def test_every_reader_sees_each_curve_table_whole(rough, table, reader):
    files = json.loads((rough / f"{table}.dataset.json").read_text())["files"]
    assert sorted(files) == sorted(p.name for p in (rough / table).iterdir())
    # One file per profile; a file per input holds that input's rows alone.
    assert len(files) == len(PROFILES)
    for f in files:
        assert pl.read_parquet(rough / table / f)["source"].n_unique() == 1
    ref = tribo.read_table(rough / table)
    assert ref["source"].unique(maintain_order=True).to_list() == sorted(PROFILES)
    df = read_with(reader, rough / table)
    assert df.columns == ref.columns
    key = CURVES[table]
    assert_frame_equal(canonical(df, key), canonical(ref, key), check_dtypes=False, check_exact=True)


def read_with(reader: str, folder: Path) -> pl.DataFrame:
    """The dataset in `folder` as `reader` reads it."""
    if reader == "polars_glob":
        df = pl.scan_parquet(str(folder / "*.parquet")).collect()
    elif reader == "polars_folder":
        df = pl.scan_parquet(str(folder)).collect()
    elif reader == "pyarrow":
        ds = pytest.importorskip("pyarrow.dataset")
        df = pl.from_arrow(ds.dataset(str(folder), format="parquet").to_table())
    else:
        duckdb = pytest.importorskip("duckdb")
        df = duckdb.sql(f"select * from read_parquet('{folder}/*.parquet')").pl()
    return df
