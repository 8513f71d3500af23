#!/usr/bin/python3
"""Screenshot of the WebGL2 viewer in headless Chromium, driven through the DevTools protocol
over a pipe (--remote-debugging-pipe: Python's standard library is enough, no npm).

usage: screenshot.py WIDTH HEIGHT URL OUT.png [URL OUT.png ...] [--chromium PATH] [--timeout S]

Loads each URL in turn in one browser (so compiled shaders are reused), waits until the page
sets document.title to "biref ready" (the frame is drawn) and captures the top-left
WIDTH x HEIGHT pixels into OUT.png. Exit 1 with one line on stderr if the page reports an error,
never gets ready, or Chromium cannot start."""
import argparse
import base64
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time


class Pipe:
    def __init__(self, proc, to_browser, from_browser):
        self.proc, self.w, self.r = proc, to_browser, from_browser
        self.buf = b""
        self.next_id = 0

    def call(self, method, params=None, session=None, timeout=60):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.w, json.dumps(msg).encode() + b"\0")
        deadline = time.time() + timeout
        while True:
            while b"\0" in self.buf:
                raw, self.buf = self.buf.split(b"\0", 1)
                reply = json.loads(raw)
                if reply.get("id") == self.next_id:
                    if "error" in reply:
                        raise RuntimeError(f"{method}: {reply['error'].get('message')}")
                    return reply.get("result", {})
            if time.time() > deadline:
                raise RuntimeError(f"{method}: no reply from Chromium in {timeout} s")
            chunk = os.read(self.r, 1 << 20)
            if not chunk:
                raise RuntimeError("Chromium closed the DevTools pipe (did it start?)")
            self.buf += chunk


def chromium_args(binary, profile, width, height):
    return [binary, "--headless", "--no-sandbox", "--remote-debugging-pipe", f"--user-data-dir={profile}",
            # WebGL2 without a GPU: ANGLE on SwiftShader (software Vulkan).
            "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
            "--allow-file-access-from-files", "--force-device-scale-factor=1", "--force-color-profile=srgb",
            f"--window-size={width},{height}", "--hide-scrollbars",
            "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run",
            "--disable-quic", "--disable-default-apps", "--disable-extensions", "--mute-audio", "about:blank"]


def launch(binary, width, height):
    """Starts Chromium headless with the DevTools pipe in a fresh profile; returns the process,
    its Pipe and the profile directory (the caller removes it)."""
    profile = tempfile.mkdtemp(prefix="biref-chromium-")
    # Chromium reads commands from fd 3 and writes replies to fd 4. Our ends are moved above 10
    # first, so the dup2 calls in the child cannot overwrite one another.
    def high(fd):
        moved = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(fd)
        return moved

    to_r, to_w = (high(fd) for fd in os.pipe())
    from_r, from_w = (high(fd) for fd in os.pipe())

    def child_fds():
        os.dup2(to_r, 3)
        os.dup2(from_w, 4)

    proc = subprocess.Popen(chromium_args(binary, profile, width, height), preexec_fn=child_fds,
                            close_fds=False, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=open(os.environ.get("BIREF_CHROMIUM_LOG", os.devnull), "w"))
    os.close(to_r)
    os.close(from_w)
    return proc, Pipe(proc, to_w, from_r), profile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("width", type=int)
    ap.add_argument("height", type=int)
    ap.add_argument("pages", nargs="+", metavar="URL OUT.png")
    ap.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    ap.add_argument("--timeout", type=float, default=180)
    a = ap.parse_args()
    if len(a.pages) % 2:
        ap.error("expected pairs of URL and OUT.png")
    proc, cdp, profile = launch(a.chromium, a.width, a.height)
    try:
        target = cdp.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        sess = cdp.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        cdp.call("Emulation.setDeviceMetricsOverride",
                 {"width": a.width, "height": a.height, "deviceScaleFactor": 1, "mobile": False}, sess)
        for url, out in zip(a.pages[::2], a.pages[1::2]):
            cdp.call("Page.navigate", {"url": url}, sess)
            deadline = time.time() + a.timeout
            title = ""
            while time.time() < deadline:
                title = cdp.call("Runtime.evaluate", {"expression": "document.title", "returnByValue": True},
                                 sess, timeout=a.timeout)["result"].get("value", "")
                if title == "biref ready" or title.startswith("biref error"):
                    break
                time.sleep(0.1)
            if title != "biref ready":
                raise RuntimeError(f"{url}: the page did not get ready in {a.timeout:.0f} s (title: {title!r})")
            shot = cdp.call("Page.captureScreenshot", {"format": "png", "clip": {
                "x": 0, "y": 0, "width": a.width, "height": a.height, "scale": 1}}, sess, timeout=a.timeout)
            with open(out, "wb") as f:
                f.write(base64.b64decode(shot["data"]))
        try:
            cdp.call("Browser.close", timeout=10)
        except RuntimeError:
            pass
        return 0
    except (RuntimeError, OSError) as e:
        print(f"screenshot.py: error: {e}", file=sys.stderr)
        return 1
    finally:
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
