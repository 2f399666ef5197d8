"""A multisampling rasterizer for `rasterlab check --msaa N --persistent`.

    rasterlab check --msaa 4 --persistent \
        --exec "python3 examples/student/multisample.py {msaa}"

It reads case after case on its standard input (the `--persistent`
protocol: `# size WxH`, `# msaa N`, one triangle per line, then `end`)
and answers each with `x y id mask` lines, then `end`: bit i of a pixel's
mask is set when the triangle covers sample i of the standard N-sample
pattern. It decides each sample as the rules decide a pixel centre:
vertices snapped to 1/256 pixel, exact integer edge functions, and the
top-left rule for a sample exactly on an edge. So it passes.

Two classic mistakes can be asked for, to see the check name them:

    ... multisample.py {msaa} centre     every sample decided at the pixel
                                         centre (a full mask or none)
    ... multisample.py {msaa} mirrored   the pattern mirrored in y, as
                                         OpenGL's y-up sample positions
                                         are when used on a y-down screen
"""

import sys

# The standard patterns, in 1/16 pixel from the pixel centre, y down
# (Direct3D 11's standard multisample patterns, Vulkan's standard sample
# locations).
STANDARD = {
    1: [(0, 0)],
    2: [(4, 4), (-4, -4)],
    4: [(-2, -6), (6, -2), (-6, 2), (2, 6)],
    8: [(1, -3), (-1, 3), (5, 1), (-3, -5), (-5, 5), (-7, -1), (3, 7), (7, -7)],
    16: [(1, 1), (-1, -3), (-3, 2), (4, -1), (-5, -2), (2, 5), (5, 3), (3, -5),
         (-2, 6), (0, -7), (-4, -6), (-6, 4), (-8, 0), (7, -4), (6, 7), (-7, -8)],
}


def snap(v):
    """A coordinate in 1/256 pixel, rounded to even as the rules snap."""
    return round(v * 256)


def edge(a, b, p):
    """Twice the signed area of (a, b, p): which side of a -> b p is on."""
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


def owns_ties(a, b):
    """The top-left rule, for an edge a -> b of a triangle wound so that
    its inside has positive edge values: a top edge (horizontal, the
    inside below it) or a left edge owns the samples exactly on it."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    return (dy == 0 and dx > 0) or dy < 0


def masks(width, height, triangle, offsets):
    """(x, y, mask) for every pixel where the triangle covers a sample."""
    v = [(snap(triangle[i]), snap(triangle[i + 1])) for i in (0, 2, 4)]
    if edge(v[0], v[1], v[2]) < 0:
        v = [v[0], v[2], v[1]]
    elif edge(v[0], v[1], v[2]) == 0:
        return []
    edges = [(v[k], v[(k + 1) % 3]) for k in range(3)]
    out = []
    for y in range(height):
        for x in range(width):
            mask = 0
            for i, (dx, dy) in enumerate(offsets):
                p = (x * 256 + 128 + dx * 16, y * 256 + 128 + dy * 16)
                if all(edge(a, b, p) > 0 or (edge(a, b, p) == 0 and owns_ties(a, b))
                       for a, b in edges):
                    mask |= 1 << i
            if mask:
                out.append((x, y, mask))
    return out


def main():
    samples = int(sys.argv[1])
    mistake = sys.argv[2] if len(sys.argv) > 2 else None
    offsets = STANDARD[samples]
    if mistake == "mirrored":
        offsets = [(dx, -dy) for dx, dy in offsets]
    case = []
    for line in sys.stdin:
        line = line.strip()
        if line != "end":
            case.append(line)
            continue
        width = height = 0
        triangles = []
        for row in case:
            if row.startswith("# size "):
                width, height = map(int, row[len("# size "):].split("x"))
            elif row and not row.startswith("#"):
                triangles.append([float(w) for w in row.split()])
        answer = []
        for tid, triangle in enumerate(triangles):
            if mistake == "centre":
                full = (1 << samples) - 1
                answer += [(x, y, tid, full)
                           for x, y, _ in masks(width, height, triangle, [(0, 0)])]
            else:
                answer += [(x, y, tid, m) for x, y, m in masks(width, height, triangle, offsets)]
        print("".join(f"{x} {y} {tid} {m}\n" for x, y, tid, m in answer) + "end", flush=True)
        case = []


if __name__ == "__main__":
    main()
