#!/bin/bash
# Times reuse_unchanged on a GPU machine (docs/reuse-measured.md "On a real GPU"): per scene (the
# three shared scenes and the embedded one, or the bundle's scenes named in $SCENES), quality (lowest, high, highest) and resolution mode,
# the full frame and five ways of --reuse (tools/reuse-report.py names them), 3 interleaved
# repetitions of 30 timed frames each. Run from the repository's root on the device, with the
# bundle of tools/device-bundle.sh (.gpu: libraries and scenes) and build/tools/cli/cacao carried;
# writes $OUT/reuse-gpu.txt (a '#' line naming the GPU, then one line per run) and
# $OUT/reuse-gpu-steps.txt (per-pass timings of three ways). Summarise with
# tools/reuse-report.py --render-only --gpu FILE.
export LD_LIBRARY_PATH=$PWD/.gpu/lib
for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json /etc/vulkan/icd.d/nvidia_icd.json; do
  [ -f $f ] && { export VK_DRIVER_FILES=$f VK_ICD_FILENAMES=$f; break; }
done
T0=$SECONDS
{ date; uptime; nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,pstate --format=csv; } > $OUT/machine.txt 2>&1
GPU=$(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -1)
C=build/tools/cli/cacao
for rep in 1 2 3; do
for s in ${SCENES:-street_track statues_scanned interior_fzkhaus embedded}; do
  S="--scene .gpu/shared/scenes/$s"; W=1280; H=720
  [ $s = embedded ] && S="" || read W H < <(head -c 64 .gpu/shared/scenes/$s/depth.pfm | sed -n 2p)
  WHOLE=0,0,$W,$H; BOX=$((W/3)),$((H/3)),$((W/3)),$((H/3))
  for q in lowest high highest; do for ds in "" "--downsample"; do
    for way in full camera "allmoved" "unchanged" "unchangedapply" "moved"; do
      case $way in
        full) extra="";; camera) extra="--reuse --move-camera";; allmoved) extra="--reuse --move-box $WHOLE";; unchanged) extra="--reuse --keep-output";;
        unchangedapply) extra="--reuse";; moved) extra="--reuse --keep-output --move-box $BOX";;
      esac
      t=$(timeout 30 $C --device NVIDIA $S --quality $q $ds $extra --timings --repeat 30 -o /tmp/o.pfm 2>&1 | awk '/^total/{print $2} /^reuse/{print "R",$0}' | tr '\n' ' ')
      echo "$rep $s $q ${ds:-native} $way $t"
    done
  done; done
done; done > $OUT/reuse-runs.txt 2>&1
{ echo "# ${GPU:-unknown GPU} (driver), $(date -u +%Y-%m-%d)"; cat $OUT/reuse-runs.txt; } > $OUT/reuse-gpu.txt; rm $OUT/reuse-runs.txt
# one per-step listing of each way at HIGH native on street_track
for way in full unchanged moved; do
  case $way in full) extra="";; unchanged) extra="--reuse --keep-output";; moved) extra="--reuse --keep-output --move-box 320,180,320,180";; esac
  echo "== $way"; timeout 30 $C --device NVIDIA --scene .gpu/shared/scenes/street_track --quality high $extra --timings --repeat 30 -o /tmp/o.pfm 2>&1
done > $OUT/reuse-gpu-steps.txt 2>&1
echo "all: $((SECONDS-T0)) s"
tail -5 $OUT/reuse-gpu.txt
