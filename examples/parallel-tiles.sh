#!/usr/bin/env bash
# One frame as N tiles with GNU parallel, then assembled:
#
#   examples/parallel-tiles.sh 8 scenes/cornell.ron renders/cornell [render options...]
#
# The line that does the work: job k (PARALLEL_SEQ, 1 to N) renders tile
# k − 1 (--tile auto/N); -N0 runs N jobs without appending arguments to the
# command. Add `--sshlogin host1,host2` (and a shared OUT_DIR) to spread the
# jobs over machines. JOBS sets how many run at once (default 2).
set -euo pipefail
usage="usage: $0 N SCENE OUT_DIR [render options...]"
tiles=${1:?$usage}
scene=${2:?$usage}
out=${3:?$usage}
shift 3
ronray=${RONRAY:-ronray}
mkdir -p "$out"
seq "$tiles" | parallel -N0 -q --will-cite --halt now,fail=1 -j "${JOBS:-2}" \
    "$ronray" render "$scene" --tile "auto/$tiles" -o "$out/tile-{tile}.exr" --threads 1 --resume "$@"
"$ronray" assemble "$out"/tile-*.exr -o "$out/frame.exr"
