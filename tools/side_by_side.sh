#!/usr/bin/env bash
# Issue 18's table in one run, on each reference scene with a ronray twin:
#
# 1. Warm-up: Mitsuba 3's JIT caches, and one Mitsuba `llvm_ad_rgb`
#    256-spp render per scene, whose error off the light pixels (against
#    the reference, `ronray diff --mask`) is the target.
# 2. `ronray bench --scenes`: ronray's error per sample count with its
#    defaults (Sobol, samples spread by noise); the sample count that reaches
#    the target is interpolated (log-log) and rounded up. Only the errors
#    are used: the bench's timings are single runs.
# 3. Rounds, alternating per scene: Mitsuba 256 spp; ronray `Independent`,
#    256 spp in every pixel (`allocation: Even`), one path per camera sample
#    (`splits: 1`) and no light-traced caustics (`caustics: PathOnly`:
#    Mitsuba's `path` has none; PER_SAMPLE_CAUSTICS=LightTracing times
#    ronray's with them), for the per-sample ratio: the same algorithm;
#    ronray's defaults at the sample count of step 2, timed and measured
#    against the reference (so the table shows that the timed render does
#    reach Mitsuba's error).
# 4. The summary: medians over the rounds. Only ratios within one run mean
#    anything on a shared machine; alternating renders minutes apart is
#    what keeps the time-to-error ratio from swinging with the machine's
#    load (the bench-timing version of this script moved it by ±0.1
#    between runs). The last column scales ronray's time to Mitsuba's
#    error exactly (time × (its RMSE / Mitsuba's)², error ∝ 1/√time): the
#    timed render lands a little either side of it.
#
# Needs: a release build (`cargo build --release`, or RONRAY=path of another
# binary, e.g. target/pgo/release/ronray from tools/pgo-build.sh), the reference folder
# (`../shared/refs` beside the checkout, or REFS=...), Mitsuba's runner
# (`../shared/tools/mitsuba_run.py`, or MITSUBA_RUN=...) and a Python with
# the `mitsuba` package (MITSUBA_PYTHON=..., default `python3`; Mitsuba's
# LLVM backend may need DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so).
#
# EXTRA=path of a second ronray binary (say target/pgo/release/ronray):
# timed in the same rounds, right after the first (same scenes, same sample
# counts), as two more columns of the summary. NEED="name=spp name=spp ..."
# skips step 2 and takes those sample counts instead (from an earlier run of
# the same sampling code: the counts depend on the images, not the build).
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
ronray="${RONRAY:-$here/target/release/ronray}"
extra="${EXTRA:-}"
threads="${THREADS:-2}"
per_sample_caustics="${PER_SAMPLE_CAUSTICS:-PathOnly}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# One line per measurement, for the summary: "mi|rr|err NAME VALUE".
log="$out/log"
: > "$log"
[ -x "$ronray" ] || { echo "build first: cargo build --release" >&2; exit 2; }
[ -z "$extra" ] || [ -x "$extra" ] || { echo "EXTRA=$extra is not an executable" >&2; exit 2; }
[ -d "$refs" ] || { echo "no reference folder at $refs (set REFS)" >&2; exit 2; }
scenes=()
for json in "$refs"/*.json; do
    name="$(basename "$json" .json)"
    twin="$here/scenes/$name.ron"
    [ "$name" = cornell_diffuse ] && twin="$here/scenes/cornell.ron"
    [ -f "$twin" ] && scenes+=("$name:$twin")
done
# The benchmark scenes of bench/NAME/ (tools/make_bench_scenes.py): a ronray
# scene and its Mitsuba twin rendering one of the references (the JSON's
# "reference"), measured against that reference. Each gets a folder of its
# own that holds the reference under its name, for `ronray bench --scenes`.
for json in "$here"/bench/*/*.json; do
    [ -f "$json" ] || continue
    name="$(basename "$json" .json)"
    ref="$(sed -n 's/.*"reference": "\([^"]*\)".*/\1/p' "$json")"
    twin="${json%.json}.ron"
    [ -n "$ref" ] && [ -f "$twin" ] && [ -f "$refs/${ref}_ref.exr" ] || continue
    mkdir -p "$out/b_$name"
    ln -s "$refs/${ref}_ref.exr" "$out/b_$name/${name}_ref.exr"
    [ -f "$refs/${ref}_emitter_mask.png" ] && ln -s "$refs/${ref}_emitter_mask.png" "$out/b_$name/${name}_emitter_mask.png"
    scenes+=("$name:$twin")
done
# The Khronos FlightHelmet (glTF, 94,722 triangles, base-colour and normal
# maps under the sky map): the twin of tests/fixtures/refs/flight_helmet.ron
# drawn by tools/gltf_to_mitsuba.py (needs `pygltflib` beside `mitsuba`; the
# row is left out without it, or with NO_HELMET=1). Its reference is a Mitsuba
# `llvm_ad_rgb` render at HELMET_REF_SPP (default 4096, seed 1) made here in
# the warm-up: no shared reference exists at 256². Both sides draw every
# material with the model they share (docs/gltf.md, "Mitsuba reference").
helmet_gltf="$here/assets/gltf/FlightHelmet/FlightHelmet.gltf"
helmet=""
if [ -z "${NO_HELMET:-}" ] && "$py" -c "import pygltflib, mitsuba" 2> /dev/null; then
    helmet="$out/helmet"
    mkdir -p "$helmet" "$out/b_flight_helmet"
    scenes+=("flight_helmet:$here/tests/fixtures/refs/flight_helmet.ron")
fi
helmet_run() { # gltf_to_mitsuba.py ARGS...: the twin at 256², llvm, its JSON report
    "$py" "$here/tools/gltf_to_mitsuba.py" "$helmet_gltf" --out "$helmet" --envmap "$here/assets/sky_sun.exr" \
        --size 256 --variant llvm_ad_rgb --threads "$threads" "$@" 2> /dev/null
}
# ONLY=SUBSTRING keeps the scenes whose name holds it.
if [ -n "${ONLY:-}" ]; then
    kept=()
    for s in "${scenes[@]}"; do [[ "${s%%:*}" == *"$ONLY"* ]] && kept+=("$s"); done
    scenes=("${kept[@]}")
fi
# Where scene NAME's reference, mask and Mitsuba JSON are.
refdir_of() { if [ -d "$out/b_$1" ]; then echo "$out/b_$1"; else echo "$refs"; fi; }
json_of() { local j=("$here"/bench/*/"$1".json); if [ -f "${j[0]}" ]; then echo "${j[0]}"; else echo "$refs/$1.json"; fi; }
mask_of() { local d; d="$(refdir_of "$1")"; [ -f "$d/${1}_emitter_mask.png" ] && echo "--mask $d/${1}_emitter_mask.png"; }
mi_render() { # NAME OUT -> "render_s" or "failed"
    if [ "$1" = flight_helmet ]; then
        helmet_run --spp 256 --exr "$2"
    else
        "$py" "$run" "$(json_of "$1")" --variant llvm_ad_rgb --spp 256 --out "$2" 2>/dev/null
    fi | sed -n 's/.*"render_s": \([0-9.]*\).*/\1/p' | grep . || echo failed
}
rr_render() { # TWIN SPP OUT EXTRA... -> seconds or "failed" (RR_BIN: another binary)
    local twin="$1" spp="$2" o="$3"; shift 3
    "${RR_BIN:-$ronray}" render "$twin" --size 256x256 --spp "$spp" --threads "$threads" "$@" \
        --progress none -o "$o" 2>&1 | sed -n 's/.* in \([0-9.]*\) s.*/\1/p' | grep . || echo failed
}
err_of() { "$ronray" diff "$1" "$(refdir_of "$2")/${2}_ref.exr" $(mask_of "$2") | awk '$1 == "rmse" {print $2}'; }

echo "== $("$ronray" --version) at $ronray"
if [ -n "$helmet" ] && [[ "flight_helmet" == *"${ONLY:-}"* ]]; then
    echo "== the FlightHelmet's reference: Mitsuba llvm, ${HELMET_REF_SPP:-4096} spp $(date -u +%T)"
    helmet_run --spp "${HELMET_REF_SPP:-4096}" --seed 1 --exr "$out/b_flight_helmet/flight_helmet_ref.exr" > /dev/null \
        || echo "the FlightHelmet's reference failed" >&2
fi
echo "== warm-up (Mitsuba's JIT caches) and Mitsuba's 256-spp error per scene"
for s in "${scenes[@]}"; do
    name="${s%%:*}"
    "$py" "$run" "$(json_of "$name")" --variant llvm_ad_rgb --spp 16 --out "$out/warm.exr" > /dev/null 2>&1 || true
    [ "$(mi_render "$name" "$out/mi.exr")" != failed ] && echo "err0 $name $(err_of "$out/mi.exr" "$name")" >> "$log"
done
if [ -n "${NEED:-}" ]; then
    for kv in $NEED; do echo "need ${kv%%=*} ${kv#*=}" >> "$log"; done
else
    echo "== ronray error per sample count $(date -u +%T) (its timings are single runs: not used)"
    : > "$out/bench"
    for s in "${scenes[@]}"; do
        name="${s%%:*}" twin="${s#*:}"
        d="$(refdir_of "$name")"
        # One scene at a time: a folder of references renders every twin it finds.
        mkdir -p "$out/one_$name"
        ln -s "$d/${name}_ref.exr" "$out/one_$name/${name}_ref.exr"
        [ -f "$d/${name}_emitter_mask.png" ] && ln -s "$d/${name}_emitter_mask.png" "$out/one_$name/"
        "$ronray" bench --scenes "$out/one_$name" --ronray-scenes "$(dirname "$twin")" --spp "$spps" \
            --sampler Independent,Sobol --threads "$threads" | tee -a "$out/bench"
    done
    # The sample count at which ronray's defaults reach Mitsuba's error: log-log
    # interpolation between the bench's counts, rounded up.
    awk -F'|' '
        FILENAME == ARGV[1] { split($0, w, " "); if (w[1] == "err0") e[w[2]] = w[3]; next }
        $3 ~ /Sobol/ && $4 + 0 > 0 { n = $2; gsub(/ /, "", n); k = ++rows[n]; spp[n, k] = $4 + 0; off[n, k] = $10 + 0 }
        END {
            for (n in e) {
                s = 0
                for (k = 1; k <= rows[n]; k++) if (off[n, k] <= e[n]) {
                    if (k == 1) { s = spp[n, 1]; break }
                    f = log(off[n, k - 1] / e[n]) / log(off[n, k - 1] / off[n, k])
                    s = spp[n, k - 1] * exp(f * log(spp[n, k] / spp[n, k - 1])); break
                }
                if (s > 0) printf "need %s %d\n", n, (s == int(s) ? s : int(s) + 1)
            }
        }' "$log" "$out/bench" >> "$log"
fi
for round in $(seq "$rounds"); do
    echo "== round $round $(date -u +%T), load $(cut -d' ' -f1-3 /proc/loadavg)"
    for s in "${scenes[@]}"; do
        name="${s%%:*}" twin="${s#*:}"
        need=$(awk -v n="$name" '$1 == "need" && $2 == n {print $3}' "$log")
        mi=$(mi_render "$name" "$out/mi.exr")
        rr=$(rr_render "$twin" 256 "$out/rr.exr" --set film.sampler=Independent --set film.allocation=Even \
            --set integrator.splits=1 --set integrator.caustics="$per_sample_caustics")
        line="$name | mitsuba llvm 256 spp $mi s | ronray Independent 256 spp $rr s"
        if [ "$mi" != failed ]; then
            echo "mi $name $mi" >> "$log"
            echo "err $name $(err_of "$out/mi.exr" "$name")" >> "$log"
        fi
        [ "$rr" != failed ] && echo "rr $name $rr" >> "$log"
        if [ -n "$need" ]; then
            dt=$(rr_render "$twin" "$need" "$out/def.exr" --set film.sampler=Sobol)
            if [ "$dt" != failed ]; then
                echo "def $name $dt" >> "$log"
                echo "deferr $name $(err_of "$out/def.exr" "$name")" >> "$log"
            fi
            line="$line | ronray defaults $need spp $dt s"
        fi
        if [ -n "$extra" ]; then
            x=$(RR_BIN="$extra" rr_render "$twin" 256 "$out/rr.exr" --set film.sampler=Independent \
                --set film.allocation=Even --set integrator.splits=1 \
                --set integrator.caustics="$per_sample_caustics")
            [ "$x" != failed ] && echo "xrr $name $x" >> "$log"
            line="$line | extra Independent 256 spp $x s"
            if [ -n "$need" ]; then
                x=$(RR_BIN="$extra" rr_render "$twin" "$need" "$out/def.exr" --set film.sampler=Sobol)
                [ "$x" != failed ] && echo "xdef $name $x" >> "$log"
                line="$line | extra defaults $x s"
            fi
        fi
        echo "$line"
    done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "== summary (medians over the rounds, every time from renders alternated in them)"
awk '
    { v[$1, $2] = v[$1, $2] " " $3; names[$2] = 1; if ($1 == "need") need[$2] = $3 }
    function median(s,   a, m, i, j, t) {
        m = split(s, a, " "); if (m == 0) return 0
        for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
        return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
    }
    END {
        print "| scene | Mitsuba 256 spp s | ronray Independent 256 spp s | per sample | Mitsuba RMSE off light | ronray defaults: spp to it | their RMSE off light | their s | their time / Mitsuba | scaled to Mitsuba error |"
        print "|---|---|---|---|---|---|---|---|---|---|"
        xs = ""
        for (n in names) {
            mi = median(v["mi", n]); rr = median(v["rr", n]); e = median(v["err", n])
            d = median(v["def", n]); de = median(v["deferr", n])
            at = (n in need) ? need[n] : "> bench range"
            printf "| %s | %.2f | %.2f | %.2f× | %.5f | %s | %.5f | %.2f | %s | %s |\n", n, mi, rr, (mi > 0 ? rr / mi : 0), e, at, de, d, (mi > 0 && d > 0 ? sprintf("%.2f×", d / mi) : "—"), (mi > 0 && d > 0 && e > 0 ? sprintf("%.2f×", d / mi * (de / e) ^ 2) : "—")
            xr = median(v["xrr", n]); xd = median(v["xdef", n])
            if (xr > 0) xs = xs sprintf("| %s | %.2f | %.2f× | %.2f | %s |\n", n, xr, (mi > 0 ? xr / mi : 0), xd, (mi > 0 && xd > 0 ? sprintf("%.2f×", xd / mi) : "—"))
        }
        if (xs != "") {
            print "\nThe EXTRA binary, same rounds:\n"
            print "| scene | Independent 256 spp s | per sample | defaults s | their time / Mitsuba |"
            print "|---|---|---|---|---|"
            printf "%s", xs
        }
    }' "$log"
