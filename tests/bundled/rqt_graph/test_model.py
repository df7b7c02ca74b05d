"""What rqt_graph shows of a known graph: hidden, debug and leaf topics filtered by default."""

from __future__ import annotations

from ros2lite.bundled.rqt_graph.model import Endpoint, Graph, Options, build

NODES = ['/turtlesim', '/teleop_turtle', '/_ros2lite_cli', '/sim/_hidden']
ENDPOINTS = [
    Endpoint('/teleop_turtle', 'pub', '/turtle1/cmd_vel'),
    Endpoint('/turtlesim', 'sub', '/turtle1/cmd_vel'),
    Endpoint('/turtlesim', 'pub', '/turtle1/pose'),  # a leaf: nobody listens
    Endpoint('/turtlesim', 'pub', '/rosout'),
    Endpoint('/turtlesim', 'pub', '/parameter_events'),
    Endpoint('/turtlesim', 'sub', '/parameter_events'),
    Endpoint('/turtlesim', 'pub', '/turtle1/rotate_absolute/_action/feedback'),
    Endpoint('/_ros2lite_cli', 'sub', '/turtle1/pose'),  # a hidden node's subscription
]


def lesson() -> Graph:
    return Graph(
        ('/teleop_turtle', '/turtlesim'),
        ('/turtle1/cmd_vel',),
        (('/teleop_turtle', '/turtle1/cmd_vel'), ('/turtle1/cmd_vel', '/turtlesim')),
    )


def test_default_view_is_the_lessons_picture() -> None:
    assert build(NODES, ENDPOINTS, Options()) == lesson()


def test_options_show_more() -> None:
    leaf = build(NODES, ENDPOINTS, Options(show_leaf_topics=True))
    assert leaf.topics == ('/turtle1/cmd_vel', '/turtle1/pose')
    assert ('/turtlesim', '/turtle1/pose') in leaf.edges
    debug = build(NODES, ENDPOINTS, Options(show_debug=True))
    assert debug.topics == ('/parameter_events', '/turtle1/cmd_vel')  # /rosout is a leaf
    hidden = build(NODES, ENDPOINTS, Options(include_hidden=True))
    assert hidden.nodes == ('/_ros2lite_cli', '/sim/_hidden', '/teleop_turtle', '/turtlesim')
    assert ('/turtle1/pose', '/_ros2lite_cli') in hidden.edges
