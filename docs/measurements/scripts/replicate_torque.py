#!/usr/bin/env python3
"""Mean drive torque over the runs of a replicate_surface.sh / answer_transfer.sh WORK folder
(each run_*/summary.txt), against a reference torque [N m], for docs/measurements/README.md reading 14.
Usage: replicate_torque.py WORK REFERENCE_N_M"""
import glob
import statistics
import sys

if len(sys.argv) != 3:
    sys.exit("usage: replicate_torque.py WORK REFERENCE_N_M")
work, reference = sys.argv[1], float(sys.argv[2])
values = []
for path in sorted(glob.glob(work + "/run_*/summary.txt")):
    for line in open(path):
        if line.strip().startswith("mean drive torque"):
            values.append(float(line.split()[-1]))
if len(values) < 2:
    sys.exit("replicate_torque.py: fewer than 2 run_*/summary.txt with a torque line in " + work)
mean = statistics.mean(values)
print("torque %.5f sd %.5f N m over %d runs, %+.0f %% against %.5f"
      % (mean, statistics.stdev(values), len(values), 100.0 * (mean / reference - 1.0), reference))
