#!/usr/bin/python3
"""Draw the quality histograms of a `mixmesh check --json` report into one PNG.

    plot-quality-histograms.py REPORT.json OUTPUT.png

One panel per metric, one bar series per cell type (or face set), counts on a
logarithmic axis so that the few bad cells stay visible next to millions of good
ones. Headless (matplotlib's Agg backend).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(sys.argv[1]) as file:
        report = json.load(file)
    metrics = []
    for entry in report["quality"]:
        if entry["metric"] not in metrics:
            metrics.append(entry["metric"])
    if not metrics:
        print("no quality statistics in " + sys.argv[1], file=sys.stderr)
        return 1
    columns = min(3, len(metrics))
    rows = (len(metrics) + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(5.5 * columns, 3.8 * rows), squeeze=False)
    for panel, metric in enumerate(metrics):
        axis = axes[panel // columns][panel % columns]
        for entry in report["quality"]:
            histogram = entry["histogram"]
            if entry["metric"] != metric or histogram["min"] is None:
                continue
            counts = histogram["counts"]
            low, high = histogram["min"], histogram["max"]
            scale = max(1.0, abs(low))
            if high - low <= 1e-9 * scale:
                # One value (all counts in the first bin): a narrow bar around it.
                counts = [sum(counts)]
                edges = [low - 0.005 * scale, low + 0.005 * scale]
            else:
                width = (high - low) / len(counts)
                edges = [low + width * bin for bin in range(len(counts) + 1)]
            axis.stairs(counts, edges, label=f"{entry['entity']} ({entry['count']})")
        axis.set_yscale("log")
        axis.set_ylim(bottom=0.5)
        axis.set_title(metric.replace("_", " "))
        axis.set_ylabel("count")
        axis.legend(fontsize="small")
    for panel in range(len(metrics), rows * columns):
        axes[panel // columns][panel % columns].axis("off")
    figure.suptitle(f"{report['file']}: {report['summary']}", fontsize="small")
    figure.tight_layout()
    figure.savefig(sys.argv[2], dpi=100, format="png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
