#!/usr/bin/env python3
"""Every command's output on the bundled scenes, compared byte for byte between two kepler
binaries: for refactoring, where nothing a user sees may change (issue 28).

    python3 scripts/same_output.py --old OLD_KEPLER --new target/release/kepler [--quick]

Each case runs both binaries in their own empty folder with the same arguments (paths to the
scenes are absolute) and compares standard output, standard error, the exit code and every
file written. Lines that carry measured times (`--stats`, `segx`, `report`) are left out of the
comparison: they differ from run to run. Prints one line per differing case and exits 1 if
any differ.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "scenes")

# Scenes drawn by every drawing command; the metropolis only by the commands that are fast on it.
SMALL = ["cube", "solids", "polyhedra", "torus", "city", "meshes", "bunny"]
VIEWS = [
    [],
    ["--view-dir", "-1,-2,-3"],
    ["--view-dir", "0,0,-1", "--up", "0,1,0"],
    ["--eye", "3,2,1.5", "--target", "0,0,0"],
]
STREET = ["--eye", "0.5,0.5,0.3", "--target", "3,3,0.2", "--fov", "70"]

# Text with times in it: `1.23 s`, `45 ms`, `0.5 µs`, and rates.
TIMES = re.compile(r"seconds\s+[\d.e-]+|\d+(\.\d+)?(e-?\d+)?\s*(M |k )?(s|ms|µs|us|ns|points/s|/s)\b")


def scene(name):
    return os.path.join(SCENES, f"{name}.toml")


def cases(quick):
    """(name, arguments, whether to mask times) for every case."""
    commands = ["render", "surfaces", "include", "visp", "visobj", "cull", "triboxes", "gen",
                "bounds", "boxtree", "report", "segx"]
    yield "help", ["--help"], False
    for c in commands:
        yield f"help {c}", [c, "--help"], False
    for s in SMALL + ["metropolis"]:
        yield f"bounds {s}", ["bounds", scene(s)], False
        yield f"bounds --json {s}", ["bounds", scene(s), "--json"], False
    views = VIEWS[:2] if quick else VIEWS
    for s in SMALL:
        for i, v in enumerate(views):
            base = ["render", scene(s), "-o", "out.svg", "--json", "out.json"] + v
            yield f"render {s} view{i}", base, False
            yield f"render {s} view{i} all", base + ["--edges", "all"], False
            yield f"render {s} view{i} keep", base + ["--keep-overlaps"], False
            yield f"render {s} view{i} omit order", base + ["--hidden", "omit", "--order"], False
            yield f"render {s} view{i} dxf", ["render", scene(s), "-o", "out.dxf"] + v, False
            yield f"render {s} view{i} hatch", base + ["--hatch"], False
            yield f"render {s} view{i} hatch order", base + ["--hatch", "--order", "--stats"], True
            yield f"render {s} view{i} verify", base + ["--verify"], True
            yield f"render {s} view{i} stats", base + ["--stats"], True
            yield f"surfaces {s} view{i}", ["surfaces", scene(s), "-o", "out.svg",
                                             "--json", "out.json", "--outlines"] + v, False
            yield f"cull {s} view{i}", ["cull", scene(s), "--json", "out.json"] + v, False
    for s in ["city", "metropolis"]:
        yield f"render {s} street", ["render", scene(s), "-o", "out.svg", "--json", "out.json"] + STREET, False
        yield f"surfaces {s} street", ["surfaces", scene(s), "-o", "out.svg"] + STREET, False
    yield "render metropolis", ["render", scene("metropolis"), "-o", "out.svg", "--json", "out.json"], False
    yield "render dxf binary", ["render", scene("city"), "-o", "out.dxf", "--dxf", "binary"], False
    points = os.path.join(SCENES, "city-points.txt")
    yield "include city", ["include", scene("city"), "--points", points], True
    yield "visp city", ["visp", scene("city"), "--points", points], True
    yield "visp city eye", ["visp", scene("city"), "--points", points] + STREET, True
    yield "triboxes solids", ["triboxes", scene("solids"), "-o", "out.svg", "--json", "out.json"], False
    yield "triboxes torus", ["triboxes", scene("torus"), "--levels", "3"], False
    yield "gen list", ["gen", "--list"], False
    for family in ["sliver", "offset", "fan"]:
        yield f"gen {family}", ["gen", "--family", family, "--k", "3", "--seed", "7", "-o", "."], False
    yield "segx", ["segx", "--n", "2000", "--pairs"], True
    yield "boxtree", ["boxtree", "--experiment", "spheres", "--json", "out.json"], True
    if not quick:
        yield "report quick", ["report", "--quick", "--out", "rep", "--scenes", SCENES], True
    # Errors a user meets: messages must not change either.
    yield "missing scene", ["render", os.path.join(SCENES, "missing.toml"), "-o", "out.svg"], False
    yield "bad option", ["render", scene("cube"), "--edges", "some"], False


# The `--stats` table's seconds column.
STAGE_TIMES = re.compile(r"^(\w+ +)\d+\.\d+", re.M)
# Measured seconds in JSON.
SECONDS = re.compile(r'("seconds":\s*)[\d.e+-]+')
# The dxf crate writes fresh random GUIDs and the time of writing (Julian dates) into every
# file's header; in a binary DXF the dates are raw doubles, so its header is left out whole.
GUIDS = re.compile(rb"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}")
DATES = re.compile(rb"^24\d{5}\.\d+\r?$", re.M)


def masked(data, mask):
    if data.startswith(b"AutoCAD Binary DXF"):
        data = data[data.find(b"ENTITIES"):]
    data = DATES.sub(b"<date>", GUIDS.sub(b"<guid>", data))
    if not mask:
        return data
    text = data.decode("utf-8", "replace")
    text = SECONDS.sub(r"\1<time>", STAGE_TIMES.sub(r"\1<time>", TIMES.sub("<time>", text)))
    return text.encode()


def run(binary, args, mask, timeout):
    folder = tempfile.mkdtemp(prefix="same-output-")
    try:
        p = subprocess.run([binary] + args, cwd=folder, capture_output=True, timeout=timeout)
        result = {"exit": str(p.returncode).encode(), "stdout": masked(p.stdout, mask),
                  "stderr": masked(p.stderr, mask)}
    except subprocess.TimeoutExpired:
        result = {"exit": b"timeout"}
    for dirpath, _, files in os.walk(folder):
        for f in files:
            path = os.path.join(dirpath, f)
            with open(path, "rb") as fh:
                result[os.path.relpath(path, folder)] = masked(fh.read(), mask)
    subprocess.run(["rm", "-rf", folder])
    return result


def named_kepler(binary):
    folder = tempfile.mkdtemp(prefix="same-output-bin-")
    path = os.path.join(folder, "kepler")
    subprocess.run(["cp", os.path.abspath(binary), path], check=True)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--old", required=True)
    parser.add_argument("--new", required=True)
    parser.add_argument("--quick", action="store_true", help="fewer views, no report")
    parser.add_argument("--only", default="", help="comma-separated substrings of case names")
    parser.add_argument("--timeout", type=float, default=600)
    a = parser.parse_args()
    only = [o for o in a.only.split(",") if o]
    # Each binary is run as `kepler` (clap prints the program's name in messages).
    old, new = named_kepler(a.old), named_kepler(a.new)
    differ, total = 0, 0
    for name, args, mask in cases(a.quick):
        if only and not any(o in name for o in only):
            continue
        total += 1
        x, y = run(old, args, mask, a.timeout), run(new, args, mask, a.timeout)
        if name.startswith("report"):
            # Its tables and charts show times relative to the exact run's; its JSON has
            # every measured figure beside the seconds (masked).
            x, y = ({k: v for k, v in r.items() if k.endswith(".json")} for r in (x, y))
        if x != y:
            differ += 1
            keys = sorted(k for k in set(x) | set(y) if x.get(k) != y.get(k))
            print(f"DIFFER {name}: {', '.join(keys)}  ({' '.join(args)})", flush=True)
    print(f"{total - differ} of {total} cases the same")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
