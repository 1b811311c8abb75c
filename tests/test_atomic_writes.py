"""Atomic outputs: an interrupted write leaves the old file (or none) and no temporary."""

import json
import os

import numpy as np
import pytest

from tendonsheath import io
from tendonsheath._util import atomic as _atomic


class Interrupted(KeyboardInterrupt):
    pass


def test_an_interrupted_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "model.json"
    _atomic.write_json(target, {"a": 1})
    with pytest.raises(Interrupted), _atomic.atomic_path(target) as tmp:
        tmp.write_text('{"a": 2, "half')
        raise Interrupted
    assert json.loads(target.read_text()) == {"a": 1}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.json"]


def test_a_failed_csv_write_leaves_nothing(tmp_path, monkeypatch):
    def boom(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(np, "savetxt", boom)
    with pytest.raises(OSError, match="disk full"):
        io.write_csv(tmp_path / "pred.csv", {"a": np.arange(3.0)})
    assert list(tmp_path.iterdir()) == []


def test_written_files_get_the_usual_permissions(tmp_path):
    umask = os.umask(0o022)
    os.umask(umask)
    path = _atomic.write_text(tmp_path / "r.html", "<p>x</p>")
    assert path.read_text() == "<p>x</p>"
    assert (path.stat().st_mode & 0o777) == (0o666 & ~umask)


def test_figures_keep_their_format(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    png = _atomic.save_figure(fig, tmp_path / "f.png", dpi=50)
    svg = _atomic.save_figure(fig, tmp_path / "f.svg")
    plt.close(fig)
    assert png.read_bytes().startswith(b"\x89PNG") and b"<svg" in svg.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "f.svg"]
