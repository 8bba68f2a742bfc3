"""How far a render of a run's result.glb / fields_full.ply (tests/blender_render.py) is from its preview.png.

    compare_render.py PREVIEW_PNG RENDER_PNG [--max D] [--reference FULL_PNG]

Prints `distance D`: the mean absolute difference of the sRGB bytes (0..255, all three channels) over
the mesh's pixels, the union of both pictures' foreground (not the white background). A render of
the full-resolution mesh still differs along the edges of colour-map-saturated bands (a file carries
interpolated colours, the preview colours interpolated values), about 1-4.5 on the runs measured;
input-vertex colours add triangle-sized blotches, about 6-11. Also prints the silhouettes' overlap
(intersection over union): well below 1 means the camera, not the colours, differs.

--max D: exit 1 when the distance is above D (an absolute limit; 5 separated the runs measured, thinly).
--reference FULL_PNG: exit 1 when the distance is above 1.5 x FULL_PNG's distance + 1, where FULL_PNG
is a render of the same run's fields_full.ply: robust across patterns, since smooth patterns give
small distances for both files and sharp ones large distances for both.
Exit 2 on bad input.
"""
import argparse
import sys

import numpy as np
from PIL import Image

BACKGROUND_MIN = 250  # every channel at least this: the preview's white background
REFERENCE_RATIO, REFERENCE_SLACK = 1.5, 1.0  # full-resolution renders measured 1.0x, coarse ones 2.4x and more


def bad_input(message):
    print("compare_render.py: " + message, file=sys.stderr)
    sys.exit(2)  # not 1, which means "too far"


def load(path, size):
    try:
        image = Image.open(path).convert("RGB")
    except OSError as error:
        bad_input(f"{path}: {error}")
    # The preview fits the mesh to the tighter image axis, so only a picture of the same aspect has
    # the same framing; a different resolution is only resampled.
    if size and abs(image.width * size[1] - size[0] * image.height) > max(size):
        bad_input(f"{path}: aspect of {image.width}x{image.height} differs from the preview's {size[0]}x{size[1]}")
    return np.asarray(image.resize(size, Image.BILINEAR) if size else image, dtype=np.int16)


def distance(preview, render):
    mask_a, mask_b = (preview < BACKGROUND_MIN).any(axis=2), (render < BACKGROUND_MIN).any(axis=2)
    union = mask_a | mask_b
    if not union.any():
        bad_input("neither picture shows a mesh")
    return float(np.abs(preview - render)[union].mean()), float((mask_a & mask_b).sum() / union.sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("preview")
    parser.add_argument("render")
    parser.add_argument("--max", type=float, help="fail (exit 1) when the distance is above this")
    parser.add_argument("--reference", help="a render of fields_full.ply: fail when the distance is above 1.5 x its distance + 1")
    args = parser.parse_args()
    preview = load(args.preview, None)
    size = (preview.shape[1], preview.shape[0])
    found, overlap = distance(preview, load(args.render, size))
    print(f"distance {found:.2f} silhouette_iou {overlap:.4f}")
    limits = [args.max] if args.max is not None else []
    if args.reference:
        reference, _ = distance(preview, load(args.reference, size))
        print(f"reference_distance {reference:.2f}")
        limits.append(REFERENCE_RATIO * reference + REFERENCE_SLACK)
    if limits and found > min(limits):
        print(f"compare_render.py: distance {found:.2f} > {min(limits):.2f}: {args.render} does not show the "
              f"picture of {args.preview}", file=sys.stderr)
        sys.exit(1)


main()
