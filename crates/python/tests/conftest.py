import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def cli() -> str:
    """The command line built from the same checkout (``cargo build --release -p roughcontact``),
    or the one ROUGHCONTACT_BIN names."""
    path = os.environ.get("ROUGHCONTACT_BIN") or str(ROOT / "target" / "release" / "roughcontact")
    if not (os.path.isfile(path) or shutil.which(path)):
        pytest.fail(f"no roughcontact binary at {path}: run `cargo build --release -p roughcontact` first")
    return path
