"""docs/python_api.ipynb runs headless from top to bottom (nbclient, Debian's python3 kernel), so that the
worked example cannot rot. It runs a copy: the committed notebook and its outputs are left as they are."""
import os
import time

from conftest import REPO

NOTEBOOK = os.path.join(REPO, "docs", "python_api.ipynb")


def test_the_worked_notebook_runs(lk):
    import nbformat
    from nbclient import NotebookClient
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger warns about frozen modules
    start = time.monotonic()
    # The kernel inherits this process's environment: PYTHONPATH (lane_keeping) and LK_BIN_DIR.
    NotebookClient(notebook, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": os.path.join(REPO, "docs")}}).execute()
    elapsed = time.monotonic() - start
    outputs = "".join(o.get("text", "") for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs)
    assert "critical tau2 = 1.763006 ms" in outputs
    assert "verdict: steering_friction" in outputs
    images = sum("image/png" in o.get("data", {}) for cell in notebook.cells if cell.cell_type == "code"
                 for o in cell.outputs)
    assert images == 4
    print(f"notebook ran in {elapsed:.1f} s")
