#!/usr/bin/env python3
"""Plot where the order-efficiency models agree with rigorous electromagnetics, from
docs/data/validity.csv.

    cargo test --release --all-features --test relief_validity -- --ignored   # writes the CSV
    python3 python_ref/plot_validity.py                                      # writes the PNG

Writes docs/images/validity.png: one panel per profile (rows: sinusoid, lamellar, sawtooth) and
model (columns: the scalar relief model in TE, in TM, and Stam's model in TE and TM together),
over the period and the depth in wavelengths (d/λ, h/λ, both logarithmic). Each point is one
(grating, wavelength) pair, its colour the fraction of its scored orders (rigorous η ≥ 1 %, over
the metals Al and Ag and the angles 0°, 30°, 60°) within 10 % of the rigorous values. The black
line bounds the scalar model's stated valid region (`ScalarRelief::is_valid`).
"""

from __future__ import annotations

import csv
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CSV = ROOT / "docs" / "data" / "validity.csv"
PNG = ROOT / "docs" / "images" / "validity.png"
PROFILES = ["sinusoid", "lamellar", "sawtooth"]
# (title, model column prefix, polarisations)
PANELS = [("scalar, TE", "scalar", {"TE"}), ("scalar, TM", "scalar", {"TM"}), ("Stam, TE + TM", "stam", {"TE", "TM"})]
# The region of ScalarRelief::is_valid (src/relief/validity.rs).
SMOOTH_MIN_PERIOD, SMOOTH_MAX_DEPTH_OVER_PERIOD = 2.5, 0.03
LAMELLAR_MIN_PERIOD, LAMELLAR_MAX_DEPTH = 4.0, 0.05
BOX = {"facecolor": "white", "alpha": 0.85, "edgecolor": "0.6"}


def main() -> None:
    rows = list(csv.DictReader(line for line in CSV.open(encoding="utf-8") if not line.startswith("#")))
    fig, axes = plt.subplots(len(PROFILES), len(PANELS), figsize=(13, 11), sharex=True, sharey=True)
    cmap = plt.get_cmap("RdYlGn")
    for i, profile in enumerate(PROFILES):
        for j, (title, model, pols) in enumerate(PANELS):
            ax = axes[i][j]
            tally = defaultdict(lambda: [0, 0])
            for r in rows:
                if r["profile"] != profile or r["polarisation"] not in pols or r[f"{model}_10"] == "":
                    continue
                key = (float(r["period_nm"]) / float(r["lambda_nm"]), float(r["depth_nm"]) / float(r["lambda_nm"]))
                tally[key][0] += int(r["scored"])
                tally[key][1] += int(r[f"{model}_10"])
            pts = [(x, y, hit / n) for (x, y), (n, hit) in tally.items() if n > 0]
            if pts:
                x, y, f = map(np.array, zip(*pts))
                ax.scatter(x, y, c=f, cmap=cmap, vmin=0, vmax=1, s=42, edgecolors="k", linewidths=0.3)
            else:
                ax.text(0.5, 0.5, "no model", transform=ax.transAxes, ha="center", va="center", color="0.4")
            if profile == "sinusoid":
                xs = np.geomspace(SMOOTH_MIN_PERIOD, 30, 50)
                ax.plot(xs, SMOOTH_MAX_DEPTH_OVER_PERIOD * xs, "k-", lw=1.2)
                ax.plot([SMOOTH_MIN_PERIOD] * 2, [1e-2, SMOOTH_MAX_DEPTH_OVER_PERIOD * SMOOTH_MIN_PERIOD], "k-", lw=1.2)
                ax.text(0.97, 0.55, "valid:\nd ≥ 2.5λ, h ≤ 0.03d", transform=ax.transAxes, fontsize=8, ha="right", bbox=BOX)
            elif profile == "lamellar":
                ax.plot([LAMELLAR_MIN_PERIOD, 30], [LAMELLAR_MAX_DEPTH] * 2, "k-", lw=1.2)
                ax.plot([LAMELLAR_MIN_PERIOD] * 2, [1e-2, LAMELLAR_MAX_DEPTH], "k-", lw=1.2)
                ax.text(0.97, 0.3, "valid: d ≥ 4λ, h ≤ λ/20", transform=ax.transAxes, fontsize=8, ha="right", bbox=BOX)
            else:
                ax.text(0.03, 0.05, "never valid (not measured\nat d/λ > 3.6)", transform=ax.transAxes, fontsize=8)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlim(0.6, 30)
            ax.set_ylim(0.015, 1.6)
            ax.grid(True, which="both", alpha=0.25)
            if i == 0:
                ax.set_title(title)
            if j == 0:
                ax.set_ylabel(f"{profile}\ndepth / λ")
            if i == len(PROFILES) - 1:
                ax.set_xlabel("period / λ")
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, 1))
    fig.colorbar(sm, ax=axes, shrink=0.6, label="fraction of orders (η ≥ 1 %) within 10 % of rigorous")
    fig.suptitle("Order efficiencies against rigorous electromagnetics (Al, Ag; 450-650 nm; 0°, 30°, 60°)")
    PNG.parent.mkdir(parents=True, exist_ok=True)
    tmp = PNG.with_suffix(".tmp.png")
    fig.savefig(tmp, dpi=90)
    tmp.replace(PNG)
    print(f"wrote {PNG.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
