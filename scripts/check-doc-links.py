#!/usr/bin/env python3
"""Checks the links between the project's Markdown files.

    scripts/check-doc-links.py        (from anywhere; exit status 1 on a broken link)

Every relative link or image of README.md, CHANGELOG.md, docs/*.md and bench/README.md,
[text](path) or [text](path#anchor), must name a file or folder that exists, and an
anchor must be the GitHub slug of a heading of the target. Links into code blocks are
ignored; http(s) and mailto links are not checked.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
FILES = [ROOT / "README.md", ROOT / "CHANGELOG.md", ROOT / "bench" / "README.md",
         *sorted((ROOT / "docs").glob("*.md"))]
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def prose(text):
    """The text without fenced code blocks and inline code spans."""
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", text)


def slugs(path):
    out = set()
    for line in path.read_text(encoding="utf-8").splitlines():
        m = re.match(r"#{1,6}\s+(.*)", line)
        if m:
            s = m.group(1).strip().lower()
            s = re.sub(r"[^\w\- ]", "", s)
            out.add(s.replace(" ", "-"))
    return out


bad = 0
for f in FILES:
    if not f.exists():
        continue
    for target in LINK.findall(prose(f.read_text(encoding="utf-8"))):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        dest = (f.parent / path).resolve() if path else f
        where = f.relative_to(ROOT)
        if not dest.exists():
            print(f"{where}: {target}: no such file")
            bad += 1
        elif anchor and dest.suffix == ".md" and anchor not in slugs(dest):
            print(f"{where}: {target}: no heading with that anchor")
            bad += 1
print(f"check-doc-links: {len(FILES)} files, {bad} broken links")
sys.exit(1 if bad else 0)
