"""`view_frames`: listen to `/tf` and `/tf_static` for a while (5 s by default), then write the
frame tree as `frames_<date>.gv` (Graphviz text, as tf2_tools writes it) and
`frames_<date>.pdf` (drawn here, so no Graphviz is needed), or `<output>.gv`/`.pdf`."""

from __future__ import annotations

import argparse
import sys
import time

from ros2lite.bundled.display import own_arguments
from ros2lite.tf2.qos import TF_STATIC_TOPIC, TF_TOPIC


def view(options: argparse.Namespace) -> None:
    """Fill a buffer for `options.wait_time` s, then write both files."""
    import ros2lite
    from ros2lite.bundled.tf2_tools.frames import parse, to_dot
    from ros2lite.bundled.tf2_tools.pdf import to_pdf
    from ros2lite.msgs.tf2_msgs.srv import FrameGraph
    from ros2lite.node import Node
    from ros2lite.tf2 import Buffer, TransformListener
    from ros2lite.util.files import replace_file

    # other topics are remaps of the listener's: the node's own rules, as `-r` would give
    remaps = [(TF_TOPIC, options.tf_topic), (TF_STATIC_TOPIC, options.tf_static_topic)]
    rules = [arg for old, new in remaps if new != old for arg in ('-r', f'{old}:={new}')]
    node = Node('view_frames', cli_args=['--ros-args', *rules] if rules else None)
    buffer = Buffer(node=node)  # serves tf2_frames too, as tf2_ros's buffer with a node does
    TransformListener(buffer, node)
    log = node.get_logger()
    log.info(f'Listening to tf data for {options.wait_time} seconds...')
    end = time.monotonic() + options.wait_time
    while time.monotonic() < end:
        ros2lite.spin_once(node, timeout_sec=min(0.1, max(end - time.monotonic(), 0.0)))
    log.info('Generating graph...')
    # the real tool asks this very buffer through its tf2_frames service; asking it directly
    # gives the same text without a second node answering for another view_frames' buffer
    result = FrameGraph.Response(frame_yaml=buffer.all_frames_as_yaml())
    log.info('Result:' + repr(result))
    skipped: list[str] = []
    frames = parse(result.frame_yaml, skipped)
    for line in skipped[:20]:
        log.warning(line)
    if len(skipped) > 20:
        log.warning(f'({len(skipped) - 20} more entries skipped)')
    if options.output is not None:
        gv, pdf = f'{options.output}.gv', f'{options.output}.pdf'
    else:
        stamp = time.strftime('%Y-%m-%d_%H.%M.%S')
        gv, pdf = f'frames_{stamp}.gv', f'frames_{stamp}.pdf'
    sec, nsec = node.get_clock().now().seconds_nanoseconds()
    recorded_at = sec + nsec / 1e9
    log.info(f'Exporting graph in {pdf} file...')
    try:
        # a stop signal (SIGTERM, Ctrl-C) ends the context: nothing more is drawn or written
        files = []
        for path, draw in ((gv, to_dot), (pdf, to_pdf)):
            if not node.context.ok():
                return
            files.append((path, draw(frames, recorded_at)))
        for path, content in files:
            if not node.context.ok():
                return
            try:
                replace_file(path, content, sync=False)
            except OSError as e:
                raise ValueError(f"cannot write '{path}': {e.strerror or e}") from None
    finally:
        node.destroy_node()


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0 <= value < 1e6:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds")
    return value


def main(args: list[str] | None = None) -> int:
    """`view_frames`' entry point."""
    from ros2lite.bundled.runner import run_main

    parser = argparse.ArgumentParser(
        prog='view_frames', description='Create a diagram of the TF frames being broadcast over ROS'
    )
    parser.add_argument(
        '--wait-time',
        '-t',
        type=_seconds,
        default=5.0,
        help='Listen to the /tf topic for this many seconds before rendering the frame tree',
    )
    parser.add_argument('-o', '--output', help='Output filename')
    parser.add_argument('--tf_topic', default=TF_TOPIC, help='Topic for dynamic transforms')
    parser.add_argument(
        '--tf_static_topic', default=TF_STATIC_TOPIC, help='Topic for static transforms'
    )
    options = parser.parse_args(own_arguments(args))
    return run_main(lambda: view(options), args)


if __name__ == '__main__':
    sys.exit(main())
