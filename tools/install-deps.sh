#!/usr/bin/env bash
# Installs cacao's build and test dependencies from Debian 12 packages (runs apt-get update once).
set -euo pipefail
packages=(cmake ninja-build gcc pkg-config
          glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev
          libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
          libvulkan-volk-dev # the consumer_volk test: an engine on volk, no loader linked
          libpng-dev libcjson-dev libopenexr-dev
          gnuplot-nox   # cacao-bench's plots
          python3-numpy # tools/accuracy-report.py, tools/estimators-report.py
          clang-14 libclang-rt-14-dev) # clang: the libFuzzer harnesses of the sanitizer build
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update
"${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${packages[@]}"
