#!/usr/bin/env bash
# What the settled-fill cache saves per evaluation: the same case run with an empty fill cache
# (the fill is poured, settled and cached, then the measured stage runs) and with the fill read
# back from the cache (only the measured stage runs), REPEATS times each; medians of the wall
# times, the share of a cold run the cache saves, and the load average beside every figure.
#   bench/cases/fill_reuse.sh [DEMFIT] [CASE] [REPEATS] [-- demfit simulate options, e.g. --set drum.scale_factor=4]
# Defaults: build/apps/demfit, cases/granudrum_mcc.json at SCG s = 4 (--set drum.scale_factor=4), 3 repeats.
# A study's evaluations that do not change the fill all start from the cached bed, so a study of N
# such evaluations pays the fill once instead of N times.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
demfit="${1:-$root/build/apps/demfit}"
case_file="${2:-$root/cases/granudrum_mcc.json}"
repeats="${3:-3}"
shift $(($# < 3 ? $# : 3))
[[ "${1:-}" == "--" ]] && shift
options=("$@")
((${#options[@]})) || options=(--set drum.scale_factor=4)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }
# "WALL FILL" of one `demfit simulate`: its wall seconds and the fill wall time its summary.txt
# reports (0 when the fill came from the cache). A failure stops the script.
run_seconds() {
  local start end
  start=$(date +%s.%N)
  DEMFIT_CACHE_DIR="$work/cache" "$demfit" simulate "$case_file" --threads 1 --out "$work/out" "${options[@]}" \
    >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
  end=$(date +%s.%N)
  echo "$(awk -v a="$start" -v b="$end" 'BEGIN {print b - a}') $(awk '/fill wall time/ {print $NF}' "$work/out/summary.txt")"
}
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
echo "fill reuse: $case_file ${options[*]}, 1 thread, $repeats repeats; load $(load)"
cold=() fill=() warm=()
for ((i = 1; i <= repeats; ++i)); do
  rm -rf "$work/cache"
  read -r c f < <(run_seconds)
  read -r w _ < <(run_seconds)
  cold+=("$c") fill+=("$f") warm+=("$w")
  printf '  repeat %d: cold cache %.2f s (fill %.2f s), cached fill %.2f s  [load %s]\n' "$i" "$c" "$f" "$w" "$(load)"
done
mc=$(median "${cold[@]}") mf=$(median "${fill[@]}") mw=$(median "${warm[@]}")
printf 'median: cold cache %.2f s of which the fill %.2f s (%.1f %%); cached fill %.2f s (%.1f %% of a cold run saved)  [load %s]\n' \
  "$mc" "$mf" "$(awk -v f="$mf" -v c="$mc" 'BEGIN {print 100 * f / c}')" "$mw" \
  "$(awk -v w="$mw" -v c="$mc" 'BEGIN {print 100 * (c - w) / c}')" "$(load)"
