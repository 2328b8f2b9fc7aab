#!/usr/bin/env bash
# Paper 001 §5.4, deep beams: examples/deep-beam-links.json (notch at mid-span,
# mode I) and examples/deep-beam-mixed-links.json (notch 75 mm from the left
# support, mixed mode) at several spacings, 1 thread each; one row per run of
# the table in docs/virtual-links.md (crack path by bench/deep_beam_path.py, its
# docstring states the definitions) and the SVG of the crack paths
# (bench/deep_beam_plot.py) in OUT_DIR/deep-beams.svg.
# usage: bench/deep_beams.sh [OUT_DIR]   (BUILD_DIR: the build, default build/)
#   SPACINGS="0.001 0.0005" (m; bench/deep_beam_scene.py writes the scenes: the
#   notch, supports and load patch stay the same boxes at 1 and 0.5 mm),
#   END (s, default the examples' 400e-6).
set -eu
. "$(dirname "$0")/common.sh"
out=${1:-$(mktemp -d "${TMPDIR:-/tmp}/deep_beams.XXXXXX")}
mkdir -p "$out"
echo "| case | spacing | crack angle (fit) | notch-to-load line | difference | mean offset | largest offset | top: offset from the load | ligament crossed | first broken link: from tip, time | 90 % crossed | crack particles | particles | steps | wall time | max balance / external work |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
plots=()
for c in "mode I:deep-beam-links:154" "mixed mode:deep-beam-mixed-links:102"; do
  title=${c%%:*}; rest=${c#*:}; name=${rest%%:*}; notch=${rest#*:}
  for s in ${SPACINGS:-0.001 0.0005}; do
    r=$out/$name-$s
    "$py" "$here/deep_beam_scene.py" "$top/examples/$name.json" "$s" "$r.json" ${END:-}
    "$run" "$r.json" -o "$r" --threads 1 >"$r.log" 2>&1 || true
    printf '| %s ' "$title"
    "$py" "$here/deep_beam_path.py" "$r" "$r.log" --notch "$notch" --row
    plots+=("$title, $(awk "BEGIN{print $s*1000}") mm=$r=$notch")
  done
done
"$py" "$here/deep_beam_plot.py" "$out/deep-beams.svg" "${plots[@]}"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "picture: $out/deep-beams.svg"
