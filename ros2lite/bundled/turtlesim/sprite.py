"""How a turtle looks, for every view: a shell, a head, four legs, in metres around its
centre with the head along +x; rotate and place with `parts()`."""

from __future__ import annotations

import math

# shell colours of the twelve looks (one per ROS 2 release turtle, in spirit)
SHELLS = (
    (0x22, 0x8B, 0x22),
    (0x2E, 0x8B, 0x57),
    (0x6B, 0x8E, 0x23),
    (0x8B, 0x45, 0x13),
    (0x55, 0x6B, 0x2F),
    (0xA0, 0x52, 0x2D),
    (0x00, 0x80, 0x80),
    (0x80, 0x80, 0x00),
    (0x6A, 0x5A, 0xCD),
    (0xB8, 0x86, 0x0B),
    (0x3C, 0xB3, 0x71),
    (0xCD, 0x85, 0x3F),
)
SKIN = (0x9A, 0xCD, 0x32)


def _ellipse(cx: float, cy: float, rx: float, ry: float, n: int = 14) -> list[tuple[float, float]]:
    return [
        (cx + rx * math.cos(2 * math.pi * i / n), cy + ry * math.sin(2 * math.pi * i / n))
        for i in range(n)
    ]


# (polygon in metres, 'shell' or 'skin'), drawn in this order
SHAPE: tuple[tuple[list[tuple[float, float]], str], ...] = (
    (_ellipse(0.2, 0.24, 0.1, 0.07, 8), 'skin'),
    (_ellipse(0.2, -0.24, 0.1, 0.07, 8), 'skin'),
    (_ellipse(-0.2, 0.24, 0.1, 0.07, 8), 'skin'),
    (_ellipse(-0.2, -0.24, 0.1, 0.07, 8), 'skin'),
    ([(-0.32, 0.05), (-0.45, 0.0), (-0.32, -0.05)], 'skin'),
    (_ellipse(0.4, 0.0, 0.12, 0.1, 10), 'skin'),
    (_ellipse(0.0, 0.0, 0.34, 0.27, 16), 'shell'),
)


def colours(sprite: int) -> dict[str, tuple[int, int, int]]:
    """A turtle sprite's shell and skin colours."""
    return {'shell': SHELLS[sprite % len(SHELLS)], 'skin': SKIN}


def parts(
    x: float, y: float, theta: float, scale: float, height: float
) -> list[tuple[list[float], str]]:
    """The shape of a turtle at (x, y, theta), in screen pixels (y down): `scale` pixels per
    metre on a canvas `height` metres tall. Each part: flat [x0, y0, x1, y1, …] and its role."""
    cos, sin = math.cos(theta), math.sin(theta)
    out = []
    for points, role in SHAPE:
        flat: list[float] = []
        for px, py in points:
            wx = x + px * cos - py * sin
            wy = y + px * sin + py * cos
            flat += [wx * scale, (height - wy) * scale]
        out.append((flat, role))
    return out


def hex_colour(rgb: tuple[int, int, int]) -> str:
    """'#rrggbb' of a colour (what tkinter takes)."""
    r, g, b = rgb
    return f'#{r:02x}{g:02x}{b:02x}'
