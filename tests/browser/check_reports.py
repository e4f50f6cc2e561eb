#!/usr/bin/env python3
"""Renders femup's report.html pages in headless Chromium and fails on what a
reader would see as broken: a console error or a failed load, an image that did
not decode, a section with nothing in it, a reference to the network, or a page
wider than a laptop screen.

    check_reports.py [--screenshot-dir DIR] REPORT.html...

Needs Debian's chromium, chromium-driver and python3-selenium (scripts/setup.sh).
Prints one line per page; exit status 1 when any page fails, 2 on bad usage.
"""
import argparse
import os
import sys

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

LAPTOP = (1366, 768)

# Everything the checks need, read in one script run inside the page.
PROBE = r"""
const sections = [...document.querySelectorAll('section')].map(s => {
  const heading = s.querySelector('h2');
  const body = [...s.children].filter(c => c !== heading);
  const text = body.map(c => c.innerText || '').join('').trim();
  return {id: s.id, heading: heading ? heading.innerText.trim() : '',
          text: text.length, images: s.querySelectorAll('img').length};
});
const images = [...document.images].map(i => ({
  alt: i.alt, complete: i.complete, width: i.naturalWidth,
  inline: i.src.startsWith('data:')}));
const refs = [...document.querySelectorAll('[src],[href]')]
  .map(e => e.getAttribute('src') || e.getAttribute('href'))
  .filter(u => /^(https?:)?\/\//i.test(u));
const resources = performance.getEntriesByType('resource').map(r => r.name)
  .filter(u => !u.startsWith('data:'));
return {title: document.title, h1: (document.querySelector('h1') || {}).innerText || '',
        sections, images, refs, resources,
        scrollWidth: document.documentElement.scrollWidth,
        innerWidth: window.innerWidth,
        stylesheets: document.querySelectorAll('link[rel=stylesheet]').length,
        scripts: document.scripts.length};
"""


def problems_of(page):
    found = []
    if not page["title"] or not page["h1"].strip():
        found.append("no title or heading")
    if not page["sections"]:
        found.append("no section")
    for s in page["sections"]:
        if not s["heading"]:
            found.append(f"section '{s['id']}' has no heading")
        if s["text"] == 0 and s["images"] == 0:
            found.append(f"section '{s['heading'] or s['id']}' is empty")
    for i in page["images"]:
        if not i["complete"] or i["width"] == 0:
            found.append(f"image '{i['alt']}' did not load")
        if not i["inline"]:
            found.append(f"image '{i['alt']}' is not inline")
    for u in page["refs"] + page["resources"]:
        found.append(f"reaches the network or a file beside it: {u}")
    if page["stylesheets"]:
        found.append("links an external stylesheet")
    if page["scrollWidth"] > page["innerWidth"]:
        found.append(f"wider than the window ({page['scrollWidth']} px in "
                     f"{page['innerWidth']} px)")
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reports", nargs="+")
    parser.add_argument("--screenshot-dir")
    parser.add_argument("--full-page", action="store_true",
                        help="screenshots of the whole page, not the first screen")
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    parser.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    args = parser.parse_args()
    for tool in (args.chromium, args.chromedriver):
        if not os.access(tool, os.X_OK):
            print(f"check_reports: {tool} not found (scripts/setup.sh installs "
                  "chromium and chromium-driver)", file=sys.stderr)
            return 2
    missing = [r for r in args.reports if not os.path.isfile(r)]
    if missing:
        print(f"check_reports: no such report: {', '.join(missing)}", file=sys.stderr)
        return 2

    options = webdriver.ChromeOptions()
    options.binary_location = args.chromium
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu",
              "--disable-dev-shm-usage", f"--window-size={LAPTOP[0]},{LAPTOP[1]}"):
        options.add_argument(a)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(args.chromedriver), options=options)
    failed = 0
    try:
        for n, report in enumerate(args.reports):
            path = os.path.abspath(report)
            driver.get("file://" + path)
            page = driver.execute_script(PROBE)
            logs = [e for e in driver.get_log("browser")
                    if e["level"] in ("SEVERE", "WARNING")]
            found = problems_of(page) + [f"console: {e['message']}" for e in logs]
            if args.screenshot_dir:
                os.makedirs(args.screenshot_dir, exist_ok=True)
                label = os.path.basename(os.path.dirname(path)) or "report"
                if args.full_page:
                    height = driver.execute_script(
                        "return document.documentElement.scrollHeight")
                    driver.set_window_size(LAPTOP[0], height)
                driver.save_screenshot(os.path.join(args.screenshot_dir,
                                                    f"{n + 1:02d}_{label}.png"))
                if args.full_page:
                    driver.set_window_size(*LAPTOP)
            if found:
                failed += 1
                print(f"FAIL {report}:")
                for f in found:
                    print(f"  - {f}")
            else:
                print(f"ok   {report}: {len(page['sections'])} sections, "
                      f"{len(page['images'])} plots")
    finally:
        driver.quit()
    print(f"{len(args.reports) - failed} of {len(args.reports)} reports render cleanly")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
