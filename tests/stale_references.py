"""No comment or document names a file, folder or function that is not there (ctest's `stale_references`).

Reads every file git tracks (and new ones it does not ignore) that holds prose: the comments of
C++, OpenCL, Python, shell and CMake files, and the whole of Markdown files. In them:
  * a repository path (a word with a slash whose first part is a top-level folder, `tools/run/`,
    `common/harness/comparison_metrics.hpp`, or a relative Markdown link such as `../api/x.hpp`) must
    exist; a path without an extension names a file pair (`api/session` for .hpp/.cpp), and a last
    part ending in `_` a family of files (`tests/test_cli_`);
  * a function named with parentheses (`name()`, `Class::name()`) must be defined or called
    somewhere in the code (not only in comments).
Placeholders in capitals (`tools/scenes/SCENE.json`, `common/LAYER/`), globs and paths under
out/ or ../shared (the meshes beside a checkout) are not names of the repository's files. NOT_NAMES lists the few words the check would take for
names of ours, each with the reason.

    python stale_references.py REPOSITORY            (exit 1 and the list when something is stale)
"""
import builtins
import pathlib
import re
import subprocess
import sys

PROSE = {".cpp", ".hpp", ".h", ".cl", ".py", ".cmake", ".sh", ".md", ".in", ".toml"}
C_LIKE = {".cpp", ".hpp", ".h", ".cl"}
C_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
HASH_COMMENT = re.compile(r"#[^\n]*")
PATH = re.compile(r"(?<![\w./-])((?:\.\./)*(?:[\w.+-]+/)+[\w.+-]*)")
CALLED = re.compile(r"`?\b([A-Za-z_][\w:]*)\(\)")
NOT_NAMES = {
    "show": "polyscope's ps.show() in docs/python.md",
    "N": "Python's statistics.NormalDist imported as N, in a comment's one-line check",
}


def tracked_files(root):
    listed = subprocess.run(["git", "-C", str(root), "ls-files", "--cached", "--others", "--exclude-standard"],
                            capture_output=True, text=True, check=True).stdout.split("\n")
    return [f for f in listed if f and (pathlib.Path(f).suffix in PROSE or pathlib.Path(f).name == "CMakeLists.txt")
            and (root / f).is_file()]


def split(name, text):
    """(prose, code) of a file: its comments and the rest (Markdown is all prose)."""
    suffix = pathlib.Path(name).suffix
    if suffix == ".md":
        return text, ""
    pattern = C_COMMENT if suffix in C_LIKE else HASH_COMMENT
    return "\n".join(pattern.findall(text)), pattern.sub(" ", text)


def names_a_file(root, source, path, top_folders):
    """Whether `path` (as written in `source`) is a file or folder of the repository; None when it is
    not a repository path at all."""
    path = path.rstrip(".,;:)'\"`")
    parts = [p for p in path.split("/") if p]
    if not parts or any(ch in path for ch in "*<>{}…$%") or "..." in path.replace("../", ""):
        return None
    if any(p.isupper() or re.fullmatch(r"[A-Z][A-Z_]+(\.\w+)?", p) for p in parts):
        return None  # a placeholder: SCENE.json, LAYER, MODEL.csv
    if path.lstrip("./").startswith("shared"):
        return None  # the workplace's ../shared/meshes beside the checkout, not the repository's
    if path.startswith("../"):
        target = ((root / source).parent / path).resolve()
        if not str(target).startswith(str(root)) or "/out/" in str(target):
            return None
    elif parts[0] in top_folders:
        target = root / path
    else:
        return None
    if target.exists():
        return True
    if list(target.parent.glob(target.name + ".*")):
        return True  # a file pair without its extension
    return path.endswith("_") and bool(list(target.parent.glob(target.name + "*")))


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    files = tracked_files(root)
    top_folders = {f.split("/")[0] for f in files if "/" in f} - {"out", "build"}
    texts = {f: (root / f).read_text(errors="replace") for f in files}
    defined = set(dir(builtins))
    for f, text in texts.items():
        code = split(f, text)[1]
        defined |= set(re.findall(r"\b([A-Za-z_]\w*)\s*\(", code))
    stale = []
    for f, text in texts.items():
        prose = split(f, text)[0]
        for m in PATH.finditer(prose):
            if names_a_file(root, f, m.group(1), top_folders) is False:
                stale.append(f"{f}: the path {m.group(1)} is not in the repository")
        for m in CALLED.finditer(prose):
            name = m.group(1).split("::")[-1]
            if name not in defined and name not in NOT_NAMES:
                stale.append(f"{f}: {m.group(1)}() is defined nowhere in the code")
    for line in sorted(set(stale)):
        print(line)
    print(f"{len(files)} files read; {len(set(stale))} stale references")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
