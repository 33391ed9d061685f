#!/usr/bin/env python3
"""Sends an NMEA log line by line as UDP datagrams, paced by the sentences' own UTC times.

What the lead car's computer does in the field (`socat -u /dev/ttyACM0,raw,b115200
UDP-SENDTO:follower-host:10110` forwards a live receiver the same way); here, for tests, a
recorded log replayed at RATE times real time from an absolute wall-clock start, so that two
senders (leader and follower) started in different network namespaces stay in step.

Usage: nmea_udp_sender.py LOG HOST PORT [--rate R] [--start-at UNIX_S] [--stats FILE]
"""
import argparse
import json
import re
import socket
import time

TIME = re.compile(r"^\$..(?:GGA|RMC|GLL|ZDA|GST),(\d{2})(\d{2})(\d{2}(?:\.\d+)?)")


def time_of_day_s(line):
    match = TIME.match(line)
    if not match:
        return None
    hours, minutes, seconds = match.groups()
    return int(hours) * 3600 + int(minutes) * 60 + float(seconds)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log")
    parser.add_argument("host")
    parser.add_argument("port", type=int)
    parser.add_argument("--rate", type=float, default=1.0)
    parser.add_argument("--start-at", type=float, default=0.0, help="wall-clock start (default: now)")
    parser.add_argument("--stats", help="write {sent} here at the end")
    args = parser.parse_args()
    lines = [line for line in open(args.log, newline="").read().splitlines() if line.strip()]
    start_wall = args.start_at or time.time()
    first_s, last_s, day = None, None, 0.0
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sent = 0
    for line in lines:
        t = time_of_day_s(line)
        if t is not None:
            if last_s is not None and t + day < last_s - 43200:  # midnight in the log
                day += 86400.0
            t += day
            first_s = t if first_s is None else first_s
            last_s = t
            delay = start_wall + (t - first_s) / args.rate - time.time()
            if delay > 0:
                time.sleep(delay)
        sock.sendto((line + "\r\n").encode(), (args.host, args.port))
        sent += 1
    if args.stats:
        json.dump({"sent": sent}, open(args.stats, "w"))


if __name__ == "__main__":
    main()
