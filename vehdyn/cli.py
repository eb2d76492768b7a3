"""The ``vehdyn`` command.

``vehdyn report [--out DIR] [--quick] [--only NAME ...]``
    Run every study in ``studies/`` and write ``DIR/index.html`` with its figures and tables.
``vehdyn study NAME [--out DIR] [--quick]``
    Run one study.
``vehdyn tire FILE.tir [--out DIR]``
    Print a tire file's version and key values and write its standard figures.
``vehdyn vehicles``
    List the shipped vehicles with their key numbers.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

__all__ = ["main"]


def _progress(i: int, n: int, name: str, width: int = 24) -> str:
    done = int(width * i / n) if n else width
    return f"\r[{'#' * done}{'.' * (width - done)}] {i}/{n} {name:<40.40}"


def _quick(args) -> bool:
    from .report import _quick_from_env

    return bool(args.quick) or _quick_from_env()


def cmd_report(args) -> int:
    from .report import discover_studies, run_study, write_report

    paths = discover_studies(args.studies)
    if args.only:
        wanted = set(args.only)
        unknown = wanted - {p.stem for p in paths}
        if unknown:
            print(f"vehdyn report: no study named {sorted(unknown)}; studies are {[p.stem for p in paths]}",
                  file=sys.stderr)
            return 2
        paths = [p for p in paths if p.stem in wanted]
    if not paths:
        print("vehdyn report: no studies found", file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    quick = _quick(args)
    outcomes = []
    start = time.perf_counter()
    for i, path in enumerate(paths):
        sys.stderr.write(_progress(i, len(paths), path.stem))
        sys.stderr.flush()
        outcomes.append(run_study(path, out, quick=quick))
    sys.stderr.write(_progress(len(paths), len(paths), "done") + "\n")
    index = write_report(outcomes, out, quick=quick)
    failed = [o for o in outcomes if o.error]
    print(f"\nvehdyn report: {len(outcomes)} studies in {time.perf_counter() - start:.1f} s -> {index}")
    for o in outcomes:
        print(f"  {'FAILED' if o.error else 'ok    '} {o.name:<34} {o.seconds:6.1f} s")
    for o in failed:
        print(f"\n--- {o.name} failed:\n{o.error}", file=sys.stderr)
    return 1 if failed else 0


def cmd_study(args) -> int:
    from .report import discover_studies, run_study, write_report

    paths = {p.stem: p for p in discover_studies(args.studies)}
    if args.name not in paths:
        print(f"vehdyn study: no study named {args.name!r}; studies are {sorted(paths)}", file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    outcome = run_study(paths[args.name], out, quick=_quick(args))
    index = write_report([outcome], out, quick=_quick(args))
    if outcome.error:
        print(outcome.error, file=sys.stderr)
        return 1
    print(f"vehdyn study {args.name}: {outcome.seconds:.1f} s -> {index}")
    return 0


def cmd_tire(args) -> int:
    from .errors import VehdynError, VehdynWarning

    try:
        from .tire import load_tire
        from .tire.plots import plot_tire_characteristics, describe_tire
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
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for name, fig in plot_tire_characteristics(tire).items():
        path = out / f"{name}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        print(f"wrote {path}")
    return 0


def cmd_vehicles(args) -> int:
    from .params import load_vehicle, shipped_vehicles

    print(f"{'name':<10} {'mass [kg]':>10} {'L [m]':>7} {'a [m]':>7} {'b [m]':>7} {'Izz [kg m2]':>12} "
          f"{'Cf [kN/rad]':>12} {'Cr [kN/rad]':>12}  description")
    for name in shipped_vehicles():
        v = load_vehicle(name)
        print(f"{name:<10} {v.mass.mass:10.1f} {v.wheelbase:7.3f} {v.geometry.a:7.3f} {v.geometry.b:7.3f} "
              f"{v.mass.yaw_inertia:12.1f} {v.tires.front_cornering_stiffness / 1e3:12.2f} "
              f"{v.tires.rear_cornering_stiffness / 1e3:12.2f}  {v.description}")
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
    p.add_argument("--only", nargs="+", metavar="NAME", help="run only these studies")
    p.add_argument("--studies", default=None, help=argparse.SUPPRESS)
    p.set_defaults(func=cmd_report)
    p = sub.add_parser("study", help="run one study")
    p.add_argument("name", help="study name (file stem in studies/)")
    p.add_argument("--out", default="report", help="output folder (default: ./report)")
    p.add_argument("--quick", action="store_true", help="small grids")
    p.add_argument("--studies", default=None, help=argparse.SUPPRESS)
    p.set_defaults(func=cmd_study)
    p = sub.add_parser("tire", help="describe a .tir file and plot its characteristics")
    p.add_argument("file", help="path of a .tir file")
    p.add_argument("--out", default="tire_plots", help="output folder (default: ./tire_plots)")
    p.set_defaults(func=cmd_tire)
    p = sub.add_parser("vehicles", help="list the shipped vehicles")
    p.set_defaults(func=cmd_vehicles)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 0
    return int(args.func(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
