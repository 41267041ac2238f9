"""Translate CasADi SX functions into heyoka expressions.

The equations are written once, as CasADi SX (:mod:`phasekit.model`); this walks a
function's instruction list (its algorithm, with common subexpressions already shared)
and rebuilds each instruction with heyoka's expression system, so the Taylor integrator
runs exactly the compiled model and nothing is transcribed twice.
"""

from __future__ import annotations

import casadi as ca

__all__ = ["to_heyoka"]


def _unary(hy):
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
        ca.OP_ASSIGN: lambda a: a,
    }


def _binary(hy):
    return {
        ca.OP_ADD: lambda a, b: a + b,
        ca.OP_SUB: lambda a, b: a - b,
        ca.OP_MUL: lambda a, b: a * b,
        ca.OP_DIV: lambda a, b: a / b,
        ca.OP_POW: lambda a, b: a**b,
        ca.OP_CONSTPOW: lambda a, b: a**b,
        ca.OP_ATAN2: hy.atan2,
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
    unary, binary = _unary(hy), _binary(hy)
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
        elif op in unary:
            work[o[0]] = unary[op](work[i[0]])
        elif op in binary:
            work[o[0]] = binary[op](work[i[0]], work[i[1]])
        else:
            raise NotImplementedError(f"CasADi operation {op} has no heyoka translation")
    for i, out in enumerate(outputs):
        for j, e in enumerate(out):
            if e is None:  # structurally zero entry
                out[j] = hy.expression(0.0)
    return outputs
