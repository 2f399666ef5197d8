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

Polygon adapters (`check --kind polygons`, the `*_polygon.py` here) read a
polygon a line, `polygon x0 y0 x1 y1 ...`, each followed by its holes,
`hole x0 y0 ...`, and are drawn by `run_polygons`, one polygon alone at a
time, given its rings (each hole wound against the outer ring, as rasterlab
winds it) and the fill rule, `even-odd` or `nonzero`, that `{rule}` puts on
the command line.
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


def serve(draw, numbers, parser=None):
    """Answers check in either protocol: the case file named on the
    command line (`{input} {width} {height}`), or, with no case on the
    command line (`--persistent`), case after case on standard input.
    `parser(lines)` reads a case, by default `parse` with `numbers`."""
    if parser is None:
        parser = lambda lines: parse(lines, numbers)
    if len(sys.argv) >= 4:
        path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
        with open(path) as f:
            try:
                _, _, primitives = parser(f.read().splitlines())
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
            width, height, primitives = parser(case)
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


FILLS = ("even-odd", "nonzero")


def signed_area(ring):
    """Twice the ring's signed area (shoelace)."""
    return sum(
        a[0] * b[1] - b[0] * a[1] for a, b in zip(ring, ring[1:] + ring[:1])
    )


def parse_polygons(lines):
    """(width, height, polygons) from a polygon case's lines, each polygon
    a list of rings (lists of (x, y)), the outer ring first; a hole wound
    as its outer ring is reversed, as rasterlab reverses it."""
    width = height = None
    polygons = []
    for line in lines:
        if line.startswith("# size"):
            width, height = (int(v) for v in line.split()[2].split("x"))
            continue
        line = line.split("#")[0].strip()
        if not line:
            continue
        word, *rest = line.split()
        if word not in ("polygon", "hole"):
            raise ValueError(f"expected a `polygon` or `hole` line, got `{word}`")
        v = [float(t) for t in rest]
        ring = [(v[i], v[i + 1]) for i in range(0, len(v) - 1, 2)]
        if word == "polygon":
            polygons.append([ring])
            continue
        if not polygons:
            raise ValueError("`hole` before any `polygon`")
        outer = signed_area(polygons[-1][0])
        if outer * signed_area(ring) > 0:
            ring = ring[::-1]
        polygons[-1].append(ring)
    return width, height, polygons


def bridged(rings):
    """The rings as one ring, for a library that takes one: each hole
    joined to the outer ring's first vertex by an edge there and back
    (the two cancel under either fill rule)."""
    first = rings[0][0]
    out = list(rings[0]) + [first]
    for hole in rings[1:]:
        out += list(hole) + [hole[0], first]
    return out


def run_polygons(draw):
    """Serves polygons: `draw(width, height, rings, fill)`, `fill` the
    rule named on the command line (`{rule}`: even-odd, the default, or
    nonzero); see [`answer`]."""
    fill = next((a for a in sys.argv[1:] if a in FILLS), "even-odd")
    sys.argv = [a for a in sys.argv if a not in FILLS]
    serve(lambda w, h, rings: draw(w, h, rings, fill), 0, parse_polygons)
