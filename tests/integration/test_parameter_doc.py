#!/usr/bin/python3
"""docs/parameters.md is generated from the scene schema; this test fails when it is stale
(regenerate with: build/bin/fsi-server --write-parameter-doc docs/parameters.md)."""
import os
import subprocess
import sys
import tempfile

from fsi_test import binary, check

docs = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "parameters.md")
with tempfile.TemporaryDirectory() as folder:
    generated = os.path.join(folder, "parameters.md")
    subprocess.run([binary("fsi-server"), "--write-parameter-doc", generated], check=True)
    with open(generated) as handle:
        fresh = handle.read()
with open(docs) as handle:
    stored = handle.read()
check(fresh == stored, "docs/parameters.md matches the schema (regenerate it if this fails)")
