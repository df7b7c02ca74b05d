"""``ROS_DOMAIN_ID`` as rcl reads it: one reading for the transport, security and doctor, so
a node never joins one domain while its permissions are checked for another."""

from __future__ import annotations

__all__ = ['DDS_MAX_DOMAIN_ID', 'parse_domain_id']

# DDS maps a domain to UDP ports and so ends at 232; rmw_zenoh only writes the number into keys
DDS_MAX_DOMAIN_ID = 232
_ULONG_MAX = 2**64 - 1
_DIGITS = "0123456789abcdefghijklmnopqrstuvwxyz"


def parse_domain_id(raw: str) -> int:
    """A ``ROS_DOMAIN_ID`` value as rcl takes it: C's ``strtoul(raw, &end, 0)`` (leading
    blanks, a sign, ``0x`` hex, ``0`` octal), refused only when it reads as 0 with
    characters left over or overflows 64 bits; so ``010`` is 8, ``0x2b`` is 43 and ``43abc``
    is 43, as for every rcl node. rmw_zenoh takes any such value (no DDS limit of 232), and
    reads rcl's "default" (SIZE_MAX, which ``-1`` gives) as domain 0."""
    if raw == "":
        return 0
    text = raw.lstrip(" \t\n\v\f\r")
    negative = text[:1] == "-"
    if text[:1] in "+-" and text:
        text = text[1:]
    base = 10
    if text[:2].lower() == "0x" and text[2:3].lower() in _DIGITS[:16] and text[2:3]:
        base, text = 16, text[2:]
    elif text[:1] == "0":
        base = 8
    digits = 0
    while digits < len(text) and text[digits].lower() in _DIGITS[:base]:
        digits += 1
    number = int(text[:digits], base) if digits else 0
    # strtoul leaves `end` at the start when it read no digit at all
    rest = text[digits:] if digits else raw
    if number == 0 and rest:
        raise ValueError(f"ROS_DOMAIN_ID is not an integral number: {raw!r}")
    if number > _ULONG_MAX:
        raise ValueError(f"ROS_DOMAIN_ID is out of range: {raw!r}")
    if negative:
        number = (-number) & _ULONG_MAX
    return 0 if number == _ULONG_MAX else number
