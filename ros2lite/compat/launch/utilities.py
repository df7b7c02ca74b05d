"""`launch.utilities`: the substitution helpers launch files call."""

from ros2lite.launch.substitutions import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = ['normalize_to_list_of_substitutions', 'perform_substitutions']
