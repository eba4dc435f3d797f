"""Peer for the ingest_extract benchmark: the friction features of one trace
with pandas + scipy, so that tribo's speed can be stated as a ratio.

usage: python3 pandas_scipy.py TRACE.csv OUT.parquet [--traces]

Reads a CSV `t (s),Fx [mN],Fz [mN]`, converts to SI, takes the static peak
(first prominent maximum of |Fx| on a 3-sample running median), the dynamic
mean (mean |Fx| over the second half) and the stick-slip count (drops larger
than 5 noise sigmas, noise from the MAD of first differences / sqrt 2, as in
src/signal/stats.rs), and writes a one-row Parquet; with --traces the trace
in SI as well.
"""
import sys

import numpy as np
import pandas as pd
from scipy.signal import find_peaks, medfilt


def features(t, fx):
    f = np.abs(fx)
    d = np.diff(f)
    noise = 1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(2.0)
    smooth = medfilt(f, 3)
    level = np.median(smooth)
    peaks, _ = find_peaks(smooth, prominence=max(5.0 * noise, 0.05 * level))
    static = float(smooth[peaks[0]]) if len(peaks) else float("nan")
    dynamic = float(f[len(f) // 2 :].mean())
    drops, _ = find_peaks(-d, height=5.0 * noise)
    return static, dynamic, len(drops)


def main():
    src, out = sys.argv[1], sys.argv[2]
    df = pd.read_csv(src)
    t = df.iloc[:, 0].to_numpy()
    fx = df.iloc[:, 1].to_numpy() * 1e-3
    fz = df.iloc[:, 2].to_numpy() * 1e-3
    static, dynamic, n_slips = features(t, fx)
    pd.DataFrame(
        {"static_n": [static], "dynamic_n": [dynamic], "stick_slips": [n_slips]}
    ).to_parquet(out)
    if "--traces" in sys.argv:
        pd.DataFrame({"t_s": t, "fx_n": fx, "fz_n": fz}).to_parquet(out + ".traces.parquet")


if __name__ == "__main__":
    main()
