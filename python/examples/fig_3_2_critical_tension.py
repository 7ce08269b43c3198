# %% [markdown]
# # Critical tension against h for four kernels (Powell 2012, Fig. 3.2)
# The largest pre-tension T a regular 1D bar of 30 particles carries before A(T) = K - 4 T L (the conservative form,
# Powell (3.40)) stops being positive definite, from the same library call `sphstab tcrit` makes.
# %%
import os
import numpy as np
import matplotlib.pyplot as plt
import sphstab

h = np.arange(0.8, 3.0001, float(os.environ.get("SPHSTAB_EXAMPLE_STEP", "0.05")))
kernels = ["cubic", "quartic", "quintic", "wendland-c2"]
t = sphstab.table(sphstab.critical_tension(n=30, kernels=kernels, h=h))
for k in kernels:
    plt.semilogy(h, t["tcrit"][t["kernel"] == k], label=k)
plt.xlabel("h / dx"), plt.ylabel("T_crit"), plt.legend(), plt.savefig("fig_3_2_critical_tension.png", dpi=120)
