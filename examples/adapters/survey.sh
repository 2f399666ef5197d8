#!/bin/sh
# The survey of rasterizers people use, in one command:
#
#     sh examples/adapters/survey.sh [CASES] [SEED]
#
# judges every subject of the check guide's survey (the Python adapters
# here, started once each with --persistent, and the crates and Mesa's
# OpenGL of examples/peer_adapters.rs) by `rasterlab check --rule any`,
# then the line drawers by `--kind lines --convention any`, on the same
# CASES (150) cases of seed SEED (0), and prints one Markdown table row a
# subject with the seconds it took. A subject whose library is missing
# says so in its row. Run from the repository's root; it builds rasterlab
# and the peer adapters first.
set -u
cases=${1:-150}
seed=${2:-0}
cargo build --release --quiet --bin rasterlab --example peer_adapters || exit 2
rasterlab=target/release/rasterlab
peers=target/release/examples/peer_adapters

row() { # KIND NAME COMMAND...: one table row
    kind=$1 name=$2
    shift 2
    # Lines one at a time (the Python line drawers are quick), triangles
    # two cases at once.
    judged="--rule any --jobs 2"
    [ "$kind" = lines ] && judged="--kind lines --convention any"
    start=$(date +%s.%N)
    # $judged is split into its words on purpose.
    json=$("$rasterlab" check $judged --cases "$cases" --seed "$seed" \
        --timeout 30 --format json --out "${TMPDIR:-/tmp}/rasterlab-survey" "$@" 2>/dev/null)
    end=$(date +%s.%N)
    printf '%s' "$json" | python3 examples/adapters/survey_row.py "$name" "$start" "$end"
}

echo "Triangles: rasterlab check --rule any, $cases cases of seed $seed"
echo
echo "| subject | follows | closest, cases agreeing | watertight | crack-free | seconds |"
echo "|---|---|---|---|---|---|"
a=examples/adapters
row triangles "GDAL through rasterio" --persistent --exec "python3 $a/rasterio_gdal.py"
row triangles "scikit-image draw.polygon" --persistent --exec "python3 $a/scikit_image.py"
row triangles "matplotlib Path.contains_points" --persistent --exec "python3 $a/matplotlib_path.py"
row triangles "Skia through skia-python" --persistent --exec "python3 $a/skia_path.py"
row triangles "Pillow ImageDraw.polygon" --persistent --exec "python3 $a/pillow.py"
row triangles "OpenCV fillPoly, shift=8" --persistent --exec "python3 $a/opencv.py"
row triangles "OpenCV fillPoly, whole pixels" --persistent --exec "python3 $a/opencv.py noshift"
row triangles "cairo fill (pycairo)" --persistent --exec "python3 $a/cairo_fill.py"
row triangles "OpenGL 3.3, Mesa's llvmpipe" --exec "$peers opengl {input} {width} {height}"
row triangles "tiny-skia 0.12" --exec "$peers tiny-skia {input} {width} {height}"
row triangles "euc 0.5" --exec "$peers euc {input} {width} {height}"
row triangles "embedded-graphics 0.8" --exec "$peers embedded-graphics {input} {width} {height}"
echo
echo "Lines: rasterlab check --kind lines --convention any, $cases cases of seed $seed"
echo
echo "| subject | follows | closest, cases agreeing | | | seconds |"
echo "|---|---|---|---|---|---|"
row lines "scikit-image draw.line" --persistent --exec "python3 $a/skimage_line.py"
row lines "Pillow ImageDraw.line" --persistent --exec "python3 $a/pillow_line.py"
row lines "OpenCV line, LINE_8" --persistent --exec "python3 $a/opencv_line.py"
row lines "OpenCV line, LINE_4" --persistent --exec "python3 $a/opencv_line.py --line-type 4"
row lines "OpenCV line, LINE_8, shift=8" --persistent --exec "python3 $a/opencv_line.py --shift 8"
row lines "OpenCV line, LINE_4, shift=8" --persistent --exec "python3 $a/opencv_line.py --line-type 4 --shift 8"
