"""Translate CasADi SX functions into heyoka expressions.

The equations are written once, as CasADi SX (:mod:`phasekit.core.fields`); this walks a
function's instruction list (its algorithm, with common subexpressions already shared)
and rebuilds each instruction with heyoka's expression system, so the Taylor integrator
runs exactly the compiled model and nothing is transcribed twice.

Piecewise expressions: CasADi's ``if_else(cond, a, b)`` (a compound body's support function,
the max of its pieces', :mod:`phasekit.bodies.compound`) compiles to comparisons and
``if_else_zero(cond, x)`` (x where cond holds, else 0), which become heyoka's ``select`` and its
comparisons. heyoka takes the Taylor coefficients of ``select`` from the branch chosen at the
start of a step, so a step must never cross the switch: the hybrid system watches it as an
event in every mode (:func:`phasekit.core.system.declare`), which cuts the step there, and its
reset moves the state just past it. The other non-smooth operations (fabs, fmax, sign, ...)
stay refused (which operations a body may use: :mod:`phasekit.bodies.operations`, whose
``SMOOTH`` set lists exactly the keys of :func:`unary` and :func:`binary`).
"""

from __future__ import annotations

import casadi as ca


def unary(hy):
    return {
        ca.OP_NEG: lambda a: -a,
        ca.OP_SQ: lambda a: a * a,
        ca.OP_TWICE: lambda a: 2.0 * a,
        ca.OP_INV: lambda a: 1.0 / a,
        ca.OP_SQRT: hy.sqrt,
        ca.OP_SIN: hy.sin,
        ca.OP_COS: hy.cos,
        ca.OP_TAN: hy.tan,
        ca.OP_EXP: hy.exp,
        ca.OP_LOG: hy.log,
        ca.OP_ASIN: hy.asin,
        ca.OP_ACOS: hy.acos,
        ca.OP_ATAN: hy.atan,
        ca.OP_TANH: hy.tanh,
        ca.OP_SINH: hy.sinh,
        ca.OP_COSH: hy.cosh,
        ca.OP_ASINH: hy.asinh,
        ca.OP_ACOSH: hy.acosh,
        ca.OP_ATANH: hy.atanh,
        ca.OP_ERF: hy.erf,
        ca.OP_LOG1P: lambda a: hy.log(1.0 + a),
        ca.OP_EXPM1: lambda a: hy.exp(a) - 1.0,
        ca.OP_ASSIGN: lambda a: a,
    }


def binary(hy):
    return {
        ca.OP_ADD: lambda a, b: a + b,
        ca.OP_SUB: lambda a, b: a - b,
        ca.OP_MUL: lambda a, b: a * b,
        ca.OP_DIV: lambda a, b: a / b,
        ca.OP_POW: lambda a, b: a**b,
        ca.OP_CONSTPOW: lambda a, b: a**b,
        ca.OP_ATAN2: hy.atan2,
        ca.OP_HYPOT: lambda a, b: hy.sqrt(a * a + b * b),
    }


def piecewise(hy):
    # comparisons give 1.0 or 0.0, as CasADi's do; select(cond, x, 0) is CasADi's if_else_zero
    zero = hy.expression(0.0)
    return {
        ca.OP_LT: hy.lt,
        ca.OP_LE: hy.lte,
        ca.OP_EQ: hy.eq,
        ca.OP_NE: hy.neq,
        ca.OP_NOT: lambda a: hy.eq(a, zero),
        ca.OP_AND: lambda a, b: hy.logical_and([a, b]),
        ca.OP_OR: lambda a, b: hy.logical_or([a, b]),
        ca.OP_IF_ELSE_ZERO: lambda cond, a: hy.select(cond, a, zero),
    }


def to_heyoka(f: ca.Function, inputs: list[list]) -> list:
    """Evaluate the SX function ``f`` on heyoka expressions.

    Parameters
    ----------
    f : casadi.Function
        An SX function with dense vector inputs and outputs.
    inputs : list of lists
        For each input of ``f``, one heyoka expression (or float) per entry.

    Returns
    -------
    list of lists: for each output, one heyoka expression per entry.
    """
    import heyoka as hy

    if not f.is_a("SXFunction"):
        raise TypeError("to_heyoka needs an SX function")
    unary_ops, binary_ops, piecewise_ops = unary(hy), binary(hy), piecewise(hy)
    work: dict[int, object] = {}
    outputs = [[None] * f.nnz_out(i) for i in range(f.n_out())]
    for k in range(f.n_instructions()):
        op = f.instruction_id(k)
        o = f.instruction_output(k)
        i = f.instruction_input(k)
        if op == ca.OP_CONST:
            work[o[0]] = hy.expression(float(f.instruction_constant(k)))
        elif op == ca.OP_INPUT:
            work[o[0]] = inputs[i[0]][i[1]]
        elif op == ca.OP_OUTPUT:
            outputs[o[0]][o[1]] = work[i[0]]
        elif op in unary_ops:
            work[o[0]] = unary_ops[op](work[i[0]])
        elif op in binary_ops:
            work[o[0]] = binary_ops[op](work[i[0]], work[i[1]])
        elif op in piecewise_ops:
            args = [work[i[0]]] if op == ca.OP_NOT else [work[i[0]], work[i[1]]]
            work[o[0]] = piecewise_ops[op](*args)
        else:
            raise NotImplementedError(f"CasADi operation {op} has no heyoka translation")
    for i, out in enumerate(outputs):
        for j, e in enumerate(out):
            if e is None:  # structurally zero entry
                out[j] = hy.expression(0.0)
    return outputs
