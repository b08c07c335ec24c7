"""The 2-D engine passes no integer constant to a compiled function: one machine code per argument-type signature.

numba types an integer constant passed from compiled code as ``Literal[int](k)`` and compiles the callee once per
value: ``locate_peak(0, LOG, …)`` and ``locate_peak(2, LOG, …)`` were two machine codes of the same function, and
the planar engine's warm-up compiled seven of it, 90 versions of 48 functions in all, where one each is enough
(docs/performance.md, "One version per signature": 48 versions, ~20 % less compile time).  A variable assigned a
constant is a literal too where no other assignment reaches the call, and so is a ``bool`` constant
(``Literal[bool](True)``: the 2-D multi-surface kernels' flags, ``be_step(…, -1, True)``).  The kernels pass these
as ``np.int64(k)`` and ``np.bool_(b)`` (docs/performance.md, h188: the triple pendulum's engines).  The check reads the sources (numba does not fill ``overloads`` of the callees when it loads a
kernel from its cache, and a cold compile takes minutes).
"""

from __future__ import annotations

import ast
import inspect

from numba.core.registry import CPUDispatcher

from isolator.solver import (
    planar_control,
    planar_events,
    planar_kernel,
    planar_rim_kernel,
)

MODULES = (planar_kernel, planar_events, planar_control)
#: The triple pendulum's engines: checked also for a name that ever holds a constant (its loop's first pass).
#: planar_multisurface_kernel (99 such arguments) and planar_multisurface_stepper (22) not yet: docs/performance.md, h188.
MULTISURFACE = (planar_rim_kernel,)


def _literal_passes(module, loop_carried: bool = False) -> list[str]:
    """Calls of a compiled function (not one inlined by numba) with an int or bool constant as an argument, or
    with a name assigned one earlier in the same block (nothing else reaches the call there).  With
    ``loop_carried`` also a name the function assigns a constant anywhere: numba types a loop from its first pass,
    where ``comp = 0`` before the loop still reaches the call, and can compile the callee for ``Literal[int](0)``
    before it unifies the loop's other values (the multi-surface kernel's ``_join``: 3 versions)."""
    space = vars(module)

    def constant(node) -> bool:  # numba types int and bool constants as literals (-1 too: folded by Python)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd, ast.Invert)):
            return constant(node.operand)
        if isinstance(node, ast.Constant):
            return type(node.value) in (int, bool)
        return isinstance(node, ast.Name) and type(space.get(node.id)) in (int, bool)

    def compiled(call) -> bool:
        fn = space.get(call.func.id) if isinstance(call.func, ast.Name) else None
        return isinstance(fn, CPUDispatcher) and fn.targetoptions.get("inline", "never") == "never"

    def held(function) -> set[str]:  # the names the function assigns a constant anywhere
        names = set()
        for node in (n for n in ast.walk(function) if isinstance(n, (ast.Assign, ast.AnnAssign))):
            for target in getattr(node, "targets", [getattr(node, "target", None)]):
                value = node.value
                pairs = (zip(target.elts, value.elts, strict=True) if isinstance(target, ast.Tuple)
                         and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts)
                         else [(target, value)])
                names.update(t.id for t, v in pairs if isinstance(t, ast.Name) and v is not None and constant(v))
        return names

    def passes(call, names) -> list[str]:
        return [f"{module.__name__}:{call.lineno} {call.func.id}(… {ast.unparse(arg)} …)"
                for arg in [*call.args, *(kw.value for kw in call.keywords)]
                if constant(arg) or (isinstance(arg, ast.Name) and arg.id in names)]

    found = []
    tree = ast.parse(inspect.getsource(module))
    for function in (f for f in ast.walk(tree) if isinstance(f, ast.FunctionDef)):
        if loop_carried:  # every name assigned a constant, wherever the call is
            names = held(function)
            for call in (c for c in ast.walk(function) if isinstance(c, ast.Call) and compiled(c)):
                found += passes(call, names)
            continue
        blocks = [function.body] + [b for node in ast.walk(function) if node is not function
                                    for b in (getattr(node, "body", None), getattr(node, "orelse", None))
                                    if isinstance(b, list)]
        for block in blocks:
            fixed: set[str] = set()  # names assigned a constant by an earlier statement of this block
            for stmt in block:
                for call in (c for c in ast.walk(stmt) if isinstance(c, ast.Call) and compiled(c)):
                    found += passes(call, fixed)
                for node in ast.walk(stmt):
                    for target in getattr(node, "targets", [getattr(node, "target", None)]):
                        if isinstance(target, ast.Name):
                            fixed.discard(target.id)
                if isinstance(stmt, ast.Assign) and constant(stmt.value):
                    fixed.update(t.id for t in stmt.targets if isinstance(t, ast.Name))
    return sorted(set(found))


def test_planar_engine_passes_no_literal_to_a_compiled_function():
    found = [line for module in MODULES for line in _literal_passes(module)]
    assert found == [], f"{len(found)} literal arguments: " + "; ".join(found[:8])


def test_planar_multisurface_engines_pass_no_literal_to_a_compiled_function():
    found = [line for module in MULTISURFACE for line in _literal_passes(module, loop_carried=True)]
    assert found == [], f"{len(found)} literal arguments: " + "; ".join(found[:8])
