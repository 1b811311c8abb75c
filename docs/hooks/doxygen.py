"""MkDocs hook: serve Doxygen's HTML reference of the C++ headers at ``cpp/`` in the site.

``make docs`` runs Doxygen (``Doxyfile``: build/doxygen/html, warnings are errors) before
``mkdocs build``. Adding its files to the site's file list, rather than copying them after the
build, lets ``--strict`` check the links into ``cpp/`` like any other link.
"""

from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

HTML = Path("build/doxygen/html")
SITE_FOLDER = "cpp"


def on_files(files, config):
    html = Path(config.config_file_path).parent / HTML
    if not (html / "index.html").is_file():
        raise PluginError(f"no C++ reference in {html}: run `doxygen Doxyfile` (make docs does)")
    for path in sorted(p for p in html.rglob("*") if p.is_file()):
        uri = f"{SITE_FOLDER}/{path.relative_to(html).as_posix()}"
        files.append(File.generated(config, uri, abs_src_path=str(path)))
    return files
