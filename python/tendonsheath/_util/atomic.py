"""Atomic output files: every file is written to a temporary file in the same folder and
renamed over the target only when complete, so an interrupted command (Ctrl-C, a crash, a
full disk) leaves the old file or none, never a half-written one."""

from __future__ import annotations

import errno
import json
import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

_UMASK = os.umask(0o022)
os.umask(_UMASK)


@contextmanager
def atomic_path(path) -> Iterator[Path]:
    """Yields a temporary path beside ``path`` (same suffix) to write to; on success it is
    renamed to ``path``, on any exception (KeyboardInterrupt included) it is removed."""
    path = Path(path)
    _check_folder(path)
    fd, tmp_name = tempfile.mkstemp(
        prefix=f".{path.name}.", suffix=f".tmp{path.suffix}", dir=path.parent
    )
    os.close(fd)
    tmp = Path(tmp_name)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_UMASK)  # mkstemp makes it private; outputs get the usual mode
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def _check_folder(path: Path) -> None:
    """The folder ``path`` goes in exists: else the error names it (mkstemp's own would name
    the hidden temporary file)."""
    folder = path.parent
    if folder.is_dir():
        return
    if folder.exists():
        raise NotADirectoryError(
            errno.ENOTDIR, f"cannot write {path.name}: not a folder", str(folder)
        )
    raise FileNotFoundError(errno.ENOENT, f"cannot write {path.name}: no such folder", str(folder))


def write_bytes(path, data: bytes) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)


def write_text(path, text: str) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def write_json(path, obj, **kwargs) -> Path:
    return write_text(path, json.dumps(obj, indent=2, **kwargs) + "\n")


def save_figure(fig, path, **kwargs) -> Path:
    """``fig.savefig`` through a temporary file (the format from the target's suffix)."""
    path = Path(path)
    kwargs.setdefault("format", path.suffix.lstrip(".").lower() or None)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, **kwargs)
    return path
