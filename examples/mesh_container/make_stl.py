#!/usr/bin/env python3
"""Writes the STL files of the mesh_container examples (ASCII STL, coordinates in millimetres).

Standard library only; run once from this folder: /usr/bin/python3 make_stl.py
Every facet's stored normal is the normal of its vertex winding (right-hand rule), as dem_core's
STL reader requires; contact with a mesh is two-sided, so the direction does not matter for the
simulation.
"""
import math


def facet_normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    return [x / length for x in n]


def write_stl(path, name, triangles):
    with open(path, "w", encoding="ascii", newline="\n") as out:
        out.write(f"solid {name}\n")
        for a, b, c in triangles:
            n = facet_normal(a, b, c)
            out.write(f"  facet normal {n[0]:.6e} {n[1]:.6e} {n[2]:.6e}\n    outer loop\n")
            for p in (a, b, c):
                out.write(f"      vertex {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}\n")
            out.write("    endloop\n  endfacet\n")
        out.write(f"endsolid {name}\n")
    print(f"{path}: {len(triangles)} triangles")


def ring(radius, z, n):
    return [(radius * math.cos(2 * math.pi * k / n), radius * math.sin(2 * math.pi * k / n), z) for k in range(n)]


def cylinder_side(radius, z0, z1, n, rows):
    """Side of a cylinder about z, `rows` bands of 2 n triangles."""
    tris = []
    for j in range(rows):
        lo = ring(radius, z0 + (z1 - z0) * j / rows, n)
        hi = ring(radius, z0 + (z1 - z0) * (j + 1) / rows, n)
        for k in range(n):
            m = (k + 1) % n
            tris += [(lo[k], lo[m], hi[m]), (lo[k], hi[m], hi[k])]
    return tris


def annulus(r_in, r_out, z, n, rings):
    """Flat annulus (a disk when r_in == 0) at height z, `rings` concentric bands."""
    tris = []
    for j in range(rings):
        a = r_in + (r_out - r_in) * j / rings
        b = r_in + (r_out - r_in) * (j + 1) / rings
        inner, outer = ring(a, z, n), ring(b, z, n)
        for k in range(n):
            m = (k + 1) % n
            if a == 0.0:
                tris.append(((0.0, 0.0, z), outer[k], outer[m]))
            else:
                tris += [(inner[k], outer[k], outer[m]), (inner[k], outer[m], inner[m])]
    return tris


def rectangle(origin, edge_u, edge_v, nu, nv):
    """Flat rectangle origin + s edge_u + t edge_v, split into nu x nv cells of two triangles."""
    def point(i, j):
        return tuple(origin[k] + edge_u[k] * i / nu + edge_v[k] * j / nv for k in range(3))

    tris = []
    for i in range(nu):
        for j in range(nv):
            tris += [(point(i, j), point(i + 1, j), point(i + 1, j + 1)), (point(i, j), point(i + 1, j + 1), point(i, j + 1))]
    return tris


# heap: a GranuHeap-like cylindrical pedestal, diameter 40 mm, top at z = 20 mm.
write_stl("pedestal.stl", "pedestal",
          annulus(0.0, 20.0, 20.0, 64, 4) + cylinder_side(20.0, 0.0, 20.0, 64, 2) + annulus(0.0, 20.0, 0.0, 64, 1))

# discharge: a flat-bottomed cylinder, inner diameter 30 mm, 40 mm tall, with a centred orifice of
# diameter 10 mm in its floor (z = 0); a square shutter 1.5 mm under the floor closes the orifice
# until it slides away along +x.
write_stl("silo.stl", "silo", annulus(5.0, 15.0, 0.0, 64, 3) + cylinder_side(15.0, 0.0, 40.0, 64, 4))
write_stl("shutter.stl", "shutter", rectangle((-9.0, -9.0, -1.5), (18.0, 0.0, 0.0), (0.0, 18.0, 0.0), 6, 6))

# torque: a bowl (inner diameter 50 mm, 30 mm tall, closed floor at z = 0) and a flat two-blade
# paddle through the z axis, 40 mm tip to tip, from z = 2 mm to z = 14 mm.
write_stl("bowl.stl", "bowl", annulus(0.0, 25.0, 0.0, 64, 3) + cylinder_side(25.0, 0.0, 30.0, 64, 3))
write_stl("paddle.stl", "paddle", rectangle((-20.0, 0.0, 2.0), (40.0, 0.0, 0.0), (0.0, 0.0, 12.0), 16, 6))
