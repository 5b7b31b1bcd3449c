#!/usr/bin/env python3
"""How far apart two output trees of scripts/same-numbers.sh are, number by number:

  scripts/max-difference.py OLD_DIR NEW_DIR

For every file that differs: CSV files column by column, the largest relative
difference |a - b| / max(|a|, |b|) of a number and the largest difference relative
to the column's largest magnitude (a value that is zero up to round-off, a contact
pressure of 1e-12 Pa in a column of 1e6 Pa, has a relative difference of order 1
but not of its column); other text files number by number in order. Files with a
different layout (other rows or columns) are named as such.
"""
import csv
import os
import re
import sys

NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def rel(a, b):
    s = max(abs(a), abs(b))
    return abs(a - b) / s if s else 0.0


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def compare_csv(pa, pb):
    ra, rb = list(csv.reader(open(pa))), list(csv.reader(open(pb)))
    if len(ra) != len(rb) or ra[:1] != rb[:1]:
        return ["layout differs"]
    out = []
    for k, name in enumerate(ra[0]):
        worst, worst_col, scale = 0.0, 0.0, 0.0
        for x, y in zip(ra[1:], rb[1:]):
            u, v = number(x[k]), number(y[k])
            if u is None or v is None:
                if x[k] != y[k]:
                    out.append(f"{name}: text {x[k]!r} -> {y[k]!r}")
                continue
            scale = max(scale, abs(u))
            worst = max(worst, rel(u, v))
            worst_col = max(worst_col, abs(u - v))
        if worst:
            out.append(f"{name}: max relative {worst:.2e}, max of the column's scale "
                       f"{worst_col / scale if scale else 0.0:.2e}")
    return out


def compare_text(pa, pb):
    na, nb = NUM.findall(open(pa).read()), NUM.findall(open(pb).read())
    if len(na) != len(nb):
        return ["layout differs"]
    worst = max((rel(float(x), float(y)) for x, y in zip(na, nb)), default=0.0)
    return [f"numbers: max relative {worst:.2e}"]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    old, new = sys.argv[1], sys.argv[2]
    same = 0
    for root, _, files in os.walk(old):
        for f in sorted(files):
            pa = os.path.join(root, f)
            pb = os.path.join(new, os.path.relpath(pa, old))
            if not os.path.exists(pb):
                print(f"{pb}: missing")
                continue
            if open(pa, "rb").read() == open(pb, "rb").read():
                same += 1
                continue
            lines = compare_csv(pa, pb) if f.endswith(".csv") else compare_text(pa, pb)
            print(f"{os.path.relpath(pa, old)}:")
            for line in lines:
                print(f"  {line}")
    print(f"{same} files identical")


if __name__ == "__main__":
    main()
