"""Closed-form predictions for the tippe top (eccentric sphere with sliding friction).

Model and units
---------------
A sphere of radius R = 1 and mass m = 1 whose centre of mass G lies a distance ``alpha``
(0 < alpha < 1) from the geometric centre O along the symmetry axis k, G = O - alpha k;
gravity g = 1, so time is in units of sqrt(R/g). theta is the angle between k and the
vertical e_Z: theta = 0 upright (resting on the ball, G below O), theta = pi inverted.
``A`` (transverse, I1 in the literature) and ``C`` (axial, I3) are the principal moments
*about G* in units of m R^2, gamma = A/C. The contact point P = O - e_Z, so the vector
from G to P is r_P = GP = alpha k - e_Z. Friction acts only at P and only while P slides.

Status of every result (read this before citing)
------------------------------------------------
Only the abstracts / introductions of the papers below could be consulted while writing
this module (stored copies of arXiv / ar5iv / journal landing pages).
"Quoted" means the formula was seen in that text; "derived here" means it was derived for
this module and checked numerically in tests/test_tippetop_theory.py, not quoted.

[RR14] S. Rauch-Wojciechowski and N. Rutstam, "Dynamics of an inverting tippe top",
       SIGMA 10 (2014) 017, 18 pp., doi:10.3842/SIGMA.2014.017, arXiv:1306.2470
       (NOT 1309.5843). Quoted from the abstract: lambda_thres =
       sqrt(m g R^3 I3 alpha) (1+alpha)^2 / sqrt(1+alpha-gamma), gamma = I1/I3, stated
       there together with 1 - alpha^2 < gamma < 1. Quoted from the first paragraph of
       Sec. 1 (Introduction): "the TT inverts when ... 1 - alpha < gamma = I1/I3 < 1 + alpha
       where 0 < alpha < 1 is the eccentricity of the center of mass and I1, I3 are the main
       moments of inertia". The equation numbers inside the paper were not seen.
[RW13] S. Rauch-Wojciechowski and N. Rutstam, "Dynamics of the tippe top -- properties of
       numerical solutions versus the dynamical equations", arXiv:1306.5641 (abstract only
       seen; no formula from it is used here; journal reference not verified).
[USW05] T. Ueda, K. Sasaki and S. Watanabe, "Motion of the tippe top: gyroscopic balance
       condition and stability", SIAM J. Appl. Dyn. Syst. 4 (2005) 1159-1194,
       doi:10.1137/040615985, arXiv:physics/0507198. (The title is NOT "its phase diagram
       and bifurcation".) Only the abstract was seen: eccentric-sphere model, a modified
       Coulomb law vanishing at zero slip, three groups (I never flips however large the
       spin; II inverts completely; III turns over only to some theta_f < pi when spun
       sufficiently rapidly), three steady states, and a critical initial spin n_c for
       Group II to reach the completely inverted position. Their parameter definitions,
       group boundaries, n_c and theta_f formulas were NOT seen; everything implemented
       for that classification below is derived here.
[BMR04] N. M. Bou-Rabee, J. E. Marsden and L. A. Romero, "Tippe top inversion as a
       dissipation-induced instability", SIAM J. Appl. Dyn. Syst. 3 (2004) 352-377,
       doi:10.1137/030601351 (abstract seen: explicit spectral-stability criteria for the
       inverted / noninverted states, agreeing with the criterion for a heteroclinic
       connection; the model follows Or, SIAM J. Appl. Math. 54 (1994) 597-609). Their
       explicit formulas were not seen.

Not consulted at all (cited only because the task brief named them): Hugenholtz (Physica,
1952), Cohen (Am. J. Phys. 45 (1977) 12-17). Whether their statements use moments about G
or about O is UNVERIFIED.

The derivation used throughout (derived here, not quoted)
---------------------------------------------------------
Jellett's integral. With L the angular momentum about G and d = e_Z - alpha k = -r_P,
lambda = L . d is conserved for ANY friction law acting at P (the torques of the contact
force are r_P x F, orthogonal to d, and L . d(-alpha k)/dt = -alpha L.(w x k) = 0).
In phasekit's Euler-chart variables lambda = A Omega sin^2(theta) + C n (cos(theta) - alpha),
which is exactly what phasekit's ``jellett`` output computes (charts.py: ``A*Om*s*xP +
C*n*zPm`` with xP = sin(theta), zPm = cos(theta) - alpha for this body; vector chart:
``-dot(L, rP)``). NOTE the sign: phasekit's quantity is -L.r_P = L.(G - P) = L.PG, i.e.
MINUS L.GP; the words "L.GP" in phasekit/core/model.py and trajectory.py are a sign slip of the
text (the code is -L.GP). It is positive, = C n (1 - alpha), for the upright top spinning
with n > 0. [RR14]'s threshold, squared, coincides with the inverted-state stability
boundary derived below using exactly this lambda (see ``jellett_threshold``), so their
lambda equals phasekit's ``jellett`` up to an overall sign convention (UNVERIFIED in their
text; only lambda^2 enters any result here).

Energy / effective potential. The energy E = |v_G|^2/2 + w.L/2 + z_G (z_G = 1 - alpha cos
theta) never increases under sliding friction. Minimising E over the velocities at fixed
theta and fixed lambda gives L = lambda I d / (d.I d) and

    V(theta; lambda) = lambda^2 / (2 f(cos theta)) + 1 - alpha cos(theta),
    f(z) = d.I d = A (1 - z^2) + C (z - alpha)^2.

Its critical points are the steady (non-sliding) states: theta = 0, theta = pi and the
intermediate states with w = Omega d (rotation about the axis through G and P),
Omega^2 = alpha / D(z), D(z) = (A - C) z + C alpha > 0, z = cos(theta), which exist at
lambda^2 = g(z) := alpha f(z)^2 / D(z). With z = cos(theta),
dV/dz = (D / f^2)(lambda^2 - g(z)), so a steady state is a strict minimum of V (stable:
nearby motions keep E close and lambda fixed, and LaSalle takes them back) or a maximum
(unstable under dissipation): the upright state is stable iff lambda^2 < g(1), the
inverted state iff lambda^2 > g(-1), an intermediate state iff g'(z) < 0 there. The curve
lambda^2 = g(z) is therefore the whole bifurcation diagram. The tests confirm that this
energy criterion coincides with the eigenvalues of the full linearised equations (with a
viscous friction law F = -kappa u_P) and with long simulations.
Because the Coulomb law is discontinuous at zero slip, "linear stability" is only defined
for a regularised law; the energy criterion does not depend on the law (nor on mu).
"""

from __future__ import annotations

import math

import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_finite, check_positive, check_range, check_real

__all__ = [
    "classical_inversion",
    "critical_spin_from_jellett",
    "effective_potential",
    "full_inversion_jellett",
    "full_inversion_spin",
    "inversion_interval",
    "inverted_stable_spin",
    "jellett_of_vertical_start",
    "jellett_threshold",
    "moments_about_G",
    "spin_for_jellett",
    "steady_precession",
    "steady_state_jellett_sq",
    "theta_f",
    "theta_f_limit",
    "ueda_group",
    "ueda_group_limit",
    "upright_unstable_jellett",
    "upright_unstable_spin",
]


# ----------------------------------------------------------------------------- checks

def _alpha(alpha) -> float:
    return check_range("alpha", alpha, 0.0, 1.0, label="(0, 1) (G strictly between O and the surface)")


def _params(alpha, A, C) -> tuple[float, float, float]:
    return _alpha(alpha), check_positive("A", A), check_positive("C", C)


def _theta0(theta0) -> float:
    return check_range("theta0", theta0, 0.0, math.pi, closed="lr", label="[0, pi]")


def _f(z, alpha, A, C):
    """d.I d = A sin^2 + C (cos - alpha)^2 at z = cos(theta)."""
    return A * (1.0 - z * z) + C * (z - alpha) ** 2


def _D(z, alpha, A, C):
    return (A - C) * z + C * alpha


def _margins(a, A, C) -> tuple[float, float]:
    """(A - C (1 - alpha), C (1 + alpha) - A) = (D(1), D(-1)): both > 0 iff gamma is in the
    classical interval. Every function tests the boundaries through these two numbers, so
    they agree with each other exactly, also under rounding."""
    return A - C * (1.0 - a), C * (1.0 + a) - A


# -------------------------------------------------------------- 1. inversion condition

def inversion_interval(alpha) -> tuple[float, float]:
    """The open interval of gamma = A/C (moments about G) in which the tippe top inverts
    when spun fast enough: (1 - alpha, 1 + alpha).

    Source: [RR14], Sec. 1 (Introduction), first paragraph: "1 - alpha < gamma = I1/I3 <
    1 + alpha" with I1, I3 "the main moments of inertia" (quoted). That the moments are about
    the centre of mass G is not spelt out in the sentence seen; it is confirmed here by
    derivation (derived here, not quoted): the upright spinning state can be destabilised by
    spin iff A > C(1 - alpha) (``upright_unstable_spin`` finite) and the inverted one can be
    stabilised iff A < C(1 + alpha) (``inverted_stable_spin`` finite), both with A, C about G;
    with these moments the derivation also reproduces [RR14]'s lambda_thres exactly.
    For moments about the geometric centre O (A_O = A + alpha^2, C_O = C, parallel-axis
    theorem, m = R = 1) the same condition reads
    C_O (1 - alpha) + alpha^2 < A_O < C_O (1 + alpha) + alpha^2; see ``moments_about_G``.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.inversion_interval(0.3)
    (0.7, 1.3)
    """
    a = check_range("alpha", alpha, 0.0, 1.0, closed="l", label="[0, 1)")
    return (1.0 - a, 1.0 + a)


def classical_inversion(alpha, A, C) -> bool:
    """True iff 1 - alpha < A/C < 1 + alpha (moments about G), the condition for the top to
    invert fully when spun fast enough ([RR14] Sec. 1, quoted; see ``inversion_interval``).
    Equivalent to ``ueda_group_limit(...) == "II"``.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.classical_inversion(0.3, 0.38, 0.4)
    True
    """
    a, A, C = _params(alpha, A, C)
    up, inv = _margins(a, A, C)
    return up > 0 and inv > 0


def moments_about_G(alpha, A_O, C_O) -> tuple[float, float]:
    """Convert moments about the geometric centre O to moments about G (units m R^2):
    A = A_O - alpha^2, C = C_O (parallel-axis theorem; G lies on the axis, so C is unchanged).
    Elementary, derived here.

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(v, 6) for v in pk.theory.tippetop.moments_about_G(0.3, 0.5, 0.4)]
    [0.41, 0.4]
    """
    a = check_range("alpha", alpha, 0.0, 1.0, closed="l", label="[0, 1)")
    A_O, C_O = check_positive("A_O", A_O), check_positive("C_O", C_O)
    A = A_O - a * a
    if A <= 0:
        raise ParameterError("A_O", f"must exceed alpha^2 = {a * a:g} (A about G would be <= 0)", A_O)
    return A, C_O


# ----------------------------------------------------------------- Jellett and V

def jellett_of_vertical_start(alpha, A, C, theta0, n0) -> float:
    """Jellett's integral of phasekit's standard start ``vertical_spin_start(theta0, n0)``
    (angular velocity n0 e_Z at inclination theta0, G at rest: Omega = n0, n = n0 cos theta0):

        lambda = n0 [A sin^2(theta0) + C cos(theta0) (cos(theta0) - alpha)].

    This is phasekit's ``jellett`` output (= -L.r_P = L.(e_Z - alpha k)); derived here.
    At theta0 = 0 it is C n0 (1 - alpha), the Jellett integral of the upright top spinning at n0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.jellett_of_vertical_start(0.3, 0.38, 0.4, 0.1, 15.0), 6)
    4.206002
    """
    a, A, C = _params(alpha, A, C)
    th = _theta0(theta0)
    n0 = check_finite("n0", n0)
    return n0 * (A * math.sin(th) ** 2 + C * math.cos(th) * (math.cos(th) - a))


def spin_for_jellett(alpha, A, C, jellett, theta0=0.0) -> float:
    """The n0 >= 0 of ``vertical_spin_start(theta0, n0)`` whose Jellett integral has modulus
    |jellett| (inf if the start's Jellett factor vanishes at this theta0). Derived here.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.spin_for_jellett(0.3, 0.38, 0.4, 6.0, theta0=0.1), 6)
    21.39799
    """
    a, A, C = _params(alpha, A, C)
    th = _theta0(theta0)
    lam = check_real("jellett", jellett)
    if not math.isfinite(lam):
        return math.inf
    factor = A * math.sin(th) ** 2 + C * math.cos(th) * (math.cos(th) - a)
    return math.inf if factor == 0.0 else abs(lam) / abs(factor)


def effective_potential(alpha, A, C, jellett, theta):
    """V(theta; lambda) = lambda^2 / (2 (A sin^2 theta + C (cos theta - alpha)^2)) + 1 - alpha cos theta,
    the least energy compatible with inclination theta and Jellett integral lambda (derived
    here). Its critical points are the steady spinning states; minima are stable.
    ``theta`` may be an array.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.tippetop.effective_potential(0.3, 0.38, 0.4, 6.0, 1.0)), 6)
    62.446725
    """
    a, A, C = _params(alpha, A, C)
    lam = check_finite("jellett", jellett)
    z = np.cos(np.asarray(theta, dtype=float))
    return lam * lam / (2.0 * _f(z, a, A, C)) + 1.0 - a * z


def steady_state_jellett_sq(alpha, A, C, z):
    """g(z) = alpha f(z)^2 / D(z): the squared Jellett integral of the steady state at
    cos(theta) = z (inf where D(z) = (A - C) z + C alpha <= 0, i.e. no intermediate steady
    state at that angle). g(1) and g(-1) are the stability boundaries of the upright and the
    inverted state. Derived here; ``z`` may be an array.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.tippetop.steady_state_jellett_sq(0.3, 0.38, 0.4, 0.5)), 6)
    0.247094
    """
    a, A, C = _params(alpha, A, C)
    z = np.asarray(z, dtype=float)
    D = _D(z, a, A, C)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(D > 0, a * _f(z, a, A, C) ** 2 / np.where(D > 0, D, 1.0), np.inf)
    return out if out.ndim else float(out)


def steady_precession(alpha, A, C, theta) -> dict:
    """The intermediate steady state at inclination theta in (0, pi) (derived here): the body
    turns about the axis through G and P, w = Omega (e_Z - alpha k), with G at rest and P not
    sliding, precessing at Omega (> 0 branch) where Omega^2 = alpha / ((A - C) cos theta + C alpha).
    Returns dict(Omega, n, jellett, D) with spin n = w.k = Omega (cos theta - alpha) and
    jellett = Omega (A sin^2 theta + C (cos theta - alpha)^2).
    Raises ParameterError if no steady state exists at this theta (D <= 0).

    Examples
    --------
    >>> import phasekit as pk
    >>> {k: round(float(v), 6) for k, v in pk.theory.tippetop.steady_precession(0.3, 0.38, 0.4, 1.0).items()}
    {'Omega': 1.65753, 'n': 0.398308, 'jellett': 0.484274, 'D': 0.109194}
    """
    a, A, C = _params(alpha, A, C)
    th = check_range("theta", theta, 0.0, math.pi, label="(0, pi)")
    z = math.cos(th)
    D = _D(z, a, A, C)
    if D <= 0:
        raise ParameterError("theta", f"admits no steady precession for these moments ((A - C) cos(theta) + C alpha = {D:.6g} <= 0)", theta)
    Om = math.sqrt(a / D)
    return {"Omega": Om, "n": Om * (z - a), "jellett": Om * _f(z, a, A, C), "D": D}


# ------------------------------------------------------- 2/3. critical Jellett and spins

def upright_unstable_jellett(alpha, A, C) -> float:
    """abs(lambda) above which the upright spinning state (theta = 0) is unstable:
    lambda_up = sqrt(alpha C (1 - alpha)^4 / (gamma - 1 + alpha)) = sqrt(g(1)), inf (always
    stable) if gamma = A/C <= 1 - alpha. Derived here, not quoted (mirror image of [RR14]'s
    lambda_thres under alpha -> -alpha).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.upright_unstable_jellett(0.3, 0.38, 0.4), 6)
    0.339482
    """
    a, A, C = _params(alpha, A, C)
    den = _margins(a, A, C)[0]
    return math.inf if den <= 0 else math.sqrt(a * C * C * (1.0 - a) ** 4 / den)


def jellett_threshold(alpha, A, C) -> float:
    """[RR14]'s threshold of Jellett's integral, in units m = g = R = 1:

        lambda_thres = sqrt(C alpha) (1 + alpha)^2 / sqrt(1 + alpha - gamma),  gamma = A/C,

    quoted from the abstract of [RR14] (sqrt(m g R^3 I3 alpha) (1+alpha)^2 / sqrt(1+alpha-gamma)),
    where it is the threshold above which the minimum of their effective potential moves
    from near theta = 0 to near theta = pi (stated with 1 - alpha^2 < gamma < 1).
    Derived here independently: it is exactly the boundary lambda^2 = g(-1) above which the
    inverted spinning state is stable (for gamma < 1 + alpha) -- this agreement is what fixes
    the correspondence lambda_[RR14] = phasekit ``jellett`` (up to sign).
    Returns inf if gamma >= 1 + alpha (the inverted state is then never stable).
    The threshold is in terms of abs(lambda); phasekit's ``jellett`` is lambda itself.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.jellett_threshold(0.3, 0.38, 0.4), 6)
    0.989563
    """
    a, A, C = _params(alpha, A, C)
    den = _margins(a, A, C)[1]  # = C (1 + alpha - gamma)
    return math.inf if den <= 0 else math.sqrt(C * a) * (1.0 + a) ** 2 / math.sqrt(den / C)


def upright_unstable_spin(alpha, A, C) -> float:
    """Spin n (about the symmetry axis, = angular velocity) of the upright state theta = 0
    above which that state is unstable under sliding friction:

        n_up = (1 - alpha) sqrt(alpha / (A - C (1 - alpha))),   inf if A <= C (1 - alpha).

    Derived here, not quoted: lambda = C n (1 - alpha) at theta = 0 and lambda^2 > g(1). Checked
    in the tests against the eigenvalues of the linearised full equations (viscous friction),
    which change sign exactly there, independently of the friction coefficient.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.upright_unstable_spin(0.3, 0.38, 0.4), 6)
    1.212436
    """
    a, A, C = _params(alpha, A, C)
    den = _margins(a, A, C)[0]
    return math.inf if den <= 0 else (1.0 - a) * math.sqrt(a / den)


def inverted_stable_spin(alpha, A, C) -> float:
    """|spin| of the inverted state theta = pi (spinning on the 'stem' side, G above O) above
    which that state is stable:

        n_inv = (1 + alpha) sqrt(alpha / (C (1 + alpha) - A)),   inf if A >= C (1 + alpha).

    Derived here, not quoted (lambda = -C n (1 + alpha) at theta = pi, lambda^2 > g(-1)); it is
    [RR14]'s lambda_thres divided by C (1 + alpha). Note this is the spin IN the inverted state;
    the initial spin needed is ``critical_spin_from_jellett`` / ``full_inversion_spin``.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.inverted_stable_spin(0.3, 0.38, 0.4), 6)
    1.903005
    """
    a, A, C = _params(alpha, A, C)
    den = _margins(a, A, C)[1]
    return math.inf if den <= 0 else (1.0 + a) * math.sqrt(a / den)


# ------------------------------------------------------------ Ueda-type classification

def ueda_group_limit(alpha, A, C) -> str:
    """The fast-spin classification in the sense of [USW05]'s abstract (derived here; their
    own boundaries were not seen): "I" (never flips, gamma <= 1 - alpha: the upright state is
    stable at every spin), "II" (inverts completely once spun fast enough,
    1 - alpha < gamma < 1 + alpha, the classical interval) or "III" (gamma >= 1 + alpha: the
    inverted state is never stable and a fast top settles at theta_f < pi, see ``theta_f_limit``).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.ueda_group_limit(0.3, 0.38, 0.4)
    'II'
    """
    a, A, C = _params(alpha, A, C)
    up, inv = _margins(a, A, C)
    if up <= 0:
        return "I"
    if inv > 0:
        return "II"
    return "III"


def _quartic_roots(a, A, C, lam2):
    """Real roots in [-1, 1] of F(z) = alpha f(z)^2 - lam2 D(z) (sign of g(z) - lam2 where D > 0)."""
    delta = C - A
    fpoly = np.array([delta, -2.0 * C * a, A + C * a * a])
    F = a * np.polymul(fpoly, fpoly)
    F = np.polyadd(F, -lam2 * np.array([-delta, C * a]))
    F = np.trim_zeros(F, "f")
    if F.size <= 1:
        return []
    roots = np.roots(F)
    scale = max(1.0, float(np.max(np.abs(roots)))) if roots.size else 1.0
    out = []
    dF = np.polyder(F)
    for r in roots:
        if abs(r.imag) > 1e-7 * scale:
            continue
        z = float(r.real)
        for _ in range(3):  # Newton polish on the real polynomial
            d = np.polyval(dF, z)
            if d == 0:
                break
            z -= np.polyval(F, z) / d
        if -1.0 - 1e-12 <= z <= 1.0 + 1e-12:
            out.append(min(1.0, max(-1.0, z)))
    return sorted(out, reverse=True)


def _classify(a, A, C, lam2) -> tuple[str, float]:
    if not lam2 > 0:
        return "never", 0.0
    g1 = steady_state_jellett_sq(a, A, C, 1.0)
    if lam2 <= g1:
        return "never", 0.0
    # dV/dz = (D / f^2)(lam2 - g(z)) > 0 at z = 1: V falls as theta grows, until the first z
    # (going down from 1) where g(z) >= lam2, i.e. F(z) = alpha f^2 - lam2 D >= 0 (F > 0 where D <= 0).
    roots = [z for z in _quartic_roots(a, A, C, lam2) if z < 1.0]
    if roots:
        z = roots[0]
        if z > -1.0:
            return "partial", math.acos(z)
    return "full", math.pi


def ueda_group(alpha, A, C, n, *, theta0: float = 0.0) -> str:
    """Predicted fate of a top launched with phasekit's ``vertical_spin_start(theta0, n)``
    (theta0 small; for theta0 = 0, n is the spin of the upright top): "never" (stays near
    upright), "full" (ends spinning inverted, theta = pi) or "partial" (settles in the steady
    precession at theta_f < pi, see ``theta_f``).

    Derived here, not quoted (the finite-spin analogue of [USW05]'s Groups I / II / III, whose
    exact finite-spin statements were not seen). With lambda the start's Jellett integral
    (conserved) and g(z) = ``steady_state_jellett_sq``:

    * lambda^2 <= g(1) (upright stable; always so if gamma <= 1 - alpha): "never";
    * otherwise the energy descends from theta = 0 to the first steady state z = cos theta
      with g(z) >= lambda^2, which is a minimum of V: "partial" if it is interior,
      "full" if g < lambda^2 on all of [-1, 1] (no interior steady state, inverted state stable).

    For gamma in the classical interval and n -> inf this gives "full"; for gamma >= 1 + alpha
    "partial" with theta_f -> ``theta_f_limit``; for gamma <= 1 - alpha always "never".
    Validated in the tests by long simulations with a viscous friction law. Caveat: the rule
    assumes the motion stays close to the slow energy descent (small theta0, weak friction);
    where two stable states coexist (e.g. upright and intermediate) only the one reached from
    near upright is reported. It also assumes the top keeps sliding: under exact Coulomb
    friction the slip can vanish and the top then rolls, which does no work, so it inverts
    less than predicted (studies/tippe_top.py, mu = 0.3: the prediction holds in 164 of 165
    viscous runs and 108 of 165 Coulomb runs; every Coulomb exception stuck and rolled).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.ueda_group(0.3, 0.38, 0.4, 15.0, theta0=0.1)
    'full'
    """
    a, A, C = _params(alpha, A, C)
    lam = jellett_of_vertical_start(a, A, C, theta0, n)
    return _classify(a, A, C, lam * lam)[0]


def theta_f(alpha, A, C, n, *, theta0: float = 0.0) -> float:
    """The final inclination predicted by ``ueda_group`` for ``vertical_spin_start(theta0, n)``:
    theta_f = arccos(z_f) for the "partial" outcome, where z_f is the largest root in (-1, 1) of
    the quartic alpha f(z)^2 = lambda^2 ((A - C) z + C alpha) (i.e. g(z_f) = lambda^2 with
    g'(z_f) <= 0), f(z) = A (1 - z^2) + C (z - alpha)^2; 0 for "never", pi for "full".
    Derived here, not quoted ([USW05]'s theta_f formula was not seen).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.theta_f(0.3, 0.38, 0.4, 15.0, theta0=0.1), 6)
    3.141593
    """
    a, A, C = _params(alpha, A, C)
    lam = jellett_of_vertical_start(a, A, C, theta0, n)
    return _classify(a, A, C, lam * lam)[1]


def theta_f_limit(alpha, A, C) -> float:
    """Limit of theta_f for n -> inf in group III (gamma > 1 + alpha):
    cos(theta_f) = C alpha / (C - A) = -alpha / (gamma - 1), the angle where D(z) = 0 (the
    steady precession rate diverges there). nan outside group III. Derived here, not quoted.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.theta_f_limit(0.3, 0.38, 0.4), 6)
    nan
    """
    a, A, C = _params(alpha, A, C)
    if _margins(a, A, C)[1] >= 0:
        return math.nan
    return math.acos(C * a / (C - A))


def full_inversion_jellett(alpha, A, C) -> float:
    """The least abs(lambda) above which ``ueda_group`` is "full" for every larger lambda:
    sqrt(max over z in [-1, 1] of g(z)) (inf unless gamma is in the classical interval).
    It equals [RR14]'s ``jellett_threshold`` whenever g attains its maximum at z = -1 (e.g.
    always for gamma >= 1, where g is decreasing); it is larger when the upright instability
    (g(1)) or an interior maximum of g is the binding constraint. Derived here.
    g'(z) has the sign of -(4 D^2 + (A - C) f), a convex quadratic, so the interior extrema
    are the (at most two) roots of 3 (C-A)^2 z^2 - 6 (C-A) C alpha z + 4 C^2 alpha^2 - (C-A)(A + C alpha^2).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.full_inversion_jellett(0.3, 0.38, 0.4), 6)
    0.989563
    """
    a, A, C = _params(alpha, A, C)
    if not classical_inversion(a, A, C):
        return math.inf
    cand = [1.0, -1.0]
    delta = C - A
    if delta != 0.0:
        q = np.roots([3 * delta * delta, -6 * delta * C * a, 4 * C * C * a * a - delta * (A + C * a * a)])
        cand += [float(r.real) for r in q if abs(r.imag) < 1e-12 and -1.0 < r.real < 1.0]
    return math.sqrt(max(steady_state_jellett_sq(a, A, C, z) for z in cand))


def full_inversion_spin(alpha, A, C, *, theta0: float = 0.0) -> float:
    """n_c: the initial spin of ``vertical_spin_start(theta0, n)`` above which full inversion
    is predicted (``full_inversion_jellett`` converted with the start's Jellett factor).
    The analogue of [USW05]'s n_c (their formula not seen; derived here).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.full_inversion_spin(0.3, 0.38, 0.4, theta0=0.1), 6)
    3.529109
    """
    return spin_for_jellett(alpha, A, C, full_inversion_jellett(alpha, A, C), theta0)


def critical_spin_from_jellett(alpha, A, C, theta0) -> float:
    """The n0 at which the Jellett integral of ``vertical_spin_start(theta0, n0)`` equals
    [RR14]'s lambda_thres (``jellett_threshold``):

        n0 = lambda_thres / |A sin^2 theta0 + C cos theta0 (cos theta0 - alpha)|

    (inf if gamma >= 1 + alpha or the factor vanishes). At theta0 = 0 this is
    (1 + alpha)^2 sqrt(alpha / (C (1 + alpha - gamma))) / (1 - alpha). This is where the inverted
    state becomes stable; full inversion of that start additionally needs the upright state to
    be unstable and no intermediate steady state in the way -- see ``full_inversion_spin``,
    which equals this value whenever max g = g(-1).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.critical_spin_from_jellett(0.3, 0.38, 0.4, 0.1), 6)
    3.529109
    """
    return spin_for_jellett(alpha, A, C, jellett_threshold(alpha, A, C), theta0)
