#!/usr/bin/python3
"""Regenerates docs/gpu.md: what AMD's shader compiler says of cacao and of AMD FidelityFX CACAO v1.2.

For each AMD family (RADV's null device: RADV_FORCE_FAMILY, no GPU needed), runs AMD's
`amd_cacao_pipelines` (statistics of AMD's 33 pipelines) and `cacao-inspect gpu --all` with those
statistics (--amd), and writes per family: the estimated frame cost of the ten default
configurations (five qualities x native/downsampled, 1920x1080) per stage for cacao and AMD with
their ratio, every permutation's registers, occupancy and cycle estimates, AMD's pipelines, and
every permutation that uses scratch memory. The figures are a compiler's estimate, never a timing;
the text says what that leaves out. Needs a build (cacao-inspect), ../shared/amd-cacao and Mesa's
RADV driver (mesa-vulkan-drivers). Python's standard library only.

With the timings a real GPU gave (tools/device-sidebyside.py on the GPU's machine, its runs merged
into docs/gpu-measured/, see MEASURED below), the report begins with those: cacao and AMD side by
side in milliseconds, per stage, both shader forms, the horizon estimators, and the statistics that
GPU's driver reports; and it sets the RADV estimate beside them.

usage: tools/gpu-report.py [--inspect build/tools/inspect/cacao-inspect]
                           [--amd-pipelines ../shared/amd-cacao/amd_cacao_pipelines]
                           [--icd /usr/share/vulkan/icd.d/radeon_icd.x86_64.json]
                           [--families vega10,navi21,gfx1100] [--measured docs/gpu-measured]
                           [--out docs/gpu.md]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUALITIES = ['lowest', 'low', 'medium', 'high', 'highest']
CONFIGS = ['%s_%s' % (q, r) for r in ('native', 'downsampled') for q in QUALITIES]
HORIZON = ['%s_%s_%s' % (e, q, r) for r in ('native', 'downsampled') for e in ('gtao', 'bitmask')
           for q in ('lowest', 'low', 'medium', 'high', 'highest')]
STAGES = ['prepare', 'classify/compact', 'base', 'importance', 'generate', 'blur', 'apply/upsample']
HORIZON_STAGES = ['horizon_prepare', 'horizon_main', 'horizon_denoise']
FAMILY_NAMES = {'vega10': 'Vega 10 (GCN5, gfx9)', 'navi10': 'Navi 10 (RDNA1, gfx10.1)',
                'navi21': 'Navi 21 (RDNA2, gfx10.3)', 'gfx1100': 'Navi 31 (RDNA3, gfx11)'}
# The permutation table's columns: (statistic as the tool's JSON names it, header).
STAT_COLUMNS = [('VGPRs', 'VGPRs'), ('SGPRs', 'SGPRs'), ('Spilled VGPRs', 'spilled VGPRs'),
                ('Spilled SGPRs', 'spilled SGPRs'), ('Scratch size', 'scratch B'), ('LDS size', 'LDS B'),
                ('Subgroups per SIMD', 'waves/SIMD'), ('Instructions', 'instructions'), ('Latency', 'latency'),
                ('Inverse Throughput', 'inv. throughput')]
# Issue 31's own figures (navi21, 1920x1080, cacao/AMD totals), for the comparison the text makes.
ISSUE_31 = {'lowest_native': 0.78, 'low_native': 0.60, 'medium_native': 0.50, 'high_native': 0.83,
            'highest_native': 0.81, 'lowest_downsampled': 0.55, 'low_downsampled': 0.52,
            'medium_downsampled': 0.47, 'high_downsampled': 0.60, 'highest_downsampled': 0.61}


# The runs on a real GPU (tools/device-sidebyside.py --merge writes one file per run), by role:
# 'final' is the code as it stands (the GPU forms' depth mip chain), and in the same run
# 'chain_before' the main before it; 'classify_gpu'/'classify_gpu_before' a later run of the
# classification from the caller's depth against its parent (the cacao part only);
# 'classify_fused'/'classify_nofuse' a run of commit f745aa5 against a build of it whose native
# prepare did not classify (classify_gpu before it instead: tried, not kept); 'classify_quad'/
# 'classify_quad_before' a build of classify_gpu with 2x2 texels per invocation against f745aa5's
# (downsampled configurations only: tried, not kept); 'classify_groups'/'classify_groups_before'
# the downsampled prepare classifying in groups of its own against classify_gpu before it
# (downsampled configurations only); 'prev_final' an earlier session's final run, and in that run
# 'before' its previous main and 'lists' the GPU forms with tile lists (an older main), 'diag' a
# diagnostic build (generate's taps all from
# level 0: wrong output, a timing only); 'upsample'/'upsample_before' and 'counting'/
# 'counting_before' two earlier runs of this session's experiments, each against its own baseline;
# 'horizon' a later run of the horizon estimators against AMD HIGH, after their GPU forms' fills;
# 'tf_final'/'tf_before' an earlier session's run of generate's taps through the sampled view,
# 'forms'/'forms_before' and 'atomics'/'atomics_before' that session's other runs.
MEASURED = {'final': 'h200-mipchain.json', 'chain_before': 'h200-mipchain-before.json',
            'prev_final': 'h200-final.json', 'before': 'h200-before.json',
            'classify_gpu': 'h200-classify-gpu.json', 'classify_gpu_before': 'h200-classify-gpu-before.json',
            'classify_fused': 'h200-classify-fused.json', 'classify_nofuse': 'h200-classify-nofuse.json',
            'classify_quad': 'h200-classify-quad.json', 'classify_quad_before': 'h200-classify-quad-before.json',
            'classify_groups': 'h200-classify-groups.json', 'classify_groups_before': 'h200-classify-groups-before.json', 'lists': 'h200-lists.json',
            'diag': 'h200-diag-level0.json', 'horizon': 'h200-horizon.json',
            'upsample': 'h200-run-upsample.json', 'upsample_before': 'h200-run-upsample-before.json',
            'counting': 'h200-run-counting.json', 'counting_before': 'h200-run-counting-before.json',
            'tf_final': 'h200-texelfetch-final.json', 'tf_before': 'h200-texelfetch-before.json',
            'forms': 'h200-run-texelfetch.json', 'forms_before': 'h200-run-texelfetch-before.json',
            'atomics': 'h200-run-atomics.json', 'atomics_before': 'h200-run-atomics-before.json',
            'fused': 'h200-run-fused.json', 'fused_before': 'h200-run-fused-before.json',
            'horizon_direct': 'h200-horizon-direct.json', 'horizon_direct_before': 'h200-horizon-direct-before.json'}
# The commit each role's build was (said with the tables: a run measures its code).
MEASURED_COMMITS = {'final': '77d676c', 'chain_before': 'c51cb89', 'prev_final': '349c7a2',
                    'classify_gpu': 'f745aa5', 'classify_gpu_before': '77b5614',
                    'classify_groups': 'fb04f36', 'classify_groups_before': '6f4ae34', 'before': 'abd0c77', 'lists': '0c7a571', 'horizon': '1065bc3',
                    'tf_before': '6588704', 'tf_final': '8ba0da9', 'fused': '35f1533', 'fused_before': '16e6be8',
                    'horizon_direct': 'd643d71', 'horizon_direct_before': '16e6be8',
                    'horizon_direct_since': '269c67e'}
# The per-pass timings of the 'fused' run's two builds (.gpu/steps.sh of that session: cacao --timings,
# the builds alternating, two rounds, 960x540).
FUSED_STEPS = 'h200-fused-steps.txt'
C = MEASURED_COMMITS
MEASURED_CODE = ('The final run is of commit %s; in the same run, interleaved with it, its "before" is '
                 'commit %s (the previous main: the GPU forms\' depths an atlas, as the CPU forms\' are, '
                 'generate\'s taps through `texelFetch` below HIGH and `imageLoad` at HIGHEST).') % (
                     C['final'], C['chain_before'])
SCENES = ['interior_fzkhaus', 'statues_scanned', 'street_track']
AMD_CONFIGS = ['%s_%s' % (q.upper(), r) for r in ('native', 'downsampled') for q in QUALITIES]
MEASURED_STAGES = ['prepare', 'other', 'base', 'importance', 'generate', 'blur', 'apply', 'upsample']


def run(argv, env, what):
    r = subprocess.run(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if r.returncode != 0:
        sys.exit('%s failed (exit %d): %s\n%s' % (what, r.returncode, ' '.join(argv), r.stderr.strip()))
    return r.stdout


def measure(a, family, work):
    """The JSON of `cacao-inspect gpu --all` with AMD's statistics on RADV's null device for family."""
    env = dict(os.environ, RADV_FORCE_FAMILY=family, VK_ICD_FILENAMES=a.icd, MESA_SHADER_CACHE_DISABLE='true')
    amd = os.path.join(work, 'amd-%s.jsonl' % family)
    with open(amd, 'w') as f:
        f.write(run([a.amd_pipelines, '--device', 'RADV'], env, 'amd_cacao_pipelines (%s)' % family))
    out = os.path.join(work, 'gpu-%s.json' % family)
    run([a.inspect, 'gpu', '--all', '--config', ','.join(CONFIGS + HORIZON), '--amd', amd, '--json', out], env,
        'cacao-inspect gpu (%s)' % family)
    with open(out) as f:
        result = json.load(f)
    with open(amd) as f:
        result['amd_pipelines'] = [json.loads(line) for line in f if line.strip()]
    # the CPU forms (lavapipe's shapes of the blur, apply, prepare and generate), which a context
    # on a GPU never runs
    cpu_out = os.path.join(work, 'gpu-%s-cpu.json' % family)
    run([a.inspect, 'gpu', '--all', '--shader-forms', 'cpu', '--json', cpu_out], env,
        'cacao-inspect gpu --shader-forms cpu (%s)' % family)
    with open(cpu_out) as f:
        result['cpu_forms'] = json.load(f)
    return result


def mcycles(v):
    return '-' if v is None else '%.2f' % (v / 1e6)


def ratio(c, a):
    return '-' if c is None or not a else '%.2f' % (c / a)


def by_name(result):
    return {c['name']: c for c in result['configurations']}


def config_table(result):
    """Per configuration and stage: cacao / AMD Mcycles (cacao/AMD), then the totals."""
    lines = ['| configuration | ' + ' | '.join(STAGES) + ' | total cacao | total AMD | cacao/AMD |',
             '|---|' + '---:|' * (len(STAGES) + 3)]
    configs = by_name(result)
    for name in CONFIGS:
        c = configs[name]
        cs, ams = c['cacao']['stages'], c['amd']['stages']
        cells = []
        for s in STAGES:
            if s not in cs and s not in ams:
                cells.append('')
            else:
                cells.append('%s / %s (%s)' % (mcycles(cs.get(s)), mcycles(ams.get(s)), ratio(cs.get(s), ams.get(s))))
        ct, at = c['cacao']['total_cycles'], c['amd']['total_cycles']
        lines.append('| %s | %s | %s | %s | **%s** |' % (name, ' | '.join(cells), mcycles(ct), mcycles(at),
                                                         ratio(ct, at)))
    return lines


def horizon_table(result):
    configs = by_name(result)
    amd_high = configs['high_native']['amd']['total_cycles']
    lines = ['| configuration | budget | ' + ' | '.join(HORIZON_STAGES) + ' | total | / AMD HIGH |',
             '|---|---|' + '---:|' * 5]
    for name in HORIZON:
        c = configs[name]
        st = c['cacao']['stages']
        lines.append('| %s | %sx%s | %s | %s | %s |' % (
            name, c['horizon_slices'], c['horizon_steps'],
            ' | '.join(mcycles(st.get(s)) for s in HORIZON_STAGES), mcycles(c['cacao']['total_cycles']),
            ratio(c['cacao']['total_cycles'], amd_high)))
    return lines


def number(v):
    return '-' if v is None else '%d' % v


def permutation_table(result):
    lines = ['| key | wave | workgroup | ' + ' | '.join(h for _, h in STAT_COLUMNS) + ' |',
             '|---|---:|---|' + '---:|' * len(STAT_COLUMNS)]
    for p in result['permutations']:
        wg = p['workgroup_size']
        key = '**%s**' % p['key'] if p['spills'] else p['key']
        lines.append('| %s | %d | %dx%d | %s |' % (key, p['subgroup_size'], wg[0], wg[1],
                                                  ' | '.join(number(p['stats'].get(k)) for k, _ in STAT_COLUMNS)))
    return lines


def amd_table(result):
    lines = ['| AMD entry point | ' + ' | '.join(h for _, h in STAT_COLUMNS) + ' |', '|---|' + '---:|' * len(STAT_COLUMNS)]
    for p in result['amd_pipelines']:
        lines.append('| %s | %s |' % (p['entry'], ' | '.join(number(p['stats'].get(k)) for k, _ in STAT_COLUMNS)))
    return lines


def spill_lines(result):
    spills = [p for p in result['permutations'] if p['spills']]
    if not spills:
        return ['No permutation uses scratch memory or spills registers.']
    lines = ['%d permutations use scratch memory (registers spilled to it):' % len(spills), '']
    for p in spills:
        s = p['stats']
        lines.append('- `%s`: %d bytes of scratch, %d VGPRs and %d SGPRs spilled (%d VGPRs allocated, %d waves/SIMD)'
                     % (p['key'], s['Scratch size'], s['Spilled VGPRs'], s['Spilled SGPRs'], s['VGPRs'],
                        s['Subgroups per SIMD']))
    return lines


def overview(results):
    fams = list(results)
    lines = ['| configuration | ' + ' | '.join('%s cacao/AMD' % f for f in fams) + ' |', '|---|' + '---:|' * len(fams)]
    for name in CONFIGS:
        cells = []
        for f in fams:
            c = by_name(results[f])[name]
            cells.append(ratio(c['cacao']['total_cycles'], c['amd']['total_cycles']))
        lines.append('| %s | %s |' % (name, ' | '.join(cells)))
    return lines


def issue_comparison(result):
    lines = ['| configuration | this estimate | issue 31 |', '|---|---:|---:|']
    configs = by_name(result)
    for name in CONFIGS:
        c = configs[name]
        lines.append('| %s | %s | %.2f |' % (name, ratio(c['cacao']['total_cycles'], c['amd']['total_cycles']),
                                             ISSUE_31[name]))
    return lines


def targets_section(results):
    """Issue 31's targets against this estimate: scratch and spills per family, navi21's stages
    above AMD's and totals above 0.6 (stretch 0.5) of AMD's, over the ten configurations above."""
    lines = ['## Issue 31\'s targets, against this estimate', '']
    spills = ['%s %d' % (f, sum(1 for p in r['permutations'] if p['spills'])) for f, r in results.items()]
    cpu = ['%s %d' % (f, sum(1 for p in r['cpu_forms']['permutations'] if p['spills'])) for f, r in results.items()]
    lines.append('- No pipeline with scratch or spilled VGPRs, over every embedded permutation a context on a GPU '
                 'creates (the GPU forms and the passes both forms share): %s (%s). The CPU forms (lavapipe\'s '
                 'shapes of the blur, apply, prepare and generate, which a context on a GPU never creates; '
                 '`gpu-compile` checks them on neither family): %s permutations with scratch.' % (
                     'met' if all(x.endswith(' 0') for x in spills) else '**missed**', ', '.join(spills),
                     ', '.join(cpu)))
    if 'navi21' not in results:
        return lines + ['- navi21: not measured.']
    configs = by_name(results['navi21'])
    above, totals = [], []
    for name in CONFIGS:
        c = configs[name]
        cs, ams = c['cacao']['stages'], c['amd']['stages']
        for st in STAGES:
            if st in cs and ams.get(st) and cs[st] > ams[st]:
                above.append('%s %s %.3f' % (name, st, cs[st] / ams[st]))
        totals.append((name, c['cacao']['total_cycles'] / c['amd']['total_cycles']))
    lines.append('- navi21, every stage at most AMD\'s equivalent stage (the ten configurations, blur 2, fp32): '
                 + ('met' if not above else '**missed**: ' + '; '.join(above)) + '.')
    over = ['%s %.2f' % (n, r) for n, r in totals if r > 0.6]
    lines.append('- navi21, every total at most 0.6 of AMD\'s: ' + ('met' if not over else '**missed** by %d of %d: %s'
                 % (len(over), len(totals), ', '.join(over))) + '; at most 0.5 (stretch): %d of %d.' % (
                     sum(1 for _, r in totals if r <= 0.5), len(totals)))
    return lines


HEADER = """# What AMD's shader compiler says: cacao beside AMD FidelityFX CACAO on AMD GPUs

**A compiler's estimate, not a timing.** Every figure here comes from Mesa's RADV driver compiling
the pipelines with ACO, AMD's compiler, for an AMD GPU family on RADV's *null device*
(`RADV_FORCE_FAMILY`): no GPU runs anything. It shows what the code costs in registers, occupancy
and issued instructions, and where a permutation spills; it does not show what a frame takes on a
real GPU. Left out: memory bandwidth and caches (every texture fetch and image store costs its issue
slot and ACO's fixed latency, nothing more), the traffic of scratch memory (a spilling permutation's
scratch loads and stores are counted as instructions, not as memory traffic), the real trip count of
loops bounded by runtime values, and everything between dispatches (barriers, cache flushes, idle
SIMDs at the tail of a small dispatch).

**Where the estimate and a real GPU disagree, the real GPU wins.** One real GPU has timed cacao
against AMD's code so far (an NVIDIA H200: section "Measured on a real GPU", after the overview):
there cacao takes %(measured)s AMD's time, more than AMD in %(above)s of the %(pairs)s scene x
configuration pairs (%(later)s), where this estimate puts it under AMD's cost in every one; two of the changes
that made it faster there (the Q3 base pass one texel per invocation, classify's counting moved)
cost a little in this estimate, and one that the estimate favours (Q0's taps through the sampler)
costs that GPU a little. Read the estimate for registers, spills and occupancy, not for speed. The
GPU forms' depth mip chain (section "The GPU forms": generate's taps through the sampler) gained on
the real GPU what the estimate said it would (section "The depth mip chain and the changes with it,
measured in the same run").

Regenerate with `tools/gpu-report.py` (needs a build, `../shared/amd-cacao` and mesa-vulkan-drivers;
it takes seconds and no GPU). Device and driver: %(driver)s. Size 1920x1080; both sides fp32,
normals reconstructed from depth (AMD's reference setting), blur 2 (AMD's blur is modelled with the
same pass count as ours).

## How the estimate is made

`cacao-inspect gpu` creates a configuration's pipelines through the runtime
(`cacao_context_create_pipelines` with `VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR`) and reads
each pipeline's statistics (`VK_KHR_pipeline_executable_properties`). A step of the frame's plan
(`cacao_plan_build` at 1920x1080) costs

    workgroups (x * y * z of its dispatch) x invocations per workgroup / 64 x ACO's "Inverse Throughput"

ACO's *Inverse Throughput* is the cycles a SIMD spends per wave64 of active invocations at the
pipeline's occupancy (its source, `aco_statistics.cpp`, scales wave32 code to wave64 and divides
by the share of lanes a workgroup leaves idle), so for the wave64 code RADV makes here and
workgroups of 64 or 256 invocations this is workgroups x waves per workgroup x inverse throughput.
Stages sum their steps: prepare, classify/compact (cacao's tile classification), base (HIGHEST's
Q3 base pass), importance, generate, blur, apply/upsample. cacao's indirect steps (generate and blur
over the tiles that need them, and the horizon estimators' main and denoise passes) count their
largest grid, as if every tile were active: on real frames with sky or faded tiles cacao does less.
Such a step's shader begins with its group's entry check (the groups past the list's last entry
return at once), a workgroup-uniform branch, and ACO weighs everything under a uniform branch as
run half the time (below): its "Inverse Throughput" is half the body's. The estimate therefore
doubles it for list-dispatched steps (the same horizon_main.gtao code: 7727 cycles per wave as a
direct dispatch, 3863 from the list). The GPU forms of generate and the blur run every group and
branch the same way on their group's needed flag (docs/tiles.md): doubled too, which also
doubles what the branch does not cover (the blur's stores, after it), an overestimate. Estimates made before this correction (this report's
earlier versions, issue 31's table) counted cacao's generate and blur at half their weight. The
per-permutation tables below print ACO's figure as it reports it. The tile fill and clear steps
are left out (the fill dispatches nothing with every tile active; a clear runs no shader). The GPU
form of the fused prepare downsampled classifies the tiles in groups of its own (its dispatch's z
0); ACO's figure holds both sides of that workgroup-uniform branch, and the estimate moves the
classification's share, weighed as `classify_gpu.downsampled` (the same function) over the same
groups, to the classify/compact stage, where it was while it had a dispatch of its own.

AMD's steps per configuration follow AMD's own code (`FFX_CACAO_VkDraw` in `ffx_cacao_impl.cpp`,
`FFX_CACAO_UpdateBufferSizeInfo` in `ffx_cacao.cpp`, `ffx_cacao_defines.h`, the numthreads of
`ffx_cacao.hlsl`), written as one table in `tools/inspect/gpu_model.c`: clear load counter; prepare
depths (half at LOWEST, full at LOW, with mips above) and normals; at HIGHEST the Q3 base pass x4
and three importance passes; generate Q0 at LOWEST and LOW, Q1 at MEDIUM (both on AMD's sparse
4x16 grid), Q2 at HIGH, Q3 at HIGHEST, x4 (x2 at LOWEST); blur x4 (x2); apply or the bilateral
upscale. Their statistics come from `amd_cacao_pipelines` on the same null device.

**Loops.** ACO does not know a loop's trip count: its estimate weighs every loop body as if it ran 8
times (x4 for each further level of nesting), a uniform branch as taken half the time and each side
of a divergent branch 75%% of the time. So HIGHEST's adaptive taps (cacao's `generate.q3` and AMD's
`GenerateQ3` alike: up to 27 more taps where the importance map asks) are weighed at those assumed
counts, not at the counts a frame measures. The horizon-slice estimators' slice loop and the step
loop nested in it run to the frame's budget (slices x steps per side, a runtime value: one key
serves every quality), so ACO weighs the main pass as 8 slices x 4 steps; the estimate reweighs it by
the real count, x (slices x steps) / 32 (`cacao-inspect gpu`, estimate_cacao). That scales the
per-pixel and per-slice setup with the step body; the step body dominates ACO's figure, but at the
smallest budgets (LOWEST: 4 iterations) the setup's share makes the reweighed figure low. The
budget is not specialised per key: on lavapipe compile-time budgets measured no faster.

## The GPU forms

A context on a GPU runs the GPU forms of four passes (`cacao_shader_forms`; `--shader-forms cpu`
compiles lavapipe's instead): the same arithmetic, so the same output bit for bit on lavapipe in
fp32 (`test_shader_forms`), in shapes that cost a GPU compiler less.

- `blur_gpu`: every pass count in shared memory (the CPU form's 8x4 register block spills on every
  family), 16x16 threads of 4x3 texels: a 64x48 padded tile whose inner (64 - 2N) x (48 - 2N)
  texels a group writes, AMD's tile. With 2x2 texels per thread (a 32x32 tile) the blur was 1.75x
  AMD's estimate at blur 2 on navi21: the halo was 1.31x the texels written (1.16x at 64x48) and a
  texel cost 118 instructions (AMD's: 62). Per wave at blur 2 (ACO's figure doubled for the
  list), 4 waves a group: 566 cycles with 2x2 texels (2.89 per texel written); 4x3 texels with each
  neighbour read from shared memory without a branch, the block's own texels included, where the
  CPU form takes those from registers (a branch per read; lavapipe's shared loads run lane by
  lane): 1,318; each store's test made per row and column: 1,234; the edge weights and their sum
  read from a 256-entry shared table of the edge codes, which the group's 256 invocations write
  before the first iteration's barrier, instead of unpacked per texel (18 instructions a texel on
  navi21, a quarter of the shader): 988 (1.50 per texel written), 0.91 of AMD's
  `EdgeSensitiveBlur2` (1,090 on the same grid), and 0.89 to 0.94 of AMD's at every pass count.
  Measured before the table and not kept: 4x2 texels (1.17x AMD's) and 4x4 (1.09x; 168 VGPRs,
  6 waves per SIMD). `apply_gpu`: 2x2 pixels per invocation, each read through the sampler (one pixel
  per invocation until the H200 timed the quad at half the time: section "Measured on a real GPU"; on
  navi21 the estimate of apply at LOWEST native went from 1.43 to 0.63 Mcycles, AMD's 1.49).
- `prepare_gpu` (normals from depth): ACO estimates the fused prepare as VALU-bound, about 125
  instructions per normal, as AMD's `PrepareNormals` is. The GPU form normalises each direction
  between two neighbouring depths once, for the two normals that use it (the other takes its
  negation, exactly the direction the other way): 40 normalisations per 16 normals instead of 64.
  It computes the centres row by row and the block's rows as they are reached, so that few rows are
  live: with all of them live it took 192 VGPRs on navi21, where the estimate became latency-bound
  at the lower occupancy and gained nothing, and gfx1100 spilled. HALF (LOWEST: slices 0 and 3,
  which share no neighbour) and MIPS downsampled (gfx1100 spilled two VGPRs) keep the shared form's
  code. Measured alternatives: one full-resolution pixel per invocation with the positions in shared
  memory costs about as much per normal (the normal's own arithmetic dominates), and so does one
  slice texel per invocation.
- `generate_gpu`: the depths and their mips as the image's mip chain (the CPU forms: an atlas,
  one level holding all four, cacao_shared.h), and each tap one `textureLod` through the nearest
  sampler at the tap's LOD: the sampler picks the level and the texel, clamped to the level's
  edge, where the CPU form computes them (the level, the level's extent and place in the atlas, the
  texel and its clamp: 17 instructions a tap and 10 a sample on navi21, of a tap's 113). Below
  HIGH there is one level and the tap is a `textureLod` at LOD 0. On lavapipe the sampler's
  choices are the CPU form's (`test_shader_forms`: bit-identical); a GPU rounds a LOD's tie
  upwards and a texel coordinate to its sub-texel precision, so near a tie it may take the
  neighbouring level or texel (as AMD's own sampling does). The prepares of the GPU forms write levels 1..3
  through storage views of one level each (`prepare_gpu.mips`, `prepare_depths.mips_chain`). On
  navi21 (ACO's figure per wave, `cacao-inspect gpu --all --device RADV` built at c51cb89 and at
  d9cc280): `generate_gpu.q0` 196 -> 167, `q1` 397 -> 350, `q2` 934 -> 676,
  `q3` 694 -> 522, the Q3 base pass 1,817 -> 1,248; the generate stage at HIGH 60.97 -> 44.13 Mcycles (AMD's
  57.25), the base pass at HIGHEST 29.65 -> 20.37 (AMD's 22.07). The H200 timed it (section
  "The depth mip chain and the changes with it, measured in the same run"): generate at HIGH and
  HIGHEST about a fifth shorter, where earlier runs had found the atlas's address arithmetic not
  to be generate's cost there and Q3's taps slower through `texelFetch` of the sampled view than
  through `imageLoad`; Q0 a little longer. The Q3 base pass
  computes one slice texel (its four layers) per invocation and reduces the importance map's 2x2
  quads in shared memory (the CPU form: 16 texels per invocation, 2x2 of each layer): the H200
  timed it faster (HIGHEST's generate stage 233 -> 226 microseconds native, 81 -> 73 downsampled)
  than the 16-texel GPU form it replaced, which ACO's estimate put 1.3x cheaper per texel.
- `generate_gpu`'s obscurance and halo weight without two of their three max0 (a compare and a
  select each on a GPU): the falloff term is at most 1, so its max0 is a saturate, which folds
  into the multiply-add; the halo's max0 goes, since a positive depth difference takes the
  saturated sum to 1 anyway. Equal for every input (`test_shader_forms`: bit-identical). On navi21
  (the same command at d9cc280 and dd555a9) `q2` 676 -> 617 cycles per wave, `q3` 522 -> 482, the Q3 base pass 1,248 -> 1,128.
- The upsample (one form for both devices): an entry outside the image weighs 0 through its
  depth term alone (the sentinel depth's difference squares to +inf, exp2(-inf) = 0, the
  multiplier kept below -FLT_MIN) instead of a select per weight: on navi21 (at 53b8eed and 0e6873b) `upsample.smart.fp32`
  8,375 -> 7,503 cycles per wave, the downsampled totals 0.55-0.63 -> 0.50-0.60 of AMD's. The
  same output (`tools/output-matrix.sh`, byte for byte).
- The blur's mirrored load coordinates without branches or selects (`mirror_coord`, the same
  value for every int; both forms, lavapipe's blur as fast as before): at 9ec59b5 and 53b8eed `blur_gpu.2.fp32` 551 -> 543
  cycles per wave on navi21, the blur stage at blur 2 1.01 -> 1.00 of AMD's (0.996).
- `generate_gpu` and `blur_gpu` run on direct grids and skip by the tile classes themselves: a
  group reads its needed flag (classify marks them) and, when not needed, stores AO 1 and computes
  nothing else; the CPU forms run from compact's lists and fill the rest (docs/tiles.md). On
  navi21 at LOWEST native the estimate of generate went from 5.94 to 6.23 Mcycles and the blur's
  from 1.64 to 1.90 (against the lists), and the compact pass, two fill dispatches and their
  barriers, which the estimate does not weigh, are gone. Most of the blur's difference is the
  estimate's: its stores follow the flag's branch, where the list's entry check covered them, and
  the doubling above counts them twice. On the H200 the tiles stage went from 16.8-36.7 to
  10.5-14.7 microseconds (section "Measured on a real GPU"). Since then classify's marks do not
  count (generate and the blur count the groups they run): 0.94 -> 0.91 Mcycles for classify here.
- The tile classes: with normals from depth the prepare (`prepare_gpu`) classifies, native the
  texels it stores, downsampled in groups of its own (its dispatch's z 0) from the caller's
  depth; with the caller's normals `classify_gpu` classifies from the caller's depth, first in the
  frame, with no barrier before the prepare (the CPU forms' classify pass reads the stored depths
  after the prepare, behind a barrier). The estimate does not see the dispatch and the barrier
  they save; the H200 timed both (sections "The classification in the prepare's own groups" and
  "The classes from the caller's depth").

## Against issue 31's measurement

Issue 31 gave, for navi21 at 1920x1080, cacao/AMD totals of 0.78 0.60 0.50 0.83 0.81 (native,
LOWEST..HIGHEST) and 0.55 0.52 0.47 0.60 0.61 (downsampled). The code has changed since (the GPU
forms), and so has the estimate (list-dispatched steps weighed in full, above); besides, at LOW,
MEDIUM and HIGH the issue's model of AMD ran the generate shader one level too high (Q1 at LOW, Q2 at MEDIUM, Q3 at HIGH). AMD's `FFX_CACAO_VkDraw`
picks `CS_GENERATE_Q0 + max(0, quality - 1)` with LOWEST = 0, i.e. Q0 at LOWEST *and* LOW, Q1 at
MEDIUM, Q2 at HIGH (the levels whose taps cacao's LOW, MEDIUM and HIGH reproduce, which is why
cacao's output matches AMD's at every level). When this report was written, this tool run with the
issue's choice of generate shaders gave the issue's figures: LOW 0.60 and 0.52, HIGH 0.83 and 0.60,
MEDIUM 0.49 and 0.48 (the issue: 0.50 and 0.47).

%(issue)s

## Overview: cacao/AMD per family (total estimated cycles per frame, below 1: cacao issues less)

%(overview)s
"""


def load_measured(folder):
    """The runs of MEASURED found in folder, by role (an absent file: an absent role)."""
    runs = {}
    for role, name in MEASURED.items():
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            with open(path) as f:
                runs[role] = json.load(f)['parts']
    return runs


def results_of(parts, part, scene):
    """{config: result} of one sidebyside part (cacao, cpuforms) on one scene."""
    doc = parts.get('%s.%s' % (part, scene))
    return {r['config']: r for r in doc['results']} if doc else {}


def us(v):
    return '-' if v is None else '%.1f' % (v * 1000.0)


def line_of(text, prefix):
    return next((l.strip() for l in text.splitlines() if l.startswith(prefix)), '?')


def nvidia_stats(text):
    """(key, registers, stack bytes, shared bytes) per permutation from cacao-inspect gpu's table."""
    rows, header = [], None
    for line in text.splitlines():
        cells = line.split()
        if cells[:1] == ['key']:
            header = cells
        elif header and len(cells) == len(header):
            row = dict(zip(header, cells))
            if all(row[k].isdigit() for k in ('regs', 'stack', 'shared')):
                rows.append((row['key'], int(row['regs']), int(row['stack']), int(row['shared'])))
        elif header and rows:
            break
    return rows


def text_part(parts, name):
    """A text file of a run (merged as NAME.txt; runs merged before that change keyed it NAME)."""
    v = parts.get(name + '.txt', parts.get(name))
    return v if isinstance(v, str) else ''


def estimator_results(parts):
    """[(estimator configuration, [its result against AMD HIGH per scene of SCENES, or None])] of a
    run's estimators part (device-sidebyside.py writes estimators.SCENE.CONFIG)."""
    names = sorted({k.split('.', 2)[2] for k in parts if k.startswith('estimators.')})
    return [(n, [parts['estimators.%s.%s' % (sc, n)]['results'][0] if 'estimators.%s.%s' % (sc, n) in parts else None
                 for sc in SCENES]) for n in names]


HORIZON_ROLES = ('horizon_direct', 'horizon', 'final', 'forms')


def horizon_role(runs):
    """The role of the run whose estimators part reports the horizon estimators: the latest, with
    their direct grids ('horizon_direct'), else the one after their GPU fills ('horizon'), else the
    final run's, else the older 'forms' run's (None without any)."""
    return next((r for r in HORIZON_ROLES if estimator_results(runs.get(r, {}))), None)


def horizon_run(runs):
    """That run's parts ({} without any)."""
    role = horizon_role(runs)
    return runs[role] if role else {}


def sm_clock(text):
    """The SM clock of an `nvidia-smi --query-gpu=...,clocks.sm,... --format=csv` reading."""
    lines = text.splitlines()
    first = next((k for k, l in enumerate(lines) if l.startswith('name,')), None)
    if first is None or first + 1 >= len(lines):
        return '?'
    head = [h.strip() for h in lines[first].split(',')]
    vals = [v.strip() for v in lines[first + 1].split(',')]
    i = next((k for k, h in enumerate(head) if h.startswith('clocks.current.sm') or h.startswith('clocks.sm')), None)
    return vals[i] if i is not None and i < len(vals) else '?'


def stage_ranges(fin):
    """cacao/AMD per stage over every scene and configuration of the final run (AMD's base pass
    counted with its generate, as cacao's GPU form of it is), and the range of cacao's tiles stage."""
    ratios, tiles = {}, []
    for sc in SCENES:
        for r in results_of(fin, 'cacao', sc).values():
            a, c = dict(r['amd']['stages']), r['cacao']['stages']
            a['generate'] = a.get('generate', 0.0) + a.pop('base', 0.0)
            for st in ('prepare', 'generate', 'blur', 'apply', 'upsample'):
                if a.get(st) and c.get(st):
                    ratios.setdefault(st, []).append(c[st] / a[st])
            if 'other' in c:
                tiles.append(c['other'])
    return ratios, tiles


def stage_of(parts, scene, cfg, stage):
    r = results_of(parts, 'cacao', scene).get(cfg)
    return r['cacao']['stages'].get(stage) if r else None


def scene_rows(cell, cfgs=AMD_CONFIGS):
    """One table row per configuration of cfgs: cell(scene, config) per scene of SCENES."""
    return ['| %s | %s |' % (cfg, ' | '.join(cell(sc, cfg) for sc in SCENES)) for cfg in cfgs]


def ratio_rows(before, after, cfgs=AMD_CONFIGS):
    """Table of cacao/AMD 'before / after' of two runs' cacao parts, per configuration and scene."""
    def cell(sc, cfg):
        b, a = results_of(before, 'cacao', sc).get(cfg), results_of(after, 'cacao', sc).get(cfg)
        return '%.2f / %.2f' % (b['ratio'], a['ratio']) if b and a else '-'
    return ['| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)] + scene_rows(cell, cfgs)


def us_range(values):
    values = [v for v in values if v is not None]
    return '%s-%s' % (us(min(values)), us(max(values))) if values else '-'


def steps_of(text, build, scene, flags):
    """{pass: median ms} of the first block of FUSED_STEPS for build, scene and cacao flags."""
    head = '== %s %s %s (round 1)' % (build, scene, flags)
    lines = text.splitlines()
    if head not in lines:
        return {}
    out = {}
    for l in lines[lines.index(head) + 2:]:
        if l.startswith('tiles:') or l.startswith('=='):
            break
        f = l.split()
        if len(f) >= 2:
            out[f[0]] = float(f[1])
    return out


def fused_section(fused, before):
    """The classification inside the GPU form of prepare: the run of that change against its parent."""
    out = ['', '### The tile classes from the prepare, measured (commit %s against %s)' % (C['fused'], C['fused_before']),
           '',
           'In the GPU forms with normals reconstructed from depth (AMD\'s reference setting), native, the prepare '
           'classifies the tiles of the texels it stores and no classify pass runs: the classify pass, its '
           'dispatch and its barrier took %s microseconds of each native frame in the run before (its tiles '
           'stage), for a few microseconds of work. Downsampled, and with the caller\'s normals, the classify '
           'pass still runs: with the classification in it, gfx11 spilled two registers of the downsampled '
           'prepare wherever it was placed (a register through its unrolled block, shared memory, the depths read '
           'again before or after the block). cacao/AMD, before / after, interleaved with AMD in one run of both '
           'builds (`%s`, `%s`; the same procedure as above; since then `classify_gpu` classifies there, below):' % (
               us_range([stage_of(before, sc, c, 'other') for sc in SCENES for c in AMD_CONFIGS if c.endswith('native')]),
               MEASURED['fused_before'], MEASURED['fused']), '']
    out += ratio_rows(before, fused)
    native = [c for c in AMD_CONFIGS if c.endswith('native')]
    pairs = [(results_of(before, 'cacao', sc).get(c), results_of(fused, 'cacao', sc).get(c)) for sc in SCENES for c in native]
    saved = [1000.0 * (b['cacao']['total_ms'] - f['cacao']['total_ms']) for b, f in pairs if b and f]
    after = [f['ratio'] for b, f in pairs if f]
    if saved:
        out += ['', 'Native, the frame is %.1f-%.1f microseconds shorter (cacao/AMD after: %.2f-%.2f over the 15 '
                'native pairs); downsampled nothing changed beyond the noise: there classify scans a tile\'s every '
                'layer until a texel that is not quiet (it stopped at the first layer with a texel that was not '
                'background, which called tiles faded whose other layers were active: a bug, found while building '
                'this), a little more work on faded tiles. The RADV estimates above do not see the dispatch and '
                'the barrier: they weigh the classification in the prepare about as they weighed the classify pass '
                '(its marks of the 3x3 tiles around an active one unrolled, which ACO otherwise weighs as a loop of '
                '64 iterations), so the estimated totals did not move.' % (min(saved), max(saved), min(after), max(after))]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'docs', 'gpu-measured', FUSED_STEPS)
    if os.path.exists(path):
        text = open(path).read()
        rows = []
        for sc in ('interior_fzkhaus', 'street_track'):
            for flags in ('--quality high', '--quality lowest --downsample'):
                b, f = steps_of(text, 'old', sc, flags), steps_of(text, 'new', sc, flags)
                if b and f:
                    prep = next((k for k in f if k.startswith('prepare')), None)
                    rows.append('| %s %s | %s | %s | %s / %s | %.0f / %.0f |' % (
                        sc, flags.replace('--', ''), '%.0f' % (1000 * b[prep]) if prep in b else '-',
                        '%.0f' % (1000 * b['classify']) if 'classify' in b else '-',
                        '%.0f' % (1000 * f[prep]) if prep in f else '-',
                        '%.0f' % (1000 * f['classify']) if 'classify' in f else '-',
                        1000 * b['total'], 1000 * f['total']))
        if rows:
            out += ['', 'Per pass (`cacao --timings --repeat 30 --no-normals`, 960x540, the two builds alternating, '
                    '`%s`), microseconds: prepare and classify before; prepare and classify after; total before / '
                    'after:' % FUSED_STEPS, '',
                    '| scene, settings | prepare before | classify before | prepare / classify after | total |',
                    '|---|---:|---:|---:|---:|'] + rows
    return out


# Per-pass timings of two classify shapes tried for the GPU forms before the prepare took the
# classification over (.gpu/steps.sh of that session; "new" the shape, "old" commit 16e6be8).
CLASSIFY_SHAPES = [('h100-classify-pertile-steps.txt', 'an NVIDIA H100',
                    'a workgroup per tile, an invocation per texel (its four layers), the flags met in shared memory'),
                   ('h200-classify-batched-steps.txt', 'an NVIDIA H200',
                    'an invocation per tile reading a layer\'s 16 gathers at once, the classes counted per '
                    'workgroup in shared memory; with compact\'s entries reserved per workgroup and list')]


def classify_shapes():
    """Lines on the classify shapes tried (their per-pass files in docs/gpu-measured)."""
    out = []
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'docs', 'gpu-measured')
    for name, gpu, what in CLASSIFY_SHAPES:
        path = os.path.join(here, name)
        if not os.path.exists(path):
            continue
        text = open(path).read()
        cells = []
        for sc in ('interior_fzkhaus', 'street_track'):
            for flags, label in (('--quality high', 'CACAO HIGH'), ('--estimator gtao --quality high', 'GTAO HIGH')):
                b, f = steps_of(text, 'old', sc, flags), steps_of(text, 'new', sc, flags)
                kb = next((k for k in b if k.startswith('classify')), None)
                kf = next((k for k in f if k.startswith('classify')), None)
                if kb and kf:
                    cells.append('%s %s %.0f -> %.0f' % (sc, label, 1000 * b[kb], 1000 * f[kf]))
        if cells:
            out.append('- A GPU shape of classify, %s (`%s`, %s, 960x540, per-pass microseconds before -> after): '
                       '%s. Not kept: what the pass costs is its dispatch and barrier, not its work (the prepare '
                       'took it over, above).' % (what, name, gpu, '; '.join(cells)))
    return out


def result_pairs(before, after, cfgs=AMD_CONFIGS):
    """(before, after) cacao results of every scene of SCENES and configuration of cfgs both runs have."""
    pairs = [(results_of(before, 'cacao', sc).get(c), results_of(after, 'cacao', sc).get(c)) for sc in SCENES for c in cfgs]
    return [(b, a) for b, a in pairs if b and a]


def step_range(before, after, step, cfgs):
    """'b -> a' microseconds (ranges over the scenes and cfgs) of one pass of cacao_steps, '-' without it."""
    b = [(results_of(before, 'cacao', sc).get(c) or {}).get('cacao_steps', {}).get(step) for sc in SCENES for c in cfgs]
    a = [(results_of(after, 'cacao', sc).get(c) or {}).get('cacao_steps', {}).get(step) for sc in SCENES for c in cfgs]
    return '%s -> %s' % (us_range(b), us_range(a))


def chain_section(fin, before):
    """The final run against its "before" (the GPU forms' depth mip chain and the changes with it)."""
    out = ['', '### The depth mip chain and the changes with it, measured in the same run', '',
           'cacao/AMD, "before" (commit %s) / final (commit %s), each build interleaved with AMD in one run, scene '
           'by scene (`%s`, `%s`). Between them: the GPU forms\' depths as a mip chain, read by one `textureLod` a '
           'tap (Q0 and Q1 at LOD 0, where they used `texelFetch`; Q2 and Q3 at the tap\'s level, where they '
           'computed the atlas\'s level, extent and texel and used `texelFetch` (Q2) or `imageLoad` (Q3)); '
           'generate\'s obscurance with two max0 fewer; the blur\'s branch-free mirror; the upsample without a '
           'select per weight ("The GPU forms" above).' % (C['chain_before'], C['final'], MEASURED['chain_before'],
                                                           MEASURED['final']), '']
    out += ratio_rows(before, fin)
    pairs = [(cfg, results_of(before, 'cacao', sc).get(cfg), results_of(fin, 'cacao', sc).get(cfg))
             for sc in SCENES for cfg in AMD_CONFIGS]
    pairs = [(cfg, b, f) for cfg, b, f in pairs if b and f]
    if not pairs:
        return out
    saved = lambda sel: [1000.0 * (b['cacao']['total_ms'] - f['cacao']['total_ms']) for cfg, b, f in pairs if sel(cfg)]
    hi = saved(lambda c: c.startswith('HIGH'))
    ds = saved(lambda c: c.endswith('downsampled') and not c.startswith('HIGH'))
    q0 = [-v for v in saved(lambda c: c in ('LOWEST_native', 'LOW_native'))]
    rng = lambda v: '%.1f to %.1f' % (min(v), max(v))
    native = [c for c in AMD_CONFIGS if c.endswith('native')]
    down = [c for c in AMD_CONFIGS if c.endswith('downsampled')]
    out += ['',
            'Per pass (cacao_steps of the same runs, microseconds over the three scenes, before -> after):', '',
            '- **Q2 and Q3 through the mip chain: the gain the estimate predicted, measured.** `generate_gpu.q2` '
            '%s native, %s downsampled; `generate_gpu.q3` %s native, %s downsampled; the Q3 base pass %s native. '
            'The frames at HIGH and HIGHEST are %s microseconds shorter. The doubt the earlier runs left (Q3\'s '
            'taps were slower through `texelFetch` of the sampled view than through `imageLoad`, section "An '
            'earlier change") does not hold for the sampler at the tap\'s level: on this GPU the sampler\'s '
            'level and texel choice replaces the address arithmetic at no cost.' % (
                step_range(before, fin, 'generate_gpu.q2', ['HIGH_native']),
                step_range(before, fin, 'generate_gpu.q2', ['HIGH_downsampled']),
                step_range(before, fin, 'generate_gpu.q3', ['HIGHEST_native']),
                step_range(before, fin, 'generate_gpu.q3', ['HIGHEST_downsampled']),
                step_range(before, fin, 'generate_gpu.q3base', ['HIGHEST_native']), rng(hi)),
            '- **The upsample without a select per weight**: `upsample.half.fp32` %s, `upsample.nonsmart.fp32` %s, '
            '`upsample.smart.fp32` %s; the downsampled frames below HIGH are %s microseconds shorter.' % (
                step_range(before, fin, 'upsample.half.fp32', down),
                step_range(before, fin, 'upsample.nonsmart.fp32', down),
                step_range(before, fin, 'upsample.smart.fp32', down), rng(ds)),
            '- **Q0 through the sampler at LOD 0 costs this GPU a little**: `generate_gpu.q0` %s at LOWEST native, '
            '%s at LOW native (`texelFetch` -> `textureLod`; those frames %s microseconds longer), while Q1 gained (`generate_gpu.q1` %s at MEDIUM native). On navi21 the estimate of q0 went '
            'from 196 to 167 cycles per wave with the same change. Kept: the loss is a few microseconds of a frame '
            'on this GPU (the CPU form\'s `imageLoad` of the atlas is the fastest of the three here: "The shader '
            'forms on this GPU" below), the estimated gain on AMD\'s GPUs larger; a real AMD GPU would settle it.' % (
                step_range(before, fin, 'generate_gpu.q0', ['LOWEST_native']),
                step_range(before, fin, 'generate_gpu.q0', ['LOW_native']), rng(q0),
                step_range(before, fin, 'generate_gpu.q1', ['MEDIUM_native'])),
            '- The blur (`blur_gpu.2.fp32` %s native) and the prepare (`prepare_gpu.full.native` %s) did not move '
            'beyond the noise.' % (step_range(before, fin, 'blur_gpu.2.fp32', native),
                                   step_range(before, fin, 'prepare_gpu.full.native', native))]
    return out


def ab_head(title, role, before_role, text, before, after, cfgs=AMD_CONFIGS):
    """A before/after section's heading, its text (%s, %s: the runs' files) and its cacao/AMD table."""
    return (['', '### %s (commit %s against %s)' % (title, C[role], C[before_role]), '',
             text % (MEASURED[before_role], MEASURED[role]), ''] + ratio_rows(before, after, cfgs))


def classify_groups_section(after, before):
    """The downsampled prepare classifying in groups of its own, against classify_gpu before it."""
    down = [c for c in AMD_CONFIGS if c.endswith('downsampled')]
    pairs = result_pairs(before, after, down)
    saved = [1000.0 * (b['cacao']['total_ms'] - a['cacao']['total_ms']) for b, a in pairs]
    out = ab_head('The classification in the prepare\'s own groups, downsampled, measured', 'classify_groups',
                  'classify_groups_before',
                  'Downsampled with normals from depth, `prepare_gpu`\'s dispatch has twice the groups: those at z 0 '
                  'compute the tile classes from the caller\'s depth (the function `classify_gpu` runs, 2x2 slice texels '
                  'an invocation, a group per 2x2 tiles: the same footprint as a prepare group), those at z 1 prepare. One '
                  'dispatch instead of two (`classify_gpu`, then the prepare, with no barrier between), and the '
                  'prepare\'s code holds no classification (in it, gfx11 spilled two registers). The two builds, each '
                  'interleaved with AMD, scene by scene, the downsampled configurations (`%s`, `%s`). cacao/AMD, before / '
                  'after:', before, after, down)
    if saved:
        out += ['', 'The frames are %.1f-%.1f microseconds shorter; the prepare step, its classification groups '
                'included, takes %s microseconds where `classify_gpu` and the prepare took %s and %s: the second '
                'dispatch was what cost. Since then cacao takes %.2f-%.2f of AMD\'s time downsampled on this GPU '
                '(this run).' % (
                    min(saved), max(saved),
                    us_range([a['cacao']['stages'].get('prepare') for b, a in pairs]),
                    us_range([b['cacao_steps'].get('classify_gpu.downsampled') for b, a in pairs]),
                    us_range([b['cacao']['stages'].get('prepare') for b, a in pairs]),
                    min(a['ratio'] for b, a in pairs), max(a['ratio'] for b, a in pairs))]
    return out


def classify_gpu_section(after, before):
    """The classes from the caller's depth (classify_gpu) against the classify pass after the prepare."""
    out = ab_head('The classes from the caller\'s depth, measured', 'classify_gpu', 'classify_gpu_before',
                  'Where the GPU forms\' prepare does not classify (downsampled, and with the caller\'s normals), '
                  '`classify_gpu` computes the tile classes from the caller\'s depth, before the prepare and with no '
                  'barrier between them, in place of the classify pass over the stored depths after the prepare (a '
                  'barrier, a dispatch, a barrier; docs/tiles.md). A later run than the final one, of both builds, each '
                  'interleaved with AMD, scene by scene (`%s`, `%s`; the cacao part only). cacao/AMD, before / after:',
                  before, after)
    saved = {}
    for sc in SCENES:
        for cfg in AMD_CONFIGS:
            b, f = results_of(before, 'cacao', sc).get(cfg), results_of(after, 'cacao', sc).get(cfg)
            if b and f and cfg.endswith('downsampled'):
                saved.setdefault(sc, []).append(1000.0 * (b['cacao']['total_ms'] - f['cacao']['total_ms']))
    nat = [1000.0 * (b['cacao']['total_ms'] - f['cacao']['total_ms'])
           for sc in SCENES for cfg in AMD_CONFIGS if cfg.endswith('native')
           for b, f in [(results_of(before, 'cacao', sc).get(cfg), results_of(after, 'cacao', sc).get(cfg))] if b and f]
    if saved:
        down = [c for c in AMD_CONFIGS if c.endswith('downsampled')]
        out += ['', 'Downsampled frames shorter by %s microseconds (per scene); the native ones, which run no '
                'classification pass either way (the prepare classifies), changed by %.1f to %.1f (the noise). Per pass '
                '(cacao_steps, microseconds over the three scenes, before -> after): the classification %s -> %s; '
                'the prepare %s -> %s (its timestamp is taken when it ends: it began while `classify_gpu` ran). What the '
                'frame saves is a barrier and the overlap. Less on interior_fzkhaus: there the classify pass was the '
                'shortest (it stops a tile\'s scan at its first active texel, and nearly every tile is active), '
                'shorter than `classify_gpu`, which reads every texel.' % (
                    '; '.join('%s %.1f to %.1f' % (sc, min(v), max(v)) for sc, v in saved.items()),
                    -max(nat) if nat else 0.0, -min(nat) if nat else 0.0,
                    step_range(before, before, 'classify', down).split(' -> ')[0],
                    step_range(after, after, 'classify_gpu.downsampled', down).split(' -> ')[0],
                    us_range([(results_of(before, 'cacao', sc).get(c) or {}).get('cacao', {}).get('stages', {}).get('prepare')
                              for sc in SCENES for c in down]),
                    us_range([(results_of(after, 'cacao', sc).get(c) or {}).get('cacao', {}).get('stages', {}).get('prepare')
                              for sc in SCENES for c in down]))]
    return out


def measured_section(runs, results):
    """The real GPU's timings as markdown lines (none without the 'final' run)."""
    if 'final' not in runs:
        return []
    fin = runs['final']
    proc = next(v for k, v in fin.items() if k.startswith('cacao.'))['procedure']
    machine, after = text_part(fin, 'machine'), text_part(fin, 'machine_after')
    device = line_of(text_part(fin, 'devices'), '0:')
    clocks = (sm_clock(machine), sm_clock(after))
    navi = by_name(results['navi21']) if 'navi21' in results else {}
    out = ['## Measured on a real GPU (%s)' % device.split(':', 1)[-1].strip(), '',
           'These are timings, not estimates: GPU timestamps in milliseconds, first to last pass of a frame, cacao '
           'and AMD FidelityFX CACAO v1.2 (AMD\'s own code, `../shared/amd-cacao/amd_cacao --device`) side by side '
           'in one run on one machine: `tools/device-sidebyside.py --device NVIDIA` (`../shared/amd-cacao/sidebyside.py`: '
           'fresh processes, AMD and cacao alternately, %d runs of each per configuration, each timing %d frames after '
           '%d warm-up frame; the median over the frames, then over the runs). 1920x1080: the nearest 2x upscale of each '
           'scene\'s depth; AMD\'s reference settings of each scene on both sides (fp32, normals reconstructed from '
           'depth, blur 2). The GPU\'s clocks are its driver\'s own (this workplace leaves the GPU\'s settings as they '
           'are): `nvidia-smi` read an SM clock of %s before the run and %s after it; both sides ran under the '
           'same conditions, interleaved. In frames this short (0.06-0.35 ms) the fixed costs of each dispatch, barrier '
           'and workgroup weigh heavily (the tables below), and no compiler statistic shows them. %s' % (
               proc['reps'], proc['frames'], proc['warmup_frames'], clocks[0], clocks[1], MEASURED_CODE),
           '', '### Totals: cacao / AMD', '',
           '| configuration | AMD ms (interior) | cacao ms (interior) | cacao/AMD interior | statues | street | '
           'navi21 estimate (RADV, below: this report\'s code) |', '|---|---:|---:|---:|---:|---:|---:|']
    ratios = []
    for cfg in AMD_CONFIGS:
        per = [results_of(fin, 'cacao', sc).get(cfg) for sc in SCENES]
        ratios += [r['ratio'] for r in per if r]
        first = per[0]
        est = navi.get(cfg.lower())
        est_ratio = ratio(est['cacao']['total_cycles'], est['amd']['total_cycles']) if est else '-'
        out.append('| %s | %s | %s | %s | %s |' % (
            cfg, '%.3f' % first['amd']['total_ms'] if first else '-', '%.3f' % first['cacao']['total_ms'] if first else '-',
            ' | '.join('%.2f' % r['ratio'] if r else '-' for r in per), est_ratio))
    ests = [navi[c.lower()]['cacao']['total_cycles'] / navi[c.lower()]['amd']['total_cycles']
            for c in AMD_CONFIGS if c.lower() in navi and navi[c.lower()]['amd']['total_cycles']]
    if ratios:
        below = ['%s %s' % (sc.split('_')[0], cfg) for cfg in AMD_CONFIGS for sc in SCENES
                 if (results_of(fin, 'cacao', sc).get(cfg) or {}).get('ratio', 9.0) < 1.0]
        out += ['', '**On this GPU cacao takes %.2f-%.2fx AMD\'s time** over the %d scene x configuration pairs, '
                'less than AMD\'s in %d of them (%s), where the RADV estimate below (navi21), of the code this '
                'report was made from (newer than the timed commit where they differ), puts it at %s of '
                'AMD\'s cost. The estimate counts issued instructions; what it leaves out (the fixed cost of each '
                'dispatch and barrier, workgroup launches, memory) decides frames this short.' % (
                    min(ratios), max(ratios), len(ratios), len(below), ', '.join(below) or 'none',
                    '%.2f-%.2f' % (min(ests), max(ests)) if ests else '(not run)')]
    # per stage
    out += ['', '### Per stage (interior_fzkhaus, microseconds, AMD / cacao)', '',
            'Stages as sidebyside.py groups the passes. cacao\'s "tiles" stage is its tile classification '
            '(`classify`: one dispatch, which AMD does not have); its GPU form of the Q3 base pass is counted in '
            'generate (AMD\'s base pass has a column of its own: compare their sum).', '',
            '| configuration | ' + ' | '.join('tiles' if s == 'other' else s for s in MEASURED_STAGES) + ' |',
            '|---|' + '---:|' * len(MEASURED_STAGES)]
    for cfg, r in results_of(fin, 'cacao', SCENES[0]).items():
        a, c = r['amd']['stages'], r['cacao']['stages']
        out.append('| %s | %s |' % (cfg, ' | '.join(
            '' if s not in a and s not in c else '%s / %s' % (us(a.get(s)), us(c.get(s))) for s in MEASURED_STAGES)))
    ratios, tiles = stage_ranges(fin)
    if ratios:
        out += ['', 'Over the 30 scene x configuration pairs, cacao/AMD per stage: %s; and cacao\'s tiles stage '
                'takes %s-%s microseconds.' % ('; '.join('%s %.2f-%.2f' % (st, min(v), max(v)) for st, v in ratios.items()),
                                               us(min(tiles)), us(max(tiles)))]
    # the changes measured in the final run
    if 'chain_before' in runs:
        out += chain_section(fin, runs['chain_before'])
    if 'classify_groups' in runs and 'classify_groups_before' in runs:
        out += classify_groups_section(runs['classify_groups'], runs['classify_groups_before'])
    if 'classify_gpu' in runs and 'classify_gpu_before' in runs:
        out += classify_gpu_section(runs['classify_gpu'], runs['classify_gpu_before'])
    # an earlier session's final run and its changes
    if 'before' in runs and 'prev_final' in runs:
        bef, lists, pfin = runs['before'], runs.get('lists', {}), runs['prev_final']
        out += ['', '### Earlier changes, measured in an earlier run (commit %s)' % C['prev_final'], '',
                'cacao/AMD of the three builds, interleaved with AMD in one run: "lists" (%s) / "before" '
                '(%s) / that session\'s final (%s).' % (C['lists'], C['before'], C['prev_final']), '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        out += scene_rows(lambda sc, cfg: ' / '.join(
            '%.2f' % r['ratio'] if r else '-' for r in (results_of(x, 'cacao', sc).get(cfg) for x in (lists, bef, pfin))))
        def stage_values(parts, stage, cfgs=AMD_CONFIGS):
            return [stage_of(parts, sc, c, stage) for sc in SCENES for c in cfgs]
        native = [c for c in AMD_CONFIGS if c.endswith('native')]
        out += ['',
                '- **Skipping in the shader instead of tile lists** ("lists" -> "before"): the tiles stage went '
                'from %s to %s microseconds (classify, compact, two fills and indirect dispatches -> classify '
                'alone); most on the scenes whose fills had work (street_track LOWEST native: %s -> %s).' % (
                    us_range(stage_values(lists, 'other')), us_range(stage_values(bef, 'other')),
                    us(stage_of(lists, 'street_track', 'LOWEST_native', 'other')),
                    us(stage_of(bef, 'street_track', 'LOWEST_native', 'other'))),
                '- **`apply_gpu` with 2x2 pixels per invocation** (each through the sampler, as before): apply %s '
                '-> %s microseconds over the native configurations (AMD\'s: %s). A quarter of the workgroups; '
                'the same reads per pixel. On navi21 the RADV estimate of the stage falls too (below).' % (
                    us_range(stage_values(bef, 'apply', native)), us_range(stage_values(pfin, 'apply', native)),
                    us_range([(results_of(pfin, 'cacao', sc).get(c) or {}).get('amd', {}).get('stages', {}).get('apply')
                              for sc in SCENES for c in native])),
                '- **The Q3 base pass one slice texel per invocation** (the importance map reduced in shared '
                'memory; the CPU form computes 16 texels per invocation): HIGHEST\'s generate stage (base pass '
                'and Q3) %s -> %s native, %s -> %s downsampled (interior_fzkhaus).' % (
                    us(stage_of(bef, SCENES[0], 'HIGHEST_native', 'generate')),
                    us(stage_of(pfin, SCENES[0], 'HIGHEST_native', 'generate')),
                    us(stage_of(bef, SCENES[0], 'HIGHEST_downsampled', 'generate')),
                    us(stage_of(pfin, SCENES[0], 'HIGHEST_downsampled', 'generate'))),
                '- **classify\'s marks as atomics nothing waits for**, the needed groups counted by generate and '
                'the blur as they run them: tiles stage %s -> %s microseconds; generate pays about a microsecond '
                'for the count (interior_fzkhaus LOWEST native: %s -> %s).' % (
                    us_range(stage_values(bef, 'other')), us_range(stage_values(pfin, 'other')),
                    us(stage_of(bef, SCENES[0], 'LOWEST_native', 'generate')),
                    us(stage_of(pfin, SCENES[0], 'LOWEST_native', 'generate')))]
    if 'fused' in runs and 'fused_before' in runs:
        out += fused_section(runs['fused'], runs['fused_before'])
    # experiments
    exp = []
    if 'upsample' in runs and 'upsample_before' in runs:
        pairs = [(stage_of(runs['upsample_before'], sc, c, 'upsample'), stage_of(runs['upsample'], sc, c, 'upsample'))
                 for sc in SCENES for c in AMD_CONFIGS if c.endswith('downsampled')]
        pairs = [p for p in pairs if p[0] and p[1]]
        if pairs:
            q = sorted(b / a for a, b in pairs)
            exp.append('- The upsample with 16x16 threads of one half-resolution position each (today: 8x8 threads '
                       'of 2x2 positions, 110-127 registers on this GPU) (`%s`): upsample stage after / before '
                       '%.3f-%.3f over %d pairs. Not kept: the registers are not what it waits on.' % (
                           MEASURED['upsample'], q[0], q[-1], len(q)))
    if 'diag' in runs and 'prev_final' in runs:
        pairs = [(stage_of(runs['prev_final'], SCENES[0], c, 'generate'), stage_of(runs['diag'], SCENES[0], c, 'generate'))
                 for c in AMD_CONFIGS]
        pairs = [(c, p) for c, p in zip(AMD_CONFIGS, pairs) if p[0] and p[1]]
        if pairs:
            exp.append('- Where generate\'s time goes (it is 1.0-1.9x AMD\'s at HIGH and HIGHEST, where the RADV '
                       'estimate puts it below AMD\'s): a diagnostic build that reads every tap at level 0 of the '
                       'depths, without the atlas level, extent and place arithmetic (`%s`, same run): %s '
                       'microseconds, commit %s / diagnostic. The per-tap address arithmetic (of the atlas) is not the cost.' % (
                           MEASURED['diag'], '; '.join('%s %s / %s' % (c, us(p[0]), us(p[1])) for c, p in pairs),
                           C['prev_final']))
    if 'atomics' in runs and 'atomics_before' in runs:
        ratios_a = []
        for cfg, b in results_of(runs['atomics_before'], 'cacao', SCENES[0]).items():
            f = results_of(runs['atomics'], 'cacao', SCENES[0]).get(cfg)
            if f and 'other' in f['cacao']['stages'] and 'other' in b['cacao']['stages']:
                ratios_a.append(f['cacao']['stages']['other'] / b['cacao']['stages']['other'])
        if ratios_a:
            exp.append('- An earlier session gathered classify\'s and compact\'s atomic additions per workgroup '
                       '(`%s`): the tiles stage after / before %.2f-%.2f; not kept. What paid this session was '
                       'the chain of atomics each active tile waited on (above).' % (
                           MEASURED['atomics'], min(ratios_a), max(ratios_a)))
    if 'classify_fused' in runs and 'classify_nofuse' in runs:
        pairs = result_pairs(runs['classify_fused'], runs['classify_nofuse'],
                             [c for c in AMD_CONFIGS if c.endswith('native')])
        longer = [1000.0 * (n['cacao']['total_ms'] - f['cacao']['total_ms']) for f, n in pairs]
        cls = [n.get('cacao_steps', {}).get('classify_gpu.native') for f, n in pairs]
        prep = [(f['cacao']['stages'].get('prepare'), n['cacao']['stages'].get('prepare')) for f, n in pairs]
        if longer:
            exp.append('- `classify_gpu` for the native frames too, the prepare not classifying (a build of commit '
                       'f745aa5 so changed, against f745aa5 in one run: `%s`, `%s`): native frames %.1f-%.1f '
                       'microseconds longer. `classify_gpu` took %s microseconds there (four times the tiles of a '
                       'downsampled frame), the prepare %s -> %s: the classification inside the prepare costs it less '
                       'than a pass of its own, barrier or not. Not kept.' % (
                           MEASURED['classify_fused'], MEASURED['classify_nofuse'], min(longer), max(longer),
                           us_range(cls), us_range([p[0] for p in prep]), us_range([p[1] for p in prep])))
    if 'classify_quad' in runs and 'classify_quad_before' in runs:
        pairs = result_pairs(runs['classify_quad_before'], runs['classify_quad'])
        diff = [1000.0 * (b['cacao']['total_ms'] - q['cacao']['total_ms']) for b, q in pairs]
        steps = [(b['cacao_steps'].get('classify_gpu.downsampled'), q['cacao_steps'].get('classify_gpu.downsampled'))
                 for b, q in pairs]
        if diff:
            exp.append('- `classify_gpu` with 2x2 slice texels per invocation, a workgroup per 2x2 tiles (the shape of '
                       'the prepare\'s own classification), against one texel per invocation and a workgroup per tile '
                       '(`%s`, `%s`; a build of commit f745aa5 so changed, the downsampled configurations in one run): '
                       'the frames changed by %.1f to %.1f microseconds (shorter: positive), `classify_gpu` took %s '
                       'then %s microseconds. At a downsampled frame\'s 2040 tiles its time is not its work. Not kept.' % (
                           MEASURED['classify_quad_before'], MEASURED['classify_quad'], min(diff), max(diff),
                           us_range([x[0] for x in steps]), us_range([x[1] for x in steps])))
    exp += classify_shapes()
    if exp:
        out += ['', '### Tried and not kept, or diagnostic', ''] + exp
    # an earlier change
    if 'tf_final' in runs and 'tf_before' in runs:
        out += ['', '### An earlier change, measured: generate\'s taps through the sampled view', '',
                'The GPU form of generate at Q0..Q2 fetches its taps\' depths through the sampled view of the '
                'depth atlas (`texelFetch`), where the CPU form, and Q3 and its base pass, load them from the '
                'storage image (`imageLoad`: lavapipe runs that faster). Same texels, same output (since '
                'replaced by the mip chain, "The GPU forms" above). The generate '
                'stage in microseconds, before / after, in an earlier session\'s run (commits %s / %s):' % (C['tf_before'], C['tf_final']), '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        def generate_cell(sc, cfg):
            b, f = stage_of(runs['tf_before'], sc, cfg, 'generate'), stage_of(runs['tf_final'], sc, cfg, 'generate')
            return '%s / %s' % (us(b), us(f)) if b and f else '-'
        out += scene_rows(generate_cell)
        if 'forms' in runs and 'forms_before' in runs:
            cells = []
            for sc in SCENES:
                b = stage_of(runs['forms_before'], sc, 'HIGHEST_native', 'generate')
                f = stage_of(runs['forms'], sc, 'HIGHEST_native', 'generate')
                if b and f:
                    cells.append('%s: %s -> %s' % (sc, us(b), us(f)))
            out += ['', 'Why Q3 keeps `imageLoad`: a run with `texelFetch` in every variant (%s) made HIGHEST '
                    'native\'s generate stage (the Q3 base pass and Q3) slower: %s microseconds, before -> after.'
                    % (MEASURED['forms'], '; '.join(cells))]
    # the shader forms
    cpu = results_of(fin, 'cpuforms', SCENES[0])
    gpu = results_of(fin, 'cacao', SCENES[0])
    if cpu and gpu:
        out += ['', '### The shader forms on this GPU (interior_fzkhaus, the final run)', '',
                'A context on a GPU runs the GPU forms; `--shader-forms cpu` runs lavapipe\'s. Microseconds, '
                'AMD / GPU form / CPU form:', '',
                '| configuration | cacao/AMD, GPU forms | cacao/AMD, CPU forms | blur | apply or upsample | generate |',
                '|---|---:|---:|---:|---:|---:|']
        for cfg in AMD_CONFIGS:
            g, c = gpu.get(cfg), cpu.get(cfg)
            if not g or not c:
                continue
            fin_stage = 'upsample' if 'downsampled' in cfg else 'apply'
            cell = lambda s: '%s / %s / %s' % (us(g['amd']['stages'].get(s)), us(g['cacao']['stages'].get(s)),
                                               us(c['cacao']['stages'].get(s)))
            out.append('| %s | %.2f | %.2f | %s | %s | %s |' % (cfg, g['ratio'], c['ratio'], cell('blur'),
                                                               cell(fin_stage), cell('generate')))
        out += ['', 'The GPU forms are the faster ones here, with two exceptions at LOWEST and LOW native. The '
                'non-smart apply (LOW) of the CPU form, 2x2 pixels filtered by hand from one gather per layer, is '
                'faster on this GPU than the GPU form\'s 2x2 pixels through the sampler, where the RADV estimate '
                'puts the CPU form at several times the GPU form\'s cost on AMD\'s GPUs; the GPU form keeps the '
                'sampler. And generate at Q0 is faster through the CPU form\'s `imageLoad` of the atlas than '
                'through the GPU form\'s `textureLod` (the section before). The CPU forms\' '
                'tiles stage is classify, compact and fills over lists. The upsample has one form.']
    # the horizon estimators (the later run after their fix, else the final run's)
    hor = horizon_run(runs)
    rows = estimator_results(hor)
    if rows:
        role = horizon_role(runs)
        out += ['', '### The horizon-slice estimators against AMD HIGH (%s)' % (
            'a later run, commit %s' % C[role] if hor is not fin else 'the final run'), '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        for n, per in rows:
            out.append('| %s (1 denoise pass) | %s |' % (n, ' | '.join(
                '%.3f ms / %.3f ms = %.2f' % (r['cacao']['total_ms'], r['amd']['total_ms'], r['ratio']) if r else '-'
                for r in per)))
    before = runs.get('horizon_direct_before', {})
    if rows and estimator_results(before):
        prev = dict(estimator_results(before))
        saved = []
        out += ['', '**Since commit %s the GPU forms of the horizon estimators run no classify, compact, clear or '
                'fill pass**: the prepare (`horizon_prepare_gpu`) stores every pixel and classifies its tile (a '
                'workgroup is one), the estimator and the denoise passes (`horizon_main_gpu`, '
                '`horizon_denoise_gpu`; the downsampled estimator was already a direct grid) run every tile and '
                'store AO 1 in the tiles that are not needed, as CACAO\'s generate and blur do. cacao/AMD HIGH, '
                'before (commit %s) / after (commit %s), each build timed against AMD in the same session '
                '(`%s`, `%s`):' % (
                    C['horizon_direct_since'], C['horizon_direct_before'], C['horizon_direct'],
                    MEASURED['horizon_direct_before'], MEASURED['horizon_direct']), '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        for n, per in rows:
            cells = []
            for sc, r, b in zip(SCENES, per, prev.get(n, [None] * len(SCENES))):
                cells.append('%.2f / %.2f' % (b['ratio'], r['ratio']) if r and b else '-')
                if r and b:
                    saved.append(1000.0 * (b['cacao']['total_ms'] - r['cacao']['total_ms']))
            out.append('| %s | %s |' % (n, ' | '.join(cells)))
        if saved:
            cells = []
            path = os.path.join(ROOT, 'docs', 'gpu-measured', 'h200-horizon-direct-steps.txt')
            if os.path.isfile(path):
                text = open(path).read()
                for sc in ('interior_fzkhaus', 'street_track'):
                    for flags in ('--estimator gtao --quality high', '--estimator bitmask --quality highest --downsample'):
                        b, f = steps_of(text, 'old', sc, flags), steps_of(text, 'new', sc, flags)
                        small = sum(v for k, v in b.items() if k.split('.')[0] in ('classify', 'compact', 'fill', 'horizon_prepare'))
                        prep = sum(v for k, v in f.items() if k.startswith('horizon_prepare'))
                        if b and f:
                            cells.append('%s %s: %.0f -> %.0f (total %.0f -> %.0f)' % (
                                sc, flags.replace('--estimator ', '').replace('--quality ', '').replace('--', ''),
                                1000 * small, 1000 * prep, 1000 * b['total'], 1000 * f['total']))
            out += ['', 'The frames became %.0f-%.0f microseconds shorter. Per pass at 960x540 '
                    '(`docs/gpu-measured/h200-horizon-direct-steps.txt`, `cacao --timings --repeat 30 --no-normals`, '
                    'the two builds alternating), classify, compact, the fills and the prepare before against the '
                    'prepare after, microseconds: %s.' % (min(saved), max(saved), '; '.join(cells) or '-')]
    steps = os.path.join(ROOT, 'docs', 'gpu-measured', 'h200-horizon-steps.txt')
    if rows and os.path.isfile(steps):
        with open(steps) as f:
            body = [l.rstrip('\n') for l in f if not l.startswith('#')]
        out += ['', '**Commit 97cb2c7 had made these frames about twice as long on this GPU**: it gave the '
                'horizon estimators clear steps (`vkCmdClearColorImage`) where fill dispatches wrote their '
                'intermediates, and on this GPU a clear of the view z costs 90 microseconds and one of the AO 41 '
                'at 960x540, where the fills took 4 each. From commit %s to %s the GPU forms filled with a '
                'dispatch over every tile that skipped the tiles a later pass writes (`fill.view_all`, '
                '`fill.horizon_all`; since then they need no fill, above); the CPU forms keep the clears, which '
                'lavapipe runs faster (docs/tiles.md). Per-pass `--timings` '
                '(`docs/gpu-measured/h200-horizon-steps.txt`: median ms, min, max; "final" %s, "fixed" '
                '%s, "old" %s):' % (C['horizon'], C['horizon_direct_since'], C['prev_final'], C['horizon'], C['lists']), '',
                '```'] + body + ['```']
    # the driver's statistics
    text = text_part(fin, 'stats.cacao')
    if text:
        rows = nvidia_stats(text)
        amd = fin.get('stats.amd', [])
        if rows:
            spilled = [r[0] for r in rows if r[2] > 0]
            top = sorted(rows, key=lambda r: -r[1])[:8]
            out += ['', '### What the driver reports of the pipelines (`cacao-inspect gpu --all --device NVIDIA`)', '',
                    '%s: %d permutations of the GPU forms compiled; %s. Registers per thread, the most: %s. AMD\'s '
                    '33 pipelines: %d-%d registers, stack %s.' % (
                        line_of(text, 'device:').replace('device: ', ''), len(rows),
                        'none has stack (spill) memory' if not spilled else 'stack memory in ' + ', '.join(spilled),
                        ', '.join('%s %d' % (r[0], r[1]) for r in top),
                        min(p['stats'].get('Register Count', 0) for p in amd) if amd else 0,
                        max(p['stats'].get('Register Count', 0) for p in amd) if amd else 0,
                        'none' if amd and all(p['stats'].get('Stack Size', 0) == 0 for p in amd) else 'in some')]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--inspect', default=os.path.join(ROOT, 'build/tools/inspect/cacao-inspect'))
    ap.add_argument('--amd-pipelines', default=os.path.join(ROOT, '../shared/amd-cacao/amd_cacao_pipelines'))
    ap.add_argument('--icd', default='/usr/share/vulkan/icd.d/radeon_icd.x86_64.json')
    ap.add_argument('--families', default='vega10,navi21,gfx1100')
    ap.add_argument('--measured', default=os.path.join(ROOT, 'docs/gpu-measured'))
    ap.add_argument('--out', default=os.path.join(ROOT, 'docs/gpu.md'))
    a = ap.parse_args()
    for path, what in ((a.inspect, '--inspect'), (a.amd_pipelines, '--amd-pipelines'), (a.icd, '--icd')):
        if not os.path.exists(path):
            sys.exit('%s %s: not found' % (what, path))
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for family in a.families.split(','):
            results[family] = measure(a, family, work)
    first = next(iter(results.values()))
    runs = load_measured(a.measured)
    timed = [r['ratio'] for sc in SCENES for r in results_of(runs.get('final', {}), 'cacao', sc).values()]
    later = [a['ratio'] for b, a in result_pairs(runs.get('classify_groups_before', {}), runs.get('classify_groups', {}))]
    doc = HEADER % {'driver': first['driver'], 'above': sum(1 for r in timed if r > 1.0), 'pairs': len(timed),
                    'later': 'downsampled %.2f-%.2fx in a later run of newer code' % (min(later), max(later))
                             if later else 'its final run',
                    'measured': '%.2f-%.2fx' % (min(timed), max(timed)) if timed else '(not measured)', 'issue': '\n'.join(issue_comparison(results['navi21']))
                    if 'navi21' in results else '(navi21 not measured)',
                    'overview': '\n'.join(overview(results))}
    parts = [doc.rstrip('\n'), ''] + targets_section(results)
    measured = measured_section(runs, results)
    if measured:
        parts += [''] + measured
    for family, result in results.items():
        parts += ['', '## %s: `RADV_FORCE_FAMILY=%s` (%s)' % (FAMILY_NAMES.get(family, family), family,
                                                              result['device']), '',
                  '### Estimated Mcycles per frame: cacao / AMD (cacao/AMD)', ''] + config_table(result)
        parts += ['', 'The horizon-slice estimators (no AMD counterpart; the main pass weighed by its budget, slices x steps per side, see Loops), against AMD\'s HIGH:', '']
        parts += horizon_table(result)
        parts += ['', '### Scratch and spills', ''] + spill_lines(result)
        parts += ['', '### The CPU forms (`--shader-forms cpu`: lavapipe\'s shapes, which a context on a GPU never '
                  'runs), scratch and spills', ''] + spill_lines(result['cpu_forms'])
        parts += ['', '### Every permutation (bold: uses scratch)', ''] + permutation_table(result)
        parts += ['', '### AMD FidelityFX CACAO v1.2\'s pipelines', ''] + amd_table(result)
    with open(a.out, 'w') as f:
        f.write('\n'.join(parts) + '\n')
    print('wrote %s (%s)' % (a.out, ', '.join(results)))


if __name__ == '__main__':
    main()
