"""A sweep's finished runs on disk, as they finish, so that an interrupted sweep resumes.

One JSON line per finished run (``{"i": index, "params": ..., "value": ...}``) after a
header line naming the sweep (design, seed, number of runs, and a caller's ``tag``, e.g. a
hash of the sweep file). Lines are appended and flushed as each batch comes back, so Ctrl-C
or a crash loses at most the batches still running; a line cut off by the interruption is
ignored. Resuming checks that every stored run has the parameters the plan gives it, so the
runs of another sweep are never mixed in. Failed runs are not stored: a resume runs them again.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, TextIO

import numpy as np

FORMAT = "tendonsheath-sweep-runs/1"


def _plain(value) -> Any:
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return repr(value)


def _canonical(params: dict) -> str:
    return json.dumps(params, sort_keys=True, default=_plain)


class Checkpoint:
    """``path``: the JSON-lines file; ``plan``: the sweep's :class:`Plan`."""

    def __init__(self, path, plan, tag: str | None = None):
        self.path = Path(path)
        self.plan = plan
        self.header = {
            "format": FORMAT,
            "design": plan.kind,
            "seed": plan.seed,
            "runs": len(plan.runs),
            "tag": tag,
        }
        self._file: TextIO | None = None

    def load(self) -> dict[int, tuple[Any, None]]:
        """The finished runs stored for this very sweep (empty when there is no file); a
        ValueError when the file holds another sweep's runs."""
        if not self.path.is_file():
            return {}
        lines = self.path.read_text(encoding="utf-8").splitlines()
        if not lines:
            return {}
        other = f"{self.path} holds the runs of another sweep"
        try:
            header = json.loads(lines[0])
        except json.JSONDecodeError:
            raise ValueError(f"{other} (or is not a runs file); remove it") from None
        if header != self.header:
            diff = [k for k in self.header if header.get(k) != self.header[k]]
            raise ValueError(f"{other} (its {', '.join(diff)} differ); remove it to start afresh")
        done: dict[int, tuple[Any, None]] = {}
        for k, line in enumerate(lines[1:], start=2):
            try:
                rec = json.loads(line)
            except json.JSONDecodeError:
                if k == len(lines):  # the last line, cut off by the interruption
                    break
                raise ValueError(f"{self.path}, line {k}: not a stored run") from None
            i = rec.get("i")
            if not (isinstance(i, int) and 0 <= i < len(self.plan.runs)):
                raise ValueError(f"{self.path}, line {k}: run index {i!r} is not in this sweep")
            if _canonical(rec.get("params")) != _canonical(self.plan.runs[i]):
                raise ValueError(f"{other} (run {i} had other parameters); remove it")
            done[i] = (rec["value"], None)
        return done

    def open(self, keep: bool) -> None:
        """Start appending (``keep``: after the stored runs; else a new file)."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fresh = not keep or not self.path.is_file() or self.path.stat().st_size == 0
        if not fresh:
            self._truncate_cut_line()
        self._file = open(self.path, "w" if fresh else "a", encoding="utf-8")  # noqa: SIM115
        if fresh:
            self._write(self.header)

    def _truncate_cut_line(self) -> None:
        data = self.path.read_bytes()
        if data and not data.endswith(b"\n"):
            self.path.write_bytes(data[: data.rfind(b"\n") + 1])

    def _write(self, record: dict) -> None:
        assert self._file is not None, "open() comes first"
        self._file.write(json.dumps(record, default=_plain) + "\n")

    def record(self, outcomes) -> None:
        """Append the successful runs of one batch and flush."""
        if self._file is None:
            return
        for index, value, error, _seconds in outcomes:
            if error is None:
                self._write({"i": index, "params": self.plan.runs[index], "value": value})
        self._file.flush()

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None


__all__ = ["Checkpoint", "FORMAT"]
