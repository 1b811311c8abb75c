"""The progress display of compare_models: one bar over every candidate's fits, with an ETA."""

from __future__ import annotations

from .progress import StepProgress


class CompareProgress(StepProgress):
    """A bar counting the fits (candidates x folds, and the winner's final fit), naming the
    current candidate and fold. Silent unless ``enabled`` and the output is a terminal."""

    def __init__(self, enabled: bool, total: int):
        super().__init__(enabled, total, "comparing", "fits")
