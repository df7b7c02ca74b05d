"""The commands a ROS shell has, defined by ``ros2lite env``: ``ros2`` (ros2lite under the name
every course prints), tab completion for it and for ``ros2lite``, and one-line answers for the
ROS tools a course types that ros2lite does not replace (``rosdep``, ``vcs``).

Why shell functions, not a console script named ``ros2``: a pip extra cannot add or withhold a
script, and a script on ``PATH`` would shadow a real ROS 2 install whenever the venv is active.
A function exists only in a shell that evaluated ``ros2lite env``; it is defined only when no
``ros2`` is on ``PATH`` (unless the user forces it), and it runs the interpreter ros2lite is
installed in, so a second terminal that evaluates the same lines needs no activated venv.

Completion speaks click's protocol (``<VAR>=bash_complete|zsh_complete|fish_complete`` with
``COMP_WORDS``/``COMP_CWORD``); the functions below are ros2lite's own readers of it, calling the
interpreter directly, because click's generated scripts call the program by the name being
completed, and ``env ros2 …`` cannot run a shell function.
"""

from __future__ import annotations

import os
import shlex
import shutil
import sys
from collections.abc import Mapping

from .environment import SHELLS, UnknownShellError, _fish_quote

__all__ = ['STAND_INS', 'command_lines', 'real_command']

# what a course's line would have done, and what to do here; printed by the stand-in
STAND_INS = {
    'rosdep': (
        "rosdep is not installed: on ROS it installs the system packages a workspace's "
        'package.xml files depend on; ros2lite runs Python packages and needs none of them: '
        "pip install what a package's setup.py names (install_requires)"
    ),
    'vcs': (
        'vcs is not installed: it clones each repository a .repos file lists (vcs import '
        "src < my.repos); here, git clone each url at its 'version' into src/, or "
        'pip install vcstool for the real one (it needs no ROS)'
    ),
}


def real_command(name: str, env: Mapping[str, str] | None = None) -> str | None:
    """Where `name` is on the ``PATH`` of `env` (default: ours), if anywhere."""
    environ = os.environ if env is None else env
    return shutil.which(name, path=environ.get('PATH', os.defpath))


def command_lines(
    shell: str,
    *,
    complete_var: str,
    ros2: bool | None = None,
    python: str | None = None,
    env: Mapping[str, str] | None = None,
) -> str:
    """Lines for `shell` (bash, zsh, fish) defining ``ros2`` and the completion functions.

    `ros2`: None defines the function only when no ``ros2`` is on PATH; True always (the user
    asked to shadow a real one in this shell); False never. `complete_var` is the variable the
    CLI reads completion requests from; `python` the interpreter to run (default: ours)."""
    writers = {'bash': _bash, 'zsh': _zsh, 'fish': _fish}
    if shell not in writers:
        raise UnknownShellError(f"unknown shell '{shell}'; choose one of: {', '.join(SHELLS)}")
    real = real_command('ros2', env)
    define_ros2 = ros2 if ros2 is not None else real is None
    lines: list[str] = []
    if real is not None and not define_ros2:
        # a comment: evaluating these lines in every new terminal stays silent
        lines.append(
            f'# ros2 stays {real} (a ROS 2 install); `ros2lite env --ros2` makes ros2 run '
            'ros2lite in this shell'
        )
    quote = _fish_quote if shell == 'fish' else shlex.quote
    run = f'{quote(python or sys.executable)} -m ros2lite'
    names = ['ros2lite', *(['ros2'] if define_ros2 else [])]
    missing = {name: line for name, line in STAND_INS.items() if real_command(name, env) is None}
    # the function's mode: forced (True), deferring to a later real one (None), absent (False)
    mode = True if ros2 else (None if define_ros2 else False)
    lines += writers[shell](run, complete_var, names, mode, missing)
    return '\n'.join(lines) + '\n'


def _posix_functions(run: str, ros2: bool | None, missing: dict[str, str], find: str) -> list[str]:
    """``ros2`` and the stand-ins for bash and zsh (`find`: the builtin that looks on PATH
    only). Unless forced, each defers to a real command that appears on PATH later (ROS's
    setup script sourced, ``pip install vcstool``), so none shadows one."""
    lines = []
    if ros2:
        lines.append(f'ros2() {{ {run} "$@"; }}')
    elif ros2 is None:
        lines.append(
            f'ros2() {{ if {find} ros2 >/dev/null; then command ros2 "$@"; else {run} "$@"; fi; }}'
        )
    for name, text in missing.items():
        lines.append(
            f'{name}() {{ if {find} {name} >/dev/null; then command {name} "$@"; '
            f"else printf '%s\\n' {shlex.quote(text)} >&2; return 1; fi; }}"
        )
    return lines


def _bash(
    run: str, var: str, names: list[str], ros2: bool | None, missing: dict[str, str]
) -> list[str]:
    lines = _posix_functions(run, ros2, missing, 'type -P')
    # click answers one `type,value` line per candidate; `dir`/`file` hand over to bash's own
    lines += [
        '_ros2lite_complete() {',
        '    local item',
        '    COMPREPLY=()',
        '    while IFS= read -r item; do',
        '        case ${item%%,*} in',
        '            plain) COMPREPLY+=("${item#*,}") ;;',
        '            dir) compopt -o dirnames; COMPREPLY=(); return 0 ;;',
        '            file) compopt -o default; COMPREPLY=(); return 0 ;;',
        '        esac',
        f'    done < <(COMP_WORDS="${{COMP_WORDS[*]}}" COMP_CWORD=$COMP_CWORD '
        f'{var}=bash_complete {run} 2>/dev/null)',
        '}',
        f'complete -o nosort -F _ros2lite_complete {" ".join(names)}',
    ]
    return lines


def _zsh(
    run: str, var: str, names: list[str], ros2: bool | None, missing: dict[str, str]
) -> list[str]:
    lines = _posix_functions(run, ros2, missing, 'whence -p')
    # click answers three lines per candidate: type, value, help (`_` for none)
    lines += [
        '_ros2lite_complete() {',
        '    local -a reply plain described',
        '    local i',
        f'    reply=("${{(@f)$(COMP_WORDS="${{words[*]}}" COMP_CWORD=$((CURRENT-1)) '
        f'{var}=zsh_complete {run} 2>/dev/null)}}")',
        '    for ((i = 1; i + 2 <= ${#reply}; i += 3)); do',
        '        case ${reply[i]} in',
        '            plain) if [[ ${reply[i+2]} == _ ]]; then plain+=("${reply[i+1]}");',
        '                   else described+=("${reply[i+1]}:${reply[i+2]}"); fi ;;',
        '            dir) _path_files -/ ;;',
        '            file) _path_files -f ;;',
        '        esac',
        '    done',
        '    (( ${#described} )) && _describe -V unsorted described -U',
        '    (( ${#plain} )) && compadd -U -V unsorted -a plain',
        '    return 0',
        '}',
        # compdef exists once compinit ran (most ~/.zshrc do); load it if not, or Tab stays dumb
        'if (( ! $+functions[compdef] )); then autoload -Uz compinit && compinit -i; fi',
        f'compdef _ros2lite_complete {" ".join(names)}',
    ]
    return lines


def _fish(
    run: str, var: str, names: list[str], ros2: bool | None, missing: dict[str, str]
) -> list[str]:
    lines = []
    if ros2:
        lines.append(f'function ros2; {run} $argv; end')
    elif ros2 is None:
        lines.append(
            f'function ros2; if command -q ros2; command ros2 $argv; else; {run} $argv; end; end'
        )
    for name, text in missing.items():
        lines.append(
            f'function {name}; if command -q {name}; command {name} $argv; '
            f"else; printf '%s\\n' {_fish_quote(text)} >&2; return 1; end; end"
        )
    # click answers one `type,value[<tab>help]` line per candidate
    lines += [
        'function __ros2lite_complete',
        f'    for item in (env {var}=fish_complete COMP_WORDS=(commandline -cp) '
        f'COMP_CWORD=(commandline -t) {run} 2>/dev/null)',
        '        set -l part (string split -m 1 , -- $item)',
        '        switch $part[1]',
        '            case plain',
        "                printf '%s\\n' $part[2]",
        '            case dir',
        '                __fish_complete_directories $part[2]',
        '            case file',
        '                __fish_complete_path $part[2]',
        '        end',
        '    end',
        'end',
    ]
    lines += [
        f"complete --no-files --command {name} --arguments '(__ros2lite_complete)'"
        for name in names
    ]
    return lines
