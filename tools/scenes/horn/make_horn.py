#!/usr/bin/env python3
"""Writes horn.obj: an open surface of revolution (a flared horn, two boundary circles) whose rings
are spaced geometrically, so its triangles range from slivers a few millimetres long at the narrow
end to faces over a hundred times larger at the bell. It stands in for the meshes users bring from
CAD exports and scanners, whose faces are anything but equal: the harness's planted faults that
depend on face areas (respawn weighted by area) or on boundaries (reflection) have something to
act on. Run: python3 make_horn.py > horn.obj (deterministic)."""
import math

RINGS = 36          # rings of vertices along the axis
SEGMENTS = 40       # vertices around each ring
LENGTH = 1.0        # axis length
GROWTH = 1.11       # ratio of consecutive ring spacings


def radius(z):
    # narrow throat, flaring bell (z in 0..1)
    return 0.08 + 0.5 * z ** 3


def main():
    total = sum(GROWTH ** k for k in range(RINGS - 1))
    z, zs = 0.0, [0.0]
    for k in range(RINGS - 1):
        z += LENGTH * GROWTH ** k / total
        zs.append(z)
    print("# horn.obj: written by make_horn.py (flared horn, geometrically graded rings)")
    for k, z in enumerate(zs):
        r = radius(z / LENGTH)
        offset = 0.5 * (k % 2)  # stagger alternate rings: no long diagonals all leaning one way
        for s in range(SEGMENTS):
            a = 2.0 * math.pi * (s + offset) / SEGMENTS
            print(f"v {r * math.cos(a):.6f} {r * math.sin(a):.6f} {z:.6f}")
    for k in range(RINGS - 1):
        for s in range(SEGMENTS):
            a = k * SEGMENTS + s + 1
            b = k * SEGMENTS + (s + 1) % SEGMENTS + 1
            c = (k + 1) * SEGMENTS + s + 1
            d = (k + 1) * SEGMENTS + (s + 1) % SEGMENTS + 1
            if k % 2 == 0:
                print(f"f {a} {b} {c}")
                print(f"f {b} {d} {c}")
            else:
                print(f"f {a} {b} {d}")
                print(f"f {a} {d} {c}")


if __name__ == "__main__":
    main()
