"""The wheel on its own: a fresh venv, `pip install` of the wheel, three lines of Python."""

import glob
import subprocess
import sys


def test_a_newcomer_installs_the_wheel_in_a_fresh_venv_and_generates_in_three_lines(root, tmp_path):
    wheels = glob.glob(f"{root}/target/wheels/shade_sim-*.whl")
    assert len(wheels) == 1, wheels
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    # Only the wheel and its declared dependency (numpy, the newest: 2.x here, where the project's
    # venv has 1.x for robosuite).
    subprocess.run([python, "-m", "pip", "install", "--quiet", "--disable-pip-version-check", wheels[0]], check=True)
    three_lines = (
        "import shade_sim\n"
        f"layouts = shade_sim.generate('{root}/scenes/examples/living_l.json', require_clean=True)\n"
        "print(len(layouts), shade_sim.check(layouts[0]), layouts[0].boxes().shape[1])\n"
    )
    out = subprocess.run([python, "-c", three_lines], check=True, capture_output=True, text=True, cwd=tmp_path)
    assert out.stdout.strip() == "1 [] 7", out.stdout + out.stderr
