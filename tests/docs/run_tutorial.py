#!/usr/bin/python3
"""Runs every command of docs/tutorial.md exactly as written, in order, in a fresh folder.

The commands are the `$ ` lines of the tutorial's ```console blocks. The folder gets a copy of the
source tree's examples/ and data/ (the tutorial runs from the top folder of the sources), the
build's demfit first on PATH and an empty settled-fill cache, as a new user would have. A command
that exits non-zero fails the test. Then the outputs the text names are checked, and every JSON
file the text shows is compared with the shipped file of that name.

Usage: run_tutorial.py SOURCE_DIR DEMFIT_EXECUTABLE [SCRATCH_DIR]
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# Outputs the tutorial text names, with a line each must contain.
EXPECTED_OUTPUTS = {
    "my_pellets_results/report.md": "## Identified variables",
    "my_pellets_results/best_parameters.json": "normk",
    "my_pellets_results/target_pressure_volume.png": "",
    "my_pellets.k": "*CONTROL_DISCRETE_ELEMENT",
    "mcc_photo/overlay.png": "",
    "mcc_photo/free_surface.csv": "x_mm,z_mm",
    "mcc_drum_results/report.md": "## Identified variables",
    "mcc_drum_results/target_surface.png": "",
    "mcc_drum.in": "pair_style gran model hertz tangential history",
}


def console_commands(markdown):
    commands = []
    for block in re.findall(r"^```console\n(.*?)^```", markdown, flags=re.S | re.M):
        commands += [line[2:] for line in block.splitlines() if line.startswith("$ ")]
    return commands


def shown_json_files(markdown):
    """(path, JSON text) for every ```json block introduced by a line "`path`:"."""
    return re.findall(r"^`([^`]+\.json)`:\n\n```json\n(.*?)^```", markdown, flags=re.S | re.M)


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    source, demfit = sys.argv[1], os.path.abspath(sys.argv[2])
    scratch_parent = sys.argv[3] if len(sys.argv) > 3 else None
    with open(os.path.join(source, "docs", "tutorial.md"), encoding="utf-8") as f:
        markdown = f.read()

    for path, text in shown_json_files(markdown):
        with open(os.path.join(source, path), encoding="utf-8") as f:
            if json.load(f) != json.loads(text):
                fail(f"the JSON shown for {path} differs from the shipped file")
    if len(shown_json_files(markdown)) != 4:
        fail("expected the four tutorial input files (two cases, two studies) shown in the text")
    for path in EXPECTED_OUTPUTS:
        if os.path.basename(path) not in markdown:
            fail(f"the output {path} checked here is not named in the tutorial")

    commands = console_commands(markdown)
    if not any(c.startswith("demfit identify") for c in commands):
        fail("no `$ demfit identify` line found in the tutorial's console blocks")
    if scratch_parent:
        os.makedirs(scratch_parent, exist_ok=True)
    work = tempfile.mkdtemp(prefix="tutorial_", dir=scratch_parent)
    shutil.copytree(os.path.join(source, "examples"), os.path.join(work, "examples"))
    shutil.copytree(os.path.join(source, "data"), os.path.join(work, "data"))
    bin_dir = os.path.join(work, "bin")
    os.makedirs(bin_dir)
    os.symlink(demfit, os.path.join(bin_dir, "demfit"))
    env = dict(os.environ)
    env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
    env["DEMFIT_CACHE_DIR"] = os.path.join(work, "cache")

    for command in commands:
        start = time.monotonic()
        run = subprocess.run(["/bin/bash", "-c", command], cwd=work, env=env, capture_output=True, text=True)
        print(f"$ {command}   [{time.monotonic() - start:.1f} s, exit {run.returncode}]", flush=True)
        if run.returncode != 0:
            print(run.stdout[-4000:])
            print(run.stderr[-4000:])
            fail(f"`{command}` exited with status {run.returncode} (folder {work})")

    for path, line in EXPECTED_OUTPUTS.items():
        full = os.path.join(work, path)
        if not os.path.isfile(full) or os.path.getsize(full) == 0:
            fail(f"{path}, named in the tutorial, was not written")
        if line:
            with open(full, encoding="utf-8", errors="replace") as f:
                if line not in f.read():
                    fail(f"{path} does not contain '{line}'")
    shutil.rmtree(work)
    print(f"all {len(commands)} tutorial commands ran")


if __name__ == "__main__":
    main()
