#!/usr/bin/env python3
"""Checks the source tree's rooms (docs/architecture.md, "Folders"): prints every include
that crosses a wall and exits 1 if there is one.

  - a GI method's folders (common/gi/NAME/, node/gi/NAME/, NAME a line of
    common/gi/gi_methods.def) include no header of another method's folders;
  - master/ includes nothing of node/: every quoted include of master/ resolves in
    master/, common/ or include/;
  - common/ includes nothing of node/ or master/.

Usage: scripts/check_layout.py [ROOT]   (default: the tree this script is in)."""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def sources(root, folder):
    for base, _, files in os.walk(os.path.join(root, folder)):
        for f in sorted(files):
            if f.endswith(('.c', '.h', '.cpp')):
                path = os.path.join(base, f)
                with open(path, encoding='utf-8') as fh:
                    yield os.path.relpath(path, root), INCLUDE.findall(fh.read())


def resolves(root, src, inc, folders):
    """The folder of folders where inc, included from src, is found (its own folder first)."""
    if os.path.exists(os.path.join(root, os.path.dirname(src), inc)):
        return os.path.normpath(os.path.join(os.path.dirname(src), inc)).split(os.sep)[0]
    for f in folders:
        if os.path.exists(os.path.join(root, f, inc)):
            return f
    return None


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..')
    with open(os.path.join(root, 'common/gi/gi_methods.def'), encoding='utf-8') as fh:
        methods = re.findall(r'^GI_METHOD\((\w+)\)', fh.read(), re.M)
    bad = []
    for m in methods:
        others = [o for o in methods if o != m]
        for half in ('common/gi/' + m, 'node/gi/' + m):
            for src, incs in sources(root, half):
                for inc in incs:
                    if any(inc.startswith('gi/%s/' % o) for o in others):
                        bad.append('%s: includes "%s", a header of another method' % (src, inc))
    for room, allowed in (('master', ['master', 'common', 'include']),
                          ('common', ['common', 'include'])):
        everything = ['master', 'common', 'include', 'node']
        for src, incs in sources(root, room):
            for inc in incs:
                where = resolves(root, src, inc, allowed) or resolves(root, src, inc, everything)
                if where not in allowed:
                    bad.append('%s: includes "%s", which is %s' %
                               (src, inc, 'under ' + where + '/' if where else 'nowhere'))
    for line in bad:
        print(line)
    print('layout: %d method folders, %d include(s) across a wall' % (2 * len(methods), len(bad)))
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
