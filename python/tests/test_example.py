"""docs/examples/compare_designs.py runs and draws its figure."""
import os
import subprocess
import sys

import pytest

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "examples", "compare_designs.py")


def test_the_example_compares_two_designs(tmp_path):
    pytest.importorskip("matplotlib")
    figure = tmp_path / "designs.png"
    out = subprocess.run([sys.executable, EXAMPLE, "--replicates", "20", "--out", str(figure)],
                         check=True, capture_output=True, text=True, env=os.environ)
    assert "raised skirt: fails" in out.stdout and "raised skirt + chains:" in out.stdout
    assert figure.stat().st_size > 10_000 and figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
