#!/usr/bin/env python3
"""Pixel bytes of uncompressed EXRs, compared bit for bit (header metadata such as the render
time or host does not count; the parsing is bench/image_identity.sh's).
  exr_pixels.py compare DIR_A DIR_B   every *.exr of A has the same pixel bytes in B (exit 1 if not)
  exr_pixels.py flip-bit FILE.exr     flips one bit of the last pixel chunk (for self-tests)
"""
import os
import struct
import sys


def pixel_offset(data):
    """Offset of the first pixel chunk: after the header attributes, their null byte and the
    offset table (uncompressed EXRs have one chunk a scan line, 8 bytes each in the table)."""
    p, lines = 8, None
    while data[p] != 0:
        n = data.index(b"\0", p)
        t = data.index(b"\0", n + 1)
        (size,) = struct.unpack("<i", data[t + 1:t + 5])
        if data[p:n] == b"dataWindow":
            _, y0, _, y1 = struct.unpack("<4i", data[t + 5:t + 21])
            lines = y1 - y0 + 1
        p = t + 5 + size
    if lines is None:
        raise ValueError("no dataWindow attribute")
    return p + 1 + 8 * lines


def pixels(path):
    data = open(path, "rb").read()
    return data[pixel_offset(data):]


def compare(a, b):
    names = sorted(f for f in os.listdir(a) if f.endswith(".exr"))
    bad = 0
    for f in names:
        other = os.path.join(b, f)
        if not os.path.exists(other):
            print("missing in %s: %s" % (b, f))
            bad += 1
        elif pixels(os.path.join(a, f)) != pixels(other):
            print("differs: %s" % f)
            bad += 1
    print("%d frames compared, %d differ or are missing" % (len(names), bad))
    return 1 if bad or not names else 0


def flip_bit(path):
    data = bytearray(open(path, "rb").read())
    data[-1] ^= 1  # the last byte is pixel data: the last channel of the last scan line
    open(path, "wb").write(data)
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    if len(sys.argv) == 3 and sys.argv[1] == "flip-bit":
        sys.exit(flip_bit(sys.argv[2]))
    sys.stderr.write(__doc__)
    sys.exit(2)
