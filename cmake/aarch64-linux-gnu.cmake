# Cross-building for 64-bit Arm Linux with Debian's cross compiler (g++-aarch64-linux-gnu); the
# programs run on x86-64 under qemu-user (qemu-aarch64 -L /usr/aarch64-linux-gnu). Meant for a
# DISCREEL_PHYSICS_ONLY build, whose only dependency is Eigen (tests/arch/cross_check.sh):
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
#     -DDISCREEL_PHYSICS_ONLY=ON
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)

# Libraries and headers from the target's tree only; tools from the host.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# Packages from both: Eigen is header only, so the host's (libeigen3-dev) serves every target.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
