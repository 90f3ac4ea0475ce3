# SPDX-License-Identifier: MIT
"""Runs an NC program on a board and plots the tool centre path with matplotlib.

    python3 examples/python/plot_run.py examples/wr_quad_disc.nc \\
        --tools examples/tools/wr_quad_disc.tools --output wr_quad_disc.png

The plot shows, in the program's plane, the programmed contour (dashed), the executed
segments of the tool centre path (contour, transitions, approach and departure in their own
colours), the positions of every interpolation cycle as a
thin line, and the place of the first error if the board stopped the run. Without --output it
opens a window (or, with no display, writes PROGRAM.png beside the current directory).
docs/python.md describes the package apci it uses.
"""

from __future__ import annotations

import argparse
import math
import os
import pathlib
import sys

import numpy as np

import apci

# The plane's axes as indices into X, Y, Z: 17 X-Y, 18 Z-X, 19 Y-Z (path.h, plane_axes).
PLANE_AXES = {17: (0, 1), 18: (2, 0), 19: (1, 2)}
PLANE_NAMES = {17: ("X", "Y"), 18: ("Z", "X"), 19: ("Y", "Z")}
ROLE_COLOURS = {"contour": "tab:blue", "transition": "tab:orange", "approach": "tab:green",
                "departure": "tab:purple", "uncompensated": "tab:gray"}


def segment_points(segment, plane: int, step_deg: float = 2.0) -> np.ndarray:
    """(K, 2) points along one executed segment in `plane`: a line's ends, an arc in the plane
    by angle (its radius interpolated, as the board runs it); an arc in another plane by its
    chord."""
    a, b = PLANE_AXES.get(plane, PLANE_AXES[17])
    start = np.array([segment["start"][a], segment["start"][b]])
    end = np.array([segment["end"][a], segment["end"][b]])
    if apci.SEGMENT_KINDS[segment["kind"]] != "arc" or int(segment["plane"]) != plane:
        return np.vstack([start, end])
    centre = np.array([segment["center"][a], segment["center"][b]])
    a0 = math.atan2(*(start - centre)[::-1])
    a1 = math.atan2(*(end - centre)[::-1])
    if segment["ccw"]:
        sweep = (a1 - a0) % (2 * math.pi) or 2 * math.pi
    else:
        sweep = -((a0 - a1) % (2 * math.pi) or 2 * math.pi)
    r0 = np.linalg.norm(start - centre)
    r1 = np.linalg.norm(end - centre)
    n = max(2, int(abs(math.degrees(sweep)) / step_deg) + 1)
    t = np.linspace(0.0, 1.0, n)
    r = r0 + (r1 - r0) * t
    angle = a0 + sweep * t
    return np.column_stack([centre[0] + r * np.cos(angle), centre[1] + r * np.sin(angle)])


def plot(result: apci.RunResult, output: str | None, title: str) -> None:
    import matplotlib
    if output is not None or not os.environ.get("DISPLAY"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plane = result.plot_plane
    a, b = PLANE_AXES.get(plane, PLANE_AXES[17])
    fig, ax = plt.subplots(figsize=(8, 8))
    if len(result.axes):
        xyz = result.xyz
        ax.plot(xyz[:, a], xyz[:, b], color="black", linewidth=0.5, alpha=0.4,
                label="every cycle")
    label = "programmed"
    for move in result.programmed:
        if apci.SEGMENT_KINDS[move["kind"]] == "rapid":
            continue
        points = segment_points(move, plane)
        ax.plot(points[:, 0], points[:, 1], color="black", linewidth=0.8, linestyle="--",
                label=label)
        label = None
    seen = set()
    for segment in result.segments:
        role = apci.SEGMENT_ROLES[segment["role"]]
        points = segment_points(segment, plane)
        ax.plot(points[:, 0], points[:, 1], color=ROLE_COLOURS.get(role, "tab:red"),
                linewidth=1.5, label=None if role in seen else role)
        seen.add(role)
    if result.errors and len(result.segments):
        last = result.segments[-1]["end"]
        first = result.errors[0]
        ax.plot([last[a]], [last[b]], "rx", markersize=12, label=f"{first.where}: {first.code}")
    names = PLANE_NAMES.get(plane, PLANE_NAMES[17])
    ax.set_xlabel(f"{names[0]} (mm)")
    ax.set_ylabel(f"{names[1]} (mm)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, linewidth=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(title)
    if output is None and os.environ.get("DISPLAY"):
        plt.show()
        return
    target = output or f"{pathlib.Path(result.file).stem}.png"
    fig.savefig(target, dpi=120)
    print(f"plot_run: wrote {target}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("program", help="NC program (DIN 66025 or Klartext)")
    parser.add_argument("--tools", help="tool list (wz[i].field value)")
    parser.add_argument("--device", default="emu:",
                        help="device URI (default emu:, the embedded emulator)")
    parser.add_argument("--output", "-o", help="write the plot to this PNG (or PDF, SVG) file")
    args = parser.parse_args(argv)
    try:
        result = apci.run(args.program, tools=args.tools, device=args.device, check=False)
    except apci.Error as e:
        print(f"plot_run: {e}", file=sys.stderr)
        return 1
    print(result.summary(), end="")
    plot(result, args.output, f"{result.file} ({args.device})")
    return 0 if result.ok else 1


if __name__ == "__main__":
    sys.exit(main())
