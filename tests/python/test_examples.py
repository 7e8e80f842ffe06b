"""The worked examples in examples/ run and show what the README says they show."""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(script, *args):
    result = subprocess.run([sys.executable, os.path.join(ROOT, "examples", script), *args], check=True,
                            capture_output=True, text=True)
    return result.stdout


def test_stereo_triangulation_meets_p():
    out = run("stereo_triangulation.py")
    worst = float(re.search(r"max ([0-9.e+-]+) m", out).group(1))
    points = int(re.search(r"(\d+) points seen by both cameras", out).group(1))
    assert points > 10000
    # Exact calibration files, disparity and P agree to float32 rounding: P's half ulp at 0.5 m.
    assert worst < 3e-8


def test_dic_bias_is_an_s_curve(tmp_path):
    out = run("dic_bias.py", "-o", str(tmp_path / "bias.png"))
    rows = re.findall(r"shift ([0-9.]+) px: bias bilinear ([+-][0-9.]+) px, bicubic ([+-][0-9.]+) px", out)
    assert len(rows) == 21
    shift = [float(r[0]) for r in rows]
    for name, column in (("bilinear", 1), ("bicubic", 2)):
        bias = [float(r[column]) for r in rows]
        # No bias at whole and half pixels (the images are the same there, up to the half-pixel
        # symmetry), a sizeable one in between, of opposite signs in the two halves.
        for s, b in zip(shift, bias):
            if abs(s - round(s * 2) / 2) < 1e-6:
                assert abs(b) < 0.003, (name, s, b)
        quarter, three_quarters = bias[5], bias[15]
        assert 0.005 < abs(quarter) < 0.05, (name, quarter)
        assert quarter * three_quarters < 0, (name, quarter, three_quarters)
    assert (tmp_path / "bias.png").stat().st_size > 10000
