"""The ``vehdyn`` command.

``vehdyn report [--out DIR] [--quick | --full] [--only NAME ...]``
    Run every study in ``studies/`` and write ``DIR/index.html`` with its figures and tables. The
    new report replaces ``DIR`` as a whole once every study has finished
    (:func:`vehdyn.report.build_report`); until then ``DIR`` keeps the previous report.
``vehdyn study NAME [--out DIR] [--quick]``
    Run one study into a report of its own (the same way).
``vehdyn tire FILE.tir [--out DIR]``
    Print a tire file's version and key values and write its standard figures.
``vehdyn tire --soil NAME [--out DIR]``
    Print a soil's parameters and a rigid wheel's sinkage and drawbar pull against slip on it (a
    shipped soil name or ``soils.toml:NAME``) and write the curves' figure.
``vehdyn vehicles``
    List the shipped vehicles with their key numbers.
``vehdyn compile [MODEL ...]``
    Build the compiled code of the shipped models (all, or those named: :func:`shipped_runs`) into
    numba's cache ahead of time, with a progress bar (:func:`warm_up`), so that the first
    ``simulate`` of each runs compiled.
``vehdyn scene FILE.toml [--verify [--no-escalate]]``
    Plan a scene (the fidelity ladder), run the chosen model and print the headline numbers. With
    ``--verify`` the reference rung runs too; a rung beyond the tolerance is reported (a warning on
    stderr, the verdict in the headline) and the scene rerun on the next rung up that meets it,
    unless ``--no-escalate``.
``vehdyn sweep FILE.toml [OPTIONS]``
    Sweep a scene's parameters (:func:`vehdyn.sweep.run`) with a progress bar; print a summary of the
    metrics and write the table chunk by chunk. Options: ``[--grid NAME=START:STOP:COUNT ...]
    [--samples N --vary NAME=LAW:ARGS ...] [--metric NAME ...] [--out results.parquet [--resume]]
    [--processes | --scheduler ADDRESS] [--method METHOD] [--rtol RTOL]`` (``--method``/``--rtol``:
    the solver of every variant instead of the rung's own).

Exit status: 0 on success; 1 if a study failed (its traceback is in the report and on stderr); 2 for
a usage error - an unknown study, a missing or unreadable input file, an output folder that is a
file or cannot be created - reported as one line ``vehdyn COMMAND: what is wrong`` without a
traceback; 130 if interrupted (Ctrl-C): the report folder then holds the previous complete report
(or the new one, had it finished), never a mix.
Every file is written atomically (a temporary file moved over the destination when complete).
"""

from __future__ import annotations

import argparse
import sys
import time

__all__ = ["main", "shipped_runs"]


class _UsageError(Exception):
    """A user error the command reports as one line, with exit status 2."""


def _os_reason(exc: OSError) -> str:
    """``"Permission denied (/some/path)"`` from an OSError."""
    reason = exc.strerror or str(exc)
    return f"{reason} ({exc.filename})" if exc.filename else reason


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _progress(i: int, n: int, name: str, width: int = 24) -> str:
    done = int(width * i / n) if n else width
    return f"\r[{'#' * done}{'.' * (width - done)}] {i}/{n} {name:<40.40}"


def _quick(args) -> bool:
    from vehdyn.report import quick_from_env

    return bool(args.quick) or quick_from_env()


def _default_jobs() -> int:
    import os

    return max(1, min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1))


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"jobs must be a whole number >= 1, got {text!r}")
    return value


def cmd_report(args) -> int:
    from vehdyn.report import build_report, discover_studies

    paths = discover_studies(args.studies)
    if args.only:
        wanted = set(args.only)
        unknown = wanted - {p.stem for p in paths}
        if unknown:
            raise _UsageError(f"no study named {sorted(unknown)}; studies are {[p.stem for p in paths]}")
        paths = [p for p in paths if p.stem in wanted]
    if not paths:
        raise _UsageError(f"no studies found{f' in {args.studies}' if args.studies else ''}")
    quick = _quick(args)
    if getattr(args, "full", False):
        import os

        os.environ["VEHDYN_FULL"] = "1"  # read by each Study (report.Study.full)
    start = time.perf_counter()

    def progress(i, n, name):
        args.progress_line_open = True
        sys.stderr.write(_progress(i, n, name))
        sys.stderr.flush()

    from vehdyn.simulation.compiled import numba_available

    index, outcomes = build_report(paths, args.out, quick=quick, progress=progress, jobs=args.jobs,
                                   prebuild=warm_up if numba_available() else None)
    sys.stderr.write(_progress(len(paths), len(paths), "done") + "\n")
    failed = [o for o in outcomes if o.error]
    print(f"\nvehdyn report: {len(outcomes)} studies in {time.perf_counter() - start:.1f} s -> {index}")
    for o in outcomes:
        print(f"  {'FAILED' if o.error else 'ok    '} {o.name:<34} {o.seconds:6.1f} s")
    for o in failed:
        print(f"\n--- {o.name} failed:\n{o.error}", file=sys.stderr)
    return 1 if failed else 0


def cmd_study(args) -> int:
    from vehdyn.report import build_report, discover_studies

    paths = {p.stem: p for p in discover_studies(args.studies)}
    if args.name not in paths:
        raise _UsageError(f"no study named {args.name!r}; studies are {sorted(paths)}")
    index, (outcome,) = build_report([paths[args.name]], args.out, quick=_quick(args))
    if outcome.error:
        print(outcome.error, file=sys.stderr)
        return 1
    print(f"vehdyn study {args.name}: {outcome.seconds:.1f} s -> {index}")
    return 0


def cmd_tire_soil(args) -> int:
    """``vehdyn tire --soil NAME``: a soil's parameters and curves (vehdyn.tire.terramechanics)."""
    from vehdyn.tire.terramechanics import load_soil
    from vehdyn.tire.terramechanics.curves import describe_soil, plot_soil_curves, soil_curves

    from vehdyn.report import make_folder

    soil = load_soil(args.soil)
    out = make_folder(args.out)  # a bad --out is said before anything is printed
    print(describe_soil(soil))
    import matplotlib

    matplotlib.use("Agg")
    from vehdyn.plotting import save_figure

    print(f"wrote {save_figure(plot_soil_curves({soil.name: soil_curves(soil)}), out / f'soil_{soil.name}.png')}")
    return 0


def cmd_tire(args) -> int:
    from vehdyn.errors import VehdynError, VehdynWarning

    if args.soil is not None:
        if args.file is not None:
            raise _UsageError("give a .tir file or --soil NAME, not both")
        return cmd_tire_soil(args)
    if args.file is None:
        raise _UsageError("give a .tir file or --soil NAME")

    try:
        from vehdyn.tire import load_tire
        from vehdyn.tire.plots import plot_tire_characteristics, describe_tire
    except ImportError as exc:  # pragma: no cover - until the tire layer is complete
        print(f"vehdyn tire: the tire layer is not available in this version ({exc})", file=sys.stderr)
        return 2
    import warnings

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", VehdynWarning)
            tire = load_tire(args.file)
    except (VehdynError, OSError) as exc:  # unreadable file, malformed line, non-finite coefficient, ...
        print(f"vehdyn tire: {exc}", file=sys.stderr)
        return 2
    for warning in caught:  # e.g. missing sections: said, and the tire is still described
        print(f"vehdyn tire: warning: {warning.message}", file=sys.stderr)
    print(describe_tire(tire))
    from vehdyn.report import make_folder

    out = make_folder(args.out)
    import matplotlib

    matplotlib.use("Agg")
    from vehdyn.plotting import save_figure

    for name, fig in plot_tire_characteristics(tire).items():
        path = save_figure(fig, out / f"{name}.png")
        print(f"wrote {path}")
    return 0


def cmd_tire_fit(args) -> int:
    # Bad data or a bad start file raise a VehdynError: main() reports it as one line, exit status 2.
    import warnings
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    from vehdyn.errors import VehdynWarning
    from vehdyn.plotting import save_figure
    from vehdyn.tire import fit_magic_formula, read_tire_data

    data = read_tire_data(args.data, convention=args.convention, units=dict(_unit_option(u) for u in args.unit or ()))
    with warnings.catch_warnings():  # the fit's warnings are also its messages, printed with the table
        warnings.simplefilter("ignore", VehdynWarning)
        fit = fit_magic_formula(data, version=args.version, start=args.start,
                                cross_validation=not args.no_cross_validation)
    print(fit)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    print(f"wrote {fit.to_tir(out)}")
    for stage, fig in fit.plot().items():
        print(f"wrote {save_figure(fig, out.with_name(f'{out.stem}_{stage}.png'))}")
    return 0


def _unit_option(text):
    """``--unit alpha=deg`` -> ("alpha", "deg")."""
    from vehdyn.errors import ParameterError

    name, sep, unit = text.partition("=")
    if not sep or not name.strip() or not unit.strip():
        raise ParameterError(f"--unit takes COLUMN=UNIT (e.g. alpha=deg), got {text!r}", key="unit", value=text)
    return name.strip(), unit.strip()


def cmd_vehicles(args) -> int:
    from vehdyn.params import load_vehicle, shipped_vehicles

    print(f"{'name':<10} {'mass [kg]':>10} {'L [m]':>7} {'a [m]':>7} {'b [m]':>7} {'Izz [kg m2]':>12} "
          f"{'Cf [kN/rad]':>12} {'Cr [kN/rad]':>12}  description")
    for name in shipped_vehicles():
        v = load_vehicle(name)
        print(f"{name:<10} {v.mass.mass:10.1f} {v.wheelbase:7.3f} {v.geometry.a:7.3f} {v.geometry.b:7.3f} "
              f"{v.mass.yaw_inertia:12.1f} {v.tires.front_cornering_stiffness / 1e3:12.2f} "
              f"{v.tires.rear_cornering_stiffness / 1e3:12.2f}  {v.description}")
    return 0


def _sine_steer():
    from vehdyn.procedures import sine_steer

    return sine_steer(0.035, 0.5)  # 2 deg road-wheel amplitude, 0.5 Hz


def _sedan_single_track(**options):
    import numpy as np

    from vehdyn.handling import SingleTrack
    from vehdyn.params import load_vehicle

    model = SingleTrack(load_vehicle("sedan"), **options)
    return model, np.linspace(0.0, 5.0, 501), {"front_steer_angle": _sine_steer()}, model.straight_running(20.0)


def _linear_single_track():
    import numpy as np

    from vehdyn.handling import SingleTrack
    from vehdyn.params import load_vehicle
    from vehdyn.tire import LinearTire

    car = load_vehicle("sedan")
    model = SingleTrack(car, LinearTire(cornering_stiffness=car.tires.front_cornering_stiffness / 2, nominal_load=3000.0),
                        LinearTire(cornering_stiffness=car.tires.rear_cornering_stiffness / 2))
    return model, np.linspace(0.0, 5.0, 501), {"front_steer_angle": _sine_steer()}, model.straight_running(20.0)


def _full_vehicle():
    import numpy as np

    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.params import load_vehicle

    model = FullVehicle(load_vehicle("sedan"))
    x0, u0 = model.trim(20.0)
    inputs = dict(zip(model.input_names, u0))
    inputs["front_steer_angle"] = _sine_steer()
    return model, np.linspace(0.0, 5.0, 501), inputs, x0


def _loop(controller, speed, duration, steer=True, wheel_spin=False):
    import numpy as np

    from vehdyn.handling import SingleTrack
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.params import load_vehicle

    car = load_vehicle("sedan")
    plant = SingleTrack(car, wheel_spin=wheel_spin)
    model = controller(car).close(plant) if controller.__name__ == "driver" else ClosedLoop(plant, controller(car))
    x0 = model.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    return model, np.linspace(0.0, duration, int(round(duration * 100)) + 1), (
        {"front_steer_angle": _sine_steer()} if steer else None), x0


def _abs_loop():
    from vehdyn.chassis import ABS

    return _loop(ABS, 25.0, 2.0, steer=False, wheel_spin=True)


def _esc_loop():
    from vehdyn.chassis import ESC

    return _loop(ESC, 20.0, 5.0)


def _driver_loop():
    import numpy as np

    from vehdyn.driver import PreviewDriver

    path_x = np.linspace(-10.0, 300.0, 120)

    def driver(car):
        return PreviewDriver(path_x, 2.0 * np.sin(path_x / 25.0), wheelbase=car.geometry.wheelbase, target_speed=18.0,
                             mass=car.mass.mass)

    return _loop(driver, 18.0, 5.0, steer=False)


def _lift_off():
    import numpy as np

    from vehdyn.params import load_vehicle
    from vehdyn.ride import FullCar, LiftOff

    model = LiftOff(FullCar(load_vehicle("sedan")))
    t = np.linspace(0.0, 1.0, 201)
    w = 2 * np.pi * 1.5
    inputs = {}
    for corner, phase in zip(("front_left", "front_right", "rear_left", "rear_right"), (0.0, 0.5, 1.0, 1.5)):
        inputs[f"road_displacement_{corner}"] = 0.03 * np.sin(w * t + phase)  # lifts the wheels off
        inputs[f"road_velocity_{corner}"] = 0.03 * w * np.cos(w * t + phase)
    return model, t, inputs, None


_RUNS = {"single_track": _sedan_single_track, "single_track_linear": _linear_single_track,
         "single_track_wheel_spin": lambda: _sedan_single_track(wheel_spin=True), "full_vehicle": _full_vehicle,
         "abs": _abs_loop, "esc": _esc_loop, "driver": _driver_loop, "lift_off": _lift_off}


def shipped_runs(names=None) -> dict:
    """One representative ``simulate`` call of each shipped model with a compiled form (the sedan's).

    Parameters
    ----------
    names : list of str, optional
        The models (default: all): ``single_track`` (Magic Formula tires), ``single_track_linear``,
        ``single_track_wheel_spin``, ``full_vehicle``, ``abs`` / ``esc`` (a single track with the
        controller in the loop), ``driver`` (a preview driver closing the loop), ``lift_off`` (the
        full car's wheels leaving the road).

    Returns
    -------
    dict
        Per name a function returning ``(model, time [s], inputs, x0)`` for :func:`vehdyn.simulate`.

    Raises
    ------
    ParameterError
        For an unknown name.
    """
    from vehdyn.errors import ParameterError

    names = list(_RUNS) if not names else list(names)
    for name in names:
        if name not in _RUNS:
            raise ParameterError(f"unknown model {name!r}: one of {', '.join(_RUNS)}", key="models", value=name)
    return {name: _RUNS[name] for name in names}


def warm_up(models=None, progress=None) -> dict:
    """Build the compiled code of shipped models into numba's on-disk cache ahead of time.

    Each model's representative run (:func:`shipped_runs`) is simulated with
    ``backend="compiled"``: its rhs, outputs and integrator loop are compiled in this process (or
    loaded, when already cached) and recorded as built, so that a later ``simulate`` of the model
    on ``backend="auto"``, in any process, runs compiled from its first call.

    Parameters
    ----------
    models : list of str, optional
        The models (default: all; names as in :func:`shipped_runs`).
    progress : callable or bool, optional
        Called as ``progress(i, n, name)`` before each model and once with ``i == n`` at the end;
        True: a progress bar on stderr.

    Returns
    -------
    dict
        Per model the time it took [s] (a cold compile, or a cache load).
    """
    from vehdyn.simulation import simulate

    runs = shipped_runs(models)
    if progress is True:
        def progress(i, n, name):
            sys.stderr.write(_progress(i, n, name) + ("\n" if i == n else ""))
    elif not progress:
        progress = None
    seconds = {}
    for i, (name, make) in enumerate(runs.items()):
        if progress is not None:
            progress(i, len(runs), name)
        start = time.perf_counter()
        model, t, inputs, x0 = make()
        simulate(model, t, inputs, x0=x0, backend="compiled")
        seconds[name] = time.perf_counter() - start
    if progress is not None:
        progress(len(runs), len(runs), "done")
    return seconds


def cmd_compile(args) -> int:
    from vehdyn.simulation.compiled import numba_available

    if not numba_available():
        raise _UsageError("numba is not installed (pip install vehdyn[fast]): nothing to compile")
    shipped_runs(args.models)  # an unknown name: one line before any work

    def progress(i, n, name):
        args.progress_line_open = i < n
        sys.stderr.write(_progress(i, n, name) + ("\n" if i == n else ""))

    seconds = warm_up(args.models, progress=progress)
    for name, value in seconds.items():
        print(f"{name:<26} {value:7.1f} s")
    print(f"{'total':<26} {sum(seconds.values()):7.1f} s")
    return 0


def cmd_scene(args) -> int:
    import warnings

    from vehdyn.errors import VehdynWarning
    from vehdyn.scene import Scene, run

    if args.no_escalate and not args.verify:
        raise _UsageError("--no-escalate goes with --verify (a miss is found by verifying)")
    # A bad scene file or field raises a VehdynError: main() reports it as one line, exit status 2.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VehdynWarning)
        outcome = run(Scene.from_toml(args.file), verify=args.verify, escalate=False if args.no_escalate else None)
    print(outcome.plan)
    print()
    print(outcome.headline())
    for warning in caught:  # a verified miss (and the escalation): said on stderr, one line each
        print(f"vehdyn scene: warning: {_one_line(warning.message)}", file=sys.stderr)
    return 0


def cmd_sweep(args) -> int:
    from vehdyn.errors import ParameterError
    from vehdyn.scene import Scene
    from vehdyn.sweep import run
    from vehdyn.sweep.api import distribution_from_text, grid_from_text

    # bad specs, names or values raise ParameterError: main() reports it as one line, exit status 2
    grid = dict(grid_from_text(g) for g in args.grid or ())
    samples = dict(distribution_from_text(v) for v in args.vary or ())
    if bool(samples) != (args.samples is not None):
        raise ParameterError("--samples N and --vary NAME=LAW:ARGS go together", key="samples", value=args.samples)
    executor = args.scheduler or ("processes" if args.processes else None)
    solver = {k: v for k, v in (("method", args.method), ("rtol", args.rtol)) if v is not None} or None
    table = run(Scene.from_toml(args.file), grid=grid or None, samples=samples or None, n=args.samples,
                sampling=args.sampling, metrics=args.metric, executor=executor, out=args.out, resume=args.resume,
                seed=args.seed, progress=True, solver=solver)
    failed = int(table["error"].notna().sum())
    metrics = [c for c in table.columns if c not in grid and c not in samples and c != "error"]
    print(f"vehdyn sweep: {len(table)} variants, {failed} failed" + (f" -> {args.out}" if args.out else ""))
    if metrics:
        print(table[metrics].describe().T.to_string())
    if failed:
        print(f"first failure (variant {table.index[table['error'].notna()][0]}): "
              f"{table['error'].dropna().iloc[0]}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vehdyn",
        description="vehdyn: vehicle dynamics in Python - tires, handling and ride.",
        epilog="Set VEHDYN_QUICK=1 for small grids (as CI does).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    p = sub.add_parser("report", help="run every study and write an HTML report")
    p.add_argument("--out", default="report", help="output folder (default: ./report)")
    p.add_argument("--quick", action="store_true", help="small grids (fast; as in CI)")
    p.add_argument("--full", action="store_true",
                   help="also the heavy series (complete FMVSS 126 series on the full vehicle, ...; or VEHDYN_FULL=1)")
    p.add_argument("--only", nargs="+", metavar="NAME", help="run only these studies")
    p.add_argument("--jobs", type=_positive_int, default=_default_jobs(), metavar="N",
                   help="studies run at the same time in N processes (default: the cores, at most 4)")
    p.add_argument("--studies", default=None, help=argparse.SUPPRESS)
    p.set_defaults(func=cmd_report)
    p = sub.add_parser("study", help="run one study")
    p.add_argument("name", help="study name (file stem in studies/)")
    p.add_argument("--out", default="report", help="output folder (default: ./report)")
    p.add_argument("--quick", action="store_true", help="small grids")
    p.add_argument("--studies", default=None, help=argparse.SUPPRESS)
    p.set_defaults(func=cmd_study)
    p = sub.add_parser("tire", help="describe a .tir file (or a soil) and plot its characteristics")
    p.add_argument("file", nargs="?", help="path of a .tir file")
    p.add_argument("--soil", metavar="NAME", help="a soil (shipped name or soils.toml:NAME): its terramechanics curves")
    p.add_argument("--out", default="tire_plots", help="output folder (default: ./tire_plots)")
    p.set_defaults(func=cmd_tire)
    p = sub.add_parser("tire-fit", help="fit a Magic Formula to measured tire data; write a .tir and figures")
    p.add_argument("data", help="CSV or test-consortium run file (see vehdyn.tire.read_tire_data)")
    p.add_argument("--out", default="fitted.tir", help="output .tir file (default: ./fitted.tir); figures beside it")
    p.add_argument("--start", default=None, help="start from this .tir file (default: from the data)")
    p.add_argument("--version", default="6.1", choices=("5.2", "6.1", "6.2"), help="Magic Formula version")
    p.add_argument("--convention", default="ISO-W", choices=("ISO-W", "SAE"), help="axes of a CSV file")
    p.add_argument("--unit", action="append", metavar="COLUMN=UNIT",
                   help="unit of a CSV column without one in its header (e.g. alpha=deg, kappa=%%, fz=kN); repeat")
    p.add_argument("--no-cross-validation", action="store_true",
                   help="skip leaving each measured condition out in turn (about halves the time)")
    p.set_defaults(func=cmd_tire_fit)
    p = sub.add_parser("vehicles", help="list the shipped vehicles")
    p.set_defaults(func=cmd_vehicles)
    p = sub.add_parser("compile", help="build the compiled code of the shipped models ahead of time")
    p.add_argument("models", nargs="*", metavar="MODEL", help=f"default: all ({', '.join(_RUNS)})")
    p.set_defaults(func=cmd_compile)
    p = sub.add_parser("scene", help="plan a scene (.toml), run the chosen model, print the headline numbers")
    p.add_argument("file", help="path of a scene .toml file")
    p.add_argument("--verify", action="store_true", help="also run the reference rung and measure the error; "
                   "beyond the tolerance, rerun on the next rung up that meets it (and say so)")
    p.add_argument("--no-escalate", action="store_true", help="with --verify: report a miss, do not rerun")
    p.set_defaults(func=cmd_scene)
    p = sub.add_parser("sweep", help="sweep a scene's parameters (grid, Monte Carlo) and summarize the metrics")
    p.add_argument("file", help="path of a scene .toml file")
    p.add_argument("--grid", action="append", metavar="NAME=START:STOP:COUNT", help="full-factorial values "
                   "(or NAME=V1,V2,...); repeatable")
    p.add_argument("--samples", type=int, metavar="N", help="number of Monte Carlo draws of the --vary laws")
    p.add_argument("--vary", action="append", metavar="NAME=LAW:ARGS", help="a scipy.stats law, e.g. "
                   "vehicle.mass.mass=norm:1500:50; repeatable")
    p.add_argument("--sampling", default="lhs", choices=("lhs", "sobol", "random"), help="default: lhs")
    p.add_argument("--metric", action="append", metavar="NAME", help="metric name (default: peak of each output)")
    p.add_argument("--out", default=None, help="Parquet folder written chunk by chunk")
    p.add_argument("--resume", action="store_true", help="run only the variants not yet in --out")
    p.add_argument("--seed", type=int, default=0, help="seed of the draws (default 0)")
    p.add_argument("--processes", action="store_true", help="a process pool on every core")
    p.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786)")
    p.add_argument("--method", default=None, help="solver of every variant (e.g. BDF; default: the rung's own)")
    p.add_argument("--rtol", type=float, default=None, help="its relative tolerance (atol = rtol / 100)")
    p.set_defaults(func=cmd_sweep)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the ``vehdyn`` command (module docstring) and return its exit status.

    Errors the library reports (:class:`~vehdyn.errors.ParameterError`,
    :class:`~vehdyn.errors.VehdynError`, an ``OSError``) and usage errors are printed as one line
    ``vehdyn COMMAND: what is wrong`` on stderr, without a traceback (a ``ParameterError`` about
    ``out_dir`` names the option ``--out``).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``vehdyn`` (default: ``sys.argv[1:]``, as :mod:`argparse` reads it).

    Returns
    -------
    int
        The exit status: 0 on success (also for no command: the help is printed), the command's
        own status (1 if a study failed), 2 for a usage or input error, 130 if interrupted
        (Ctrl-C). An argument :mod:`argparse` rejects exits with status 2 (``SystemExit``), as
        ``--help`` exits with 0.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 0
    from vehdyn.errors import ParameterError, VehdynError

    def fail(message: str, status: int = 2) -> int:
        if getattr(args, "progress_line_open", False):
            sys.stderr.write("\n")
        print(f"vehdyn {args.command}: {_one_line(message)}", file=sys.stderr)
        return status

    try:
        return int(args.func(args) or 0)
    except _UsageError as exc:
        return fail(str(exc))
    except ParameterError as exc:
        if exc.key == "out_dir":  # the library names its parameter; the user typed --out
            return fail(str(exc).replace("out_dir", "--out", 1))
        return fail(str(exc))
    except VehdynError as exc:
        return fail(str(exc))
    except OSError as exc:
        return fail(_os_reason(exc))
    except KeyboardInterrupt:
        return fail("interrupted" + ("; the report folder holds the previous complete report (or, if the "
                                     "run had finished, the new one), never a mix"
                                     if args.command in ("report", "study") else ""), 130)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
