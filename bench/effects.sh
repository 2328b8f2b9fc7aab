#!/usr/bin/env bash
# The effects table (issue 18): every effect switched on one at a time on the
# same scene, with the modules it adds, its bytes per particle and its time
# per particle-step against the scene without it (bench/effects.py has the
# scene and the variants); then every example for the same number of steps,
# with its modules, bytes per particle and time per particle-step.
#   usage: bench/effects.sh [ROUNDS] [STEPS]
set -euo pipefail
. "$(dirname "$0")/common.sh"
"$py" "$here/effects.py" "$run" --rounds "${1:-3}" --steps "${2:-300}" --scenes "$top/examples" \
  --scenes "$top/tests/hard"
