#!/usr/bin/env bash
# Issue 18's table in one run: Mitsuba 3 (`llvm_ad_rgb`, 256 spp) and ronray
# (independent sampler, every pixel 256 spp: `allocation: Even`) on each
# reference scene, alternating, then
# `ronray bench --scenes` for ronray's error per sample count, then the
# summary: per-sample time ratio, Mitsuba's own 256-spp error off the light
# pixels (its renders of this run against the reference, `ronray diff
# --mask`), the spp at which ronray's defaults (Sobol, samples spread by
# noise) reach it
# (log-log interpolation between the bench's sample counts) and that
# render's time over Mitsuba's. Only ratios within one run mean anything on
# a shared machine.
#
# Needs: a release build (`cargo build --release`), the reference folder
# (`../shared/refs` beside the checkout, or REFS=...), Mitsuba's runner
# (`../shared/tools/mitsuba_run.py`, or MITSUBA_RUN=...) and a Python with
# the `mitsuba` package (MITSUBA_PYTHON=..., default `python3`; Mitsuba's
# LLVM backend may need DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so).
#
# Usage: tools/side_by_side.sh [ROUNDS] [SPP_LIST]   (defaults 3, 48,64,96,128,192,256;
# SPP_LIST ascending: the summary interpolates between neighbours)
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
# One line per measurement, for the summary: "mi|rr|err NAME VALUE".
log="$out/log"
: > "$log"
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
            --set film.sampler=Independent --set film.allocation=Even --progress none -o "$out/rr.exr" 2>&1 | grep -o 'in [0-9.]* s' || echo "failed")
        echo "$name | mitsuba llvm 256 spp $mi | ronray independent 256 spp $rr"
        mask=()
        [ -f "$refs/${name}_emitter_mask.png" ] && mask=(--mask "$refs/${name}_emitter_mask.png")
        if [ "$mi" != failed ]; then
            echo "mi $name $(sed 's/.*"render_s": \([0-9.]*\).*/\1/' <<< "$mi")" >> "$log"
            err=$("$ronray" diff "$out/mi.exr" "$refs/${name}_ref.exr" "${mask[@]}" | awk '$1 == "rmse" {print $2}')
            [ -n "$err" ] && echo "err $name $err" >> "$log"
        fi
        [ "$rr" != failed ] && echo "rr $name $(awk '{print $2}' <<< "$rr")" >> "$log"
    done
done
echo "== ronray error per sample count $(date -u +%T)"
"$ronray" bench --scenes "$refs" --ronray-scenes "$here/scenes" --spp "$spps" \
    --sampler Independent,Sobol --threads "$threads" | tee "$out/bench"
echo "== summary (medians over the rounds; Mitsuba's error is its own, measured here)"
awk -F'|' '
    FILENAME == ARGV[1] { split($0, w, " "); v[w[1], w[2]] = v[w[1], w[2]] " " w[3]; names[w[2]] = 1; next }
    $3 ~ /Sobol/ && $4 + 0 > 0 {
        n = $2; gsub(/ /, "", n); k = ++rows[n]
        spp[n, k] = $4 + 0; sec[n, k] = $5 + 0; off[n, k] = $10 + 0
    }
    function median(s,   a, m, i, j, t) {
        m = split(s, a, " "); if (m == 0) return 0
        for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
        return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
    }
    END {
        print "| scene | Mitsuba 256 spp s | ronray Independent 256 spp s | per sample | Mitsuba RMSE off light | ronray Sobol spp to it | its s | its time / Mitsuba s |"
        print "|---|---|---|---|---|---|---|---|"
        for (n in names) {
            mi = median(v["mi", n]); rr = median(v["rr", n]); e = median(v["err", n])
            at = "> " spp[n, rows[n]]; t = "—"; ratio = "—"
            for (k = 1; k <= rows[n]; k++) {
                if (off[n, k] <= e) {
                    if (k == 1) { at = "≤ " spp[n, 1]; t = sec[n, 1]; break }
                    f = log(off[n, k - 1] / e) / log(off[n, k - 1] / off[n, k])
                    s = spp[n, k - 1] * exp(f * log(spp[n, k] / spp[n, k - 1]))
                    t = sec[n, k - 1] + (s - spp[n, k - 1]) / (spp[n, k] - spp[n, k - 1]) * (sec[n, k] - sec[n, k - 1])
                    at = sprintf("%.0f", s); break
                }
            }
            if (t != "—" && mi > 0) ratio = sprintf("%.2f×", t / mi)
            if (t != "—") t = sprintf("%.2f", t)
            printf "| %s | %.2f | %.2f | %.2f× | %.5f | %s | %s | %s |\n", n, mi, rr, (mi > 0 ? rr / mi : 0), e, at, t, ratio
        }
    }' "$log" "$out/bench"
