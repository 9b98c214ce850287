#!/usr/bin/env bash
# `vgd avatar report` over every file of Debian's assimp-testmodels: each one
# is read as a body or refused with a message (exit 0 or 1); none crashes
# (a signal) or fails inside vgd (exit 4). A file still running after the
# time limit is counted and listed, not failed (bounded time is a limit of
# its own, docs/avatar.md). Prints the counts by format.
#
#   avatar_robustness.sh VGD [MODELS_DIR] [SECONDS_PER_FILE]
set -uo pipefail
vgd=${1:?usage: avatar_robustness.sh VGD [MODELS_DIR] [SECONDS]}
dir=${2:-/usr/share/assimp/models}
limit=${3:-10}
if [ ! -d "$dir" ]; then
  echo "SKIPPED: $dir is absent (Debian's assimp-testmodels; .ci/install-deps installs it)"
  exit 0
fi
declare -A read refused slow
err=$(mktemp)
trap 'rm -f "$err"' EXIT
bad=0 files=0
while IFS= read -r -d '' f; do
  files=$((files + 1))
  ext=${f##*.}
  ext=${ext,,}
  timeout "$limit" "$vgd" avatar report "$f" >/dev/null 2>"$err" </dev/null
  rc=$?
  case $rc in
    0) read[$ext]=$((${read[$ext]:-0} + 1)) ;;
    1) refused[$ext]=$((${refused[$ext]:-0} + 1))
       if ! grep -q "$(basename "$f")" "$err"; then
         echo "NO FILE NAME: $f: $(head -c 300 "$err")"
         bad=$((bad + 1))
       fi ;;
    124) slow[$ext]=$((${slow[$ext]:-0} + 1)); echo "time limit ($limit s): $f" ;;
    *) echo "FAILED (exit $rc): $f: $(head -c 300 "$err")"; bad=$((bad + 1)) ;;
  esac
done < <(find "$dir" -type f -print0 | sort -z)
printf '%-8s %6s %8s %6s\n' format read refused slow
for ext in $(printf '%s\n' "${!read[@]}" "${!refused[@]}" "${!slow[@]}" | sort -u); do
  printf '%-8s %6d %8d %6d\n' "$ext" "${read[$ext]:-0}" "${refused[$ext]:-0}" "${slow[$ext]:-0}"
done
echo "$files files, $bad crashed, failed inside vgd or refused without naming the file"
[ "$bad" -eq 0 ]
