#!/usr/bin/env bash
# Issue 18's table in one run: Mitsuba 3 (`llvm_ad_rgb`, 256 spp) and ronray
# (independent sampler, 256 spp) on each reference scene, alternating, then
# `ronray bench --scenes` for ronray's error per sample count. Only ratios
# within one run mean anything on a shared machine.
#
# Needs: a release build (`cargo build --release`), the reference folder
# (`../shared/refs` beside the checkout, or REFS=...), Mitsuba's runner
# (`../shared/tools/mitsuba_run.py`, or MITSUBA_RUN=...) and a Python with
# the `mitsuba` package (MITSUBA_PYTHON=..., default `python3`; Mitsuba's
# LLVM backend may need DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so).
#
# Usage: tools/side_by_side.sh [ROUNDS] [SPP_LIST]   (defaults 3, 48,64,96,128,192,256)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
rounds="${1:-3}"
spps="${2:-48,64,96,128,192,256}"
refs="${REFS:-$here/../shared/refs}"
run="${MITSUBA_RUN:-$here/../shared/tools/mitsuba_run.py}"
py="${MITSUBA_PYTHON:-python3}"
ronray="$here/target/release/ronray"
threads="${THREADS:-2}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
[ -x "$ronray" ] || { echo "build first: cargo build --release" >&2; exit 2; }
[ -d "$refs" ] || { echo "no reference folder at $refs (set REFS)" >&2; exit 2; }
scenes=()
for json in "$refs"/*.json; do
    name="$(basename "$json" .json)"
    twin="$here/scenes/$name.ron"
    [ "$name" = cornell_diffuse ] && twin="$here/scenes/cornell.ron"
    [ -f "$twin" ] && scenes+=("$name:$twin")
done
echo "== warm-up (Mitsuba's JIT caches)"
for s in "${scenes[@]}"; do
    "$py" "$run" "$refs/${s%%:*}.json" --variant llvm_ad_rgb --spp 16 --out "$out/warm.exr" > /dev/null 2>&1 || true
done
for round in $(seq "$rounds"); do
    echo "== round $round $(date -u +%T), load $(cut -d' ' -f1-3 /proc/loadavg)"
    for s in "${scenes[@]}"; do
        name="${s%%:*}" twin="${s#*:}"
        mi=$("$py" "$run" "$refs/$name.json" --variant llvm_ad_rgb --spp 256 --out "$out/mi.exr" 2>/dev/null | grep render_s || echo "failed")
        rr=$("$ronray" render "$twin" --size 256x256 --spp 256 --threads "$threads" \
            --set film.sampler=Independent --progress none -o "$out/rr.exr" 2>&1 | grep -o 'in [0-9.]* s' || echo "failed")
        echo "$name | mitsuba llvm 256 spp $mi | ronray independent 256 spp $rr"
    done
done
echo "== ronray error per sample count $(date -u +%T)"
"$ronray" bench --scenes "$refs" --ronray-scenes "$here/scenes" --spp "$spps" \
    --sampler Independent,Sobol --threads "$threads"
