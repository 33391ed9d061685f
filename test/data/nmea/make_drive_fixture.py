#!/usr/bin/env python3
"""Writes drive_10s.nmea: 10 s of a u-blox-like receiver at 10 Hz (talker GN; RMC, VTG, GGA,
GSA, GST, ZDA per epoch), driving north-east at 10 m/s + 0.5 m/s^2 from 2020-10-27 10:15:30 UTC.
The first 3 epochs have no date yet (RMC date empty, ZDA without date), as a receiver at
start-up; epoch 50 has one line with a corrupted checksum and a few stray bytes before it.
Expected content (used by the tests): 100 epochs -> 100 fixes, 97 with a date."""
import math
from functools import reduce

def sentence(body):
    return "$%s*%02X" % (body, reduce(lambda a, c: a ^ ord(c), body, 0))

def angle(deg, width, pos, neg):
    units = round(abs(deg) * 60 * 1e5)
    return "%0*d%02d.%05d,%s" % (width, units // 6000000, (units % 6000000) // 100000, units % 100000,
                                 pos if deg >= 0 else neg)

LAT0, LON0, R = 45.1300, 8.4500, 6378137.0
lines = []
for k in range(100):
    t = 0.1 * k
    s = 10.0 * t + 0.25 * t * t
    v = 10.0 + 0.5 * t
    north = east = s / math.sqrt(2)
    lat = LAT0 + math.degrees(north / R)
    lon = LON0 + math.degrees(east / (R * math.cos(math.radians(LAT0))))
    cs = round((10 * 3600 + 15 * 60 + 30 + t) * 100)
    hms = "%02d%02d%02d.%02d" % (cs // 360000, cs // 6000 % 60, cs // 100 % 60, cs % 100)
    dated = k >= 3
    pos = angle(lat, 2, "N", "S") + "," + angle(lon, 3, "E", "W")
    epoch = [
        "GNRMC,%s,A,%s,%.3f,45.00,%s,,,A,V" % (hms, pos, v * 3600 / 1852, "271020" if dated else ""),
        "GNVTG,45.00,T,,M,%.3f,N,%.3f,K,A" % (v * 3600 / 1852, v * 3.6),
        "GNGGA,%s,%s,1,12,0.80,%.1f,M,47.3,M,," % (hms, pos, 150.0 + 0.1 * k),
        "GNGSA,A,3,05,13,15,18,20,23,24,,,,,,1.40,0.80,1.10,1",
        "GNGST,%s,12,0.85,0.62,45.1,0.70,0.60,1.20" % hms,
        "GNZDA,%s,%s,00,00" % (hms, "27,10,2020" if dated else ",,"),
    ]
    text = [sentence(b) for b in epoch]
    if k == 50:
        text[3] = text[3][:-2] + ("00" if text[3][-2:] != "00" else "01")  # bad checksum (GSA)
        text[3] = "\x00\x01" + text[3]  # 2 stray bytes
    lines.extend(text)
with open(__file__.replace("make_drive_fixture.py", "drive_10s.nmea"), "w", newline="") as f:
    f.write("".join(line + "\r\n" for line in lines))
