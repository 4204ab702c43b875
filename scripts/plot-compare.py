#!/usr/bin/env python3
"""Bar chart of a `mixmesh compare` table (compare.csv) beside Wild's Table 1.

    plot-compare.py compare.csv -o compare_bars.png [--size 1600x700]

Left: the counts of each mesh (points, surface elements and each cell type) on a
logarithmic axis, mixmesh solid, the paper's rows hatched. Right: each mesh's points as
a share of its hybrid's points. Headless (Agg).
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COUNTS = ["points", "surface_elements", "hexahedra", "tetrahedra", "prisms", "pyramids"]
COUNT_LABELS = ["points", "surface\nelements", "hexahedra", "tetrahedra", "prisms", "pyramids"]
MESH_COLOURS = {"mixed_anisotropic": "#1f5fbf", "mixed_isotropic": "#5fa8e8", "hybrid": "#d9822b"}
REQUIRED = ["mesh", "label", "source", "points_to_hybrid"] + COUNTS


def read_rows(path):
    try:
        with open(path, newline="") as file:
            reader = csv.DictReader(file)
            missing = [column for column in REQUIRED if column not in (reader.fieldnames or [])]
            if missing:
                sys.exit(f"plot-compare: {path}: missing columns {', '.join(missing)}")
            rows = []
            for line, row in enumerate(reader, start=2):
                try:
                    for column in COUNTS:
                        row[column] = int(row[column])
                    # Empty when the table has no hybrid row to compare with.
                    share = row["points_to_hybrid"]
                    row["points_to_hybrid"] = float(share) if share else float("nan")
                except ValueError as error:
                    sys.exit(f"plot-compare: {path}:{line}: {error}")
                rows.append(row)
    except OSError as error:
        sys.exit(f"plot-compare: {path}: {error.strerror}")
    if not rows:
        sys.exit(f"plot-compare: {path}: no rows")
    return rows


def parse_size(text):
    try:
        width, height = (int(value) for value in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size '{text}' is not WIDTHxHEIGHT in pixels")
    return width, height


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("table", help="compare.csv written by mixmesh compare")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    parser.add_argument("--size", type=parse_size, default=(1600, 700), help="pixels, WIDTHxHEIGHT")
    arguments = parser.parse_args()
    rows = read_rows(arguments.table)
    measured = [row for row in rows if row["source"] == "mixmesh"]
    reference = [row for row in rows if row["source"] != "mixmesh"]
    series = [(row, False) for row in measured] + [(row, True) for row in reference]

    width, height = arguments.size
    dpi = 100
    figure, (counts_axes, share_axes) = plt.subplots(
        1, 2, figsize=(width / dpi, height / dpi), dpi=dpi, gridspec_kw={"width_ratios": [3, 1]})
    positions = np.arange(len(COUNTS))
    bar_width = 0.8 / len(series)
    for k, (row, is_reference) in enumerate(series):
        values = np.array([row[column] for column in COUNTS], dtype=float)
        values[values == 0] = np.nan  # no cells of that type: no bar on a log axis
        colour = MESH_COLOURS.get(row["mesh"], "grey")
        counts_axes.bar(positions - 0.4 + (k + 0.5) * bar_width, values, bar_width,
                        color="white" if is_reference else colour, edgecolor=colour,
                        hatch="///" if is_reference else None, linewidth=1.0,
                        label=f"{row['label']} ({row['source']})")
    counts_axes.set_yscale("log")
    largest = max(row[column] for row, _ in series for column in COUNTS)
    counts_axes.set_ylim(top=largest * 10)  # room for the legend above the bars
    counts_axes.set_xticks(positions)
    counts_axes.set_xticklabels(COUNT_LABELS)
    counts_axes.set_ylabel("count")
    counts_axes.set_title("Mesh sizes: mixmesh (solid) and Wild Table 1, ONERA M6 (hatched)")
    counts_axes.grid(axis="y", which="major", alpha=0.4)
    counts_axes.legend(fontsize="small", loc="upper left", ncol=2)

    labels = []
    for k, (row, is_reference) in enumerate(series):
        colour = MESH_COLOURS.get(row["mesh"], "grey")
        share = 100.0 * row["points_to_hybrid"]
        if np.isnan(share):
            share = 0.0
        share_axes.bar(k, share, 0.7, color="white" if is_reference else colour, edgecolor=colour,
                       hatch="///" if is_reference else None)
        share_axes.text(k, share + 2, f"{share:.1f} %", ha="center", fontsize="small")
        labels.append(f"{row['mesh'].replace('_', chr(10))}\n({'paper' if is_reference else 'mixmesh'})")
    share_axes.axhline(25.0, color="black", linestyle="--", linewidth=0.8, label="25 %")
    share_axes.set_xticks(range(len(series)))
    share_axes.set_xticklabels(labels, fontsize="x-small")
    share_axes.set_ylim(0, 115)
    share_axes.set_ylabel("points / hybrid points [%]")
    share_axes.set_title("Points relative to the hybrid")
    share_axes.legend(fontsize="small", loc="upper left")
    figure.tight_layout()
    figure.savefig(arguments.output, dpi=dpi)
    plt.close(figure)


if __name__ == "__main__":
    main()
