#!/bin/bash
# The GranuDrum surfaces measured so far, each against its photo, split by `demfit target compare`
# into level offset, angle difference, tilt and shape (docs/measurements/README.md, "Where the 45 rpm gap
# lies"). Usage (from the repository root, after scripts/build): docs/measurements/scripts/level_split.sh WORK
# Prints one line per surface pair: label, then for 15 and 45 rpm the RMS gap and its level offset
# [mm], the level difference 45 - 15 [mm], and each speed's angle difference [deg] and shape RMS [mm].
set -euo pipefail
work=$1
source "$(dirname "$0")/photo_profile.sh"
photo15=$(photo_profile "$work" 15)
photo45=$(photo_profile "$work" 45)
g=docs/measurements/granudrum
# label  15 rpm surface  45 rpm surface (the 45 rpm-only s = 1 fills have no 15 rpm partner)
pairs=(
  "source_s1_fill1 $g/s3_calibration_and_anchor/published_rpm15_s1_free_surface_image.csv $g/s3_calibration_and_anchor/published_rpm45_s1_free_surface_image.csv"
  "source_s2 $g/s3_calibration_and_anchor/published_rpm15_s2_free_surface_image.csv $g/s3_calibration_and_anchor/published_rpm45_s2_free_surface_image.csv"
  "source_s3 $g/s3_calibration_and_anchor/published_rpm15_s3_free_surface_image.csv $g/s3_calibration_and_anchor/published_rpm45_s3_free_surface_image.csv"
  "source_s4 $g/s3_calibration_and_anchor/published_rpm15_s4_free_surface_image.csv $g/s3_calibration_and_anchor/published_rpm45_s4_free_surface_image.csv"
  "source_s1.5 $g/s15_and_wall_scan/src15_rpm15_free_surface_image.csv $g/s15_and_wall_scan/src15_rpm45_free_surface_image.csv"
  "s2point_s2 $g/s15_and_wall_scan/base_rpm15_free_surface_image.csv $g/s15_and_wall_scan/base_rpm45_free_surface_image.csv"
  "s2point_s2_wall_mus0.2 $g/s15_and_wall_scan/wfs02_rpm15_free_surface_image.csv $g/s15_and_wall_scan/wfs02_rpm45_free_surface_image.csv"
  "s2point_s2_wall_mus0.7 $g/s15_and_wall_scan/wfs07_rpm15_free_surface_image.csv $g/s15_and_wall_scan/wfs07_rpm45_free_surface_image.csv"
  "s2point_s2_wall_mur0.05 $g/s15_and_wall_scan/wfr005_rpm15_free_surface_image.csv $g/s15_and_wall_scan/wfr005_rpm45_free_surface_image.csv"
  "s2point_s2_wall_mur0.4 $g/s15_and_wall_scan/wfr04_rpm15_free_surface_image.csv $g/s15_and_wall_scan/wfr04_rpm45_free_surface_image.csv"
  "s2point_s1.5_fill1 $g/s15_and_wall_scan/s15_rpm15_free_surface_image.csv $g/s15_and_wall_scan/s15_rpm45_free_surface_image.csv"
  "s2point_s1.5_fill2 $g/s15_and_wall_scan/s15f2_rpm15_free_surface_image.csv $g/s15_and_wall_scan/s15f2_rpm45_free_surface_image.csv"
  "calibrated_s1.5_fill1 $g/s15_calibration_loop_fix/best_rpm15.surface.csv $g/s15_calibration_loop_fix/best_rpm45.surface.csv"
  "calibrated_s1.5_fill2 $g/s15_calibration_loop_fix/fill_replicas/fill2_rpm15_free_surface_image.csv $g/s15_calibration_loop_fix/fill_replicas/fill2_rpm45_free_surface_image.csv"
  "calibrated_s1.5_fill3 $g/s15_calibration_loop_fix/fill_replicas/fill3_rpm15_free_surface_image.csv $g/s15_calibration_loop_fix/fill_replicas/fill3_rpm45_free_surface_image.csv"
  "s2point_s2_restitution0.1 $g/level_split/s2point_restitution0.1_rpm15_free_surface_image.csv $g/level_split/s2point_restitution0.1_rpm45_free_surface_image.csv"
  "s2point_s2_restitution0.6 $g/level_split/s2point_restitution0.6_rpm15_free_surface_image.csv $g/level_split/s2point_restitution0.6_rpm45_free_surface_image.csv"
  "count29000_s1.5_fill1 $g/level_split/count29000_fill1_rpm15_free_surface_image.csv $g/level_split/count29000_fill1_rpm45_free_surface_image.csv"
  "count29000_s1.5_fill2 $g/level_split/count29000_fill2_rpm15_free_surface_image.csv $g/level_split/count29000_fill2_rpm45_free_surface_image.csv"
  "shipped_s1.5_fill1 $g/s15_reference_scaled/best_rpm15.surface.csv $g/s15_reference_scaled/best_rpm45.surface.csv"
  "shipped_s1.5_fill2 $g/s15_reference_scaled/fill_replicas/fill2_rpm15_free_surface_image.csv $g/s15_reference_scaled/fill_replicas/fill2_rpm45_free_surface_image.csv"
  "shipped_s1.5_fill3 $g/s15_reference_scaled/fill_replicas/fill3_rpm15_free_surface_image.csv $g/s15_reference_scaled/fill_replicas/fill3_rpm45_free_surface_image.csv"
  "source_s1_fill2 - $g/s1_source_fill_seed2/published_rpm45_s1_fill_seed2_free_surface_image.csv"
  "source_s1_fill3 - $g/s1_source_fill_seeds3_4/published_rpm45_s1_fill_seed3_free_surface_image.csv"
  "source_s1_fill4 - $g/s1_source_fill_seeds3_4/published_rpm45_s1_fill_seed4_free_surface_image.csv"
)
[ $# -ge 2 ] && pairs=("${@:2}")  # further arguments: own "LABEL CSV15 CSV45" triples
# compare CSV PHOTO -> "rms level angle shape"
compare() {
  build/apps/demfit target compare "$1" "$2" |
    sed -n 's/.*RMS gap \([0-9.]*\) mm.*/\1/p; s/.*level offset \([-+0-9.]*\) mm.*angle difference \([-+0-9.]*\) deg.*shape \([0-9.]*\) mm.*/\1 \2 \3/p' |
    tr '\n' ' '
}
printf '%-24s %22s %22s %8s %18s %18s\n' label "15 rpm RMS/level" "45 rpm RMS/level" "45-15" "angle 15/45 [deg]" "shape 15/45 [mm]"
for pair in "${pairs[@]}"; do
  read -r label s15 s45 <<< "$pair"
  read -r r45 l45 a45 h45 <<< "$(compare "$s45" "$photo45/free_surface.csv")"
  if [ "$s15" = - ]; then
    printf '%-24s %22s %11s/%+10.2f %8s %8s/%+9.1f %8s/%9.2f\n' "$label" - "$r45" "$l45" - - "$a45" - "$h45"
    continue
  fi
  read -r r15 l15 a15 h15 <<< "$(compare "$s15" "$photo15/free_surface.csv")"
  printf '%-24s %11s/%+10.2f %11s/%+10.2f %+8.2f %+8.1f/%+9.1f %8.2f/%9.2f\n' "$label" "$r15" "$l15" "$r45" "$l45" \
    "$(python3 -c "print($l45 - ($l15))")" "$a15" "$a45" "$h15" "$h45"
done
