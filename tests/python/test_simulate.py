"""demfit.simulate: a case run with overrides returns the curves `demfit simulate --set` writes,
and bad input raises the command line's one-line message."""
import math

import numpy as np
import pytest

import demfit
from conftest import cli_error, read_csv, run_cli

# A small pellet bed (120 pellets, 24 mm cylinder, 6 mm stroke to 0.5 MPa), frictionless walls so
# that its statics are exact, run with an identified parameter changed for the measured stage.
SMALL_PELLET = {
    "pellet.particle_count": 120,
    "pellet.container_diameter": 0.024,
    "pellet.settle_time": 0.3,
    "pellet.max_pressure": 0.5e6,
    "pellet.max_travel": 0.006,
    "wall_contact.frics": 0.0,
    "normk": 0.5,
}


def cli_settings(overrides):
    args = []
    for name, value in overrides.items():
        args += ["--set", f"{name}={value!r}"]
    return args


@pytest.fixture(scope="module")
def small_pellet(source_dir):
    return demfit.simulate(str(source_dir / "cases" / "pellet_compression.json"), SMALL_PELLET)


def test_a_case_run_with_overrides_returns_the_curves_the_command_line_writes(small_pellet, source_dir, demfit_exe,
                                                                                tmp_path):
    case = source_dir / "cases" / "pellet_compression.json"
    code, _, err = run_cli(demfit_exe, "simulate", case, *cli_settings(SMALL_PELLET), "--out", tmp_path / "out")
    assert code == 0, err
    header, (volume, pressure) = read_csv(tmp_path / "out" / "pressure_volume.csv")
    curve = small_pellet.curves["pressure_volume"]
    assert header == [curve.x_label, curve.y_label] == ["volume_cm3", "pressure_MPa"]
    # Same input, same seed: bit-identical (the CSV holds 17 significant digits).
    assert isinstance(curve.x, np.ndarray) and curve.x.dtype == np.float64
    assert np.array_equal(curve.x, volume) and np.array_equal(curve.y, pressure)
    assert small_pellet.parameters == {"normk": 0.5}
    assert small_pellet.case["pellet"]["particle_count"] == 120


def test_the_bottom_plate_of_a_frictionless_bed_carries_the_piston_force_plus_the_weight(small_pellet):
    # Quasi-static loading against frictionless walls: bottom force = piston force + m g at the end
    # of loading, within 2 % (the bed's kinetic energy is under 1 % of its elastic energy there).
    history = small_pellet.tables["history"]
    piston, bottom = history["piston_force_N"], history["bottom_force_N"]
    end = int(np.argmax(piston))
    case = small_pellet.case
    radius, density = case["particle"]["radius"], case["particle"]["density"]
    mass = 120 * density * 4.0 / 3.0 * math.pi * radius**3
    assert bottom[end] == pytest.approx(piston[end] + mass * 9.81, rel=0.02)


def test_an_unknown_case_field_raises_the_command_lines_one_line_message(source_dir, demfit_exe, tmp_path):
    case = source_dir / "cases" / "rotary_drum.json"
    code, _, err = run_cli(demfit_exe, "simulate", case, "--set", "drum.rpmm=30", "--out", tmp_path / "out")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.simulate(str(case), {"drum.rpmm": 30})
    assert str(raised.value) == cli_error(err)
    assert "\n" not in str(raised.value) and "rpmm" in str(raised.value)


def test_a_nan_parameter_raises_an_input_error_naming_it(source_dir):
    with pytest.raises(demfit.InputError, match=r"^overrides\['normk'\]: nan is not a finite number") as raised:
        demfit.simulate(str(source_dir / "cases" / "pellet_compression.json"), {"normk": float("nan")})
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, demfit.Error)


def test_a_missing_case_file_raises_the_command_lines_message(demfit_exe, tmp_path):
    missing = tmp_path / "nope.json"
    code, _, err = run_cli(demfit_exe, "simulate", missing, "--out", tmp_path / "out")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.simulate(str(missing))
    assert str(raised.value) == cli_error(err)


def test_other_python_threads_run_while_a_case_runs(small_pellet, source_dir):
    # The GIL is released during the run: the main thread keeps counting meanwhile. Were it held,
    # the main thread could not run until the case had finished (a count of at most one or two).
    import threading
    import time

    results = []
    worker = threading.Thread(target=lambda: results.append(
        demfit.simulate(str(source_dir / "cases" / "pellet_compression.json"), SMALL_PELLET)))
    worker.start()
    ticks = 0
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert ticks >= 20
    assert np.array_equal(results[0].curves["pressure_volume"].y, small_pellet.curves["pressure_volume"].y)
