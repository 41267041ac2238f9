"""The contact patch's size from Hertz's theory: the effective modulus of two elastic bodies
(:func:`effective_modulus`), the radius of a circular patch (:func:`hertz_radius`) and the
ellipse of an elliptical one (:func:`hertz_ellipse`), the principal radii of a body's surface at
the contact point from its support function (:func:`principal_radii`), and materials
(:class:`Material`, :data:`MATERIALS`). The patch's friction is :mod:`phasekit.friction.patch`'s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special
from scipy.optimize import brentq

from .._runtime.validate import check_positive, check_range
from ..errors import ParameterError
from .patch import PI, hyp2f1


def effective_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """The contact modulus E* = 1/((1 - nu1^2)/E1 + (1 - nu2^2)/E2), in the unit of E1 and E2.

    Parameters
    ----------
    E1, nu1, E2, nu2 : float
        Young's moduli (> 0) and Poisson's ratios (in (-1, 0.5]); ParameterError otherwise.

    Examples
    --------
    >>> from phasekit.friction.hertz import effective_modulus
    >>> round(effective_modulus(210e9, 0.3, 72e9, 0.23) / 1e9, 3)   # steel on glass, GPa
    57.184
    """
    E1, E2 = check_positive("E1", E1), check_positive("E2", E2)
    nu1 = check_range("nu1", nu1, -1.0, 0.5, closed="r", label="(-1, 0.5]")
    nu2 = check_range("nu2", nu2, -1.0, 0.5, closed="r", label="(-1, 0.5]")
    return 1.0 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2)


def hertz_radius(R_newton: float, E1: float, nu1: float, E2: float, nu2: float, rho1: float, rho2: float) -> float:
    """Radius of the Hertz patch of a body on a flat table, SI in and out: a = (3 R r_e/(4 E*))^(1/3),
    r_e = sqrt(rho1 rho2), the circle equivalent to Hertz's ellipse (Johnson 1985, section 4.2): exact
    for rho1 = rho2; sqrt(a_major b_minor) of :func:`hertz_ellipse` is 0.975 of it at rho_max/rho_min
    = 4, 0.937 at 10 (an approximation for elongated contacts).

    Parameters
    ----------
    R_newton, E1, nu1, E2, nu2, rho1, rho2 : float
        Normal force (N), Young's modulus (Pa) and Poisson's ratio (in (-1, 0.5]) of the body, then of
        the table, and the body's principal radii of curvature at the contact (m; :func:`principal_radii`).
        Returns a, m; ParameterError for a value out of range.

    Examples
    --------
    >>> from phasekit.friction.hertz import hertz_radius
    >>> round(hertz_radius(1.0, 210e9, 0.3, 72e9, 0.23, 0.01, 0.01) * 1e6, 2)  # 1 N, 10 mm steel ball on glass: um
    50.81
    """
    R_newton = check_positive("R_newton", R_newton)
    rho1, rho2 = check_positive("rho1", rho1), check_positive("rho2", rho2)
    return (3 * R_newton * math.sqrt(rho1 * rho2) / (4 * effective_modulus(E1, nu1, E2, nu2))) ** (1 / 3)


def unit_patch_radius(weight_newton: float, b: float, E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Hertz's patch radius, in units of b, of a contact whose principal radii are both b, under the
    weight: what :class:`phasekit.Contensou` with ``curvature=True`` scales by (rho1 rho2)^(1/6).

    Parameters
    ----------
    weight_newton, b : float
        The body's weight M g (N) and its unit of length b (m).
    E1, nu1, E2, nu2 : float
        As :func:`hertz_radius` (body, then table).

    Examples
    --------
    >>> from phasekit.friction.hertz import MATERIALS, unit_patch_radius
    >>> m, t = MATERIALS["hardwood"], MATERIALS["laminate"]   # a 5.9 g maple tippe top, b = 12.5 mm
    >>> round(unit_patch_radius(5.9e-3 * 9.81, 0.0125, m.E, m.nu, t.E, t.nu) * 12.5, 4)   # mm
    0.0706
    """
    b = check_positive("b", b)
    return hertz_radius(weight_newton, E1, nu1, E2, nu2, b, b) / b


def hertz_ellipse(R_newton: float, E1: float, nu1: float, E2: float, nu2: float, rho1: float,
                  rho2: float) -> tuple[float, float]:
    """The exact Hertz contact ellipse of a body on a flat table: semi-axes (a_major, b_minor), SI.

    A = 1/(2 rho_max), B = 1/(2 rho_min), e^2 = 1 - (b/a)^2 (Johnson 1985, eqs. (3.63)-(3.67)):
    B/A = [(a/b)^2 E(e) - K(e)]/[K(e) - E(e)] fixes b/a, then a^3 = 3 R rho_max [K - E]/(pi E* e^2),
    a along the flatter direction. Johnson's b/a ~ (rho_min/rho_max)^(2/3): 0.3969 for 0.3999 at a
    ratio of 4, 0.2154 for 0.2222 at 10.

    Parameters
    ----------
    R_newton, E1, nu1, E2, nu2, rho1, rho2 : float
        As :func:`hertz_radius`; rho_max/rho_min at most 1e8 (beyond: a line contact). Returns
        (a_major, b_minor), m, equal for rho1 = rho2.

    Examples
    --------
    >>> from phasekit.friction.hertz import hertz_ellipse
    >>> a, b = hertz_ellipse(1.0, 210e9, 0.3, 72e9, 0.23, 0.04, 0.01)
    >>> round(float(b / a), 4), round(float(0.25 ** (2 / 3)), 4)   # exact, Johnson's approximation
    (0.3999, 0.3969)
    """
    R_newton = check_positive("R_newton", R_newton)
    rho1, rho2 = check_positive("rho1", rho1), check_positive("rho2", rho2)
    E_star = effective_modulus(E1, nu1, E2, nu2)
    rmax, ratio = max(rho1, rho2), max(rho1, rho2) / min(rho1, rho2)
    if ratio > 1e8:
        raise ParameterError("rho1", "and `rho2` must differ by a factor below 1e8 (a line contact)", (rho1, rho2))
    if ratio - 1 < 1e-10:  # a circle: (K - E)/e^2 -> pi/4
        a = (3 * R_newton * math.sqrt(rho1 * rho2) / (4 * E_star)) ** (1 / 3)
        return a, a

    def parts(y):  # y = log((b/a)^2), m = e^2 = 1 - (b/a)^2: (B/A, (K - E)/e^2), free of cancellation
        k2, m = math.exp(y), -math.expm1(y)
        if m < 0.5:  # K - E = (pi m/4) 2F1(1/2, 3/2; 2; m), E - (1 - m) K = (pi m/4) 2F1(1/2, 1/2; 2; m)
            f1, f3 = (float(hyp2f1(0.5, b_, 2.0, np.array(m))) for b_ in (0.5, 1.5))
            return f1 / (k2 * f3), PI / 4 * f3
        K, E = special.ellipkm1(k2), special.ellipe(m)
        return (E - k2 * K) / (k2 * (K - E)), (K - E) / m

    # B/A grows from 1 (b = a) to oo (b -> 0); b/a ~ ratio^(-2/3) brackets the root from below
    y = brentq(lambda y: parts(y)[0] - ratio, -4 / 3 * math.log(ratio) - 6, -1e-300, xtol=1e-300, rtol=1e-15)
    a = (3 * R_newton * rmax * parts(y)[1] / (PI * E_star)) ** (1 / 3)
    return a, a * math.exp(y / 2)


def principal_radii(h, h_t, h_tt, theta):
    """Principal radii (rho1, rho2) of a body of revolution at its contact point, in the unit of h,
    from its support function h(theta) (the height of G with the axis at theta from the vertical).

    The meridian is the envelope of x sin(theta) - z cos(theta) = h (x from the axis, z along it): the
    contact point is x_P = h sin + h_t cos, z_P = h_t sin - h cos, d(x_P, z_P)/dtheta = (h + h_tt)(cos,
    sin), so rho1 = h + h_tt (meridional); the normal (vertical) meets the axis x_P/sin(theta) from P
    (Meusnier): rho2 = x_P/sin(theta) (parallel), at a pole (|sin| < 1e-8) its limit h + h_tt.

    Parameters
    ----------
    h, h_t, h_tt, theta : float or array_like
        h(theta) and its first two derivatives (any length unit), and theta (radians).

    Examples
    --------
    >>> import numpy as np
    >>> from phasekit.friction.hertz import principal_radii
    >>> th = 0.7   # a sphere of radius 2 with G 0.5 off centre along the axis
    >>> [round(float(x), 12) for x in principal_radii(2 - 0.5 * np.cos(th), 0.5 * np.sin(th), 0.5 * np.cos(th), th)]
    [2.0, 2.0]
    """
    h, h_t, h_tt, theta = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (h, h_t, h_tt, theta)))
    s = np.sin(theta)
    rho1, pole = h + h_tt, np.abs(s) < 1e-8
    with np.errstate(divide="ignore", invalid="ignore"):
        rho2 = np.where(pole, rho1, (h * s + h_t * np.cos(theta)) / np.where(pole, 1.0, s))
    return (float(rho1), float(rho2)) if rho1.ndim == 0 else (rho1, rho2)


@dataclass(frozen=True)
class Material:
    """Elastic constants for Hertz contacts, with where they come from.

    Attributes
    ----------
    name, E, nu, source, note
        What the material is, Young's modulus (Pa; wood: across the grain, what a contact on a board's
        face sees), Poisson's ratio, where they come from, and their spread and doubts.
    """

    name: str
    E: float
    nu: float
    source: str
    note: str = ""

    def __repr__(self) -> str:
        return f"Material({self.name!r}, E={self.E:.3g}, nu={self.nu:g})"


_WOOD = "USDA FPL Wood Handbook FPL-GTR-190 (2010) ch. 5: E_L at 12% moisture (T. 5-3a), nu (T. 5-2)"
_WOOD_NOTE = ("UNCERTAIN: E = E_L x ~0.13-0.15 (radial; tangential ~0.07), ratios from memory of T. 5-1, not "
              "rechecked; nu across the grain 0.3-0.7; wood is orthotropic: isotropic Hertz only estimates")
#: elastic constants for :func:`hertz_radius`, each with its source and doubts
MATERIALS = {m.name.split(" (")[0]: m for m in (
    Material("steel (AISI 52100 bearing steel; carbon steels alike)", 210e9, 0.30, "AISI 52100 datasheets (astmsteel"
             ".com: E 190-210 GPa, nu 0.27-0.30); Ashby & Jones, Engineering Materials 1, T. 3.1", "190-215 GPa"),
    Material("glass (soda-lime, float)", 72e9, 0.23, "makeitfrom.com soda-lime float glass (70-71 GPa, nu 0.23); "
             "Fluegel's data in Wikipedia 'Soda-lime glass' (72 container, 74 window)", "borosilicate ~63 GPa"),
    Material("brass (70/30 cartridge brass C26000, CuZn30)", 110e9, 0.33, "makeitfrom.com UNS C26000 (110 GPa, nu "
             "0.31); Olin Brass C26000 (112 GPa); AZoM article 6341 (117 GPa, nu 0.34)", "100-125 GPa over brasses"),
    Material("eggshell (hen's egg, calcite composite)", 30e9, 0.30, "Chiang et al., Biology 10:989 (2021), DOI 10.3390/"
             "biology10100989: effective moduli 23-48 GPa over 58 species", "UNCERTAIN: the chicken value not read, "
             "nu assumed (calcite); the shell is ~0.3 mm thick: a wider patch bends it, beyond half-space Hertz"),
    Material("hardwood (sugar maple, across the grain)", 1.6e9, 0.35, _WOOD + "; E_L = 12.6 GPa, nu_LR = 0.42",
             _WOOD_NOTE),
    Material("laminate (melamine-faced HPL table top)", 9e9, 0.30, "EN 438 minimum flexural modulus (>= 9000 N/mm^2) "
             "as tabulated in HPL-Kompendium, Anhang T. 12", "UNCERTAIN: nu assumed; a flexural minimum; the layer "
             "is 0.6-1.5 mm on particleboard (E ~ 2-4 GPa), which a wide patch feels"),
    Material("abs (acrylonitrile butadiene styrene)", 2.3e9, 0.40, "Granta MaterialUniverse, ABS (extrusion): E 2-2.9 "
             "GPa, nu 0.394-0.422", "grade-dependent; datasheets give nu 0.35; viscoelastic"),
    Material("pmma (acrylic, Plexiglas)", 3.2e9, 0.37, "makeitfrom.com PMMA (3.2 GPa); Cardarelli, Materials Handbook "
             "(2018) via matmake.com (3.04 GPa)", "E 2.4-3.3 GPa; nu 0.35-0.40 usual, not found in the pages read"),
    Material("oak (white oak, across the grain)", 1.9e9, 0.35, _WOOD + "; E_L = 12.3 GPa (red oak 12.5), nu_LR = 0.37",
             _WOOD_NOTE),
)}
