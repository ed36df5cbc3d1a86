#!/usr/bin/python3
"""Plot the Fig. 5 TCA curves written by validate_fig5_tca.

Usage: /usr/bin/python3 scripts/plot_fig5.py (OUT_DIR | OUT/fig5_curves.csv) [OUT/fig5.png]
One panel per TCA and load, one line per material and f12 form. Reads columns by name;
pass/fail lives in validate_fig5_tca.
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    csv_path = Path(argv[1])
    if csv_path.is_dir():
        csv_path = csv_path / "fig5_curves.csv"
    png_path = Path(argv[2]) if len(argv) > 2 else csv_path.with_name("fig5.png")
    data = np.genfromtxt(csv_path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    tcas = list(dict.fromkeys(data["tca"]))
    loads = sorted(set(data["load_g"]))
    fig, axes = plt.subplots(len(tcas), len(loads), figsize=(5 * len(loads), 3.8 * len(tcas)),
                             sharex=True, squeeze=False)
    styles = {"paper": "--", "castigliano": "-"}
    for i, tca in enumerate(tcas):
        for j, load in enumerate(loads):
            ax = axes[i][j]
            sel = (data["tca"] == tca) & (data["load_g"] == load)
            for material in dict.fromkeys(data["material"][sel]):
                for form in dict.fromkeys(data["f12_form"][sel]):
                    s = sel & (data["material"] == material) & (data["f12_form"] == form)
                    ax.plot(data["temperature_degC"][s], 1e3 * data["elongation_m"][s],
                            styles.get(form, ":"), marker=".", label=f"{material}, {form}")
            ax.set_title(f"{tca}, {load:g} g (incl. friction equivalent)")
            ax.set_xlabel("temperature [degC]")
            ax.set_ylabel("elongation [mm]")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
    fig.suptitle("Extension TCAs of [Pawlowski2019] Fig. 5: model curves")
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)
    print(f"wrote {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
