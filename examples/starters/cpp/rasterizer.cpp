// Your rasterizer: write `rasterize_triangle` (and `rasterize_segment`).
//
// Build and check it, from the folder of this file:
//
//     g++ -O2 -std=c++17 -o rasterizer rasterizer.cpp
//     rasterlab check --persistent --exec "./rasterizer"
//     rasterlab check --kind lines --convention pixel-index-left-to-right --persistent --exec "./rasterizer"
//
// As shipped, `rasterize_triangle` is the course's rasterisation
// pseudocode: every pixel of the target, drawn when the barycentric
// coordinates of its centre are all between 0 and 1; `rasterize_segment`
// is the direct evaluation of y = m x + b. Run the check: it says what the
// rules want instead, and why this is not it.
#include <algorithm>
#include <cmath>
#include <utility>

#include "rasterlab_check.hpp"

using rasterlab_check::Pixel;
using rasterlab_check::Point;

// The implicit line equation of the line through a and b, at p: zero on
// the line, positive on one side, negative on the other.
static double implicit_line(Point a, Point b, Point p) {
    return (a.y - b.y) * p.x + (b.x - a.x) * p.y + a.x * b.y - b.x * a.y;
}

// The pixels of the target whose centre is inside triangle abc.
//
// How check judges it: it snaps every vertex to 1/256 px first (a
// coordinate exactly halfway between two steps rounded to even, as
// std::nearbyint(v * 256) / 256 does in the default rounding mode), then
// decides each pixel centre with integer edge functions, and a centre
// exactly on an edge by the fill rule (--rule, top-left by default). To
// agree bit for bit, snap the same way and compute in integers (64 bits);
// floating point on the vertices as given differs on a few cases (the
// ties family, whose vertices lie exactly halfway). Under --snap none
// check snaps nothing and judges the vertices as given, exactly; its
// coordinates are then multiples of 1/256 px, where doubles are exact.
std::vector<Pixel> rasterize_triangle(Point a, Point b, Point c, int width, int height) {
    double f_bc_a = implicit_line(b, c, a), f_ca_b = implicit_line(c, a, b),
           f_ab_c = implicit_line(a, b, c);
    std::vector<Pixel> fragments;
    if (f_bc_a == 0) return fragments;  // no area: no barycentric coordinates
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            Point p{x + 0.5, y + 0.5};
            double alpha = implicit_line(b, c, p) / f_bc_a;
            double beta = implicit_line(c, a, p) / f_ca_b;
            double gamma = implicit_line(a, b, p) / f_ab_c;
            if (alpha >= 0 && alpha <= 1 && beta >= 0 && beta <= 1 && gamma >= 0 && gamma <= 1)
                fragments.push_back({x, y});
        }
    }
    return fragments;
}

// The pixels of the line from pixel p0 to pixel p1 (whole numbers naming
// pixels): direct evaluation of y = m x + b in every column from the left
// end to the right end, the row nearest the line, a row exactly halfway
// going to the left end's side.
std::vector<Pixel> rasterize_segment(Point p0, Point p1, int width, int height) {
    long long x0 = std::llround(p0.x), y0 = std::llround(p0.y);
    long long x1 = std::llround(p1.x), y1 = std::llround(p1.y);
    if (std::make_pair(x1, y1) < std::make_pair(x0, y0)) {
        std::swap(x0, x1);
        std::swap(y0, y1);
    }
    std::vector<Pixel> fragments;
    if (x0 == x1) {  // vertical: no slope, every row between the ends
        for (long long y = y0; y <= y1; ++y)
            if (x0 >= 0 && x0 < width && y >= 0 && y < height) fragments.push_back({x0, y});
        return fragments;
    }
    double m = double(y1 - y0) / double(x1 - x0);
    double b = y0 - m * x0;
    for (long long x = x0; x <= x1; ++x) {
        double y = m * x + b;
        long long row = m >= 0 ? (long long)std::ceil(y - 0.5) : (long long)std::floor(y + 0.5);
        if (x >= 0 && x < width && row >= 0 && row < height) fragments.push_back({x, row});
    }
    return fragments;
}

int main(int argc, char** argv) {
    return rasterlab_check::run(argc, argv, rasterize_triangle, rasterize_segment);
}
