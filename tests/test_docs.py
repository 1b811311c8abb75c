"""The documentation site's tutorials run as written (issue 14, item 5; issue 17, item 10).

Each page's Python blocks run in order in one namespace, in a temporary folder, as a reader
would paste them; a block with an ``if __name__ == "__main__":`` block is a script of its own and
runs as one, in a fresh interpreter (as in ``test_readme_snippets.py``). On the pages of
SHELL_PAGES the commands run too, in order with the Python blocks, and a C++ or TOML block the
page tells the reader to save is saved; what a page shows a command print (its ```text blocks)
is what it printed. A figure a page's prose quotes from what its code computes carries a
marker, an HTML comment right after it (the site and GitHub show nothing):

    at 0.135 <!-- check: cmp.row("Loaded(Backlash)")["ratio_to_affine"] ~ 0.135 -->

says that the expression, evaluated in the namespace the page's blocks ran in, rounds to the
quoted figure at its digits (0.135: three decimals; 6.0e-4: one in the mantissa); the figure
must stand in the page's text since the marker before (so the prose and the marker change
together; markers may also follow a paragraph or a block as a group, one a line). A marker
without ``~``, ``<!-- check: EXPR -->``, is a claim in words: EXPR must be true. A figure the
code no longer prints fails the page's test. (A figure quoted from benchmarks/results/*.json
carries a ``<!-- result: FILE KEY ~ FIGURE -->`` marker instead, which
``tools/readme_tables.py --check`` checks.) The scenario page's key table is checked
against the parser. Building the site with warnings as errors is ``make docs``, which
``make test`` runs.
"""

import importlib
import importlib.util
import inspect
import os
import re
import subprocess
import tomllib
from pathlib import Path
from xml.etree import ElementTree

import numpy as np
import pytest
from _snippets import MAIN_GUARD, python_blocks, run_as_script

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
SHARED_DATA = ROOT.parent / "shared" / "data"
# the pages whose blocks run: the tutorials and the guides that hold code
PAGES = [
    "index.md",
    "scenario-toml.md",
    *sorted(p.relative_to(DOCS).as_posix() for p in DOCS.glob("tutorials/*.md")),
]
# the only edits: run lengths (a sweep of 4 draws takes the same code path as 200)
SHORTER = {"n=200": "n=4"}
# the pages whose commands (```bash blocks) run too, in order with their Python blocks; the
# others' commands are installation steps (make demo, make test)
SHELL_PAGES = {
    "scenario-toml.md",
    "tutorials/compare-real-data.md",
    "tutorials/deploy.md",
    "tutorials/ros-bags.md",
}
# the only edits of a page's blocks: where this checkout's headers and the shared data are (the
# pages run from the repository's root, the test in a temporary folder); each must be used
EDITS = {
    "tutorials/deploy.md": {"-Iinclude": f"-I{ROOT / 'include'}", "build/cpp": f"{ROOT}/build/cpp"},
    "tutorials/compare-real-data.md": {"../shared/data": str(SHARED_DATA)},
}
FENCE = re.compile(r"^```(\w+)\n(.*?)^```", flags=re.S | re.M)
# a C++ or TOML block that a page tells the reader to save: its first line names the file
SAVED_AS = re.compile(r"\A(?://|#) file: (\S+)\n")


def page_blocks(page: str) -> list[str]:
    return python_blocks((DOCS / page).read_text())


def fenced_blocks(page: str) -> list[tuple[str, str]]:
    """(language, code) of every fenced block of ``page``, in order, with the page's EDITS."""
    edits = EDITS.get(page, {})
    text = (DOCS / page).read_text()
    for old in edits:
        assert old in text, f"docs/{page} no longer holds {old!r}"
    blocks = []
    for lang, code in FENCE.findall(text):
        for old, new in edits.items():
            code = code.replace(old, new)
        blocks.append((lang, code))
    return blocks


def text_blocks(page: str) -> list[str]:
    """The ```text blocks of ``page``: what its code prints, as the page shows it."""
    return [code for lang, code in fenced_blocks(page) if lang == "text"]


def _command_lines(code: str) -> list[str]:
    """A shell block's commands: continued lines joined, comments and blank lines left out."""
    joined = re.sub(r"\\\n\s*", "", code)
    return [line for line in joined.splitlines() if line.strip() and not line.startswith("#")]


def run_commands(code: str, folder: Path, source: str) -> str:
    """A page's shell block, command by command, in ``folder``; its standard output. A
    ``NAME=value`` line sets a variable for the lines after it; a ``tendonsheath`` command runs
    in this process (its arguments as the shell splits them, variables expanded), as the
    installed script would run it, without a fresh interpreter's start-up each time; any other
    runs in bash."""
    import shlex

    from typer.testing import CliRunner

    from tendonsheath.apps.cli import app

    env, out = dict(os.environ), []
    for line in _command_lines(code):
        if re.fullmatch(r"[A-Z_]+=\S+", line):
            name, _, value = line.partition("=")
            env[name] = value
        elif line.startswith("tendonsheath "):
            expand = re.compile(r"\$\{?(\w+)\}?")
            args = [expand.sub(lambda m: env[m[1]], a) for a in shlex.split(line)[1:]]
            done = CliRunner().invoke(app, args)
            assert done.exit_code == 0, f"{source}: {line}\n{done.output[-3000:]}"
            out.append(done.stdout)
        else:
            run = subprocess.run(
                ["bash", "-e", "-o", "pipefail", "-c", line],
                cwd=folder,
                env=env,
                capture_output=True,
                text=True,
                timeout=600,
            )
            why = f"{source}: {line}\n{run.stdout[-2000:]}{run.stderr[-3000:]}"
            assert run.returncode == 0, why
            out.append(run.stdout)
    return "".join(out)


def run_page(page: str, folder: Path) -> dict:
    """Every block of ``page`` in order: Python blocks in one namespace (a script with a main
    guard in a fresh interpreter), a C++ or TOML block whose first line is ``// file: NAME``
    (``# file: NAME``) saved as NAME,
    and the commands of SHELL_PAGES (their output in the namespace's ``_shell`` list)."""
    namespace: dict = {"__name__": "docs_page", "_shell": []}
    setup = SETUP.get(page)
    if setup is not None:
        setup(folder)
    for i, (lang, code) in enumerate(fenced_blocks(page)):
        where = f"docs/{page} block {i + 1}"
        if lang == "python" and MAIN_GUARD in code:
            run_as_script(code, folder / f"block_{i}.py", SHORTER, f"docs/{page}")
        elif lang == "python":
            exec(compile(code, where, "exec"), namespace)
        elif lang in ("cpp", "toml") and SAVED_AS.match(code):
            (folder / SAVED_AS.match(code)[1]).write_text(code)
        elif lang == "bash" and page in SHELL_PAGES:
            namespace["_shell"].append(run_commands(code, folder, where))
    return namespace


# a checked figure: <!-- check: EXPR ~ FIGURE --> (or a claim, <!-- check: EXPR -->)
CHECK = re.compile(r"<!-- check: (.+?) -->", flags=re.S)
FIGURE = r"-?\d+(?:\.\d+)?(?:e[+-]?\d+)?"


def rounds_to(value: float, figure: str) -> bool:
    """Whether ``value`` rounded to the digits ``figure`` shows is ``figure``."""
    mantissa, _, exponent = figure.lower().partition("e")
    digits = len(mantissa.partition(".")[2])
    shown = f"{value:.{digits}e}" if exponent else f"{value:.{digits}f}"
    return float(shown) == float(figure)


def quoted_figures_wrong(text: str, namespace: dict, page: str) -> list[str]:
    """Every marker of ``text`` whose figure (or claim) is not what the code computes, each as
    a line naming the page, the expression, its value and the figure quoted."""
    wrong, since, end = [], 0, 0
    for m in CHECK.finditer(text):
        if text[end : m.start()].strip():  # not the next of a group of markers: a new text
            since = end
        end = m.end()
        expr, _, figure = (part.strip() for part in m[1].rpartition(" ~ "))
        expr = expr or figure  # no "~": the whole marker is a claim
        where = f"docs/{page}: <!-- check: {m[1]} -->"
        try:
            value = eval(expr, namespace)  # noqa: S307 (the page's own expressions)
        except Exception as exc:  # a marker that cannot be evaluated is wrong too
            wrong.append(f"{where}: {type(exc).__name__}: {exc}")
            continue
        if expr == figure:
            if value is not True and value is not np.True_:
                wrong.append(f"{where}: {value!r}, not True")
        elif not re.fullmatch(FIGURE, figure):
            wrong.append(f"{where}: {figure!r} is not a figure")
        elif not re.search(rf"(?<![\d.]){re.escape(figure)}(?![\d])", text[since : m.start()]):
            wrong.append(f"{where}: the text before it no longer quotes {figure}")
        elif not rounds_to(float(value), figure):
            wrong.append(f"{where}: the code gives {float(value):.6g}, the page quotes {figure}")
    return wrong


def test_a_quoted_figure_that_the_code_no_longer_gives_fails():
    ns = {"ratio": 0.1349, "tiny": 6.04e-4, "n": 4}
    good = (
        "wins at 0.135 <!-- check: ratio ~ 0.135 -->, rmse 6.0e-4 <!-- check: tiny ~ 6.0e-4 -->"
        " and 4 cycles <!-- check: n ~ 4 --> <!-- check: n == 4 -->"
    )
    assert quoted_figures_wrong(good, ns, "p.md") == []
    stale = [
        "wins at 0.14 <!-- check: ratio ~ 0.14 -->",  # 0.13 at two decimals
        "wins at 0.135 <!-- check: ratio ~ 0.136 -->",  # the prose and the marker differ
        "wins at 1.135 <!-- check: ratio ~ 0.135 -->",  # not the same figure
        "4 cycles <!-- check: n == 5 -->",  # a claim that is false
        "4 cycles <!-- check: gone ~ 4 -->",  # a name the page no longer defines
    ]
    for text in stale:
        assert len(quoted_figures_wrong(text, ns, "p.md")) == 1, text
    # markers may follow a paragraph as a group; the figure must stand in the text before the
    # group, after the marker before it: one quote does not serve two texts
    group = "0.135 and 4\n<!-- check: ratio ~ 0.135 -->\n<!-- check: n ~ 4 -->"
    assert quoted_figures_wrong(group, ns, "p.md") == []
    twice = "0.135 <!-- check: ratio ~ 0.135 --> more <!-- check: ratio ~ 0.135 -->"
    assert len(quoted_figures_wrong(twice, ns, "p.md")) == 1
    # the pages' markers are read (a changed syntax would find none and pass)
    assert sum(len(CHECK.findall((DOCS / page).read_text())) for page in PAGES) >= 25


def test_the_four_tutorials_are_there_with_code():
    assert set(PAGES) >= {
        "index.md",
        "tutorials/simulate.md",
        "tutorials/identify.md",
        "tutorials/compensate.md",
        "tutorials/sweep.md",
    }
    runs = {page for page in PAGES if page_blocks(page)}
    runs |= {p for p in SHELL_PAGES if any(lang == "bash" for lang, _ in fenced_blocks(p))}
    assert runs == set(PAGES)


def test_every_page_is_in_the_site_navigation():
    nav = set(re.findall(r":\s*(\S+\.md)\s*$", (ROOT / "mkdocs.yml").read_text(), flags=re.M))
    pages = {p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md")}
    assert pages == nav


def test_make_docs_installs_the_docs_extra():
    extra = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"
    ]["docs"]
    rule = re.search(r"^\$\(DOCS_TOOLS\):.*\n\t(.*)$", (ROOT / "Makefile").read_text(), re.M)
    assert rule is not None
    assert re.findall(r'"([^"]+)"', rule.group(1)) == extra


API_MODULES = [
    "models",
    "identify",
    "compensate",
    "bench",
    "io",
    "sweep",
    "plant.physics",
    "plant.presets",
    "plant.loads",
]


def api_directives() -> set[str]:
    text = "\n".join(p.read_text() for p in (DOCS / "api").glob("*.md"))
    return set(re.findall(r"^::: (\S+)$", text, flags=re.M))


def test_the_api_reference_covers_the_public_modules():
    assert {"tendonsheath", *(f"tendonsheath.{m}" for m in API_MODULES)} <= api_directives()


@pytest.mark.parametrize("module", [f"tendonsheath.{m}" for m in API_MODULES])
def test_no_public_function_is_hidden_behind_its_submodule(module):
    """mkdocstrings documents ``bench.run`` as the submodule bench/run.py, not the function it
    exports: such a name needs its own ``::: module.name.name`` directive."""
    mod = importlib.import_module(module)
    is_package = hasattr(mod, "__path__")
    shadowed = [
        name
        for name in getattr(mod, "__all__", [])
        if is_package
        and importlib.util.find_spec(f"{module}.{name}") is not None
        and not inspect.ismodule(getattr(mod, name))
    ]
    directives = api_directives()
    assert [n for n in shadowed if f"{module}.{n}.{n}" not in directives] == []


def test_the_site_loads_nothing_from_the_network():
    """The site is read from disk, offline: the theme's fonts are the system's (Material would
    load Roboto from Google Fonts), no script or style sheet comes from a URL, and no math
    engine is loaded: arithmatex only marks the formulas (generic mode, no MathJax or KaTeX)
    and the hook docs/hooks/mathml.py writes them as MathML when the site is built."""
    config = (ROOT / "mkdocs.yml").read_text()
    assert re.search(r"^theme:\n(?:  .*\n)*?  font: false$", config, flags=re.M)
    assert not re.search(r"^extra_(?:javascript|css):", config, flags=re.M)
    assert re.search(r"^  - pymdownx\.arithmatex:\n      generic: true$", config, flags=re.M)
    assert re.search(r"^hooks:\n(?:  .*\n)*?  - docs/hooks/mathml\.py$", config, flags=re.M)
    assert "mathjax" not in config.lower() and "katex" not in config.lower()
    assert not re.search(r"^USE_MATHJAX\s*=\s*YES", (ROOT / "Doxyfile").read_text(), re.M)


# a formula on a page: \( ... \) inline, \[ ... \] displayed (mkdocs.yml's arithmatex syntax)
FORMULA = re.compile(r"\\\((.+?)\\\)|\\\[(.+?)\\\]", flags=re.S)
MATH_ELEMENT = re.compile(r"<math\b.*?</math>", flags=re.S)
# what would load from the network: a script, style sheet, font or image from a URL
REMOTE = re.compile(r"<(?:script|link|img|iframe)\b[^>]*\b(?:src|href)=\"(?:https?:)?//", re.I)


def math_pages() -> list[str]:
    """The pages that hold a formula."""
    return sorted(
        p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md") if FORMULA.search(p.read_text())
    )


def mkdocs_or_fail():
    try:
        import latex2mathml  # noqa: F401
        from mkdocs.commands.build import build
        from mkdocs.config import load_config
    except ImportError:
        pytest.fail("mkdocs or latex2mathml not found: `make docs` installs the docs extra")
    return build, load_config


@pytest.fixture(scope="module")
def built_math_pages(tmp_path_factory) -> dict[str, str]:
    """The pages with formulas built as `make docs` builds them (mkdocs.yml's theme, Markdown
    extensions and math hook), without the API reference and C++ reference: page -> HTML."""
    build, load_config = mkdocs_or_fail()
    folder = tmp_path_factory.mktemp("site")
    pages = math_pages()
    for page in pages:
        (folder / "docs" / page).parent.mkdir(parents=True, exist_ok=True)
        (folder / "docs" / page).write_text((DOCS / page).read_text())
    here = os.getcwd()
    os.chdir(ROOT)  # pymdownx.snippets reads the quoted files from the repository's root
    try:
        config = load_config(
            config_file=str(ROOT / "mkdocs.yml"),
            docs_dir=str(folder / "docs"),
            site_dir=str(folder / "site"),
            nav=pages,
            plugins=["search"],
            hooks=[str(DOCS / "hooks" / "mathml.py")],
            strict=False,  # the links into the pages left out are broken here
        )
        build(config)
    finally:
        os.chdir(here)
    return {p: (folder / "site" / p.replace(".md", ".html")).read_text() for p in pages}


def test_the_equations_page_and_the_others_with_formulas_hold_mathml(built_math_pages):
    """Every formula of a page is a <math> element in the built page (well-formed XML, none
    left as LaTeX), and the pages load nothing from the network."""
    assert {"equations.md", "tutorials/real-drives.md", "vocabulary.md"} <= set(built_math_pages)
    for page, html in built_math_pages.items():
        source = (DOCS / page).read_text()
        elements = MATH_ELEMENT.findall(html)
        assert len(elements) == len(FORMULA.findall(source)), page
        for element in elements:
            ElementTree.fromstring(element)  # raises on a malformed element
        shown = re.sub(r"<(pre|code)\b.*?</\1>", "", MATH_ELEMENT.sub("", html), flags=re.S)
        assert not re.search(r"\\[(\[]|arithmatex", shown), page
        assert not REMOTE.search(html), (page, REMOTE.search(html))
    equations = built_math_pages["equations.md"]
    # the displayed ones are blocks: the capstan law A1, the pull-pull pair's A7, D2's inverse
    assert equations.count('display="block"') >= 12
    assert "<mi>&#x003B8;</mi>" in equations  # theta, a MathML identifier


def test_a_formula_latex2mathml_cannot_convert_stops_the_build():
    mkdocs_or_fail()
    from mkdocs.exceptions import PluginError

    spec = importlib.util.spec_from_file_location("mathml_hook", DOCS / "hooks" / "mathml.py")
    hook = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hook)

    class Page:  # what the hook reads of mkdocs' page
        class file:
            src_uri = "equations.md"

    ok = hook.on_page_content(
        '<p><span class="arithmatex">\\(a &lt; b\\)</span></p>', Page, None, None
    )
    assert ok.startswith('<p><math xmlns="http://www.w3.org/1998/Math/MathML" display="inline">')
    # the < that arithmatex escaped is MathML's operator
    assert "<mo>&#x0003C;</mo>" in ok and "arithmatex" not in ok
    with pytest.raises(PluginError, match=r"equations\.md: '\\\\nosuch x' is not MathML"):
        hook.on_page_content('<div class="arithmatex">\\[\\nosuch x\\]</div>', Page, None, None)


SNIPPET = re.compile(r'^--8<-- "([^":]+):(\d+):(\d+)"$', flags=re.M)


@pytest.mark.parametrize("page", sorted(SHELL_PAGES))
def test_quoted_line_ranges_are_whole_functions(page):
    """A page that quotes lines of a file quotes a whole function: the first line opens it
    and the last closes it (lines moved in the file would cut it)."""
    for path, first, last in SNIPPET.findall((DOCS / page).read_text()):
        lines = (ROOT / path).read_text().splitlines()[int(first) - 1 : int(last)]
        assert re.match(r"^\w[\w:&<> ]* \w+\(.*\{$", lines[0]), (path, first, lines[0])
        assert lines[-1] == "}", (path, last, lines[-1])


@pytest.mark.parametrize("page", PAGES)
def test_every_python_block_runs_as_written(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace = run_page(page, tmp_path)
    check = CHECKS.get(page)
    if check is not None:
        check(namespace, tmp_path)
    assert quoted_figures_wrong((DOCS / page).read_text(), namespace, page) == []


def _simulate(ns, _folder):
    assert np.all(np.isfinite(ns["q_out"])) and ns["q_out"].shape == ns["t"].shape


def _identify(ns, folder):
    assert (folder / "model.json").is_file()
    # measured 6.0e-4 rad (sensor noise 2e-4 on a plant outside the model class): 3x margin
    assert ns["rmse"] < 2e-3


def _compensate(ns, _folder):
    # measured 0.0675 -> 0.0015 rad (45x); the page says it helps: hold a 5x reduction
    assert ns["compensated"].metrics["rmse"] < ns["plain"].metrics["rmse"] / 5


def _sweep(_ns, folder):
    assert any((folder / "sweep-out").iterdir())


def _real_drives(ns, _folder):
    # the stretch gain -1.5 found within 1 % (measured -1.4975); the coupling 0.25 within 3
    # standard errors (measured 0.249977 +- 3.5e-5)
    assert abs(ns["fit"].model.terms["gain"] + 1.5) < 0.05
    assert abs(ns["coupled"].coupling[1, 0] - 0.25) < 3 * ns["coupled"].coupling_se[1, 0]
    # the staged Loaded fit extrapolates to the lightest load left out no worse than the affine
    # map there (the joint-only fit was 1.01x worse, so it could not win; the page's paragraph
    # on it is the lead's to update): it wins now, the Backlash without the load cannot
    assert ns["cmp"].winner_name == "Loaded(Backlash)" and "Backlash" in ns["cmp"].excluded()
    assert np.all(np.isfinite(ns["u"]))


NUMBER = re.compile(r"-?\d+\.\d+(?:e-?\d+)?")


def _to_6_digits(text: str) -> str:
    return NUMBER.sub(lambda m: f"{float(m[0]):.6g}", text)


def _deploy(ns, folder):
    # the C++ commands, from the JSON loader (example 12) and from the generated header, are
    # Python's (measured: 0 difference; example 12 prints 17 digits)
    assert np.max(np.abs(ns["u_cpp"] - ns["u_python"])) < 1e-12
    assert np.max(np.abs(ns["u_params"] - ns["u_python"])) < 1e-12
    import tendonsheath as ts

    # the line the program prints, as the page quotes it, with Python's count of the cycles cut
    saturated = ts.status_counts(ns["u_python"].status)["saturated"]
    printed = f"0 cycles held at the range's edge, {saturated} saturated"
    assert printed in ns["_shell"][-1] and printed in (DOCS / "tutorials/deploy.md").read_text()
    # the header the page shows is the one the command wrote (to 6 digits: the identified
    # parameters may differ in their last digits on another machine)
    shown = [code for _, code in fenced_blocks("tutorials/deploy.md") if "// Generated" in code]
    written = (folder / "ff_params.hpp").read_text()
    assert [_to_6_digits(c) for c in shown] == [_to_6_digits(written)]


def _ros_bags_written(folder: Path) -> None:
    """What docs/tutorials/ros-bags.md reads: run.bag (ROS 1), run_db3/ and run_mcap/ (ROS 2),
    10 s at 50 Hz of /joint_states (JointState: joints roll and bend, header stamps set,
    received 1 ms later; the publisher swaps their order half-way) and /tip/angle (Float64, no
    header: received 4 ms after the tip was measured)."""
    from _rosbag_helpers import EPOCH_NS, float64, joint_state, write_bag

    import tendonsheath as ts

    t = np.arange(0.0, 10.0, 0.02)
    bend, roll = 0.6 * np.sin(2 * np.pi * 0.3 * t), 0.2 * np.sin(2 * np.pi * 0.1 * t)
    tip = ts.models.Backlash(B_r=0.05, B_l=0.05).simulate(t, bend)
    stamps = EPOCH_NS + np.round(t * 1e9).astype(np.int64)
    for kind, path in (("ros1", "run"), ("sqlite3", "run_db3"), ("mcap", "run_mcap")):
        states = [
            (s + 1_000_000, joint_state(kind, s, [r, b], names=["roll", "bend"]))
            if k < t.size // 2
            else (s + 1_000_000, joint_state(kind, s, [b, r], names=["bend", "roll"]))
            for k, (s, r, b) in enumerate(zip(stamps, roll, bend, strict=True))
        ]
        tips = [(s + 4_000_000, float64(kind, y)) for s, y in zip(stamps, tip, strict=True)]
        write_bag(folder / path, kind, {"/joint_states": states, "/tip/angle": tips})


def _ros_bags(ns, folder):
    log = ns["log"]
    # the bend joint read by name across the swap: its amplitude (0.6, not roll's 0.2) and no
    # jump at the swap (a 0.3 Hz sine of 0.6 rad moves at most 0.023 rad in 20 ms)
    assert np.ptp(log.x) > 1.0 and np.max(np.abs(np.diff(log.x))) < 0.03
    # the notes the page shows are the ones read
    shown = text_blocks("tutorials/ros-bags.md")
    assert shown[0].splitlines() == [f"- {note}" for note in log.notes]
    assert all("receive time" in n for n in ns["same_base"].notes if n.startswith("time of"))
    assert (folder / "bag_pred.csv").is_file()


def _masked(text: str) -> list[str]:
    """Lines with every number as N and runs of blanks as one: what a run prints, whatever
    its timings (and the widths they take)."""
    return [" ".join(re.sub(r"\d+(?:\.\d+)?", "N", line).split()) for line in text.splitlines()]


def _compare_real_data(ns, folder):
    # the table, the candidates that cannot win and why, the winner, and predict's lines: the
    # page shows what the commands print (numbers masked: the timings vary)
    shown = text_blocks("tutorials/compare-real-data.md")
    assert [_masked(c) for c in shown] == [_masked(out) for out in ns["_shell"]]
    assert ns["comparison"]["winner"] == "Backlash" and (folder / "pred.csv").is_file()


def _two_digits(text: str) -> list[str]:
    """Lines with every number to 2 significant digits and runs of blanks as one."""
    number = re.compile(r"\d+(?:\.\d+)?(?:e[+-]?\d+)?")
    return [
        " ".join(number.sub(lambda m: f"{float(m[0]):.2g}", ln).split()) for ln in text.splitlines()
    ]


def _scenario_toml(ns, folder):
    # the page shows what the command prints (to 2 digits: another machine's rounding may
    # differ in the last ones), and what it writes is there
    shown = text_blocks("scenario-toml.md")
    assert [_two_digits(c) for c in shown] == [_two_digits(out) for out in ns["_shell"]]
    assert (folder / "bench-out" / "report.html").is_file()


def _cpp_build_configured(_folder: Path) -> None:
    """docs/tutorials/deploy.md builds and runs C++ example 12 in the build folder that
    `make test-cpp` configures (it needs nlohmann/json, which `make test-cpp` installs)."""
    if not (ROOT / "build" / "cpp" / "CMakeCache.txt").is_file():
        pytest.fail("docs/tutorials/deploy.md runs C++ example 12: run `make test-cpp` first")


SETUP = {"tutorials/ros-bags.md": _ros_bags_written, "tutorials/deploy.md": _cpp_build_configured}


CHECKS = {
    "tutorials/real-drives.md": _real_drives,
    "tutorials/simulate.md": _simulate,
    "tutorials/identify.md": _identify,
    "tutorials/compensate.md": _compensate,
    "tutorials/sweep.md": _sweep,
    "tutorials/ros-bags.md": _ros_bags,
    "tutorials/deploy.md": _deploy,
    "tutorials/compare-real-data.md": _compare_real_data,
    "scenario-toml.md": _scenario_toml,
}


# --- the C++ reference (Doxygen) ---------------------------------------------------------

HEADERS = ROOT / "include" / "tendonsheath"
# not part of the real-time API, kept out of the reference by Doxyfile's EXCLUDE_PATTERNS
NOT_REAL_TIME = {"batch.hpp"}
DETAIL = re.compile(r"namespace (?:\w+::)*detail \{.*?\}\s*// namespace (?:\w+::)*detail", re.S)
CLASS = re.compile(r"^\s*(?:template\s*<[^;{]*>\s*)?(?:class|struct)\s+(\w+)\b[^;]*?\{", re.M)


def public_classes() -> set[str]:
    """Every class and struct defined in namespace tendonsheath outside its detail namespaces."""
    names = set()
    for header in HEADERS.rglob("*.hpp"):
        if header.name in NOT_REAL_TIME:
            continue
        names |= set(CLASS.findall(DETAIL.sub("", header.read_text())))
    return names


@pytest.fixture(scope="module")
def doxygen_html(tmp_path_factory) -> Path:
    """Doxyfile run as `make docs` runs it, into a temporary folder; its warnings are errors."""
    out = tmp_path_factory.mktemp("doxygen")
    doxyfile = (ROOT / "Doxyfile").read_text() + f"\nOUTPUT_DIRECTORY = {out}\n"
    try:
        run = subprocess.run(
            ["doxygen", "-"], input=doxyfile, cwd=ROOT, capture_output=True, text=True
        )
    except FileNotFoundError:
        pytest.fail("doxygen not found: `make doxygen` installs Debian's package")
    assert run.returncode == 0 and run.stderr == "", run.stderr
    return out


def compound_pages(out: Path) -> dict[str, Path]:
    """Doxygen's index: qualified class name -> its HTML page."""
    index = ElementTree.parse(out / "xml" / "index.xml").getroot()
    return {
        c.findtext("name"): out / "html" / f"{c.get('refid')}.html"
        for c in index.iter("compound")
        if c.get("kind") in ("class", "struct")
    }


def test_the_header_parser_finds_the_classes():
    # guards the test below against a parser that finds nothing: known public and detail names
    names = public_classes()
    assert {"Backlash", "PullPullPlant", "Affine", "LoadedCompensator"} <= names
    assert "AbsPower" not in names and "FixedPower" not in names  # in detail namespaces


def test_every_public_class_has_a_page_in_the_cpp_reference(doxygen_html):
    pages = compound_pages(doxygen_html)
    documented = {name.rsplit("::", 1)[-1] for name, page in pages.items() if page.is_file()}
    assert sorted(public_classes() - documented) == []
    assert [name for name in pages if "::detail::" in name] == []


# --- the scenario file's keys (docs/scenario-toml.md) ------------------------------------

SCENARIO_PAGE = DOCS / "scenario-toml.md"
TYPE_WORDS = {str: "string", float: "number", int: "integer", bool: "boolean", list: "array"}
# keys whose default is not one value: the calibration angles follow the test routes'
DEFAULT_IN_WORDS = {("calibration", "angles")}


def scenario_key_table() -> dict[tuple[str, str], tuple[str, str, str]]:
    """(table, key) -> (type, default, allowed) of the page's key table; "" is the top level."""
    rows = {}
    for line in SCENARIO_PAGE.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 5 or not cells[1].startswith("`"):
            continue
        table = cells[0].strip("`[]") if cells[0] != "(top)" else ""
        rows[(table, cells[1].strip("`"))] = (cells[2], cells[3].strip("`"), cells[4])
    return rows


def scenario_defaults() -> dict[tuple[str, str], object]:
    """Every key's default as the code has it: the tables of a scenario that gives none, the
    classes' signatures, and the literal defaults in tendonsheath/bench/user_scenario.py."""
    import tendonsheath as ts
    from tendonsheath.bench import user_scenario as us

    sc = us.parse('title = "user scenario"')
    source = inspect.getsource(us)
    literal = {
        key: eval(value, {"math": __import__("math")})
        for key, value in re.findall(r'\.get\("(\w+)", ([\w."]+)\)', source)
    }
    pair = inspect.signature(ts.PullPullPlant.__init__).parameters
    continuum = inspect.signature(ts.ContinuumPlant.__init__).parameters
    motor = inspect.signature(ts.Motor.position).parameters
    sensor = inspect.signature(ts.Sensor.__init__).parameters
    out = {("", "title"): sc.title, ("", "seed"): sc.seed}
    for key in us._KEYS["plant"]:
        given = sc.plant.get(key, literal.get(key) if key in ("realistic",) else None)
        params = continuum if key in continuum and key not in pair else pair
        out[("plant", key)] = given if given is not None else params[key].default
    initial = sc.route["initial"]
    out.update({("route", "length"): initial.length, ("route", "total_angle"): initial.curve_angle})
    out.update({("route", "arcs"): None, ("route", "changes"): None})
    out.update({("load", k): literal[k] if k != "type" else None for k in us._KEYS["load"]})
    for table, params in (("motor", motor), ("sensor", sensor)):
        values = getattr(sc, table)
        out.update({(table, k): values.get(k, params[k].default) for k in us._KEYS[table]})
    for table in ("torque_motor", "reference", "calibration"):
        values = getattr(sc, table)
        out.update({(table, k): values.get(k, literal.get(k)) for k in us._KEYS[table]})
    out.update({("compare", "compensators"): sc.compensators, ("compare", "user"): None})
    return out


def _same_default(cell: str, value) -> bool:
    if value is None or value == float("inf"):
        return cell.startswith("none")
    parsed = tomllib.loads(f"v = {cell}")["v"]
    if isinstance(value, float):
        return isinstance(parsed, int | float) and np.isclose(parsed, value, rtol=1e-4)
    return parsed == value


def test_the_scenario_page_lists_every_key_with_its_type_and_default():
    from tendonsheath.bench import user_scenario as us

    rows = scenario_key_table()
    keys = {("", k) for k in us._TOP if us._TOP[k] is not dict}
    keys |= {(table, key) for table, known in us._KEYS.items() for key in known}
    assert sorted(rows) == sorted(keys)
    types = {("", k): v for k, v in us._TOP.items()}
    types.update({(t, k): v for t, known in us._KEYS.items() for k, v in known.items()})
    assert {k: rows[k][0] for k in rows} == {k: TYPE_WORDS[types[k]] for k in rows}
    defaults = scenario_defaults()
    wrong = {
        k: (rows[k][1], defaults[k])
        for k in rows
        if k not in DEFAULT_IN_WORDS and not _same_default(rows[k][1], defaults[k])
    }
    assert wrong == {}


def test_the_scenario_page_lists_the_keys_of_its_arrays_of_tables():
    from tendonsheath.bench import user_compensators, user_scenario

    rows = {}
    for line in SCENARIO_PAGE.read_text().splitlines():
        cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0].startswith("[["):
            rows.setdefault(cells[0].strip("[]"), set()).add(cells[1])
    # the keys a route change takes, as parse() checks them
    change = re.search(r"set\(change\) - \{([^}]*)\}", inspect.getsource(user_scenario))
    assert change is not None
    assert rows == {
        "route.changes": set(re.findall(r'"(\w+)"', change[1])),
        "compare.user": set(user_compensators._ENTRY_KEYS),
    }


BOUND = re.compile(r"^`(>=|>) (-?[0-9.e+-]+)`(.*)$")
# the load type that takes each bounded [load] key
LOAD_TYPE = {"stiffness": "torsional_spring", "damping": "spring_damper"}


def _scenario_with(table: str, key: str, value) -> str:
    """A scenario that sets one key (with the plant or load type that takes it)."""
    import tendonsheath as ts

    line = f"{key} = {str(value).lower() if isinstance(value, bool) else repr(value)}"
    if table == "":
        return f'title = "probe"\n{line}\n'
    if table == "plant" and key not in inspect.signature(ts.PullPullPlant.__init__).parameters:
        line = f'type = "continuum"\n{line}'
    if table == "load":
        line = f'type = "{LOAD_TYPE[key]}"\n{line}'
    return f"[{table}]\n{line}\n"


def test_the_scenario_page_bounds_are_the_checks():
    """Each bound the page states (`> B`, `>= B`) is where the parser starts refusing: the
    bound itself (> B) or just below it (>= B) is an error naming the key's table, and the
    value just inside it passes (unless the page states another condition after a ";")."""
    import warnings

    from tendonsheath.bench import user_scenario as us

    probed = 0
    for (table, key), (kind, _default, allowed) in scenario_key_table().items():
        m = BOUND.match(allowed)
        if m is None:
            continue
        op, bound, more = m[1], float(m[2]), m[3]
        step = 1 if kind == "integer" else 1e-3 * max(1.0, abs(bound))
        bad, good = (bound, bound + step) if op == ">" else (bound - step, bound)
        if kind == "integer":
            bad, good = int(bad), int(good)
        where = f"[{table}]" if table else key
        with pytest.raises(us.ScenarioError, match=re.escape(where)):
            us.parse(_scenario_with(table, key, bad))
        if not more.startswith(";"):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # a test route outside the calibration's
                us.parse(_scenario_with(table, key, good))
        probed += 1
    assert probed >= 25
