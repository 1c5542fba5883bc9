#!/usr/bin/env bash
# Writes the AO of one cacao binary over a matrix of configurations, one .pfm per run, so that two
# builds (a change and its parent) can be compared byte for byte:
#
#   tools/output-matrix.sh OLD/tools/cli/cacao /tmp/old
#   tools/output-matrix.sh NEW/tools/cli/cacao /tmp/new
#   diff -r /tmp/old /tmp/new && echo byte-identical
#
# The matrix: on each shared scene every quality, native and downsampled, in fp32 with blur 2
# (the defaults: the scene's normals where it has them) and in fp16 with blur 4, with no blur,
# with blur 8, with normals from depth (--no-normals), reverse-Z,
# every tile computed (--all-tiles); the GTAO and bitmask estimators at every quality with and
# without denoise passes, with normals from depth and downsampled, and with temporal accumulation
# (the third frame); the embedded scene, and crops of it from 1x1 to odd sizes (the estimators
# also downsampled with three denoise passes), with a depth holding NaN and Inf. Needs ../shared/scenes (CACAO_SHARED_DIR) for the scene
# rows; without it only the embedded-scene rows run. --validate on every run (any validation
# message fails the run). Prints the number of runs; exits non-zero on the first failed run.
set -euo pipefail
if [ $# -ne 2 ]; then
    echo "usage: tools/output-matrix.sh CACAO_BINARY OUT_DIR" >&2
    exit 2
fi
cacao=$1
out=$2
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${CACAO_SHARED_DIR:-$root/../shared}
mkdir -p "$out"
runs=0
run() { # NAME ARGS...
    local name=$1
    shift
    if ! "$cacao" --validate "$@" -o "$out/$name.pfm" > /dev/null 2> "$out/$name.err"; then
        echo "output-matrix.sh: $name failed: $(head -c 400 "$out/$name.err")" >&2
        exit 1
    fi
    rm -f "$out/$name.err"
    runs=$((runs + 1))
}
qualities="lowest low medium high highest"
if [ -d "$shared/scenes" ]; then
    for dir in "$shared"/scenes/*/; do
        scene=$(basename "$dir")
        for q in $qualities; do
            for ds in native downsampled; do
                flag=()
                [ "$ds" = downsampled ] && flag=(--downsample)
                run "$scene.$q.$ds" --scene "$dir" --quality "$q" "${flag[@]}"
                run "$scene.$q.$ds.fp16.blur4" --scene "$dir" --quality "$q" "${flag[@]}" --precision fp16 --blur 4
                run "$scene.$q.$ds.blur0" --scene "$dir" --quality "$q" "${flag[@]}" --blur 0
                run "$scene.$q.$ds.blur8" --scene "$dir" --quality "$q" "${flag[@]}" --blur 8
                run "$scene.$q.$ds.no-normals" --scene "$dir" --quality "$q" "${flag[@]}" --no-normals
            done
            run "$scene.$q.reversez" --scene "$dir" --quality "$q" --reverse-z
            run "$scene.$q.alltiles" --scene "$dir" --quality "$q" --all-tiles
            for est in gtao bitmask; do
                run "$scene.$est.$q" --scene "$dir" --estimator "$est" --quality "$q"
                run "$scene.$est.$q.blur0" --scene "$dir" --estimator "$est" --quality "$q" --blur 0
                run "$scene.$est.$q.no-normals" --scene "$dir" --estimator "$est" --quality "$q" --no-normals
                run "$scene.$est.$q.downsampled" --scene "$dir" --estimator "$est" --quality "$q" --downsample
            done
        done
        for est in gtao bitmask; do
            run "$scene.$est.temporal" --scene "$dir" --estimator "$est" --quality medium --temporal 4 --repeat 3
        done
    done
fi
# The embedded scene, and crops of its depth (odd and tiny sizes; one with NaN and Inf).
run default
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$tmp" << 'EOF'
import struct, sys, math
def write(path, w, h, f):
    with open(path, 'wb') as o:
        o.write(b'Pf\n%d %d\n-1.0\n' % (w, h))
        for y in range(h):
            o.write(b''.join(struct.pack('<f', f(x, y, w, h)) for x in range(w)))
def plane(x, y, w, h):  # a tilted floor with a box and a far background band
    if y < h // 5: return 1.0
    d = 0.9 + 0.09 * (y / max(h - 1, 1))
    if w // 3 <= x < w // 2 and h // 2 <= y < 3 * h // 4: d -= 0.02
    return d
def holes(x, y, w, h):
    if (x * 7 + y * 13) % 97 == 0: return float('nan')
    if 5 <= x < 9 and 5 <= y < 9: return float('inf')
    return plane(x, y, w, h)
for w, h in [(1, 1), (2, 3), (7, 5), (17, 9), (33, 31), (130, 67), (1001, 37)]:
    write('%s/plane_%dx%d.pfm' % (sys.argv[1], w, h), w, h, plane)
write('%s/holes_96x80.pfm' % sys.argv[1], 96, 80, holes)
EOF
for depth in "$tmp"/*.pfm; do
    base=$(basename "$depth" .pfm)
    for q in $qualities; do
        run "crop.$base.$q" --depth "$depth" --fov 60 --near 0.1 --far 100 --quality "$q"
        run "crop.$base.$q.ds" --depth "$depth" --fov 60 --near 0.1 --far 100 --quality "$q" --downsample
    done
    for est in gtao bitmask; do
        run "crop.$base.$est" --depth "$depth" --fov 60 --near 0.1 --far 100 --estimator "$est"
        run "crop.$base.$est.ds.blur3" --depth "$depth" --fov 60 --near 0.1 --far 100 --estimator "$est" \
            --downsample --blur 3
    done
done
echo "output-matrix.sh: $runs runs into $out"
