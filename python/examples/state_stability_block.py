# %% [markdown]
# # Which mode grows? The Swegle block's spectrum, from a state given as arrays
# The Swegle block as this project sets it up (problems/swegle.hpp; Powell 2012, Fig. 4.2): 21 x 21 free particles of
# steel (g-cm-us units: rho0 7.8, E 2.1, nu 0.3) at dx = 0.01 cm, h = 1.3 dx, with fixed layers one support thick,
# under a uniform volume strain of 2 % (tension). Any SPH code's state can be passed the same way: positions,
# densities, masses, h, fixed flags (and velocities and deviatoric stresses when it moves). The verdict separates the
# scheme's own growth (semi-discrete, J = dF/dy) from the integrator's (the one-step map at dt).
# %%
import os
import numpy as np
import matplotlib.pyplot as plt
import sphstab

dx, h, n = 0.01, 0.013, int(os.environ.get("SPHSTAB_EXAMPLE_BLOCK", "21"))
p = sphstab.lattice("square", n, spacing=dx, support_radius=sphstab.Kernel("cubic", 2).support_radius(h))
rho = np.full(len(p), 7.8 / 1.02)
rho0, K, mu = sphstab.material_from_youngs(2.1, 0.3, 7.8)
c_p = np.sqrt((K + 4 * mu / 3) / rho0)  # P-wave speed: dt = 0.2 h / c_p, a customary Courant number
s = sphstab.state_stability(p.x, rho, rho * p.volume, h, fixed=p.fixed, spacing=dx, youngs=2.1, poisson=0.3,
                            rho0=7.8, integrator="pc", dt=0.2 * h / c_p, t_end=20.0)
v, mode = s.verdict, s.semi_discrete_mode
print(f"verdict {v.letter} ({v.name}): gamma_J = {v.semi_discrete_growth:.4g} /us, gamma_M = {v.map_growth:.4g} /us, "
      f"floor {v.floor:.4g} /us; mode at k dx/pi = ({mode['kx_over_pi']:.3f}, {mode['ky_over_pi']:.3f}); "
      f"leap-frog limit {s.time_step.leapfrog:.4g} us")
# %%
free = p.x[~p.fixed]
plt.figure(figsize=(5, 5))
plt.scatter(p.x[p.fixed, 0], p.x[p.fixed, 1], s=4, c="0.7", label="fixed")
if mode["shape"].size:
    plt.quiver(free[:, 0], free[:, 1], mode["shape"][:, 0], mode["shape"][:, 1], color="C3", label="unstable mode")
plt.gca().set_aspect("equal"), plt.legend(loc="upper right"), plt.title(f"verdict {v.letter}")
plt.savefig("state_stability_block.png", dpi=120)
