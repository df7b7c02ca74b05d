"""`AsyncParameterClient` (rclpy's): futures of another node's parameter services, completed
by spinning, with done-callbacks; loading a file into the remote node."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.parameter import Parameter, parameter_value_to_python
from ros2lite.parameter_client import AsyncParameterClient


def test_async_calls(ros_context: Any, ros_router: str, tmp_path: Path) -> None:
    from ros2lite.context import Context

    remote_ctx = Context().init([])  # the served node lives in another session
    try:
        served = Node(
            "served", namespace="/async", context=remote_ctx, allow_undeclared_parameters=True
        )
        served.declare_parameter("gain", 1.0)
        served_ex = SingleThreadedExecutor(context=remote_ctx)
        served_ex.add_node(served)
        import threading

        spinner = threading.Thread(target=served_ex.spin, daemon=True)
        spinner.start()

        node = Node("asker", context=ros_context, start_parameter_services=False)
        client = AsyncParameterClient(node, "/async/served")
        assert client.wait_for_services(10.0) and client.services_are_ready()
        ex = SingleThreadedExecutor(context=ros_context)
        ex.add_node(node)

        def done(future: Any) -> Any:
            ex.spin_until_future_complete(future, timeout_sec=10.0)
            assert future.done()
            return future.result()

        seen: list[Any] = []
        response = done(
            client.set_parameters(
                [Parameter("gain", value=2.0), Parameter("gain", value="no")], callback=seen.append
            )
        )
        assert [r.successful for r in response.results] == [True, False]
        assert len(seen) == 1 and seen[0].result() is response
        values = done(client.get_parameters(["gain"])).values
        assert parameter_value_to_python(values[0]) == 2.0
        assert list(done(client.get_parameter_types(["gain"])).types) == [3]
        assert done(client.describe_parameters(["gain"])).descriptors[0].name == "gain"
        assert "gain" in done(client.list_parameters()).result.names
        path = tmp_path / "p.yaml"
        path.write_text(
            "/**:\n  ros__parameters:\n    extra: x\n"
            "/async/served:\n  ros__parameters:\n    gain: 4.0\n"
        )
        assert done(client.load_parameter_file(str(path))).results[0].successful
        assert not served.has_parameter("extra")
        assert done(client.load_parameter_file_atomically(str(path), True)).result.successful
        assert served.get_parameter("extra").value == "x"
        assert served.get_parameter("gain").value == 4.0
        assert done(client.delete_parameters(["extra"])).results[0].successful
        assert not served.has_parameter("extra")
        client.destroy()
    finally:
        remote_ctx.shutdown()
