#!/usr/bin/env python3
"""Plot the error against run time of the spectral strategies from docs/accuracy.csv.

    cargo run --release --example accuracy_report      # writes docs/accuracy.csv
    python3 python_ref/plot_accuracy.py                # writes docs/images/accuracy_*.png

Writes
  docs/images/accuracy_error_vs_time.png  ΔE2000 (max over u) against ns per XYZ, one panel per
                                          (N, period), one curve per strategy family across its
                                          parameter (samples K, intervals K, requested accuracy);
  docs/images/accuracy_error_vs_n.png     ΔE2000 (max over u) and ns per XYZ against N, one panel
                                          per period, for the strategies a renderer would pick.

Errors of 0 (the reference itself, and `auto` where it picks it) are drawn at the plot's floor.
With --markdown, also prints the tables of docs/accuracy.md (per period: ΔE2000 max and ns per
XYZ of the main strategies against N, and the cheapest strategy within 0.5 ΔE2000; the
ColorTable's lookup error and cost beside its build time and memory).
"""

from __future__ import annotations

import argparse
import csv
import math
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
FLOOR = 1e-6  # ΔE2000 below this is drawn at this value (log axes)
# The accuracy of the report's ColorTable rows (`spectrum::DEFAULT_ACCURACY`), read from the CSV
# by `read` (the report writes it as the rows' `param`).
TABLE_PARAM = "1e-3"

# Strategy families: (CSV name, label, colour, marker, how to order the parameter).
FAMILIES = [
    ("uniform", "uniform K", "tab:blue", "o", float),
    ("gauss", "Gauss-Legendre K×8", "tab:orange", "s", float),
    ("auto", "auto (accuracy 1e-1…1e-6)", "tab:green", "^", lambda p: -float(p)),
    ("peaks", "peak search", "tab:red", "D", None),
    ("peaks-refined", "peak search, refined", "tab:purple", "v", None),
    ("exact", "exact (reference)", "black", "*", None),
    ("asymptotic", "asymptotic", "tab:olive", "h", None),
    ("table", "ColorTable lookup (build not counted)", "tab:cyan", "X", None),
    ("stratified", "stratified 8 (one estimate)", "tab:brown", "x", None),
    ("hero", "hero 4 (one estimate)", "tab:gray", "+", None),
    ("paper-own-exposure", "paper's peak colours (own exposure)", "tab:pink", "P", None),
]


def read(path: Path) -> list[dict]:
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["n"] = int(r["n"])
        r["period_nm"] = float(r["period_nm"])
        for k in ("ns_per_eval", "de2000_max", "de2000_median", "rel_xyz_max"):
            r[k] = float(r[k])
        # Older CSVs have no table columns.
        r["build_ms"] = float(r.get("build_ms") or 0.0)
        r["table_bytes"] = int(r.get("table_bytes") or 0)
    global TABLE_PARAM
    params = {r["param"] for r in rows if r["strategy"] == "table"}
    if len(params) == 1:
        TABLE_PARAM = params.pop()
    return rows


def shown(de: float) -> float:
    return max(de, FLOOR)


def fmt_n(n: int) -> str:
    return "10⁶" if n == 1_000_000 else f"{n}"


def error_vs_time(rows: list[dict], out: Path) -> None:
    panels = [(n, d) for d in (1600.0, 100_000.0) for n in (5, 30, 1000, 1_000_000)]
    fig, axes = plt.subplots(2, 4, figsize=(15, 7.4), sharex=True, sharey=True)
    for ax, (n, d) in zip(axes.flat, panels):
        sel = [r for r in rows if r["n"] == n and r["period_nm"] == d]
        for name, label, colour, marker, order in FAMILIES:
            fam = [r for r in sel if r["strategy"] == name]
            if not fam:
                continue
            if order is not None:
                fam.sort(key=lambda r: order(r["param"]))
            xs = [r["ns_per_eval"] for r in fam]
            ys = [shown(r["de2000_max"]) for r in fam]
            style = "-" if order is not None else "none"
            ax.plot(xs, ys, linestyle=style, marker=marker, color=colour, label=label, ms=6)
            if name in ("uniform", "gauss"):
                for r in fam:
                    if r["param"] in ("8", "32", "471", "4000", "1", "4", "59", "470"):
                        ax.annotate(
                            r["param"],
                            (r["ns_per_eval"], shown(r["de2000_max"])),
                            textcoords="offset points",
                            xytext=(3, 3),
                            fontsize=7,
                            color=colour,
                        )
        ax.axhline(0.5, color="0.5", lw=0.8, ls="--")
        ax.axvline(2000, color="0.5", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"N = {fmt_n(n)}, d = {d:g} nm", fontsize=10)
        ax.grid(True, which="major", lw=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("ns per XYZ (median, one core)")
    for ax in axes[:, 0]:
        ax.set_ylabel("ΔE2000, max over u")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8, frameon=False)
    fig.suptitle(
        "Error against run time (D65, w = d/2; dashed: ΔE 0.5, dotted: 2 µs; "
        f"errors below {FLOOR:g} drawn at {FLOOR:g})",
        fontsize=11,
    )
    fig.tight_layout(rect=(0, 0.07, 1, 0.96))
    fig.savefig(out, dpi=72)
    plt.close(fig)


def error_vs_n(rows: list[dict], out: Path) -> None:
    picks = [
        ("uniform", "471", "uniform 471 (1 nm)", "tab:blue", "o"),
        ("gauss", "59", "Gauss-Legendre 59×8", "tab:orange", "s"),
        ("peaks", "-", "peak search", "tab:red", "D"),
        ("peaks-refined", "-", "peak search, refined", "tab:purple", "v"),
        ("auto", "1e-3", "auto 1e-3", "tab:green", "^"),
        ("exact", "-", "exact", "black", "*"),
        ("asymptotic", "-", "asymptotic", "tab:olive", "h"),
        ("table", TABLE_PARAM, "ColorTable lookup", "tab:cyan", "X"),
        ("hero", "4", "hero 4 (one estimate)", "tab:gray", "+"),
    ]
    periods = sorted({r["period_nm"] for r in rows})
    fig, axes = plt.subplots(2, len(periods), figsize=(15, 7.4), sharex=True, sharey="row")
    by = defaultdict(list)
    for r in rows:
        by[(r["strategy"], r["param"], r["period_nm"])].append(r)
    for col, d in enumerate(periods):
        for name, param, label, colour, marker in picks:
            pts = sorted(by[(name, param, d)], key=lambda r: r["n"])
            if not pts:
                continue
            ns = [r["n"] for r in pts]
            if name != "exact":
                axes[0, col].plot(
                    ns, [shown(r["de2000_max"]) for r in pts], marker=marker, color=colour,
                    label=label, ms=5,
                )
            axes[1, col].plot(
                ns, [r["ns_per_eval"] for r in pts], marker=marker, color=colour, label=label,
                ms=5,
            )
        tab = sorted(by[("table", TABLE_PARAM, d)], key=lambda r: r["n"])
        if tab:
            axes[1, col].plot(
                [r["n"] for r in tab], [r["build_ms"] * 1e6 for r in tab], marker="X",
                color="tab:cyan", ls="--", label="ColorTable build (once per grating)", ms=5,
            )
        axes[0, col].set_title(f"d = {d:g} nm", fontsize=10)
        axes[0, col].axhline(0.5, color="0.5", lw=0.8, ls="--")
        axes[1, col].axhline(2000, color="0.5", lw=0.8, ls=":")
        axes[1, col].set_xlabel("N (slits)")
        for ax in axes[:, col]:
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="major", lw=0.3)
    axes[0, 0].set_ylabel("ΔE2000, max over u")
    axes[1, 0].set_ylabel("ns per XYZ (median)")
    handles, labels = axes[1, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8, frameon=False)
    fig.suptitle("Error and cost against N (D65, w = d/2; dashed: ΔE 0.5, dotted: 2 µs)", fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.96))
    fig.savefig(out, dpi=72)
    plt.close(fig)


def cell(r: dict | None) -> str:
    if r is None:
        return "–"
    de = r["de2000_max"]
    de_s = "0" if de == 0 else (f"{de:.2g}" if de >= 0.01 else f"{de:.0e}".replace("e-0", "e-"))
    return f"{de_s} / {ns_text(r['ns_per_eval'])}"


def ns_text(ns: float) -> str:
    if ns >= 1e6:
        return f"{ns / 1e6:.3g} ms"
    if ns >= 1e3:
        return f"{ns / 1e3:.3g} µs"
    return f"{ns:.0f} ns"


def markdown(rows: list[dict]) -> None:
    cols = [
        ("uniform", "471", "uniform 471"),
        ("gauss", "16", "Gauss 16×8"),
        ("peaks", "-", "peak search"),
        ("peaks-refined", "-", "refined"),
        ("auto", "1e-3", "auto 1e-3"),
        ("exact", "-", "exact"),
        ("asymptotic", "-", "asymptotic"),
        ("table", TABLE_PARAM, "table lookup"),
    ]
    index = {(r["strategy"], r["param"], r["n"], r["period_nm"]): r for r in rows}
    # The table's lookup cost leaves out its build: it is compared separately.
    integral = [r for r in rows if r["strategy"] not in ("paper", "paper-own-exposure", "table")]
    for d in sorted({r["period_nm"] for r in rows}):
        print(f"\n**d = {d:g} nm** (ΔE2000 max over u / time per XYZ)\n")
        head = ["N"] + [c[2] for c in cols] + ["cheapest within 0.5 ΔE2000"]
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for n in sorted({r["n"] for r in rows}):
            cells = [fmt_n(n)] + [cell(index.get((a, b, n, d))) for a, b, _ in cols]
            ok = [r for r in integral if r["n"] == n and r["period_nm"] == d and r["de2000_max"] <= 0.5]
            best = min(ok, key=lambda r: r["ns_per_eval"], default=None)
            if best is None:
                cells.append("none")
            else:
                name = best["strategy"] + ("" if best["param"] == "-" else ":" + best["param"])
                cells.append(f"{name}: {cell(best)}")
            print("| " + " | ".join(cells) + " |")
    tab = sorted((r for r in rows if r["strategy"] == "table"), key=lambda r: (r["period_nm"], r["n"]))
    if tab:
        print(f"\n**ColorTable at accuracy {TABLE_PARAM}** (ΔE2000 max over u / lookup; build; memory)\n")
        periods = sorted({r["period_nm"] for r in tab})
        print("| N | " + " | ".join(f"d = {d:g} nm" for d in periods) + " |")
        print("|" + "---|" * (len(periods) + 1))
        for n in sorted({r["n"] for r in tab}):
            cells = [fmt_n(n)]
            for d in periods:
                r = index.get(("table", TABLE_PARAM, n, d))
                cells.append(
                    "–" if r is None
                    else f"{cell(r)}; {ns_text(r['build_ms'] * 1e6)}; {r['table_bytes'] / 1024:.0f} KiB"
                )
            print("| " + " | ".join(cells) + " |")


def facts(rows: list[dict]) -> None:
    """The ranges quoted in the text of docs/accuracy.md, from the same CSV."""

    def pick(strategy, param=None, n=None, d=None, nmin=None, nmax=None):
        return [
            r
            for r in rows
            if r["strategy"] == strategy
            and (param is None or r["param"] == param)
            and (n is None or r["n"] == n)
            and (d is None or r["period_nm"] in d)
            and (nmin is None or r["n"] >= nmin)
            and (nmax is None or r["n"] <= nmax)
        ]

    def span(sel, key):
        v = [r[key] for r in sel]
        if not v:
            return "–"
        lo, hi = min(v), max(v)
        if key == "ns_per_eval":
            return f"{ns_text(lo)} – {ns_text(hi)}"
        return f"{lo:.3g} – {hi:.3g}"

    def both(label, sel):
        print(f"- {label}: ΔE2000 {span(sel, 'de2000_max')}, time {span(sel, 'ns_per_eval')}")

    small, fine, coarse = (740.0, 1600.0), (740.0, 1600.0, 10_000.0), (100_000.0,)
    every = (740.0, 1600.0, 10_000.0, 100_000.0)
    print("\nRanges quoted in the text:\n")
    both("gauss:4, N ≤ 2", pick("gauss", "4", nmax=2))
    both("gauss:8, N = 5", pick("gauss", "8", n=5))
    both("uniform:32, N = 5", pick("uniform", "32", n=5))
    both("uniform:471, N ≤ 30", pick("uniform", "471", nmax=30))
    both("uniform:471, N ≥ 1000", pick("uniform", "471", nmin=1000))
    both("uniform:4000, N ≥ 3000", pick("uniform", "4000", nmin=3000))
    both("peaks, N = 30", pick("peaks", n=30))
    both("peaks, N = 300", pick("peaks", n=300))
    for n in (1000, 3000, 30_000, 1_000_000):
        both(f"peaks, N = {fmt_n(n)}", pick("peaks", n=n))
    both("peaks, N ≥ 1000, d ≤ 10 µm", pick("peaks", nmin=1000, d=fine))
    both("peaks, N ≥ 1000, d = 100 µm", pick("peaks", nmin=1000, d=coarse))
    both("peaks, N ≥ 1000, d ≤ 1.6 µm", pick("peaks", nmin=1000, d=small))
    both("peaks-refined, N ≥ 300", pick("peaks-refined", nmin=300))
    both("auto:1e-3, N ≥ 30000", pick("auto", "1e-3", nmin=30_000))
    both("auto:1e-3, N = 1000-3000", pick("auto", "1e-3", nmin=1000, nmax=3000))
    both("exact, N = 30-300", pick("exact", nmin=30, nmax=300))
    both("exact, N ≥ 300, d = 100 µm", pick("exact", nmin=300, d=coarse))
    both("asymptotic, N ≥ 5", pick("asymptotic", nmin=5))
    both("asymptotic, N = 30-300", pick("asymptotic", nmin=30, nmax=300))
    both("asymptotic, N ≥ 1000", pick("asymptotic", nmin=1000))
    both("table lookup", pick("table"))
    tab = pick("table")
    if tab:
        for label, sel in (("d ≤ 1.6 µm", [r for r in tab if r["period_nm"] <= 2000]), ("all", tab)):
            b = [r["build_ms"] for r in sel]
            m = [r["table_bytes"] / 1024 for r in sel]
            print(f"- table build, {label}: {min(b):.3g} – {max(b):.3g} ms; memory {min(m):.0f} – {max(m):.0f} KiB")
    both("stratified:8", pick("stratified"))
    both("hero:4", pick("hero"))
    for d in every:
        both(f"paper, d = {d:g}", pick("paper", d=(d,)))
    both("paper, N ≥ 30 (integral's exposure)", pick("paper", nmin=30))
    both("paper-own-exposure", pick("paper-own-exposure"))
    index = {(r["strategy"], r["param"], r["n"], r["period_nm"]): r for r in rows}
    for d in every:
        ratios = []
        for n in (300, 1000, 3000, 30_000, 1_000_000):
            u, p = index.get(("uniform", "471", n, d)), index.get(("peaks", "-", n, d))
            if u and p:
                ratios.append(f"{fmt_n(n)}: {u['ns_per_eval'] / p['ns_per_eval']:.1f}x")
        print(f"- uniform:471 / peaks time, d = {d:g}: " + ", ".join(ratios))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--csv", type=Path, default=REPO / "docs" / "accuracy.csv")
    p.add_argument("--out", type=Path, default=REPO / "docs" / "images")
    p.add_argument("--markdown", action="store_true", help="also print the tables of docs/accuracy.md")
    args = p.parse_args()
    rows = read(args.csv)
    if not rows or any(math.isnan(r["ns_per_eval"]) for r in rows):
        raise SystemExit(f"{args.csv}: no usable rows")
    args.out.mkdir(parents=True, exist_ok=True)
    error_vs_time(rows, args.out / "accuracy_error_vs_time.png")
    error_vs_n(rows, args.out / "accuracy_error_vs_n.png")
    for name in ("accuracy_error_vs_time.png", "accuracy_error_vs_n.png"):
        f = args.out / name
        print(f"wrote {f} ({f.stat().st_size // 1024} KB)")
    if args.markdown:
        markdown(rows)
        facts(rows)


if __name__ == "__main__":
    main()
