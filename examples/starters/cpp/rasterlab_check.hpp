// The `rasterlab check` protocol for a rasterizer written in C++: one
// header, no dependency beyond the standard library (C++17).
//
// Define your functions and hand them to `rasterlab_check::run`:
//
//     int main(int argc, char** argv) {
//         return rasterlab_check::run(argc, argv, rasterize_triangle, rasterize_segment);
//     }
//
// It reads the cases, calls your functions and prints the fragments, in
// either of check's two ways:
//
//     rasterlab check --exec "./rasterizer {input} {width} {height}"
//         started once per case, the case in the file {input};
//     rasterlab check --persistent --exec "./rasterizer"
//         started once, the cases one after another on standard input.
//
// A case is a target size and primitives in screen coordinates: pixels, x
// right, y down, pixel (i, j) covering [i, i+1) x [j, j+1), its centre at
// (i + 0.5, j + 0.5). Your functions return the pixels they draw; this
// header numbers them by primitive and prints `x y id` lines.
#pragma once

#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rasterlab_check {

struct Point {
    double x, y;
};

struct Pixel {
    long long x, y;
};

using TriangleFn = std::function<std::vector<Pixel>(Point, Point, Point, int, int)>;
using SegmentFn = std::function<std::vector<Pixel>(Point, Point, int, int)>;

// The `x y id` lines of one case, its lines given.
inline std::string answer(const std::vector<std::string>& lines, const TriangleFn& triangle,
                          const SegmentFn& segment) {
    int width = -1, height = -1;
    std::vector<std::vector<double>> primitives;
    for (const std::string& line : lines) {
        if (line.rfind("# size ", 0) == 0) {
            if (std::sscanf(line.c_str(), "# size %dx%d", &width, &height) != 2)
                throw std::runtime_error("a malformed size line: " + line);
            continue;
        }
        std::string text = line.substr(0, line.find('#'));
        std::istringstream words(text);
        std::vector<double> v;
        double d;
        while (words >> d) v.push_back(d);
        if (v.empty()) continue;
        if (v.size() != 6 && v.size() != 4)
            throw std::runtime_error("expected 6 or 4 numbers a line: " + line);
        primitives.push_back(v);
    }
    if (width < 0) throw std::runtime_error("the case has no `# size WxH` line");
    std::ostringstream out;
    for (size_t id = 0; id < primitives.size(); ++id) {
        const std::vector<double>& v = primitives[id];
        std::vector<Pixel> drawn;
        if (v.size() == 6) {
            drawn = triangle({v[0], v[1]}, {v[2], v[3]}, {v[4], v[5]}, width, height);
        } else {
            if (!segment) throw std::runtime_error("this rasterizer draws no line segments");
            drawn = segment({v[0], v[1]}, {v[2], v[3]}, width, height);
        }
        for (const Pixel& p : drawn) out << p.x << ' ' << p.y << ' ' << id << '\n';
    }
    return out.str();
}

// Answers check: one case from the file named on the command line, or,
// with no arguments, case after case from standard input. Returns the
// exit status.
inline int run(int argc, char** argv, const TriangleFn& triangle,
               const SegmentFn& segment = nullptr) {
    std::vector<std::string> lines;
    std::string line;
    if (argc > 1) {
        std::ifstream file(argv[1]);
        if (!file) {
            std::cerr << "cannot read " << argv[1] << '\n';
            return 1;
        }
        while (std::getline(file, line)) lines.push_back(line);
        try {
            std::cout << answer(lines, triangle, segment);
        } catch (const std::exception& e) {
            std::cerr << e.what() << '\n';
            return 1;
        }
        return 0;
    }
    while (std::getline(std::cin, line)) {
        if (line != "end") {
            lines.push_back(line);
            continue;
        }
        try {
            std::cout << answer(lines, triangle, segment) << "end\n";
        } catch (const std::exception& e) {
            std::string message = e.what();
            for (char& c : message)
                if (c == '\n') c = ' ';
            std::cout << "error " << message << '\n';
        }
        std::cout.flush();
        lines.clear();
    }
    return 0;
}

}  // namespace rasterlab_check
