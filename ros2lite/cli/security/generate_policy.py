"""`security generate_policy POLICY_FILE_PATH`: what the live nodes do, as an sros2 policy
(added to the file's own enclaves when it exists)."""

from __future__ import annotations

from pathlib import Path

import click

from ..common import connect
from ..errors import CliError
from ..options import strategy_options
from ..parsing import command


@command('generate_policy')
@click.argument('policy_file_path', metavar='POLICY_FILE_PATH', type=click.Path(path_type=Path))
@strategy_options()
def cli(policy_file_path: Path, use_sim_time: bool, no_daemon: bool) -> None:
    """Generate XML policy file from ROS graph data."""
    from ros2lite.security import SecurityError
    from ros2lite.security.files import write_file
    from ros2lite.security.policy import (
        add_node_access,
        dump_policy,
        graph_access,
        load_policy,
        new_policy,
    )

    try:
        policy = load_policy(policy_file_path) if policy_file_path.is_file() else new_policy()
    except SecurityError as e:
        raise CliError(str(e)) from None
    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        nodes = graph_access(conn.entities())
    if not nodes:
        raise CliError('No nodes detected in the ROS graph. No policy file was generated.')
    add_node_access(policy, nodes)
    try:
        write_file(policy_file_path, dump_policy(policy).encode())
    except SecurityError as e:
        raise CliError(str(e)) from None
