"""Figures of seed 001 runs (matplotlib, Agg)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def section5_figure(res, path: Path, i: int = 0, ideal=None) -> None:
    """Height error, velocity error, error quaternion, thrust, torque and d0e of case i (and
    optionally the ideal-pointing run, dashed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(3, 2, figsize=(11, 9))
    t, o = res.t, res.out
    runs = [(res, "-", "coupled")] + ([(ideal, "--", "ideal pointing")] if ideal else [])
    for r, ls, lab in runs:
        ax[0, 0].plot(r.t, r.out["eh"][:, i], ls, label=lab)
        ax[0, 1].plot(r.t, np.linalg.norm(r.out["ev"][:, :, i], axis=1), ls, label=lab)
        ax[1, 1].plot(r.t, r.out["thrust"][:, i] / 1e3, ls, label=lab)
    ax[0, 0].set_ylabel("e_h [m]")
    ax[0, 1].set_ylabel("|e_v| [m/s]")
    ax[0, 1].set_yscale("log")
    for k in range(4):
        ax[1, 0].plot(t, o["eq"][:, k, i], label=f"e_Q{k}")
    ax[1, 0].set_ylabel("error quaternion")
    ax[1, 1].axhline(34.0, color="k", lw=0.5)
    ax[1, 1].set_ylabel("thrust [kN]")
    for k, n in enumerate("xyz"):
        ax[2, 0].plot(t, o["torque"][:, k, i], label=f"M_{n}")
    ax[2, 0].set_ylabel("torque [N m]")
    ax[2, 1].plot(t, o["d0e_attitude"][:, i], label="d0e attitude [rad/s^2]")
    ax[2, 1].plot(t, o["d0e_orbit"][:, i] / 100, label="d0e orbit / 100 [m/s^2]")
    ax[2, 1].set_ylabel("d0e")
    for a in ax.ravel():
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
        a.set_xlabel("t [s]")
    fig.suptitle("seed 001 Section 5 case (lgw)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
