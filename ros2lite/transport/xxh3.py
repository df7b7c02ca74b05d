"""Pure-Python XXH3-128 (seed 0, default secret).

rmw_zenoh derives publisher and client GIDs from the XXH3-128 hash of the
liveliness key.  We only hash one short string per endpoint creation, so a
slow but dependency-free implementation is the right trade-off: no compiled
``xxhash`` wheel is needed.  Written from the public XXH3 specification; the
tests pin it to vectors produced by the reference implementation for every
length class (0, 1-3, 4-8, 9-16, 17-128, 129-240 and >240 bytes).
"""

from __future__ import annotations

__all__ = ["xxh3_128", "xxh3_128_digest", "xxh3_128_hexdigest"]

_M64 = (1 << 64) - 1
_M32 = (1 << 32) - 1

_P32_1 = 0x9E3779B1
_P32_2 = 0x85EBCA77
_P32_3 = 0xC2B2AE3D
_P64_1 = 0x9E3779B185EBCA87
_P64_2 = 0xC2B2AE3D27D4EB4F
_P64_3 = 0x165667B19E3779F9
_P64_4 = 0x85EBCA77C2B2AE63
_P64_5 = 0x27D4EB2F165667C5
_PMX_1 = 0x165667919E3779F9
_PMX_2 = 0x9FB21C651E98DF25

# The 192-byte default secret of XXH3.
_SECRET = bytes.fromhex(
    "b8fe6c3923a44bbe7c01812cf721ad1cded46de9839097db7240a4a4b7b3671f"
    "cb79e64eccc0e578825ad07dccff7221b8084674f743248ee03590e6813a264c"
    "3c2852bb91c300cb88d0658b1b532ea371644897a20df94e3819ef46a9deacd8"
    "a8fa763fe39c343ff9dcbbc7c70b4f1d8a51e04bcdb45931c89f7ec9d9787364"
    "eac5ac8334d3ebc3c581a0fffa1363eb170ddd51b7f0da49d316552629d4689e"
    "2b16be587d47a1fc8ff8b8d17ad031ce45cb3a8f95160428afd7fbcabb4b407e"
)
_SECRET_SIZE = len(_SECRET)
_STRIPE_LEN = 64
_SECRET_CONSUME_RATE = 8
_ACC_NB = 8
_MIDSIZE_START_OFFSET = 3
_MIDSIZE_LAST_OFFSET = 17
_SECRET_SIZE_MIN = 136
_SECRET_LASTACC_START = 7
_SECRET_MERGEACCS_START = 11


def _r64(buf: bytes, off: int) -> int:
    return int.from_bytes(buf[off : off + 8], "little")


def _r32(buf: bytes, off: int) -> int:
    return int.from_bytes(buf[off : off + 4], "little")


def _swap32(x: int) -> int:
    return int.from_bytes((x & _M32).to_bytes(4, "little"), "big")


def _swap64(x: int) -> int:
    return int.from_bytes((x & _M64).to_bytes(8, "little"), "big")


def _rotl32(x: int, r: int) -> int:
    x &= _M32
    return ((x << r) | (x >> (32 - r))) & _M32


def _xxh64_avalanche(h: int) -> int:
    h ^= h >> 33
    h = (h * _P64_2) & _M64
    h ^= h >> 29
    h = (h * _P64_3) & _M64
    return h ^ (h >> 32)


def _xxh3_avalanche(h: int) -> int:
    h ^= h >> 37
    h = (h * _PMX_1) & _M64
    return h ^ (h >> 32)


def _mul128_fold64(a: int, b: int) -> int:
    p = (a & _M64) * (b & _M64)
    return (p & _M64) ^ (p >> 64)


def _mix16(data: bytes, off: int, s_off: int) -> int:
    lo = _r64(data, off) ^ _r64(_SECRET, s_off)
    hi = _r64(data, off + 8) ^ _r64(_SECRET, s_off + 8)
    return _mul128_fold64(lo, hi)


def _mix32(acc: list[int], data: bytes, off1: int, off2: int, s_off: int) -> None:
    """Fold two 16-byte lanes into the (low, high) accumulator pair."""
    acc[0] = (acc[0] + _mix16(data, off1, s_off)) & _M64
    acc[0] ^= (_r64(data, off2) + _r64(data, off2 + 8)) & _M64
    acc[1] = (acc[1] + _mix16(data, off2, s_off + 16)) & _M64
    acc[1] ^= (_r64(data, off1) + _r64(data, off1 + 8)) & _M64


def _len_0() -> tuple[int, int]:
    low = _xxh64_avalanche(_r64(_SECRET, 64) ^ _r64(_SECRET, 72))
    high = _xxh64_avalanche(_r64(_SECRET, 80) ^ _r64(_SECRET, 88))
    return low, high


def _len_1to3(data: bytes) -> tuple[int, int]:
    n = len(data)
    c1, c2, c3 = data[0], data[n >> 1], data[n - 1]
    combined_l = (c1 << 16) | (c2 << 24) | c3 | (n << 8)
    combined_h = _rotl32(_swap32(combined_l), 13)
    flip_l = _r32(_SECRET, 0) ^ _r32(_SECRET, 4)
    flip_h = _r32(_SECRET, 8) ^ _r32(_SECRET, 12)
    return _xxh64_avalanche(combined_l ^ flip_l), _xxh64_avalanche(combined_h ^ flip_h)


def _len_4to8(data: bytes) -> tuple[int, int]:
    n = len(data)
    in64 = (_r32(data, 0) + (_r32(data, n - 4) << 32)) & _M64
    flip = _r64(_SECRET, 16) ^ _r64(_SECRET, 24)
    prod = (in64 ^ flip) * ((_P64_1 + (n << 2)) & _M64)
    low, high = prod & _M64, prod >> 64
    high = (high + (low << 1)) & _M64
    low ^= high >> 3
    low ^= low >> 35
    low = (low * _PMX_2) & _M64
    low ^= low >> 28
    return low, _xxh3_avalanche(high)


def _len_9to16(data: bytes) -> tuple[int, int]:
    n = len(data)
    flip_l = _r64(_SECRET, 32) ^ _r64(_SECRET, 40)
    flip_h = _r64(_SECRET, 48) ^ _r64(_SECRET, 56)
    in_lo = _r64(data, 0)
    in_hi = _r64(data, n - 8)
    prod = (in_lo ^ in_hi ^ flip_l) * _P64_1
    m_low, m_high = prod & _M64, prod >> 64
    m_low = (m_low + ((n - 1) << 54)) & _M64
    in_hi ^= flip_h
    m_high = (m_high + in_hi + (in_hi & _M32) * (_P32_2 - 1)) & _M64
    m_low ^= _swap64(m_high)
    prod = m_low * _P64_2
    h_low, h_high = prod & _M64, prod >> 64
    h_high = (h_high + m_high * _P64_2) & _M64
    return _xxh3_avalanche(h_low), _xxh3_avalanche(h_high)


def _finish_mid(acc: list[int], n: int) -> tuple[int, int]:
    low = (acc[0] + acc[1]) & _M64
    high = (acc[0] * _P64_1 + acc[1] * _P64_4 + n * _P64_2) & _M64
    return _xxh3_avalanche(low), (-_xxh3_avalanche(high)) & _M64


def _len_17to128(data: bytes) -> tuple[int, int]:
    n = len(data)
    acc = [(n * _P64_1) & _M64, 0]
    for i in range((n - 1) // 32, -1, -1):
        _mix32(acc, data, 16 * i, n - 16 * (i + 1), 32 * i)
    return _finish_mid(acc, n)


def _len_129to240(data: bytes) -> tuple[int, int]:
    n = len(data)
    acc = [(n * _P64_1) & _M64, 0]
    for i in range(4):
        _mix32(acc, data, 32 * i, 32 * i + 16, 32 * i)
    acc = [_xxh3_avalanche(acc[0]), _xxh3_avalanche(acc[1])]
    for i in range(4, n // 32):
        _mix32(acc, data, 32 * i, 32 * i + 16, _MIDSIZE_START_OFFSET + 32 * (i - 4))
    _mix32(acc, data, n - 16, n - 32, _SECRET_SIZE_MIN - _MIDSIZE_LAST_OFFSET - 16)
    return _finish_mid(acc, n)


def _accumulate_512(acc: list[int], data: bytes, off: int, s_off: int) -> None:
    for i in range(_ACC_NB):
        value = _r64(data, off + 8 * i)
        key = value ^ _r64(_SECRET, s_off + 8 * i)
        acc[i ^ 1] = (acc[i ^ 1] + value) & _M64
        acc[i] = (acc[i] + (key & _M32) * (key >> 32)) & _M64


def _scramble(acc: list[int], s_off: int) -> None:
    for i in range(_ACC_NB):
        a = acc[i]
        a ^= a >> 47
        a ^= _r64(_SECRET, s_off + 8 * i)
        acc[i] = (a * _P32_1) & _M64


def _merge(acc: list[int], s_off: int, start: int) -> int:
    result = start & _M64
    for i in range(4):
        result += _mul128_fold64(
            acc[2 * i] ^ _r64(_SECRET, s_off + 16 * i),
            acc[2 * i + 1] ^ _r64(_SECRET, s_off + 16 * i + 8),
        )
    return _xxh3_avalanche(result & _M64)


def _long(data: bytes) -> tuple[int, int]:
    n = len(data)
    acc = [_P32_3, _P64_1, _P64_2, _P64_3, _P64_4, _P32_2, _P64_5, _P32_1]
    stripes_per_block = (_SECRET_SIZE - _STRIPE_LEN) // _SECRET_CONSUME_RATE
    block_len = _STRIPE_LEN * stripes_per_block
    nb_blocks = (n - 1) // block_len
    for b in range(nb_blocks):
        for s in range(stripes_per_block):
            _accumulate_512(acc, data, b * block_len + s * _STRIPE_LEN, s * _SECRET_CONSUME_RATE)
        _scramble(acc, _SECRET_SIZE - _STRIPE_LEN)
    nb_stripes = ((n - 1) - block_len * nb_blocks) // _STRIPE_LEN
    tail = nb_blocks * block_len
    for s in range(nb_stripes):
        _accumulate_512(acc, data, tail + s * _STRIPE_LEN, s * _SECRET_CONSUME_RATE)
    _accumulate_512(acc, data, n - _STRIPE_LEN, _SECRET_SIZE - _STRIPE_LEN - _SECRET_LASTACC_START)
    low = _merge(acc, _SECRET_MERGEACCS_START, n * _P64_1)
    high = _merge(acc, _SECRET_SIZE - _STRIPE_LEN - _SECRET_MERGEACCS_START, ~(n * _P64_2))
    return low, high


def _parts(data: bytes) -> tuple[int, int]:
    n = len(data)
    if n == 0:
        return _len_0()
    if n <= 3:
        return _len_1to3(data)
    if n <= 8:
        return _len_4to8(data)
    if n <= 16:
        return _len_9to16(data)
    if n <= 128:
        return _len_17to128(data)
    if n <= 240:
        return _len_129to240(data)
    return _long(data)


def xxh3_128(data: bytes | bytearray | memoryview) -> int:
    """XXH3-128 of ``data`` as an int: ``high64 << 64 | low64`` (like xxhash's intdigest)."""
    low, high = _parts(bytes(data))
    return (high << 64) | low


def xxh3_128_digest(data: bytes | bytearray | memoryview) -> bytes:
    """The canonical (big-endian) 16-byte representation."""
    return xxh3_128(data).to_bytes(16, "big")


def xxh3_128_hexdigest(data: bytes | bytearray | memoryview) -> str:
    """The canonical hex string, e.g. ``99aa06d3014798d86001c324468d497f`` for ``b""``."""
    return xxh3_128_digest(data).hex()

