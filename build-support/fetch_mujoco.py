#!/usr/bin/env python3
"""Fetch the MuJoCo 3.17.0 shared library from the PyPI wheel `mujoco==3.17.0`.

Usage: fetch_mujoco.py DEST

Leaves DEST/lib/libmujoco.so.3.17.0, the linker name DEST/lib/libmujoco.so and the
plugins in DEST/bin/mujoco_plugin (the layout of MuJoCo's release archives). Safe to run
concurrently: it unpacks into a private folder and renames it into place. Exits 0 at once
if DEST is already complete. Prints one line saying how to fix any failure.
"""
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import zipfile

VERSION = "3.17.0"
SONAME = f"libmujoco.so.{VERSION}"


def fail(message: str) -> None:
    print(f"fetch_mujoco: {message}", file=sys.stderr)
    sys.exit(1)


def main() -> None:
    if len(sys.argv) != 2:
        fail("usage: fetch_mujoco.py DEST")
    dest = os.path.abspath(sys.argv[1])
    if os.path.isfile(os.path.join(dest, "lib", SONAME)):
        return
    if platform.system() != "Linux":
        fail("only Linux wheels are fetched automatically; set MUJOCO_DYNAMIC_LINK_DIR "
             f"to the lib/ folder of a MuJoCo {VERSION} release")
    arch = platform.machine()
    parent = os.path.dirname(dest)
    os.makedirs(parent, exist_ok=True)
    work = tempfile.mkdtemp(prefix=".mujoco-fetch-", dir=parent)
    try:
        wheel_dir = os.path.join(work, "wheel")
        cmd = [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
               "--only-binary=:all:", "--python-version", "3.11", "--implementation", "cp",
               "--platform", f"manylinux_2_28_{arch}", "--dest", wheel_dir, f"mujoco=={VERSION}"]
        result = subprocess.run(cmd, capture_output=True, text=True)
        if result.returncode != 0:
            detail = (result.stderr.strip().splitlines() or ["no output"])[-1]
            fail(f"`pip download mujoco=={VERSION}` failed ({detail}); check that pip can reach "
                 "PyPI, or set MUJOCO_DYNAMIC_LINK_DIR to the lib/ folder of a MuJoCo "
                 f"{VERSION} install")
        wheels = [f for f in os.listdir(wheel_dir) if f.endswith(".whl")]
        if len(wheels) != 1:
            fail(f"expected one mujoco wheel, found {wheels}")
        staged = os.path.join(work, "mujoco")
        lib_dir = os.path.join(staged, "lib")
        plugin_dir = os.path.join(staged, "bin", "mujoco_plugin")
        os.makedirs(lib_dir)
        os.makedirs(plugin_dir)
        with zipfile.ZipFile(os.path.join(wheel_dir, wheels[0])) as wheel:
            for name in wheel.namelist():
                base = os.path.basename(name)
                if name == f"mujoco/{SONAME}":
                    target = os.path.join(lib_dir, SONAME)
                elif name.startswith("mujoco/plugin/") and base.endswith(".so"):
                    target = os.path.join(plugin_dir, base)
                else:
                    continue
                with wheel.open(name) as src, open(target, "wb") as out:
                    shutil.copyfileobj(src, out)
        if not os.path.isfile(os.path.join(lib_dir, SONAME)):
            fail(f"the wheel {wheels[0]} holds no mujoco/{SONAME}")
        os.symlink(SONAME, os.path.join(lib_dir, "libmujoco.so"))
        try:
            os.rename(staged, dest)
        except OSError:
            if not os.path.isfile(os.path.join(dest, "lib", SONAME)):
                raise
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
