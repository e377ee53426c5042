# %% [markdown]
# # gearimpact from Python: your gear pair, a time history, the friction sweep
#
# The spur gear impact model of Yang and Lin (1987) through the Python package
# `gearimpact`: numpy arrays in and out, the same numbers as the `gearimpact`
# program, SI units inside (m, kg, s, N, rad).
#
# Open it in Jupyter (Debian: `jupyter-notebook`) with the package from the
# build tree, after `scripts/test.sh` or `scripts/build.sh`:
#
#     PYTHONPATH=build/python jupyter notebook examples/gear_pair.ipynb
#
# or with the package installed in a virtual environment
# (`python3 -m venv --system-site-packages .venv && .venv/bin/pip install --no-build-isolation .`).
# The twin runs as a script too: `PYTHONPATH=build/python /usr/bin/python3 examples/gear_pair.py`.
# This notebook is written from its twin `examples/gear_pair.py` by
# `examples/make_notebook.py`; edit the twin.

# %%
import csv

import gearimpact
import matplotlib.pyplot as plt
import numpy as np

print("gearimpact", gearimpact.__version__)

# %% [markdown]
# ## 1. The mesh stiffness of your own gear pair
#
# A gear pair takes the keys of a case file's `[gears]` section, with units
# (`"3 mm"`, `"20 deg"`, `"210 GPa"`) or as SI floats. Keys you leave out keep
# the paper's values (20 and 80 teeth, module 2 mm, 20 deg, 10 mm wide, steel).
# A value outside its range raises `gearimpact.CaseError` naming the key.

# %%
mine = gearimpact.gear_pair(teeth1=25, teeth2=60, module="3 mm", face_width="15 mm")
paper = gearimpact.GearPair()
print(mine)
print("contact ratio: mine %.3f, the paper's %.3f"
      % (gearimpact.contact_ratio(mine), gearimpact.contact_ratio(paper)))

try:
    gearimpact.gear_pair(teeth1=6)
except gearimpact.CaseError as error:
    print("CaseError:", error)

# %% [markdown]
# `stiffness` gives the program's columns as numpy arrays: the contact
# position `x_m` on the line of action, the contact angle `phi1_rad` of (12),
# the bending and axial stiffnesses of each tooth, the Hertzian one and the
# pair's `ke` of (29), in N/m.

# %%
k_mine = gearimpact.stiffness(mine, points=101)
k_paper = gearimpact.stiffness(paper, points=101)

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
for k, label in [(k_mine, "25/60 teeth, m = 3 mm, L = 15 mm"), (k_paper, "the paper's 20/80")]:
    left.plot(np.degrees(k["phi1_rad"]), k["ke"] / 1e6, label=label)
left.set_xlabel("contact angle phi1 (deg)")
left.set_ylabel("Ke of one tooth pair (N/um)")
left.set_title("Mesh stiffness of one pair, (29)")
left.legend()
for name in ("kb1", "kb2", "ka1", "ka2"):
    right.semilogy(np.degrees(k_mine["phi1_rad"]), k_mine[name], label=name)
right.semilogy(np.degrees(k_mine["phi1_rad"]), k_mine["kh"], "k--", label="kh")
right.set_xlabel("contact angle phi1 (deg)")
right.set_ylabel("stiffness (N/m)")
right.set_title("The terms of your pair")
right.legend()
plt.show()

# %% [markdown]
# ## 2. Case 1 of the paper: free vibration in the backlash (Fig. 4)
#
# `simulate` runs a case: a `Case`, a case file's path or a Table 1 case
# number, with fields changed by keyword (`friction_coefficient=0.06`,
# `end_time="10 ms"`, `output_every=10`). `.summary` holds the program's JSON
# summary, `.series` its time-series columns.

# %%
result = gearimpact.simulate(1, output_every=10)
print(result)
s = result.series
for key in ("impacts_n1", "impacts_n2", "damping_loss_J", "friction_loss_J", "ledger_residual_max_J"):
    print(f"{key:>24}: {result.summary[key]}")

# %%
backlash_um = result.case.gears.backlash_m * 1e6
fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
top.plot(s["t_s"] * 1e3, s["s_m"] * 1e6, lw=1)
for level in (backlash_um, -backlash_um):
    top.axhline(level, color="gray", ls="--")
top.set_ylabel("s = Rb1 theta1 - Rb2 theta2 (um)")
top.set_title("Fig. 4(a) Case 1: relative displacement (dashed: the backlash)")
bottom.plot(s["t_s"] * 1e3, s["w1_rad_s"], label="omega1")
bottom.plot(s["t_s"] * 1e3, s["w2_rad_s"], label="omega2")
bottom.set_xlabel("time (ms)")
bottom.set_ylabel("angular velocity (rad/s)")
bottom.set_title("Fig. 4(c) Case 1: angular velocities")
bottom.legend()
plt.show()

# %% [markdown]
# Each impact is a record: the line (N1 drive flanks, N2 coast flanks), when
# it starts, its approach speed Vi and the restitution e(Vi) of (33).

# %%
for impact in result.impacts[:6]:
    print(f"{impact['line']} at {impact['start_s'] * 1e3:7.3f} ms: "
          f"Vi = {impact['impact_speed_m_s']:.4f} m/s, e = {impact['restitution']:.3f}")

# %% [markdown]
# A case of your own: start from a paper case (or `gearimpact.read_case("my_pair.toml")`)
# and change what differs, with the units of case files.

# %%
mine_case = gearimpact.paper_case(2, name="mine", friction_coefficient=0.06, module="3 mm",
                                  teeth1=25, teeth2=60, face_width="15 mm", end_time="10 ms",
                                  output_every=10)
print(mine_case.to_toml())
print(gearimpact.simulate(mine_case))

# %% [markdown]
# ## 3. The friction sweep (Fig. 7)
#
# Friction loss over damping loss for f = 0.01 ... 0.09, for Table 1's three
# cases (27 runs over every core). The stars are the paper's "about" values
# from `paper_data/dynamics_statements.csv`, shipped with the package.

# %%
sweep = gearimpact.sweep_friction()
statements = {}
with open(gearimpact.paper_data_dir() / "dynamics_statements.csv", newline="") as file:
    for row in csv.DictReader(file):
        statements[row["id"]] = float(row["paper_low"])

fig, axis = plt.subplots(figsize=(7, 4.5))
for n, marker in zip((1, 2, 3), "os^"):
    line, = axis.plot(sweep["f"], sweep[f"ratio_case{n}"], marker=marker, label=f"case {n}")
    for f, tag in ((0.01, "001"), (0.09, "009")):
        axis.plot(f, 1 / statements[f"fig7_case{n}_f{tag}"], "*", ms=14, color=line.get_color())
axis.set_xlabel("friction coefficient f")
axis.set_ylabel("friction loss / damping loss")
axis.set_title("Fig. 7 (stars: the paper's values)")
axis.legend()
plt.show()
