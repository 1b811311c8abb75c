"""Optional dependencies: imported where a feature uses them, never at ``import tendonsheath``.

``pip install tendonsheath`` simulates, identifies, compensates and runs the command line; the
extras of pyproject.toml add one feature each (the HTML report, HDF5 and Excel logs, ...). A
feature used without its extra raises :class:`MissingExtraError`, one line that names the
package and the install command; the command line prints it as ``error: ...`` (exit 2).
"""

from __future__ import annotations

import sys
from types import ModuleType


class MissingExtraError(ImportError):
    """A feature needs an optional package that is not installed.

    An ImportError (``except ImportError`` catches it) whose message is one line:
    ``"<feature> needs <package>: pip install 'tendonsheath[<extra>]'"``; its ``name`` is the
    package, its ``extra`` and ``feature`` attributes the other two.

    Parameters
    ----------
    package : str
        The package that is not installed, e.g. ``"plotly"``.
    extra : str
        The extra of pyproject.toml that installs it, e.g. ``"report"``.
    feature : str
        What needs it, in words, e.g. ``"the HTML report"``.
    """

    def __init__(self, package: str, extra: str, feature: str) -> None:
        super().__init__(
            f"{feature} needs {package}: pip install 'tendonsheath[{extra}]'", name=package
        )
        self.extra = extra
        self.feature = feature


def require(module: str, *, extra: str, feature: str) -> ModuleType:
    """Import ``module`` (e.g. ``"plotly.graph_objects"``), or say which extra installs it.

    Parameters
    ----------
    module : str
        The module to import; its top-level package is the one named in the error.
    extra : str
        The extra of pyproject.toml that installs it.
    feature : str
        What needs it, in words (the error's subject), e.g. ``"the HTML report"``.

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        The module cannot be imported.
    """
    try:  # the import statement's own hook (builtins.__import__), so that it can be replaced
        __import__(module)
    except ImportError as exc:
        raise MissingExtraError(module.partition(".")[0], extra, feature) from exc
    return sys.modules[module]


def require_plotly(module: str = "plotly") -> ModuleType:
    """Plotly (or ``module``, one of its modules) for the HTML report's interactive figures.

    Parameters
    ----------
    module : str, default "plotly"
        The module to import, e.g. ``"plotly.graph_objects"``.

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        Plotly is not installed (the ``report`` extra).
    """
    return require(module, extra="report", feature="the HTML report")
