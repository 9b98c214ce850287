#!/usr/bin/env bash
# A catalogue run through a real scheduler: starts a one-node Slurm cluster on
# localhost (slurm-local.sh), submits a catalogue of 6 small drapes (2 styles
# x 3 sizes) as a job array with `vgd batch slurm --submit`, waits, and checks
# every item's manifest (`vgd batch status`: SHA-256 of every output). Then
# submits a second catalogue, cancels it with scancel midway, resubmits what
# is unfinished, and shows that items finished before the cancel are not
# redone (their manifests unchanged) and none is lost. Stops the cluster at
# the end. Prints "SKIPPED: ..." and exits 0 where Slurm cannot start (not
# root, not installed); CI runs it.
#
#   slurm_catalogue.sh VGD SOURCE_DIR
set -euo pipefail
VGD=$1
SRC=$2
HERE=$(cd "$(dirname "$0")" && pwd)
CLUSTER=/tmp/vgd-slurm-$$      # short: munge's socket path is limited
WORK=$(mktemp -d /tmp/vgd-slurm-test-XXXXXX)

if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  echo "SKIPPED: slurm-wlm or munge not installed (.ci/install-deps installs them)"
  exit 0
fi
stop() {
  "$HERE/slurm-local.sh" stop "$CLUSTER" > /dev/null 2>&1 || true
  rm -rf "$CLUSTER" "$WORK"
}
trap stop EXIT
set +e
envlines=$("$HERE/slurm-local.sh" start "$CLUSTER" 2> "$WORK/start.err")
rc=$?
set -e
if [ $rc -eq 77 ]; then
  echo "SKIPPED: a one-node Slurm cluster cannot start here: $(head -1 "$WORK/start.err")"
  exit 0
fi
[ $rc -eq 0 ] || { cat "$WORK/start.err"; echo "FAIL: slurm-local.sh start exit $rc"; exit 1; }
eval "$envlines"
echo "cluster up: $SLURM_CONF"

fail() { echo "FAIL: $*"; exit 1; }

# Two styles (the shipped skirt and a copy that differs by a comment) x 3 sizes, ~3 s each.
make_catalogue() {  # DIR
  mkdir -p "$1"
  cp "$SRC/data/garments/a-line-skirt.xvc" "$1/skirt.xvc"
  { cat "$SRC/data/garments/a-line-skirt.xvc"; echo "<!-- $1 -->"; } > "$1/skirt-b.xvc"
  cat > "$1/catalogue.json" <<JSON
{"name": "slurm-test",
 "styles": [{"id": "skirt", "file": "skirt.xvc"}, {"id": "b", "file": "skirt-b.xvc"}],
 "sizes": ["34", "38", "42"],
 "settings": {"quality": "preview", "spacing": 0.03, "time_limit": 3, "wall_limit": 240, "memory_mb": 1000},
 "outputs": ["certificate", "previews"], "views": ["front"], "preview_size": 128}
JSON
}

# Waits until the job has left the queue (bounded).
wait_job() {  # JOB SECONDS
  local t=0
  while [ -n "$(squeue -h -j "$1" 2> /dev/null)" ]; do
    sleep 1
    t=$((t + 1))
    [ $t -lt "$2" ] || fail "job $1 still queued after $2 s: $(squeue -j "$1")"
  done
}

job_of() { sed -n 's/^submitted job \([0-9]*\).*/\1/p'; }

# 1. The whole catalogue as one array.
A=$WORK/a
make_catalogue "$A"
[ "$("$VGD" batch count "$A/catalogue.json")" = 6 ] || fail "6 items expected"
out=$("$VGD" batch slurm "$A/catalogue.json" -o "$A/out" --max-running 2 --submit)
echo "$out"
echo "$out" | grep -q -- "6 items as --array=0-5%2" || fail "array of 6 items"
grep -q -- "--mem=1000M" "$A/out/slurm/slurm-test.sbatch" || fail "memory from the catalogue"
job=$(echo "$out" | job_of)
[ -n "$job" ] || fail "no job id"
wait_job "$job" 300
status=$("$VGD" batch status "$A/catalogue.json" -o "$A/out") || { echo "$status"; fail "status after the array"; }
echo "$status"
echo "$status" | grep -q "6 items: 6 passed, 0 failed, 0 partial, 0 pending" || fail "every item passed and verified"
ls "$A/out/slurm/${job}"_*.log > /dev/null || fail "task logs in out/slurm"
"$VGD" batch collect "$A/catalogue.json" -o "$A/out" > /dev/null
[ "$(tail -n +2 "$A/out/summary.csv" | grep -c ',passed,')" = 6 ] || fail "summary.csv rows"

# 2. A submission cancelled midway, then resubmitted.
B=$WORK/b
make_catalogue "$B"
out=$("$VGD" batch slurm "$B/catalogue.json" -o "$B/out" --max-running 1 --submit)
job=$(echo "$out" | job_of)
t=0
# Cancelled with two items finished and the next one halfway (its .partial folder there).
until [ "$(find "$B/out/items" -name manifest.json 2> /dev/null | wc -l)" -ge 2 ] &&
  [ -n "$(find "$B/out/items" -maxdepth 1 -name '*.partial' 2> /dev/null)" ]; do
  sleep 0.5
  t=$((t + 1))
  [ $t -lt 400 ] || fail "no two items finished and a third started in 200 s"
done
scancel "$job"
wait_job "$job" 60
before=$("$VGD" batch status "$B/catalogue.json" -o "$B/out" || true)
echo "after scancel: $before"
done_before=$(find "$B/out/items" -name manifest.json | sort)
n_before=$(echo "$done_before" | wc -l)
[ "$n_before" -ge 2 ] && [ "$n_before" -lt 6 ] || fail "cancelled midway: $n_before finished"
echo "$before" | grep -q "[1-9] partial" || fail "the item cancelled halfway counts as partial: $before"
sums_before=$(for m in $done_before; do sha256sum "$m"; done)
out=$("$VGD" batch slurm "$B/catalogue.json" -o "$B/out" --submit)
echo "$out"
left=$((6 - n_before))
echo "$out" | grep -q "$left items as --array" || fail "only the $left unfinished items resubmitted"
job=$(echo "$out" | job_of)
wait_job "$job" 300
after=$("$VGD" batch status "$B/catalogue.json" -o "$B/out") || { echo "$after"; fail "status after the resubmission"; }
echo "$after" | grep -q "6 items: 6 passed, 0 failed, 0 partial, 0 pending" || fail "none lost: $after"
sums_after=$(for m in $done_before; do sha256sum "$m"; done)
[ "$sums_before" = "$sums_after" ] || fail "items finished before the cancel were redone"
[ -z "$(find "$B/out/items" -maxdepth 1 -name '*.partial')" ] || fail "a partial folder left"
echo "PASS: 6 items through Slurm; cancelled after $n_before, the $left others resubmitted, none redone, none lost"
