#!/usr/bin/env python3
"""Compare two mower designs with the j232 Python module, notebook style.

The raised-skirt highway mower fails SAE J232 in the shipped reports; the same deck with
chain guards passes. This script runs both with the same seed (common random numbers: the
same nails meet both designs, so their difference is sharper than two independent runs),
prints each criterion's mean share against its limit, and plots the shares per replicate.

    PYTHONPATH=build/python python3 docs/examples/compare_designs.py [--replicates N] [--out FIGURE.png]

Each block below is a notebook cell.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")  # a file, not a window: runs anywhere
import matplotlib.pyplot as plt
import numpy as np

import j232

# %% Inputs: two scenario files in the repository and the run size.
here = os.path.dirname(os.path.abspath(__file__))
scenarios = os.path.join(here, "..", "..", "scenarios")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--replicates", type=int, default=400, help="replicates of the 150-nail test per design")
parser.add_argument("--out", default="compare_designs.png", help="where the figure goes")
args = parser.parse_args()
designs = {
    "raised skirt": j232.Scenario(os.path.join(scenarios, "highway-pivoted-raised-skirt.toml")),
    "raised skirt + chains": j232.Scenario(os.path.join(scenarios, "highway-pivoted-raised-skirt-chains.toml")),
}

# %% Run both designs with the same seed; the GIL is released while each runs.
results = {name: s.assess(replicates=args.replicates, seed=2024, marks=True) for name, s in designs.items()}

# %% The verdicts and each criterion's mean share against its limit.
for name, r in results.items():
    p = r["pass_probability"]
    print(f"{name}: {r['verdict']}, P(pass) = {p['estimate']:.3f} ({p['low']:.3f}-{p['high']:.3f})")
    for c in r["criteria"]:
        print(f"    {c['name']:<34} mean share {100 * c['mean_share']:6.2f} %   limit {100 * c['limit']:.2f} %")

# %% A picture: each criterion's mean share per design, its 5-95 % band over replicates, the limit.
criteria = [c["name"] for c in next(iter(results.values()))["criteria"]]
fig, axes = plt.subplots(1, len(criteria), figsize=(3.2 * len(criteria), 3.4), sharey=False)
for ax, name in zip(axes, criteria):
    for i, (design, r) in enumerate(results.items()):
        c = next(c for c in r["criteria"] if c["name"] == name)
        mean, low, high = (100 * c[k] for k in ("mean_share", "share_q05", "share_q95"))
        ax.bar(i, mean, color=("#c0392b", "#2e86c1")[i], label=design)
        ax.errorbar(i, mean, yerr=[[mean - low], [high - mean]], color="black", capsize=4)
    ax.axhline(100 * c["limit"], color="black", linestyle="--", linewidth=1)
    ax.set_title(name, fontsize=9)
    ax.set_xticks(range(len(results)), [d.replace(" + ", "\n+ ") for d in results], fontsize=8)
    ax.set_ylabel("share of nails (%)")
fig.suptitle(f"Mean share per test, 5-95 % band, limit dashed ({args.replicates} replicates each)", fontsize=10)
fig.tight_layout()
fig.savefig(args.out, dpi=120)
print(f"figure: {args.out}")

# %% Where the marks of the failing design land (NumPy columns of every located mark).
marks = results["raised skirt"]["marks_table"]
counted = marks["counted"]
azimuth = np.degrees(np.arctan2(marks["y"][counted], marks["x"][counted]))
print(f"raised skirt: {counted.sum()} counted marks, azimuth {np.percentile(azimuth, 5):.0f} to "
      f"{np.percentile(azimuth, 95):.0f} deg (5-95 %), {marks['puncture'][counted].mean():.0%} punctures")
