#!/usr/bin/python3
# Writes drum.stl: the closed drum of the LIGGGHTS study (inner diameter 50 mm, depth 10 mm,
# axis z through the origin, faces z = 0 and z = depth), as an ASCII STL in metres. The shell is
# a 64-gon, inscribed so that its flat faces lie at most 0.06 mm inside the circle.
#   /usr/bin/python3 make_drum_mesh.py > drum.stl
import math

RADIUS = 0.025
DEPTH = 0.010
SEGMENTS = 64


def facet(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    n = [x / length for x in n]
    lines = ["facet normal %.9g %.9g %.9g" % tuple(n), " outer loop"]
    lines += ["  vertex %.9g %.9g %.9g" % tuple(p) for p in (a, b, c)]
    lines += [" endloop", "endfacet"]
    return "\n".join(lines)


ring = [(RADIUS * math.cos(2 * math.pi * k / SEGMENTS), RADIUS * math.sin(2 * math.pi * k / SEGMENTS))
        for k in range(SEGMENTS)]
facets = []
for k in range(SEGMENTS):
    (x0, y0), (x1, y1) = ring[k], ring[(k + 1) % SEGMENTS]
    # Shell: two triangles per segment, normals towards the axis.
    facets.append(facet((x0, y0, 0.0), (x0, y0, DEPTH), (x1, y1, 0.0)))
    facets.append(facet((x1, y1, 0.0), (x0, y0, DEPTH), (x1, y1, DEPTH)))
    # End caps: fans from the axis.
    facets.append(facet((0.0, 0.0, 0.0), (x0, y0, 0.0), (x1, y1, 0.0)))
    facets.append(facet((0.0, 0.0, DEPTH), (x1, y1, DEPTH), (x0, y0, DEPTH)))
print("solid drum\n" + "\n".join(facets) + "\nendsolid drum")
