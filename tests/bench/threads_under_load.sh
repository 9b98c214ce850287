#!/usr/bin/env bash
# Threads on a shared machine: `vgd bench sew-cylinder` (1 thread, every core
# adapted to the load, every core fixed) while 0, 1 and 2 other processes keep
# a core busy each (a shell loop), N times each, in one run. Prints each run's
# wall seconds and the ratios to the one-thread run of the same row.
#
#   tests/bench/threads_under_load.sh build/apps/vgd/vgd [N]
set -euo pipefail
vgd=${1:?usage: threads_under_load.sh VGD [N]}
n=${2:-3}
spinners=()
stop() { for p in "${spinners[@]}"; do kill "$p" 2>/dev/null || true; done; spinners=(); }
trap stop EXIT
echo "busy  1 thread  adapted  fixed  adapted/1  fixed/1"
for busy in 0 1 2; do
  stop
  for ((k = 0; k < busy; k++)); do
    sh -c 'while :; do :; done' &
    spinners+=($!)
  done
  sleep 0.5
  for ((i = 0; i < n; i++)); do
    "$vgd" bench sew-cylinder --json 2>/dev/null | python3 -c '
import json, sys
r = json.load(sys.stdin)
one = next(x["wall_s"] for x in r if x["threads"] == 1)
ad = next(x["wall_s"] for x in r if x["threads"] > 1 and x["adapt_threads"])
fx = next(x["wall_s"] for x in r if x["threads"] > 1 and not x["adapt_threads"])
print(f"{sys.argv[1]:>4}  {one:7.2f}  {ad:7.2f}  {fx:5.2f}  {ad / one:9.2f}  {fx / one:7.2f}")' "$busy"
  done
done
