"""The CasADi operations a body's support function may use: what is smooth, what is piecewise
(a compound body's switches), and what the engines' translator takes
(:mod:`phasekit.core.engines.translate` rebuilds exactly the operations listed here).

A profile written with a kink or a jump (``fabs``, ``fmax``, ``sign``, ...) is not smooth
whatever its values at sample points say, so :class:`~phasekit.bodies.custom.CustomBody`
refuses it; only the PIECEWISE operations (CasADi's ``if_else``: comparisons, their logic and
``if_else_zero``) are translated, for the bodies built of pieces whose switches are events.
"""

from __future__ import annotations

import casadi as ca

#: the smooth operations the translator rebuilds (unary and binary), besides the structural ones
SMOOTH = frozenset(getattr(ca, f"OP_{n}") for n in (
    "NEG", "SQ", "TWICE", "INV", "SQRT", "SIN", "COS", "TAN", "EXP", "LOG", "ASIN", "ACOS", "ATAN", "TANH", "SINH",
    "COSH", "ASINH", "ACOSH", "ATANH", "ERF", "LOG1P", "EXPM1", "ASSIGN",
    "ADD", "SUB", "MUL", "DIV", "POW", "CONSTPOW", "ATAN2", "HYPOT"))
#: operations with a kink or a jump: a body's profile (or a law) built from them is not smooth;
#: of these only the PIECEWISE ones are translated
NON_SMOOTH = frozenset(getattr(ca, f"OP_{n}") for n in (
    "FABS", "FMAX", "FMIN", "IF_ELSE_ZERO", "SIGN", "FLOOR", "CEIL", "FMOD", "COPYSIGN", "REMAINDER", "EQ", "NE", "LT",
    "LE", "AND", "OR", "NOT"))
PIECEWISE = frozenset(getattr(ca, f"OP_{n}") for n in ("IF_ELSE_ZERO", "EQ", "NE", "LT", "LE", "AND", "OR", "NOT"))
#: operations whose value is constant inside a piece (comparisons, their logic, steps)
STEPS = frozenset(getattr(ca, f"OP_{n}") for n in ("LT", "LE", "EQ", "NE", "NOT", "AND", "OR", "SIGN", "FLOOR", "CEIL"))
#: the instructions that only move data in and out
STRUCTURAL = frozenset((ca.OP_CONST, ca.OP_INPUT, ca.OP_OUTPUT))
OP_NAMES = {getattr(ca, n): n[3:].lower() for n in dir(ca) if n.startswith("OP_")}


def operations(f: ca.Function) -> dict[str, set[str]]:
    """The operations of an SX function that the Taylor integrator cannot take:
    ``{"non_smooth": names, "untranslated": names}`` (both empty when all is well)."""
    ops = {f.instruction_id(k) for k in range(f.n_instructions())}
    return {"non_smooth": {OP_NAMES.get(op, str(op)) for op in ops & NON_SMOOTH},
            "untranslated": {OP_NAMES.get(op, str(op)) for op in ops - SMOOTH - STRUCTURAL - NON_SMOOTH}}
