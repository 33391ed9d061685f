#!/usr/bin/env python3
"""A radio link between two computers, for tests: every IPv4 packet between two network
namespaces, whatever its protocol (UDP, TCPROS, the master's XML-RPC), with seeded delay, jitter
(hence reordering), random loss and an outage, counted per direction.

One TUN device in each namespace (opened while this process is in that namespace, then the
namespace is left again), point-to-point addresses on them (A <-> B), and this process between
the two devices: each packet read from one device is dropped with probability --loss, dropped
while the outage lasts, or written to the other device after --delay-s plus a uniform jitter in
[-jitter, +jitter] (never below 0; netem's `delay D J`): packets overtake each other when the
jitter exceeds their spacing. Both directions are impaired alike, each with its own seeded
sequence of fates. This machine's kernel has no netem qdisc; this is its userspace stand-in.

The outage starts --outage-start-s after the data start mark: SIGUSR1, or this process's start
if it never comes. With --clean-until-mark the link is perfect until the mark (the computers start
while the cars stand side by side; what is measured is the drive) and only then impaired; the
packets it passed clean are counted apart (clean_forwarded).
Stops after --duration-s, after --idle-s without a packet (0: never), or on SIGINT/SIGTERM;
then writes its counts to --stats (JSON). The devices go with the process.

Usage (root):
  tun_link_emulator.py --netns-a /run/netns/lead --ip-a 10.213.78.1 \\
      --netns-b /run/netns/follower --ip-b 10.213.78.2 --delay-s 0.2 --jitter-s 0.1 --loss 0.1 \\
      --duration-s 600 --stats link.json --ready link.ready
"""
import argparse
import ctypes
import errno
import fcntl
import heapq
import json
import os
import random
import select
import signal
import struct
import subprocess
import time

CLONE_NEWNET = 0x40000000
TUNSETIFF = 0x400454CA
IFF_TUN, IFF_NO_PI = 0x0001, 0x1000
MAX_PACKETS_PER_WAKEUP = 256  # bounds one pass of the loop, so a flood cannot starve the timers
LIBC = ctypes.CDLL(None, use_errno=True)


def set_network_namespace(fd):
    # Python 3.11 has no os.setns; the process is single-threaded here, so it moves as a whole.
    if LIBC.setns(fd, CLONE_NEWNET) != 0:
        error = ctypes.get_errno()
        raise OSError(error, "setns: " + os.strerror(error))


def open_tun_in(netns_path, name, address, peer):
    """A TUN device made in the namespace at netns_path, addressed and up; its descriptor."""
    home = os.open("/proc/self/ns/net", os.O_RDONLY)
    target = os.open(netns_path, os.O_RDONLY)
    try:
        set_network_namespace(target)
        try:
            device = os.open("/dev/net/tun", os.O_RDWR | os.O_NONBLOCK)
            fcntl.ioctl(device, TUNSETIFF, struct.pack("16sH22x", name.encode(), IFF_TUN | IFF_NO_PI))
            # `ip` started now runs in this namespace too.
            for args in (["ip", "addr", "add", address, "peer", peer, "dev", name],
                         ["ip", "link", "set", name, "up"]):
                subprocess.run(args, check=True)
            # No IPv6 chatter (router solicitations) on the link: only the traffic under test.
            subprocess.run(["sysctl", "-q", "-w", "net.ipv6.conf.%s.disable_ipv6=1" % name],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        finally:
            set_network_namespace(home)
    finally:
        os.close(home)
        os.close(target)
    return device


class Direction:
    """One direction of the link: its seeded fates and its counts."""

    def __init__(self, seed):
        self.fate = random.Random(seed)
        self.sequence = 0
        self.last_forwarded_sequence = -1
        self.counts = {"received": 0, "lost": 0, "outage": 0, "forwarded": 0, "reordered": 0,
                       "not_ipv4": 0, "pending_at_stop": 0, "clean_forwarded": 0, "forwarded_udp_by_dst_port": {},
                       "forwarded_tcp": 0}

    def count_forwarded(self, sequence, packet):
        self.counts["forwarded"] += 1
        self.counts["reordered"] += sequence < self.last_forwarded_sequence
        self.last_forwarded_sequence = max(self.last_forwarded_sequence, sequence)
        protocol, header_length = packet[9], (packet[0] & 0x0F) * 4
        if protocol == 17 and len(packet) >= header_length + 4:  # UDP: by destination port
            port = str(struct.unpack("!H", packet[header_length + 2:header_length + 4])[0])
            by_port = self.counts["forwarded_udp_by_dst_port"]
            by_port[port] = by_port.get(port, 0) + 1
        elif protocol == 6:
            self.counts["forwarded_tcp"] += 1


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--netns-a", required=True, help="e.g. /run/netns/lead")
    parser.add_argument("--ip-a", required=True)
    parser.add_argument("--netns-b", required=True)
    parser.add_argument("--ip-b", required=True)
    parser.add_argument("--name-a", default="linka")
    parser.add_argument("--name-b", default="linkb")
    parser.add_argument("--delay-s", type=float, default=0.0)
    parser.add_argument("--jitter-s", type=float, default=0.0)
    parser.add_argument("--loss", type=float, default=0.0)
    parser.add_argument("--outage-start-s", type=float, default=-1.0, help="after the data start mark; <0: none")
    parser.add_argument("--outage-s", type=float, default=0.0)
    parser.add_argument("--clean-until-mark", action="store_true",
                        help="no delay, loss or outage before SIGUSR1")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--duration-s", type=float, default=600.0)
    parser.add_argument("--idle-s", type=float, default=0.0)
    parser.add_argument("--stats", required=True)
    parser.add_argument("--ready", help="written once both devices are up")
    args = parser.parse_args()

    stop = []
    signal.signal(signal.SIGINT, lambda *_: stop.append(True))
    signal.signal(signal.SIGTERM, lambda *_: stop.append(True))
    started = time.time()
    data_start, marked = [started], []

    def mark_data_start(*_):
        data_start[0] = time.time()
        marked.append(True)
    signal.signal(signal.SIGUSR1, mark_data_start)

    device_a = open_tun_in(args.netns_a, args.name_a, args.ip_a, args.ip_b)
    device_b = open_tun_in(args.netns_b, args.name_b, args.ip_b, args.ip_a)
    directions = {device_a: ("a_to_b", device_b, Direction(2 * args.seed)),
                  device_b: ("b_to_a", device_a, Direction(2 * args.seed + 1))}
    by_name = {name: direction for name, _, direction in directions.values()}
    if args.ready:
        open(args.ready, "w").write("%d\n" % os.getpid())
    queue = []  # (due, direction name, sequence, packet, output device)
    last_packet = None

    def in_outage(now):
        if args.outage_start_s < 0:
            return False
        since = now - data_start[0]
        return args.outage_start_s <= since < args.outage_start_s + args.outage_s

    while not stop:
        now = time.time()
        if now - started > args.duration_s:
            break
        if args.idle_s > 0 and last_packet is not None and not queue and now - last_packet > args.idle_s:
            break
        while queue and queue[0][0] <= now:
            _, name, sequence, packet, output = heapq.heappop(queue)
            try:
                os.write(output, packet)
            except OSError as error:  # the device's queue is full or it went away: the packet is lost
                if error.errno not in (errno.EAGAIN, errno.EIO, errno.ENOBUFS):
                    raise
                continue
            by_name[name].count_forwarded(sequence, packet)
        timeout = min(0.05, max(0.0, queue[0][0] - now)) if queue else 0.05
        try:
            readable, _, _ = select.select(list(directions), [], [], timeout)
        except InterruptedError:
            continue
        for device in readable:
            name, output, direction = directions[device]
            for _ in range(MAX_PACKETS_PER_WAKEUP):
                try:
                    packet = os.read(device, 65536)
                except BlockingIOError:
                    break
                now = time.time()
                last_packet = now
                counts = direction.counts
                if args.clean_until_mark and not marked:
                    try:
                        os.write(output, packet)
                        counts["clean_forwarded"] += 1
                    except OSError as error:
                        if error.errno not in (errno.EAGAIN, errno.EIO, errno.ENOBUFS):
                            raise
                    continue
                counts["received"] += 1
                # Draw both fates for every packet, so one packet's fate does not shift the next's.
                lost = direction.fate.random() < args.loss
                jitter = direction.fate.uniform(-args.jitter_s, args.jitter_s) if args.jitter_s > 0 else 0.0
                if not packet or packet[0] >> 4 != 4:
                    counts["not_ipv4"] += 1
                elif in_outage(now):
                    counts["outage"] += 1
                elif lost:
                    counts["lost"] += 1
                else:
                    heapq.heappush(queue, (now + max(0.0, args.delay_s + jitter), name, direction.sequence,
                                           packet, output))
                direction.sequence += 1
    for entry in queue:
        by_name[entry[1]].counts["pending_at_stop"] += 1
    stats = {name: direction.counts for name, direction in by_name.items()}
    stats["seconds"] = round(time.time() - started, 3)
    stats["data_start_after_s"] = round(data_start[0] - started, 3)
    with open(args.stats + ".tmp", "w") as out:
        json.dump(stats, out, indent=1, sort_keys=True)
    os.replace(args.stats + ".tmp", args.stats)
    os.close(device_a)
    os.close(device_b)


if __name__ == "__main__":
    main()
