"""`ament_copyright.main`: the copyright and licence check that `ros2 pkg create`'s
`test/test_copyright.py` runs (``main(argv=['.', 'test'])``, 0 when every file passes).

ROS's checker has no wheel on PyPI; this one checks the same things the same way from the
command line's view: every C/C++, CMake and Python source file (not `setup.py` beside a
`package.xml`, not folders starting with `.` or `_`, nothing under an `AMENT_IGNORE`) must
open, after any shebang and coding line, with a comment block holding a `Copyright <years>
<holder>` line and a known licence's file header; a repository root's LICENSE must be a known
licence and its CONTRIBUTING.md present. Problems go to stderr as `<file>: <problem>`, then
`N errors, checked M files`; a clean run prints `No problems found, checked M files`.
The licence texts are the ones `ros2lite pkg create --license` writes.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources
from xml.sax.saxutils import escape, quoteattr

__all__ = ['LICENSES', 'UNKNOWN_IDENTIFIER', 'FileReport', 'check_file', 'get_files', 'main']

UNKNOWN_IDENTIFIER = '<unknown>'
EXTENSIONS = ('c', 'cc', 'cpp', 'cxx', 'h', 'hh', 'hpp', 'hxx', 'cmake', 'py')
_LICENSE_FILE = 'LICENSE'
_CONTRIBUTING_FILE = 'CONTRIBUTING.md'
# ament_copyright's names for the licences, their titles, and the SPDX id of the text
LICENSES = {
    'apache2': ('Apache License, Version 2.0', 'Apache-2.0'),
    'boost1': ('Boost Software License - Version 1.0', 'BSL-1.0'),
    'bsd_2clause': ('2-Clause BSD License', 'BSD-2-Clause'),
    'bsd_3clause': ('3-Clause BSD License', 'BSD-3-Clause'),
    'gplv3': ('GNU General Public License 3.0', 'GPL-3.0-only'),
    'lgplv3': ('GNU Lesser General Public License 3.0', 'LGPL-3.0-only'),
    'mit': ('MIT License', 'MIT'),
    'mit0': ('MIT-0 License', 'MIT-0'),
}
_COPYRIGHT = re.compile(
    r'^\s*copyright\s+(?:\(c\)\s+)?(?P<years>\d{4}(?:\s*[-,]\s*\d{4})*)\s*,?\s+(?P<name>\S.*?)'
    r'\s*\.?\s*$',
    re.IGNORECASE,
)
_CODING = re.compile(r'^#.*coding[:=]')


def _licence_text(spdx: str) -> str:
    return (resources.files('ros2lite.pkg') / 'licenses' / f'{spdx}.txt').read_text(
        encoding='utf-8'
    )


def _between(text: str, first: str, last: str) -> str:
    start = text.index(first)
    end = text.index(last, start) + len(last)
    return text[start:end]


def _gpl_notice(lesser: bool) -> str:
    notice = _between(
        _licence_text('GPL-3.0-only'),
        'This program is free software',
        '<https://www.gnu.org/licenses/>.',
    )
    if lesser:
        notice = notice.replace('General Public License', 'Lesser General Public License')
    return notice


def _normal(text: str) -> str:
    return ' '.join(text.split()).lower()


_headers: dict[str, str] = {}


def licence_headers() -> dict[str, str]:
    """Licence name → the normalised text a source file's header must hold: the notice the
    licence asks a file to carry (Apache's boilerplate, the GNU notice), else its text."""
    if not _headers:
        for name, (_title, spdx) in LICENSES.items():
            if name == 'apache2':
                text = _between(
                    _licence_text(spdx),
                    'Licensed under the Apache License',
                    'limitations under the License.',
                )
            elif name in ('gplv3', 'lgplv3'):
                text = _gpl_notice(lesser=name == 'lgplv3')
            else:
                text = _licence_text(spdx)
            _headers[name] = _normal(text)
    return _headers


@dataclass(frozen=True)
class FileReport:
    """One checked file: its path, whether it passes, and the message ament prints."""

    path: str
    ok: bool
    message: str


def _strip_comment(line: str, python_like: bool) -> str | None:
    """The line without its comment marker, or None when the line is not a comment."""
    text = line.strip()
    if python_like:
        return text[1:] if text.startswith('#') else None
    for marker in ('//', '/*', '*/', '*'):
        if text.startswith(marker):
            return text[len(marker) :].removesuffix('*/')
    return None


def _first_comment_block(content: str, python_like: bool) -> list[str]:
    lines = content.splitlines()
    index = 0
    if index < len(lines) and lines[index].startswith('#!'):
        index += 1
    if index < len(lines) and _CODING.match(lines[index]):
        index += 1
    while index < len(lines) and not lines[index].strip():
        index += 1
    block: list[str] = []
    for line in lines[index:]:
        stripped = _strip_comment(line, python_like)
        if stripped is None:
            break
        block.append(stripped)
    return block


def _identify_licence(text: str) -> str:
    normal = _normal(text)
    for name, header in licence_headers().items():
        if header in normal:
            return name
    return UNKNOWN_IDENTIFIER


def check_file(path: str) -> FileReport:
    """Check one source file's copyright notice and licence header."""
    try:
        with open(path, encoding='utf-8') as f:
            content = f.read()
    except FileNotFoundError:
        return FileReport(path, False, 'file not found')
    except (OSError, UnicodeDecodeError) as e:
        return FileReport(path, False, f'cannot be read: {e}')
    if not content.strip():
        return FileReport(path, True, 'file empty')
    python_like = path.endswith(('.py', '.cmake')) or os.path.basename(path) == 'CMakeLists.txt'
    block = _first_comment_block(content, python_like)
    holders = []
    rest = []
    for line in block:
        m = _COPYRIGHT.match(line)
        if m:
            years = re.sub(r'\s', '', m['years'])
            holders.append(f"{m['name']} ({years})")
        elif holders:
            rest.append(line)
    if not holders:
        return FileReport(path, False, 'could not find copyright notice')
    licence = _identify_licence('\n'.join(rest))
    return FileReport(
        path,
        licence != UNKNOWN_IDENTIFIER,
        f"copyright={', '.join(holders)}, license={licence}",
    )


def _check_repository_file(path: str) -> FileReport:
    if not os.path.exists(path):
        return FileReport(path, False, 'file not found')
    with open(path, encoding='utf-8', errors='replace') as f:
        content = f.read()
    if not content.strip():
        return FileReport(path, False, 'file empty')
    if os.path.basename(path) == _CONTRIBUTING_FILE:
        return FileReport(path, True, 'present')
    licence = _identify_licence(content)
    return FileReport(path, licence != UNKNOWN_IDENTIFIER, licence)


def _is_repository_root(path: str) -> bool:
    return any(os.path.exists(os.path.join(path, vcs)) for vcs in ('.git', '.hg'))


def get_files(paths: Sequence[str], excludes: Sequence[str] = ()) -> dict[str, str]:
    """Path → 'source' or 'repository' for every file the check covers, as ament crawls."""
    excluded = {os.path.realpath(p) for p in excludes}
    files: dict[str, str] = {}

    def add_repository(root: str) -> None:
        for name in (_LICENSE_FILE, _CONTRIBUTING_FILE):
            files[os.path.normpath(os.path.join(root, name))] = 'repository'

    def wanted(name: str) -> bool:
        return os.path.splitext(name)[1][1:] in EXTENSIONS

    for path in paths:
        if os.path.isdir(path):
            for dirpath, dirnames, filenames in os.walk(path):
                if 'AMENT_IGNORE' in dirnames + filenames:
                    dirnames[:] = []
                    continue
                if _is_repository_root(dirpath):
                    add_repository(dirpath)
                dirnames[:] = sorted(d for d in dirnames if d[0] not in '._')
                beside_manifest = os.path.exists(os.path.join(dirpath, 'package.xml'))
                for name in sorted(filenames):
                    if name == 'setup.py' and beside_manifest:
                        continue
                    full = os.path.join(dirpath, name)
                    if wanted(name) and os.path.realpath(full) not in excluded:
                        files[os.path.normpath(full)] = 'source'
        elif wanted(path) and os.path.realpath(path) not in excluded:
            files[os.path.normpath(path)] = 'source'
    return files


def _xunit(reports: list[FileReport], testname: str, elapsed: float) -> str:
    failures = sum(not r.ok for r in reports)
    cases = []
    for r in reports:
        case = f'  <testcase name={quoteattr(r.path)} classname="{testname}"'
        if r.ok:
            cases.append(case + '/>')
        else:
            cases.append(case + f'>\n    <failure message={quoteattr(r.message)}/>\n  </testcase>')
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<testsuite name="{testname}" tests="{len(reports)}" failures="{failures}" '
        f'time="{elapsed:.3f}">\n' + '\n'.join(cases) + '\n'
        f'  <system-out>{escape(", ".join(r.path for r in reports))}</system-out>\n'
        '</testsuite>\n'
    )


def main(argv: Sequence[str] | None = None) -> int:
    """Check the files under `argv`'s paths (default: the current directory); 0 when
    every one passes, 1 otherwise."""
    parser = argparse.ArgumentParser(
        prog='ament_copyright',
        description='Check code files for copyright and license information.',
    )
    parser.add_argument('paths', nargs='*', default=[os.curdir])
    parser.add_argument('--exclude', nargs='*', default=[], dest='excludes', metavar='filename')
    parser.add_argument('--list-licenses', action='store_true')
    parser.add_argument('--list-copyright-names', action='store_true')
    parser.add_argument('--verbose', action='store_true')
    parser.add_argument('--xunit-file')
    args = parser.parse_args(sys.argv[1:] if argv is None else list(argv))

    if args.list_licenses:
        for name in sorted(LICENSES):
            print(f'{name}: {LICENSES[name][0]}')
        return 0
    if args.list_copyright_names:
        return 0  # holders are not registered here: any name is accepted
    started = time.monotonic()
    files = get_files(args.paths, args.excludes)
    if not files:
        print('No repository roots and files found')
    reports = []
    for path in sorted(files):
        report = check_file(path) if files[path] == 'source' else _check_repository_file(path)
        if args.verbose or not report.ok:
            print(f'{report.path}: {report.message}', file=sys.stdout if report.ok else sys.stderr)
        reports.append(report)
    errors = sum(not r.ok for r in reports)
    if errors:
        print(f'{errors} errors, checked {len(reports)} files', file=sys.stderr)
    else:
        print(f'No problems found, checked {len(reports)} files')
    if args.xunit_file:
        folder = os.path.basename(os.path.dirname(os.path.abspath(args.xunit_file)))
        stem = os.path.basename(args.xunit_file).removesuffix('.xml').removesuffix('.xunit')
        os.makedirs(os.path.dirname(os.path.abspath(args.xunit_file)), exist_ok=True)
        with open(args.xunit_file, 'w', encoding='utf-8') as f:
            f.write(_xunit(reports, f'{folder}.{stem}', time.monotonic() - started))
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
