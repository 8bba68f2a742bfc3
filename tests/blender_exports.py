#!/usr/bin/env python3
"""result.glb keeps the run's detail where users look: Blender (Debian 12's 3.4, headless) imports a
run's result.glb and fields_full.ply, renders each as preview.png is drawn (tests/blender_render.py),
and the renders are compared with preview.png (tests/compare_render.py: mean absolute sRGB difference
over the mesh's pixels, at most 1.5 x the fields_full.ply render's distance + 1 and at most 8).

    blender_exports.py PHYSARUM_EXE WORK_DIR SHARED_MESHES

Runs: the default scene (a sphere, no UVs: result.glb is the full-resolution mesh) and, when the
shared meshes are there, spot (UVs: result.glb is the input mesh with the baked texture). The power
check: on the sphere, the input mesh's own vertex colours (pheromone.ply, what result.glb carried
before) must FAIL the same comparison; WORK_DIR/sphere_side_by_side.png shows preview.png, the render
of result.glb and that of the input mesh's colours in a row. Exits 1 with a message per failure.
"""
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[1]


def run(*args):
    result = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def render(model: Path, png: Path):
    code, out = run("blender", "-b", "--factory-startup", "--python", SOURCE / "tests" / "blender_render.py", "--",
                    model, png, "800x600")
    if code != 0 or not png.is_file():
        raise SystemExit(f"blender_exports: rendering {model} failed ({code}):\n{out[-3000:]}")


def compare(run_dir: Path, render_png: Path, reference_png: Path):
    code, out = run(sys.executable, SOURCE / "tests" / "compare_render.py", run_dir / "preview.png", render_png,
                    "--reference", reference_png, "--max", "8")
    if code not in (0, 1):
        raise SystemExit(f"blender_exports: compare_render.py failed ({code}):\n{out}")
    print(f"{run_dir.name}: {render_png.name}: {out.strip().splitlines()[0]}")
    return code == 0, out


def side_by_side(preview: Path, renders: list, out: Path):
    """preview.png and the renders in a row, half size: what to look at when the comparison fails (and
    the gallery's picture of result.glb in Blender)."""
    from PIL import Image
    pictures = [Image.open(p).convert("RGB") for p in [preview, *renders]]
    width, height = pictures[0].width // 2, pictures[0].height // 2
    row = Image.new("RGB", (width * len(pictures), height), "white")
    for k, picture in enumerate(pictures):
        row.paste(picture.resize((width, height), Image.LANCZOS), (k * width, 0))
    row.save(out)


def main(argv):
    if len(argv) != 4:
        raise SystemExit(__doc__)
    exe, work, meshes = Path(argv[1]), Path(argv[2]), Path(argv[3])
    if shutil.which("blender") is None:
        raise SystemExit("blender_exports: no `blender` on PATH: run `bash tools/setup.sh --tests` (it installs "
                         "Debian's blender and python3-numpy)")
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    scenes = {"sphere": SOURCE / "tools" / "scenes" / "default.json"}
    if (meshes / "spot.obj").exists():
        scenes["spot"] = SOURCE / "tools" / "scenes" / "spot.json"
    else:
        print(f"blender_exports: {meshes}/spot.obj absent: the mesh with UVs is not checked")
    failures = []
    for name, scene in scenes.items():
        run_dir = work / name
        code, out = run(exe, "run", scene, "--backend", "reference", "--out", run_dir)
        if code != 0:
            raise SystemExit(f"blender_exports: physarum run {scene} failed:\n{out}")
        render(run_dir / "fields_full.ply", work / f"{name}_full.png")
        render(run_dir / "result.glb", work / f"{name}_glb.png")
        close, out = compare(run_dir, work / f"{name}_glb.png", work / f"{name}_full.png")
        if not close:
            failures.append(f"{name}: result.glb in Blender is not the preview's picture: {out.strip()}")
        if name == "sphere":  # the check's power: the input vertices' colours alone must be refused
            render(run_dir / "pheromone.ply", work / "sphere_coarse.png")
            passed, out = compare(run_dir, work / "sphere_coarse.png", work / "sphere_full.png")
            if passed:
                failures.append(f"sphere: the input mesh's vertex colours passed the comparison: it cannot tell: {out}")
            side_by_side(run_dir / "preview.png", [work / "sphere_glb.png", work / "sphere_coarse.png"],
                         work / "sphere_side_by_side.png")
    for failure in failures:
        print("FAILED: " + failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
