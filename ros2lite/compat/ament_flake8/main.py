"""`ament_flake8.main`: flake8 with ROS's settings, as `test/test_flake8.py` runs it
(``rc, errors = main_with_errors(argv=[])``; rc 0 when no file has a problem).

ROS's settings: lines up to 99 characters, the docstring checks pep257's test covers left out
(D100-D107, D203, D212, D404), and the plugin codes ROS ignores (B902, C816, I202) should those
plugins be installed. Output as ROS's checker prints it: each problem
`path:line:col: CODE text` with its source line, the statistics, `N files checked`, `No
problems found` or `N errors` with the count per type, and the files checked.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections import Counter
from collections.abc import Sequence
from typing import TYPE_CHECKING
from xml.sax.saxutils import escape, quoteattr

from flake8.api import legacy
from flake8.formatting.base import BaseFormatter

if TYPE_CHECKING:
    from flake8.violation import Violation

__all__ = ['EXTEND_IGNORE', 'MAX_LINE_LENGTH', 'main', 'main_with_errors']

MAX_LINE_LENGTH = 99
EXTEND_IGNORE = (
    *('B902', 'C816'),
    *('D100', 'D101', 'D102', 'D103', 'D104', 'D105', 'D106', 'D107'),
    *('D203', 'D212', 'D404', 'I202'),
)


class _Collecting(BaseFormatter):
    """flake8's default line format, each problem also kept for the caller."""

    errors: list[str] = []

    def after_init(self) -> None:
        """Start a fresh list for this run."""
        type(self).errors = []

    def format(self, error: Violation) -> str:
        """`path:line:col: CODE text`, as flake8's default formatter prints it."""
        line = f'{error.filename}:{error.line_number}:{error.column_number}: '
        line += f'{error.code} {error.text}'
        type(self).errors.append(line)
        return line


def _excluded(excludes: list[str]) -> list[str]:
    """Folders below the current one that ROS's checker leaves out: `.`/`_` ones and those
    holding AMENT_IGNORE."""
    out = list(excludes)
    for dirpath, dirnames, filenames in os.walk(os.getcwd()):
        if 'AMENT_IGNORE' in dirnames + filenames:
            dirnames[:] = []
            out.append(dirpath)
        else:
            out.extend(d for d in dirnames if d[0] in '._')
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Run the check; the status only."""
    rc, _ = main_with_errors(argv=argv)
    return rc


def main_with_errors(argv: Sequence[str] | None = None) -> tuple[int, list[str]]:
    """Run the check on `argv`'s paths (default: the current directory); the status and
    each problem as `path:line:col: CODE text`."""
    parser = argparse.ArgumentParser(prog='ament_flake8', description='Check code using flake8.')
    parser.add_argument('paths', nargs='*', default=[os.curdir])
    parser.add_argument('--config', dest='config_file', metavar='path')
    parser.add_argument('--linelength', metavar='N', type=int)
    parser.add_argument('--exclude', nargs='*', default=[], dest='excludes', metavar='filename')
    parser.add_argument('--xunit-file')
    args = parser.parse_args(sys.argv[1:] if argv is None else list(argv))
    started = time.monotonic()
    excluded = _excluded(args.excludes)
    options: dict[str, object] = {
        'max_line_length': args.linelength or MAX_LINE_LENGTH,
        'extend_ignore': list(EXTEND_IGNORE),
        'exclude': excluded,
        'show_source': True,
    }
    if args.config_file:
        if not os.path.exists(args.config_file):
            print(f"Could not find config file '{args.config_file}'", file=sys.stderr)
            return 1, []
        options['config'] = args.config_file
    style = legacy.get_style_guide(**options)
    style.init_report(_Collecting)
    report = style.check_files(args.paths)
    errors = list(_Collecting.errors)
    files = sorted(_checked_files(args.paths, excluded))
    if errors:
        print('')
        for code, count in sorted(Counter(e.split(': ', 1)[1].split()[0] for e in errors).items()):
            print(f'{count:<5} {code}')
    print('')
    print(f'{len(files)} files checked')
    if not report.total_errors:
        print('No problems found')
        rc = 0
    else:
        print(f'{report.total_errors} errors')
        print('')
        kinds = Counter(e.split(': ', 1)[1][0] for e in errors)
        for kind, count in kinds.items():
            print(f"'{kind}'-type errors: {count}")
        rc = 1
    print('')
    print('Checked files:')
    print(''.join(f'\n* {f}' for f in files))
    if args.xunit_file:
        _write_xunit(args.xunit_file, files, errors, time.monotonic() - started)
    return rc, errors


def _checked_files(paths: Sequence[str], excludes: list[str]) -> list[str]:
    names = {os.path.basename(e) for e in excludes}
    absolute = {os.path.abspath(e) for e in excludes}
    found: list[str] = []
    for path in paths:
        if os.path.isfile(path):
            found.append(path)
            continue
        for dirpath, dirnames, filenames in os.walk(path):
            dirnames[:] = [
                d
                for d in dirnames
                if d not in names and os.path.abspath(os.path.join(dirpath, d)) not in absolute
            ]
            found += [os.path.join(dirpath, f) for f in filenames if f.endswith('.py')]
    return found


def _write_xunit(path: str, files: list[str], errors: list[str], elapsed: float) -> None:
    folder = os.path.basename(os.path.dirname(os.path.abspath(path)))
    stem = os.path.basename(path).removesuffix('.xml').removesuffix('.xunit')
    name = f'{folder}.{stem}'
    cases = [
        f'  <testcase name={quoteattr(e.split(": ", 1)[0])} classname="{name}">\n'
        f'    <failure message={quoteattr(e)}/>\n  </testcase>'
        for e in errors
    ]
    if not errors:
        cases.append(f'  <testcase name="flake8" classname="{name}"/>')
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(
            '<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<testsuite name="{name}" tests="{len(cases)}" failures="{len(errors)}" '
            f'time="{elapsed:.3f}">\n' + '\n'.join(cases) + '\n'
            f'  <system-out>{escape(", ".join(files))}</system-out>\n</testsuite>\n'
        )


if __name__ == '__main__':
    sys.exit(main())
