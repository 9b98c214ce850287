#!/usr/bin/env bash
# Start-up time of vgd commands that open no heavy library, against another
# build of vgd in the same run (the machine's load changes from day to day;
# the ratio is what holds). Median of N runs of each, wall clock.
#
#   tests/bench/startup.sh build/apps/vgd/vgd [OTHER_VGD] [N]
#
# Prints one row per command: ms for this build, ms for the other, ratio.
set -euo pipefail
vgd=${1:?usage: startup.sh VGD [OTHER_VGD] [N]}
other=${2:-}
n=${3:-41}
here=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dxf="$here/data/garments/a-line-skirt.dxf"

median_ms() {  # median_ms CMD... : median wall time of n runs, ms
  local t=()
  for ((i = 0; i < n; i++)); do
    local s e
    s=${EPOCHREALTIME/[.,]/}  # µs, without forking a clock program
    "$@" >/dev/null 2>&1 || true
    e=${EPOCHREALTIME/[.,]/}
    t+=($((e - s)))
  done
  printf '%s\n' "${t[@]}" | sort -n | awk -v n="$n" 'NR == int((n + 1) / 2) { printf "%.1f", $1 / 1000 }'
}

printf '%-34s %10s %10s %7s\n' "command" "ms" "other ms" "ratio"
for cmd in "--version" "--help" "import $dxf -o $tmp/s.xvc -q" "validate $here/data/garments/a-line-skirt.xvc -q"; do
  # shellcheck disable=SC2086
  a=$(median_ms "$vgd" $cmd)
  if [ -n "$other" ]; then
    # shellcheck disable=SC2086
    b=$(median_ms "$other" $cmd)
    r=$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", b / a }')
  else
    b="-" r="-"
  fi
  printf '%-34s %10s %10s %7s\n' "${cmd%% *}" "$a" "$b" "$r"
done
