"""The 2-D engine passes no integer constant to a compiled function: one machine code per argument-type signature.

numba types an integer constant passed from compiled code as ``Literal[int](k)`` and compiles the callee once per
value: ``locate_peak(0, LOG, …)`` and ``locate_peak(2, LOG, …)`` were two machine codes of the same function, and
the planar engine's warm-up compiled seven of it, 90 versions of 48 functions in all, where one each is enough
(docs/performance.md, "One version per signature": 48 versions, ~20 % less compile time).  A variable assigned a
constant is a literal too where no other assignment reaches the call.  The kernels pass these codes as
``np.int64(k)``.  The check reads the sources (numba does not fill ``overloads`` of the callees when it loads a
kernel from its cache, and a cold compile takes minutes).
"""

from __future__ import annotations

import ast
import inspect

from numba.core.registry import CPUDispatcher

from isolator.solver import (
    building_kernel,
    building_multisurface_kernel,
    events,
    kernel,
    linear,
    multisurface_kernel,
    multisurface_rate_kernel,
    planar_building_kernel,
    planar_building_multisurface_kernel,
    planar_control,
    planar_events,
    planar_kernel,
    record,
    segments,
)

MODULES = (planar_kernel, planar_events, planar_control)
#: The building kernels and the 1-D kernels (docs/performance.md, "Building and 1-D kernels' literal constants").
BUILDING_AND_1D_MODULES = (planar_building_kernel, planar_building_multisurface_kernel, building_kernel,
                           building_multisurface_kernel, events, kernel, segments, multisurface_kernel,
                           multisurface_rate_kernel, record, linear)


def _stored(stmt) -> set[str]:
    """The names a statement assigns, tuple targets and nested statements included."""
    return {n.id for n in ast.walk(stmt) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}


def _literal_passes(module) -> list[str]:
    """Calls of a compiled function (not one inlined by numba) with an int constant as an argument, or with a
    name assigned one earlier in the same block (nothing else reaches the call there)."""
    space = vars(module)

    def constant(node) -> bool:
        if isinstance(node, ast.Constant):
            return type(node.value) is int
        return isinstance(node, ast.Name) and type(space.get(node.id)) is int

    def compiled(call) -> bool:
        fn = space.get(call.func.id) if isinstance(call.func, ast.Name) else None
        return isinstance(fn, CPUDispatcher) and fn.targetoptions.get("inline", "never") == "never"

    found = []
    for block in (b for node in ast.walk(ast.parse(inspect.getsource(module)))
                  for b in (getattr(node, "body", None), getattr(node, "orelse", None)) if isinstance(b, list)):
        fixed: set[str] = set()  # names assigned a constant by an earlier statement of this block
        for stmt in block:
            if isinstance(stmt, (ast.For, ast.While)):  # a name the loop assigns is int64 there, not a literal
                fixed.difference_update(_stored(stmt))
            for call in (c for c in ast.walk(stmt) if isinstance(c, ast.Call) and compiled(c)):
                for arg in call.args:
                    if constant(arg) or (isinstance(arg, ast.Name) and arg.id in fixed):
                        found.append(f"{module.__name__}:{call.lineno} {call.func.id}(… {ast.unparse(arg)} …)")
            fixed.difference_update(_stored(stmt))
            if isinstance(stmt, ast.Assign) and constant(stmt.value):
                fixed.update(t.id for t in stmt.targets if isinstance(t, ast.Name))
    return sorted(set(found))


def test_planar_engine_passes_no_literal_to_a_compiled_function():
    found = [line for module in MODULES for line in _literal_passes(module)]
    assert found == [], f"{len(found)} literal arguments: " + "; ".join(found[:8])


def test_building_and_1d_kernels_pass_no_literal_to_a_compiled_function():
    found = [line for module in BUILDING_AND_1D_MODULES for line in _literal_passes(module)]
    assert found == [], f"{len(found)} literal arguments: " + "; ".join(found[:8])
