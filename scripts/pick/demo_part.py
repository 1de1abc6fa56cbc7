#!/usr/bin/env python3
"""Writes the main job's part: a bracket of our own (binary STL, millimetres, centred on
its bounding box), so that scripts/run.sh needs no CAD model from outside the repository.

A base plate with a round boss at one end and a raised rib at the other: no rotation maps
it onto itself, so its pose has one answer. Usage: demo_part.py OUT.stl
"""
import struct
import sys

import numpy as np


def box(lo, hi):
    """The 12 outward, counter-clockwise triangles of an axis-aligned box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (3, 0, 4, 7)]
    return [v[[a, b, c]] for a, b, c, d in quads] + [v[[a, c, d]] for a, b, c, d in quads]


def cylinder(centre, radius, z0, z1, segments=48):
    """A closed cylinder along z, outward, counter-clockwise."""
    cx, cy = centre
    angles = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    ring = np.stack([cx + radius * np.cos(angles), cy + radius * np.sin(angles)], axis=1)
    triangles = []
    for i in range(segments):
        (ax, ay), (bx, by) = ring[i], ring[(i + 1) % segments]
        a0, b0, a1, b1 = [ax, ay, z0], [bx, by, z0], [ax, ay, z1], [bx, by, z1]
        triangles += [np.array([a0, b0, b1]), np.array([a0, b1, a1])]
        triangles += [np.array([[cx, cy, z1], a1, b1]), np.array([[cx, cy, z0], b0, a0])]
    return triangles


def bracket():
    triangles = box((-36, -22, 0), (36, 22, 12))           # the base plate
    triangles += cylinder((18, 0), 12, 12, 40)             # the boss
    triangles += box((-36, -22, 12), (-24, 22, 28))        # the rib
    triangles = np.array(triangles)
    lo, hi = triangles.reshape(-1, 3).min(0), triangles.reshape(-1, 3).max(0)
    return triangles - (lo + hi) / 2.0


def write_stl(path, triangles):
    with open(path, "wb") as out:
        out.write(b"FlexSight demo bracket".ljust(80, b" "))
        out.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            normal = np.cross(t[1] - t[0], t[2] - t[0])
            normal /= np.linalg.norm(normal)
            out.write(struct.pack("<12fH", *normal, *t.reshape(-1), 0))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: demo_part.py OUT.stl")
    write_stl(sys.argv[1], bracket())
