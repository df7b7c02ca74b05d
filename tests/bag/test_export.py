"""`bag export`: CSV rows equal `topic echo --csv`'s, JSON lines and Parquet read back into
the same values, image frames become PNG files whose pixels are the frames', and what cannot
be exported is one line."""

from __future__ import annotations

import io
import json
import math
from pathlib import Path

import pytest

from ros2lite.bag import BagError, Reader, Writer
from ros2lite.bag.export import ExportOptions, export
from ros2lite.cli.topic.echo import Printer
from ros2lite.interfaces.json_form import json_to_message
from ros2lite.message_info import MessageInfo
from ros2lite.msgs.sensor_msgs.msg import CompressedImage, Image, Imu
from ros2lite.msgs.std_msgs.msg import Float64MultiArray

CDR_TEST = Path(__file__).parent / "data" / "mcap" / "cdr_test"


def test_csv_rows_are_topic_echo_csv(tmp_path: Path) -> None:
    for topic in ("/test_topic", "/array_topic"):
        for info in (False, True):
            out = tmp_path / f"{topic[1:]}{info}.csv"
            n = export(CDR_TEST, topic, "csv", out, ExportOptions(include_info=info))
            printer = Printer(
                type_name="", csv=True, field=None, truncate_length=None, no_arr=False,
                no_str=False, flow_style=False, raw=False, filter_fn=None, once=False,
                include_info=info, clear=False, lost=None, warn=print,
            )  # fmt: skip
            with Reader(CDR_TEST) as r:
                want = "".join(
                    printer.render(r.decode(topic, d), MessageInfo(p, t, 0, b""))
                    for _, d, t, p in r.raw_messages([topic])
                )
            assert out.read_text() == want and n == want.count("\n") > 0


def test_jsonl_and_parquet_keep_the_values(tmp_path: Path) -> None:
    pq = pytest.importorskip("pyarrow.parquet")
    with Writer(tmp_path / "bag") as w:
        for i in range(3):
            w.write("/f", Float64MultiArray(data=[i + 0.5, math.nan]), 100 + i)
        w.write("/imu", Imu(), 50)
    assert export(tmp_path / "bag", "f", "jsonl", tmp_path / "f.jsonl") == 3
    objs = [json.loads(x) for x in (tmp_path / "f.jsonl").read_text().splitlines()]
    back = json_to_message(Float64MultiArray, objs[2])
    assert back.data[0] == 2.5 and math.isnan(back.data[1])
    export(tmp_path / "bag", "/f", "jsonl", tmp_path / "t.jsonl", ExportOptions(include_info=True))
    first = json.loads((tmp_path / "t.jsonl").read_text().splitlines()[0])
    assert first["info"]["received_timestamp"] == 100 and first["message"]["data"] == [0.5, "nan"]
    assert export(tmp_path / "bag", "/f", "parquet", tmp_path / "f.parquet") == 3
    table = pq.read_table(tmp_path / "f.parquet").to_pylist()
    assert [r["log_time"] for r in table] == [100, 101, 102]
    assert table[1]["data"][0] == 1.5 and math.isnan(table[1]["data"][1])
    assert table[0]["layout"] == {"dim": [], "data_offset": 0}
    assert export(tmp_path / "bag", "/imu", "parquet", tmp_path / "imu.parquet") == 1
    imu = pq.read_table(tmp_path / "imu.parquet").to_pylist()[0]
    assert imu["orientation"]["w"] == 1.0 and imu["header"]["frame_id"] == ""
    none = ExportOptions(start=1000)
    assert export(tmp_path / "bag", "/f", "parquet", tmp_path / "e.parquet", none) == 0
    assert pq.read_table(tmp_path / "e.parquet").num_rows == 0


def test_images_become_png_files(tmp_path: Path) -> None:
    from PIL import Image as PILImage

    w_, h_ = 4, 3
    rgb = b"".join(bytes((x * 60, y * 80, 200)) for y in range(h_) for x in range(w_))
    bgr = b"".join(bytes((200, y * 80, x * 60)) for y in range(h_) for x in range(w_))
    padded = b"".join(bgr[y * 12 : y * 12 + 12] + b"\0\0" for y in range(h_))  # step 14
    mono16 = b"".join((x * 1000 + y).to_bytes(2, "little") for y in range(h_) for x in range(w_))
    png = io.BytesIO()
    PILImage.frombytes("RGB", (w_, h_), rgb).save(png, format="PNG")
    with Writer(tmp_path / "bag") as w:
        w.write("/cam", Image(width=4, height=3, encoding="rgb8", step=12, data=rgb), 1)
        w.write("/cam", Image(width=4, height=3, encoding="bgr8", step=14, data=padded), 2)
        w.write("/depth", Image(width=4, height=3, encoding="16UC1", step=8, data=mono16), 3)
        w.write("/cam/compressed", CompressedImage(format="png", data=png.getvalue()), 4)
        w.write("/bad", Image(width=4, height=3, encoding="yuv422", step=8, data=b"\0" * 24), 5)
    assert export(tmp_path / "bag", "/cam", "png", tmp_path / "cam") == 2
    files = sorted((tmp_path / "cam").iterdir())
    assert [f.name for f in files] == ["000000_0.000000001.png", "000001_0.000000002.png"]
    for f in files:  # rgb8 and padded bgr8 of the same picture
        assert PILImage.open(f).convert("RGB").tobytes() == rgb
    export(tmp_path / "bag", "/depth", "png", tmp_path / "depth")
    depth = PILImage.open(next((tmp_path / "depth").iterdir()))
    assert depth.getpixel((3, 2)) == 3002
    export(tmp_path / "bag", "/cam/compressed", "png", tmp_path / "c")
    assert PILImage.open(next((tmp_path / "c").iterdir())).convert("RGB").tobytes() == rgb
    with pytest.raises(BagError, match="encoding 'yuv422' is not exported"):
        export(tmp_path / "bag", "/bad", "png", tmp_path / "bad")
    with pytest.raises(BagError, match="only sensor_msgs/msg/Image"):
        export(CDR_TEST, "/test_topic", "png", tmp_path / "x")
    with pytest.raises(BagError, match="no topic '/nope'"):
        export(CDR_TEST, "/nope", "csv", tmp_path / "x.csv")


def test_no_write_through_a_symlink(tmp_path: Path) -> None:
    target = tmp_path / "target"
    target.write_text("keep")
    (tmp_path / "link.csv").symlink_to(target)
    with pytest.raises(BagError, match="Cannot write"):
        export(CDR_TEST, "/test_topic", "csv", tmp_path / "link.csv")
    assert target.read_text() == "keep"
