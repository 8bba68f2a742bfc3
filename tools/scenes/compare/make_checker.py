"""Writes checker.ply for activation_map.json: the vertices of shape:square (a 33 x 33 grid on the
unit square, row by row, as common/mesh/shapes.cpp builds it) with a per-vertex property "checker" that
alternates 0 / 1 between neighbouring grid vertices. A parameter map that changes at every vertex
makes reading it at the face centroid (the planted fault map-at-centroid) differ from interpolating
it at the agent's position in every face, not only along a few region borders.

Run: python3 tools/scenes/compare/make_checker.py (no dependencies); the output is committed.
"""
import os
import struct

N = 33
vertices = [(i / (N - 1), j / (N - 1), (i + j) % 2) for j in range(N) for i in range(N)]
header = (
    "ply\nformat binary_little_endian 1.0\ncomment physarum: tools/scenes/compare/make_checker.py\n"
    f"element vertex {len(vertices)}\nproperty float x\nproperty float y\nproperty float z\n"
    "property float checker\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
)
path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "checker.ply")
with open(path, "wb") as f:
    f.write(header.encode("ascii"))
    for x, y, c in vertices:
        f.write(struct.pack("<ffff", x, y, 0.0, float(c)))
print("wrote", path)
