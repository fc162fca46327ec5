#!/usr/bin/env python3
"""How each stage's cost grows with the input, family by family (issue 29).

    cargo build --release && python3 scripts/scaling.py [--only FAMILY,...] [--sizes N]
        [--runs R] [--dir DIR]

Each family is a kind of input people have (a clean scan, a fan of edges round one vertex,
overlapping parts, coincident lines, an edge-on sheet, many small objects), generated at
several sizes (plain Python, cached in DIR, default target/scaling). Each size is drawn by
the release binary as a new user would, with `--stats`; the script prints, per family, the
whole process's time and each stage's time per element (microseconds per triangle), and the
exponent fitted to time ∝ size^k by least squares on the logarithms, and the exponent between
the two largest sizes (where a family's own growth has settled). A stage whose exponent is
well above 1 grows faster than its input: that is a bug (the guide's words), and the number
names the stage, unless what it makes grows so too: the intersections stage is output-
sensitive, so the script also prints its time per segment found and the segments' exponent. Times are medians of R runs (default 1); stages under a millisecond
at the largest size are left out of the fit, where the clock's resolution dominates.
"""

import argparse
import math
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from perf import (CAMERA, KEPLER, ROOT, cached_obj, cube_sphere, cubes, flat_grid,  # noqa: E402
                  parts, run, written)

STAGE = re.compile(r"^(\S+)\s+(\d+\.\d+)\s\s")
SEGMENTS = re.compile(r"^intersections\s+\d+\.\d+\s+(\d+) segments")


def sphere_toml(segments, rings, step=None, count=1):
    """A UV sphere (2·segments·(rings−1) triangles), or `count` of them in a row `step`
    apart (overlapping when step < 2)."""
    array = "" if count == 1 else "array = { count = [%d, 1, 1], step = [%r, 0, 0] }\n" % (
        count, step)
    camera = CAMERA.format(ex=3, ey=-4, ez=2, tx=0, ty=0, tz=0, fov=40)
    return camera + """
[[object]]
name = "s"
solid = "sphere"
radius = 1
segments = %d
rings = %d
%s""" % (segments, rings, array)


def families(d, count):
    """(family, [(size, triangles, arguments)]) for every family, files made as needed."""
    os.makedirs(d, exist_ok=True)
    out = os.path.join(d, "out.svg")

    def obj(name, make):
        return cached_obj(d, name, make)

    def toml(name, text):
        return written(d, name, text)

    def sizes(first, factor):
        return [int(round(first * factor ** i)) for i in range(count)]

    out_all = ["--edges", "all", "-o", out]
    fams = []
    # A clean closed scan: 12 n² triangles.
    fams.append(("scan, all edges", [
        (12 * n * n, 12 * n * n, ["render", obj("scan-%d.obj" % n, lambda n=n: cube_sphere(n, 25, 2))] + out_all)
        for n in sizes(16, 2)]))
    fams.append(("scan, feature edges", [
        (12 * n * n, 12 * n * n, ["render", obj("scan-%d.obj" % n, lambda n=n: cube_sphere(n, 25, 2)), "-o", out])
        for n in sizes(16, 2)]))
    # A cone of s slivers round one apex seen head-on (the fan): 2 s triangles.
    fams.append(("fan head-on, all edges", [
        (s, 2 * s, ["render", toml("fan-%d.toml" % s, sphere_toml(s, 2)), "--view-dir", "0,0,-1",
                    "--up", "0,1,0"] + out_all)
        for s in sizes(1000, 3)]))
    # k spheres overlapping along a line, each meeting its neighbours.
    fams.append(("overlapping parts", [
        (k, 2 * 24 * 11 * k, ["render", toml("overlap-%d.toml" % k, sphere_toml(24, 12, 0.5, k))]
         + out_all)
        for k in sizes(4, 3)]))
    # k overlapping blobs of 2,700 triangles in one mesh (a model exported as one OBJ): the
    # mesh intersects itself wherever two parts meet.
    fams.append(("parts in one mesh", [
        (k, 2700 * k, ["render", obj("parts-%d.obj" % k, lambda k=k: parts(k, 15, 5))] + out_all)
        for k in sizes(4, 3)]))
    # k unit cubes face to face in a row: their edges coincide in space and in the picture.
    fams.append(("coincident lines", [
        (k, 12 * k, ["render", toml("touching-%d.toml" % k, cubes(k, 1.0)), "-o", out])
        for k in sizes(100, 3)]))
    # A flat grid of 2 n² triangles seen edge-on.
    fams.append(("edge-on sheet", [
        (2 * n * n, 2 * n * n, ["render", obj("flat-%d.obj" % n, lambda n=n: flat_grid(n)),
                                "--view-dir", "1,2,0", "-o", out])
        for n in sizes(25, 2)]))
    # k cubes apart on a grid.
    fams.append(("many small objects", [
        (k, 12 * k, ["render", toml("cubes-%d.toml" % k, cubes(k, 2.0)), "-o", out])
        for k in sizes(300, 3)]))
    return fams


def slope(points):
    """The least-squares slope of log t against log n, or None with fewer than two points."""
    pts = [(math.log(n), math.log(t)) for n, t in points if t > 0]
    if len(pts) < 2:
        return None
    mx = statistics.fmean(x for x, _ in pts)
    my = statistics.fmean(y for _, y in pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx else None


def large_end(points):
    """The exponent between the last two points, as text ('-' when either time is 0)."""
    k = slope(points[-2:]) if len(points) >= 2 else None
    return "-" if k is None else "%.2f" % k


def measure(args, runs, binary):
    """Median whole time, peak memory and the stages' median times of `runs` runs."""
    wholes, peaks, stages, segments = [], [], {}, 0
    for _ in range(runs):
        seconds, peak, code, err = run(args + ["--stats"], binary)
        if code != 0:
            raise SystemExit("kepler %s failed:\n%s" % (" ".join(args), err))
        wholes.append(seconds)
        peaks.append(peak)
        for line in err.splitlines():
            if line.startswith("class "):
                break  # the lengths per class follow the stages
            found = SEGMENTS.match(line)
            if found:
                segments = int(found.group(1))
            m = STAGE.match(line)
            if m:
                stages.setdefault(m.group(1), []).append(float(m.group(2)))
    return (statistics.median(wholes), max(peaks),
            {k: statistics.median(v) for k, v in stages.items()}, segments)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--dir", default=os.path.join(ROOT, "target", "scaling"))
    p.add_argument("--sizes", type=int, default=4, help="sizes per family (each ×2 to ×3)")
    p.add_argument("--runs", type=int, default=1)
    p.add_argument("--only", default="", help="comma-separated substrings of family names")
    p.add_argument("--binary", default=KEPLER)
    a = p.parse_args()
    only = [s for s in a.only.split(",") if s]
    worst = []
    for family, cases in families(a.dir, a.sizes):
        if only and not any(s in family for s in only):
            continue
        print("## %s" % family)
        rows = []
        for size, triangles, args in cases:
            whole, peak, stages, segments = measure(args, a.runs, a.binary)
            rows.append((size, triangles, whole, peak, stages, segments))
            print("  size %8d  %8d triangles  %7.3f s  %6.2f µs/triangle  %5.0f MB  %s" % (
                size, triangles, whole, 1e6 * whole / triangles, peak / 1e6,
                "  ".join("%s %.3f" % kv for kv in sorted(stages.items(), key=lambda kv: -kv[1])[:3])))
            sys.stdout.flush()
        k = slope([(r[1], r[2]) for r in rows])
        print("  exponent, whole process: %.2f  (%s between the two largest sizes)" % (
            k, large_end([(r[1], r[2]) for r in rows])))
        if rows[-1][5] > 0:
            found = [(r[1], r[5]) for r in rows if r[5] > 0]
            print("  segments found: %s (exponent %.2f); intersections %s µs per segment" % (
                ", ".join(str(r[5]) for r in rows), slope(found),
                ", ".join("%.1f" % (1e6 * r[4].get("intersections", 0.0) / r[5])
                          for r in rows if r[5] > 0)))
        names = sorted({s for r in rows for s in r[4]})
        for name in names:
            pts = [(r[1], r[4].get(name, 0.0)) for r in rows]
            if pts[-1][1] < 1e-3:
                continue
            ks = slope(pts)
            if ks is not None:
                print("  exponent, %-14s %.2f  (%.3f s at the largest size; %s between the two largest)" % (
                    name + ":", ks, pts[-1][1], large_end(pts)))
                worst.append((ks, family, name))
    if worst:
        k, family, name = max(worst)
        print("\nsteepest stage: %s in '%s', exponent %.2f" % (name, family, k))


if __name__ == "__main__":
    main()
