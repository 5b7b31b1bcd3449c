#!/usr/bin/env python3
"""Who calls each function of the public API (issue 30).

For every function declared in the public headers (include/viscolube/*.h,
the prototypes universal-ctags finds), lists the code that names it:

  cli        the program, src/cli
  python     the Python extension, python/src
  examples   the example programs, examples/ (the public API as a client
             program uses it)
  bench      the benchmark programs, bench/
  tests      tests/ (cmocka tests, oracles, fuzz targets, hard cases)
  lib:LAYER  the library itself, src/LAYER (another function than its own
             definition: a call, or its address taken)
  none       nobody

A public function is one a client calls: the CLI, Python or an example (and the few of
KEEP below, with the reason). Every other function belongs in a private
header of its layer (src/LAYER/*.h), which tests and the benchmarks reach
through viscolube_internal.

  scripts/api-users.py               every function, by header, then a summary
  scripts/api-users.py --private     only those that should leave include/, each
                                     with the folder of its definition
  scripts/api-users.py --summary     only the summary
  scripts/api-users.py --check       the summary; exit 1 when a function should leave
  scripts/api-users.py HEADER...     only these headers (persson.h ...)

Occurrences in comments and strings do not count (both are blanked before
the names are matched); declarations and definitions (as ctags sees them) do
not either. Needs ctags (universal-ctags, Debian package universal-ctags).
"""
import collections
import os
import re
import signal
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAYERS = ["base", "materials", "mechanics", "import", "solver", "db", "study", "writers"]
CLIENTS = ("cli", "python", "examples")  # who makes a function public
# Public although no client calls them yet, and why.
KEEP = {
    "vl_scene_defaults": "the manual's way to fill a vl_scene in code (include/viscolube.h)",
    "vl_atomic_file_abort": "ends an open vl_atomic_file on the caller's own failure",
    "vl_json_integer": "a value of the public JSON writer (json.h writes every kind)",
    "vl_json_bool": "a value of the public JSON writer (json.h writes every kind)",
    "vl_topography_psd_options_default": "the options of the public vl_topography_psd: a "
    "program that changes one takes the others from here",
}
SOURCE_EXT = (".c", ".h")


def ctags(paths, kinds):
    """(name, path relative to ROOT, line) of each tag of these kinds."""
    out = subprocess.run(
        ["ctags", "-x", "--c-kinds=" + kinds, "--language-force=C", "--_xformat=%N\t%F\t%n"]
        + paths,
        cwd=ROOT, check=True, capture_output=True, text=True).stdout
    tags = []
    for line in out.splitlines():
        name, path, n = line.split("\t")
        tags.append((name, path, int(n)))
    return tags


def blank_comments_and_strings(text):
    """text with comments, string and character literals replaced by spaces
    (newlines kept, so line numbers stay)."""
    pattern = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                         re.S)
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def category(path):
    """Who a source file is (cli, python, bench, tests, lib:LAYER), or None."""
    parts = path.split("/")
    if parts[0] == "src" and len(parts) > 2:
        return "cli" if parts[1] == "cli" else "lib:" + parts[1]
    if parts[0] == "python" and parts[1] == "src":
        return "python"
    if parts[0] in ("bench", "tests", "examples"):
        return parts[0]
    return None


def source_files():
    files = []
    for top in ("src", "python/src", "bench", "tests", "examples"):
        for d, _, names in os.walk(os.path.join(ROOT, top)):
            for n in names:
                if n.endswith(SOURCE_EXT):
                    files.append(os.path.relpath(os.path.join(d, n), ROOT))
    return sorted(files)


def main(argv):
    only_private = "--private" in argv
    check = "--check" in argv
    only_summary = "--summary" in argv or check
    headers = [a for a in argv if not a.startswith("--")]
    bad = [a for a in argv if a.startswith("--") and a not in ("--private", "--summary", "--check")]
    if bad:
        sys.exit(__doc__)

    folder = os.path.join(ROOT, "include/viscolube")
    include = sorted("include/viscolube/" + n for n in os.listdir(folder) if n.endswith(".h"))
    public = sorted(ctags(include, "p"), key=lambda t: (t[1], t[2]))
    names = {t[0] for t in public}
    files = source_files()
    # declarations and definitions of the public names outside include/
    tags = ctags(files, "fp")
    skip = {(p, n) for name, p, n in tags if name in names}
    # where each is defined: its private header belongs to that layer
    defined = {name: p for name, p, _ in ctags([f for f in files if f.endswith(".c")], "f")
               if name in names}

    users = collections.defaultdict(lambda: collections.Counter())
    word = re.compile(r"\bvl_\w+\b")
    for path in files:
        who = category(path)
        if who is None:
            continue
        with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
            text = blank_comments_and_strings(f.read())
        for lineno, line in enumerate(text.splitlines(), 1):
            for m in word.finditer(line):
                name = m.group(0)
                if name in names and (path, lineno) not in skip:
                    users[name][who] += 1

    def kind(name):
        who = set(users[name])
        if who & set(CLIENTS):
            return "public"
        if name in KEEP:
            return "kept"
        if not who:
            return "none"
        if "bench" in who:
            return "bench"
        if "tests" in who:
            return "tests only" if who == {"tests"} else "tests and library"
        return "library only"

    by_header = collections.OrderedDict()
    for name, path, _ in public:
        by_header.setdefault(os.path.basename(path), []).append(name)
    if headers:
        unknown = [h for h in headers if h not in by_header]
        if unknown:
            sys.exit("api-users.py: no public function declared in " + ", ".join(unknown))
        by_header = collections.OrderedDict((h, by_header[h]) for h in headers)

    counts = collections.Counter()
    for header, funcs in by_header.items():
        shown = [f for f in funcs if not only_private or kind(f) != "public"]
        for f in funcs:
            counts[kind(f)] += 1
        if only_summary or not shown:
            continue
        print(f"{header}:")
        for f in shown:
            who = users[f]
            order = list(CLIENTS) + ["bench", "tests"] + ["lib:" + l for l in LAYERS]
            text = " ".join(w for w in order if w in who) or "none"
            home = os.path.dirname(defined.get(f, "?"))
            mark = {"public": "", "kept": "public: " + KEEP.get(f, "") + "; "}.get(
                kind(f), f"-> private ({home}): ")
            print(f"  {f:<40} {mark}{text}")
    total = sum(counts.values())
    leave = total - counts["public"] - counts["kept"]
    print(f"\n{total} functions declared in include/viscolube/*.h ({len(by_header)} headers):")
    print(f"  {counts['public']:4d}  public: called by the CLI, Python or an example")
    print(f"  {counts['kept']:4d}  public, no client yet (KEEP in scripts/api-users.py)")
    print(f"  {leave:4d}  should leave include/ (private headers of src/LAYER):")
    for k, text in (("library only", "the library only"),
                    ("tests and library", "tests and the library"),
                    ("tests only", "tests only"),
                    ("bench", "bench/ (and tests, the library)"),
                    ("none", "nobody")):
        print(f"  {counts[k]:8d}  {text}")
    if check and leave:
        sys.exit(1)


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quietly into `| head`
    main(sys.argv[1:])
