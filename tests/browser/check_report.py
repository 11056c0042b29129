#!/usr/bin/env python3
"""Opens a report's index.html in headless Chromium and fails on anything a reader would see broken.

    check_report.py CHROMIUM REPORT_DIR SCREENSHOT.png [--verdict-first] [--anchors ID,ID,...] [--near-top ID,...]
                    [--section-shot ID OUT.png] [--shot-height PX]

Talks to Chromium over the DevTools protocol on a pipe (--remote-debugging-pipe: file descriptors 3 and 4, JSON
messages ended by NUL), so no network port and no extra package is needed. Fails (exit status 1, one line per
problem) on: a console error or warning of level error, an uncaught exception, a resource that failed to load, an
image whose naturalWidth is 0, a page without lang, title or table of contents, a page that scrolls sideways at 1200 px
(a wide table scrolls in its own box); with --verdict-first, a page whose first screen (1200 x 900) does not show the
heading "Verdict", its engine table and its coloured engine x quantity matrix whole; with --anchors, a listed id that
is not a heading's (a part's anchor is its key, the same in every report: #torsion); with --near-top, a listed heading
that does not begin within the first two screens (a scene's section, #your-engine-STEM, right after the verdict). With
--section-shot, OUT.png is a picture of the section that heading ID opens (down to the next heading of its level or
above), as README shows one; --shot-height cuts the picture at PX pixels. Keeps a full-page screenshot, and SCREENSHOT_first.png of the first screen.
The page is opened from the file system with the network disabled: the report must work offline.
"""
import base64
import json
import os
import subprocess
import sys
import tempfile
import time


class DevTools:
    def __init__(self, chromium, profile):
        to_child_r, self.to_child = os.pipe()
        self.from_child, from_child_w = os.pipe()
        os.set_inheritable(to_child_r, True)
        os.set_inheritable(from_child_w, True)

        def fds():  # fds 3 and 4 in the child, as --remote-debugging-pipe expects
            os.dup2(to_child_r, 3)
            os.dup2(from_child_w, 4)

        self.process = subprocess.Popen(
            [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
             "--user-data-dir=" + profile, "--no-first-run", "--no-default-browser-check",
             "--proxy-server=127.0.0.1:9", "--proxy-bypass-list=<-loopback>", "about:blank"],
            preexec_fn=fds, close_fds=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child_r)
        os.close(from_child_w)
        self.buffer = b""
        self.next_id = 0
        self.events = []

    def send(self, method, params=None, session=None):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self.to_child, json.dumps(message).encode() + b"\0")
        wanted = self.next_id
        deadline = time.time() + 60
        while time.time() < deadline:
            reply = self.read()
            if reply.get("id") == wanted:
                if "error" in reply:
                    raise RuntimeError(method + ": " + json.dumps(reply["error"]))
                return reply.get("result", {})
            self.events.append(reply)
        raise RuntimeError(method + ": no reply within 60 s")

    def read(self):
        while b"\0" not in self.buffer:
            chunk = os.read(self.from_child, 1 << 20)
            if not chunk:
                raise RuntimeError("chromium closed the DevTools pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def wait_for(self, method, seconds=60):
        deadline = time.time() + seconds
        while time.time() < deadline:
            for event in self.events:
                if event.get("method") == method:
                    return event
            self.events.append(self.read())
        raise RuntimeError("no " + method + " within %d s" % seconds)

    def close(self):
        try:
            self.send("Browser.close")
        except Exception:
            pass
        try:
            self.process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()


def main():
    chromium, report_dir, screenshot = sys.argv[1:4]
    verdict_first = "--verdict-first" in sys.argv[4:]
    anchors = []
    if "--anchors" in sys.argv[4:]:
        anchors = sys.argv[sys.argv.index("--anchors") + 1].split(",")
    near_top = []
    if "--near-top" in sys.argv[4:]:
        near_top = sys.argv[sys.argv.index("--near-top") + 1].split(",")
    section_shot = None
    if "--section-shot" in sys.argv[4:]:
        at = sys.argv.index("--section-shot")
        section_shot = (sys.argv[at + 1], sys.argv[at + 2])
    shot_height = None
    if "--shot-height" in sys.argv[4:]:
        shot_height = int(sys.argv[sys.argv.index("--shot-height") + 1])
    index = os.path.abspath(os.path.join(report_dir, "index.html"))
    if not os.path.isfile(index):
        print("check_report: no index.html in " + report_dir)
        return 1
    problems = []
    with tempfile.TemporaryDirectory() as profile:
        tools = DevTools(chromium, profile)
        try:
            target = tools.send("Target.createTarget", {"url": "about:blank"})["targetId"]
            session = tools.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
            for domain in ("Page", "Runtime", "Log", "Network"):
                tools.send(domain + ".enable", session=session)
            tools.send("Emulation.setDeviceMetricsOverride",
                       {"width": 1200, "height": 900, "deviceScaleFactor": 1, "mobile": False}, session=session)
            tools.send("Page.navigate", {"url": "file://" + index}, session=session)
            tools.wait_for("Page.loadEventFired")
            time.sleep(0.5)  # late console messages
            state = tools.send("Runtime.evaluate", {"returnByValue": True, "expression": """({
                lang: document.documentElement.lang,
                title: document.title,
                toc: document.querySelectorAll('nav a[href^="#"]').length,
                images: document.images.length,
                broken: Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0).map(i => i.getAttribute('src')),
                anchors: Array.from(document.querySelectorAll('nav a[href^="#"]')).filter(a => !document.getElementById(a.getAttribute('href').slice(1))).map(a => a.getAttribute('href')),
                sideways: document.documentElement.scrollWidth - innerWidth,
                headings: Array.from(document.querySelectorAll('h2[id], h3[id]')).map(h => h.id),
                verdict: (() => {
                    const h = Array.from(document.querySelectorAll('h2')).find(e => e.textContent.trim() === 'Verdict');
                    if (!h) return ['no heading "Verdict"'];
                    const problems = [], tables = [];
                    for (let e = h.nextElementSibling; e && e.tagName !== 'H2' && e.tagName !== 'NAV'; e = e.nextElementSibling)
                        if (e.tagName === 'TABLE') tables.push(e);
                        else if (e.querySelector && e.querySelector('table')) tables.push(e.querySelector('table'));
                    if (tables.length < 2) problems.push('the verdict has no engine table and matrix');
                    for (const t of tables) {
                        const bottom = Math.round(t.getBoundingClientRect().bottom);
                        if (bottom > innerHeight) problems.push('a table of the verdict ends below the first screen (' + bottom + ' px > ' + innerHeight + ' px)');
                    }
                    if (!document.querySelector('td.mark0, td.mark1, td.mark2, td.mark3')) problems.push('the matrix has no coloured cell');
                    return problems;
                })()
            })"""}, session=session)["result"]["value"]
            tops = tools.send("Runtime.evaluate", {"returnByValue": True, "expression": "(" + json.dumps(near_top) + """)
                .map(id => [id, document.getElementById(id), innerHeight])
                .map(([id, e, h]) => [id, e ? e.getBoundingClientRect().top + scrollY : -1, h])"""}, session=session)["result"]["value"]
            for anchor, top, height in tops:
                if top < 0:
                    problems.append("no heading #" + anchor + " for --near-top")
                elif top > 2 * height:
                    problems.append("#%s begins at %d px, below the first two screens (%d px)" % (anchor, top, 2 * height))
            if section_shot:
                box = tools.send("Runtime.evaluate", {"returnByValue": True, "expression": """(() => {
                    const h = document.getElementById(%s);
                    if (!h) return null;
                    const level = Number(h.tagName[1]);
                    let end = h.nextElementSibling;
                    while (end && !(/^H[1-6]$/.test(end.tagName) && Number(end.tagName[1]) <= level)) end = end.nextElementSibling;
                    const top = h.getBoundingClientRect().top + scrollY;
                    const bottom = end ? end.getBoundingClientRect().top + scrollY : document.documentElement.scrollHeight;
                    const left = h.parentElement.getBoundingClientRect().left;
                    return {x: Math.max(0, left - 8), y: top - 8, width: Math.min(innerWidth, h.parentElement.getBoundingClientRect().width + 16), height: bottom - top};
                })()""" % json.dumps(section_shot[0])}, session=session)["result"].get("value")
                if not box:
                    problems.append("no heading #" + section_shot[0] + " for --section-shot")
                else:
                    box["scale"] = 1
                    if shot_height:
                        box["height"] = min(box["height"], shot_height)
                    shot = tools.send("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True, "clip": box},
                                      session=session)
                    with open(section_shot[1], "wb") as out:
                        out.write(base64.b64decode(shot["data"]))
            first = tools.send("Page.captureScreenshot", {"format": "png"}, session=session)
            with open(screenshot[:-4] + "_first.png" if screenshot.endswith(".png") else screenshot + "_first", "wb") as out:
                out.write(base64.b64decode(first["data"]))
            shot = tools.send("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True}, session=session)
            with open(screenshot, "wb") as out:
                out.write(base64.b64decode(shot["data"]))
            for event in tools.events:
                method, params = event.get("method"), event.get("params", {})
                if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
                    problems.append("console error: " + json.dumps(params.get("args"))[:300])
                elif method == "Runtime.exceptionThrown":
                    problems.append("uncaught exception: " + json.dumps(params.get("exceptionDetails"))[:300])
                elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
                    entry = params["entry"]
                    problems.append("error: " + entry.get("text", "") + " " + entry.get("url", ""))
                elif method == "Network.loadingFailed":
                    problems.append("failed to load: " + params.get("errorText", "") + " (request " + params.get("requestId", "") + ")")
        finally:
            tools.close()
    if state["lang"] != "en":
        problems.append("the page has no lang=\"en\"")
    if not state["title"]:
        problems.append("the page has no title")
    if state["toc"] < 2:
        problems.append("the page has no table of contents")
    if state["images"] == 0:
        problems.append("the page has no image")
    for src in state["broken"]:
        problems.append("image did not load: " + src)
    for href in state["anchors"]:
        problems.append("table of contents link to nothing: " + href)
    if state["sideways"] > 0:
        problems.append("the page scrolls sideways at 1200 px by %d px" % state["sideways"])
    for anchor in anchors:
        if anchor not in state["headings"]:
            problems.append("no heading with the anchor #" + anchor)
    if verdict_first:
        problems += ["the first screen: " + p for p in state["verdict"]]
    for p in problems:
        print("check_report: " + p)
    print("check_report: %d images, %d contents entries, screenshot %s: %s" %
          (state["images"], state["toc"], screenshot, "OK" if not problems else "%d problems" % len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
