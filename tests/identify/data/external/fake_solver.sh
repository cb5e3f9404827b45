#!/bin/sh
# A stand-in simulation program for the external-model tests. It reads "in.txt" (written by demfit
# from in.txt.template: one "name = value" per line) and writes response.csv with
#   force_N = amplitude * (1 - exp(-rate * time_s))  at 21 times in [0, 1] s.
# The first argument selects a misbehaviour, to test how demfit handles it:
#   normal | hang | hang_child | no_output | nan | fail | fail_high | link_out | empty
mode=${1:-normal}
value() { awk -F= -v name="$1" '{ gsub(/[ \t]/, "", $1) } $1 == name { print $2 + 0 }' in.txt; }
amplitude=$(value amplitude)
rate=$(value rate)
case $mode in
  hang) exec sleep 60 ;;
  hang_child)
    # A child process that outlives the solver unless its whole process group is killed.
    sleep 60 &
    echo $! > child.pid
    exec sleep 60 ;;
  fail) echo "solver diverged" >&2; exit 3 ;;
  no_output) exit 0 ;;
  link_out)
    # A curve file that is a link to a file outside the run folder.
    printf 'time_s,force_N\n0,1\n1,2\n' > ../../outside.csv
    ln -s "$(cd ../.. && pwd)/outside.csv" response.csv
    exit 0 ;;
  fail_high) if awk -v a="$amplitude" 'BEGIN { exit !(a > 1.7) }'; then exit 3; fi ;;
esac
awk -v a="$amplitude" -v r="$rate" -v mode="$mode" 'BEGIN {
  print "time_s,force_N"
  if (mode == "empty") exit
  for (i = 0; i <= 20; ++i) {
    t = i / 20
    y = a * (1 - exp(-r * t))
    if (mode == "nan" && i == 10) printf "%.17g,nan\n", t
    else printf "%.17g,%.17g\n", t, y
  }
}' > response.csv
