"""The time split of the 2-D multi-surface event kernel (benchmarks/planar_multisurface_split.py) patches cycle
counters into the kernel's own source at fixed anchors.  A change of the kernel that moves an anchor would leave the
benchmark measuring something else or nothing: each anchor must occur in the kernel exactly once, and the patched
source must parse, with every counter slot past the kernel's own stats slots.  (Its compiled runs give the kernel's
histories bitwise on the 10 finishing real pairs: docs/multisurface.md, "The corner steps' time, split".)"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from isolator.solver import planar_multisurface_kernel as pm

split = pytest.importorskip("benchmarks.planar_multisurface_split", reason="run from the repository root")


def test_every_anchor_of_the_split_is_in_the_kernel_once_and_the_patched_source_parses():
    source = Path(pm.__file__).read_text()
    patched = source
    for anchor, before, after in split.PATCHES:
        assert source.count(anchor) == 1, anchor
        patched = patched.replace(anchor, before + anchor + after)
    tree = ast.parse(patched)
    names = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    assert {"_cycles", "_last", "_bk", "_t0", "_t1", "_t2", "_sa", "_bd", "_dc", "_BAND_EDGES"} <= names
    # the counters go to slots the kernel does not use
    assert split.SLOT >= pm.ST_SIZE
    assert split.BAND_EDGES[0] == pm.CROSS_ANGLE and split.BAND_EDGES[-1] == 1.0
    assert list(split.BAND_EDGES) == sorted(split.BAND_EDGES)


def test_the_split_refuses_a_kernel_whose_anchor_moved(monkeypatch, tmp_path):
    fake = tmp_path / "kernel.py"
    fake.write_text(Path(pm.__file__).read_text().replace("        while tau < hi:\n", "        while hi > tau:\n"))
    monkeypatch.setattr(pm, "__file__", str(fake))
    with pytest.raises(SystemExit, match="source changed"):
        split.instrumented_kernel()
