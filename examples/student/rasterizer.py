#!/usr/bin/env python3
"""A rasterizer as a student might write it for an assignment.

    python3 rasterizer.py INPUT WIDTH HEIGHT

INPUT holds one triangle per line, `x0 y0 x1 y1 x2 y2` in screen pixels
(`#` lines are comments). For every pixel of the bounding box it computes
the barycentric coordinates of the pixel centre in floating point and draws
the pixel when all three are >= 0. It prints one fragment per line,
`x y t`, where t is the triangle's index.

`rasterlab check --exec "python3 examples/student/rasterizer.py {input}
{width} {height}"` finds what is wrong with it.
"""

import math
import sys


def edge(ax, ay, bx, by, px, py):
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax)


def main():
    path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    triangles = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                triangles.append([float(v) for v in line.split()])
    out = []
    for t, (x0, y0, x1, y1, x2, y2) in enumerate(triangles):
        area = edge(x0, y0, x1, y1, x2, y2)
        if area == 0:
            continue
        xmin = max(0, math.floor(min(x0, x1, x2)))
        xmax = min(width - 1, math.ceil(max(x0, x1, x2)))
        ymin = max(0, math.floor(min(y0, y1, y2)))
        ymax = min(height - 1, math.ceil(max(y0, y1, y2)))
        for y in range(ymin, ymax + 1):
            for x in range(xmin, xmax + 1):
                px, py = x + 0.5, y + 0.5
                w0 = edge(x1, y1, x2, y2, px, py) / area
                w1 = edge(x2, y2, x0, y0, px, py) / area
                w2 = edge(x0, y0, x1, y1, px, py) / area
                if w0 >= 0 and w1 >= 0 and w2 >= 0:
                    out.append(f"{x} {y} {t}")
    print("\n".join(out))


if __name__ == "__main__":
    main()
