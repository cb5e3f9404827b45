#!/usr/bin/env python3
# How far a drum free-surface curve lies from a target curve, split into a mean vertical offset and
# shape, and the bed's cross-section below each surface (docs/measurements/README.md, Table 3 reading 5).
# Curves are demfit free_surface CSVs (x_mm, height_mm; '#' lines skipped). The offset is taken
# over the target abscissae the curve spans (linear interpolation); the cross-section between the
# drum wall (radius 50 mm) and the surface over X0..X1 by the midpoint rule (2,000 strips).
# Usage: surface_offset.py TARGET_CSV CURVE_CSV [X0 X1]   (X0 X1 default -30 30 [mm])
import math, sys

DRUM_RADIUS_MM = 50.0

def read(path):
    xs, ys = [], []
    for line in open(path):
        if line.startswith('#') or line.startswith('x_mm'):
            continue
        a, b = line.strip().split(',')
        xs.append(float(a)); ys.append(float(b))
    return xs, ys

def interpolate(xs, ys, x):
    for i in range(len(xs) - 1):
        if xs[i] <= x <= xs[i + 1] and xs[i + 1] > xs[i]:
            return ys[i] + (x - xs[i]) / (xs[i + 1] - xs[i]) * (ys[i + 1] - ys[i])
    return None

def cross_section(xs, ys, x0, x1, strips=2000):
    area, width = 0.0, (x1 - x0) / strips
    for i in range(strips):
        x = x0 + (i + 0.5) * width
        top, wall = interpolate(xs, ys, x), math.sqrt(DRUM_RADIUS_MM ** 2 - x * x)
        if top is None:
            raise SystemExit('surface_offset.py: the curve does not span x = %.2f mm' % x)
        area += max(0.0, min(top, wall) + wall) * width
    return area

target, curve = read(sys.argv[1]), read(sys.argv[2])
x0, x1 = (float(sys.argv[3]), float(sys.argv[4])) if len(sys.argv) > 4 else (-30.0, 30.0)
d = [v - y for x, y in zip(*target) for v in [interpolate(*curve, x)] if v is not None]
mean = sum(d) / len(d)
print('RMS %.2f mm, mean offset %+.2f mm, RMS about the mean %.2f mm over %d of %d target points'
      % (math.sqrt(sum(e * e for e in d) / len(d)), mean, math.sqrt(sum((e - mean) ** 2 for e in d) / len(d)),
         len(d), len(target[0])))
print('cross-section below the surface, x %g..%g mm: target %.1f mm2, curve %.1f mm2'
      % (x0, x1, cross_section(*target, x0, x1), cross_section(*curve, x0, x1)))
