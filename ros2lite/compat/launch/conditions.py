"""`launch.conditions`: ros2lite's conditions under launch's names."""

from ros2lite.launch.conditions import (
    Condition,
    IfCondition,
    LaunchConfigurationEquals,
    LaunchConfigurationNotEquals,
    UnlessCondition,
    evaluate_condition_expression,
)

__all__ = [
    'Condition',
    'IfCondition',
    'LaunchConfigurationEquals',
    'LaunchConfigurationNotEquals',
    'UnlessCondition',
    'evaluate_condition_expression',
]
