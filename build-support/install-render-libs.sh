#!/bin/sh
# Installs what headless rendering (the `render` feature) needs at run time when it is
# missing: libEGL (glvnd) with a vendor library — a GPU driver's, or Mesa's software EGL
# (libegl-mesa0 + libgl1-mesa-dri) on a CPU-only machine — and libGL for MuJoCo.
set -e
have() { ldconfig -p 2>/dev/null | grep -q "$1"; }
if have libEGL.so.1 && have libGL.so.1 && { have libEGL_mesa.so.0 || have libEGL_nvidia.so.0; }; then
    exit 0
fi
PKGS="libegl1 libegl-mesa0 libgl1-mesa-dri libgl1"
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "make: installing $PKGS with apt-get (headless rendering)"
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $PKGS >/dev/null
elif command -v sudo >/dev/null && command -v apt-get >/dev/null; then
    echo "make: installing $PKGS with sudo apt-get (headless rendering)"
    sudo apt-get update -qq >/dev/null && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $PKGS >/dev/null
else
    echo "make: libEGL/Mesa missing; install $PKGS (or your GPU's EGL) with your package manager" >&2
    exit 1
fi
