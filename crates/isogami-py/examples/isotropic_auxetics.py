"""Find the best isotropic auxetic design of a design database, deploy it and plot how it
opens: its principal expansions against t and the polar profile of its expansion.

    python isotropic_auxetics.py DATABASE [FIGURE]

DATABASE comes from `isogami explore --quick --db quick.db` (seconds) or a full exploration;
FIGURE defaults to isotropic_auxetic.png. Needs matplotlib (pandas is used when present).
"""

import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import isogami  # noqa: E402


def main(database: str, figure: str = "isotropic_auxetic.png") -> None:
    with isogami.open_database(database) as db:
        # The browser's filters: isotropic auxetics, largest area ratio first.
        query = isogami.Query(behaviour="isotropic_auxetic", sort="-max_area_ratio")
        try:
            table = db.dataframe(query)
            print(table[["spec", "max_area_ratio", "max_expansion", "linkage_signature"]].head().to_string())
        except ImportError:
            pass
        records = db.designs(query, limit=1)
    if not records:
        sys.exit(f"{database}: no isotropic auxetic design")
    best = records[0]
    print(f"best: {best.spec} (area ratio up to {best.max_area_ratio:.3f}, {best.linkage_signature})")

    run = isogami.deploy(best.design(), frames=120)
    print(f"deployed: {len(run)} frames, {run.end_reason}, behaviour {run.behaviour}")

    fig = plt.figure(figsize=(10, 4.2))
    ax = fig.add_subplot(1, 2, 1)
    lo, hi = run.principal_expansions.T
    ax.plot(run.t, hi, label="largest expansion")
    ax.plot(run.t, lo, "--", label="smallest expansion")
    ax.plot(run.t, run.area_ratio - 1, ":", label="area ratio − 1")
    ax.set_xlabel("deployment parameter t")
    ax.set_ylabel("expansion")
    ax.set_title(best.spec, fontsize=8)
    ax.legend()

    polar = fig.add_subplot(1, 2, 2, projection="polar")
    for t in (0.25, 0.5, 0.75, 1.0):
        p = run.profile(t=t)
        theta = np.append(p[:, 0], p[0, 0])
        eps = np.append(p[:, 1], p[0, 1])
        polar.plot(theta, eps, label=f"t = {run.t[run.frame_index(t)]:.2f}")
    polar.set_title("directional expansion ε(θ)")
    polar.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    fig.savefig(figure, dpi=120)
    print(f"wrote {figure}")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(*sys.argv[1:])
