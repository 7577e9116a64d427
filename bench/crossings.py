#!/usr/bin/env python3
"""Crossing-free garments, measured (docs/BENCHMARKS.md, "Crossing-free garments").

For each garment and body, back to back: the drape with cloth self-contact on and off (contact.self_collision), each
in the stage given (--solver, default full: the preview, then the drape). Reported: wall time, the crossing triangle
pairs at rest (the verdict's self_intersections), the largest seam gap, the ratio of the wall times and the verdict.

  python3 bench/crossings.py --drape build/app/drape [--solver full] [--rounds 2] [--only NAME] -o out/crossings.json
  python3 bench/crossings.py --table out/crossings.json     # the markdown table
"""
import argparse
import json
import os

from drape_process import simulate

GC = os.path.join("..", "shared", "data", "garmentcode")
SCENES = [
    ("default t-shirt (2 cm)", ["assets/scenes/default.json"]),
    ("t-shirt (1.5 cm)", ["assets/scenes/tshirt.json"]),
    ("A-line skirt", ["assets/scenes/aline_skirt.json"]),
    ("trousers", ["assets/scenes/trousers.json"]),
    ("sleeveless dress", ["assets/scenes/sleeveless_dress.json"]),
    ("shirt over skirt", ["assets/scenes/shirt_over_skirt.json"]),
    ("t-shirt on the male mannequin", ["assets/scenes/default.json", "--avatar", "assets/avatars/male.obj"]),
    ("GarmentCode shirt (1 cm)", ["tests/data/scenes/shirt_mean_on_mean_all.json"]),
    ("GarmentCode pencil dress", ["tests/data/scenes/dress_pencil_on_mean_all.json"]),
    ("GPG tee", ["tests/data/scenes/gpg_tee_on_mean_all.json"]),
    ("GPG skirt", ["tests/data/scenes/gpg_skirt_2_panels_on_mean_all.json"]),
]


def run(drape, scene, solver, self_contact, out):
    stats = out + ".json"
    cmd = [drape, "--simulate", *scene, "--solver", solver, "-o", out, "--stats", stats,
           "--set", f"contact.self_collision={'true' if self_contact else 'false'}"]
    wall, s = simulate(cmd, stats)
    checks = s["quality"]["checks"]
    gap = checks.get("seam_gap", {}).get("value")
    return {"wall": wall, "crossings": int(checks["self_intersections"]["value"]), "seam_gap": gap,
            "passed": s["quality"]["passed"], "status": s["status"], "sim_time": s["sim_time_s"],
            "failed": [k for k, c in checks.items() if not c["passed"]]}


def measure(args):
    results = {}
    for rnd in range(args.rounds):
        for name, scene in SCENES:
            if args.only and name not in args.only:
                continue
            r = results.setdefault(name, {"on": [], "off": []})
            for mode in ("on", "off"):
                out = os.path.join(args.work, f"{name.replace(' ', '_').replace('/', '_')}_{mode}.obj")
                r[mode].append(run(args.drape, scene, args.solver, mode == "on", out))
                print(name, mode, r[mode][-1], flush=True)
    with open(args.output, "w") as f:
        json.dump({"solver": args.solver, "results": results}, f, indent=1)


def table(path):
    with open(path) as f:
        data = json.load(f)
    print("| garment and body | crossings on | crossings off | wall on | wall off | ratio | seam gap on | verdict on | verdict off |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in data["results"].items():
        on, off = r["on"], r["off"]
        won = min(x["wall"] for x in on)
        woff = min(x["wall"] for x in off)
        gap = on[-1]["seam_gap"]
        verdict = lambda r: "passes" if r["passed"] else "fails: " + ", ".join(r["failed"])
        print(f"| {name} | {max(x['crossings'] for x in on)} | {max(x['crossings'] for x in off)} | {won:.1f} s | "
              f"{woff:.1f} s | {won / woff:.2f}x | {'-' if gap is None else f'{1e3 * gap:.2f} mm'} | "
              f"{verdict(on[-1])} | {verdict(off[-1])} |")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--drape", default="build/app/drape")
    p.add_argument("--solver", default="full")
    p.add_argument("--rounds", type=int, default=1)
    p.add_argument("--only", action="append")
    p.add_argument("--work", default="out/crossings")
    p.add_argument("-o", "--output", default="out/crossings.json")
    p.add_argument("--table")
    args = p.parse_args()
    if args.table:
        table(args.table)
        return
    os.makedirs(args.work, exist_ok=True)
    measure(args)


if __name__ == "__main__":
    main()
