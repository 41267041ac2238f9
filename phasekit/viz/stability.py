"""The stability vocabulary of the figures: one word per steady state, and the colour and legend
label each word is drawn with, the same in every figure and 3-D scene.

The words follow :class:`phasekit.steady.FixedPoint`'s classification of its eigenvalues:
``unstable`` (a real part positive beyond its error bound), ``undecided`` (a real part within
its bound that double precision cannot sign), ``neutral`` (no growth and, beyond the family's
zero eigenvalues, no decay either) and ``stable``. Under exact Coulomb friction a zero-slip
state is linearised on the rolling field, which does no work: its spectrum is symmetric about
the imaginary axis, so a state that does not grow does not decay either, and is drawn as
neutral, never as stable. A family's stability (:class:`phasekit.steady.families.SpinFamily`,
``stable_on``) under exact Coulomb friction is a statement about that rolling spectrum too.
"""

from __future__ import annotations

#: the words, in the order of a legend
WORDS = ("stable", "neutral", "undecided", "unstable")
#: one colour per word (unknown: a family whose stability was not computed)
COLOURS = {"stable": "#1a9850", "neutral": "#2c7bb6", "undecided": "#de77ae", "unstable": "#d73027",
           "unknown": "#808080"}


def _rolling(law) -> bool:
    """Whether stability under ``law`` (a FrictionLaw) is that of the rolling field."""
    return law is not None and bool(law.has_rolling_mode)


def state_word(fp) -> str:
    """The word of a steady state: its :class:`phasekit.steady.FixedPoint` classification, with
    "stable" read as "neutral" on the rolling field (it has no decaying modes).

    Parameters
    ----------
    fp : FixedPoint
        A linearised steady state, e.g. a point of a branch of :func:`phasekit.steady_structure`.

    Returns
    -------
    str
        One of :data:`WORDS`.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.viz.stability import state_word
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Coulomb(0.1))
    >>> sorted({state_word(p) for b in s.branches for p in b.points})
    ['neutral']
    """
    word = fp.classification.split(":")[0].split(" ")[0]
    if word == "stable" and fp.law == "coulomb-rolling":
        return "neutral"
    return word if word in WORDS else "undecided"


def family_word(side, law) -> str:
    """The word of a family on one interval of its parameter (``side``: an entry of
    ``SpinFamily.stable_on``, True, False or None) under the friction law ``law``.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.viz.stability import family_word
    >>> family_word(True, pk.Coulomb(0.1)), family_word(True, pk.Viscous(0.1)), family_word(None, pk.Viscous(0.1))
    ('neutral', 'stable', 'unknown')
    """
    if side is None:
        return "unknown"
    return "unstable" if not side else "neutral" if _rolling(law) else "stable"


def law_text(law) -> str:
    """The friction law as a legend shows it, e.g. "viscous $\\mu$ = 0.1", "exact Coulomb $\\mu$ = 0.1".

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.viz.stability import law_text
    >>> law_text(pk.Viscous(0.1)), law_text(pk.Coulomb(0.3))
    ('viscous $\\\\mu$ = 0.1', 'exact Coulomb $\\\\mu$ = 0.3')
    """
    name = {"coulomb": "exact Coulomb", "coulomb-regularised": f"regularised Coulomb (eps = {law.eps:g})",
            "viscous": "viscous"}.get(law.name, law.name)
    return f"{name} $\\mu$ = {law.mu:g}"


def legend_label(word: str, law_label: str, *, rolling: bool) -> str:
    """The legend entry of a word: ``law_label`` (e.g. :func:`law_text`) says under which law;
    ``rolling``: the states were linearised on the rolling field (exact Coulomb).

    Examples
    --------
    >>> from phasekit.viz.stability import legend_label
    >>> legend_label("neutral", "exact Coulomb $\\\\mu$ = 0.1", rolling=True)
    'neutral (exact Coulomb $\\\\mu$ = 0.1: rolling, no decay)'
    """
    return {"stable": f"stable ({law_label})",
            "neutral": f"neutral ({law_label}: rolling, no decay)" if rolling
            else "neutral (zero real parts: no decay)",
            "undecided": "undecided (real part within its error bound)",
            "unstable": "unstable",
            "unknown": "stability not computed"}[word]
