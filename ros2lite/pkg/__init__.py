"""Packages and what they provide: the executable index behind `ros2lite run`.

Later this grows the rest of `ros2 pkg` (listing, prefixes, `pkg create` templates); the lookup
rules live in :mod:`ros2lite.pkg.executables`.
"""
