"""Finds TensorBoard's own event-file reader for test_tensorboard_reader.py: an installed
`tensorboard` first, else the unmodified subset of its source kept in shared/pydeps/tensorboard-*/
beside the repository (its event loaders, accumulator and compat protos, with the *_pb2.py modules
that protoc generated from those unmodified .proto files; see that folder's README). Without
either, or without what the reader imports (Debian's python3-protobuf, python3-absl and
python3-numpy), the test module is skipped and pytest exits with code 77 (conftest.py), which ctest
reports as skipped: never a pass."""

import importlib
import importlib.util
import sys

import pytest

from gymnasium_import import pydeps_folders

SKIP_RETURN_CODE = 77
missing = False  # set when the test module was skipped for want of TensorBoard's reader
NEEDED = {"numpy": "python3-numpy", "google.protobuf": "python3-protobuf", "absl": "python3-absl"}


def _skip(reason):
    global missing
    missing = True
    pytest.skip(reason, allow_module_level=True)


def _vendored_folder():
    for folder in pydeps_folders():
        copies = sorted(folder.glob("tensorboard-*/tensorboard/backend/event_processing/event_accumulator.py"))
        if copies:
            return copies[-1].parents[3]
    return None


def import_event_processing():
    """tensorboard.backend.event_processing (with event_accumulator and event_file_loader
    loaded), or skips the calling test module."""
    for module, package in NEEDED.items():
        try:
            found = importlib.util.find_spec(module) is not None
        except ImportError:
            found = False
        if not found:
            _skip(f"TensorBoard's reader needs {module} (Debian: {package}), which is not installed")
    if importlib.util.find_spec("tensorboard") is None:
        folder = _vendored_folder()
        if folder is None:
            _skip("tensorboard is neither installed nor in shared/pydeps/tensorboard-*/ beside the "
                  "repository")
        sys.path.insert(0, str(folder))
    importlib.import_module("tensorboard.backend.event_processing.event_accumulator")
    importlib.import_module("tensorboard.backend.event_processing.event_file_loader")
    return importlib.import_module("tensorboard.backend.event_processing")
