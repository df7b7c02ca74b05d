"""`introspection`: the `add_two_ints` service (node `introspection_service`) and a client
asking it for 2 + 3 every half second (node `introspection_client`) in one process, each
reporting to `/add_two_ints/_service_event` as its parameter says
(`service_configure_introspection` / `client_configure_introspection`: `disabled`,
`metadata` or `contents`; change them at run time with `ros2lite param set`)."""

from __future__ import annotations

from ros2lite.bundled.demo_nodes_py.introspection_client import IntrospectionClientNode
from ros2lite.bundled.demo_nodes_py.introspection_service import IntrospectionServiceNode
from ros2lite.bundled.runner import run_main
from ros2lite.executors import SingleThreadedExecutor


def spin_both() -> None:
    """Both nodes on one executor until Ctrl-C or shutdown."""
    executor = SingleThreadedExecutor()
    service_node = IntrospectionServiceNode()
    client_node = IntrospectionClientNode()
    executor.add_node(service_node)
    executor.add_node(client_node)
    try:
        executor.spin()
    finally:
        executor.shutdown()
        client_node.destroy_node()
        service_node.destroy_node()


def main(args: list[str] | None = None) -> int:
    """`introspection`'s entry point."""
    return run_main(spin_both, args)


if __name__ == '__main__':
    raise SystemExit(main())
