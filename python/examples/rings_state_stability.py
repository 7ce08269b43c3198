# %% [markdown]
# # The stability of a GMS rings state at mid-collision, perturbed
# Two rubber rings collide (Gray, Monaghan & Swift 2001, §7.2, GMS units) with GMS's scheme (XSPH, viscosity,
# artificial stress eps = 0.3), on a coarse grid so that the dense Jacobian of the moving state stays small. The run
# loop stops when the rings' centres are closest (a Python observer); the state there, with a small random velocity
# perturbation, is handed to state_stability: is it linearly unstable, and where does the fastest mode live?
# %%
import os
import numpy as np
import matplotlib.pyplot as plt
import sphstab

spacing, r_in, r_out = map(float, os.environ.get("SPHSTAB_EXAMPLE_RINGS", "0.4,3,4").split(","))
scene = sphstab.gms_rings_scene(spacing=spacing, inner_radius=r_in, outer_radius=r_out)
half = scene.particles // 2  # ring 0, then ring 1
distance = []


def observer(step, t, y):  # stop at the closest approach of the rings' centres: mid-collision
    x = scene.state(y)["x"]
    distance.append(x[half:, 0].mean() - x[:half, 0].mean())
    return "closest approach" if len(distance) > 2 and distance[-1] > distance[-2] else None


run = sphstab.run(scene, cfl=0.5, t_end=60.0, record_every=20, observer=observer)
state = scene.state(run.y)
rng = np.random.default_rng(1)
state["v"] = state["v"] + 1e-4 * rng.standard_normal(state["v"].shape)
s = sphstab.state_stability(**state, **scene.material, scheme=scene.scheme_options, dt=run.dt, t_end=scene.t_end)
v, mode = s.verdict, s.semi_discrete_mode
print(f"run: {run.message}; state at t = {run.time:.3g}: verdict {v.letter} ({v.name}), gamma_J = "
      f"{v.semi_discrete_growth:.3g}, gamma_M = {v.map_growth:.3g}, floor {v.floor:.3g}; fastest mode peaks at particle "
      f"{mode['particle']} (share {mode['particle_share']:.2f}); max |a| = {s.acceleration_max:.3g}")
# %%
x = state["x"]
plt.figure(figsize=(7, 4))
plt.scatter(x[:, 0], x[:, 1], s=6, c=np.r_[np.zeros(half), np.ones(scene.particles - half)], cmap="coolwarm")
if mode["shape"].size:
    plt.quiver(x[:, 0], x[:, 1], mode["shape"][:, 0], mode["shape"][:, 1], color="k")
plt.gca().set_aspect("equal"), plt.title(f"t = {run.time:.3g}: verdict {v.letter}")
plt.savefig("rings_state_stability.png", dpi=120)
