"""Training from Python: ``bsg.train`` and ``bsg.sweep``, `bsg train` and `bsg sweep` in this process.

    run_dir = bsg.train("configs/runs/ballcircle_trpol.yaml", out="runs/demo", epochs=5,
                        callback=lambda row: print(row["Epoch"], row["AverageEpRet"]))
    policy = bsg.load_policy(run_dir)

``bsg.train`` runs the C++ trainer of `bsg train` (the same start, the same files, the same
numbers) with the GIL released. Ctrl-C (KeyboardInterrupt), or any exception raised by the
callback, stops the run at the end of the epoch with a checkpoint, as a stop signal stops
`bsg train`; ``bsg.train(resume=run_dir)`` or `bsg train --resume` continues it identically.
``bsg.sweep`` runs a grid file's runs as `bsg sweep` does, as children of the bsg program
(docs/python.md#train-from-python).
"""

import os
import shutil

from . import _core


def _path_or_none(value, name):
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a path (str or os.PathLike) or None, got {value!r}")
    return os.fspath(value)


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def train(config=None, out=None, *, callback=None, resume=None, configs=None, verbose=True,
          stop_after=0, **overrides):
    """Trains the run ``config`` describes and returns its run directory (str).

    ``config``: a run file (YAML path, as ``bsg train CONFIG``) or a dict of the same keys
    (configs/README.md); ``overrides``: keys applied after it, as ``--set key=value``
    (``epochs=3``, ``hidden_sizes=[32, 32]``, ``env={"bombs": 12}``). ``out``: the run
    directory (default ``<log_dir>/<env_id>/<alg>/seed_<seed>``); ``configs``: the configs folder
    (default: searched as ``bsg train`` searches). ``callback(row)`` receives each epoch's
    progress.csv row as a dict ``{column: float}`` once it is written. ``verbose`` prints
    ``bsg train``'s progress lines to ``sys.stdout``. ``stop_after``: stop, with a checkpoint,
    once this many epochs are done in total (as ``--stop-after``). ``resume``: a run directory to
    continue (its config.yaml describes it; give no ``config`` or keys).

    A bad key or value raises ValueError carrying the C++ message (the key and where its value
    came from: ``config['epochs']``, ``bsg.train(epochs=...)`` or the file and line). A
    KeyboardInterrupt, or an exception from ``callback``, stops the run at the end of the
    current epoch with a checkpoint and is then raised, with the run directory in its
    ``bsg_run_dir`` attribute and in its notes.
    """
    config_file = None
    config_dict = None
    if isinstance(config, dict):
        config_dict = config
    elif config is not None:
        if not isinstance(config, (str, os.PathLike)):
            raise TypeError(f"config must be a run file's path or a dict of keys, got {config!r}")
        config_file = os.fspath(config)
    if callback is not None and not callable(callback):
        raise TypeError(f"callback must be callable (it receives each epoch's row as a dict), got {callback!r}")
    if isinstance(stop_after, bool) or not isinstance(stop_after, int):
        raise TypeError(f"stop_after must be an int, got {stop_after!r}")
    if resume is None and config is None and not overrides:
        raise ValueError("bsg.train needs a config (a run file or a dict of keys), keywords, or resume=RUN_DIR")
    run_dir, _, _ = _core.train(config_file, config_dict, overrides, _path_or_none(out, "out"),
                                _path_or_none(configs, "configs"), _path_or_none(resume, "resume"), callback,
                                bool(verbose), stop_after, _PACKAGE_DIR)
    return run_dir


def _bsg_program(program):
    """The bsg program the runs of a sweep are children of."""
    if program is not None:
        path = shutil.which(os.fspath(program))
        if path is None:
            raise FileNotFoundError(f"program {program!r} is not an executable")
        return os.path.abspath(path)
    for candidate in (os.path.join(_PACKAGE_DIR, _core.program_from_package), _core.build_tree_program):
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.normpath(candidate)
    found = shutil.which("bsg")
    if found is None:
        raise FileNotFoundError("bsg.sweep runs its runs with the bsg program, which was found neither installed "
                                "beside this package, nor in its build tree, nor on PATH: pass program=PATH")
    return os.path.abspath(found)


def _names(value, name):
    if value is None:
        return []
    if isinstance(value, str):
        return [value]
    if not all(isinstance(item, str) for item in value):
        raise TypeError(f"{name} must be a str or a list of str, got {value!r}")
    return list(value)


def sweep(grid, out=None, *, jobs=None, ranks_per_run=1, env=None, alg=None, configs=None, program=None):
    """Runs the grid file ``grid`` as ``bsg sweep GRID`` does and returns the sweep directory (str).

    ``out``: the sweep directory (default ``sweeps/<grid name>``); ``jobs``: runs at a time
    (default: cores / ``ranks_per_run``); ``env``, ``alg``: only these environments or
    algorithms of the grid (a name or a list); ``configs``: the configs folder; ``program``: the
    bsg program (default: the installed one beside this package, the build tree's, or ``bsg`` on
    PATH). Finished runs are skipped and unfinished ones resumed, so a stopped sweep run again
    continues. A bad grid raises ValueError; failed runs RuntimeError (each listed on stderr with
    its log). Ctrl-C stops the running runs at the end of their epoch with a checkpoint, then
    raises KeyboardInterrupt with the sweep directory in ``bsg_sweep_dir``.
    """
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ValueError(f"jobs must be an int >= 1 or None, got {jobs!r}")
    return _core.sweep(_path_or_none(grid, "grid"), _path_or_none(out, "out"), _path_or_none(configs, "configs"),
                       jobs or 0, ranks_per_run, _names(env, "env"), _names(alg, "alg"), _bsg_program(program),
                       _PACKAGE_DIR)
