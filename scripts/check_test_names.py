#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks Catch2 test names for characters CTest discovery cannot carry.

catch_discover_tests() passes each test's name to CTest as a list element and to Catch2 as a
filter: a ';' cuts the name in two, and a backslash escapes the next character of the filter, so
the name matches no test case (the suites run with --warn NoTests, so such an entry fails; without
it, it would pass without running anything). This prints every TEST_CASE name (adjacent string
literals joined) holding a ';' or a backslash and exits 1 if there is one.

    check_test_names.py TESTS_DIR
"""
import pathlib
import re
import sys

NAME = re.compile(r'(?:TEST_CASE|SCENARIO)\s*\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)')
LITERAL = re.compile(r'"((?:[^"\\]|\\.)*)"')


def test_names(text):
    for match in NAME.finditer(text):
        yield text.count('\n', 0, match.start()) + 1, ''.join(LITERAL.findall(match.group(1)))


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    bad = 0
    for path in sorted(pathlib.Path(sys.argv[1]).rglob('*.cpp')):
        for line, name in test_names(path.read_text(encoding='utf-8', errors='replace')):
            if ';' in name or '\\' in name:
                print('%s:%d: test name holds ";" or a backslash (no CTest entry could run it): %s' % (path, line, name))
                bad += 1
    print('%d test names with ";" or a backslash' % bad)
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
