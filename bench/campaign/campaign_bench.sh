#!/usr/bin/env bash
# campaign_bench.sh: hitl campaign run's figures for one campaign file (default: the 36-flight
# docs/examples/campaigns/regression.toml against the emulated board): the wall time at -j 1 and
# at -j N (default 2), the speed-up, and the overhead per flight:
#   in a flight's process  = its process's wall time (the runner's measure) - its session's wall time
#   in the runner          = (wall time x jobs - the sum of the flights' process times) / flights
# (the runner's share: starting each child, its 10 ms poll, collecting; idle cores at the end count);
# and the results page (index.html): its size and how long writing it took.
# Prints figures, asserts none (bench/ convention). Needs python3.
#   bench/campaign/campaign_bench.sh [FILE.toml] [JOBS]     (HITL=path/to/hitl, default build/cli/hitl)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
HITL=${HITL:-$ROOT/build/cli/hitl}
FILE=${1:-$ROOT/docs/examples/campaigns/regression.toml}
JOBS=${2:-2}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/campaign_bench.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

for j in 1 "$JOBS"; do
  "$HITL" -q campaign run "$FILE" -j "$j" --out "$WORK/j$j" --no-history >/dev/null 2>"$WORK/j$j.err" || true
done

# The results page: collect writes it again, and -v says its size and how long it took.
"$HITL" -v campaign collect "$FILE" --out "$WORK/j$JOBS" --no-history 2>&1 >/dev/null | grep -o 'index.html: .*' >"$WORK/page" || true

python3 - "$WORK" "$JOBS" <<'PY'
import json, sys, os
work, jobs = sys.argv[1], int(sys.argv[2])
def figures(j):
    d = os.path.join(work, "j%d" % j)
    s = json.load(open(os.path.join(d, "summary.json")))
    process = inside = 0.0
    for r in s["results"]:
        res = json.load(open(os.path.join(d, "flights", r["id"], "result.json")))
        fs = json.load(open(os.path.join(d, "flights", r["id"], "summary.json")))
        process += res["process_wall_s"]
        inside += res["process_wall_s"] - fs["wall_time_s"]
    n = s["flights"]
    return s, n, s["wall_s"], inside / n, (s["wall_s"] * j - process) / n
s1, n, w1, in1, run1 = figures(1)
sj, _, wj, inj, runj = figures(jobs)
print("campaign %s: %d flights (%d passed at -j 1, %d at -j %d)" % (s1["campaign"], n, s1["passed"], sj["passed"], jobs))
print("wall time     -j 1: %.1f s   -j %d: %.1f s   speed-up %.2f" % (w1, jobs, wj, w1 / wj))
print("per flight    in its process beyond the session: %.0f ms (-j 1), %.0f ms (-j %d)" % (in1 * 1e3, inj * 1e3, jobs))
print("per flight    in the runner: %.0f ms (-j 1), %.0f ms (-j %d)" % (run1 * 1e3, runj * 1e3, jobs))
page = open(os.path.join(work, "page")).read().strip()
print("results page  %s" % (page if page else "not written"))
PY
