"""Regenerate docs/images/report-castle.png, the screenshot in docs/report.md.

Run from the repository root with the package installed and Chromium on PATH:
    python docs/make_report_screenshot.py
It writes the castle's report with `ggc report` and photographs its first screen with
headless Chromium (`--screenshot`).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "images" / "report-castle.png"


def main() -> int:
    chromium = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                     if shutil.which(n)), None)
    if chromium is None:
        sys.exit("no chromium on PATH (apt-get install chromium)")
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / "castle.html"
        subprocess.run([sys.executable, "-m", "report.ggc", "report",
                        "examples/castle.gg", "-o", str(page),
                        "--gallery", "3", "--no-times"], check=True, cwd=ROOT)
        subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                        "--hide-scrollbars", f"--user-data-dir={tmp}/profile",
                        "--window-size=1280,1400", f"--screenshot={OUT}", page.as_uri()],
                       check=True, capture_output=True)
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
