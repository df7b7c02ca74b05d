"""`xacro`: upstream's command line (`xacro file.xacro name:=value [-o out]`), the registry's
own code. It asks `ament_index_python` for `$(find pkg)`; a process started through the
package index has ros2lite's face of that module first on its path, so packages resolve
through the one package index (workspaces, ament prefixes, bundled packages)."""

from __future__ import annotations

import sys


def main(args: list[str] | None = None) -> int:
    """Run upstream xacro with `args` (default: this process's arguments); its exit status."""
    # xacro 2.1's error handler names xml.parsers.expat without importing it: loaded here,
    # a missing input file is its one error line rather than a traceback
    import xml.parsers.expat  # noqa: F401

    import xacro  # the registry's xacro, not this module (absolute import)

    argv = sys.argv[1:] if args is None else args
    sys.argv[:] = ['xacro', *argv]
    try:
        xacro.main()
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    return 0


if __name__ == '__main__':
    sys.exit(main())
