#!/usr/bin/python3
"""Regenerates docs/tiles-measured.md: what tile classification saves, measured.

For each shared scene, an all-background frame and a frame three quarters of which lie beyond the
fade-out, at each quality level (960x540, native, the CLI's default settings), runs `cacao
--timings` with skipping and with --all-tiles (every tile computed), interleaved, --reps times
(each repetition runs every frame of an estimator and quality before the next),
and reports the median frame time of each, their ratio and the work skipped (the runtime's tile
counts). Same binary, same run: the ratio is the figure, never the absolute milliseconds. The same
for the horizon estimators (GTAO, bitmask; native and downsampled) at LOWEST and HIGH.

usage: tools/tiles-report.py [--cacao build/tools/cli/cacao] [--shared ../shared] [--reps 3]
                             [--out docs/tiles-measured.md]
"""
import argparse, importlib.util, json, os, re, statistics, struct, subprocess, sys, tempfile

# The PFM reader of accuracy-report.py (a numpy array, rows top to bottom).
_spec = importlib.util.spec_from_file_location(
    'accuracy_report', os.path.join(os.path.dirname(os.path.abspath(__file__)), 'accuracy-report.py'))
acc = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(acc)

QUALITIES = ['lowest', 'low', 'medium', 'high', 'highest']
# (label, flags, qualities): CACAO at every level, the horizon estimators at their cheapest level
# and at HIGH
ESTIMATORS = [('cacao', [], QUALITIES), ('cacao downsampled', ['--downsample'], QUALITIES)] + [
    ('%s%s' % (e, ' downsampled' if ds else ''), ['--estimator', e] + (['--downsample'] if ds else []), ['lowest', 'high'])
    for ds in (False, True) for e in ('gtao', 'bitmask')]


def write_pfm(path, w, h, values):
    with open(path, 'wb') as f:
        f.write(b'Pf\n%d %d\n-1.0\n' % (w, h))
        f.write(struct.pack('<' + 'f' * len(values), *values))


def run(cacao, args):
    out = subprocess.run([cacao] + args + ['--timings', '--repeat', '5', '-o', os.devnull + '.pfm'],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit('cacao failed: %s\n%s' % (' '.join(args), out.stderr))
    total = tiles = None
    for line in out.stdout.splitlines():
        f = line.split()
        if f and f[0] == 'total':
            total = float(f[1])
        if line.startswith('tiles:'):
            tiles = line
    return total, tiles


def skipped(tiles_line):
    g = re.search(r'generate \d+ of \d+ tiles \(([0-9.]+)%\)', tiles_line)
    b = re.search(r'blur \d+ of \d+ groups \(([0-9.]+)%\)', tiles_line)
    return (g.group(1) if g else '-'), (b.group(1) if b else '-')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--cacao', default='build/tools/cli/cacao')
    ap.add_argument('--shared', default='../shared')
    ap.add_argument('--reps', type=int, default=3)
    ap.add_argument('--out', default='docs/tiles-measured.md')
    a = ap.parse_args()
    scenes_dir = os.path.join(a.shared, 'scenes')
    if not os.path.isdir(scenes_dir):
        sys.exit('no scenes at %s (--shared)' % scenes_dir)
    up_before = open('/proc/loadavg').read().split()[:3]
    work = tempfile.mkdtemp(prefix='cacao-tiles-')
    street = os.path.join(scenes_dir, 'street_track')
    cases = []
    for name in ['street_track', 'statues_scanned', 'interior_fzkhaus']:
        d = os.path.join(scenes_dir, name)
        cases.append((name, ['--scene', d]))
    # All background: the far plane everywhere (street_track's camera).
    depth = acc.read_pfm(os.path.join(street, 'depth.pfm'))
    h, w = depth.shape
    sky = os.path.join(work, 'sky.pfm')
    write_pfm(sky, w, h, [1.0] * (w * h))
    cam = os.path.join(street, 'camera.json')
    cases.append(('all background', ['--depth', sky, '--camera', cam]))
    # Three quarters beyond the fade-out: fade_out_to at the 25th percentile of view z.
    c = json.load(open(cam))
    near, far = c['near'], c['far']
    z = sorted(near * far / (far - d * (far - near)) if d < 1.0 else float('inf') for d in depth.ravel().tolist())
    to = z[len(z) // 4]
    cases.append(('3/4 faded (street_track, fade-out %.1f..%.1f)' % (to / 2, to),
                  ['--scene', street, '--fade-out', '%g,%g' % (to / 2, to)]))

    # Per estimator and quality, each repetition runs every case (skipping, then all tiles) before
    # the next: a case's runs and street_track's lie seconds apart, so the ratios against
    # street_track are paired per repetition (the median of the per-repetition ratios), where a
    # ratio of medians taken minutes apart carried this machine's drift (up to 1.6x).
    rows, paired = [], {}
    for est, flags, qualities in ESTIMATORS:
        for q in qualities:
            on = {label: [] for label, _ in cases}
            off = {label: [] for label, _ in cases}
            tiles = {}
            for _ in range(a.reps):
                for label, args in cases:
                    t, tiles[label] = run(a.cacao, args + flags + ['--quality', q])
                    on[label].append(t)
                    off[label].append(run(a.cacao, args + flags + ['--quality', q, '--all-tiles'])[0])
            for label, _ in cases:
                m_on, m_off = statistics.median(on[label]), statistics.median(off[label])
                g, b = skipped(tiles[label])
                rows.append((est, label, q, m_on, m_off, m_on / m_off, g, b))
                paired[(est, label, q)] = statistics.median(
                    x / y for x, y in zip(on[label], on['street_track']))
                print('%-20s %-44s %-8s on %8.2f  all %8.2f  ratio %.3f  generate skipped %s%%  blur %s%%' % rows[-1],
                      flush=True)
    up_after = open('/proc/loadavg').read().split()[:3]
    lines = ['# Tile classification, measured', '',
             'Regenerated by `tools/tiles-report.py --reps %d` (lavapipe, 960x540, native unless the estimator says downsampled, the CLI defaults: '
             'fade-out 50..300, blur 2). Load average before %s, after %s. Each cell is the median over %d '
             'interleaved runs of the median of 5 timed frames; *all tiles* is the same binary with `--all-tiles` '
             '(no skipping). The ratio is the figure: absolute times vary between runs of this machine. Each '
             'repetition runs every frame of an estimator and quality (skipping, then all tiles) before the next, '
             'so the ratios against street_track below are paired: the median over the repetitions of '
             'the frame\'s time over street_track\'s in the same repetition.'
             % (a.reps, ' '.join(up_before), ' '.join(up_after), a.reps), '',
             'The horizon estimators count their estimator\'s tiles as "generate" (downsampled: the upsample\'s; '
             'the estimator itself runs over the blocks of 2x2 tiles holding an active tile), and have no blur groups.',
             '',
             '| estimator | frame | quality | skipping (ms) | all tiles (ms) | ratio | generate tiles skipped | blur groups skipped |',
             '|---|---|---|---:|---:|---:|---:|---:|']
    for est, label, q, m_on, m_off, r, g, b in rows:
        lines.append('| %s | %s | %s | %.1f | %.1f | %.3f | %s%% | %s%% |' % (est, label, q, m_on, m_off, r, g, b))
    lines += ['', 'All-background frame against street_track (skipping, same estimator and quality, paired per repetition):', '',
              '| estimator | quality | all background / street_track |', '|---|---|---:|']
    for est, label, q, _, _, _, _, _ in rows:
        if label == 'all background':
            lines.append('| %s | %s | %.3f |' % (est, q, paired[(est, label, q)]))
    lines += ['', '3/4-faded frame against street_track (skipping, same estimator and quality, paired per repetition):', '',
              '| estimator | quality | 3/4 faded / street_track |', '|---|---|---:|']
    for est, label, q, _, _, _, _, _ in rows:
        if label.startswith('3/4'):
            lines.append('| %s | %s | %.3f |' % (est, q, paired[(est, label, q)]))
    with open(a.out, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('wrote', a.out)


if __name__ == '__main__':
    main()
