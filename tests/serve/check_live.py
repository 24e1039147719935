#!/usr/bin/env python3
"""`vkfuse run --serve` end to end (ctest serve.live), with real clients.

Starts `vkfuse run --sensors 4 --serve 127.0.0.1:0` on simulated DIGITs, then
at once:
  - a real headless Chromium (browse_page.mjs, puppeteer-core) opens the page:
    no console error, every sensor's images drawn, the plots moving; it leaves
    canvases.json and a screenshot;
  - a protocol client (Python's websockets, from Debian) checks the Foxglove
    handshake, serverInfo and advertise, subscribe and unsubscribe, the
    metrics messages, and what hostile messages get;
  - a client that subscribes to everything and then stops reading, a
    slowloris request, a flood of connections and requests for paths outside
    the page: the rig must keep its pace, memory stay bounded, others served.
Then it interrupts the run and compares: every metrics message received is a
line of the run's metrics.jsonl, and every fused image the page drew is, pixel
for pixel, the run's fused PNG of the same cycle.

    check_live.py VKFUSE NODE_WORK WORK
"""
import asyncio
import base64
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import time

import cv2
import numpy as np
import websockets

SENSORS = 4
SUBPROTOCOL = "foxglove.websocket.v1"


def fail(message):
    print(f"serve.live: {message}", file=sys.stderr)
    sys.exit(1)


def rss_mib(pid):
    with open(f"/proc/{pid}/status") as f:
        return int(re.search(r"VmRSS:\s+(\d+)", f.read()).group(1)) / 1024


async def connect(port, **kw):
    return await websockets.connect(f"ws://127.0.0.1:{port}/", subprotocols=[SUBPROTOCOL], max_size=None,
                                    open_timeout=20, **kw)


async def handshake(ws):
    info = json.loads(await ws.recv())
    advertise = json.loads(await ws.recv())
    if info.get("op") != "serverInfo" or advertise.get("op") != "advertise":
        fail(f"expected serverInfo then advertise, got {info.get('op')}, {advertise.get('op')}")
    return {c["topic"]: c for c in advertise["channels"]}


async def next_status(ws, timeout=10):
    """The next status (op) text message, skipping data."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        m = await asyncio.wait_for(ws.recv(), timeout)
        if isinstance(m, str):
            return json.loads(m)
    fail("no status message within 10 s")


async def protocol_checks(port, results):
    ws = await connect(port)
    if ws.subprotocol != SUBPROTOCOL:
        fail(f"the server answered subprotocol {ws.subprotocol!r}")
    channels = await handshake(ws)
    want = SENSORS * 7 + 2  # per sensor fused raw and PNG, two settings raw and JPEG, metrics; status; rig
    if len(channels) != want:
        fail(f"{len(channels)} channels advertised, expected {want}: {sorted(channels)}")
    for topic, c in channels.items():
        if "/fused" in topic or "/lit/" in topic:
            schema = "sensor_msgs/msg/CompressedImage" if topic.endswith("/compressed") else "sensor_msgs/msg/Image"
            if (c["encoding"], c["schemaName"], c["schemaEncoding"]) != ("cdr", schema, "ros2msg"):
                fail(f"{topic}: {c['encoding']} {c['schemaName']} {c['schemaEncoding']}")
            if not c["schema"].startswith("std_msgs/Header header"):
                fail(f"{topic}: schema {c['schema'][:40]!r}")
        elif c["encoding"] != "json" or c["schemaEncoding"] != "jsonschema":
            fail(f"{topic}: {c['encoding']} {c['schemaEncoding']}")
    results["channels"] = channels

    # Subscribe to every sensor's metrics and the status.
    metric_topics = [f"/vkfuse/SIM_{i:04d}/metrics" for i in range(1, SENSORS + 1)]
    subs = {100 + i: channels[t]["id"] for i, t in enumerate(metric_topics)}
    subs[200] = channels["/vkfuse/status"]["id"]
    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": k, "channelId": v} for k, v in subs.items()]}))
    lines, statuses = [], []
    while len(lines) < 12 * SENSORS:
        m = await asyncio.wait_for(ws.recv(), 30)
        if isinstance(m, str):
            fail(f"unexpected text message {m[:200]}")
        op, sub, _ = struct.unpack_from("<BIQ", m)
        if op != 1 or sub not in subs:
            fail(f"a binary message with op {op} for subscription {sub}")
        text = m[13:].decode()
        (statuses if sub == 200 else lines).append(text)
    # Unsubscribe one sensor's metrics: after what was in flight, none of it again.
    await ws.send(json.dumps({"op": "unsubscribe", "subscriptionIds": [100]}))
    end = time.monotonic() + 0.5
    while time.monotonic() < end:
        try:
            await asyncio.wait_for(ws.recv(), 0.2)
        except asyncio.TimeoutError:
            pass
    seen = set()
    end = time.monotonic() + 2.5
    while time.monotonic() < end:
        try:
            m = await asyncio.wait_for(ws.recv(), 0.5)
        except asyncio.TimeoutError:
            continue
        if isinstance(m, bytes):
            op, sub, _ = struct.unpack_from("<BIQ", m)
            seen.add(sub)
            if sub != 200:
                lines.append(m[13:].decode())
    if 100 in seen:
        fail("messages kept coming for an unsubscribed subscription")
    if not {101, 102, 103, 200} <= seen:
        fail(f"the other subscriptions stopped after an unsubscribe: {sorted(seen)}")
    results["metrics_lines"] = lines
    results["status"] = [json.loads(s) for s in statuses]

    # Hostile messages get a status naming the problem; the connection lives on.
    for message, level, fragment in [
        ("{not json", 2, "not JSON"),
        ('{"op": "advertise", "channels": []}', 2, "not supported"),
        ('{"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 9999}]}', 1, "no channel 9999"),
        ('{"op": "subscribe", "subscriptions": [{"id": 101, "channelId": 1}]}', 1, "subscription id 101 is in use"),
        ('{"op": "subscribe", "subscriptions": [{"id": -1, "channelId": 1}]}', 2, "subscriptions[0].id"),
        ('{"op": "unsubscribe", "subscriptionIds": [424242]}', 1, "no subscription 424242"),
        ('[1, 2, 3]', 2, "expected a JSON object"),
    ]:
        await ws.send(message)
        status = await next_status(ws)
        if status.get("op") != "status" or status.get("level") != level or fragment not in status.get("message", ""):
            fail(f"{message[:60]}: got {status}")
    await ws.send(b"\x01\x00\x00\x00\x00binary")
    status = await next_status(ws)
    if status.get("level") != 2 or "binary" not in status.get("message", ""):
        fail(f"a binary message: got {status}")
    await ws.close()

    # A message over 64 KiB closes that connection, and only that one.
    big = await connect(port)
    await handshake(big)
    await big.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": i, "channelId": 1} for i in range(9000)]}))
    try:
        while True:
            await asyncio.wait_for(big.recv(), 10)
    except websockets.ConnectionClosed:
        pass
    except asyncio.TimeoutError:
        fail("a 100 KiB message did not close its connection")

    # No subprotocol: refused at the handshake.
    try:
        async with websockets.connect(f"ws://127.0.0.1:{port}/", open_timeout=10):
            fail("a client without the subprotocol was accepted")
    except websockets.InvalidStatusCode as e:
        if e.status_code != 400:
            fail(f"a client without the subprotocol got HTTP {e.status_code}")
    results["protocol"] = "ok"


async def stalled_client(port, pid, results):
    """Subscribes to everything, then never reads again while the rig goes on."""
    ws = await connect(port, max_queue=1, read_limit=2**16)
    channels = await handshake(ws)
    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": c["id"], "channelId": c["id"]} for c in channels.values()]}))
    watcher = await connect(port)
    w_channels = await handshake(watcher)
    await watcher.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": w_channels["/vkfuse/status"]["id"]}]}))

    async def cycle_now():
        m = await asyncio.wait_for(watcher.recv(), 20)
        return json.loads(m[13:])["cycle"]

    first = await cycle_now()
    rss = [rss_mib(pid)]
    start = time.monotonic()
    while time.monotonic() - start < 8:
        await asyncio.sleep(1)
        rss.append(rss_mib(pid))
        # Keep the watcher drained; the stalled client reads nothing.
        try:
            while True:
                await asyncio.wait_for(watcher.recv(), 0.01)
        except asyncio.TimeoutError:
            pass
    last = await cycle_now()
    results["stalled"] = {"cycles": last - first, "seconds": time.monotonic() - start, "rss_mib": rss}
    # Not a speed target (a busy host may be slow): only that the rig went on.
    if last - first < 5:
        fail(f"with a client that stopped reading, the rig advanced {last - first} cycles in 8 s")
    if max(rss) > 1024:
        fail(f"with a client that stopped reading, memory reached {max(rss):.0f} MiB")
    ws.transport.abort()
    await watcher.close()


def slowloris(port, results):
    """A request trickled in byte by byte is cut off; others are served meanwhile."""
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n")
    start = time.monotonic()
    s.settimeout(1)
    while time.monotonic() - start < 20:
        try:
            s.sendall(b"X")
            if s.recv(1024) == b"":
                break
        except socket.timeout:
            continue
        except (BrokenPipeError, ConnectionResetError):
            break
    else:
        fail("a request trickled byte by byte was never cut off")
    results["slowloris_s"] = time.monotonic() - start


def http_get(port, request):
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    s.sendall(request)
    reply = s.recv(4096)
    s.close()
    return int(reply.split(b" ", 2)[1]) if reply.startswith(b"HTTP/1.1 ") else 0


def paths(port):
    for request, want in [
        (b"GET / HTTP/1.1\r\nHost: x\r\n\r\n", 200),
        (b"GET /app.js HTTP/1.1\r\nHost: x\r\n\r\n", 200),
        (b"GET /../../etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n", 404),
        (b"GET /%2e%2e/%2e%2e/etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n", 404),
        (b"GET /CMakeLists.txt HTTP/1.1\r\nHost: x\r\n\r\n", 404),
        (b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\n\r\nhi", 405),
        (b"GET / HTTP/1.1\r\nHost: x\r\nX: " + b"a" * 20000 + b"\r\n\r\n", 0),
    ]:
        got = http_get(port, request)
        if got != want:
            fail(f"{request[:40]!r}...: HTTP {got}, expected {want}")


async def flood(port):
    """More WebSocket clients than the cap: the extra ones are refused with 503."""
    opened, refused = [], 0
    for _ in range(20):
        try:
            opened.append(await connect(port))
        except websockets.InvalidStatusCode as e:
            if e.status_code != 503:
                fail(f"a client over the cap got HTTP {e.status_code}")
            refused += 1
    for ws in opened:
        await ws.close()
    if refused == 0:
        fail("20 more clients were all accepted")
    return refused


async def main(vkfuse, node_work, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "out")
    log = open(os.path.join(work, "run.err"), "wb")
    run = subprocess.Popen([vkfuse, "run", "--sensors", str(SENSORS), "--serve", "127.0.0.1:0", "--virtual-clock",
                            "--backend", "cpu", "--out", out], stdout=subprocess.DEVNULL, stderr=log)
    try:
        port = None
        for _ in range(600):
            with open(os.path.join(work, "run.err"), "rb") as f:
                m = re.search(rb"serving http://127\.0\.0\.1:(\d+)/", f.read())
            if m:
                port = int(m.group(1))
                break
            if run.poll() is not None:
                fail(f"vkfuse run ended ({run.returncode}) before serving")
            await asyncio.sleep(0.1)
        if port is None:
            fail("vkfuse run did not say where it serves")
        browser = await asyncio.create_subprocess_exec("node", os.path.join(node_work, "browse_page.mjs"),
                                                       f"http://127.0.0.1:{port}/", work)
        results = {}
        await protocol_checks(port, results)
        paths(port)
        loris = asyncio.get_running_loop().run_in_executor(None, slowloris, port, results)
        await stalled_client(port, run.pid, results)
        await loris
        refused = await flood(port)
        if await browser.wait() != 0:
            fail("the browser check failed (above)")
    finally:
        if run.poll() is None:
            run.send_signal(signal.SIGINT)
        code = run.wait(timeout=120)
    if code != 0:
        fail(f"vkfuse run exited {code} on SIGINT")

    # Every metrics message is a line of metrics.jsonl, verbatim but for
    # image_from_cycle, which names an earlier file of --out.
    with open(os.path.join(out, "metrics.jsonl")) as f:
        written = set(re.sub(r', "image_from_cycle": [0-9]+', "", line.rstrip("\n")) for line in f)
    missing = [line for line in results["metrics_lines"] if line not in written]
    if missing:
        fail(f"{len(missing)} metrics messages are not lines of metrics.jsonl, e.g. {missing[0][:200]}")
    # Every fused image the page drew is the run's PNG of that cycle, pixel for pixel.
    page = json.load(open(os.path.join(work, "canvases.json")))
    fused = lit = 0
    for c in page["canvases"]:
        rgba = np.frombuffer(base64.b64decode(c["rgba"]), np.uint8).reshape(c["height"], c["width"], 4)
        serial = c["topic"].split("/")[2].replace("_", "-")  # SIM_0001: SIM-0001's token
        if c["topic"].endswith("/fused/compressed"):
            if c["cycle"] < 0:
                fail(f"{c['topic']}: the page did not know the drawn image's cycle")
            png = cv2.imread(os.path.join(out, "fused", serial, f"{c['cycle']:06d}.png"), cv2.IMREAD_COLOR)
            if png is None:
                fail(f"{c['topic']}: no fused PNG of cycle {c['cycle']}")
            if not np.array_equal(png[:, :, ::-1], rgba[:, :, :3]):
                fail(f"{c['topic']}: the page's pixels differ from fused/{serial}/{c['cycle']:06d}.png")
            fused += 1
        else:
            if rgba[:, :, :3].max() == 0:
                fail(f"{c['topic']}: a black image")
            lit += 1
    if fused != SENSORS or lit != 2 * SENSORS:
        fail(f"the page drew {fused} fused and {lit} lit images, expected {SENSORS} and {2 * SENSORS}")
    st = results["stalled"]
    print(f"serve.live: chromium drew {fused} fused images (each its PNG, pixel for pixel) and {lit} lit ones; "
          f"{len(results['metrics_lines'])} metrics messages are metrics.jsonl lines; a stalled client: "
          f"{st['cycles']} cycles in {st['seconds']:.1f} s, RSS {min(st['rss_mib']):.0f}-{max(st['rss_mib']):.0f} MiB; "
          f"slowloris cut after {results['slowloris_s']:.1f} s; {refused} clients over the cap refused")


if __name__ == "__main__":
    asyncio.run(main(*sys.argv[1:4]))
