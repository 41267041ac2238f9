"""The body's surface as a mesh, from its support function (shared by movies and 3-D scenes).

The meridian of the surface relative to G is, for theta in [0, pi], the contact point of
inclination theta: z = h_t sin(theta) - h cos(theta) along the axis k and x_P = h sin(theta) +
h_t cos(theta) from it (section 2), revolved about k. PyVista is imported only when called.
"""

from __future__ import annotations

import numpy as np

#: alternate azimuthal sectors: the spin about the axis shows
BODY_COLORS = ("#e6550d", "#fdd0a2")


def body_mesh(body, *, n_theta: int = 64, n_azimuth: int = 48):
    """The body's surface in body axes (G at the origin, axis k = e_z) as a PyVista PolyData
    with a ``sector`` scalar (0/1 in four azimuthal sectors).

    Parameters
    ----------
    body : Body
        The body, drawn from its support function.
    n_theta : int
        Points along the meridian, theta in [0, pi] (default 64).
    n_azimuth : int
        Intervals around the axis (default 48).

    Returns
    -------
    pyvista.PolyData
        The triangulated surface (units b).

    Examples
    --------
    >>> import phasekit as pk
    >>> mesh = pk.viz.body_mesh(pk.Spheroid(1.5), n_theta=8, n_azimuth=6)
    >>> mesh.n_points > 0
    True
    """
    import pyvista as pv

    z, r = body.outline(n_theta)  # an edged body's support traces only the rim, a compound's misses the joins
    az = np.linspace(0.0, 2 * np.pi, n_azimuth + 1)
    R, AZ = np.meshgrid(r, az, indexing="ij")
    pts = np.column_stack([(R * np.cos(AZ)).ravel(), (R * np.sin(AZ)).ravel(), np.repeat(z, az.size)])
    i, j = np.meshgrid(np.arange(z.size - 1), np.arange(az.size - 1), indexing="ij")
    a = (i * az.size + j).ravel()
    quads = np.column_stack([np.full(a.size, 4), a, a + az.size, a + az.size + 1, a + 1])
    mesh = pv.PolyData(pts, quads.ravel())
    mesh["sector"] = (np.floor(AZ / (np.pi / 2)) % 2).ravel()
    return mesh.triangulate()


def decorations(body):
    """Body-frame meshes drawn with the body: the stem of the tippe top modelled as a ball
    (:class:`~phasekit.bodies.spheroid.EccentricSphere`) on +k, decoration only; the top with its
    stem (:class:`~phasekit.bodies.compound.TippeTop`) is drawn whole from its outline."""
    import pyvista as pv

    from ..bodies.spheroid import EccentricSphere

    if isinstance(body, EccentricSphere):
        centre = body.offset  # the ball's centre is offset above G along k
        return [pv.Cylinder(center=(0.0, 0.0, centre + 1.05), direction=(0, 0, 1), radius=0.12, height=0.4)]
    return []
