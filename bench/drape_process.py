"""One `drape --simulate` process as the bench scripts run it: timed from outside, stopped with its error when it
fails, its --stats read back."""
import json
import subprocess
import sys
import time


def simulate(cmd, stats):
    """Runs cmd (a drape --simulate command line that writes --stats to `stats`); returns (wall seconds, stats).
    Exit 4 (the quality verdict failed) still wrote the drape and its stats; any other failure ends the script."""
    start = time.perf_counter()
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    if done.returncode not in (0, 4):
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}: {done.stderr.strip()}")
    with open(stats) as f:
        return wall, json.load(f)
