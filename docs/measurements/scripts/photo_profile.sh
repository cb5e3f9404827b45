# Sourced by the GranuDrum measurement scripts (granudrum_setup below). photo_profile WORK RPM
# extracts the photo's free surface once (margin 0.3, 41 points, as the shipped studies) into WORK/photoRPM and prints that folder.
photo_profile() {
  local photo=$1/photo$2
  [ -f "$photo/free_surface.csv" ] ||
    build/apps/demfit target from-image "data/granudrum_mcc/granudrum_mcc_${2}rpm.bmp" --diameter 84mm \
      --margin 0.3 --points 41 --out "$photo" > /dev/null
  echo "$photo"
}

# granudrum_setup WORK RPM: the scratch folder every GranuDrum measurement script starts from:
# creates WORK, keeps the fills and results it caches in WORK/cache (not the user's cache), and sets
# `photo` to the folder of the RPM photo's extracted surface.
granudrum_setup() {
  mkdir -p "$1"
  export DEMFIT_CACHE_DIR=$1/cache
  photo=$(photo_profile "$1" "$2")
}
