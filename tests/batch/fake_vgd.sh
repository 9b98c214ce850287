#!/bin/bash
# A stand-in for vgd in the batch tests: answers `vgd [--threads N] dress ...
# -o DIR ...` as $FAKE_VGD says, and `compress`/`export` by writing their -o
# file. Modes: pass, check-failed, bad-input, crash, hang. $FAKE_PNG: a PNG
# to copy as the preview.
set -u
while [ "${1:-}" = "--threads" ]; do shift 2; done
cmd=$1; shift
out=""; trj=""
while [ $# -gt 0 ]; do
  case "$1" in
    -o) out=$2; shift ;;
    --trj) trj=$2; shift ;;
    --gltf) : > "$2"; shift ;;
  esac
  shift
done
case "$cmd" in
  dress)
    mkdir -p "$out/previews"
    case "${FAKE_VGD:-pass}" in
      bad-input) echo "vgd: error: style.xvc: SIZE '99': no such size (the sizes are 36, 38)" >&2; exit 1 ;;
      crash) echo "about to crash" >&2; kill -SEGV $$ ;;
      hang) sleep 60 & wait; exit 0 ;;
    esac
    echo "garment" > "$out/garment.obj"
    if [ -n "${FAKE_PNG:-}" ]; then cp "$FAKE_PNG" "$out/previews/front.png"; else echo "png" > "$out/previews/front.png"; fi
    [ -n "$trj" ] && echo "trj" > "$trj"
    if [ "${FAKE_VGD:-pass}" = check-failed ]; then
      printf '{"passed": false, "stop": {"reason": "time limit", "simulated_s": 8.0, "wall_s": 3.5}, "seams": [{"closed": 10, "pairs": 40}], "penetration": {"max_m": 0.0004}, "triangle_intersections": 0, "failures": [{"class": "seams open", "detail": "left armhole 10/40 pairs closed"}, {"class": "no rest", "detail": "still moving"}]}' > "$out/certificate.json"
      exit 3
    fi
    printf '{"passed": true, "stop": {"reason": "rest", "simulated_s": 1.5, "wall_s": 2.0}, "seams": [{"closed": 40, "pairs": 40}], "penetration": {"max_m": 0.0002}, "triangle_intersections": 0, "strain": [{"piece": "FRONT", "warp": {"p95": 0.05}, "weft": {"p95": 0.08}}], "failures": []}' > "$out/certificate.json"
    ;;
  compress|export) [ -n "$out" ] && echo "$cmd" > "$out"; exit 0 ;;
  *) echo "fake vgd: unknown command $cmd" >&2; exit 2 ;;
esac
