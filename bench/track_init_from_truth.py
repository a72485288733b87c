#!/usr/bin/env python3
"""Writes a pull/init.json-style file (simtree.track_init v1) from a synth capture's truth: each
marker's pixel is the centre of its true tape-band box (gt/markers_2d.json) in the first frame.
For tests and benchmarks of `simtree track` on captures made before synth wrote pull/init.json;
never used by `track` itself.

  bench/track_init_from_truth.py CAPTURE OUT.json [--frame N] [--offset PX]
"""
import argparse
import json
import math
import random


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("capture")
    parser.add_argument("out")
    parser.add_argument("--frame", type=int, default=0, help="frame number (default 0)")
    parser.add_argument("--offset", type=float, default=0.0,
                        help="displace each pixel by this many px in a random direction (a click's error)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    with open(f"{args.capture}/gt/markers_2d.json") as f:
        frames = json.load(f)["frames"]
    frame = next(f for f in frames if f["frame"] == args.frame)
    rng = random.Random(args.seed)
    markers = []
    for m in frame["markers"]:
        x, y, w, h = m["box"]
        if w <= 0 or h <= 0:
            continue
        a = rng.uniform(0, 2 * math.pi)
        u = x + w / 2 + args.offset * math.cos(a)
        v = y + h / 2 + args.offset * math.sin(a)
        markers.append({"id": m["id"], "pixel": [round(max(u, 0), 3), round(max(v, 0), 3)]})
    doc = {"format": "simtree.track_init", "version": 1, "frame": args.frame, "markers": markers}
    with open(args.out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
