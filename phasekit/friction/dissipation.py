"""Where the energy goes besides sliding: rolling resistance, spin friction and air drag.

Each law is a *wrench* on the body, a force f at the centre of mass G and a couple Gamma,
given symbolically from the body's angular velocity w, the velocity v of G and the normal
reaction R (all in axes with e_Z vertical), and affine in R, so that the contact constraint
(2.8) still fixes R by one linear equation (:mod:`phasekit.core.fields`). Units are the
paper's: lengths b, forces M g, times sqrt(b/g).

RollingResistance(delta)
    Gamma = -delta R w_h/|w_h|, with w_h = w - (w.e_Z) e_Z the rolling part of w: the couple
    of a normal pressure displaced by delta ahead of the contact point. delta is a length.
    A uniform sphere of radius r rolling straight decelerates at (5/7) g delta / r.
SpinFriction(mu_s)
    Gamma = -mu_s R sign(w_Z) e_Z: Coulomb friction over a contact patch opposing the spin
    about the normal (pivoting). mu_s is a length (for a Hertz patch of radius a,
    mu_s = 3 pi mu a / 16). A body spinning in place stops at t = C n0 / (mu_s R).
AirDrag(rotation, rotation_quadratic, translation, translation_quadratic)
    Gamma = -(k1 + k2 |w|) w and f = -(c1 + c2 |v|) v: linear (viscous, Stokes) and quadratic
    (form drag) resistance of the air, acting in contact and in flight.
AirLayer(k)
    Gamma = -(k psidot / sin^3(theta)) (e_Z - cos(theta) k), psidot the precession rate of the
    axis k: viscous dissipation in the thin air layer under a disk rolling on its rim at a small
    angle to the table (Moffatt 2000), power exactly -k psidot^2 / sin(theta) along any motion.

The sign laws are set-valued at zero rate (stick in spin, stick in rolling). phasekit writes
spin friction's as x/sqrt(x^2 + eps^2) and rolling resistance's as x|x|^2/(|x|^2 + eps^2)^(3/2)
(flat at zero, so a rolling part that is zero up to rounding meets no stiff couple), with
eps = 1e-9 (a rate in units sqrt(g/b)): each couple differs from the set-valued law by a
relative (eps/|x|)^2/2 or 3 (eps/|x|)^2/2, below 2e-8 for rates above 1e-5; below that the
couple falls short by up to 1e-4 (at 1e-7, where the rest event fires) over the last
~1e-5/|dx/dt| of the approach, which the events then extrapolate to the exact zero. Where spin friction stops the spin about the
normal it holds it exactly (the modes ``sliding_no_pivot``, ``rolling_no_pivot``); the body's
coming to rest, where every rate vanishes together, is an event whose time is extrapolated to
the exact zero of the motion (:mod:`phasekit.core.system`). Not modelled: rolling held at zero
while the body still pivots or slides (the regularised couple then holds it, stiffly), and the
coupling of sliding and spin friction over a contact patch (Contensou). The power each law
takes out of the motion is f.v + Gamma.w, reported per law along a run.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from .._runtime.validate import check_nonnegative
from ..errors import ParameterError

#: the regularisation of the sign laws at zero rate (units sqrt(g/b)); see the module notes
SIGN_EPS = 1e-9
#: coefficients above this are not dissipation but numerical trouble
COEFF_MAX = 1e3


class Dissipation:
    """Base class of the dissipation laws: a wrench (f at G, couple Gamma) affine in R.

    Required of a subclass: ``name``, ``coefficients`` (the names of its parameters, in order),
    and ``wrench(w, v, R, q, k)`` returning CasADi 3-vectors (f, Gamma) from the angular velocity
    ``w``, the velocity ``v`` of G, the normal reaction ``R``, the parameters ``q`` and the unit
    vector ``k`` of the symmetry axis (in the axes of w; most laws ignore it).

    Parameters
    ----------
    *values : float
        The coefficients, in the order of ``coefficients``, each in [0, 1e3].

    Raises
    ------
    ParameterError
        If a coefficient is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> law = pk.SpinFriction(0.02)
    >>> isinstance(law, pk.friction.Dissipation), law.coefficients, law.contact
    (True, ('mu_s',), True)
    """

    name = "dissipation"
    coefficients: tuple[str, ...] = ()
    #: True when the law acts through the contact (it vanishes in flight, where R = 0)
    contact = True
    #: True when the wrench needs the contact point (:meth:`wrench_at`): friction over a patch
    needs_contact_point = False

    def __init__(self, *values: float):
        self.values = tuple(check_nonnegative(n, v, upper=COEFF_MAX) for n, v in zip(self.coefficients, values))

    @property
    def params(self) -> np.ndarray:
        """The law's part of a model's parameter vector."""
        return np.array(self.values, dtype=float)

    @property
    def n_params(self) -> int:
        return len(self.coefficients)

    def wrench(self, w, v, R, q, k):
        raise NotImplementedError("a Dissipation subclass must define wrench(w, v, R, q, k)")

    def wrench_at(self, w, v, R, q, k, contact):
        """The wrench given also the contact's geometry (:class:`phasekit.core.fields.ContactGeometry`:
        the contact point from G and the principal radii there), what the simulator calls; only a law
        with ``needs_contact_point`` reads it."""
        return self.wrench(w, v, R, q, k)

    def power(self, w, v, R, q, k, contact=None):
        """The power the law adds to the motion, f.v + Gamma.w (<= 0); contact as in :meth:`wrench_at`."""
        f, G = self.wrench_at(w, v, R, q, k, contact)
        return ca.dot(f, v) + ca.dot(G, w)

    def to_dict(self) -> dict:
        return {"law": self.name, **dict(zip(self.coefficients, self.values))}

    def describe(self) -> str:
        return f"{self.name}({', '.join(f'{n}={v:g}' for n, v in zip(self.coefficients, self.values))})"

    def __eq__(self, other) -> bool:
        return type(other) is type(self) and other.values == self.values

    def __hash__(self) -> int:
        return hash((type(self), self.values))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(f'{n}={v!r}' for n, v in zip(self.coefficients, self.values))})"


def _unit(x, eps=SIGN_EPS):
    return x / ca.sqrt(ca.dot(x, x) + eps * eps)


class RollingResistance(Dissipation):
    """Rolling resistance: a couple -delta R w_h/|w_h| against the rolling part of w.

    Parameters
    ----------
    delta : float
        The rolling-resistance length (units b), in [0, 1e3]: the offset of the normal
        pressure's resultant ahead of the contact point.

    Raises
    ------
    ParameterError
        If ``delta`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.RollingResistance(0.01).describe()
    'rolling-resistance(delta=0.01)'
    """

    name = "rolling-resistance"
    coefficients = ("delta",)

    def __init__(self, delta: float):
        super().__init__(delta)

    def wrench(self, w, v, R, q, k):
        # w_h |w_h|^2 / (|w_h|^2 + eps^2)^(3/2): flat at w_h = 0, so a rolling part that is zero up
        # to rounding (a body spinning in place) meets no stiff couple
        w_h = ca.vertcat(w[0], w[1], 0)
        s2 = ca.dot(w_h, w_h)
        return ca.SX.zeros(3), -q[0] * R * w_h * s2 / (s2 + SIGN_EPS * SIGN_EPS) ** 1.5


class SpinFriction(Dissipation):
    """Spin (pivoting) friction: a couple -mu_s R sign(w_Z) about the normal.

    Parameters
    ----------
    mu_s : float
        The spin-friction length (units b), in [0, 1e3]: the friction couple per unit normal
        force (3 pi mu a / 16 for a Hertz contact patch of radius a with friction mu).

    Raises
    ------
    ParameterError
        If ``mu_s`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.SpinFriction(0.02).describe()
    'spin-friction(mu_s=0.02)'
    """

    name = "spin-friction"
    coefficients = ("mu_s",)

    def __init__(self, mu_s: float):
        super().__init__(mu_s)

    def wrench(self, w, v, R, q, k):
        wz = w[2]
        return ca.SX.zeros(3), ca.vertcat(0, 0, -q[0] * R * wz / ca.sqrt(wz * wz + SIGN_EPS * SIGN_EPS))


class AirDrag(Dissipation):
    """Air drag on the moving body: a couple -(k1 + k2 |w|) w and a force -(c1 + c2 |v|) v at G.

    Parameters
    ----------
    rotation : float, optional
        k1, the linear (viscous) couple per unit angular velocity (units M b^2 sqrt(g/b)),
        in [0, 1e3]; default 0.
    rotation_quadratic : float, optional
        k2, the quadratic couple coefficient (units M b^2), in [0, 1e3]; default 0.
    translation : float, optional
        c1, the linear force per unit speed of G (units M sqrt(g/b)), in [0, 1e3]; default 0.
    translation_quadratic : float, optional
        c2, the quadratic force coefficient (units M / b), in [0, 1e3]; default 0.

    Raises
    ------
    ParameterError
        If a coefficient is not a finite number in [0, 1e3], or all four are zero.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.AirDrag(rotation=0.001).describe()
    'air-drag(rotation=0.001, rotation_quadratic=0, translation=0, translation_quadratic=0)'
    """

    name = "air-drag"
    coefficients = ("rotation", "rotation_quadratic", "translation", "translation_quadratic")
    contact = False

    def __init__(self, rotation: float = 0.0, rotation_quadratic: float = 0.0, translation: float = 0.0,
                 translation_quadratic: float = 0.0):
        super().__init__(rotation, rotation_quadratic, translation, translation_quadratic)
        if not any(self.values):
            raise ParameterError("rotation", "or another air-drag coefficient must be > 0 (all four are 0)", 0.0)

    def wrench(self, w, v, R, q, k):
        # |x| is smooth enough here: the quadratic term x|x| is C^1 at 0 and vanishes there
        wn = ca.sqrt(ca.dot(w, w) + SIGN_EPS * SIGN_EPS)
        vn = ca.sqrt(ca.dot(v, v) + SIGN_EPS * SIGN_EPS)
        return -(q[2] + q[3] * vn) * v, -(q[0] + q[1] * wn) * w


class AirLayer(Dissipation):
    """Viscous dissipation in the air layer under a disk on its rim (Moffatt 2000): a couple
    -(k psidot / sin^3(theta)) (e_Z - cos(theta) k) whose power is exactly -k psidot^2 / sin(theta).

    psidot = (w.e_Z - (w.k) cos(theta)) / sin^2(theta) is the precession rate of the axis k (the
    rate Omega at which the contact point goes round; Omega itself in the Euler chart). Moffatt's
    dissipation Phi = k Omega^2 / alpha, alpha the angle between the disk and the table (= theta,
    the axis from the vertical), is derived for a disk spinning in place at small alpha; this
    couple gives it, with sin(theta) for alpha, along *any* motion, so that the energy
    balance is the law's and the exponents alpha ~ (t0 - t)^(1/3), Omega ~ (t0 - t)^(-1/6) follow
    wherever the disk stays near spinning in place. The couple lies in the plane of e_Z and k,
    orthogonal to k: it brakes the precession only (neither the spin about k nor the rate of
    theta). It is singular at theta = 0 (a disk's run stops at ``FLAT_ANGLE``, face down): not for
    bodies that pass through the poles. It does not scale with R (it acts in flight too).

    Parameters
    ----------
    k : float
        The air layer's coefficient (units M b^2 sqrt(g/b)), in [0, 1e3]: Phi = k Omega^2 / alpha.
        For a disk of radius a in air of viscosity mu_air, Moffatt's estimate is of order
        2 pi mu_air a^3 (docs/physics.md).

    Raises
    ------
    ParameterError
        If ``k`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.friction.AirLayer(1e-4).describe()
    'air-layer(k=0.0001)'
    """

    name = "air-layer"
    coefficients = ("k",)
    contact = False

    def __init__(self, k: float):
        super().__init__(k)

    def wrench(self, w, v, R, q, k):
        # sin^2 from the horizontal part of k: exact near theta = 0, where 1 - cos^2 loses digits.
        # In the Euler chart sin^2 is sq(sin): CasADi turns sqrt(sq(x)) (and the derivative of
        # sq(x)^1.5) into |x|, which heyoka cannot take; 1e-300 keeps the sqrt and is lost to
        # rounding wherever sin^2 > 1e-284 (the disk stops at sin^2 = 1e-6)
        s2 = k[0] * k[0] + k[1] * k[1]
        c = k[2]
        psidot = (w[2] - ca.dot(w, k) * c) / s2
        return ca.SX.zeros(3), -(q[0] * psidot / (s2 * ca.sqrt(s2 + 1e-300))) * (ca.vertcat(0, 0, 1) - c * k)


#: the laws a model's description names, for rebuilding it
LAWS = {c.name: c for c in (RollingResistance, SpinFriction, AirDrag, AirLayer)}


def dissipation_from_dict(d: dict) -> Dissipation:
    """The law a :meth:`Dissipation.to_dict` describes."""
    cls = LAWS.get(d.get("law"))
    if cls is None:
        raise ParameterError("dissipation", f"must name one of {', '.join(LAWS)}", d.get("law"))
    return cls(*(d[n] for n in cls.coefficients))


def check_dissipation(laws) -> tuple[Dissipation, ...]:
    """A tuple of dissipation laws, at most one of each kind."""
    if isinstance(laws, Dissipation):
        laws = (laws,)
    try:
        laws = tuple(laws)
    except TypeError:
        raise ParameterError("dissipation", "must be a list of laws such as [pk.SpinFriction(0.02)]", laws) from None
    for d in laws:
        if not isinstance(d, Dissipation):
            raise ParameterError("dissipation", "must hold laws such as pk.RollingResistance(0.01)", d)
    kinds = [type(d) for d in laws]
    if len(set(kinds)) != len(kinds):
        raise ParameterError("dissipation", "must hold each kind of law at most once", [d.describe() for d in laws])
    return laws

