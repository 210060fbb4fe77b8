"""Two "hosts" on one machine for the TCP transport's tests and benchmark (docs/clusters.md):
two network namespaces joined by a veth pair, each end with its address and loopback up.
Needs root.

    with network_hosts.TwoHosts() as hosts:
        hosts.a, hosts.b                  # the namespaces' names (ip netns exec NAME ...)
        hosts.address_a, hosts.address_b  # 10.231.50.1, 10.231.50.2
        hosts.cut()                       # delete the veth pair: the link is gone
"""
import os
import subprocess
import sys


def ip(*arguments, accepted=(0,)):
    result = subprocess.run(["ip", *arguments], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    if result.returncode not in accepted:
        sys.exit(f"FAILED: ip {' '.join(arguments)}: {result.stdout}")


class TwoHosts:
    address_a, address_b = "10.231.50.1", "10.231.50.2"

    def __init__(self):
        if os.geteuid() != 0:
            sys.exit("FAILED: two hosts need root for network namespaces (CI runs as root)")
        tag = f"cc{os.getpid() % 100000}"
        self.a, self.b = f"{tag}a", f"{tag}b"
        self.veth_a, self.veth_b = f"{tag}va", f"{tag}vb"

    def __enter__(self):
        self.remove()
        for host in (self.a, self.b):
            ip("netns", "add", host)
            ip("-n", host, "link", "set", "lo", "up")
        ip("link", "add", self.veth_a, "netns", self.a, "type", "veth", "peer", "name",
           self.veth_b, "netns", self.b)
        for host, end, address in ((self.a, self.veth_a, self.address_a),
                                   (self.b, self.veth_b, self.address_b)):
            ip("-n", host, "addr", "add", f"{address}/24", "dev", end)
            ip("-n", host, "link", "set", end, "up")
        return self

    def __exit__(self, *exception):
        self.remove()

    def cut(self):
        ip("-n", self.a, "link", "delete", self.veth_a)

    def remove(self):
        for host in (self.a, self.b):
            ip("netns", "delete", host, accepted=(0, 1, 2))
