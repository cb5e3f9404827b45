# A stand-in simulation program for the external-diagnosis test, run as
# "awk -f hidden_effect_solver.awk in.txt" (one process per run). It reads in.txt (written by
# demfit from in.txt.template: one "name = value" per line) and writes response.csv with
#   force_N = amplitude (1 - exp(-rate time_s)) + late_gain time_s^3 + offset
# at 41 times in [0, 1] s. late_gain and offset are the effects a diagnosis may add; 0 = off.
BEGIN { FS = "=" }
/^#/ { next }
{ gsub(/[ \t]/, "", $1); value[$1] = $2 + 0 }
END {
  out = "response.csv"
  print "time_s,force_N" > out
  for (i = 0; i <= 40; ++i) {
    t = i / 40
    y = value["amplitude"] * (1 - exp(-value["rate"] * t)) + value["late_gain"] * t * t * t + value["offset"]
    printf "%.17g,%.17g\n", t, y > out
  }
}
