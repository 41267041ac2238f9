"""Number and table formatting shared by the generated pages (Markdown, read by MyST)."""

from __future__ import annotations

import math

import pandas as pd


def sig(x: float, n: int = 4) -> str:
    """``x`` to ``n`` significant digits, without an exponent for everyday magnitudes."""
    x = float(x)
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    if 1e-3 <= abs(x) < 1e6:
        digits = max(n - 1 - int(math.floor(math.log10(abs(x)))), 0)
        return f"{x:.{digits}f}"
    return sci(x, n - 1)


def sci(x: float, d: int = 1) -> str:
    """``1.2e-5`` (no zero padding in the exponent)."""
    m, e = f"{float(x):.{d}e}".split("e")
    return f"{m}e{int(e)}"


def fixed(x: float, d: int) -> str:
    return f"{float(x):.{d}f}"


def pct(x: float, d: int = 1, sign: bool = False) -> str:
    """A fraction as a percentage: 0.043 -> ``4.3%``."""
    return f"{100 * float(x):{'+' if sign else ''}.{d}f}%"


def rng(lo: float, hi: float, f=sig, sep: str = "-") -> str:
    a, b = f(lo), f(hi)
    return a if a == b else f"{a}{sep}{b}"


def table(header: list[str], rows: list[list]) -> str:
    """A Markdown pipe table."""

    def cell(v):
        return str(v).replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cell(h) for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(v) for v in r) + " |" for r in rows]
    return "\n".join(lines)


def a_label(a: float) -> str:
    """Aspect ratios as the studies name them (2/3, not 0.6667)."""
    return "2/3" if abs(a - 2 / 3) < 1e-9 else f"{a:g}"


def eps_label(e, digits: int = 1) -> str:
    return "exact" if pd.isna(e) else sci(e, digits)
