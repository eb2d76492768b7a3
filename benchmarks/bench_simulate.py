"""Speed against error of vehdyn's linear simulation and frequency response.

Run: ``python benchmarks/bench_simulate.py``. Prints, from one run on this machine:

1. a 4-state, 2-input linear system (two coupled mass-spring-dampers) simulated over 10 s at
   1 kHz (10,001 samples) from an initial state with constant inputs, by ``vehdyn.simulate``
   (method ``"exact"``), ``control.forced_response``, ``scipy.signal.lsim`` and
   ``scipy.integrate.solve_ivp`` (RK45, rtol 1e-10): best-of-N time, ratio to vehdyn, and the max
   error against x(t) = e^(At) x0 + A^-1 (e^(At) - I) B u evaluated sample by sample with
   ``scipy.linalg.expm`` (independent of every method timed);
2. the frequency response at 1,000 frequencies by ``LinearModel.frequency_response`` and
   ``control.frequency_response``: time, ratio and max relative difference;
3. the time to import vehdyn (in a fresh interpreter).
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import os
import platform
import subprocess
import sys
import time

import numpy as np



def system():
    import vehdyn

    M = np.diag([2.0, 1.0])
    K = np.array([[3000.0, -1000.0], [-1000.0, 1000.0]])
    C = np.array([[6.0, -2.0], [-2.0, 2.0]])
    return vehdyn.LinearModel.from_second_order(M, C, K, np.eye(2), dof=["body_displacement", "wheel_displacement"],
                                                inputs=["body_force", "wheel_force"])


def main():
    import control as ct
    from scipy import signal
    from scipy.integrate import solve_ivp
    from scipy.linalg import expm

    import vehdyn

    model = system()
    t = np.linspace(0.0, 10.0, 10001)
    x0 = np.array([0.01, -0.02, 0.0, 0.1])
    u_const = np.array([5.0, -3.0])
    U = np.repeat(u_const[:, None], t.size, axis=1)

    # independent reference: expm per sample
    A, B = model.A, model.B
    forced = np.linalg.solve(A, B @ u_const)
    ref = np.stack([expm(A * tk) @ (x0 + forced) - forced for tk in t], axis=1)

    sys_ct = model.to_control()
    sys_sp = model.to_scipy()

    runs = {}
    runs["vehdyn simulate(exact)"] = best_time(lambda: vehdyn.simulate(model, t, inputs=U, x0=x0, method="exact").states)
    runs["control.forced_response"] = best_time(lambda: ct.forced_response(sys_ct, t, U, X0=x0, return_x=True).states,
                                                repeats=3)
    runs["scipy.signal.lsim"] = best_time(lambda: signal.lsim(sys_sp, U.T, t, X0=x0)[2].T, repeats=3)
    runs["solve_ivp RK45 (rtol 1e-10)"] = best_time(
        lambda: solve_ivp(lambda tt, x: A @ x + B @ u_const, (0, 10), x0, t_eval=t, rtol=1e-10, atol=1e-13).y,
        repeats=1)

    base = runs["vehdyn simulate(exact)"][0]
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"numpy {np.__version__}, control {ct.__version__}")
    print("\n1. 4-state linear system, 10 s at 1 kHz (10,001 samples), error against expm(A t) per sample")
    print(f"{'method':<30} {'time [ms]':>10} {'ratio':>9} {'max error':>11}")
    for name, (secs, states) in runs.items():
        err = np.max(np.abs(np.asarray(states) - ref))
        print(f"{name:<30} {secs * 1e3:10.3f} {secs / base:8.1f}x {err:11.2e}")

    omega = np.logspace(-1, 3, 1000)
    t_ours, fr = best_time(lambda: model.frequency_response(omega))
    t_ct, fr_ct = best_time(lambda: ct.frequency_response(sys_ct, omega), repeats=5)
    H_ct = fr_ct.magnitude * np.exp(1j * fr_ct.phase)
    rel = np.max(np.abs(fr.response - H_ct) / np.maximum(np.abs(H_ct), 1e-300))
    print("\n2. frequency response, 4 states x 2 inputs x 4 outputs, 1,000 frequencies")
    print(f"{'method':<30} {'time [ms]':>10} {'ratio':>9} {'max rel. diff':>14}")
    print(f"{'vehdyn frequency_response':<30} {t_ours * 1e3:10.3f} {1.0:8.1f}x {'':>14}")
    print(f"{'control.frequency_response':<30} {t_ct * 1e3:10.3f} {t_ct / t_ours:8.1f}x {rel:14.2e}")

    code = "import time; t=time.perf_counter(); import vehdyn; print(time.perf_counter()-t)"
    imports = [float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout)
               for _ in range(3)]
    print(f"\n3. import vehdyn: {min(imports) * 1e3:.0f} ms (best of 3 fresh interpreters)")


if __name__ == "__main__":
    main()
