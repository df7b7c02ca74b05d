"""`async_param_client`: drives another node's parameters through AsyncParameterClient, each
step logged — set, list, get, load `params.yaml` (this package's share), delete — on
`parameter_blackboard` (start it first: `ros2lite run demo_nodes_cpp parameter_blackboard`)."""

from __future__ import annotations

import os
from typing import TypeVar

import ros2lite
from ros2lite.bundled.runner import run_main
from ros2lite.exceptions import Ros2liteError
from ros2lite.parameter import Parameter, parameter_value_to_python
from ros2lite.parameter_client import AsyncParameterClient
from ros2lite.parameters.files import parameter_dict_from_yaml_file
from ros2lite.pkg.ament_index import get_package_share_directory

TARGET = 'parameter_blackboard'
NAMES = ['int_parameter', 'bool_parameter', 'string_parameter']
TO_DELETE = ['other_int_parameter', 'other_string_parameter', 'string_parameter']

_R = TypeVar('_R')  # what a call's future holds


class BlackboardMissing(Ros2liteError):
    """The node whose parameters the demo works on is not running."""


def walk_through() -> None:
    """Each step in turn, waiting for its answer; an unanswered step is logged as an error."""
    node = ros2lite.create_node('async_param_client')
    client = AsyncParameterClient(node, TARGET)
    log = node.get_logger()
    if not client.wait_for_services(3.0):
        raise BlackboardMissing(
            'parameter_blackboard is not available, start parameter blackboard with '
            '`ros2 run demo_nodes_cpp parameter_blackboard` before running this demo'
        )

    def answer(future: ros2lite.Future[_R], what: str) -> _R | None:
        ros2lite.spin_until_future_complete(node, future)
        if future.exception() is not None or future.result() is None:
            log.error(f'Error {what} parameters: {future.exception()}')
            return None
        return future.result()

    log.info('Setting parameters:')
    values = [
        Parameter('int_parameter', Parameter.Type.INTEGER, 10),
        Parameter('bool_parameter', Parameter.Type.BOOL, False),
        Parameter('string_parameter', Parameter.Type.STRING, 'Fee Fi Fo Fum'),
    ]
    set_result = answer(client.set_parameters(values), 'setting')
    for name, outcome in zip(NAMES, set_result.results if set_result else [], strict=False):
        log.info(f'    {name}:')
        log.info(f'        successful: {outcome.successful}')

    log.info('Listing Parameters:')
    listed = answer(client.list_parameters(NAMES, 10), 'listing')
    for name in listed.result.names if listed else []:
        log.info(f'    - {name}')

    log.info('Getting parameters:')
    got = answer(client.get_parameters(NAMES), 'getting')
    for name, value in zip(NAMES, got.values if got else [], strict=False):
        log.info(f'    - {name}: {parameter_value_to_python(value)}')

    log.info('Loading parameters: ')
    path = os.path.join(get_package_share_directory('demo_nodes_py'), 'params.yaml')
    loaded = answer(client.load_parameter_file(path), 'loading')
    if loaded is not None:
        from_file = parameter_dict_from_yaml_file(path)
        for (name, param), outcome in zip(from_file.items(), loaded.results, strict=False):
            log.info(f'    {name}:')
            log.info(f'        successful: {outcome.successful}')
            log.info(f'        value: {parameter_value_to_python(param.value)}')

    log.info('Deleting parameters: ')
    result = answer(client.delete_parameters(TO_DELETE), 'deleting')
    for name, outcome in zip(TO_DELETE, result.results if result else [], strict=False):
        log.info(f'    {name}:')
        log.info(f'        successful: {outcome.successful}')
        log.info(f'        reason: {outcome.reason}')


def main(args: list[str] | None = None) -> int:
    """`async_param_client`'s entry point."""
    return run_main(walk_through, args)


if __name__ == '__main__':
    raise SystemExit(main())
