#!/usr/bin/env python3
"""A marker file (.trc) without some of its markers: what a lab with a
smaller marker set records (docs/markers.md measures a lower-body set this
way). The standard library only.

  trc_drop_markers.py IN.trc OUT.trc NAME [NAME ...]

Drops each named marker (its name and its X Y Z columns; NumMarkers and the
X1 Y1 Z1 labels renumbered); every other byte of a row is kept. Refuses a
name the file does not have and an OUT that exists. Errors are one line on
stderr, exit status 1.
"""
import os
import sys


def fail(message):
    sys.stderr.write("trc_drop_markers: " + message + "\n")
    sys.exit(1)


def main(argv):
    if len(argv) < 4:
        fail("usage: trc_drop_markers.py IN.trc OUT.trc NAME [NAME ...]")
    src, dst, drop = argv[1], argv[2], set(argv[3:])
    if os.path.exists(dst):
        fail(dst + ": exists")
    with open(src, newline="") as f:
        lines = f.read().split("\n")
    if len(lines) < 6:
        fail(src + ": expected a .trc file (5 header lines), found " + str(len(lines)) + " lines")
    names = [c for c in lines[3].rstrip("\r").split("\t")[2:] if c.strip()]
    missing = sorted(drop - set(names))
    if missing:
        fail(src + ": no marker " + ", ".join(missing))
    keep = [i for i, n in enumerate(names) if n not in drop]
    header = lines[1].rstrip("\r").split("\t")
    values = lines[2].rstrip("\r").split("\t")
    if "NumMarkers" in header:
        values[header.index("NumMarkers")] = str(len(keep))
    out = lines[:2] + ["\t".join(values), "Frame#\tTime\t" + "\t\t\t".join(names[i] for i in keep) + "\t\t",
                       "\t\t" + "\t".join("%s%d" % (a, k + 1) for k in range(len(keep)) for a in "XYZ")]
    for line in lines[5:]:
        cells = line.rstrip("\r").split("\t")
        if len(cells) < 2 + 3 * len(names):
            out.append(line)  # blank lines, the end
            continue
        out.append("\t".join(cells[:2] + [cells[2 + 3 * i + a] for i in keep for a in range(3)]))
    with open(dst, "w", newline="") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main(sys.argv)
