"""ExecuteProcess: the action that starts a process (launch_ros' Node builds on it).

What it resolves when reached — the command with its prefix, the label (`talker-1`), the
working directory, the environment, where output goes, the stop timeouts — becomes a
:class:`ProcessSpec`; the launch service starts and watches the process
(:class:`ros2lite.util.process.ChildProcess`).
"""

from __future__ import annotations

import os
import re
import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING

from ros2lite.pkg.environment import child_environment

from .actions import Action, ActionOptions, Entities, seconds_of
from .errors import LaunchError
from .event_handlers import OnProcessExit
from .output import destinations
from .process_spec import ProcessSpec
from .substitutions import (
    LaunchConfiguration,
    SomeSubstitutionsType,
    Substitution,
    SubstitutionMapping,
    describe_substitutions,
    evaluate_condition_expression,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from .context import LaunchContext
    from .event_handlers import Reaction
    from .events import ProcessDetails

__all__ = ['ExecuteProcess', 'ProcessSpec']


# launch's defaults: launch configurations, so `sigterm_timeout:=10` on the command line works
_SIGTERM_TIMEOUT = LaunchConfiguration('sigterm_timeout', default=5)
_SIGKILL_TIMEOUT = LaunchConfiguration('sigkill_timeout', default=5)


class ExecuteProcess(Action):
    """Starts a process and watches it; stopping it follows launch's escalation."""

    completes_on_execute = False

    def __init__(
        self,
        *,
        cmd: Iterable[SomeSubstitutionsType],
        name: SomeSubstitutionsType | None = None,
        cwd: SomeSubstitutionsType | None = None,
        env: SubstitutionMapping | None = None,
        additional_env: SubstitutionMapping | None = None,
        shell: bool = False,
        prefix: SomeSubstitutionsType | None = None,
        output: SomeSubstitutionsType = 'log',
        sigterm_timeout: SomeSubstitutionsType = _SIGTERM_TIMEOUT,
        sigkill_timeout: SomeSubstitutionsType = _SIGKILL_TIMEOUT,
        emulate_tty: bool = False,
        on_exit: Reaction = None,
        respawn: bool | SomeSubstitutionsType = False,
        respawn_delay: float | None = None,
        respawn_max_retries: int = -1,
        log_cmd: bool = False,
        cached_output: bool = False,
        arguments: Iterable[SomeSubstitutionsType] | None = None,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        self.cmd = [normalize_to_list_of_substitutions(c) for c in cmd]
        self.cmd += [normalize_to_list_of_substitutions(a) for a in arguments or []]
        self.name = None if name is None else normalize_to_list_of_substitutions(name)
        self.cwd = None if cwd is None else normalize_to_list_of_substitutions(cwd)
        self.env = _normalize_env(env)
        self.additional_env = _normalize_env(additional_env)
        self.shell = shell
        self.prefix = None if prefix is None else normalize_to_list_of_substitutions(prefix)
        self.output = normalize_to_list_of_substitutions(output)
        self.sigterm_timeout = normalize_to_list_of_substitutions(sigterm_timeout)
        self.sigkill_timeout = normalize_to_list_of_substitutions(sigkill_timeout)
        self.emulate_tty = emulate_tty  # output is line-buffered (PYTHONUNBUFFERED) anyway
        self.on_exit = on_exit
        self.respawn = (
            respawn if isinstance(respawn, bool) else normalize_to_list_of_substitutions(respawn)
        )
        self.respawn_delay = respawn_delay
        self.respawn_max_retries = respawn_max_retries
        self.respawn_count = 0
        self.log_cmd = log_cmd
        self.cached_output = cached_output
        self.process_details: ProcessDetails | None = None
        self.return_code: int | None = None

    # -- resolving -------------------------------------------------------------------------------
    def command(self, context: LaunchContext) -> tuple[list[str], list[str], list[str]]:
        """(argv, argv to display, extra PYTHONPATH entries); Node overrides this."""
        cmd = [perform_substitutions(context, c) for c in self.cmd]
        if not cmd or not cmd[0]:
            raise LaunchError('ExecuteProcess needs a command')
        return cmd, cmd, []

    def label(self, context: LaunchContext, cmd: list[str]) -> str:
        """The process' name before its number: `name` if given, else the command's base name."""
        if self.name is not None:
            return perform_substitutions(context, self.name)
        return os.path.basename(cmd[0])

    def _with_prefix(self, context: LaunchContext, cmd: list[str]) -> list[str]:
        if self.prefix is not None:
            return shlex.split(perform_substitutions(context, self.prefix)) + cmd
        prefix = context.launch_configurations.get('launch-prefix', '')
        if not prefix:
            return cmd
        pattern = context.launch_configurations.get('launch-prefix-filter', '')
        if pattern and re.match(pattern, os.path.basename(cmd[0])) is None:
            return cmd
        return shlex.split(prefix) + cmd

    def resolve(self, context: LaunchContext) -> ProcessSpec:
        """Everything about the process, performed now."""
        cmd, display, pythonpath = self.command(context)
        name = self.label(context, display)
        if self.shell:
            cmd = ['/bin/sh', '-c', ' '.join(cmd)]
        cmd = self._with_prefix(context, cmd)
        cwd = None if self.cwd is None else perform_substitutions(context, self.cwd)
        if self.env is not None:
            env = {
                perform_substitutions(context, k): perform_substitutions(context, v)
                for k, v in self.env
            }
        else:
            env = child_environment(
                context.environment,
                pythonpath=pythonpath,
                workspaces=context.package_index.workspaces(),
            )
            # Python children write through pipes: unbuffered, so lines show as they happen
            env.setdefault('PYTHONUNBUFFERED', '1')
        for k, v in self.additional_env or []:
            env[perform_substitutions(context, k)] = perform_substitutions(context, v)
        mode = (
            context.output_override
            or os.environ.get('OVERRIDE_LAUNCH_PROCESS_OUTPUT')
            or perform_substitutions(context, self.output)
        )
        try:
            output = destinations(mode)
        except ValueError as e:
            raise LaunchError(str(e)) from None
        return ProcessSpec(
            name=name,
            cmd=cmd,
            display_cmd=self._with_prefix(context, display),
            cwd=cwd,
            env=env,
            output=output,
            sigterm_timeout=seconds_of(context, self.sigterm_timeout, 'sigterm_timeout'),
            sigkill_timeout=seconds_of(context, self.sigkill_timeout, 'sigkill_timeout'),
            log_cmd=self.log_cmd,
        )

    def should_respawn(self, context: LaunchContext) -> bool:
        """Whether to start the process again after it exited."""
        if isinstance(self.respawn, bool):
            wanted = self.respawn
        else:
            wanted = evaluate_condition_expression(context, self.respawn)
        limit = self.respawn_max_retries
        return wanted and (limit < 0 or self.respawn_count < limit)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Resolve the process and have the launch service start it."""
        if context.is_shutdown:
            return None
        spec = self.resolve(context)
        if self.on_exit is not None:
            context.register_event_handler(OnProcessExit(target_action=self, on_exit=self.on_exit))
        context.service.start_process(self, spec)
        return None

    def describe(self) -> str:
        """The command, for introspection."""
        cmd = ' '.join(describe_substitutions(c) for c in self.cmd)
        return f'{type(self).__name__}(cmd=[{cmd}])'


def _normalize_env(
    env: SubstitutionMapping | None,
) -> list[tuple[list[Substitution], list[Substitution]]] | None:
    if env is None:
        return None
    return [
        (normalize_to_list_of_substitutions(k), normalize_to_list_of_substitutions(v))
        for k, v in env.items()
    ]
