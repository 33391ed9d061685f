#!/usr/bin/env python3
"""A radio link between two cars, for tests: forwards UDP datagrams with seeded delay, jitter
(hence reordering), loss and an outage, and counts what it did.

Every datagram received on LISTEN is dropped with probability --loss, dropped while the outage
lasts (--outage-start-s/--outage-s after the first datagram), or forwarded to TARGET after
--delay-s plus a uniform jitter in [0, --jitter-s): datagrams overtake each other when the jitter
exceeds their spacing. Stops after --idle-s without traffic and writes its counts to --stats.
Seeded (--seed): the same traffic gives the same fates.

Usage: lossy_udp_relay.py LISTEN_HOST LISTEN_PORT TARGET_HOST TARGET_PORT [options]
"""
import argparse
import heapq
import json
import random
import select
import socket
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("listen_host")
    parser.add_argument("listen_port", type=int)
    parser.add_argument("target_host")
    parser.add_argument("target_port", type=int)
    parser.add_argument("--delay-s", type=float, default=0.0)
    parser.add_argument("--jitter-s", type=float, default=0.0)
    parser.add_argument("--loss", type=float, default=0.0)
    parser.add_argument("--outage-start-s", type=float, default=-1.0)
    parser.add_argument("--outage-s", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--idle-s", type=float, default=5.0)
    parser.add_argument("--stats", required=True)
    args = parser.parse_args()
    fate = random.Random(args.seed)
    inbound = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    inbound.bind((args.listen_host, args.listen_port))
    outbound = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    queue, sequence = [], 0
    counts = {"received": 0, "lost": 0, "outage": 0, "forwarded": 0, "reordered": 0}
    first = last_activity = None
    last_forwarded_sequence = -1
    while True:
        now = time.time()
        while queue and queue[0][0] <= now:
            _, number, data = heapq.heappop(queue)
            outbound.sendto(data, (args.target_host, args.target_port))
            counts["forwarded"] += 1
            counts["reordered"] += number < last_forwarded_sequence
            last_forwarded_sequence = max(last_forwarded_sequence, number)
        if last_activity is not None and not queue and now - last_activity > args.idle_s:
            break
        timeout = min(0.01, max(0.0, queue[0][0] - now)) if queue else 0.05
        readable, _, _ = select.select([inbound], [], [], timeout)
        if not readable:
            continue
        data, _ = inbound.recvfrom(65536)
        now = time.time()
        first = now if first is None else first
        last_activity = now
        counts["received"] += 1
        lost = fate.random() < args.loss
        jitter = fate.uniform(0.0, args.jitter_s) if args.jitter_s > 0 else 0.0
        in_outage = args.outage_start_s >= 0 and args.outage_start_s <= now - first < args.outage_start_s + args.outage_s
        if in_outage:
            counts["outage"] += 1
        elif lost:
            counts["lost"] += 1
        else:
            heapq.heappush(queue, (now + args.delay_s + jitter, sequence, data))
        sequence += 1
    json.dump(counts, open(args.stats, "w"))


if __name__ == "__main__":
    main()
