#!/usr/bin/env python3
"""Fails when a function in the given folders is longer than the limit (120 lines by default).

    scripts/check_function_length.py [--limit N] FOLDER...

The code is clang-formatted, so a function's signature starts at its first line's indentation and
its body closes with a lone '}' at that indentation; lambdas and nested bodies close deeper.
Lines are counted from the signature's first line to the closing brace.
"""
import argparse
import re
import sys
from pathlib import Path

OPENS_BODY = re.compile(r"\)\s*(const)?\s*(override)?\s*(noexcept)?\s*(->\s*[\w:<>]+)?\s*\{$")
CONTROL = re.compile(r"\s*(if|for|while|switch|else|do|catch)\b")


def long_functions(path: Path, limit: int):
    lines = path.read_text().split("\n")
    open_bodies = []  # (indentation, first line index)
    for i, line in enumerate(lines):
        text = line.rstrip()
        indent = len(line) - len(line.lstrip())
        if OPENS_BODY.search(text) and not CONTROL.match(text):
            first = i
            while first > 0:
                previous = lines[first - 1].rstrip()
                if (not previous.strip() or previous.endswith((";", "}", "{")) or
                        previous.lstrip().startswith(("//", "#"))):
                    break
                first -= 1
            open_bodies.append((len(lines[first]) - len(lines[first].lstrip()), first))
        elif text.strip() in ("}", "};"):
            while open_bodies and open_bodies[-1][0] > indent:
                open_bodies.pop()
            if open_bodies and open_bodies[-1][0] == indent:
                _, first = open_bodies.pop()
                length = i - first + 1
                if length > limit:
                    yield first + 1, length, lines[first].strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=120)
    parser.add_argument("folders", nargs="+")
    args = parser.parse_args()
    found = 0
    for folder in args.folders:
        for path in sorted(Path(folder).rglob("*.cc")) + sorted(Path(folder).rglob("*.h")):
            for line, length, signature in long_functions(path, args.limit):
                print(f"{path}:{line}: {length} lines (limit {args.limit}): {signature[:80]}")
                found += 1
    if found:
        print(f"{found} function(s) over {args.limit} lines: split them into named steps")
        return 1
    print(f"no function over {args.limit} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
