#!/usr/bin/env python3
"""Files and functions a reader cannot hold: every `.rs` file over MAX_LINES lines and every
function over MAX_FN lines (from its `fn` line to its closing brace), in the folders given.

    python3 scripts/sizes.py [--max-lines 800] [--max-fn 80] [FOLDER ...]   # default: src

Prints one line per file or function over its limit and exits 1 if there is any. Braces are
counted on each line after string and character literals and `//` comments are blanked, which
is enough for this code base (no braces in raw strings spanning lines).
"""
import argparse
import os
import re
import sys

FN = re.compile(r"\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)")


def code(line):
    """The line with string and character literals emptied and its comment dropped."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])'", "''", line)
    return line.split("//")[0]


def long_functions(lines, limit):
    """(length, line number, name) of every function longer than `limit` lines."""
    out = []
    for i, line in enumerate(lines):
        m = FN.match(line)
        if not m or line.strip().startswith("//"):
            continue
        depth, started = 0, False
        for j in range(i, len(lines)):
            text = code(lines[j])
            for c in text:
                if c == "{":
                    depth, started = depth + 1, True
                elif c == "}":
                    depth -= 1
            if started and depth <= 0:
                break
            if not started and text.rstrip().endswith(";"):
                break
        if started and j - i + 1 > limit:
            out.append((j - i + 1, i + 1, m.group(6)))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folders", nargs="*", default=["src"])
    parser.add_argument("--max-lines", type=int, default=800)
    parser.add_argument("--max-fn", type=int, default=80)
    args = parser.parse_args()
    found = []
    for folder in args.folders:
        for root, _, files in sorted(os.walk(folder)):
            for name in sorted(files):
                if not name.endswith(".rs"):
                    continue
                path = os.path.join(root, name)
                with open(path, encoding="utf-8") as f:
                    lines = f.read().split("\n")
                if len(lines) - 1 > args.max_lines:
                    found.append(f"{path}: {len(lines) - 1} lines")
                for n, at, fn in long_functions(lines, args.max_fn):
                    found.append(f"{path}:{at}: fn {fn}, {n} lines")
    for line in found:
        print(line)
    print(f"{len(found)} over the limits ({args.max_lines} lines a file, {args.max_fn} a function)")
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
