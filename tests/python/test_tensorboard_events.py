"""TensorBoard event files beside progress.csv (algos/training/event_file.h), decoded by a reader
written here from the formats' public descriptions, never by the writer's code: TFRecord framing
(uint64 length, masked CRC-32C of it, data, masked CRC-32C of the data, little-endian), CRC-32C
computed bit by bit from its polynomial (checked on the standard check value), and the protocol
buffer wire format of tensorflow's Event, Summary and Summary.Value. The decoded scalars must be
progress.csv's numbers (as float32) at each epoch, after a resume too; with tensorboard: false
there is no event file and progress.csv and evaluation.json are the same as with it."""

import csv
import json
import pathlib
import struct
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
TIMING = {"time_collect_s", "time_update_s", "time_s", "fps"}


def crc32c(data):
    """CRC-32C, bit by bit: reflected polynomial 0x82F63B78, initial and final xor 0xFFFFFFFF."""
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ (0x82F63B78 if crc & 1 else 0)
    return crc ^ 0xFFFFFFFF


def masked(crc):
    return ((((crc >> 15) | (crc << 17)) & 0xFFFFFFFF) + 0xA282EAD8) & 0xFFFFFFFF


def records(path):
    data = path.read_bytes()
    offset = 0
    while offset < len(data):
        header = data[offset:offset + 8]
        (length,) = struct.unpack("<Q", header)
        (length_crc,) = struct.unpack("<I", data[offset + 8:offset + 12])
        assert length_crc == masked(crc32c(header)), "the length's CRC"
        body = data[offset + 12:offset + 12 + length]
        (body_crc,) = struct.unpack("<I", data[offset + 12 + length:offset + 16 + length])
        assert body_crc == masked(crc32c(body)), "the data's CRC"
        yield body
        offset += 16 + length
    assert offset == len(data)


def fields(message):
    """(field number, wire type, value) of a protocol buffer message."""
    offset = 0

    def varint():
        nonlocal offset
        value, shift = 0, 0
        while True:
            byte = message[offset]
            offset += 1
            value |= (byte & 0x7F) << shift
            shift += 7
            if byte < 0x80:
                return value

    while offset < len(message):
        key = varint()
        number, wire = key >> 3, key & 7
        if wire == 0:
            yield number, wire, varint()
        elif wire == 1:
            yield number, wire, message[offset:offset + 8]
            offset += 8
        elif wire == 2:
            length = varint()
            yield number, wire, message[offset:offset + length]
            offset += length
        elif wire == 5:
            yield number, wire, message[offset:offset + 4]
            offset += 4
        else:
            raise AssertionError(f"wire type {wire}")


def decode_event(body):
    """Event: wall_time 1 (double), step 2 (int64), file_version 3, summary 5 (Summary: value 1,
    each Value: tag 1, simple_value 2 float)."""
    event = {"step": 0, "scalars": {}}
    for number, _, value in fields(body):
        if number == 1:
            event["wall_time"] = struct.unpack("<d", value)[0]
        elif number == 2:
            event["step"] = value
        elif number == 3:
            event["file_version"] = value.decode()
        elif number == 5:
            for _, _, summary_value in fields(value):
                parts = {n: v for n, _, v in fields(summary_value)}
                event["scalars"][parts[1].decode()] = struct.unpack("<f", parts[2])[0]
    return event


def events_of(run_dir):
    files = sorted(run_dir.glob("events.out.tfevents.*"))
    assert len(files) == 1, files
    return [decode_event(body) for body in records(files[0])]


def progress(run_dir):
    with open(run_dir / "progress.csv", newline="") as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def train(bsg_binary, out, *settings, extra=()):
    arguments = [bsg_binary, "train", "--configs", str(CONFIGS), "--quiet", "--out", str(out), *extra]
    for setting in ["env_id=SafetyBallCircle-v0", "alg=ppo-lag", "epochs=3", "steps_per_epoch=400",
                    "eval_episodes=1", "save_freq=1", *settings]:
        arguments += ["--set", setting]
    result = subprocess.run(arguments, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def assert_events_equal_progress(run_dir):
    events = events_of(run_dir)
    assert events[0]["file_version"] == "brain.Event:2" and not events[0]["scalars"]
    rows = progress(run_dir)
    assert [e["step"] for e in events[1:]] == [int(r["epoch"]) for r in rows] == list(range(len(rows)))
    for event, row in zip(events[1:], rows):
        assert list(event["scalars"]) == list(row)
        for name, value in row.items():
            written, decoded = np.float32(value), np.float32(event["scalars"][name])
            assert decoded == written or (np.isnan(decoded) and np.isnan(written)), name


def test_the_crc_is_crc32c():
    assert crc32c(b"123456789") == 0xE3069283  # the standard check value


def test_event_files_hold_progress_csvs_numbers(bsg_binary, tmp_path):
    train(bsg_binary, tmp_path / "on")
    assert_events_equal_progress(tmp_path / "on")


def test_a_resumed_run_writes_the_kept_rows_and_the_rest(bsg_binary, tmp_path):
    run_dir = tmp_path / "resumed"
    train(bsg_binary, run_dir, extra=["--stop-after", "2"])
    assert len(events_of(run_dir)) == 3
    result = subprocess.run([bsg_binary, "train", "--quiet", "--configs", str(CONFIGS), "--resume", str(run_dir)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert_events_equal_progress(run_dir)


def test_turned_off_there_is_no_event_file_and_nothing_else_changes(bsg_binary, tmp_path):
    train(bsg_binary, tmp_path / "on")
    train(bsg_binary, tmp_path / "off", "tensorboard=false")
    assert not list((tmp_path / "off").glob("events.out.tfevents.*"))

    def without_timing(rows):
        return [{k: v for k, v in row.items() if k not in TIMING} for row in rows]

    assert without_timing(progress(tmp_path / "on")) == without_timing(progress(tmp_path / "off"))
    assert (json.loads((tmp_path / "on" / "evaluation.json").read_text())
            == json.loads((tmp_path / "off" / "evaluation.json").read_text()))
    # config.yaml (and so the checkpoint's copy of it) names the key only when it is off.
    on = (tmp_path / "on" / "config.yaml").read_text().splitlines()
    off = (tmp_path / "off" / "config.yaml").read_text().splitlines()
    assert [line for line in on if line not in off] == []
    extra = [line for line in off if line not in on]
    assert len(extra) == 1 and extra[0].startswith("tensorboard: false"), extra
