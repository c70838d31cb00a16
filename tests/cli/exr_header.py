#!/usr/bin/env python3
"""Reads what the CLI tests check in an OpenEXR file's header, without OpenEXR.

usage: exr_header.py FILE FIELD...   prints the fields joined by ";" on one line, where FIELD is
  channels        the channel names of the chlist attribute, comma-separated, in file order
  channel-types   "name:type" for each channel (uint, half, float), sorted as text
  attr:NAME       the value of attribute NAME ("-" if absent): strings as text, int and float
                  attributes as numbers
  attr-names:PREFIX  the names of the attributes starting with PREFIX, sorted, comma-separated

Layout (OpenEXR file layout, single-part scan-line file): the magic 76 2f 31 01 and a 4-byte
version, then attributes as name\\0 type\\0 int32 size, value, ended by a 0 byte; a chlist value
is, per channel, name\\0 then int32 pixel type, uint8 pLinear, 3 reserved bytes and two int32
sampling factors (16 bytes), ended by a 0 byte.
"""
import struct
import sys

PIXEL_TYPES = {0: "uint", 1: "half", 2: "float"}


def read_attributes(path):
    """Returns {name: (type, raw value bytes)} of the header."""
    data = open(path, "rb").read()
    if data[:4] != b"\x76\x2f\x31\x01":
        sys.exit("%s: not an EXR file" % path)
    attributes, p = {}, 8
    while data[p] != 0:
        name_end = data.index(b"\0", p)
        type_end = data.index(b"\0", name_end + 1)
        (size,) = struct.unpack("<i", data[type_end + 1:type_end + 5])
        value = data[type_end + 5:type_end + 5 + size]
        attributes[data[p:name_end].decode()] = (data[name_end + 1:type_end].decode(), value)
        p = type_end + 5 + size
    return attributes


def channels(attributes):
    """[(name, pixel type name)] of the chlist attribute, in file order."""
    value, result, q = attributes["channels"][1], [], 0
    while value[q] != 0:
        e = value.index(b"\0", q)
        (pixel_type,) = struct.unpack("<i", value[e + 1:e + 5])
        result.append((value[q:e].decode(), PIXEL_TYPES[pixel_type]))
        q = e + 1 + 16
    return result


def attribute(attributes, name):
    if name not in attributes:
        return "-"
    kind, value = attributes[name]
    if kind == "int":
        return str(struct.unpack("<i", value)[0])
    if kind == "float":
        return repr(struct.unpack("<f", value)[0])
    if kind == "double":
        return repr(struct.unpack("<d", value)[0])
    return value.decode()


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    attributes = read_attributes(sys.argv[1])
    fields = []
    for field in sys.argv[2:]:
        if field == "channels":
            fields.append(",".join(name for name, _ in channels(attributes)))
        elif field == "channel-types":
            fields.append(",".join(sorted("%s:%s" % c for c in channels(attributes))))
        elif field.startswith("attr-names:"):
            prefix = field[len("attr-names:"):]
            fields.append(",".join(sorted(n for n in attributes if n.startswith(prefix))))
        elif field.startswith("attr:"):
            fields.append(attribute(attributes, field[len("attr:"):]))
        else:
            sys.exit("unknown field %r\n%s" % (field, __doc__))
    print(";".join(fields))


if __name__ == "__main__":
    main()
