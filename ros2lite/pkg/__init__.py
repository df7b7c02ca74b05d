"""Packages and what they provide: the one package index (:mod:`ros2lite.pkg.index`) and the
executables behind `ros2lite run` (:mod:`ros2lite.pkg.executables`).
"""
