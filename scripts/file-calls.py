#!/usr/bin/env python3
"""Calls between the files of each folder of the library and the program.

  scripts/file-calls.py BUILD_DIR            the calls, folder by folder
  scripts/file-calls.py BUILD_DIR --check    exit 1 when files of a folder call
                                             each other in a circle

Reads the object files of a build (nm: the functions each file defines and
the ones it uses), so it sees calls as the linker does, macros and all. Inside
a folder calls should go one way, as they do between the layers: a circle
(a -> b -> ... -> a) is two jobs mixed in the files, and the test
`files_call_one_way` fails on it."""
import glob
import os
import subprocess
import sys


def source_root(build):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            if line.startswith("CMAKE_HOME_DIRECTORY:"):
                return line.split("=", 1)[1].strip()
    return None


def objects(build):
    """{folder: [object files]} of the layers (vl_LAYER) and the program; an
    object whose source is gone (a file renamed since that build) is left out."""
    out = {}
    root = source_root(build)
    for d in sorted(glob.glob(os.path.join(build, "src", "CMakeFiles", "*.dir"))):
        name = os.path.basename(d)[:-4]
        if not (name.startswith("vl_") or name == "viscolube_cli"):
            continue
        files = [
            f
            for f in glob.glob(os.path.join(d, "*", "*.c.o"))
            if not root
            or os.path.exists(os.path.join(root, "src", os.path.relpath(f, d)[: -len(".o")]))
        ]
        if files:
            out[name[3:] if name.startswith("vl_") else "cli"] = sorted(files)
    return out


def symbols(path):
    defined, used = set(), set()
    text = subprocess.run(["nm", path], capture_output=True, text=True, check=True).stdout
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[1] in "TDBR":
            defined.add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            used.add(parts[1])
    return defined, used


def edges(files):
    owner, uses = {}, {}
    for f in files:
        name = os.path.basename(f)[:-4]
        defined, used = symbols(f)
        for s in defined:
            owner[s] = name
        uses[name] = used
    return {a: sorted({owner[s] for s in u if s in owner and owner[s] != a}) for a, u in uses.items()}


def circles(graph):
    """The strongly connected components of more than one file (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, []):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    found = objects(argv[1])
    if not found:
        print(f"file-calls: no object files under {argv[1]}/src/CMakeFiles")
        return 2
    bad = 0
    for folder, files in found.items():
        graph = edges(files)
        loops = circles(graph)
        bad += len(loops)
        if "--check" not in argv:
            print(f"{folder}:")
            for a in sorted(graph):
                if graph[a]:
                    print(f"  {a} -> {' '.join(graph[a])}")
        for c in loops:
            print(f"{folder}: files call each other in a circle: {' -> '.join(c)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
