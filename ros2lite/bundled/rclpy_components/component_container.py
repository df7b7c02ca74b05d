"""`component_container`: an empty container node (`/ComponentManager`) on one thread;
`ros2lite component load` fills it. Its components are destroyed when it stops."""

from __future__ import annotations

from ros2lite.bundled.runner import run_main


def run_container(*, multi_threaded: bool, args: list[str] | None = None) -> int:
    """Spin a ComponentManager on a single- or multi-threaded executor until Ctrl-C or
    shutdown; returns the exit status."""

    def body() -> None:
        from ros2lite.components.manager import ComponentManager
        from ros2lite.executors import Executor, MultiThreadedExecutor, SingleThreadedExecutor

        manager = ComponentManager()
        executor: Executor
        if multi_threaded:
            manager.declare_parameter('thread_num', 0)
            threads = manager.get_parameter('thread_num').value
            executor = MultiThreadedExecutor(num_threads=threads if threads > 0 else None)
        else:
            executor = SingleThreadedExecutor()
        executor.add_node(manager)
        try:
            executor.spin()
        finally:
            executor.shutdown()
            manager.destroy_node()

    return run_main(body, args)


def main(args: list[str] | None = None) -> int:
    """`component_container`'s entry point (one thread)."""
    return run_container(multi_threaded=False, args=args)


if __name__ == '__main__':
    raise SystemExit(main())
