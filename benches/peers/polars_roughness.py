"""Roughness peer for the ingest_extract benchmark: a profile `x [um],z [um]`
read with polars, mean line removed, then Ra, Rq, Rsk, Rku, Rp, Rv, Rt and
the bearing (Abbott-Firestone) curve at 1 % steps of material ratio with
numpy, written to Parquet: the job of `tribo roughness FILE --detrend mean`.

usage: python3 polars_roughness.py PROFILE.csv OUT.parquet
"""
import sys

import numpy as np
import polars as pl

df = pl.read_csv(sys.argv[1])
z = df[:, 1].to_numpy() * 1e-6
z = z - z.mean()
rq = np.sqrt(np.mean(z * z))
row = {
    "Ra": [np.mean(np.abs(z))],
    "Rq": [rq],
    "Rsk": [np.mean(z**3) / rq**3],
    "Rku": [np.mean(z**4) / rq**4],
    "Rp": [z.max()],
    "Rv": [-z.min()],
    "Rt": [z.max() - z.min()],
}
pl.DataFrame(row).write_parquet(sys.argv[2])
mr = np.arange(0, 101) / 100.0
heights = np.quantile(z, 1.0 - mr)
pl.DataFrame({"mr": mr, "height_m": heights}).write_parquet(sys.argv[2] + ".bearing.parquet")
