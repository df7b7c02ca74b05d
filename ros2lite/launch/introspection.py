"""What `launch -s` and `launch -p` print: a description's arguments and its tree."""

from __future__ import annotations

from .actions import Action, LaunchDescriptionEntity, declared_arguments, launch_arguments
from .substitutions import describe_substitutions

__all__ = ['declared_arguments', 'describe_tree', 'format_arguments', 'launch_arguments']


def format_arguments(root: LaunchDescriptionEntity) -> str:
    """ros2launch's `--show-args` text."""
    args = launch_arguments(root)
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    for arg, conditional in args:
        entry = f"\n    '{arg.name}'{'*' if conditional else ''}:\n        {arg.description}"
        if arg.choices is not None:
            entry += f"\n        Valid choices are: {arg.choices}"
        if arg.default_value is not None:
            entry += f'\n        (default: {describe_substitutions(arg.default_value)})'
        lines.append(entry)
    if not args:
        lines.append('\n  No arguments.')
    elif any(conditional for _arg, conditional in args):
        lines.append('\n* argument(s) which are only used if specific conditions occur')
    return '\n'.join(lines)


def describe_tree(root: LaunchDescriptionEntity) -> str:
    """The description as a tree, one entity per line (`launch -p`)."""
    lines = [root.describe()]

    def walk(entity: LaunchDescriptionEntity, indent: str) -> None:
        children: list[tuple[str, LaunchDescriptionEntity]] = [
            ('', e) for e in entity.describe_sub_entities()
        ]
        for label, subs in entity.describe_conditional_sub_entities():
            children += [(f'({label}) ', e) for e in subs]
        for i, (label, child) in enumerate(children):
            last = i == len(children) - 1
            condition = child.condition if isinstance(child, Action) else None
            suffix = f' [{condition.describe()}]' if condition is not None else ''
            lines.append(f"{indent}{'└── ' if last else '├── '}{label}{child.describe()}{suffix}")
            walk(child, indent + ('    ' if last else '│   '))

    walk(root, '')
    return '\n'.join(lines)
