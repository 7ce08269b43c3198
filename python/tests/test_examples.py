"""The examples in python/examples run (each in a temporary folder, on coarser grids where they offer one)."""
import os
import pathlib
import runpy

import pytest

EXAMPLES = sorted((pathlib.Path(__file__).parent.parent / "examples").glob("*.py"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("SPHSTAB_EXAMPLE_STEP", "0.2")  # coarser sweeps, smaller blocks: the test checks that it runs
    monkeypatch.setenv("SPHSTAB_EXAMPLE_BLOCK", "8")
    monkeypatch.setenv("SPHSTAB_EXAMPLE_RINGS", "0.5,1,2")  # smaller rings: a dense J of ~600 states
    monkeypatch.setenv("MPLBACKEND", "Agg")
    runpy.run_path(str(path), run_name="__main__")
    assert list(tmp_path.glob("*.png")), "the example saves its figure"


def test_fig_3_2_example_is_about_ten_lines():
    text = (pathlib.Path(__file__).parent.parent / "examples" / "fig_3_2_critical_tension.py").read_text()
    code = [l for l in text.splitlines() if l.strip() and not l.lstrip().startswith("#")]
    assert len(code) <= 12, code


def test_the_readme_session_runs(tmp_path, monkeypatch, capsys):
    """The ten-line session in README.md (its ```python block) runs as printed."""
    readme = (pathlib.Path(__file__).parent.parent.parent / "README.md").read_text()
    start = readme.index("```python\n") + len("```python\n")
    code = readme[start:readme.index("```", start)]
    lines = [l for l in code.splitlines() if l.strip() and not l.lstrip().startswith("#")]
    assert len(lines) <= 12, lines
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert out.strip(), "the session prints its results"
