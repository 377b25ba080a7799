"""Headless Chromium driven over the DevTools protocol, from the standard library alone.

Chromium is started with --remote-debugging-pipe: it reads JSON commands from file
descriptor 3 and writes answers and events to descriptor 4, each message ended by a NUL
byte (no WebSocket, no port). One page is attached; `evaluate` runs JavaScript in it,
`screenshot` returns its pixels (PNG decoded here, zlib only)."""
import base64
import json
import os
import select
import shutil
import struct
import subprocess
import tempfile
import time
import zlib

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-extensions", "--disable-default-apps", "--mute-audio",
         "--hide-scrollbars", "--disable-dev-shm-usage", "--remote-debugging-pipe"]


class BrowserError(Exception):
    pass


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    """with Browser() as b: b.open(url); b.evaluate("1 + 1")"""

    def __init__(self, width=1400, height=860, timeout=60.0):
        exe = find_chromium()
        if not exe:
            raise BrowserError("no Chromium found (Debian package chromium: tools/setup --browser)")
        self.profile = tempfile.mkdtemp(prefix="wb-chromium-")
        to_r, self._to_w = os.pipe()     # our commands -> Chromium's fd 3
        self._from_r, from_w = os.pipe()  # Chromium's fd 4 -> us
        self.timeout = timeout
        self.width, self.height = width, height

        def fds():
            os.dup2(to_r, 3)
            os.dup2(from_w, 4)
        self.proc = subprocess.Popen(
            [exe] + FLAGS + [f"--user-data-dir={self.profile}",
                             f"--window-size={width},{height}", "about:blank"],
            pass_fds=(3, 4), preexec_fn=fds, stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        os.close(to_r)
        os.close(from_w)
        self._buf = b""
        self._next = 0
        self.events = []       # (method, params) of the page's session, in order
        self.session = None
        self.errors = []       # console errors, exceptions and failed loads of the page

    # -- protocol
    def _send(self, method, params=None, session=None):
        self._next += 1
        msg = {"id": self._next, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_w, json.dumps(msg).encode() + b"\0")
        return self._next

    def _read(self, deadline):
        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise BrowserError("Chromium did not answer in time")
            r, _, _ = select.select([self._from_r], [], [], left)
            if not r:
                continue
            chunk = os.read(self._from_r, 1 << 20)
            if not chunk:
                err = self.proc.stderr.read().decode("utf-8", "replace")[-500:] \
                    if self.proc.poll() is not None else ""
                raise BrowserError(f"Chromium closed the DevTools pipe {err}".strip())
            self._buf += chunk
        msg, _, self._buf = self._buf.partition(b"\0")
        return json.loads(msg)

    def call(self, method, params=None, session=None, timeout=None):
        want = self._send(method, params, session)
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            m = self._read(deadline)
            if m.get("id") == want:
                if "error" in m:
                    raise BrowserError(f"{method}: {m['error'].get('message')}")
                return m.get("result", {})
            self._event(m)

    def _event(self, m):
        method = m.get("method")
        if not method:
            return
        p = m.get("params", {})
        self.events.append((method, p))
        if method == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            text = d.get("exception", {}).get("description") or d.get("text")
            self.errors.append(f"exception: {text} ({d.get('url', '')}:{d.get('lineNumber')})")
        elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", "")))
                            for a in p.get("args", []))
            self.errors.append(f"console.{p.get('type')}: {args}")
        elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            e = p["entry"]
            self.errors.append(f"log: {e.get('text')} {e.get('url', '')}".strip())

    def pump(self, seconds):
        """Reads events for a while (console messages arrive as events)."""
        deadline = time.monotonic() + seconds
        while True:
            try:
                r, _, _ = select.select([self._from_r], [], [], max(0, deadline - time.monotonic()))
            except InterruptedError:
                continue
            if not r and b"\0" not in self._buf:
                return
            if b"\0" not in self._buf:
                chunk = os.read(self._from_r, 1 << 20)
                if not chunk:
                    return
                self._buf += chunk
            while b"\0" in self._buf:
                msg, _, self._buf = self._buf.partition(b"\0")
                self._event(json.loads(msg))
            if time.monotonic() >= deadline:
                return

    # -- page
    def start(self):
        targets = self.call("Target.getTargets")["targetInfos"]
        page = next((t for t in targets if t["type"] == "page"), None)
        if page is None:
            made = self.call("Target.createTarget", {"url": "about:blank"})
            page = {"targetId": made["targetId"]}
        self.session = self.call("Target.attachToTarget", {"targetId": page["targetId"],
                                                           "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            self.call(f"{domain}.enable", session=self.session)
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": self.width, "height": self.height, "deviceScaleFactor": 1,
                   "mobile": False}, session=self.session)
        return self

    def open(self, url, ready="window.wbView && window.wbView.ready", timeout=60.0):
        """Loads url and waits until `ready` is true in the page; returns the seconds from
        the navigation to that moment."""
        self.errors = []
        t0 = time.monotonic()
        self.call("Page.navigate", {"url": url}, session=self.session)
        while True:
            try:
                if self.evaluate(f"!!({ready})"):
                    return time.monotonic() - t0
            except BrowserError:
                pass  # the old page went away mid-evaluation
            if time.monotonic() - t0 > timeout:
                raise BrowserError(f"{url}: not ready after {timeout:.0f} s ({ready})"
                                   + (f"; errors: {self.errors[:3]}" if self.errors else ""))
            self.pump(0.02)

    def evaluate(self, expr, await_promise=False, timeout=None):
        r = self.call("Runtime.evaluate", {"expression": expr, "returnByValue": True,
                                           "awaitPromise": await_promise},
                      session=self.session, timeout=timeout)
        if "exceptionDetails" in r:
            d = r["exceptionDetails"]
            why = d.get("exception", {}).get("description") or d.get("text")
            raise BrowserError(f"{expr[:80]}: {why}")
        return r.get("result", {}).get("value")

    def mouse(self, kind, x, y, button="left"):
        """A real mouse event at page point (x, y) (CSS pixels): kind "pressed", "moved"
        or "released" (what a user's hand does; the page sees mousedown/move/up)."""
        self.call("Input.dispatchMouseEvent",
                  {"type": "mouse" + kind.capitalize(), "x": x, "y": y, "button": button,
                   "buttons": 1 if kind != "released" else 0, "clickCount": 1},
                  session=self.session)

    def screenshot(self, path):
        """Writes the whole page as a PNG file."""
        data = base64.b64decode(self.call("Page.captureScreenshot", {"format": "png"},
                                          session=self.session)["data"])
        with open(path, "wb") as f:
            f.write(data)

    def pixels(self, x, y, r=2):
        """A screenshot of the (2r+1)-pixel square centred on CSS pixel (x, y), as an Image
        whose pixel(x, y) takes page coordinates (a clip: decoding a whole page's PNG
        here would take seconds)."""
        x0, y0 = int(round(x)) - r, int(round(y)) - r
        data = base64.b64decode(self.call(
            "Page.captureScreenshot",
            {"format": "png", "clip": {"x": x0, "y": y0, "width": 2 * r + 1,
                                       "height": 2 * r + 1, "scale": 1}},
            session=self.session)["data"])
        img = decode_png(data)
        img.x0, img.y0 = x0, y0
        return img

    def _processes(self):
        """{pid: CPU seconds (user + system)} of Chromium and every process it started
        (renderer, GPU/compositor, utility): /proc, Linux only."""
        tick = os.sysconf("SC_CLK_TCK")
        parent, used = {}, {}
        for d in os.listdir("/proc"):
            if not d.isdigit():
                continue
            try:
                with open(f"/proc/{d}/stat", "rb") as f:
                    fields = f.read().rsplit(b")", 1)[1].split()
            except OSError:
                continue
            parent[int(d)] = int(fields[1])
            used[int(d)] = (int(fields[11]) + int(fields[12])) / tick
        mine = {self.proc.pid}
        changed = True
        while changed:
            changed = False
            for pid, pp in parent.items():
                if pp in mine and pid not in mine:
                    mine.add(pid)
                    changed = True
        return {pid: used.get(pid, 0.0) for pid in mine}

    def cpu_seconds(self):
        """CPU seconds (user + system) used so far by Chromium and every process it started
        (renderer, GPU/compositor, utility): /proc, Linux only."""
        return sum(self._processes().values())

    def page_cpu_seconds(self):
        """CPU seconds used so far by the main threads of Chromium's renderer processes, where
        a page's JavaScript and WebAssembly run (/proc/PID/task/PID/schedstat, nanoseconds):
        a page's own computation, without the browser's other processes and threads (the
        browser process, the GPU process, compositor threads), which keep using CPU of their
        own while a page computes. Linux only."""
        total = 0.0
        for pid in self._processes():
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    if b"--type=renderer" not in f.read():
                        continue
                with open(f"/proc/{pid}/task/{pid}/schedstat", encoding="ascii") as f:
                    total += int(f.read().split()[0]) * 1e-9
            except (OSError, ValueError, IndexError):
                continue
        return total

    def close(self):
        try:
            if self.proc.poll() is None:
                try:
                    self._send("Browser.close")
                except OSError:
                    pass
                try:
                    self.proc.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    self.proc.kill()
                    self.proc.wait()
        finally:
            for fd in (self._to_w, self._from_r):
                try:
                    os.close(fd)
                except OSError:
                    pass
            if self.proc.stderr:
                self.proc.stderr.close()
            shutil.rmtree(self.profile, ignore_errors=True)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.close()


class Image:
    def __init__(self, width, height, rows):
        self.width, self.height, self.rows = width, height, rows  # rows: RGBA bytes
        self.x0 = self.y0 = 0  # page coordinates of its top-left pixel

    def pixel(self, x, y):
        """(r, g, b) at page pixel (x, y) (device scale factor 1), None outside."""
        x, y = int(round(x)) - self.x0, int(round(y)) - self.y0
        if not (0 <= x < self.width and 0 <= y < self.height):
            return None
        row = self.rows[y]
        return tuple(row[4 * x:4 * x + 3])


def decode_png(data):
    """8-bit RGB or RGBA, non-interlaced PNG (what Chromium writes) into an Image."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise BrowserError("screenshot: not a PNG")
    pos, idat, width = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            if depth != 8 or color not in (2, 6) or interlace:
                raise BrowserError(f"screenshot: PNG of depth {depth}, colour type {color}, "
                                   f"interlace {interlace}: not read here")
            bpp = 4 if color == 6 else 3
        elif kind == b"IDAT":
            idat.append(chunk)
        elif kind == b"IEND":
            break
    raw = zlib.decompress(b"".join(idat))
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif f == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        if bpp == 3:
            rgba = bytearray(width * 4)
            rgba[0::4], rgba[1::4], rgba[2::4] = line[0::3], line[1::3], line[2::3]
            rgba[3::4] = b"\xff" * width
            line = rgba
        rows.append(bytes(line))
    return Image(width, height, rows)
