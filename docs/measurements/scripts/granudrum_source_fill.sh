#!/bin/bash
# One run of the source's published parameters (frics 0.561, fricr 0.293, 29,185 particles) at
# full resolution (s = 1) on another random packing (drum.fill_seed), scored against the photo by
# profile_error.py as `reproduce granudrum` scores its full-resolution check (docs/measurements/README.md,
# "The source's s = 1 figure on more fills").
# Usage (from the repository root, after scripts/build):
#   docs/measurements/scripts/granudrum_source_fill.sh WORK FILL_SEED RPM [THREADS]
# WORK: scratch folder (photo profiles, runs, logs; DEMFIT_CACHE_DIR=WORK/cache).
# Prints: source fill FILL_SEED rpm RPM wall-time RMS [mm] area [mm2] common x-range [mm].
set -euo pipefail
work=$1 seed=$2 rpm=$3 threads=${4:-1}
source "$(dirname "$0")/photo_profile.sh"
granudrum_setup "$work" "$rpm"
out=$work/run_source_f${seed}_$rpm
log=$work/log_source_f${seed}_$rpm
/usr/bin/time -f "%e s" build/apps/demfit simulate cases/granudrum_mcc.json --threads "$threads" --out "$out" \
  --set frics=0.561 fricr=0.293 particle_count=29185 drum.rpm="$rpm" drum.scale_factor=1 \
  drum.fill_seed="$seed" drum.image.margin=0.3 > "$log" 2>&1
echo "source fill $seed rpm $rpm $(tail -1 "$log") $(python3 docs/measurements/scripts/profile_error.py \
  "$out/free_surface_image.csv" "$photo/free_surface.csv")"
