#!/usr/bin/env python3
"""Writes the IES LM-63 test files of tests/lights/ies_test.cpp from closed-form distributions.

revision_*.ies: one type C table, bilateral about the 0-180 plane,
    I(gamma, C) = 200 cos(gamma) (1 + 0.5 cos C) + 50 cd, gamma 0..90 by 30, C 0..180 by 90,
    written in each published revision of LM-63 (1986, 1991, 1995, 2002, 2019) with that
    revision's label lines. The 1986 file stores 2 I with a ballast-lamp photometric factor of
    0.5 and separates numbers by commas; the 2019 file's third factor is a file generation type
    code (1.00010), which is not a multiplier.
tilt_include.ies, tilt_file.ies + vertical_lamp.tlt: the 2002 table with lamp-to-luminaire
    geometry 1 and multipliers 0.8, 0.9, 0.6 at tilts 0, 45, 90 degrees (inline and in a file).
mirror_90_270.ies, full_0_360.ies: I(gamma, C) = (300 cos gamma + 20)(1 + 0.5 sin C + 0.2 cos 2C),
    symmetric about the 90-270 plane (sin(180 - C) = sin C, cos 2(180 - C) = cos 2C), stored over
    C 90..270 by 30 and over 0..360 by 30.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def table(fn, vertical, horizontal, scale=1.0, sep=" "):
    rows = []
    for c in horizontal:
        rows.append(sep.join("%.4f" % (scale * fn(g, c)) for g in vertical))
    return rows


def write(name, lines):
    with open(os.path.join(HERE, name), "w", newline="\r\n") as f:
        f.write("\n".join(lines) + "\n")


def bilateral(g, c):
    return 200.0 * math.cos(math.radians(g)) * (1.0 + 0.5 * math.cos(math.radians(c))) + 50.0


V = [0, 30, 60, 90]
H = [0, 90, 180]
ANGLES = ["0 30 60 90", "0 90 180"]


def data(first, second="1.0", tilt="TILT=NONE", scale=1.0, sep=" "):
    return [tilt, f"1{sep}1000{sep}1.0{sep}4{sep}3{sep}1{sep}2{sep}0.1{sep}0.2{sep}0.0",
            f"1.0{sep}{second}{sep}40"] + [a.replace(" ", sep) for a in ANGLES] + \
        table(bilateral, V, H, scale, sep)


write("revision_1986.ies",
      ["ACME LIGHTING 1986 TEST REPORT 1234", "Bilateral wall washer, clear lens",
       "Lamp: 100 W incandescent"] + data(None, second="0.5", scale=2.0, sep=","))
write("revision_1991.ies",
      ["IESNA91", "[TEST] 1234", "[MANUFAC] ACME LIGHTING", "free text a 1991 writer left here"]
      + data(None))
write("revision_1995.ies",
      ["IESNA:LM-63-1995", "[TEST] 1234", "[MANUFAC] ACME LIGHTING", "[LUMINAIRE] wall washer",
       "[MORE] clear lens"] + data(None))
write("revision_2002.ies",
      ["IESNA:LM-63-2002", "[TEST] 1234", "[TESTLAB] ACME LAB", "[MANUFAC] ACME LIGHTING"]
      + data(None))
write("revision_2019.ies",
      ["IES:LM-63-2019", "[TEST] 1234", "[TESTLAB] ACME LAB", "[ISSUEDATE] 2026-11-30",
       "[MANUFAC] ACME LIGHTING"] + data(None, second="1.00010"))

TILT_BLOCK = ["1", "3", "0 45 90", "0.8 0.9 0.6"]
write("tilt_include.ies",
      ["IESNA:LM-63-2002", "[TEST] tilt", "TILT=INCLUDE"] + TILT_BLOCK + data(None)[1:])
write("tilt_file.ies", ["IESNA:LM-63-2002", "[TEST] tilt file", "TILT=vertical_lamp.tlt"]
      + data(None)[1:])
write("vertical_lamp.tlt", TILT_BLOCK)


def mirrored(g, c):
    c = math.radians(c)
    return (300.0 * math.cos(math.radians(g)) + 20.0) * (1.0 + 0.5 * math.sin(c) + 0.2 * math.cos(2 * c))


VM = [0, 22.5, 45, 67.5, 90]
for name, hs in (("mirror_90_270.ies", list(range(90, 271, 30))),
                 ("full_0_360.ies", list(range(0, 361, 30)))):
    write(name, ["IESNA:LM-63-2002", "[TEST] %s" % name, "TILT=NONE",
                 "1 -1 1.0 %d %d 1 2 0 0 0" % (len(VM), len(hs)), "1.0 1.0 30",
                 " ".join("%g" % g for g in VM), " ".join("%d" % c for c in hs)]
          + table(mirrored, VM, hs))
