#!/bin/sh
# Installs Xvfb (a virtual X display) when it is missing: python/tests/test_viewer.py opens
# the on-screen viewers there. GLX on it comes from Mesa (libgl1 with libglx-mesa0, which
# install-render-libs.sh's libgl1 brings).
have() { command -v "$1" >/dev/null 2>&1; }
if have Xvfb; then
    exit 0
fi
PKGS="xvfb libgl1 libglx-mesa0"
if [ "$(id -u)" = 0 ] && have apt-get; then
    echo "test.sh: installing $PKGS with apt-get (the viewer tests' virtual display)"
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $PKGS >/dev/null
elif have sudo && have apt-get; then
    echo "test.sh: installing $PKGS with sudo apt-get (the viewer tests' virtual display)"
    sudo apt-get update -qq >/dev/null && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $PKGS >/dev/null
else
    echo "test.sh: Xvfb is missing and cannot be installed here; install $PKGS (the viewer tests fail without it)" >&2
    exit 1
fi
