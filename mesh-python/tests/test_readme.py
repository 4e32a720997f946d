"""The README's example runs as written (on the shared bunny)."""

import pathlib
import re
import shutil
import subprocess
import sys

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def test_the_readme_example_runs(data_dir, tmp_path):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    assert blocks, "no python example in the README"
    shutil.copy(data_dir / "npm_bunny.obj", tmp_path / "bunny.obj")
    out = subprocess.run([sys.executable, "-c", blocks[0]], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "0"  # the bunny's genus
    assert (tmp_path / "bunny-curvature.ply").is_file()
