#!/bin/bash
# The plots as a person sees them: `tlsph plot` SVGs rendered to PNG by
# rsvg-convert (Debian: librsvg2-bin), then read back with the standard
# library (plot_check.py png): the PNG has the SVG's size, is not blank, each
# frame has curve ink, and the small series' colour spans its frame.  Skips
# (exit 77) when rsvg-convert is missing.
command -v rsvg-convert >/dev/null 2>&1 || {
    echo "SKIP: rsvg-convert missing (install librsvg2-bin: deploy/install-deps.sh)"; exit 77; }
. "$(cd "$(dirname "$0")" && pwd)/fake_common.sh"
PC=$top_srcdir/tests/client/plot_check.py

render() { # NAME: NAME.svg (the last `cl plot`'s) -> NAME.png
    rc_is 0 || return 1
    rsvg-convert -o "$TMP/$1.png" "$TMP/$1.svg" 2>"$TMP/rsvg.err" || { cat "$TMP/rsvg.err"; return 1; }
}
# kinetic energy (the first colour, #1f77b4) is 1e4 times smaller than the others
cl plot "$FID" kinetic_energy internal_energy external_work -o "$TMP/energy.svg" --title "Energies"
check "energies: rendered to PNG" render energy
check "energies PNG: size, not blank, every frame inked, kinetic energy not flat" \
    "$PY" "$PC" png "$TMP/energy.png" "$TMP/energy.svg" --colour '#1f77b4'
# reaction force: y (the second colour, #d62728) is 15 N beside 2e5 N
cl plot "$FID" groups/right/reaction_force -o "$TMP/force.svg"
check "force: rendered to PNG" render force
check "force PNG: size, not blank, every frame inked, the 15 N component not flat" \
    "$PY" "$PC" png "$TMP/force.png" "$TMP/force.svg" --colour '#d62728'
cl plot "$FID" kinetic_energy internal_energy --log -o "$TMP/log.svg"
check "log axis: rendered to PNG" render log
check "log PNG: size, not blank, every frame inked" "$PY" "$PC" png "$TMP/log.png" "$TMP/log.svg"
cl plot "$FID" groups/right/reaction_force:x --x groups/right/displacement:x -o "$TMP/fd.svg"
check "force-displacement: rendered to PNG" render fd
check "force-displacement PNG: size, not blank, the curve spans its frame" \
    "$PY" "$PC" png "$TMP/fd.png" "$TMP/fd.svg" --colour '#1f77b4'
# the check itself: a white picture of the same size is refused as blank
sed 's|<polyline[^>]*>.*</polyline>||; s|<text[^>]*>.*</text>||; s|<line [^>]*/>||' "$TMP/fd.svg" >"$TMP/blank.svg"
check "the check refuses a blank picture" bash -c "rsvg-convert -o '$TMP/blank.png' '$TMP/blank.svg' &&
    ! '$PY' '$PC' png '$TMP/blank.png' '$TMP/blank.svg'"
finish
