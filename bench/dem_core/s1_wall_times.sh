#!/bin/bash
# One full-resolution (s = 1) run's wall time on 2 threads in three kernel set-ups
# (docs/cases.md "numerics"): stored = the cases' defaults (insertion order, pair loads
# own_row_first), reordered = Morton order at rebuilds, lean = Morton order and pair loads summed
# in ascending first member (dem_core's defaults), for
#   - the paper's drum (cases/rotary_drum.json: s = 1, ~9,000 spheres, 3 s at 60 rpm), and
#   - the GranuDrum MCC drum (cases/granudrum_mcc.json at s = 1: 29,185 spheres, 1.7 s at 15 rpm,
#     the source's published frics 0.561 and fricr 0.293).
# Each run is cold: its own empty DEMFIT_CACHE_DIR, so the time includes packing and densifying the
# fill (the reordered run packs its own fill: its cache key differs). One run per variant (a
# GranuDrum run takes tens of minutes); the load average is printed beside each figure.
# Time it only when nothing else runs (README "Performance").
# After both orders of a case, the RMS difference of their free surfaces (common x-range, linear
# interpolation at 400 points) says how far a round-off realisation moves the result.
# Usage: bench/dem_core/s1_wall_times.sh BUILD_DIR OUT_DIR [paper|granudrum|all (all)|compare]
#        [SET-UPS (default "stored reordered lean")]
# (compare: only the surface differences of the runs already in OUT_DIR)
set -euo pipefail
demfit="$(cd "$1" && pwd)/apps/demfit"
out="$2"
which="${3:-all}"
setups="${4:-stored reordered lean}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
mkdir -p "$out"
out="$(cd "$out" && pwd)"

run_case() {  # label case-file set-up(stored|reordered|lean) [--set ...]
  local label="$1" case_file="$2" order="$3"
  shift 3
  local dir="$out/$label-$order"
  local cache="$out/cache-$label-$order"
  rm -rf "$dir" "$cache"
  mkdir -p "$cache"
  local reorder=false pair_order=own_row_first
  [ "$order" != stored ] && reorder=true
  [ "$order" = lean ] && pair_order=ascending_first_member
  local load_before start end
  load_before="$(cut -d' ' -f1-3 /proc/loadavg)"
  start="$(date +%s.%N)"
  DEMFIT_CACHE_DIR="$cache" "$demfit" simulate "$case_file" --threads 2 --out "$dir" \
    --set "numerics.reorder_particles=$reorder" "numerics.pair_load_order=$pair_order" "$@" \
    >"$out/$label-$order.log" 2>&1
  end="$(date +%s.%N)"
  printf '%-10s %-9s %8.1f s wall, 2 threads  [load before %s, after %s]\n' "$label" "$order" \
    "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" "$load_before" "$(cut -d' ' -f1-3 /proc/loadavg)"
  # The run's own split and what it computed (another order is another round-off realisation).
  grep -E "particles  |fill wall time|rotation wall time|dynamic angle of repose|mean drive torque" "$dir/summary.txt" |
    sed -E 's/  +/ /g; s/^/    /'
}

surface_difference() {  # label csv-name set-up set-up: RMS and max |dz| [mm] between two profiles
  local a="$out/$1-$3/$2" b="$out/$1-$4/$2"
  [ -f "$a" ] && [ -f "$b" ] || return 0
  awk -F, -v label="$1" -v name="$2" -v pair="$3 vs $4" '
    FNR == 1 { file++ } /^#/ || /^x_mm/ { next }
    { n[file]++; x[file, n[file]] = $1; z[file, n[file]] = $2 }
    function at(f, xq,   k, t) {
      for (k = 2; k <= n[f]; k++)
        if (x[f, k] >= xq) { t = (xq - x[f, k - 1]) / (x[f, k] - x[f, k - 1]); return z[f, k - 1] + t * (z[f, k] - z[f, k - 1]) }
      return z[f, n[f]]
    }
    END {
      lo = x[1, 1] > x[2, 1] ? x[1, 1] : x[2, 1]; hi = x[1, n[1]] < x[2, n[2]] ? x[1, n[1]] : x[2, n[2]]
      for (k = 0; k < 400; k++) { xq = lo + (hi - lo) * k / 399; d = at(1, xq) - at(2, xq); s += d * d; if (d < 0) d = -d; if (d > m) m = d }
      printf "%-10s %s %s: RMS %.3f mm, max %.3f mm over x %.1f..%.1f mm\n", label, name, pair, sqrt(s / 400), m, lo, hi
    }' "$a" "$b"
}

compare_all() {  # label csv-name: every set-up present against the stored one
  local setup
  for setup in reordered lean; do surface_difference "$1" "$2" stored "$setup"; done
}

if [ "$which" = compare ]; then
  compare_all paper free_surface.csv
  compare_all granudrum free_surface_image.csv
  exit 0
fi

echo "s = 1 wall times (demfit simulate --threads 2, cold cache: fill included), $(date -u +%F)"
if [ "$which" = paper ] || [ "$which" = all ]; then
  for order in $setups; do run_case paper "$root/cases/rotary_drum.json" "$order"; done
  compare_all paper free_surface.csv
fi
if [ "$which" = granudrum ] || [ "$which" = all ]; then
  for order in $setups; do
    run_case granudrum "$root/cases/granudrum_mcc.json" "$order" --set drum.scale_factor=1 \
      --set frics=0.561 --set fricr=0.293
  done
  compare_all granudrum free_surface_image.csv
fi
