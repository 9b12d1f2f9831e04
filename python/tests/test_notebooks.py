"""The example notebooks run from top to bottom (their cells check themselves numerically),
and show what a notebook should: dqsym's LaTeX and the walkthrough page."""

import pathlib

import nbclient
import nbformat
import pytest

from conftest import ROOT

NOTEBOOKS = sorted((ROOT / "examples" / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert NOTEBOOKS, "examples/notebooks/ has no notebook"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path: pathlib.Path):
    nb = nbformat.read(path, as_version=4)
    assert all(c.get("outputs", []) == [] for c in nb.cells if c.cell_type == "code"), (
        "commit notebooks without outputs"
    )
    # Raises CellExecutionError, with the cell and the traceback, if any cell fails.
    nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}}
    ).execute()
    kinds = [
        set(o.get("data", {})) for c in nb.cells if c.cell_type == "code" for o in c.outputs
    ]
    assert any("text/latex" in k for k in kinds), "no LaTeX output"
    pages = [
        o["data"]["text/html"]
        for c in nb.cells
        if c.cell_type == "code"
        for o in c.outputs
        if "text/html" in o.get("data", {})
    ]
    assert any("<iframe srcdoc=" in p and "katex" in p for p in pages), "no walkthrough page"
