"""Parse-alone peer for the ingest_extract benchmark: polars.read_csv of one
file, timed inside Python (start-up excluded), printed as seconds.

usage: python3 polars_read.py FILE.csv
"""
import sys
import time

import polars as pl

t0 = time.perf_counter()
df = pl.read_csv(sys.argv[1])
print(f"{time.perf_counter() - t0:.6f} {df.height}")
