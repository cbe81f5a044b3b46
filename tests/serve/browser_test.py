#!/usr/bin/env python3
"""End-to-end test of the `discreel serve` web page in headless Chromium.

    python3 tests/serve/browser_test.py DISCREEL_BIN WORK_DIR

Starts the service and Chromium, then drives the page through the DevTools protocol: types a
scene with a bad radius and expects the problem on its line, then one too fast for a crowd and
expects a warning on its line, fixes it, renders, and waits
until the video plays. Exit 0 on pass; on failure it prints why, the page's status and
problems, and the tail of the logs. Needs Chromium (`chromium`, or $CHROMIUM) and the
websocket-client library (Debian: python3-websocket).
"""
import collections
import json
import os
import queue
import shutil
import signal
import subprocess
import sys
import threading
import time
import urllib.request

try:
    import websocket
except ImportError:
    # Debian's python3-websocket lives in the system interpreter's dist-packages; a python3
    # from elsewhere (pyenv, a venv) does not see it. The library is pure Python.
    sys.path.append("/usr/lib/python3/dist-packages")
    try:
        import websocket
    except ImportError:
        sys.exit("browser_test: needs websocket-client (apt-get install python3-websocket)")

BUDGET_S = 90           # the whole test
POLL_S = 0.1            # every wait loop polls this often
START = time.monotonic()

# A small, quick scene whose disc radius is negative: validate reports the line of the value.
BAD_SCENE = """version: 1
video:
  size: [320, 180]
  fps: 30
  duration: 1.0
  background: "#0f1419"
discs:
  - position: [0.8, 1.2]
    radius: -0.2
    velocity: [1.5, 0]
    color: "#f4d35e"
  - position: [2.2, 1.0]
    velocity: [-1, 0.5]
    radius: 0.15
    color: "#17bebb"
walls:
  - box: [[0, 0], [3.2, 1.8]]
    thickness: 0.05
physics:
  gravity: [0, -9.81]
  restitution: 0.7
"""
BAD_LINE = BAD_SCENE.split("\n").index("    radius: -0.2") + 1
assert BAD_LINE == 9, BAD_LINE
GOOD_SCENE = BAD_SCENE.replace("radius: -0.2", "radius: 0.2")
# Valid, but faster than a crowd of its discs holds (eight more discs make the crowd): one
# warning, at the velocity.
FAST_SCENE = GOOD_SCENE.replace("velocity: [1.5, 0]", "velocity: [2000, 0]").replace(
    "walls:\n",
    "  - grid: {origin: [0.4, 1.6], count: [8, 1], spacing: [0.3, 1], radius: 0.05}\nwalls:\n")
FAST_LINE = BAD_LINE + 1


class Failure(Exception):
    pass


def deadline(seconds):
    """The earlier of now + seconds and the end of the overall budget."""
    return min(time.monotonic() + seconds, START + BUDGET_S)


def wait_for(what, probe, seconds):
    """Polls probe() until it returns something truthy; returns that, or fails at the deadline."""
    end = deadline(seconds)
    while True:
        value = probe()
        if value:
            return value
        if time.monotonic() >= end:
            raise Failure(f"timed out after {seconds} s waiting for {what}")
        time.sleep(POLL_S)


def stop(proc, name):
    """Stops a process we started: terminate, wait, kill. Also its process group (Chromium's
    helpers), which it leads because it was started with start_new_session."""
    if proc is None:
        return
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            print(f"browser_test: {name} ignored SIGTERM; killing it", file=sys.stderr)
            proc.kill()
            proc.wait(timeout=5)
    try:
        os.killpg(proc.pid, signal.SIGKILL)   # leftovers in its own group, if any
    except (ProcessLookupError, PermissionError):
        pass


def tail(path, lines=20):
    try:
        with open(path, errors="replace") as f:
            return "".join(collections.deque(f, lines))
    except OSError as e:
        return f"({e})\n"


def start_server(binary, work):
    data = os.path.join(work, "data")
    os.makedirs(data, exist_ok=True)
    log = open(os.path.join(work, "serve.log"), "wb")
    proc = subprocess.Popen([binary, "serve", "--listen", "127.0.0.1:0", "--data", data],
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=log,
                            start_new_session=True)
    log.close()   # the child holds its own copy
    # A thread reads stdout so that neither a silent server nor a chatty one can block us:
    # the first line goes to the queue, the rest is drained.
    lines = queue.Queue()

    def reader():
        for raw in proc.stdout:
            lines.put(raw.decode(errors="replace").rstrip("\r\n"))
        lines.put(None)

    threading.Thread(target=reader, daemon=True).start()
    try:
        first = lines.get(timeout=max(0.1, deadline(15) - time.monotonic()))
    except queue.Empty:
        raise Failure("the server printed no 'listening on' line within 15 s") from None
    prefix = "listening on http://127.0.0.1:"
    if first is None or not first.startswith(prefix) or not first[len(prefix):].isdigit():
        raise Failure(f"expected '{prefix}PORT' as the server's first line, got {first!r} "
                      f"(exit status {proc.poll()})")
    return proc, first[len("listening on "):]


def start_chromium(work):
    profile = os.path.join(work, "profile")
    shutil.rmtree(profile, ignore_errors=True)   # a stale DevToolsActivePort would mislead us
    log = open(os.path.join(work, "chromium.log"), "wb")
    proc = subprocess.Popen(
        [os.environ.get("CHROMIUM", "chromium"), "--headless=new", "--no-sandbox", "--disable-gpu",
         "--no-first-run", "--no-default-browser-check", f"--user-data-dir={profile}",
         "--remote-debugging-port=0", "--remote-debugging-address=127.0.0.1",
         "--autoplay-policy=no-user-gesture-required", "about:blank"],
        stdin=subprocess.DEVNULL, stdout=log, stderr=log, start_new_session=True)
    log.close()
    port_file = os.path.join(profile, "DevToolsActivePort")

    def port():
        if proc.poll() is not None:
            raise Failure(f"chromium exited with status {proc.returncode}")
        try:
            with open(port_file) as f:
                first = f.readline().strip()
        except OSError:
            return None
        return int(first) if first.isdigit() else None   # may be caught half-written

    devtools = wait_for("chromium's DevToolsActivePort", port, 20)
    with urllib.request.urlopen(f"http://127.0.0.1:{devtools}/json/list", timeout=5) as r:
        targets = json.load(r)
    pages = [t for t in targets if t.get("type") == "page" and t.get("webSocketDebuggerUrl")]
    if not pages:
        raise Failure(f"no page target in chromium's /json/list: {targets}")
    return proc, pages[0]["webSocketDebuggerUrl"]


class Cdp:
    """The least of the DevTools protocol: one call at a time, events kept for diagnostics."""

    def __init__(self, url):
        # suppress_origin: Chromium refuses DevTools websockets whose Origin it does not allow.
        self.ws = websocket.create_connection(url, timeout=10, suppress_origin=True)
        self.next_id = 0
        self.events = collections.deque(maxlen=50)

    def call(self, method, timeout=10, **params):
        self.next_id += 1
        mid = self.next_id
        self.ws.send(json.dumps({"id": mid, "method": method, "params": params}))
        end = deadline(timeout)
        while True:
            left = end - time.monotonic()
            if left <= 0:
                raise Failure(f"no answer to {method} within {timeout} s")
            self.ws.settimeout(left)
            try:
                msg = json.loads(self.ws.recv())
            except websocket.WebSocketTimeoutException:
                continue   # the loop's deadline check decides
            if msg.get("id") != mid:
                if msg.get("method") in ("Runtime.exceptionThrown", "Runtime.consoleAPICalled"):
                    self.events.append(msg)
                continue
            if "error" in msg:
                raise Failure(f"{method} failed: {msg['error']}")
            return msg.get("result", {})

    def eval(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                           awaitPromise=True)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            raise Failure(f"page script failed: {text}\n  in: {expression}")
        return result["result"].get("value")

    def replace_text(self, text):
        """Selects all of #scene and types text over it, as a user pasting would."""
        self.eval("(() => { const s = document.getElementById('scene'); s.focus(); s.select(); })()")
        self.call("Input.insertText", text=text)
        typed = self.eval("document.getElementById('scene').value")
        if typed != text:
            raise Failure(f"#scene holds {typed!r} after typing, expected {text!r}")

    def close(self):
        try:
            self.ws.close()
        except Exception:
            pass


PROBLEMS_JS = """[...document.querySelectorAll('#problems li')]
                   .map(li => ({line: li.dataset.line, text: li.textContent}))"""
STATUS_JS = "document.getElementById('status').textContent"


def run(cdp, base):
    cdp.call("Runtime.enable")
    cdp.call("Page.navigate", url=base + "/")
    wait_for("the page to load", lambda: cdp.eval(
        "document.readyState === 'complete' && !!document.getElementById('scene')"), 15)

    # 1. A scene with a negative radius: the problem names the radius, on its line.
    cdp.replace_text(BAD_SCENE)

    def radius_problem():
        for p in cdp.eval(PROBLEMS_JS) or []:
            if "radius" in p["text"]:
                return p
        return None

    problem = wait_for("a problem about the radius in #problems", radius_problem, 10)
    if problem["line"] != str(BAD_LINE):
        raise Failure(f"the radius problem is on line {problem['line']}, expected {BAD_LINE}: "
                      f"{problem['text']!r}")
    if not problem["text"].startswith(f"line {BAD_LINE}, column "):
        raise Failure(f"the problem's text should start 'line {BAD_LINE}, column ': "
                      f"{problem['text']!r}")
    if not cdp.eval(f"!!document.querySelector('#gutter .bad[data-line=\"{BAD_LINE}\"]')"):
        raise Failure(f"gutter line {BAD_LINE} is not marked bad")
    # Clicking the problem selects its line in the editor.
    selected = cdp.eval(f"""(() => {{
        document.querySelector('#problems li[data-line="{BAD_LINE}"]').click();
        const s = document.getElementById('scene');
        return s.value.slice(s.selectionStart, s.selectionEnd); }})()""")
    if selected != "    radius: -0.2":
        raise Failure(f"clicking the problem selected {selected!r}, expected line {BAD_LINE}")
    found = problem["text"]

    # 2. Too fast for a crowd: a warning on the velocity's line, and it would render.
    cdp.replace_text(FAST_SCENE)
    warning = wait_for("one warning in #problems and '1 warning'", lambda: cdp.eval(
        f"({PROBLEMS_JS}).length === 1 && /^1 warning$/.test({STATUS_JS})") and
        cdp.eval(PROBLEMS_JS)[0], 10)
    if warning["line"] != str(FAST_LINE) or ": warning: " not in warning["text"]:
        raise Failure(f"expected a warning on line {FAST_LINE}: {warning!r}")
    if not cdp.eval(f"!!document.querySelector('#gutter .warn[data-line=\"{FAST_LINE}\"]') && "
                    "!document.querySelector('#gutter .bad')"):
        raise Failure(f"gutter line {FAST_LINE} is not marked as a warning (and nothing bad)")

    # 3. Fixed: no problems.
    cdp.replace_text(GOOD_SCENE)
    wait_for("an empty problem list and 'No problems'", lambda: cdp.eval(
        f"({PROBLEMS_JS}).length === 0 && /no problems/i.test({STATUS_JS})"), 10)

    # 4. Render, and watch the video play.
    rendered_at = time.monotonic()
    cdp.eval("document.getElementById('render').click()")

    def playing():
        state = cdp.eval("""(() => {
            const v = document.getElementById('video'), s = document.getElementById('status');
            if (v.src && v.readyState >= 2 && v.paused) v.play().catch(() => {});
            return {src: v.src, ready: v.readyState, time: v.currentTime,
                    error: v.error && v.error.message, failed: s.className === 'err',
                    status: s.textContent}; })()""")
        if state["failed"]:
            raise Failure(f"the page reports an error: {state['status']!r}")
        if state["error"]:
            raise Failure(f"the video element failed: {state['error']}")
        return state["src"] and state["ready"] >= 2 and state["time"] > 0

    wait_for("#video to play the render", playing, 60)
    href = cdp.eval("document.getElementById('download').href")
    if not href or not href.startswith("blob:"):
        raise Failure(f"#download has no blob href: {href!r}")
    status = cdp.eval(STATUS_JS)
    return found, time.monotonic() - rendered_at, status


def main():
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} DISCREEL_BIN WORK_DIR")
    binary, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    server = browser = cdp = None
    try:
        server, base = start_server(binary, work)
        browser, ws_url = start_chromium(work)
        cdp = Cdp(ws_url)
        found, render_s, status = run(cdp, base)
        print(f"browser_test: ok: problem at {found!r}; render played after {render_s:.1f} s "
              f"({status}); {time.monotonic() - START:.1f} s in all")
        return 0
    except Exception as e:
        print(f"browser_test: FAILED: {e}", file=sys.stderr)
        if cdp is not None:
            try:
                print("page #status:", repr(cdp.eval(STATUS_JS)), file=sys.stderr)
                print("page #problems:", cdp.eval(PROBLEMS_JS), file=sys.stderr)
            except Exception as inner:
                print(f"(could not read the page: {inner})", file=sys.stderr)
            for event in cdp.events:
                print("page event:", json.dumps(event.get("params"))[:500], file=sys.stderr)
        print("--- serve.log (tail) ---\n" + tail(os.path.join(work, "serve.log")), file=sys.stderr)
        print("--- chromium.log (tail) ---\n" + tail(os.path.join(work, "chromium.log"), 10),
              file=sys.stderr)
        return 1
    finally:
        if cdp is not None:
            cdp.close()
        stop(browser, "chromium")
        stop(server, "the server")


if __name__ == "__main__":
    sys.exit(main())
