"""Published numbers, with where they come from (Shimomura, Branicki & Moffatt, Proc. R. Soc. A)."""

import numpy as np

# Section 5, eq. (5.2): the prolate start (printed to one significant figure, "approximately").
PAPER_START_5_2 = dict(U=7e-5, V=2e-6, Lambda=-1e-4, theta=np.pi / 2 - 1e-3, n=2e-2)
# Section 5, eq. (5.1): the oblate start.
PAPER_START_5_1 = dict(U=8e-7, V=4e-6, Lambda=1e-5, theta=4e-6)

# docs/physics.md (zero slip, pitfall 1): from (5.2) with Omega0 = 10.5 and the slip regularised as
# sqrt(|u|^2 + eps^2): eps = 1e-3 jumps at t ~ 52, eps = 1e-4 at t ~ 157, eps <= 1e-6 sticks.
PITFALL_5_2_JUMP_T = {1e-3: 52.0, 1e-4: 157.0}
