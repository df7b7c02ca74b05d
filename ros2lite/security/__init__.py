"""Security as ROS users know it (sros2 keystores), enforced with Zenoh's own machinery.

* :mod:`.keystore` makes and reads sros2-layout keystores (:mod:`.pki` holds the crypto,
  done by the ``cryptography`` package);
* :mod:`.policy` and :mod:`.permissions` read and write sros2 policies and the DDS
  governance/permissions documents made from them;
* :mod:`.environment` decides which enclave a process uses from ``ROS_SECURITY_*``;
* :mod:`.access` turns every enclave's permissions into the router's access rules.

The Zenoh side (TLS links, the ``access_control`` section) is written by
:mod:`ros2lite.transport.security`; nothing here imports zenoh.  Importing this package
loads neither ``cryptography`` nor XML code.
"""

from __future__ import annotations

from ros2lite.security.environment import Identity, enforced, resolve, security_enabled
from ros2lite.security.errors import EnclaveError, KeystoreError, PolicyError, SecurityError

__all__ = [
    'EnclaveError',
    'Identity',
    'KeystoreError',
    'PolicyError',
    'SecurityError',
    'enforced',
    'resolve',
    'security_enabled',
]
