"""demfit.diagnose on the analytic study with a hidden stiffening (tests/diagnose/data): the verdict
and the named effect are the command line's."""
import json
import shutil

import pytest

import demfit
from conftest import cli_error, run_cli


@pytest.fixture(scope="module")
def study_file(source_dir, tmp_path_factory):
    folder = tmp_path_factory.mktemp("diagnose")
    for name in ("hidden_stiffening_study.json", "hidden_stiffening.csv"):
        shutil.copy(source_dir / "tests" / "diagnose" / "data" / name, folder / name)
    return folder / "hidden_stiffening_study.json"


def test_diagnose_names_the_hidden_effect_as_the_command_line_does(study_file, demfit_exe):
    out = study_file.parent / "cli"
    code, stdout, err = run_cli(demfit_exe, "diagnose", study_file, "--out", out, "--no-plots")
    assert code == 0, err
    cli = json.loads((out / "diagnosis.json").read_text())
    result = demfit.diagnose(str(study_file))
    assert result["effect"] == cli["effect"] == "stiffening"
    assert f"verdict: {result['verdict']}" in stdout
    assert result["summary"] in stdout
    named = [r for r in result["refits"] if r["effect"] == "stiffening"][0]
    assert named["passes"] and named["delta_bic"] > 10.0


def test_an_unknown_effect_raises_the_command_lines_one_line_message(study_file, demfit_exe):
    code, _, err = run_cli(demfit_exe, "diagnose", study_file, "--out", study_file.parent / "bad", "--effects",
                           "cohesion")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.diagnose(str(study_file), effects="cohesion")
    assert str(raised.value) == cli_error(err)


def test_a_study_with_experiments_is_diagnosed_as_the_command_line_does(source_dir, demfit_exe, tmp_path):
    data = source_dir / "tests" / "cases" / "data" / "diagnose_two_experiments_study.json"
    study = json.loads(data.read_text())
    csv = (data.parent / "../../diagnose/data/hidden_stiffening.csv").resolve()
    for experiment in study["experiments"]:
        experiment["targets"][0]["csv"] = str(csv)
    study_file = tmp_path / "two_experiments.json"
    study_file.write_text(json.dumps(study))
    out = tmp_path / "cli"
    code, stdout, err = run_cli(demfit_exe, "diagnose", study_file, "--out", out, "--no-plots")
    assert code == 0, err
    cli = json.loads((out / "diagnosis.json").read_text())
    result = demfit.diagnose(study_file)
    assert result["effect"] == cli["effect"] == "stiffening"
    assert result["summary"] in stdout


def test_a_dem_study_gets_the_dem_candidates_of_the_command_line(source_dir, demfit_exe, tmp_path):
    # An effect that is not among the DEM pellet case's candidates: both front ends build the DEM
    # model and its candidates, then refuse the selection with the same line, before any run.
    study_file = source_dir / "cases" / "table1_study_quick.json"
    code, _, err = run_cli(demfit_exe, "diagnose", study_file, "--out", tmp_path / "cli", "--effects", "stiffening")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.diagnose(study_file, effects="stiffening", out=tmp_path / "py")
    assert str(raised.value) == cli_error(err)
    assert "hertz_stiffness" in str(raised.value) or "cohesion" in str(raised.value) or "wall" in str(raised.value)
