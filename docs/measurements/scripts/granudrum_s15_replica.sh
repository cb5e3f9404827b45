#!/bin/bash
# One fill replica of the s = 1.5 calibration's best point (docs/measurements/README.md, "The full
# calibration at s = 1.5"): the study's overrides, another random packing (drum.fill_seed), scored
# against the photo by profile_error.py as the report scores it.
# Usage (from the repository root, after scripts/build):
#   docs/measurements/scripts/granudrum_s15_replica.sh WORK FILL_SEED RPM [BEST_JSON]
# WORK: scratch folder (photo profiles, runs, logs; DEMFIT_CACHE_DIR=WORK/cache).
# BEST_JSON: a study's best_parameters.json whose "parameters" (frics, fricr, particle_count) are
# run (default: the first s = 1.5 calibration's, docs/measurements/granudrum/s15_full_calibration/).
# Prints: fill FILL_SEED rpm RPM wall-time RMS [mm] area [mm2] common x-range [mm].
# Another resolution: SCALE (drum.scale_factor, default 1.5) and TIME_STEP (s, default 1.5e-5) in
# the environment, e.g. SCALE=2 TIME_STEP=2e-5 for an s = 2 study's point.
set -euo pipefail
work=$1 seed=$2 rpm=$3
scale=${SCALE:-1.5} time_step=${TIME_STEP:-1.5e-5}
best=${4:-docs/measurements/granudrum/s15_full_calibration/best_parameters.json}
read -r frics fricr count < <(python3 -c 'import json, sys
p = json.load(open(sys.argv[1]))["parameters"]
print(repr(p["frics"]), repr(p["fricr"]), repr(p["particle_count"]))' "$best")
source "$(dirname "$0")/photo_profile.sh"
granudrum_setup "$work" "$rpm"
out=$work/run_f${seed}_$rpm
log=$work/log_f${seed}_$rpm
/usr/bin/time -f "%e s" build/apps/demfit simulate cases/granudrum_mcc.json --threads 1 --out "$out" \
  --set frics="$frics" fricr="$fricr" particle_count="$count" \
  drum.rpm="$rpm" time_step.value="$time_step" drum.scale_factor="$scale" drum.duration=1.7 drum.surface_window=0.2 \
  drum.surface_snapshots=21 drum.image.margin=0.3 drum.fill_seed="$seed" > "$log" 2>&1
echo "fill $seed rpm $rpm $(tail -1 "$log") $(python3 docs/measurements/scripts/profile_error.py \
  "$out/free_surface_image.csv" "$photo/free_surface.csv")"
