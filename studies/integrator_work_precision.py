"""Integrator work-precision: CPU time against error for every simulation method.

Two systems with exact reference solutions. (1) A two-degree-of-freedom mass-spring-damper driven
by a harmonic force at its first resonance; the force comes from an exosystem (an undamped
oscillator appended to the state), so the whole system is linear and autonomous and the matrix
exponential gives its exact solution. Its normal modes and the resonance peaks of its frequency
response are shown first. (2) A pendulum released from 150 degrees, whose exact motion is
theta(t) = 2 arcsin(k cd(omega0 t | k^2)), k = sin(theta0 / 2) (Jacobi elliptic functions; Lawden,
Elliptic Functions and Applications, 1989, sec. 5.2). Each method runs at several tolerances (or
fixed steps for rk4); the error is the maximum absolute state error on the output grid.
"""

import numpy as np
from scipy.linalg import expm
from scipy.special import ellipj

import vehdyn
from vehdyn.simulation import work_precision
from vehdyn.plotting import new_figure
from vehdyn.report import Study

M1, M2 = 1.0, 0.5  # [kg]
K1, K2 = 400.0, 200.0  # [N/m]
C1, C2 = 0.8, 0.4  # [N*s/m]


def two_dof(forcing_frequency=None):
    """The 2-DOF chain ground-k1-m1-k2-m2 with a force on m1 (an exosystem when a frequency is given)."""
    M = np.diag([M1, M2])
    K = np.array([[K1 + K2, -K2], [-K2, K2]])
    C = np.array([[C1 + C2, -C2], [-C2, C2]])
    plant = vehdyn.LinearModel.from_second_order(M, C, K, [[1.0], [0.0]], dof=["mass1_displacement",
                                                 "mass2_displacement"], inputs=["force"])
    if forcing_frequency is None:
        return plant
    w = forcing_frequency
    exo = vehdyn.LinearModel([[0.0, w], [-w, 0.0]], np.zeros((2, 0)), [[1.0, 0.0]], np.zeros((1, 0)),
                             states=["forcing_sine", "forcing_cosine"], inputs=[], outputs=["force"])
    return vehdyn.connect_in_series(exo, plant)


class Pendulum(vehdyn.Model):
    """Undamped pendulum theta'' = -(g/l) sin(theta)."""

    states = ("swing_angle", "swing_rate")
    phenomena = frozenset()

    def __init__(self, length=1.0, gravity=9.81):
        self.omega0 = np.sqrt(gravity / length)

    def rhs(self, t, x, u):
        angle, rate = x
        return np.stack([rate, -self.omega0**2 * np.sin(angle)])


def pendulum_exact(t, theta0, omega0):
    k = np.sin(theta0 / 2)
    sn, cn, dn, _ = ellipj(omega0 * t, k**2)
    theta = 2 * np.arcsin(k * cn / dn)
    # theta' = -2 k omega0 sn / dn * sqrt(1-k^2) ... from d/du cd = -(1-m) sn/dn^2
    rate = -2 * k * omega0 * (1 - k**2) * sn / dn**2 / np.sqrt(1 - (k * cn / dn) ** 2)
    return np.stack([theta, rate])


def run(study: Study) -> None:
    quick = study.quick
    repeats = 1 if quick else 3 if study.full else 2
    if quick:
        methods = {m: (1e-4, 1e-8) for m in ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")}
    elif study.full:
        # low-order methods take ~10^(digits/order) steps: stop them where a run would take minutes
        methods = {"RK45": (1e-3, 1e-5, 1e-7, 1e-9), "RK23": (1e-3, 1e-5, 1e-7),
                   "DOP853": (1e-3, 1e-5, 1e-7, 1e-9, 1e-11), "Radau": (1e-3, 1e-5, 1e-7, 1e-9),
                   "BDF": (1e-3, 1e-5, 1e-7), "LSODA": (1e-3, 1e-5, 1e-7, 1e-9, 1e-11)}
    else:  # the report's budget: the tightest tolerance of each method with --full
        methods = {"RK45": (1e-3, 1e-5, 1e-7), "RK23": (1e-3, 1e-5), "DOP853": (1e-3, 1e-5, 1e-7, 1e-9),
                   "Radau": (1e-3, 1e-5, 1e-7), "BDF": (1e-3, 1e-5), "LSODA": (1e-3, 1e-5, 1e-7, 1e-9)}

    # ---- 2-DOF: modes and resonance
    plant = two_dof()
    modal = plant.modal_analysis()
    study.table(modal.to_frame(), "two_dof_modes", caption="2-DOF normal modes (mass-normalized shapes)")
    fig, axes = new_figure(1, 2, width=9.0, height_per_row=3.2)
    ax = axes[0, 0]
    for i in range(2):
        shape = modal.shape(i, normalize="max")
        ax.plot([1, 2], list(shape.values()), "o-", label=f"mode {i + 1}: {modal.natural_frequency_hz[i]:.2f} Hz")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xticks([1, 2], ["mass 1", "mass 2"])
    ax.set_ylabel("mode shape [-] (max = 1)")
    ax.legend(fontsize=8)
    f = np.logspace(0, 1.7, 400 if quick else 2000)
    fr = plant.frequency_response(2 * np.pi * f)
    ax = axes[0, 1]
    for out in ("mass1_displacement", "mass2_displacement"):
        ax.loglog(f, np.abs(fr[out, "force"]), label=out.replace("_", " "))
    for fn in modal.natural_frequency_hz:
        ax.axvline(fn, color="grey", ls=":", lw=1)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("displacement / force [m/N]")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    study.figure(fig, "two_dof_modes_and_resonance", caption="Normal modes and frequency response (dotted: undamped natural frequencies)")

    # ---- work-precision, 2-DOF at resonance (exact reference through the matrix exponential)
    w1 = modal.natural_frequency[0]
    sys = two_dof(w1)
    t = np.linspace(0.0, 2.0 if quick else 10.0, 1001)
    x0 = {"forcing_sine": 0.0, "forcing_cosine": 1.0}
    # reference: x(t) = expm(A t) x0 sample by sample (independent of simulate's prefix scan)
    x0v = sys.state_vector(x0)
    ref = np.stack([expm(sys.A * tk) @ x0v for tk in t], axis=1)
    names = ["mass1_displacement", "mass2_displacement", "mass1_velocity", "mass2_velocity"]
    ref = ref[[sys.index(n) for n in names]]
    wp_lin = work_precision(sys, t, ref, x0=x0, signals=names,
                            methods={"exact": [0.0], **methods}, rk4_steps=(t[1] - t[0]) / np.array([1, 4] if quick else [1, 2, 4, 8]),
                            repeats=repeats)
    study.table(wp_lin, "work_precision_two_dof",
                caption=f"2-DOF at resonance, 0-{t[-1]:g} s: CPU time and max error against expm(A t) x0")

    # ---- work-precision, pendulum (exact elliptic-function reference)
    pend = Pendulum()
    theta0 = np.deg2rad(150.0)
    tp = np.linspace(0.0, 2.0 if quick else 10.0, 1001)
    refp = pendulum_exact(tp, theta0, pend.omega0)
    wp_pend = work_precision(pend, tp, refp, x0=[theta0, 0.0], methods=methods,
                             rk4_steps=(tp[1] - tp[0]) / np.array([1, 4] if quick else [1, 2, 4, 8]), repeats=repeats)
    study.table(wp_pend, "work_precision_pendulum", caption="Pendulum from 150 deg: CPU time and max error")

    fig, axes = new_figure(1, 2, width=10.0, height_per_row=3.6)
    for ax, df, title in ((axes[0, 0], wp_lin, "2-DOF at resonance"), (axes[0, 1], wp_pend, "pendulum, 150 deg")):
        for method, grp in df[df.status == "ok"].groupby("method", sort=False):
            grp = grp.sort_values("cpu_time")
            ax.loglog(np.maximum(grp.max_error, 1e-16), grp.cpu_time, "o-", label=method)
        ax.set_xlabel("max error [state units]")
        ax.set_ylabel("CPU time [s]")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    study.figure(fig, "work_precision", caption="Work-precision diagrams: lower left is better")
    best = wp_pend[(wp_pend.status == "ok") & (wp_pend.max_error <= 1e-6)].sort_values("cpu_time").head(1)
    if len(best):
        b = best.iloc[0]
        study.text(f"Pendulum: the cheapest run with max error <= 1e-6 rad is {b.method} "
                   f"({'rtol %.0e' % b.rtol if b.rtol == b.rtol and b.rtol is not None else 'step %.1e s' % b.step}), "
                   f"{b.cpu_time * 1e3:.2f} ms, error {b.max_error:.1e}.")
    ex = wp_lin[wp_lin.method == "exact"].iloc[0]
    study.text(f"2-DOF: the exact method (one matrix exponential and a prefix scan) is within {ex.max_error:.1e} "
               f"of expm(A t) x0 evaluated sample by sample, in {ex.cpu_time * 1e3:.2f} ms.")


if __name__ == "__main__":
    Study.main(run, __file__)
