#!/usr/bin/env bash
# Catalogue throughput (docs/scaling.md): the same catalogue run by
# `vgd batch run` with 1 and with 2 workers, and through a one-node Slurm
# cluster on localhost as a job array of at most 2 tasks at once (skipped when
# Slurm cannot start), one after the other in one run on this machine. Prints
# a markdown table: wall time, items per hour, speed-up against one worker,
# and where the items' time went (drape, import and previews, compression,
# exports), summed over the items from their manifests.
#
#   tests/bench/batch_scaling.sh VGD [CATALOGUE]    (default: data/catalogues/demo.json)
set -euo pipefail
VGD=$(realpath "$1")
SRC=$(cd "$(dirname "$0")/../.." && pwd)
CAT=$(realpath "${2:-$SRC/data/catalogues/demo.json}")
WORK=$(mktemp -d /tmp/vgd-scaling-XXXXXX)
CLUSTER=/tmp/vgd-scal-$$
cleanup() { "$SRC/tests/batch/slurm-local.sh" stop "$CLUSTER" > /dev/null 2>&1 || true; rm -rf "$WORK" "$CLUSTER"; }
trap cleanup EXIT

now() { date +%s.%N; }
since() { python3 -c 'import sys; print("%.2f" % (float(sys.argv[2]) - float(sys.argv[1])))' "$1" "$(now)"; }
row() {  # LABEL OUT WALL BASE
  python3 - "$@" <<'PY'
import glob, json, sys
label, out, wall, base = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
t = dict(items=0, passed=0, item=0.0, drape=0.0, dress=0.0, compress=0.0, export=0.0)
for m in glob.glob(out + "/items/*/manifest.json"):
    j = json.load(open(m))
    t["items"] += 1
    t["passed"] += j["state"] == "passed"
    t["item"] += j["wall_s"]
    t["drape"] += (j.get("certificate") or {}).get("drape_wall_s", 0.0)
    for s in j["steps"]:
        key = "export" if s["name"].startswith("export") else s["name"]
        t[key] += s["wall_s"]
speed = "1.00" if base == "-" else "%.2f" % (float(base) / wall)
print("| %s | %d (%d passed) | %.1f | %.0f | %s | %.1f | %.1f | %.1f | %.1f | %.1f |" % (
    label, t["items"], t["passed"], wall, 3600 * t["items"] / wall, speed, t["item"], t["drape"],
    t["dress"] - t["drape"], t["compress"], t["export"]))
PY
}

echo "catalogue: $CAT ($("$VGD" batch count "$CAT") items); $(nproc) cores; $(date -u +%Y-%m-%d)"
echo
echo "| run | items | wall s | items/hour | speed-up | item s (sum) | drape s | import + previews s | compress s | export s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
t0=$(now); "$VGD" -q batch run "$CAT" -o "$WORK/j1" --jobs 1 > /dev/null || true; w1=$(since "$t0")
row "vgd batch run --jobs 1" "$WORK/j1" "$w1" -
t0=$(now); "$VGD" -q batch run "$CAT" -o "$WORK/j2" --jobs 2 > /dev/null || true; w2=$(since "$t0")
row "vgd batch run --jobs 2" "$WORK/j2" "$w2" "$w1"
if envlines=$("$SRC/tests/batch/slurm-local.sh" start "$CLUSTER" 2> "$WORK/slurm.err"); then
  eval "$envlines"
  t0=$(now)
  job=$("$VGD" batch slurm "$CAT" -o "$WORK/slurm" --max-running 2 --submit | sed -n 's/^submitted job //p')
  while [ -n "$(squeue -h -j "$job" 2> /dev/null)" ]; do sleep 0.5; done
  ws=$(since "$t0")
  row "Slurm, one node, --max-running 2" "$WORK/slurm" "$ws" "$w1"
else
  echo "| Slurm | skipped: $(head -1 "$WORK/slurm.err") |"
fi
