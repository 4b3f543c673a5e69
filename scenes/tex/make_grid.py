#!/usr/bin/env python3
"""Writes grid.png, the bitmap texture of scenes/textured.yaml: a 256x256 8-bit RGB
image of light-grey 32-pixel cells separated by dark 2-pixel lines, with one red cell
at the top-left and one blue cell at the bottom-right so uv orientation is visible
(v = 0 is the bottom row). Standard library only (zlib + struct)."""
import struct
import sys
import zlib

SIZE, CELL, LINE = 256, 32, 2


def pixel(x, y):
    if x % CELL < LINE or y % CELL < LINE:
        return (40, 40, 40)
    cx, cy = x // CELL, y // CELL
    if (cx, cy) == (0, 0):
        return (200, 40, 30)
    if (cx, cy) == (SIZE // CELL - 1, SIZE // CELL - 1):
        return (30, 60, 200)
    return (200, 200, 200) if (cx + cy) % 2 == 0 else (170, 170, 170)


def chunk(kind, payload):
    body = kind + payload
    return struct.pack(">I", len(payload)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def png_bytes():
    rows = bytearray()
    for y in range(SIZE):
        rows.append(0)  # filter type 0 (None) for every scanline
        for x in range(SIZE):
            rows.extend(pixel(x, y))
    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)  # 8-bit RGB, no interlace
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(rows), 9))
            + chunk(b"IEND", b""))


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "grid.png"
    with open(out, "wb") as f:
        f.write(png_bytes())
