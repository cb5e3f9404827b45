#!/usr/bin/env python3
# Is the s = 4 bed really higher than the s = 1 bed, or does the silhouette surface put it there?
# (docs/measurements/README.md, Table 3 reading 11.) The free_surface curve is the top of the particles'
# silhouette (cases/free_surface.hpp), which lies about one particle radius above the bulk, and the
# coarse particles are 4 x larger. A size-independent surface: the solid fraction averaged over the
# drum depth, phi(x, y) = sum over spheres of their chord along z / depth, smoothed by one Gaussian
# of width SIGMA for both beds (the same kernel, so the same bias), and the surface at x is the
# highest y where it reaches half the bulk value (the 75th percentile of phi > 0.05).
# Input: particles_end.csv of `demfit simulate` (x_mm, y_mm, z_mm, radius_mm; two header lines).
# Usage: surface_half_density.py S1_PARTICLES_CSV S4_PARTICLES_CSV [SIGMAS_MM, default 1,2,4,8]
# Prints, for the silhouette and each kernel width, the s = 4 surface minus the s = 1 surface over
# x = -35..35 mm (mean, RMS, RMS about the mean [mm]) and the bulk solid fractions.
import math
import sys

DEPTH_MM = 25.0  # drum axial length (SPEC 2.2)
GRID_MM = 0.5
CELLS = int(100 / GRID_MM) + 1  # the drum's 100 mm diameter, centred on the axis
COORDS = [-50 + i * GRID_MM for i in range(CELLS)]
ABSCISSAE = [-35 + 2.5 * i for i in range(29)]


def load(path):
    rows = [line.split(',') for line in open(path).read().splitlines()[2:]]
    return [tuple(map(float, row)) for row in rows]


def solid_fraction(spheres):
    phi = [[0.0] * CELLS for _ in range(CELLS)]  # phi[y][x]
    for x, y, _z, r in spheres:
        i0, i1 = max(0, int((x - r + 50) / GRID_MM)), min(CELLS - 1, int((x + r + 50) / GRID_MM) + 1)
        j0, j1 = max(0, int((y - r + 50) / GRID_MM)), min(CELLS - 1, int((y + r + 50) / GRID_MM) + 1)
        for j in range(j0, j1 + 1):
            dy = COORDS[j] - y
            for i in range(i0, i1 + 1):
                q = r * r - (COORDS[i] - x) ** 2 - dy * dy
                if q > 0:
                    phi[j][i] += 2 * math.sqrt(q) / DEPTH_MM
    return phi


def gaussian_smooth(phi, sigma):
    half = int(3 * sigma / GRID_MM)
    weights = [math.exp(-0.5 * (t * GRID_MM / sigma) ** 2) for t in range(-half, half + 1)]
    total = sum(weights)
    weights = [w / total for w in weights]

    def along(values, k):
        return sum(weights[t + half] * values[k + t] for t in range(-half, half + 1) if 0 <= k + t < CELLS)

    rows = [[along(row, i) for i in range(CELLS)] for row in phi]
    columns = [[along([rows[j][i] for j in range(CELLS)], j) for j in range(CELLS)] for i in range(CELLS)]
    return [[columns[i][j] for i in range(CELLS)] for j in range(CELLS)]


def silhouette_surface(spheres):
    heights = []
    for xv in ABSCISSAE:
        tops = [y + math.sqrt(r * r - (xv - x) ** 2) for x, y, _z, r in spheres if abs(x - xv) < r]
        heights.append(max(tops) if tops else math.nan)
    return heights


def half_density_surface(smoothed):
    values = sorted(v for row in smoothed for v in row if v > 0.05)
    bulk = values[int(0.75 * len(values))]
    heights = []
    for xv in ABSCISSAE:
        i = int(round((xv + 50) / GRID_MM))
        column = [smoothed[j][i] for j in range(CELLS)]
        dense = [j for j in range(CELLS) if column[j] >= 0.5 * bulk]
        if not dense or max(dense) + 1 >= CELLS:
            heights.append(math.nan)
            continue
        j = max(dense)
        heights.append(COORDS[j] + (column[j] - 0.5 * bulk) / (column[j] - column[j + 1]) * GRID_MM)
    return heights, bulk


def difference(coarse, fine):
    d = [a - b for a, b in zip(coarse, fine) if not (math.isnan(a) or math.isnan(b))]
    mean = sum(d) / len(d)
    rms = math.sqrt(sum(v * v for v in d) / len(d))
    about = math.sqrt(sum((v - mean) ** 2 for v in d) / len(d))
    return 'mean %.2f mm, RMS %.2f mm, RMS about the mean %.2f mm, %d abscissae' % (mean, rms, about, len(d))


def main():
    sigmas = [float(v) for v in sys.argv[3].split(',')] if len(sys.argv) > 3 else [1.0, 2.0, 4.0, 8.0]
    beds = [load(sys.argv[1]), load(sys.argv[2])]
    print('silhouette (free_surface) s4 - s1: ' + difference(*[silhouette_surface(b) for b in reversed(beds)]))
    fields = [solid_fraction(b) for b in beds]
    for sigma in sigmas:
        (fine, fine_bulk), (coarse, coarse_bulk) = [half_density_surface(gaussian_smooth(f, sigma)) for f in fields]
        print('half density, sigma %g mm, s4 - s1: %s; bulk solid fraction s1 %.3f, s4 %.3f'
              % (sigma, difference(coarse, fine), fine_bulk, coarse_bulk))


if __name__ == '__main__':
    main()
