"""demfit.identify / resume / open_study on the analytic-model study of tests/identify (well under a
second per study): the answer, intervals and runs are the ones the command line reports."""
import json
import shutil

import numpy as np
import pytest

import demfit
from conftest import cli_error, run_cli


@pytest.fixture(scope="module")
def study_file(source_dir, tmp_path_factory):
    # A copy beside its target CSV, so that no output lands in the source tree.
    folder = tmp_path_factory.mktemp("study")
    for name in ("analytic_study.json", "analytic_target.csv"):
        shutil.copy(source_dir / "tests" / "identify" / "data" / name, folder / name)
    return folder / "analytic_study.json"


@pytest.fixture(scope="module")
def cli_study(study_file, demfit_exe):
    out = study_file.parent / "cli"
    code, _, err = run_cli(demfit_exe, "identify", study_file, "--out", out, "--no-plots")
    assert code == 0, err
    return out


@pytest.fixture(scope="module")
def python_study(study_file):
    return demfit.identify(str(study_file), out=str(study_file.parent / "python"))


def test_identify_gives_the_answer_and_intervals_of_the_command_lines_best_parameters(python_study, cli_study):
    best = json.loads((cli_study / "best_parameters.json").read_text())
    answer = python_study.answer
    assert answer["finished"] and best["finished"]
    assert answer["run"] == (best["run"]["iteration"], best["run"]["point"])
    assert answer["objective"] == best["objective"]
    assert answer["parameters"] == best["parameters"]
    intervals = python_study.intervals
    assert sorted(intervals) == sorted(best["variables"]) == sorted(python_study.variables)
    for name, entry in best["variables"].items():
        assert intervals[name]["value"] == entry["value"]
        assert intervals[name]["available"]
        assert [intervals[name]["lower"], intervals[name]["upper"]] == entry["interval_95"]
        assert intervals[name]["method"] == entry["interval_method"]
        assert intervals[name]["identifiable"] == entry["identifiable"]
    # The target was made at amplitude 1.3: the answer finds it and its interval holds it.
    assert answer["parameters"]["amplitude"] == pytest.approx(1.3, abs=1e-3)
    assert intervals["amplitude"]["lower"] <= 1.3 <= intervals["amplitude"]["upper"]


def test_the_runs_are_the_command_lines_evaluations(python_study, cli_study):
    header, columns = read_csv_text(cli_study / "evaluations.csv")
    runs = python_study.runs
    assert len(runs) == len(columns["iteration"]) > 2
    for k, run in enumerate(runs):
        assert (run["iteration"], run["point"]) == (int(columns["iteration"][k]), int(columns["point"][k]))
        assert run["ok"]
        assert run["objective"] == pytest.approx(float(columns["objective"][k]), rel=1e-9)
        for name in python_study.variables:
            assert run["parameters"][name] == pytest.approx(float(columns[name][k]), rel=1e-9)
    objectives = np.array([run["objective"] for run in runs])
    assert python_study.answer["objective"] == objectives.min()


def read_csv_text(path):
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:]]
    return header, {name: [row[i] for row in rows] for i, name in enumerate(header)}


def test_resume_of_a_finished_study_repeats_no_run_and_keeps_the_answer(python_study, study_file):
    again = demfit.resume(str(study_file), out=str(study_file.parent / "python"))
    assert [(r["iteration"], r["point"], r["objective"]) for r in again.runs] == [
        (r["iteration"], r["point"], r["objective"]) for r in python_study.runs]
    assert again.answer["parameters"] == python_study.answer["parameters"]


def test_a_store_the_command_line_made_resumes_and_reads_the_same_in_python(cli_study, study_file, python_study):
    resumed = demfit.identify(study_file, out=cli_study, resume=True)  # os.PathLike arguments too
    assert resumed.answer["parameters"] == python_study.answer["parameters"]
    assert len(resumed.runs) == len(python_study.runs)
    opened = demfit.open_study(cli_study)
    assert opened.finished and opened.answer["objective"] == resumed.answer["objective"]
    assert opened.name == "analytic_cli"


def test_an_existing_store_without_resume_is_refused_before_any_run(python_study, study_file):
    with pytest.raises(demfit.Error, match=r"^study store '.*study\.db' already exists; pass resume=True"):
        demfit.identify(str(study_file), out=str(study_file.parent / "python"))


def test_a_malformed_study_raises_the_command_lines_one_line_message(source_dir, demfit_exe, tmp_path):
    study = source_dir / "tests" / "identify" / "data" / "malformed_study.json"
    code, _, err = run_cli(demfit_exe, "identify", study, "--out", tmp_path / "cli")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.identify(str(study), out=str(tmp_path / "python"))
    assert str(raised.value) == cli_error(err)
    assert str(raised.value).startswith('study: variables[0].lowr: unknown key; did you mean "lower"?')
    assert not (tmp_path / "python").exists()


def test_opening_a_missing_store_raises_an_error_naming_it(tmp_path):
    with pytest.raises(demfit.Error, match="nothing"):
        demfit.open_study(str(tmp_path / "nothing" / "study.db"))
