#!/usr/bin/env python3
# The best-so-far path of a finished study (docs/measurements/README.md, "where the runs go"): every run that
# lowered the best objective, in run order (iteration, point), with its variable values and, when a
# target CSV is given, the RMS distance [target's y unit] of that run's curve from the target over
# the target's abscissae (linear interpolation; target points outside the run's x-range skipped).
# Usage: best_so_far.py STUDY_FOLDER [CURVE TARGET_CSV]
#   e.g. best_so_far.py results/table3/study free_surface results/table3/study/target_free_surface.csv
import csv, json, math, sqlite3, sys

def read_target(path):
    rows = [l for l in open(path) if not l.startswith('#')]
    return [(float(a), float(b)) for a, b in list(csv.reader(rows))[1:]]

def interpolate(x, xs, ys):
    for i in range(len(xs) - 1):
        lo, hi = sorted((xs[i], xs[i + 1]))
        if lo <= x <= hi and xs[i + 1] != xs[i]:
            t = (x - xs[i]) / (xs[i + 1] - xs[i])
            return ys[i] + t * (ys[i + 1] - ys[i])
    return None

def rms(curve, target):
    d = [interpolate(x, curve['x'], curve['y']) for x, _ in target]
    pairs = [(v, y) for v, (_, y) in zip(d, target) if v is not None]
    return math.sqrt(sum((v - y) ** 2 for v, y in pairs) / len(pairs)) if pairs else float('nan')

folder = sys.argv[1]
curve_name = sys.argv[2] if len(sys.argv) > 3 else None
target = read_target(sys.argv[3]) if curve_name else None
db = sqlite3.connect(folder + '/study.db')
study = json.loads(db.execute("select value from meta where key='study_json'").fetchone()[0])
names = [v['name'] for v in study['variables']]
best, first_rms = math.inf, None
runs = db.execute("select iteration, point, kind, parameters, curves, objective, status "
                  "from evaluations order by iteration, point").fetchall()
for n, (iteration, point, kind, parameters, curves, objective, status) in enumerate(runs, 1):
    if status != 'ok' or objective >= best:
        continue
    best = objective
    values = json.loads(parameters)
    line = 'run %3d (iteration %d point %d, %s) objective %.6g  ' % (n, iteration, point, kind, objective)
    line += ' '.join('%s %.6g' % (k, values[k]) for k in names)
    if curve_name:
        r = rms(json.loads(curves)[curve_name], target)
        first_rms = first_rms or r
        line += '  rms %.3f (ratio %.3f)' % (r, r / first_rms)
    print(line)
print('%d runs' % len(runs))
