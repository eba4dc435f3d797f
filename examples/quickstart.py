"""Quickstart: the bundled lab folder from Python, step by step and as the
demo pipeline, reproducing the demo's numbers.

    bash scripts/python-tests.sh     # or: pip install ./python
    python examples/quickstart.py    # from the repository root

The sled traces in fixtures/lab were generated with thesis Table 4.2's
Coulomb coefficients (sample 1 exactly, sample 2 3 % rougher) and the ice
run with a = 5 mm (fixtures/lab/SOURCES.md); the fits recover them. With
matplotlib installed, the figure of the report's Coulomb fit (shear stress
against pressure, per sample) is saved as out/quickstart_coulomb.png.
"""

import sys
import tempfile
from pathlib import Path

import polars as pl

import tribo

LAB = Path("fixtures/lab")
# Thesis Table 4.2: (mu_s, tau0_s [Pa], mu_d, tau0_d [Pa]) per pattern.
TABLE_4_2 = {"F": (4.76, 23.45e3, 2.88, 11.85e3), "A": (5.71, 15.41e3, 3.75, 4.02e3)}

# 1. One trace, as the instrument wrote it, in SI.
trace = tribo.read(LAB / "friction/sled_F1_100g.csv")
print(trace.head(3))
print(tribo.inspect(LAB / "friction/sled_F1_100g.csv")["format"])

# 2. Friction features of the sled traces, then the Coulomb law per sample.
sleds = sorted(str(p) for p in (LAB / "friction").glob("sled_*.csv"))
fr = tribo.friction(sleds, samples=LAB / "samples.csv", traces=False)
print(fr["friction"].select("source", "static_force_N", "dynamic_force_N"))
co = tribo.fit_coulomb(fr["friction"], by=["sample_id"])["coulomb"]
print(co.select("group", "regime", "mu", "tau0_Pa", "r2", "status"))

worst = 0.0
for pattern, (mu_s, tau_s, mu_d, tau_d) in TABLE_4_2.items():
    for regime, mu, tau in (("static", mu_s, tau_s), ("dynamic", mu_d, tau_d)):
        row = co.filter((pl.col("group") == f"sample_id={pattern}-1") & (pl.col("regime") == regime))
        got_mu, got_tau = row["mu"][0], row["tau0_Pa"][0]
        err = max(abs(got_mu / mu - 1), abs(got_tau / tau - 1))
        worst = max(worst, err)
        print(f"{pattern}-1 {regime:7}: mu {got_mu:.3f} (Table 4.2: {mu}), "
              f"tau0 {got_tau / 1e3:.2f} kPa (Table 4.2: {tau / 1e3}), off by {err:.1%}")

# 3. The whole demo pipeline: every table of the run, errors included.
with tempfile.TemporaryDirectory() as out:
    demo = tribo.run("pipelines/demo.toml", out=out)
    print(sorted(demo))
    ice = demo["ice_fit"].select("group", "bound", "a_m", "status")
    print(ice)
    a_upper = ice.filter(pl.col("bound") == "upper")["a_m"][0]
    print(f"ice: a = {a_upper * 1e3:.3f} mm (built with 5 mm)")
    assert demo["coulomb"].height > 0 and demo["errors"].height == 0

if worst > 0.02 or abs(a_upper / 5e-3 - 1) > 0.02:
    sys.exit(f"the fits are off the generating values by more than 2 % ({worst:.1%})")

# 4. One figure of the report: tau = tau0 + mu p per sample (Eq. 4.1).
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib not installed: no figure")
else:
    f = fr["friction"]
    fig, ax = plt.subplots(figsize=(5, 3.5))
    for (sample,), g in f.group_by("sample_id", maintain_order=True):
        p = g["normal_force_N"] / g["apparent_area_m2"]
        (dots,) = ax.plot(p / 1e3, g["static_force_N"] / g["apparent_area_m2"] / 1e3, "o", label=sample)
        fit = co.filter((pl.col("group") == f"sample_id={sample}") & (pl.col("regime") == "static"))
        ax.plot(p / 1e3, (fit["tau0_Pa"][0] + fit["mu"][0] * p) / 1e3, "-", lw=0.8, color=dots.get_color())
    ax.set_xlabel("pressure p [kPa]")
    ax.set_ylabel("static shear stress τ [kPa]")
    ax.legend(fontsize=7)
    fig.tight_layout()
    Path("out").mkdir(exist_ok=True)
    fig.savefig("out/quickstart_coulomb.png", dpi=120)
    print("figure: out/quickstart_coulomb.png")
