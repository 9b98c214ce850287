#!/bin/sh
# vgd-studio's command line: --help, a scripted off-screen session, and a
# script line that fails (exit 1, the message names the script and the line).
#   cli_smoke.sh VGD_STUDIO SOURCE_DIR OUT_DIR
set -u
studio=$1 src=$2 out=$3
mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$studio" --help | grep -q -- "--headless" || fail "--help does not list --headless"
printf 'click quality\nclick quality:precise\nexpect-status Opened\nscreenshot %s/s.png\n' "$out" > "$out/ok.txt"
"$studio" --headless "$src/data/garments/a-line-skirt.xvc" --script "$out/ok.txt" > "$out/ok.log" 2>&1 || fail "a good script failed: $(cat "$out/ok.log")"
[ -s "$out/s.png" ] || fail "no screenshot"
printf '# comment\nclick quality\nclick No such button\n' > "$out/bad.txt"
"$studio" --headless "$src/data/garments/a-line-skirt.xvc" --script "$out/bad.txt" > "$out/bad.log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a failing script exited $code, not 1"
grep -q "bad.txt:3: click: .*No such button" "$out/bad.log" || fail "the error does not name the line: $(cat "$out/bad.log")"
"$studio" --headless "$out/missing.xvc" > "$out/missing.log" 2>&1 && fail "a missing file was accepted"
echo "ok"
