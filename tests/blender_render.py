# Renders a run's result.glb or fields_full.ply headless in Blender the way preview.png is drawn
# (common/output/preview_image.cpp), so tests/compare_render.py can check that the file shows the
# same picture:
#   blender -b --factory-startup --python tests/blender_render.py -- MODEL OUT_PNG SIZE
# MODEL is .glb/.gltf or .ply; SIZE is WIDTHxHEIGHT (preview.png is 800x600) or N for N x N.
# Exits 1 with a message on any failure: without that, Blender's --python swallows the exception and
# exits 0.
import math
import os
import sys

import numpy

# Blender 3.4's glTF importer uses numpy.bool, removed in numpy 1.24 (Debian 12). vars() rather than
# hasattr(): numpy's module __getattr__ warns on the lookup.
if "bool" not in vars(numpy):
    numpy.bool = bool

import bpy
from mathutils import Matrix, Vector

# preview_view() in common/output/camera_views.cpp and the margin of render_shaded().
AZIMUTH_DEG, ELEVATION_DEG, MARGIN = 35.0, 25.0, 0.9


def fail(message):
    print("blender_render.py: error: " + message, file=sys.stderr)
    sys.exit(1)


def to_blender(v):
    # The preview works in the file's y-up axes; Blender is z-up and the glTF importer maps
    # (x, y, z) -> (x, -z, y). PLY meshes are rotated the same way below.
    return Vector((v[0], -v[2], v[1]))


def import_model(path):
    before = set(bpy.data.objects)
    if path.lower().endswith((".glb", ".gltf")):
        result = bpy.ops.import_scene.gltf(filepath=path)
    elif path.lower().endswith(".ply"):
        result = bpy.ops.import_mesh.ply(filepath=path)
    else:
        fail(path + ": not a .glb, .gltf or .ply file")
    meshes = [o for o in set(bpy.data.objects) - before if o.type == "MESH"]
    if result != {"FINISHED"} or not meshes:
        fail(path + ": import gave no mesh")
    if path.lower().endswith(".ply"):
        for o in meshes:
            o.matrix_world = Matrix.Rotation(math.pi / 2, 4, "X") @ o.matrix_world
    return meshes


def camera_axes():
    # As render_shaded(): toward_camera, right = y x toward, up = toward x right, and the light.
    az, el = math.radians(AZIMUTH_DEG), math.radians(ELEVATION_DEG)
    toward = Vector((math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az)))
    right = Vector((0, 1, 0)).cross(toward).normalized()
    up = toward.cross(right)
    light = (toward + 0.6 * up - 0.4 * right).normalized()
    return to_blender(toward), to_blender(right), to_blender(up), to_blender(light)


def srgb_colour_source(obj, tree):
    # A node giving the surface colour as sRGB numbers, interpolated as the preview does (the preview
    # interpolates before its sRGB colour map; Blender would interpolate colours in linear RGB, which
    # widens bright bands along every triangle edge). The baked texture of a textured glb, read as
    # Non-Color so its sRGB texels are not decoded, else the mesh's colour attribute (glb COLOR_0,
    # PLY red/green/blue) copied to a float attribute as its sRGB values.
    textures = [n for m in obj.data.materials if m and m.use_nodes for n in m.node_tree.nodes if n.type == "TEX_IMAGE" and n.image]
    if textures:
        texture = tree.nodes.new("ShaderNodeTexImage")
        texture.image, texture.interpolation, texture.extension = textures[0].image, textures[0].interpolation, textures[0].extension
        texture.image.colorspace_settings.name = "Non-Color"
        return texture.outputs["Color"]
    mesh = obj.data
    if not mesh.color_attributes:
        fail(obj.name + ": the mesh has neither a texture nor vertex colours")
    colours = mesh.color_attributes[0]
    values = numpy.empty(4 * len(colours.data), dtype=numpy.float32)
    colours.data.foreach_get("color_srgb", values)
    srgb = mesh.color_attributes.new("srgb", "FLOAT_COLOR", colours.domain)
    srgb.data.foreach_set("color", values)  # a float attribute stores and interpolates its numbers as given
    attribute = tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "srgb"
    return attribute.outputs["Color"]


def preview_material(obj, light):
    # Emission only: the preview's sRGB colour times its shade 0.3 + 0.7 |n . light| (two-sided
    # Lambert plus ambient, smooth normals), decoded to the linear RGB Blender renders in; the
    # "Standard" view transform encodes it back, so the bytes come out as the preview computes them.
    obj.data.polygons.foreach_set("use_smooth", [True] * len(obj.data.polygons))
    material = bpy.data.materials.new("preview")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    new, link = tree.nodes.new, tree.links.new
    colour = srgb_colour_source(obj, tree)
    normal_dot = new("ShaderNodeVectorMath")
    normal_dot.operation = "DOT_PRODUCT"
    link(new("ShaderNodeNewGeometry").outputs["Normal"], normal_dot.inputs[0])
    normal_dot.inputs[1].default_value = light
    absolute = new("ShaderNodeMath")
    absolute.operation = "ABSOLUTE"
    link(normal_dot.outputs["Value"], absolute.inputs[0])
    shade = new("ShaderNodeMath")
    shade.operation = "MULTIPLY_ADD"
    link(absolute.outputs[0], shade.inputs[0])
    shade.inputs[1].default_value, shade.inputs[2].default_value = 0.7, 0.3
    shaded = new("ShaderNodeVectorMath")
    shaded.operation = "SCALE"
    link(colour, shaded.inputs[0])
    link(shade.outputs[0], shaded.inputs["Scale"])
    # sRGB to linear: ((c + 0.055) / 1.055)^2.4, the standard curve without its linear toe below
    # c = 0.04045 (at most 3 of 255 too bright at black).
    offset = new("ShaderNodeVectorMath")
    offset.operation = "MULTIPLY_ADD"
    link(shaded.outputs[0], offset.inputs[0])
    offset.inputs[1].default_value, offset.inputs[2].default_value = (1 / 1.055,) * 3, (0.055 / 1.055,) * 3
    decode = new("ShaderNodeGamma")
    link(offset.outputs[0], decode.inputs["Color"])
    decode.inputs["Gamma"].default_value = 2.4
    emission = new("ShaderNodeEmission")
    link(decode.outputs["Color"], emission.inputs["Color"])
    link(emission.outputs["Emission"], new("ShaderNodeOutputMaterial").inputs["Surface"])
    obj.data.materials.clear()
    obj.data.materials.append(material)


def add_camera(meshes, toward, right, up, width, height):
    # Orthographic, fitted like render_shaded(): the projected bounding box, centred, scaled to fill
    # MARGIN of the image along its tighter axis. Blender's ortho_scale spans the longer image side.
    points = [o.matrix_world @ v.co for o in meshes for v in o.data.vertices]
    xs, ys, zs = ([p.dot(axis) for p in points] for axis in (right, up, toward))
    extent_x, extent_y = max(max(xs) - min(xs), 1e-30), max(max(ys) - min(ys), 1e-30)
    pixels_per_unit = min(MARGIN * width / extent_x, MARGIN * height / extent_y)
    depth = max(zs) - min(zs)
    camera = bpy.data.cameras.new("preview")
    camera.type = "ORTHO"
    camera.ortho_scale = max(width, height) / pixels_per_unit
    camera.clip_start, camera.clip_end = 1e-3 * depth, 3 * depth + 1
    obj = bpy.data.objects.new("preview", camera)
    centre = 0.5 * (max(xs) + min(xs)) * right + 0.5 * (max(ys) + min(ys)) * up
    obj.matrix_world = Matrix.Translation(centre + (max(zs) + depth + 1) * toward) @ Matrix(
        (right, up, toward)).transposed().to_4x4()  # camera looks down its -z: the columns are right, up, toward
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj


def setup_render(width, height, out_png):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"  # Eevee and Workbench need OpenGL, which a headless machine lacks
    scene.cycles.device = "CPU"
    # Emission only, one sample at the pixel centre (tiny filter): the preview point-samples without
    # anti-aliasing, and nothing here is noisy.
    scene.cycles.samples, scene.cycles.max_bounces, scene.cycles.filter_width = 1, 0, 0.01
    scene.cycles.use_denoising = False  # on by default, and Debian's Blender is built without OIDN
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = width, height, 100
    # "Standard" with no look/exposure: linear colours go back to the same sRGB bytes (the default,
    # Filmic, would wash them out). No dither noise in the 8-bit output.
    scene.view_settings.view_transform, scene.view_settings.look = "Standard", "None"
    scene.view_settings.exposure, scene.view_settings.gamma = 0.0, 1.0
    scene.render.dither_intensity = 0.0
    world = bpy.data.worlds.new("white")  # the preview's white background
    world.color = (1.0, 1.0, 1.0)
    scene.world = world
    scene.render.image_settings.file_format, scene.render.image_settings.color_mode = "PNG", "RGB"
    scene.render.image_settings.color_depth = "8"
    scene.render.filepath, scene.render.use_file_extension = out_png, False


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 3:
        fail("usage: blender -b --factory-startup --python tests/blender_render.py -- MODEL OUT_PNG SIZE")
    model, out_png, size = argv
    try:
        width, height = (int(s) for s in (size.split("x") if "x" in size else (size, size)))
    except ValueError:
        fail("SIZE " + size + " is not N or WIDTHxHEIGHT")
    if not (1 <= width <= 16384 and 1 <= height <= 16384):
        fail("SIZE " + size + " is out of range (1..16384 each)")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    meshes = import_model(model)
    toward, right, up, light = camera_axes()
    for obj in meshes:
        preview_material(obj, light)
    add_camera(meshes, toward, right, up, width, height)
    setup_render(width, height, out_png)
    if os.path.exists(out_png):
        os.remove(out_png)  # so a render that writes nothing cannot pass on an old picture
    bpy.ops.render.render(write_still=True)
    if not os.path.isfile(out_png):
        fail(out_png + ": the render wrote no picture")


try:
    main()
except SystemExit:
    raise
except Exception as error:  # an importer or render error: report it and exit non-zero
    fail(type(error).__name__ + ": " + str(error))
