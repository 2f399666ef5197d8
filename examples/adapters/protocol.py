"""The `rasterlab check --exec` protocol, shared by the adapters here.

An adapter is started once per case as

    python3 examples/adapters/LIBRARY.py {input} {width} {height}

`{input}` holds `# size WxH`, then one triangle per line, `x0 y0 x1 y1 x2 y2`
in screen coordinates: pixels, x right, y down, pixel (i, j) covering
[i, i+1) x [j, j+1) with its centre at (i + 0.5, j + 0.5). The adapter prints
one fragment per line, `x y id`, id the triangle's 0-based index.

Each adapter draws one triangle at a time into a mask of the target's size,
so that every fragment is known by its triangle, and maps the library's own
pixel convention to the one above (said at the top of each adapter).

Started without `{input} {width} {height}` (`rasterlab check --persistent
--exec "python3 examples/adapters/LIBRARY.py"`), an adapter instead reads
case after case on standard input, each ended by a line `end`, and answers
each with its fragments and `end`: the library is imported once, not once
per case.

Line adapters (`check --kind lines`, the `*_line.py` here) are the same but
for the input: one segment per line, `x0 y0 x1 y1`, drawn by `run_lines`,
one segment alone at a time. Under `--convention
pixel-index` the numbers are whole and name pixels (`pixel_index` turns
them into ints and refuses any that is not whole); otherwise they are
screen coordinates as above.
"""

import math
import sys


def parse(lines, numbers):
    """(width, height, primitives) from a case's lines, each primitive a
    list of `numbers // 2` (x, y) points."""
    width = height = None
    primitives = []
    for line in lines:
        if line.startswith("# size"):
            width, height = (int(v) for v in line.split()[2].split("x"))
            continue
        line = line.split("#")[0].strip()
        if line:
            v = [float(t) for t in line.split()]
            if len(v) != numbers:
                raise ValueError(f"expected {numbers} numbers a line, got {len(v)}")
            primitives.append([(v[i], v[i + 1]) for i in range(0, numbers, 2)])
    return width, height, primitives


def answer(width, height, primitives, draw):
    """The `x y id` lines: `draw(width, height, primitive)` returns the
    drawn pixels as (x, y) pairs, or a 2D array indexed [y][x] that is
    non-zero where drawn."""
    out = []
    for t, primitive in enumerate(primitives):
        pixels = draw(width, height, primitive)
        if hasattr(pixels, "nonzero"):
            ys, xs = pixels.nonzero()
            pixels = zip(xs.tolist(), ys.tolist())
        out.extend(f"{x} {y} {t}" for x, y in pixels)
    return out


def serve(draw, numbers):
    """Answers check in either protocol: the case file named on the
    command line (`{input} {width} {height}`), or, with no case on the
    command line (`--persistent`), case after case on standard input."""
    if len(sys.argv) >= 4:
        path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
        with open(path) as f:
            try:
                _, _, primitives = parse(f.read().splitlines(), numbers)
            except ValueError as e:
                sys.exit(str(e))
        out = answer(width, height, primitives, draw)
        sys.stdout.write("\n".join(out) + ("\n" if out else ""))
        return
    case = []
    for line in sys.stdin:
        if line.strip() != "end":
            case.append(line.rstrip("\n"))
            continue
        try:
            width, height, primitives = parse(case, numbers)
            out = answer(width, height, primitives, draw)
            sys.stdout.write("".join(f"{l}\n" for l in out) + "end\n")
        except Exception as e:  # reported with the case's input
            sys.stdout.write(f"error {type(e).__name__}: {e}\n".replace("\n", " ").rstrip() + "\n")
        sys.stdout.flush()
        case = []


def run(draw):
    """Serves triangles: `draw(width, height, triangle)`, see [`answer`]."""
    serve(draw, 6)


def pixel_index(v):
    """The pixel index a number names, as an int: the number itself when it
    is whole (the cases of the whole-pixel conventions), else rounded half
    up (`--convention any` also gives screen cases to every subject, which
    a whole-pixel drawer then draws at the nearest pixel indices)."""
    return math.floor(v + 0.5)


def run_lines(draw):
    """Serves line segments: `draw(width, height, segment)`, see
    [`answer`]."""
    serve(draw, 4)
