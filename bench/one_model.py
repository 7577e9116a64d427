#!/usr/bin/env python3
"""The preview on the drape's own model, measured (docs/BENCHMARKS.md, "One model").

For each scene, back to back: Newton alone (--solver drape), the pipeline (--solver full) through today's preview and,
given --old DRAPE, through another build's pipeline (the projective preview's), Newton's spread (Newton alone with
solver.newton.h_max doubled, and with its relaxation step held), and the preview's targets:
  1. faithful: the preview started at Newton alone's rest state (--from), 0.5 s: mean distance moved;
  2. fast: wall time per simulated second of the preview against the drape, 0.3 s from the placed garment;
  4. as a designer sees it: the preview alone to rest, then the drape from its state: mean distance between the two.
Distances are means over the garment's vertices between two OBJs of the same mesh. Wall times are whole processes.

  python3 bench/one_model.py --drape build/app/drape [--old OLD/drape] [--rounds 2] [--only NAME] -o out/one_model.json
  python3 bench/one_model.py --table out/one_model.json     # the markdown table
"""
import argparse
import json
import math
import os
import sys

from drape_process import simulate

SHARED = os.path.join("..", "shared", "data", "garmentcode")
SCENES = [
    ("t-shirt (1.5 cm)", ["assets/scenes/tshirt.json"]),
    ("default", ["assets/scenes/default.json"]),
    ("A-line skirt", ["assets/scenes/aline_skirt.json"]),
    ("trousers", ["assets/scenes/trousers.json"]),
    ("sleeveless dress", ["assets/scenes/sleeveless_dress.json"]),
    ("default, cotton shirting", ["assets/scenes/default.json", "--fabric", "cotton_shirting"]),
    ("default, denim", ["assets/scenes/default.json", "--fabric", "denim"]),
    ("GarmentCode shirt (1 cm)", ["tests/data/scenes/shirt_mean_on_mean_all.json"]),
    ("t-shirt (1 cm)", ["bench/scenes/tshirt_female.json"]),
]


def vertices(path):
    with open(path) as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]


def mean_distance(a, b):
    va, vb = vertices(a), vertices(b)
    if len(va) != len(vb) or not va:
        return float("nan")
    return sum(math.dist(p, q) for p, q in zip(va, vb)) / len(va)


def run(drape, scene, solver, out, extra=()):
    """Runs drape --simulate; returns (wall seconds, stats)."""
    stats = out + ".json"
    cmd = [drape, "--simulate", *scene, "--solver", solver, "-o", out, "--stats", stats, *extra]
    return simulate(cmd, stats)


def crossings(stats):
    return stats.get("quality", {}).get("checks", {}).get("self_intersections", {}).get("value")


def measure(args, name, scene, work, rounds):
    row = {"scene": name}
    tag = os.path.join(work, name.replace(" ", "_").replace(",", "").replace("(", "").replace(")", ""))
    for r in range(rounds):
        newton = run(args.drape, scene, "drape", f"{tag}_newton.obj")
        pipeline = run(args.drape, scene, "full", f"{tag}_full.obj")
        row.setdefault("newton_s", []).append(newton[0])
        row.setdefault("pipeline_s", []).append(pipeline[0])
        if args.old:
            old = run(args.old, scene, "full", f"{tag}_old.obj")
            row.setdefault("projective_s", []).append(old[0])
    row["newton_crossings"] = crossings(newton[1])
    row["pipeline_crossings"] = crossings(pipeline[1])
    row["pipeline_status"] = pipeline[1]["status"]
    row["pipeline_mm"] = 1e3 * mean_distance(f"{tag}_full.obj", f"{tag}_newton.obj")
    if args.old:
        row["projective_crossings"] = crossings(old[1])
        row["projective_mm"] = 1e3 * mean_distance(f"{tag}_old.obj", f"{tag}_newton.obj")
    # Newton's spread: equally valid paths.
    run(args.drape, scene, "drape", f"{tag}_hmax2.obj", ["--set", "solver.newton.h_max=0.004"])
    run(args.drape, scene, "drape", f"{tag}_hold.obj", ["--set", "solver.newton.relaxation_step=hold"])
    row["spread_mm"] = 1e3 * max(mean_distance(f"{tag}_hmax2.obj", f"{tag}_newton.obj"),
                                 mean_distance(f"{tag}_hold.obj", f"{tag}_newton.obj"))
    # 1. faithful
    run(args.drape, scene, "preview", f"{tag}_faithful.obj",
        ["--from", f"{tag}_newton.obj", "--set", "solver.max_sim_time=0.5", "--set", "quality.require_rest=false"])
    row["faithful_mm"] = 1e3 * mean_distance(f"{tag}_faithful.obj", f"{tag}_newton.obj")
    # 2. fast: simulated seconds per wall second, 0.3 s from the placed garment
    limit = ["--max-sim-time", "0.3", "--set", "quality.require_rest=false"]
    preview = run(args.drape, scene, "preview", f"{tag}_rate_preview.obj", limit)
    drape = run(args.drape, scene, "drape", f"{tag}_rate_drape.obj", limit)
    row["rate_ratio"] = (preview[1]["sim_time_s"] / preview[0]) / (drape[1]["sim_time_s"] / drape[0])
    row["preview_steps_per_s"] = preview[1]["steps"] / preview[0]
    # 4. as a designer sees it
    alone = run(args.drape, scene, "preview", f"{tag}_preview.obj")
    row["preview_status"] = alone[1]["status"]
    row["preview_s"] = alone[0]
    after = run(args.drape, scene, "drape", f"{tag}_after.obj", ["--from", f"{tag}_preview.obj"])
    row["designer_mm"] = 1e3 * mean_distance(f"{tag}_after.obj", f"{tag}_preview.obj")
    row["after_status"] = after[1]["status"]
    return row


def span(values, digits=1):
    lo, hi = min(values), max(values)
    return f"{lo:.{digits}f}" if f"{lo:.{digits}f}" == f"{hi:.{digits}f}" else f"{lo:.{digits}f}-{hi:.{digits}f}"


def table(rows):
    """The markdown table of docs/BENCHMARKS.md, "One model", from the rows measure() wrote."""
    print("| scene | Newton alone, s | projective pipeline: s, speed-up, mm | pipeline: s, speed-up, mm | Newton's "
          "spread, mm | crossing pairs: Newton / projective / pipeline | 1. faithful, mm | 2. rate vs Newton | 4. preview "
          "to the drape after it, mm |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        newton = r["newton_s"]
        speed = [n / p for n, p in zip(newton, r["pipeline_s"])]
        old = ""
        if "projective_s" in r:
            oldspeed = [n / p for n, p in zip(newton, r["projective_s"])]
            old = f"{span(r['projective_s'])}, {span(oldspeed, 2)}x, {r['projective_mm']:.1f}"
        crossings = " / ".join(str(int(c)) if c is not None else "-" for c in
                               (r.get("newton_crossings"), r.get("projective_crossings"), r.get("pipeline_crossings")))
        print(f"| {r['scene']} | {span(newton)} | {old} | {span(r['pipeline_s'])}, {span(speed, 2)}x, "
              f"{r['pipeline_mm']:.1f} | {r['spread_mm']:.1f} | {crossings} | {r['faithful_mm']:.2f} | "
              f"{r['rate_ratio']:.2f}x | {r['designer_mm']:.2f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--table", help="print the markdown table of a report this script wrote, and stop")
    parser.add_argument("--drape")
    parser.add_argument("--old", help="another build's drape: its pipeline goes in the projective column")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--only", action="append", help="scene names to run (default: all)")
    parser.add_argument("--work", default="out/one_model")
    parser.add_argument("-o", "--output")
    args = parser.parse_args()
    if args.table:
        with open(args.table) as f:
            table(json.load(f))
        return
    if not args.drape or not args.output:
        parser.error("--drape and -o are required")
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for name, scene in SCENES:
        if args.only and name not in args.only:
            continue
        if "shirt_mean" in scene[0] and not os.path.isdir(SHARED):
            print(f"{name}: skipped, {SHARED} is absent", file=sys.stderr)
            continue
        row = measure(args, name, scene, args.work, args.rounds)
        print(json.dumps(row), flush=True)
        rows.append(row)
    tmp = args.output + ".tmp"
    with open(tmp, "w") as f:
        json.dump(rows, f, indent=1)
    os.replace(tmp, args.output)


if __name__ == "__main__":
    main()
