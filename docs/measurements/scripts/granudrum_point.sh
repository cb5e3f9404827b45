#!/bin/bash
# One GranuDrum run at the s = 2 calibrated point (or other --set values) and its profile error
# against the photo, as measured in docs/measurements/README.md ("Wall friction and s = 1.5", 2026-12-04).
# Usage (from the repository root, after scripts/build):
#   docs/measurements/scripts/granudrum_point.sh WORK NAME RPM [name=value ...]
# WORK: scratch folder (photo profiles, runs, logs; DEMFIT_CACHE_DIR=WORK/cache); NAME: a label;
# RPM: 15 or 45; the extra name=value pairs are appended to --set and override the defaults below
# (later --set values win). Prints: NAME RPM wall-time RMS [mm] area [mm2] common x-range [mm].
set -euo pipefail
work=$1 name=$2 rpm=$3
shift 3
case_file=docs/measurements/granudrum/s15_and_wall_scan/case_walls_separate.json
source "$(dirname "$0")/photo_profile.sh"
granudrum_setup "$work" "$rpm"
out=$work/run_${name}_$rpm
/usr/bin/time -f "%e s" build/apps/demfit simulate "$case_file" --threads 1 --out "$out" \
  --set frics=0.38523 fricr=0.15210 particle_count=28796 wall_frics=0.38523 wall_fricd=0.15210 \
  drum.rpm="$rpm" time_step.value=2e-5 drum.scale_factor=2 drum.image.margin=0.3 "$@" > "$work/log_${name}_$rpm" 2>&1
echo "$name $rpm $(tail -1 "$work/log_${name}_$rpm") $(python3 docs/measurements/scripts/profile_error.py \
  "$out/free_surface_image.csv" "$photo/free_surface.csv")"
