#!/bin/sh
# The README's screenshots, taken from this code with headless Chromium:
# the lab (two triangles under the inclusive rule; the course's
# depth-buffer example), a labelled grid picture from `explain --picture`,
# a `compare` report and a `check` report; and the grid pictures of the
# README's table, as `explain --picture` writes them.
#
#   sh docs/screenshots.sh        (needs chromium and python3)
set -eu
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=$PWD/target/release/rasterlab
tmp=$(mktemp -d)
lab=
trap '[ -n "$lab" ] && kill "$lab"; rm -rf "$tmp"' EXIT

shot() { # WIDTHxHEIGHT OUT.png URL
    chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --no-first-run --disable-background-networking --disable-component-update \
        --user-data-dir="$tmp/profile" --window-size="$(echo "$1" | tr x ,)" \
        --virtual-time-budget=5000 --screenshot="$2" "$3" 2>/dev/null
    echo "$2"
}
encode() { python3 -c 'import sys, urllib.parse; print(urllib.parse.quote(sys.argv[1], safe=""))' "$1"; }
backends='["naive","bbox","scanline","incremental","tiled"]'

# The lab: its page in a 1400 px window, the state in the URL.
"$bin" lab --port 0 >"$tmp/lab.txt" &
lab=$!
while ! grep -q http "$tmp/lab.txt"; do sleep 0.2; done
url=$(grep -o 'http://[^ ]*' "$tmp/lab.txt")
two=$(encode '{"preset":"two","kind":"triangles","width":12,"height":12,"triangles":[[[1,1],[11,1],[1,11]],[[11,1],[11,11],[1,11]]],"depths":[],"lines":[],"backends":'"$backends"',"rule":"inclusive","trace":"bbox"}')
shot 1400x1150 docs/lab.png "$url#$two"
depth=$(encode '{"preset":"depth","kind":"triangles","width":14,"height":9,"triangles":[[[2.75,3],[12.3359375,3],[1.9296875,6.9]],[[3.6,1],[6.8,1],[10,9]]],"depths":[0.5,0.8],"lines":[],"backends":'"$backends"',"rule":"top-left","trace":"depth-buffer"}')
shot 1400x1000 docs/lab-depth.png "$url#$depth"
kill "$lab"
lab=

# A labelled grid picture, its SVG drawn 1000 px wide.
"$bin" explain --backend bbox --size 11x9 --picture "$tmp/bbox.svg" 1 1 9 2 3 7 >/dev/null
size=$(sed -n 's/^<svg[^>]* width="\([0-9.]*\)" height="\([0-9.]*\)".*/\1 \2/p' "$tmp/bbox.svg")
height=$(echo "$size" | awk '{ printf "%d", 1000 * $2 / $1 + 0.999 }')
echo "<body style=\"margin:0\"><img src=\"bbox.svg\" style=\"width:1000px;display:block\">" >"$tmp/bbox.html"
shot "1000x$height" docs/grid-picture.png "file://$tmp/bbox.html"

# The pictures of the README's table, as `explain --picture` writes them.
"$bin" explain --backend bbox --size 11x9 --picture docs/bbox-grid.png 1 1 9 2 3 7 >/dev/null
"$bin" explain --backend tiled --size 32x24 --picture docs/tiled-grid.png 1 1 31 2 2 23 >/dev/null
"$bin" explain --backend wu --size 14x8 --picture docs/wu-grid.png 0 1 13 6 >/dev/null

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
