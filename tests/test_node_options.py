"""NodeOptions lists exactly Node's keyword options, so code that passes them on stays checked."""

from __future__ import annotations

import inspect

from ros2lite.node import Node
from ros2lite.node_options import NodeOptions


def test_node_options_are_the_keyword_parameters_of_node() -> None:
    parameters = inspect.signature(Node.__init__).parameters.values()
    keyword_only = {p.name for p in parameters if p.kind is inspect.Parameter.KEYWORD_ONLY}
    assert NodeOptions.__optional_keys__ | NodeOptions.__required_keys__ == keyword_only
