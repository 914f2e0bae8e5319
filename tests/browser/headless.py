"""What the browser checks share: failing with the check's name, and finding Chromium
(Debian's chromium, installed by `scripts/bootstrap --tests`). Standard library only."""
import os
import shutil
import sys


def fail(msg):
    """Ends the check: its name (the script's), FAIL and why, on stderr; exit code 1."""
    name = os.path.splitext(os.path.basename(sys.argv[0]))[0]
    print(f"{name}: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    fail("no chromium on PATH: install it with `scripts/bootstrap --tests` (Debian package chromium)")
