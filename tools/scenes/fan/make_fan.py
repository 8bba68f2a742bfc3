#!/usr/bin/env python3
"""Writes the fan-shaped open surfaces of the two map-tool scenes: a circular sector with its apex
(the stem of a sea fan, the petiole of a ginkgo leaf) at the origin, opening toward +y.

  sea_fan.obj  a 120 degree sector of radius 1, gently cupped (z = 0.15 r^2 (1 - 2 cos^2 of the
               angle from the axis)): a sea fan is a thin curved sheet, and the bias has to follow
               the surface, not the plane
  ginkgo.obj   a flat 150 degree sector whose margin has a shallow notch at the middle (the bilobed
               ginkgo leaf), radius 1 elsewhere
  petal.obj    a flower petal for the reaction-diffusion flower scene: a 70 degree sector with a
               rounded tip (radius 1 on the axis, falling off toward the sides as a cosine), cupped
               across (z = 0.25 r^2 sin^2 of the angle, scaled to the half-angle) and curled back
               along its length (z -= 0.1 r^2): the shipped meshes hold no petal, and the stripes
               have to follow a curved sheet from its base

Rings of vertices are spaced evenly in r and each ring gets a number of segments proportional to its
length, so the triangles are roughly equilateral everywhere, including at the apex (no slivers for
refinement to clean up). Run: python3 make_fan.py (deterministic; writes both files beside itself).
"""
import math
import os

RINGS = 24          # rings between the apex and the margin
SPACING = 1.0 / RINGS


def sector(half_angle, radius_of, height_of):
    """Vertices and triangles of the sector |angle from +y| <= half_angle, r <= radius_of(angle)."""
    vertices = [(0.0, 0.0, height_of(0.0, 0.0))]
    rings = [[0]]
    for k in range(1, RINGS + 1):
        s = k / RINGS
        arc = s * 2.0 * half_angle
        count = max(1, round(arc / SPACING)) + 1
        ring = []
        for i in range(count):
            a = -half_angle + 2.0 * half_angle * i / (count - 1)
            r = s * radius_of(a)
            x, y = r * math.sin(a), r * math.cos(a)
            ring.append(len(vertices))
            vertices.append((x, y, height_of(r, a)))
        rings.append(ring)
    faces = []
    for inner, outer in zip(rings, rings[1:]):
        # zipper the two open polylines: advance on whichever side lags in its 0..1 parameter
        i = j = 0
        ni, no = len(inner) - 1, len(outer) - 1
        while i < ni or j < no:
            ti = (i + 1) / ni if ni else 2.0
            to = (j + 1) / no if no else 2.0
            if j < no and (i >= ni or to <= ti):
                faces.append((inner[i], outer[j], outer[j + 1]))
                j += 1
            else:
                faces.append((inner[i], outer[j], inner[i + 1]))
                i += 1
    return vertices, faces


def write_obj(path, comment, vertices, faces):
    with open(path, "w") as out:
        out.write(f"# {comment} (written by make_fan.py)\n")
        for v in vertices:
            out.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for f in faces:
            # CCW seen from +z
            out.write("f {} {} {}\n".format(f[0] + 1, f[2] + 1, f[1] + 1))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    sea = sector(math.radians(60.0), lambda a: 1.0,
                 lambda r, a: 0.15 * r * r * (1.0 - 2.0 * math.cos(a) ** 2))
    write_obj(os.path.join(here, "sea_fan.obj"), "sea fan: cupped 120 degree sector, stem at the origin", *sea)
    notch = lambda a: 1.0 - 0.18 * math.exp(-(a / math.radians(6.0)) ** 2)
    ginkgo = sector(math.radians(75.0), notch, lambda r, a: 0.0)
    half = math.radians(35.0)
    petal = sector(half, lambda a: 0.55 + 0.45 * math.cos(0.5 * math.pi * a / half),
                   lambda r, a: 0.25 * r * r * math.sin(0.5 * math.pi * a / half) ** 2 - 0.1 * r * r)
    write_obj(os.path.join(here, "petal.obj"), "petal: cupped 70 degree sector with a rounded tip, base at the origin", *petal)
    write_obj(os.path.join(here, "ginkgo.obj"), "ginkgo leaf: flat 150 degree sector, notched margin, base at the origin", *ginkgo)


if __name__ == "__main__":
    main()
