"""Screenshots of a virtual X display, read without extra packages: `xwd` writes the root
window, this reads its pixels (and can save a PNG to look at)."""

from __future__ import annotations

import shutil
import struct
import subprocess
import zlib
from dataclasses import dataclass


@dataclass
class Image:
    width: int
    height: int
    rgb: bytes  # 3 bytes a pixel, rows top to bottom

    def pixel(self, x: int, y: int) -> tuple[int, int, int]:
        i = (y * self.width + x) * 3
        return (self.rgb[i], self.rgb[i + 1], self.rgb[i + 2])

    def count(self, colour: tuple[int, int, int], box: tuple[int, int, int, int]) -> int:
        """Pixels of exactly `colour` inside box (left, top, right, bottom; exclusive)."""
        left, top, right, bottom = box
        want = bytes(colour)
        n = 0
        for y in range(top, bottom):
            row = self.rgb[(y * self.width + left) * 3 : (y * self.width + right) * 3]
            n += sum(1 for i in range(0, len(row), 3) if row[i : i + 3] == want)
        return n

    def save_png(self, path: str) -> None:
        raw = b''.join(
            b'\0' + self.rgb[y * self.width * 3 : (y + 1) * self.width * 3]
            for y in range(self.height)
        )

        def chunk(kind: bytes, data: bytes) -> bytes:
            body = kind + data
            return struct.pack('>I', len(data)) + body + struct.pack('>I', zlib.crc32(body))

        header = struct.pack('>IIBBBBB', self.width, self.height, 8, 2, 0, 0, 0)
        with open(path, 'wb') as f:
            f.write(b'\x89PNG\r\n\x1a\n')
            f.write(chunk(b'IHDR', header) + chunk(b'IDAT', zlib.compress(raw)))
            f.write(chunk(b'IEND', b''))


def parse_xwd(data: bytes) -> Image:
    """A TrueColor XWD image (what `xwd -root` gives on a 24-bit Xvfb screen)."""
    fields = struct.unpack('>25I', data[:100])
    header_size, _, _, _, width, height, _, byte_order = fields[:8]
    bits_per_pixel, bytes_per_line = fields[11], fields[12]
    red_mask, green_mask, blue_mask = fields[14:17]
    ncolors = fields[19]
    assert bits_per_pixel == 32, f'expected a 32-bit image, got {bits_per_pixel}'
    offset = header_size + 12 * ncolors
    order = '<' if byte_order == 0 else '>'
    shifts = [(mask, (mask & -mask).bit_length() - 1) for mask in (red_mask, green_mask, blue_mask)]
    out = bytearray(width * height * 3)
    for y in range(height):
        row = data[offset + y * bytes_per_line : offset + y * bytes_per_line + width * 4]
        values = struct.unpack(f'{order}{width}I', row)
        base = y * width * 3
        for x, v in enumerate(values):
            i = base + 3 * x
            out[i] = (v & shifts[0][0]) >> shifts[0][1]
            out[i + 1] = (v & shifts[1][0]) >> shifts[1][1]
            out[i + 2] = (v & shifts[2][0]) >> shifts[2][1]
    return Image(width, height, bytes(out))


def screenshot(display: str) -> Image:
    xwd = shutil.which('xwd')
    assert xwd, 'xwd is not installed'
    data = subprocess.run(
        [xwd, '-root', '-silent', '-display', display], capture_output=True, check=True
    ).stdout
    return parse_xwd(data)
