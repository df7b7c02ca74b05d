"""`ros2lite security`: sros2's verbs, making keystores that secure a Zenoh graph."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'create_enclave': 'Create enclave',
    'create_key': 'Create key (older name of create_enclave)',
    'create_keystore': 'Create keystore',
    'create_permission': 'Create permission',
    'generate_artifacts': (
        'Generate keys and permission files from a list of identities and policy files'
    ),
    'generate_policy': 'Generate XML policy file from ROS graph data',
    'list_enclaves': 'List enclaves in keystore',
}


cli = command_group(__name__, 'Various security related sub-commands.', VERBS)
