"""The Python API refuses wrong arguments with TypeError or ValueError naming the argument, as
the command line names its options (issue 46); nothing runs and no folder is made."""

from __future__ import annotations

import pytest

from gripper.bench.benchmark import BenchConfig, run_benchmark
from gripper.core.params import GripperParams
from gripper.envs.grasp_env import make_config
from gripper.experiments.trial import run_trial
from gripper.studies.envelope import Envelope, run_envelope
from gripper.studies.study import run_study


@pytest.mark.parametrize(("call", "error", "name"), [
    (lambda: run_trial("block", 0, 1.5), TypeError, "index"),
    (lambda: run_trial("block", 0, -1), ValueError, "index"),
    (lambda: run_trial("block", -3), ValueError, "seed"),
    (lambda: run_trial("block", 2**40), ValueError, "seed"),
    (lambda: run_trial("block", True), TypeError, "seed"),
    (lambda: run_trial(3.5), TypeError, "obj"),
    (lambda: run_trial("block", params={"finger": 1}), TypeError, "params"),
    (lambda: run_trial("block", protocol="fast"), TypeError, "protocol"),
    (lambda: run_benchmark({"objects": ["block"]}, "run"), TypeError, "cfg"),
    (lambda: run_benchmark(BenchConfig(objects=("block",), trials=1), 3), TypeError, "out"),
    (lambda: BenchConfig(objects="block").validate(), ValueError, "objects"),
    (lambda: BenchConfig(trials=10**6).validate(), ValueError, "trials"),
    (lambda: BenchConfig(params={}).validate(), TypeError, "params"),
    (lambda: run_envelope({"shapes": ["box"]}, "env"), TypeError, "env"),
    (lambda: run_envelope(Envelope(seed=-1), "env"), ValueError, "seed"),
    (lambda: run_study("one_at_a_time", "st"), TypeError, "study"),
    (lambda: make_config(objects=3), TypeError, "objects"),
    (lambda: make_config(params=3), TypeError, "params"),
    (lambda: make_config(params="default"), ValueError, "params"),
    (lambda: GripperParams.load(3), TypeError, "path"),
])
def test_a_wrong_argument_is_named(call, error, name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(error, match=rf"^(envelope\.)?{name}\b"):
        call()
    assert list(tmp_path.iterdir()) == []  # nothing made
