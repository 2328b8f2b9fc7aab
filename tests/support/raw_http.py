#!/usr/bin/env python3
"""Raw-socket checks of tlsphd's HTTP layer (stdlib only), for tests/daemon/api_http.sh.

usage: raw_http.py CHECK PORT [PID]

Checks:
  auth-before-body PORT PID  with tokens on, a tokenless upload is refused (401
                             problem+json) on its headers, before any of its
                             body is read; 40 concurrent tokenless 8 MiB
                             uploads do not grow the daemon's peak RSS by
                             their bodies' size.
  slow PORT                  a client dribbling its headers, or its body, a
                             line or a byte at a time is closed by the
                             daemon's deadlines (configured at 2 s and 4 s
                             by the test); while 5 addresses (127.0.0.2-6)
                             hold 64 dribbling connections each, a normal
                             client's /healthz is answered.
  reserve PORT LIMIT         LIMIT + 4 connections (LIMIT: the daemon's
                             connection_limit) from 127.0.0.2 that never end
                             their headers:
                             the daemon closes the oldest ones to keep a
                             reserve, and a normal client's /healthz is
                             answered.
  malformed PORT             each malformed request gets its 4xx/5xx as
                             problem+json, promptly, and the connection is
                             closed: nothing smuggled after it is answered.

Each check prints "ok N - ..." / "FAIL N - ..." lines and exits 1 when one
failed.  Socket reads have a hang detector of HANG_S seconds (default 300),
never a speed limit: a check that waits for an answer fails only when none
comes at all.
"""
import json
import os
import selectors
import socket
import sys
import threading
import time

HANG_S = float(os.environ.get("HANG_S", "300"))
PROBLEM = "application/problem+json"
results = []


def report(good, desc):
    results.append(good)
    print("%s %d - %s" % ("ok" if good else "FAIL", len(results), desc), flush=True)


def connect(port, source="127.0.0.1"):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.bind((source, 0))
    s.settimeout(HANG_S)
    s.connect(("127.0.0.1", port))
    return s


def read_response(s, buf=b""):
    """One response: (status, headers dict (lower-case names), body bytes, rest),
    buf: what was read already (the rest of a previous response's read).
    status None when the connection closed (or hung) before a status line."""
    try:
        while b"\r\n\r\n" not in buf:
            b = s.recv(65536)
            if not b:
                return None, {}, b"", buf
            buf += b
    except (socket.timeout, ConnectionError):
        return None, {}, b"", buf
    head, _, rest = buf.partition(b"\r\n\r\n")
    lines = head.decode("latin1").split("\r\n")
    try:
        status = int(lines[0].split()[1])
    except (IndexError, ValueError):
        return None, {}, b"", buf
    hdrs = {}
    for ln in lines[1:]:
        k, _, v = ln.partition(":")
        hdrs[k.strip().lower()] = v.strip()
    n = int(hdrs.get("content-length", "0"))
    try:
        while len(rest) < n:
            b = s.recv(65536)
            if not b:
                break
            rest += b
    except (socket.timeout, ConnectionError):
        pass
    return status, hdrs, rest[:n], rest[n:]


def read_rest(s):
    """Everything the server sends until it closes (b"" when it closes at once)."""
    out = b""
    try:
        while True:
            b = s.recv(65536)
            if not b:
                return out
            out += b
    except (socket.timeout, ConnectionError):
        return out


def is_problem(hdrs, body, status):
    if hdrs.get("content-type") != PROBLEM:
        return False
    try:
        return json.loads(body).get("status") == status
    except ValueError:
        return False


def vm_hwm_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for ln in f:
            if ln.startswith("VmHWM:"):
                return int(ln.split()[1])
    raise RuntimeError("no VmHWM")


UPLOAD = 8 << 20


def upload_head(length):
    return (b"POST /processes/run/execution HTTP/1.1\r\nHost: t\r\n"
            b"Content-Type: application/json\r\nContent-Length: %d\r\n\r\n" % length)


def check_auth_before_body(port, pid):
    # The headers alone: the 401 must come without any of the body sent (a
    # daemon that reads the body first waits for it and answers nothing).
    s = connect(port)
    s.sendall(upload_head(UPLOAD))
    status, hdrs, body, _ = read_response(s)
    s.close()
    report(status == 401 and is_problem(hdrs, body, 401),
           "tokenless upload refused on its headers: %s %s" % (status, hdrs.get("content-type")))

    # 40 concurrent tokenless 8 MiB uploads.  Reading their bodies would cost
    # up to 40 x 8 MiB = 320 MiB; refusing on the headers costs at most the
    # connections' memory pools (MHD's per-connection limit, 128 KiB: 5 MiB)
    # plus allocator slack, so the peak RSS may grow by 48 MiB at most (less
    # than 6 bodies).
    before = vm_hwm_kib(pid)
    payload = b"x" * UPLOAD
    statuses = []

    def one():
        c = connect(port)
        try:
            c.sendall(upload_head(UPLOAD) + payload)
        except OSError:
            pass  # refused and closed while we were still sending
        st, _, _, _ = read_response(c)
        statuses.append(st)
        c.close()

    threads = [threading.Thread(target=one) for _ in range(40)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    after = vm_hwm_kib(pid)
    grew = (after - before) / 1024.0
    report(grew < 48, "40 tokenless 8 MiB uploads: peak RSS grew %.1f MiB (limit 48)" % grew)
    report(all(st in (401, None) for st in statuses),
           "every answered upload was a 401: %s" % sorted(set(map(str, statuses))))


GOOD = b"GET /healthz HTTP/1.1\r\nHost: t\r\n\r\n"
RUN = b"POST /processes/run/execution HTTP/1.1\r\nHost: t\r\nContent-Type: application/json\r\n"
MALFORMED = [
    # (what, request, status); GOOD follows each request on the same connection
    ("Content-Length and Transfer-Encoding (a smuggled request follows)",
     RUN + b"Content-Length: 5\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n", 400),
    ("two different Content-Lengths",
     RUN + b"Content-Length: 2\r\nContent-Length: 3\r\n\r\n{}x", 400),
    ("two equal Content-Lengths", RUN + b"Content-Length: 2\r\nContent-Length: 2\r\n\r\n{}", 400),
    ("HTTP/1.1 without Host", b"GET /healthz HTTP/1.1\r\n\r\n", 400),
    ("two Hosts", b"GET /healthz HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n", 400),
    ("space before a header's colon", b"GET /healthz HTTP/1.1\r\nHost : t\r\n\r\n", 400),
    ("space before Content-Type's colon",
     b"POST /processes/run/execution HTTP/1.1\r\nHost: t\r\nContent-Type : application/json\r\n"
     b"Content-Length: 2\r\n\r\n{}", 400),
    ("Transfer-Encoding: gzip, chunked",
     RUN + b"Transfer-Encoding: gzip, chunked\r\n\r\n0\r\n\r\n", 501),
    ("Transfer-Encoding: identity", RUN + b"Transfer-Encoding: identity\r\n\r\n{}", 501),
    ("10 000 query parameters",
     b"GET /jobs?" + b"&".join(b"a%d=1" % i for i in range(10000)) + b" HTTP/1.1\r\nHost: t\r\n\r\n",
     414),
]


def check_malformed(port):
    for what, raw, want in MALFORMED:
        s = connect(port)
        try:
            s.sendall(raw + GOOD)
        except OSError:
            pass
        status, hdrs, body, rest = read_response(s)
        rest += read_rest(s)
        s.close()
        report(status == want and is_problem(hdrs, body, want),
               "%s: %s %s (want %d problem+json)" % (what, status, hdrs.get("content-type"), want))
        report(b"HTTP/1." not in rest and hdrs.get("connection", "").lower() == "close",
               "%s: Connection: close, nothing more answered (%r)" % (what, rest[:60]))
    # what MHD answers itself, before the daemon sees the request: a
    # Content-Length that is not a number gets MHD's own 400 (HTML), and the
    # connection is closed (docs/deployment.md, "Hostile clients")
    s = connect(port)
    s.sendall(b"GET /healthz HTTP/1.1\r\nHost: t\r\nContent-Length: abc\r\n\r\n" + GOOD)
    status, hdrs, body, rest = read_response(s)
    rest += read_rest(s)
    s.close()
    report(status == 400 and b"200 OK" not in rest,
           "Content-Length: abc: MHD's own %s, the request after it not answered" % status)
    # well-formed requests still pass: keep-alive, HTTP/1.0 without Host, chunked
    s = connect(port)
    s.sendall(GOOD + GOOD)
    a = read_response(s)
    b = read_response(s, a[3])
    s.close()
    report(a[0] == 200 and b[0] == 200, "two requests on one connection: %s %s" % (a[0], b[0]))
    s = connect(port)
    s.sendall(b"GET /healthz HTTP/1.0\r\n\r\n")
    status = read_response(s)[0]
    s.close()
    report(status == 200, "HTTP/1.0 without Host: %s" % status)
    s = connect(port)
    s.sendall(RUN + b"Transfer-Encoding: chunked\r\n\r\n2\r\n{}\r\n0\r\n\r\n")
    status, hdrs, body, _ = read_response(s)
    s.close()
    report(status == 422, "a chunked body is read: %s (422: {} is no execute request)" % status)


def healthz(port):
    """The status of a GET /healthz from 127.0.0.1 (None: no answer)."""
    s = connect(port)
    try:
        s.sendall(GOOD)
        return read_response(s)[0]
    except OSError:
        return None
    finally:
        s.close()


DRIBBLE_PERIOD = 0.5
# How long a dribbler keeps going before the check gives up: a hang detector
# (30 times the deadlines the test configures), not a speed limit.
DRIBBLE_HANG_S = float(os.environ.get("DRIBBLE_HANG_S", "60"))


def dribble(port, first, each):
    """Sends first, then each every DRIBBLE_PERIOD until the daemon closes
    the connection: True when it did, False when DRIBBLE_HANG_S passed."""
    s = connect(port)
    s.setblocking(False)
    end = time.monotonic() + DRIBBLE_HANG_S
    data, n = first, 0
    while time.monotonic() < end:
        try:
            s.sendall(data)
            if s.recv(4096) == b"":
                return True
        except BlockingIOError:
            pass
        except OSError:
            return True
        n += 1
        data = each(n)
        time.sleep(DRIBBLE_PERIOD)
    s.close()
    return False


class Attack:
    """addresses x per_address connections that dribble a header line every
    DRIBBLE_PERIOD and never end their headers; a closed one is opened again."""

    def __init__(self, port, addresses, per_address):
        self.port, self.stop, self.reopened = port, threading.Event(), 0
        self.slots = [a for a in addresses for _ in range(per_address)]
        self.socks = [None] * len(self.slots)
        self.started = threading.Event()
        self.thread = threading.Thread(target=self.run)
        self.thread.start()
        self.started.wait()

    def open(self, i):
        try:
            s = connect(self.port, self.slots[i])
            s.setblocking(False)
            s.send(b"GET /healthz HTTP/1.1\r\nHost: t\r\n")
            self.socks[i] = s
        except OSError:
            self.socks[i] = None

    def run(self):
        for i in range(len(self.slots)):
            self.open(i)
        self.started.set()
        n = 0
        while not self.stop.wait(DRIBBLE_PERIOD):
            n += 1
            for i, s in enumerate(self.socks):
                try:
                    if s is None:
                        raise OSError
                    s.send(b"X-Slow-%d: 1\r\n" % n)
                    if s.recv(4096) == b"":
                        raise OSError
                except BlockingIOError:
                    pass
                except OSError:
                    if s is not None:
                        s.close()
                    self.reopened += 1
                    self.open(i)
        for s in self.socks:
            if s is not None:
                s.close()

    def end(self):
        self.stop.set()
        self.thread.join()


def check_slow(port):
    results_of = {}

    def run(name, first, each):
        results_of[name] = dribble(port, first, each)

    threads = [
        threading.Thread(target=run, args=("headers", b"GET /healthz HTTP/1.1\r\nHost: t\r\n",
                                           lambda n: b"X-Slow-%d: 1\r\n" % n)),
        threading.Thread(target=run, args=("body", upload_head(100000) + b"{",
                                           lambda n: b" ")),
    ]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    report(results_of["headers"], "a client dribbling a header line every %.1f s is closed "
           "(hang detector %d s)" % (DRIBBLE_PERIOD, DRIBBLE_HANG_S))
    report(results_of["body"], "a client dribbling its body a byte every %.1f s is closed "
           "(hang detector %d s)" % (DRIBBLE_PERIOD, DRIBBLE_HANG_S))

    attack = Attack(port, ["127.0.0.%d" % k for k in range(2, 7)], 64)
    try:
        for k in range(3):
            time.sleep(2 * DRIBBLE_PERIOD)  # let the attack dribble, not a deadline
            status = healthz(port)
            report(status == 200, "/healthz during 5 x 64 slow connections (try %d): %s"
                   % (k + 1, status))
    finally:
        attack.end()


def check_reserve(port, limit):
    idle = []
    for _ in range(limit + 4):  # beyond the limit: the last wait in the listen backlog
        c = connect(port, "127.0.0.2")
        c.sendall(b"GET /healthz HTTP/1.1\r\nHost: t\r\n")
        idle.append(c)

    def closed(c):
        c.setblocking(False)
        try:
            return c.recv(4096) == b""
        except BlockingIOError:
            return False
        except OSError:
            return True

    # the reserve is made within a watcher period or two; wait for it (a hang
    # detector, not a speed limit)
    end = time.monotonic() + HANG_S
    while time.monotonic() < end and not any(closed(c) for c in idle):
        time.sleep(0.1)
    gone = [closed(c) for c in idle]
    report(any(gone), "%d connections that never end their headers: %d closed to keep a "
           "reserve" % (len(idle), sum(gone)))
    report(gone[0] and gone == sorted(gone, reverse=True),
           "the oldest ones were closed: %s" % "".join("x" if g else "." for g in gone))
    status = healthz(port)
    report(status == 200, "/healthz while they hold the rest: %s" % status)
    for c in idle:
        c.close()


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    check, port = sys.argv[1], int(sys.argv[2])
    if check == "auth-before-body":
        check_auth_before_body(port, int(sys.argv[3]))
    elif check == "slow":
        check_slow(port)
    elif check == "reserve":
        check_reserve(port, int(sys.argv[3]))
    elif check == "malformed":
        check_malformed(port)
    else:
        sys.exit("unknown check %s" % check)
    sys.exit(0 if all(results) else 1)


if __name__ == "__main__":
    main()
