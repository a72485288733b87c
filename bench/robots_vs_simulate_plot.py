#!/usr/bin/env python3
"""SVG of bench_robots_vs_simulate's CSV: the pulled tip's displacement (x, y, z) in simtree
simulate (solid) and MuJoCo (dashed) against time.
  python3 bench/robots_vs_simulate_plot.py /tmp/simtree_robots_vs_simulate_b1.csv out.svg"""
import csv
import sys

W, H, PAD = 720, 300, 40
COLOURS = ["#d62728", "#2ca02c", "#1f77b4"]


def main(csv_path, svg_path):
    rows = [[float(v) for v in r] for r in list(csv.reader(open(csv_path)))[1:]]
    t = [r[0] for r in rows]
    values = [v for r in rows for v in r[1:]]
    lo, hi = min(values), max(values)
    span = (hi - lo) or 1.0

    def x(ti):
        return PAD + (ti - t[0]) / (t[-1] - t[0]) * (W - 2 * PAD)

    def y(v):
        return H - PAD - (v - lo) / span * (H - 2 * PAD)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<line x1="{PAD}" y1="{y(0)}" x2="{W - PAD}" y2="{y(0)}" stroke="#bbb"/>']
    for axis in range(3):
        for model, dash in ((0, ""), (1, ' stroke-dasharray="5,3"')):
            column = 1 + 3 * model + axis
            points = " ".join(f"{x(r[0]):.1f},{y(r[column]):.1f}" for r in rows)
            out.append(f'<polyline fill="none" stroke="{COLOURS[axis]}"{dash} points="{points}"/>')
    out.append(f'<text x="{PAD}" y="20" font-size="13">tip displacement x/y/z (m, {lo:.3f} to '
               f'{hi:.3f}) over {t[0]:.1f}-{t[-1]:.1f} s: simulate solid, MuJoCo dashed</text>')
    out.append("</svg>")
    open(svg_path, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
