"""The `rasterlab check` protocol for a rasterizer written in Python.

Import `run` and give it your functions; this module reads the cases,
calls them and prints the fragments, in either of check's two ways:

    rasterlab check --exec "python3 rasterizer.py {input} {width} {height}"
        started once per case, the case in the file {input};
    rasterlab check --persistent --exec "python3 rasterizer.py"
        started once, the cases one after another on standard input
        (many times faster: Python starts once).

A case is a target size and primitives in screen coordinates: pixels, x
right, y down, pixel (i, j) covering [i, i+1) x [j, j+1), its centre at
(i + 0.5, j + 0.5). Your functions return the pixels they draw as (x, y)
pairs; this module numbers them by primitive and prints `x y id` lines.
"""

import sys
import traceback


def parse_case(lines):
    """(width, height, triangles, segments) from a case's lines."""
    width = height = None
    triangles, segments = [], []
    for line in lines:
        text = line.strip()
        if text.startswith("# size"):
            width, height = (int(v) for v in text.split()[2].split("x"))
            continue
        text = text.split("#")[0].strip()
        if not text:
            continue
        v = [float(t) for t in text.split()]
        if len(v) == 6:
            triangles.append(((v[0], v[1]), (v[2], v[3]), (v[4], v[5])))
        elif len(v) == 4:
            segments.append(((v[0], v[1]), (v[2], v[3])))
        else:
            raise ValueError(f"expected 6 or 4 numbers a line, got {len(v)}: {text!r}")
    if width is None:
        raise ValueError("the case has no `# size WxH` line")
    return width, height, triangles, segments


def answer(lines, rasterize_triangle, rasterize_segment):
    """The `x y id` lines for one case."""
    width, height, triangles, segments = parse_case(lines)
    out = []
    primitives = [(rasterize_triangle, t) for t in triangles]
    primitives += [(rasterize_segment, s) for s in segments]
    for index, (draw, vertices) in enumerate(primitives):
        if draw is None:
            raise ValueError("this rasterizer draws no line segments")
        for x, y in draw(*vertices, width, height):
            out.append(f"{x} {y} {index}")
    return out


def run(rasterize_triangle, rasterize_segment=None):
    """Answers check: one case from the file named on the command line,
    or, with no arguments, case after case from standard input."""
    if len(sys.argv) > 1:
        with open(sys.argv[1]) as f:
            out = answer(f.read().splitlines(), rasterize_triangle, rasterize_segment)
        sys.stdout.write("".join(line + "\n" for line in out))
        return
    case = []
    for line in sys.stdin:
        if line.strip() != "end":
            case.append(line)
            continue
        try:
            out = answer(case, rasterize_triangle, rasterize_segment)
            sys.stdout.write("".join(line + "\n" for line in out) + "end\n")
        except Exception as e:  # the case is reported with its input
            traceback.print_exc()  # shown by check under the message
            message = f"{type(e).__name__}: {e}".replace("\n", " ")
            sys.stdout.write(f"error {message}\n")
        sys.stdout.flush()
        case = []
