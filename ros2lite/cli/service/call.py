"""`service call`: send one request (or one every 1/RATE s) and print the response."""

from __future__ import annotations

import sys
import time
from typing import TYPE_CHECKING

import click

from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.client import Client
    from ros2lite.interfaces import Message, ServiceType
    from ros2lite.node import Node

from .. import completion, numbers, render
from ..common import (
    connect,
    interface_type_name,
    known_type_if_graph,
    message_fields,
    wait_saying_other_types,
    yaml_fields,
)
from ..errors import CliError
from ..options import NDJSON, check_stdin, json_option, values_argument


@command('call')
@click.argument('service_name', shell_complete=completion.services)
@click.argument('service_type', shell_complete=completion.service_types)
@values_argument()
@click.option(
    '-r',
    '--rate',
    # <= 0 is ros2cli's own error (exit 1) below; nan, inf and absurd rates are usage errors
    type=numbers.Finite(max=numbers.MAX_RATE),
    metavar='N',
    help='Repeat the call at a specific rate in Hz',
)
@click.option(
    '--timeout',
    type=numbers.seconds(min_open=True),
    metavar='SECONDS',
    help='Give up if the service is not available, or does not answer, within '
    'this many seconds (default: wait forever, as ros2cli does)',
)
@json_option(f'{{"request", "response"}} per call ({NDJSON})')
def cli(
    service_name: str,
    service_type: str,
    values: str | None,
    use_stdin: bool,
    rate: float | None,
    timeout: float | None,
    as_json: bool,
) -> None:
    """Call a service.

    VALUES fills the request in YAML (e.g. '{a: 1, b: 2}') or JSON (as --json prints it).
    """
    from ros2lite.interfaces import get_interface, set_message_fields

    check_stdin(values, use_stdin)
    if rate is not None and rate <= 0:
        raise CliError('rate must be greater than zero')
    type_name = _service_type(service_type, service_name)
    srv_class: type[ServiceType] = get_interface(type_name)
    fields = yaml_fields(sys.stdin.read() if use_stdin else values or '{}', allow_empty=True)
    request = srv_class.Request()
    try:
        set_message_fields(request, message_fields(type(request), fields))
    except Exception as e:  # any reason the values do not fit, as ros2cli reports it
        raise CliError(f'Failed to populate field: {e}') from None
    package, _, name = type_name.split('/')
    with connect() as conn:
        node = conn.node(f'_ros2lite_requester_{package}_{name}')
        client = node.create_client(srv_class, service_name, fail_without_server=True)
        _wait(client, timeout, node, type_name, as_json)
        period = None if rate is None else 1.0 / rate
        while True:
            last_call = time.monotonic()
            if as_json:
                from ros2lite.interfaces.json_form import message_to_json

                response = _call(client, request, timeout)
                render.print_json_line(
                    {'request': message_to_json(request), 'response': message_to_json(response)}
                )
            else:
                click.echo(f'requester: making request: {request!r}\n')
                click.echo(f'response:\n{_call(client, request, timeout)!r}\n')
            if period is None or not conn.context.ok():
                return
            time.sleep(max(0.0, last_call + period - time.monotonic()))


def _service_type(service_type: str, service_name: str) -> str:
    """The full name of the service type, fetched from the graph's nodes if it has no local
    definition."""

    def full_name() -> str:
        return interface_type_name(
            service_type,
            'srv',
            invalid='The passed service type is invalid',
            not_kind='The passed type is not a service',
        )

    try:
        return full_name()
    except CliError:
        parts = service_type.split('/')
        guess = '/'.join([parts[0], 'srv', parts[1]] if len(parts) == 2 else parts)
        known_type_if_graph(guess, service_name if service_name.startswith('/') else None)
        return full_name()


def _wait(
    client: Client[Message, Message],
    timeout: float | None,
    node: Node,
    type_name: str,
    as_json: bool = False,
) -> None:
    if client.service_is_ready():
        return
    click.echo('waiting for service to become available...', err=as_json)
    if not wait_saying_other_types(
        lambda step: client.wait_for_service(timeout_sec=step),
        timeout,
        'service',
        client.srv_name,
        type_name,
        node.get_service_names_and_types,
    ):
        raise CliError(f"Timed out after {timeout:g} s waiting for service '{client.srv_name}'")


def _call(client: Client[Message, Message], request: Message, timeout: float | None) -> Message:
    from ros2lite.client import ServiceCallError

    try:
        response = client.call(request, timeout_sec=timeout)
    except ServiceCallError as e:
        raise CliError(f'Exception while calling service: {e!r}') from None
    if response is None:
        raise CliError(
            f"Timed out after {timeout:g} s waiting for a response from '{client.srv_name}'"
        )
    return response
