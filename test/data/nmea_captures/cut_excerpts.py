#!/usr/bin/env python3
"""Cuts the excerpts in this folder from gpsd's regression logs (see ATTRIBUTION.md).

Usage: python3 cut_excerpts.py CAPTURES_DIR   (a folder of X.nmea + X.chk as described in ATTRIBUTION.md)

For each excerpt below, the listed line ranges (1-based, inclusive, lines split at '\\n' and kept
byte for byte with their '\\r') of X.nmea are written to X.nmea here, and the part of X.chk that
gpsd produced for them to X.chk: every echoed sentence of those lines and the JSON reports that
follow it, up to the echo of the first line after the range. Not run by the build or the tests.
"""
import os
import sys

# name: (line ranges, why it is here)
EXCERPTS = {
    "GPSmap-76S": ([(1, 26)], "simulator mode: GGA quality 8, RMC/GLL status V mode S"),
    "ais-nmea": ([(1, 30), (210, 225)], "AIS !AIVDM lines between NMEA; an epoch gpsd reports no TPV for"),
    "beidou-bd": ([(36, 73)], "BD talker, GNS, first fix; a line with a leading space"),
    "bu353-glonass": ([(38, 60)], "GNRMC with GPGGA and GPZDA; the fix is lost"),
    "cat-ms352": ([(1, 20)], "clean: GGA and RMC only"),
    "com-1289": ([(1, 30)], "GSV with a bad checksum"),
    "ericsson-gru04-02-70sec": ([(1, 31)], "position only in GNS and GLL; VTG knots 0.0 and km/h 0.1"),
    "foretrex-201": ([(50, 80)], "a line's tail without '$'; GGA quality 2 with 00 satellites"),
    "garmin15x": ([(1, 17)], "clean: Garmin proprietary PGRME/PGRMV/PGRMT"),
    "gp-320fw-2019-04-06-overflow": ([(1, 20)], "GLL before the first RMC (no date yet); week rollover date"),
    "gpsdf": ([(37, 100)], "blank lines; proprietary PGLOR with wrong checksums; IMGSA"),
    "holux-gm-210": ([(28, 41)], "no fix; truncated last sentence"),
    "iTrek": ([(1, 20)], "two logs joined (time jumps back); malformed GSA; RMC V"),
    "jl-micro-jlt": ([(1, 13)], "clean: GNGGA with a lock state as quality"),
    "meinberg-gps164": ([(15, 30)], "RMC only, 2-decimal minutes; status A to V"),
    "mtk-3301": ([(1, 43)], "cold start: 8960.000000,N placeholders, 1980 dates, $POLYN without checksum"),
    "neo-m8n": ([(1, 30)], "gpsd adds 1024 weeks to the 2015 date"),
    "nmea-fuzzy-cases": ([(1, 28)], "clean: 8-decimal minutes, GP and GN talkers"),
    "polarx2": ([(1, 20)], "GNS, GBS, GRS, GST, ZDA, GLL; empty course at standstill"),
    "quectel-eg25-g": ([(314, 353)], "first fix: GPGGA counts 3 satellites, GNGNS 8; PQGSV"),
    "saab-r4": ([(1, 30)], "GGA without its trailing fields; AIS !AIVDO/!AIVDM; HDT, ROT, DTM"),
    "skytraq-dgps": ([(1, 24)], "clean: DGPS with GST and ZDA"),
    "st-teseo-liv4f": ([(1, 24), (318, 330)], "every line starts with \"$$\"; GSV with a bad checksum"),
    "telit-pls83-w": ([(1, 31)], "GP/GA/GN talkers per epoch (satellites per constellation); \\r\\r\\n"),
    "tomtom-mkII": ([(13, 24), (60, 67)], "status A to V; a stray 'r' before '$'"),
    "ublox-8": ([(1, 25)], "binary UBX bytes before the first sentence"),
    "ublox-neo-m9n-nmea": ([(1, 26)], "clean: four GNSS, GST, GBS, ZDA"),
}


def normalise(line):
    text = line.rstrip(b"\r\n").strip()
    while text.startswith(b"$$"):
        text = text[1:]
    return text


def cut(source, name, ranges, target):
    lines = open(os.path.join(source, name + ".nmea"), "rb").read().split(b"\n")
    chk = open(os.path.join(source, name + ".chk"), "rb").read().split(b"\n")
    # Which input line each echoed sentence of the .chk is (gpsd echoes what it accepted, in
    # order, sometimes shortened).
    echo_of_line = {}
    at = 0
    for index, text in enumerate(chk):
        if not text[:1] in (b"$", b"!"):
            continue
        for candidate in range(at, min(at + 200, len(lines))):
            if normalise(lines[candidate]).startswith(text.rstrip(b"\r")):
                echo_of_line[candidate] = index
                at = candidate + 1
                break
    nmea, chk_out = b"", []
    for first, last in ranges:
        for i in range(first - 1, min(last, len(lines))):
            nmea += lines[i] + (b"\n" if i < len(lines) - 1 else b"")  # the file's own ending
        echoed = [echo_of_line[i] for i in range(first - 1, last) if i in echo_of_line]
        after = [echo_of_line[i] for i in sorted(echo_of_line) if i >= last]
        if echoed:
            chk_out += chk[echoed[0]:after[0] if after else len(chk)]
    open(os.path.join(target, name + ".nmea"), "wb").write(nmea)
    text = b"\n".join(line for line in chk_out if line) + b"\n"
    open(os.path.join(target, name + ".chk"), "wb").write(text)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    target = os.path.dirname(os.path.abspath(__file__))
    for name, (ranges, _) in EXCERPTS.items():
        cut(sys.argv[1], name, ranges, target)


if __name__ == "__main__":
    main()
