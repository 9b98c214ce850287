#!/bin/sh
# The studio's tests with goldens, and the whole session on a shared DXF,
# drawn in a GLFW window on a virtual X display (Xvfb) instead of off-screen:
# the window's OpenGL context must give the goldens the off-screen tests
# give (vgd_test_studio_window is test_studio.cpp built with
# VGD_STUDIO_TEST_WINDOW).
#   window_tests.sh VGD_TEST_STUDIO_WINDOW
set -eu
bin=$1
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIPPED: xvfb-run is not installed (.ci/install-deps installs it)"
  exit 77
fi
# Mesa's GLX driver, loaded and unloaded by GLFW, leaves bytes LeakSanitizer
# can only report as "<unknown module>" (as in window_smoke.sh).
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
exec xvfb-run -a -s "-screen 0 1280x800x24" "$bin" \
  --gtest_filter='Studio.TheFirstFrameWithTheTShirtMatchesItsGolden:Studio.ASharedDxfIsImportedEditedArrangedDrapedAndSaved:Studio.AnArrangedPieceIsTurnedRoundTheBodyAndMovedOffIt:Studio.ThePreviewDrawsTheDocumentsTexture'
