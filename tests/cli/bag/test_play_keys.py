"""`bag play` and `bag record` on a pseudo-terminal, keys pressed as a person presses them:
SPACE pauses and resumes, CURSOR_RIGHT plays the next message while paused, CURSOR_UP and
CURSOR_DOWN change the rate by 10%; the terminal is given back as it was."""

from __future__ import annotations

import termios
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bag import Writer
from ros2lite.interfaces import deserialize, get_interface
from tests.bundled.ptyproc import PtyProcess, ros2lite_argv

from .conftest import subscribed, wait_until

String = get_interface("std_msgs/msg/String")
T0 = 1_700_000_000_000_000_000


@pytest.fixture
def pty_procs(ros_router: str) -> Iterator[list[PtyProcess]]:
    made: list[PtyProcess] = []
    yield made
    for proc in made:
        proc.close()


def published(ctx: Any, topic: str) -> bool:
    from ros2lite.graph import snapshot

    return any(
        e.kind.value == "MP" and e.topic_name == topic for e in snapshot(ctx.session, ctx.domain_id)
    )


def given_back(proc: PtyProcess) -> bool:
    lflag = int(proc.attrs()[3])
    return bool(lflag & termios.ECHO and lflag & termios.ICANON)


def test_play_keys(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str, pty_procs: list[PtyProcess]
) -> None:
    with Writer(tmp_path / "bag") as bag:
        for i in range(5):
            bag.write(topic, String(data=str(i)), T0 + i * 20_000_000)
    lst = listener(topic, String, raw=True)
    wait_until(lambda: subscribed(ros_context, topic))
    proc = PtyProcess(ros2lite_argv("bag", "play", str(tmp_path / "bag"), "--start-paused"))
    pty_procs.append(proc)
    proc.expect("Press CURSOR_DOWN for Decrease Rate 10%")
    lflag = int(proc.attrs()[3])
    assert not lflag & (termios.ECHO | termios.ICANON)  # keys arrive one by one
    wait_until(lambda: published(ros_context, topic))

    proc.send("\x1b[C")  # CURSOR_RIGHT: the next message, still paused
    wait_until(lambda: len(lst.messages) == 1)
    proc.send("\x1b[C")
    wait_until(lambda: len(lst.messages) == 2)
    proc.send("\x1b[A")  # CURSOR_UP: rate 1.1
    proc.expect(r"\[P\] x1\.1 ")
    mark = len(proc.output)
    proc.send("\x1b[B\x1b[B")  # CURSOR_DOWN twice in one burst (a held key): two presses
    proc.expect(r"\[P\] x0\.9 ", start=mark)
    assert len(lst.messages) == 2  # nothing played meanwhile
    proc.send(" ")  # SPACE: resume, the rest plays and play ends
    proc.expect("Resuming play.")
    assert proc.wait() == 0
    wait_until(lambda: len(lst.messages) == 5)
    got = [deserialize("std_msgs/msg/String", m).data for m in lst.messages]
    assert got == ["0", "1", "2", "3", "4"]
    assert given_back(proc)


def test_record_space_pauses_and_resumes(
    tmp_path: Path, ros_context: Any, topic: str, pty_procs: list[PtyProcess]
) -> None:
    argv = ros2lite_argv("bag", "record", "-o", str(tmp_path / "bag"), "--topics", topic)
    proc = PtyProcess(argv, cols=200)  # wide: the log lines above the live table stay whole
    pty_procs.append(proc)
    proc.expect("Press SPACE for pausing/resuming")
    proc.send(" ")
    proc.expect("Pausing recording.", plain=True)
    proc.send(" ")
    proc.expect("Resuming recording.", plain=True)
    proc.send("\x03")  # Ctrl-C through the terminal: the bag is closed, the terminal restored
    assert proc.wait() == 0
    assert given_back(proc)
    assert (tmp_path / "bag" / "metadata.yaml").exists()
