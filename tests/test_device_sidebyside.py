#!/usr/bin/env python3
"""The parts of tools/device-sidebyside.py and of tools/gpu-report.py's measured section that need
no GPU: argument errors, the wrapper commands, the merge of a run's folder, and the report of the
runs committed under docs/gpu-measured (and of none).

usage: test_device_sidebyside.py SOURCE_DIR WORK_DIR"""
import importlib.util
import json
import os
import shutil
import subprocess
import sys

SRC, WORK = sys.argv[1], sys.argv[2]
TOOL = os.path.join(SRC, 'tools', 'device-sidebyside.py')
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print('FAIL: ' + what)


def load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def tool(*args):
    r = subprocess.run([sys.executable, TOOL] + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       universal_newlines=True)
    return r.returncode, r.stdout + r.stderr


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# Bad arguments: one clear error naming the flag or value, non-zero exit, nothing written. They are
# checked before any path, so this runs with or without ../shared (the last case names a missing one).
out_dir = os.path.join(WORK, 'never')
for args, needle in ((['--out', out_dir], '--device'),
                     (['--device', 'X', '--parts', 'cacao,bogus', '--out', out_dir], "'bogus'"),
                     (['--device', 'X', '--estimators', 'gtao_ultra_native', '--out', out_dir], 'gtao_ultra_native'),
                     (['--device', 'X', '--reps', '0', '--out', out_dir], '--reps'),
                     (['--device', 'X', '--shared', os.path.join(WORK, 'no-shared'), '--out', out_dir], '--shared')):
    rc, text = tool(*args)
    check(rc != 0 and needle in text, 'device-sidebyside.py %s: exit %d, message %r (wanted %s)' %
          (' '.join(args), rc, text.strip(), needle))
check(not os.path.exists(out_dir), 'a refused run wrote %s' % out_dir)

ds = load('device_sidebyside', TOOL)

# The wrapper runs the real command with the caller's arguments first, then its own (a later flag
# overrides an earlier one in cacao's parser), quoting what needs it.
w = ds.wrapper(os.path.join(WORK, 'wrap'), '/bin/echo', ['--device', 'NVIDIA H200', "it's"])
r = subprocess.run([w, '--quality', 'high'], stdout=subprocess.PIPE, universal_newlines=True)
check(r.stdout == "--quality high --device NVIDIA H200 it's\n", 'wrapper output %r' % r.stdout)
check(ds.estimator_flags('bitmask_highest_downsampled') ==
      ['--estimator', 'bitmask', '--quality', 'highest', '--blur', '1', '--downsample'], 'estimator flags')

# The merge: one document of a run folder; per-run details reduced to totals; a .txt keeps its
# suffix (stats.cacao.txt beside stats.cacao.json); temporary files left out.
run_dir = os.path.join(WORK, 'run')
os.makedirs(run_dir)
side = {'total_ms': 0.1, 'stages': {'generate': 0.05}}
result = {'config': 'HIGH_native', 'ratio': 1.5, 'amd': dict(side), 'cacao': dict(side),
          'runs': {'amd': [{'total_ms': 0.1, 'frames_total_ms': [0.1] * 30}],
                   'cacao': [{'total_ms': 0.15, 'steps': {'generate_gpu.q2': 0.05, 'classify': 0.01}},
                             {'total_ms': 0.17, 'steps': {'generate_gpu.q2': 0.07, 'classify': 0.01}}]}}
json.dump({'procedure': {'reps': 1}, 'results': [result]}, open(os.path.join(run_dir, 'cacao.sceneA.json'), 'w'))
json.dump({'configurations': []}, open(os.path.join(run_dir, 'stats.cacao.json'), 'w'))
open(os.path.join(run_dir, 'stats.cacao.txt'), 'w').write('key wave\n')
open(os.path.join(run_dir, 'stats.amd.jsonl'), 'w').write('{"entry": "A"}\nFFX_CACAO_VkInitContext: 0\n{"entry": "B"}\n')
open(os.path.join(run_dir, 'machine.txt'), 'w').write('NVIDIA\n')
open(os.path.join(run_dir, 'front.x.json.1.tmp'), 'w').write('')
merged = os.path.join(WORK, 'merged.json')
ds.merge(run_dir, merged)
parts = json.load(open(merged))['parts']
check(sorted(parts) == ['cacao.sceneA', 'machine.txt', 'stats.amd', 'stats.cacao', 'stats.cacao.txt'],
      'merged parts %s' % sorted(parts))
check(parts.get('stats.amd') == [{'entry': 'A'}, {'entry': 'B'}], 'JSON lines merged as a list, other lines left out')
check(parts['cacao.sceneA']['results'][0]['runs'] == {'amd': [{'total_ms': 0.1}],
                                                      'cacao': [{'total_ms': 0.15}, {'total_ms': 0.17}]},
      'per-run details reduced to totals')
steps = parts['cacao.sceneA']['results'][0].get('cacao_steps', {})
check(sorted(steps) == ['classify', 'generate_gpu.q2'] and abs(steps['generate_gpu.q2'] - 0.06) < 1e-12 and
      steps['classify'] == 0.01,
      "cacao's passes kept as the median over the runs")

# The report of the committed runs: every table present, every ratio the runs' own.
report = load('gpu_report', os.path.join(SRC, 'tools', 'gpu-report.py'))
measured_dir = os.path.join(SRC, 'docs', 'gpu-measured')
check(report.measured_section(report.load_measured(WORK), {}) == [], 'no runs: no section')
runs = report.load_measured(measured_dir)
if 'final' in runs:
    lines = report.measured_section(runs, {})
    text = '\n'.join(lines)
    for heading in ('## Measured on a real GPU', '### Totals: cacao / AMD', '### Per stage',
                    '### The depth mip chain and the changes with it, measured in the same run',
                    '### Earlier changes, measured in an earlier run', '### Tried and not kept',
                    '### The classes from the caller\'s depth, measured',
                    '### The classification in the prepare\'s own groups, downsampled, measured',
                    '### The shader forms on this GPU',
                    '### The horizon-slice estimators', '### What the driver reports'):
        check(heading in text, 'report lacks %r' % heading)
    ratios = [r['ratio'] for sc in report.SCENES for r in report.results_of(runs['final'], 'cacao', sc).values()]
    check(len(ratios) == 30, '30 scene x configuration pairs in the final run, not %d' % len(ratios))
    check('takes %.2f-%.2fx AMD' % (min(ratios), max(ratios)) in text, 'the totals sentence is the runs\' range')
    check('SM clock of ? ' not in text, 'the SM clock was read')
    if 'chain_before' in runs:
        b = report.results_of(runs['chain_before'], 'cacao', report.SCENES[0])['HIGH_native']['ratio']
        f = report.results_of(runs['final'], 'cacao', report.SCENES[0])['HIGH_native']['ratio']
        check('| HIGH_native | %.2f / %.2f |' % (b, f) in text, 'the before / after table holds the runs\' ratios')
else:
    print('no committed runs under %s: report part skipped' % measured_dir)

if failures:
    sys.exit('%d failure(s)' % len(failures))
print('device_sidebyside: all checks passed')
