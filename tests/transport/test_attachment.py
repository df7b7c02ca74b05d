from __future__ import annotations

import time

import pytest

from ros2lite.transport.attachment import (
    ATTACHMENT_SIZE,
    LEGACY_ATTACHMENT_SIZE,
    Attachment,
    decode_attachment,
    encode_attachment,
    encode_legacy_attachment,
    gid_from_token,
    is_legacy_attachment,
)

GID = bytes(range(16))
TALKER_TOKEN = (
    "@ros2_lv/0/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%robot1/talker/%robot1%chatter/"
    "std_msgs::msg::dds_::String_/"
    "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18/::,7:,:,:,,"
)


def test_reference_example_bytes() -> None:
    raw = encode_attachment(1, 1700000000123456789, GID)
    assert len(raw) == ATTACHMENT_SIZE
    expected = bytes.fromhex("010000000000000015cd853dfe9c971710") + GID
    assert raw == expected
    assert decode_attachment(raw) == Attachment(1, 1700000000123456789, GID)


def test_round_trip_and_now() -> None:
    before = time.time_ns()
    att = decode_attachment(encode_attachment(42, None, GID))
    assert att.sequence_number == 42
    assert before <= att.source_timestamp <= time.time_ns()
    assert Attachment(7, 9, GID).encode() == encode_attachment(7, 9, GID)
    assert decode_attachment(memoryview(encode_attachment(3, 4, GID))).source_gid == GID


def test_legacy_format() -> None:
    raw = encode_legacy_attachment(5, 1700000000123456789, GID)
    assert len(raw) == LEGACY_ATTACHMENT_SIZE
    assert raw.startswith(bytes.fromhex("0f73657175656e63655f6e756d626572"))  # 0f "sequence_number"
    assert is_legacy_attachment(raw)
    assert not is_legacy_attachment(encode_attachment(5, 1, GID))
    assert decode_attachment(raw) == Attachment(5, 1700000000123456789, GID)


@pytest.mark.parametrize(
    "raw",
    [b"", b"\x00" * 32, b"\x00" * 16 + b"\x0f" + b"\x00" * 16, b"\x0f" + b"x" * 76, b"\x00" * 77],
)
def test_garbage_is_rejected(raw: bytes) -> None:
    with pytest.raises(ValueError, match="attachment"):
        decode_attachment(raw)


def test_gid_size_is_checked() -> None:
    with pytest.raises(ValueError, match="16 bytes"):
        encode_attachment(1, 1, b"short")
    with pytest.raises(ValueError, match="16 bytes"):
        Attachment(1, 1, b"\x00" * 15)


def test_negative_values_are_flagged() -> None:
    assert Attachment(1, 1, GID).is_valid
    assert not Attachment(-1, 1, GID).is_valid
    assert not Attachment(1, -1, GID).is_valid


def test_gid_from_token() -> None:
    # xxh3_128(key) stored low64 then high64, little-endian.
    gid = gid_from_token(TALKER_TOKEN)
    assert gid.hex() == "800ff240d6ceac8243e3d6d5a20c6459"
    assert len(gid) == 16
    assert gid_from_token(TALKER_TOKEN + "x") != gid
