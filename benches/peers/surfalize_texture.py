"""Surface-texture peers for `cargo bench --bench texture`.

  generate OUT.sur SIDE   a seeded self-affine map (H 0.8, roll-off at a
                          sixteenth of the side, Sq 0.5 um, 0.5 um steps),
                          written by surfalize's own SUR writer
  params FILE OUT.jsonl   surfalize: read, plane levelling, then the ISO
                          25178-2 parameters tribo also computes, each group
                          timed inside the process (start-up excluded)
  psd FILE OUT.jsonl      SurfaceTopography: the radially averaged PSD of the
                          levelled map, timed inside the process

The groups are the ones the benchmark times in tribo; each run appends one
JSON line (values in surfalize's units, um and percent, beside the seconds)
so that the benchmark takes medians over its runs.
"""
import json
import sys
import time

import numpy as np


def generate(path, side):
    import surfalize

    rng = np.random.default_rng(2048)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(side), np.fft.fftfreq(side)))
    q_roll = 16.0 / side
    amp = np.where(q < q_roll, 1.0, (np.where(q > 0, q, 1.0) / q_roll) ** -1.8)
    amp[0, 0] = 0.0
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((side, side))) * amp))
    z *= 0.5 / z.std()
    surfalize.Surface(z, 0.5, 0.5).save(path)


def timed(out, group, fn):
    t = time.perf_counter()
    values = fn()
    out["seconds"][group] = time.perf_counter() - t
    out["values"].update(values)


def params(path, dest):
    import surfalize

    out = {"seconds": {}, "values": {}}
    t = time.perf_counter()
    s = surfalize.Surface.load(path)
    out["seconds"]["read"] = time.perf_counter() - t
    t = time.perf_counter()
    s.level(inplace=True)
    out["seconds"]["form"] = time.perf_counter() - t
    names = {
        "amplitude": ["Sa", "Sq", "Ssk", "Sku", "Sp", "Sv", "Sz"],
        "slope": ["Sdq"],
        "area": ["Sdr"],
        "acf": ["Sal", "Str"],
        "direction": ["Std"],
        "functional": ["Sk", "Spk", "Svk", "Smr1", "Smr2", "Sxp",
                       "Vmp", "Vmc", "Vvc", "Vvv"],
    }
    for group, ps in names.items():
        timed(out, group, lambda: {p: float(getattr(s, p)()) for p in ps})
    with open(dest, "a") as fh:
        fh.write(json.dumps(out) + "\n")


def psd(path, dest):
    import surfalize
    import SurfaceTopography as st

    s = surfalize.Surface.load(path)
    s.level(inplace=True)
    z = s.data.T * 1e-6
    size = (z.shape[0] * s.step_x * 1e-6, z.shape[1] * s.step_y * 1e-6)
    out = {"seconds": {}, "values": {}}

    def spectrum():
        t = st.Topography(z, size, periodic=False)
        q, c = t.power_spectrum_from_area()
        keep = np.isfinite(np.ma.filled(c, np.nan))
        return {"n": int(keep.sum()), "q": np.asarray(q)[keep].tolist(),
                "C": np.asarray(c)[keep].tolist()}

    timed(out, "psd", spectrum)
    with open(dest, "a") as fh:
        fh.write(json.dumps(out) + "\n")


if __name__ == "__main__":
    mode, path, arg = sys.argv[1:4]
    if mode == "generate":
        generate(path, int(arg))
    elif mode == "params":
        params(path, arg)
    elif mode == "psd":
        psd(path, arg)
    else:
        sys.exit(f"unknown mode {mode}")
