#!/bin/sh
# Installs pkg-config, which mujoco-rs's build script uses to find MuJoCo.
set -e
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "make: installing pkg-config with apt-get"
    apt-get update -qq >/dev/null && apt-get install -y -qq pkg-config >/dev/null
elif command -v sudo >/dev/null && command -v apt-get >/dev/null; then
    echo "make: installing pkg-config with sudo apt-get"
    sudo apt-get update -qq >/dev/null && sudo apt-get install -y -qq pkg-config >/dev/null
else
    echo "make: pkg-config is missing; install it with your package manager" >&2
    exit 1
fi
