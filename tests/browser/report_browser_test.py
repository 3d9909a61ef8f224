#!/usr/bin/python3
"""The HTML report in a real browser (ctest label `browser`).

Runs configs/quickstart.yaml into a temporary folder (`symembed run` writes the report), opens
the report in headless Chromium through the DevTools protocol (--remote-debugging-pipe: JSON
messages on file descriptors 3 and 4, no network) and checks that
  - no page loads with a console error, an uncaught exception or an entry in #report-errors;
  - the summary table shows every variant's summary.json (values exact in data-value, text to
    three significant digits), the pair table every row of pairs.csv, and its "flipped only"
    filter the pairs whose flip class is not none;
  - a pair view (the base variant's worst pair) decodes the pair's map exactly (a checksum
    against maps/A_B.map) and draws: in a screenshot of its canvas each of the four panels has
    mesh pixels (not the background) in many colours;
  - a second, small run whose variant remeshes the shapes (other meshes under the same names)
    draws that variant's pair on its own meshes (the checksum of its map, which fits only them).
Prints the time each page took to open. Exits 77 (ctest SKIP_RETURN_CODE) when no browser is
installed. Standard library only.

usage: report_browser_test.py --symembed BIN --config CONFIG [--screenshot PNG] [--keep DIR]
  --screenshot PNG  also save the pair view's canvas (the README's picture) to PNG
  --keep DIR        run in DIR and keep it (default: a temporary folder, removed)
"""
import argparse
import base64
import csv
import json
import os
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

SKIP = 77
BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
BACKGROUND = (247, 247, 247)  # viewer.js BACKGROUND, 0.97 * 255


class Failure(Exception):
    pass


def find_browser():
    override = os.environ.get("SYMEMBED_BROWSER")
    if override:
        return override if shutil.which(override) else None
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    """Headless Chromium driven over --remote-debugging-pipe."""

    def __init__(self, binary, profile):
        read_theirs, write_ours = os.pipe()   # we write commands, Chromium reads fd 3
        read_ours, write_theirs = os.pipe()   # Chromium writes fd 4, we read
        self.log = open(os.path.join(profile, "chromium.log"), "wb")
        # Software WebGL (SwiftShader) so that no GPU is needed; no --allow-file-access-from-files:
        # the page must work under the file:// rules a user's browser applies. --no-sandbox:
        # CI runs as root, where Chromium's sandbox cannot start; --disable-dev-shm-usage:
        # containers often have a small /dev/shm.
        args = [binary, "--headless", "--remote-debugging-pipe", "--no-sandbox",
                "--disable-dev-shm-usage", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                "--user-data-dir=" + profile, "--no-first-run", "--no-default-browser-check",
                "--disable-extensions", "--disable-background-networking", "--hide-scrollbars",
                "about:blank"]

        def child_fds():
            os.dup2(read_theirs, 3)
            os.dup2(write_theirs, 4)

        self.process = subprocess.Popen(args, pass_fds=(3, 4), preexec_fn=child_fds,
                                        stdout=self.log, stderr=self.log)
        os.close(read_theirs)
        os.close(write_theirs)
        self.out = write_ours
        self.inp = read_ours
        self.buffer = b""
        self.next_id = 0
        self.events = []
        self.session = None
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget",
                                 {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page.enable", "Runtime.enable", "Log.enable"):
            self.call(domain)
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": 1280, "height": 900, "deviceScaleFactor": 1, "mobile": False})

    def send(self, method, params):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if self.session and not method.startswith("Target."):
            message["sessionId"] = self.session
        os.write(self.out, json.dumps(message).encode() + b"\0")
        return self.next_id

    def receive(self, timeout):
        deadline = time.time() + timeout
        while b"\0" not in self.buffer:
            if time.time() > deadline:
                raise Failure("the browser did not answer within %g s" % timeout)
            ready, _, _ = select.select([self.inp], [], [], 0.2)
            if ready:
                chunk = os.read(self.inp, 1 << 20)
                if not chunk:
                    raise Failure("the browser exited (see chromium.log)")
                self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, params=None, timeout=60):
        wanted = self.send(method, params)
        while True:
            message = self.receive(timeout)
            if message.get("id") == wanted:
                if "error" in message:
                    raise Failure("%s: %s" % (method, message["error"]))
                return message.get("result", {})
            if "method" in message:
                self.events.append(message)

    def evaluate(self, expression, timeout=60):
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True}, timeout)
        if "exceptionDetails" in result:
            raise Failure("page script failed: %s\n%s" % (
                expression[:200], json.dumps(result["exceptionDetails"])[:2000]))
        return result["result"].get("value")

    def open(self, url, ready, timeout=60):
        """Loads url (from about:blank, so every page starts afresh) and waits until the
        expression `ready` is true; returns the seconds from navigation to ready."""
        self.call("Page.navigate", {"url": "about:blank"})
        self.events.clear()
        start = time.time()
        self.call("Page.navigate", {"url": url})
        while time.time() - start < timeout:
            if self.evaluate("document.readyState === 'complete' && !!(%s)" % ready):
                return time.time() - start
            time.sleep(0.05)
        raise Failure("%s: not ready within %d s (%s)" % (url, timeout, ready))

    def errors(self):
        """Console errors and uncaught exceptions since the last open()."""
        found = []
        for event in self.events:
            method, params = event["method"], event.get("params", {})
            if method == "Runtime.exceptionThrown":
                details = params["exceptionDetails"]
                found.append("exception: %s" % details.get("exception", {}).get(
                    "description", details.get("text")))
            elif method == "Runtime.consoleAPICalled" and params["type"] in ("error", "assert"):
                found.append("console.%s: %s" % (params["type"], " ".join(
                    str(a.get("value", a.get("description"))) for a in params["args"])))
            elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
                found.append("log: %s" % params["entry"]["text"])
        box = self.evaluate("(document.getElementById('report-errors') || {}).textContent || ''")
        if box:
            found.append("#report-errors: " + box)
        return found

    def close(self):
        try:
            self.send("Browser.close", {})
            self.process.wait(timeout=10)
        except Exception:
            self.process.kill()
            self.process.wait()
        self.log.close()


def read_png(data):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise Failure("not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour = header[:4]
    if depth != 8 or colour not in (2, 6):
        raise Failure("unsupported PNG (depth %d, colour type %d)" % (depth, colour))
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def check(condition, message):
    if not condition:
        raise Failure(message)


SUMMARY_KEYS = {  # summary table column (experiment.js) -> path in summary.json
    "pairs": ["pairs"], "failed_pairs": ["failed_pairs"], "mean_direct": ["mean_direct"],
    "median_direct": ["median_direct"], "mean_flip_tolerant": ["mean_flip_tolerant"],
    "auc_direct": ["auc_direct"], "auc_flip_tolerant": ["auc_flip_tolerant"],
    "flipped_left_right": ["flipped_pairs", "left_right"],
    "flipped_front_back": ["flipped_pairs", "front_back"],
    "flipped_up_down": ["flipped_pairs", "up_down"], "flipped_total": ["flipped_pairs", "total"],
    "time_total_s": ["time_total_s"], "time_per_shape_s": ["time_per_shape_s"],
    "time_per_pair_s": ["time_per_pair_s"], "peak_rss_mb": ["peak_rss_mb"],
}
for t in ("0.05", "0.10", "0.25"):
    SUMMARY_KEYS["pct_direct_" + t] = ["pct_direct", t]
    SUMMARY_KEYS["pct_flip_tolerant_" + t] = ["pct_flip_tolerant", t]


def check_summary_table(browser, results):
    cells = browser.evaluate("""Array.from(document.querySelectorAll('#summary-table tbody tr')).map(
        (tr) => Array.from(tr.cells).map((td) => [td.dataset.key, td.dataset.value || null, td.textContent]))""")
    variants = [v for v in open(os.path.join(results, "variants.txt")).read().split() if v]
    check(len(cells) == len(variants), "summary table: %d rows for %d variants" % (len(cells), len(variants)))
    for row, name in zip(cells, variants):
        summary = json.load(open(os.path.join(results, name, "summary.json")))
        by_key = {key: (value, text) for key, value, text in row}
        check(by_key["variant"][1] == name, "summary table: row %s for variant %s" % (by_key["variant"][1], name))
        for key, path in SUMMARY_KEYS.items():
            expected = summary
            for part in path:
                expected = expected[part]
            value, text = by_key[key]
            if expected is None:
                check(text == "n/a", "%s %s: shows %r for null" % (name, key, text))
                continue
            check(value is not None and float(value) == float(expected),
                  "%s %s: data-value %r, summary.json %r" % (name, key, value, expected))
            shown = float(text)
            tolerance = 0.0 if expected == 0 else 0.5 * 10 ** (len(str(int(abs(expected)))) - 3) \
                if abs(expected) >= 1 else abs(expected) * 0.006
            check(abs(shown - expected) <= tolerance + 1e-12,
                  "%s %s: shows %r for %r (3 significant digits)" % (name, key, text, expected))
    return len(variants)


def check_pair_table(browser, url, results):
    with open(os.path.join(results, "base", "pairs.csv"), newline="") as f:
        pairs = list(csv.DictReader(f))
    seconds = browser.open(url + "#pairs=base", "document.querySelector('#pair-table tbody tr')")
    rows = browser.evaluate("document.querySelectorAll('#pair-table tbody tr').length")
    check(rows == len(pairs), "pair table: %d rows, pairs.csv %d" % (rows, len(pairs)))
    shown = browser.evaluate("""Array.from(document.querySelectorAll('#pair-table tbody tr')).map(
        (tr) => [tr.querySelector('[data-key=source]').textContent, tr.querySelector('[data-key=target]').textContent,
                 Number(tr.querySelector('[data-key=mean_direct]').dataset.value)])""")
    by_pair = {(p["source"], p["target"]): float(p["mean_direct"]) for p in pairs if p["status"] == "ok"}
    for source, target, mean in shown:
        check(abs(by_pair[(source, target)] - mean) <= 1e-12 + 1e-7 * abs(mean),
              "pair table: %s -> %s mean %r, pairs.csv %r" % (source, target, mean, by_pair[(source, target)]))
    means = [m for _, _, m in shown]
    check(means == sorted(means, reverse=True), "pair table: not worst first by default")
    check(not browser.errors(), "pair table: %s" % browser.errors())
    flipped = sum(1 for p in pairs if p["status"] == "ok" and p["flip"] != "none")
    browser.open(url + "#pairs=base&flipped=1", "document.getElementById('pair-count')")
    rows = browser.evaluate("document.querySelectorAll('#pair-table tbody tr').length")
    check(rows == flipped, "flipped only: %d rows, pairs.csv has %d flipped" % (rows, flipped))
    check(not browser.errors(), "pair table (flipped): %s" % browser.errors())
    return seconds, pairs


def map_checksum(path):
    """pairs.js's checksum of a decoded map: sum of (i + 1) * (1-based target id), mod 1e9+7."""
    with open(path) as f:
        ids = [int(line) for line in f if line.strip()]
    return sum((i + 1) * t for i, t in enumerate(ids)) % 1000000007


def check_pair_view(browser, url, results, pair, screenshot, variant="base"):
    link = "#pair=%s/%s/%s" % (variant, pair["source"], pair["target"])
    seconds = browser.open(url + link,
                           "['drawn'].includes((document.getElementById('view-status') || {dataset: {}}).dataset.state) "
                           "|| document.getElementById('view-status').className === 'warning'", timeout=120)
    status = browser.evaluate("document.getElementById('view-status').textContent")
    check(browser.evaluate("document.getElementById('view-status').dataset.state") == "drawn",
          "pair view did not draw: %s" % status)
    check(not browser.errors(), "pair view: %s" % browser.errors())
    checksum = browser.evaluate("document.getElementById('view-status').dataset.mapChecksum")
    expected = map_checksum(os.path.join(results, variant, "maps", "%s_%s.map" % (pair["source"], pair["target"])))
    check(checksum == str(expected), "pair view: the decoded map's checksum %s, the map file's %d" % (checksum, expected))
    rect = browser.evaluate("(() => { const r = document.getElementById('viewer-canvas').getBoundingClientRect();"
                            " return [r.left + scrollX, r.top + scrollY, r.width, r.height]; })()")
    shot = browser.call("Page.captureScreenshot", {"format": "png", "clip": {
        "x": rect[0], "y": rect[1], "width": rect[2], "height": rect[3], "scale": 1},
        "captureBeyondViewport": True})
    png = base64.b64decode(shot["data"])
    if screenshot:
        with open(screenshot, "wb") as f:
            f.write(png)
    width, height, rows = read_png(png)
    for panel in range(4):
        x0, y0 = (panel % 2) * width // 2, (panel // 2) * height // 2
        mesh, colours, total = 0, set(), 0
        for y in range(y0 + 20, y0 + height // 2 - 2, 2):  # below the panel's label
            for x in range(x0 + 2, x0 + width // 2 - 2, 2):
                total += 1
                pixel = rows[y][x]
                if max(abs(pixel[k] - BACKGROUND[k]) for k in range(3)) > 12:
                    mesh += 1
                    colours.add(tuple(c // 8 for c in pixel))
        check(mesh > 0.02 * total, "panel %d: %d of %d pixels are not background: nothing drawn"
              % (panel, mesh, total))
        check(len(colours) > 20, "panel %d: only %d colours: not a coloured mesh" % (panel, len(colours)))
    return seconds, status


# A run whose variant loads other meshes under the shapes' names: the synthetic poses remeshed.
REMESHED_CONFIG = """name: remeshed
dataset: {format: synthetic, kinds: [humanoid], poses: 3, vertices: 600, seed: 3}
pipeline:
  sampling: {type: farthest_point, count: 80}
  symmetry: {type: plane3d}
  flip: {type: oracle}
evaluation: {geodesics: dijkstra}
variants:
  - {name: remeshed, set: {dataset.remesh: 400}}
"""


def run_remeshed(symembed, work):
    config = os.path.join(work, "remeshed.yaml")
    with open(config, "w") as f:
        f.write(REMESHED_CONFIG)
    results = os.path.join(work, "results", "remeshed")
    run = subprocess.run([os.path.abspath(symembed), "run", config, "--quiet", "--jobs", "2",
                          "--cache", os.path.join(work, "cache"), "--out", results],
                         cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check(run.returncode == 0, "symembed run (remeshed) failed:\n" + run.stdout)
    with open(os.path.join(results, "remeshed", "pairs.csv"), newline="") as f:
        pair = next(p for p in csv.DictReader(f) if p["status"] == "ok")
    return results, pair


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--symembed", required=True)
    parser.add_argument("--config", required=True)
    parser.add_argument("--screenshot")
    parser.add_argument("--keep")
    args = parser.parse_args()
    browser_binary = find_browser()
    if not browser_binary:
        print("SKIP: no browser installed (chromium; scripts/install-deps --browser installs it)")
        return SKIP

    work = args.keep or tempfile.mkdtemp(prefix="symembed_browser_")
    os.makedirs(work, exist_ok=True)
    try:
        results = os.path.join(work, "results", "quickstart")
        start = time.time()
        # cwd = work: the synthetic dataset's default cache is relative to the working directory.
        run = subprocess.run([os.path.abspath(args.symembed), "run", os.path.abspath(args.config), "--quiet", "--jobs", "2",
                              "--cache", os.path.join(work, "cache"), "--out", results],
                             cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print("run: %.1f s" % (time.time() - start))
        index = os.path.join(results, "report", "index.html")
        check(run.returncode == 0, "symembed run failed:\n" + run.stdout)
        check("report: " + index in run.stdout, "the run did not print its report's path:\n" + run.stdout)
        url = "file://" + index
        profile = os.path.join(work, "profile")
        os.makedirs(profile, exist_ok=True)
        browser = Browser(browser_binary, profile)
        try:
            seconds = browser.open(url, "document.querySelector('#summary-table tbody tr')")
            check(not browser.errors(), "experiment page: %s" % browser.errors())
            variants = check_summary_table(browser, results)
            for table in ("class-table", "flip-table", "shape-stage-table", "pair-stage-table"):
                check(browser.evaluate("document.querySelectorAll('#%s tbody tr').length" % table) == variants,
                      "experiment page: #%s lacks rows" % table)
            print("experiment page: %d variants, opened in %.2f s" % (variants, seconds))
            seconds, pairs = check_pair_table(browser, url, results)
            print("pair table: %d pairs, opened in %.2f s" % (len(pairs), seconds))
            # The worst pair: its map shows what the numbers say (the README's picture).
            pair = max((p for p in pairs if p["status"] == "ok"), key=lambda p: float(p["mean_direct"]))
            seconds, status = check_pair_view(browser, url, results, pair, args.screenshot)
            print("pair view %s -> %s: drawn in %.2f s (%s)" % (pair["source"], pair["target"], seconds, status))
            remeshed, pair = run_remeshed(args.symembed, work)
            url = "file://" + os.path.join(remeshed, "report", "index.html")
            seconds, status = check_pair_view(browser, url, remeshed, pair, None, variant="remeshed")
            print("remeshed pair view %s -> %s: drawn in %.2f s (%s)" % (pair["source"], pair["target"], seconds, status))
        finally:
            browser.close()
    except Failure as failure:
        print("FAIL: %s" % failure)
        return 1
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
