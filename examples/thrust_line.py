# %% [markdown]
# # The thrust line of an arch at collapse
#
# A notebook-style script (each `# %%` is a cell in Jupyter or VS Code): it analyses a bundled
# scene with the Python package `voussoir` (pip install ./python) and draws the voussoirs,
# the thrust line at the collapse multiplier and its hinges with matplotlib.
#
#     python examples/thrust_line.py [SCENE.toml] [OUT.png]

# %%
import sys
from pathlib import Path

import matplotlib

if __name__ == "__main__" and "ipykernel" not in sys.modules:
    matplotlib.use("Agg")  # a file, not a window, when run as a script
import matplotlib.pyplot as plt
from matplotlib.patches import Polygon

import voussoir

repo = Path(__file__).resolve().parents[1]
args = [a for a in sys.argv[1:] if not a.startswith("-")] if __name__ == "__main__" else []
scene_path = Path(args[0]) if args else repo / "data" / "semicircular.toml"
out = Path(args[1]) if len(args) > 1 else Path("thrust_line.png")

# %% Analyse: the static lower bound gives the thrust line, the kinematic bound certifies it.
scene = voussoir.Scene.from_toml(str(scene_path))
r = voussoir.analyze(scene, direction="right")
print(f"{scene}: {r.status}, lambda = {r.lambda_lower} (upper bound {r.lambda_upper})")

# %% Draw: block i lies between joints i and i + 1 of the chain (left pier from its base,
# the arch from the left springing, the right pier down). A voussoir's outline is
# p1[i], p2[i], p2[i+1], p1[i+1] (straight chords); a pier course is the rectangle as wide
# as its lower joint (its top course is wider than the springing joint it carries).
p1, p2, thrust = r.p1, r.p2, r.thrust
kinds = [j["kind"] for j in r.joints]


def outline(i):
    if "left_pier" in kinds[i]:
        (x0, y0), (x1, _), y_top = p1[i], p2[i], p1[i + 1][1]
        return [(x0, y0), (x1, y0), (x1, y_top), (x0, y_top)]
    if "right_pier" in kinds[i + 1]:
        (x0, y0), (x1, _), y_top = p1[i + 1], p2[i + 1], p1[i][1]
        return [(x0, y0), (x1, y0), (x1, y_top), (x0, y_top)]
    return [p1[i], p2[i], p2[i + 1], p1[i + 1]]


fig, ax = plt.subplots(figsize=(8, 5.5))
for i in range(r.blocks):
    block = outline(i)
    ax.add_patch(Polygon(block, closed=True, facecolor="0.85", edgecolor="0.35", lw=0.6))
if r.status == "collapse":
    ax.plot(thrust[:, 0], thrust[:, 1], color="tab:red", lw=1.8, label="thrust line at collapse")
    for k, h in enumerate(r.hinges, start=1):
        ax.plot(h["x"], h["y"], "o", ms=9, mfc="white", mec="tab:blue", mew=2,
                label="hinges" if k == 1 else None)
        ax.annotate(str(k), (h["x"], h["y"]), xytext=(6, 6), textcoords="offset points",
                    color="tab:blue")
    # The load arrow in the top left corner, which a structure standing on the ground and
    # spanning the plot leaves free (the bottom corners hold its supports and hinges).
    ax.annotate("", xy=(0.19, 0.93), xytext=(0.04, 0.93), xycoords="axes fraction",
                arrowprops=dict(arrowstyle="->", color="k"))
    ax.text(0.115, 0.95, r"$\lambda g$", transform=ax.transAxes, ha="center")
lam = "none" if r.lambda_lower is None else f"{r.lambda_lower:.4f}"
ax.set_title(f"{scene_path.stem}: {r.status}, collapse multiplier $\\lambda$ = {lam}")
ax.set_aspect("equal")
ax.autoscale_view()
ax.set_xlabel("x (m)")
ax.set_ylabel("y (m)")
# The legend goes under the plot, outside the axes, so it never covers the structure (inside
# the axes it sat on a portal's pier or an arch's haunch, whatever corner it took).
ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
fig.tight_layout()
fig.savefig(out, dpi=120, bbox_inches="tight")
print(f"written {out}")
