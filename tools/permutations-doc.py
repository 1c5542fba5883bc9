#!/usr/bin/python3
"""Refresh the `cacao-inspect` examples in docs/permutations.md from the current build.

usage: tools/permutations-doc.py [--inspect PATH] [--doc FILE] [--check]

Every fenced block of the document whose first line is `$ cacao-inspect ARGS` is replaced by that
command's real output. A block whose first line ends in `(first part ...)` keeps only as many
output lines as it has now, followed by `  ...`. With --check nothing is written; the exit status
is 1 when the document is stale (and says which command), 0 when it is current.
"""
import argparse
import re
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--inspect', default='build/tools/inspect/cacao-inspect')
    ap.add_argument('--doc', default='docs/permutations.md')
    ap.add_argument('--check', action='store_true')
    a = ap.parse_args()

    try:
        text = open(a.doc).read()
    except OSError as e:
        sys.exit('permutations-doc.py: %s: %s' % (a.doc, e.strerror))
    block = re.compile(r'```\n(\$ cacao-inspect ([^\n]*))\n(.*?)```', re.S)
    stale = []

    def refresh(m):
        header, args, body = m.group(1), m.group(2), m.group(3)
        partial = re.search(r'\s+\(first part[^)]*\)\s*$', args)
        argv = (args[:partial.start()] if partial else args).split()
        r = subprocess.run([a.inspect] + argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True)
        if r.returncode != 0:
            sys.exit('permutations-doc.py: `cacao-inspect %s` failed: %s' % (' '.join(argv), r.stderr.strip()))
        lines = r.stdout.rstrip('\n').split('\n')
        if partial:
            keep = len([l for l in body.rstrip('\n').split('\n') if l != '  ...'])
            lines = lines[:keep] + ['  ...']
        new_body = '\n'.join(lines) + '\n'
        if new_body != body:
            stale.append(' '.join(argv))
        return '```\n%s\n%s```' % (header, new_body)

    new_text = block.sub(refresh, text)
    if a.check:
        for s in stale:
            print('stale: cacao-inspect %s' % s)
        sys.exit(1 if stale else 0)
    if new_text != text:
        open(a.doc, 'w').write(new_text)
    print('%s: %d block(s) refreshed' % (a.doc, len(stale)))


if __name__ == '__main__':
    main()
