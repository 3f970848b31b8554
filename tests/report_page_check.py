#!/usr/bin/python3
"""tests/report_page_check.py PAGE.html SHOT.png: loads PAGE in headless Chromium (Debian's
`chromium`) as a reader would open plots/out/index.html, offline, and checks it.

  1. --dump-dom after the load: the page's inline script has written into #imgcheck how many of
     its images loaded (naturalWidth > 0); all of them must have, and there must be at least one.
  2. --screenshot SHOT.png (1280 x 2400) with --log-net-log: the screenshot is a PNG, and no
     request made on behalf of the page (network isolation key of the file:// page) went to
     anything but file: or data:.  Every host name resolves to nothing (--host-resolver-rules),
     so no request leaves the machine even from the browser's own services.
  3. The page holds no http(s):// URL in a src or href attribute.
Exit 0: passed; 77: Chromium absent (skipped, said on stderr); 1: failed (why on stderr).
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--host-resolver-rules=MAP * ~NOTFOUND", "--virtual-time-budget=10000"]


def chromium(args, timeout=120):
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    with tempfile.TemporaryDirectory(prefix="haff-chromium-") as prof:
        return subprocess.run([exe] + FLAGS + ["--user-data-dir=" + prof] + args,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              timeout=timeout, check=False)


def fail(msg):
    print("report_page_check: " + msg, file=sys.stderr)
    return 1


def main():
    if len(sys.argv) != 3:
        return fail("usage: report_page_check.py PAGE.html SHOT.png")
    page, shot = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if not (shutil.which("chromium") or shutil.which("chromium-browser")):
        print("report_page_check: chromium not installed (make deps): skipped", file=sys.stderr)
        return 77
    url = "file://" + page
    with open(page, encoding="utf-8") as f:
        text = f.read()
    ext = re.findall(r"""(?:src|href)\s*=\s*['"]?\s*(https?:[^'" >]*)""", text, re.I)
    if ext:
        return fail("%s: links to the network: %s" % (page, ", ".join(ext[:3])))
    dom = chromium(["--dump-dom", url]).stdout.decode("utf-8", "replace")
    m = re.search(r"""id=["']imgcheck["'][^>]*""", dom)
    if not m:
        return fail("no #imgcheck in the loaded page (did its script run?): %.300s" % dom)
    lo = re.search(r'data-loaded="(\d+)"', m.group(0))
    to = re.search(r'data-total="(\d+)"', m.group(0))
    if not lo or not to:
        return fail("#imgcheck not written by the page's script: %s" % m.group(0))
    loaded, total = int(lo.group(1)), int(to.group(1))
    if total == 0 or loaded != total:
        return fail("%d of %d images loaded" % (loaded, total))
    with tempfile.TemporaryDirectory(prefix="haff-netlog-") as d:
        log = os.path.join(d, "net.json")
        if os.path.exists(shot):
            os.unlink(shot)
        chromium(["--screenshot=" + shot, "--window-size=1280,2400", "--log-net-log=" + log, url])
        with open(shot, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return fail("%s: not a PNG" % shot)
        with open(log, encoding="utf-8") as f:
            net = json.load(f)
    types = {v: k for k, v in net["constants"]["logEventTypes"].items()}
    page_reqs, bad = 0, []
    for e in net["events"]:
        p = e.get("params") or {}
        if types.get(e["type"]) != "URL_REQUEST_START_JOB" or "url" not in p:
            continue
        if "file://" not in str(p.get("network_isolation_key", "")):
            continue  # the browser's own (update, accounts): not the page's, and blocked anyway
        page_reqs += 1
        if not p["url"].startswith(("file:", "data:")):
            bad.append(p["url"])
    if bad:
        return fail("the page requested the network: " + ", ".join(bad[:3]))
    print("report_page_check: %d of %d images loaded, %d page requests (none to the network), "
          "screenshot %s" % (loaded, total, page_reqs, shot))
    return 0


if __name__ == "__main__":
    sys.exit(main())
