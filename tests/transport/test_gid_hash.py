"""The GID hash (XXH3-128 from the `xxhash` package) against vectors produced by the reference
implementation (xxhash 0.8, seed 0), and the GID rmw_zenoh derives from it.

Inputs are ``bytes((i * 7 + 3) % 251 for i in range(n))`` so every length class of the
algorithm (0, 1-3, 4-8, 9-16, 17-128, 129-240, >240 incl. more than one 1024-byte block)
is covered.
"""

from __future__ import annotations

import pytest
import xxhash

from ros2lite.transport.attachment import gid_from_token


def xxh3_128_hexdigest(data: bytes) -> str:
    return xxhash.xxh3_128_hexdigest(data)


PATTERN_VECTORS = {
    0: "99aa06d3014798d86001c324468d497f",
    1: "22bbb76b211a39ba13e608bc156defed",
    2: "a6b9dd53b14487221c9074b93943b86c",
    3: "ce31763cbf8245a5a9088dda485b481c",
    4: "47197970590746b1788a609154b0fe20",
    7: "a051eefb8df8740e7af1e487627dd4bc",
    8: "e3bc8a5f461715553cd024e3d63a1588",
    9: "c72c88247a9a56d7eafab1c7f123109f",
    15: "68f75783c1d1a650c30b29715d7282a3",
    16: "ce0b9647ab24f88460d75c5e47d40a24",
    17: "bfd327edcc2fbd12eeed7654312a26d7",
    64: "535e7888f9116d98dc2d589f4a9d3f1a",
    100: "6d8810f455fc234be2686bc5df2074cc",
    128: "a04233e3c9599748ef7e4d57ed67de26",
    129: "6e83694c09641bb7a28da26446fd5ab0",
    200: "4093d6e3aba36a2cecc6481fa3516bc5",
    240: "9a8457fec9cfea5e2288b3c22f48dea4",
    241: "07870750a974395682b1de299f6e411e",
    1024: "f96a1bbdb2fef572f75e768c7cdd54b2",
    1025: "2b5651dd466531ba667a5eabe344e5df",
    2500: "37ed47ddb294ac3b93e751d9f3daad9b",
}

TEXT_VECTORS = {
    b"": "99aa06d3014798d86001c324468d497f",
    b"a": "a96faf705af16834e6c632b61e964e1f",
    b"abc": "06b05ab6733a618578af5f94892f3950",
    b"hello world": "df8d09e93f874900a99b8775cc15b6c7",
}


def pattern(n: int) -> bytes:
    return bytes((i * 7 + 3) % 251 for i in range(n))


@pytest.mark.parametrize(("length", "expected"), sorted(PATTERN_VECTORS.items()))
def test_pattern_vectors(length: int, expected: str) -> None:
    assert xxh3_128_hexdigest(pattern(length)) == expected


@pytest.mark.parametrize(("data", "expected"), sorted(TEXT_VECTORS.items()))
def test_text_vectors(data: bytes, expected: str) -> None:
    assert xxh3_128_hexdigest(data) == expected


def test_gid_is_the_little_endian_hash_of_the_token() -> None:
    token = "@ros2_lv/0/aac3178e146ba6f1fc6e6a4085e77f21/0/10/MS/%/%/listener/%chatter"
    value = int(xxh3_128_hexdigest(token.encode()), 16)
    assert gid_from_token(token) == value.to_bytes(16, "little")
