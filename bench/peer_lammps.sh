#!/usr/bin/env bash
# tlsph against LAMMPS MACHDYN (pair_style smd/tlsph) on the same copper Taylor
# bar (examples/taylor-bar.json, 190 m/s, to 80 us): same particles (LAMMPS
# reads tlsph's own lattice), spacing, kernel support (2.01 spacings),
# Johnson-Cook constants, Mie-Grueneisen EOS and rigid anvil; what cannot be
# the same is listed in bench/peer_lammps.py.  Runs the two codes interleaved,
# PAIRS times, one core each, and prints per run: particle-steps/s (process
# wall clock: setup included, for both), steps to 80 us, wall time to solution,
# peak RSS per particle (/usr/bin/time -v), and the medians with the ratio
# LAMMPS / tlsph; then the bar's final length and foot diameter of both with
# the same measure (bench/taylor_metrics.py).
#
# LAMMPS: $LAMMPS_BIN if set; else $LAMMPS_DIR/build/lmp (default
# /tmp/lammps-machdyn), built there once from Debian's source package
# (apt-get source lammps; as root the script adds a deb-src line and installs
# libeigen3-dev; cmake with MACHDYN only, nice -n 10, -j2: 30 min on the
# 2-core VM while other jobs ran).  Serial (MPI stubs) where MPI headers are
# missing (openmpi-bin without libopenmpi-dev).
# PEER_BUILD=0 never builds.  Without a binary it runs tlsph alone and says so.
#
# usage: bench/peer_lammps.sh [SPACING_M] [PAIRS]   (default 0.0006 = 5 334
#        particles, 3 pairs; THREADS=n for tlsph's threads, default 1;
#        END=seconds for another end time than the example's 80 us: LAMMPS
#        stops at the tlsph scene's end, so both solve the same interval)
set -euo pipefail
. "$(dirname "$0")/common.sh"
spacing=${1:-0.0006}
pairs=${2:-3}
threads=${THREADS:-1}
scratch_dir
# LAMMPS build (sourced into peer_lammps.sh)
lammps_dir=${LAMMPS_DIR:-/tmp/lammps-machdyn}
build_lammps() {
  local bin="$lammps_dir/build/lmp"
  [ -x "$bin" ] && { echo "$bin"; return 0; }
  if [ "$(id -u)" = 0 ]; then
    # deb-src lines for Debian's own archive (idempotent: one file, written once)
    local src=/etc/apt/sources.list.d/tlsph-deb-src.sources
    if [ ! -e "$src" ] && ! grep -rqs '^Types:.*deb-src\|^deb-src' /etc/apt/sources.list /etc/apt/sources.list.d/; then
      printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: %s\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
        "$(. /etc/os-release; echo "$VERSION_CODENAME")" >"$src"
      apt-get update -qq >&2
    fi
    dpkg -s libeigen3-dev >/dev/null 2>&1 || apt-get install -y -qq libeigen3-dev >&2
  fi
  command -v cmake >/dev/null && [ -d /usr/include/eigen3 ] ||
    { echo "peer_lammps: needs cmake and libeigen3-dev (run as root once, or give LAMMPS_BIN)" >&2; return 1; }
  mkdir -p "$lammps_dir"
  if [ ! -d "$lammps_dir/tree" ]; then
    (cd "$lammps_dir" && apt-get source -qq lammps >&2) || return 1
    local d; d=$(find "$lammps_dir" -mindepth 1 -maxdepth 1 -type d -name 'lammps-*' | head -1)
    [ -n "$d" ] || { echo "peer_lammps: apt-get source lammps gave no tree" >&2; return 1; }
    ln -sfn "$d" "$lammps_dir/tree"
  fi
  # MACHDYN only (all packages are off by default in this version); MPI for
  # the 2-rank runs; no image/movie/compression libraries.
  # (MPI only where its headers are installed: openmpi-bin alone has none).
  local mpi=no inc
  inc=$(mpicxx -showme:incdirs 2>/dev/null | awk '{print $1}')
  [ -n "$inc" ] && [ -e "$inc/mpi.h" ] && mpi=yes
  nice -n 10 cmake -S "$lammps_dir/tree/cmake" -B "$lammps_dir/build" -D CMAKE_BUILD_TYPE=Release \
    -D PKG_MACHDYN=on -D DOWNLOAD_EIGEN3=no -D BUILD_MPI=$mpi $( [ $mpi = no ] && echo -D CMAKE_DISABLE_FIND_PACKAGE_MPI=TRUE) -D BUILD_OMP=no \
    -D WITH_JPEG=no -D WITH_PNG=no -D WITH_GZIP=no -D WITH_FFMPEG=no -D BUILD_TOOLS=no >&2 || return 1
  nice -n 10 cmake --build "$lammps_dir/build" -j2 >&2 || return 1
  [ -x "$bin" ] && echo "$bin"
}

lmp=${LAMMPS_BIN:-}
if [ -z "$lmp" ]; then
  if [ -x "$lammps_dir/build/lmp" ]; then
    lmp=$lammps_dir/build/lmp
  elif [ "${PEER_BUILD:-1}" != 0 ]; then
    echo "building LAMMPS with MACHDYN in $lammps_dir (once) ..." >&2
    lmp=$(build_lammps) || lmp=
  fi
fi
[ -n "$lmp" ] && [ -x "$lmp" ] || {
  echo "NOTE: no LAMMPS binary (set LAMMPS_BIN, or let the script build one): running tlsph alone"
  lmp=
}

# wall (s) and peak RSS (kB) of a /usr/bin/time -v report
timev() {
  "$py" - "$1" <<'PY'
import sys
w = m = None
for l in open(sys.argv[1]):
    if "Elapsed (wall clock)" in l:
        t = l.rsplit(" ", 1)[1].strip().split(":")
        w = sum(float(p) * 60 ** i for i, p in enumerate(reversed(t)))
    if "Maximum resident set size" in l:
        m = int(l.rsplit(" ", 1)[1])
print(w, m)
PY
}

"$py" "$here/peer_lammps.py" scene "$spacing" >"$out/s.json"
if [ -n "${END:-}" ]; then
  "$py" - "$out/s.json" "$END" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = float(sys.argv[2])
json.dump(s, open(sys.argv[1], "w"), indent=1)
PY
fi
t_end_us=$("$py" -c 'import json,sys; print("%g" % (json.load(open(sys.argv[1]))["time"]["end"] * 1e6))' "$out/s.json")
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg); tlsph threads: $threads; LAMMPS: ${lmp:-none} (1 rank)"
echo
echo "| pair | code | particles | steps to $t_end_us us | wall (s) | particle-steps/s | peak RSS/particle (B) | load |"
echo "|---:|---|---:|---:|---:|---:|---:|---|"
: >"$out/rows"
for i in $(seq 1 "$pairs"); do
  rm -rf "$out/t"
  /usr/bin/time -v "$run" "$out/s.json" -o "$out/t" --threads "$threads" --quiet 2>"$out/time.t" >/dev/null
  read -r w m < <(timev "$out/time.t")
  read -r n steps < <("$py" "$here/taylor_metrics.py" "$out/t" --json |
    "$py" -c 'import json,sys; m=json.load(sys.stdin); print(m["particles"], m["steps"])')
  echo "tlsph $n $steps $w $m" >>"$out/rows"
  printf '| %d | tlsph | %d | %d | %.1f | %.3g | %.0f | %s |\n' "$i" "$n" "$steps" "$w" \
    "$(echo "$n * $steps / $w" | bc -l)" "$(echo "$m * 1024 / $n" | bc -l)" "$(cut -d' ' -f1 /proc/loadavg)"
  [ "$i" = 1 ] && "$py" "$here/taylor_metrics.py" "$out/t" --json >"$out/shape.t"
  [ -n "$lmp" ] || continue
  rm -rf "$out/l"; mkdir -p "$out/l"
  "$py" "$here/peer_lammps.py" lammps "$out/t" "$out/l"
  (cd "$out/l" && /usr/bin/time -v "$lmp" -in in.taylor -log log.lammps -screen none 2>"$out/time.l" >/dev/null) ||
    { echo "LAMMPS failed: tail of its log:"; tail -20 "$out/l/log.lammps"; exit 1; }
  read -r w m < <(timev "$out/time.l")
  lsteps=$(awk '/^PEER_END/ {print $3}' "$out/l/log.lammps")
  echo "lammps $n $lsteps $w $m" >>"$out/rows"
  printf '| %d | LAMMPS | %d | %d | %.1f | %.3g | %.0f | %s |\n' "$i" "$n" "$lsteps" "$w" \
    "$(echo "$n * $lsteps / $w" | bc -l)" "$(echo "$m * 1024 / $n" | bc -l)" "$(cut -d' ' -f1 /proc/loadavg)"
  [ "$i" = 1 ] && "$py" "$here/peer_lammps.py" measure-lammps "$out/l/final.dump" "$spacing" >"$out/shape.l"
done

echo
"$py" - "$out" <<'PY'
import json, os, statistics, sys
out = sys.argv[1]
rows = {}
for l in open(os.path.join(out, "rows")):
    code, n, steps, w, m = l.split()
    rows.setdefault(code, []).append((int(n), int(steps), float(w), int(m)))
med = {c: (r[0][0], statistics.median(x[1] for x in r), statistics.median(x[2] for x in r),
           statistics.median(x[0] * x[1] / x[2] for x in r), statistics.median(x[3] for x in r) * 1024 / r[0][0])
       for c, r in rows.items()}
print("| medians | steps | wall to solution (s) | particle-steps/s | peak RSS/particle (B) |")
print("|---|---:|---:|---:|---:|")
for c, (n, s, w, ps, m) in med.items():
    print("| %s | %d | %.1f | %.3g | %.0f |" % (c, s, w, ps, m))
if "lammps" in med:
    t, l = med["tlsph"], med["lammps"]
    print("| LAMMPS / tlsph | %.2f | %.2f | %.2f (tlsph / LAMMPS) | %.2f |" % (l[1] / t[1], l[2] / t[2], t[3] / l[3], l[4] / t[4]))
print()
print("| shape at the end | L (mm) | D foot (mm) | lift-off (mm) | max eps_p |")
print("|---|---:|---:|---:|---:|")
for c, f in (("tlsph", "shape.t"), ("LAMMPS", "shape.l")):
    p = os.path.join(out, f)
    if os.path.exists(p):
        m = json.load(open(p))
        print("| %s | %.2f | %.2f | %.2f | %.2f |" % (c, m["length_mm"], m["foot_diameter_mm"], m["lift_off_mm"], m["max_plastic_strain"]))
print("(Johnson & Cook 1983 test: L = 16.21 mm, D = 13.56 mm)")
PY
