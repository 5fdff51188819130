"""The "Done when" checks of the installed package (issue "Python for learning to group"),
run against a usar installed from its wheel, from a folder outside the checkout.

    python /path/to/checkout/python/tests/installed_check.py           # every check
    python /path/to/checkout/python/tests/installed_check.py NAME ...  # some of them

Each check runs in a child interpreter of its own (the same ``sys.executable``) in a fresh
temporary folder, under a timeout (``USAR_CHECK_TIMEOUT`` seconds, default 600), so a crash,
an abort or a hang fails that check alone. It prints one line per check (PASS or FAIL, the
seconds, what it measured or the error) and exits 0 when every check passed, 1 otherwise.
It needs the package with its ``gym`` and ``pettingzoo`` extras (``pip install
"usar-*.whl[gym,pettingzoo]"``); pytest does not collect it (not a ``test_*.py`` file).

The checks (:data:`CHECKS`, in order):

- ``location``: ``usar`` is imported from the installed package, not from the checkout;
  ``usar.scenario_path()`` is the wheel's ``usar/scenarios/paper.ron``, with paper.ron's
  targets and claims files beside it.
- ``module_size``: the native module ``usar._usar`` is under 30 MB.
- ``side_files``: a short sweep of the shipped paper.ron with ``out`` finds its targets and
  claims (no warning, ``## Claims`` in report.md).
- ``warning``: a copy of paper.ron alone in a folder (its side files missing): the notice
  arrives as a Python warning of category ``usar.UsarWarning``.
- ``make_no_args``: ``gymnasium.make("usar/Grouping-v0")`` with no argument (after
  ``import usar.gym``; Gymnasium 1.x registers no package's environments on its own) runs the
  shipped paper.ron, resets and steps, and an interpreter that leaves it open exits with
  status 0; so does
  ``gymnasium.make("usar.gym:usar/Grouping-v0")`` without importing usar first.
- ``unseeded_resets``: 20 unseeded resets after ``reset(seed=1)`` give at least 18 distinct
  trials (by ``info["seed"]``), none of them trials 0-9 of a sweep of the env's scenario.
- ``vector_sync``, ``vector_async``: ``SyncVectorEnv`` and ``AsyncVectorEnv`` of 2 envs
  (300 s trials) reset with ``options={"trial": k}`` for k = 0..9, step until each sub-env
  has ended an episode and been reset by the wrapper, and close.
- ``bad_action``: ``env.step`` with an out-of-range action raises ``ValueError`` and the
  next valid step works.
- ``pettingzoo``: ``pettingzoo.test.parallel_api_test(usar.pettingzoo.parallel_env())``.
"""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import tempfile
import time

ENV_ID = "usar/Grouping-v0"
#: The checkout this file is in (``usar`` must not come from it).
CHECKOUT = pathlib.Path(__file__).resolve().parents[2]
#: Simulated seconds of the vector envs' trials (short: several episodes end).
VECTOR_DURATION_S = 300.0
MAX_MODULE_BYTES = 30 * 1000 * 1000


def _inside(path: pathlib.Path, folder: pathlib.Path) -> bool:
    path, folder = path.resolve(), folder.resolve()
    return path == folder or folder in path.parents


def check_location() -> str:
    import usar

    here = pathlib.Path(usar.__file__).resolve()
    assert not _inside(here, CHECKOUT), f"usar imported from the checkout: {here}"
    assert not _inside(pathlib.Path.cwd(), CHECKOUT), f"run from the checkout: {os.getcwd()}"
    paper = usar.scenario_path()
    shipped = here.parent / "scenarios"
    assert paper == shipped / "paper.ron" and paper.is_file(), (
        f"usar.scenario_path() is {paper}, not the wheel's {shipped / 'paper.ron'}"
    )
    for side in ("paper-targets.ron", "paper-claims.ron"):
        assert (shipped / side).is_file(), f"{side} not shipped beside paper.ron in {shipped}"
    names = usar.scenario_names()
    return f"usar at {here.parent}; {len(names)} shipped scenarios"


def check_module_size() -> str:
    import usar._usar

    size = os.path.getsize(usar._usar.__file__)
    assert size < MAX_MODULE_BYTES, f"{usar._usar.__file__} is {size / 1e6:.1f} MB (limit 30 MB)"
    return f"{pathlib.Path(usar._usar.__file__).name}: {size / 1e6:.1f} MB"


def _short_sweep(scenario, out):
    import warnings

    import usar

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        usar.sweep(scenario, trials=2, duration_s=20.0, out=str(out), progress=False)
    return caught


def check_side_files() -> str:
    import usar

    out = pathlib.Path("side-files")
    caught = _short_sweep(usar.scenario_path(), out)
    about = [str(w.message) for w in caught if "targets" in str(w.message) or "claims" in str(w.message)]
    assert not about, f"the shipped paper.ron's side files not found: {about}"
    report = (out / "report.md").read_text()
    assert "\n## Claims" in report, "report.md of the shipped paper.ron has no ## Claims section"
    return "report.md checks paper.ron's claims and targets"


def check_warning() -> str:
    import usar

    alone = pathlib.Path("alone")
    alone.mkdir()
    copy = alone / "paper.ron"
    copy.write_text(usar.scenario_path().read_text())
    assert hasattr(usar, "UsarWarning"), "usar.UsarWarning does not exist"
    caught = _short_sweep(copy, pathlib.Path("alone-out"))
    ours = [w for w in caught if issubclass(w.category, usar.UsarWarning)]
    assert ours, (
        "no usar.UsarWarning for a paper.ron without its side files; warnings: "
        f"{[(w.category.__name__, str(w.message)) for w in caught]}"
    )
    return f"{ours[0].category.__name__}: {str(ours[0].message)[:100]}"


_LEFT_OPEN = """
import gymnasium
{imports}
env = gymnasium.make({env_id!r})
obs, info = env.reset(seed=0)
env.step(env.action_space.sample())
print("left open; scenario", env.unwrapped.scenario.origin)
"""


def check_make_no_args() -> str:
    for imports, env_id in (("import usar.gym", ENV_ID), ("", f"usar.gym:{ENV_ID}")):
        code = _LEFT_OPEN.format(imports=imports, env_id=env_id)
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
        assert p.returncode == 0 and "left open" in p.stdout, (
            f"gymnasium.make({env_id!r}) left open: exit {p.returncode}; stderr: {p.stderr[-1500:]}"
        )
        assert "Fatal" not in p.stderr, f"gymnasium.make({env_id!r}) left open: {p.stderr[-1500:]}"
        origin = p.stdout.split("left open; scenario ", 1)[1].strip()
        assert origin.endswith(os.path.join("usar", "scenarios", "paper.ron")), (
            f"gymnasium.make({env_id!r}) with no argument runs {origin}, not the shipped paper.ron"
        )
    return f"made with no argument ({origin}), reset, stepped, left open: exit 0"


def _seed(info) -> int:
    assert "seed" in info, f"info has no 'seed' (keys: {sorted(info)})"
    return int(info["seed"]) % 2**64


def check_unseeded_resets() -> str:
    import gymnasium
    import usar
    import usar.gym  # noqa: F401  (registers the env)

    env = gymnasium.make(ENV_ID)
    try:
        env.reset(seed=1)
        drawn = [_seed(env.reset()[1]) for _ in range(20)]
        scenario = getattr(env.unwrapped, "scenario", None)
    finally:
        env.close()
    distinct = len(set(drawn))
    assert distinct >= 18, f"20 unseeded resets after reset(seed=1): {distinct} distinct trials"
    assert scenario is not None, "the env has no `scenario` attribute to sweep"
    frame = usar.sweep(scenario, methods=["rne"], trials=10, duration_s=1.0, progress=False)
    sweep = {int(s) % 2**64 for s in frame["seed"].unique()}
    assert len(sweep) == 10, f"the sweep's trials 0-9 have {len(sweep)} seeds"
    both = sorted(sweep & set(drawn))
    assert not both, f"unseeded resets drew the sweep's trials (seeds {both})"
    return f"{distinct} distinct of 20, none of the sweep's trials 0-9"


def _vector(kind: str) -> str:
    import functools

    import gymnasium
    import numpy as np
    import usar.gym  # noqa: F401  (registers the env)

    make = functools.partial(gymnasium.make, ENV_ID, duration_s=VECTOR_DURATION_S)
    wrapper = gymnasium.vector.SyncVectorEnv if kind == "sync" else gymnasium.vector.AsyncVectorEnv
    venv = wrapper([make, make])
    steps = 0
    try:
        for k in range(10):
            venv.reset(options={"trial": k})
            ended = np.zeros(2, dtype=bool)
            after = 0
            # Until both sub-envs have ended an episode, then 2 steps more (the wrapper's
            # unseeded reset of an ended sub-env, and a step of its new episode).
            while after < 2:
                _, _, terminated, truncated, _ = venv.step(venv.action_space.sample())
                steps += 1
                ended |= np.asarray(terminated) | np.asarray(truncated)
                after += bool(ended.all())
                assert steps < 2000, f"trial {k}: no episode ended in {steps} steps"
    finally:
        venv.close()
    return f"{wrapper.__name__} over trials 0-9: {steps} steps, closed"


def check_vector_sync() -> str:
    return _vector("sync")


def check_vector_async() -> str:
    return _vector("async")


def _out_of_range(space):
    import numpy as np
    from gymnasium import spaces

    if isinstance(space, spaces.MultiDiscrete):
        return np.asarray(space.nvec, dtype=np.int64) + np.asarray(space.start, dtype=np.int64)
    if isinstance(space, spaces.Discrete):
        return int(space.n + space.start)
    if isinstance(space, spaces.Box):
        return np.asarray(space.high, dtype=space.dtype) + 1
    raise AssertionError(f"no out-of-range action known for {space}")


def check_bad_action() -> str:
    import gymnasium
    import usar.gym  # noqa: F401  (registers the env)

    env = gymnasium.make(ENV_ID)
    try:
        env.reset(seed=0)
        bad = _out_of_range(env.action_space)
        try:
            env.step(bad)
        except ValueError as e:
            message = str(e)
        else:
            raise AssertionError(f"env.step({bad!r}) (out of range) raised nothing")
        result = env.step(env.action_space.sample())
        assert len(result) == 5, f"the valid step after it returned {result!r}"
    finally:
        env.close()
    return f"ValueError: {message[:100]}; the next valid step worked"


def check_pettingzoo() -> str:
    from pettingzoo.test import parallel_api_test

    import usar.pettingzoo

    parallel_api_test(usar.pettingzoo.parallel_env())
    return "parallel_api_test passed"


CHECKS = {
    "location": check_location,
    "module_size": check_module_size,
    "side_files": check_side_files,
    "warning": check_warning,
    "make_no_args": check_make_no_args,
    "unseeded_resets": check_unseeded_resets,
    "vector_sync": check_vector_sync,
    "vector_async": check_vector_async,
    "bad_action": check_bad_action,
    "pettingzoo": check_pettingzoo,
}


def _one(name: str) -> None:
    """In the child: runs check ``name``, prints its line's text on stdout (exit 0) or its
    error on stderr (exit 1)."""
    try:
        print(CHECKS[name]())
    except BaseException as e:  # noqa: BLE001 - every failure is the check's verdict
        import traceback

        traceback.print_exc()
        print(f"{type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(1)


def main(argv) -> int:
    if argv[:1] == ["--one"]:
        _one(argv[1])
        return 0
    names = argv or list(CHECKS)
    unknown = [n for n in names if n not in CHECKS]
    if unknown:
        print(f"unknown check(s) {unknown}; known: {', '.join(CHECKS)}", file=sys.stderr)
        return 2
    timeout = float(os.environ.get("USAR_CHECK_TIMEOUT", "600"))
    failed = []
    for name in names:
        start = time.monotonic()
        with tempfile.TemporaryDirectory(prefix=f"usar-check-{name}-") as folder:
            try:
                p = subprocess.run(
                    [sys.executable, str(pathlib.Path(__file__).resolve()), "--one", name],
                    cwd=folder, capture_output=True, text=True, timeout=timeout,
                )
                ok, text = p.returncode == 0, (p.stdout.strip().splitlines() or [""])[-1]
                if not ok:
                    lines = p.stderr.strip().splitlines()
                    text = lines[-1] if lines else f"exit status {p.returncode}"
                    if p.returncode < 0:
                        text = f"killed by signal {-p.returncode}; {text}"
                    detail = "\n".join("    " + l for l in lines[-25:])
            except subprocess.TimeoutExpired:
                ok, text, detail = False, f"no answer in {timeout:.0f} s (hung)", ""
        seconds = time.monotonic() - start
        print(f"{'PASS' if ok else 'FAIL'} {name} ({seconds:.0f} s): {text}", flush=True)
        if not ok:
            failed.append(name)
            if detail:
                print(detail, flush=True)
    print(f"{len(names) - len(failed)} of {len(names)} checks passed"
          + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
