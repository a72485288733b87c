#!/usr/bin/env python3
"""Automatic tracking initialisation (`simtree track --init-from`) scored against synth's truth:
for every capture, the markers of gt/tree.json are projected into frame 0 with gt/pull_camera.json,
exact and perturbed by a registration-like error (a rotation about a random axis and a shift in a
random direction, seeded), and the written init.json is compared with gt/markers_2d.json:
a marker is right when its pixel lies in its own true tape box (grown by 1 px) and no other
visible marker's box centre is nearer. For scale, "tracker sees" counts the visible markers the
tracker itself measures in frame 0 when started from synth's clicks (pull/init.json): a tape it
cannot detect there cannot be matched either. Prints one markdown row per capture and error.

  bench/track_init_on_synth.py SIMTREE WORK CAPTURE... [--errors 0:0,1:0.02,2:0.04] [--draws 3]
"""
import argparse
import csv
import json
import math
import os
import random
import statistics
import subprocess
import sys
import time


def rotation(axis, angle):
    x, y, z = axis
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


def unit(rng):
    while True:
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(a * a for a in v))
        if n > 1e-6:
            return [a / n for a in v]


def perturbed(pose16, deg, metres, rng):
    """world_from_camera followed by a camera-frame error."""
    m = [pose16[0:4], pose16[4:8], pose16[8:12], pose16[12:16]]
    r = rotation(unit(rng), math.radians(deg))
    t = [metres * a for a in unit(rng)]
    e = [r[0] + [t[0]], r[1] + [t[1]], r[2] + [t[2]], [0, 0, 0, 1]]
    out = [[sum(m[i][k] * e[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
    return [v for row in out for v in row]


def score(init_path, truth_frame):
    with open(init_path) as f:
        init = {m["id"]: m["pixel"] for m in json.load(f)["markers"]}
    visible = {m["id"]: m["box"] for m in truth_frame["markers"] if m["visible"]}
    right = wrong = hidden_given = 0
    for mid, (u, v) in init.items():
        if mid not in visible:
            hidden_given += 1
            continue
        x, y, w, h = visible[mid]
        inside = x - 1 <= u <= x + w + 1 and y - 1 <= v <= y + h + 1
        def dist(b):
            return math.hypot(u - (b[0] + b[2] / 2), v - (b[1] + b[3] / 2))
        nearest = min(visible, key=lambda k: dist(visible[k]))
        if inside and nearest == mid:
            right += 1
        else:
            wrong += 1
    return len(visible), right, wrong, len(visible) - right - wrong, hidden_given


def tracker_sees(simtree, cap, out):
    """Visible markers measured in frame 0 by `track` started from pull/init.json."""
    subprocess.run([simtree, "-q", "track", f"{cap}/pull", "--out", out], check=True,
                   capture_output=True)
    with open(f"{out}/boxes.csv") as f:
        rows = [r for r in csv.DictReader(l for l in f if not l.startswith("#"))]
    first = min(int(r["frame"]) for r in rows)
    return {int(r["marker"]) for r in rows if int(r["frame"]) == first and r["state"] == "tracked"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("simtree")
    parser.add_argument("work")
    parser.add_argument("captures", nargs="+")
    parser.add_argument("--errors", default="0:0,1:0.02,2:0.04",
                        help="comma-separated DEG:METRES pose errors")
    parser.add_argument("--draws", type=int, default=3, help="random error directions per error")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print("| capture | pose error | draws | visible | tracker sees | right | wrong | missed | hidden given |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    totals = {}
    seconds = []
    for cap in args.captures:
        with open(f"{cap}/gt/pull_camera.json") as f:
            pose = json.load(f)["world_from_camera"]
        with open(f"{cap}/gt/markers_2d.json") as f:
            truth = json.load(f)["frames"][0]
        name = os.path.basename(os.path.normpath(cap))
        visible_ids = {m["id"] for m in truth["markers"] if m["visible"]}
        sees = len(tracker_sees(args.simtree, cap, f"{args.work}/{name}_clicked") & visible_ids)
        for spec in args.errors.split(","):
            deg, metres = (float(v) for v in spec.split(":"))
            draws = 1 if deg == 0 and metres == 0 else args.draws
            sums = [0] * 5
            for d in range(draws):
                rng = random.Random(1000 * d + 7)
                pose_path = f"{args.work}/{name}_{deg}_{metres}_{d}.json"
                with open(pose_path, "w") as f:
                    json.dump({"world_from_camera": perturbed(pose, deg, metres, rng)}, f)
                out = f"{args.work}/{name}_{deg}_{metres}_{d}"
                start = time.monotonic()
                run = subprocess.run([args.simtree, "-q", "track", f"{cap}/pull", "--init-from",
                                      f"{cap}/gt/tree.json", "--pull-pose", pose_path,
                                      "--init-only", "--out", out],
                                     capture_output=True, text=True)
                seconds.append(time.monotonic() - start)
                if run.returncode != 0:
                    print(f"{name} {spec} draw {d}: {run.stderr.strip()}", file=sys.stderr)
                    row = (sum(1 for m in truth["markers"] if m["visible"]), 0, 0, 0, 0)
                    row = (row[0], 0, 0, row[0], 0)
                else:
                    row = score(f"{out}/init.json", truth)
                sums = [a + b for a, b in zip(sums, row)]
            sums.insert(1, sees * draws)
            t = totals.setdefault(spec, [0] * 6)
            totals[spec] = [a + b for a, b in zip(t, sums)]
            print(f"| {name} | {deg:g} deg, {100 * metres:g} cm | {draws} | " +
                  " | ".join(str(v) for v in sums) + " |")
    for spec, t in totals.items():
        deg, metres = spec.split(":")
        print(f"| **all** | {deg} deg, {100 * float(metres):g} cm | | {t[0]} | {t[1]} | "
              f"{t[2]} ({100 * t[2] / max(t[0], 1):.1f}%; {100 * t[2] / max(t[1], 1):.1f}% of seen) | "
              f"{t[3]} | {t[4]} | {t[5]} |")
    print(f"\nwall time of `track --init-from --init-only` (process, one frame): median "
          f"{statistics.median(seconds):.2f} s over {len(seconds)} runs")


if __name__ == "__main__":
    main()
