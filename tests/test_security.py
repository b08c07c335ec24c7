"""Nothing in isolator loads code from disk: no pickle, eval/exec, yaml.load, marshal, shelve,
and every np.load says allow_pickle=False.  A test over the source, so that a new module cannot
quietly add one."""

from __future__ import annotations

import ast
from pathlib import Path

import isolator

PACKAGE = Path(isolator.__file__).resolve().parent
FORBIDDEN_MODULES = {"pickle", "cPickle", "dill", "cloudpickle", "marshal", "shelve", "yaml", "joblib"}
FORBIDDEN_CALLS = {"eval", "exec", "compile", "__import__"}


def _sources():
    files = sorted(PACKAGE.rglob("*.py"))
    assert len(files) > 20  # the package, not an empty folder
    return [(path, ast.parse(path.read_text(encoding="utf-8"), filename=str(path))) for path in files]


def _offences(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (f"import {a.name}" for a in node.names if a.name.split(".")[0] in FORBIDDEN_MODULES)
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] in FORBIDDEN_MODULES:
            yield f"from {node.module} import"
        elif isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            if isinstance(func, ast.Name) and name in FORBIDDEN_CALLS:  # the builtins (re.compile is fine)
                yield f"{name}()"
            if name == "load" and isinstance(func, ast.Attribute) and getattr(func.value, "id", "") in ("np", "numpy"):
                flags = {k.arg: k.value for k in node.keywords}
                if not (isinstance(flags.get("allow_pickle"), ast.Constant) and flags["allow_pickle"].value is False):
                    yield "np.load without allow_pickle=False"
            if name in ("read_pickle", "load_pickle"):
                yield f"{name}()"
            if any(k.arg == "allow_pickle" and not (isinstance(k.value, ast.Constant) and k.value.value is False)
                   for k in node.keywords):
                yield f"{name}(allow_pickle=…)"


def test_no_code_is_ever_loaded_from_disk():
    found = [f"{path.relative_to(PACKAGE.parent)}:{offence}" for path, tree in _sources() for offence in _offences(tree)]
    assert found == []


def test_the_checker_finds_what_it_forbids():
    bad = ast.parse("import pickle\nfrom yaml import load\neval('1')\nre.compile('x')\nimport numpy as np\nnp.load('x')\n"
                    "np.load('y', allow_pickle=True)\npd.read_pickle('z')\n")
    assert sorted(_offences(bad)) == sorted(["import pickle", "from yaml import", "eval()",
                                             "np.load without allow_pickle=False", "np.load without allow_pickle=False",
                                             "load(allow_pickle=…)", "read_pickle()"])
