#!/usr/bin/python3
"""Regenerate every count the hand-written docs state about the code, and their cacao-inspect examples.

usage: tools/refresh-docs.py [--build DIR] [--inspect PATH] [--bench PATH] [--shadergen PATH]
                             [--check | --list]

Run it after any change that can move such a number (a pass, a key, a module's size, a plan, the
configurations a test or the bench covers); ctest `docs_current` runs it with --check, so CI fails
when a doc is stale. It reads README.md and every docs/*.md and rewrites only two kinds of text:

  - a fenced block whose first line is `$ cacao-inspect ARGS`: that command's real output (a first
    line ending in `(first part ...)` keeps as many output lines as the block has now, then `  ...`);
  - an inline fact `<!-- fact:NAME ARGS -->VALUE<!-- /fact -->` (the markers do not render): VALUE
    is what the fact NAME below computes from ARGS, from the build's tools or the sources.

Measured figures (docs/speed.md, accuracy.md, ...) come from their own report tools and carry no
markers. With --check nothing is written: the exit status is 1, naming each stale block and fact,
0 when all are current. --list prints the facts known, then each one the docs use: where, value.
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class DocError(Exception):
    pass


class Build:
    """The build's tools, each command run once."""

    def __init__(self, inspect, bench, shadergen):
        self.tools = {'cacao-inspect': inspect, 'cacao-bench': bench, 'shadergen': shadergen}
        self.outputs = {}

    def run(self, tool, *args):
        argv = (self.tools[tool],) + args
        if argv not in self.outputs:
            try:
                r = subprocess.run(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   universal_newlines=True)
            except OSError as e:
                raise DocError('cannot run %s (build it, or name it with --%s): %s' % (
                    argv[0], tool.split('-')[-1], e.strerror))
            if r.returncode != 0:
                raise DocError('`%s %s` failed: %s' % (tool, ' '.join(args), r.stderr.strip()))
            self.outputs[argv] = r.stdout
        return self.outputs[argv]

    def facts(self):
        return json.loads(self.run('cacao-inspect', 'facts'))

    def permutations(self, names):
        """Entries of `cacao-inspect list --json` whose key is one of names or of a pass among them."""
        found = [p for p in json.loads(self.run('cacao-inspect', 'list', '--json'))
                 if any(p['key'] == n or p['key'].startswith(n + '.') for n in names)]
        if not found:
            raise DocError('no embedded permutation matches %s' % ' '.join(names))
        return found

    def plan(self, flags):
        """`cacao-inspect plan FLAGS`, at 1920x1080 unless FLAGS give a size."""
        flags = tuple(flags) if '--size' in flags else ('--size', '1920x1080') + tuple(flags)
        return self.run('cacao-inspect', 'plan', *flags)


FACTS = {}


def fact(fn):
    """Registers fn(build, *args) -> value as the fact named after it."""
    FACTS[fn.__name__] = fn
    return fn


def kb(n_bytes):
    return '%d' % round(n_bytes / 1000.0)


# ---- the embedded table, the pass table and the API's limits ----

@fact
def inspect(b, field):
    """a field of `cacao-inspect facts`: key_space, permutations, modules, passes, max_size, ..."""
    value = b.facts()[field]
    return 'x'.join(map(str, value)) if isinstance(value, list) else str(value)


@fact
def keys(b, *names):
    """permutations of these passes or keys (`cacao-inspect list --json`)"""
    return str(len(b.permutations(names)))


@fact
def kb_total(b, *names):
    """SPIR-V kilobytes (1000 bytes) of these passes' or keys' modules, each module once"""
    return kb(sum({p['module']: p['spirv_bytes'] for p in b.permutations(names)}.values()))


@fact
def kb_range(b, *names):
    """smallest-largest SPIR-V kilobytes of one module among these passes or keys"""
    sizes = [p['spirv_bytes'] for p in b.permutations(names)]
    return '%s-%s' % (kb(min(sizes)), kb(max(sizes)))


@fact
def workgroup(b, key):
    """a key's workgroup size, XxY"""
    return '%dx%d' % tuple(b.permutations([key])[0]['workgroup_size'][:2])


@fact
def size_saving(b):
    """percent fewer SPIR-V bytes than without the size optimisation (shadergen --no-optimize)"""
    with tempfile.TemporaryDirectory() as out:
        summary = b.run('shadergen', '--source', os.path.join(ROOT, 'shaders', 'cacao.comp'), '--out', out,
                        '--no-optimize')
    unoptimised = int(re.search(r'(\d+) after', summary).group(1))
    return '%d' % round(100.0 * (1 - b.facts()['spirv_bytes'] / unoptimised))


# ---- plans (cacao-inspect plan: the runtime's own cacao_plan_build) ----

def plan_steps_keys(b, flags):
    return re.findall(r'^\s*\d+ (\S+)\s+dispatch', b.plan(flags), re.M)


@fact
def plan_steps(b, *flags):
    """steps (dispatches) of the plan for these settings flags"""
    return str(len(plan_steps_keys(b, flags)))


@fact
def plan_pipelines(b, *flags):
    """pipelines the plan needs: one per distinct permutation among its steps"""
    return str(len(set(plan_steps_keys(b, flags))))


@fact
def plan_mb(b, *args):
    """megabytes (10^6 bytes) of these intermediates, then the plan's settings flags: view_depth --estimator gtao"""
    split = next((i for i, a in enumerate(args) if a.startswith('--')), len(args))
    names, flags = args[:split], args[split:]
    text = b.plan(flags)
    total = 0
    for name in names:
        m = re.search(r'^\s+%s\s.* (\d+) bytes$' % re.escape(name), text, re.M)
        if not m:
            raise DocError('the plan for %s has no intermediate %s' % (' '.join(flags), name))
        total += int(m.group(1))
    return '%.1f' % (total / 1e6)


def horizon_line(b, estimator, quality):
    m = re.search(r'horizon slices: (\d+) x (\d+) steps per side = (\d+) depth reads',
                  b.plan(('--estimator', estimator, '--quality', quality)))
    if not m:
        raise DocError('no horizon budget in the plan at quality %s' % quality)
    return m


@fact
def horizon_budget(b, estimator, quality):
    """an estimator's (gtao, bitmask) slices x steps per side at a quality level"""
    m = horizon_line(b, estimator, quality)
    return '%sx%s' % (m.group(1), m.group(2))


@fact
def horizon_reads(b, estimator, quality):
    """an estimator's (gtao, bitmask) depth reads per pixel at a quality level"""
    return horizon_line(b, estimator, quality).group(3)


@fact
def tile(b, where):
    """a tile's side in slice texels (slice) or in output pixels (native, downsampled): NxN"""
    side = b.facts()['tile_texels']
    if where != 'slice':
        text = b.plan(('--downsample',) if where == 'downsampled' else ())
        width = int(re.match(r'plan: (\d+)x', text).group(1))
        side = side * width // int(re.search(r'slices: \d+ of (\d+)x', text).group(1))
    return '%dx%d' % (side, side)


# ---- what the tests and the bench cover, and the sources ----

@fact
def asserted(b, path, variable):
    """the count a test asserts: CHECK(VARIABLE == EXPR) in PATH"""
    text = open(os.path.join(ROOT, path)).read()
    found = re.findall(r'CHECK\(\s*%s\s*==\s*([0-9+* ]+?)\s*(?:\)|&&)' % re.escape(variable), text)
    if len(found) != 1:
        raise DocError('%s: expected one CHECK(%s == N), found %d' % (path, variable, len(found)))
    return str(eval(found[0], {'__builtins__': {}}))


@fact
def bench_configs(b, *flags):
    """configurations `cacao-bench FLAGS --list-configs` selects"""
    return str(len(b.run('cacao-bench', *(flags + ('--list-configs',))).split()))


@fact
def lines(b, path):
    """lines of a source file"""
    return str(sum(1 for _ in open(os.path.join(ROOT, path))))


# ---- the documents ----

BLOCK = re.compile(r'```\n(\$ cacao-inspect ([^\n]*))\n(.*?)```', re.S)
FACT = re.compile(r'<!-- fact:(\w+)((?: [^ >]+)*) -->([^<`\n]*)<!-- /fact -->')  # a value has no ` < or newline


def refresh_blocks(b, doc, text, stale):
    def refresh(m):
        header, args, body = m.group(1), m.group(2), m.group(3)
        partial = re.search(r'\s+\(first part[^)]*\)\s*$', args)
        argv = (args[:partial.start()] if partial else args).split()
        lines_out = b.run('cacao-inspect', *argv).rstrip('\n').split('\n')
        if partial:
            keep = len([l for l in body.rstrip('\n').split('\n') if l != '  ...'])
            lines_out = lines_out[:keep] + ['  ...']
        new_body = '\n'.join(lines_out) + '\n'
        if new_body != body:
            stale.append('%s: block `cacao-inspect %s`' % (doc, ' '.join(argv)))
        return '```\n%s\n%s```' % (header, new_body)
    return BLOCK.sub(refresh, text)


def refresh_facts(b, doc, text, stale, used):
    def refresh(m):
        name, args, old = m.group(1), m.group(2).split(), m.group(3)
        where = '%s:%d' % (doc, text.count('\n', 0, m.start()) + 1)
        if name not in FACTS:
            raise DocError('%s: unknown fact %s (known: %s)' % (where, name, ', '.join(sorted(FACTS))))
        try:
            new = FACTS[name](b, *args)
        except (DocError, KeyError, TypeError, OSError) as e:
            raise DocError('%s: fact %s %s: %s' % (where, name, ' '.join(args), e))
        used.append('%-30s %-8s %s' % (where, new, ' '.join([name] + args)))
        if new != old:
            stale.append('%s: fact %s %s: %s -> %s' % (where, name, ' '.join(args), old, new))
        return m.group(0)[:m.start(3) - m.start()] + new + '<!-- /fact -->'
    new_text, count = FACT.subn(refresh, text)
    if count != len(re.findall(r'(?<!`)<!-- fact:', text)):
        raise DocError('%s: a fact marker is malformed or has no <!-- /fact -->' % doc)
    return new_text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'), help='build tree (default: build/)')
    ap.add_argument('--inspect', help='cacao-inspect (default: BUILD/tools/inspect/cacao-inspect)')
    ap.add_argument('--bench', help='cacao-bench (default: BUILD/tools/bench/cacao-bench)')
    ap.add_argument('--shadergen', help='shadergen (default: BUILD/shadergen)')
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument('--check', action='store_true', help='write nothing; exit 1 when a doc is stale')
    mode.add_argument('--list', action='store_true', help='print the facts known and those the docs use; write nothing')
    a = ap.parse_args()
    b = Build(a.inspect or os.path.join(a.build, 'tools', 'inspect', 'cacao-inspect'),
              a.bench or os.path.join(a.build, 'tools', 'bench', 'cacao-bench'),
              a.shadergen or os.path.join(a.build, 'shadergen'))

    docs = ['README.md'] + sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, 'docs', '*.md')))
    stale, used, changed = [], [], {}
    try:
        subset = b.facts()['subset']
        if subset != 'all':
            raise DocError('the docs describe the full build; this one embeds subset %s' % subset)
        for doc in docs:
            text = open(os.path.join(ROOT, doc)).read()
            new_text = refresh_blocks(b, doc, refresh_facts(b, doc, text, stale, used), stale)
            if new_text != text:
                changed[doc] = new_text
    except DocError as e:
        sys.exit('refresh-docs.py: %s' % e)
    if a.list:
        for name, fn in sorted(FACTS.items()):
            print('fact %-15s %s' % (name, fn.__doc__))
        print('\n'.join(used))
        return
    if a.check:
        for s in stale:
            print('stale: %s' % s)
        print('%d doc(s), %d fact(s): %s' % (len(docs), len(used), 'stale' if stale else 'current'))
        sys.exit(1 if stale else 0)
    for doc, new_text in changed.items():
        with open(os.path.join(ROOT, doc), 'w') as f:
            f.write(new_text)
    print('%d doc(s), %d fact(s): %d stale item(s) rewritten in %s' % (
        len(docs), len(used), len(stale), ', '.join(sorted(changed)) or 'none'))


if __name__ == '__main__':
    main()
