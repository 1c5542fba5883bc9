#!/usr/bin/env bash
# Speed of cacao against AMD FidelityFX CACAO v1.2, measured side by side in one run on this
# machine (../shared/amd-cacao/sidebyside.py: AMD and cacao alternately, fresh processes, same
# scenes and settings), written as docs/speed.md with the per-stage table, the ratios, and the
# load average before and after (a ratio taken on a busy machine means little: check it).
#
# Default: all 30 configurations at 960x540 (3 shared scenes x 5 qualities x native/downsampled)
# and the 10 of interior_fzkhaus at 1920x1080 (nearest 2x upscale of its depth).
#
# usage: tools/speed-vs-amd.sh [--cacao PATH] [--out FILE] [--reps N] [--frames K]
#                              [--scenes A,B] [--configs X,Y] [--no-2x]
#   --cacao PATH    cacao command (default build/tools/cli/cacao)
#   --out FILE      markdown to write (default docs/speed.md); sidebyside's JSON of both sizes
#                   goes beside it (FILE with .json); nothing is written unless every run succeeded
#   --reps N        AMD/cacao pairs per configuration (default 5)
#   --frames K      frames per process (default 6)
#   --scenes A,B    scenes under $CACAO_SHARED_DIR/scenes (default interior_fzkhaus,
#                   statues_scanned,street_track); the 1920x1080 part uses the first one
#   --configs X,Y   configurations (default all 10, LOWEST_native .. HIGHEST_downsampled)
#   --no-2x         skip the 1920x1080 part (for a quick check)
# CACAO_SHARED_DIR (default ../shared) holds amd-cacao/, scenes/ and reference-amd/.
set -euo pipefail
cd "$(dirname "$0")/.."

die() { echo "speed-vs-amd.sh: $*" >&2; exit 1; }

cacao=build/tools/cli/cacao
out=docs/speed.md
reps=5
frames=6
scenes=interior_fzkhaus,statues_scanned,street_track
configs=
twox=1
while [ $# -gt 0 ]; do
    case "$1" in
    --cacao | --out | --reps | --frames | --scenes | --configs)
        [ $# -ge 2 ] || die "$1 needs a value"
        case "$1" in
        --cacao) cacao=$2 ;; --out) out=$2 ;; --reps) reps=$2 ;; --frames) frames=$2 ;;
        --scenes) scenes=$2 ;; --configs) configs=$2 ;;
        esac
        shift 2 ;;
    --no-2x) twox=0; shift ;;
    -h | --help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
    esac
done
case "$reps" in '' | *[!0-9]* | 0) die "--reps must be a positive integer, not '$reps'" ;; esac
case "$frames" in '' | *[!0-9]* | 0) die "--frames must be a positive integer, not '$frames'" ;; esac

shared=${CACAO_SHARED_DIR:-$(pwd)/../shared}
sbs=$shared/amd-cacao/sidebyside.py
amd=$shared/amd-cacao/amd_cacao
python=/usr/bin/python3 # sidebyside.py needs numpy and PIL from Debian's python3
[ -f "$sbs" ] || die "no side-by-side script at $sbs (set CACAO_SHARED_DIR)"
[ -x "$amd" ] || die "no AMD program at $amd (set CACAO_SHARED_DIR)"
[ -x "$cacao" ] || die "no cacao command at $cacao (build first, or give --cacao)"
[ -x "$python" ] || die "$python not found (apt-get install -y python3-numpy python3-pil)"

scene_dirs=()
IFS=, read -r -a names <<<"$scenes"
for s in "${names[@]}"; do
    [ -d "$shared/scenes/$s" ] || die "--scenes: no scene '$s' in $shared/scenes"
    scene_dirs+=("$shared/scenes/$s")
done
config_args=()
[ -n "$configs" ] && config_args=(--configs "$configs")

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

load_before=$(uptime)
"$python" "$sbs" --amd "$amd" --cacao "$cacao" "${scene_dirs[@]}" "${config_args[@]}" \
    --reps "$reps" --frames "$frames" --json "$work/1x.json" --markdown "$work/1x.md" >"$work/1x.log" 2>&1 ||
    { cat "$work/1x.log" >&2; die "side-by-side run at 960x540 failed"; }
if [ "$twox" = 1 ]; then
    "$python" "$sbs" --amd "$amd" --cacao "$cacao" "${scene_dirs[0]}" "${config_args[@]}" --sizes 2x \
        --reps "$reps" --frames "$frames" --json "$work/2x.json" --markdown "$work/2x.md" >"$work/2x.log" 2>&1 ||
        { cat "$work/2x.log" >&2; die "side-by-side run at 1920x1080 failed"; }
fi
load_after=$(uptime)

# Per-stage ratios (cacao/AMD) from the JSON, plus the worst stage of each configuration.
"$python" - "$work" "$twox" >"$work/ratios.md" <<'EOF'
import json, os, sys
work, twox = sys.argv[1], sys.argv[2] == '1'
stages = ['prepare', 'base', 'importance', 'generate', 'blur', 'apply', 'upsample']
def rows(doc):
    """Yield (scene, size, config, total ratio, {stage: ratio}) from sidebyside's --json."""
    for r in doc['results']:
        size = '%dx%d' % (r['width'], r['height'])
        yield r['scene'], size, r['config'], r['ratio'], r['ratio_stages']
print('| scene | size | configuration | total | ' + ' | '.join(stages) + ' | worst stage |')
print('|' + ' --- |' * (len(stages) + 5))
for name in ['1x.json'] + (['2x.json'] if twox else []):
    with open(os.path.join(work, name)) as f:
        doc = json.load(f)
    for scene, size, config, total, ratios in rows(doc):
        ratios = {s: v for s, v in ratios.items() if v is not None}
        worst = max(ratios, key=ratios.get) if ratios else '-'
        cells = ['%.2f' % ratios[s] if s in ratios else '-' for s in stages]
        print('| %s | %s | %s | %.2f | %s | %s %.2f |' % (scene, size, config, total, ' | '.join(cells),
                                                        worst, ratios.get(worst, float('nan'))))
EOF

tmp_out=$work/speed.md
{
    echo "# Speed against AMD FidelityFX CACAO v1.2 (lavapipe), side by side"
    echo
    echo "Regenerate with \`tools/speed-vs-amd.sh\` (it runs \`../shared/amd-cacao/sidebyside.py\`:"
    echo "AMD and cacao alternately in fresh processes, $reps pairs per configuration, $frames frames each)."
    echo "Only the ratios mean anything; absolute milliseconds move 2-3x between machines and runs."
    echo
    echo "Load before: \`$load_before\`"
    echo
    echo "Load after: \`$load_after\`"
    echo
    echo "## cacao/AMD per stage (below 1.0: cacao is faster)"
    echo
    cat "$work/ratios.md"
    echo
    echo "## 960x540"
    echo
    sed '1,/^$/d' "$work/1x.md"
    if [ "$twox" = 1 ]; then
        echo
        echo "## 1920x1080"
        echo
        sed '1,/^$/d' "$work/2x.md"
    fi
} >"$tmp_out"
mkdir -p "$(dirname "$out")"
"$python" - "$work" "$twox" >"${out%.md}.json.tmp" <<'EOF'
import json, os, sys
work, twox = sys.argv[1], sys.argv[2] == '1'
doc = {}
for size, name in [('960x540', '1x.json')] + ([('1920x1080', '2x.json')] if twox else []):
    with open(os.path.join(work, name)) as f:
        doc[size] = json.load(f)
json.dump(doc, sys.stdout, indent=1)
EOF
mv "${out%.md}.json.tmp" "${out%.md}.json"
cp "$tmp_out" "$out.tmp"
mv "$out.tmp" "$out"
echo "speed-vs-amd.sh: wrote $out"
