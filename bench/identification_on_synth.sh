#!/usr/bin/env bash
# Identification on synthetic pull tests, scored against the FEM truth (issue 8's bench):
# for every species and seed, `simtree synth` makes a capture, its true marker tracks get a
# tracker's errors (2.5 mm RMS, gaps, jumps, lost where the tape is not seen), `simtree identify`
# estimates every link with all three estimators over 10 s of free decay, `simtree build` makes the
# simulation-ready tree on the true static tree, and `simtree eval identification` scores links and
# branches. The same identification on the true tracks (no tracker error) is scored beside it: it
# separates what the tracker's noise costs from what a 10 s record of a tree's modes allows. Both
# default (each link's choice between the poles shared by all links and its own fit) writes both
# readings in materials.json (`poles`), scored in the last table; with COMPARE=1 the captures are
# also identified with `--joint-poles` and `--per-link` and scored in the pooled table. Captures
# and scores already in <work> are reused (synth is the expensive part).
# Prints one markdown row per capture and estimator, then the medians over every link of every
# capture (pooled), per-link detail in <work>/links.md, and the issue-23 table: FEM records and,
# with BENCH=<bench_identification binary>, 20 seeds of independent-mode records, the paper's
# half-power beside the fit's three readings, with the share of truths within one standard
# deviation of the estimate.
#
# CLEAN=0 skips the error-free runs (half the time).
# usage: [BENCH=build/bin/bench_identification] [CLEAN=0] [COMPARE=1] bench/identification_on_synth.sh <simtree binary>
#          <work folder> [seeds] [species...]
#   e.g. BENCH=build/bin/bench_identification bench/identification_on_synth.sh build/bin/simtree \
#          /tmp/ident "1 2 3"
set -euo pipefail
simtree=$1
work=$2
seeds=${3:-"1 2 3"}
shift $(( $# >= 3 ? 3 : $# ))
species=${*:-"acer_palmatum magnolia acer_rubrum"}
mkdir -p "$work"

echo "| species | seed | estimator | links scored | not estimated (why) | median df/f | median dzeta/zeta | no tracker error: median df/f, dzeta/zeta | measured f range | measured zeta range | interpolated branches: median df/f |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
scores=()
captures=()
for sp in $species; do
  for seed in $seeds; do
    scene="$work/${sp}_$seed"
    run="$work/${sp}_$seed"
    [ -f "$scene/gt/modal.json" ] || "$simtree" -q synth --species "$sp" --seed "$seed" \
      --no-contact-sheet --out "$scene" > /dev/null
    kinds=("2.5 choice" "0 choice")
    [ "${COMPARE:-0}" = 1 ] && kinds+=("2.5 joint-poles" "0 joint-poles" "2.5 per-link" "0 per-link")
    for run_kind in "${kinds[@]}"; do
      read -r noise fit <<< "$run_kind"
      [ "$noise" = 0 ] && [ "${CLEAN:-1}" = 0 ] && continue
      tag=$([ "$noise" = 0 ] && echo ".clean" || echo "")
      case $fit in joint-poles) tag=$tag.joint ;; per-link) tag=$tag.perlink ;; esac
      # Reused between runs of the bench: delete <work> (or its *.scores.json) to measure anew.
      [ -f "$run$tag.scores.json" ] && continue
      "$simtree" -q identify "$scene/gt/trajectories.csv" --links "$scene/pull/markers.json" \
        --tree "$scene/gt/tree.json" --camera-pose "$scene/gt/pull_camera.json" \
        --out "$run$tag.materials.json" --no-plots --window 10 \
        $([ "$fit" = choice ] || echo "--$fit") \
        $([ "$noise" = 0 ] || echo "--simulate-tracker-noise $noise --visibility $scene/gt/markers_2d.json --seed $seed") \
        > "$run$tag.identify.txt" 2>&1
      "$simtree" -q build "$scene/gt/tree.json" -m "$run$tag.materials.json" \
        -o "$run$tag.simready.json" > /dev/null 2>&1
      "$simtree" -q eval identification "$run$tag.materials.json" --gt "$scene" \
        --tree "$run$tag.simready.json" --json "$run$tag.scores.json" > /dev/null
    done
    scores+=("$run.scores.json")
    captures+=("$scene")
    python3 - "$run.scores.json" "$run.clean.scores.json" "$run.materials.json" "$sp" "$seed" <<'EOF'
import json, sys
from collections import Counter
import os
scores = json.load(open(sys.argv[1]))
clean = json.load(open(sys.argv[2])) if os.path.exists(sys.argv[2]) else {"links": {}}
materials = json.load(open(sys.argv[3]))
sp, seed = sys.argv[4], sys.argv[5]
def pct(v): return "-" if v is None else f"{100 * v:.2f}%"
interp = scores.get("branches", {}).get("interpolated", {})
for name, s in scores["links"].items():
    # Table IV-style ranges over the values the estimator knows to the summary's bounds, by the
    # rule of identify.h's ComputeRanges; "(n uncertain)": values left out.
    bound = materials["summary"]["max_relative_std"]
    f, z, uncertain = [], [], 0
    for link in materials["links"]:
        e = link.get("estimators", {}).get(name, {})
        if e.get("status") != "ok": continue
        fs, zs = e.get("frequency_std_hz"), e.get("damping_std")
        none_given = fs is None and zs is None  # the spectral estimators: every value counts
        ok = lambda sd, v, b: sd is not None and sd / v <= b
        f_ok = none_given or ok(fs, e["frequency_hz"], bound["frequency"])
        z_ok = none_given or ok(zs, e["damping_ratio"], bound["damping"])
        if f_ok: f.append(e["frequency_hz"])
        if z_ok: z.append(e["damping_ratio"])
        uncertain += not (f_ok and z_ok)
    fr = f"{min(f):.2f}-{max(f):.2f} Hz" if f else "-"
    zr = (f"{min(z):.3f}-{max(z):.3f}" if z else "-") + (f" ({uncertain} uncertain)" if uncertain else "")
    why = Counter(l["status"] for l in s["per_link"] if l["status"] != "ok")
    why = ", ".join(f"{n} {k}" for k, n in why.most_common())
    c = clean["links"].get(name, {})
    print(f"| {sp} | {seed} | {name} | {s['scored']} | {s['not_estimated']}{' (' + why + ')' if why else ''} | "
          f"{pct(s['median_frequency_error'])} | {pct(s['median_damping_error'])} | "
          f"{pct(c.get('median_frequency_error'))}, {pct(c.get('median_damping_error'))} | {fr} | {zr} | "
          f"{pct(interp.get('median_frequency_error')) if name == materials['estimator'] else ''} |")
EOF
  done
done

# Medians over every link of every capture, per estimator; "clear" links are those whose truth's
# runner-up mode peaks below 70% of the dominant one (where the dominant mode is well defined).
python3 - "$work/links.md" "${scores[@]}" <<'EOF'
import json, os, sys, statistics
out, files = sys.argv[1], sys.argv[2:]
def med(v): return f"{100 * statistics.median(v):.2f}%" if v else "-"
rows, pooled = [], {}
for path in files:
    for tag in ("", ".clean", ".joint", ".clean.joint", ".perlink", ".clean.perlink"):
        if not os.path.exists(path.replace(".scores.json", tag + ".scores.json")):
            continue  # CLEAN=0: no error-free runs
        s = json.load(open(path.replace(".scores.json", tag + ".scores.json")))
        for name, est in s["links"].items():
            if tag.endswith((".perlink", ".joint")) and name != "damped_sinusoid_fit":
                continue  # --per-link and --joint-poles change the fit's values only
            p = pooled.setdefault((name, tag), {"all": [], "clear": [], "n": 0, "none": 0, "clear_n": 0})
            for l in est["per_link"]:
                p["n"] += 1
                clear = l["runner_up_ratio"] < 0.7
                p["clear_n"] += clear
                if tag == "":
                    rows.append((path.split("/")[-1].replace(".scores.json", ""), name, l))
                if l["frequency_error"] is None:
                    p["none"] += 1
                    continue
                v = (l["frequency_error"], l["damping_error"], l["nearest_mode_frequency_error"])
                p["all"].append(v)
                if clear: p["clear"].append(v)
print()
print("| estimator | tracker error | links | not estimated | median df/f | median dzeta/zeta | f error to the nearest strong mode | clear-dominant links: n, df/f, dzeta/zeta |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for (name, tag), p in sorted(pooled.items(), key=lambda kv: (kv[0][1], kv[0][0])):
    a, c = p["all"], p["clear"]
    label = name + {".perlink": " (per link)", ".joint": " (joint poles)"}.get(
        tag.replace(".clean", ""), " (choice)" if name == "damped_sinusoid_fit" else "")
    print(f"| {label} | {'none' if tag.startswith('.clean') else '2.5 mm'} | {p['n']} | {p['none']} | "
          f"{med([x[0] for x in a])} | {med([x[1] for x in a if x[1] is not None])} | "
          f"{med([x[2] for x in a])} | {len(c)} of {p['clear_n']}: {med([x[0] for x in c])}, "
          f"{med([x[1] for x in c if x[1] is not None])} |")
with open(out, "w") as f:
    f.write("| capture | estimator | link | status | f true | f | df/f | zeta true | zeta | dzeta/zeta | runner-up | note |\n")
    f.write("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n")
    for cap, name, l in rows:
        g = lambda k, fmt: "-" if l[k] is None else fmt.format(l[k])
        f.write(f"| {cap} | {name} | {l['label']} | {l['status']} | {l['truth_frequency_hz']:.3f} | "
                f"{g('frequency_hz', '{:.3f}')} | {g('frequency_error', '{:.2%}')} | "
                f"{l['truth_damping_ratio']:.4f} | {g('damping_ratio', '{:.4f}')} | "
                f"{g('damping_error', '{:.1%}')} | {l['runner_up_frequency_hz']:.3f} Hz at "
                f"{l['runner_up_ratio']:.2f} | {l['message'][:80]} |\n")
EOF

# Per preset, pooled over its seeds: the default estimator's Table IV-style ranges (values known to
# the summary's bounds; the range over every value beside it), the FEM truth of the links (how many
# inside Table IV) and the FEM first mode, against the paper's Table IV.
echo
echo "| preset | measured f, zeta (default estimator, 2.5 mm; uncertain left out) | every measured value | uncertain / measured | FEM truth of the links (links inside Table IV) | FEM first mode | paper Table IV |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
python3 - "${captures[@]}" <<'PY'
import json, sys
table = {"acer_palmatum": (1.07, 1.50, 0.031, 0.060), "magnolia": (0.72, 1.19, 0.023, 0.033),
         "acer_rubrum": (0.93, 1.50, 0.022, 0.056)}
presets = {}
for scene in sys.argv[1:]:
    sp = scene.rstrip("/").split("/")[-1].rsplit("_", 1)[0]
    s = json.load(open(scene + ".materials.json"))["summary"]
    truth = json.load(open(scene + "/gt/modal.json"))
    p = presets.setdefault(sp, {"f": [], "z": [], "fa": [], "za": [], "unc": 0, "meas": 0,
                                "tf": [], "tz": [], "in": 0, "f1": []})
    for key, pair in (("f", "frequency_hz"), ("z", "damping_ratio"), ("fa", "all_frequency_hz"),
                      ("za", "all_damping_ratio")):
        p[key] += [v for v in s[pair] if v is not None]
    p["unc"] += len(s["uncertain"]); p["meas"] += s["measured"]
    lo, hi, zlo, zhi = table.get(sp, (0, 99, 0, 1))
    for l in truth["links"]:
        p["tf"].append(l["frequency_hz"]); p["tz"].append(l["damping_ratio"])
        p["in"] += lo <= l["frequency_hz"] <= hi and zlo <= l["damping_ratio"] <= zhi
    p["f1"].append(truth["modes"][0]["frequency_hz"])
r = lambda v, fmt: f"{fmt.format(min(v))}-{fmt.format(max(v))}" if v else "-"
for sp, p in presets.items():
    t = table.get(sp)
    print(f"| {sp} | {r(p['f'], '{:.2f}')} Hz, {r(p['z'], '{:.3f}')} | {r(p['fa'], '{:.2f}')} Hz, "
          f"{r(p['za'], '{:.3f}')} | {p['unc']} / {p['meas']} | {r(p['tf'], '{:.2f}')} Hz, "
          f"{r(p['tz'], '{:.3f}')} ({p['in']} of {len(p['tf'])}) | {r(p['f1'], '{:.2f}')} Hz | "
          f"{t[0]:.2f}-{t[1]:.2f} Hz, {t[2]:.3f}-{t[3]:.3f} |" if t else "")
PY

# Issue 23's table: one row per kind of record and reading, the truth's share within 1 sd.
echo
echo "| records | estimator | tracker error | links | not estimated | median df/f | median dzeta/zeta | truth within 1 sd (f / zeta) | note |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
python3 - "${scores[@]}" <<'EOF'
import json, sys, statistics
# The fit's three readings from the default run's materials.json: "poles" holds the shared and the
# own reading of every link (a link without a shared reading keeps its own, as --joint-poles does).
def reading(ml, name, how):
    if name != "damped_sinusoid_fit": return ml.get("estimators", {}).get(name, {})
    p = ml.get("poles") or {}
    if how == "own": return p.get("own", ml)
    if how == "shared": return p["shared"] if p.get("shared", {}).get("status") == "ok" else p.get("own", ml)
    return ml
rows = [("half_power_fft", "", "half_power_fft"),
        ("damped_sinusoid_fit", "own", "damped_sinusoid_fit (per link)"),
        ("damped_sinusoid_fit", "shared", "damped_sinusoid_fit (joint poles)"),
        ("damped_sinusoid_fit", "", "damped_sinusoid_fit (choice)")]
for name, how, label in rows:
    df, dz, n, none, fc, zc, sd, shared = [], [], 0, 0, 0, 0, 0, 0
    for path in sys.argv[1:]:
        s = json.load(open(path))
        m = json.load(open(path.replace(".scores.json", ".materials.json")))
        by_label = {l["label"]: l for l in m["links"]}
        for l in s["links"]["damped_sinusoid_fit"]["per_link"]:
            n += 1
            ml = by_label.get(l["label"], {})
            shared += (ml.get("poles") or {}).get("used") == "shared"
            e = reading(ml, name, how)
            f, z = e.get("frequency_hz"), e.get("damping_ratio")
            if e.get("status") != "ok" or f is None or z is None:
                none += 1
                continue
            tf, tz = l["truth_frequency_hz"], l["truth_damping_ratio"]
            df.append(abs(f / tf - 1)); dz.append(abs(z / tz - 1))
            fs, zs = e.get("frequency_std_hz"), e.get("damping_std")
            if fs is not None and zs is not None:
                sd += 1
                fc += abs(f - tf) <= fs
                zc += abs(z - tz) <= zs
    cover = f"{100 * fc / sd:.0f}% / {100 * zc / sd:.0f}%" if sd else "-"
    note = f" {shared} of {n} links shared" if label.endswith("(choice)") else ""
    print(f"| FEM synth, {len(sys.argv) - 1} captures | {label} | 2.5 mm | {n} | {none} | "
          f"{100 * statistics.median(df):.2f}% | {100 * statistics.median(dz):.1f}% | {cover} |{note}")
EOF
if [ -n "${BENCH:-}" ]; then "$BENCH" --independent 20 2> /dev/null; fi
