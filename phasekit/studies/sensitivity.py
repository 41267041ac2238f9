"""The definitions at which the threshold study measures a threshold's sensitivity
(:func:`sensitivity_definitions`, :func:`sensitivity_parent`) and :func:`prepare_definitions`,
which compiles their models before a run. The sensitivity of one threshold to its seed distance
is :class:`phasekit.thresholds.result.Sensitivity`."""

from __future__ import annotations

from dataclasses import replace

from ..thresholds.definition import DEFAULT_DEFINITIONS, Definition


def sensitivity_definitions(quick: bool = False) -> list[Definition]:
    """The variants of the default definition ("sliding", d = 0.01) and of the literal one with
    eps = 1e-4 at which a threshold's sensitivity is measured: the seed distance d (or delta)
    halved and doubled, rtol 1e-8 and 1e-10, and (unless ``quick``) eps 1e-4, 1e-6, 1e-8 for the
    sliding seed and the literal variants. Each is named after what it changes
    (:func:`sensitivity_parent` names the definition it varies).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [d.name for d in ps.sensitivity_definitions(quick=True)]
    ['sliding-d0.005', 'sliding-d0.02', 'sliding-rtol1e-8', 'sliding-rtol1e-10']
    >>> len(ps.sensitivity_definitions())
    13
    """
    base = next(d for d in DEFAULT_DEFINITIONS if d.name == "sliding")
    lit = Definition("literal-eps1e-4", "literal", eps=1e-4)
    out = [replace(base, name="sliding-d0.005", amplitude=0.005), replace(base, name="sliding-d0.02", amplitude=0.02),
           replace(base, name="sliding-rtol1e-8", rtol=1e-8), replace(base, name="sliding-rtol1e-10", rtol=1e-10)]
    if quick:
        return out
    out += [replace(base, name=f"sliding-eps{e:g}", eps=e) for e in (1e-4, 1e-6, 1e-8)]
    out += [replace(lit, name="literal-eps1e-4-delta0.005", amplitude=0.005), replace(lit, name="literal-eps1e-4-delta0.02", amplitude=0.02),
            replace(lit, name="literal-eps1e-4-rtol1e-8", rtol=1e-8), replace(lit, name="literal-eps1e-4-rtol1e-10", rtol=1e-10),
            replace(lit, name="literal-eps1e-6", eps=1e-6), replace(lit, name="literal-eps1e-8", eps=1e-8)]
    return out


def sensitivity_parent(defn) -> str:
    """The name of the definition of :data:`DEFAULT_DEFINITIONS` that a variant of
    :func:`sensitivity_definitions` (a definition, or a row with its ``seed``) varies.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [ps.sensitivity_parent(d) for d in ps.sensitivity_definitions()][::6]
    ['sliding', 'sliding', 'literal-eps1e-4']
    """
    return "literal-eps1e-4" if defn.seed == "literal" else "sliding"


def prepare_definitions(definitions, bodies, engine: str = "batch") -> None:
    """Compile (or load) the models and integrators of each definition for each body (or
    aspect ratio) in ``bodies`` (:meth:`Definition.prepare`), e.g. before a Dask run ships them
    to the workers; a definition that cannot be prepared is skipped (its runs compile when they
    first need it).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.prepare_definitions(pk.thresholds.DEFAULT_DEFINITIONS[:1], [1.5])
    """
    for d in definitions:
        for a in bodies:
            try:
                d.prepare(a, engine=engine)
            except Exception:
                pass
