#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Resonance about a contact state: the paper's contactor before and after it touches
#
# Contact changes resonance: a sensor pressed on a surface, a transducer
# clamped in its housing. A modal analysis linearised about the state the
# quasistatic loop computes answers it. Here the contactor of the paper's
# example 2 (`demos/contactor_in_contact.json`: 20 V drive it across a
# 2e-11 m gap onto the foundation, which it touches) is analysed twice:
#   * `"at": "start"`: about the initial state, contact open: the modes of
#     the clamped body;
#   * `"at": "end"`: about the last converged state of the quasistatic run:
#     the foundation acts as a bed of stiffness p'(r) = c_p per unit area
#     where the body presses on it (SPEC: dynamics), so closing the contact
#     raises every mode.
# The paper gives no density: ZnO's, 5676 kg/m^3 (Auld), the same as the
# `ZnO-paper` preset. Both engines compute each spectrum; the demo checks
# that they agree to 1e-9 and that no mode went down. A figure of both
# spectra goes in DIR/figures/.
#
#     /usr/bin/python3 demos/demo_contact_resonance.py [--set time.steps=100]

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CONFIG = HERE / "contactor_in_contact.json"
MODES = 8


def spectrum(engine, state, out, overrides, build):
    args = runs.solver_commands(build, 1)[engine] + [
        "--config", str(CONFIG), "--output", str(out), "--quiet",
        "--set", "material.density=5676",
        "--set", f'analysis={{"modal":{{"modes":{MODES},"at":"{state}"}}}}']
    for o in overrides:
        args += ["--set", o]
    subprocess.run(args, check=True, env=runs.ENV)
    summary = json.loads((Path(out) / "summary.json").read_text())
    return [m["frequency"] for m in summary["modes"]], summary


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "contact_resonance"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    args = ap.parse_args()
    out = Path(args.output)
    (out / "figures").mkdir(parents=True, exist_ok=True)

    f, ok = {}, True
    for state in ("start", "end"):
        for engine in ("cpp", "reference"):
            f[state, engine], summary = spectrum(engine, state, out / f"{state}_{engine}",
                                                 args.set, args.build)
        a, b = f[state, "cpp"], f[state, "reference"]
        worst = max(abs(x - y) / abs(x) for x, y in zip(a, b))
        ok = ok and worst <= 1e-9
        contact = ""
        if state == "end":
            c = summary["steps"][-1]
            contact = (f" (contact force {c['contact_force'][1]:.4g} N/m, "
                       f"largest u.nu - g {c['max_penetration']:.2e} m)")
        print(f"at the {state}{contact}:\n  modes (Hz) "
              f"{', '.join(f'{x:.2f}' for x in a)}\n  engines differ by {worst:.1e}")
    raised = [e / s for s, e in zip(f["start", "cpp"], f["end", "cpp"])]
    print(f"end / start, mode by mode: {', '.join(f'{r:.4f}' for r in raised)}")
    ok = ok and min(raised) >= 1 - 1e-9

    # ## Both spectra
    fig, ax = plt.subplots(figsize=(7, 3.2))
    for state, mark, y in (("start", "o", 0), ("end", "s", 1)):
        ax.plot(f[state, "cpp"], [y] * MODES, mark, label=f'"at": "{state}"')
        for x in f[state, "cpp"]:
            ax.plot([x, x], [y - 0.15, y + 0.15], "k-", lw=0.6)
    ax.set(yticks=[0, 1], yticklabels=["contact open", "in contact"], ylim=(-0.6, 1.6),
           xlabel="frequency (Hz)", title="the contactor's first modes before and after it touches")
    fig.tight_layout()
    fig.savefig(out / "figures" / "spectra.png", dpi=130)
    plt.close(fig)
    print(f"figure: {out / 'figures' / 'spectra.png'}")
    if not ok:
        print("error: the engines disagree, or a mode went down on contact", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
