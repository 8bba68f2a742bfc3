#!/usr/bin/env python3
"""Reads a finished `physarum run` folder with tools that are not physarum's own, as a user's
viewer or script would, and checks that the files say what the run wrote.

    read_exports.py RUN_DIR [RUN_DIR ...]

- result.glb, loaded twice: with trimesh (a widely used glTF loader) and with the small GLB parser
  below (the binary container and accessors read straight from the specification), which must agree.
  Its mesh is the PLY's that carries the run's detail: with a baked texture (a mesh with UVs) the
  input mesh's (pheromone.ply or morphogens.ply), its vertices in order followed by the copies made
  along UV seams (run.json's result_glb_vertices and result_glb_seam_splits); without, fields_full.ply's
  (every intrinsic vertex). Every triangle, position and value is that PLY's; COLOR_0 (or
  _FIELD_COLOR when a texture is embedded) is the PLY's sRGB colours converted to linear light by the
  sRGB transfer function; POSITION carries its min/max; normals are
  unit length; an embedded texture decodes (through Pillow) to texture.png's size when that exists.
- pheromone.ply (or morphogens.ply) and, when present, fields_full.ply, loaded with trimesh and with the PLY parser
  below: same vertex count as the header, same positions and vertex colours.

Exits 1 with one line per failed check; prints a summary ending in 'N passed, N failed'.
Run by ctest through tests/read_exports.cmake with the Python of tools/setup.sh's .venv.
"""
import json
import struct
import sys
from pathlib import Path

import numpy as np
import trimesh

COMPONENT_DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
TYPE_WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
PLY_DTYPES = {"char": "i1", "uchar": "u1", "short": "<i2", "ushort": "<u2", "int": "<i4", "uint": "<u4",
              "float": "<f4", "double": "<f8", "int8": "i1", "uint8": "u1", "int16": "<i2", "uint16": "<u2",
              "int32": "<i4", "uint32": "<u4", "float32": "<f4", "float64": "<f8"}


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = []

    def check(self, condition, what):
        if condition:
            self.passed += 1
        else:
            self.failed.append(what)
            print(f"FAILED: {what}", file=sys.stderr)
        return bool(condition)


def srgb_to_linear(c):
    """The sRGB decoding curve (IEC 61966-2-1) on values in [0, 1]."""
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def parse_glb(path):
    """GLB container (12-byte header, JSON chunk, BIN chunk) -> (gltf json, bin bytes)."""
    data = Path(path).read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length != len(data):
        raise ValueError(f"{path}: not a glTF 2.0 binary (magic {magic!r}, version {version}, length {length} of {len(data)})")
    json_length, json_type = struct.unpack_from("<I4s", data, 12)
    if json_type != b"JSON":
        raise ValueError(f"{path}: first chunk is {json_type!r}, not JSON")
    gltf = json.loads(data[20:20 + json_length])
    at = 20 + json_length
    binary = b""
    if at < len(data):
        bin_length, bin_type = struct.unpack_from("<I4s", data, at)
        if bin_type != b"BIN\x00":
            raise ValueError(f"{path}: second chunk is {bin_type!r}, not BIN")
        binary = data[at + 8:at + 8 + bin_length]
    return gltf, binary


def read_accessor(gltf, binary, index):
    accessor = gltf["accessors"][index]
    view = gltf["bufferViews"][accessor["bufferView"]]
    dtype = np.dtype(COMPONENT_DTYPES[accessor["componentType"]]).newbyteorder("<")
    width = TYPE_WIDTHS[accessor["type"]]
    stride = view.get("byteStride", 0)
    if stride not in (0, dtype.itemsize * width):
        raise ValueError(f"accessor {index}: interleaved data (stride {stride}) is not expected here")
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    values = np.frombuffer(binary, dtype=dtype, count=accessor["count"] * width, offset=start)
    return values.reshape(accessor["count"], width) if width > 1 else values


def parse_ply(path):
    """Binary little-endian PLY with scalar vertex properties and triangle faces -> (vertex record array, faces)."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    elements = []
    for line in data[:end].decode("ascii").splitlines():
        words = line.split()
        if words[:1] == ["format"] and words[1] != "binary_little_endian":
            raise ValueError(f"{path}: format {words[1]} is not the binary little-endian PLY physarum writes")
        if words[:1] == ["element"]:
            elements.append({"name": words[1], "count": int(words[2]), "properties": []})
        elif words[:1] == ["property"]:
            elements[-1]["properties"].append(words[1:])
    at = end
    vertices = faces = None
    for element in elements:
        if element["name"] == "vertex":
            dtype = np.dtype([(p[1], PLY_DTYPES[p[0]]) for p in element["properties"]])
            vertices = np.frombuffer(data, dtype=dtype, count=element["count"], offset=at)
            at += dtype.itemsize * element["count"]
        elif element["name"] == "face":
            (_, count_type, index_type, _) = element["properties"][0]
            dtype = np.dtype([("n", PLY_DTYPES[count_type]), ("v", PLY_DTYPES[index_type], (3,))])
            records = np.frombuffer(data, dtype=dtype, count=element["count"], offset=at)
            if element["count"] and not np.all(records["n"] == 3):
                raise ValueError(f"{path}: faces that are not triangles")
            faces = records["v"].astype(np.int64)
            at += dtype.itemsize * element["count"]
    if at != len(data):
        raise ValueError(f"{path}: {len(data) - at} bytes after the last element")
    return vertices, faces


def check_ply(checks, path):
    """trimesh and the parser above agree on vertices, colours and faces of a PLY with vertex colours."""
    vertices, faces = parse_ply(path)
    mesh = trimesh.load(path, process=False)
    name = path.name
    checks.check(len(mesh.vertices) == len(vertices), f"{name}: trimesh reads {len(mesh.vertices)} vertices, the header says {len(vertices)}")
    checks.check(len(mesh.faces) == len(faces), f"{name}: trimesh reads {len(mesh.faces)} faces, the header says {len(faces)}")
    xyz = np.column_stack([vertices["x"], vertices["y"], vertices["z"]])
    checks.check(np.array_equal(np.asarray(mesh.vertices, dtype=np.float32), xyz), f"{name}: positions differ")
    checks.check(np.array_equal(mesh.faces, faces), f"{name}: faces differ")
    if "red" in vertices.dtype.names:
        rgb = np.column_stack([vertices["red"], vertices["green"], vertices["blue"]])
        colors = mesh.visual.vertex_colors
        checks.check(colors is not None and np.array_equal(colors[:, :3], rgb), f"{name}: trimesh's vertex colours differ from the file's")
    return vertices, faces


def check_glb(checks, run_dir, ply_vertices, ply_faces, run):
    path = run_dir / "result.glb"
    gltf, binary = parse_glb(path)
    checks.check(gltf["asset"]["version"] == "2.0", "result.glb: asset.version is not 2.0")
    checks.check(len(gltf["meshes"]) == 1 and len(gltf["meshes"][0]["primitives"]) == 1, "result.glb: not one mesh with one primitive")
    primitive = gltf["meshes"][0]["primitives"][0]
    checks.check(primitive.get("mode", 4) == 4, "result.glb: primitive is not TRIANGLES")
    attributes = primitive["attributes"]
    textured = "baseColorTexture" in gltf["materials"][primitive["material"]]["pbrMetallicRoughness"]
    color_name = "_FIELD_COLOR" if textured else "COLOR_0"
    for required in ("POSITION", "NORMAL", color_name, "_PHEROMONE"):
        if not checks.check(required in attributes, f"result.glb: no {required} attribute"):
            return
    if textured:
        checks.check("COLOR_0" not in attributes, "result.glb: COLOR_0 beside a baseColorTexture (viewers would multiply them)")

    position = read_accessor(gltf, binary, attributes["POSITION"])
    normal = read_accessor(gltf, binary, attributes["NORMAL"])
    color = read_accessor(gltf, binary, attributes[color_name])
    value = read_accessor(gltf, binary, attributes["_PHEROMONE"])
    faces = read_accessor(gltf, binary, primitive["indices"]).reshape(-1, 3).astype(np.int64)
    color_accessor = gltf["accessors"][attributes[color_name]]
    checks.check(color_accessor["componentType"] == 5126 and color_accessor["type"] == "VEC3", f"result.glb: {color_name} is not float VEC3")
    checks.check(gltf["accessors"][primitive["indices"]]["componentType"] == 5125, "result.glb: indices are not uint32")
    position_accessor = gltf["accessors"][attributes["POSITION"]]
    checks.check(np.array_equal(np.asarray(position_accessor.get("min")), position.min(axis=0))
                 and np.array_equal(np.asarray(position_accessor.get("max")), position.max(axis=0)),
                 "result.glb: POSITION min/max missing or not the bounds of the data")
    checks.check(np.allclose(np.linalg.norm(normal, axis=1), 1.0, atol=1e-5), "result.glb: normals are not unit length")

    # Vertex count: the input's plus the seam copies that run.json reports.
    n = len(ply_vertices)
    expected = n + run["result_glb_seam_splits"]
    checks.check(run["result_glb_vertices"] == expected, f"run.json: result_glb_vertices {run['result_glb_vertices']} != {n} + seam splits")
    checks.check(len(position) == expected, f"result.glb: {len(position)} vertices, expected {n} PLY vertices + {run['result_glb_seam_splits']} seam splits")

    # trimesh, as a viewer loads it, sees the same arrays.
    scene = trimesh.load(path, process=False)
    geometries = list(scene.geometry.values()) if isinstance(scene, trimesh.Scene) else [scene]
    if checks.check(len(geometries) == 1, f"trimesh: {len(geometries)} geometries in result.glb"):
        mesh = geometries[0]
        checks.check(np.array_equal(np.asarray(mesh.vertices, dtype=np.float32), position), "trimesh: result.glb positions differ from the accessor's")
        checks.check(np.array_equal(mesh.faces, faces), "trimesh: result.glb faces differ from the indices accessor's")
        trimesh_value = mesh.vertex_attributes.get("_PHEROMONE")
        checks.check(trimesh_value is not None and np.array_equal(np.ravel(trimesh_value), value), "trimesh: _PHEROMONE missing or different")
        if textured:
            trimesh_color = mesh.vertex_attributes.get("_FIELD_COLOR")
        else:
            trimesh_color = getattr(mesh.visual, "vertex_attributes", {}).get("color")
        checks.check(trimesh_color is not None and np.array_equal(np.asarray(trimesh_color)[:, :3], color), f"trimesh: {color_name} missing or different")
        if textured:
            image = getattr(mesh.visual.material, "baseColorTexture", None)
            if checks.check(image is not None, "trimesh: no decodable baseColorTexture"):
                texture_png = run_dir / "texture.png"
                if texture_png.exists():
                    from PIL import Image
                    with Image.open(texture_png) as baked:
                        checks.check(image.size == baked.size, f"result.glb texture is {image.size}, texture.png {baked.size}")
                checks.check(image.size[0] > 0 and image.size[1] > 0, "result.glb: empty texture")

    # Each file vertex is an PLY vertex: the first n in order, the copies found by position and value.
    ply_xyz = np.column_stack([ply_vertices["x"], ply_vertices["y"], ply_vertices["z"]]).astype(np.float32)
    ply_value = ply_vertices[[p for p in ply_vertices.dtype.names if p not in ("x", "y", "z", "red", "green", "blue")][0]]
    source = np.arange(len(position))
    if len(position) >= n:
        by_key = {ply_xyz[v].tobytes() + ply_value[v].tobytes(): v for v in range(n)}
        for i in range(n, len(position)):
            source[i] = by_key.get(position[i].tobytes() + value[i].tobytes(), -1)
        checks.check(np.all(source >= 0), "result.glb: seam copies that are no PLY vertex")
        source = np.maximum(source, 0)
        checks.check(np.array_equal(position[:n], ply_xyz), "result.glb: first vertices are not the PLY's, in order")
        checks.check(np.array_equal(value, ply_value[source]), "result.glb: _PHEROMONE differs from the PLY's values")
        checks.check(len(faces) == len(ply_faces) and np.array_equal(source[faces], ply_faces), "result.glb: triangles differ from the PLY's")
        rgb = np.column_stack([ply_vertices["red"], ply_vertices["green"], ply_vertices["blue"]])[source]
        expected_linear = srgb_to_linear(rgb / 255.0)
        error = np.abs(color - expected_linear).max() if len(color) else 0.0
        checks.check(error < 1e-6, f"result.glb: {color_name} is not the PLY's colours in linear light (max error {error:.3g})")


def check_run(checks, run_dir):
    run_dir = Path(run_dir)
    run = json.loads((run_dir / "run.json").read_text())
    on_input = check_ply(checks, run_dir / run.get("fields_file", "pheromone.ply"))
    full = run_dir / "fields_full.ply"
    full_mesh = check_ply(checks, full) if full.exists() else None
    if full_mesh is None:
        print(f"read_exports: {full} absent, not checked")
    # result.glb is the input mesh where a baked texture carries the detail, else the full-resolution mesh.
    textured = "texture" in run
    checks.check(textured or full_mesh is not None, f"{run_dir}: no texture and no fields_full.ply for result.glb")
    check_glb(checks, run_dir, *(on_input if textured or full_mesh is None else full_mesh), run)


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    checks = Checks()
    for run_dir in argv[1:]:
        try:
            check_run(checks, run_dir)
        except Exception as error:  # an unreadable file is a failed check, reported with its cause
            checks.check(False, f"{run_dir}: {type(error).__name__}: {error}")
    print(f"read_exports: {checks.passed} passed, {len(checks.failed)} failed")
    return 1 if checks.failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
