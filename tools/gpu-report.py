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
# 'final' is the code as it stands; 'before' the same run with the code before the last change it
# measured; 'forms' another run, whose cpuforms and estimators parts serve (the passes they time
# are unchanged since), with 'forms_before' beside it; 'atomics' and 'atomics_before' a run of an
# experiment not kept (classify and compact with their atomics gathered per workgroup).
MEASURED = {'final': 'h200-final.json', 'before': 'h200-before.json',
            'forms': 'h200-run-texelfetch.json', 'forms_before': 'h200-run-texelfetch-before.json',
            'atomics': 'h200-run-atomics.json', 'atomics_before': 'h200-run-atomics-before.json'}
# What the runs are of, and what changed after them (said with the tables: a run measures its code).
MEASURED_CODE = ('The final run is of commit 8ba0da9, its "before" of 6588704 (the previous main); the changes made '
                 'after them were not measured on this GPU: the fills with one workgroup per tile instead of one per '
                 'tile and layer (9d4d565), then no fills at all: on a GPU generate and the blur skip the groups '
                 'that are not needed in the shader, with no compact pass, list or clear (docs/tiles.md, "What runs").')
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
there cacao takes more time than AMD in every configuration, where this estimate puts it at about or
under AMD's cost. Read the estimate for registers, spills and occupancy, not for speed.

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
are left out (the fill dispatches nothing with every tile active; a clear runs no shader).

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
  6 waves per SIMD). `apply_gpu`: one pixel per invocation through the sampler.
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
- `generate_gpu`: the tap's atlas level, extent and place as integers (the CPU form selects among
  four float vec4s and converts them, 25 instructions of a tap's 110 on navi21); the Q3 base pass
  takes a quad's four centre depths from one gather and steps the pattern's row from texel to texel.
  Q3 base on navi21: 12,001 cycles per wave (11,463 instructions) in the CPU form, 10,781 (10,294)
  in the GPU form, whose 16 texels of 5 taps x 2 samples each are the instructions: no loop is left
  rolled. At Q0..Q2 the GPU form fetches its taps' depths through the sampled view of the atlas
  (`texelFetch`; the CPU form, Q3 and its base pass load them from the storage image): the same
  texels, chosen by what a real GPU measured (section "Measured on a real GPU").
- `generate_gpu` and `blur_gpu` run on direct grids and skip by the tile classes themselves: a
  group reads its needed flag (classify marks them) and, when not needed, stores AO 1 and computes
  nothing else; the CPU forms run from compact's lists and fill the rest (docs/tiles.md). On
  navi21 at LOWEST native the estimate of generate went from 5.94 to 6.23 Mcycles and the blur's
  from 1.64 to 1.90 (against the lists), and the compact pass, two fill dispatches and their
  barriers, which the estimate does not weigh, are gone. Most of the blur's difference is the
  estimate's: its stores follow the flag's branch, where the list's entry check covered them, and
  the doubling above counts them twice. Not yet timed on a GPU.

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
           'same conditions, interleaved. In frames this short (0.06-0.35 ms) the fixed costs of each dispatch, barrier and workgroup '
           'weigh heavily (the tables below), and no compiler statistic shows them. %s' % (proc['reps'], proc['frames'], proc['warmup_frames'],
                                  clocks[0], clocks[1], MEASURED_CODE),
           '', '### Totals: cacao / AMD', '',
           '| configuration | AMD ms (interior) | cacao ms (interior) | cacao/AMD interior | statues | street | '
           'navi21 estimate (RADV, below) |', '|---|---:|---:|---:|---:|---:|---:|']
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
        out += ['', '**On this GPU cacao takes %.2f-%.2fx AMD\'s time** (all 30 scene x configuration pairs): slower '
                'than AMD everywhere, where the RADV estimate below (navi21) puts it at %s of AMD\'s cost. The '
                'estimate counts issued instructions; what it leaves out (the fixed cost of each dispatch and '
                'barrier, workgroup launches, memory) decides frames this short.' % (
                    min(ratios), max(ratios), '%.2f-%.2f' % (min(ests), max(ests)) if ests else '(not run)')]
    # per stage
    out += ['', '### Per stage (interior_fzkhaus, microseconds, AMD / cacao)', '',
            'Stages as sidebyside.py groups the passes. cacao\'s "tiles" are its tile classification and lists '
            '(classify, compact, and the two fills of tiles no pass computes: four dispatches); its GPU form of the Q3 '
            'base pass is counted in generate (AMD\'s base pass has a column of its own: compare their sum).', '',
            '| configuration | ' + ' | '.join('tiles' if s == 'other' else s for s in MEASURED_STAGES) + ' |',
            '|---|' + '---:|' * len(MEASURED_STAGES)]
    for cfg, r in results_of(fin, 'cacao', SCENES[0]).items():
        a, c = r['amd']['stages'], r['cacao']['stages']
        out.append('| %s | %s |' % (cfg, ' | '.join(
            '' if s not in a and s not in c else '%s / %s' % (us(a.get(s)), us(c.get(s))) for s in MEASURED_STAGES)))
    ratios, tiles = stage_ranges(fin)
    exp = []
    if 'atomics' in runs and 'atomics_before' in runs:
        for cfg, b in results_of(runs['atomics_before'], 'cacao', SCENES[0]).items():
            f = results_of(runs['atomics'], 'cacao', SCENES[0]).get(cfg)
            if f and 'other' in f['cacao']['stages'] and 'other' in b['cacao']['stages']:
                exp.append(f['cacao']['stages']['other'] / b['cacao']['stages']['other'])
    atomics = ('was measured (`%s`: interior_fzkhaus, the tiles stage after / before %.2f-%.2f over the ten '
               'configurations) and not kept' % (MEASURED['atomics'], min(exp), max(exp))) if exp else \
        'was measured in an earlier run and not kept'
    if ratios:
        out += ['', 'Over the 30 scene x configuration pairs, cacao/AMD per stage: %s; and cacao\'s tiles stage, which '
                'AMD does not have, takes %s-%s microseconds: four dispatches, each a barrier the next waits for, '
                'the least where every tile is computed (interior_fzkhaus: the fills have nothing to fill), the most '
                'where the fills fill (the scenes with background or faded tiles), although a fill only writes 1s: one workgroup of 64 '
                'invocations per tile and layer. With the apply forms below, this points at the number of workgroups '
                'as a cost of its own on this GPU. Gathering the classification\'s and the compaction\'s atomic '
                'additions per workgroup (one global atomic per group instead of one per tile) %s: the atomics are '
                'not where the time goes.' % (
                    '; '.join('%s %.2f-%.2f' % (st, min(v), max(v)) for st, v in ratios.items()),
                    us(min(tiles)), us(max(tiles)), atomics)]
    # the change measured in the final run
    if 'before' in runs:
        out += ['', '### The last change, measured: generate\'s taps through the sampled view', '',
                'The GPU form of generate at Q0..Q2 fetches its taps\' depths through the sampled view of the '
                'depth atlas (`texelFetch`), where the CPU form, and Q3 and its base pass, load them from the '
                'storage image (`imageLoad`: lavapipe runs that faster). Same texels, same output. The generate '
                'stage in microseconds, before / after, same run:', '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        totals = []
        for cfg in AMD_CONFIGS:
            cells = []
            for sc in SCENES:
                b, f = results_of(runs['before'], 'cacao', sc).get(cfg), results_of(fin, 'cacao', sc).get(cfg)
                if b and f:
                    cells.append('%s / %s' % (us(b['cacao']['stages'].get('generate')),
                                              us(f['cacao']['stages'].get('generate'))))
                    totals.append(f['cacao']['total_ms'] / b['cacao']['total_ms'])
                else:
                    cells.append('-')
            out.append('| %s | %s |' % (cfg, ' | '.join(cells)))
        if totals:
            totals.sort()
            out += ['', 'cacao\'s total after / before: median %.3f (%.3f-%.3f over the 30 pairs).'
                    % (totals[len(totals) // 2], totals[0], totals[-1])]
        if 'forms' in runs and 'forms_before' in runs:
            cells = []
            for sc in SCENES:
                b = results_of(runs['forms_before'], 'cacao', sc).get('HIGHEST_native')
                f = results_of(runs['forms'], 'cacao', sc).get('HIGHEST_native')
                if b and f:
                    cells.append('%s: %s -> %s' % (sc, us(b['cacao']['stages']['generate']),
                                                   us(f['cacao']['stages']['generate'])))
            out += ['', 'Why Q3 keeps `imageLoad`: an earlier run with `texelFetch` in every variant (%s) made '
                    'HIGHEST native\'s generate stage (the Q3 base pass and Q3) slower: %s microseconds, before -> '
                    'after.' % (MEASURED['forms'], '; '.join(cells))]
    # the shader forms
    forms = runs.get('forms', {})
    cpu = results_of(forms, 'cpuforms', SCENES[0])
    gpu = results_of(forms, 'cacao', SCENES[0])
    if cpu and gpu:
        out += ['', '### The shader forms on this GPU (interior_fzkhaus, one run)', '',
                'A context on a GPU runs the GPU forms; `--shader-forms cpu` runs lavapipe\'s. Both timed in the '
                'run of `%s` against AMD (there, generate\'s GPU form fetched every variant\'s taps through the '
                'sampled view; the blur and apply forms are today\'s). Microseconds, AMD / GPU form / CPU form:'
                % MEASURED['forms'], '',
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
        out += ['', 'The GPU form of the blur (shared memory, 16x16 threads) is the faster one here too. The apply is '
                'not: at LOWEST and LOW the CPU form (2x2 texels per invocation, a quarter of the workgroups) takes '
                'half the GPU form\'s time and half AMD\'s, against the RADV estimate, which counts the CPU form\'s '
                'instructions and puts it above AMD\'s (`cacao-inspect gpu --shader-forms cpu --config '
                'lowest_native,low_native --amd ...`). Both apply forms are kept as they are until a GPU of each '
                'vendor has timed them: the AMD estimate and the NVIDIA timing disagree. The upsample has one form.']
    # the horizon estimators
    rows = estimator_results(forms)
    if rows:
        out += ['', '### The horizon-slice estimators against AMD HIGH (same run as the forms)', '',
                '| configuration | ' + ' | '.join(SCENES) + ' |', '|---|' + '---:|' * len(SCENES)]
        for n, per in rows:
            out.append('| %s (1 denoise pass) | %s |' % (n, ' | '.join(
                '%.3f ms / %.3f ms = %.2f' % (r['cacao']['total_ms'], r['amd']['total_ms'], r['ratio']) if r else '-'
                for r in per)))
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
    doc = HEADER % {'driver': first['driver'], 'issue': '\n'.join(issue_comparison(results['navi21']))
                    if 'navi21' in results else '(navi21 not measured)',
                    'overview': '\n'.join(overview(results))}
    parts = [doc.rstrip('\n')]
    measured = measured_section(load_measured(a.measured), results)
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
