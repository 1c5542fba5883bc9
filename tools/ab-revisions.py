#!/usr/bin/python3
"""Interleaved A/B timing of the cacao command built from two git revisions of this repository.

Builds each revision in its own worktree and build folder (under --work, kept for reuse), then
alternates the two binaries in fresh processes (A, B, A, B, ...) --reps times, each run
`cacao ARGS --timings --repeat 5`. It prints the median over the runs of each pass's median ms.
Both sides run in the same stretch of time on the same machine, so their ratio is the figure.
This is how docs/speed-notes.md measures a change against its parent.

usage: tools/ab-revisions.py REV_A REV_B [--reps N] [--work DIR] [--pass REGEX] -- CACAO_ARGS...
  e.g. tools/ab-revisions.py e4bbb70~1 e4bbb70 --reps 8 --pass generate -- \\
         --scene ../shared/scenes/interior_fzkhaus --quality high
"""
import argparse, os, re, statistics, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def build(rev, work):
    sha = subprocess.run(['git', '-C', ROOT, 'rev-parse', '--verify', rev + '^{commit}'],
                         capture_output=True, text=True)
    if sha.returncode != 0:
        sys.exit('ab-revisions.py: no such revision: %s' % rev)
    sha = sha.stdout.strip()
    tree = os.path.join(work, sha[:12])
    binary = os.path.join(tree, 'build', 'tools', 'cli', 'cacao')
    if not os.path.isdir(tree):
        subprocess.run(['git', '-C', ROOT, 'worktree', 'add', '--detach', tree, sha], check=True,
                       stdout=subprocess.DEVNULL)
    if not os.path.exists(binary):
        for cmd in (['cmake', '-S', tree, '-B', os.path.join(tree, 'build'), '-G', 'Ninja',
                     '-DCMAKE_BUILD_TYPE=Release'],
                    ['cmake', '--build', os.path.join(tree, 'build'), '--target', 'cacao_cli']):
            if subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode != 0:
                sys.exit('ab-revisions.py: building %s failed: %s' % (rev, ' '.join(cmd)))
    if not os.path.exists(binary):
        sys.exit('ab-revisions.py: the build of %s made no %s' % (rev, binary))
    return binary


def main():
    argv = sys.argv[1:]
    cacao_args = argv[argv.index('--') + 1:] if '--' in argv else []
    argv = argv[:argv.index('--')] if '--' in argv else argv
    p = argparse.ArgumentParser(usage=__doc__.split('\n\n')[-1])
    p.add_argument('rev_a')
    p.add_argument('rev_b')
    p.add_argument('--reps', type=int, default=6)
    p.add_argument('--work', default=os.path.join(tempfile.gettempdir(), 'cacao-ab'))
    p.add_argument('--pass', dest='pass_re', default='.')
    a = p.parse_args(argv)
    if a.reps < 1:
        sys.exit('ab-revisions.py: --reps must be at least 1')
    os.makedirs(a.work, exist_ok=True)
    sides = [(a.rev_a, build(a.rev_a, a.work)), (a.rev_b, build(a.rev_b, a.work))]
    rx = re.compile(a.pass_re)
    times = {rev: {} for rev, _ in sides}
    out_pfm = os.path.join(a.work, 'ab-out.pfm')
    for _ in range(a.reps):
        for rev, binary in sides:
            r = subprocess.run([binary] + cacao_args + ['--timings', '--repeat', '5', '-o', out_pfm],
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit('ab-revisions.py: %s failed:\n%s' % (rev, r.stderr))
            for line in r.stdout.splitlines():
                f = line.split()
                if len(f) >= 2 and rx.search(f[0]) and re.fullmatch(r'[0-9]+(\.[0-9]*)?', f[1]):
                    times[rev].setdefault(f[0], []).append(float(f[1]))  # a pass row, not "tiles: ..."
    print('uptime: %s' % subprocess.run(['uptime'], capture_output=True, text=True).stdout.strip())
    for rev, _ in sides:
        print('%-12s %s' % (rev, '  '.join('%s %.1f' % (k, statistics.median(v)) for k, v in times[rev].items())))


if __name__ == '__main__':
    main()
