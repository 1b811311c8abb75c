"""MkDocs hook: the pages' equations as MathML, written into the HTML when the site is built.

``pymdownx.arithmatex`` (generic mode, mkdocs.yml) leaves each formula as its LaTeX source:
``\\(...\\)`` inline in ``<span class="arithmatex">``, ``\\[...\\]`` as a block in
``<div class="arithmatex">``. This hook converts each with latex2mathml into a ``<math>``
element, which every current browser lays out itself: the site loads no math engine, script or
font, and reads offline from disk (file://build/docs). A formula that latex2mathml cannot
convert stops the build, naming the page and the formula.
"""

import html
import re

from latex2mathml.converter import convert
from mkdocs.exceptions import PluginError

# what arithmatex writes (generic mode): the LaTeX with <, > and & escaped, in its delimiters
FORMULA = re.compile(
    r'<(?P<tag>span|div) class="arithmatex">\s*'
    r"(?:\\\((?P<inline>.*?)\\\)|\\\[(?P<block>.*?)\\\])"
    r"\s*</(?P=tag)>",
    flags=re.S,
)
# latex2mathml writes a command it does not know as the text "\\name"
UNKNOWN = re.compile(r">(\\[A-Za-z]+)<")


def to_mathml(latex: str, block: bool) -> str:
    """One formula's MathML: a ``<math>`` element, ``display="block"`` for a block; a
    command latex2mathml does not know is a ValueError."""
    mathml = convert(latex.strip(), display="block" if block else "inline")
    unknown = UNKNOWN.search(mathml)
    if unknown:
        raise ValueError(f"latex2mathml does not know {unknown[1]}")
    return mathml


def on_page_content(content, page, config, files):
    def replace(match: re.Match) -> str:
        block = match["block"] is not None
        latex = html.unescape(match["block"] if block else match["inline"])
        try:
            mathml = to_mathml(latex, block)
        except Exception as err:  # latex2mathml raises its own classes and plain ones
            raise PluginError(f"{page.file.src_uri}: {latex!r} is not MathML: {err}") from err
        return f'<div class="equation">{mathml}</div>' if block else mathml

    return FORMULA.sub(replace, content)
