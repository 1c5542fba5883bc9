#!/usr/bin/python3
"""Regenerates docs/reuse-measured.md: what reusing the previous frame (--reuse, docs/tiles.md
"Reusing the previous frame") saves, measured on lavapipe.

For each shared scene, quality level and resolution mode, runs `cacao --timings` (2 warm-up frames,
then --frames timed ones) in five ways, interleaved, --reps times, and reports the median frame
time of each against the first:
  full       no reuse: every frame computed whole (the reference);
  camera moving  --reuse --move-camera: every frame another projection, so a full frame (what
             reuse costs a frame with nothing to skip, as a moving camera gives it);
  all moved  --reuse with --move-box over the whole image: every frame changes every tile under a
             still camera (the diff finds it: the worst case);
  unchanged  --reuse --keep-output: the same depth every frame, the output kept by the caller
             (nothing written);
  unchanged, apply   --reuse without --keep-output: apply writes the whole output every frame;
  moved      --reuse --keep-output --move-box over a box of 10% of the image (a third of the width
             and of the height, centred): every frame an object moves (the box's depth shifted 8
             pixels, back and forth), the runtime's tile counts say how many tiles changed and
             how many it recomputed.
Same binary, same run: the ratios are the figures, never the absolute milliseconds.

usage: tools/reuse-report.py [--cacao build/tools/cli/cacao] [--shared ../shared] [--reps 3]
                             [--frames 5] [--qualities lowest,...] [--out docs/reuse-measured.md]
"""
import argparse, os, re, statistics, subprocess, sys

QUALITIES = ['lowest', 'low', 'medium', 'high', 'highest']
SCENES = ['street_track', 'statues_scanned', 'interior_fzkhaus']


def run(cacao, args, frames):
    out = subprocess.run([cacao] + args + ['--timings', '--repeat', str(frames), '-o', os.devnull + '.pfm'],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit('cacao failed: %s\n%s' % (' '.join(args), out.stderr))
    total, reuse = None, None
    for line in out.stdout.splitlines():
        f = line.split()
        if f and f[0] == 'total':
            total = float(f[1])
        m = re.match(r'reuse \(the last frame\): (\d+) of (\d+) tiles changed, (\d+) recomputed', line)
        if m:
            reuse = tuple(int(x) for x in m.groups())
    return total, reuse


def size_of(scene_dir):
    with open(os.path.join(scene_dir, 'depth.pfm'), 'rb') as f:
        f.readline()
        w, h = (int(x) for x in f.readline().split())
    return w, h


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--cacao', default='build/tools/cli/cacao')
    ap.add_argument('--shared', default='../shared')
    ap.add_argument('--reps', type=int, default=3)
    ap.add_argument('--frames', type=int, default=5)
    ap.add_argument('--qualities', default=','.join(QUALITIES))
    ap.add_argument('--out', default='docs/reuse-measured.md')
    a = ap.parse_args()
    scenes_dir = os.path.join(a.shared, 'scenes')
    if not os.path.isdir(scenes_dir):
        sys.exit('no scenes at %s (--shared)' % scenes_dir)
    qualities = a.qualities.split(',')
    up_before = open('/proc/loadavg').read().split()[:3]
    rows = []
    for name in SCENES:
        d = os.path.join(scenes_dir, name)
        w, h = size_of(d)
        whole = '0,0,%d,%d' % (w, h)
        box = '%d,%d,%d,%d' % (w // 3, h // 3, w // 3, h // 3)
        ways = [('full', []), ('camera moving', ['--reuse', '--move-camera']),
                ('all moved', ['--reuse', '--move-box', whole]),
                ('unchanged', ['--reuse', '--keep-output']), ('unchanged, apply', ['--reuse']),
                ('moved', ['--reuse', '--keep-output', '--move-box', box])]
        for ds in (False, True):
            for q in qualities:
                base = ['--scene', d, '--quality', q] + (['--downsample'] if ds else [])
                times = {k: [] for k, _ in ways}
                counts = None
                for _ in range(a.reps):
                    for k, extra in ways:
                        t, reuse = run(a.cacao, base + extra, a.frames)
                        times[k].append(t)
                        if k == 'moved':
                            counts = reuse
                med = {k: statistics.median(v) for k, v in times.items()}
                row = (name, 'downsampled' if ds else 'native', q, med['full'], med['camera moving'] / med['full'],
                       med['all moved'] / med['full'],
                       med['unchanged'] / med['full'], med['unchanged, apply'] / med['full'],
                       med['moved'] / med['full'], counts)
                rows.append(row)
                print('%-17s %-11s %-8s full %7.2f ms  camera %.3f  all moved %.3f  unchanged %.3f  (apply %.3f)  moved %.3f  %s'
                      % row, flush=True)
    up_after = open('/proc/loadavg').read().split()[:3]
    lines = ['# Reusing the previous frame, measured', '',
             'Regenerated by `tools/reuse-report.py --reps %d --frames %d` (lavapipe, the shared scenes at their '
             'size, the CLI defaults: normals given where the scene has them, fade-out 50..300, blur 2). Load average '
             'before %s, after %s. Each cell is the median over %d interleaved runs of the median of %d timed frames '
             '(after 2 warm-up frames), divided by the full frame of the same run (*full*, no reuse). '
             '*camera moving*: every frame another projection (`--move-camera`), a full frame for reuse; '
             '*all moved*: every tile changes every frame under a still camera (`--move-box` over the whole image); *unchanged*: the same '
             'depth every frame with the output kept by the caller (`--keep-output`); *unchanged, apply*: the same '
             'without it (apply writes the whole output); *moved*: a box of a ninth of the image (a third of each '
             'side, centred) moves 8 pixels every frame, with the output kept; its tile counts are the runtime\'s '
             '(changed: tiles whose depth or normals differ; recomputed: tiles whose output a change can reach).'
             % (a.reps, a.frames, ' '.join(up_before), ' '.join(up_after), a.reps, a.frames), '',
             '| scene | mode | quality | full (ms) | camera moving | all moved | unchanged | unchanged, apply | moved | moved: tiles changed / recomputed / all |',
             '|---|---|---|---:|---:|---:|---:|---:|---:|---|']
    for name, mode, q, full, cam, allm, unch, unch_apply, moved, counts in rows:
        c = '%d / %d / %d' % (counts[0], counts[2], counts[1]) if counts else '-'
        lines.append('| %s | %s | %s | %.1f | %.3f | %.3f | %.3f | %.3f | %.3f | %s |'
                     % (name, mode, q, full, cam, allm, unch, unch_apply, moved, c))
    with open(a.out, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('wrote', a.out)


if __name__ == '__main__':
    main()
