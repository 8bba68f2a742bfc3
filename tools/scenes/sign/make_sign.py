"""Builds the assets of the slime-mold sign scene (tools/scenes/sign.json, after Fig. 7 of the paper):

  sign.obj        a 2 x 1 rectangle (input units), 80 x 40 cells split into triangles, with UVs
                  covering the image (u = x / 2, v = y);
  sign.png        1024 x 512, red = the text (the read-stimulus), green = dots along the border
                  (the write-stimulus), blue unused;
  sign_along.ply  the same mesh with a per-face direction along the nearest side of the rectangle
                  (face properties along_x, along_y, along_z): the bias that elongates the pattern
                  around the border.

Run with the project's venv (Pillow): .venv/bin/python tools/scenes/sign/make_sign.py
The outputs are committed; the script says how they were made.
"""
import os
import struct

from PIL import Image, ImageDraw, ImageFilter, ImageFont

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH, HEIGHT = 2.0, 1.0      # the rectangle, input units
NX, NY = 80, 40               # grid cells
IMAGE = (1024, 512)           # pixels; u = x / WIDTH, v = y / HEIGHT
TEXT = "PHYSARUM"
BORDER = 0.12                 # the dots lie on a line this far inside the edge
DOT_SPACING, DOT_RADIUS = 0.16, 0.025


def grid():
    vertices = [(WIDTH * i / NX, HEIGHT * j / NY) for j in range(NY + 1) for i in range(NX + 1)]
    faces = []
    for j in range(NY):
        for i in range(NX):
            a = j * (NX + 1) + i
            b, c, d = a + 1, a + NX + 2, a + NX + 1
            # Alternating diagonals, so the grid has no preferred direction.
            faces += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    return vertices, faces


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        f.write("# physarum sign: tools/scenes/sign/make_sign.py\n")
        for x, y in vertices:
            f.write(f"v {x:.6f} {y:.6f} 0\n")
        for x, y in vertices:
            f.write(f"vt {x / WIDTH:.6f} {y / HEIGHT:.6f}\n")
        for a, b, c in faces:
            f.write(f"f {a + 1}/{a + 1} {b + 1}/{b + 1} {c + 1}/{c + 1}\n")


def along_border(x, y):
    """Unit direction along the side of the rectangle nearest to (x, y)."""
    to_side = min(y, HEIGHT - y)
    to_end = min(x, WIDTH - x)
    return (1.0, 0.0, 0.0) if to_side < to_end else (0.0, 1.0, 0.0)


def write_ply(path, vertices, faces):
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment physarum sign: tools/scenes/sign/make_sign.py\n"
        f"element vertex {len(vertices)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
        "property float along_x\nproperty float along_y\nproperty float along_z\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        for x, y in vertices:
            f.write(struct.pack("<fff", x, y, 0.0))
        for a, b, c in faces:
            cx = (vertices[a][0] + vertices[b][0] + vertices[c][0]) / 3
            cy = (vertices[a][1] + vertices[b][1] + vertices[c][1]) / 3
            f.write(struct.pack("<Biii", 3, a, b, c))
            f.write(struct.pack("<fff", *along_border(cx, cy)))


def to_pixel(x, y):
    return x / WIDTH * IMAGE[0], (1.0 - y / HEIGHT) * IMAGE[1]  # image rows top first, v = 0 at the bottom


def dot_centres():
    left, right, bottom, top = BORDER, WIDTH - BORDER, BORDER, HEIGHT - BORDER
    perimeter = 2 * (right - left) + 2 * (top - bottom)
    count = int(round(perimeter / DOT_SPACING))
    for k in range(count):
        s = perimeter * k / count
        for length, start, step in (
            (right - left, (left, bottom), (1, 0)),
            (top - bottom, (right, bottom), (0, 1)),
            (right - left, (right, top), (-1, 0)),
            (top - bottom, (left, top), (0, -1)),
        ):
            if s < length:
                yield start[0] + step[0] * s, start[1] + step[1] * s
                break
            s -= length


def write_png(path):
    red = Image.new("L", IMAGE, 0)
    draw = ImageDraw.Draw(red)
    font = ImageFont.load_default(size=190)
    box = draw.textbbox((0, 0), TEXT, font=font, stroke_width=10)
    draw.text(((IMAGE[0] - (box[2] - box[0])) / 2 - box[0], (IMAGE[1] - (box[3] - box[1])) / 2 - box[1]), TEXT,
              fill=255, font=font, stroke_width=10, stroke_fill=255)
    # Soft edges: a sensor is steered by differences, and a ramp a few centimetres wide reaches
    # agents before they cross a stroke.
    red = red.filter(ImageFilter.GaussianBlur(6))
    green = Image.new("L", IMAGE, 0)
    draw = ImageDraw.Draw(green)
    r = DOT_RADIUS / WIDTH * IMAGE[0]
    for x, y in dot_centres():
        px, py = to_pixel(x, y)
        draw.ellipse((px - r, py - r, px + r, py + r), fill=255)
    Image.merge("RGB", (red, green, Image.new("L", IMAGE, 0))).save(path)


if __name__ == "__main__":
    vertices, faces = grid()
    write_obj(os.path.join(HERE, "sign.obj"), vertices, faces)
    write_ply(os.path.join(HERE, "sign_along.ply"), vertices, faces)
    write_png(os.path.join(HERE, "sign.png"))
    print("wrote sign.obj, sign_along.ply, sign.png in", HERE)
