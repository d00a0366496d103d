"""Tool poses for many recorded runs on Dask: a Parquet dataset and a manifest of runs.

``run_batch(runs, out, frame, relative_to=...)`` is what ``pinframes batch`` runs. This
package needs the ``batch`` extra (``pip install "pinframes[batch]"``: dask.distributed and
pyarrow); ``import pinframes`` never imports it.
"""

from ._driver import BatchSummary, run_batch
from ._manifest import MANIFEST_NAME
from ._partition import POSES_FOLDER, partition_path
from ._runs import Run, find_runs

__all__ = ["MANIFEST_NAME", "POSES_FOLDER", "BatchSummary", "Run", "find_runs",
           "partition_path", "run_batch"]
