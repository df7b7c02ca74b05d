"""`rviz2`: the live 3D scene in a web browser, served from where the graph runs.

Built on viser (a three.js client served over a WebSocket, with a frame tree and scene click
events), so the viewing machine needs only a browser: a phone, a Mac, a laptop over SSH
(`ssh -L 8080:localhost:8080`). Loopback by default; `--host 0.0.0.0` shares it. `-d`
opens a `.rviz` file's displays; without it every drawable topic gets its display.
`--terminal` draws the top-down terminal view instead.
"""

from __future__ import annotations

import argparse
import sys

from ros2lite.bundled.display import own_arguments


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog='rviz2',
        description='Show the live scene (TF, scans, clouds, markers, maps, the '
        'robot) in a web browser.',
    )
    p.add_argument(
        '-d',
        '--display-config',
        metavar='FILE.rviz',
        help='open the displays, fixed frame and view of an RViz configuration',
    )
    p.add_argument(
        '-f',
        '--fixed-frame',
        default='',
        metavar='FRAME',
        help='the frame the scene is drawn in (default: the root of the TF tree)',
    )
    p.add_argument(
        '--host',
        default='127.0.0.1',
        help='address to serve on (default 127.0.0.1: this machine only)',
    )
    p.add_argument('--port', type=int, default=8080, help='port to serve on (default 8080)')
    p.add_argument(
        '--point-budget',
        type=int,
        default=200_000,
        metavar='N',
        help='most points of each cloud or scan sent to a browser, which can change its own '
        '(default 200000, 1..5000000)',
    )
    p.add_argument(
        '--image-width',
        type=int,
        default=640,
        metavar='PIXELS',
        help='camera images are shrunk to at most this width (default 640)',
    )
    p.add_argument(
        '--terminal',
        action='store_true',
        help='draw the top-down view on this terminal instead (over SSH); the view\'s own '
        'options (--scan, --rate, --base-frame, --robot-radius, --no-frames) follow',
    )
    return p


def serve(options: argparse.Namespace) -> None:
    """Start the node, the TF listener and the server; render until Ctrl-C."""
    import ros2lite
    from ros2lite.bundled.rviz2.config import Config, load
    from ros2lite.bundled.rviz2.viewer import Settings, Viewer
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.node import Node
    from ros2lite.tf2 import Buffer, TransformListener

    config = load(options.display_config) if options.display_config else Config()
    node = Node('rviz2')
    buffer = Buffer(node=node)
    TransformListener(buffer, node)
    settings = Settings(
        host=options.host,
        port=options.port,
        fixed_frame=options.fixed_frame.lstrip('/'),
        point_budget=options.point_budget,
        image_width=options.image_width,
    )
    try:
        viewer = Viewer(node, buffer, settings, config)
    except OSError as e:
        raise ValueError(
            f'rviz2: cannot serve on {options.host}:{options.port}: {e.strerror or e}'
        ) from None
    for skipped in config.skipped:
        node.get_logger().warning(f'{skipped} is not drawn here; the other displays are')
    print(f'rviz2: open {viewer.url} in a browser', flush=True)
    try:
        with BackgroundSpin(node):
            viewer.run(ros2lite.ok)
    finally:
        viewer.close()
        node.destroy_node()


def main(args: list[str] | None = None) -> int:
    """`rviz2`'s entry point."""
    from ros2lite.bundled.runner import run_main

    argv = list(sys.argv[1:] if args is None else args)
    cli = parser()
    # the terminal view's own options (--scan, --rate, ...) pass through to it
    options, unknown = cli.parse_known_args(own_arguments(argv))
    if unknown and not options.terminal:
        cli.error(f'unrecognized arguments: {" ".join(unknown)}')
    if options.terminal:
        import importlib

        try:  # the terminal view is its own module (topview's), loaded only when asked for
            top_view = importlib.import_module('ros2lite.bundled.rviz2.top_view')
        except ModuleNotFoundError:
            print(
                'rviz2: --terminal needs the top-down view (rviz2.top_view), which this '
                'install does not have',
                file=sys.stderr,
            )
            return 1
        rest = [a for a in argv if a != '--terminal']
        return int(top_view.main(rest))
    if not 0 <= options.port <= 65535:
        print(f'rviz2: --port must be 0..65535, not {options.port}', file=sys.stderr)
        return 1
    from ros2lite.bundled.rviz2.clients import MAX_BUDGET, MIN_BUDGET

    if not MIN_BUDGET <= options.point_budget <= MAX_BUDGET:
        print(
            f'rviz2: --point-budget must be {MIN_BUDGET}..{MAX_BUDGET}, not {options.point_budget}',
            file=sys.stderr,
        )
        return 1
    return run_main(lambda: serve(options), args)


if __name__ == '__main__':
    sys.exit(main())
