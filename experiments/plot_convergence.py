#!/usr/bin/env python3
"""Convergence plot of a Deltapath experiment: error against wall-clock time, log-log.

Usage: plot_convergence.py RESULTS.csv --out PREFIX [--title TITLE]

Reads the runner's results.csv (columns name, budget, seed, wall_time, spp, then one
column per metric) and writes PREFIX.png and PREFIX.svg with one panel per metric. Each
run is one line through its budgets: x = mean wall time over seeds, y = mean error over
seeds, with a shaded band and error bars spanning the min..max over seeds. Needs only
matplotlib (Debian: python3-matplotlib); no numpy code here.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter  # noqa: E402

FIXED = ["name", "budget", "seed", "wall_time", "spp"]


def load(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None or reader.fieldnames[: len(FIXED)] != FIXED:
            sys.exit(f"{path}: expected the columns {', '.join(FIXED)}, ...")
        metrics = reader.fieldnames[len(FIXED):]
        rows = list(reader)
    if not metrics:
        sys.exit(f"{path}: no metric columns")
    return metrics, rows


def series(rows, metric):
    """{run name: [(mean time, mean err, min err, max err, budget)]} in file order."""
    runs = {}
    for r in rows:
        by_budget = runs.setdefault(r["name"], {})
        by_budget.setdefault(float(r["budget"]), []).append((float(r["wall_time"]), float(r[metric])))
    out = {}
    for name, by_budget in runs.items():
        pts = []
        for budget in sorted(by_budget):
            vals = by_budget[budget]
            errs = [e for _, e in vals]
            t = sum(t for t, _ in vals) / len(vals)
            pts.append((t, sum(errs) / len(errs), min(errs), max(errs), budget))
        out[name] = pts
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out", required=True, help="output prefix (writes PREFIX.png and PREFIX.svg)")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    metrics, rows = load(args.csv)
    fig, axes = plt.subplots(1, len(metrics), figsize=(5.2 * len(metrics), 4.2), squeeze=False)
    for ax, metric in zip(axes[0], metrics):
        for name, pts in series(rows, metric).items():
            pts = [p for p in pts if p[0] > 0 and p[1] > 0]
            if not pts:
                continue
            t = [p[0] for p in pts]
            mean = [p[1] for p in pts]
            lo = [max(p[2], 1e-300) for p in pts]
            hi = [p[3] for p in pts]
            line = ax.plot(t, mean, marker="o", label=name)[0]
            ax.fill_between(t, lo, hi, color=line.get_color(), alpha=0.2, linewidth=0)
            ax.errorbar(t, mean, yerr=[[m - l for m, l in zip(mean, lo)], [h - m for m, h in zip(mean, hi)]],
                        fmt="none", ecolor=line.get_color(), capsize=3, linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        seconds = FuncFormatter(lambda v, _pos: f"{v:g}")  # 0.5, 2, 20 rather than 2x10^0
        ax.xaxis.set_major_formatter(seconds)
        ax.xaxis.set_minor_formatter(seconds)
        ax.tick_params(axis="x", which="minor", labelsize="x-small")
        ax.set_xlabel("wall-clock time [s]")
        ax.set_ylabel(metric)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small")
    if args.title:
        fig.suptitle(args.title + " (mean over seeds, band = min..max)")
    fig.tight_layout()
    fig.savefig(args.out + ".png", dpi=110)
    fig.savefig(args.out + ".svg")
    return 0


if __name__ == "__main__":
    sys.exit(main())
