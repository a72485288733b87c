#!/usr/bin/env python3
"""Measured and interpolated branches of bench/identification_on_synth.sh's simulation-ready trees
against their own FEM truth (gt/modal.json `branches`): per capture and pooled, the median
|df/f| and |dzeta/zeta| of each branch's dominant value (its twist mode) and how many measured
branches are within 10%. `eval identification --tree` gives the per-capture medians; this pools
the branches of every capture. A measured branch `build` flagged uncertain counts as measured
whether it kept its value or the interpolation replaced it (the same branches before and after),
and the flagged ones are also scored on their own.

usage: bench/identification_branch_scores.py <work folder of identification_on_synth.sh> [tag]
  tag: "" (default run), ".clean", ".joint", ".perlink", ...
"""
import json, statistics, sys
work = sys.argv[1]
tag = sys.argv[2] if len(sys.argv) > 2 else ""
pool = {"measured": [], "interpolated": [], "flagged": []}
pz = {"measured": [], "interpolated": [], "flagged": []}
rows = []
for sp in ["acer_palmatum", "magnolia", "acer_rubrum"]:
  for seed in [1, 2, 3]:
    try: t = json.load(open(f"{work}/{sp}_{seed}{tag}.simready.json"))
    except Exception: continue
    gt = {b["branch"]: b for b in json.load(open(f"{work}/{sp}_{seed}/gt/modal.json"))["branches"]}
    per = {"measured": [], "interpolated": [], "flagged": []}
    perz = {"measured": [], "interpolated": [], "flagged": []}
    for b in t["branches"]:
      m = b.get("material"); g = gt.get(b["id"])
      if not m or not g: continue
      flagged = bool(m.get("uncertain"))
      k = "measured" if m["source"] == "measured" or flagged else "interpolated"
      tw = m["modes"][2]
      for key in [k] + (["flagged"] if flagged else []):
        per[key].append(abs(tw["frequency_hz"] / g["frequency_hz"] - 1))
        perz[key].append(abs(tw["damping_ratio"] / g["damping_ratio"] - 1))
    for k in per: pool[k] += per[k]; pz[k] += perz[k]
    md = lambda v: 100 * statistics.median(v) if v else float("nan")
    rows.append(f"| {sp} | {seed} | {len(per['measured'])}, {md(per['measured']):.2f}%, {md(perz['measured']):.1f}% | {len(per['interpolated'])}, {md(per['interpolated']):.2f}%, {md(perz['interpolated']):.1f}% | {len(per['flagged'])} |")
print("| preset | seed | measured branches: n, median df/f, dzeta/zeta | interpolated: n, median df/f, dzeta/zeta | flagged |\n| --- | --- | --- | --- | --- |")
print("\n".join(rows))
for k in pool:
  if pool[k]: print(f"pooled {k}: n={len(pool[k])} median df/f {100*statistics.median(pool[k]):.2f}% dzeta {100*statistics.median(pz[k]):.1f}%; within 10%: {sum(x<0.1 for x in pool[k])} (f), {sum(x<0.1 for x in pz[k])} (zeta)")
