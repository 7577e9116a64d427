#!/usr/bin/env python3
"""How the drape's cost grows with the mesh (docs/BENCHMARKS.md, "A drape at rest in seconds").

The 1 cm t-shirt scene (bench/scenes/tshirt_female.json) meshed at each target edge length, Newton alone from the
placed garment to rest, one process per run: wall time to rest, peak resident memory (GNU time's maximum resident set
size), vertices, steps, and where the steps' time went (--stats "profile"). The slope of log(time) and of
log(memory) against log(vertices) is fitted by least squares over the runs.

  python3 bench/scaling.py --drape build/app/drape [--rounds 2] -o out/scaling.json
  python3 bench/scaling.py --table out/scaling.json     # the markdown table and the slopes
  build/app/drape --scaling-plot out/scaling.json -o docs/images/scaling.png
"""
import argparse
import json
import math
import os

from drape_process import simulate

SCENE = "bench/scenes/tshirt_female.json"
EDGES_CM = [3.0, 2.0, 1.4, 1.0, 0.7]


def run(drape, edge_cm, out):
    stats, rss = out + ".json", out + ".rss"
    cmd = ["/usr/bin/time", "-f", "%M", "-o", rss, drape, "--simulate", SCENE, "--solver", "drape", "--set",
           f"mesh.target_edge_length={edge_cm / 100:g}", "-o", out, "--stats", stats]
    wall, s = simulate(cmd, stats)
    with open(rss) as f:
        peak_kb = int(f.read().split()[-1])
    return {"edge_cm": edge_cm, "vertices": s["vertices"], "wall_s": wall, "peak_mb": peak_kb / 1024.0,
            "steps": s["steps"], "sim_time_s": s["sim_time_s"], "status": s["status"], "profile": s["profile"]}


def slope(points):
    xs = [math.log(p[0]) for p in points]
    ys = [math.log(p[1]) for p in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def measure(args):
    os.makedirs(args.work, exist_ok=True)
    rounds = [[run(args.drape, e, os.path.join(args.work, f"tshirt_{e:g}cm.obj")) for e in EDGES_CM]
              for _ in range(args.rounds)]
    with open(args.output, "w") as f:
        json.dump({"scene": SCENE, "rounds": rounds}, f, indent=2)


def table(path):
    with open(path) as f:
        rounds = json.load(f)["rounds"]
    print("| edge | vertices | steps | time to rest, s | peak memory, MB | assembly | linear solve | contact queries "
          "| line search | bookkeeping |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for i, first in enumerate(rounds[0]):
        runs = [r[i] for r in rounds]
        walls = [r["wall_s"] for r in runs]
        mems = [r["peak_mb"] for r in runs]
        p = first["profile"]
        share = lambda k: f"{100 * p[k] / p['steps_s']:.0f} %"
        print(f"| {first['edge_cm']:g} cm | {first['vertices']} | {first['steps']} | "
              f"{min(walls):.1f}-{max(walls):.1f} | {min(mems):.0f}-{max(mems):.0f} | {share('assembly_s')} | "
              f"{share('linear_solve_s')} | {share('contact_queries_s')} | {share('line_search_s')} | "
              f"{share('bookkeeping_s')} |")
    for r in rounds:
        t = slope([(x["vertices"], x["wall_s"]) for x in r])
        m = slope([(x["vertices"], x["peak_mb"]) for x in r])
        print(f"slope: time {t:.2f}, memory {m:.2f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--drape", default="build/app/drape")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--work", default="out/scaling")
    ap.add_argument("-o", "--output", default="out/scaling.json")
    ap.add_argument("--table")
    args = ap.parse_args()
    if args.table:
        table(args.table)
    else:
        measure(args)


if __name__ == "__main__":
    main()
