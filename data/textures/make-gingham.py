#!/usr/bin/env python3
"""Writes gingham.png: the project's own red-and-white gingham, one repeat.

A 64 x 64 RGB image: a red band 32 pixels wide across the top half and one
down the left half, over white; where they cross the red is full, where one
band lies alone it is half-strength (a woven gingham's three tones). Tiled,
it is a 2 x 2 check per repeat; the document's SCALE2D says how many metres
of fabric one repeat covers. Python standard library only (zlib); the bytes
are the same on every run.

    python3 data/textures/make-gingham.py data/textures/gingham.png
"""
import struct
import sys
import zlib

SIZE, BAND = 64, 32
WHITE, HALF, RED = (246, 244, 238), (214, 134, 140), (178, 34, 52)


def pixel(x, y):
    bands = (x < BAND) + (y < BAND)
    return (WHITE, HALF, RED)[bands]


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def png():
    rows = b"".join(b"\0" + bytes(c for x in range(SIZE) for c in pixel(x, y)) for y in range(SIZE))
    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)  # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) +
            chunk(b"IEND", b""))


if __name__ == "__main__":
    with open(sys.argv[1] if len(sys.argv) > 1 else "gingham.png", "wb") as f:
        f.write(png())
