#!/usr/bin/env python3
"""Time cacao against AMD FidelityFX CACAO v1.2 on a real GPU, side by side in one run.

usage: tools/device-sidebyside.py --device NAME [options]      (on the GPU's machine)
       tools/device-sidebyside.py --merge DIR --out FILE.json   (anywhere: one JSON of a run's parts)

Both programs run on the Vulkan device whose name contains NAME (cacao --device, amd_cacao
--device). Every part is timed by ../shared/amd-cacao/sidebyside.py, the project's one side-by-side
instrument (fresh processes, AMD and cacao alternately, GPU timestamps first to last pass), except
`front`, which times cacao alone:

  cacao       AMD's ten configurations (LOWEST..HIGHEST x native/downsampled, AMD's reference
              settings of each scene) against cacao with the device's shader forms (the GPU forms)
  cpuforms    the same on the first scene with --shader-forms cpu (lavapipe's shapes), to check on
              real hardware the choice a context makes by device
  estimators  AMD HIGH_native against cacao's horizon-slice estimators (--estimators: gtao and
              bitmask configurations, reconstructed normals as AMD's settings); sidebyside.py
              labels these rows HIGH_native, this script relabels them
  front       cacao-bench on each scene, every estimator level and cacao level in one process
              (reconstructed normals); its times are set beside AMD's of the `cacao` part of the
              same run, which is the same machine but not interleaved: say so where quoted
  stats       the driver's pipeline statistics (cacao-inspect gpu --all, amd_cacao_pipelines)

sidebyside.py has no device option: this script writes small wrapper commands into its work
folder that add --device (and the estimator's flags: a later flag overrides an earlier one) to
what sidebyside.py passes. Each part and scene writes its own JSON as it ends (DIR/PART.SCENE.json),
so a run cut short keeps what it finished. The sizes are sidebyside.py's (default 2x: 1920x1080,
the nearest upscale of the 960x540 scenes).

options:
  --device NAME      Vulkan device name substring (required)
  --shared DIR       holds amd-cacao/, scenes/, reference-amd/ (default $CACAO_SHARED_DIR or ../shared)
  --build DIR        cacao's build folder (default build)
  --out DIR          result folder (default device-results)
  --parts LIST       comma list of the parts above (default cacao,estimators,cpuforms,front,stats)
  --scenes LIST      scenes under DIR/scenes (default interior_fzkhaus,statues_scanned,street_track)
  --configs LIST     AMD configurations for `cacao`/`cpuforms` (default all ten)
  --estimators LIST  estimator configurations, ESTIMATOR_QUALITY_native|downsampled (default
                     gtao_high_native,bitmask_highest_native,gtao_high_downsampled,bitmask_highest_downsampled)
  --sizes LIST       1x and/or 2x (default 2x)
  --reps N           AMD/cacao pairs per configuration (default 3)
  --frames K         frames per process (default 20)
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AMD_CONFIGS = ['%s_%s' % (q, r) for r in ('native', 'downsampled')
               for q in ('LOWEST', 'LOW', 'MEDIUM', 'HIGH', 'HIGHEST')]
ESTIMATORS = 'gtao_high_native,bitmask_highest_native,gtao_high_downsampled,bitmask_highest_downsampled'
PARTS = ['cacao', 'estimators', 'cpuforms', 'front', 'stats']


def die(msg):
    sys.exit('device-sidebyside.py: ' + msg)


def fail(a, msg):
    """A part that failed: said at once and at the end (exit 1); the other parts go on."""
    print('device-sidebyside.py: ' + msg, file=sys.stderr, flush=True)
    a.failures.append(msg)
    return None


def wrapper(path, real, extra):
    """A command that runs REAL with the caller's arguments followed by EXTRA."""
    with open(path, 'w') as f:
        f.write('#!/bin/sh\nexec %s "$@" %s\n' % (shlex.quote(real), ' '.join(shlex.quote(x) for x in extra)))
    os.chmod(path, 0o755)
    return path


def estimator_flags(name):
    parts = name.split('_')
    if len(parts) != 3 or parts[0] not in ('gtao', 'bitmask') or \
            parts[1] not in ('lowest', 'low', 'medium', 'high', 'highest') or parts[2] not in ('native', 'downsampled'):
        die("--estimators: '%s' is not ESTIMATOR_QUALITY_native|downsampled (e.g. gtao_high_native)" % name)
    return ['--estimator', parts[0], '--quality', parts[1], '--blur', '1'] + (['--downsample'] if parts[2] == 'downsampled' else [])


def sidebyside(a, part, scene, amd, cacao, configs, tag=None):
    tag = tag or scene
    out = os.path.join(a.out, '%s.%s.json' % (part, tag))
    cmd = [sys.executable, os.path.join(a.shared, 'amd-cacao', 'sidebyside.py'), '--amd', amd, '--cacao', cacao,
           os.path.join(a.shared, 'scenes', scene), '--configs', ','.join(configs), '--sizes', a.sizes,
           '--reps', str(a.reps), '--frames', str(a.frames),
           '--workdir', os.path.join(a.work, part + '.' + tag), '--json', out]
    print('== %s %s' % (part, tag), flush=True)
    r = subprocess.run(cmd)
    if r.returncode != 0:
        return fail(a, '%s on %s failed (%d): %s' % (part, tag, r.returncode, ' '.join(cmd)))
    return out


def run_front(a, scene):
    """cacao-bench at the sidebyside sizes, on the upscaled depth sidebyside.py made."""
    bench = os.path.join(a.build, 'tools', 'bench', 'cacao-bench')
    configs = ','.join(['%s_%s_%s' % (e, q, r) for e in ('gtao', 'bitmask') for r in ('native', 'downsampled')
                        for q in ('lowest', 'low', 'medium', 'high', 'highest')] +
                       ['%s_%s' % (q, r) for r in ('native', 'downsampled')
                        for q in ('lowest', 'low', 'medium', 'high', 'highest')])
    for size in a.sizes.split(','):
        sdir = os.path.join(a.shared, 'scenes', scene)
        if size == '2x':  # the folder sidebyside.py made for the `cacao` part of this scene
            sdir = os.path.join(a.work, 'cacao.' + scene, scene + '_2x')
            if not os.path.isfile(os.path.join(sdir, 'depth.pfm')):
                fail(a, 'front needs the cacao part of %s first (no %s)' % (scene, sdir))
                continue
        out = os.path.join(a.out, 'front.%s.%s.json' % (scene, size))
        cmd = [bench, '--device', a.device, '--scene', sdir, '--configs', configs, '--no-normals',
               '--warmup', '2', '--repeat', str(a.frames), '--json', out]
        print('== front %s %s' % (scene, size), flush=True)
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL)
        if r.returncode != 0:
            fail(a, 'front on %s failed (%d): %s' % (scene, r.returncode, ' '.join(cmd)))


def run_stats(a):
    """The driver's statistics of every embedded permutation (cacao-inspect's table and JSON) and of
    AMD's pipelines: registers, spills, shared memory, as the driver names them."""
    inspect = os.path.join(a.build, 'tools', 'inspect', 'cacao-inspect')
    amdp = os.path.join(a.shared, 'amd-cacao', 'amd_cacao_pipelines')
    print('== stats', flush=True)
    with open(os.path.join(a.out, 'stats.cacao.txt'), 'w') as f:
        r = subprocess.run([inspect, 'gpu', '--all', '--device', a.device, '--size', '1920x1080',
                            '--json', os.path.join(a.out, 'stats.cacao.json')], stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        fail(a, 'cacao-inspect gpu failed (%d): see stats.cacao.txt' % r.returncode)
    with open(os.path.join(a.out, 'stats.amd.jsonl'), 'w') as f:
        subprocess.run([amdp, '--device', a.device], stdout=f)


def merge(folder, out):
    """Every part's JSON of a run folder as one document (what tools/gpu-report.py --measured reads)."""
    doc = {'parts': {}}
    for name in sorted(os.listdir(folder)):
        p = os.path.join(folder, name)
        if name.endswith('.json'):
            doc['parts'][name[:-5]] = json.load(open(p))
        elif name.endswith('.jsonl'):
            doc['parts'][name[:-6]] = [json.loads(l) for l in open(p) if l.strip().startswith('{')]
        elif name.endswith('.txt'):  # keyed with its suffix: stats.cacao.txt beside stats.cacao.json
            doc['parts'][name] = open(p).read()
    for res in (r for k, v in doc['parts'].items() if k.startswith(('cacao.', 'cpuforms.', 'estimators.'))
                for r in v['results']):
        # cacao's passes one by one (the stages group them): the median over the runs of each pass
        steps = [r['steps'] for r in res['runs']['cacao'] if 'steps' in r]
        if steps:
            res['cacao_steps'] = {n: statistics.median(s[n] for s in steps if n in s)
                                  for n in sorted({n for s in steps for n in s})}
        for side in ('amd', 'cacao'):  # other per-run details stay in the run folder
            res['runs'][side] = [{'total_ms': r['total_ms']} for r in res['runs'][side]]
    json.dump(doc, open(out, 'w'), indent=1, sort_keys=True)
    print('wrote %s (%d parts)' % (out, len(doc['parts'])))


def main():
    ap = argparse.ArgumentParser(usage=__doc__.split('\n\n')[1])
    ap.add_argument('--device')
    ap.add_argument('--shared', default=os.environ.get('CACAO_SHARED_DIR', os.path.join(ROOT, '..', 'shared')))
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--out', default='device-results')
    ap.add_argument('--parts', default=','.join(PARTS))
    ap.add_argument('--scenes', default='interior_fzkhaus,statues_scanned,street_track')
    ap.add_argument('--configs', default=','.join(AMD_CONFIGS))
    ap.add_argument('--estimators', default=ESTIMATORS)
    ap.add_argument('--sizes', default='2x')
    ap.add_argument('--reps', type=int, default=3)
    ap.add_argument('--frames', type=int, default=20)
    ap.add_argument('--merge')
    a = ap.parse_args()
    if a.merge:
        return merge(a.merge, a.out)
    if not a.device:
        die('--device NAME is required (a real GPU; lavapipe has its own reports)')
    parts = a.parts.split(',')
    for p in parts:
        if p not in PARTS:
            die("--parts: unknown part '%s' (%s)" % (p, ', '.join(PARTS)))
    if a.reps < 1 or a.frames < 2:
        die('--reps must be >= 1 and --frames >= 2')
    estimators = a.estimators.split(',')
    for e in estimators:  # every argument checked before any path
        estimator_flags(e)
    a.shared, a.build, a.out = (os.path.abspath(x) for x in (a.shared, a.build, a.out))
    for need in (os.path.join(a.shared, 'amd-cacao', 'sidebyside.py'), os.path.join(a.build, 'tools', 'cli', 'cacao')):
        if not os.path.exists(need):
            die('missing %s (--shared, --build)' % need)
    scenes = a.scenes.split(',')
    os.makedirs(a.out, exist_ok=True)
    a.failures = []
    a.work = os.path.join(a.out, 'work')
    os.makedirs(a.work, exist_ok=True)
    cacao = os.path.join(a.build, 'tools', 'cli', 'cacao')
    amd = wrapper(os.path.join(a.work, 'amd'), os.path.join(a.shared, 'amd-cacao', 'amd_cacao'), ['--device', a.device])
    gpu = wrapper(os.path.join(a.work, 'cacao'), cacao, ['--device', a.device])
    for part in parts:
        if part == 'cacao':
            for s in scenes:
                sidebyside(a, 'cacao', s, amd, gpu, a.configs.split(','))
        elif part == 'cpuforms':
            cpu = wrapper(os.path.join(a.work, 'cacao-cpuforms'), cacao, ['--device', a.device, '--shader-forms', 'cpu'])
            sidebyside(a, 'cpuforms', scenes[0], amd, cpu, a.configs.split(','))
        elif part == 'estimators':
            for s in scenes:
                for e in estimators:
                    w = wrapper(os.path.join(a.work, 'cacao-' + e), cacao, ['--device', a.device] + estimator_flags(e))
                    out = sidebyside(a, 'estimators', s, amd, w, ['HIGH_native'], s + '.' + e)
                    if out is None:
                        continue
                    doc = json.load(open(out))
                    for r in doc['results']:
                        r['cacao_config'] = e
                    json.dump(doc, open(out, 'w'), indent=1)
        elif part == 'front':
            for s in scenes:
                run_front(a, s)
        elif part == 'stats':
            run_stats(a)
    if a.failures:
        die('%d part(s) failed:\n  ' % len(a.failures) + '\n  '.join(a.failures))


if __name__ == '__main__':
    main()
