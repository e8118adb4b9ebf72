#!/usr/bin/env python3
"""The verdict of scripts/run_tests.sh from its JUnit XML files: per file the tests, failures and time; every
failed, errored or skipped test by name (gtest binary and Suite.Test, rostest and its test case, pytest node id);
the slowest test cases; the count of test cases by kind. Exit status 1 if anything failed or errored, or a result
file is missing or unreadable.

Counting: each test case once. A rostest writes two files: rostest-<file>.xml, one case for the whole test node
("test<test-name>"), and the node's own rosunit-<test-name>.xml with its cases; the rostest file's case is counted
only when the node left no rosunit file (it died, or never started), and its failure is named either way.
(catkin_test_results counts differently: it adds a gtest file's <testsuites tests="N"> to its <testsuite>
children's, so every gtest case twice, and it counts both rostest files; docs/tests.md, Counting.)

Usage: scripts/test_summary.py [--slowest N] [--expect NAME ...] DIR_OR_FILE ...
  --expect NAME  a result file (its name without .xml) that must exist: a runner that died before writing it
                 is then a failure named here, not a silently shorter list.
"""
import argparse
import glob
import os
import sys
import xml.etree.ElementTree as ET


def result_files(paths):
    files = []
    for path in paths:
        if os.path.isdir(path):
            files.extend(sorted(glob.glob(os.path.join(path, '*.xml'))))
        elif os.path.exists(path):
            files.append(path)
    return files


def pytest_node_id(classname, name, source_dir):
    """pytest's JUnit classname is the dotted module path (and class); the node id is path::Class::test."""
    parts = classname.split('.')
    for i in range(len(parts), 0, -1):
        candidate = os.path.join(source_dir, *parts[:i]) + '.py'
        if os.path.exists(candidate):
            return '::'.join(['/'.join(parts[:i]) + '.py'] + parts[i:] + [name])
    return '%s::%s' % (classname, name)


def label(kind, unit, case, source_dir):
    classname, name = case.get('classname', ''), case.get('name', '')
    if kind == 'gtest':
        return 'gtest %s: %s.%s' % (unit, classname, name)
    if kind == 'pytest':
        return 'pytest %s' % pytest_node_id(classname, name, source_dir)
    if kind == 'rostest':
        return 'rostest %s: %s' % (unit, name)
    if kind == 'rosunit':
        return 'rostest %s: %s.%s' % (unit, classname.split('.')[-1], name)
    return '%s %s: %s.%s' % (kind, unit, classname, name)


def kind_and_unit(path):
    base = os.path.basename(path)[:-len('.xml')]
    for kind in ('gtest', 'rostest', 'pytest', 'rosunit', 'fuzz', 'sanitized'):
        if base.startswith(kind + '-'):
            return kind, base[len(kind) + 1:]
    return 'test', base


def first_line(text):
    for line in (text or '').splitlines():
        if line.strip():
            return line.strip()[:200]
    return ''


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--slowest', type=int, default=8)
    parser.add_argument('--source-dir', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument('--expect', action='append', default=[])
    parser.add_argument('paths', nargs='+')
    args = parser.parse_args()

    files = result_files(args.paths)
    problems, skipped, cases, table = [], [], [], []
    counted = {}  # kind -> test cases counted
    seen = {os.path.basename(f)[:-len('.xml')] for f in files}
    for name in args.expect:
        if name not in seen:
            problems.append('%s: no result file (the runner died or never ran)' % name)
    for path in files:
        kind, unit = kind_and_unit(path)
        # (rosunit-<test-name>.xml is the test node's own result: on these Debian packages a failed assertion is
        # only there — rostest-<file>.xml records its test case as passed. Both are read, as catkin_test_results does.)
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as error:
            problems.append('%s %s: unreadable result file %s (%s)' % (kind, unit, path, error))
            continue
        suites = [root] if root.tag == 'testsuite' else root.findall('testsuite')
        n = failed = 0
        seconds = 0.0
        for suite in suites:
            for case in suite.iter('testcase'):
                n += 1
                name = case.get('name', '')
                node_wrote_its_own = kind == 'rostest' and name.startswith('test') and 'rosunit-' + name[4:] in seen
                if not node_wrote_its_own:
                    count_kind = 'rostest' if kind == 'rosunit' else kind
                    counted[count_kind] = counted.get(count_kind, 0) + 1
                seconds_case = float(case.get('time') or 0.0)
                seconds += seconds_case
                what = label(kind, unit, case, args.source_dir)
                if not node_wrote_its_own:
                    cases.append((seconds_case, what))
                bad = case.find('failure')
                if bad is None:
                    bad = case.find('error')
                if bad is not None:
                    failed += 1
                    problems.append('%s  -- %s' % (what, first_line(bad.get('message') or bad.text)))
                elif case.find('skipped') is not None or case.get('status') == 'notrun':
                    skipped.append(what)
        if kind == 'rostest' and n == 0:
            problems.append('rostest %s: no test case ran' % unit)
        table.append((kind, unit, n, failed, float(root.get('time') or seconds)))

    print('%-8s %-58s %6s %7s %9s' % ('kind', 'result', 'tests', 'failed', 'seconds'))
    for kind, unit, n, failed, seconds in table:
        print('%-8s %-58s %6d %7d %9.1f' % (kind, unit[:58], n, failed, seconds))
    total = sum(counted.values())
    rostest_files = sum(1 for row in table if row[0] == 'rostest')
    by_kind = ', '.join('%s %d' % (kind, counted[kind]) for kind in sorted(counted))
    print('%d test cases in %d result files: %s%s' % (
        total, len(table), by_kind, ' (the rostest cases of %d launch files)' % rostest_files if rostest_files else ''))
    if args.slowest > 0:
        print('slowest test cases:')
        for seconds, what in sorted(cases, reverse=True)[:args.slowest]:
            print('  %7.1f s  %s' % (seconds, what))
    for what in skipped:
        print('SKIPPED %s' % what)
    for what in problems:
        print('FAILED  %s' % what)
    if problems:
        print('%d FAILED (above; the logs: build/test_logs/)' % len(problems))
        return 1
    print('all %d tests passed%s' % (total, ', %d skipped' % len(skipped) if skipped else ''))
    return 0


if __name__ == '__main__':
    sys.exit(main())
