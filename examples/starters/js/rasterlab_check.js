// The `rasterlab check` protocol for a rasterizer written in JavaScript
// (Node, no package needed).
//
// Hand your functions to `run`:
//
//     require("./rasterlab_check").run(rasterizeTriangle, rasterizeSegment);
//
// It reads the cases, calls your functions and prints the fragments, in
// either of check's two ways:
//
//     rasterlab check --exec "node rasterizer.js {input} {width} {height}"
//         started once per case, the case in the file {input};
//     rasterlab check --persistent --exec "node rasterizer.js"
//         started once, the cases one after another on standard input.
//
// A case is a target size and primitives in screen coordinates: pixels, x
// right, y down, pixel (i, j) covering [i, i+1) x [j, j+1), its centre at
// (i + 0.5, j + 0.5). A point is [x, y]. Your functions return the pixels
// they draw as [x, y] pairs; this module numbers them by primitive and
// prints `x y id` lines.
"use strict";

const fs = require("fs");
const readline = require("readline");

// The `x y id` lines of one case, its lines given.
function answer(lines, rasterizeTriangle, rasterizeSegment) {
  let width = null;
  let height = null;
  const primitives = [];
  for (const line of lines) {
    const size = /^# size (\d+)x(\d+)/.exec(line.trim());
    if (size) {
      width = Number(size[1]);
      height = Number(size[2]);
      continue;
    }
    const text = line.split("#")[0].trim();
    if (!text) continue;
    const v = text.split(/\s+/).map(Number);
    if ((v.length !== 6 && v.length !== 4) || v.some(Number.isNaN)) {
      throw new Error(`expected 6 or 4 numbers a line: ${text}`);
    }
    primitives.push(v);
  }
  if (width === null) throw new Error("the case has no `# size WxH` line");
  const out = [];
  primitives.forEach((v, id) => {
    let drawn;
    if (v.length === 6) {
      drawn = rasterizeTriangle([v[0], v[1]], [v[2], v[3]], [v[4], v[5]], width, height);
    } else {
      if (!rasterizeSegment) throw new Error("this rasterizer draws no line segments");
      drawn = rasterizeSegment([v[0], v[1]], [v[2], v[3]], width, height);
    }
    for (const [x, y] of drawn) out.push(`${x} ${y} ${id}\n`);
  });
  return out.join("");
}

// Answers check: one case from the file named on the command line, or,
// with no arguments, case after case from standard input.
function run(rasterizeTriangle, rasterizeSegment = null) {
  if (process.argv.length > 2) {
    const lines = fs.readFileSync(process.argv[2], "utf8").split("\n");
    process.stdout.write(answer(lines, rasterizeTriangle, rasterizeSegment));
    return;
  }
  let lines = [];
  const input = readline.createInterface({ input: process.stdin, terminal: false });
  input.on("line", (line) => {
    if (line.trim() !== "end") {
      lines.push(line);
      return;
    }
    let reply;
    try {
      reply = answer(lines, rasterizeTriangle, rasterizeSegment) + "end\n";
    } catch (e) {
      reply = `error ${String(e.message).replace(/\n/g, " ")}\n`;
    }
    lines = [];
    process.stdout.write(reply);
  });
}

module.exports = { answer, run };
