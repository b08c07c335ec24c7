"""Start-up stays light: ``import isolator`` and the CLI's module load no heavy library.

The list of modules is asserted, not the time (times depend on the machine; the timing
is ``benchmarks/main_job.py``, quoted in ``docs/performance.md``).  Each check runs in a
fresh interpreter, since this test process has long imported everything.
"""

from __future__ import annotations

import functools
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "scipy", "obspy", "matplotlib", "numba", "dask", "pandas", "pyarrow")


def _loaded_after(statement: str) -> list[str]:
    code = (f"import sys\n{statement}\n"
            f"print(' '.join(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r}))))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


@pytest.mark.parametrize("statement", ["import isolator", "import isolator.cli"])
def test_no_heavy_library_at_import(statement):
    assert _loaded_after(statement) == []


def test_the_lazy_api_still_resolves():
    """The names of ``isolator.__all__`` load on first use (here one that needs numba)."""
    loaded = _loaded_after("import isolator; isolator.simulate_record")
    assert "numba" in loaded and "numpy" in loaded  # the check above is not vacuous


def test_every_public_name_resolves():
    """Each name of ``isolator.__all__`` is found where the lazy table says (a moved name breaks this)."""
    import isolator

    missing = []
    for name in isolator.__all__:
        try:
            getattr(isolator, name)
        except AttributeError as err:
            missing.append(f"{name}: {err}")
    assert missing == [] and {"read_motion", "MotionPair", "MotionError", "harmonic_thresholds"} <= set(isolator.__all__)


def test_the_report_loads_only_what_it_uses(tmp_path):
    """The main job imports neither pandas, dask, pyarrow, pyplot nor scipy's integrate/ndimage.

    (numba itself imports scipy.linalg, for BLAS, on its first compiled call.)
    """
    data = ROOT / "data" / "example_pendulum.toml"
    statement = ("import contextlib, io\nfrom isolator.cli import app\n"
                 "with contextlib.redirect_stdout(io.StringIO()):\n"
                 f"    app(['report', '--design', {str(data)!r}, 'example:knet', '--scale-to-pga', '0.3', "
                 f"'-o', {str(tmp_path / 'r.pdf')!r}, '--map-resolution', '8'], standalone_mode=False)\n"
                 "import sys\nprint(' '.join(sorted(m for m in sys.modules if m.startswith(("
                 "'scipy.integrate', 'scipy.ndimage', 'matplotlib.pyplot', 'pandas', 'dask', 'pyarrow')))))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
           "ISOLATOR_CACHE_DIR": str(tmp_path / "cache")}
    done = subprocess.run([sys.executable, "-c", statement], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "r.pdf").is_file()  # the report was written: the list is not vacuous
    assert done.stdout.split() == []


# ---- layering: the AST import graph of the package (imports inside functions and __init__ included) ----

#: Circles still open, each a set of modules.  Issue 21 closes them; remove a line when its circle
#: is cut (the test fails on a stale line, so the list only shrinks).
ALLOWED_CIRCLES: list = []
#: Private names still imported across modules, as (importer, source module, name); the same rule.
ALLOWED_PRIVATE: set = set()


def _modules(package: Path) -> dict[str, Path]:
    out = {}
    for path in package.rglob("*.py"):
        name = ".".join(path.relative_to(package.parent).with_suffix("").parts)
        out[name.removesuffix(".__init__")] = path
    return out


def _longest_module(modules, dotted: str) -> str | None:
    while dotted and dotted not in modules:
        dotted = dotted.rpartition(".")[0]
    return dotted or None


@functools.cache  # the package's graph is built once per process: 6 tests read it (each parse ~2 s of CPU)
def import_graph(package: Path = ROOT / "isolator"):
    """(edges {module: set of modules it imports}, [(importer, source, private name)]) from the AST.

    Cached per ``package`` (the sources do not change while the tests run); callers only read the result.

    Every ``import`` and ``from … import`` counts, wherever it sits (a function body, a package's
    ``__init__``); a relative import is resolved against the importing module's package.
    """
    import ast

    modules = _modules(package)
    edges, private = {}, []
    for name, path in modules.items():
        base = name if path.name == "__init__.py" else name.rpartition(".")[0]
        targets = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets.update(filter(None, (_longest_module(modules, alias.name) for alias in node.names)))
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    parts = base.split(".")
                    parts = parts[: len(parts) - node.level + 1]
                    source = ".".join(parts + ([node.module] if node.module else []))
                else:
                    source = node.module or ""
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    target = full if full in modules else _longest_module(modules, source)
                    if target is None:
                        continue
                    targets.add(target)
                    if alias.name.startswith("_") and not alias.name.startswith("__") and full not in modules \
                            and target != name:
                        private.append((name, target, alias.name))
        targets.discard(name)
        edges[name] = targets
    return edges, private


def circles(edges) -> list[set]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index, low, on_stack, stack, found, counter = {}, {}, set(), [], [], [0]
    for root in edges:
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.add(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(component)
    return found


def test_the_graph_finds_a_circle_and_a_private_import(tmp_path):
    """The checker itself: a two-module circle through a function-level import, a private name, a
    package's __init__ importing its child that imports the package back."""
    package = tmp_path / "pkg"
    (package / "sub").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("from pkg.b import public\n")
    (package / "b.py").write_text("def public():\n    from pkg.a import _hidden\n")
    (package / "c.py").write_text("import pkg.a\n")
    (package / "sub" / "__init__.py").write_text("from .leaf import thing\n")
    (package / "sub" / "leaf.py").write_text("from pkg.sub import other\n")
    edges, private = import_graph(package)
    assert sorted(map(sorted, circles(edges))) == [["pkg.a", "pkg.b"], ["pkg.sub", "pkg.sub.leaf"]]
    assert private == [("pkg.b", "pkg.a", "_hidden")]


def test_no_import_circle_in_the_package():
    found = circles(import_graph()[0])
    unexpected = [sorted(c) for c in found if c not in ALLOWED_CIRCLES]
    assert not unexpected, f"import circles: {unexpected}"
    stale = [sorted(c) for c in ALLOWED_CIRCLES if c not in found]
    assert not stale, f"circles cut: remove them from ALLOWED_CIRCLES: {stale}"


def test_no_private_name_imported_from_another_module():
    private = set(import_graph()[1])
    assert not private - ALLOWED_PRIVATE, f"private imports: {sorted(private - ALLOWED_PRIVATE)}"
    assert not ALLOWED_PRIVATE - private, f"fixed: remove them from ALLOWED_PRIVATE: {sorted(ALLOWED_PRIVATE - private)}"


def test_the_layers_fixed_in_issue_21_stay_fixed():
    """Edges that made the circles of issue 21: they must not come back (each is an upward import)."""
    edges = import_graph()[0]
    upward = [("isolator.motion.ground_motion", "isolator.motion.read"),
              ("isolator.solver.harmonic", "isolator.solver.thresholds"),
              ("isolator.bench.cases", "isolator.bench.methods"), ("isolator.bench.methods", "isolator.bench.cases"),
              ("isolator.bench.pairs", "isolator.bench.methods"),
              ("isolator.report.pair", "isolator.report.pdf"), ("isolator.review.suite", "isolator.batch")]
    assert [edge for edge in upward if edge[1] in edges[edge[0]]] == []
    # the package's lowest modules import nothing of the package above them
    assert edges["isolator.errors"] == set() and edges["isolator.motion.components"] == set()


@pytest.mark.parametrize("module", ["isolator.review.suite", "isolator.review.suite_specs",
                                    "isolator.review.suite_components"])
def test_suite_reading_never_reaches_batch(module):
    """Reading a suite (SUITE.toml, files into pairs, one time base) is below batch: no import path, direct or
    through other modules, from a suite module leads into ``isolator.batch`` (imports inside functions count)."""
    edges = import_graph()[0]
    assert module in edges  # the module exists under this name: the check is not vacuous
    reached, todo = set(), [module]
    while todo:
        for target in edges.get(todo.pop(), ()):
            if target not in reached:
                reached.add(target)
                todo.append(target)
    assert "isolator.errors" in reached  # the walk follows edges
    assert sorted(name for name in reached if name == "isolator.batch" or name.startswith("isolator.batch.")) == []
