"""demfit.surface_profile: the free surface of a drum photo, as `demfit target from-image` writes it,
and of a synthetic picture whose surface is known."""
import numpy as np
import pytest

import demfit
from conftest import cli_error, read_csv, run_cli


def test_a_photo_gives_the_profile_the_command_line_writes(source_dir, demfit_exe, tmp_path):
    photo = source_dir / "data" / "granudrum_mcc" / "granudrum_mcc_15rpm.bmp"
    code, _, err = run_cli(demfit_exe, "target", "from-image", photo, "--diameter", "84mm", "--out", tmp_path / "cli")
    assert code == 0, err
    header, (x_mm, z_mm) = read_csv(tmp_path / "cli" / "free_surface.csv")
    assert header == ["x_mm", "z_mm"]
    profile = demfit.surface_profile(str(photo), 0.084)
    # The file holds 6 significant digits of millimetres: half a unit of the sixth digit.
    assert len(profile.x) == len(x_mm) == 41
    assert np.allclose(profile.x * 1e3, x_mm, rtol=5.001e-6, atol=0.0)
    assert np.allclose(profile.z * 1e3, z_mm, rtol=5.001e-6, atol=0.0)


def test_a_picture_of_a_straight_tilted_bed_gives_that_line_within_a_pixel():
    # 201 x 201 pixels spanning a 100 mm drum: pixel centres at x = -R + i h, z = R - j h,
    # h = D / (N - 1) (imaging/surface.hpp). Dark below z = a + b x, white above.
    n, diameter = 201, 0.1
    h, radius = diameter / (n - 1), diameter / 2
    a, b = -0.012, 0.35
    centres = -radius + h * np.arange(n)
    x = centres[np.newaxis, :]
    z = -centres[:, np.newaxis]
    grey = np.where(z < a + b * x, 0.1, 0.9).astype(np.float32)
    profile = demfit.surface_profile(grey, diameter, points=31)
    assert len(profile.x) == 31
    assert np.max(np.abs(profile.z - (a + b * profile.x))) <= h
    assert profile.angle_deg == pytest.approx(np.degrees(np.arctan(b)), abs=0.5)


def test_a_missing_photo_raises_the_command_lines_one_line_message(demfit_exe, tmp_path):
    missing = tmp_path / "missing.png"
    code, _, err = run_cli(demfit_exe, "target", "from-image", missing, "--diameter", "84mm", "--out", tmp_path / "o")
    assert code != 0
    with pytest.raises(demfit.Error) as raised:
        demfit.surface_profile(str(missing), 0.084)
    assert str(raised.value) == cli_error(err)


def test_a_diameter_out_of_range_raises_an_error_naming_the_field():
    with pytest.raises(demfit.Error, match="^diameter"):
        demfit.surface_profile(np.zeros((10, 10)), 1e-6)
