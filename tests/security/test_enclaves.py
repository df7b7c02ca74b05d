"""Enclave names follow the namespace rules, and each has its directory in the keystore."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.security import environment
from ros2lite.security.enclaves import enclave_directory, validate_enclave_name
from ros2lite.security.errors import EnclaveError


@pytest.mark.parametrize('name', ['/', '/talker', '/robot/arm_1'])
def test_a_namespace_shaped_name_is_an_enclave_name(name: str) -> None:
    validate_enclave_name(name)


@pytest.mark.parametrize('name', ['talker', '/robot//arm', '/robot/', '/a-b', ''])
def test_other_names_are_refused_with_the_name_in_the_message(name: str) -> None:
    with pytest.raises(EnclaveError, match=f"'{name}' is not a valid enclave name"):
        validate_enclave_name(name)


def test_an_enclave_lives_under_the_keystores_enclaves_directory(tmp_path: Path) -> None:
    assert enclave_directory(tmp_path, '/') == tmp_path / 'enclaves'
    assert enclave_directory(tmp_path, '/robot/arm') == tmp_path / 'enclaves' / 'robot' / 'arm'
    with pytest.raises(EnclaveError):
        enclave_directory(tmp_path, '/../etc')


def test_the_environment_module_still_offers_the_rules() -> None:
    # rcl's names stay importable where users of ros2lite.security.environment found them
    assert environment.validate_enclave_name is validate_enclave_name
    assert environment.enclave_directory is enclave_directory
    assert environment.KEYSTORE_ENV == 'ROS_SECURITY_KEYSTORE'
