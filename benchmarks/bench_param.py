"""Parameter benchmark: `ros2lite param get` against a running node, whole-process wall time.

A child process runs a router on a free loopback port; the parameter_blackboard demo runs
against it with one parameter set from the command line. The measured CLI process pays for
what a user's does: start-up, connecting, finding the node, one GetParameters call, printing.
Baseline: `python -c 'import click'` in the same environment.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from common import cli_env, environment, free_port, import_click_wall, report, router_process, wall


def bench_param_get() -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, "219", runtime)
        node = None
        with router_process(endpoint, env):
            try:
                node = subprocess.Popen(
                    [
                        sys.executable,
                        "-m",
                        "ros2lite.bundled.demo_nodes_py.parameter_blackboard",
                        "--ros-args",
                        "-p",
                        "answer:=42",
                    ],
                    env=env,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                )
                exe = os.path.join(os.path.dirname(sys.executable), "ros2lite")
                cmd = [exe, "param", "get", "/parameter_blackboard", "answer"]
                deadline = time.monotonic() + 15
                while True:  # sanity: the node answers before we time it
                    out = subprocess.run(cmd, env=env, capture_output=True, text=True).stdout
                    if out == "Integer value is: 42\n" or time.monotonic() > deadline:
                        break
                    time.sleep(0.1)
                assert out == "Integer value is: 42\n", out
                with environment(env):
                    ours = wall(cmd, runs=9)
                    base = import_click_wall()
            finally:
                if node is not None:
                    node.terminate()
                    node.wait(timeout=10)
    report("param_get_wall", ours * 1000, "ms", ours / base)


BENCHES = {"param_get": bench_param_get}
