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
this module and checked numerically in tests/theory/test_tippe_top_closed_forms.py, not quoted.

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
MINUS L.GP; the words "L.GP" in phasekit/core/observables.py and trajectory.py are a sign slip of the
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


from .groups import theta_f, ueda_group, ueda_group_limit
from .inversion import classical_inversion, full_inversion_spin, jellett_of_vertical_start
from .steady import inverted_stable_spin, upright_unstable_spin

__all__ = [
    "classical_inversion",
    "full_inversion_spin",
    "inverted_stable_spin",
    "jellett_of_vertical_start",
    "theta_f",
    "ueda_group",
    "ueda_group_limit",
    "upright_unstable_spin",
]
