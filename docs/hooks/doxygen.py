"""MkDocs hook: serve Doxygen's HTML reference of the C++ headers at ``cpp/reference/``.

``make docs`` runs Doxygen (``Doxyfile``: build/doxygen/html, warnings are errors) before
``mkdocs build``. Adding its files to the site's file list, rather than copying them after the
build, lets ``--strict`` check the links into the reference like any other link. The page
docs/cpp.md is served at ``cpp/index.html`` itself, hence the subfolder; a file that would
overwrite a page of the site stops the build.
"""

from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

HTML = Path("build/doxygen/html")
SITE_FOLDER = "cpp/reference"


def on_files(files, config):
    html = Path(config.config_file_path).parent / HTML
    if not (html / "index.html").is_file():
        raise PluginError(f"no C++ reference in {html}: run `doxygen Doxyfile` (make docs does)")
    taken = {f.dest_uri for f in files}
    for path in sorted(p for p in html.rglob("*") if p.is_file()):
        uri = f"{SITE_FOLDER}/{path.relative_to(html).as_posix()}"
        generated = File.generated(config, uri, abs_src_path=str(path))
        if generated.dest_uri in taken:
            raise PluginError(f"the C++ reference's {uri} would overwrite a page of the site")
        files.append(generated)
    return files
