"""tribo from Python: raw tribology exports to SI tables, features and fits.

Every function runs the same library code as the ``tribo`` command line and
returns polars DataFrames (``.to_pandas()`` for pandas). Tables are the
Parquet files a run publishes, read with polars, so the numbers are the
CLI's to the last bit; the files keep the provenance (``tribo.*`` keys) in
the Arrow schema metadata and each column's ``unit`` and ``description`` as
field metadata (see :func:`schema`).

Units: every column is in SI and its name ends with the unit
(``friction_force_N``, ``time_s``, ``velocity_m_per_s``, ``temperature_K``,
``pressure_Pa``); the field metadata gives the unit of every column.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable, Mapping, Optional, Sequence, Union

import numpy as np
import polars as pl

from . import _tribo
from ._tribo import TriboError

__all__ = [
    "TriboError",
    "inspect",
    "read",
    "Map",
    "friction",
    "tensile",
    "roughness",
    "fit_coulomb",
    "fit_ice",
    "run",
    "read_table",
    "schema",
]

PathLike = Union[str, "os.PathLike[str]"]


def inspect(path: PathLike, format: Optional[str] = None) -> dict:
    """The structure of one export, as ``tribo inspect --json`` prints it.

    Keys: ``source``, ``format`` (the reader), ``dialect``, ``sha256``,
    ``preamble`` (metadata lines with their line numbers) and ``sections``
    (rows, sample rate in Hz, each column's unit as written and its SI
    unit). Raises :class:`TriboError` naming the file, line and column for a
    file tribo cannot read.
    """
    return json.loads(_tribo.inspect(os.fspath(path), format))


def _column(name: str, si: str) -> str:
    return f"{name}_{si.replace('/', '_per_')}" if si else name


@dataclass(frozen=True)
class Map:
    """One channel of a map or profile file (X3P, SUR, ZON, ...), as
    :func:`read` gives it.

    ``heights`` is an ``(ny, nx)`` float64 array (a profile has ``ny`` 1),
    row ``r`` at y = ``y0_m`` + r·``dy_m``, in metres for a height channel
    (``unit`` ``"m"``) and in ``unit`` otherwise; NaN where the instrument
    measured nothing, which ``mask`` marks (True = not measured, as in
    ``numpy.ma``). ``channels`` lists every channel of the file as
    ``(name, unit)``; ``metadata`` holds the file's keys (``instrument``,
    ``acquisition_date``, ...)."""

    heights: np.ndarray
    channel: str
    unit: str
    dx_m: float
    dy_m: float
    x0_m: float
    y0_m: float
    n_invalid: int
    channels: list
    metadata: dict

    @property
    def mask(self) -> np.ndarray:
        return np.isnan(self.heights)

    def masked(self) -> np.ma.MaskedArray:
        """The heights as a masked array (points not measured masked)."""
        return np.ma.masked_invalid(self.heights)


def read(
    path: PathLike, format: Optional[str] = None, channel: Optional[str] = None
) -> Union[pl.DataFrame, Map]:
    """One export: a :class:`Map` for a map or profile file (its height
    channel, or the one named by ``channel``), else a DataFrame in SI units,
    one row per sample.

    The DataFrame's first column, ``section``, names the step or table of the file
    (``1``, ``2``, ... or the instrument's own name); then one column per
    channel, converted to the SI unit of its quantity and named
    ``<channel>_<SI unit>`` (``/`` written ``_per_``): N, kg, s, m, m/s, Pa,
    K, ... A channel without a unit keeps its name and values. Masses stay
    masses (kg); the friction stages read a mass column as a force.
    Sections with different channels leave nulls where a channel is absent.
    Raises :class:`TriboError` naming the file for an unreadable file.
    """
    sections, grid = _tribo.read(os.fspath(path), format, channel)
    if grid is not None:
        name, unit, (nx, ny), (dx, dy, x0, y0), raw, n_invalid, channels, meta = grid
        heights = np.frombuffer(raw, dtype="<f8").reshape(ny, nx).copy()
        return Map(
            heights=heights,
            channel=name,
            unit=unit,
            dx_m=dx,
            dy_m=dy,
            x0_m=x0,
            y0_m=y0,
            n_invalid=n_invalid,
            channels=[(n, u) for n, u, _ in channels],
            metadata=dict(meta),
        )
    frames = []
    for section, columns in sections:
        data: dict[str, Any] = {}
        rows = len(columns[0][2]) if columns else 0
        data["section"] = [section] * rows
        for name, si, values in columns:
            data[_column(name, si)] = pl.Series(values, dtype=pl.Float64).fill_nan(None)
        frames.append(pl.DataFrame(data))
    if not frames:
        return pl.DataFrame({"section": pl.Series([], dtype=pl.String)})
    return pl.concat(frames, how="diagonal")


def read_table(path: PathLike) -> pl.DataFrame:
    """A table a run published, as one DataFrame: a Parquet file
    (``out/friction.parquet``), or a dataset folder (``out/traces``, one
    file per input) read in the order its published manifest
    (``out/traces.dataset.json``) lists its files, so that a run in
    progress is never half seen. Dictionary columns (``source``,
    ``section``) are ``pl.Enum`` over their values in order of first
    appearance, as in a single file."""
    path = Path(path)
    if not path.is_dir():
        return pl.read_parquet(path)
    manifest = json.loads(path.with_name(path.name + ".dataset.json").read_text())
    files = [str(path / f) for f in manifest["files"]]
    if not files:
        return pl.DataFrame()
    df = pl.concat([pl.read_parquet(f) for f in files], how="vertical_relaxed")
    enums = {
        c: pl.Enum(df[c].cast(pl.String).unique(maintain_order=True).drop_nulls().to_list())
        for c, t in df.schema.items()
        if t == pl.Categorical
    }
    return df.with_columns(pl.col(c).cast(pl.String).cast(e) for c, e in enums.items())


def _tables(outputs: Sequence[str]) -> dict[str, pl.DataFrame]:
    tables = {}
    for p in map(Path, outputs):
        if p.suffix == ".parquet" or p.is_dir():
            tables[p.name.removesuffix(".parquet")] = read_table(p)
    return tables


def _stage(
    stage: str,
    paths: Union[PathLike, Iterable[PathLike]],
    samples: Optional[PathLike],
    out: Optional[PathLike],
    format: Optional[str],
    traces: bool,
    params: Mapping[str, Any],
) -> dict[str, pl.DataFrame]:
    files = [os.fspath(paths)] if isinstance(paths, (str, os.PathLike)) else [os.fspath(p) for p in paths]
    with tempfile.TemporaryDirectory(prefix="tribo-") as tmp:
        outputs, _summary = _tribo.run_stage(
            stage,
            files,
            os.fspath(out) if out is not None else tmp,
            os.fspath(samples) if samples is not None else None,
            format,
            json.dumps(dict(params)),
            traces,
        )
        return _tables(outputs)


def friction(
    paths: Union[PathLike, Iterable[PathLike]],
    samples: Optional[PathLike] = None,
    *,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    traces: bool = True,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """Friction features of traces, as ``tribo friction`` computes them.

    ``paths``: files or globs. ``samples``: the manifest CSV (normal force in
    N or mass in g, apparent area in m², pattern) joined on the file name.
    ``params``: the keys of a pipeline's ``[friction]`` table
    (``median_window``, ``peak_noise_factor``, ``plateau_tolerance``, ...).
    Returns ``friction`` (static and kinetic force in N, μ), ``friction_steps``
    (per velocity step, m/s), ``friction_cycles`` (per stroke or lap),
    ``friction_tests`` (running-in and steady μ per test), ``stickslip``,
    ``traces`` (every sample in SI, unless ``traces=False``; ``source`` and
    ``section`` are ``pl.Enum`` columns, dictionary-encoded) and ``errors`` (one row per file that failed,
    as the CLI writes it; never an exception). ``out``: also keep the
    Parquet files in this folder.
    """
    return _stage("friction", paths, samples, out, format, traces, params)


def tensile(
    paths: Union[PathLike, Iterable[PathLike]],
    samples: Optional[PathLike] = None,
    *,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """Fibre tests, as ``tribo tensile``: strength (N, Pa), strain at
    break, toughness (J/m³) and knot release per curve in ``tensile``,
    with ``errors``. ``params``: keys of a pipeline's ``[tensile]`` table."""
    return _stage("tensile", paths, samples, out, format, True, params)


def roughness(
    paths: Union[PathLike, Iterable[PathLike]],
    samples: Optional[PathLike] = None,
    *,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """Surface profiles and maps, as ``tribo roughness``: Ra, Rq (m), Rdq
    (rad and degrees), ... per profile in ``roughness``, with
    ``bearing_curve``, ``psd``, ``acf`` and ``errors``.
    ``params``: keys of a pipeline's ``[roughness]`` table."""
    return _stage("roughness", paths, samples, out, format, True, params)


def _write(df: Union[pl.DataFrame, PathLike], tmp: str, name: str) -> str:
    if isinstance(df, (str, os.PathLike)):
        return os.fspath(df)
    path = os.path.join(tmp, f"{name}.parquet")
    df.write_parquet(path)
    return path


def _table_stage(stage: str, settings: dict, inputs: dict) -> dict[str, pl.DataFrame]:
    with tempfile.TemporaryDirectory(prefix="tribo-") as tmp:
        settings = {k: v for k, v in settings.items() if v is not None}
        settings["inputs"] = {
            name: _write(df, tmp, name) for name, df in inputs.items() if df is not None
        }
        outputs, _summary = _tribo.run_stage(
            stage, [], os.path.join(tmp, "out"), None, None, json.dumps(settings), True
        )
        return _tables(outputs)


def fit_coulomb(
    friction: Union[pl.DataFrame, PathLike],
    by: Optional[Sequence[str]] = None,
    *,
    samples: Optional[PathLike] = None,
    reference: Sequence[str] = ("F", "flat"),
    huber: Optional[float] = None,
) -> dict[str, pl.DataFrame]:
    """Coulomb law with cohesion, τ = τ0 + μ p (MODELS.md §2), as
    ``tribo fit coulomb``: τ0 in Pa and μ per group in ``coulomb``, the
    pattern summary (Eq. 4.2) in ``coulomb_summary``, and ``errors``.

    ``friction``: the ``friction`` table of :func:`friction` (or its
    Parquet file). ``by``: grouping columns (default ``sample_id`` and
    ``pattern``). ``huber``: Huber threshold for a robust fit.
    """
    settings = {
        "by": list(by) if by is not None else None,
        "reference": list(reference),
        "huber": huber,
        "samples": os.fspath(samples) if samples is not None else None,
    }
    return _table_stage("coulomb", settings, {"friction": friction})


def fit_ice(
    steps: Union[pl.DataFrame, PathLike],
    roughness: Union[pl.DataFrame, PathLike, None] = None,
    *,
    delta_t: Optional[float] = None,
    fit_delta_t: bool = False,
    misfit_tol: float = 0.15,
) -> dict[str, pl.DataFrame]:
    """Makkonen ice-friction model with ALSFM roughness bounds (MODELS.md
    §6), as ``tribo fit ice``: ``ice_fit`` (parameters, ΔT in K, status),
    ``ice_residuals`` (μ measured and modelled per velocity in m/s) and
    ``errors``. ``steps``: the ``friction_steps`` table; ``roughness``: a
    table with ``pin`` and ``Rdq_deg`` when the steps carry no ``Rdq_deg``.
    ``misfit_tol``: relative RMSE above which a fit is flagged.
    """
    settings = {"delta_t": delta_t, "fit_delta_t": fit_delta_t, "misfit_tol": misfit_tol}
    return _table_stage("ice", settings, {"friction_steps": steps, "roughness": roughness})


def run(pipeline: PathLike, out: Optional[PathLike] = None) -> dict[str, pl.DataFrame]:
    """Runs a pipeline file as ``tribo run`` does and returns every table it
    published, ``errors`` included. Tables are published in the pipeline's
    ``[output] dir`` (relative to the file), or in ``out`` when given."""
    outputs, _summary = _tribo.run_file(
        os.fspath(pipeline), os.fspath(out) if out is not None else None
    )
    return _tables(outputs)


def schema(path: PathLike) -> dict[str, dict[str, str]]:
    """Each column's ``unit`` and ``description`` from a tribo Parquet
    file's field metadata (read with pyarrow when installed)."""
    import pyarrow.parquet as pq

    return {
        f.name: {k.decode(): v.decode() for k, v in (f.metadata or {}).items()}
        for f in pq.read_schema(os.fspath(path))
    }
