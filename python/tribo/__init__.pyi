"""Type hints of the tribo package (units in each function's docstring)."""

import os
from typing import Any, Iterable, Mapping, Optional, Sequence, Union

import numpy as np
import polars as pl

PathLike = Union[str, os.PathLike[str]]
Paths = Union[PathLike, Iterable[PathLike]]

class TriboError(Exception):
    """A file or setting tribo cannot use; the message names the file, line
    and column, as the CLI prints it."""

def inspect(path: PathLike, format: Optional[str] = ...) -> dict[str, Any]:
    """Structure of one export (`tribo inspect --json`); raises TriboError."""

def read_table(path: PathLike) -> pl.DataFrame:
    """A published table as one DataFrame: a Parquet file, or a dataset
    folder (`out/traces`) in its manifest's order."""

class Map:
    """One channel of a map or profile file: `heights` (ny, nx) float64 in
    metres for heights (NaN not measured), spacing and origin in metres."""

    heights: np.ndarray
    channel: str
    unit: str
    dx_m: float
    dy_m: float
    x0_m: float
    y0_m: float
    n_invalid: int
    channels: list[tuple[str, str]]
    metadata: dict[str, str]
    @property
    def mask(self) -> np.ndarray: ...
    def masked(self) -> np.ma.MaskedArray: ...

def read(
    path: PathLike, format: Optional[str] = ..., channel: Optional[str] = ...
) -> Union[pl.DataFrame, Map]:
    """A map or profile file as a Map (its height channel, or `channel`);
    any other export in SI (`section` column, then `<channel>_<SI unit>`);
    raises TriboError."""

def friction(
    paths: Paths,
    samples: Optional[PathLike] = ...,
    *,
    out: Optional[PathLike] = ...,
    format: Optional[str] = ...,
    traces: bool = ...,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """`friction` (forces in N, μ), `friction_steps` (m/s),
    `friction_cycles`, `friction_tests`, `stickslip`, `traces` (SI) and
    `errors`; never raises for a bad file."""

def tensile(
    paths: Paths,
    samples: Optional[PathLike] = ...,
    *,
    out: Optional[PathLike] = ...,
    format: Optional[str] = ...,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """`tensile` (N, Pa, J/m³) and `errors`."""

def roughness(
    paths: Paths,
    samples: Optional[PathLike] = ...,
    *,
    out: Optional[PathLike] = ...,
    format: Optional[str] = ...,
    **params: Any,
) -> dict[str, pl.DataFrame]:
    """`roughness` (Ra, Rq in m; Rdq in rad and degrees) and `errors`."""

def fit_coulomb(
    friction: Union[pl.DataFrame, PathLike],
    by: Optional[Sequence[str]] = ...,
    *,
    samples: Optional[PathLike] = ...,
    reference: Sequence[str] = ...,
    huber: Optional[float] = ...,
) -> dict[str, pl.DataFrame]:
    """τ = τ0 + μ p (τ0 in Pa): `coulomb`, `coulomb_summary`, `errors`."""

def fit_ice(
    steps: Union[pl.DataFrame, PathLike],
    roughness: Union[pl.DataFrame, PathLike, None] = ...,
    *,
    delta_t: Optional[float] = ...,
    fit_delta_t: bool = ...,
    misfit_tol: float = ...,
) -> dict[str, pl.DataFrame]:
    """Makkonen fit (ΔT in K, v in m/s): `ice_fit`, `ice_residuals`, `errors`."""

def run(pipeline: PathLike, out: Optional[PathLike] = ...) -> dict[str, pl.DataFrame]:
    """Every table a pipeline file publishes, `errors` included."""

def schema(path: PathLike) -> dict[str, dict[str, str]]:
    """Each column's `unit` and `description` from a tribo Parquet file."""
