// Your rasterizer: write `rasterizeTriangle` (and `rasterizeSegment`).
//
// Check it, from the folder of this file:
//
//     rasterlab check --persistent --exec "node rasterizer.js"
//     rasterlab check --kind lines --convention pixel-index-left-to-right --persistent --exec "node rasterizer.js"
//
// As shipped, `rasterizeTriangle` is the course's rasterisation
// pseudocode: every pixel of the target, drawn when the barycentric
// coordinates of its centre are all between 0 and 1; `rasterizeSegment`
// is the direct evaluation of y = m x + b. Run the check: it says what the
// rules want instead, and why this is not it.
"use strict";

const { run } = require("./rasterlab_check");

// The implicit line equation of the line through a and b, at p: zero on
// the line, positive on one side, negative on the other.
function implicitLine(a, b, p) {
  return (a[1] - b[1]) * p[0] + (b[0] - a[0]) * p[1] + a[0] * b[1] - b[0] * a[1];
}

// The pixels [x, y] of the target whose centre is inside triangle abc.
//
// How check judges it: it snaps every vertex to 1/256 px first (a
// coordinate exactly halfway between two steps rounded to even; note that
// Math.round rounds halfway up, not to even), then decides each pixel
// centre with integer edge functions, and a centre exactly on an edge by
// the fill rule (--rule, top-left by default). To agree bit for bit, snap
// the same way and compute in integers (BigInt, or numbers while they stay
// below 2^53); floating point on the vertices as given differs on a few
// cases (the ties family, whose vertices lie exactly halfway). Under
// --snap none check snaps nothing and judges the vertices as given,
// exactly; its coordinates are then multiples of 1/256 px, where numbers
// are exact.
function rasterizeTriangle(a, b, c, width, height) {
  const fBCa = implicitLine(b, c, a);
  const fCAb = implicitLine(c, a, b);
  const fABc = implicitLine(a, b, c);
  const fragments = [];
  if (fBCa === 0) return fragments; // no area: no barycentric coordinates
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = [x + 0.5, y + 0.5];
      const alpha = implicitLine(b, c, p) / fBCa;
      const beta = implicitLine(c, a, p) / fCAb;
      const gamma = implicitLine(a, b, p) / fABc;
      if (alpha >= 0 && alpha <= 1 && beta >= 0 && beta <= 1 && gamma >= 0 && gamma <= 1) {
        fragments.push([x, y]);
      }
    }
  }
  return fragments;
}

// The pixels [x, y] of the line from pixel p0 to pixel p1 (whole numbers
// naming pixels): direct evaluation of y = m x + b in every column from
// the left end to the right end, the row nearest the line, a row exactly
// halfway going to the left end's side.
function rasterizeSegment(p0, p1, width, height) {
  let [[x0, y0], [x1, y1]] = [p0.map(Math.round), p1.map(Math.round)];
  if (x1 < x0 || (x1 === x0 && y1 < y0)) [[x0, y0], [x1, y1]] = [[x1, y1], [x0, y0]];
  const fragments = [];
  const onTarget = (x, y) => x >= 0 && x < width && y >= 0 && y < height;
  if (x0 === x1) {
    // vertical: no slope, every row between the ends
    for (let y = y0; y <= y1; y++) if (onTarget(x0, y)) fragments.push([x0, y]);
    return fragments;
  }
  const m = (y1 - y0) / (x1 - x0);
  const b = y0 - m * x0;
  for (let x = x0; x <= x1; x++) {
    const y = m * x + b;
    const row = m >= 0 ? Math.ceil(y - 0.5) : Math.floor(y + 0.5);
    if (onTarget(x, row)) fragments.push([x, row]);
  }
  return fragments;
}

run(rasterizeTriangle, rasterizeSegment);
