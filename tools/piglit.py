#!/usr/bin/env python3
"""piglit.py: runs Debian's piglit tests natively and with libquadgl-preload.so preloaded.

The tests come from piglit's own list (tests/opengl.xml.gz), chosen by the rules of
tools/piglit-tests.txt (groups, name patterns, single tests, exclusions with their reason and
the subset CI runs). Each test binary is run as piglit's runner would (its command, then -auto,
and -fbo for the tests piglit runs concurrently), natively first and then once per method with
LD_PRELOAD and QUADGL_METHOD set; a test that does not pass natively is not run preloaded (it
cannot fail us). The result is the PIGLIT: {"result": ...} line (or the worst subtest), a crash
when the process dies by a signal, a timeout past --timeout. A failure or a crash is run once
more before it counts, since Xvfb sometimes refuses a connection under load (a timeout is not:
the limit is generous, and a second wait would double the cost).
Must be run inside an X server (tools/conformance.sh starts Xvfb). Prints one row per test and
ends with "N passed, N failed": a test passes when it passes natively and with every method,
fails when it passes natively and not with some method; tests that do not pass natively are
counted apart. The --json results also hold, per test, the quads the library saw (its
QUADGL_STATS line): the tests that reach its paths.
"""
import argparse
import ast
import concurrent.futures
import gzip
import json
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

PIGLIT = '/usr/lib/x86_64-linux-gnu/piglit'
ORDER = {'pass': 0, 'warn': 1, 'skip': 2, 'fail': 3, 'timeout': 4, 'crash': 5}


def read_rules(path):
    """The list file: 'group G', 'match REGEX', 'test NAME', 'exclude NAME  # reason',
    'ci NAME' lines; '#' starts a comment."""
    rules = {'group': [], 'match': [], 'test': [], 'exclude': {}, 'ci': []}
    with open(path) as f:
        for line in f:
            text, _, reason = line.partition('#')
            text = text.strip()
            if not text:
                continue
            kind, _, arg = text.partition(' ')
            arg = arg.strip()
            if kind == 'exclude':
                rules['exclude'][arg] = reason.strip()
            elif kind in rules:
                rules[kind].append(arg)
            else:
                sys.exit('piglit.py: %s: unknown rule %r' % (path, kind))
    return rules


def load_tests(rules, subset):
    """(name, argv, concurrent) of every selected test, in piglit's order."""
    root = ET.parse(gzip.open(os.path.join(PIGLIT, 'tests', 'opengl.xml.gz'))).getroot()
    pattern = re.compile('|'.join(rules['match'])) if rules['match'] else None
    tests = []
    for t in root:
        name = t.get('name')
        if t.get('type') != 'gl' or name in rules['exclude']:
            continue
        chosen = (name in rules['test'] or any(name.startswith(g + '@') for g in rules['group'])
                  or (pattern and pattern.search(name)))
        if not chosen or (subset and name not in rules['ci']):
            continue
        opts = {o.get('name'): o.get('value') for o in t.findall('option')}
        argv = ast.literal_eval(opts['command'])  # piglit writes a Python list literal
        concurrent = opts.get('run_concurrent', 'True') == 'True'
        tests.append((name, argv + (['-auto', '-fbo'] if concurrent else ['-auto']), concurrent))
    return tests


def interpret(returncode, out, timed_out):
    """piglit's own reading of a run (framework/test/base.py and piglit_test.py)."""
    if timed_out:
        return 'timeout'
    result, subtests = None, []
    for line in out.splitlines():
        if line.startswith('PIGLIT: '):
            try:
                d = json.loads(line[8:])
            except ValueError:
                continue
            if 'result' in d:
                result = d['result']
            for v in d.get('subtest', {}).values():
                subtests.append(v)
    if result is None:
        result = max(subtests, key=lambda s: ORDER.get(s, 3)) if subtests else 'fail'
    if returncode < 0:
        return 'crash'
    if returncode != 0:
        return 'warn' if result == 'pass' else 'fail' if result != 'crash' else 'crash'
    return result if result in ORDER else 'fail'


def run_once(argv, env, timeout):
    path = os.path.join(PIGLIT, 'bin', argv[0])
    try:
        p = subprocess.run([path] + argv[1:], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           stdin=subprocess.DEVNULL, timeout=timeout, cwd=PIGLIT)
        return interpret(p.returncode, p.stdout.decode(errors='replace'), False), p.stdout
    except subprocess.TimeoutExpired as e:
        return 'timeout', e.stdout or b''
    except OSError as e:
        return 'fail', str(e).encode()


def quads_seen(out):
    """The quads the library saw, from its QUADGL_STATS line at exit (0 without one)."""
    m = re.findall(rb'quadgl: (\d+) quads', out)
    return int(m[-1]) if m else 0


def run(argv, env, timeout, logdir, tag):
    """One configuration of one test, run again once if it failed or crashed. Returns the
    result and the quads the library saw."""
    result, out = run_once(argv, env, timeout)
    if result in ('fail', 'crash'):
        result, out = run_once(argv, env, timeout)
    if logdir and result not in ('pass', 'skip'):
        with open(os.path.join(logdir, re.sub(r'[^\w.-]+', '_', tag) + '.log'), 'wb') as f:
            f.write(out)
    return result, quads_seen(out)


def run_test(test, configs, args, known):
    name, argv, _ = test
    t0 = time.monotonic()
    row = {}
    for cfg, env in configs:
        if cfg == 'native' and name in known:
            row[cfg] = known[name]
            continue
        if cfg != 'native' and row['native'] not in ('pass', 'warn'):
            row[cfg] = '-'
            continue
        row[cfg], quads = run(argv, env, args.timeout, args.logs, name + '.' + cfg)
        if cfg != 'native':
            row['quads'] = max(row.get('quads', 0), quads)
    return name, row, time.monotonic() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--rules', default=os.path.join(os.path.dirname(__file__), 'piglit-tests.txt'))
    ap.add_argument('--lib', required=True, help='libquadgl-preload.so')
    ap.add_argument('--methods', default='auto,mvc,split')
    ap.add_argument('--ci', action='store_true', help="only the list's ci subset")
    ap.add_argument('--filter', help='only tests whose name matches this regular expression')
    ap.add_argument('--jobs', type=int, default=os.cpu_count() or 2)
    ap.add_argument('--timeout', type=float, default=120, help='seconds per run')
    ap.add_argument('--logs', help='folder for the output of every run that did not pass')
    ap.add_argument('--json', help='write the results here')
    ap.add_argument('--native-from', help="take the native results from this --json file of an earlier run")
    ap.add_argument('--progress', action='store_true', help='a line on stderr as each test ends')
    ap.add_argument('--extra-env', action='append', default=[], help='VAR=VALUE for preloaded runs')
    ap.add_argument('--preload-first', help="a library LD_PRELOAD lists before --lib (a sanitizer's runtime)")
    args = ap.parse_args()

    rules = read_rules(args.rules)
    tests = load_tests(rules, args.ci)
    if args.filter:
        tests = [t for t in tests if re.search(args.filter, t[0])]
    if args.logs:
        os.makedirs(args.logs, exist_ok=True)
    base = dict(os.environ)
    for k in ('LD_PRELOAD', 'QUADGL_METHOD'):
        base.pop(k, None)
    methods = [m for m in args.methods.split(',') if m]
    configs = [('native', base)]
    for m in methods:
        preload = os.path.abspath(args.lib)
        if args.preload_first:
            preload = args.preload_first + ':' + preload
        env = dict(base, LD_PRELOAD=preload, QUADGL_METHOD=m, QUADGL_STATS='1')
        env.update(kv.split('=', 1) for kv in args.extra_env)
        configs.append((m, env))

    known = {}
    if args.native_from:
        with open(args.native_from) as f:
            known = {n: r['native'] for n, r in json.load(f).items()}
    t0 = time.monotonic()
    results = {}

    def done(name, row, secs):
        results[name] = (row, secs)
        if args.progress:
            print('[%d/%d] %s: %s (%.0f s)' % (len(results), len(tests), name,
                                             ' '.join(row[c] for c, _ in configs), secs), file=sys.stderr, flush=True)

    # Concurrent tests side by side, then the others alone (they use the window's own buffer).
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        futures = [pool.submit(run_test, t, configs, args, known) for t in tests if t[2]]
        for f in concurrent.futures.as_completed(futures):
            done(*f.result())
    for t in tests:
        if not t[2]:
            done(*run_test(t, configs, args, known))
    wall = time.monotonic() - t0

    cols = [c for c, _ in configs]
    width = max([len(t[0]) for t in tests] + [4])
    print('%-*s %s %8s' % (width, 'test', ' '.join('%-7s' % c for c in cols), 'quads'))
    passed = failed = other = 0
    failed_by = {m: 0 for m in methods}
    for name, _, _ in tests:
        row, _ = results[name]
        bad = [m for m in methods if row[m] not in ('pass', 'warn')]
        mark = ''
        if row['native'] not in ('pass', 'warn'):
            other += 1
        elif bad:
            failed += 1
            mark = '  <-- fails preloaded'
            for m in bad:
                failed_by[m] += 1
        else:
            passed += 1
        print('%-*s %s %8s%s' % (width, name, ' '.join('%-7s' % row[c] for c in cols),
                                 row.get('quads', '-'), mark))
    print()
    others = ', '.join('%d %s' % (sum(1 for r, _ in results.values() if r['native'] == s), s)
                       for s in sorted(set(r['native'] for r, _ in results.values())) if s not in ('pass', 'warn'))
    print('%d tests in %.0f s; %d pass natively; %d do not pass natively%s' % (
        len(tests), wall, passed + failed, other, ' (not compared: %s)' % others if others else ''))
    if methods:
        print('fail preloaded: ' + ', '.join('%s %d' % (m, failed_by[m]) for m in methods))
    slow = sorted(((s, n) for n, (_, s) in results.items()), reverse=True)[:5]
    print('slowest: ' + ', '.join('%s %.0f s' % (n, s) for s, n in slow))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({n: dict(r, seconds=round(s, 2)) for n, (r, s) in results.items()}, f, indent=1)
    print('%d passed, %d failed' % (passed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
