"""`daemon status`: ros2cli's one line, then which router serves the endpoint and who is
connected to it."""

from __future__ import annotations

import click

from ..options import json_option
from ..parsing import command


@command('status')
@json_option(
    '{"running", "ours", "endpoint", "pid", "secured", "answers_zenoh", "message", '
    '"sessions": [{"whatami", "zid", "nodes"}…] or null}'
)
def cli(as_json: bool) -> None:
    """Output the status of the daemon."""
    from ros2lite import daemon

    from .common import table

    st = daemon.status(sessions=True)
    if as_json:
        from .. import render

        render.print_json(
            {
                'running': st.running,
                'ours': st.ours,
                'endpoint': st.endpoint,
                'pid': st.pid,
                'secured': st.secured,
                'answers_zenoh': st.answers_zenoh,
                'message': st.message,
                'sessions': None
                if st.sessions is None
                else [
                    {'whatami': s.whatami, 'zid': s.zid, 'nodes': list(s.nodes)}
                    for s in st.sessions
                ],
            }
        )
        return
    if st.running and not st.answers_zenoh and not st.secured:
        # a frozen router, or another program on the port: neither running nor free
        click.echo('The daemon is not answering')
        click.echo(st.message)
        return
    click.echo('The daemon is running' if st.running else 'The daemon is not running')
    secured = ', secured: TLS with client certificates' if st.secured else ''
    if st.running and st.ours:
        click.echo(f'Serving {st.endpoint} (ros2lite daemon, pid {st.pid}{secured})')
    elif st.running:
        click.echo(f'Serving {st.endpoint} (a Zenoh router not started by ros2lite{secured})')
    elif st.ours:
        click.echo(
            f'The ros2lite daemon (pid {st.pid}) exists but does not answer at {st.endpoint}'
        )
    else:
        click.echo(f'No Zenoh router answers at {st.endpoint}')
    if st.running and st.ours:
        from ros2lite.daemon.graph_cache import cache_stats

        stats = cache_stats(st.endpoint)
        if stats and stats.get('dropped'):
            click.echo(
                f"Graph cache full: {stats['dropped']} token(s) dropped past its "
                f"{stats.get('limit')}; tools ask the router for the domains concerned"
            )
    if st.running and not st.answers_zenoh:  # secured, and no way in from here
        click.echo(st.message)
        return
    if st.running:
        if st.sessions is None:
            click.echo("Connected sessions: unknown (the router's admin space does not answer)")
        else:
            for line in table(st.sessions):
                click.echo(line)
