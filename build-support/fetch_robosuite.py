#!/usr/bin/env python3
"""Fetch robosuite 1.5.2's model files (MJCF, meshes, textures) and controller configs.

Usage: fetch_robosuite.py [DEST]

Downloads the PyPI wheel `robosuite==1.5.2` with pip (`--no-deps`: nothing of robosuite's
Python is installed or run) and unpacks only its data into DEST:

    DEST/robosuite/models/assets/...        arenas, robots, grippers, bases, objects, textures
    DEST/robosuite/controllers/config/...   robosuite's controller JSON files

(the layout of an installed robosuite, so scene files saved by robosuite, whose asset paths
run through a `robosuite/` folder, resolve here too). `bullet_data` (PyBullet's URDFs) is
left out. DEST defaults to the cache robosuite-rs reads: $ROBOSUITE_RS_CACHE, else
$XDG_CACHE_HOME/robosuite-rs, else ~/.cache/robosuite-rs, each plus `/robosuite-1.5.2`.

Safe to run concurrently: it unpacks into a private folder and renames it into place.
Exits 0 at once if DEST is already complete. Prints one line saying how to fix any failure.
"""
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile

VERSION = "1.5.2"
# Written last: its presence means DEST is complete.
MARKER = ".robosuite-rs-complete"
KEEP = ("robosuite/models/assets/", "robosuite/controllers/config/")
SKIP = ("robosuite/models/assets/bullet_data/",)


def fail(message: str) -> None:
    print(f"fetch_robosuite: {message}", file=sys.stderr)
    sys.exit(1)


def default_dest() -> str:
    base = os.environ.get("ROBOSUITE_RS_CACHE")
    if not base:
        xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        base = os.path.join(xdg, "robosuite-rs")
    return os.path.join(base, f"robosuite-{VERSION}")


def main() -> None:
    if len(sys.argv) > 2:
        fail("usage: fetch_robosuite.py [DEST]")
    dest = os.path.abspath(sys.argv[1] if len(sys.argv) == 2 else default_dest())
    if os.path.isfile(os.path.join(dest, MARKER)):
        print(dest)
        return
    parent = os.path.dirname(dest)
    try:
        os.makedirs(parent, exist_ok=True)
        work = tempfile.mkdtemp(prefix=".robosuite-fetch-", dir=parent)
    except OSError as e:
        fail(f"cannot write to {parent} ({e}); set ROBOSUITE_RS_CACHE to a writable folder, "
             "or ROBOSUITE_ASSETS to an existing robosuite 1.5.2 install")
    try:
        wheel_dir = os.path.join(work, "wheel")
        cmd = [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
               "--only-binary=:all:", "--dest", wheel_dir, f"robosuite=={VERSION}"]
        result = subprocess.run(cmd, capture_output=True, text=True)
        if result.returncode != 0:
            detail = (result.stderr.strip().splitlines() or ["no output"])[-1]
            fail(f"`pip download robosuite=={VERSION}` failed ({detail}); check that pip can "
                 "reach PyPI, or set ROBOSUITE_ASSETS to an existing robosuite 1.5.2 install "
                 "(its `robosuite` folder or its `robosuite/models/assets` folder)")
        wheels = [f for f in os.listdir(wheel_dir) if f.endswith(".whl")]
        if len(wheels) != 1:
            fail(f"expected one robosuite wheel, found {wheels}")
        staged = os.path.join(work, "robosuite-rs")
        count = 0
        with zipfile.ZipFile(os.path.join(wheel_dir, wheels[0])) as wheel:
            for info in wheel.infolist():
                name = info.filename
                if info.is_dir() or not name.startswith(KEEP) or name.startswith(SKIP):
                    continue
                target = os.path.join(staged, *name.split("/"))
                os.makedirs(os.path.dirname(target), exist_ok=True)
                with wheel.open(info) as src, open(target, "wb") as out:
                    shutil.copyfileobj(src, out)
                count += 1
        if not os.path.isfile(os.path.join(staged, "robosuite", "models", "assets", "base.xml")):
            fail(f"the wheel {wheels[0]} holds no robosuite/models/assets/base.xml")
        with open(os.path.join(staged, MARKER), "w") as marker:
            marker.write(f"robosuite {VERSION}: {count} files\n")
        try:
            os.rename(staged, dest)
        except OSError:
            if not os.path.isfile(os.path.join(dest, MARKER)):
                raise
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(dest)


if __name__ == "__main__":
    main()
