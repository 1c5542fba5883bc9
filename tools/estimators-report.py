#!/usr/bin/python3
"""Regenerates docs/estimators.md, docs/estimators-pareto.png and docs/estimators-error.png: what the
horizon-slice estimators (GTAO, visibility bitmask) buy against ray-traced truth, and what they cost
beside cacao's own CACAO levels and AMD FidelityFX CACAO v1.2's best level, timed in one run.

usage: tools/estimators-report.py [--build build] [--shared ../shared] [--out docs] [--reps 3]
                                  [--warmup 2] [--repeat 7] [--scenes A,B] [--no-amd]

For each repetition and scene, interleaved (alternating which goes first): one cacao-bench process
running the estimators at every quality level (falloff visibility against ao_gt_falloff, the scene's
normals and, as a second set, normals reconstructed from depth), one running binary visibility
against ao_gt, one running cacao's CACAO levels with AMD's reference settings (as docs/accuracy.md),
and amd_cacao (../shared/amd-cacao) at each native quality level with AMD's reference settings.
Times are medians over --reps processes of each process's median frame; AMD's best level is the one
with the lowest RMSE against ao_gt_falloff. One parameter set for every scene: the estimators run
with the scene's radius (camera.json ao_radius_world) and no fade-out (the truths have none).

Needs /usr/bin/python3 with numpy, gnuplot and a build. Time it on a quiet machine (`uptime` is
recorded)."""
import argparse
import datetime
import importlib.util
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
spec = importlib.util.spec_from_file_location('accuracy_report', os.path.join(ROOT, 'tools', 'accuracy-report.py'))
acc = importlib.util.module_from_spec(spec)
spec.loader.exec_module(acc)

QUALITIES = acc.QUALITIES
ESTIMATORS = ['gtao', 'bitmask']
NO_FADE = ['--fade-out', '1000000,2000000']
CACAO_CONFIGS = ['%s_native' % q for q in QUALITIES]
GPU_FAMILY = 'navi21'  # the compiler estimate beside each time (docs/gpu.md explains it)
GPU_ICD = '/usr/share/vulkan/icd.d/radeon_icd.x86_64.json'
DEVICE = ['?']  # the bench's device and driver, as its JSON reports them


def ds_configs():
    """The estimators downsampled (falloff visibility, the scenes' normals)."""
    return ['%s_%s_downsampled' % (e, q) for e in ESTIMATORS for q in QUALITIES]


def est_configs(suffix=''):
    return ['%s_%s_native%s' % (e, q, suffix) for e in ESTIMATORS for q in QUALITIES]


def write_png_rgb(path, rgb):
    """A minimal 8-bit RGB PNG (zlib + CRCs), so the report needs nothing beyond numpy."""
    h, w, _ = rgb.shape
    raw = b''.join(b'\x00' + rgb[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def signed_error_png(path, ao, truth, mask):
    """Blue where the estimate is lighter than the truth (missed occlusion), red where darker;
    full colour at |error| 0.25; background grey."""
    e = np.clip((ao - truth) / 0.25, -1, 1)
    rgb = np.empty(ao.shape + (3,))
    rgb[..., 0] = 255 * (1 - np.clip(e, 0, 1))
    rgb[..., 2] = 255 * (1 - np.clip(-e, 0, 1))
    rgb[..., 1] = 255 * (1 - np.abs(e))
    rgb[~mask] = 96
    write_png_rgb(path, rgb)


def bench_json(bench, scene_dir, configs, flags, a, path, save_dir=None):
    cmd = [bench, '--scene', scene_dir, '--configs', ','.join(configs), '--warmup', str(a.warmup),
           '--repeat', str(a.repeat), '--json', path] + flags
    if save_dir:
        cmd += ['--save-ao', save_dir]
    return cmd


def measure(a, bench, scenes, work):
    ours, amd = {}, {}
    for rep in range(a.reps):
        for k, scene in enumerate(scenes):
            scene_dir = os.path.join(a.shared, 'scenes', scene)
            save = work if rep == 0 else None
            cmds = []
            falloff = os.path.join(work, 'f-%s-%d.json' % (scene, rep))
            cmds.append(('est', falloff, bench_json(bench, scene_dir, est_configs() + est_configs('_gennormals') + ds_configs(),
                                                    NO_FADE, a, falloff, save)))
            binary_dir = os.path.join(work, 'binary')
            os.makedirs(binary_dir, exist_ok=True)
            binary = os.path.join(work, 'b-%s-%d.json' % (scene, rep))
            cmds.append(('bin', binary, bench_json(bench, scene_dir, est_configs(), NO_FADE + ['--visibility', 'binary'],
                                                   a, binary, binary_dir if rep == 0 else None)))
            for config in CACAO_CONFIGS:
                flags, _, _ = acc.amd_settings_flags(a.shared, scene, config)
                path = os.path.join(work, 'c-%s-%s-%d.json' % (scene, config, rep))
                cmds.append(('cacao', path, bench_json(bench, scene_dir, [config], flags, a, path)))
            if not a.no_amd:
                for q in QUALITIES:
                    config = '%s_native' % q
                    _, settings, amd_config = acc.amd_settings_flags(a.shared, scene, config)
                    path = os.path.join(work, 'amd-%s-%s-%d.json' % (scene, config, rep))
                    out = os.path.join(work, 'amd-%s-%s.pfm' % (scene, config))
                    cmds.append(('amd', path, [os.path.join(a.shared, 'amd-cacao', 'amd_cacao'), '--depth',
                                               os.path.join(scene_dir, 'depth.pfm')] +
                                 acc.amd_args(a.shared, settings, amd_config, scene_dir) +
                                 ['--warmup', str(a.warmup), '--repeat', str(a.repeat), '--json', path, '--out', out],
                                 ))
            if rep == 0:  # the error after 8 frames of temporal accumulation (a still camera; not timed)
                temporal = os.path.join(work, 't-%s.json' % scene)
                cmds.append(('temporal', temporal, [bench, '--scene', scene_dir, '--configs',
                                                    ','.join(est_configs() + ds_configs()), '--warmup', '0',
                                                    '--repeat', '8', '--temporal', '8', '--json', temporal] + NO_FADE))
            if (rep + k) % 2:
                cmds.reverse()
            for kind, path, cmd in cmds:
                acc.run(cmd)
                if kind == 'amd':
                    j = json.load(open(path))
                    config = os.path.basename(path).split('-')[2]
                    e = amd.setdefault((scene, config), {'total': []})
                    e['total'].append(j['median']['total_ms'])
                    if 'errors' not in e:
                        e['errors'] = acc.errors_of(acc.read_pfm(cmd[cmd.index('--out') + 1]), scene_dir)
                else:
                    j = json.load(open(path))
                    DEVICE[0] = '%s (%s)' % (j.get('device', '?'), j.get('driver', '?'))
                    for r in j['results']:
                        prefix = {'bin': 'binary:', 'temporal': 'temporal:'}.get(kind, '')
                        key = (scene, prefix + r['config'])
                        ours.setdefault(key, []).append(r)
            print('[%d/%d] %s' % (rep * len(scenes) + k + 1, a.reps * len(scenes), scene), file=sys.stderr, flush=True)
    return ours, amd


def budget(r):
    s = r['settings']
    return '%dx%d' % (s['horizon_slices'], s['horizon_steps']), 2 * s['horizon_slices'] * s['horizon_steps']


def gpu_estimates(a, work):
    """Mcycles per frame at 1920x1080 on RADV's null device (GPU_FAMILY): {config: total} for the
    estimators (the scenes' normals given, as measured here) and cacao's CACAO levels, and
    {'amd ' + quality: total} for AMD's native levels (reconstructed normals, AMD's reference
    setting). None when RADV or amd_cacao_pipelines is missing."""
    inspect = os.path.join(a.build, 'tools', 'inspect', 'cacao-inspect')
    pipelines = os.path.join(a.shared, 'amd-cacao', 'amd_cacao_pipelines')
    if not (os.path.exists(GPU_ICD) and os.path.exists(pipelines) and os.path.exists(inspect)):
        return None
    env = dict(os.environ, RADV_FORCE_FAMILY=GPU_FAMILY, VK_ICD_FILENAMES=GPU_ICD, MESA_SHADER_CACHE_DISABLE='true')
    amd_lines = os.path.join(work, 'amd-pipelines.jsonl')

    def run(cmd):
        r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
        if r.returncode != 0:
            sys.exit('estimators-report: failed (%d): %s\n%s' % (r.returncode, ' '.join(cmd), r.stderr))
        return r.stdout
    with open(amd_lines, 'w') as f:
        f.write(run([pipelines, '--device', 'RADV']))
    out = {}
    for normals, configs in (('input', est_configs() + ds_configs()), ('depth', CACAO_CONFIGS)):
        path = os.path.join(work, 'gpu-%s.json' % normals)
        run([inspect, 'gpu', '--config', ','.join(configs), '--normals', normals, '--amd', amd_lines, '--json', path])
        for c in json.load(open(path))['configurations']:
            out[c['name']] = c['cacao']['total_cycles'] / 1e6
            if 'amd' in c:
                out['amd ' + c['quality']] = c['amd']['total_cycles'] / 1e6
    return out


def med(rs, field='total_ms'):
    return float(np.median([r[field] for r in rs]))


def rmse(r, truth):
    return r['errors'][truth]['rmse']


def front_table(scenes, ours, amd, gpu):
    """One row per estimator quality, cacao CACAO level and AMD level: mean RMSE over the scenes,
    time against AMD's HIGH of the same run scene by scene, and the GPU estimate against AMD's HIGH."""
    have_amd = all((s, 'high_native') in amd for s in scenes)
    amd_high = {s: float(np.median(amd[(s, 'high_native')]['total'])) for s in scenes} if have_amd else {}
    gpu_high = gpu.get('amd high') if gpu else None
    head = ['| | quality | budget | mean RMSE vs ao_gt_falloff | time / AMD HIGH (%s) | %s estimate / AMD HIGH | '
            'after 8 frames (temporal accumulation) |' % (', '.join(s.split('_')[0] for s in scenes), GPU_FAMILY),
            '|---|---|---|---:|---|---:|---:|']
    rows, front = [], {}

    def ratios(times):
        return ', '.join('%.2f' % (t / amd_high[s]) for s, t in zip(scenes, times)) if have_amd else '-'

    def gpu_ratio(key):
        return '%.2f' % (gpu[key] / gpu_high) if gpu and gpu_high and key in gpu else '-'
    for res in ('native', 'downsampled'):
        for e in ESTIMATORS:
            for q in QUALITIES:
                c = '%s_%s_%s' % (e, q, res)
                errs = [rmse(ours[(s, c)][0], 'ao_gt_falloff') for s in scenes]
                times = [med(ours[(s, c)]) for s in scenes]
                b, reads = budget(ours[(scenes[0], c)][0])
                front[c] = (float(np.mean(errs)), [t / amd_high[s] for s, t in zip(scenes, times)] if have_amd else None,
                            gpu[c] / gpu_high if gpu and gpu_high else None)
                t = [rmse(ours[(s, 'temporal:' + c)][0], 'ao_gt_falloff') for s in scenes
                     if (s, 'temporal:' + c) in ours]
                rows.append('| %s%s | %s | %s (%d reads%s) | %.4f | %s | %s | %s |' % (
                    e, ' downsampled' if res != 'native' else '', q, b, reads, ' per block' if res != 'native' else '',
                    np.mean(errs), ratios(times), gpu_ratio(c), '%.4f' % np.mean(t) if len(t) == len(scenes) else '-'))
    for c in CACAO_CONFIGS:
        errs = [rmse(ours[(s, c)][0], 'ao_gt_falloff') for s in scenes]
        rows.append('| cacao CACAO (AMD\'s settings) | %s | - | %.4f | %s | %s | - |' % (
            c.split('_')[0], np.mean(errs), ratios([med(ours[(s, c)]) for s in scenes]), gpu_ratio(c)))
    if have_amd:
        for q in QUALITIES:
            k = [(s, q + '_native') for s in scenes]
            rows.append('| **AMD CACAO v1.2** | %s | - | %.4f | %s | %s | - |' % (
                q, np.mean([amd[x]['errors']['ao_gt_falloff']['rmse'] for x in k]),
                ratios([float(np.median(amd[x]['total'])) for x in k]), gpu_ratio('amd ' + q)))
    return head + rows, front


def targets(scenes, ours, front):
    """Issue 34's targets, each met or missed with its numbers."""
    out = []
    best = [(c, v) for c, v in front.items() if v[0] <= 0.048]
    if not best:
        c, v = min(front.items(), key=lambda kv: kv[1][0])
        out.append('- Mean RMSE <= 0.048: **missed**; the lowest is %s at %.4f.' % (c, v[0]))
    for c, (err, t, g) in sorted(best, key=lambda kv: kv[1][0]):
        tt = 'time / AMD HIGH %s (target <= 0.8 on every scene: %s)' % (
            ', '.join('%.2f' % x for x in t), 'met' if max(t) <= 0.8 else '**missed**') if t else 'no AMD timing'
        gg = '%s estimate / AMD HIGH %.2f (target <= 1: %s)' % (GPU_FAMILY, g, 'met' if g <= 1 else '**missed**') \
            if g is not None else 'no GPU estimate'
        out.append('- Mean RMSE <= 0.048 (stretch 0.045: %s): %s at %.4f; %s; %s.' % (
            'met' if err <= 0.045 else 'missed', c, err, tt, gg))
    fast = [(c, v) for c, v in front.items() if v[1] and max(v[1]) <= 0.8]
    if fast:
        c, v = min(fast, key=lambda kv: kv[1][0])
        out.append('- The most accurate configuration within 0.8 of AMD HIGH\'s time on every scene: %s, mean RMSE %.4f '
                   '(time / AMD HIGH %s%s).' % (c, v[0], ', '.join('%.2f' % x for x in v[1]),
                                                '; %s estimate / AMD HIGH %.2f' % (GPU_FAMILY, v[2]) if v[2] is not None else ''))
    worse = []
    for res in ('native', 'downsampled'):
        for e in ESTIMATORS:
            for s in scenes:
                errs = [rmse(ours[(s, '%s_%s_%s' % (e, q, res))][0], 'ao_gt_falloff') for q in QUALITIES]
                worse += ['%s %s %s on %s (%.4f after %.4f)' % (e, QUALITIES[i], res, s, errs[i], errs[i - 1])
                          for i in range(1, len(errs)) if errs[i] > errs[i - 1]]
    out.append('- No quality less accurate than a lower one of the same estimator (native, and downsampled), on any '
               'scene: %s.' % (
        'met' if not worse else '**missed**: ' + '; '.join(worse)))
    for e in ESTIMATORS:
        c = '%s_lowest_native' % e
        bad = [s for s in scenes if not (med(ours[(s, c)]) <= med(ours[(s, 'lowest_native')]) or
                                         rmse(ours[(s, c)][0], 'ao_gt_falloff') <
                                         rmse(ours[(s, 'lowest_native')][0], 'ao_gt_falloff'))]
        out.append('- %s LOWEST at most as costly as cacao\'s CACAO LOWEST or more accurate, on every scene: %s '
                   '(RMSE %s against %s; time %s ms against %s ms).' % (
                       e, 'met' if not bad else '**missed** on ' + ', '.join(bad),
                       '/'.join('%.4f' % rmse(ours[(s, c)][0], 'ao_gt_falloff') for s in scenes),
                       '/'.join('%.4f' % rmse(ours[(s, 'lowest_native')][0], 'ao_gt_falloff') for s in scenes),
                       '/'.join('%.1f' % med(ours[(s, c)]) for s in scenes),
                       '/'.join('%.1f' % med(ours[(s, 'lowest_native')]) for s in scenes)))
    return out


def real_gpu():
    """The horizon estimators' times on a real GPU: the runs docs/gpu.md reports (tools/gpu-report.py's
    MEASURED under docs/gpu-measured), time / AMD HIGH per scene; nothing where there are none."""
    spec = importlib.util.spec_from_file_location('gpu_report', os.path.join(ROOT, 'tools', 'gpu-report.py'))
    g = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(g)
    runs = g.load_measured(os.path.join(ROOT, 'docs', 'gpu-measured'))
    forms = g.horizon_run(runs)
    rows = g.estimator_results(forms)
    if not rows:
        return []
    device = g.line_of(g.text_part(forms, 'devices'), '0:').split(':', 1)[-1].strip()
    out = ['', 'On a real GPU (%s; docs/gpu.md, "Measured on a real GPU": 1920x1080, timed side by side with AMD\'s '
           'code, one denoise pass, normals from depth), time / AMD HIGH per scene (%s):' % (
               device, ', '.join(g.SCENES)), '']
    worst = []
    for n, per in rows:
        ratios = [r['ratio'] for r in per if r]
        worst.append(max(ratios))
        out.append('- %s: %s' % (n, ', '.join('%.2f' % r for r in ratios)))
    out.append('')
    out.append('The time target (<= 0.8) is %s there by every configuration measured.' % (
        'missed' if min(worst) > 0.8 else 'not missed'))
    return out


def report(a, scenes, ours, amd, gpu, up_before, up_after, work, device):
    lines = ['# The horizon-slice estimators: accuracy and time', '',
             '*Generated by `tools/estimators-report.py --reps %d` on %s, %s. `uptime` before: `%s`; after: `%s`. '
             'Every time below is from this one run: cacao-bench and AMD\'s own code interleaved, median over %d '
             'processes of each process\'s median of %d frames after %d warm-up frames. The %s figures are ACO\'s '
             'cost estimate at 1920x1080 on RADV\'s null device (`cacao-inspect gpu`, docs/gpu.md: a compiler\'s '
             'estimate, not a timing; the horizon main pass weighed by its budget).*' % (
                 a.reps, datetime.date.today().isoformat(), device, up_before, up_after, a.reps, a.repeat, a.warmup,
                 GPU_FAMILY),
             '',
             '`--estimator gtao` and `--estimator bitmask` (cacao.h `cacao_estimator`; design in '
             '[estimators-design](#design)) estimate the cosine-weighted visibility the ray-traced truths measure. '
             'One parameter set for every scene: the scene\'s radius, no fade-out, the constants of '
             '`shared/spec/estimators.md`; nothing was fitted to these scenes. RMSE over non-background pixels; '
             '"given" = the scene\'s normals (the spec\'s protocol), "reconstructed" = normals from depth (AMD\'s '
             'reference settings reconstruct them too). AMD\'s best = its native level with the lowest RMSE against '
             '`ao_gt_falloff` under its reference settings. Every figure is of a single frame except the front\'s last '
             'column: the error after 8 frames of temporal accumulation inside cacao (`--temporal 8`, a still '
             'camera, frame_index 0..7; docs/integration.md), which a single frame\'s target is never read '
             'against.', '']
    table, front = front_table(scenes, ours, amd, gpu)
    lines += ['## The front', '',
              'Every quality level of both estimators (given normals), cacao\'s CACAO levels and AMD\'s (AMD\'s '
              'reference settings, reconstructed normals), mean over the scenes; times as ratios to AMD\'s HIGH '
              'of this run, scene by scene; the last column: mean RMSE after 8 frames of temporal accumulation '
              '(not timed; its pass costs about four fifths of the upsample here, docs/estimators-design.md).', ''] + table + ['', 'Issue 34\'s targets:', ''] + \
        targets(scenes, ours, front) + real_gpu() + ['']
    for scene in scenes:
        amd_high = float(np.median(amd[(scene, 'high_native')]['total'])) if (scene, 'high_native') in amd else None
        lines += ['## %s' % scene, '',
                  '| estimator | quality | budget (depth reads / px) | RMSE vs ao_gt_falloff (given / reconstructed '
                  'normals) | RMSE vs ao_gt, binary visibility | total ms | / AMD HIGH | horizon_main ms | %s Mcycles |'
                  % GPU_FAMILY, '|---|---|---|---|---|---|---|---|---|']
        for e in ESTIMATORS:
            for q in QUALITIES:
                c = '%s_%s_native' % (e, q)
                rs, rg, rb = ours[(scene, c)], ours[(scene, c + '_gennormals')], ours[(scene, 'binary:' + c)]
                main = float(np.median([p['time_ms'] for r in rs for p in r['passes'] if p['name'].startswith('horizon_main')]))
                b, reads = budget(rs[0])
                lines.append('| %s | %s | %s (%d) | %.4f / %.4f | %.4f | %.1f | %s | %.1f | %s |' % (
                    e, q, b, reads, rmse(rs[0], 'ao_gt_falloff'), rmse(rg[0], 'ao_gt_falloff'),
                    rmse(rb[0], 'ao_gt'), med(rs), '%.2f' % (med(rs) / amd_high) if amd_high else '-', main,
                    '%.1f' % gpu[c] if gpu else '-'))
        for e in ESTIMATORS:
            for q in QUALITIES:
                c = '%s_%s_downsampled' % (e, q)
                rs = ours[(scene, c)]
                main = float(np.median([p['time_ms'] for r in rs for p in r['passes'] if p['name'].startswith('horizon_main')]))
                b, reads = budget(rs[0])
                lines.append('| %s downsampled | %s | %s (%d per block) | %.4f / - | - | %.1f | %s | %.1f | %s |' % (
                    e, q, b, reads, rmse(rs[0], 'ao_gt_falloff'), med(rs),
                    '%.2f' % (med(rs) / amd_high) if amd_high else '-', main, '%.1f' % gpu[c] if gpu else '-'))
        for c in CACAO_CONFIGS:
            rs = ours[(scene, c)]
            lines.append('| cacao (CACAO, AMD\'s settings) | %s | - | %.4f (reconstructed) | %.4f | %.1f | %s | - | %s |' % (
                c.split('_')[0], rmse(rs[0], 'ao_gt_falloff'), rmse(rs[0], 'ao_gt'), med(rs),
                '%.2f' % (med(rs) / amd_high) if amd_high else '-', '%.1f' % gpu[c] if gpu else '-'))
        if amd:
            best = min((k for k in amd if k[0] == scene), key=lambda k: amd[k]['errors']['ao_gt_falloff']['rmse'])
            b = amd[best]
            lines.append('| **AMD CACAO v1.2, best level** | %s | - | %.4f (reconstructed) | %.4f | %.1f | %s | - | %s |' % (
                best[1].split('_')[0], b['errors']['ao_gt_falloff']['rmse'], b['errors']['ao_gt']['rmse'],
                float(np.median(b['total'])), '%.2f' % (float(np.median(b['total'])) / amd_high),
                '%.1f' % gpu['amd ' + best[1].split('_')[0]] if gpu else '-'))
            lines += ['', 'AMD per native level (RMSE vs ao_gt_falloff, ms): ' + ', '.join(
                '%s %.4f / %.1f' % (q, amd[(scene, q + '_native')]['errors']['ao_gt_falloff']['rmse'],
                                    float(np.median(amd[(scene, q + '_native')]['total']))) for q in QUALITIES) + '.']
        lines.append('')
    # worst case: the highest RMSE of the default mode (bitmask, highest, given normals)
    worst = max(scenes, key=lambda s: rmse(ours[(s, 'bitmask_highest_native')][0], 'ao_gt_falloff'))
    ao = acc.read_pfm(os.path.join(work, '%s.bitmask_highest_native.pfm' % worst))
    scene_dir = os.path.join(a.shared, 'scenes', worst)
    truth = acc.read_pfm(os.path.join(scene_dir, 'ao_gt_falloff.pfm'))
    depth = acc.read_pfm(os.path.join(scene_dir, 'depth.pfm'))
    mask = np.isfinite(depth) & (depth < 1.0) & np.isfinite(truth)
    signed_error_png(os.path.join(a.out, 'estimators-error.png'), ao, truth, mask)
    d = (ao - truth)[mask]
    lines += ['## Where the error sits', '',
              '![signed error](estimators-error.png)', '',
              '*bitmask, highest, given normals, on %s (the scene where its RMSE is highest), minus `ao_gt_falloff`: '
              'blue = lighter than the truth (occlusion missed), red = darker; full colour at 0.25. Mean signed error '
              '%+.4f; %.1f%% of pixels more than 0.1 too light, %.1f%% more than 0.1 too dark.*' % (
                  worst, float(np.mean(d)), 100 * float(np.mean(d > 0.1)), 100 * float(np.mean(d < -0.1))), '',
              '![error against time](estimators-pareto.png)', '',
              '*RMSE against `ao_gt_falloff` against total GPU time, every configuration of this run (cacao-bench '
              '`--plot-from`), AMD\'s native levels as reference points.*', '']
    with open(os.path.join(ROOT, 'docs', 'estimators-design.md')) as f:
        lines += [f.read().rstrip(), '']
    with open(os.path.join(a.out, 'estimators.md'), 'w') as f:
        f.write('\n'.join(lines))


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--build', default=os.path.join(ROOT, 'build'))
    p.add_argument('--shared', default=os.path.join(ROOT, '..', 'shared'))
    p.add_argument('--out', default=os.path.join(ROOT, 'docs'))
    p.add_argument('--reps', type=int, default=3)
    p.add_argument('--warmup', type=int, default=2)
    p.add_argument('--repeat', type=int, default=7)
    p.add_argument('--scenes', default='interior_fzkhaus,statues_scanned,street_track')
    p.add_argument('--no-amd', action='store_true')
    a = p.parse_args()
    bench = os.path.join(a.build, 'tools', 'bench', 'cacao-bench')
    scenes = a.scenes.split(',')
    up_before = acc.uptime()
    with tempfile.TemporaryDirectory() as work:
        ours, amd = measure(a, bench, scenes, work)
        up_after = acc.uptime()
        device = DEVICE[0]
        merged = os.path.join(work, 'merged.json')
        configs = est_configs() + ds_configs() + CACAO_CONFIGS
        results = []
        for c in configs:
            for s in scenes:
                rs = ours[(s, c)]
                results.append(dict(rs[0], total_ms=med(rs)))
        with open(merged, 'w') as f:
            json.dump({'tool': 'tools/estimators-report.py', 'scenes': [{'name': s, 'truths': acc.TRUTHS} for s in scenes],
                       'configurations': [{'name': c} for c in configs], 'results': results}, f)
        plot_cmd = [bench, '--plot-from', merged, '--plot', os.path.join(a.out, 'estimators-pareto.png')]
        if amd:
            ref = os.path.join(work, 'amd.json')
            with open(ref, 'w') as f:
                json.dump({'name': 'AMD FidelityFX CACAO v1.2', 'points': [{'scene': s, 'config': 'AMD ' + c.split('_')[0], 'total_ms': float(np.median(v['total'])),
                                       'rmse_ao_gt_falloff': v['errors']['ao_gt_falloff']['rmse'],
                                       'rmse_ao_gt': v['errors']['ao_gt']['rmse']} for (s, c), v in amd.items()]}, f)
            plot_cmd += ['--reference', ref]
        acc.run(plot_cmd)
        report(a, scenes, ours, amd, gpu_estimates(a, work), up_before, up_after, work, device)
    print('wrote %s' % os.path.join(a.out, 'estimators.md'))


if __name__ == '__main__':
    main()
