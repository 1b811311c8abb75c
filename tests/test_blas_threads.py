"""The jobs' one-thread BLAS covers SciPy's own OpenBLAS too, which ``import tendonsheath`` no
longer loads (threadpoolctl limits only the libraries loaded when it is asked): a fit that
loaded it inside the limit summed on every core, and the demo's figures moved."""

import json
import subprocess
import sys

CHECK = """
import json
import threadpoolctl
import tendonsheath
from tendonsheath._util.blas import one_blas_thread
with one_blas_thread():
    import scipy.linalg  # what a fit imports inside the limit
    inside = [(i["filepath"], i["num_threads"]) for i in threadpoolctl.threadpool_info()
              if i["user_api"] == "blas"]
print(json.dumps(inside))
"""


def test_one_blas_thread_holds_scipys_blas_loaded_after_the_package():
    out = subprocess.run(
        [sys.executable, "-c", CHECK], capture_output=True, text=True, check=True, timeout=120
    ).stdout
    blas = json.loads(out.strip().splitlines()[-1])
    assert any("scipy" in path for path, _ in blas), blas  # SciPy's own library is there
    assert all(threads == 1 for _, threads in blas), blas
