#!/usr/bin/env python3
# A second, local study around a Table 3 answer (docs/measurements/README.md, Table 3 reading 11): the
# shipped study's variables with bounds shrunk to +-HALF_WIDTH of each range around the answer (in
# the sampled scale: decades for log-scaled variables; clipped to the original bounds), the answer
# as initial point, SRSM with 10 points x 6 iterations and a final selection among the 4 best runs.
# Usage: table3_local_study.py CASES_DIR BEST_PARAMETERS_JSON HALF_WIDTH > study.json
#   then: cp TARGET_CSV target_free_surface.csv && demfit identify study.json --out out --jobs 2
import json
import math
import sys


def shrunk(variable, centre, half_width):
    lower, upper = variable['lower'], variable['upper']
    if variable.get('log_scale'):
        span = math.log10(upper) - math.log10(lower)
        low = 10 ** (math.log10(centre) - half_width * span)
        high = 10 ** (math.log10(centre) + half_width * span)
    else:
        span = upper - lower
        low, high = centre - half_width * span, centre + half_width * span
    return max(lower, low), min(upper, high)


def main():
    study = json.load(open(sys.argv[1] + '/table3_study.json'))
    answer = json.load(open(sys.argv[2]))['parameters']
    half_width = float(sys.argv[3])
    for variable in study['variables']:
        centre = answer[variable['name']]
        variable['lower'], variable['upper'] = shrunk(variable, centre, half_width)
        variable['initial'] = centre
    study['name'] = 'table3_local'
    study['sampling'] = {'points_per_iteration': 10, 'strategy': 'srsm'}
    study['stopping'] = {'max_iterations': 6}
    study['final_selection'] = {'candidates': 4, 'replicates': 3}
    json.dump(study, sys.stdout, indent=1)
    print()


if __name__ == '__main__':
    main()
