#!/bin/sh
# Regenerates the golden previews in tests/golden/ (docs/qa.md) after an
# intended change to the drape or the renderer. Builds the qa test and runs
# its golden test with VGD_UPDATE_GOLDENS=1: it drapes the A-line skirt and
# renders it exactly as the comparison does, then writes the PNGs here; the
# studio test does the same for the studio's first frame and a whole session's
# weft map on the shared racer-back tank, and the real-garment
# suite for every shared garment that drapes and passes.
#
#   tests/golden/regenerate.sh [BUILD_DIR]      (default: build)
#
# Look at the new images (and `git diff --stat`) before committing them.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
cmake --build "$build" --target vgd_test_qa
VGD_UPDATE_GOLDENS=1 "$build/tests/qa/vgd_test_qa" --gtest_filter='Golden.TheRedrapedSkirtMatchesItsGoldenPreviews'
cmake --build "$build" --target vgd_test_studio
VGD_UPDATE_GOLDENS=1 "$build/tests/studio/vgd_test_studio" \
  --gtest_filter='Studio.TheFirstFrameWithTheTShirtMatchesItsGolden:Studio.ASharedDxfIsImportedEditedArrangedDrapedAndSaved'
# The real-garment suite (only where ../shared is present; it skips otherwise).
cmake --build "$build" --target vgd_test_apps vgd
VGD_UPDATE_GOLDENS=1 "$build/tests/apps/vgd_test_apps" --gtest_filter='Shared/RealGarments.*'
ls -l "$root/tests/golden/a-line-skirt/" "$root/tests/golden/studio/" "$root/tests/golden/real-garments/"
