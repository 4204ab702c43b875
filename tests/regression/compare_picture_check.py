#!/usr/bin/env python3
"""Checks a picture of scripts/: the PNG has the requested size, is not blank and, for
a cut picture, shows the fill colour of each expected cell type.

    compare_picture_check.py PNG --size 1200x700 [--cell-types hexahedron wedge tetra pyramid]
                             [--absent-cell-types hexahedron]
"""
import argparse
import importlib.util
import os
import sys

import matplotlib.image
import numpy as np

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")


def cut_colours():
    spec = importlib.util.spec_from_file_location("plot_mesh_cut", os.path.join(SCRIPTS, "plot-mesh-cut.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.CELL_COLOURS


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("png")
    parser.add_argument("--size", required=True)
    parser.add_argument("--cell-types", nargs="*", default=[])
    parser.add_argument("--absent-cell-types", nargs="*", default=[])
    parser.add_argument("--minimum-pixels", type=int, default=200)
    arguments = parser.parse_args()
    image = matplotlib.image.imread(arguments.png)
    height, width = image.shape[:2]
    expected = tuple(int(value) for value in arguments.size.split("x"))
    failures = []
    if (width, height) != expected:
        failures.append(f"size {width}x{height}, expected {arguments.size}")
    rgb = image[:, :, :3]
    if rgb.std() < 0.05:
        failures.append("the picture is blank")
    white = np.all(rgb > 0.98, axis=2).mean()
    if white > 0.97:
        failures.append(f"{100 * white:.1f} % of the picture is white")
    colours = cut_colours()
    for cell_type in arguments.cell_types:
        label, colour = colours[cell_type]
        matches = int(np.all(np.abs(rgb - np.array(colour)) < 0.02, axis=2).sum())
        print(f"{label}: {matches} pixels")
        if matches < arguments.minimum_pixels:
            failures.append(f"{label}: {matches} pixels of their colour, expected at least {arguments.minimum_pixels}")
    for cell_type in arguments.absent_cell_types:
        label, colour = colours[cell_type]
        matches = int(np.all(np.abs(rgb - np.array(colour)) < 0.02, axis=2).sum())
        # The legend swatch of a type is drawn only when the cut has cells of it.
        if matches > 0:
            failures.append(f"{label}: {matches} pixels of their colour, expected none")
    for failure in failures:
        print(f"{arguments.png}: {failure}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
