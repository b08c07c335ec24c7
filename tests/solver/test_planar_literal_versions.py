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
    planar_multisurface_kernel,
    planar_multisurface_rate_kernel,
    planar_multisurface_stepper,
    planar_rim_kernel,
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


def _literal_passes(module, strict: bool = False) -> list[str]:
    """Calls of a compiled function (not one inlined by numba) with an int constant as an argument, or with a
    name assigned one earlier in the same block (nothing else reaches the call there).  ``strict``: bool and
    negative constants (``True``, ``-1``) count too, and keyword arguments are read."""
    space = vars(module)
    kinds = (int, bool) if strict else (int,)

    def constant(node) -> bool:
        if strict and isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return constant(node.operand)
        if isinstance(node, ast.Constant):
            return type(node.value) in kinds
        return isinstance(node, ast.Name) and type(space.get(node.id)) in kinds

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
                for arg in [*call.args, *((k.value for k in call.keywords) if strict else ())]:
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


#: The triple pendulum's 2-D engines and the rim's slide (docs/performance.md, h197): bool constants are literals too
#: (``Literal[bool](True)``), and so is a negative int (``-1``).
MULTISURFACE_MODULES = (planar_multisurface_stepper, planar_multisurface_rate_kernel, planar_rim_kernel,
                        planar_building_multisurface_kernel)


def _arities(modules) -> dict[str, set[int]]:
    """Per compiled function, the numbers of arguments its calls in these modules pass: a default left out is an
    ``Omitted`` type, so a call that leaves it out and one that passes it compile two versions."""
    seen: dict[str, set[int]] = {}
    for module in modules:
        space = vars(module)
        for call in (c for c in ast.walk(ast.parse(inspect.getsource(module)))
                     if isinstance(c, ast.Call) and isinstance(c.func, ast.Name)):
            fn = space.get(call.func.id)
            if isinstance(fn, CPUDispatcher) and fn.targetoptions.get("inline", "never") == "never":
                seen.setdefault(f"{fn.py_func.__module__}.{call.func.id}", set()).add(len(call.args) + len(call.keywords))
    return seen


def test_multisurface_kernels_pass_no_bool_or_int_literal_to_a_compiled_function():
    found = [line for module in MULTISURFACE_MODULES for line in _literal_passes(module, strict=True)]
    assert found == [], f"{len(found)} literal arguments: " + "; ".join(found[:8])


def test_the_2d_building_on_a_multi_surface_bearing_passes_each_default_always_or_never():
    # each module on its own: its model's warm-up runs in a process of its own (be_step's ``block`` is left out by the
    # building, passed by the stepper: one version in each).  row_peak's signed/z0/zs/off: 3 versions on edf7ccb;
    # off (an array or left out) keeps 2
    mixed = {name: counts for module in MULTISURFACE_MODULES for name, counts in _arities((module,)).items()
             if len(counts) > 1}
    assert mixed == {f"{planar_building_multisurface_kernel.__name__}.row_peak": {19, 20}}, mixed


#: The 2-D multi-surface event kernel's literal arguments still passed (h215): the ones whose ``np.int64``/``np.bool_``
#: form was not shown bit-identical on both the fresh-compile and the cached path (docs/performance.md, h207/h215).
#: A ratchet: remove an entry when its call passes a typed value; never add one.
EVENT_KERNEL_LITERALS_LEFT = {
    "_radau_estimate(… False …)", "_radau_estimate(… True …)",
    "_restep_value(… 0 …)", "_secant_resteps(… 0 …)", "_secant_resteps(… LOCATE_RESTEPS …)",
    "_secant_resteps(… True …)", "_secant_resteps(… -1 …)", "_secant_resteps(… False …)",
    "_secant_resteps(… PEAK_RESTEPS …)", "_secant_resteps(… RS_PEAK …)",
    "_locate_multi(… 0 …)", "_locate_multi(… 1 …)",
}


def test_the_2d_event_kernel_passes_no_literal_beyond_its_ratchet():
    # 22 literal arguments on 8e44dd2 (_record(… EV_JOIN/EV_LEAVE/EV_STICK/EV_REVERSAL/EV_BREAKAWAY …),
    # _joins_in_step(… LOG …) …), 13 now; their versions cost compile time (h207: all 27 changes, 215.5 → 158–171 s CPU cold)
    found = {line.split(" ", 1)[1] for line in _literal_passes(planar_multisurface_kernel, strict=True)}
    assert found == EVENT_KERNEL_LITERALS_LEFT, sorted(found ^ EVENT_KERNEL_LITERALS_LEFT)
