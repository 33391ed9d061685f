#!/usr/bin/env python3
"""Cuts columns out of OpenACC platoon files into a small, deterministic archive.

The JRC OpenACC database (Makridis et al., Transportation Research Part C 125 (2021) 103047;
(c) European Union, CC BY 4.0) ships each platoon run as one wide CSV with every car's columns.
Two kinds of excerpt, each keeping the metadata lines as they are:
  --follower NAME: one pair per run, for the NMEA bags: the Time column, the six columns of the
      follower and of the car directly ahead of it (Speed, E, N, Lon, Lat, Alt), and their gap IVS;
  --speeds-and-gaps: every car, for the identification of whole campaigns: Time, every Speedk and
      every IVSk (no positions: a fraction of the size). Every kept cell is copied as
written, byte for byte; the columns keep their numbers, as the database's own files with missing
cars do, so any OpenACC reader reads an excerpt as it reads the original. The archive is
deterministic (sorted names, fixed times and owners, xz preset 9e): the same input gives the same
bytes.

Usage:
  make_openacc_excerpt.py --source DIR --speeds-and-gaps --out data/openacc/NAME.tar.xz RUN... \
  make_openacc_excerpt.py --source DIR --follower TOYOTA_RAV4 --out data/openacc/NAME.tar.xz \
      [--extra Zala_notes.txt --extra copyright.txt ...] dynamic_part5 dynamic_part6 ...
"""
import argparse
import csv
import io
import lzma
import os
import sys
import tarfile

METADATA_LINES = 5
PER_CAR = ("Speed", "E", "N", "Lon", "Lat", "Alt")
MTIME = 1570492800  # 2019-10-08 00:00 UTC, the day of the ZalaZone dynamic-platform runs


def read_lines(path):
    with open(path, newline="") as f:
        lines = f.read().splitlines()
    return lines[:METADATA_LINES], lines[METADATA_LINES], lines[METADATA_LINES + 1:]


def keep_columns(path, metadata, header, rows, wanted):
    """The file's text with only the wanted columns, every kept cell as written."""
    index = [header.index(c) for c in wanted]
    out = io.StringIO()
    out.write("\n".join(metadata) + "\n" + ",".join(wanted) + "\n")
    for number, line in enumerate(rows, start=METADATA_LINES + 2):
        cells = line.split(",")
        if len(cells) != len(header):
            sys.exit(f"{path}:{number}: {len(cells)} fields, the header has {len(header)}")
        out.write(",".join(cells[i] for i in index) + "\n")
    return out.getvalue()


def speeds_and_gaps(path):
    """Time, every Speedk and every IVSk of one file, in the file's column order."""
    metadata, header_line, rows = read_lines(path)
    header = next(csv.reader([header_line]))
    wanted = [c for c in header if c == "Time" or c.startswith("Speed") or c.startswith("IVS")]
    return keep_columns(path, metadata, header, rows, wanted)


def excerpt(path, follower):
    """The excerpt of one file as text, and the pair it holds as (leader, follower) positions."""
    metadata, header_line, rows = read_lines(path)
    order = [name for name in next(csv.reader([metadata[1]]))[1:] if name]
    if follower not in order:
        sys.exit(f"{path}: no {follower} in Vehicle_order {order}")
    k = order.index(follower) + 1
    if k == 1:
        sys.exit(f"{path}: {follower} leads the platoon; it follows nobody")
    header = next(csv.reader([header_line]))
    wanted = ["Time"] + [c + str(k - 1) for c in PER_CAR] + [c + str(k) for c in PER_CAR] + ["IVS" + str(k - 1)]
    missing = [c for c in wanted if c not in header]
    if missing:
        sys.exit(f"{path}: columns {missing} are not in the file")
    return keep_columns(path, metadata, header, rows, wanted), (k - 1, k), order[k - 2]


def add(archive, name, data):
    info = tarfile.TarInfo(name)
    info.size = len(data)
    info.mtime = MTIME
    info.mode = 0o644
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    archive.addfile(info, io.BytesIO(data))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", required=True, help="folder of the database's files")
    kind = parser.add_mutually_exclusive_group(required=True)
    kind.add_argument("--follower", help="one pair per run: this car, by its Vehicle_order name, and the car ahead")
    kind.add_argument("--speeds-and-gaps", action="store_true", help="every car's speed and gap, no positions")
    parser.add_argument("--out", required=True, help="archive to write (.tar.xz)")
    parser.add_argument("--extra", action="append", default=[], help="a file of the folder copied as it is (repeatable)")
    parser.add_argument("runs", nargs="+", help="run names (file names without .csv)")
    args = parser.parse_args()

    members = {}
    for run in args.runs:
        path = os.path.join(args.source, run + ".csv")
        if args.speeds_and_gaps:
            text = speeds_and_gaps(path)
            print(f"{run}: speeds and gaps of every car, {text.count(chr(10)) - METADATA_LINES - 1} rows")
        else:
            text, pair, leader = excerpt(path, args.follower)
            print(f"{run}: {args.follower} (position {pair[1]}) behind {leader} (position {pair[0]}), "
                  f"{text.count(chr(10)) - METADATA_LINES - 1} rows")
        members[run + ".csv"] = text.encode()
    for name in args.extra:
        with open(os.path.join(args.source, name), "rb") as f:
            members[name] = f.read()
    tar_bytes = io.BytesIO()
    with tarfile.open(fileobj=tar_bytes, mode="w", format=tarfile.GNU_FORMAT) as archive:
        for name in sorted(members):
            add(archive, name, members[name])
    with open(args.out, "wb") as f:
        f.write(lzma.compress(tar_bytes.getvalue(), preset=9 | lzma.PRESET_EXTREME))
    print(f"{args.out}: {os.path.getsize(args.out)} bytes")


if __name__ == "__main__":
    main()
