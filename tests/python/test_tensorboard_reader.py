"""A run's event file (algos/training/event_file.h) read by TensorBoard's own code, not by a decoder
written here (test_tensorboard_events.py does that): its record reader, which checks both masked
CRC-32Cs of every record; its EventFileLoader, which the dashboards read through and which turns
each simple_value into a "scalars" plugin tensor; and its EventAccumulator, which lists the scalar
tags and their (wall_time, step, value) events. Every progress.csv column must be a scalar tag whose
steps are the epochs and whose values are the column's numbers as float32. TensorBoard installed,
else its unmodified source in shared/pydeps beside the repository (tensorboard_import.py), else
skipped."""

import csv
import pathlib
import subprocess
import time

import numpy as np
import pytest

from tensorboard_import import import_event_processing

import_event_processing()
from tensorboard.backend.event_processing import event_accumulator, event_file_loader, io_wrapper  # noqa: E402
from tensorboard.compat.proto import event_pb2  # noqa: E402
from tensorboard.compat.tensorflow_stub import errors, pywrap_tensorflow  # noqa: E402
from tensorboard.util import tensor_util  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
EPOCHS = 3


@pytest.fixture(scope="module")
def run(bsg_binary, tmp_path_factory):
    """A tiny PPO-Lag run: (its directory, the seconds since the epoch before and after it)."""
    run_dir = tmp_path_factory.mktemp("tensorboard") / "run"
    arguments = [bsg_binary, "train", "--configs", str(ROOT / "configs"), "--quiet", "--out", str(run_dir)]
    for setting in ["env_id=SafetyBallCircle-v0", "alg=ppo-lag", f"epochs={EPOCHS}",
                    "steps_per_epoch=400", "eval_episodes=1"]:
        arguments += ["--set", setting]
    started = time.time()
    result = subprocess.run(arguments, capture_output=True, text=True)
    finished = time.time()
    assert result.returncode == 0, result.stdout + result.stderr
    return run_dir, started, finished


def progress_columns(run_dir):
    """progress.csv as {column: [its numbers, one per epoch]}, in the file's column order."""
    with open(run_dir / "progress.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == EPOCHS
    return {name: [float(row[name]) for row in rows] for name in rows[0]}


def event_file(run_dir):
    files = [path for path in run_dir.iterdir() if io_wrapper.IsSummaryEventsFile(str(path))]
    assert len(files) == 1, sorted(run_dir.iterdir())
    return files[0]


def assert_float32_equal(read, written, what):
    read, written = np.float32(read), np.float32(written)
    assert read == written or (np.isnan(read) and np.isnan(written)), (what, read, written)


def test_the_file_is_named_as_tensorboard_looks_for_it(run):
    run_dir, started, finished = run
    path = event_file(run_dir)
    assert io_wrapper.IsTensorFlowEventsFile(str(path))
    seconds = int(path.name.split(".")[3])  # events.out.tfevents.<seconds>.<host>
    assert int(started) <= seconds <= int(finished)


def test_the_record_reader_accepts_every_crc(run):
    run_dir, started, finished = run
    reader = pywrap_tensorflow.PyRecordReader_New(str(event_file(run_dir)))
    events = []
    while True:
        try:
            reader.GetNext()  # raises DataLossError on a wrong length or data CRC
        except errors.OutOfRangeError:
            break
        events.append(event_pb2.Event.FromString(reader.record()))
    assert len(events) == 1 + EPOCHS
    assert events[0].file_version == "brain.Event:2"
    assert [event.step for event in events[1:]] == list(range(EPOCHS))
    wall_times = [event.wall_time for event in events]
    assert started <= wall_times[0] and wall_times == sorted(wall_times) and wall_times[-1] <= finished


def test_a_flipped_byte_is_caught_by_the_reader(run, tmp_path):
    """The control: TensorBoard's reader does check the CRCs the test above relies on."""
    data = bytearray(event_file(run[0]).read_bytes())
    data[-5] ^= 0x01  # the last record's last data byte
    corrupted = tmp_path / "events.out.tfevents.0.corrupted"
    corrupted.write_bytes(bytes(data))
    reader = pywrap_tensorflow.PyRecordReader_New(str(corrupted))
    with pytest.raises(errors.DataLossError, match="crc32"):
        for _ in range(1 + EPOCHS):
            reader.GetNext()


def test_the_dashboards_loader_gives_scalars_plugin_tensors_of_progress_csvs_numbers(run):
    run_dir = run[0]
    columns = progress_columns(run_dir)
    loader = event_file_loader.EventFileLoader(str(event_file(run_dir)))
    events = [event for event in loader.Load() if event.HasField("summary")]
    assert [event.step for event in events] == [int(epoch) for epoch in columns["epoch"]]
    for index, event in enumerate(events):
        assert [value.tag for value in event.summary.value] == list(columns)
        for value in event.summary.value:
            assert value.metadata.plugin_data.plugin_name == "scalars", value.tag
            tensor = tensor_util.make_ndarray(value.tensor)
            assert tensor.shape == () and tensor.dtype == np.float32, value.tag
            assert_float32_equal(tensor, columns[value.tag][index], value.tag)


def test_the_accumulator_lists_every_column_as_a_scalar_tag_with_its_numbers(run):
    run_dir = run[0]
    columns = progress_columns(run_dir)
    accumulator = event_accumulator.EventAccumulator(str(run_dir), size_guidance={event_accumulator.SCALARS: 0})
    accumulator.Reload()
    assert sorted(accumulator.Tags()[event_accumulator.SCALARS]) == sorted(columns)
    for tag, numbers in columns.items():
        scalars = accumulator.Scalars(tag)
        assert [scalar.step for scalar in scalars] == [int(epoch) for epoch in columns["epoch"]], tag
        for scalar, number in zip(scalars, numbers):
            assert_float32_equal(scalar.value, number, tag)
