"""No function of the engine's C++ runs past 100 lines (ctest's `function_length`): a reader should not
have to scroll through one. Tables (a list of rows written as code) are exempt, by name, in TABLES.
Functions are found by their braces at namespace level, with comments and string literals removed;
members defined inside a class body are not measured (they are short by the same rule in review).
The OpenCL kernels are not measured yet: agent_step.cl's agent_step and trace.cl's walk are longer
(the closing note of issue 55 says so).

    python function_length.py REPOSITORY
"""
import pathlib
import re
import sys

LIMIT = 100
TABLES = {
    "source_kinds": "common/maps/map_definition.cpp: one row per kind of map source",
    "build_keys": "common/scene/scene_keys.cpp: one row per scene key",
}
FOLDERS = ("api", "common", "opencl", "reference", "tools")


def strip(text):
    # remove comments and string/char literals, keep newlines
    out=[]; i=0; n=len(text)
    while i<n:
        c=text[i]
        if text.startswith('//',i):
            j=text.find('\n',i); j=n if j<0 else j; i=j; continue
        if text.startswith('/*',i):
            j=text.find('*/',i+2); seg=text[i:j+2]; out.append('\n'*seg.count('\n')); i=j+2; continue
        if text.startswith('R"',i):
            m=re.match(r'R"([^(]*)\(',text[i:]); d=m.group(1); j=text.find(')'+d+'"',i); seg=text[i:j]; out.append('""'+'\n'*seg.count('\n')); i=j+len(d)+2; continue
        if c in '"\'':
            j=i+1
            while j<n and text[j]!=c:
                j+= 2 if text[j]=='\\' else 1
            out.append(c+c); i=j+1; continue
        out.append(c); i+=1
    return ''.join(out)

def long_functions(root):
    found = []
    for folder in FOLDERS:
        for f in sorted((root / folder).glob("**/*.cpp")):
            text = strip(f.read_text())
            stack, line, last = [], 1, 0
            for i, ch in enumerate(text):
                if ch == "\n":
                    line += 1
                elif ch == "{":
                    head = text[last:i]
                    if re.search(r"\bnamespace\b[^;{}]*$", head) or re.search(r'extern\s+"[^"]*"\s*$', head):
                        kind = "namespace"
                    elif (re.search(r"\)\s*(const|noexcept|override|->[^{;]*|:[^;{}]*)?\s*$", head, re.S)
                          and all(k == "namespace" for k, _, _ in stack)):
                        kind = "function"
                    else:
                        kind = "other"
                    names = re.findall(r"([\w:~]+)\s*\(", head)
                    stack.append((kind, line, names[0] if names else "?"))
                    last = i + 1
                elif ch == "}":
                    if stack:
                        kind, start, name = stack.pop()
                        length = line - start + 1
                        if kind == "function" and length > LIMIT and name.split("::")[-1] not in TABLES:
                            found.append(f"{f.relative_to(root)}:{start}: {name} runs {length} lines")
                    last = i + 1
                elif ch == ";":
                    last = i + 1
    return found


def main():
    found = long_functions(pathlib.Path(sys.argv[1]))
    for line in found:
        print(line)
    print(f"{len(found)} functions over {LIMIT} lines")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
