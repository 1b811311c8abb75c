"""Output paths checked before the work: a folder that refuses writes, a file where a folder
belongs (or the reverse), an image format nobody can write. One-line ValueErrors."""

from __future__ import annotations

import tempfile
from pathlib import Path


def check_output_file(path, what: str = "--out", suffixes=None) -> Path:
    """A file we are about to write: not a folder, its folder writable, a known suffix."""
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"{what} {path} is a folder; give a file name")
    if suffixes is not None and path.suffix.lower().lstrip(".") not in suffixes:
        known = ", ".join(f".{s}" for s in sorted(suffixes))
        raise ValueError(f"{what} {path}: unknown file type {path.suffix!r}; use one of {known}")
    _check_writable(path.parent, what, path)
    return path


def check_output_folder(path, what: str = "--out") -> Path:
    """A folder we are about to fill: not an existing file, and writable (or creatable)."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"{what} {path} is a file, not a folder")
    _check_writable(path, what, path)
    return path


def check_image_file(path, what: str = "--report") -> Path:
    """A figure file: a format that matplotlib writes (png, pdf, svg, ...)."""
    return check_output_file(path, what, suffixes=image_suffixes())


def image_suffixes() -> set[str]:
    from matplotlib.figure import Figure

    return set(Figure().canvas.get_supported_filetypes())


def _check_writable(folder: Path, what: str, path: Path) -> None:
    existing = folder
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if not existing.is_dir():
        raise ValueError(f"{what} {path}: {existing} is a file, not a folder")
    try:  # the only check that also holds for root, read-only mounts and ACLs
        with tempfile.TemporaryFile(dir=existing):
            pass
    except OSError as exc:
        raise ValueError(f"{what} {path}: cannot write in {existing} ({exc.strerror})") from None


__all__ = ["check_image_file", "check_output_file", "check_output_folder", "image_suffixes"]
