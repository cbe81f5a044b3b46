#!/usr/bin/env python3
"""End-to-end test of the studio on the `discreel serve` page, in headless Chromium.

    python3 tests/serve/studio_browser_test.py DISCREEL_BIN WORK_DIR

Types a scene and sees the preview change; scrubs; steps with the keyboard; plays and sees
frames advance; clicks a body and sees its data and its line; restarts the server and sees the
page reconnect; reloads (the scene kept in localStorage) and compares the preview's bytes with
`discreel render --at` at the same size. Writes WORK_DIR/studio.png, the screenshot docs/serve.md shows. Exit 0 on pass.
The server, Chromium and the DevTools plumbing are browser_test.py's.
"""
import base64
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402

SCENE = """version: 1
video:
  size: [320, 180]
  fps: 30
  duration: 2.0
  background: "#0f1419"
physics:
  gravity: [0, -9.81]
  restitution: 0.7
walls:
  - box: [[0, 0], [3.2, 1.8]]
    thickness: 0.05
discs:
  - id: peg
    position: [1.6, 0.9]
    radius: 0.25
    static: true
    color: "#888888"
  - id: ball
    position: [0.6, 1.4]
    velocity: [2.5, 0]
    radius: 0.15
    color: "#f4d35e"
  - position: [2.6, 1.2]
    velocity: [-1, 0.5]
    radius: 0.2
    color: "#17bebb"
"""
PEG_LINE = SCENE.split("\n").index("  - id: peg") + 1
# A disc at rest on the floor from the start: its contact is under it in every frame, at pixel
# (240, 257) of the 480x270 preview (the fitted camera: 270 / 1.98 pixels a metre about the
# walls' centre, (1.6, 0.9)).
RESTING = """version: 1
video: {size: [320, 180], fps: 30, duration: 2}
walls:
  - box: [[0, 0], [3.2, 1.8]]
discs:
  - {position: [1.6, 0.2], radius: 0.2, color: "#17bebb"}
"""
# Red pixels (the debug drawing's contact dots) around (x, y) in the preview.
RED_NEAR_JS = """((x, y) => {
    const img = document.getElementById('preview');
    const c = document.createElement('canvas');
    c.width = img.naturalWidth; c.height = img.naturalHeight;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(x - 6, y - 6, 13, 13).data;
    let red = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] > 200 && d[i + 1] < 110 && d[i + 2] < 110) red++;
    return red;
})"""
SIZE = "480x270"

FRAME_JS = "document.getElementById('preview').dataset.frame"
# The preview's pixels, summed into a short fingerprint, once it has loaded: drawn through a
# canvas, which the page's CSP allows (a blob image is same-origin).
PREVIEW_PIXELS_JS = """(() => {
    const img = document.getElementById('preview');
    if (!img.src || !img.complete || !img.naturalWidth) return null;
    const c = document.createElement('canvas');
    c.width = img.naturalWidth; c.height = img.naturalHeight;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let h1 = 0, h2 = 0;
    for (let i = 0; i < d.length; i++) { h1 = (h1 + d[i]) % 65521; h2 = (h2 + h1) % 65521; }
    return {frame: img.dataset.frame, pixels: h1 + ':' + h2, width: img.naturalWidth};
})()"""
# The preview's PNG bytes, base64, once it has loaded.
PREVIEW_BYTES_JS = """(async () => {
    const img = document.getElementById('preview');
    if (!img.src || !img.complete || !img.naturalWidth) return null;
    const src = img.src, frame = img.dataset.frame;
    const bytes = new Uint8Array(await (await fetch(src)).arrayBuffer());
    if (img.src !== src || img.dataset.frame !== frame) return null;   // replaced meanwhile
    let text = '';
    for (const b of bytes) text += String.fromCharCode(b);
    return {frame: img.dataset.frame, png: btoa(text), width: img.naturalWidth};
})()"""


def preview(cdp, frame=None, probe_js=PREVIEW_PIXELS_JS):
    """The preview once it shows `frame` (any frame if None) at the preview size."""
    def probe():
        got = cdp.eval(probe_js)
        if got and got["width"] == 480 and (frame is None or got["frame"] == str(frame)):
            return got
        return None
    return bt.wait_for(f"the preview of frame {frame}", probe, 15)


def key(cdp, name, code, shift=False):
    modifiers = 8 if shift else 0
    for kind in ("keyDown", "keyUp"):
        cdp.call("Input.dispatchKeyEvent", type=kind, key=name, code=code,
                 windowsVirtualKeyCode={"ArrowRight": 39, "ArrowLeft": 37, " ": 32}[name],
                 modifiers=modifiers)


def run(cdp, base, binary, work, stop_server, start_server):
    cdp.call("Runtime.enable")
    cdp.call("Emulation.setDeviceMetricsOverride", width=1280, height=720, deviceScaleFactor=1,
             mobile=False)
    cdp.call("Page.navigate", url=base + "/")
    bt.wait_for("the page to load", lambda: cdp.eval(
        "document.readyState === 'complete' && !!document.getElementById('preview')"), 15)

    # 1. Typed: the preview follows the text.
    shown = preview(cdp, 0)   # the page's own scene
    cdp.replace_text(SCENE)
    first = bt.wait_for("the preview of the typed scene", lambda: (lambda p: p if p and p[
        "pixels"] != shown["pixels"] else None)(cdp.eval(PREVIEW_PIXELS_JS)), 10)
    cdp.replace_text(SCENE.replace('"#888888"', '"#d03030"'))
    bt.wait_for("the preview to change with the text",
                lambda: (cdp.eval(PREVIEW_PIXELS_JS) or first)["pixels"] != first["pixels"], 10)
    cdp.replace_text(SCENE)
    bt.wait_for("the preview to come back", lambda: (cdp.eval(PREVIEW_PIXELS_JS) or {}).get(
        "pixels") == first["pixels"], 10)

    # 2. Scrubbed to frame 45.
    cdp.eval("(() => { const s = document.getElementById('scrub'); s.value = 45;"
             " s.dispatchEvent(new Event('input')); })()")
    preview(cdp, 45)

    # 3. The keyboard: a frame on, a second back (Shift), outside the editor.
    cdp.eval("document.activeElement.blur()")
    key(cdp, "ArrowRight", "ArrowRight")
    preview(cdp, 46)
    key(cdp, "ArrowLeft", "ArrowLeft", shift=True)
    preview(cdp, 16)
    key(cdp, "ArrowLeft", "ArrowLeft", shift=True)
    preview(cdp, 0)

    # 4. Played: frames advance on their own, to the end of the clip.
    key(cdp, " ", "Space")
    seen = set()

    def advancing():
        frame = cdp.eval(FRAME_JS)
        seen.add(frame)
        return len(seen) >= 10 and frame
    bt.wait_for("ten frames while playing", advancing, 15)
    bt.wait_for("the play to end at the last frame", lambda: cdp.eval(
        "document.getElementById('play').textContent === 'Play'") and cdp.eval(FRAME_JS) == "59",
        15)

    # 5. The contacts' ticks and a click on the peg at the frame's centre.
    cdp.eval("(() => { const s = document.getElementById('scrub'); s.value = 10;"
             " s.dispatchEvent(new Event('input')); })()")
    preview(cdp, 10)
    box = cdp.eval("(() => { const r = document.getElementById('preview')"
                   ".getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; })()")
    x, y = box[0] + box[2] / 2, box[1] + box[3] / 2
    for kind in ("mousePressed", "mouseReleased"):
        cdp.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left", clickCount=1)
    picked = bt.wait_for("the peg's data", lambda: "peg (static)" in (cdp.eval(
        "document.getElementById('picked').textContent") or "") and cdp.eval(
        "document.getElementById('picked').textContent"), 10)
    if "velocity (0.000, 0.000) m/s" not in picked or f"line {PEG_LINE} " not in picked:
        raise bt.Failure(f"the picked body's data is wrong: {picked!r}")
    if not cdp.eval(f"!!document.querySelector('#gutter .pick[data-line=\"{PEG_LINE}\"]')"):
        raise bt.Failure(f"the peg's line {PEG_LINE} is not marked in the gutter")
    ticks = bt.wait_for("the contacts' ticks", lambda: cdp.eval(
        "events.length"), 10)

    shot = cdp.call("Page.captureScreenshot", format="png")
    with open(os.path.join(work, "studio.png"), "wb") as f:
        f.write(base64.b64decode(shot["data"]))

    # 6. Debug drawing: ticking "contacts" draws the resting disc's contact, a red dot under it.
    cdp.replace_text(RESTING)
    teal_js = """(() => { const img = document.getElementById('preview');
        if (!img.naturalWidth) return false;
        const c = document.createElement('canvas'); c.width = img.naturalWidth;
        c.height = img.naturalHeight; const g = c.getContext('2d'); g.drawImage(img, 0, 0);
        const d = g.getImageData(240, 230, 1, 1).data;
        return d[0] < 60 && d[1] > 150 && d[2] > 150; })()"""
    bt.wait_for("the resting disc in the preview", lambda: cdp.eval(teal_js), 10)
    plain = cdp.eval(PREVIEW_PIXELS_JS)
    if cdp.eval(RED_NEAR_JS + "(240, 257)") != 0:
        raise bt.Failure("red under the disc before any debug drawing was ticked")
    cdp.eval("document.querySelector('#debug input[value=contacts]').click()")
    red = bt.wait_for("a red contact dot under the disc", lambda: (
        cdp.eval(PREVIEW_PIXELS_JS) or plain)["pixels"] != plain["pixels"] and cdp.eval(
        RED_NEAR_JS + "(240, 257)"), 10)
    cdp.eval("document.querySelector('#debug input[value=contacts]').click()")
    bt.wait_for("the dot gone again", lambda: (cdp.eval(PREVIEW_PIXELS_JS) or {}).get(
        "pixels") == plain["pixels"], 10)
    cdp.replace_text(SCENE)
    bt.wait_for("the studio scene again", lambda: (cdp.eval(PREVIEW_PIXELS_JS) or {}).get(
        "pixels") not in (None, plain["pixels"]), 10)

    # 7. The server goes away while the page asks for a frame, and comes back: the page says it
    # is reconnecting, asks again, and shows the frame.
    stop_server()
    cdp.eval("(() => { const s = document.getElementById('scrub'); s.value = 33;"
             " s.dispatchEvent(new Event('input')); })()")
    bt.wait_for("'Reconnecting' in the status", lambda: "Reconnecting" in (cdp.eval(
        bt.STATUS_JS) or ""), 10)
    start_server()
    preview(cdp, 33)
    bt.wait_for("'Connected again' in the status", lambda: "Connected again" in (cdp.eval(
        bt.STATUS_JS) or ""), 10)

    # 8. The bytes of frame 20 are `discreel render --at`'s at this size. Reading them back
    # needs connect-src blob:, which the page's CSP (rightly) leaves out: the test turns the CSP
    # off for this last step only, and the page comes back with its scene from localStorage.
    cdp.call("Page.setBypassCSP", enabled=True)
    cdp.eval("window.beforeReload = true")   # gone once the new document is there
    cdp.call("Page.reload", ignoreCache=True)
    bt.wait_for("the page to load again", lambda: cdp.eval(
        "!window.beforeReload && document.readyState === 'complete' && "
        "document.getElementById('scene').value") == SCENE, 15)
    preview(cdp, 0)
    # The scrubber's range is the clip's once the first frame has said how long it is.
    bt.wait_for("the scrubber's range", lambda: cdp.eval(
        "Number(document.getElementById('scrub').max)") > 20, 15)
    cdp.eval("(() => { const s = document.getElementById('scrub'); s.value = 20;"
             " s.dispatchEvent(new Event('input')); })()")
    scrubbed = preview(cdp, 20, PREVIEW_BYTES_JS)
    with open(os.path.join(work, "studio.yaml"), "w") as f:
        f.write(SCENE)
    cli = os.path.join(work, "cli.png")
    subprocess.run([binary, "render", os.path.join(work, "studio.yaml"), "--at", str(20 / 30),
                    "--size", SIZE, "-o", cli, "-q"], check=True, timeout=30)
    with open(cli, "rb") as f:
        if base64.b64decode(scrubbed["png"]) != f.read():
            with open(os.path.join(work, "preview.png"), "wb") as out:
                out.write(base64.b64decode(scrubbed["png"]))
            raise bt.Failure("the preview of frame 20 (preview.png) differs from "
                             "`discreel render --at` (cli.png)")
    return ticks


def main():
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} DISCREEL_BIN WORK_DIR")
    binary, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    server = browser = cdp = None
    try:
        server, base = bt.start_server(binary, work)
        port = base.rsplit(":", 1)[1]

        def stop_server():
            bt.stop(server, "the server")

        def start_server():   # on the same port and store
            nonlocal server
            with open(os.path.join(work, "serve2.log"), "wb") as log:
                server = subprocess.Popen(
                    [binary, "serve", "--listen", "127.0.0.1:" + port, "--data",
                     os.path.join(work, "data")], stdin=subprocess.DEVNULL,
                    stdout=subprocess.DEVNULL, stderr=log, start_new_session=True)

        browser, ws_url = bt.start_chromium(work)
        cdp = bt.Cdp(ws_url)
        ticks = run(cdp, base, binary, work, stop_server, start_server)
        print(f"studio_browser_test: ok: {ticks} contacts on the timeline; "
              f"{time.monotonic() - bt.START:.1f} s in all")
        return 0
    except Exception as e:
        print(f"studio_browser_test: FAILED: {e}", file=sys.stderr)
        if cdp is not None:
            try:
                print("page #status:", repr(cdp.eval(bt.STATUS_JS)), file=sys.stderr)
            except Exception as inner:
                print(f"(could not read the page: {inner})", file=sys.stderr)
            for event in cdp.events:
                print("page event:", str(event.get("params"))[:500], file=sys.stderr)
        print("--- serve.log (tail) ---\n" + bt.tail(os.path.join(work, "serve.log")),
              file=sys.stderr)
        return 1
    finally:
        if cdp is not None:
            cdp.close()
        bt.stop(browser, "chromium")
        bt.stop(server, "the server")


if __name__ == "__main__":
    sys.exit(main())
