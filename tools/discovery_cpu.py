#!/usr/bin/env python3
"""CPU each kind of process spent on a fleet's discovery.

    tools/discovery_cpu.py [--bin DIR] [--runs K] [--out DIR] -- [maptr run options]

Runs `maptr run OPTIONS --out OUT/rI` K times (default 1) with the launcher of DIR (default
build/bin). At the moment the launcher logs that every process matched, it reads the CPU time
(user + system, from /proc/PID/stat) of every process of the run: the launcher itself, the
discovery server, the plant, the groups, central and the agents. It prints one line per run
with the run's status and `discovery_s` from its summary.json, the CPU seconds per kind, and
the UDP datagrams this machine's kernel dropped for a full receive buffer during the run
(`RcvbufErrors` of /proc/net/snmp: the machine's count, so run nothing else meanwhile).
Compare two builds by alternating --bin between runs. A benchmark: it prints, it asserts
nothing.
"""
import argparse
import collections
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_by_kind(launcher_pid):
    """CPU seconds per process kind: the launcher and its descendants named maptr_*."""
    hz = os.sysconf("SC_CLK_TCK")
    kinds = collections.Counter()
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        comm = stat[stat.index("(") + 1:stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        cpu = (int(fields[11]) + int(fields[12])) / hz
        if int(pid) == launcher_pid:
            kinds["launcher"] += cpu
        elif comm.startswith("maptr_"):
            kinds[comm[len("maptr_"):]] += cpu
    return kinds


def udp_rcvbuf_errors():
    with open("/proc/net/snmp") as f:
        rows = [line.split() for line in f if line.startswith("Udp:")]
    return int(rows[1][rows[0].index("RcvbufErrors")])


def one_run(binary, options, out):
    log_path = os.path.join(out, "logs", "launcher.log")
    dropped = udp_rcvbuf_errors()
    with open(os.devnull, "w") as null:
        p = subprocess.Popen([binary, "run", *options, "--out", out], stdout=null, stderr=null)
    kinds = None
    while p.poll() is None:
        if kinds is None and os.path.exists(log_path):
            with open(log_path) as f:
                if "processes matched" in f.read():
                    kinds = cpu_by_kind(p.pid)
        time.sleep(0.1)
    dropped = udp_rcvbuf_errors() - dropped
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    cpu = " ".join(f"{k}={v:.1f}" for k, v in sorted((kinds or {}).items()))
    return f"{out}: status={s.get('status')} discovery_s={s.get('discovery_s', 0):.2f} udp_dropped={dropped} cpu_s: {cpu}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", time.strftime("%Y%m%d-%H%M%S") + "-discovery-cpu"))
    ap.add_argument("options", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    options = a.options[1:] if a.options[:1] == ["--"] else a.options
    if "--out" in options:
        sys.exit("discovery_cpu: give --out before --, not as a maptr run option")
    binary = os.path.join(a.bin, "maptr")
    if not os.access(binary, os.X_OK):
        sys.exit(f"discovery_cpu: --bin = {a.bin}: no maptr launcher there")
    os.makedirs(a.out, exist_ok=True)
    for i in range(a.runs):
        print(one_run(binary, options, os.path.join(a.out, f"r{i + 1}")), flush=True)


if __name__ == "__main__":
    main()
