"""Rebuilds scenes/motion/*.bvh, the real motion-capture clips shade-sim ships, from their public
sources (see scenes/motion/README.md for what each is and its licence):

- the sdists of the PyPI packages bvhtoolbox 0.1.3 and bvhtools 1.6.0 (`pip download`),
- Debian's assimp-testmodels package (`apt-get install assimp-testmodels`).

Each clip is shortened to at most 15 s and thinned to at most 30 fps by keeping every k-th frame
(the frame time multiplied by k); values are rounded to 3 decimals. Nothing else is changed.

Run: python3 scripts/motion_clips.py   (from the repository root)
"""
import glob
import os
import subprocess
import sys
import tarfile
import tempfile

OUT = "scenes/motion"
ASSIMP = "/usr/share/assimp/models/BVH"
# (output name, source, keep every k-th frame)
CLIPS = [
    ("mocapbank_sit.bvh", "bvhtoolbox:tests/example_files/test_mocapbank.bvh", 1),
    ("freebvh_walk.bvh", "bvhtoolbox:tests/example_files/test_freebvh.bvh", 1),
    ("cmu_01_01.bvh", ASSIMP + "/01_01.bvh", 4),
    ("cmu_01_03.bvh", ASSIMP + "/01_03.bvh", 4),
    ("assimp_boxing.bvh", ASSIMP + "/Boxing_Toes.bvh", 4),
    ("freemocap_lafan.bvh", "bvhtools:testBvhFiles/test.bvh", 1),
    ("freemocap_rigify.bvh", "bvhtools:testBvhFiles/test3.bvh", 1),
]
SECONDS = 15.0


def sdist(package, version, tmp):
    subprocess.run([sys.executable, "-m", "pip", "download", "--no-deps", "--no-binary", ":all:",
                    f"{package}=={version}", "-d", tmp], check=True, capture_output=True)
    archive = glob.glob(os.path.join(tmp, f"{package}-{version}.tar.gz"))[0]
    with tarfile.open(archive) as t:
        t.extractall(tmp)
    return os.path.join(tmp, f"{package}-{version}")


def thin(text, k):
    head, motion = text.split("MOTION", 1)
    lines = [l for l in motion.strip().splitlines() if l.strip()]
    frame_time = float(lines[1].split(":")[1]) * k
    rows = lines[2:][::k][: int(SECONDS / frame_time) + 1]
    rows = [" ".join(f"{float(v):.3f}" for v in r.split()) for r in rows]
    return head + f"MOTION\nFrames: {len(rows)}\nFrame Time: {frame_time:.6f}\n" + "\n".join(rows) + "\n"


def main():
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        roots = {"bvhtoolbox": sdist("bvhtoolbox", "0.1.3", tmp), "bvhtools": sdist("bvhtools", "1.6.0", tmp)}
        for name, source, k in CLIPS:
            package, _, path = source.partition(":")
            file = os.path.join(roots[package], path) if package in roots else source
            with open(file, encoding="utf-8", errors="strict") as f:
                text = f.read()
            with open(os.path.join(OUT, name), "w") as f:
                f.write(thin(text, k))
            print(name, os.path.getsize(os.path.join(OUT, name)))


if __name__ == "__main__":
    main()
