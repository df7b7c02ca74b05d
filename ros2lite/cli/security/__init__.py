"""`ros2lite security`: sros2's verbs, making keystores that secure a Zenoh graph."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'create_enclave': (__name__ + '.create_enclave', 'Create enclave'),
    'create_key': (__name__ + '.create_key', 'Create key (older name of create_enclave)'),
    'create_keystore': (__name__ + '.create_keystore', 'Create keystore'),
    'create_permission': (__name__ + '.create_permission', 'Create permission'),
    'generate_artifacts': (
        __name__ + '.generate_artifacts',
        'Generate keys and permission files from a list of identities and policy files',
    ),
    'generate_policy': (
        __name__ + '.generate_policy',
        'Generate XML policy file from ROS graph data',
    ),
    'list_enclaves': (__name__ + '.list_enclaves', 'List enclaves in keystore'),
}


cli = command_group('security', 'Various security related sub-commands.', VERBS)
