#!/usr/bin/env python3
"""cairo (through pycairo) filling triangles anti-aliased, as the
anti-aliasing benchmark compares it (`cargo bench --bench antialias`).

Standard input: a line `WIDTH HEIGHT ROUNDS`, then one triangle a line,
`x0 y0 x1 y1 x2 y2` in pixels (y down, pixel (i, j) covering
[i, i+1) x [j, j+1), as cairo's own convention is).

Standard output:

* `time NS`: the median over ROUNDS of the time to fill the whole mesh,
  each triangle a path filled over the others with cairo's default
  anti-aliasing, on an A8 surface, in nanoseconds;
* `t ID X Y ALPHA`: triangle ID's coverage of pixel (X, Y), filled alone,
  ALPHA in 1..255 (pixels it leaves at 0 are not written);
* `p X Y ALPHA`: the mesh filled, each triangle over the others (shared
  edges blend: conflation), for each pixel not at 0.
"""

import statistics
import sys
import time

import cairo
import numpy


def fill(ctx, triangles):
    for t in triangles:
        ctx.move_to(t[0], t[1])
        ctx.line_to(t[2], t[3])
        ctx.line_to(t[4], t[5])
        ctx.close_path()
        ctx.fill()


def alpha(surface, width, height):
    surface.flush()
    stride = surface.get_stride()
    data = numpy.frombuffer(surface.get_data(), numpy.uint8).reshape(height, stride)
    return data[:, :width]


def new_surface(width, height):
    surface = cairo.ImageSurface(cairo.FORMAT_A8, width, height)
    ctx = cairo.Context(surface)
    ctx.set_antialias(cairo.ANTIALIAS_DEFAULT)
    ctx.set_fill_rule(cairo.FILL_RULE_WINDING)
    return surface, ctx


def main():
    lines = sys.stdin.read().split("\n")
    width, height, rounds = (int(v) for v in lines[0].split())
    triangles = [[float(v) for v in line.split()] for line in lines[1:] if line.strip()]
    out = []
    times = []
    for _ in range(rounds):
        surface, ctx = new_surface(width, height)
        start = time.perf_counter_ns()
        fill(ctx, triangles)
        surface.flush()
        times.append(time.perf_counter_ns() - start)
    out.append(f"time {statistics.median(times)}")
    for i, t in enumerate(triangles):
        xs, ys = t[0::2], t[1::2]
        x0 = max(int(min(xs)) - 1, 0)
        y0 = max(int(min(ys)) - 1, 0)
        x1 = min(int(max(xs)) + 2, width)
        y1 = min(int(max(ys)) + 2, height)
        if x1 <= x0 or y1 <= y0:
            continue
        w, h = x1 - x0, y1 - y0
        surface, ctx = new_surface(w, h)
        ctx.translate(-x0, -y0)
        fill(ctx, [t])
        a = alpha(surface, w, h)
        for y, x in zip(*numpy.nonzero(a)):
            out.append(f"t {i} {x + x0} {y + y0} {a[y, x]}")
    surface, ctx = new_surface(width, height)
    fill(ctx, triangles)
    a = alpha(surface, width, height)
    for y, x in zip(*numpy.nonzero(a)):
        out.append(f"p {x} {y} {a[y, x]}")
    sys.stdout.write("\n".join(out) + "\n")


main()
