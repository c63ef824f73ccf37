#!/usr/bin/env python3
"""Copy an experiments directory with its inputs moved by one unit in the last place, a model of
what rounding does: each `theta0 = [...]` array of every experiment file (TOML, at any depth),
entry i moved to the next representable double up or down by PATTERN: `up` (every entry up),
`down`, `alternate` (entry i up for even i, down for odd i) or `alternate-down` (the reverse);
and every path's `duration` moved up (`up`, `alternate`) or down (the others). The initial
configuration is moved once; the duration enters the path's time law t / T at every
evaluation, so every right-hand side is moved by about an ulp, as a reordering of its
operations moves it. The values are written with Python's repr, the shortest decimal that
reads back as that double, so the run reads exactly the moved numbers.

Usage: perturb.py EXPERIMENTS_DIR OUT_DIR PATTERN   (OUT_DIR must not exist)"""
import math
import re
import shutil
import sys
from pathlib import Path

ARRAY = re.compile(r"(\btheta0\s*=\s*)\[([^\]]*)\]")
DURATION = re.compile(r"(\bduration\s*=\s*)([0-9][0-9.eE+-]*)")


PATTERNS = {
    "up": lambda i: True,
    "down": lambda i: False,
    "alternate": lambda i: i % 2 == 0,
    "alternate-down": lambda i: i % 2 == 1,
}


def moved(text: str, up_at) -> tuple[str, int]:
    count = 0

    def one(match: re.Match) -> str:
        nonlocal count
        count += 1
        values = [float(v) for v in match.group(2).split(",") if v.strip()]
        out = []
        for i, v in enumerate(values):
            up = up_at(i)
            out.append(repr(math.nextafter(v, math.inf if up else -math.inf)))
        return match.group(1) + "[" + ", ".join(out) + "]"

    text = ARRAY.sub(one, text)
    direction = math.inf if up_at(0) else -math.inf
    text, durations = DURATION.subn(
        lambda m: m.group(1) + repr(math.nextafter(float(m.group(2)), direction)), text
    )
    return text, count + durations


def main() -> None:
    if len(sys.argv) != 4 or sys.argv[3] not in PATTERNS:
        sys.exit(__doc__)
    src, out, pattern = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
    if out.exists():
        sys.exit(f"{out}: exists")
    shutil.copytree(src, out)
    arrays = 0
    for path in sorted(out.rglob("*.toml")):
        text, count = moved(path.read_text(), PATTERNS[pattern])
        if count:
            path.write_text(text)
            arrays += count
    if arrays == 0:
        sys.exit(f"{src}: no theta0 array or duration to move")
    print(f"{arrays} theta0 arrays and durations moved by one ulp ({pattern}) into {out}")


if __name__ == "__main__":
    main()
