"""The log readers: measured recordings in (CSV and other text tables, NumPy, HDF5, Excel,
ROS bags) as a :class:`Log`, and CSV out."""

from .log import MAX_UPSAMPLING, MIN_ROWS, Log, columns, deg2rad, rad2deg, read_log, write_csv

__all__ = [
    "Log",
    "MAX_UPSAMPLING",
    "MIN_ROWS",
    "columns",
    "deg2rad",
    "rad2deg",
    "read_log",
    "write_csv",
]
