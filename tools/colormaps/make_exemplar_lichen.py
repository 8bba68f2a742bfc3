#!/usr/bin/env python3
"""Synthesises exemplar_lichen.png: crustose lichen rosettes (in the manner of Xanthoria parietina:
an orange centre, ochre-yellow body, a pale sage-green growing margin) on grey-brown bark with
vertical furrows and grain. A stand-in for a photograph, made here so the repository ships no
third-party picture; `physarum colormap exemplar_lichen.png --out lichen_from_exemplar.json`
extracts the map beside it. Standard library only; fixed seed, so the file is reproducible."""
import math
import random
import struct
import sys
import zlib

WIDTH, HEIGHT = 192, 192
rng = random.Random(7)


def lattice_noise(seed, cell):
    """Smooth value noise in [0, 1]: random values on a lattice of `cell` pixels, smoothstep-blended."""
    r = random.Random(seed)
    nx, ny = WIDTH // cell + 2, HEIGHT // cell + 2
    grid = [[r.random() for _ in range(nx)] for _ in range(ny)]

    def at(x, y):
        gx, gy = x / cell, y / cell
        ix, iy = int(gx), int(gy)
        fx, fy = gx - ix, gy - iy
        sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)
        top = grid[iy][ix] * (1 - sx) + grid[iy][ix + 1] * sx
        bottom = grid[iy + 1][ix] * (1 - sx) + grid[iy + 1][ix + 1] * sx
        return top * (1 - sy) + bottom * sy
    return at


def mix(a, b, f):
    return tuple(a[c] + (b[c] - a[c]) * f for c in range(3))


# Bark: grey-brown, darker in the furrows, with fine grain.
BARK_LIGHT, BARK_DARK = (142, 136, 124), (88, 82, 74)
# Lichen, from the growing margin to the oldest centre.
MARGIN, BODY, CENTRE = (172, 184, 140), (222, 178, 48), (212, 104, 24)

furrows = lattice_noise(11, 24)
grain = lattice_noise(12, 3)
lobes = lattice_noise(13, 6)

rosettes = []
for _ in range(14):
    rosettes.append((rng.uniform(10, WIDTH - 10), rng.uniform(10, HEIGHT - 10), rng.uniform(12, 30),
                     rng.uniform(0, 2 * math.pi), rng.randint(5, 9)))

rows = []
for y in range(HEIGHT):
    row = bytearray()
    for x in range(WIDTH):
        # Furrows run vertically: stretch the noise along y.
        furrow = furrows(x, y / 5.0)
        bark = mix(BARK_DARK, BARK_LIGHT, min(1.0, max(0.0, 1.4 * furrow - 0.1)))
        g = (grain(x, y) - 0.5) * 18
        colour = tuple(c + g for c in bark)
        # The strongest rosette here: depth = 1 at its centre, 0 at its lobed edge.
        depth = 0.0
        for cx, cy, radius, phase, k in rosettes:
            dx, dy = x - cx, y - cy
            angle = math.atan2(dy, dx)
            edge = radius * (1 + 0.18 * math.sin(k * angle + phase) + 0.25 * (lobes(x, y) - 0.5))
            depth = max(depth, 1 - math.hypot(dx, dy) / edge)
        if depth > 0:
            lichen = mix(MARGIN, BODY, depth / 0.45) if depth < 0.45 else mix(BODY, CENTRE, (depth - 0.45) / 0.55)
            lichen = tuple(c + (grain(y, x) - 0.5) * 10 for c in lichen)
            colour = mix(colour, lichen, min(1.0, depth * 12))  # a soft, one-pixel edge
        row += bytes(int(min(255, max(0, round(c)))) for c in colour)
    rows.append(row)


def png(width, height, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


out = sys.argv[1] if len(sys.argv) > 1 else "exemplar_lichen.png"
with open(out, "wb") as f:
    f.write(png(WIDTH, HEIGHT, rows))
