#!/usr/bin/env bash
# A profile-guided (PGO) release build of ronray: the release binary
# compiled once with instrumentation, run on the shipped scenes and the
# bunny benchmark, then compiled again with the measured branch and call
# counts, so LLVM lays out and inlines the hot paths (traversal, the path
# loop) as they run. Same source, same floating-point operations: images
# are byte-identical to `cargo build --release`'s (below, one render is
# compared with the instrumented build's); only time changes. README,
# "Benchmark": the measured gain.
#
# Needs llvm-profdata of the compiler's own LLVM version:
#     rustup component add llvm-tools
# The result is target/pgo/release/ronray; the instrumented build and its
# profiles live in target/pgo-train/ (both can be deleted).
#
# Usage: tools/pgo-build.sh
#        CPU=native tools/pgo-build.sh
# CPU also compiles for that CPU (`native`: this machine's, AVX-512 where it
# has it), in place of .cargo/config.toml's portable x86-64-v3; the binary
# then goes to target/pgo-CPU/release/ronray and may not start on an older
# CPU (README, "Benchmark").
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"
sysroot="$(rustc --print sysroot)"
host="$(rustc -vV | sed -n 's/^host: //p')"
profdata="$sysroot/lib/rustlib/$host/bin/llvm-profdata"
if [ ! -x "$profdata" ]; then
    echo "pgo-build: no llvm-profdata in $sysroot; install it with: rustup component add llvm-tools" >&2
    exit 2
fi
cpu="${CPU:-}"
out_dir="$here/target/pgo${cpu:+-$cpu}"
train="$here/target/pgo-train${cpu:+-$cpu}"
profiles="$train/profiles"
rm -rf "$profiles"
mkdir -p "$profiles"

# Extra flags are given as a `cfg(all())` target table: cargo joins it with
# the project's own `target.<triple>.rustflags` (.cargo/config.toml, the
# CPU level), where RUSTFLAGS would replace them.
# With CPU set, RUSTFLAGS carries every flag instead: it replaces the
# config's rustflags (and so the CPU level) as a whole.
# Usage: build TARGET_DIR FLAG [cargo args...]
build() {
    local dir="$1" flag="$2"
    shift 2
    if [ -n "$cpu" ]; then
        RUSTFLAGS="-Ctarget-cpu=$cpu $flag" cargo build --release --locked --target-dir "$dir" "$@"
    else
        cargo build --release --locked --target-dir "$dir" --config "target.'cfg(all())'.rustflags=[\"$flag\"]" "$@"
    fi
}

echo "== 1/4 instrumented build ($train)"
build "$train" "-Cprofile-generate=$profiles"

echo "== 2/4 training runs: every shipped scene at 96x96, and the bunny benchmark"
bin="$train/release/ronray"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for scene in scenes/*.ron; do
    "$bin" render "$scene" --size 96x96 --spp 16 --progress none -o "$out/a.exr" > /dev/null 2>&1 \
        || echo "   (training render of $scene failed; left out)"
    # The sampler and allocation of issue 18's per-sample line too.
    "$bin" render "$scene" --size 96x96 --spp 16 --progress none -o "$out/b.exr" \
        --set film.sampler=Independent --set film.allocation=Even > /dev/null 2>&1 || true
done
"$bin" bench assets/bunny.obj > /dev/null

echo "== 3/4 merging $(find "$profiles" -name '*.profraw' | wc -l) profiles"
"$profdata" merge -o "$train/ronray.profdata" "$profiles"

echo "== 4/4 optimised build ($out_dir)"
version="$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)"
build "$out_dir" "-Cprofile-use=$train/ronray.profdata" \
    --config "env.RONRAY_BUILD='$version (profile-guided${cpu:+, target-cpu=$cpu})'"

# The guarantee above, checked: the same image as the instrumented build
# (whose code is the plain release build's plus counters).
"$bin" render scenes/cornell.ron --size 64x64 --spp 8 --progress none -o "$out/train.exr" > /dev/null 2>&1
"$out_dir/release/ronray" render scenes/cornell.ron --size 64x64 --spp 8 --progress none -o "$out/pgo.exr" > /dev/null 2>&1
if ! cmp -s "$out/train.exr" "$out/pgo.exr"; then
    echo "pgo-build: the PGO build renders a different image from the instrumented one" >&2
    exit 1
fi
echo "built $out_dir/release/ronray: $("$out_dir/release/ronray" --version) (image check passed)"
