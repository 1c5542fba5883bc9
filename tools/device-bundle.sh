#!/usr/bin/env bash
# Packs what a run of tools/device-sidebyside.py needs on a GPU machine that has a GPU driver but
# none of Debian's libraries: the built commands' shared libraries (and libglvnd's, which NVIDIA's
# Vulkan driver loads), a copy of the parts of ../shared the run reads (amd-cacao, each scene's
# depth and camera, AMD's settings), and run.sh, which finds the driver's Vulkan ICD, runs the
# parts and merges the results into $OUT (or the folder given to it). The bundle is ignored by git
# (.git/info/exclude) and travels with the device tool's `carry` (run.sh prints the list).
#
# usage: tools/device-bundle.sh [--out DIR] [--build DIR] [--old-build DIR] [--also NAME=DIR ...]
#   --out DIR          the bundle (default .gpu, in the repository)
#   --build DIR        the build whose cacao, cacao-bench and cacao-inspect run there (default build)
#   --also NAME=DIR    another build to time in the same run (its tools/cli/cacao and
#                      tools/inspect/cacao-inspect are copied into the bundle's builds/NAME):
#                      the A/B of a change, or several candidates; repeatable
#   --old-build DIR    the same as --also old=DIR
# On the GPU machine, from the repository's root:  bash .gpu/run.sh [PARTS] [SCENES] [REPS]
# (defaults: stats,cacao,estimators,cpuforms; the three shared scenes; 3), results in
# $OUT/measured.json and one measured_NAME.json per other build. The `cacao` part runs scene by
# scene, every build's after the main one's (each beside AMD), so that drift reaches them alike;
# the other builds run the `cacao` and `stats` parts only. Each merged result keeps cacao's passes
# one by one (cacao_steps). Copy the files to docs/gpu-measured/ and name them in
# tools/gpu-report.py's MEASURED.
# CACAO_SHARED_DIR (default ../shared) holds amd-cacao/, scenes/ and reference-amd/.
set -euo pipefail
cd "$(dirname "$0")/.."

die() { echo "device-bundle.sh: $*" >&2; exit 1; }

out=.gpu
build=build
also=()
while [ $# -gt 0 ]; do
    case "$1" in
    --out | --build | --old-build | --also)
        [ $# -ge 2 ] || die "$1 needs a value"
        case "$1" in
        --out) out=$2 ;;
        --build) build=$2 ;;
        --old-build) also+=("old=$2") ;;
        --also)
            [[ "$2" =~ ^[A-Za-z0-9_-]+=.+ ]] || die "--also '$2': give NAME=DIR (NAME: letters, digits, _ and -)"
            also+=("$2") ;;
        esac
        shift 2 ;;
    -h | --help) sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
    esac
done
shared=${CACAO_SHARED_DIR:-$(pwd)/../shared}
bins=("$build/tools/cli/cacao" "$build/tools/bench/cacao-bench" "$build/tools/inspect/cacao-inspect")
for b in "${bins[@]}"; do [ -x "$b" ] || die "no $b (build first, or give --build)"; done
for a in "${also[@]+"${also[@]}"}"; do
    [ -x "${a#*=}/tools/cli/cacao" ] || die "no ${a#*=}/tools/cli/cacao (--also ${a%%=*}=...)"
done
[ -x "$shared/amd-cacao/amd_cacao" ] || die "no AMD program under $shared/amd-cacao (set CACAO_SHARED_DIR)"

rm -rf "$out"
mkdir -p "$out/lib" "$out/shared/scenes" "$out/shared/reference-amd"
# Every library the commands load, but the C and C++ runtimes and zlib (the machine's newer ones serve; an
# older one first on LD_LIBRARY_PATH could break its own programs), and
# libglvnd's dispatch libraries, which the NVIDIA Vulkan ICD loads itself.
for lib in $(ldd "${bins[@]}" "$shared/amd-cacao/amd_cacao" | awk '/=> \//{print $3}' | sort -u); do
    case "$(basename "$lib")" in libc.so* | libm.so* | libpthread* | libdl.so* | librt.so* | ld-linux* | libstdc++* | libgcc_s* | libz.so*) continue ;; esac
    cp -L "$lib" "$out/lib/"
done
for lib in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0 libGL.so.1; do
    [ -f "/lib/x86_64-linux-gnu/$lib" ] && cp -L "/lib/x86_64-linux-gnu/$lib" "$out/lib/"
done
mkdir -p "$out/shared/amd-cacao"
cp "$shared"/amd-cacao/* "$out/shared/amd-cacao/"
for s in "$shared"/reference-amd/*/; do
    name=$(basename "$s")
    [ -f "$shared/scenes/$name/depth.pfm" ] || continue
    mkdir -p "$out/shared/scenes/$name" "$out/shared/reference-amd/$name"
    cp "$shared/scenes/$name/depth.pfm" "$shared/scenes/$name/camera.json" "$out/shared/scenes/$name/"
    cp "$s/settings.json" "$out/shared/reference-amd/$name/"
done
for a in "${also[@]+"${also[@]}"}"; do
    name=${a%%=*} dir=${a#*=}
    [ ! -d "$out/builds/$name" ] || die "--also $name given twice"
    mkdir -p "$out/builds/$name/tools/cli" "$out/builds/$name/tools/inspect"
    cp "$dir/tools/cli/cacao" "$out/builds/$name/tools/cli/"
    [ -x "$dir/tools/inspect/cacao-inspect" ] && cp "$dir/tools/inspect/cacao-inspect" "$out/builds/$name/tools/inspect/"
done
cat >"$out/run.sh" <<'EOF'
#!/bin/bash
# Made by tools/device-bundle.sh. From the repository's root on the GPU machine:
#   bash BUNDLE/run.sh [PARTS] [SCENES] [REPS]   results: $OUT (or ./device-out)/measured*.json
# FRAMES (default 30) sets the frames per process; CONFIGS (a comma list of AMD's configurations,
# default all ten) limits the cacao and cpuforms parts.
here=$(cd "$(dirname "$0")" && pwd)
parts=${1:-stats,cacao,estimators,cpuforms}
scenes=${2:-$(ls "$here/shared/scenes" | paste -sd, -)}
reps=${3:-3}
dest=${OUT:-$PWD/device-out}
mkdir -p "$dest"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
           /etc/vulkan/icd.d/nvidia_icd.json; do
    [ -f "$icd" ] && { export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd; break; }
done
R=/tmp/device-run; rm -rf "$R" "$R"-*; mkdir -p "$R"
{ date; uptime; nproc; nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,pstate,temperature.gpu --format=csv; } >"$R/machine.txt" 2>&1
build/tools/cli/cacao --list-devices >"$R/devices.txt" 2>&1
cat "$R/devices.txt"
# the first GPU (DEVICE=NAME picks another, e.g. llvmpipe to try the bundle without a GPU)
device=${DEVICE:-$(sed -n 's/^[0-9]*: \(.*\) (\(discrete\|integrated\|virtual\) GPU).*/\1/p' "$R/devices.txt" | head -1)}
[ -n "$device" ] || { echo "no GPU among the Vulkan devices (ICD: ${VK_DRIVER_FILES:-none})"; exit 3; }
D=(python3 tools/device-sidebyside.py --device "$device" --shared "$here/shared" --reps "$reps" --frames "${FRAMES:-30}" --scenes "$scenes"
   ${CONFIGS:+--configs "$CONFIGS"})
builds=$(ls "$here/builds" 2>/dev/null || true)
has() { echo ",$parts," | grep -q ",$1,"; }
for b in $builds; do mkdir -p "$R-$b"; cp "$R/machine.txt" "$R/devices.txt" "$R-$b/"; done
if has stats; then
    "${D[@]}" --out "$R" --parts stats
    for b in $builds; do "${D[@]}" --build "$here/builds/$b" --out "$R-$b" --parts stats; done
fi
if has cacao; then # scene by scene, every build after the main one
    for s in $(echo "$scenes" | tr , ' '); do
        "${D[@]}" --out "$R" --parts cacao --scenes "$s"
        for b in $builds; do "${D[@]}" --build "$here/builds/$b" --out "$R-$b" --parts cacao --scenes "$s"; done
    done
fi
rest=$(echo "$parts" | tr , '\n' | grep -vx 'cacao\|stats' | paste -sd, -)
[ -z "$rest" ] || "${D[@]}" --out "$R" --parts "$rest"
{ date; uptime; nvidia-smi --query-gpu=name,clocks.sm,clocks.mem,pstate,temperature.gpu --format=csv; } >"$R/machine_after.txt" 2>&1
python3 tools/device-sidebyside.py --merge "$R" --out "$dest/measured.json"
for b in $builds; do
    cp "$R/machine_after.txt" "$R-$b/" && python3 tools/device-sidebyside.py --merge "$R-$b" --out "$dest/measured_$b.json"
done
exit 0
EOF
chmod +x "$out/run.sh"
case "$(realpath "$out")" in
"$(pwd)"/*) rel=${out#./}; grep -qx "/$rel/" .git/info/exclude 2>/dev/null || echo "/$rel/" >>.git/info/exclude ;;
esac
du -sh "$out" | awk '{print "bundle: " $2 ", " $1}'
echo "carry: [\"$out\", \"${bins[0]}\", \"${bins[1]}\", \"${bins[2]}\"]"
echo "command: bash $out/run.sh   (on the GPU machine, from the repository's root)"
