"""The `$(…)` syntax of XML and YAML launch files."""

from __future__ import annotations

import pytest

from ros2lite.launch.context import LaunchContext
from ros2lite.launch.errors import InvalidFrontendLaunchFileError
from ros2lite.launch.frontend.substitutions import parse_substitutions
from ros2lite.launch.substitutions import perform_substitutions


def _text(source: str) -> str:
    ctx = LaunchContext(environment={'E': 'env-value'})
    ctx.launch_configurations.update({'a': 'A', 'n': '2', 'flag': 'true'})
    return perform_substitutions(ctx, parse_substitutions(source))


@pytest.mark.parametrize(
    ('source', 'expected'),
    [
        ('plain text', 'plain text'),
        ('x$(var a)y', 'xAy'),
        ('$(var missing default)', 'default'),
        ('$(var missing "with space")', 'with space'),
        ('$(env E)/$(optenv NOPE)|$(env NOPE fallback)', 'env-value/|fallback'),
        ("$(eval '$(var n) * 3')", '6'),
        ('$(not $(var flag))', 'false'),
        ('$(equals $(var a) A)', 'true'),
        (r'cost: \$(var a)', 'cost: $(var a)'),
        (r'C:\path', r'C:\path'),
    ],
)
def test_parse_and_perform(source: str, expected: str) -> None:
    assert _text(source) == expected


@pytest.mark.parametrize(
    ('source', 'error'),
    [
        ('$(var a', 'unterminated substitution'),
        ('$(nope x)', "unknown substitution '$(nope)'"),
        ('$(var)', 'takes 1 to 2 argument(s), got 0'),
        ("$(var 'a)", 'unterminated'),
    ],
)
def test_errors(source: str, error: str) -> None:
    with pytest.raises(InvalidFrontendLaunchFileError) as info:
        parse_substitutions(source)
    assert error in str(info.value)
