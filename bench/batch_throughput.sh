#!/usr/bin/env bash
# Batch throughput, side by side in one run (docs/BENCHMARKS.md, "Batch draping"): the 20 jobs of
# bench/batches/throughput.json run one at a time with every thread, two at a time with one thread each, and as a
# Slurm job array of one task per job on the local one-node Slurm (scripts/slurm-local.sh), interleaved over ROUNDS
# rounds. Prints one line per run: mode, round, wall seconds, drapes per hour, and the summed job wall times.
#   bash bench/batch_throughput.sh [ROUNDS] [DRAPE]
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS="${1:-1}"
DRAPE="$(realpath "${2:-build/app/drape}")"
MANIFEST="$(realpath bench/batches/throughput.json)"
OUT="$(realpath -m "${DRAPE_BENCH_OUT:-/tmp/drape-throughput}")"
bash scripts/slurm-local.sh status || bash scripts/slurm-local.sh start >&2
JOBS=$("$DRAPE" --batch "$MANIFEST" --list | wc -l)

# Seconds since the epoch, with fractions.
now() { date +%s.%N; }
report() {  # mode round start end outdir
  python3 - "$@" "$JOBS" <<'PY'
import json, sys
mode, rnd, start, end, out, jobs = sys.argv[1:7]
wall = float(end) - float(start)
rows = json.load(open(out + "/summary.json"))
done = sum(1 for r in rows if r["exit_status"] in (0, 4))
jobwall = sum(r["wall_time_s"] or 0 for r in rows)
print(f"{mode:10s} round {rnd}: {wall:7.1f} s for {done}/{jobs} drapes, {3600 * done / wall:6.1f} drapes/h, "
      f"job wall times summed {jobwall:7.1f} s")
PY
}

# The mannequins and placements are the scenes' own: nothing is made before the jobs.
for round in $(seq 1 "$ROUNDS"); do
  for mode in serial parallel slurm; do
    dir="$OUT/$mode-$round"
    rm -rf "$dir"
    start=$(now)
    case "$mode" in
      serial) "$DRAPE" --batch "$MANIFEST" -o "$dir" --jobs 1 >/dev/null || true ;;
      parallel) "$DRAPE" --batch "$MANIFEST" -o "$dir" --jobs "$(nproc)" >/dev/null || true ;;
      slurm)
        line=$("$DRAPE" --batch "$MANIFEST" -o "$dir" --slurm --cpus-per-task 1)
        ids=$(echo "$line" | sed -E 's/.*job array ([0-9]+) .*then job ([0-9]+),.*/\1,\2/')
        while [ -n "$(squeue -h -o %i -j "$ids" 2>/dev/null)" ]; do sleep 0.2; done
        ;;
    esac
    end=$(now)
    report "$mode" "$round" "$start" "$end" "$dir"
  done
done
