"""`ros2lite doctor` (and `wtf`): ros2doctor's checks summary, warnings and reports, and
its verb `hello`.

Warnings and errors go to stderr as ros2doctor's Python warnings print them
(`<file>: <line>: UserWarning: <message>`, errors prefixed `ERROR: `); the summary
(`All 6 checks passed` / `1/6 check(s) failed` + `Failed modules: …`) and the reports
(`--report`) go to stdout.
"""

from __future__ import annotations

import click

from .. import render
from ..lazy import LazyGroup
from ..options import json_option

VERBS = {'hello': 'Check network connectivity between multiple hosts'}


@click.group(
    'doctor',
    cls=LazyGroup,
    lazy={verb: (f'{__name__}.{verb}', summary) for verb, summary in VERBS.items()},
    invoke_without_command=True,
)
@click.option('-r', '--report', is_flag=True, help='Print all reports.')
@click.option(
    '-rf',
    '--report-failed',
    '--report-fail',
    'report_failed',
    is_flag=True,
    help='Print reports of failed checks only.',
)
@click.option(
    '-ep',
    '--exclude-packages',
    is_flag=True,
    help='Exclude package checks or report.',
)
@click.option(
    '-iw',
    '--include-warnings',
    is_flag=True,
    help='Include warnings as failed checks. Warnings are ignored by default.',
)
@json_option(
    '{"checks": [{"category", "failed", "findings"}…], "failed": [category…], "reports": '
    '[{"name", "category", "items": [{"key", "value"}…]}…] (with -r/-rf)}'
)
@click.pass_context
def cli(
    ctx: click.Context,
    report: bool,
    report_failed: bool,
    exclude_packages: bool,
    include_warnings: bool,
    as_json: bool,
) -> None:
    """Check ROS setup and other potential issues."""
    if ctx.invoked_subcommand is not None:
        return  # the verb does the work
    from ros2lite.tools.doctor import Diagnosis, Report

    diagnosis = Diagnosis()
    exclude = ('package',) if exclude_packages else ()
    if as_json:
        _print_json(diagnosis, exclude, report, report_failed, include_warnings)
        return
    if report:
        for section in diagnosis.reports():
            if section.category not in exclude:
                _print_report(section)
        return
    results = diagnosis.run_checks(exclude=exclude)
    for result in results:
        for finding in result.findings:
            prefix = 'ERROR: ' if finding.severity == 'error' else ''
            # findings name nodes and topics from the graph: escaped on a terminal
            render.echo(
                f'{finding.filename}: {finding.lineno}: UserWarning: {prefix}{finding.message}',
                err=True,
            )
    failed = [r.category for r in results if r.failed(include_warnings)]
    if failed:
        click.echo(f'\n{len(failed)}/{len(results)} check(s) failed\n')
        click.echo('Failed modules: ' + ' '.join(failed))
    else:
        click.echo(f'\nAll {len(results)} checks passed\n')
    if report_failed and failed:
        sections: list[Report] = diagnosis.reports(set(failed))
        for section in sections:
            _print_report(section)


def _print_json(
    diagnosis: object, exclude: tuple[str, ...], report: bool, failed_only: bool, warnings: bool
) -> None:
    """`doctor --json`: the checks (unless -r), the failed categories, and the reports asked
    for, as one document."""
    from ros2lite.tools.doctor import Diagnosis

    assert isinstance(diagnosis, Diagnosis)
    doc: dict[str, object] = {}
    failed: list[str] = []
    if not report:
        results = diagnosis.run_checks(exclude=exclude)
        failed = [r.category for r in results if r.failed(warnings)]
        doc['checks'] = [
            {
                'category': r.category,
                'failed': r.failed(warnings),
                'findings': [{'severity': f.severity, 'message': f.message} for f in r.findings],
            }
            for r in results
        ]
        doc['failed'] = failed
    if report or (failed_only and failed):
        sections = diagnosis.reports() if report else diagnosis.reports(set(failed))
        doc['reports'] = [
            {
                'name': s.name,
                'category': s.category,
                'items': [{'key': k, 'value': v} for k, v in s.items],
            }
            for s in sections
            if s.category not in exclude
        ]
    render.print_json(doc)


def _print_report(report: object) -> None:
    from ros2lite.tools.doctor import Report

    assert isinstance(report, Report)
    click.echo(f'\n   {report.name}')
    pad = max([8, *(len(key) + 4 for key, _ in report.items)])
    for key, value in report.items:
        render.echo(f'{key:{pad}}: {value}')
