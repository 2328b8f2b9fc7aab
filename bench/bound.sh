#!/usr/bin/env bash
# The machine's bound for one core, in particle-steps per second
# (docs/performance.md, "Single-core throughput and the machine's bound").
#
# 1. Builds bench/stream_triad.c with the compiler and flags the engine was
#    configured with ($BUILD_DIR/Makefile: CC, CFLAGS) and runs it: the triad's
#    bandwidth from L1 to main memory, and the flop rate packed (as the
#    compiler vectorises) and scalar.
# 2. Divides by what a step moves and computes per particle, counted from the
#    code (the counts below; the pair loops read each neighbour's data from
#    cache, so a pair costs its own stream of pair arrays; every particle
#    array a phase touches is counted once per phase, read and written):
#      bytes = B0 + Bp * pairs,  flops = F0 + Fp * pairs   per particle-step
#    This VM exposes no hardware counters (`perf stat -e instructions` says
#    "not supported"), so the counts are by hand, not measured.
# 3. Prints each scene's memory bound at the cache level a 40k-particle run's
#    arrays fit in and at main memory, its compute bound scalar and packed,
#    and which one binds.
#
# usage: bench/bound.sh [PAIRS_PER_PARTICLE] [BIG_MIB]   (default 30, 1024)
set -euo pipefail
. "$(dirname "$0")/common.sh"
pairs=${1:-30}
big=${2:-1024}
build=${BUILD_DIR:-$top/build}
cc=$(sed -n 's/^CC = //p' "$build/Makefile" | head -1)
cflags=$(sed -n 's/^CFLAGS = //p' "$build/Makefile" | head -1)
scratch_dir
$cc $cflags -o "$out/stream_triad" "$here/stream_triad.c"
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs, $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1), $cc $cflags"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$out/stream_triad" "$big" | tee "$out/rates"
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
"$py" - "$out/rates" "$pairs" <<'PY'
import sys
rates = [l.split() for l in open(sys.argv[1])]
P = float(sys.argv[2])
triad = {int(r[1]): float(r[2]) for r in rates if r[0] == "triad"}
flops = {r[0]: float(r[1]) for r in rates if r[0].startswith("flops")}
sizes = sorted(triad)
# a 40k-particle run's arrays (~50 MB) against the triad at 3 x 16 MiB; the
# largest size is main memory
llc = triad[min(sizes, key=lambda s: abs(3 * s - 50e6))]
mem = triad[sizes[-1]]
# (B0, Bp, F0, Fp): bytes and flops per particle-step, counted in
# core/run/integrate.c (kicks, drift, energies), sph/kinematics.c (gather,
# 12 B and 52 flops a pair), material/ (point update: Jacobi ~9 rotations of
# 66 flops), sph/forces.c and hourglass.h (20 B and 93 flops a pair).
scenes = {
    "elastic": (1104, 32, 1135, 145),
    "plastic": (1280, 32, 1550, 147),
    "plastic+thermal": (1296, 32, 1570, 147),
    "damage": (1700, 32, 1670, 169),
}
print("| scene | bytes / p-step | flops / p-step | memory bound, LLC %.1f GB/s | memory bound, DRAM %.1f GB/s"
      " | compute bound, scalar %.1f Gflop/s | compute bound, packed %.1f Gflop/s | binds |"
      % (llc, mem, flops["flops_scalar"], flops["flops"]))
print("|---|---:|---:|---:|---:|---:|---:|---|")
for name, (b0, bp, f0, fp) in scenes.items():
    B, F = b0 + bp * P, f0 + fp * P
    mb_llc, mb_mem = llc * 1e9 / B, mem * 1e9 / B
    cb_s, cb_p = flops["flops_scalar"] * 1e9 / F, flops["flops"] * 1e9 / F
    binds = "compute (scalar)" if cb_s < mb_mem else "memory"
    print("| %s | %.0f | %.0f | %.2e | %.2e | %.2e | %.2e | %s |" % (name, B, F, mb_llc, mb_mem, cb_s, cb_p, binds))
PY
