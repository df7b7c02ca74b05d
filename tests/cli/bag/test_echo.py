"""`bag echo`: the text of each message is what `topic echo`'s own printer makes of it (YAML,
CSV, message info, --field, --no-arr), several topics get a header per message that keeps the
output parseable, JSON lines read back into the same messages, and errors are one line."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
import yaml

from ros2lite.bag import Reader, Writer
from ros2lite.cli.topic.echo import Printer
from ros2lite.interfaces.json_form import json_to_message
from ros2lite.message_info import MessageInfo
from ros2lite.msgs.std_msgs.msg import String

DATA = Path(__file__).parents[2] / "bag" / "data"
CDR_TEST = DATA / "mcap" / "cdr_test"


def topic_echo_text(bag: Path, topic: str, **options: Any) -> str:
    """What `topic echo` prints for the bag's messages of one topic, through its printer."""
    out = []
    with Reader(bag) as reader:
        meta = reader.topic(topic)
        assert meta is not None
        fmt = {
            "csv": False,
            "flow_style": False,
            "truncate_length": 128,
            "no_arr": False,
            "no_str": False,
        }
        fmt.update({k: v for k, v in options.items() if k in fmt})
        printer = Printer(
            type_name=meta.type,
            field=options.get("field"),
            raw=False,
            filter_fn=None,
            once=False,
            include_info=options.get("include_info", False),
            clear=False,
            lost=None,
            warn=print,
            **fmt,  # type: ignore[arg-type]
        )
        for _, data, log_time, publish_time in reader.raw_messages([topic]):
            value: object = reader.decode(topic, data)
            for name in options.get("field") or []:
                value = getattr(value, name)
            info = MessageInfo(publish_time, log_time, 0, b"")
            out.append(printer.render(value, info))
    return "".join(out)


@pytest.mark.parametrize(
    ("args", "options"),
    [
        ((), {}),
        (("--csv",), {"csv": True}),
        (("--no-arr", "-l", "2"), {"no_arr": True, "truncate_length": 2}),
        (("--flow-style",), {"flow_style": True}),
        (("-i",), {"include_info": True}),
        (("--csv", "-i"), {"csv": True, "include_info": True}),
        (("--field", "int32_value"), {"field": ["int32_value"]}),
    ],
)
def test_one_topic_prints_what_topic_echo_prints(
    run: Any, args: tuple[str, ...], options: dict[str, Any]
) -> None:
    topic = "/array_topic" if "--no-arr" in args or "--flow-style" in args else "/test_topic"
    result = run("bag", "echo", str(CDR_TEST), topic, *args)
    assert result.code == 0, result.err
    assert result.out == topic_echo_text(CDR_TEST, topic, **options)
    assert result.out


def test_several_topics_say_topic_and_time(run: Any) -> None:
    result = run("bag", "echo", str(CDR_TEST))
    assert result.code == 0, result.err
    docs = result.out.split("---\n")[:-1]
    assert len(docs) == 7
    heads = [d.splitlines()[0] for d in docs]
    assert heads[0] == "# /test_topic 1586406456.763032325"
    assert all(yaml.safe_load(d) for d in docs)  # a comment line keeps each document YAML
    human = run("bag", "echo", str(CDR_TEST), "--human", "-n", "1")
    assert human.out.startswith("# /test_topic ") and "2020" in human.out.splitlines()[0]
    rows = run("bag", "echo", str(CDR_TEST), "--csv").out.splitlines()
    assert len(rows) == 7 and rows[0].startswith("/test_topic,1586406456.763032325,")


def test_json_lines_read_back_into_the_messages(run: Any, tmp_path: Path) -> None:
    from ros2lite.msgs.std_msgs.msg import Float64MultiArray

    with Writer(tmp_path / "bag") as w:
        w.write("/f", Float64MultiArray(data=[1.5, math.nan, -math.inf]), 10)
        w.write("/f", Float64MultiArray(data=[2.0]), 20)
        w.write("/s", String(data="ü"), 15)
    one = run("bag", "echo", str(tmp_path / "bag"), "/f", "--json")
    assert one.code == 0, one.err
    objs = [json.loads(line) for line in one.out.splitlines()]
    assert objs[0]["data"] == [1.5, "nan", "-inf"]
    back = json_to_message(Float64MultiArray, objs[0])
    assert back.data[0] == 1.5 and math.isnan(back.data[1])
    both = run("bag", "echo", str(tmp_path / "bag"), "--json")
    lines = [json.loads(line) for line in both.out.splitlines()]
    # several topics: topic echo -i's {"message", "info"} with the topic added
    got = [(x["topic"], x["info"]["received_timestamp"]) for x in lines]
    assert got == [("/f", 10), ("/s", 15), ("/f", 20)]
    assert lines[1]["message"] == {"data": "ü"}
    assert list(lines[1]) == ["topic", "message", "info"]
    info = run("bag", "echo", str(tmp_path / "bag"), "/s", "--json", "-i").out
    assert json.loads(info) == {
        "message": {"data": "ü"},
        "info": {
            "source_timestamp": 15,
            "received_timestamp": 15,
            "publication_sequence_number": 0,
            "reception_sequence_number": 0,
        },
    }
    raw = run("bag", "echo", str(tmp_path / "bag"), "/s", "--json", "--raw").out
    assert isinstance(json.loads(raw), str)  # the CDR as base64, as topic echo --raw --json


def test_time_range_and_count(run: Any, tmp_path: Path) -> None:
    with Writer(tmp_path / "bag") as w:
        for i in range(10):
            w.write("/s", String(data=str(i)), 1_000_000_000 * (i + 1))
    result = run(
        "bag",
        "echo",
        str(tmp_path / "bag"),
        "s",
        "--field",
        "data",
        "--start",
        "2",
        "--end",
        "0:04",
    )
    assert result.out == "2\n---\n3\n---\n4\n---\n"
    result = run(
        "bag", "echo", str(tmp_path / "bag"), "/s", "--filter", "int(m.data) % 3 == 0", "-n", "2"
    )
    assert result.out == "data: '0'\n---\ndata: '3'\n---\n"


def test_errors_are_one_line(run: Any) -> None:
    for args, message in [
        (["/nope"], "no topic '/nope'"),
        (["--start", "later"], "Bad time 'later'"),
        (["--json", "--csv"], "cannot be combined"),
    ]:
        result = run("bag", "echo", str(CDR_TEST), *args)
        assert result.code != 0 and message in result.err, (args, result.err)
        assert len(result.err.strip().splitlines()) == 1
