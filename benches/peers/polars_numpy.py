"""Peer for the ingest_extract benchmark: the same job as pandas_scipy.py
with polars + numpy only (no scipy).

usage: python3 polars_numpy.py TRACE.csv OUT.parquet [--traces]
"""
import sys

import numpy as np
import polars as pl


def running_median3(f):
    m = f.copy()
    m[1:-1] = np.median(np.stack([f[:-2], f[1:-1], f[2:]]), axis=0)
    return m


def features(fx):
    f = np.abs(fx)
    d = np.diff(f)
    noise = 1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(2.0)
    smooth = running_median3(f)
    # Static peak: the running maximum at the first drop below it by more
    # than the prominence threshold of pandas_scipy.py (the detachment).
    runmax = np.maximum.accumulate(smooth)
    drop = max(5.0 * noise, 0.05 * np.median(smooth))
    below = np.nonzero(smooth < runmax - drop)[0]
    static = float(runmax[below[0]]) if len(below) else float("nan")
    dynamic = float(f[len(f) // 2 :].mean())
    big = -d > 5.0 * noise
    n_slips = int(np.count_nonzero(big[1:] & ~big[:-1]) + big[0])
    return static, dynamic, n_slips


def main():
    src, out = sys.argv[1], sys.argv[2]
    df = pl.read_csv(src)
    t = df[:, 0].to_numpy()
    fx = df[:, 1].to_numpy() * 1e-3
    fz = df[:, 2].to_numpy() * 1e-3
    static, dynamic, n_slips = features(fx)
    pl.DataFrame(
        {"static_n": [static], "dynamic_n": [dynamic], "stick_slips": [n_slips]}
    ).write_parquet(out)
    if "--traces" in sys.argv:
        pl.DataFrame({"t_s": t, "fx_n": fx, "fz_n": fz}).write_parquet(out + ".traces.parquet")


if __name__ == "__main__":
    main()
