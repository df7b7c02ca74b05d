"""`component_container_mt`: the container on a multi-threaded executor (threads: the
container's `thread_num` parameter, else one per CPU)."""

from __future__ import annotations

from ros2lite.bundled.rclpy_components.component_container import run_container


def main(args: list[str] | None = None) -> int:
    """`component_container_mt`'s entry point."""
    return run_container(multi_threaded=True, args=args)


if __name__ == '__main__':
    raise SystemExit(main())
