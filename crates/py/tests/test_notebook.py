"""The notebook docs/notebooks/paper-experiment.ipynb runs from top to bottom (nbclient, in its
own folder), so that it cannot rot; it must stay quick (under a minute)."""

import time

import pytest


def test_the_paper_experiment_notebook_runs(in_root):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("matplotlib")
    nb = nbformat.read(in_root / "docs/notebooks/paper-experiment.ipynb", as_version=4)
    start = time.perf_counter()
    nbclient.NotebookClient(
        nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(in_root / "docs/notebooks")}}
    ).execute()
    took = time.perf_counter() - start
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    assert any("mu_e,a" in o.get("text", "") for o in outputs)
    assert took < 60, f"the notebook took {took:.0f} s"
