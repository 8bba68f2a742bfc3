#!/usr/bin/env python3
"""Writes saddle.obj: a square patch of the saddle z = 0.6 (x^2 - y^2) over [-1, 1]^2 (one boundary
loop with four corners, negative curvature everywhere) on a grid whose lines are spaced
geometrically from one corner, so its triangles grow more than a hundredfold across the patch. Like
horn.obj it stands in for the unequal meshes users bring, here with corners and a saddle instead of a
surface of revolution. Run: python3 make_saddle.py > saddle.obj (deterministic)."""

LINES = 34     # grid lines per direction
GROWTH = 1.1   # ratio of consecutive spacings


def graded(n, growth):
    """n values from -1 to 1, spacings growing geometrically."""
    steps = [growth ** k for k in range(n - 1)]
    total = sum(steps)
    values, t = [-1.0], -1.0
    for s in steps:
        t += 2.0 * s / total
        values.append(t)
    values[-1] = 1.0
    return values


def main():
    xs = graded(LINES, GROWTH)
    print("# saddle.obj: written by make_saddle.py (saddle patch, geometrically graded grid)")
    for y in xs:
        for x in xs:
            print(f"v {x:.6f} {y:.6f} {0.6 * (x * x - y * y):.6f}")
    for j in range(LINES - 1):
        for i in range(LINES - 1):
            a = j * LINES + i + 1
            b, c, d = a + 1, a + LINES, a + LINES + 1
            if (i + j) % 2 == 0:  # alternate diagonals: no grain along one direction
                print(f"f {a} {b} {d}")
                print(f"f {a} {d} {c}")
            else:
                print(f"f {a} {b} {c}")
                print(f"f {b} {d} {c}")


if __name__ == "__main__":
    main()
