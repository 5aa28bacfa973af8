#!/usr/bin/env bash
# Fetches Intel Open Image Denoise 2.5 (the official Linux x86-64 shared
# libraries, which the `pyoidn` wheel on PyPI ships) into .oidn/ (git-ignored)
# and prints the environment that `cargo build --features denoise` and the
# built binaries need. OIDN is not packaged in Debian; this is the only
# network access besides pip's own. Use it as
#
#     eval "$(scripts/fetch-oidn.sh)"
#     cargo build --release --features denoise
#
# OIDN_DIR is what the `oidn` crate's build script links against
# (OIDN_DIR/lib); LD_LIBRARY_PATH lets the binaries find the libraries at
# run time (or copy .oidn/lib next to an installed ronray and set its rpath).
# A second run reuses the unpacked folder.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=${OIDN_DEST:-$PWD/.oidn}
version=2.5.1.0
if [ ! -e "$dest/lib/libOpenImageDenoise.so.2" ]; then
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    python3 -m pip download "pyoidn==$version" --no-deps --only-binary=:all: -d "$tmp" >&2
    # Only what linking and the CPU device need (about 56 MB of the wheel's
    # 87: no GPU back ends, no SYCL runtime, no tools).
    python3 - "$tmp" "$dest" <<'PY'
import glob, os, re, sys, zipfile
tmp, dest = sys.argv[1], sys.argv[2]
wheel = glob.glob(os.path.join(tmp, "pyoidn-*.whl"))[0]
keep = re.compile(r"pyoidn/oidn/(lib/lib(OpenImageDenoise(_core|_device_cpu)?|tbb)\.so[.0-9]*|include/.*\.h|LICENSE.*|third-party-programs.*)$")
with zipfile.ZipFile(wheel) as z:
    for info in z.infolist():
        if keep.match(info.filename):
            out = os.path.join(dest, info.filename[len("pyoidn/oidn/"):])
            os.makedirs(os.path.dirname(out), exist_ok=True)
            with z.open(info) as src, open(out, "wb") as dst:
                dst.write(src.read())
PY
    echo "unpacked OIDN $version into $dest" >&2
fi
echo "export OIDN_DIR=$dest"
echo "export LD_LIBRARY_PATH=$dest/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
