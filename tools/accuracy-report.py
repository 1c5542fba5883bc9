#!/usr/bin/python3
"""Regenerates docs/accuracy.md and docs/accuracy-pareto.png: what accuracy costs in time.

usage: tools/accuracy-report.py [--build build] [--shared ../shared] [--out docs] [--reps 3]
                                [--warmup 2] [--repeat 7] [--scenes A,B] [--configs high_native,...]
                                [--no-amd] [--calibrate] [--grid "s=...;p=...;h=..."]

On the shared scenes, every default-sweep configuration of cacao-bench (quality x native /
downsampled, blur 2, fp32) runs with AMD's reference settings (../shared/reference-amd/<scene>/
settings.json, turned into cacao flags by ../shared/amd-cacao/amd_flags.py), and AMD FidelityFX
CACAO v1.2 itself (../shared/amd-cacao/amd_cacao) runs the same configuration on the same depth,
interleaved: for each repetition, configuration and scene one cacao-bench process and one amd_cacao
process, alternating which goes first. Both discard --warmup frames and take the median of --repeat
frames per process (GPU timestamps around the passes); the report gives the median over --reps
processes. Errors (RMSE, MAE over non-background pixels) are against ao_gt_falloff.pfm and ao_gt.pfm;
AMD's are computed here from the image it wrote. The plot is cacao-bench --plot-from on the merged
results with AMD's points as --reference.

--calibrate adds the leave-one-scene-out fit of strength / power / horizon (clamp 1, detail 0) per
quality level, native: fitted on two scenes, reported on the third beside AMD's look and the
physical look (strength 1, power 1, clamp 1, detail 0).

Needs /usr/bin/python3 with numpy (python3-numpy), gnuplot (tools/install-deps.sh) and a build.
Timings are meaningful only on a quiet machine: the report records `uptime` before and after."""
import argparse
import datetime
import itertools
import json
import os
import shlex
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUALITIES = ['lowest', 'low', 'medium', 'high', 'highest']
DEFAULT_CONFIGS = ['%s_%s' % (q, r) for q in QUALITIES for r in ('native', 'downsampled')]
TRUTHS = ['ao_gt_falloff', 'ao_gt']
# Flags of amd_flags.py that a cacao-bench configuration sets itself.
CONFIG_FLAGS = {'--quality': 1, '--blur': 1, '--downsample': 0}


def run(cmd, quiet=False):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if r.returncode != 0:
        raise SystemExit('accuracy-report: command failed (%d): %s\n%s%s' % (
            r.returncode, ' '.join(shlex.quote(c) for c in cmd), r.stdout, r.stderr))
    return r.stdout


def uptime():
    return run(['uptime']).strip()


def read_pfm(path):
    with open(path, 'rb') as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        ch = 3 if kind == b'PF' else 1
        a = np.frombuffer(f.read(w * h * ch * 4), dtype='<f4' if scale < 0 else '>f4').astype(np.float64)
    return a.reshape(h, w, ch)[::-1, :, 0]


def errors_of(ao, scene_dir):
    """RMSE and MAE of an AO image against the scene's truths over depth < 1 (as cacao-bench)."""
    depth = read_pfm(os.path.join(scene_dir, 'depth.pfm'))
    mask = np.isfinite(depth) & (depth < 1.0)
    out = {}
    for t in TRUTHS:
        path = os.path.join(scene_dir, t + '.pfm')
        if os.path.exists(path):
            d = np.abs(ao - read_pfm(path))[mask]
            out[t] = {'rmse': float(np.sqrt(np.mean(d * d))), 'mae': float(np.mean(d))}
    return out


def amd_settings_flags(shared, scene, config):
    """AMD's settings of (scene, config) as cacao flags, less what the configuration sets."""
    amd_config = config.split('_')[0].upper() + '_' + config.split('_')[1]
    settings = os.path.join(shared, 'reference-amd', scene, 'settings.json')
    flags = run([sys.executable, os.path.join(shared, 'amd-cacao', 'amd_flags.py'), settings, amd_config]).split()
    out, i = [], 0
    while i < len(flags):
        if flags[i] in CONFIG_FLAGS:
            i += 1 + CONFIG_FLAGS[flags[i]]
        else:
            out.append(flags[i])
            i += 1
    return out, settings, amd_config


def amd_args(shared, settings, amd_config, scene_dir):
    sys.path.insert(0, os.path.join(shared, 'amd-cacao'))
    import amdrun  # noqa: E402  (AMD's harness helpers, shared read-only input)
    s, downsampled, proj = amdrun.load_config(settings, amd_config, os.path.join(scene_dir, 'camera.json'))
    return amdrun.harness_args(s, downsampled, proj)


def median(v):
    return float(np.median(v))


def measure(a, bench, scenes, work):
    """Interleaved runs; returns (ours[(scene, config)], amd[(scene, config)], device info)."""
    runs = {}
    amd = {}
    info = {}
    jobs = [(c, s) for c in a.configs for s in scenes]
    total = a.reps * len(jobs)
    done = 0
    for rep in range(a.reps):
        for k, (config, scene) in enumerate(jobs):
            scene_dir = os.path.join(a.shared, 'scenes', scene)
            flags, settings, amd_config = amd_settings_flags(a.shared, scene, config)
            piece = os.path.join(work, 'cacao-%s-%s-%d.json' % (scene, config, rep))
            ours_cmd = [bench, '--scene', scene_dir, '--configs', config, '--warmup', str(a.warmup),
                        '--repeat', str(a.repeat), '--json', piece] + flags
            if rep == 0:
                ours_cmd += ['--save-ao', work]
            amd_json = os.path.join(work, 'amd-%s-%s-%d.json' % (scene, config, rep))
            amd_out = os.path.join(work, 'amd-%s-%s.pfm' % (scene, config))
            amd_cmd = [os.path.join(a.shared, 'amd-cacao', 'amd_cacao'), '--depth',
                       os.path.join(scene_dir, 'depth.pfm')] + amd_args(a.shared, settings, amd_config, scene_dir) + [
                       '--warmup', str(a.warmup), '--repeat', str(a.repeat), '--json', amd_json, '--out', amd_out]
            order = [ours_cmd, amd_cmd] if (rep + k) % 2 == 0 else [amd_cmd, ours_cmd]
            for cmd in order:
                if cmd is amd_cmd and a.no_amd:
                    continue
                run(cmd)
            r = json.load(open(piece))
            info = {'device': r['device'], 'driver': r['driver']}
            runs.setdefault((scene, config), []).append(r['results'][0])
            if not a.no_amd:
                j = json.load(open(amd_json))
                entry = amd.setdefault((scene, config), {'total': [], 'stages': []})
                entry['total'].append(j['median']['total_ms'])
                entry['stages'].append(j['median']['stages'])
                if rep == 0:
                    amd_ao = read_pfm(amd_out)
                    entry['errors'] = errors_of(amd_ao, scene_dir)
                    ours_ao = read_pfm(os.path.join(work, '%s.%s.pfm' % (scene, config)))
                    depth = read_pfm(os.path.join(scene_dir, 'depth.pfm'))
                    mask = np.isfinite(depth) & (depth < 1.0)
                    entry['mean_abs_vs_cacao'] = float(np.mean(np.abs(ours_ao - amd_ao)[mask]))
            done += 1
            print('[%d/%d] %s %s' % (done, total, scene, config), file=sys.stderr, flush=True)
    ours = {}
    for key, rs in runs.items():
        first = rs[0]
        passes = [{'name': p['name'], 'time_ms': median([r['passes'][i]['time_ms'] for r in rs])}
                  for i, p in enumerate(first['passes'])]
        ours[key] = dict(first, passes=passes, total_ms=median([r['total_ms'] for r in rs]),
                         total_min_ms=min(r['total_min_ms'] for r in rs),
                         total_max_ms=max(r['total_max_ms'] for r in rs),
                         process_totals_ms=[r['total_ms'] for r in rs])
    for e in amd.values():
        e['total_ms'] = median(e['total'])
    return ours, amd, info


def write_merged(path, scenes, configs, ours, a):
    merged = {'tool': 'tools/accuracy-report.py (median over %d interleaved cacao-bench runs)' % a.reps,
              'scenes': [{'name': s, 'truths': [t for t in TRUTHS if os.path.exists(
                  os.path.join(a.shared, 'scenes', s, t + '.pfm'))]} for s in scenes],
              'configurations': [{'name': c} for c in configs],
              'results': [ours[(s, c)] for c in configs for s in scenes]}
    with open(path, 'w') as f:
        json.dump(merged, f, indent=1)


def fmt(v, digits=4):
    return '-' if v is None else ('%.*f' % (digits, v))


def err(e, t, k):
    return e.get(t, {}).get(k) if e else None


# ---- leave-one-scene-out calibration -----------------------------------------------------------

def parse_grid(text):
    g = {}
    for part in text.split(';'):
        k, v = part.split('=')
        g[k.strip()] = [float(x) for x in v.split(',')]
    return g['s'], g['p'], g['h']


def calibrate(a, bench, scenes, work):
    """RMSE against ao_gt_falloff for every grid point, quality (native) and scene."""
    strengths, powers, horizons = parse_grid(a.grid)
    table = {}
    points = list(itertools.product(strengths, powers, horizons))
    for n, (s, p, h) in enumerate(points):
        out = os.path.join(work, 'calib-%d.json' % n)
        cmd = [bench, '--configs', '*_native', '--warmup', '0', '--repeat', '1', '--json', out]
        for scene in scenes:
            cmd += ['--scene', os.path.join(a.shared, 'scenes', scene)]
        flags, _, _ = amd_settings_flags(a.shared, scenes[0], 'high_native')
        keep = []
        i = 0
        while i < len(flags):  # AMD's settings but the shaping under calibration
            if flags[i] in ('--strength', '--power', '--clamp', '--horizon', '--detail', '--radius'):
                i += 2
            else:
                keep.append(flags[i])
                i += 1
        cmd += keep + ['--strength', '%g' % s, '--power', '%g' % p, '--horizon', '%g' % h, '--clamp', '1',
                       '--detail', '0']
        run(cmd)
        for r in json.load(open(out))['results']:
            table[(r['config'].split('_')[0], r['scene'], s, p, h)] = r['errors']['ao_gt_falloff']['rmse']
        print('[calibration %d/%d]' % (n + 1, len(points)), file=sys.stderr, flush=True)
    rows = []
    for q in QUALITIES:
        for left in scenes:
            fit = [sc for sc in scenes if sc != left]
            best = min(points, key=lambda g: np.mean([table[(q, sc) + g] for sc in fit]))
            rows.append({'quality': q, 'left_out': left, 'fit': best,
                         'calibrated': table[(q, left) + best],
                         'physical': table.get((q, left, 1.0, 1.0, 0.06)),
                         'fit_rmse': float(np.mean([table[(q, sc) + best] for sc in fit]))})
    return rows


# ---- the report --------------------------------------------------------------------------------

def report(a, scenes, ours, amd, info, up_before, up_after, calib, command):
    L = ['# What accuracy costs in time', '',
         '*Generated by `%s` on %s. Do not edit: rerun the command.*' % (
             command, datetime.datetime.utcnow().strftime('%Y-%m-%d %H:%M UTC')), '',
         'Device: %s (%s). `uptime` before: `%s`; after: `%s`.' % (info['device'], info['driver'], up_before,
                                                                   up_after), '',
         'Every configuration ran with AMD\'s reference settings for the scene (radius, fade-out, normals '
         'reconstructed from depth, as `../shared/reference-amd/<scene>/settings.json`); cacao through '
         '`cacao-bench`, AMD FidelityFX CACAO v1.2 through `../shared/amd-cacao/amd_cacao`, **interleaved in '
         'one run** (per repetition, configuration and scene one process of each, alternating which goes first). '
         'Each process discards %d warm-up frame(s) and takes the median of %d timed frames (GPU timestamps '
         'around the passes); the tables give the median over %d processes per side (min..max: the fastest and '
         'slowest single cacao frame over all of them). Errors are over the non-background pixels '
         '(depth < 1); AMD\'s are computed from the image it wrote, and "mean abs cacao - AMD" compares the two '
         'images (`test_amd_reference` holds cacao to 2/255 = 0.0078 of AMD\'s output).' % (a.warmup, a.repeat, a.reps), '',
         'Absolute times on a shared 2-core machine move by 2-3x between runs; only the ratio cacao/AMD, '
         'measured side by side, carries over.', '',
         '![error against time](accuracy-pareto.png)', '',
         '*`accuracy-pareto.png`: RMSE against `ao_gt_falloff` over the median GPU time per frame, one panel per '
         'scene; the red line is the Pareto front of cacao\'s configurations, green squares are AMD\'s.*', '']
    L += ['## cacao against AMD, total GPU time per frame (ms)', '',
          '| configuration | ' + ' | '.join('%s cacao | AMD | cacao/AMD' % s for s in scenes) + ' |',
          '|---|' + '---:|---:|---:|' * len(scenes)]
    for c in a.configs:
        cells = []
        for s in scenes:
            o = ours[(s, c)]['total_ms']
            m = amd.get((s, c), {}).get('total_ms')
            cells += [fmt(o, 1), fmt(m, 1), fmt(o / m, 2) if m else '-']
        L.append('| %s | %s |' % (c, ' | '.join(cells)))
    L.append('')
    for s in scenes:
        L += ['## %s' % s, '',
              '| configuration | ms (min..max) | AMD ms | memory MiB | pipelines | RMSE gt_falloff | MAE gt_falloff '
              '| RMSE gt | MAE gt | AMD RMSE gt_falloff | AMD RMSE gt | mean abs cacao - AMD |',
              '|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|']
        for c in a.configs:
            r = ours[(s, c)]
            e = r['errors']
            ae = amd.get((s, c), {}).get('errors')
            L.append('| %s | %s (%s..%s) | %s | %.2f | %d | %s | %s | %s | %s | %s | %s | %s |' % (
                c, fmt(r['total_ms'], 1), fmt(r['total_min_ms'], 1), fmt(r['total_max_ms'], 1),
                fmt(amd.get((s, c), {}).get('total_ms'), 1), r['memory_bytes'] / 1048576.0, r['pipeline_count'],
                fmt(err(e, 'ao_gt_falloff', 'rmse')), fmt(err(e, 'ao_gt_falloff', 'mae')),
                fmt(err(e, 'ao_gt', 'rmse')), fmt(err(e, 'ao_gt', 'mae')),
                fmt(err(ae, 'ao_gt_falloff', 'rmse')), fmt(err(ae, 'ao_gt', 'rmse')),
                fmt(amd.get((s, c), {}).get('mean_abs_vs_cacao'), 5)))
        L += ['', 'Per pass, median ms (cacao-bench pass names = permutation keys):', '']
        for c in a.configs:
            L.append('- %s: %s' % (c, ', '.join('%s %.2f' % (p['name'], p['time_ms']) for p in ours[(s, c)]['passes'])))
        L.append('')
    if calib is not None:
        L += ['## Calibrated shaping, leave one scene out', '',
              'Per quality level (native, AMD\'s other settings, clamp 1, detail 0) the strength / power / horizon of '
              'the grid `%s` with the lowest mean RMSE against `ao_gt_falloff` on two scenes, reported on the third '
              '(left out), beside AMD\'s look (AMD\'s settings, the table above) and the physical look (strength 1, '
              'power 1, clamp 1, detail 0, horizon 0.06).' % a.grid, '',
              '| quality | left out | fitted s / p / h | fit RMSE (2 scenes) | left-out RMSE: calibrated | AMD look '
              '| physical |', '|---|---|---|---:|---:|---:|---:|']
        better = better_amd = better_physical = 0
        for row in calib:
            amd_look = err(ours.get((row['left_out'], row['quality'] + '_native'), {}).get('errors'),
                           'ao_gt_falloff', 'rmse')
            rivals = [v for v in (amd_look, row['physical']) if v is not None]
            better += bool(rivals) and row['calibrated'] < min(rivals)
            better_amd += amd_look is not None and row['calibrated'] < amd_look
            better_physical += row['physical'] is not None and row['calibrated'] < row['physical']
            L.append('| %s | %s | %g / %g / %g | %.4f | %.4f | %s | %s |' % (
                row['quality'], row['left_out'], row['fit'][0], row['fit'][1], row['fit'][2], row['fit_rmse'],
                row['calibrated'], fmt(amd_look), fmt(row['physical'])))
        n = len(calib)
        generalises = better_amd == n
        L += ['', 'On the left-out scene the calibrated look has a lower RMSE than AMD\'s look in %d of %d cases, '
              'than the physical look in %d of %d, than both in %d of %d. %s' % (
                  better_amd, n, better_physical, n, better, n,
                  'It generalises against AMD\'s look; presets (`--look`) are not implemented yet.' if generalises else
                  'It does not generalise (the left-out figure does not improve on AMD\'s look everywhere), so no '
                  '`--look` presets are offered.'), '']
    return '\n'.join(L) + '\n'


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--shared', default=os.path.join(ROOT, '..', 'shared'))
    ap.add_argument('--out', default=os.path.join(ROOT, 'docs'))
    ap.add_argument('--reps', type=int, default=3)
    ap.add_argument('--warmup', type=int, default=2)
    ap.add_argument('--repeat', type=int, default=7)
    ap.add_argument('--scenes', default='interior_fzkhaus,statues_scanned,street_track')
    ap.add_argument('--configs', default=','.join(DEFAULT_CONFIGS))
    ap.add_argument('--no-amd', action='store_true', help='time cacao only (no AMD columns or points)')
    ap.add_argument('--calibrate', action='store_true')
    ap.add_argument('--grid', default='s=0.5,0.75,1,1.25,1.5;p=0.75,1,1.5,2;h=0,0.06,0.2')
    ap.add_argument('--workdir')
    a = ap.parse_args()
    a.configs = a.configs.split(',')
    scenes = a.scenes.split(',')
    bench = os.path.join(a.build, 'tools', 'bench', 'cacao-bench')
    for need in [bench] + [os.path.join(a.shared, 'scenes', s, 'depth.pfm') for s in scenes]:
        if not os.path.exists(need):
            raise SystemExit('accuracy-report: %s is missing (build first; --shared names ../shared)' % need)
    work = a.workdir or tempfile.mkdtemp(prefix='cacao-accuracy-')
    os.makedirs(work, exist_ok=True)
    command = 'tools/accuracy-report.py ' + ' '.join(shlex.quote(x) for x in sys.argv[1:])
    up_before = uptime()
    ours, amd, info = measure(a, bench, scenes, work)
    up_after = uptime()
    calib = calibrate(a, bench, scenes, work) if a.calibrate else None
    merged = os.path.join(work, 'merged.json')
    write_merged(merged, scenes, a.configs, ours, a)
    reference = os.path.join(work, 'amd-points.json')
    with open(reference, 'w') as f:
        json.dump({'name': 'AMD CACAO v1.2', 'points': [
            dict({'scene': s, 'config': 'AMD ' + c, 'total_ms': e['total_ms']},
                 **{'rmse_' + t: e['errors'][t]['rmse'] for t in e.get('errors', {})})
            for (s, c), e in amd.items()]}, f)
    os.makedirs(a.out, exist_ok=True)
    plot = os.path.join(a.out, 'accuracy-pareto.png')
    run([bench, '--plot-from', merged, '--plot', plot] + ([] if a.no_amd else ['--reference', reference]))
    text = report(a, scenes, ours, amd, info, up_before, up_after, calib, command)
    target = os.path.join(a.out, 'accuracy.md')
    with open(target + '.tmp', 'w') as f:
        f.write(text)
    os.replace(target + '.tmp', target)
    print('accuracy-report: wrote %s and %s (runs in %s)' % (target, plot, work))


if __name__ == '__main__':
    main()
