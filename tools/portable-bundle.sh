#!/usr/bin/env bash
# Packs built luxel programs with every shared library they load (Debian 12's glibc and loader
# included, and libglvnd's EGL and OpenGL dispatchers, which libepoxy opens at run time) into one
# tar.xz, so that they run on a machine without luxel's Debian packages: a lent GPU machine
# (docs/performance.md says which figures came from one). On that machine:
#   mkdir -p /tmp/luxel && tar -xJf BUNDLE -C /tmp/luxel
#   /tmp/luxel/run luxel bench dynamic ...        # or: /tmp/luxel/run luxel-tests --gtest_filter=...
# `run` starts the program through the bundled loader, with the bundle's libraries first and the
# machine's own GPU driver folders after them; EGL finds the NVIDIA driver through
# __EGL_VENDOR_LIBRARY_FILENAMES when /usr/local/nvidia has one.
# Usage: tools/portable-bundle.sh OUT.tar.xz PROGRAM...
set -euo pipefail
out=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lib" "$work/bin"
# libGL.so.1 and libGLX.so.0: Dear ImGui's OpenGL loader (Debian's libimgui) opens libGL.so.1 by name.
libs=(/lib/x86_64-linux-gnu/libEGL.so.1 /lib/x86_64-linux-gnu/libOpenGL.so.0 /lib/x86_64-linux-gnu/libGLdispatch.so.0
      /lib/x86_64-linux-gnu/libGL.so.1 /lib/x86_64-linux-gnu/libGLX.so.0)
for program in "$@"; do
  cp -L "$program" "$work/bin/"
  while read -r lib; do libs+=("$lib"); done < <(ldd "$program" | awk '/=> \// {print $3} /^\s*\/lib/ {print $1}')
done
for lib in "${libs[@]}"; do
  cp -L "$lib" "$work/lib/"
  while read -r dep; do cp -Ln "$dep" "$work/lib/" 2>/dev/null || true; done < <(ldd "$lib" | awk '/=> \// {print $3}')
done
cp -L /lib64/ld-linux-x86-64.so.2 "$work/lib/"
cat > "$work/run" <<'EOF'
#!/bin/sh
# Runs a bundled program: run PROGRAM [ARGS...]
here=$(dirname "$(readlink -f "$0")")
program=$1
shift
for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
  [ -f "$f" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$f" && break
done
# The loader's --library-path reaches the program and what it opens (the NVIDIA EGL driver), not
# its children: the machine's own programs (a shell, git) keep the machine's own libc.
path="$here/lib:/usr/local/nvidia/lib64:/usr/local/nvidia/lib:/usr/lib/x86_64-linux-gnu"
exec "$here/lib/ld-linux-x86-64.so.2" --library-path "$path" "$here/bin/$program" "$@"
EOF
chmod +x "$work/run"
tar -cJf "$out" -C "$work" .
echo "$out: $(du -h "$out" | cut -f1), $(ls "$work/lib" | wc -l) libraries"
