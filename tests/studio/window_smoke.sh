#!/bin/sh
# vgd-studio in its GLFW window (GLX on a virtual X display, Xvfb): it opens,
# draws, and its frame matches the off-screen golden of the same document, so
# the window path draws what the tested off-screen path draws.
#   window_smoke.sh VGD_STUDIO VGD SOURCE_DIR OUT_DIR
set -eu
studio=$1 vgd=$2 src=$3 out=$4
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIPPED: xvfb-run is not installed (.ci/install-deps installs it)"
  exit 77
fi
mkdir -p "$out"
# Under AddressSanitizer: Mesa's GLX driver, which GLFW loads with dlopen and
# unloads at exit, leaves 240 bytes LeakSanitizer can only report as
# "<unknown module>". The same studio code runs leak-checked off-screen in
# vgd_test_studio; here the leak check is off.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
out=$(cd "$out" && pwd)
# Opened by its path from the source folder, as the golden was: the status bar says it.
(cd "$src" && xvfb-run -a -s "-screen 0 1280x800x24" \
  "$studio" data/garments/t-shirt.xvc --quit-after 5 --screenshot "$out/window.png" > "$out/window.txt")
grep -q "Opened .*t-shirt.xvc: 20 patterns" "$out/window.txt"
"$vgd" compare "$out/window.png" "$src/tests/golden/studio/t-shirt.png" --threshold 0.98
