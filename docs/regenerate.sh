#!/bin/sh
# Regenerates every picture and pasted output of README.md and docs/*.md
# from this code:
#
#   sh docs/regenerate.sh          the screenshots and grid pictures
#                                  (headless Chromium, python3), and the
#                                  output under every `$ ` command of a
#                                  `console` block, rewritten in place
#   sh docs/regenerate.sh --all    also the timing runs, minutes long: the
#                                  bench chart, the side_by_side table
#                                  (Mesa's llvmpipe; the Stanford models
#                                  in RASTERLAB_DATA), the survey of
#                                  docs/check.md (the Python packages of
#                                  .ci/run, Mesa) and its pictures
#
# An output is rewritten whole; where a page shows only part of it
# (lines of `...`, or a line cut short by `...`), the parts shown are
# rewritten from the same places of the new output. Each block that
# changed is named; a change only in times (a number followed by `ms`)
# is rewritten but not reported, since timings differ from run to run.
# `git diff` shows the rest. Prose that quotes a figure is not rewritten:
# after a timing run, update it from the new tables.
#
# The commands the pages show are run, without their outputs compared,
# by `cargo test --release --test docs_commands`.
set -eu
cd "$(dirname "$0")/.."
all=
[ "${1:-}" = "--all" ] && all=1

cargo build --release --quiet
target=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
bin=$target/release/rasterlab
export RASTERLAB_BIN="$bin"
tmp=$(mktemp -d)
lab=
trap '[ -n "$lab" ] && kill "$lab"; rm -rf "$tmp"' EXIT

# --- Screenshots and pictures -------------------------------------------

shot() { # WIDTHxHEIGHT OUT.png URL
    chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --no-first-run --disable-background-networking --disable-component-update \
        --user-data-dir="$tmp/profile" --window-size="$(echo "$1" | tr x ,)" \
        --virtual-time-budget=5000 --screenshot="$2" "$3" 2>/dev/null
    echo "$2"
}
encode() { python3 -c 'import sys, urllib.parse; print(urllib.parse.quote(sys.argv[1], safe=""))' "$1"; }
backends='["naive","bbox","scanline","incremental","tiled"]'

# The pictures of docs/teaching.md's table, as `explain --picture` writes them.
"$bin" explain --backend bbox --size 11x9 --picture docs/bbox-grid.png 1 1 9 2 3 7 >/dev/null
"$bin" explain --backend tiled --size 32x24 --picture docs/tiled-grid.png 1 1 31 2 2 23 >/dev/null
"$bin" explain --backend wu --size 14x8 --picture docs/wu-grid.png 0 1 13 6 >/dev/null
# A polygon whose hole runs the same way as its outer ring, under each rule.
for fill in even-odd nonzero; do
    "$bin" explain --backend edge-table --fill "$fill" --size 16x12 1 1 15 2 14 11 2 10 \
        --ring "5 4 11 4 10 8 6 8" --picture "docs/hole-$fill.png" >/dev/null
done
# The side-by-side pictures of docs/teaching.md: aliased and anti-aliased.
"$bin" render --scene fan --scale 10 --out docs/fan-aliased.png >/dev/null
"$bin" render --scene fan --scale 10 --msaa 4 --out docs/fan-msaa4.png >/dev/null
"$bin" render --scene fan --scale 10 --msaa 16 --out docs/fan-msaa16.png >/dev/null
"$bin" render assets/lines.txt --size 32x32 --backend bresenham --scale 10 --out docs/lines-bresenham.png >/dev/null
"$bin" render assets/lines.txt --size 32x32 --backend wu --scale 10 --out docs/lines-wu.png >/dev/null
# The compositing pictures of docs/teaching.md: mixing in encoded values,
# the order of transparent triangles, the cycle, the straight-alpha fringe.
"$bin" render --scene fan --scale 10 --msaa 4 --mix-in srgb --out docs/fan-msaa4-srgb.png >/dev/null
"$bin" render assets/lines.txt --size 32x32 --backend wu --scale 10 --mix-in srgb --out docs/lines-wu-srgb.png >/dev/null
"$bin" render --scene transparent --blend over-straight --scale 8 --out docs/transparent-listed.png >/dev/null
"$bin" render --scene transparent --blend over-straight --depth-test off --scale 8 --out docs/transparent-listed-no-depth.png >/dev/null
"$bin" render --scene transparent --blend over-straight --sort --scale 8 --out docs/transparent-sorted.png >/dev/null
"$bin" render --scene cycle --blend over-straight --depth-test off --sort --scale 6 --out docs/cycle-sorted.png >/dev/null
"$bin" render --scene cycle --scale 6 --out docs/cycle-opaque.png >/dev/null
cargo run --release --quiet --example alpha_fringe -- docs/alpha-fringe.png >/dev/null
# The floor of docs/teaching.md's texture section, filter by filter, the
# level each pixel reads, and the texture comparison's chart.
"$bin" render --scene floor --filter nearest --out docs/floor-nearest.png >/dev/null
"$bin" render --scene floor --out docs/floor-bilinear.png >/dev/null
"$bin" render --scene floor --mip nearest --derivatives quad --out docs/floor-nearest-level.png >/dev/null
"$bin" render --scene floor --mip linear --derivatives quad --out docs/floor-trilinear.png >/dev/null
"$bin" render --scene floor --mip linear --anisotropy 16 --derivatives quad --out docs/floor-anisotropic.png >/dev/null
"$bin" explain --backend texture --derivatives quad 160 120 --picture docs/floor-levels.png >/dev/null
"$bin" explain --backend bbox --derivatives quad --size 11x9 1 1 9 2 3 7 --picture docs/quads-grid.png >/dev/null
"$bin" compare --textures --samples 3 --out "$tmp/textures" >/dev/null
cp "$tmp/textures/textures.svg" docs/textures-chart.svg

# The screenshots, by headless Chromium.
if command -v chromium >/dev/null 2>&1; then
    # The lab: its page in a 1400 px window, the state in the URL (two
    # triangles under the inclusive rule; the course's depth-buffer example).
    "$bin" lab --port 0 >"$tmp/lab.txt" &
    lab=$!
    while ! grep -q http "$tmp/lab.txt"; do sleep 0.2; done
    url=$(grep -o 'http://[^ ]*' "$tmp/lab.txt")
    two=$(encode '{"preset":"two","kind":"triangles","width":12,"height":12,"triangles":[[[1,1],[11,1],[1,11]],[[11,1],[11,11],[1,11]]],"depths":[],"lines":[],"backends":'"$backends"',"rule":"inclusive","trace":"bbox"}')
    shot 1400x1150 docs/lab.png "$url#$two"
    depth=$(encode '{"preset":"depth","kind":"triangles","width":14,"height":9,"triangles":[[[2.75,3],[12.3359375,3],[1.9296875,6.9]],[[3.6,1],[6.8,1],[10,9]]],"depths":[0.5,0.8],"lines":[],"backends":'"$backends"',"rule":"top-left","trace":"depth-buffer"}')
    shot 1400x1000 docs/lab-depth.png "$url#$depth"
    # The texture controls: the receding textured triangle, trilinear,
    # quad derivatives, its level map and helper pixels.
    textured=$(encode '{"preset":"textured","kind":"triangles","width":32,"height":32,"triangles":[[[1,1],[31,3],[3,31]]],"depths":[],"lines":[],"backends":["bbox"],"rule":"top-left","trace":"bbox","texture":{"filter":"bilinear","levels":"linear","derivatives":"quad","anisotropy":1,"anisotropic":"probes","repeats":1,"far":4}}')
    shot 1400x1400 docs/lab-texture.png "$url#$textured"
    kill "$lab"
    lab=

    # A labelled grid picture, its SVG drawn 1000 px wide.
    "$bin" explain --backend bbox --size 11x9 --picture "$tmp/bbox.svg" 1 1 9 2 3 7 >/dev/null
    size=$(sed -n 's/^<svg[^>]* width="\([0-9.]*\)" height="\([0-9.]*\)".*/\1 \2/p' "$tmp/bbox.svg")
    height=$(echo "$size" | awk '{ printf "%d", 1000 * $2 / $1 + 0.999 }')
    echo "<body style=\"margin:0\"><img src=\"bbox.svg\" style=\"width:1000px;display:block\">" >"$tmp/bbox.html"
    shot "1000x$height" docs/grid-picture.png "file://$tmp/bbox.html"

    # A compare report.
    "$bin" compare assets/polygon.txt --size 32x32 --out "$tmp/report" >/dev/null
    shot 1280x1500 docs/compare.png "file://$tmp/report/index.html"

    # A check report: the student's rasterizer of examples/student, checked
    # for watertightness (it fails: exit status 1), run as a student runs it.
    mkdir "$tmp/student"
    ln -s "$PWD/examples" "$tmp/student/examples"
    (cd "$tmp/student" && PATH="$(dirname "$bin"):$PATH" rasterlab check --rule watertight \
        --exec "python3 examples/student/rasterizer.py {input} {width} {height}" >/dev/null || true)
    shot 1280x1000 docs/check-report.png "file://$tmp/student/check-output/report.html"
else
    echo "chromium not found: the screenshots (docs/lab.png, lab-depth.png, lab-texture.png, grid-picture.png, compare.png, check-report.png) are kept"
fi

# The full dragon of the README's first picture, where the data is.
data=${RASTERLAB_DATA:-../shared/data}
if [ -f "$data/dragon_vrip.ply.gz" ]; then
    "$bin" render "$data/dragon_vrip.ply.gz" --size 960x540 --azimuth 30 --zoom 1.3 --out docs/dragon.png
else
    echo "docs/dragon.png kept: dragon_vrip.ply.gz is not in $data (set RASTERLAB_DATA)"
fi

# --- The outputs under the pages' console commands ----------------------

python3 - <<'PYTHON'
import difflib, glob, os, re, subprocess, tempfile

BIN = os.environ["RASTERLAB_BIN"]
# Commands whose output is not regenerated here, by their start.
NOT_RUN = ("cargo install",)

def run_all(commands):
    """Runs a block's commands in order in one fresh folder; their outputs."""
    with tempfile.TemporaryDirectory() as d:
        for name in ("assets", "examples"):
            os.symlink(os.path.abspath(name), os.path.join(d, name))
        env = dict(os.environ, PATH=os.path.dirname(BIN) + os.pathsep + os.environ["PATH"])
        outs = []
        for c in commands:
            if c.startswith(NOT_RUN):
                outs.append(None)
                continue
            c = re.sub(r"^cargo run --release -- ", "rasterlab ", c)
            p = subprocess.run(["sh", "-c", c + " 2>&1"], cwd=d, env=env,
                               capture_output=True, text=True, timeout=600)
            outs.append(p.stdout.rstrip("\n").split("\n") if p.stdout.strip() else [])
        return outs

def fill(shown, new):
    """The lines `shown` with each part rewritten from `new`: parts split
    by `...` lines, each found at its place in the new output."""
    if not any(l.strip() == "..." or l.endswith(": ...") for l in shown):
        return new
    parts, part = [], []
    for l in shown:
        if l.strip() == "...":
            parts.append(part); parts.append(None); part = []
        else:
            part.append(l)
    parts.append(part)
    out, at = [], 0
    for i, part in enumerate(parts):
        if part is None:
            out.append(next(l for l in shown if l.strip() == "..."))
            continue
        if not part:
            continue
        if i > 0 or at > 0:
            # The new line most like the part's first, from here on.
            scores = [difflib.SequenceMatcher(None, part[0], l).ratio() for l in new[at:]]
            if scores:
                at += max(range(len(scores)), key=scores.__getitem__)
        for l in part:
            n = new[at] if at < len(new) else l
            if l.endswith(": ..."):
                # A line the page cuts short stays cut, as long.
                n = l if n.startswith(l[:-3]) else n[: len(l) - 3] + "..."
            out.append(n)
            at += 1
    return out

TIME = re.compile(r"\d+(\.\d+)?\s*ms")
for page in ["README.md"] + sorted(glob.glob("docs/*.md")):
    lines = open(page).read().split("\n")
    out, i, changed = [], 0, []
    while i < len(lines):
        out.append(lines[i])
        if lines[i] != "```console":
            i += 1
            continue
        j = lines.index("```", i + 1)
        block = lines[i + 1 : j]
        cmds = [(k, l[2:]) for k, l in enumerate(block) if l.startswith("$ ")]
        outs = run_all([c for _, c in cmds])
        new_block = []
        for n, (k, c) in enumerate(cmds):
            end = cmds[n + 1][0] if n + 1 < len(cmds) else len(block)
            shown = block[k + 1 : end]
            trailing = []
            while shown and shown[-1] == "":
                trailing.append(""); shown = shown[:-1]
            new_block.append(block[k])
            new_block += shown if outs[n] is None else fill(shown, outs[n])
            new_block += trailing
        if TIME.sub("ms", "\n".join(new_block)) != TIME.sub("ms", "\n".join(block)):
            changed.append(f"{page}:{i + 1}")
        out += new_block + ["```"]
        i = j + 1
    open(page, "w").write("\n".join(out))
    for c in changed:
        print(f"{c}: output changed (git diff shows how)")
PYTHON

# --- The timing runs (--all) --------------------------------------------

if [ -n "$all" ]; then
    # The bench chart of docs/benchmarks.md, on one thread.
    "$bin" --threads 1 bench --samples 5 --out "$tmp/bench"
    cp "$tmp/bench/bench.png" docs/bench.png
    echo docs/bench.png

    # The anti-aliasing comparison's chart of docs/benchmarks.md (its
    # tables are pasted by hand from the same run's output).
    mkdir -p bench-output
    cargo bench --bench antialias -- --rounds 5 | tee bench-output/antialias.txt
    cp bench-output/antialias-delaunay.svg docs/antialias-delaunay.svg
    echo "docs/antialias-delaunay.svg: update the tables of docs/benchmarks.md from bench-output/antialias.txt"

    # The side_by_side ratio table: the pasted block of docs/benchmarks.md
    # that starts with the command is replaced by the run's closing lines.
    cargo bench --bench side_by_side -- --rounds 10 | tee "$tmp/side_by_side.txt"
    python3 - "$tmp/side_by_side.txt" <<'PYTHON'
import sys
run = open(sys.argv[1]).read().rstrip("\n").split("\n")
page = "docs/benchmarks.md"
lines = open(page).read().split("\n")
start = lines.index("cargo bench --bench side_by_side -- --rounds 10")
end = lines.index("```", start)
tail = run[next(i for i, l in enumerate(run) if l.startswith("commit ")):]
lines[start + 1 : end] = tail
open(page, "w").write("\n".join(lines))
print(f"{page}: the side_by_side table rewritten; update the prose that quotes it")
PYTHON

    # The survey of docs/check.md: every subject's row, in one command,
    # then each shrunk failure's picture that a page shows.
    sh examples/adapters/survey.sh
    mkdir "$tmp/survey"
    ln -s "$PWD/examples" "$tmp/survey/examples"
    peers=$target/release/examples/peer_adapters
    picture() { # NAME CHECK-ARGS...: the shrunk failure's picture of docs/survey-NAME.svg
        rm -rf "$tmp/survey/check-output"
        name=$1
        shift
        (cd "$tmp/survey" && "$bin" check --rule any --jobs 2 --cases 150 --timeout 30 "$@" >/dev/null) || true
        if [ -f "docs/survey-$name.svg" ] && [ -f "$tmp/survey/check-output/counterexample.svg" ]; then
            cp "$tmp/survey/check-output/counterexample.svg" "docs/survey-$name.svg"
            echo "docs/survey-$name.svg"
        fi
    }
    for adapter in rasterio_gdal scikit_image matplotlib_path skia_path pillow opencv; do
        picture "$adapter" --persistent --exec "python3 examples/adapters/$adapter.py"
    done
    picture opencv-noshift --persistent --exec "python3 examples/adapters/opencv.py noshift"
    for peer in opengl tiny-skia euc embedded-graphics; do
        picture "$peer" --exec "$peers $peer {input} {width} {height}"
    done
    # The polygon fillers' survey of docs/check.md, in one command.
    sh examples/adapters/survey_polygons.sh
    echo "the survey's tables are above: update docs/check.md's tables from them"
fi
