#!/usr/bin/env python3
"""Writes an icosphere OBJ: a unit sphere centred at the origin, made by splitting every
triangle of an icosahedron into four `levels` times and pushing the new vertices onto the
sphere. No vertex normals, so kasumi computes them (angle-weighted) for Gouraud and Phong
shading. Faces wind counter-clockwise seen from outside.
Run: python3 data/meshes/make_icosphere.py 2 > data/meshes/icosphere2.obj
"""
import math
import sys


def icosphere(levels):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
                (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [normalize(p) for p in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
             (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
             (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
             (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        midpoints = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoints:
                pa, pb = vertices[a], vertices[b]
                vertices.append(normalize(tuple((x + y) / 2 for x, y in zip(pa, pb))))
                midpoints[key] = len(vertices) - 1
            return midpoints[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return vertices, faces


def normalize(p):
    length = math.sqrt(sum(c * c for c in p))
    return tuple(c / length for c in p)


def main():
    levels = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    vertices, faces = icosphere(levels)
    print(f"# icosphere, {levels} subdivision levels: {len(vertices)} vertices, "
          f"{len(faces)} triangles; unit radius; written by make_icosphere.py")
    for p in vertices:
        print("v %.7f %.7f %.7f" % p)
    for a, b, c in faces:
        print(f"f {a + 1} {b + 1} {c + 1}")


if __name__ == "__main__":
    main()
