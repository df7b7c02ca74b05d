"""`launch.some_substitutions_type`: the type of text-or-substitutions arguments."""

from ros2lite.launch.substitutions import SomeSubstitutionsType

__all__ = ['SomeSubstitutionsType']
