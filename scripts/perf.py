#!/usr/bin/env python3
"""Whole-process timings of kepler on large and pathological scenes (issue 16).

    cargo build --release && python3 scripts/perf.py [--only NAME,...] [--dir DIR] [--runs N]
        [--baseline OTHER/target/release/kepler]

Generates the scenes (plain Python, no packages; cached in DIR, default target/perf), runs
each job as a new user would (the release binary, reading the files and writing the SVG),
and prints the median wall time of N runs (default 3) and the peak resident memory of the
process (from wait4's rusage), with bytes per triangle where the scene has one mesh. With
`--baseline`, each run of this build alternates with a run of the other binary (an older
commit built elsewhere), and the table gives both medians and their ratio: measured in the
same run, so the noise of a shared machine falls on both.
"""

import argparse
import math
import os
import random
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KEPLER = os.path.join(ROOT, "target", "release", "kepler")


def cube_sphere(n, bumps, seed):
    """A closed 'scanned' blob: the six n x n grids of a cube pushed onto a sphere and
    displaced radially by a few random bumps (12 n^2 triangles), vertices and faces
    shuffled as a scanner's export would leave them."""
    rng = random.Random(seed)
    waves = [(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1),
              rng.uniform(2, 9), rng.uniform(0, 6.3), rng.uniform(0.005, 0.03))
             for _ in range(bumps)]
    index = {}
    verts = []

    def vertex(key, p):
        v = index.get(key)
        if v is None:
            x, y, z = p
            r = math.sqrt(x * x + y * y + z * z)
            x, y, z = x / r, y / r, z / r
            d = 1.0 + sum(a * math.sin(f * (ax * x + ay * y + az * z) + ph)
                          for ax, ay, az, f, ph, a in waves)
            v = len(verts)
            index[key] = v
            verts.append((x * d, y * d, z * d))
        return v

    faces = []
    for axis in range(3):
        for sign in (-1, 1):
            def corner(i, j):
                u = -1 + 2 * i / n
                w = -1 + 2 * j / n
                p = [0.0, 0.0, 0.0]
                p[axis] = float(sign)
                p[(axis + 1) % 3] = u
                p[(axis + 2) % 3] = w
                # Keys on an integer lattice, so that shared cube edges weld.
                key = tuple(round((c + 1) * n / 2) for c in p)
                return vertex(key, p)
            for i in range(n):
                for j in range(n):
                    a, b = corner(i, j), corner(i + 1, j)
                    c, d = corner(i + 1, j + 1), corner(i, j + 1)
                    if sign > 0:
                        faces += [(a, b, c), (a, c, d)]
                    else:
                        faces += [(a, c, b), (a, d, c)]
    order = list(range(len(verts)))
    rng.shuffle(order)
    new = [0] * len(verts)
    for k, v in enumerate(order):
        new[v] = k
    verts = [verts[v] for v in order]
    faces = [(new[a], new[b], new[c]) for a, b, c in faces]
    rng.shuffle(faces)
    return verts, faces


def parts(count, n, seed):
    """A model of `count` overlapping parts in one mesh, as a game character exported to one
    OBJ is: blobs of 12 n^2 triangles (`cube_sphere`), of random sizes and ellipsoidal
    stretches, along a random walk so that each part passes through its neighbours; the mesh
    intersects itself wherever two parts meet."""
    rng = random.Random(seed)
    verts, faces = [], []
    centre = [0.0, 0.0, 0.0]
    for k in range(count):
        v, f = cube_sphere(n, 6, seed * 1000 + k)
        scale = [rng.uniform(0.3, 1.0) for _ in range(3)]
        centre = [c + rng.uniform(-0.6, 0.6) for c in centre]
        base = len(verts)
        verts += [tuple(centre[i] + scale[i] * p[i] for i in range(3)) for p in v]
        faces += [(a + base, b + base, c + base) for a, b, c in f]
    return verts, faces


def flat_grid(n):
    """n x n squares in the plane z = 0, two triangles each (2 n^2 coplanar triangles)."""
    verts = [(i / n, j / n, 0.0) for i in range(n + 1) for j in range(n + 1)]
    faces = []
    for i in range(n):
        for j in range(n):
            a = i * (n + 1) + j
            b, c, d = a + n + 1, a + n + 2, a + 1
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def write_obj(path, verts, faces):
    with open(path, "w") as f:
        f.write("".join("v %.17g %.17g %.17g\n" % v for v in verts))
        f.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces))


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


CAMERA = """[camera]
projection = "perspective"
eye = [{ex}, {ey}, {ez}]
target = [{tx}, {ty}, {tz}]
fov = {fov}
"""


def cubes(count, step, stacked=False):
    nx = int(round(math.sqrt(count)))
    ny = count // nx
    extent = (nx - 1) * step
    cam = CAMERA.format(ex=-0.6 * extent - 5, ey=-0.9 * extent - 5, ez=0.7 * extent + 5,
                        tx=extent / 2, ty=extent / 2, tz=0, fov=45)
    if stacked:
        cam = CAMERA.format(ex=-3, ey=-4, ez=3, tx=0, ty=0, tz=0, fov=40)
        spec = "[%d, 1, 1]" % count, "[0, 0, 0]"
    else:
        spec = "[%d, %d, 1]" % (nx, ny), "[%g, %g, 0]" % (step, step)
    return cam + """
[[object]]
name = "cubes"
solid = "cube"
edge = 1
array = {{ count = {0}, step = {1} }}
""".format(*spec)


def cached_obj(d, name, make):
    """The OBJ file `name` in folder `d`, written from `make()` (vertices, faces) unless it
    is there already."""
    path = os.path.join(d, name)
    if not os.path.exists(path):
        write_obj(path + ".tmp", *make())
        os.replace(path + ".tmp", path)
    return path


def written(d, name, text):
    """The file `name` in folder `d`, written with `text`."""
    path = os.path.join(d, name)
    write(path, text)
    return path


def scenes(d):
    """(name, command arguments, triangles) for every job, generating missing files."""
    os.makedirs(d, exist_ok=True)

    def obj(name, make):
        return cached_obj(d, name, make)

    def toml(name, text):
        return written(d, name, text)

    scan = obj("scan.obj", lambda: cube_sphere(299, 40, 1))          # 1,073,388 triangles
    blob = obj("blob.obj", lambda: cube_sphere(76, 25, 2))           # 69,312 triangles
    flat = obj("flat.obj", lambda: flat_grid(224))                   # 100,352 triangles
    character = obj("parts.obj", lambda: parts(44, 15, 5))            # 118,800 triangles
    def uv_sphere(name, segments, rings):
        camera = CAMERA.format(ex=3, ey=-4, ez=2, tx=0, ty=0, tz=0, fov=40)
        return toml(name + ".toml", camera + """
[[object]]
name = "%s"
solid = "sphere"
radius = 1
segments = %d
rings = %d
""" % (name, segments, rings))

    sphere = uv_sphere("sphere", 1000, 501)                          # 998,000 triangles
    fan = uv_sphere("fan", 10000, 2)                                 # two cones of 10,000
    def cones(name, segments):
        """Two cones of `segments` slivers base to base, to be seen down their axis."""
        return toml(name, """
[[object]]
name = "cone"
solid = "sphere"
radius = 1
segments = %d
rings = 2
""" % segments)

    cone = cones("cone.toml", 10000)                                 # the fan, seen head-on
    cone100k = cones("cone100k.toml", 100000)
    metropolis = os.path.join(ROOT, "scenes", "metropolis.toml")
    points = os.path.join(d, "points.txt")
    if not os.path.exists(points):
        rng = random.Random(3)
        write(points, "".join("%r %r %r\n" % (rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2),
                                             rng.uniform(-1.2, 1.2)) for _ in range(100000)))
    out = os.path.join(d, "out.svg")
    jobs = [
        ("scan 1.07M tris, feature", ["render", scan, "-o", out], 1073388),
        ("scan 1.07M tris, all", ["render", scan, "--edges", "all", "-o", out], 1073388),
        ("blob 69k tris, feature", ["render", blob, "-o", out], 69312),
        ("blob 69k tris, all", ["render", blob, "--edges", "all", "-o", out], 69312),
        ("44 parts in one mesh, 119k tris, all",
         ["render", character, "--edges", "all", "-o", out], 118800),
        ("surfaces, blob 69k tris", ["surfaces", blob, "-o", out], 69312),
        ("sphere 1M tris", ["render", sphere, "-o", out], 998000),
        ("fan 10,000 edges at a point", ["render", fan, "-o", out], 20000),
        ("flat 100k tris, oblique", ["render", flat, "--view-dir", "1,2,-3", "-o", out], 100352),
        ("flat 100k tris, edge-on", ["render", flat, "--view-dir", "1,2,0", "-o", out], 100352),
        ("include 100k points, 1M sphere", ["include", "--points", points, sphere], 998000),
        ("cone of 100,000 edges head-on, all edges",
         ["render", cone100k, "--edges", "all", "--view-dir", "0,0,-1", "--up", "0,1,0", "-o", out],
         200000),
        ("cone of 10,000 edges head-on, all edges",
         ["render", cone, "--edges", "all", "--view-dir", "0,0,-1", "--up", "0,1,0", "-o", out],
         20000),
        ("metropolis", ["render", metropolis, "-o", out], 0),  # 22,789 objects
        ("metropolis, all edges", ["render", metropolis, "--edges", "all", "-o", out], 0),
        ("surfaces, metropolis", ["surfaces", metropolis, "-o", out], 0),
        ("metropolis, keep overlaps", ["render", metropolis, "--keep-overlaps", "-o", out], 0),
    ]
    for n in (1000, 3000, 10000, 30000, 100000):
        name = "cubes-%d.toml" % n
        jobs.append(("array of %d cubes" % n, ["render", toml(name, cubes(n, 2.0)), "-o", out],
                     12 * n))
    for n in (100, 300, 1000, 10000, 100000):
        name = "stacked-%d.toml" % n
        jobs.append(("%d stacked cubes" % n,
                     ["render", toml(name, cubes(n, 0, stacked=True)), "-o", out], 12 * n))
    return jobs


def run(args, binary=KEPLER):
    start = time.perf_counter()
    proc = subprocess.Popen([binary] + args, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    try:
        _, status, usage = os.wait4(proc.pid, 0)
    except KeyboardInterrupt:
        proc.kill()
        raise
    seconds = time.perf_counter() - start
    err = proc.stderr.read().decode(errors="replace")
    proc.returncode = os.waitstatus_to_exitcode(status)
    return seconds, usage.ru_maxrss * 1024, proc.returncode, err


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--dir", default=os.path.join(ROOT, "target", "perf"))
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--only", default="", help="comma-separated substrings of job names")
    p.add_argument("--timeout", type=float, default=120.0,
                   help="skip further runs of a job slower than this many seconds")
    p.add_argument("--generate", action="store_true", help="only write the scenes")
    p.add_argument("--baseline", help="another kepler binary to run alternately")
    a = p.parse_args()
    if a.generate:
        scenes(a.dir)
        return
    if not os.path.exists(KEPLER):
        sys.exit("build first: cargo build --release")
    # The scenes are generated by a child process: a child's peak memory starts from its
    # parent's (fork keeps the high-water mark), so this process must stay small.
    subprocess.run([sys.executable, __file__, "--generate", "--dir", a.dir], check=True)
    only = [s for s in a.only.split(",") if s]
    binaries = [KEPLER] + ([a.baseline] if a.baseline else [])
    header = "%-34s %10s %10s %10s" % ("job", "seconds", "peak MB", "B/tri")
    if a.baseline:
        header += " %12s %10s %8s" % ("baseline s", "base MB", "speed-up")
    print(header, flush=True)
    for name, args, tris in scenes(a.dir):
        if only and not any(s in name for s in only):
            continue
        times = [[] for _ in binaries]
        peaks = [0 for _ in binaries]
        failed = False
        for _ in range(a.runs):
            for k, binary in enumerate(binaries):
                if times[k] and times[k][-1] > a.timeout:
                    continue
                seconds, rss, code, err = run(args, binary)
                if code != 0:
                    print("%-34s failed (exit %d) with %s: %s" % (name, code, binary,
                                                                 err.strip()[-300:]))
                    failed = True
                    break
                times[k].append(seconds)
                peaks[k] = max(peaks[k], rss)
            if failed:
                break
        if failed or not times[0]:
            continue
        per = peaks[0] / tris if tris else float("nan")  # no one mesh: no bytes per triangle
        line = "%-34s %10.3f %10.0f %10.0f" % (name, statistics.median(times[0]),
                                               peaks[0] / 1e6, per)
        if a.baseline and times[1]:
            base = statistics.median(times[1])
            line += " %12.3f %10.0f %7.1fx" % (base, peaks[1] / 1e6,
                                              base / statistics.median(times[0]))
        print(line, flush=True)


if __name__ == "__main__":
    main()
