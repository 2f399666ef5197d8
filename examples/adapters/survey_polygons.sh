#!/bin/sh
# The polygon survey, in one command:
#
#     sh examples/adapters/survey_polygons.sh [CASES] [SEED]
#
# judges each polygon adapter here (`*_polygon.py`, given whole polygons,
# started once with --persistent) by `rasterlab check --kind polygons
# --keep-going` under --fill even-odd and under --fill nonzero, on the
# same CASES (150) cases of seed SEED (0), and prints one Markdown table
# row an adapter (survey_polygon_row.py says what each column counts)
# with the seconds both runs took. An adapter whose library is missing
# says so in its row. Run from the repository's root; it builds rasterlab
# first (into CARGO_TARGET_DIR, or target/).
set -u
cases=${1:-150}
seed=${2:-0}
cargo build --release --quiet --bin rasterlab || exit 2
rasterlab=${CARGO_TARGET_DIR:-target}/release/rasterlab
out=${TMPDIR:-/tmp}/rasterlab-polygon-survey
mkdir -p "$out"

row() { # NAME ADAPTER [ARGUMENTS]: one table row
    name=$1 adapter=$2
    shift 2
    start=$(date +%s.%N)
    for fill in even-odd nonzero; do
        "$rasterlab" check --kind polygons --fill "$fill" --keep-going \
            --cases "$cases" --seed "$seed" --timeout 30 --format json --out "$out/check" \
            --persistent --exec "python3 examples/adapters/$adapter {rule} $*" \
            >"$out/$fill.json" 2>/dev/null
    done
    end=$(date +%s.%N)
    python3 examples/adapters/survey_polygon_row.py "$name" "$(echo "$end - $start" | bc)" \
        "$out/even-odd.json" "$out/nonzero.json"
}

echo "Polygons: rasterlab check --kind polygons --keep-going, $cases cases of seed $seed"
echo
echo "| subject | \`--fill even-odd\`: passing; cause, cases it explains | \`--fill nonzero\` | follows: rule, convention, cases agreeing | seconds |"
echo "|---|---|---|---|---|"
row "Pillow \`ImageDraw.polygon\` (\`pillow_polygon.py\`)" pillow_polygon.py
row "OpenCV \`fillPoly\`, \`shift=8\` (\`opencv_polygon.py\`)" opencv_polygon.py
row "scikit-image \`draw.polygon\` (\`skimage_polygon.py\`)" skimage_polygon.py
row "matplotlib \`Path.contains_points\` (\`matplotlib_polygon.py\`)" matplotlib_polygon.py
row "cairo fill, \`ANTIALIAS_NONE\` (\`cairo_polygon.py\`)" cairo_polygon.py
row "GDAL (\`gdal_polygon.py\`)" gdal_polygon.py
row "Skia through skia-python, anti-alias off (\`skia_polygon.py\`)" skia_polygon.py
