"""YAML from outside: alias bombs, deep nesting and self-references are refused with one
clear line; ordinary documents load as safe_load loads them."""

from __future__ import annotations

import pytest

from ros2lite.util.safe_yaml import MAX_DEPTH, YamlInputError, load

LAUGHS = '\n'.join(
    [
        'a: &a ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]',
        *(
            f'{n}: &{n} [{", ".join([f"*{p}"] * 9)}]'
            for p, n in zip('abcdefgh', 'bcdefghi', strict=True)
        ),
    ]
)


def test_billion_laughs_is_refused_before_it_is_expanded() -> None:
    with pytest.raises(YamlInputError, match='expands to more than 1000000 values'):
        load(LAUGHS, 'the values')


def test_deep_nesting_and_self_reference_are_refused() -> None:
    with pytest.raises(YamlInputError, match=f'nested deeper than {MAX_DEPTH}'):
        load('[' * (MAX_DEPTH + 5) + ']' * (MAX_DEPTH + 5))
    with pytest.raises(YamlInputError, match='nested too deeply'):
        load('[' * 50_000)
    with pytest.raises(YamlInputError, match='refers to itself'):
        load('a: &a [*a]')


def test_syntax_errors_are_one_line_with_a_position() -> None:
    with pytest.raises(YamlInputError) as info:
        load('{a: [1', 'the values')
    text = str(info.value)
    assert text.startswith('the values is not valid YAML: ') and 'line 1, column' in text
    assert 'Mark' not in text and '\n' not in text and info.value.syntax


def test_python_tags_never_run() -> None:
    with pytest.raises(YamlInputError, match='could not determine a constructor'):
        load('!!python/object/apply:os.system ["true"]')


def test_plain_documents_load_as_usual() -> None:
    assert load('a: [1, 2.5, x]\nb: {c: null}') == {'a': [1, 2.5, 'x'], 'b': {'c': None}}
    assert load('') is None
    shared = load('a: &x [1, 2]\nb: *x')
    assert shared == {'a': [1, 2], 'b': [1, 2]}


def test_topic_pub_and_param_files_refuse_a_bomb(ros_router: str, tmp_path: object) -> None:
    from pathlib import Path

    from ros2lite.parameters.files import ParamsFileError, read_params_file
    from tests.cli.conftest import run_process

    result = run_process('topic', 'pub', '--once', '/bomb', 'std_msgs/msg/String', LAUGHS)
    assert result.code == 1 and result.err.count('\n') == 1, result
    assert 'the passed value expands to more than 1000000 values' in result.err
    params = Path(str(tmp_path)) / 'params.yaml'
    params.write_text(LAUGHS)
    with pytest.raises(ParamsFileError, match='expands to more than'):
        read_params_file(params)
