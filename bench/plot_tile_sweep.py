#!/usr/bin/env python3
"""Tile size against relMSE and efficiency (Bauszat et al. 2017, Fig. 5) from an experiment's
results.csv whose run names end in ' T<size>' (experiments/figures/bauszat2017_fig5.yaml).
Efficiency = 1 / (wall time x relMSE), mean over seeds; error bars span min..max.
Usage: plot_tile_sweep.py RESULTS.csv OUT.png"""
import collections
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(path, out):
    series = collections.defaultdict(lambda: collections.defaultdict(list))
    for row in csv.DictReader(open(path)):
        m = re.match(r"(.*) T(\d+)$", row["name"])
        if not m:
            continue
        rel, t = float(row["relmse"]), float(row["wall_time"])
        series[m.group(1)][int(m.group(2))].append((rel, 1.0 / (t * rel)))
    if not series:
        sys.exit(f"{path}: no run named '... T<size>'")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for label, by_tile in sorted(series.items()):
        tiles = sorted(by_tile)
        for ax, k in zip(axes, (0, 1)):
            vals = [[v[k] for v in by_tile[t]] for t in tiles]
            mean = [sum(v) / len(v) for v in vals]
            lo = [m - min(v) for m, v in zip(mean, vals)]
            hi = [max(v) - m for m, v in zip(mean, vals)]
            ax.errorbar(tiles, mean, yerr=[lo, hi], marker="o", capsize=3, label=label)
    axes[0].set_ylabel("relMSE")
    axes[1].set_ylabel("efficiency 1 / (time x relMSE)")
    for ax in axes:
        ax.set_xlabel("tile size T")
        ax.grid(True, alpha=0.3)
        ax.legend()
    axes[0].set_yscale("log")
    fig.suptitle("G-PR tile size at equal time (mean over seeds, bars = min..max)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
