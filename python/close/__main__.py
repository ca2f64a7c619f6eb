"""``python -m close analyze|eval|plan``: the ``close`` command line's commands, with its
flags and its output (the same JSON objects, the same table and plan text), from Python.

    python -m close analyze sample.json --json [--disks] [--start K] [--end K] [--method paper]
    python -m close eval tests/fixtures/physics [--json] [--builtin] [--method paper]
    python -m close plan sample.json --goal 0.5,3.6[;1.2,4.0] [--json]

Errors end with ``error: …`` on stderr and exit status 1 (2 for a command line that does
not fit), as the CLI's do. The server's input limits hold, as everywhere in ``close``.
"""

import argparse
import json
import sys
from typing import Any, List, Optional

from . import _close, analyze, load, plan
from ._close import CloseError
from ._progress import bar


class _Usage(Exception):
    """A command line that does not fit (exit status 2)."""


def _emit(text: str) -> None:
    try:
        print(text, flush=True)
    except BrokenPipeError:  # `python -m close … | head`
        pass


def _compact(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False, separators=(",", ":"))


def _analyze(args: argparse.Namespace) -> None:
    if args.video is not None:
        raise _Usage("--video (one fold of a VR-Folding video) is the close command's; in Python use close.vrfolding.open(STORE)")
    sample = load(*args.files)
    analysis = analyze(sample, method=args.method, start=args.start, end=args.end)
    out = analysis.to_dict()
    if args.disks:
        out["disk_start"] = analysis.disk(0).tolist()
        out["disk_end"] = analysis.disk(-1).tolist()
    _emit(_compact(out))


def _eval(args: argparse.Namespace) -> None:
    units = _close._eval_units(args.paths) if args.paths else 0
    builtin = _close._builtin() if args.builtin else []
    if units + len(builtin) == 0:
        raise _Usage("no Sample JSON file or VR-Folding video found")
    # A bar on a terminal, as the CLI draws one.
    callback, close_bar = bar(sys.stderr.isatty(), units + len(builtin), "close eval")
    offset = [0]

    def report(done: int, total: int) -> None:
        if callback is not None:
            callback(offset[0] + done, units + len(builtin))

    try:
        rows: List[str] = _close._eval_rows(args.paths, None, method=args.method, progress=report) if units else []
        offset[0] = units
        rows += _close._eval_sample_rows(builtin, method=args.method, progress=report) if builtin else []
    finally:
        close_bar()
    if args.json:
        _emit(json.dumps(_close._eval_report(rows), ensure_ascii=False, indent=2))
        return
    _emit(_close._eval_table(rows).rstrip())
    for row in map(json.loads, rows):
        if row.get("error"):
            print(f"error: {row['name']}: {row['error']}", file=sys.stderr)


def _plan(args: argparse.Namespace) -> None:
    # As the CLI reads it: folds "f1,f2" separated by ";" (none: the flat cloth).
    goal = []
    for k, fold in enumerate(f for f in args.goal.split(";") if f.strip()):
        try:
            angles = [float(a) for a in fold.split(",")]
        except ValueError as e:
            raise _Usage(f"--goal, fold {k + 1}: {fold!r}: {e}") from None
        if len(angles) != 2:
            raise _Usage(f'--goal, fold {k + 1}: "{fold}" is not two angles f1,f2')
        goal.append((angles[0], angles[1]))
    sample = load(*args.files)
    if args.json:
        _emit(_compact(plan(sample, goal)))
    else:
        _emit(_close._plan_text(sample, goal))


def parser() -> argparse.ArgumentParser:
    top = argparse.ArgumentParser(prog="python -m close", description=__doc__.splitlines()[0])
    commands = top.add_subparsers(dest="command", required=True)
    methods = ["cut", "paper"]

    a = commands.add_parser("analyze", help="analyse a sample (Sample JSON, text/CSV per frame, OBJ/PLY, .mat, .npy/.npz)")
    a.add_argument("files", nargs="+")
    a.add_argument("--video", help="(the close command's: one video of a VR-Folding store)")
    a.add_argument("--fold", type=int, choices=[1, 2], default=1)
    a.add_argument("--start", type=int, help="first frame (default: the first)")
    a.add_argument("--end", type=int, help="last frame (default: the last)")
    a.add_argument("--json", action="store_true", help="print JSON (the only output form)")
    a.add_argument("--disks", action="store_true", help="add the start and end dGLI disks as condensed pair vectors")
    a.add_argument("--method", choices=methods, default="cut", help="how fold points are chosen")
    a.set_defaults(run=_analyze)

    e = commands.add_parser("eval", help="evaluate every sample under files or folders, and VR-Folding stores")
    e.add_argument("paths", nargs="*")
    e.add_argument("--builtin", action="store_true", help="evaluate the built-in dataset (with any given paths)")
    e.add_argument("--json", action="store_true", help="print the full report as JSON instead of a table")
    e.add_argument("--method", choices=methods, default="cut", help="how fold points are chosen")
    e.set_defaults(run=_eval)

    p = commands.add_parser("plan", help="plan how to reach a goal fold from a sample's end state")
    p.add_argument("files", nargs="+")
    p.add_argument("--goal", required=True, help="the goal folds in order, each two angles in radians: 0.5,3.6 or '0.5,3.6;1.2,4.0'")
    p.add_argument("--json", action="store_true", help="print the plan as JSON instead of text")
    p.set_defaults(run=_plan)
    return top


def main(argv: Optional[List[str]] = None) -> int:
    args = parser().parse_args(argv)
    if args.command == "eval" and not args.paths and not args.builtin:
        parser().error("eval: give PATHS or --builtin")
    try:
        args.run(args)
    except _Usage as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except CloseError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except OSError as e:
        print(f"error: {e.filename}: {e.strerror} (os error {e.errno})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
