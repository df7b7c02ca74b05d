"""Nodes: names and namespaces, validation errors, `--ros-args` remapping (`__node`, `__ns`,
topics, node-specific rules), parameters from overrides, and the node's token lifetime."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from ros2lite.exceptions import ParameterAlreadyDeclaredException, ParameterNotDeclaredException
from ros2lite.graph import snapshot
from ros2lite.node import Node
from ros2lite.parameter import Parameter


def ros_args(*args: str) -> list[str]:
    return ['--ros-args', *args]


def test_names(ros_context: Any) -> None:
    node = Node('talker', namespace='robot1/', context=ros_context)
    assert node.get_name() == 'talker'
    assert node.get_namespace() == '/robot1'
    assert node.get_fully_qualified_name() == '/robot1/talker'
    assert node.get_logger_name() == 'robot1.talker'
    root = Node('root', context=ros_context)
    assert (root.get_namespace(), root.get_fully_qualified_name()) == ('/', '/root')
    assert root.get_logger().name == 'root'


@pytest.mark.parametrize('name', ['', '1talker', 'talk-er', 'a/b', 'tälker', 'with space'])
def test_invalid_node_names_are_rejected(ros_context: Any, name: str) -> None:
    with pytest.raises(ValueError, match='node name'):
        Node(name, context=ros_context)


@pytest.mark.parametrize('namespace', ['/a//b', '/1a', '/a-b', '/a b'])
def test_invalid_namespaces_are_rejected(ros_context: Any, namespace: str) -> None:
    with pytest.raises(ValueError, match='namespace'):
        Node('ok', namespace=namespace, context=ros_context)


def test_node_and_namespace_remapping(ros_context: Any) -> None:
    node = Node(
        'talker', context=ros_context, cli_args=ros_args('-r', '__node:=speaker', '-r', '__ns:=/ns')
    )
    assert node.get_fully_qualified_name() == '/ns/speaker'
    assert node.create_publisher('std_msgs/msg/String', 'chatter', 10).topic_name == '/ns/chatter'
    # `__name` is the older spelling of `__node`
    assert Node('x', context=ros_context, cli_args=ros_args('-r', '__name:=y')).get_name() == 'y'


def test_remapped_name_is_validated(ros_context: Any) -> None:
    with pytest.raises(ValueError, match='node name'):
        Node('talker', context=ros_context, cli_args=ros_args('-r', '__node:=9lives'))


def test_topic_remapping(ros_context: Any) -> None:
    node = Node(
        'talker',
        namespace='/ns',
        context=ros_context,
        cli_args=ros_args('-r', 'chatter:=/other', '-r', '/abs:=rel', '-r', '~/priv:=moved'),
    )
    assert node.resolve_topic_name('chatter') == '/other'
    assert node.resolve_topic_name('/ns/chatter') == '/other'  # matches after expansion
    assert node.resolve_topic_name('/abs') == '/ns/rel'
    assert node.resolve_topic_name('~/priv') == '/ns/moved'
    assert node.resolve_topic_name('untouched') == '/ns/untouched'
    assert node.resolve_topic_name('{node}/x') == '/ns/talker/x'
    sub = node.create_subscription('std_msgs/msg/String', 'chatter', lambda m: None, 10)
    assert sub.topic_name == '/other'


def test_node_specific_rules_only_hit_that_node(ros_context: Any) -> None:
    args = ros_args(
        '-r',
        'talker:chatter:=/for_talker',
        '-r',
        'other:__node:=renamed',
        '-p',
        'talker:rate:=5',
        '-r',
        'renamed:chatter:=/for_renamed',
    )
    talker = Node('talker', context=ros_context, cli_args=args)
    other = Node('other', context=ros_context, cli_args=args)
    assert talker.get_name() == 'talker' and other.get_name() == 'renamed'
    assert talker.resolve_topic_name('chatter') == '/for_talker'
    # as in rcl, topic rules are matched against the node's name after `__node` remapping
    assert other.resolve_topic_name('chatter') == '/for_renamed'
    assert talker.declare_parameter('rate', 1).value == 5
    assert other.declare_parameter('rate', 1).value == 1


def test_global_arguments_and_opting_out(ros_router: str) -> None:
    from ros2lite.context import Context

    ctx = Context().init(ros_args('-r', '__ns:=/global'))
    try:
        assert Node('a', context=ctx).get_namespace() == '/global'
        assert Node('b', context=ctx, use_global_arguments=False).get_namespace() == '/'
        # node-local arguments win over global ones
        assert (
            Node('c', context=ctx, cli_args=ros_args('-r', '__ns:=/local')).get_namespace()
            == '/local'
        )
    finally:
        ctx.shutdown()


def test_invalid_remap_target_topic(ros_context: Any) -> None:
    node = Node('talker', context=ros_context, cli_args=ros_args('-r', 'chatter:=bad name'))
    with pytest.raises(ValueError, match='topic name'):
        node.create_publisher('std_msgs/msg/String', 'chatter', 10)


def test_parameters(ros_context: Any, tmp_path: Path) -> None:
    params = tmp_path / 'params.yaml'
    params.write_text(
        '/**:\n  ros__parameters:\n    from_file: 1\n    nested:\n      k: v\n'
        'talker:\n  ros__parameters:\n    from_file: 2\n'
    )
    node = Node(
        'talker',
        context=ros_context,
        cli_args=ros_args(
            '-p', 'rate:=2.5', '-p', 'name:=hi', '-p', 'flag:=true', '--params-file', str(params)
        ),
        parameter_overrides=[Parameter('override', value=[1, 2])],
    )
    assert node.declare_parameter('rate', 1.0).value == 2.5
    assert node.declare_parameter('name', '').value == 'hi'
    assert node.declare_parameter('flag', False).value is True
    assert node.declare_parameter('from_file', 0).value == 2
    assert node.declare_parameter('nested.k', '').value == 'v'
    assert node.declare_parameter('override', [0]).value == [1, 2]
    assert node.declare_parameter('unset', 7).value == 7
    assert node.get_parameter('use_sim_time').value is False
    with pytest.raises(ParameterAlreadyDeclaredException, match='already declared'):
        node.declare_parameter('rate', 0.0)
    with pytest.raises(ParameterNotDeclaredException):
        node.get_parameter('never_declared')
    # as rclpy: parameters before the undeclared one are set, then it raises
    with pytest.raises(ParameterNotDeclaredException, match='never_declared'):
        node.set_parameters([Parameter('rate', value=9.0), Parameter('never_declared', value=1)])
    assert node.get_parameter('rate').value == 9.0
    assert node.has_parameter('rate') and not node.has_parameter('never_declared')
    declared = node.declare_parameters('ns', [('a', 1), ('b', 'two')])
    assert [(p.name, p.value) for p in declared] == [('ns.a', 1), ('ns.b', 'two')]


def test_automatic_declaration_from_overrides(ros_context: Any) -> None:
    node = Node(
        'auto',
        context=ros_context,
        cli_args=ros_args('-p', 'x:=3'),
        automatically_declare_parameters_from_overrides=True,
        allow_undeclared_parameters=True,
    )
    assert node.get_parameter('x').value == 3
    assert node.get_parameter('missing').type_ == Parameter.Type.NOT_SET


def test_node_token_lives_with_the_node(ros_context: Any) -> None:
    node = Node('short_lived', namespace='/tmp_ns', context=ros_context)

    def present() -> bool:
        return any(
            e.node_name == 'short_lived' and e.namespace == '/tmp_ns' and e.is_node
            for e in snapshot(ros_context.session, ros_context.domain_id)
        )

    deadline = time.monotonic() + 5
    while not present():
        assert time.monotonic() < deadline, 'node token never appeared'
        time.sleep(0.05)
    node.destroy_node()
    deadline = time.monotonic() + 5
    while present():
        assert time.monotonic() < deadline, 'node token outlived destroy_node()'
        time.sleep(0.05)


def test_logging_after_destroy_node(ros_context: Any, capsys: Any) -> None:
    node = Node('logs_late', context=ros_context)
    node.destroy_node()
    node.get_logger().info('still heard')  # on the console; /rosout is gone with the node
    assert 'still heard' in capsys.readouterr().err


def test_own_endpoints_count_at_once_and_destroy_answers(ros_context: Any) -> None:
    node = Node('counting', namespace='/c', context=ros_context)
    pub = node.create_publisher('std_msgs/msg/String', 'chatter', 1)
    assert node.count_publishers('chatter') == 1  # no wait for the graph to hear of it
    node.create_subscription('std_msgs/msg/String', 'chatter', lambda m: None, 1)
    node.create_subscription('std_msgs/msg/String', 'chatter', lambda m: None, 1)
    assert node.count_subscribers('/c/chatter') == 2 and pub.get_subscription_count() == 2
    node.create_service('std_srvs/srv/Trigger', 'srv', lambda req, res: res)
    assert node.count_services('srv') == 1
    assert node.destroy_publisher(pub) and not node.destroy_publisher(pub)
    assert node.count_publishers('chatter') == 0
    with pytest.raises(ValueError, match="'42' is invalid"):
        node.count_clients('42')
    assert ('counting', '/c', '/') in node.get_node_names_and_namespaces_with_enclaves()


def test_wait_for_node_and_the_executor_property(ros_context: Any) -> None:
    from ros2lite.executors import SingleThreadedExecutor

    node = Node('waits', context=ros_context)
    assert node.wait_for_node('/waits', 5)
    assert not node.wait_for_node('/nobody_here', 0.1)
    first, second = (
        SingleThreadedExecutor(context=ros_context),
        SingleThreadedExecutor(context=ros_context),
    )
    node.executor = first
    assert node in first.get_nodes() and node.executor is first
    node.executor = second
    assert node not in first.get_nodes() and node.executor is second
    node.executor = None
    assert node.executor is None and node not in second.get_nodes()
    # an executor of another make (here a mock) that does not attach the node itself is still
    # the node's executor once handed to it, as in rclpy; moving on removes the node from it
    from unittest.mock import Mock

    foreign = Mock()
    node.executor = foreign
    assert node.executor is foreign
    foreign.add_node.assert_called_once_with(node)
    node.executor = first
    foreign.remove_node.assert_called_once_with(node)
    assert node.executor is first
    node.executor = None


def test_adopt_makes_an_entity_built_outside_the_node_its_own(ros_context: Any) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.runtime.executable import GuardCondition
    from ros2lite.subscription import Subscription
    from tests.spinning import spin_until

    node = Node('adopter', context=ros_context)
    other = Node('other_adopter', context=ros_context)
    sub = Subscription(node, 'std_msgs/msg/String', 'adopted', lambda m: None, 1)
    assert sub not in node.subscriptions
    node.adopt(sub)
    node.adopt(sub)
    assert node.subscriptions.count(sub) == 1
    with pytest.raises(ValueError, match='another node'):
        other.adopt(sub)
    fired: list[bool] = []
    guard = GuardCondition(None, lambda: fired.append(True))
    guard_group = guard.callback_group
    node.adopt(guard)  # a nodeless one becomes the node's, and runs with it
    assert guard in node.guards and guard_group in node.callback_groups
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    guard.trigger()
    spin_until(executor, lambda: fired)
    assert node.count_subscribers('adopted') == 1
    node.destroy_node()  # the adopted subscription goes with the node
    assert other.count_subscribers('/adopted') == 0
    executor.shutdown()
